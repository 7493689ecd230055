// The reference engine's tests and its Hit for the nearest primitive, shared by the
// single-ray queries (engine_geometry.cpp) and the packet query (engine_packet.cpp).
// Not a module: see engine_geometry.cpp for why the engine repeats the modules' numerics.
#pragma once

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>

#include <glm/gtc/type_ptr.hpp>

#include "engine_data.h"
#include "engine_walk.h"
#include "raylab/engine.h"
#include "raylab/refine.h"  // unit_normal
#include "raylab/scene.h"
#include "raylab/simd.h"

namespace raylab::reference::engine_kernels {

// intersect_plane's t, or NaN when it returns nullopt
inline float plane_t(const Ray& r, const Plane& plane, float tmax) {
    const float wn = glm::dot(r.w, plane.n);
    if (wn == 0.0f) return NAN;
    const double dist =
        glm::dot(DVec3(r.o), DVec3(plane.n)) + static_cast<double>(plane.d);
    const float t = static_cast<float>(-dist / static_cast<double>(wn));
    if (!(t >= r.tmin && t <= tmax) || std::isinf(t)) return NAN;
    return t;
}

// intersect_sphere's t (Ray Tracing Gems ch. 7; rays starting on the sphere in double),
// or NaN
inline float sphere_t(const Ray& r, const Vec3& centre, float radius, float tmax) {
    const Vec3 f = r.o - centre;
    const float rr = radius * radius, ff = glm::dot(f, f);
    float c = ff - rr;
    float b, disc;
    if (std::abs(c) > 0x1p-16f * (ff + rr)) {
        b = glm::dot(f, r.w);
        const Vec3 l = f - b * r.w;
        disc = rr - glm::dot(l, l);
    } else {
        const DVec3 fd = DVec3(r.o) - DVec3(centre), w(r.w);
        const double rrd = double(radius) * double(radius), bd = glm::dot(fd, w);
        const DVec3 l = fd - bd * w;
        c = static_cast<float>(glm::dot(fd, fd) - rrd);
        b = static_cast<float>(bd);
        disc = static_cast<float>(rrd - glm::dot(l, l));
    }
    if (disc < 0.0f) return NAN;
    const float q = -b - std::copysign(std::sqrt(disc), b);
    float t0 = q;
    float t1 = q != 0.0f ? c / q : 0.0f;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 >= r.tmin && t0 <= tmax) return t0;
    if (t1 >= r.tmin && t1 <= tmax) return t1;
    return NAN;
}

// The per-ray part of the watertight test (Woop, Benthin and Wald, JCGT 2013): the
// permutation that makes the largest |w| component z, and the shear
struct WoopRay {
    double ox, oy, oz;
    int kx, ky, kz;
    double sx, sy, sz;
    bool valid;  // false: w = 0, every triangle is missed

    // The axis of w's largest |component|, and the two after it
    static int dominant_axis(const Vec3& w) {
        const float ax = std::abs(w.x), ay = std::abs(w.y), az = std::abs(w.z);
        return ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    }
    static int next_axis(int a) { return a == 2 ? 0 : a + 1; }

