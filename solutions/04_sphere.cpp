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
/// A ray that starts on or a few ulps off the sphere (a shadow ray leaving it, handout 08
/// §3) must see c = |f|^2 - r^2 > 0 and, leaving tangentially, disc < 0: in float their
/// rounding (ulps of |f|^2 and r^2) exceeds those few ulps where the sphere passes near
/// the origin. Such rays (|c| within 2^-16 of |f|^2 + r^2) take the same
/// steps with f = o - c exact and the coefficients in double; all others stay in float.
std::optional<Hit> intersect_sphere(const Ray& r, const Sphere& sphere) {
    // Half-coefficients of t^2 + 2 b t + c = 0, with f = o - c
    const Vec3 f = r.o - sphere.c;
    const float rr = sphere.r * sphere.r, ff = glm::dot(f, f);
    float c = ff - rr;
    float b, disc;
    if (std::abs(c) > 0x1p-16f * (ff + rr)) {
        b = glm::dot(f, r.w);
        // Discriminant b^2 - c = r^2 - |f - b w|^2 (the squared half chord)
        const Vec3 l = f - b * r.w;
        disc = rr - glm::dot(l, l);
    } else {
        const DVec3 fd = DVec3(r.o) - DVec3(sphere.c), w(r.w);
        const double rrd = double(sphere.r) * double(sphere.r), bd = glm::dot(fd, w);
        const DVec3 l = fd - bd * w;
        c = static_cast<float>(glm::dot(fd, fd) - rrd);
        b = static_cast<float>(bd);
        disc = static_cast<float>(rrd - glm::dot(l, l));
    }
    if (disc < 0.0f) return std::nullopt;
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
