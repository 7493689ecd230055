// The module registry's names and selections (raylab/modules.h): the part of the module
// switch that refers to neither the student's nor the reference's code (raylab_core).
#include "raylab/modules.h"

#include <cctype>

#include "raylab/error.h"

namespace raylab {

const std::array<ModuleInfo, kModuleCount>& module_infos() {
    static const std::array<ModuleInfo, kModuleCount> infos{{
#define RAYLAB_MODULE(e, id, name, title, points) {Module::e, id, name, title, points},
#include "raylab/modules.def"
    }};
    return infos;
}

const ModuleInfo& module_info(Module m) {
    return module_infos()[static_cast<int>(m)];
}

ModuleSelection ModuleSelection::all(Impl impl) {
    ModuleSelection s;
    s.impl.fill(impl);
    return s;
}

namespace detail {

std::string_view trim(std::string_view s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front())))
        s.remove_prefix(1);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back())))
        s.remove_suffix(1);
    return s;
}

// Accepts the CLI name ("point-light"), the ID ("06_point_light"), the ID without its
// number ("point_light") and the number ("6" or "06").
bool matches(const ModuleInfo& info, std::string_view word) {
    const std::string_view id = info.id;
    if (word == info.name || word == id || word == id.substr(3)) return true;
    if (word == id.substr(0, 2)) return true;
    return word.size() == 1 && id[0] == '0' && word[0] == id[1];
}

}  // namespace detail

std::string describe(const ModuleSelection& selection) {
    std::string student, reference;
    for (const ModuleInfo& info : module_infos()) {
        std::string& list = selection[info.module] == Impl::student ? student : reference;
        list += list.empty() ? info.name : std::string(",") + info.name;
    }
    if (reference.empty()) return "student: all";
    if (student.empty()) return "reference: all";
    return "reference: " + reference + "; student: " + student;
}

}  // namespace raylab
