// raylab/bvh.h: an 8-wide bounding volume hierarchy over boxes, built with binned SAH.
//
// The BVH knows nothing about primitives: it is built from one box per primitive and
// calls back with leaves (ranges of primitive slots) during traversal. The scene
// (raylab/scene.h) owns it and supplies the leaf tests, so the same tree serves
// closest-hit and any-hit, through the module table or the reference's engine.
//
// Layout: a node holds the boxes of its eight children side by side (structure of
// arrays), so two independent 4-wide SSE slab tests check all eight (Wald et al.,
// "Getting Rid of Packets", 2008; Embree does the same 4-, 8- or 16-wide). 224 bytes per
// node, four cache lines. A single ray's walk waits on each node's load before the next:
// eight children make the tree a third shallower than four (log 8 / log 4), and the
// second slab test runs beside the first. raylab-bench's "Where the time goes" table,
// run both ways on the same rays, measured less walk time 8-wide than 4-wide on every
// scene and ray set, and 16-wide in between.
#pragma once

#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "raylab/simd.h"

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
/// misses box in [tmin, tmax]. The SIMD test in Bvh::traverse computes the same.
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
    return t_enter <= t_exit * kSlabGrow ? t_enter : kInfinity;
}

/// Arrays from this size on are backed by huge pages (back_with_huge_pages).
inline constexpr size_t kHugePagesFrom = size_t{4} << 20;

/// Asks the kernel to back the huge pages (2 MiB on x86-64) lying wholly inside
/// [data, data + bytes) with huge pages, when bytes >= kHugePagesFrom: on Linux,
/// madvise(MADV_HUGEPAGE) for the range, then MADV_COLLAPSE (kernel 6.1 on; retried on
/// EAGAIN) to do it at once instead of whenever khugepaged comes by. The BVH's nodes and
/// primitive order and the scene's triangles ask for it: a random ray through a
/// million-triangle mesh loads nodes and triangles from tens of megabytes, and with 4 KiB
/// pages nearly every one of those loads also missed the TLB (Embree, the bench's peer,
/// backs its BVH with huge pages too). Only a hint: the data is unchanged, and a kernel
/// that declines (built without transparent huge pages, older than 6.1, short of free
/// memory) leaves the pages as they are. The collapse is synchronous: on a machine short
/// of free huge pages it may compact memory first, and commit() waits for it.
/// MADV_COLLAPSE does not depend on the system's transparent huge page mode
/// (/sys/kernel/mm/transparent_hugepage/enabled). Returns true when the kernel
/// collapsed the range now.
bool back_with_huge_pages(const void* data, size_t bytes);

