// The glue of the module switch (raylab/modules.h): the parts that refer to the student's
// and the reference's code, built into the raylab library with both. The trusted grader,
// the viewer and raylab-render link it; a grading worker never does.
#include <string>

#include "raylab/engine.h"
#include "raylab/error.h"
#include "raylab/modules.h"

namespace raylab {

namespace detail {
std::string_view trim(std::string_view s);
bool matches(const ModuleInfo& info, std::string_view word);
}  // namespace detail

bool reference_available() {
#if RAYLAB_HAVE_REFERENCE
    return true;
#else
    return false;
#endif
}

void apply_module_list(ModuleSelection& selection, std::string_view list, Impl impl) {
    if (impl == Impl::reference && !reference_available()) {
        throw Error(
            "this build has no reference solutions (solutions/ is absent), so "
            "--reference is unavailable");
    }
    list = detail::trim(list);
    if (list.empty()) throw Error("empty module list (expected module names or 'all')");
    while (!list.empty()) {
        const size_t comma = list.find(',');
        const std::string_view word = detail::trim(list.substr(0, comma));
        list =
            comma == std::string_view::npos ? std::string_view{} : list.substr(comma + 1);
        if (word == "all") {
            selection.impl.fill(impl);
            continue;
        }
        bool found = false;
        for (const ModuleInfo& info : module_infos()) {
            if (detail::matches(info, word)) {
                selection[info.module] = impl;
                found = true;
            }
        }
        if (!found) {
            std::string names;
            for (const ModuleInfo& info : module_infos())
                names += std::string(" ") + info.name;
            throw Error("unknown module '" + std::string(word) + "' (modules:" + names +
                        ", or all)");
        }
    }
}

ModuleTable ModuleTable::make(const ModuleSelection& selection) {
    ModuleTable t{};
    const auto pick = [&](Module m, auto student_fn, auto reference_fn) {
        if (selection[m] == Impl::student) return student_fn;
#if RAYLAB_HAVE_REFERENCE
        return reference_fn;
#else
        (void)reference_fn;
        throw Error(std::string("module ") + module_info(m).id +
                    ": the reference is not in this build (solutions/ is absent)");
#endif
    };
#if RAYLAB_HAVE_REFERENCE
#define RAYLAB_PICK(m, f) pick(Module::m, &student::f, &reference::f)
#else
#define RAYLAB_PICK(m, f) pick(Module::m, &student::f, decltype(&student::f){nullptr})
#endif
#define RAYLAB_FUNCTION(m, f) t.f = RAYLAB_PICK(m, f);
#include "raylab/modules.def"
#undef RAYLAB_PICK
#if RAYLAB_HAVE_REFERENCE
    t.engine = reference::geometry_engine();
#endif
    return t;
}

}  // namespace raylab
