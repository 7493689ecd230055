// bench/proto_bvh.h: a prototype BVH traversal, built only to measure what a change to
// framework/ would gain before anyone makes it (docs/benchmarks.md, "what-if").
//
// Same build as raylab's Bvh (binned SAH, 16 bins, leaves of at most 4), but the two
// children of a node sit side by side in one 64-byte cache line and traversal tests both
// children's boxes at the parent, descends into the nearer by entry distance, and skips
// stacked nodes whose entry distance is beyond the current closest hit.
#pragma once

#include <cstdint>
#include <vector>

#include "raylab/bvh.h"

namespace raylab::bench {

class PairBvh {
  public:
    struct Node {
        Vec3 lo;
        std::uint32_t first_or_pair = 0;  ///< leaf: first primitive; interior: child pair
        Vec3 hi;
        std::uint32_t count = 0;  ///< primitives in a leaf, 0 for interior nodes
    };
    struct alignas(64) Pair {
        Node child[2];
    };

    void build(const std::vector<Aabb>& boxes);
    size_t node_count() const { return 2 * pairs_.size() - 1; }
    const Node& root() const { return pairs_[0].child[0]; }
    const Pair& pair(std::uint32_t k) const { return pairs_[k]; }
    const std::vector<std::uint32_t>& prims() const { return prims_; }

    /// As Bvh::traverse: test(prim, tmax) may shrink tmax and returns true to stop.
    template <class Test>
    void traverse(const Ray& r, Test&& test) const;

  private:
    std::vector<Pair> pairs_;  // pairs_[0].child[0] is the root
    std::vector<std::uint32_t> prims_;
    friend struct PairBuilder;
};

// Entry distance of the ray into [lo, hi] within [tmin, tmax], or +inf when it misses
inline float entry_distance(const Vec3& o, const Vec3& inv_w, const PairBvh::Node& n,
                            float tmin, float tmax) {
    const Vec3 t0 = (n.lo - o) * inv_w, t1 = (n.hi - o) * inv_w;
    const Vec3 tn = glm::min(t0, t1), tf = glm::max(t0, t1);
    const auto max = [](float a, float b) { return a > b ? a : b; };
    const auto min = [](float a, float b) { return a < b ? a : b; };
    const float enter = max(tn.x, max(tn.y, max(tn.z, tmin)));
    const float exit = min(tf.x, min(tf.y, min(tf.z, tmax)));
    constexpr float kGrow = 1.0f + 3.0f * std::numeric_limits<float>::epsilon();
    return enter <= exit * kGrow ? enter : kInfinity;
}

template <class Test>
void PairBvh::traverse(const Ray& r, Test&& test) const {
    if (pairs_.empty()) return;
    const Vec3 inv_w(1.0f / r.w.x, 1.0f / r.w.y, 1.0f / r.w.z);
    float tmax = r.tmax;
    struct Entry {
        const Node* node;
        float t;
    };
    Entry stack[128];
    int top = 0;
    const Node* node = &pairs_[0].child[0];
    if (entry_distance(r.o, inv_w, *node, r.tmin, tmax) == kInfinity) return;
    for (;;) {
        if (node->count == 0) {
            const Pair& p = pairs_[node->first_or_pair];
            const float t0 = entry_distance(r.o, inv_w, p.child[0], r.tmin, tmax);
            const float t1 = entry_distance(r.o, inv_w, p.child[1], r.tmin, tmax);
            if (t0 != kInfinity && t1 != kInfinity) {
                const bool first_near = t0 <= t1;
                stack[top++] = {&p.child[first_near ? 1 : 0], first_near ? t1 : t0};
                node = &p.child[first_near ? 0 : 1];
                continue;
            }
            if (t0 != kInfinity || t1 != kInfinity) {
                node = &p.child[t0 != kInfinity ? 0 : 1];
                continue;
            }
        } else {
            for (std::uint32_t k = 0; k < node->count; ++k) {
                if (test(prims_[node->first_or_pair + k], tmax)) return;
            }
        }
        // Next stacked node that may still hold a nearer hit
        do {
            if (top == 0) return;
            --top;
        } while (stack[top].t > tmax);
        node = stack[top].node;
    }
}

}  // namespace raylab::bench