struct BvhTestAccess;  // the tests' way to private parts of Bvh

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
    /// Bytes held by nodes and the primitive order (both backed by huge pages from
    /// kHugePagesFrom bytes on).
    size_t bytes() const {
        return nodes_.size() * sizeof(Node) + prims_.size() * sizeof(std::uint32_t);
    }
    const Aabb& bounds() const { return bounds_; }
    /// The primitive in slot k: leaves name contiguous ranges of slots.
    const std::vector<std::uint32_t>& prims() const { return prims_; }
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
    /// Avx: each node's eight boxes in one AVX slab test instead of two SSE ones, and
    /// three or more hit children put in order by place_sorted_avx instead of the
    /// insertion sort (the same results, the same order); only from code compiled for
    /// AVX2 (the reference engine's AVX2 versions, which inline the walk), on a
    /// processor that has it. Without SSE2 or off x86-64 (RAYLAB_AVX_NODES 0) it is
    /// ignored.
    template <bool Avx = false, class Visit>
    void traverse(const Ray& r, Visit&& visit, std::uint64_t& nodes_visited) const {
        walk<true, Avx>(r, visit, nodes_visited);
    }
    /// The same for an any-hit query, without sorting: of two hit children the first
    /// slot is visited first, of more the last slot (the query stops at any hit, and a
    /// shadow ray's nearest boxes hold the surface it leaves, which it cannot hit).
    /// Measured on raylab-bench's shadow rays: faster than sorting on the large mesh; for
    /// closest hits, which sorting lets skip what lies behind a hit, slower.
    template <bool Avx = false, class Visit>
    void traverse_any(const Ray& r, Visit&& visit, std::uint64_t& nodes_visited) const {
        walk<false, Avx>(r, visit, nodes_visited);
    }

    /// A packet of rays from one origin o whose direction components each keep one sign
    /// and are never zero: per axis, the range [inv_lo, inv_hi] of the rays' 1 / w
    /// (each computed as RaySlabs does). Its slab test of a box gives a lower bound of
    /// every ray's entry distance and an upper bound of every exit, so it accepts every
    /// box that one of the rays accepts in traverse() (rounding is monotone).
    struct Frustum {
        Vec3 o{0.0f};
        Vec3 inv_lo{0.0f}, inv_hi{0.0f};
        float tmin = 0.0f;  ///< the smallest tmin of the rays
    };
    /// Visits every leaf whose box a ray of the packet may meet, nearer boxes first (by
    /// the frustum's entry distance), one slab test per node for the whole packet.
    /// visit(first, count, box) tests the leaf's slots [first, first + count) for the
    /// rays that meet the leaf's box (each its own slab test) and returns the largest
    /// tmax of the packet's rays after it: boxes entered beyond it are skipped. tmax: the
    /// largest tmax of the rays at the start.
    template <class Visit>
    void traverse_frustum(const Frustum& f, float tmax, Visit&& visit,
                          std::uint64_t& nodes_visited) const;

  private:
    friend struct BvhTestAccess;  // tests/framework: place_sorted_avx on its own
    template <bool Sorted, bool Avx, class Visit>
    void walk(const Ray& r, Visit& visit, std::uint64_t& nodes_visited) const;
    // The ray, broadcast for the SSE slab test; near[a] names the box row the ray
    // enters by along axis a (lo for a positive direction, hi for a negative one)
    struct Ray4 {
#if RAYLAB_SSE2
        __m128 o[3], inv_w[3];
#else
        float o[3], inv_w[3];
#endif
        int near[3];
    };
    // Asks for a child node's cache lines while the nearer ones are processed
    void prefetch(std::uint32_t child) const {
#if RAYLAB_SSE2
        if (child & kLeaf) return;
        const char* p = reinterpret_cast<const char*>(&nodes_[child]);
        for (size_t line = 0; line < sizeof(Node); line += 64)
            _mm_prefetch(p + line, _MM_HINT_T0);
#else
        (void)child;
#endif
    }
    static int hit_children(const Node& n, const Ray4& r, float tmin, float tmax,
                            float t_enter[kWidth]);
