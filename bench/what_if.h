// bench/what_if.h: where raylab's closest-hit time goes. The same BVH (Bvh::traverse, the
// public template the scene uses) with cheaper leaf tests, to size the gain of changes
// to framework/ before anyone makes them.
#pragma once

#include <string>
#include <vector>

#include "raylab/scene.h"
#include "report.h"

namespace raylab::bench {

/// The header of the what-if table.
Table what_if_table();

/// Adds one row per variant for the closest hits of rays in scene (triangles only), and
/// for the any-hit of shadow_rays; sets larger than max_rays are thinned by a stride.
void add_what_if_rows(Table& table, const std::string& scene_name, const Scene& scene,
                      const ModuleTable& modules, const std::vector<Ray>& closest_rays,
                      const std::string& closest_name,
                      const std::vector<Ray>& shadow_rays, int repeats, size_t max_rays);

}  // namespace raylab::bench
