// Mutant exercise file: a right plane test that calls every ray within 1e-3 of parallel
// (|w . n| < 1e-3, about 0.06 degrees) a miss
#include <cmath>

#include "raylab/contract.h"

namespace raylab::student {

std::optional<Hit> intersect_plane(const Ray& r, const Plane& plane) {
    const float wn = glm::dot(r.w, plane.n);
    if (std::abs(wn) < 1e-3f) return std::nullopt;
    const float t = -(glm::dot(r.o, plane.n) + plane.d) / wn;
    if (!(t >= r.tmin && t <= r.tmax)) return std::nullopt;
    Hit h;
    h.t = t;
    h.position = r.o + t * r.w;
    h.n = plane.n;
    return h;
}

}  // namespace raylab::student
