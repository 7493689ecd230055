// bench/mesh.h: the scene section's procedural mesh and its ray sets.
#pragma once

#include <vector>

#include "raylab/scene.h"
#include "rng.h"

namespace raylab::bench {

/// A closed, bumpy mesh of about `triangles` triangles generated in code: a unit sphere
/// tessellated as a latitude-longitude grid, its radius displaced by a few sines. Shared
/// vertices are computed once, so the mesh is watertight bit for bit. One light.
Scene displaced_sphere(int triangles);

/// The camera rays render() casts for a width x height image of scene.view: one through
/// every pixel centre, built by the camera and pixel-loop modules, w normalised.
std::vector<Ray> camera_rays(const Scene& scene, const ModuleTable& modules, int width,
                             int height);

/// The shadow rays render() casts (with shadows on) from the closest hits of the camera
/// rays: recorded from the shadow module, so offsets and tmax are the renderer's own.
std::vector<Ray> shadow_rays(const Scene& scene, const ModuleTable& modules,
                             const std::vector<Ray>& camera);

/// n incoherent rays: origins on a sphere around the scene's bounds, aimed at points
/// uniform in the bounds.
std::vector<Ray> random_rays(const Scene& scene, Rng& rng, int n);

}  // namespace raylab::bench