    // The axes chosen by branches, which coherent rays (a camera's, a light's shadow
    // rays) predict: the first test starts at once
    explicit WoopRay(const Ray& r) {
        kz = dominant_axis(r.w);
        kx = next_axis(kz);
        ky = next_axis(kx);
        const float* w = glm::value_ptr(r.w);
        const double Wz = w[kz];
        valid = Wz != 0.0;
        sz = valid ? 1.0 / Wz : 0.0;
        set_shear(r);
    }
    // The same values without a branch on the axes, for the closest-hit query, whose
    // rays may come from anywhere: the branches mispredicted 0.9 times a random ray in
    // the Cornell box. 1 / w_kz is |w|'s largest component's reciprocal, with w_kz's
    // sign (division is symmetric in sign, so the same double), and the division starts
    // without waiting for the axis, which camera rays waited on (docs/decisions/0003)
    struct Unpredictable {};
    WoopRay(const Ray& r, Unpredictable) {
        const float ax = std::abs(r.w.x), ay = std::abs(r.w.y), az = std::abs(r.w.z);
        const double largest = std::max(ax, std::max(ay, az));
        const double inv_largest = 1.0 / largest;
        // dominant_axis's choice: ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2)
        const int c1 = ax > ay, c2 = ax > az, c3 = ay > az;
        kz = 2 - ((c1 & c2) * 2 + ((c1 ^ 1) & c3));
        static constexpr int kNext[3] = {1, 2, 0};
        kx = kNext[kz];
        ky = kNext[kx];
        const double Wz = glm::value_ptr(r.w)[kz];
        valid = Wz != 0.0;
        // |w_kz| is the largest |component| unless w holds a NaN (then 1 / w_kz, as
        // above: NaN where w_kz is)
        if (__builtin_expect(std::abs(Wz) == largest || !valid, 1))
            sz = valid ? std::copysign(inv_largest, Wz) : 0.0;
        else
            sz = 1.0 / Wz;
        set_shear(r);
    }
    void set_shear(const Ray& r) {
        const float* w = glm::value_ptr(r.w);
        const float* o = glm::value_ptr(r.o);
        sx = -double(w[kx]) * sz;
        sy = -double(w[ky]) * sz;
        ox = o[kx], oy = o[ky], oz = o[kz];
    }
    // Components loaded by index: glm's operator[] is a switch, which costs a third of
    // the test
    void transform(const DVec3& vertex, double& x, double& y, double& z) const {
        const double* v = glm::value_ptr(vertex);
        z = v[kz] - oz;
        x = (v[kx] - ox) + sx * z;
        y = (v[ky] - oy) + sy * z;
    }
    void transform(const Vec3& vertex, double& x, double& y, double& z) const {
        const float* v = glm::value_ptr(vertex);
        z = double(v[kz]) - oz;
        x = (double(v[kx]) - ox) + sx * z;
        y = (double(v[ky]) - oy) + sy * z;
    }
};

// What intersect_triangle's Hit holds besides t, position and normal
struct TriangleExtra {
    Vec2 uv;
    double td, dt;  // t in double and its error bound (pbrt-v4's deltaT)
};

// intersect_triangle's t, or NaN: the same operations (and the same decisions); on a
// hit, its uv in extra. degenerate: the scene's flag for this triangle
template <class V>
inline float triangle_t(const Ray& r, const WoopRay& q, const V& v0, const V& v1,
                        const V& v2, bool degenerate, float tmax, TriangleExtra& extra) {
    if (!q.valid) return NAN;
    double x0, y0, z0, x1, y1, z1, x2, y2, z2;
    q.transform(v0, x0, y0, z0);
    q.transform(v1, x1, y1, z1);
    q.transform(v2, x2, y2, z2);
    const double e0 = x1 * y2 - y1 * x2;
    const double e1 = x2 * y0 - y2 * x0;
    const double e2 = x0 * y1 - y0 * x1;
    const bool any_negative = (e0 < 0) | (e1 < 0) | (e2 < 0);
    const bool any_positive = (e0 > 0) | (e1 > 0) | (e2 > 0);
    if (any_negative & any_positive) return NAN;
    const double det = e0 + e1 + e2;
    if (det == 0.0) return NAN;
    z0 *= q.sz, z1 *= q.sz, z2 *= q.sz;
    const double t_scaled = e0 * z0 + e1 * z1 + e2 * z2;
    const double inv_det = 1.0 / det;
    const double td = t_scaled * inv_det;
    // The module's last two tests, t's range and then t > 0, in the other order: a
    // candidate behind the nearest hit so far is refused before the bound
    const float t = static_cast<float>(td);
    if (!(t >= r.tmin && t <= tmax)) return NAN;
    // pbrt-v4 §6.8.7's conservative t > 0, with double's gamma
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
    if (!(td > dt)) return NAN;
    // The module also refuses a triangle whose normal has no length: the engine marks
    // those when it prepares the scene (SceneData::degenerate); the nearest hit's normal
    // is computed once, or read from its data (SceneData::face_normal)
    if (degenerate) return NAN;
    extra.uv = Vec2(static_cast<float>(e1 * inv_det), static_cast<float>(e2 * inv_det));
    extra.td = td;
    extra.dt = dt;
    return t;
}

// The scene's spheres and triangles as the BVH's slots name them (spheres first,
// triangles after them), read once per query
struct Primitives {
    const std::uint32_t* order;  // slot -> primitive
    const SceneSphere* spheres;
    const SceneTriangle* triangles;
    std::uint32_t sphere_count;
    const SceneData& data;

    explicit Primitives(const Scene& s)
        : order(s.bvh().prims().data()),
          spheres(s.spheres.data()),
          triangles(s.triangles.data()),
          sphere_count(static_cast<std::uint32_t>(s.spheres.size())),
          data(scene_data(s)) {}

