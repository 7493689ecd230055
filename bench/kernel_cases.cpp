// The kernel section's ray sets (bench/kernel_cases.h).
#include "kernel_cases.h"

#include <cmath>

namespace raylab::bench {

namespace {

constexpr double kOriginHalfSide = 0.125;  // ray origins in [-1/8, 1/8]^3
constexpr double kSize = 0.25;             // sphere radius; triangle vertices: c +- kSize

// Rounds to float where the compiler cannot see through it: GCC 12.2's SLP vectorizer at
// -O2/-O3 skips the rounding in `r.o = Vec3(o); ... DVec3(r.o)`
[[gnu::noinline]] Vec3 to_float(const DVec3& v) {
    return Vec3(v);
}

// The ray from o towards p: w normalised in double, then stored in float like any ray
Ray ray_towards(const DVec3& o, const DVec3& p) {
    Ray r;
    r.o = to_float(o);
    r.w = to_float(glm::normalize(p - DVec3(r.o)));
    return r;
}

DVec3 origin(Rng& rng) {
    return DVec3(to_float(rng.in_cube(kOriginHalfSide)));
}

// A point uniform in triangle (a, b, c) scaled by `scale` about its centroid
DVec3 aim_in_triangle(Rng& rng, const DVec3& a, const DVec3& b, const DVec3& c,
                      double scale) {
    const double s = std::sqrt(rng.uniform()), t = rng.uniform();
    const DVec3 p = (1.0 - s) * a + s * (1.0 - t) * b + s * t * c;
    const DVec3 centroid = (a + b + c) / 3.0;
    return centroid + scale * (p - centroid);
}

}  // namespace

std::vector<SphereCase> sphere_cases(Rng& rng, double D, int n, bool grazing) {
    std::vector<SphereCase> cases;
    cases.reserve(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k) {
        const DVec3 o = origin(rng);
        const Sphere s{Vec3(D * rng.unit_vector()), static_cast<float>(kSize)};
        const DVec3 c(s.c);
        // Impact parameter d: the distance of the ray from the centre
        double d = 1.15 * kSize * std::sqrt(rng.uniform());
        if (grazing) {
            const double eps = std::pow(10.0, -rng.uniform(1.0, 6.0));
            d = kSize * (rng.uniform() < 0.5 ? 1.0 - eps : 1.0 + eps);
        }
        // Aim across the view at offset b = d L / sqrt(L^2 - d^2), so that the ray passes
        // the centre at distance d (L: distance from the origin to the centre)
        const double L = glm::length(c - o);
        const double offset = d * L / std::sqrt(L * L - d * d);
        const DVec3 across = random_perpendicular(rng, glm::normalize(c - o));
        cases.push_back({ray_towards(o, c + offset * across), s});
    }
    return cases;
}

const char* to_string(TriangleSet set) {
    switch (set) {
        case TriangleSet::random:
            return "random";
        case TriangleSet::grazing:
            return "grazing";
        case TriangleSet::sparse:
            return "sparse";
    }
    return "?";
}

std::vector<TriangleCase> triangle_cases(Rng& rng, double D, int n, TriangleSet set) {
    const bool grazing = set == TriangleSet::grazing;
    const double aim_scale = set == TriangleSet::sparse ? 3.0 : 1.25;
    std::vector<TriangleCase> cases;
    cases.reserve(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k) {
        const DVec3 o = origin(rng), c = D * rng.unit_vector();
        DVec3 u = rng.in_cube(kSize), v = rng.in_cube(kSize), w = rng.in_cube(kSize);
        if (grazing) {
            // A plane through c whose normal is tilted by alpha from across the view
            const DVec3 view = glm::normalize(c - o);
            const DVec3 e1 = random_perpendicular(rng, view);
            const DVec3 e2 = glm::cross(view, e1);
            const double alpha = std::pow(10.0, -rng.uniform(1.0, 5.0));
            const DVec3 n = std::cos(alpha) * e2 + std::sin(alpha) * view;
            const DVec3 m = glm::cross(n, e1);
            const auto in_plane = [&] {
                return kSize * (rng.uniform(-1.0, 1.0) * e1 + rng.uniform(-1.0, 1.0) * m);
            };
            u = in_plane(), v = in_plane(), w = in_plane();
        }
        const Vec3 v0(c + u), v1(c + v), v2(c + w);
        const DVec3 p = aim_in_triangle(rng, DVec3(v0), DVec3(v1), DVec3(v2), aim_scale);
        cases.push_back({ray_towards(o, p), v0, v1, v2});
    }
    return cases;
}

std::vector<SharedEdgeCase> shared_edge_cases(Rng& rng, double D, int n) {
    std::vector<SharedEdgeCase> cases;
    cases.reserve(static_cast<size_t>(n));
    while (static_cast<int>(cases.size()) < n) {
        const DVec3 o = origin(rng), c = D * rng.unit_vector();
        const Vec3 a(c + rng.in_cube(kSize)), b(c + rng.in_cube(kSize));
        const Vec3 c1(c + rng.in_cube(kSize)), c2(c + rng.in_cube(kSize));
        // c1 and c2 on opposite sides of the plane through o, a and b
        const DVec3 side = glm::cross(DVec3(a) - o, DVec3(b) - o);
        const double s1 = glm::dot(side, DVec3(c1) - o),
                     s2 = glm::dot(side, DVec3(c2) - o);
        if (!(s1 * s2 < 0.0)) continue;
        const double s = rng.uniform(0.02, 0.98);
        const DVec3 p = DVec3(a) + s * (DVec3(b) - DVec3(a));
        cases.push_back({ray_towards(o, p), a, b, c1, c2});
    }
    return cases;
}

}  // namespace raylab::bench
