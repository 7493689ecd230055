// raylab/scenes.h: the built-in scenes, OBJ loading, and lookup by name.
#pragma once

#include <string>
#include <vector>

#include "raylab/scene.h"

namespace raylab {

/// The Cornell box of the COMS30115 lab (TestModel.h), scaled to [-1, 1]^3 and turned
/// into our y-up right-handed world (docs/conventions.md §Cornell box): room, short red
/// block, tall blue block, one point light near the ceiling with power 14 W per channel.
Scene cornell_box();

/// A DTU 02562 style scene: a ground plane, three spheres, a triangle and one point
/// light.
Scene dtu_scene();

/// Loads a Wavefront OBJ (+ MTL) with Debian's tinyobjloader: faces are triangulated, Kd
/// becomes rho, Ke emission; faces without normals shade flat. Adds a default view that
/// frames the model and a light above the eye. Throws raylab::Error naming file and
/// problem.
Scene load_obj(const std::string& path);

/// "cornell", "dtu" or a path ending in .obj. Throws raylab::Error for anything else.
Scene load_scene(const std::string& name_or_path);

/// Names of the built-in scenes, for help texts and the viewer.
std::vector<std::string> builtin_scene_names();

}  // namespace raylab
