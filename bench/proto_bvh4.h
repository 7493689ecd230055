// bench/proto_bvh4.h: a prototype 4-wide BVH with SSE box tests, collapsed from the pair
// BVH (bench/proto_bvh.h), to measure what a wide BVH would gain raylab. Embree does the
// same with 8 or 16 lanes; this is the smallest version of the idea (SSE is in every
// x86-64 CPU). Not built for other CPUs.
#pragma once

#if defined(__SSE2__)
#define RAYLAB_BENCH_HAVE_BVH4 1
#include <xmmintrin.h>

#include <cstdint>
#include <vector>

#include "proto_bvh.h"

namespace raylab::bench {

class Bvh4 {
  public:
    /// Four children: boxes in SoA layout, then per child an interior node index or, for
    /// a leaf, its first primitive and count. Two cache lines.
    struct alignas(64) Node {
        float lo_x[4], lo_y[4], lo_z[4], hi_x[4], hi_y[4], hi_z[4];
        std::uint32_t child[4];  ///< interior: node index; leaf: first primitive
        std::uint16_t count[4];  ///< 0: interior child; otherwise primitives in the leaf
        std::uint32_t valid;     ///< bit k: child k exists
    };

    /// Collapses pair: every node takes its children's children (largest area first)
    /// until it has four.
    void build(const PairBvh& pair);
    size_t node_count() const { return nodes_.size(); }

    template <class Test>
    void traverse(const Ray& r, Test&& test) const;

  private:
    std::vector<Node> nodes_;
    std::vector<std::uint32_t> prims_;
};

template <class Test>
void Bvh4::traverse(const Ray& r, Test&& test) const {
    struct Entry {
        std::uint32_t index;  // node index, or first primitive when count > 0
        std::uint32_t count;
        float t;
    };
    Entry stack[256];
    int top = 0;
    stack[top++] = {0, 0, r.tmin};
    const __m128 ox = _mm_set1_ps(r.o.x), oy = _mm_set1_ps(r.o.y),
                 oz = _mm_set1_ps(r.o.z);
    const __m128 ix = _mm_set1_ps(1.0f / r.w.x), iy = _mm_set1_ps(1.0f / r.w.y),
                 iz = _mm_set1_ps(1.0f / r.w.z);
    const __m128 tmin = _mm_set1_ps(r.tmin);
    const __m128 grow = _mm_set1_ps(1.0f + 3.0f * std::numeric_limits<float>::epsilon());
    float tmax = r.tmax;
    while (top > 0) {
        const Entry e = stack[--top];
        if (e.t > tmax) continue;
        if (e.count > 0) {
            for (std::uint32_t k = 0; k < e.count; ++k) {
                if (test(prims_[e.index + k], tmax)) return;
            }
            continue;
        }
        const Node& n = nodes_[e.index];
        // Slabs of four boxes at once; a NaN (0 * inf) operand first is dropped by
        // min/max
        const auto slab = [](__m128 lo, __m128 hi, __m128 o, __m128 inv, __m128& near,
                             __m128& far) {
            const __m128 t0 = _mm_mul_ps(_mm_sub_ps(lo, o), inv);
            const __m128 t1 = _mm_mul_ps(_mm_sub_ps(hi, o), inv);
            near = _mm_max_ps(_mm_min_ps(t0, t1), near);
            far = _mm_min_ps(_mm_max_ps(t0, t1), far);
        };
        __m128 near = tmin, far = _mm_set1_ps(tmax);
        slab(_mm_load_ps(n.lo_x), _mm_load_ps(n.hi_x), ox, ix, near, far);
        slab(_mm_load_ps(n.lo_y), _mm_load_ps(n.hi_y), oy, iy, near, far);
        slab(_mm_load_ps(n.lo_z), _mm_load_ps(n.hi_z), oz, iz, near, far);
        int mask = _mm_movemask_ps(_mm_cmple_ps(near, _mm_mul_ps(far, grow))) &
                   static_cast<int>(n.valid);
        if (mask == 0) continue;
        alignas(16) float t[4];
        _mm_store_ps(t, near);
        // Push the hit children farthest first, so the nearest is popped next
        const int first = top;
        for (int k = 0; k < 4; ++k) {
            if (!(mask & (1 << k))) continue;
            Entry in{n.child[k], n.count[k], t[k]};
            int j = top++;
            for (; j > first && stack[j - 1].t < in.t; --j)
                stack[j] = stack[j - 1];
            stack[j] = in;
        }
    }
}

}  // namespace raylab::bench

#endif  // __SSE2__
