// A student's triangle module as the textbook writes it: Moeller-Trumbore in float,
// without a threshold on the determinant (its t loses accuracy far from the origin).
#include "raylab/contract.h"

namespace raylab::student {

std::optional<Hit> intersect_triangle(const Ray& r, const Vec3& v0, const Vec3& v1,
                                      const Vec3& v2) {
    const Vec3 e1 = v1 - v0, e2 = v2 - v0;
    const Vec3 p = glm::cross(r.w, e2);
    const float det = glm::dot(e1, p);
    if (det == 0.0f) return std::nullopt;
    const float inv = 1.0f / det;
    const Vec3 s = r.o - v0;
    const float beta = glm::dot(s, p) * inv;
    if (beta < 0.0f || beta > 1.0f) return std::nullopt;
    const Vec3 q = glm::cross(s, e1);
    const float gamma = glm::dot(r.w, q) * inv;
    if (gamma < 0.0f || beta + gamma > 1.0f) return std::nullopt;
    const float t = glm::dot(e2, q) * inv;
    if (!(t >= r.tmin && t <= r.tmax)) return std::nullopt;
    Hit hit;
    hit.t = t;
    hit.position = r.o + t * r.w;
    hit.n = glm::normalize(glm::cross(e1, e2));
    hit.uv = Vec2(beta, gamma);
    return hit;
}

}  // namespace raylab::student
