// bench/kernels.h: the intersection formulations raylab-bench compares, and the long
// double ground truth they are measured against.
//
// Every kernel has the contract's signature and returns the same Hit (t, position,
// normal, and for triangles uv), so that ns per test compare like with like; each is
// called through a function pointer, as the renderer calls modules through ModuleTable.
#pragma once

#include <optional>
#include <vector>

#include "raylab/contract.h"

namespace raylab::bench {

using SphereKernel = std::optional<Hit> (*)(const Ray&, const Sphere&);
using TriangleKernel = std::optional<Hit> (*)(const Ray&, const Vec3&, const Vec3&,
                                              const Vec3&);

struct NamedSphereKernel {
    const char* name;
    SphereKernel fn;
};
struct NamedTriangleKernel {
    const char* name;
    TriangleKernel fn;
};

/// naive float (b^2 - c), naive double (also with a = w.w), the reference (RTG ch. 7,
/// float), RTG in double (also with a = w.w).
const std::vector<NamedSphereKernel>& sphere_kernels();

/// Moeller-Trumbore float, Cramer float, edge functions float, the reference (edge
/// functions, double).
const std::vector<NamedTriangleKernel>& triangle_kernels();

/// Ground truth: the nearest t in [tmin, tmax] of the ray as given (float o and w, w not
/// assumed to be of unit length) in long double (64-bit significand) with the
/// cancellation-free discriminant. std::nullopt on a miss.
std::optional<long double> exact_sphere_t(const Ray& r, const Sphere& s);

/// Ground truth for a triangle: edge functions in long double; a ray through an edge
/// or a vertex hits. std::nullopt on a miss.
std::optional<long double> exact_triangle_t(const Ray& r, const Vec3& v0, const Vec3& v1,
                                            const Vec3& v2);

}  // namespace raylab::bench