    // t of the primitive in slot s, or NaN
    __attribute__((always_inline)) float t(const Ray& r, const WoopRay& q,
                                           std::uint32_t s, float tmax,
                                           TriangleExtra& extra) const {
        const std::uint32_t p = order[s];
        if (p < sphere_count) {
            const Sphere& sphere = spheres[p].sphere;
            return sphere_t(r, sphere.c, sphere.r, tmax);
        }
        const std::uint32_t k = p - sphere_count;
        // The flag is read for every test, not only for one that passes: its load then
        // overlaps the test instead of following it (docs/decisions/0004)
        const SceneTriangle& tri = triangles[k];
        return triangle_t(r, q, tri.v0, tri.v1, tri.v2, data.degenerate(k), tmax, extra);
    }
    // The primitive in slot s, as the BVH names it
    std::uint32_t prim(std::uint32_t s) const { return order[s]; }
};

// The same tests in a scene without spheres, whose triangles commit() has put in the
// BVH's slot order (Scene::triangles): slot s holds triangle s, read with no load of the
// order before it, which random rays through large meshes wait on (docs/decisions/0004)
struct SlotOrderTriangles {
    const SceneTriangle* triangles;
    const Scene& scene;
    const SceneData& data;

    explicit SlotOrderTriangles(const Scene& s)
        : triangles(s.triangles.data()), scene(s), data(scene_data(s)) {
        assert(s.spheres.empty());
    }
    // t of the triangle in slot s, or NaN
    __attribute__((always_inline)) float t(const Ray& r, const WoopRay& q,
                                           std::uint32_t s, float tmax,
                                           TriangleExtra& extra) const {
        assert(scene.bvh().prims()[s] == s);
        const SceneTriangle& tri = triangles[s];
        return triangle_t(r, q, tri.v0, tri.v1, tri.v2, data.degenerate(s), tmax, extra);
    }
    std::uint32_t prim(std::uint32_t s) const { return s; }
};

// The same tests read from the engine's copy of the primitives in slot order
// (SceneData::slot_primitives), in scenes small enough to keep one: a leaf's primitives
// lie side by side, and no load of the order comes before each
struct SlotPrimitives {
    const SceneData::SlotPrimitive* slots;

    // t of the primitive in slot s, or NaN
    __attribute__((always_inline)) float t(const Ray& r, const WoopRay& q,
                                           std::uint32_t s, float tmax,
                                           TriangleExtra& extra) const {
        const SceneData::SlotPrimitive& p = slots[s];
        if (p.prim & SceneData::SlotPrimitive::kSphere)
            return sphere_t(r, Vec3(p.a), float(p.b.x), tmax);
        return triangle_t(r, q, p.a, p.b, p.c,
                          (p.prim & SceneData::SlotPrimitive::kDegenerate) != 0, tmax,
                          extra);
    }
    // The primitive in slot s, as the BVH names it
    std::uint32_t prim(std::uint32_t s) const {
        return slots[s].prim & SceneData::SlotPrimitive::kIndexMask;
    }
};

// at[a] = v0[a] on each axis a whose coordinate the triangle's three vertices share (the
// plane's, exactly, as the refinement's projection gives it), without a branch: which
// axes those are changes from hit to hit (the Cornell box's walls; the branches
// mispredicted 1.3 times a random ray there)
inline void snap_shared_coordinates(const SceneTriangle& tri, DVec3& at) {
    double* p = glm::value_ptr(at);
#if RAYLAB_SSE2
    // 16 bytes from each vertex: the fourth float is the next member's, never used
    static_assert(offsetof(SceneTriangle, v2) + 16 <= sizeof(SceneTriangle));
    const __m128 v0 = _mm_loadu_ps(glm::value_ptr(tri.v0));
    const __m128 same =
        _mm_and_ps(_mm_cmpeq_ps(v0, _mm_loadu_ps(glm::value_ptr(tri.v1))),
                   _mm_cmpeq_ps(v0, _mm_loadu_ps(glm::value_ptr(tri.v2))));
    // x and y: the masks of lanes 0 and 1 widened to 64 bits; z: lane 2's
    const __m128d mxy = _mm_castps_pd(_mm_unpacklo_ps(same, same));
    const __m128d mz = _mm_castps_pd(_mm_unpackhi_ps(same, same));
    const __m128d vxy = _mm_cvtps_pd(v0), vz = _mm_cvtps_pd(_mm_movehl_ps(v0, v0));
    const __m128d axy = _mm_loadu_pd(p), az = _mm_load_sd(p + 2);
    // mask ? a : b, lane by lane
    const auto select = [](__m128d mask, __m128d a, __m128d b) {
        return _mm_or_pd(_mm_and_pd(mask, a), _mm_andnot_pd(mask, b));
    };
    _mm_storeu_pd(p, select(mxy, vxy, axy));
    _mm_store_sd(p + 2, select(mz, vz, az));
#else
    // The scalar twin needs only the same results, not the absence of a branch
    const float *v0 = glm::value_ptr(tri.v0), *v1 = glm::value_ptr(tri.v1),
                *v2 = glm::value_ptr(tri.v2);
    for (int a = 0; a < 3; ++a) {
        if (v0[a] == v1[a] && v0[a] == v2[a]) p[a] = v0[a];
    }
#endif
}

