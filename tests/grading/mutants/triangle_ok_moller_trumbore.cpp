// Correct alternative: Moeller-Trumbore (in double, no fixed threshold on the
// determinant)
#include <cmath>

#include "raylab/contract.h"

namespace raylab::student {
std::optional<Hit> intersect_triangle(const Ray& r, const Vec3& v0, const Vec3& v1,
                                      const Vec3& v2) {
    const DVec3 o(r.o), w(r.w), a(v0), e1 = DVec3(v1) - a, e2 = DVec3(v2) - a;
    const DVec3 p = glm::cross(w, e2);
    const double det = glm::dot(e1, p);
    if (det == 0.0) return std::nullopt;
    const double inv = 1.0 / det;
    const DVec3 s = o - a;
    const double beta = glm::dot(s, p) * inv;
    if (beta < 0.0 || beta > 1.0) return std::nullopt;
    const DVec3 q = glm::cross(s, e1);
    const double gamma = glm::dot(w, q) * inv;
    if (gamma < 0.0 || beta + gamma > 1.0) return std::nullopt;
    const double td = glm::dot(e2, q) * inv;
    const float t = static_cast<float>(td);
    if (!(t >= r.tmin && t <= r.tmax)) return std::nullopt;
    Hit hit;
    hit.t = t;
    hit.position = r.o + t * r.w;
    hit.n = Vec3(glm::normalize(glm::cross(e1, e2)));
    hit.uv = Vec2(static_cast<float>(beta), static_cast<float>(gamma));
    return hit;
}
}  // namespace raylab::student
