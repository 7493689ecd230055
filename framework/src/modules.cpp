// The run-time module switch (raylab/modules.h).
#include "raylab/modules.h"

#include <cctype>

#include "raylab/error.h"

namespace raylab {

const std::array<ModuleInfo, kModuleCount>& module_infos() {
    static const std::array<ModuleInfo, kModuleCount> infos{{
        {Module::pixel_loop, "01_pixel_loop", "pixel-loop", "Pixel loop"},
        {Module::camera, "02_camera", "camera", "Pinhole camera"},
        {Module::plane, "03_plane", "plane", "Ray-plane intersection"},
        {Module::sphere, "04_sphere", "sphere", "Ray-sphere intersection"},
        {Module::triangle, "05_triangle", "triangle", "Ray-triangle intersection"},
        {Module::point_light, "06_point_light", "point-light", "Point light"},
        {Module::lambert, "07_lambert", "lambert", "Lambertian shading"},
        {Module::shadows, "08_shadows", "shadows", "Hard shadows"},
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

bool reference_available() {
#if RAYLAB_HAVE_REFERENCE
    return true;
#else
    return false;
#endif
}

namespace {

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

}  // namespace

void apply_module_list(ModuleSelection& selection, std::string_view list, Impl impl) {
    if (impl == Impl::reference && !reference_available()) {
        throw Error(
            "this build has no reference solutions (solutions/ is absent), so "
            "--reference is unavailable");
    }
    list = trim(list);
    if (list.empty()) throw Error("empty module list (expected module names or 'all')");
    while (!list.empty()) {
        const size_t comma = list.find(',');
        const std::string_view word = trim(list.substr(0, comma));
        list =
            comma == std::string_view::npos ? std::string_view{} : list.substr(comma + 1);
        if (word == "all") {
            selection.impl.fill(impl);
            continue;
        }
        bool found = false;
        for (const ModuleInfo& info : module_infos()) {
            if (matches(info, word)) {
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
    t.image_plane_point = RAYLAB_PICK(pixel_loop, image_plane_point);
    t.render_tile = RAYLAB_PICK(pixel_loop, render_tile);
    t.camera_frame = RAYLAB_PICK(camera, camera_frame);
    t.camera_constant = RAYLAB_PICK(camera, camera_constant);
    t.camera_ray = RAYLAB_PICK(camera, camera_ray);
    t.intersect_plane = RAYLAB_PICK(plane, intersect_plane);
    t.intersect_sphere = RAYLAB_PICK(sphere, intersect_sphere);
    t.intersect_triangle = RAYLAB_PICK(triangle, intersect_triangle);
    t.sample_point_light = RAYLAB_PICK(point_light, sample_point_light);
    t.intensity_from_power = RAYLAB_PICK(point_light, intensity_from_power);
    t.lambert = RAYLAB_PICK(lambert, lambert);
    t.in_shadow = RAYLAB_PICK(shadows, in_shadow);
#undef RAYLAB_PICK
    return t;
}

}  // namespace raylab