#if RAYLAB_AVX_NODES
    // hit_children's SSE test on all eight boxes in one AVX register: the same
    // operations, and maxps/minps's NaN rule (the second operand) holds for their AVX
    // forms; _CMP_LE_OQ is cmpleps's <= (false for NaN). raylab-bench's rays through
    // its 400,000-triangle mesh, two runs alternated: camera rays 4-6 % and shadow rays
    // 5-7 % faster than with the two SSE tests in the same AVX2 version of the query
    __attribute__((target("avx2"))) static int hit_children_avx(const Node& n,
                                                                const Ray4& r, float tmin,
                                                                float tmax,
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
        return _mm256_movemask_ps(_mm256_cmp_ps(
            enter, _mm256_mul_ps(exit, _mm256_set1_ps(kSlabGrow)), _CMP_LE_OQ));
    }
    // The walk's sort of three or more hit children, in the AVX2 versions: each hit
    // child of mask goes straight to its place on the stack (from out on, farthest
    // first), the number of hit children entered farther than it, or as far from an
    // earlier slot: where the insertion sort puts it (on a tie, the later slot nearer
    // the top). The insertion sort's comparisons are branches that a random ray makes
    // unpredictable (valgrind's branch simulation put a third of the mispredicted
    // branches of a random ray through raylab-bench's random soup in them). Old and new
    // code alternated three times on section 2's rays: random rays through the soup 10 %
    // faster, through the icosphere 4 %, the other sets unchanged within the noise. With
    // two hit children too, Cornell box camera rays were 4 % slower (in-process
    // alternation; their two-child case is predictable), so two keep their compare.
    // A hit child's t is never NaN (its slab test's ordered compare is false for NaN);
    // the ranks need that: a NaN would share a place with another child and leave one
    // unwritten. Returns the number of hit children, counted as they are placed: the
    // same as popcount(mask), but returning that instead changed GCC's registers in the
    // inlined walk and cost Cornell box camera rays 3 % (51.7 against 50.0 ns, eight
    // alternations)
    template <class Entry>
    __attribute__((target("avx2,popcnt"))) int place_sorted_avx(const Node& node,
                                                                const float t[kWidth],
                                                                int mask,
                                                                Entry* out) const {
        const __m256 all = _mm256_load_ps(t);
        int count = 0;
        for (int m = mask; m != 0; m &= m - 1) {
            const int k = __builtin_ctz(static_cast<unsigned>(m));
            assert(!std::isnan(t[k]));
            const __m256 tk = _mm256_broadcast_ss(t + k);
            const int farther = _mm256_movemask_ps(_mm256_cmp_ps(all, tk, _CMP_GT_OQ));
            const int as_far = _mm256_movemask_ps(_mm256_cmp_ps(all, tk, _CMP_EQ_OQ));
            const unsigned before = (farther | (as_far & ((1 << k) - 1))) & mask;
            prefetch(node.child[k]);
            out[_mm_popcnt_u32(before)] = Entry{node.child[k], t[k]};
            ++count;
        }
        return count;
    }
#endif
    // The frustum, broadcast: per axis the origin and the range of 1 / w
    struct Frustum4 {
#if RAYLAB_SSE2
        __m128 o[3], inv_lo[3], inv_hi[3];
#else
        float o[3], inv_lo[3], inv_hi[3];
#endif
        int near[3];
    };
    static int frustum_children(const Node& n, const Frustum4& f, float tmin, float tmax,
                                float t_enter[kWidth]);
    // The walks' stacks of waiting children: at most kWidth - 1 waiting per level of the
    // binary tree's 72 (a node is at least one binary level below its parent). The two
    // walks keep their stack code apart: the single-ray walk with the push and pop as
    // shared helpers measured 3-4 ns slower per Cornell box camera ray (51 against 54-55)
    static constexpr int kStackSize = (kWidth - 1) * 72 + 8;

    std::vector<Node> nodes_;
    std::vector<std::uint32_t> prims_;
    Aabb bounds_;
    std::uint32_t root_ = 0;  // a node index, or a leaf for a single small leaf
};

