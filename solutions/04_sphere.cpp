// Reference for module 04_sphere (docs/handouts/04_sphere.md).
#include "raylab/contract.h"

namespace raylab::reference {

/// Nearest t in [tmin, tmax] with |o + t w - c|^2 = r^2 (handout 04 §2), with outward
/// normal (p - c) / r. Returns std::nullopt on a miss. Precondition: |w| = 1.
///
/// Numerics (handout 04 §4, after Haines et al., "Precision Improvements for Ray/Sphere
/// Intersection", Ray Tracing Gems ch. 7): the discriminant is computed as r^2 - |f - b
/// w|^2 instead of b^2 - c, which cancels badly for small spheres far away, and the root
/// nearer to zero as c / q, which avoids subtracting two nearly equal numbers.
///
/// The coefficients and the discriminant in double (f = o - c is then exact): a shadow
/// ray that starts a few ulps of |o| outside a sphere and leaves it tangentially (handout
/// 08 §3) must see c = |f|^2 - r^2 > 0 and disc < 0, and in float the rounding of both
/// (ulps of r^2) exceeds those few ulps where the sphere passes near the origin (issue 8,
/// B5). Their signs settled, the square root and the division run in float.
std::optional<Hit> intersect_sphere(const Ray& r, const Sphere& sphere) {
    // Half-coefficients of t^2 + 2 b t + c = 0, with f = o - c
    const DVec3 f = DVec3(r.o) - DVec3(sphere.c), w(r.w);
    const double rr = double(sphere.r) * double(sphere.r);
    const double b = glm::dot(f, w);
    // Discriminant b^2 - c = r^2 - |f - b w|^2 (the squared half chord)
    const DVec3 l = f - b * w;
    const double disc = rr - glm::dot(l, l);
    if (disc < 0.0) return std::nullopt;
    const float c = static_cast<float>(glm::dot(f, f) - rr);
    // Both roots without cancellation: q = -b - sign(b) sqrt(disc), t = q and t = c / q
    const float bf = static_cast<float>(b);
    const float q = -bf - std::copysign(std::sqrt(static_cast<float>(disc)), bf);
    float t0 = q;
    float t1 = q != 0.0f ? c / q : 0.0f;
    if (t0 > t1) std::swap(t0, t1);
    // Nearest root inside [tmin, tmax]
    float t = t0;
    if (!(t >= r.tmin && t <= r.tmax)) {
        t = t1;
        if (!(t >= r.tmin && t <= r.tmax)) return std::nullopt;
    }
    Hit hit;
    hit.t = t;
    hit.position = r.o + t * r.w;
    hit.n = (hit.position - sphere.c) / sphere.r;
    return hit;
}

}  // namespace raylab::reference
