// The reference engine's packet query (GeometryEngine::closest_hit_packet): up to 16 rays
// from one origin, as a 4 x 4 block of a tile's camera rays, walk the BVH together (one
// frustum slab test per node, traverse_frustum) and test each triangle four rays at
// a time, with exactly the single-ray query's operations on exactly its values, so each
// ray gets closest_hit's result bit for bit (engine/tests/test_packets.cpp).
//
// Why it is faster: the walk's node tests, stack and branches are paid once per packet;
// with one origin, a triangle's vertices minus the origin (the watertight test's
// translation, in double) are computed once per packet, and the rest of the test runs on
// four rays in vectors of four doubles (two SSE2 registers each on the x86-64 baseline).
//
// Why it gives the same hits: every ray's test is the scalar test's sequence of IEEE
// operations (-ffp-contract=off), the frustum visits every leaf a ray's own walk would
// visit (Frustum), and the nearest accepted hit is the same whatever the order of
// the visit, except for a tie: two primitives accepted at the same t, where the
// single-ray walk keeps the one it visits last. A ray that meets a tie is traced again
// alone.
#include "engine_simd.h"

namespace raylab::reference::engine_kernels {

namespace {

constexpr int kMaxRays = GeometryEngine::kPacketSize;

// The packet: its rays' watertight shear (WoopRay) with the one
// permutation they share, and each ray's nearest hit so far
struct Packet {
    int kx, ky, kz;
    double ox, oy, oz;  // the shared origin, permuted
    alignas(32) double sx[kMaxRays], sy[kMaxRays], sz[kMaxRays];
    alignas(32) double tmin[kMaxRays], tmax[kMaxRays];  // floats, held exactly
    long long active[kMaxRays];  // all ones for a ray of the packet, 0 for padding
    alignas(16) float o[3];      // the shared origin
    alignas(16) float inv_w[3][kMaxRays];  // 1 / w per axis, as the single-ray walk's
    float best_t[kMaxRays];
    bool has_best[kMaxRays], in_bvh[kMaxRays], tie[kMaxRays];
    std::uint32_t best_prim[kMaxRays];
    TriangleExtra extra[kMaxRays];

