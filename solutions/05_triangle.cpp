// Reference for module 05_triangle (docs/handouts/05_triangle.md).
#include "raylab/contract.h"

namespace raylab::reference {

/// Ray-triangle intersection (handout 05 §2-§4). The hit point is
///   r(t) = (1 - beta - gamma) v0 + beta v1 + gamma v2,  beta, gamma >= 0, beta + gamma
///   <= 1,
/// hit.uv = (beta, gamma), hit.n = normalize((v1 - v0) x (v2 - v0)) (counter-clockwise
/// vertices face the viewer). Both sides are hit. Degenerate triangles are never hit.
///
/// This reference uses edge functions (signed volumes) in double precision rather than
/// Cramer's rule: each edge's sign is computed from the two vertices of that edge alone,
/// so a ray through an edge shared by two triangles hits at least one of them
/// (watertight).
std::optional<Hit> intersect_triangle(const Ray& r, const Vec3& v0, const Vec3& v1,
                                      const Vec3& v2) {
    // Vertices relative to the ray origin (exact in double for float inputs)
    const DVec3 o(r.o), w(r.w);
    const DVec3 a = DVec3(v0) - o, b = DVec3(v1) - o, c = DVec3(v2) - o;
    // Edge functions: the volume each edge spans with w, proportional to a barycentric
    // weight
    const double e0 = glm::dot(glm::cross(b, c), w);  // weight of v0
    const double e1 = glm::dot(glm::cross(c, a), w);  // weight of v1 (beta)
    const double e2 = glm::dot(glm::cross(a, b), w);  // weight of v2 (gamma)
    // Inside when no two edge functions have opposite signs
    if ((e0 < 0 || e1 < 0 || e2 < 0) && (e0 > 0 || e1 > 0 || e2 > 0)) return std::nullopt;
    // The weights sum to (v1 - v0) x (v2 - v0) . w: zero for parallel rays and degenerate
    // triangles
    const double det = e0 + e1 + e2;
    if (det == 0.0) return std::nullopt;
    // Distance along w to the triangle's plane: t = N . (v0 - o) / N . w. The denominator
    // is computed from N directly, not as det: the sum of three edge functions carries an
    // error that grows with the square of the distance from the origin
    const DVec3 N = glm::cross(b - a, c - a);
    const double Nw = glm::dot(N, w);
    if (Nw == 0.0) return std::nullopt;
    const float t = static_cast<float>(glm::dot(N, a) / Nw);
    if (!(t >= r.tmin && t <= r.tmax)) return std::nullopt;
    Hit hit;
    hit.t = t;
    hit.position = r.o + t * r.w;
    hit.n = Vec3(glm::normalize(N));
    hit.uv = Vec2(static_cast<float>(e1 / det), static_cast<float>(e2 / det));
    return hit;
}

}  // namespace raylab::reference
