// Reference for module 05_triangle (docs/handouts/05_triangle.md).
#include <algorithm>
#include <cmath>
#include <limits>

#include "raylab/contract.h"

namespace raylab::reference {

/// Ray-triangle intersection (handout 05 §2-§4). The hit point is
///   r(t) = (1 - beta - gamma) v0 + beta v1 + gamma v2,  beta, gamma >= 0, beta + gamma
///   <= 1,
/// hit.uv = (beta, gamma), hit.n = normalize((v1 - v0) x (v2 - v0)) (counter-clockwise
/// vertices face the viewer). Both sides are hit. Degenerate triangles are never hit.
///
/// Watertight test after Woop, Benthin and Wald (JCGT 2013), as in pbrt-v4: the vertices
/// are moved into a frame where the ray is the +z axis (translate to o, permute so the
/// largest |w| component is z, shear), and the edge functions are 2D cross products of
/// the transformed vertices. Every triangle sharing a vertex uses the same transformed
/// vertex, and an edge shared by two triangles gives exactly opposite edge functions, so
/// a ray through an edge or a vertex always hits one of the triangles around it. The
/// transform runs in double (o and the vertices are float, so v - o is exact).
std::optional<Hit> intersect_triangle(const Ray& r, const Vec3& v0, const Vec3& v1,
                                      const Vec3& v2) {
    // Permutation: kz is the axis of the largest |w| component, (kx, ky, kz) cyclic. The
    // components are read through pointers (glm's operator[] is a switch)
    const float ax = std::abs(r.w.x), ay = std::abs(r.w.y), az = std::abs(r.w.z);
    const int kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    const int kx = kz == 2 ? 0 : kz + 1, ky = kx == 2 ? 0 : kx + 1;
    const float* w = &r.w.x;
    const float* o = &r.o.x;
    const double Wz = w[kz];
    if (Wz == 0.0) return std::nullopt;
    const double sz = 1.0 / Wz, sx = -double(w[kx]) * sz, sy = -double(w[ky]) * sz;
    const double ox = o[kx], oy = o[ky], oz = o[kz];
    const auto transform = [&](const Vec3& vertex, double& x, double& y, double& z) {
        const float* v = &vertex.x;
        z = double(v[kz]) - oz;
        x = (double(v[kx]) - ox) + sx * z;
        y = (double(v[ky]) - oy) + sy * z;
    };
    double x0, y0, z0, x1, y1, z1, x2, y2, z2;
    transform(v0, x0, y0, z0);
    transform(v1, x1, y1, z1);
    transform(v2, x2, y2, z2);
    // Edge functions: e0 is the weight of v0 (edge v1 v2), e1 of v1, e2 of v2
    const double e0 = x1 * y2 - y1 * x2;
    const double e1 = x2 * y0 - y2 * x0;
    const double e2 = x0 * y1 - y0 * x1;
    // Mixed signs: a miss (| and &, not || and &&: one branch instead of six)
    const bool any_negative = (e0 < 0) | (e1 < 0) | (e2 < 0);
    const bool any_positive = (e0 > 0) | (e1 > 0) | (e2 > 0);
    if (any_negative & any_positive) return std::nullopt;
    const double det = e0 + e1 + e2;
    if (det == 0.0) return std::nullopt;
    // Scaled distance; t = t_scaled / det
    z0 *= sz, z1 *= sz, z2 *= sz;
    const double t_scaled = e0 * z0 + e1 * z1 + e2 * z2;
    const double inv_det = 1.0 / det;
    const double td = t_scaled * inv_det;
    // Conservative t > 0 (pbrt-v4 §6.8.7, with double's gamma): a hit whose t is within
    // its own rounding error of 0 may lie behind the origin
    constexpr double u = 0.5 * std::numeric_limits<double>::epsilon();
    const auto gamma = [](int n) { return n * u / (1 - n * u); };
    const double max_z = std::max({std::abs(z0), std::abs(z1), std::abs(z2)});
    const double max_x = std::max({std::abs(x0), std::abs(x1), std::abs(x2)});
    const double max_y = std::max({std::abs(y0), std::abs(y1), std::abs(y2)});
    const double dz = gamma(3) * max_z;
    const double dx = gamma(5) * (max_x + max_z), dy = gamma(5) * (max_y + max_z);
    const double de = 2 * (gamma(2) * max_x * max_y + dy * max_x + dx * max_y);
    const double max_e = std::max({std::abs(e0), std::abs(e1), std::abs(e2)});
    const double dt =
        3 * (gamma(3) * max_e * max_z + de * max_z + dz * max_e) * std::abs(inv_det);
    if (!(td > dt)) return std::nullopt;
    const float t = static_cast<float>(td);
    if (!(t >= r.tmin && t <= r.tmax)) return std::nullopt;
    Hit hit;
    hit.t = t;
    hit.position = r.o + t * r.w;
    const DVec3 N = glm::cross(DVec3(v1) - DVec3(v0), DVec3(v2) - DVec3(v0));
    const double len = glm::length(N);
    if (!(len > 0.0)) return std::nullopt;
    hit.n = Vec3(N * (1.0 / len));
    hit.uv = Vec2(static_cast<float>(e1 * inv_det), static_cast<float>(e2 * inv_det));
    return hit;
}

}  // namespace raylab::reference
