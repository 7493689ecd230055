// The prototype pair BVH's build (bench/proto_bvh.h): raylab's binned SAH, pair layout.
#include "proto_bvh.h"

#include <algorithm>
#include <numeric>

namespace raylab::bench {

namespace {
constexpr int kBins = 16;
constexpr std::uint32_t kMaxLeaf = 4;
constexpr int kMaxSahDepth = 40;  // then index halving: depth <= 40 + 32 < 128
}  // namespace

struct PairBuilder {
    const std::vector<Aabb>& boxes;
    std::vector<Vec3> centres;
    PairBvh& bvh;

    static int bin_of(float c, float lo, float extent) {
        return std::clamp(static_cast<int>(kBins * ((c - lo) / extent)), 0, kBins - 1);
    }

    // Best binned SAH split of prims[first, first + count): axis, bin and cost
    void best_split(std::uint32_t first, std::uint32_t count, const Aabb& centre_box,
                    int& axis_out, int& bin_out, float& cost_out) const {
        cost_out = kInfinity;
        axis_out = -1;
        for (int axis = 0; axis < 3; ++axis) {
            const float lo = centre_box.lo[axis], extent = centre_box.hi[axis] - lo;
            if (!(extent > 0.0f)) continue;
            Aabb bin_box[kBins];
            std::uint32_t bin_count[kBins] = {};
            for (std::uint32_t k = first; k < first + count; ++k) {
                const int b = bin_of(centres[bvh.prims_[k]][axis], lo, extent);
                bin_box[b].grow(boxes[bvh.prims_[k]]);
                ++bin_count[b];
            }
            float right_area[kBins];
            std::uint32_t right_count[kBins];
            Aabb acc;
            std::uint32_t n = 0;
            for (int b = kBins - 1; b > 0; --b) {
                acc.grow(bin_box[b]);
                n += bin_count[b];
                right_area[b] = acc.half_area();
                right_count[b] = n;
            }
            acc = Aabb{};
            n = 0;
            for (int b = 0; b < kBins - 1; ++b) {
                acc.grow(bin_box[b]);
                n += bin_count[b];
                if (n == 0 || right_count[b + 1] == 0) continue;
                const float cost =
                    acc.half_area() * n + right_area[b + 1] * right_count[b + 1];
                if (cost < cost_out) {
                    cost_out = cost;
                    axis_out = axis;
                    bin_out = b;
                }
            }
        }
    }

    void build(std::uint32_t pair, int slot, std::uint32_t first, std::uint32_t count,
               int depth) {
        Aabb box, centre_box;
        for (std::uint32_t k = first; k < first + count; ++k) {
            box.grow(boxes[bvh.prims_[k]]);
            centre_box.grow(centres[bvh.prims_[k]]);
        }
        const auto node = [&]() -> PairBvh::Node& {
            return bvh.pairs_[pair].child[slot];
        };
        node().lo = box.lo;
        node().hi = box.hi;
        node().first_or_pair = first;
        node().count = count;
        if (count <= 1) return;
        int axis = -1, bin = 0;
        float cost = kInfinity;
        // Deep trees (pathological input): halve by index, as raylab's build does
        if (depth < kMaxSahDepth) best_split(first, count, centre_box, axis, bin, cost);
        const float split_cost = 1.0f + cost / std::max(box.half_area(), 1e-30f);
        if (count <= kMaxLeaf && (axis < 0 || static_cast<float>(count) <= split_cost))
            return;
        std::uint32_t left = count / 2;
        if (axis >= 0) {
            const float lo = centre_box.lo[axis], extent = centre_box.hi[axis] - lo;
            std::uint32_t* begin = bvh.prims_.data() + first;
            std::uint32_t* mid =
                std::partition(begin, begin + count, [&](std::uint32_t p) {
                    return bin_of(centres[p][axis], lo, extent) <= bin;
                });
            left = static_cast<std::uint32_t>(mid - begin);
        }
        const std::uint32_t children = static_cast<std::uint32_t>(bvh.pairs_.size());
        bvh.pairs_.emplace_back();
        node().first_or_pair = children;
        node().count = 0;
        build(children, 0, first, left, depth + 1);
        build(children, 1, first + left, count - left, depth + 1);
    }
};

void PairBvh::build(const std::vector<Aabb>& boxes) {
    pairs_.clear();
    prims_.resize(boxes.size());
    std::iota(prims_.begin(), prims_.end(), 0u);
    if (boxes.empty()) return;
    pairs_.reserve(boxes.size());
    pairs_.emplace_back();  // the root's pair; its second slot stays unused
    PairBuilder builder{boxes, {}, *this};
    for (const Aabb& b : boxes)
        builder.centres.push_back(b.centre());
    builder.build(0, 0, 0, static_cast<std::uint32_t>(boxes.size()), 0);
}

}  // namespace raylab::bench
