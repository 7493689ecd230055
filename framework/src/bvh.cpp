// BVH construction (raylab/bvh.h): a binary tree by binned SAH, after pbrt-v4 §7.3 and
// Wald, "On fast Construction of SAH-based Bounding Volume Hierarchies" (2007),
// collapsed to eight children per node by pulling up the largest grandchildren (Wald,
// Benthin and Boulos, "Getting Rid of Packets", 2008) as it is built.
//
// The tree depends on the boxes only, never on the number of threads or their timing:
// - a node's split is a function of its primitives (bins merge exactly, and the
//   partition moves primitives in the order std::partition does);
// - a leaf lists its primitives in increasing order, as does a range split by index
//   (so a build of the same boxes listed in slot order gives the same slots);
// - subtrees of at least kTaskMin primitives may be built by other threads into their
//   own node lists, which join() splices into the depth-first order one thread builds.
// So the node array and the primitive order are the same bit for bit whatever the
// number of threads. The build's data, its binning and its threads are in
// bvh_build_data.h, bvh_binning.h and bvh_scheduler.h.
#include "raylab/bvh.h"

#include <algorithm>
#include <exception>
#include <system_error>
#include <thread>

#include "bvh_binning.h"
#include "bvh_build_data.h"
#include "bvh_scheduler.h"
#include "raylab/error.h"

namespace raylab {

namespace {

using namespace bvh_build;

// Builds the binary SAH tree and collapses it to Bvh::kWidth (eight) children per node as
// it goes: a node's children are decided first, then its interior child of largest area
// is opened (replaced by its two children) until there are eight, and small interior
// children left over become leaves
struct Builder {
    Ref* refs;
    std::uint32_t* prims;
    Scheduler* scheduler;  // null: all on this thread

    // Decides item.t: a leaf, or a split with its primitives partitioned
    void decide(Item& item) const {
        const Task& t = item.t;
        const auto make_leaf = [&] { leaf(item); };
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

    // Makes item a leaf of all its primitives, in increasing order
    void leaf(Item& item) const {
        const Task& t = item.t;
        order_by_prim(t.first, t.count);
        for (std::uint32_t k = t.first; k < t.first + t.count; ++k)
            prims[k] = refs[k].prim();
        item.leaf = Bvh::kLeaf | t.count << Bvh::kCountShift | t.first;
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
        order_by_prim(t.first, t.count);
        const std::uint32_t left_count = t.count / 2;
        item.child[0] = item.child[1] = Task{};
        bounds(refs, t.first, left_count, item.child[0].box, item.child[0].centres);
        bounds(refs, t.first + left_count, t.count - left_count, item.child[1].box,
               item.child[1].centres);
        set_ranges(item, left_count);
    }

    // A leaf's primitives, and a range split by index, in increasing order, not in the
    // order the partitions left them (which depends on the order the boxes came in):
    // Scene::commit() renames its triangles by slot, and a build of the same boxes in
    // that order must give the same slots (commit() twice moves nothing)
    void order_by_prim(std::uint32_t first, std::uint32_t count) const {
        const auto by_prim = [](const Ref& a, const Ref& b) {
            return a.prim() < b.prim();
        };
        Ref *begin = refs + first, *end = begin + count;
        if (!std::is_sorted(begin, end, by_prim)) std::sort(begin, end, by_prim);
    }

    static void set_ranges(Item& item, std::uint32_t left_count) {
        item.child[0].first = item.t.first;
        item.child[0].count = left_count;
        item.child[1].first = item.t.first + left_count;
        item.child[1].count = item.t.count - left_count;
        item.child[0].depth = item.child[1].depth = item.t.depth + 1;
    }

    // Builds the 8-wide subtree of a split item into out; returns its node index there.
    // A large child goes to another thread when there is one
    std::uint32_t build(const Item& item, Output& out) const {
        // Open the interior child of largest area until there are eight
        Item kids[Bvh::kWidth];
        float area[Bvh::kWidth];  // -1 for a leaf, below every interior child
        const auto take = [&](int k, const Task& t) {
            kids[k].t = t;
            decide(kids[k]);
            area[k] = kids[k].leaf ? -1.0f : t.box.half_area();
        };
        take(0, item.child[0]);
        take(1, item.child[1]);
        int n = 2;
        while (n < Bvh::kWidth) {
            int widest = 0;
            for (int k = 1; k < n; ++k) {
                if (area[k] > area[widest]) widest = k;
            }
            if (area[widest] < 0.0f) break;
            const Task opened[2] = {kids[widest].child[0], kids[widest].child[1]};
            take(widest, opened[0]);
            take(n++, opened[1]);
        }
        // An interior child that no slot is left to open and that holds at most
        // kMaxLeafSize primitives becomes one leaf instead of a node of two or three
        // leaves: before, half of all nodes held two children (224 bytes for two boxes).
        // Measured on the 1M-triangle displaced sphere: nodes 192,332 -> 99,948 (43 ->
        // 22 bytes per triangle), and on raylab-bench's 400k mesh random rays 0.46x ->
        // 0.51x Embree's speed; allowing leaves of six this way saved more bytes but
        // lost speed (more tests per ray)
        for (int k = 0; k < n; ++k) {
            if (!kids[k].leaf && kids[k].t.count <= Bvh::kMaxLeafSize) leaf(kids[k]);
        }
        const std::uint32_t self = static_cast<std::uint32_t>(out.nodes.size());
        out.nodes.emplace_back();
        Bvh::Node& node = out.nodes.back();
        for (int k = 0; k < Bvh::kWidth; ++k) {
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
        size_t fixup[Bvh::kWidth] = {};
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
