// raylab/modules.h: the run-time switch between student and reference code, per module.
//
// The framework never calls raylab::student or raylab::reference directly: it calls
// through a ModuleTable, a plain struct of function pointers filled from a
// ModuleSelection. The viewer's panel, the CLI's --student/--reference flags and the
// graders all use it.
#pragma once

#include <array>
#include <string>
#include <string_view>

#include "raylab/contract.h"

namespace raylab {

/// The eight modules in teaching order; the value + 1 is the module number.
enum class Module {
    pixel_loop,
    camera,
    plane,
    sphere,
    triangle,
    point_light,
    lambert,
    shadows
};
inline constexpr int kModuleCount = 8;

/// Names of one module, all derived from its stable ID (STYLE.md rule 3).
struct ModuleInfo {
    Module module;
    const char* id;  ///< stable ID: file, handout, TODO and test suite, e.g. "04_sphere"
    const char* name;   ///< CLI name, e.g. "sphere"
    const char* title;  ///< human title, e.g. "Ray-sphere intersection"
};

/// All modules in teaching order.
const std::array<ModuleInfo, kModuleCount>& module_infos();
const ModuleInfo& module_info(Module m);

/// Which implementation runs.
enum class Impl { student, reference };

/// One choice per module.
struct ModuleSelection {
    std::array<Impl, kModuleCount> impl{};  ///< all student by default

    Impl& operator[](Module m) { return impl[static_cast<int>(m)]; }
    Impl operator[](Module m) const { return impl[static_cast<int>(m)]; }
    /// Every module switched to impl.
    static ModuleSelection all(Impl impl);
};

/// True when this build holds solutions/ (false in a student release).
bool reference_available();

/// Applies a list such as "camera,sphere", "04_sphere", "4" or "all" to selection,
/// setting the named modules to impl. Throws raylab::Error naming the unknown module or,
/// for the reference, that this build has no solutions/.
void apply_module_list(ModuleSelection& selection, std::string_view list, Impl impl);

/// "student: all" / "reference: camera, sphere; student: others": for logs and the CLI.
std::string describe(const ModuleSelection& selection);

/// Pointers to the chosen implementation of every contract function.
struct ModuleTable {
    decltype(&reference::image_plane_point) image_plane_point;
    decltype(&reference::render_tile) render_tile;
    decltype(&reference::camera_frame) camera_frame;
    decltype(&reference::camera_constant) camera_constant;
    decltype(&reference::camera_ray) camera_ray;
    decltype(&reference::intersect_plane) intersect_plane;
    decltype(&reference::intersect_sphere) intersect_sphere;
    decltype(&reference::intersect_triangle) intersect_triangle;
    decltype(&reference::sample_point_light) sample_point_light;
    decltype(&reference::intensity_from_power) intensity_from_power;
    decltype(&reference::lambert) lambert;
    decltype(&reference::in_shadow) in_shadow;

    /// The table for selection. Throws raylab::Error when it asks for a reference that
    /// this build does not have.
    static ModuleTable make(const ModuleSelection& selection);
};

}  // namespace raylab
