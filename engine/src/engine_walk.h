// The engine's walks of the scene's BVH (raylab/bvh.h): the same leaves in the same order
// as Bvh::traverse and Bvh::traverse_any, which the module path runs, with SSE2 node
// tests (eight boxes in two registers, or in one AVX register in the AVX2 versions of
// the queries), hit children put in order without the insertion sort's branches, and
// the next nodes' cache lines asked for early. And the packet query's frustum walk: one
// slab test per node for a whole packet of camera rays.
//
// The node tests compute what Bvh::hit_children computes, operation for operation
// (maxps and minps return their second operand when either is NaN, as the scalar
// test's ternaries do), so the walks visit what the module path visits and count the
// same nodes: engine/tests (test_walk.cpp, test_module_walk.cpp) and tests/stress hold
// them to it.
#pragma once

#include <cassert>
#include <cmath>
#include <cstdint>

#include "raylab/bvh.h"
#include "raylab/simd.h"

namespace raylab::reference::engine_kernels {

using Node = Bvh::Node;
constexpr int kWidth = Bvh::kWidth;

// The ray, broadcast for the SSE slab test; near[a] names the box row the ray enters by
// along axis a (lo for a positive direction, hi for a negative one)
struct Ray4 {
#if RAYLAB_SSE2
    __m128 o[3], inv_w[3];
#else
    float o[3], inv_w[3];
#endif
    int near[3];
};

// Asks for a child node's cache lines while the nearer ones are processed
inline void prefetch(const Bvh& bvh, std::uint32_t child) {
#if RAYLAB_SSE2
    if (child & Bvh::kLeaf) return;
    const char* p = reinterpret_cast<const char*>(&bvh.nodes()[child]);
    for (size_t line = 0; line < sizeof(Node); line += 64)
        _mm_prefetch(p + line, _MM_HINT_T0);
#else
    (void)bvh, (void)child;
#endif
}

// Bvh::hit_children with two 4-wide SSE tests, the groups independent of each other
inline int hit_children(const Node& n, const Ray4& r, float tmin, float tmax,
                        float t_enter[kWidth]) {
#if RAYLAB_SSE2
    int mask = 0;
    for (int g = 0; g < kWidth; g += 4) {
        __m128 enter = _mm_set1_ps(tmin), exit = _mm_set1_ps(tmax);
        for (int a = 0; a < 3; ++a) {
            const __m128 t_near =
                _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.box[2 * a + r.near[a]] + g), r.o[a]),
                           r.inv_w[a]);
            const __m128 t_far = _mm_mul_ps(
                _mm_sub_ps(_mm_load_ps(n.box[2 * a + 1 - r.near[a]] + g), r.o[a]),
                r.inv_w[a]);
            enter = _mm_max_ps(t_near, enter);
            exit = _mm_min_ps(t_far, exit);
        }
        _mm_store_ps(t_enter + g, enter);
        mask |=
            _mm_movemask_ps(_mm_cmple_ps(enter, _mm_mul_ps(exit, _mm_set1_ps(kSlabGrow))))
            << g;
    }
    return mask;
#else
    int mask = 0;
    for (int k = 0; k < kWidth; ++k) {
        float enter = tmin, exit = tmax;
        for (int a = 0; a < 3; ++a) {
            const float t_near = (n.box[2 * a + r.near[a]][k] - r.o[a]) * r.inv_w[a];
            const float t_far = (n.box[2 * a + 1 - r.near[a]][k] - r.o[a]) * r.inv_w[a];
            enter = t_near > enter ? t_near : enter;
            exit = t_far < exit ? t_far : exit;
        }
        t_enter[k] = enter;
        mask |= (enter <= exit * kSlabGrow) << k;
    }
    return mask;
#endif
}

#if RAYLAB_AVX_NODES
// hit_children's SSE test on all eight boxes in one AVX register: the same operations,
// and maxps/minps's NaN rule (the second operand) holds for their AVX forms; _CMP_LE_OQ
// is cmpleps's <= (false for NaN)
__attribute__((target("avx2"))) inline int hit_children_avx(const Node& n, const Ray4& r,
                                                            float tmin, float tmax,
                                                            float t_enter[kWidth]) {
    __m256 enter = _mm256_set1_ps(tmin), exit = _mm256_set1_ps(tmax);
    for (int a = 0; a < 3; ++a) {
        const __m256 o = _mm256_set_m128(r.o[a], r.o[a]);
        const __m256 inv = _mm256_set_m128(r.inv_w[a], r.inv_w[a]);
        const __m256 t_near = _mm256_mul_ps(
            _mm256_sub_ps(_mm256_load_ps(n.box[2 * a + r.near[a]]), o), inv);
        const __m256 t_far = _mm256_mul_ps(
            _mm256_sub_ps(_mm256_load_ps(n.box[2 * a + 1 - r.near[a]]), o), inv);
        enter = _mm256_max_ps(t_near, enter);
        exit = _mm256_min_ps(t_far, exit);
    }
    _mm256_store_ps(t_enter, enter);
    return _mm256_movemask_ps(
        _mm256_cmp_ps(enter, _mm256_mul_ps(exit, _mm256_set1_ps(kSlabGrow)), _CMP_LE_OQ));
}

