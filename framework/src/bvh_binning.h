// The BVH build's binned SAH (framework/src/bvh.cpp): bins, the cost sweep over them, the
// partition and the bounds of a range of primitives.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "bvh_build_data.h"

namespace raylab::bvh_build {

// The bin of each axis for a centre c: floor((c - lo) * scale) clamped to [0, kBins - 1]
// (a NaN, from an inactive axis's zero scale, gives bin 0)
struct Binning {
    F4 lo, scale;
    // (c - lo) * scale clamped to [0, kBins - 1]: the bins before truncation
    F4 coordinates(F4 c) const {
        return min(max(mul(sub(c, lo), scale), splat(0.0f)), splat(kBins - 1.0f));
    }
    void bins_of(F4 c, int bin[4]) const { store_int(bin, coordinates(c)); }
};

// The bins of the three axes. A bin's box is valid when its bit in occupied is set. Its
// count rides in lane 3 of hi, as the bits kCountBase + count (a normal float, so min
// and max leave it alone; the refs' hi holds 0 there): counting costs no memory access
constexpr std::uint32_t kCountBase = 0x3f800000u;  // 1.0f
struct Bins {
    struct Bin {
        F4 lo, hi;
        std::uint32_t count() const { return lane3(hi) - kCountBase; }
    };
    Bin bin[3][kBins];
    unsigned occupied[3] = {0, 0, 0};