// The slab test of a node's boxes: a bit per child the ray meets in [tmin, tmax], and the
// entry distances. Choosing the entry plane by the sign of 1/w gives box_entry's
// min(t0, t1) without the min. A NaN (0 * inf: the origin in a slab plane along a zero
// direction component) must leave its axis unconstrained: max(t, acc) and min(t, acc)
// with the axis value first return acc for a NaN, as SSE's maxps and minps do by
// definition (Intel SDM: the second operand is returned when either is NaN).
inline int Bvh::hit_children(const Node& n, const Ray4& r, float tmin, float tmax,
                             float t_enter[kWidth]) {
#if RAYLAB_SSE2
    // Four boxes per SSE register, the groups independent of each other
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

template <bool Sorted, bool Avx, class Visit>
void Bvh::walk(const Ray& r, Visit& visit, std::uint64_t& nodes_visited) const {
    if (prims_.empty()) return;
    float tmax = r.tmax;
    if (root_ & kLeaf) {
        // One small leaf: its box is the scene's bounds
        if (box_entry(RaySlabs(r), bounds_, r.tmin, tmax) == kInfinity) return;
        visit(root_ & kFirstMask, root_ >> kCountShift & 7u, tmax);
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
    // The farther children wait on the stack with their entry distance, skipped if a hit
    // has come closer since
    struct Entry {
        std::uint32_t child;
        float t_enter;
    };
    Entry stack[kStackSize];
    int top = 0;
    std::uint32_t child = root_;
    for (;;) {
        if (child & kLeaf) {
            if (visit(child & kFirstMask, child >> kCountShift & 7u, tmax)) return;
        } else {
            const Node& node = nodes_[child];
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
                // likely: with place_sorted_avx inlined below, GCC otherwise laid the
                // walk out so that Cornell box camera rays took 8 % longer (56.3
                // against 52.2 ns, five alternations); out of line, it cost the Cornell
                // box's random rays 2.5 %
                if (__builtin_expect((rest & (rest - 1)) == 0, 1)) {
                    const int k1 = __builtin_ctz(static_cast<unsigned>(rest));
                    const bool k0_first = Sorted ? t[k0] < t[k1] : true;
                    const int near = k0_first ? k0 : k1, far = k0_first ? k1 : k0;
                    prefetch(node.child[far]);
                    stack[top++] = Entry{node.child[far], t[far]};
                    child = node.child[near];
                    continue;
                }
                // Sort the hit children farthest first onto the stack (any hit: in slot
                // order); take the top one
                const int first = top;
#if RAYLAB_AVX_NODES
                if constexpr (Sorted && Avx) {
                    top += place_sorted_avx(node, t, mask, stack + first);
                    child = stack[--top].child;
                    continue;
                }
#endif
                for (; mask != 0; mask &= mask - 1) {
                    const int k = __builtin_ctz(static_cast<unsigned>(mask));
                    const Entry e{node.child[k], t[k]};
                    prefetch(e.child);
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
        // with the slab test's own margin: a box it kept as entered just past tmax
        // (within kSlabGrow) is visited, not dropped here
        do {
            if (top == 0) return;
            --top;
        } while (stack[top].t_enter > tmax * kSlabGrow);
        child = stack[top].child;
    }
}

// The frustum's slab test of a node's boxes: per axis, the near plane's distance with
// the smaller and the far plane's with the larger of the two reciprocals bound every
// ray's (x * inv rounds monotonically in inv for a fixed x = plane - o, which all rays
// share). No NaN: the reciprocals are finite and not zero, and an unused slot's infinite
// planes give +-inf.
inline int Bvh::frustum_children(const Node& n, const Frustum4& f, float tmin, float tmax,
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

template <class Visit>
void Bvh::traverse_frustum(const Frustum& fr, float tmax, Visit&& visit,
                           std::uint64_t& nodes_visited) const {
    if (prims_.empty()) return;
    if (root_ & kLeaf) {
        // One small leaf: its box is the scene's bounds
        visit(root_ & kFirstMask, root_ >> kCountShift & 7u, bounds_);
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
    // A waiting child, its entry distance, and where its box is: node * kWidth + slot
    struct Entry {
        std::uint32_t child;
        float t_enter;
        std::uint32_t box;
    };
    Entry stack[kStackSize];
    int top = 0;
    std::uint32_t child = root_, box = 0;
    for (;;) {
        if (child & kLeaf) {
            const Node& n = nodes_[box / kWidth];
            const std::uint32_t k = box % kWidth;
            const Aabb leaf{Vec3(n.box[0][k], n.box[2][k], n.box[4][k]),
                            Vec3(n.box[1][k], n.box[3][k], n.box[5][k])};
            tmax = visit(child & kFirstMask, child >> kCountShift & 7u, leaf);
        } else {
            const Node& node = nodes_[child];
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

}  // namespace raylab