// The walk's sort of three or more hit children, in the AVX2 versions: each hit child of
// mask goes straight to its place on the stack (from out on, farthest first), the number
// of hit children entered farther than it, or as far from an earlier slot: where the
// insertion sort puts it (on a tie, the later slot nearer the top), without the
// insertion sort's comparisons, which a random ray makes unpredictable. A hit child's t
// is never NaN (its slab test's ordered compare is false for NaN); the ranks need that:
// a NaN would share a place with another child and leave one unwritten. Returns the
// number of hit children, counted as they are placed (returning popcount(mask) instead
// changed GCC's register choice in the inlined walk for the worse)
template <class Entry>
__attribute__((target("avx2,popcnt"))) int place_sorted_avx(const Bvh& bvh,
                                                            const Node& node,
                                                            const float t[kWidth],
                                                            int mask, Entry* out) {
    const __m256 all = _mm256_load_ps(t);
    int count = 0;
    for (int m = mask; m != 0; m &= m - 1) {
        const int k = __builtin_ctz(static_cast<unsigned>(m));
        assert(!std::isnan(t[k]));
        const __m256 tk = _mm256_broadcast_ss(t + k);
        const int farther = _mm256_movemask_ps(_mm256_cmp_ps(all, tk, _CMP_GT_OQ));
        const int as_far = _mm256_movemask_ps(_mm256_cmp_ps(all, tk, _CMP_EQ_OQ));
        const unsigned before = (farther | (as_far & ((1 << k) - 1))) & mask;
        prefetch(bvh, node.child[k]);
        out[_mm_popcnt_u32(before)] = Entry{node.child[k], t[k]};
        ++count;
    }
    return count;
}
#endif

