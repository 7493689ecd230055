// bench/student_cases.h: what the student bench adds to the kernel section's ray sets
// (kernel_cases.h) and kernels (kernels.h): ray-plane sets, the textbook float plane
// test and its long double truth, and rays through a vertex shared by a fan of triangles.
#pragma once

#include <optional>
#include <vector>

#include "raylab/contract.h"
#include "rng.h"

namespace raylab::bench {

struct PlaneCase {
    Ray r;
    Plane p;
};

/// The plane ray sets, each at distance scale D:
///   far plane: origins in [-1/8, 1/8]^3, the plane about D away at a random tilt (t ~
///   D); far origin: origins and plane both about D from the world origin, the plane
///   about
///     1 away from the origins (o . n and d nearly cancel);
///   grazing: as far plane, the ray meeting the plane at 10^-U(1, 5) radians.
/// A quarter of the rays point away from the plane (the truth misses them).
enum class PlaneSet { far_plane, far_origin, grazing };
const char* to_string(PlaneSet set);
std::vector<PlaneCase> plane_cases(Rng& rng, double D, int n, PlaneSet set);

/// The textbook float test: t = -(o . n + d) / (w . n), a miss when w . n = 0 or t is
/// outside [tmin, tmax].
std::optional<Hit> plane_textbook_float(const Ray& r, const Plane& p);

/// Ground truth in long double for the float ray and plane as stored.
std::optional<long double> exact_plane_t(const Ray& r, const Plane& p);

/// A fan of triangles (v, ring[i], ring[i + 1]) closing around the shared vertex v, and a
/// ray aimed at v: the fan covers every direction around v as seen from the ray origin,
/// so a watertight test hits at least one of its triangles.
struct FanCase {
    Ray r;
    Vec3 v;
    std::vector<Vec3> ring;
};
std::vector<FanCase> fan_cases(Rng& rng, double D, int n);

}  // namespace raylab::bench
