// Reference for module 05_triangle (docs/handouts/05_triangle.md).
#include "raylab/contract.h"
#include "watertight_triangle.h"

namespace raylab::reference {

/// Ray-triangle intersection (handout 05 §2-§4). The hit point is
///   r(t) = (1 - beta - gamma) v0 + beta v1 + gamma v2,  beta, gamma >= 0, beta + gamma
///   <= 1,
/// hit.uv = (beta, gamma), hit.n = normalize((v1 - v0) x (v2 - v0)) (counter-clockwise
/// vertices face the viewer). Both sides are hit. Degenerate triangles are never hit.
///
/// Watertight test after Woop, Benthin and Wald (JCGT 2013), as in pbrt-v4: the ray's
/// frame, the edge functions and the conservative t > 0 are in watertight_triangle.h,
/// which the reference's engine shares.
std::optional<Hit> intersect_triangle(const Ray& r, const Vec3& v0, const Vec3& v1,
                                      const Vec3& v2) {
    watertight::Candidate c;
    if (!watertight::candidate(watertight::WoopRay(r), v0, v1, v2, c))
        return std::nullopt;
    if (!watertight::in_front(c)) return std::nullopt;
    const float t = static_cast<float>(c.t);
    if (!(t >= r.tmin && t <= r.tmax)) return std::nullopt;
    Hit hit;
    hit.t = t;
    hit.position = r.o + t * r.w;
    double len;
    hit.n = watertight::unit_normal(v0, v1, v2, len);
    if (!(len > 0.0)) return std::nullopt;
    hit.uv = watertight::uv(c);
    return hit;
}

}  // namespace raylab::reference