// Bvh::traverse (Sorted) or Bvh::traverse_any: the same leaves in the same order, the
// same visit and the same count of nodes. Avx: each node's eight boxes in one AVX slab
// test and three or more hit children placed by place_sorted_avx; only from code
// compiled for AVX2 (engine_simd.h's AVX2 versions, which inline the walk)
template <bool Sorted, bool Avx, class Visit>
void walk(const Bvh& bvh, const Ray& r, Visit& visit, std::uint64_t& nodes_visited) {
    if (bvh.prims().empty()) return;
    float tmax = r.tmax;
    const std::uint32_t root = bvh.root();
    if (root & Bvh::kLeaf) {
        // One small leaf: its box is the scene's bounds
        if (box_entry(RaySlabs(r), bvh.bounds(), r.tmin, tmax) == kInfinity) return;
        visit(root & Bvh::kFirstMask, root >> Bvh::kCountShift & 7u, tmax);
        return;
    }
    Ray4 ray;
    for (int a = 0; a < 3; ++a) {
        const float inv_w = 1.0f / r.w[a];
#if RAYLAB_SSE2
        ray.o[a] = _mm_set1_ps(r.o[a]);
        ray.inv_w[a] = _mm_set1_ps(inv_w);
#else
        ray.o[a] = r.o[a];
        ray.inv_w[a] = inv_w;
#endif
        ray.near[a] = std::signbit(inv_w) ? 1 : 0;
    }
    const Node* nodes = bvh.nodes().data();
    // The farther children wait on the stack with their entry distance, skipped if a hit
    // has come closer since
    struct Entry {
        std::uint32_t child;
        float t_enter;
    };
    Entry stack[Bvh::kStackSize];
    int top = 0;
    std::uint32_t child = root;
    for (;;) {
        if (child & Bvh::kLeaf) {
            if (visit(child & Bvh::kFirstMask, child >> Bvh::kCountShift & 7u, tmax))
                return;
        } else {
            const Node& node = nodes[child];
            ++nodes_visited;
            alignas(32) float t[kWidth];
            int mask;
#if RAYLAB_AVX_NODES
            if constexpr (Avx)
                mask = hit_children_avx(node, ray, r.tmin, tmax, t);
            else
#endif
                mask = hit_children(node, ray, r.tmin, tmax, t);
            if (mask != 0) {
                // One child hit (the commonest case): straight down, no stack
                const int k0 = __builtin_ctz(static_cast<unsigned>(mask));
                const int rest = mask & (mask - 1);
                if (rest == 0) {
                    child = node.child[k0];
                    continue;
                }
                // Two: the farther waits on the stack (on a tie, the later one is taken
                // first, as the sort below does); any hit: the first slot first. Marked
                // likely: GCC otherwise lays the walk out around the inlined sort below
                if (__builtin_expect((rest & (rest - 1)) == 0, 1)) {
                    const int k1 = __builtin_ctz(static_cast<unsigned>(rest));
                    const bool k0_first = Sorted ? t[k0] < t[k1] : true;
                    const int near = k0_first ? k0 : k1, far = k0_first ? k1 : k0;
                    prefetch(bvh, node.child[far]);
                    stack[top++] = Entry{node.child[far], t[far]};
                    child = node.child[near];
                    continue;
                }
                // Sort the hit children farthest first onto the stack (any hit: in slot
                // order); take the top one
                const int first = top;
#if RAYLAB_AVX_NODES
                if constexpr (Sorted && Avx) {
                    top += place_sorted_avx(bvh, node, t, mask, stack + first);
                    child = stack[--top].child;
                    continue;
                }
#endif
                for (; mask != 0; mask &= mask - 1) {
                    const int k = __builtin_ctz(static_cast<unsigned>(mask));
                    const Entry e{node.child[k], t[k]};
                    prefetch(bvh, e.child);
                    int j = top++;
                    if (Sorted) {
                        for (; j > first && stack[j - 1].t_enter < e.t_enter; --j)
                            stack[j] = stack[j - 1];
                    }
                    stack[j] = e;
                }
                child = stack[--top].child;
                continue;
            }
        }
        // Next waiting node that the ray can still reach before its closest hit so far,
        // with the slab test's own margin
        do {
            if (top == 0) return;
            --top;
        } while (stack[top].t_enter > tmax * kSlabGrow);
        child = stack[top].child;
    }
}

// A packet of rays from one origin o whose direction components each keep one sign and
// are never zero: per axis, the range [inv_lo, inv_hi] of the rays' 1 / w (each computed
// as RaySlabs does). Its slab test of a box gives a lower bound of every ray's entry
// distance and an upper bound of every exit, so it accepts every box that one of the
// rays accepts in Bvh::traverse (rounding is monotone).
struct Frustum {
    Vec3 o{0.0f};
    Vec3 inv_lo{0.0f}, inv_hi{0.0f};
    float tmin = 0.0f;  // the smallest tmin of the rays
};

// The frustum, broadcast: per axis the origin and the range of 1 / w
struct Frustum4 {
#if RAYLAB_SSE2
    __m128 o[3], inv_lo[3], inv_hi[3];
#else
    float o[3], inv_lo[3], inv_hi[3];
#endif
    int near[3];
};

// The frustum's slab test of a node's boxes: per axis, the near plane's distance with
// the smaller and the far plane's with the larger of the two reciprocals bound every
// ray's (x * inv rounds monotonically in inv for a fixed x = plane - o, which all rays
// share). No NaN: the reciprocals are finite and not zero, and an unused slot's infinite
// planes give +-inf.
inline int frustum_children(const Node& n, const Frustum4& f, float tmin, float tmax,
                            float t_enter[kWidth]) {
#if RAYLAB_SSE2
    int mask = 0;
    for (int g = 0; g < kWidth; g += 4) {
        __m128 enter = _mm_set1_ps(tmin), exit = _mm_set1_ps(tmax);
        for (int a = 0; a < 3; ++a) {
            const __m128 dn =
                _mm_sub_ps(_mm_load_ps(n.box[2 * a + f.near[a]] + g), f.o[a]);
            const __m128 df =
                _mm_sub_ps(_mm_load_ps(n.box[2 * a + 1 - f.near[a]] + g), f.o[a]);
            enter = _mm_max_ps(
                _mm_min_ps(_mm_mul_ps(dn, f.inv_lo[a]), _mm_mul_ps(dn, f.inv_hi[a])),
                enter);
            exit = _mm_min_ps(
                _mm_max_ps(_mm_mul_ps(df, f.inv_lo[a]), _mm_mul_ps(df, f.inv_hi[a])),
                exit);
        }
        _mm_store_ps(t_enter + g, enter);
        mask |=
            _mm_movemask_ps(_mm_cmple_ps(enter, _mm_mul_ps(exit, _mm_set1_ps(kSlabGrow))))
            << g;
    }
    return mask;
#else
    int mask = 0;
    for (int k = 0; k < kWidth; ++k) {
        float enter = tmin, exit = tmax;
        for (int a = 0; a < 3; ++a) {
            const float dn = n.box[2 * a + f.near[a]][k] - f.o[a];
            const float df = n.box[2 * a + 1 - f.near[a]][k] - f.o[a];
            const float lo = dn * f.inv_lo[a], hi = dn * f.inv_hi[a];
            const float t_near = lo < hi ? lo : hi;
            const float flo = df * f.inv_lo[a], fhi = df * f.inv_hi[a];
            const float t_far = flo > fhi ? flo : fhi;
            enter = t_near > enter ? t_near : enter;
            exit = t_far < exit ? t_far : exit;
        }
        t_enter[k] = enter;
        mask |= (enter <= exit * kSlabGrow) << k;
    }
    return mask;
#endif
}

