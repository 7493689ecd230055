// Reference for module 04_sphere (docs/handouts/04_sphere.md).
#include "raylab/contract.h"

namespace raylab::reference {

/// Nearest t in [tmin, tmax] with |o + t w - c|^2 = r^2 (handout 04 §2), with outward
/// normal (p - c) / r. Returns std::nullopt on a miss. Precondition: |w| = 1.
///
/// Numerics (handout 04 §4, after Haines et al., "Precision Improvements for Ray/Sphere
/// Intersection", Ray Tracing Gems ch. 7): the discriminant is computed as r^2 - |f - b
/// w|^2 instead of b^2 - c, which cancels badly for small spheres far away, and the root
/// nearer to zero as c / q, which avoids subtracting two nearly equal numbers. f = o - c
/// and c = |f|^2 - r^2 in double (f is then exact): a shadow ray that starts a few ulps
/// outside a sphere (handout 08 §3) must see c > 0, and in float the rounding of f and
/// |f|^2 (ulps of |c| and r^2) exceeds those few ulps of |o| where the sphere passes near
/// the origin (issue 8, B5). The rest stays in float, as accurate as it needs to be.
std::optional<Hit> intersect_sphere(const Ray& r, const Sphere& sphere) {
    // Half-coefficients of t^2 + 2 b t + c = 0, with f = o - c
    const DVec3 fd = DVec3(r.o) - DVec3(sphere.c);
    const Vec3 f(fd);
    const float b = glm::dot(f, r.w);
    // Discriminant b^2 - c = r^2 - |f - b w|^2 (the squared half chord)
    const Vec3 l = f - b * r.w;
    const float disc = sphere.r * sphere.r - glm::dot(l, l);
    if (disc < 0.0f) return std::nullopt;
    const float c =
        static_cast<float>(glm::dot(fd, fd) - double(sphere.r) * double(sphere.r));
    // Both roots without cancellation: q = -b - sign(b) sqrt(disc), t = q and t = c / q
    const float q = -b - std::copysign(std::sqrt(disc), b);
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
