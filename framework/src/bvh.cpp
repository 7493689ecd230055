// BVH construction (raylab/bvh.h): a binary tree by binned SAH, after pbrt-v4 §7.3 and
// Wald, "On fast Construction of SAH-based Bounding Volume Hierarchies" (2007), then
// collapsed to four children per node by pulling up the largest grandchildren (Wald,
// Benthin and Boulos, "Getting Rid of Packets", 2008).
#include "raylab/bvh.h"

#include <algorithm>
#include <thread>

#include "raylab/error.h"

namespace raylab {

namespace {

constexpr int kBins = 16;
constexpr int kMaxSahDepth = 40;        // then index halving: depth <= 40 + 32
constexpr float kTraversalCost = 1.0f;  // relative to one primitive test
// Below this many primitives a second thread costs more than it saves
constexpr std::uint32_t kParallelMin = 16384;

struct Bin {
    Aabb box;
    std::uint32_t count = 0;
};

// A node of the binary tree: interior nodes have count == 0, the left child at
// index + 1 and the right one at first_or_second; a leaf holds slots [first, + count)
struct BinaryNode {
    Aabb box;
    std::uint32_t first_or_second = 0;
    std::uint32_t count = 0;
};

// A primitive during the build: its box and index, moved together so that every pass
// over a node's primitives reads memory in order
struct Ref {
    Aabb box;
    std::uint32_t prim;
    Vec3 centre() const { return box.centre(); }
};

struct Builder {
    std::vector<Ref>& refs;
    std::vector<BinaryNode> nodes;

    // Builds the subtree over refs[first, first + count) into nodes[index].
    void build(std::uint32_t index, std::uint32_t first, std::uint32_t count, int depth) {
        // Bounds of the primitives and of their centres
        Aabb box, centre_box;
        for (std::uint32_t k = first; k < first + count; ++k) {
            box.grow(refs[k].box);
            centre_box.grow(refs[k].centre());
        }
        nodes[index].box = box;
        const auto make_leaf = [&] {
            nodes[index].first_or_second = first;
            nodes[index].count = count;
        };
        if (count <= 1) return make_leaf();
        // Deep trees (pathological input): halve by index so the depth stays bounded
        if (depth >= kMaxSahDepth) return split(index, first, count, count / 2, depth);
        int axis = -1, bin = 0;
        const float cost = best_split(first, count, centre_box, axis, bin);
        // SAH termination: a leaf is cheaper than the split (small leaves only)
        const float leaf_cost = static_cast<float>(count);
        const float split_cost =
            kTraversalCost + cost / std::max(box.half_area(), 1e-30f);
        if (axis < 0 || (count <= Bvh::kMaxLeafSize && leaf_cost <= split_cost)) {
            if (axis >= 0 || count <= Bvh::kMaxLeafSize) return make_leaf();
            // All centres coincide: split by index so leaves stay small
            return split(index, first, count, count / 2, depth);
        }
        // Partition by bin
        const float lo = centre_box.lo[axis];
        const float scale = kBins / (centre_box.hi[axis] - lo);
        Ref* mid = std::partition(
            refs.data() + first, refs.data() + first + count,
            [&](const Ref& r) { return bin_of(r.centre()[axis], lo, scale) <= bin; });
        split(index, first, count,
              static_cast<std::uint32_t>(mid - (refs.data() + first)), depth);
    }

    // The SAH cost of the best split over kBins bins along every axis with a non-zero
    // centre extent (all three binned in one pass); axis stays -1 when there is none
    float best_split(std::uint32_t first, std::uint32_t count, const Aabb& centre_box,
                     int& best_axis, int& best_bin) const {
        Bin bins[3][kBins];
        float lo[3], scale[3];
        bool active[3];
        for (int axis = 0; axis < 3; ++axis) {
            const float extent = centre_box.hi[axis] - centre_box.lo[axis];
            active[axis] = extent > 0.0f;
            lo[axis] = centre_box.lo[axis];
            scale[axis] = active[axis] ? kBins / extent : 0.0f;
        }
        for (std::uint32_t k = first; k < first + count; ++k) {
            const Ref& r = refs[k];
            const Vec3 c = r.centre();
            for (int axis = 0; axis < 3; ++axis) {
                Bin& b = bins[axis][bin_of(c[axis], lo[axis], scale[axis])];
                b.box.grow(r.box);
                ++b.count;
            }
        }
        float best_cost = kInfinity;
        for (int axis = 0; axis < 3; ++axis) {
            if (!active[axis]) continue;
            // Sweep from the right, then from the left, to get both sides' areas
            float right_area[kBins];
            std::uint32_t right_count[kBins];
            Aabb acc;
            std::uint32_t n = 0;
            for (int b = kBins - 1; b > 0; --b) {
                acc.grow(bins[axis][b].box);
                n += bins[axis][b].count;
                right_area[b] = acc.half_area();
                right_count[b] = n;
            }
            acc = Aabb{};
            n = 0;
            for (int b = 0; b < kBins - 1; ++b) {
                acc.grow(bins[axis][b].box);
                n += bins[axis][b].count;
                if (n == 0 || right_count[b + 1] == 0) continue;
                const float cost =
                    acc.half_area() * n + right_area[b + 1] * right_count[b + 1];
                if (cost < best_cost) {
                    best_cost = cost;
                    best_axis = axis;
                    best_bin = b;
                }
            }
        }
        return best_cost;
    }