    // Accepts primitive p at t for ray k: the single-ray walk's update, and a tie noted
    RAYLAB_INLINE void accept(int k, float t, std::uint32_t p) {
        tie[k] = tie[k] || (has_best[k] && t == best_t[k]);
        best_t[k] = t;
        tmax[k] = t;
        best_prim[k] = p;
        has_best[k] = in_bvh[k] = true;
    }
};

// Whether the rays can travel as one packet, and if so its set-up: one origin, every
// direction component of one sign and not zero (the frustum), one dominant axis (the
// triangle test's permutation), a range from tmin >= 0. The divisions run on whole
// vectors: 1 / w_kz for four rays at a time, and the frustum's reciprocals only for the
// extreme components (1 / w rounds monotonically, so the extremes of the rays' 1 / w are
// those of 1 / w_min and 1 / w_max)
RAYLAB_INLINE bool make_packet(const Ray* rays, int n, Packet& pk, Frustum& f) {
    const Ray& r0 = rays[0];
    pk.kz = WoopRay::dominant_axis(r0.w);
    pk.kx = WoopRay::next_axis(pk.kz);
    pk.ky = WoopRay::next_axis(pk.kx);
    const float* o = glm::value_ptr(r0.o);
    pk.ox = o[pk.kx], pk.oy = o[pk.ky], pk.oz = o[pk.kz];
    f.o = r0.o;
    f.tmin = r0.tmin;
    Vec3 w_lo = r0.w, w_hi = r0.w;
    alignas(32) double wx[kMaxRays], wy[kMaxRays], wz[kMaxRays];
    for (int k = 0; k < kMaxRays; ++k) {
        const Ray& r = rays[k < n ? k : 0];  // padding lanes repeat ray 0
        if (!(r.o == r0.o) || WoopRay::dominant_axis(r.w) != pk.kz) return false;
        // A range that starts behind the origin (or is NaN) goes by the single-ray walk's
        // own rules: the slab test's margin (exit * kSlabGrow) shrinks for a negative
        // exit, and a packet that visits the leaves in another order could then skip one
        // holding a hit a few ulps nearer than its first (two spheres behind the
        // origin, hits 2 ulps apart). Camera rays start at 0
        if (!(r.tmin >= 0.0f) || std::isnan(r.tmax)) return false;
        for (int a = 0; a < 3; ++a) {
            if (!(r0.w[a] > 0.0f ? r.w[a] > 0.0f : r.w[a] < 0.0f)) return false;
        }
        const float* w = glm::value_ptr(r.w);
        wx[k] = w[pk.kx], wy[k] = w[pk.ky], wz[k] = w[pk.kz];
        for (int a = 0; a < 3; ++a)
            pk.inv_w[a][k] = w[a];
        w_lo = glm::min(w_lo, r.w);
        w_hi = glm::max(w_hi, r.w);
        f.tmin = std::min(f.tmin, r.tmin);
        pk.tmin[k] = r.tmin;
        pk.active[k] = k < n ? -1 : 0;
        pk.has_best[k] = pk.in_bvh[k] = pk.tie[k] = false;
    }
    for (int a = 0; a < 3; ++a) {
        // The reciprocals as the single-ray walk computes them (walk, engine_walk.h)
        const float lo = 1.0f / w_hi[a], hi = 1.0f / w_lo[a];
        if (!std::isfinite(lo) || !std::isfinite(hi) || lo == 0.0f || hi == 0.0f)
            return false;
        f.inv_lo[a] = lo;
        f.inv_hi[a] = hi;
    }
    // Each ray's 1 / w for its slab tests of the leaves' boxes (leaf_mask)
    for (int a = 0; a < 3; ++a) {
        pk.o[a] = r0.o[a];
        for (int g = 0; g < kMaxRays; g += kLanes) {
            F4 w;
            std::memcpy(&w, pk.inv_w[a] + g, sizeof w);
            const F4 inv = F4{1.0f, 1.0f, 1.0f, 1.0f} / w;
            std::memcpy(pk.inv_w[a] + g, &inv, sizeof inv);
        }
    }
    // WoopRay's shear, four rays at a time (w_kz is not zero: every component is not)
    for (int g = 0; g < kMaxRays; g += kLanes) {
        const D4 sz = broadcast(1.0) / load(wz + g);
        const D4 sx = -load(wx + g) * sz, sy = -load(wy + g) * sz;
        std::memcpy(pk.sx + g, &sx, sizeof sx);
        std::memcpy(pk.sy + g, &sy, sizeof sy);
        std::memcpy(pk.sz + g, &sz, sizeof sz);
    }
    return true;
}

// All ones for the rays of the packet among lanes g .. g + 3, 0 for padding
RAYLAB_INLINE M4 active4(const Packet& pk, int g) {
    M4 m;
    std::memcpy(&m, pk.active + g, sizeof m);
    return m;
}

// Which of rays g .. g + 3 meet box within their own [tmin, tmax]: the single-ray walk's
// slab test (Bvh::hit_children) on each, so a ray whose walk would not test the leaf
// does not test it here either (all of a packet's 1 / w_a share a sign, so each axis's
// entry plane is the same for all)
RAYLAB_INLINE M4 leaf_mask(const Packet& pk, int g, const Aabb& box) {
    F4 enter = __builtin_convertvector(load(pk.tmin + g), F4);
    F4 exit = __builtin_convertvector(load(pk.tmax + g), F4);
    for (int a = 0; a < 3; ++a) {
        F4 inv;
        std::memcpy(&inv, pk.inv_w[a] + g, sizeof inv);
        const bool positive = !std::signbit(pk.inv_w[a][0]);
        const float d_near = (positive ? box.lo[a] : box.hi[a]) - pk.o[a];
        const float d_far = (positive ? box.hi[a] : box.lo[a]) - pk.o[a];
        const F4 t_near = F4{d_near, d_near, d_near, d_near} * inv;
        const F4 t_far = F4{d_far, d_far, d_far, d_far} * inv;
        enter = (F4)(((I4)(t_near > enter) & (I4)t_near) |
                     (~(I4)(t_near > enter) & (I4)enter));
        exit = (F4)(((I4)(t_far < exit) & (I4)t_far) | (~(I4)(t_far < exit) & (I4)exit));
    }
    const F4 grow{kSlabGrow, kSlabGrow, kSlabGrow, kSlabGrow};
    return __builtin_convertvector((I4)(enter <= exit * grow), M4) & active4(pk, g);
}

// triangle_t for four rays of the packet (lanes g .. g + 3): the same operations, the
// vertices' translation computed once
RAYLAB_INLINE void test_triangle4(Packet& pk, int g, const double (&v)[3][3],
                                  std::uint32_t p, const M4& rays) {
    const D4 vx[3] = {broadcast(v[0][0]), broadcast(v[1][0]), broadcast(v[2][0])};
    const D4 vy[3] = {broadcast(v[0][1]), broadcast(v[1][1]), broadcast(v[2][1])};
    const D4 vz[3] = {broadcast(v[0][2]), broadcast(v[1][2]), broadcast(v[2][2])};
    Triangle4 r;
    if (!triangle_t4(vx, vy, vz, load(pk.sx + g), load(pk.sy + g), load(pk.sz + g),
                     load(pk.tmin + g), load(pk.tmax + g), rays, r))
        return;
    for (int l = 0; l < kLanes; ++l) {
        if (!r.ok[l]) continue;
        pk.accept(g + l, r.t[l], p);
        pk.extra[g + l] = lane_extra(r, l);
    }
}

// The query (GeometryEngine::closest_hit_packet), inlined into each compiled version
// below
// Avx: unused (the packet's walk is a small part of its time)
template <bool Avx>
RAYLAB_INLINE void packet_query(const Scene& scene, const Ray* rays, int n,
                                TraceCounters& counters, Hit* hits, PrimRef* prims) {
    Packet pk;
    Frustum f;
    if (n < 2 || n > kMaxRays || !make_packet(rays, n, pk, f)) {
        for (int k = 0; k < n; ++k)
            closest_hit(scene, rays[k], counters, hits[k], prims[k]);
        return;
    }
    // Planes: each ray's own loop, as closest_hit's
    float packet_tmax = -kInfinity;
    for (int k = 0; k < n; ++k) {
        const Ray& r = rays[k];
        prims[k] = PrimRef{};
        float best_t = r.tmax;
        for (size_t j = 0; j < scene.planes.size(); ++j) {
            const float t = plane_t(r, scene.planes[j].plane, best_t);
            if (!std::isnan(t)) {
                best_t = t;
                prims[k] = {PrimRef::Kind::plane, static_cast<std::uint32_t>(j)};
                pk.has_best[k] = true;
            }
        }
        pk.best_t[k] = best_t;
        pk.tmax[k] = best_t;
        packet_tmax = std::max(packet_tmax, best_t);
    }
    for (int k = n; k < kMaxRays; ++k)
        pk.tmax[k] = pk.tmax[0];
    counters.intersection_tests += std::uint64_t(n) * scene.planes.size();
    const Primitives prim(scene);
    const int groups = (n + kLanes - 1) / kLanes;
    const SceneData& data = scene_data(scene);
    traverse_frustum(
        scene.bvh(), f, packet_tmax,
        [&](std::uint32_t first, std::uint32_t count,
            const Aabb& box) __attribute__((always_inline)) {
            // The rays that meet the leaf's box, by groups of four
            M4 in_box[kMaxRays / kLanes];
            int meet = 0;
            for (int g = 0; g < groups; ++g) {
                in_box[g] = leaf_mask(pk, g * kLanes, box);
                for (int l = 0; l < kLanes; ++l)
                    meet += in_box[g][l] != 0;
            }
            if (meet == 0) return packet_tmax;
            counters.intersection_tests += std::uint64_t(count) * std::uint64_t(meet);
            for (std::uint32_t s = first; s < first + count; ++s) {
                const std::uint32_t p = prim.order[s];
                if (p < prim.sphere_count) {
                    // Spheres: each ray's own test
                    const Sphere& sphere = prim.spheres[p].sphere;
                    for (int k = 0; k < n; ++k) {
                        if (!in_box[k / kLanes][k % kLanes]) continue;
                        const float t = sphere_t(rays[k], sphere.c, sphere.r, pk.tmax[k]);
                        if (!std::isnan(t)) pk.accept(k, t, p);
                    }
                    continue;
                }
                const std::uint32_t j = p - prim.sphere_count;
                if (data.degenerate(j)) continue;  // the module refuses it for every ray
                // The translation, once: the vertices minus the origin, permuted
                const SceneTriangle& tri = prim.triangles[j];
                const Vec3* vs[3] = {&tri.v0, &tri.v1, &tri.v2};
                double v[3][3];
                for (int i = 0; i < 3; ++i) {
                    const float* c = glm::value_ptr(*vs[i]);
                    v[i][2] = double(c[pk.kz]) - pk.oz;
                    v[i][0] = double(c[pk.kx]) - pk.ox;
                    v[i][1] = double(c[pk.ky]) - pk.oy;
                }
                for (int g = 0; g < groups; ++g) {
                    if (!none(in_box[g])) test_triangle4(pk, g * kLanes, v, p, in_box[g]);
                }
            }
            packet_tmax = -kInfinity;
            for (int k = 0; k < n; ++k)
                packet_tmax = std::max(packet_tmax, static_cast<float>(pk.tmax[k]));
            return packet_tmax;
        },
        counters.bvh_nodes);
    // Each ray's Hit as closest_hit builds it; a tie, alone again
    counters.packet_rays += std::uint64_t(n);
    for (int k = 0; k < n; ++k) {
        if (pk.tie[k]) {
            --counters.packet_rays;
            closest_hit(scene, rays[k], counters, hits[k], prims[k]);
        } else if (pk.in_bvh[k] || prims[k].kind != PrimRef::Kind::none) {
            finish_hit(scene, prim, rays[k], pk.best_t[k], pk.in_bvh[k], pk.best_prim[k],
                       pk.extra[k], hits[k], prims[k]);
        }
    }
}

// The query compiled for the baseline and, on x86-64, for AVX2 and AVX-512
// (engine_simd.h)
RAYLAB_ENGINE_VERSIONS(packet_query, void, packet_versions,
                       (const Scene& scene, const Ray* rays, int n,
                        TraceCounters& counters, Hit* hits, PrimRef* prims),
                       (scene, rays, n, counters, hits, prims))

}  // namespace

decltype(GeometryEngine::closest_hit_packet) chosen_packet_query() {
    return packet_versions_chosen();
}

}  // namespace raylab::reference::engine_kernels
