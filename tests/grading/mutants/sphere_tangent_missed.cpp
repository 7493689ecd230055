// Mutant exercise file: a right sphere test that calls a tangent ray (discriminant
// exactly 0) a miss
#include <cmath>

#include "raylab/contract.h"

namespace raylab::student {

std::optional<Hit> intersect_sphere(const Ray& r, const Sphere& s) {
    const Vec3 f = r.o - s.c;
    const float b = glm::dot(f, r.w);
    const float c = glm::dot(f, f) - s.r * s.r;
    const float disc = b * b - c;
    if (disc <= 0.0f) return std::nullopt;
    const float root = std::sqrt(disc);
    for (const float t : {-b - root, -b + root}) {
        if (t >= r.tmin && t <= r.tmax) {
            Hit h;
            h.t = t;
            h.position = r.o + t * r.w;
            h.n = (h.position - s.c) / s.r;
            return h;
        }
    }
    return std::nullopt;
}

}  // namespace raylab::student
