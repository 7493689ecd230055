// Reference for module 05_triangle (docs/handouts/05_triangle.md).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

#include <glm/gtc/type_ptr.hpp>

#include "raylab/contract.h"
#include "raylab/simd.h"

namespace raylab::reference {

#if RAYLAB_SSE2
namespace {
std::optional<Hit> intersect_triangle_sse2(const Ray& r, const Vec3& v0, const Vec3& v1,
                                           const Vec3& v2);
}  // namespace
#endif

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
///
/// On x86-64 the work is done by intersect_triangle_sse2 (below): the same floating-point
/// operations on the same values, so the same results bit for bit, arranged for speed
/// (1.3 times float Moeller-Trumbore per test instead of 1.9; raylab-bench, section 1).
/// The code here is what it computes, and what runs elsewhere or with RAYLAB_NO_SIMD
/// (tests/stress/test_triangle_twins.cpp compares the two).
std::optional<Hit> intersect_triangle(const Ray& r, const Vec3& v0, const Vec3& v1,
                                      const Vec3& v2) {
#if RAYLAB_SSE2
    return intersect_triangle_sse2(r, v0, v1, v2);
#else
    // Permutation: kz is the axis of the largest |w| component, (kx, ky, kz) cyclic. The
    // components are loaded through pointers: glm's operator[] is a switch, and with it
    // the test took half as long again (raylab-bench, section 1)
    const float ax = std::abs(r.w.x), ay = std::abs(r.w.y), az = std::abs(r.w.z);
    const int kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    const int kx = kz == 2 ? 0 : kz + 1, ky = kx == 2 ? 0 : kx + 1;
    const float* w = glm::value_ptr(r.w);
    const float* o = glm::value_ptr(r.o);
    const double Wz = w[kz];
    if (Wz == 0.0) return std::nullopt;
    const double sz = 1.0 / Wz, sx = -double(w[kx]) * sz, sy = -double(w[ky]) * sz;
    const double ox = o[kx], oy = o[ky], oz = o[kz];
    const auto transform = [&](const Vec3& vertex, double& x, double& y, double& z) {
        const float* v = glm::value_ptr(vertex);
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
#endif
}

#if RAYLAB_SSE2
namespace {
// [p[i], p[j]] in double
inline __m128d pair_pd(const float* p, unsigned i, unsigned j) {
    return _mm_cvtps_pd(_mm_unpacklo_ps(_mm_load_ss(p + i), _mm_load_ss(p + j)));
}
// [p[0], p[1]] in double (the two floats copied as one 8-byte value: a float is only
// 4-byte aligned, so _mm_load_sd on them would be a misaligned double load, undefined
// behaviour that the sanitizer build reports)
inline __m128d load2_pd(const float* p) {
    double two_floats;
    std::memcpy(&two_floats, p, sizeof two_floats);
    return _mm_cvtps_pd(_mm_castpd_ps(_mm_set_sd(two_floats)));
}
// The layouts the 16-byte loads and stores below rely on
static_assert(sizeof(Vec3) == 12 && offsetof(Ray, w) == 12 && offsetof(Ray, tmin) == 24);
static_assert(offsetof(Hit, position) == 4 && offsetof(Hit, n) == 16 &&
              offsetof(Hit, ns) == 28 && offsetof(Hit, uv) == 40 &&
              offsetof(Hit, material) == 48);

// intersect_triangle with SSE2 (2026-11-25: 36 -> 24 ns per test in raylab-bench's
// section 1, the same results on 20 million adversarial cases): the transformed (x, y)
// of a vertex share a register, so one multiplication gives both products of an edge
// function; the axis choice has no branch; the sign test is one branch (GCC made the
// original two, the first as unpredictable as the second); pbrt's bound on t is tested
// against a cheap upper bound first; the Hit is written with three 16-byte stores
std::optional<Hit> intersect_triangle_sse2(const Ray& r, const Vec3& v0, const Vec3& v1,
                                           const Vec3& v2) {
    // kz: the axis of the largest |w| component, comparing bit patterns: the same order
    // as the float compares for non-NaN values (a NaN anywhere makes every choice a miss)
    uint32_t ix, iy, iz;
    std::memcpy(&ix, &r.w.x, 4), std::memcpy(&iy, &r.w.y, 4), std::memcpy(&iz, &r.w.z, 4);
    ix &= 0x7fffffffu, iy &= 0x7fffffffu, iz &= 0x7fffffffu;
    // qa: kz = 0, qb: kz = 1, neither: kz = 2; kx = (kz + 1) % 3, ky = (kz + 2) % 3
    const unsigned c1 = ix > iy, qa = c1 & (ix > iz), qb = (c1 ^ 1) & (iy > iz);
    const unsigned kz = 2 - 2 * qa - qb, kx = qa + 2 * qb, ky = 1 + qa - qb;
    const float* w = glm::value_ptr(r.w);
    const float* o = glm::value_ptr(r.o);
    // No Wz == 0 test: then w = 0, sx = -0 * inf is NaN, so is every e, and td fails
    // below
    const double sz = 1.0 / double(w[kz]);
    const __m128d S =
        _mm_mul_pd(_mm_xor_pd(pair_pd(w, kx, ky), _mm_set1_pd(-0.0)), _mm_set1_pd(sz));
    const __m128d O = pair_pd(o, kx, ky);
    const double oz = o[kz];
    const auto transform = [&](const Vec3& vertex, double& z) {  // [x, y], z
        const float* v = glm::value_ptr(vertex);
        z = double(v[kz]) - oz;
        return _mm_add_pd(_mm_sub_pd(pair_pd(v, kx, ky), O),
                          _mm_mul_pd(S, _mm_set1_pd(z)));
    };
    double z0, z1, z2;
    const __m128d p0 = transform(v0, z0), p1 = transform(v1, z1), p2 = transform(v2, z2);
    const __m128d a = _mm_mul_pd(p1, _mm_shuffle_pd(p2, p2, 1));  // x1 y2, y1 x2
    const __m128d b = _mm_mul_pd(p2, _mm_shuffle_pd(p0, p0, 1));  // x2 y0, y2 x0
    const __m128d c = _mm_mul_pd(p0, _mm_shuffle_pd(p1, p1, 1));  // x0 y1, y0 x1
    const __m128d e01 =
        _mm_sub_pd(_mm_unpacklo_pd(a, b), _mm_unpackhi_pd(a, b));  // e0 e1
    const __m128d e22 =
        _mm_sub_pd(_mm_unpacklo_pd(c, c), _mm_unpackhi_pd(c, c));  // e2 e2
    const __m128d zero = _mm_setzero_pd();
    const unsigned neg = _mm_movemask_pd(_mm_cmplt_pd(_mm_min_pd(e01, e22), zero));
    const unsigned pos = _mm_movemask_pd(_mm_cmpgt_pd(_mm_max_pd(e01, e22), zero));
    // Mixed signs (a miss) iff neg != 0 and pos != 0: one branch, bit neg | pos << 2 of
    // 0xEEE0
    if ((0xEEE0u >> (neg | pos << 2)) & 1) return std::nullopt;
    const double e0 = _mm_cvtsd_f64(e01), e1 = _mm_cvtsd_f64(_mm_unpackhi_pd(e01, e01));
    const double e2 = _mm_cvtsd_f64(e22);
    // No det == 0 test: the e are then all zero, inv_det infinite and td = 0 * inf NaN
    const double det = e0 + e1 + e2;
    z0 *= sz, z1 *= sz, z2 *= sz;
    const double t_scaled = e0 * z0 + e1 * z1 + e2 * z2;
    const double inv_det = 1.0 / det;
    const double td = t_scaled * inv_det;
    constexpr double u = 0.5 * std::numeric_limits<double>::epsilon();
    const __m128d absm = _mm_castsi128_pd(_mm_set1_epi64x(0x7fffffffffffffffLL));
    const __m128d M = _mm_max_pd(_mm_max_pd(_mm_and_pd(p0, absm), _mm_and_pd(p1, absm)),
                                 _mm_and_pd(p2, absm));  // max_x max_y
    const double max_z = std::max(std::max(std::abs(z0), std::abs(z1)), std::abs(z2));
    const double max_x = _mm_cvtsd_f64(M), max_y = _mm_cvtsd_f64(_mm_unpackhi_pd(M, M));
    const double abs_inv_det = std::abs(inv_det);
    // Fast accept of the test td > dt below. The e have one sign, so max_e |inv_det| <=
    // 1 + 4u, and dt <= max_z (18u + 30u q |inv_det|)(1 + 20u) with
    // q = 3 max_x max_y + max_z (max_x + max_y); B exceeds that with room for its own
    // rounding. max_z >= 2^-300 and |inv_det| <= 2^300 make underflow in dt's terms
    // negligible (and max_z <= 2^278 for finite float input).
    const double q = 3 * (max_x * max_y) + max_z * (max_x + max_y);
    const double B = max_z * (32 * u + (64 * u) * (q * abs_inv_det));
    if (__builtin_expect(!(td > B && max_z >= 0x1p-300 && abs_inv_det <= 0x1p300), 0)) {
        // The conservative t > 0 test of intersect_triangle, the same operations
        const auto gamma = [](int n) { return n * u / (1 - n * u); };
        const __m128d D = _mm_mul_pd(_mm_set1_pd(gamma(5)),
                                     _mm_add_pd(M, _mm_set1_pd(max_z)));  // dx dy
        const __m128d T = _mm_mul_pd(_mm_shuffle_pd(D, D, 1), M);  // dy max_x, dx max_y
        const double dz = gamma(3) * max_z;
        const double de = 2 * ((gamma(2) * max_x * max_y + _mm_cvtsd_f64(T)) +
                               _mm_cvtsd_f64(_mm_unpackhi_pd(T, T)));
        const __m128d E = _mm_and_pd(e01, absm);
        const double max_e =
            std::max(std::max(_mm_cvtsd_f64(E), _mm_cvtsd_f64(_mm_unpackhi_pd(E, E))),
                     std::abs(e2));
        const double dt =
            3 * (gamma(3) * max_e * max_z + de * max_z + dz * max_e) * abs_inv_det;
        if (!(td > dt)) return std::nullopt;
    }
    const float t = static_cast<float>(td);
    if (!(t >= r.tmin && t <= r.tmax)) return std::nullopt;
    // Normal in double, from the [x y] and [y z] pairs of each vertex
    const __m128d a0 = load2_pd(&v0.x), b0 = load2_pd(&v0.y);
    const __m128d d1 = _mm_sub_pd(load2_pd(&v1.x), a0),
                  d1s = _mm_sub_pd(load2_pd(&v1.y), b0);
    const __m128d d2 = _mm_sub_pd(load2_pd(&v2.x), a0),
                  d2s = _mm_sub_pd(load2_pd(&v2.y), b0);
    const __m128d NxNy =
        _mm_sub_pd(_mm_mul_pd(d1s, _mm_shuffle_pd(d2s, d2, 1)),     // 1y 2z, 1z 2x
                   _mm_mul_pd(d2s, _mm_shuffle_pd(d1s, d1, 1)));    // 2y 1z, 2z 1x
    const __m128d nzp = _mm_mul_pd(d1, _mm_shuffle_pd(d2, d2, 1));  // 1x 2y, 1y 2x
    const __m128d Nz = _mm_sub_sd(nzp, _mm_unpackhi_pd(nzp, nzp));
    const __m128d sq = _mm_mul_pd(NxNy, NxNy);
    const __m128d len2 =
        _mm_add_sd(_mm_add_sd(sq, _mm_unpackhi_pd(sq, sq)), _mm_mul_sd(Nz, Nz));
    const __m128d len = _mm_sqrt_sd(len2, len2);
    if (!(_mm_cvtsd_f64(len) > 0.0)) return std::nullopt;
    const __m128d inv1 = _mm_div_sd(_mm_set_sd(1.0), len);
    const __m128d inv = _mm_unpacklo_pd(inv1, inv1);
    const __m128 nxy = _mm_cvtpd_ps(_mm_mul_pd(NxNy, inv));
    const __m128 nz = _mm_cvtsd_ss(_mm_setzero_ps(), _mm_mul_sd(Nz, inv));
    const __m128 uv =
        _mm_cvtpd_ps(_mm_mul_pd(_mm_shuffle_pd(e01, e22, 1), _mm_set1_pd(inv_det)));
    Hit hit;
    // 0 o, 0 w (the loads read w.x and tmin, members of Ray)
    const __m128 ov =
        _mm_castsi128_ps(_mm_slli_si128(_mm_castps_si128(_mm_loadu_ps(o)), 4));
    const __m128 wv =
        _mm_castsi128_ps(_mm_slli_si128(_mm_castps_si128(_mm_loadu_ps(w)), 4));
    const __m128 tv = _mm_set1_ps(t);
    float* h = &hit.t;
    _mm_storeu_ps(h, _mm_move_ss(_mm_add_ps(ov, _mm_mul_ps(tv, wv)), tv));  // t, o + t w
    _mm_storeu_ps(h + 4, _mm_movelh_ps(nxy, nz));                           // n, ns.x = 0
    _mm_storeu_ps(h + 8, _mm_movelh_ps(_mm_setzero_ps(), uv));  // ns.yz = 0, uv
    return hit;
}
}  // namespace
#endif

}  // namespace raylab::reference
