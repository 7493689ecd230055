// raylab/scenes.h: the built-in scenes, OBJ loading, and lookup by name.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "raylab/error.h"
#include "raylab/scene.h"

namespace raylab {

/// Progress and cancellation of a long load. Every member may be left empty.
struct LoadProgress {
    /// Called now and then with the stage ("reading", "parsing", "triangles", "BVH") and
    /// the fraction of that stage done, in [0, 1]; from the loading thread.
    std::function<void(const char* stage, float fraction)> report;
    /// Set it (from any thread) to stop the load: it throws LoadCancelled soon after.
    const std::atomic<bool>* cancel = nullptr;
    /// Warnings (ignored lines, tinyobjloader's warnings); default: printed to stderr.
    std::function<void(const std::string& message)> warn;
};

/// Thrown by a load whose cancel flag was set.
class LoadCancelled : public Error {
  public:
    LoadCancelled() : Error("loading cancelled") {}
};

/// The Cornell box of the COMS30115 lab (TestModel.h), scaled to [-1, 1]^3 and turned
/// into our y-up right-handed world (docs/conventions.md §Cornell box): room, short red
/// block, tall blue block, one point light near the ceiling with power 14 W per channel.
Scene cornell_box();

/// A DTU 02562 style scene: a ground plane, three spheres, a triangle and one point
/// light.
Scene dtu_scene();

/// Loads a Wavefront OBJ (+ MTL) with Debian's tinyobjloader: faces are triangulated, Kd
/// becomes rho (the default material's grey, with a warning, for a material without a Kd
/// line), Ke emission; faces without normals shade flat. Adds a default view that frames
/// the model and a light above the eye. Every line is checked first (read_input_file,
/// docs/input.md "Input limits"). Throws raylab::Error naming file, line and
/// field. A missing or unreadable MTL file is a warning, not an error: the faces that use
/// its materials get the default material. One that is read must be valid.
Scene load_obj(const std::string& path, const LoadProgress& progress = {});

/// The same from OBJ text; read_mtl(name) returns the text of the MTL file an mtllib
/// line names (or throws raylab::Error). For tests and fuzzing.
Scene load_obj_text(const std::string& text, const std::string& source,
                    const std::function<std::string(const std::string&)>& read_mtl,
                    const LoadProgress& progress = {});

/// "cornell", "dtu" or a path ending in .obj. Throws raylab::Error for anything else.
Scene load_scene(const std::string& name_or_path, const LoadProgress& progress = {});

/// Names of the built-in scenes, for help texts and the viewer.
std::vector<std::string> builtin_scene_names();

}  // namespace raylab
