// Stub detection (raylab/options.h): which modules of exercises/ are still stubs.
//
// Every contract function of the registry (raylab/modules.def) has a probe here, named as
// the function, that calls the student's code once with harmless input; a stub marks its
// module in stub::called (RAYLAB_STUB). detect_stubs() calls the probes through the
// registry's RAYLAB_FUNCTION lines, so a function (and so a module) without a probe does
// not compile. Part of the glue library (raylab): it calls the student's code.
#include <cstdint>
#include <string>

#include "raylab/modules.h"
#include "raylab/options.h"

namespace raylab {

namespace {

// An any-hit query that never finds anything, for probing the shadow module
class NothingOccludes : public Occluder {
  public:
    bool occluded(const Ray&) const override { return false; }
};

const Ray kDown{Vec3(0.0f, 1.0f, 0.0f), Vec3(0.0f, -1.0f, 0.0f), 0.0f, kInfinity};
const LightSample kAbove{Vec3(0, 1.0f, 0), 2.0f, Vec3(0.25f)};

}  // namespace

namespace probe {

// 01_pixel_loop
void image_plane_point() {
    (void)student::image_plane_point(0, 0, 2, 2);
}
void render_tile() {
    Vec3 pixel(0.0f);
    student::render_tile(
        Tile{0, 0, 1, 1}, [](const Vec2&) { return Vec3(0.0f); },
        ImageView{&pixel, 1, 1});
}
// 02_camera
void camera_frame() {
    (void)student::camera_frame(Vec3(0.0f, 0.0f, 1.0f), Vec3(0.0f),
                                Vec3(0.0f, 1.0f, 0.0f));
}
void camera_constant() {
    (void)student::camera_constant(1.0f);
}
void camera_ray() {
    const PinholeCamera camera{Vec3(0.0f, 0.0f, 1.0f),
                               {Vec3(1.0f, 0, 0), Vec3(0, 1.0f, 0), Vec3(0, 0, -1.0f)},
                               1.0f};
    (void)student::camera_ray(camera, Vec2(0.0f));
}
// 03_plane, 04_sphere, 05_triangle
void intersect_plane() {
    (void)student::intersect_plane(kDown, Plane{Vec3(0.0f, 1.0f, 0.0f), 0.0f});
}
void intersect_sphere() {
    (void)student::intersect_sphere(kDown, Sphere{Vec3(0.0f), 0.5f});
}
void intersect_triangle() {
    (void)student::intersect_triangle(kDown, Vec3(-1, 0, -1), Vec3(0, 0, 1),
                                      Vec3(1, 0, -1));
}
// 06_point_light
void sample_point_light() {
    (void)student::sample_point_light(PointLight{Vec3(0.0f, 2.0f, 0.0f), Vec3(1.0f)},
                                      Vec3(0.0f));
}
void intensity_from_power() {
    (void)student::intensity_from_power(Vec3(1.0f));
}
// 07_lambert
void lambert() {
    (void)student::lambert(Vec3(0.5f), Vec3(0.0f), Vec3(0.0f, 1.0f, 0.0f), {kAbove});
}
// 08_shadows
void in_shadow() {
    (void)student::in_shadow(NothingOccludes{}, Vec3(0.0f), Vec3(0.0f, 1.0f, 0.0f),
                             kAbove);
}
// 09_antialiasing
void grid_samples() {
    (void)student::grid_samples(1);
}
void stratified_samples() {
    (void)student::stratified_samples(1, PixelRng{});
}
void pixel_radiance() {
    (void)student::pixel_radiance(0, 0, 1, 1, {PixelSample{Vec2(0.5f), 1.0f}},
                                  [](const Vec2&) { return Vec3(0.0f); });
}
void needs_more_samples() {
    (void)student::needs_more_samples({Vec3(0.0f), Vec3(1.0f)}, 0.5f);
}
// 10_area_light
void light_sample_points() {
    (void)student::light_sample_points(1, true, PixelRng{});
}
void sample_area_light() {
    (void)student::sample_area_light(
        AreaLight{Vec3(0, 2, 0), Vec3(1, 0, 0), Vec3(0, 0, -1), Vec3(1.0f)}, Vec3(0.0f),
        Vec2(0.5f), 1);
}

}  // namespace probe

std::uint32_t detect_stubs() {
    stub::called.store(0);
#define RAYLAB_FUNCTION(e, f) probe::f();
#include "raylab/modules.def"
    return stub::called.exchange(0);
}

ModuleSelection auto_selection() {
    ModuleSelection s = ModuleSelection::all(Impl::student);
    if (!reference_available()) return s;
    const std::uint32_t stubs = detect_stubs();
    for (int k = 0; k < kModuleCount; ++k) {
        if (stubs & (1u << k)) s.impl[k] = Impl::reference;
    }
    return s;
}

std::string stub_modules_running(const ModuleSelection& selection) {
    // No student module selected (--reference all): no student code runs at all
    bool any_student = false;
    for (const ModuleInfo& info : module_infos())
        any_student = any_student || selection[info.module] == Impl::student;
    if (!any_student) return "";
    const std::uint32_t stubs = detect_stubs();
    std::string list;
    for (const ModuleInfo& info : module_infos()) {
        const int k = static_cast<int>(info.module);
        if (selection[info.module] == Impl::student && (stubs & (1u << k)))
            list += list.empty() ? info.name : std::string(", ") + info.name;
    }
    return list;
}

}  // namespace raylab
