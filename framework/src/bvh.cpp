// BVH construction (raylab/bvh.h): a binary tree by binned SAH, after pbrt-v4 §7.3 and
// Wald, "On fast Construction of SAH-based Bounding Volume Hierarchies" (2007),
// collapsed to four children per node by pulling up the largest grandchildren (Wald,
// Benthin and Boulos, "Getting Rid of Packets", 2008) as it is built.
//
// The tree depends on the boxes only, never on the number of threads or their timing:
// - a node's split is a function of its primitives (bins merge exactly, and the
//   partition moves primitives in the order std::partition does);
// - subtrees of at least kTaskMin primitives may be built by other threads into their
//   own node lists, which join() splices into the depth-first order one thread builds.
// So the node array and the primitive order are the same bit for bit whatever the
// number of threads.
#include "raylab/bvh.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <system_error>
#include <thread>

#include "raylab/error.h"

namespace raylab {

namespace {

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
#if defined(__SSE2__)
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
void bin_range(const Ref* refs, std::uint32_t first, std::uint32_t end,
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
int occupied_bins(unsigned occupied, int list[kBins]) {
    int n = 0;
    for (; occupied != 0; occupied &= occupied - 1)
        list[n++] = __builtin_ctz(occupied);
    return n;
}

// The binning of t's centres: kBins bins along every axis with a non-zero centre extent
Binning binning_of(const Task& t, bool active[3]) {
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
float best_split(const Bins& bins, const bool active[3], int& best_axis, int& best_bin,
                 Box4& left, Box4& right) {
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
std::uint32_t partition(Ref* first, Ref* last, GoesLeft goes_left) {
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
void bounds(const Ref* refs, std::uint32_t first, std::uint32_t count, Box4& box,
            Box4& centres) {
    for (std::uint32_t k = first; k < first + count; ++k) {
        box.grow(load(refs[k].lo), load(refs[k].hi));
        centres.grow(refs[k].centre());
    }
}

// The 4-wide nodes of one subtree built by one thread, in depth-first order, except the
// children handed to other threads: each is a Fixup, child slot of node, whose subtree
// belongs before nodes[at] in depth-first order. join() splices them in there
struct Output {
    struct Fixup {
        std::uint32_t node;
        int slot;
        Output* subtree;
        std::uint32_t at;
    };
    std::vector<Bvh::Node> nodes;
    std::vector<Fixup> fixups;
    std::vector<std::uint32_t> index;  // of each node in the finished tree
};

// The work list the build threads share: jobs waiting for a thread, how many jobs are
// still unfinished (waiting or running) and how many threads wait for one
class Scheduler {
  public:
    void push(std::function<void()> job) {
        const std::lock_guard<std::mutex> lock(mutex_);
        waiting_.push_back(std::move(job));
        ++unfinished_;
        wake_.notify_one();
    }
    // Runs jobs, oldest (largest) first, until all are done
    void work() {
        for (;;) {
            std::function<void()> job;
            {
                std::unique_lock<std::mutex> lock(mutex_);
                ++idle_;
                wake_.wait(lock, [&] { return !waiting_.empty() || unfinished_ == 0; });
                --idle_;
                if (waiting_.empty()) return;
                job = std::move(waiting_.front());
                waiting_.pop_front();
            }
            // A failed job (out of memory) is reported after all threads are done
            std::exception_ptr failed;
            try {
                job();
            } catch (...) {
                failed = std::current_exception();
            }
            const std::lock_guard<std::mutex> lock(mutex_);
            if (failed && !error_) error_ = failed;
            if (--unfinished_ == 0) wake_.notify_all();
        }
    }
    std::exception_ptr error() const { return error_; }
    // A hint only: whether a thread waits for work now
    bool has_idle() const { return idle_.load(std::memory_order_relaxed) > 0; }
    // An output for a subtree; its address stays valid until the scheduler goes
    Output* new_output() {
        const std::lock_guard<std::mutex> lock(mutex_);
        outputs_.emplace_back();
        return &outputs_.back();
    }
    std::deque<Output>& outputs() { return outputs_; }

  private:
    std::mutex mutex_;
    std::condition_variable wake_;
    std::deque<std::function<void()>> waiting_;
    std::deque<Output> outputs_;
    std::uint32_t unfinished_ = 0;
    std::atomic<int> idle_{0};
    std::exception_ptr error_;
};

// Runs a and b: b on another thread if one takes it before a is done, else here. Either
// way the results are the same; only the time differs
template <class A, class B>
void fork_join(Scheduler* scheduler, const A& a, const B& b) {
    if (!scheduler || !scheduler->has_idle()) {
        a();
        b();
        return;
    }
    struct State {
        std::atomic<bool> taken{false}, done{false};
    };
    const auto state = std::make_shared<State>();
    scheduler->push([state, &b] {
        if (state->taken.exchange(true)) return;
        struct Done {
            State& s;
            ~Done() { s.done.store(true, std::memory_order_release); }
        } done{*state};
        b();
    });
    // b lives in this frame: once another thread has taken it, wait for it, also when a
    // throws
    const auto wait = [&] {
        while (!state->done.load(std::memory_order_acquire))
            std::this_thread::yield();
    };
    try {
        a();
    } catch (...) {
        if (state->taken.exchange(true)) wait();
        throw;
    }
    if (!state->taken.exchange(true)) return b();
    wait();
}

// Builds the binary SAH tree and collapses it to four children per node as it goes: a
// node's children are decided first, then its interior child of largest area is opened
// (replaced by its two children) until there are four
struct Builder {
    Ref* refs;
    std::uint32_t* prims;
    Scheduler* scheduler;  // null: all on this thread

    // Decides item.t: a leaf, or a split with its primitives partitioned
    void decide(Item& item) const {
        const Task& t = item.t;
        const auto make_leaf = [&] {
            for (std::uint32_t k = t.first; k < t.first + t.count; ++k)
                prims[k] = refs[k].prim();
            item.leaf = Bvh::kLeaf | t.count << Bvh::kCountShift | t.first;
        };
        if (t.count <= 1) return make_leaf();
        // Deep trees (pathological input): halve by index so the depth stays bounded
        if (t.depth >= kMaxSahDepth) return split_by_index(item);
        // Large ranges are binned and classified in two halves, on two threads if one is
        // idle (the bins' boxes and counts, and the flags, are the same either way)
        const bool halves = scheduler && t.count >= kForkMin && scheduler->has_idle();
        const std::uint32_t mid = t.first + t.count / 2, end = t.first + t.count;
        bool active[3];
        const Binning binning = binning_of(t, active);
        Bins bins, upper;
        if (halves) {
            fork_join(
                scheduler, [&] { bin_range(refs, t.first, mid, binning, bins); },
                [&] { bin_range(refs, mid, end, binning, upper); });
            bins.merge(upper);
        } else {
            bin_range(refs, t.first, end, binning, bins);
        }
        int axis = -1, bin = 0;
        Task& left = item.child[0];
        Task& right = item.child[1];
        left = right = Task{};
        const float cost = best_split(bins, active, axis, bin, left.box, right.box);
        // SAH termination: a leaf is cheaper than the split (small leaves only)
        const float leaf_cost = static_cast<float>(t.count);
        const float split_cost =
            kTraversalCost + cost / std::max(t.box.half_area(), 1e-30f);
        if (axis < 0 || (t.count <= Bvh::kMaxLeafSize && leaf_cost <= split_cost)) {
            if (axis >= 0 || t.count <= Bvh::kMaxLeafSize) return make_leaf();
            // All centres coincide: split by index so leaves stay small
            return split_by_index(item);
        }
        split(item, binning, axis, bin, halves);
    }

    // Partitions item's refs: those whose bin along axis is at most bin go left, that
    // is those whose clamped bin coordinate is below bin + 1. With halves, both halves
    // are classified first (on two threads if one is idle), then moved by the flags
    void split(Item& item, const Binning& binning, int axis, int bin, bool halves) const {
        const Task& t = item.t;
        const std::uint32_t mid = t.first + t.count / 2, end = t.first + t.count;
        const F4 bound = splat(static_cast<float>(bin + 1));
        const auto classify = [&](const Ref& r, Box4& l, Box4& rr) {
            const F4 c = r.centre();
            const bool goes_left = less(binning.coordinates(c), bound) >> axis & 1;
            if (goes_left) {
                l.grow(c);
            } else {
                rr.grow(c);
            }
            return goes_left;
        };
        Ref* const first = refs + t.first;
        std::uint32_t left_count = 0;
        Box4 l, r;  // the centres on each side, kept in registers
        if (halves) {
            std::unique_ptr<bool[]> goes_left(new bool[t.count]);
            Box4 upper_l, upper_r;
            const auto flags = [&](std::uint32_t from, std::uint32_t to, Box4& side_l,
                                   Box4& side_r) {
                Box4 ll, rr;
                for (std::uint32_t k = from; k < to; ++k)
                    goes_left[k - t.first] = classify(refs[k], ll, rr);
                side_l = ll;
                side_r = rr;
            };
            fork_join(
                scheduler, [&] { flags(t.first, mid, l, r); },
                [&] { flags(mid, end, upper_l, upper_r); });
            l.grow(upper_l);
            r.grow(upper_r);
            left_count = partition(first, first + t.count,
                                   [&](const Ref* p) { return goes_left[p - first]; });
        } else {
            left_count = partition(first, first + t.count,
                                   [&](const Ref* p) { return classify(*p, l, r); });
        }
        item.child[0].centres = l;
        item.child[1].centres = r;
        set_ranges(item, left_count);
    }

    void split_by_index(Item& item) const {
        const Task& t = item.t;
        const std::uint32_t left_count = t.count / 2;
        item.child[0] = item.child[1] = Task{};
        bounds(refs, t.first, left_count, item.child[0].box, item.child[0].centres);
        bounds(refs, t.first + left_count, t.count - left_count, item.child[1].box,
               item.child[1].centres);
        set_ranges(item, left_count);
    }

    static void set_ranges(Item& item, std::uint32_t left_count) {
        item.child[0].first = item.t.first;
        item.child[0].count = left_count;
        item.child[1].first = item.t.first + left_count;
        item.child[1].count = item.t.count - left_count;
        item.child[0].depth = item.child[1].depth = item.t.depth + 1;
    }

    // Builds the 4-wide subtree of a split item into out; returns its node index there.
    // A large child goes to another thread when there is one
    std::uint32_t build(const Item& item, Output& out) const {
        // Open the interior child of largest area until there are four
        Item kids[4];
        float area[4];  // -1 for a leaf, below every interior child
        const auto take = [&](int k, const Task& t) {
            kids[k].t = t;
            decide(kids[k]);
            area[k] = kids[k].leaf ? -1.0f : t.box.half_area();
        };
        take(0, item.child[0]);
        take(1, item.child[1]);
        int n = 2;
        while (n < 4) {
            int widest = 0;
            for (int k = 1; k < n; ++k) {
                if (area[k] > area[widest]) widest = k;
            }
            if (area[widest] < 0.0f) break;
            const Task opened[2] = {kids[widest].child[0], kids[widest].child[1]};
            take(widest, opened[0]);
            take(n++, opened[1]);
        }
        const std::uint32_t self = static_cast<std::uint32_t>(out.nodes.size());
        out.nodes.emplace_back();
        Bvh::Node& node = out.nodes.back();
        for (int k = 0; k < 4; ++k) {
            // An unused slot: an empty box and a leaf of no primitives
            alignas(16) float lo[4], hi[4];
            store(lo, k < n ? kids[k].t.box.lo : splat(kInfinity));
            store(hi, k < n ? kids[k].t.box.hi : splat(-kInfinity));
            for (int a = 0; a < 3; ++a) {
                node.box[2 * a][k] = lo[a];
                node.box[2 * a + 1][k] = hi[a];
            }
            node.child[k] = k < n ? kids[k].leaf : Bvh::kLeaf;
        }
        // Large interior children but the first go to the work list; the rest are built
        // here, depth first
        bool kept = false;
        size_t fixup[4] = {};
        for (int k = 0; k < n; ++k) {
            if (kids[k].leaf || kids[k].t.count < kTaskMin || !scheduler) continue;
            if (!kept) {
                kept = true;
                continue;
            }
            Output* sub = scheduler->new_output();
            scheduler->push([this, kid = kids[k], sub] { run(kid, *sub); });
            fixup[k] = out.fixups.size() + 1;
            out.fixups.push_back({self, k, sub, 0});
        }
        for (int k = 0; k < n; ++k) {
            if (fixup[k]) {
                out.fixups[fixup[k] - 1].at =
                    static_cast<std::uint32_t>(out.nodes.size());
            } else if (!kids[k].leaf) {
                const std::uint32_t child = build(kids[k], out);
                out.nodes[self].child[k] = child;
            }
        }
        return self;
    }

    // Builds the subtree of a split item into its own output
    void run(const Item& item, Output& out) const {
        out.nodes.reserve(item.t.count / 3 + 1);
        build(item, out);
    }
};

// Gives o's nodes and, spliced in where they belong, its fixups' subtrees their places
// in depth-first order from next on. Fixups at the same place: the deeper node's first
// (it is the later one in depth-first order), then by slot
void place(Output& o, std::uint32_t& next) {
    std::sort(o.fixups.begin(), o.fixups.end(),
              [](const Output::Fixup& a, const Output::Fixup& b) {
                  if (a.at != b.at) return a.at < b.at;
                  return a.node != b.node ? a.node > b.node : a.slot < b.slot;
              });
    o.index.resize(o.nodes.size());
    std::uint32_t k = 0;
    for (const Output::Fixup& f : o.fixups) {
        for (; k < f.at; ++k)
            o.index[k] = next++;
        place(*f.subtree, next);
    }
    for (; k < o.nodes.size(); ++k)
        o.index[k] = next++;
}

// Appends o's nodes and its fixups' subtrees to nodes in depth-first order (the order
// place() gave them), children renumbered
void append(const Output& o, std::vector<Bvh::Node>& nodes) {
    std::uint32_t k = 0;
    const auto copy_to = [&](std::uint32_t end) {
        for (; k < end; ++k) {
            Bvh::Node n = o.nodes[k];
            for (std::uint32_t& c : n.child) {
                if (!(c & Bvh::kLeaf)) c = o.index[c];
            }
            nodes.push_back(n);
        }
    };
    for (const Output::Fixup& f : o.fixups) {
        copy_to(f.at);
        append(*f.subtree, nodes);
    }
    copy_to(static_cast<std::uint32_t>(o.nodes.size()));
    for (const Output::Fixup& f : o.fixups)
        nodes[o.index[f.node]].child[f.slot] = f.subtree->index[0];
}

// The nodes of all outputs in the depth-first order of one thread's build
std::vector<Bvh::Node> join(Output& root) {
    std::uint32_t total = 0;
    place(root, total);
    std::vector<Bvh::Node> nodes;
    nodes.reserve(total);
    append(root, nodes);
    return nodes;
}

}  // namespace

void Bvh::build(const std::vector<Aabb>& boxes, unsigned threads) {
    nodes_.clear();
    bounds_ = Aabb{};
    root_ = 0;
    prims_.resize(boxes.size());
    if (boxes.empty()) return;
    if (boxes.size() > kFirstMask)
        throw Error("too many primitives for the BVH: " + std::to_string(boxes.size()) +
                    " (at most " + std::to_string(kFirstMask) + ")");
    const std::uint32_t count = static_cast<std::uint32_t>(boxes.size());
    if (threads == 0) threads = std::thread::hardware_concurrency();
    // At least kParallelMin / 2 primitives per thread: starting one costs tens of µs
    threads = std::max(1u, std::min(threads, count / (kParallelMin / 2)));
    const bool parallel = count >= kParallelMin && threads > 1;
    Scheduler scheduler;
    Builder builder{nullptr, prims_.data(), parallel ? &scheduler : nullptr};
    // Not written before the build writes it
    const std::unique_ptr<Ref[]> refs(new Ref[count]);
    builder.refs = refs.get();
    Output* out = scheduler.new_output();
    Item root;
    root.t.count = count;
    const auto all = [&] {
        // The refs and their bounds, in two halves
        Task upper;
        const auto convert = [&](std::uint32_t from, std::uint32_t to, Task& t) {
            for (std::uint32_t k = from; k < to; ++k) {
                Ref& r = refs[k];
                const Aabb& b = boxes[k];
                r = Ref{{b.lo.x, b.lo.y, b.lo.z, 0.0f}, {b.hi.x, b.hi.y, b.hi.z, 0.0f}};
                const std::uint32_t tagged = k | kPrimTag;
                std::memcpy(&r.lo[3], &tagged, sizeof tagged);
                t.box.grow(load(r.lo), load(r.hi));
                t.centres.grow(r.centre());
            }
        };
        fork_join(
            builder.scheduler, [&] { convert(0, count / 2, root.t); },
            [&] { convert(count / 2, count, upper); });
        root.t.box.grow(upper.box);
        root.t.centres.grow(upper.centres);
        builder.decide(root);
        if (!root.leaf) builder.run(root, *out);
    };
    if (!parallel) {
        all();
    } else {
        scheduler.push(all);
        std::vector<std::thread> helpers;
        try {
            for (unsigned k = 1; k < threads; ++k)
                helpers.emplace_back([&] { scheduler.work(); });
        } catch (const std::system_error&) {
            // No more threads to be had: the ones there are finish the work
        }
        scheduler.work();
        for (std::thread& h : helpers)
            h.join();
        if (scheduler.error()) {
            prims_.clear();
            std::rethrow_exception(scheduler.error());
        }
    }
    alignas(16) float lo[4], hi[4];
    store(lo, root.t.box.lo);
    store(hi, root.t.box.hi);
    bounds_.lo = Vec3(lo[0], lo[1], lo[2]);
    bounds_.hi = Vec3(hi[0], hi[1], hi[2]);
    if (root.leaf) {
        root_ = root.leaf;
    } else if (scheduler.outputs().size() == 1) {
        nodes_ = std::move(out->nodes);
        nodes_.shrink_to_fit();
    } else {
        nodes_ = join(*out);
    }
    // The root's output comes first, and the root is its first node
}

int Bvh::depth() const {
    if (nodes_.empty()) return 0;
    // Depth-first, the deepest level seen so far
    std::vector<std::pair<std::uint32_t, int>> stack{{root_, 1}};
    int deepest = 0;
    while (!stack.empty()) {
        const auto [node, level] = stack.back();
        stack.pop_back();
        deepest = std::max(deepest, level);
        for (const std::uint32_t child : nodes_[node].child) {
            if (!(child & kLeaf)) stack.push_back({child, level + 1});
        }
    }
    return deepest;
}

}  // namespace raylab
