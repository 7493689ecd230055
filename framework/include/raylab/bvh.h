// raylab/bvh.h: a bounding volume hierarchy over boxes, built with binned SAH.
//
// The BVH knows nothing about primitives: it is built from one box per primitive and
// calls back with primitive indices during traversal. The scene (raylab/scene.h) owns it
// and supplies the intersection callbacks, so the same tree serves closest-hit and
// any-hit.
#pragma once

#include <cstdint>
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

/// Slab test: the distance at which the ray enters box, or +infinity when it misses box
/// in [tmin, tmax]. The far distance is enlarged by 2 gamma(3) (pbrt-v4 §6.1.2) so
/// rounding never culls a box the ray touches.
inline float box_entry(const RaySlabs& s, const Aabb& box, float tmin, float tmax) {
    const Vec3 t0 = (box.lo - s.o) * s.inv_w;
    const Vec3 t1 = (box.hi - s.o) * s.inv_w;
    // A ray in a slab's plane along a +-0 component gives 0 * inf = NaN: that slab holds
    // the whole ray, so a NaN on either side makes the axis unconstrained (-inf, +inf).
    // glm::min/max would return the other operand and cull the box (issue 8, B2)
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
    constexpr float kGrow =
        1.0f + 2.0f * 3.0f * 0.5f * std::numeric_limits<float>::epsilon();
    return t_enter <= t_exit * kGrow ? t_enter : kInfinity;
}

class Bvh {
  public:
    /// A node: an interior node has count == 0 and children at index + 1 and second;
    /// a leaf holds prims[first, first + count).
    struct Node {
        Aabb box;
        std::uint32_t first_or_second =
            0;                    ///< leaf: first primitive; interior: right child
        std::uint32_t count = 0;  ///< primitives in a leaf, 0 for interior nodes
    };

    /// Builds the tree over one box per primitive (binned SAH, 16 bins).
    void build(const std::vector<Aabb>& boxes);

    bool empty() const { return nodes_.empty(); }
    size_t node_count() const { return nodes_.size(); }
    const Aabb& bounds() const { return nodes_.front().box; }

    /// Visits every leaf primitive whose box the ray may meet, nearer child first.
    /// visit(prim, tmax) is called with the primitive index and a reference to the
    /// current tmax, which it may shrink (closest hit); it returns true to stop (any
    /// hit). nodes_visited counts the nodes whose box was tested.
    template <class Visit>
    void traverse(const Ray& r, Visit&& visit, std::uint64_t& nodes_visited) const;

  private:
    std::vector<Node> nodes_;
    std::vector<std::uint32_t> prims_;
};

template <class Visit>
void Bvh::traverse(const Ray& r, Visit&& visit, std::uint64_t& nodes_visited) const {
    if (nodes_.empty()) return;
    const RaySlabs slabs(r);
    float tmax = r.tmax;
    ++nodes_visited;
    if (box_entry(slabs, nodes_.front().box, r.tmin, tmax) == kInfinity) return;
    // Both children's boxes are tested together; the nearer is visited first and the
    // farther waits on the stack with its entry distance, skipped if a hit has come
    // closer since
    struct Entry {
        std::uint32_t index;
        float t_enter;
    };
    Entry stack[128];  // the build bounds the depth by 72
    int top = 0;
    std::uint32_t index = 0;
    for (;;) {
        const Node& node = nodes_[index];
        if (node.count > 0) {
            for (std::uint32_t k = 0; k < node.count; ++k) {
                if (visit(prims_[node.first_or_second + k], tmax)) return;
            }
        } else {
            std::uint32_t near = index + 1, far = node.first_or_second;
            float t_near = box_entry(slabs, nodes_[near].box, r.tmin, tmax);
            float t_far = box_entry(slabs, nodes_[far].box, r.tmin, tmax);
            nodes_visited += 2;
            if (t_far < t_near) {
                std::swap(near, far);
                std::swap(t_near, t_far);
            }
            if (t_near != kInfinity) {
                if (t_far != kInfinity) stack[top++] = Entry{far, t_far};
                index = near;
                continue;
            }
        }
        // Next waiting node that the ray can still reach before its closest hit so far
        do {
            if (top == 0) return;
            --top;
        } while (stack[top].t_enter > tmax);
        index = stack[top].index;
    }
}

}  // namespace raylab
