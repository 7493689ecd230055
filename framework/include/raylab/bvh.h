// raylab/bvh.h: an 8-wide bounding volume hierarchy over boxes, built with binned SAH,
// and its walk.
//
// The BVH knows nothing about primitives: it is built from one box per primitive and
// calls back with leaves (ranges of primitive slots) during traversal. The scene
// (raylab/scene.h) owns it and supplies the leaf tests, so the same tree serves
// closest-hit and any-hit queries.
//
// Layout: a node holds the boxes of its eight children side by side (structure of
// arrays), so that a vector unit can test all eight at once (Wald et al., "Getting Rid
// of Packets", 2008; Embree does the same 4-, 8- or 16-wide). Eight children make the
// tree a third shallower than four (log 8 / log 4). The walk below is the plain one, a
// child at a time; the reference's geometry engine (engine/, not for students) walks
// the same tree with vector instructions and visits the same leaves in the same order.
#pragma once

#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "raylab/contract.h"

namespace raylab {

/// Axis-aligned box [lo, hi]; empty when lo > hi.
struct Aabb {
    Vec3 lo{kInfinity};
    Vec3 hi{-kInfinity};

    void grow(const Vec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void grow(const Aabb& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    Vec3 centre() const { return 0.5f * (lo + hi); }
    /// Half the surface area (enough for SAH ratios); 0 for an empty box.
    float half_area() const {
        const Vec3 e = glm::max(hi - lo, Vec3(0.0f));
        return e.x * e.y + e.y * e.z + e.z * e.x;
    }
};

/// Precomputed per-ray data for the slab test.
struct RaySlabs {
    Vec3 o;
    Vec3 inv_w;  ///< 1 / w per component (+-inf for zero components)
    explicit RaySlabs(const Ray& r)
        : o(r.o), inv_w(1.0f / r.w.x, 1.0f / r.w.y, 1.0f / r.w.z) {}
};

/// The far distance of a slab test is enlarged by 1 + 2 gamma(3) (pbrt-v4 §6.1.2) so
/// rounding never culls a box the ray touches.
inline constexpr float kSlabGrow =
    1.0f + 2.0f * 3.0f * 0.5f * std::numeric_limits<float>::epsilon();

/// Slab test of one box: the distance at which the ray enters box, or +infinity when it
/// misses box in [tmin, tmax].
inline float box_entry(const RaySlabs& s, const Aabb& box, float tmin, float tmax) {
    const Vec3 t0 = (box.lo - s.o) * s.inv_w;
    const Vec3 t1 = (box.hi - s.o) * s.inv_w;
    // A ray in a slab's plane along a +-0 component gives 0 * inf = NaN: that slab holds
    // the whole ray, so a NaN on either side makes the axis unconstrained (-inf, +inf).
    // glm::min/max would return the other operand and cull the box
    const auto near = [](float a, float b) {
        return a < b ? a : (b <= a ? b : -kInfinity);
    };
    const auto far = [](float a, float b) {
        return a > b ? a : (b >= a ? b : kInfinity);
    };
    const auto max = [](float a, float b) { return a > b ? a : b; };
    const auto min = [](float a, float b) { return a < b ? a : b; };
    const float t_enter =
        max(near(t0.x, t1.x), max(near(t0.y, t1.y), max(near(t0.z, t1.z), tmin)));
    const float t_exit =
        min(far(t0.x, t1.x), min(far(t0.y, t1.y), min(far(t0.z, t1.z), tmax)));
    return t_enter <= t_exit * kSlabGrow ? t_enter : kInfinity;
}

class Bvh {
  public:
    /// kWidth children. box[2 a] holds the lower bounds along axis a of the child
    /// boxes, box[2 a + 1] the upper ones; an unused slot has an empty box (lo = +inf,
    /// hi = -inf), which every ray misses. child[k]: an interior node's index, or for a
    /// leaf kLeaf | count << kCountShift | first primitive slot.
    static constexpr int kWidth = 8;
    struct alignas(32) Node {
        float box[6][kWidth];
        std::uint32_t child[kWidth];
    };
    static constexpr std::uint32_t kLeaf = 0x80000000u;
    static constexpr int kCountShift = 28;
    static constexpr std::uint32_t kFirstMask = (1u << kCountShift) - 1;
    static constexpr std::uint32_t kMaxLeafSize = 4;
    /// The walk's stack of waiting children: at most kWidth - 1 wait per level of the
    /// binary tree's 72 (a node is at least one binary level below its parent).
    static constexpr int kStackSize = (kWidth - 1) * 72 + 8;

    /// Builds the tree over one box per primitive: binned SAH (16 bins, leaves of at most
    /// four), collapsed to kWidth wide as it goes. From 4,096 primitives on, the build
    /// runs on up to `threads` threads (0: the hardware threads), one per 2,048
    /// primitives at most. The tree, node array included, depends on the boxes only,
    /// never on the number of threads or their timing; a leaf's slots hold its
    /// primitives in increasing order.
    void build(const std::vector<Aabb>& boxes, unsigned threads = 0);
    /// Interior nodes on the longest path from the root to a leaf (0 for an empty tree or
    /// a single leaf).
    int depth() const;

    bool empty() const { return prims_.empty(); }
    size_t node_count() const { return nodes_.size(); }
    /// Bytes held by nodes and the primitive order.
    size_t bytes() const {
        return nodes_.size() * sizeof(Node) + prims_.size() * sizeof(std::uint32_t);
    }
    const Aabb& bounds() const { return bounds_; }
    /// The primitive in slot k: leaves name contiguous ranges of slots.
    const std::vector<std::uint32_t>& prims() const { return prims_; }
    /// The nodes, and the root: a node index, or a leaf when the tree is one small leaf
    /// (its box is then bounds()).
    const std::vector<Node>& nodes() const { return nodes_; }
    std::uint32_t root() const { return root_; }
    /// Gives the primitives new names: the slot that held primitive p then holds
    /// new_name[p] (Scene::commit() moves its triangles into slot order). The tree and
    /// its boxes are unchanged.
    void rename(const std::vector<std::uint32_t>& new_name) {
        for (std::uint32_t& p : prims_)
            p = new_name[p];
    }

    /// Visits every leaf whose box the ray may meet, nearer boxes first.
    /// visit(first, count, tmax) is called with the leaf's slots [first, first + count)
    /// and a reference to the current tmax, which it may shrink (closest hit); it returns
    /// true to stop (any hit). nodes_visited counts the interior nodes tested.
    template <class Visit>
    void traverse(const Ray& r, Visit&& visit, std::uint64_t& nodes_visited) const {
        walk<true>(r, visit, nodes_visited);
    }
    /// The same for an any-hit query, without sorting: of two hit children the first
    /// slot is visited first, of more the last slot (the query stops at any hit, and a
    /// shadow ray's nearest boxes hold the surface it leaves, which it cannot hit).
    template <class Visit>
    void traverse_any(const Ray& r, Visit&& visit, std::uint64_t& nodes_visited) const {
        walk<false>(r, visit, nodes_visited);
    }

    /// The slab test of a node's eight boxes against r in [tmin, tmax]: bit k of the
    /// result set when the ray meets child k's box, t_enter[k] the distance at which it
    /// enters it.
    static int hit_children(const Node& n, const Ray& r, const Vec3& inv_w, float tmin,
                            float tmax, float t_enter[kWidth]);

  private:
    template <bool Sorted, class Visit>
    void walk(const Ray& r, Visit& visit, std::uint64_t& nodes_visited) const;

    std::vector<Node> nodes_;
    std::vector<std::uint32_t> prims_;
    Aabb bounds_;
    std::uint32_t root_ = 0;  // a node index, or a leaf for a single small leaf
};

// ---- The slab test of a node ----------------------------------------------------------
//
// Per axis, the ray enters a box at its near plane (lo for a positive direction
// component, hi for a negative one) and leaves it at the far plane; it meets the box when
// the largest entry is no larger than the smallest exit. Choosing the near plane by the
// sign of 1 / w gives box_entry's min(t0, t1) without the min. A NaN (0 * inf: the origin
// in a slab plane along a zero direction component) must leave its axis unconstrained:
// `t > enter ? t : enter` keeps enter when t is NaN (so do the vector instructions the
// engine uses in its place, maxps and minps, by definition).
inline int Bvh::hit_children(const Node& n, const Ray& r, const Vec3& inv_w, float tmin,
                             float tmax, float t_enter[kWidth]) {
    int mask = 0;
    for (int k = 0; k < kWidth; ++k) {
        float enter = tmin, exit = tmax;
        for (int a = 0; a < 3; ++a) {
            const int near = std::signbit(inv_w[a]) ? 1 : 0;
            const float t_near = (n.box[2 * a + near][k] - r.o[a]) * inv_w[a];
            const float t_far = (n.box[2 * a + 1 - near][k] - r.o[a]) * inv_w[a];
            enter = t_near > enter ? t_near : enter;
            exit = t_far < exit ? t_far : exit;
        }
        t_enter[k] = enter;
        mask |= (enter <= exit * kSlabGrow) << k;
    }
    return mask;
}

// ---- The walk -------------------------------------------------------------------------
//
// A depth-first walk with a stack of the children that wait, each with the distance at
// which the ray enters its box. Closest hit: the hit children go onto the stack farthest
// first, so the nearest is taken next, and a waiting child whose box the ray enters
// beyond the nearest hit so far is dropped when its turn comes.
template <bool Sorted, class Visit>
void Bvh::walk(const Ray& r, Visit& visit, std::uint64_t& nodes_visited) const {
    if (prims_.empty()) return;
    float tmax = r.tmax;

    // <<A tree of one small leaf: its box is the scene's bounds>>
    if (root_ & kLeaf) {
        if (box_entry(RaySlabs(r), bounds_, r.tmin, tmax) == kInfinity) return;
        visit(root_ & kFirstMask, root_ >> kCountShift & 7u, tmax);
        return;
    }

    const RaySlabs slabs(r);
    struct Entry {
        std::uint32_t child;
        float t_enter;
    };
    Entry stack[kStackSize];
    int top = 0;
    std::uint32_t child = root_;
    for (;;) {
        if (child & kLeaf) {
            // <<Visit a leaf: its slots [first, first + count); true stops the walk>>
            if (visit(child & kFirstMask, child >> kCountShift & 7u, tmax)) return;
        } else {
            // <<Test the node's eight boxes>>
            const Node& node = nodes_[child];
            ++nodes_visited;
            float t[kWidth];
            const int mask = hit_children(node, r, slabs.inv_w, r.tmin, tmax, t);

            // <<Push the hit children: closest hit, farthest first (on a tie the later
            // slot on top); any hit, in slot order>>
            const int first = top;
            for (int k = 0; k < kWidth; ++k) {
                if (!(mask >> k & 1)) continue;
                int j = top++;
                if (Sorted) {
                    for (; j > first && stack[j - 1].t_enter < t[k]; --j)
                        stack[j] = stack[j - 1];
                }
                stack[j] = Entry{node.child[k], t[k]};
            }
            // Any hit: of two hit children the first slot is taken first
            if (!Sorted && top - first == 2) std::swap(stack[first], stack[first + 1]);

            // <<Go down to the child on top>>
            if (top > first) {
                child = stack[--top].child;
                continue;
            }
        }
        // <<Pop the next waiting child that the ray enters before its nearest hit so
        // far (with the slab test's own margin: one entered just past tmax is visited)>>
        do {
            if (top == 0) return;
            --top;
        } while (stack[top].t_enter > tmax * kSlabGrow);
        child = stack[top].child;
    }
}

}  // namespace raylab
