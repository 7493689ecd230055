// bench/kernel_cases.h: the seeded ray sets of the kernel section.
//
// Ray origins lie in the cube [-1/8, 1/8]^3 around the world origin; the targets (a
// sphere of radius 1/4, a triangle with vertices in a cube of side 1/2) sit at distance D
// from it. Geometry is
// stored in float, as raylab stores it; the truth is computed for the float values.
#pragma once

#include <vector>

#include "raylab/contract.h"
#include "rng.h"

namespace raylab::bench {

struct SphereCase {
    Ray r;
    Sphere s;
};

struct TriangleCase {
    Ray r;
    Vec3 v0, v1, v2;
};

/// Two triangles sharing the edge (a, b): (a, b, c1) and (b, a, c2), on opposite sides of
/// the edge as seen from the ray origin (a fold, as in a mesh); the ray aims at a point
/// of the shared edge.
struct SharedEdgeCase {
    Ray r;
    Vec3 a, b, c1, c2;
};

/// Random rays at spheres of radius r = 1/4 centred at distance D: each ray passes the
/// centre at a distance uniform over the disc of radius 1.15 r, so about 3/4 of them hit.
/// grazing: the ray passes at r (1 +- s), s = 10^-U(1, 6): half hit, all near the
/// silhouette. (D must exceed 1.15 r + the origins' spread, 0.5 at most.)
std::vector<SphereCase> sphere_cases(Rng& rng, double D, int n, bool grazing);

/// The triangle ray sets: random, as many hits as a BVH's tests on camera rays see;
/// grazing, near the triangle's plane; sparse, mostly misses, as the tests of shadow rays
/// through a mesh.
enum class TriangleSet { random, grazing, sparse };
const char* to_string(TriangleSet set);

/// Random rays at random triangles at distance D: the aim point is uniform in the
/// triangle scaled by 1.25 about its centroid, so about 64% hit (sparse: by 3, about
/// 11%). grazing: as random, but the ray meets the triangle's plane at an angle of
/// 10^-U(1, 5) radians.
std::vector<TriangleCase> triangle_cases(Rng& rng, double D, int n, TriangleSet set);

/// Rays aimed at points of an edge shared by two triangles at distance D.
std::vector<SharedEdgeCase> shared_edge_cases(Rng& rng, double D, int n);

}  // namespace raylab::bench
