// The student bench's plane and shared-vertex ray sets (bench/student_cases.h).
#include "student_cases.h"

#include <cmath>

namespace raylab::bench {

namespace {

constexpr double kOriginHalfSide = 0.125;  // ray origins in [-1/8, 1/8]^3 about a centre

// Rounds to float where the compiler cannot see through it (as kernel_cases.cpp does)
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

// The plane through p with unit normal n, stored in float
Plane plane_through(const DVec3& p, const DVec3& n) {
    Plane plane;
    plane.n = to_float(n);
    plane.d = static_cast<float>(-glm::dot(DVec3(plane.n), p));
    return plane;
}

}  // namespace

const char* to_string(PlaneSet set) {
    switch (set) {
        case PlaneSet::far_plane:
            return "far plane";
        case PlaneSet::far_origin:
            return "far origin";
        case PlaneSet::grazing:
            return "grazing";
    }
    return "?";
}

std::vector<PlaneCase> plane_cases(Rng& rng, double D, int n, PlaneSet set) {
    std::vector<PlaneCase> cases;
    cases.reserve(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k) {
        // centre: where the origins are; aim: a point of the plane
        const DVec3 centre =
            set == PlaneSet::far_origin ? D * rng.unit_vector() : DVec3(0.0);
        const DVec3 o = DVec3(to_float(centre + rng.in_cube(kOriginHalfSide)));
        const double dist = set == PlaneSet::far_origin ? rng.uniform(0.5, 2.0) : D;
        const DVec3 aim = centre + dist * rng.unit_vector();
        const DVec3 view = glm::normalize(aim - o);
        DVec3 n;
        if (set == PlaneSet::grazing) {
            // w . n = sin(alpha): the ray meets the plane at angle alpha
            const double alpha = std::pow(10.0, -rng.uniform(1.0, 5.0));
            n = std::cos(alpha) * random_perpendicular(rng, view) -
                std::sin(alpha) * view;
        } else {
            // A random tilt with |cos| >= 0.1 between the normal and the view
            n = rng.unit_vector();
            while (std::abs(glm::dot(n, view)) < 0.1)
                n = rng.unit_vector();
        }
        PlaneCase c{ray_towards(o, aim), plane_through(aim, n)};
        if (rng.uniform() < 0.25) c.r.w = -c.r.w;  // away from the plane
        cases.push_back(c);
    }
    return cases;
}

std::optional<Hit> plane_textbook_float(const Ray& r, const Plane& p) {
    const float wn = glm::dot(r.w, p.n);
    if (wn == 0.0f) return std::nullopt;
    const float t = -(glm::dot(r.o, p.n) + p.d) / wn;
    if (!(t >= r.tmin && t <= r.tmax)) return std::nullopt;
    Hit hit;
    hit.t = t;
    hit.position = r.o + t * r.w;
    hit.n = p.n;
    return hit;
}

std::optional<long double> exact_plane_t(const Ray& r, const Plane& p) {
    using L = long double;
    // Each product of two floats is exact in long double's 64-bit significand
    const L wn = L(r.w.x) * p.n.x + L(r.w.y) * p.n.y + L(r.w.z) * p.n.z;
    if (wn == 0) return std::nullopt;
    const L on = L(r.o.x) * p.n.x + L(r.o.y) * p.n.y + L(r.o.z) * p.n.z;
    const L t = -(on + L(p.d)) / wn;
    if (t >= r.tmin && t <= r.tmax && std::isfinite(t)) return t;
    return std::nullopt;
}

std::vector<FanCase> fan_cases(Rng& rng, double D, int n) {
    std::vector<FanCase> cases;
    cases.reserve(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k) {
        const DVec3 o = DVec3(to_float(rng.in_cube(kOriginHalfSide)));
        const Vec3 v = to_float(D * rng.unit_vector());
        const DVec3 view = glm::normalize(DVec3(v) - o);
        const DVec3 e1 = random_perpendicular(rng, view), e2 = glm::cross(view, e1);
        // 5 to 8 ring points in angular order, each gap below pi: the fan closes around v
        const int m = 5 + static_cast<int>(rng.uniform() * 4.0);
        FanCase c;
        c.v = v;
        const double step = 6.283185307179586 / m;
        for (int i = 0; i < m; ++i) {
            const double angle = step * (i + rng.uniform(-0.3, 0.3));
            const double radius = rng.uniform(0.05, 0.25);
            const DVec3 q = DVec3(v) +
                            radius * (std::cos(angle) * e1 + std::sin(angle) * e2) +
                            rng.uniform(-0.1, 0.1) * view;
            c.ring.push_back(to_float(q));
        }
        c.r = ray_towards(o, DVec3(v));
        cases.push_back(std::move(c));
    }
    return cases;
}

}  // namespace raylab::bench
