// Binned SAH BVH construction (raylab/bvh.h), after pbrt-v4 §7.3 and Wald, "On fast
// Construction of SAH-based Bounding Volume Hierarchies" (2007).
#include "raylab/bvh.h"

#include <algorithm>
#include <numeric>

namespace raylab {

namespace {

constexpr int kBins = 16;
constexpr std::uint32_t kMaxLeaf = 4;
constexpr int kMaxSahDepth = 40;        // then index halving: depth <= 40 + 32
constexpr float kTraversalCost = 1.0f;  // relative to one primitive test

struct Bin {
    Aabb box;
    std::uint32_t count = 0;
};

struct Builder {
    const std::vector<Aabb>& boxes;
    std::vector<Vec3> centres;
    std::vector<std::uint32_t>& prims;
    std::vector<Bvh::Node>& nodes;

    // Builds the subtree over prims[first, first + count) into nodes[index].
    void build(std::uint32_t index, std::uint32_t first, std::uint32_t count, int depth) {
        // Bounds of the primitives and of their centres
        Aabb box, centre_box;
        for (std::uint32_t k = first; k < first + count; ++k) {
            box.grow(boxes[prims[k]]);
            centre_box.grow(centres[prims[k]]);
        }
        nodes[index].box = box;
        const auto make_leaf = [&] {
            nodes[index].first_or_second = first;
            nodes[index].count = count;
        };
        if (count <= 1) return make_leaf();
        // Deep trees (pathological input): halve by index so the depth stays bounded
        if (depth >= kMaxSahDepth) return split(index, first, count, count / 2, depth);

        // Best split over kBins bins along every axis with a non-zero centre extent
        float best_cost = kInfinity;
        int best_axis = -1, best_bin = 0;
        for (int axis = 0; axis < 3; ++axis) {
            const float lo = centre_box.lo[axis], extent = centre_box.hi[axis] - lo;
            if (!(extent > 0.0f)) continue;
            Bin bins[kBins];
            for (std::uint32_t k = first; k < first + count; ++k) {
                const int b = bin_of(centres[prims[k]][axis], lo, extent);
                bins[b].box.grow(boxes[prims[k]]);
                ++bins[b].count;
            }
            // Sweep from the right, then from the left, to get both sides' areas
            float right_area[kBins];
            std::uint32_t right_count[kBins];
            Aabb acc;
            std::uint32_t n = 0;
            for (int b = kBins - 1; b > 0; --b) {
                acc.grow(bins[b].box);
                n += bins[b].count;
                right_area[b] = acc.half_area();
                right_count[b] = n;
            }
            acc = Aabb{};
            n = 0;
            for (int b = 0; b < kBins - 1; ++b) {
                acc.grow(bins[b].box);
                n += bins[b].count;
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

        // SAH termination: a leaf is cheaper than the split (small leaves only)
        const float leaf_cost = static_cast<float>(count);
        const float split_cost =
            kTraversalCost + best_cost / std::max(box.half_area(), 1e-30f);
        if (best_axis < 0 || (count <= kMaxLeaf && leaf_cost <= split_cost)) {
            if (best_axis >= 0 || count <= kMaxLeaf) return make_leaf();
            // All centres coincide: split by index so leaves stay small
            return split(index, first, count, count / 2, depth);
        }

        // Partition by bin
        const float lo = centre_box.lo[best_axis];
        const float extent = centre_box.hi[best_axis] - lo;
        std::uint32_t* mid = std::partition(
            prims.data() + first, prims.data() + first + count, [&](std::uint32_t p) {
                return bin_of(centres[p][best_axis], lo, extent) <= best_bin;
            });
        split(index, first, count,
              static_cast<std::uint32_t>(mid - (prims.data() + first)), depth);
    }

    void split(std::uint32_t index, std::uint32_t first, std::uint32_t count,
               std::uint32_t left_count, int depth) {
        nodes[index].count = 0;
        const std::uint32_t left = static_cast<std::uint32_t>(nodes.size());
        nodes.emplace_back();
        build(left, first, left_count, depth + 1);
        const std::uint32_t right = static_cast<std::uint32_t>(nodes.size());
        nodes.emplace_back();
        nodes[index].first_or_second = right;
        build(right, first + left_count, count - left_count, depth + 1);
    }

    static int bin_of(float c, float lo, float extent) {
        const int b = static_cast<int>(kBins * ((c - lo) / extent));
        return std::clamp(b, 0, kBins - 1);
    }
};

}  // namespace

void Bvh::build(const std::vector<Aabb>& boxes) {
    nodes_.clear();
    prims_.resize(boxes.size());
    std::iota(prims_.begin(), prims_.end(), 0u);
    if (boxes.empty()) return;
    nodes_.reserve(2 * boxes.size());
    nodes_.emplace_back();
    Builder builder{boxes, {}, prims_, nodes_};
    builder.centres.reserve(boxes.size());
    for (const Aabb& b : boxes)
        builder.centres.push_back(b.centre());
    builder.build(0, 0, static_cast<std::uint32_t>(boxes.size()), 0);
}

}  // namespace raylab
