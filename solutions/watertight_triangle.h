// The watertight ray-triangle test of module 05's reference (05_triangle.cpp), shared
// with the reference's engine (engine_geometry.cpp) so that the two make the same
// decisions by construction: Woop, Benthin and Wald, "Watertight Ray/Triangle
// Intersection" (JCGT 2013), as in pbrt-v4 §6.5.3, in double.
//
// The vertices are moved into a frame where the ray is the +z axis (translate to o,
// permute so the largest |w| component is z, shear), and the edge functions are 2D cross
// products of the transformed vertices. Every triangle sharing a vertex uses the same
// transformed vertex, and an edge shared by two triangles gives exactly opposite edge
// functions, so a ray through an edge or a vertex always hits one of the triangles around
// it. The transform runs in double (o and the vertices are float, so v - o is exact).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/type_ptr.hpp>

#include "raylab/contract.h"

namespace raylab::reference::watertight {

/// The per-ray part: the permutation that makes the largest |w| component z (kx, ky, kz
/// cyclic), and the shear.
struct WoopRay {
    double ox, oy, oz;
    int kx, ky, kz;
    double sx, sy, sz;
    bool valid;  ///< false: w = 0, every triangle is missed

    explicit WoopRay(const Ray& r) {
        const float ax = std::abs(r.w.x), ay = std::abs(r.w.y), az = std::abs(r.w.z);
        kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
        kx = kz == 2 ? 0 : kz + 1;
        ky = kx == 2 ? 0 : kx + 1;
        // Components through pointers: glm's operator[] is a switch, and with it the
        // test took half as long again (raylab-bench, section 1)
        const float* w = glm::value_ptr(r.w);
        const float* o = glm::value_ptr(r.o);
        const double Wz = w[kz];
        valid = Wz != 0.0;
        sz = valid ? 1.0 / Wz : 0.0;
        sx = -double(w[kx]) * sz;
        sy = -double(w[ky]) * sz;
        ox = o[kx], oy = o[ky], oz = o[kz];
    }
    /// A vertex translated, permuted and sheared (x, y); z is scaled later.
    void transform(const Vec3& vertex, double& x, double& y, double& z) const {
        const float* v = glm::value_ptr(vertex);
        z = double(v[kz]) - oz;
        x = (double(v[kx]) - ox) + sx * z;
        y = (double(v[ky]) - oy) + sy * z;
    }
};

/// A triangle that passed the edge test, seen from a WoopRay.
struct Candidate {
    double x[3], y[3], z[3];  ///< transformed vertices, z scaled by sz
    double e[3];              ///< edge functions: e[i] is the weight of vertex i
    double inv_det;           ///< 1 / (e0 + e1 + e2)
    double t;                 ///< the hit's t, in double
};

/// False when the ray certainly misses (w = 0, edge functions of mixed signs, det = 0);
/// else the candidate hit in c.
inline bool candidate(const WoopRay& q, const Vec3& v0, const Vec3& v1, const Vec3& v2,
                      Candidate& c) {
    if (!q.valid) return false;
    q.transform(v0, c.x[0], c.y[0], c.z[0]);
    q.transform(v1, c.x[1], c.y[1], c.z[1]);
    q.transform(v2, c.x[2], c.y[2], c.z[2]);
    c.e[0] = c.x[1] * c.y[2] - c.y[1] * c.x[2];
    c.e[1] = c.x[2] * c.y[0] - c.y[2] * c.x[0];
    c.e[2] = c.x[0] * c.y[1] - c.y[0] * c.x[1];
    // Mixed signs: a miss (| and &, not || and &&: one branch instead of six)
    const bool any_negative = (c.e[0] < 0) | (c.e[1] < 0) | (c.e[2] < 0);
    const bool any_positive = (c.e[0] > 0) | (c.e[1] > 0) | (c.e[2] > 0);
    if (any_negative & any_positive) return false;
    const double det = c.e[0] + c.e[1] + c.e[2];
    if (det == 0.0) return false;
    // Scaled distance; t = t_scaled / det
    for (double& z : c.z)
        z *= q.sz;
    const double t_scaled = c.e[0] * c.z[0] + c.e[1] * c.z[1] + c.e[2] * c.z[2];
    c.inv_det = 1.0 / det;
    c.t = t_scaled * c.inv_det;
    return true;
}

/// Conservative t > 0 (pbrt-v4 §6.8.7, with double's gamma): false for a hit whose t is
/// within its own rounding error of 0, which may lie behind the origin.
inline bool in_front(const Candidate& c) {
    constexpr double u = 0.5 * std::numeric_limits<double>::epsilon();
    const auto gamma = [](int n) { return n * u / (1 - n * u); };
    const auto max_abs = [](const double(&v)[3]) {
        return std::max({std::abs(v[0]), std::abs(v[1]), std::abs(v[2])});
    };
    const double max_z = max_abs(c.z), max_x = max_abs(c.x), max_y = max_abs(c.y);
    const double dz = gamma(3) * max_z;
    const double dx = gamma(5) * (max_x + max_z), dy = gamma(5) * (max_y + max_z);
    const double de = 2 * (gamma(2) * max_x * max_y + dy * max_x + dx * max_y);
    const double max_e = max_abs(c.e);
    const double dt =
        3 * (gamma(3) * max_e * max_z + de * max_z + dz * max_e) * std::abs(c.inv_det);
    return c.t > dt;
}

/// The hit's uv: the barycentric weights of v1 and v2.
inline Vec2 uv(const Candidate& c) {
    return Vec2(static_cast<float>(c.e[1] * c.inv_det),
                static_cast<float>(c.e[2] * c.inv_det));
}

/// The normalised normal (v1 - v0) x (v2 - v0) in double, rounded to float; NaN when it
/// has no length.
inline Vec3 unit_normal(const Vec3& v0, const Vec3& v1, const Vec3& v2, double& len) {
    const DVec3 N = glm::cross(DVec3(v1) - DVec3(v0), DVec3(v2) - DVec3(v0));
    len = glm::length(N);
    return Vec3(N * (1.0 / len));
}

}  // namespace raylab::reference::watertight