// Visits every leaf whose box a ray of the packet may meet, nearer boxes first (by the
// frustum's entry distance), one slab test per node for the whole packet.
// visit(first, count, box) tests the leaf's slots [first, first + count) for the rays
// that meet the leaf's box (each its own slab test) and returns the largest tmax of the
// packet's rays after it: boxes entered beyond it are skipped. tmax: the largest tmax of
// the rays at the start.
template <class Visit>
void traverse_frustum(const Bvh& bvh, const Frustum& fr, float tmax, Visit&& visit,
                      std::uint64_t& nodes_visited) {
    if (bvh.prims().empty()) return;
    const std::uint32_t root = bvh.root();
    if (root & Bvh::kLeaf) {
        // One small leaf: its box is the scene's bounds
        visit(root & Bvh::kFirstMask, root >> Bvh::kCountShift & 7u, bvh.bounds());
        return;
    }
    Frustum4 f;
    for (int a = 0; a < 3; ++a) {
#if RAYLAB_SSE2
        f.o[a] = _mm_set1_ps(fr.o[a]);
        f.inv_lo[a] = _mm_set1_ps(fr.inv_lo[a]);
        f.inv_hi[a] = _mm_set1_ps(fr.inv_hi[a]);
#else
        f.o[a] = fr.o[a];
        f.inv_lo[a] = fr.inv_lo[a];
        f.inv_hi[a] = fr.inv_hi[a];
#endif
        f.near[a] = std::signbit(fr.inv_lo[a]) ? 1 : 0;
    }
    const Node* nodes = bvh.nodes().data();
    // A waiting child, its entry distance, and where its box is: node * kWidth + slot
    struct Entry {
        std::uint32_t child;
        float t_enter;
        std::uint32_t box;
    };
    Entry stack[Bvh::kStackSize];
    int top = 0;
    std::uint32_t child = root, box = 0;
    for (;;) {
        if (child & Bvh::kLeaf) {
            const Node& n = nodes[box / kWidth];
            const std::uint32_t k = box % kWidth;
            const Aabb leaf{Vec3(n.box[0][k], n.box[2][k], n.box[4][k]),
                            Vec3(n.box[1][k], n.box[3][k], n.box[5][k])};
            tmax = visit(child & Bvh::kFirstMask, child >> Bvh::kCountShift & 7u, leaf);
        } else {
            const Node& node = nodes[child];
            ++nodes_visited;
            alignas(16) float t[kWidth];
            int mask = frustum_children(node, f, fr.tmin, tmax, t);
            if (mask != 0) {
                // Hit children farthest first onto the stack; take the top one
                const int first = top;
                for (; mask != 0; mask &= mask - 1) {
                    const int k = __builtin_ctz(static_cast<unsigned>(mask));
                    const Entry e{node.child[k], t[k], child * kWidth + std::uint32_t(k)};
                    int j = top++;
                    for (; j > first && stack[j - 1].t_enter < e.t_enter; --j)
                        stack[j] = stack[j - 1];
                    stack[j] = e;
                }
                --top;
                child = stack[top].child;
                box = stack[top].box;
                continue;
            }
        }
        do {
            if (top == 0) return;
            --top;
        } while (stack[top].t_enter > tmax * kSlabGrow);
        child = stack[top].child;
        box = stack[top].box;
    }
}

}  // namespace raylab::reference::engine_kernels
