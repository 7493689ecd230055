// The BVH build's data (framework/src/bvh.cpp): its constants, four floats in one SSE
// register where there is SSE2, boxes, the primitives being sorted and the subtrees.
#pragma once

#include <cstdint>

#include "raylab/simd.h"

#include "raylab/bvh.h"

namespace raylab::bvh_build {

constexpr int kBins = 16;
constexpr int kMaxSahDepth = 40;        // then index halving: depth <= 40 + 32
constexpr float kTraversalCost = 1.0f;  // relative to one primitive test
// Below this many primitives a second thread costs more than it saves
constexpr std::uint32_t kParallelMin = 4096;
// A subtree at least this large is offered to the other threads
constexpr std::uint32_t kTaskMin = 1024;
// A node at least this large is binned and partitioned by two threads when one is idle
constexpr std::uint32_t kForkMin = 32768;

// Four floats (x, y, z and a lane the geometry ignores) in one SSE register where there
// is SSE2. min and max keep b unless a is smaller (larger), as glm::min/max and minps do
#if RAYLAB_SSE2
struct F4 {
    __m128 v;
};
inline F4 load(const float* p) {
    return {_mm_load_ps(p)};
}
inline F4 splat(float x) {
    return {_mm_set1_ps(x)};
}
inline F4 add(F4 a, F4 b) {
    return {_mm_add_ps(a.v, b.v)};
}
inline F4 sub(F4 a, F4 b) {
    return {_mm_sub_ps(a.v, b.v)};
}
inline F4 mul(F4 a, F4 b) {
    return {_mm_mul_ps(a.v, b.v)};
}
inline F4 min(F4 a, F4 b) {
    return {_mm_min_ps(a.v, b.v)};
}
inline F4 max(F4 a, F4 b) {
    return {_mm_max_ps(a.v, b.v)};
}
inline void store(float* p, F4 a) {
    _mm_store_ps(p, a.v);
}
// Truncated to integers, as static_cast<int>
inline void store_int(int* p, F4 a) {
    _mm_store_si128(reinterpret_cast<__m128i*>(p), _mm_cvttps_epi32(a.v));
}
// Lane 3's bits, and lane 3 with n added to its bits (the other lanes unchanged)
inline std::uint32_t lane3(F4 a) {
    return static_cast<std::uint32_t>(
        _mm_cvtsi128_si32(_mm_shuffle_epi32(_mm_castps_si128(a.v), 0xff)));
}
inline F4 add_lane3(F4 a, std::uint32_t n) {
    const __m128i add = _mm_set_epi32(static_cast<int>(n), 0, 0, 0);
    return {_mm_castsi128_ps(_mm_add_epi32(_mm_castps_si128(a.v), add))};
}
// Bit k set when a < b in lane k
inline int less(F4 a, F4 b) {
    return _mm_movemask_ps(_mm_cmplt_ps(a.v, b.v));
}
// Lane 3 set to zero
inline F4 xyz(F4 a) {
    const __m128i mask = _mm_set_epi32(0, -1, -1, -1);
    return {_mm_and_ps(a.v, _mm_castsi128_ps(mask))};
}
#else
struct F4 {
    float v[4];
};
template <class Op>
inline F4 lanes(F4 a, F4 b, Op op) {
    return {
        {op(a.v[0], b.v[0]), op(a.v[1], b.v[1]), op(a.v[2], b.v[2]), op(a.v[3], b.v[3])}};
}
inline F4 load(const float* p) {
    return {{p[0], p[1], p[2], p[3]}};
}
inline F4 splat(float x) {
    return {{x, x, x, x}};
}
inline F4 add(F4 a, F4 b) {
    return lanes(a, b, [](float x, float y) { return x + y; });
}
inline F4 sub(F4 a, F4 b) {
    return lanes(a, b, [](float x, float y) { return x - y; });
}
inline F4 mul(F4 a, F4 b) {
    return lanes(a, b, [](float x, float y) { return x * y; });
}
inline F4 min(F4 a, F4 b) {
    return lanes(a, b, [](float x, float y) { return x < y ? x : y; });
}
inline F4 max(F4 a, F4 b) {
    return lanes(a, b, [](float x, float y) { return x > y ? x : y; });
}
inline void store(float* p, F4 a) {
    std::copy(a.v, a.v + 4, p);
}
inline void store_int(int* p, F4 a) {
    for (int k = 0; k < 4; ++k)
        p[k] = static_cast<int>(a.v[k]);
}
inline std::uint32_t lane3(F4 a) {
    std::uint32_t bits;
    std::memcpy(&bits, &a.v[3], sizeof bits);
    return bits;
}
inline F4 add_lane3(F4 a, std::uint32_t n) {
    const std::uint32_t bits = lane3(a) + n;
    std::memcpy(&a.v[3], &bits, sizeof bits);
    return a;
}
inline int less(F4 a, F4 b) {
    int bits = 0;
    for (int k = 0; k < 4; ++k)
        bits |= (a.v[k] < b.v[k] ? 1 : 0) << k;
    return bits;
}
inline F4 xyz(F4 a) {
    return {{a.v[0], a.v[1], a.v[2], 0.0f}};
}
#endif

// A box in two F4s; empty when lo > hi
struct Box4 {
    F4 lo = splat(kInfinity), hi = splat(-kInfinity);
    void grow(F4 p) { grow(p, p); }
    void grow(F4 l, F4 h) {
        lo = min(l, lo);
        hi = max(h, hi);
    }
    void grow(const Box4& b) { grow(b.lo, b.hi); }
    // As Aabb::half_area, operation for operation
    float half_area() const {
        alignas(16) float e[4];
        store(e, max(splat(0.0f), sub(hi, lo)));
        return e[0] * e[1] + e[1] * e[2] + e[2] * e[0];
    }
};

// A primitive during the build: its box, and in lane 3 of lo its index tagged with
// kPrimTag, which makes the bits a normal float (2 .. 2^33) that min and max pass through
// without a denormal; lane 3 of hi is 0. 32 bytes, moved as a whole by the partition
constexpr std::uint32_t kPrimTag = 0x40000000u;
static_assert(Bvh::kFirstMask < kPrimTag / 4, "the tag must stay clear of the index");
struct alignas(16) Ref {
    float lo[4];
    float hi[4];
    F4 centre() const { return mul(add(xyz(load(lo)), load(hi)), splat(0.5f)); }
    std::uint32_t prim() const { return lane3(load(lo)) & Bvh::kFirstMask; }
};

// The subtree over refs[first, first + count): its box, its centres' box and its depth
// in the binary tree
struct Task {
    Box4 box, centres;
    std::uint32_t first = 0, count = 0;
    int depth = 0;
};

// A node of the binary SAH tree once decided: a leaf (leaf holds its code, as
// Bvh::Node::child does) or split into two partitioned children
struct Item {
    Task t;
    std::uint32_t leaf = 0;
    Task child[2];
};

}  // namespace raylab::bvh_build
