// Reference for module 03_plane (docs/handouts/03_plane.md).
#include "raylab/contract.h"

namespace raylab::reference {

/// Ray-plane intersection (handout 03 §2): t = -(o . n + d) / (w . n), accepted when
/// tmin <= t <= tmax. Returns std::nullopt for rays parallel to the plane.
/// The geometric normal is the plane's n, whichever side the ray comes from.
std::optional<Hit> intersect_plane(const Ray& r, const Plane& plane) {
    // Parallel rays never meet the plane (w . n = 0 would divide by zero)
    const float wn = glm::dot(r.w, plane.n);
    if (wn == 0.0f) return std::nullopt;
    // Signed distance of o from the plane, in double: o . n and -d nearly cancel when the
    // scene is far from the world origin
    const double dist =
        glm::dot(DVec3(r.o), DVec3(plane.n)) + static_cast<double>(plane.d);
    const float t = static_cast<float>(-dist / static_cast<double>(wn));
    // Conditional acceptance (tmin <= t <= tmax); also rejects NaN, and t = inf from a
    // nearly parallel ray (w . n = -1e-40) whose distance overflows float
    if (!(t >= r.tmin && t <= r.tmax) || std::isinf(t)) return std::nullopt;
    Hit hit;
    hit.t = t;
    hit.position = r.o + t * r.w;
    hit.n = plane.n;
    return hit;
}

}  // namespace raylab::reference
