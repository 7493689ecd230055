// bench/mesh.h: the scene section's procedural mesh and its ray sets.
#pragma once

#include <vector>

#include "raylab/scene.h"
#include "rng.h"

namespace raylab::bench {

/// A unit icosphere: an icosahedron whose faces are split in four, level after level,
/// the new vertices (edge midpoints) pushed out onto the sphere; 20 * 4^k triangles, the
/// most of those that is at most `triangles` (at least the 20 of the icosahedron).
/// Shared vertices are computed once, so the mesh is watertight bit for bit, and its
/// triangles are nearly equilateral and of nearly one size. One light.
Scene icosphere(int triangles);

/// A closed, bumpy mesh of about `triangles` triangles generated in code: a unit sphere
/// tessellated as a latitude-longitude grid, its radius displaced by a few sines. Shared
/// vertices are computed once, so the mesh is watertight bit for bit. One light.
Scene displaced_sphere(int triangles);

/// A terrain of about `triangles` triangles generated in code: a height field over a
/// square grid (two triangles a cell, shared vertices computed once), its heights a sum
/// of sines from broad hills to fine ripples, seen at a slant with the sky above the
/// horizon (camera rays that miss everything). One light.
Scene terrain(int triangles);

/// A random soup of `triangles` triangles: each with its centre uniform in the cube
/// [-1, 1]^3 and its vertices at random directions and distances around it, so they
/// overlap and cross each other, slivers included (the hardest case for a BVH's boxes),
/// and the order they are made in has nothing to do with where they lie (commit() then
/// moves them into the BVH's order). A line through the
/// cube's centre along an axis crosses about 12 of them, whatever their number. One
/// light.
Scene random_soup(int triangles, Rng& rng);

/// The scene as it was before its first commit(): its triangles (and vertex normals) in
/// the order they were added, which commit() changed (Scene::triangle_source), not
/// committed. Build times start from it, as a freshly made or loaded scene's commit()
/// does.
Scene as_added(const Scene& scene);

/// Median seconds of commit() on a fresh copy of as_added(scene) (the copy untimed).
double commit_seconds(const Scene& scene, int repeats);

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