    // The right half of a large split is built by a second thread into its own nodes,
    // appended after the left half (whose root is index + 1, as always)
    void split(std::uint32_t index, std::uint32_t first, std::uint32_t count,
               std::uint32_t left_count, int depth) {
        nodes[index].count = 0;
        const std::uint32_t right_count = count - left_count;
        Builder right{refs, {}};
        std::thread helper;
        if (depth == 0 && right_count >= kParallelMin &&
            std::thread::hardware_concurrency() > 1) {
            helper =
                std::thread([&] { right.build_root(first + left_count, right_count); });
        }
        const std::uint32_t left = static_cast<std::uint32_t>(nodes.size());
        nodes.emplace_back();
        build(left, first, left_count, depth + 1);
        const std::uint32_t right_root = static_cast<std::uint32_t>(nodes.size());
        nodes[index].first_or_second = right_root;
        if (helper.joinable()) {
            helper.join();
            for (BinaryNode n : right.nodes) {
                if (n.count == 0) n.first_or_second += right_root;
                nodes.push_back(n);
            }
            return;
        }
        nodes.emplace_back();
        build(right_root, first + left_count, right_count, depth + 1);
    }

    void build_root(std::uint32_t first, std::uint32_t count) {
        nodes.reserve(2 * count);
        nodes.emplace_back();
        build(0, first, count, 1);
    }

    static int bin_of(float c, float lo, float scale) {
        const int b = static_cast<int>((c - lo) * scale);
        return std::clamp(b, 0, kBins - 1);
    }
};

}  // namespace

// Collapses the binary subtree at binary[index] into 4-wide nodes; returns its child
// code (a node index or a leaf)
static std::uint32_t collapse(const std::vector<BinaryNode>& binary, std::uint32_t index,
                              std::vector<Bvh::Node>& nodes) {
    const BinaryNode& b = binary[index];
    if (b.count > 0) return Bvh::kLeaf | b.count << Bvh::kCountShift | b.first_or_second;
    // Open the interior child of largest area until there are four
    std::uint32_t kids[4] = {index + 1, b.first_or_second, 0, 0};
    int n = 2;
    while (n < 4) {
        int widest = -1;
        for (int k = 0; k < n; ++k) {
            const BinaryNode& c = binary[kids[k]];
            if (c.count == 0 &&
                (widest < 0 || c.box.half_area() > binary[kids[widest]].box.half_area()))
                widest = k;
        }
        if (widest < 0) break;
        const std::uint32_t opened = kids[widest];
        kids[widest] = opened + 1;
        kids[n++] = binary[opened].first_or_second;
    }
    const std::uint32_t self = static_cast<std::uint32_t>(nodes.size());
    nodes.emplace_back();
    for (int k = 0; k < 4; ++k) {
        const Aabb box = k < n ? binary[kids[k]].box : Aabb{};
        for (int a = 0; a < 3; ++a) {
            nodes[self].box[2 * a][k] = box.lo[a];
            nodes[self].box[2 * a + 1][k] = box.hi[a];
        }
        // An unused slot: an empty box and a leaf of no primitives
        const std::uint32_t code = k < n ? collapse(binary, kids[k], nodes) : Bvh::kLeaf;
        nodes[self].child[k] = code;
    }
    return self;
}

void Bvh::build(const std::vector<Aabb>& boxes) {
    nodes_.clear();
    bounds_ = Aabb{};
    root_ = 0;
    prims_.resize(boxes.size());
    if (boxes.empty()) return;
    if (boxes.size() > kFirstMask)
        throw Error("too many primitives for the BVH: " + std::to_string(boxes.size()) +
                    " (at most " + std::to_string(kFirstMask) + ")");
    std::vector<Ref> refs(boxes.size());
    for (std::uint32_t k = 0; k < refs.size(); ++k)
        refs[k] = Ref{boxes[k], k};
    Builder builder{refs, {}};
    builder.nodes.reserve(2 * boxes.size());
    builder.nodes.emplace_back();
    builder.build(0, 0, static_cast<std::uint32_t>(boxes.size()), 0);
    for (std::uint32_t k = 0; k < refs.size(); ++k)
        prims_[k] = refs[k].prim;
    bounds_ = builder.nodes[0].box;
    nodes_.reserve(builder.nodes.size() / 3 + 1);
    root_ = collapse(builder.nodes, 0, nodes_);
    nodes_.shrink_to_fit();
}

}  // namespace raylab