    // A bin is written when its first primitive arrives, so only the bins in use are
    // touched
    void add_sparse(const Ref& r, const Binning& binning) {
        alignas(16) int b[4];
        binning.bins_of(r.centre(), b);
        const F4 lo = load(r.lo), hi = load(r.hi);
        for (int axis = 0; axis < 3; ++axis) {
            Bin& x = bin[axis][b[axis]];
            const unsigned bit = 1u << b[axis];
            if (occupied[axis] & bit) {
                x.lo = min(lo, x.lo);
                x.hi = add_lane3(max(hi, x.hi), 1);
            } else {
                x = Bin{lo, add_lane3(hi, kCountBase + 1)};
                occupied[axis] |= bit;
            }
        }
    }
    void clear() {
        const F4 empty_hi = add_lane3(xyz(splat(-kInfinity)), kCountBase);
        for (auto& axis : bin) {
            for (Bin& x : axis)
                x = Bin{splat(kInfinity), empty_hi};
        }
    }
    void add(const Ref& r, const Binning& binning) {
        alignas(16) int b[4];
        binning.bins_of(r.centre(), b);
        const F4 lo = load(r.lo), hi = load(r.hi);
        for (int axis = 0; axis < 3; ++axis) {
            Bin& x = bin[axis][b[axis]];
            x.lo = min(lo, x.lo);
            x.hi = add_lane3(max(hi, x.hi), 1);
        }
    }
    void set_occupied() {
        for (int axis = 0; axis < 3; ++axis) {
            occupied[axis] = 0;
            for (int b = 0; b < kBins; ++b)
                occupied[axis] |= (bin[axis][b].count() != 0 ? 1u : 0u) << b;
        }
    }
    void merge(const Bins& o) {
        for (int axis = 0; axis < 3; ++axis) {
            for (int b = 0; b < kBins; ++b) {
                if (!(o.occupied[axis] >> b & 1u)) continue;
                Bin& x = bin[axis][b];
                const Bin& y = o.bin[axis][b];
                if (occupied[axis] >> b & 1u) {
                    // max of the counts' bits is the larger count; add the smaller
                    const std::uint32_t smaller = std::min(x.count(), y.count());
                    x.lo = min(y.lo, x.lo);
                    x.hi = add_lane3(max(y.hi, x.hi), smaller);
                } else {
                    x = y;
                }
            }
            occupied[axis] |= o.occupied[axis];
        }
    }
};

// Bins refs[first, end). Below 8 primitives only the bins in use are written (a branch
// per primitive and axis); from 8 on, clearing all 48 bins first is cheaper than the
// branch's mispredictions; from 64 on, even and odd primitives go to two sets of bins,
// merged after, so that neighbours (often in the same bins) do not wait on each other's
// stores
constexpr std::uint32_t kOneSetMin = 8;
constexpr std::uint32_t kTwoSetsMin = 64;
inline void bin_range(const Ref* refs, std::uint32_t first, std::uint32_t end,
                      const Binning& binning, Bins& bins) {
    if (end - first < kOneSetMin) {
        for (std::uint32_t k = first; k < end; ++k)
            bins.add_sparse(refs[k], binning);
        return;
    }
    if (end - first < kTwoSetsMin) {
        bins.clear();
        for (std::uint32_t k = first; k < end; ++k)
            bins.add(refs[k], binning);
        bins.set_occupied();
        return;
    }
    Bins odd;
    bins.clear();
    odd.clear();
    std::uint32_t k = first;
    for (; k + 1 < end; k += 2) {
        bins.add(refs[k], binning);
        odd.add(refs[k + 1], binning);
    }
    if (k < end) bins.add(refs[k], binning);
    bins.set_occupied();
    odd.set_occupied();
    bins.merge(odd);
}

// The occupied bins of one axis, in order
inline int occupied_bins(unsigned occupied, int list[kBins]) {
    int n = 0;
    for (; occupied != 0; occupied &= occupied - 1)
        list[n++] = __builtin_ctz(occupied);
    return n;
}

// The binning of t's centres: kBins bins along every axis with a non-zero centre extent
inline Binning binning_of(const Task& t, bool active[3]) {
    alignas(16) float lo[4], hi[4], scale[4] = {};
    store(lo, t.centres.lo);
    store(hi, t.centres.hi);
    for (int axis = 0; axis < 3; ++axis) {
        const float extent = hi[axis] - lo[axis];
        active[axis] = extent > 0.0f;
        scale[axis] = active[axis] ? kBins / extent : 0.0f;
    }
    return Binning{t.centres.lo, load(scale)};
}

// Finds the cheapest split between the bins of the active axes (all three binned in one
// pass). Returns the SAH cost; axis stays -1 when there is no split, else left and right
// get the two sides' boxes. The planes between two occupied bins all give the same
// cost, so only the first of them is costed
inline float best_split(const Bins& bins, const bool active[3], int& best_axis,
                        int& best_bin, Box4& left, Box4& right) {
    float best_cost = kInfinity;
    for (int axis = 0; axis < 3; ++axis) {
        int list[kBins];
        const int n_bins = occupied_bins(bins.occupied[axis], list);
        if (!active[axis] || n_bins < 2) continue;
        const Bins::Bin* bin = bins.bin[axis];
        // Sweep from the right, then from the left, to get both sides' areas
        float right_area[kBins];
        std::uint32_t right_count[kBins];
        Box4 acc;
        std::uint32_t n = 0;
        for (int i = n_bins - 1; i > 0; --i) {
            acc.grow(bin[list[i]].lo, bin[list[i]].hi);
            n += bin[list[i]].count();
            right_area[i] = acc.half_area();
            right_count[i] = n;
        }
        acc = Box4{};
        n = 0;
        for (int i = 0; i < n_bins - 1; ++i) {
            acc.grow(bin[list[i]].lo, bin[list[i]].hi);
            n += bin[list[i]].count();
            const float cost =
                acc.half_area() * n + right_area[i + 1] * right_count[i + 1];
            if (cost < best_cost) {
                best_cost = cost;
                best_axis = axis;
                best_bin = list[i];
            }
        }
    }
    if (best_axis >= 0) {
        int list[kBins];
        const int n_bins = occupied_bins(bins.occupied[best_axis], list);
        for (int i = 0; i < n_bins; ++i) {
            const Bins::Bin& b = bins.bin[best_axis][list[i]];
            (list[i] <= best_bin ? left : right).grow(b.lo, b.hi);
        }
    }
    return best_cost;
}

// Moves the refs in [first, last) that go left before the others, in the order
// std::partition (libstdc++) leaves them: each ref is asked once, before it is moved, so
// goes_left may also answer by the ref's original position. Returns the number on the
// left
template <class GoesLeft>
inline std::uint32_t partition(Ref* first, Ref* last, GoesLeft goes_left) {
    Ref* const begin = first;
    for (;;) {
        for (;; ++first) {
            if (first == last) return static_cast<std::uint32_t>(first - begin);
            if (!goes_left(first)) break;
        }
        --last;
        for (;; --last) {
            if (first == last) return static_cast<std::uint32_t>(first - begin);
            if (goes_left(last)) break;
        }
        std::swap(*first, *last);
        ++first;
    }
}

// Boxes of refs[first, first + count) and of their centres
inline void bounds(const Ref* refs, std::uint32_t first, std::uint32_t count, Box4& box,
                   Box4& centres) {
    for (std::uint32_t k = first; k < first + count; ++k) {
        box.grow(load(refs[k].lo), load(refs[k].hi));
        centres.grow(refs[k].centre());
    }
}

}  // namespace raylab::bvh_build
