// Mutant exercise file: no test for w . n = 0, so a ray parallel to the plane from its
// back side gets t = +inf, which t <= tmax = inf accepts
#include "raylab/contract.h"

namespace raylab::student {

std::optional<Hit> intersect_plane(const Ray& r, const Plane& plane) {
    const float t = -(glm::dot(r.o, plane.n) + plane.d) / glm::dot(r.w, plane.n);
    if (!(t >= r.tmin && t <= r.tmax)) return std::nullopt;
    Hit hit;
    hit.t = t;
    hit.position = r.o + t * r.w;
    hit.n = plane.n;
    return hit;
}

}  // namespace raylab::student
