// raylab/sample_scenes.h: generated sample scenes beyond the two built-ins, of
// different sizes (no model files, so no licence questions): a smooth-shaded blob, a
// terrain, a furnished room.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "raylab/scene.h"

namespace raylab {

/// "blob" (about 2k smooth-shaded triangles: shows the shadow terminator, handout 08),
/// "terrain" (about 32k smooth-shaded triangles), "room" (boxes, spheres, two lights).
std::vector<std::string> sample_scene_names();

/// The sample scene of that name, committed; nullopt for any other name.
std::optional<Scene> sample_scene(const std::string& name);

}  // namespace raylab
