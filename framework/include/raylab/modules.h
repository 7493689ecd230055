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

struct GeometryEngine;

/// The modules in teaching order (raylab/modules.def); the value + 1 is the module
/// number.
enum class Module {
#define RAYLAB_MODULE(e, id, name, title, points) e,
#include "raylab/modules.def"
};
inline constexpr int kModuleCount = 0
#define RAYLAB_MODULE(e, id, name, title, points) +1
#include "raylab/modules.def"
    ;

/// Names of one module, all derived from its stable ID (docs/style.md rule 3).
struct ModuleInfo {
    Module module;
    const char* id;  ///< stable ID: file, handout, TODO and test suite, e.g. "04_sphere"
    const char* name;   ///< CLI name, e.g. "sphere"
    const char* title;  ///< human title, e.g. "Ray-sphere intersection"
    double points;      ///< default points of the module when graded
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

/// Pointers to the chosen implementation of every contract function (one member per
/// RAYLAB_FUNCTION of modules.def).
struct ModuleTable {
#define RAYLAB_FUNCTION(e, f) decltype(&student::f) f;
#include "raylab/modules.def"
    /// The reference's fast path for the scene's queries (raylab/engine.h), or null. The
    /// scene uses it only while the three intersect_* members are the reference's.
    const GeometryEngine* engine = nullptr;
    /// The table for selection. Throws raylab::Error when it asks for a reference that
    /// this build does not have. Defined in the glue library (raylab), which links both
    /// the student's and the reference's code: raylab_core never refers to either.
    static ModuleTable make(const ModuleSelection& selection);
};

}  // namespace raylab