// The module's Hit of the query's nearest primitive, from the values of its accepted test
// (the module's expressions), and best naming it. in_bvh: the nearest is best_prim, a
// BVH slot's primitive; otherwise it is the plane best already names
inline void finish_hit(const Scene& scene, const Primitives& prims, const Ray& r,
                       float best_t, bool in_bvh, std::uint32_t best_prim,
                       const TriangleExtra& best_extra, Hit& hit, PrimRef& best) {
    // The module's Hit, from the values of the accepted test (same expressions)
    hit = Hit{};
    hit.t = best_t;
    hit.position = r.o + best_t * r.w;
    if (!in_bvh) {
        hit.n = scene.planes[best.index].plane.n;
        return;
    }
    const std::uint32_t p = best_prim;
    if (p < prims.sphere_count) {
        const Sphere& sphere = prims.spheres[p].sphere;
        hit.n = (hit.position - sphere.c) / sphere.r;
        best = {PrimRef::Kind::sphere, p};
        return;
    }
    const std::uint32_t k = p - prims.sphere_count;
    const SceneTriangle& tri = prims.triangles[k];
    // intersect_triangle's normal: the engine's, where it keeps one
    hit.n = prims.data.has_face_normals() ? prims.data.face_normal(k) : unit_normal(tri);
    hit.uv = best_extra.uv;
    // The hit point from t in double, when its error bound (pbrt-v4's deltaT, above)
    // shows it within 2^-30 of its size of the exact intersection of the ray with the
    // triangle's plane, the point the scene's refinement computes (raylab/refine.h):
    // rounded to float, at most 1/64 of an ulp more from it, and no plane normal, dot
    // products and division on the way (a fifth of a Cornell box camera ray). A
    // coordinate all three vertices share is the plane's, exactly, as the refinement's
    // projection gives it. Otherwise (grazing rays, a far camera) the scene refines
    const DVec3 o(r.o), w(r.w);
    DVec3 at = o + best_extra.td * w;
    const auto max_abs = [](const DVec3& v) {
        return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    };
    // deltaT bounds the error of t only for |w| <= 1: its shear terms take z after the
    // division by w_kz, and the rounding of the shear, about 3u |z| before it, is missed
    // when |w_kz| > 1 (a ray with |w| = 1e6 was thousands of deltaT off). Ray::w is
    // unit by contract; a longer one takes the scene's refinement. deltaT also leaves
    // out the determinant's own rounding, which can make it up to twice too small: it
    // counts twice here
    const double W = max_abs(w);
    const bool refined =
        W <= 1.0 &&
        2.0 * best_extra.dt * W + 0x1p-52 * (max_abs(o) + std::abs(best_extra.td) * W) <=
            0x1p-30 * max_abs(at);
    if (refined) {
        snap_shared_coordinates(tri, at);
        hit.position = Vec3(at);
    }
    best = {PrimRef::Kind::triangle, k, refined};
}

// The engine's queries (raylab/engine.h), each the version chosen for this processor
// (engine_simd.h): closest_hit and any_hit in engine_geometry.cpp, the packet query in
// engine_packet.cpp. closest_hit is what the packet query calls for a ray it cannot
// take or must trace again alone
void closest_hit(const Scene& scene, const Ray& r, TraceCounters& counters, Hit& hit,
                 PrimRef& best);
decltype(GeometryEngine::closest_hit_packet) chosen_packet_query();

}  // namespace raylab::reference::engine_kernels
