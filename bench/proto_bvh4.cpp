// Collapsing the pair BVH into a 4-wide BVH (bench/proto_bvh4.h).
#include "proto_bvh4.h"

#if RAYLAB_BENCH_HAVE_BVH4

#include <algorithm>

namespace raylab::bench {

namespace {

using PairNode = PairBvh::Node;

float half_area(const PairNode& n) {
    const Vec3 e = glm::max(n.hi - n.lo, Vec3(0.0f));
    return e.x * e.y + e.y * e.z + e.z * e.x;
}

struct Collapser {
    const PairBvh& pair;
    std::vector<Bvh4::Node>& nodes;

    // Writes the 4-wide node for pair node `from` into nodes[index]
    void collapse(const PairNode& from, std::uint32_t index) {
        std::vector<const PairNode*> kids = {&pair.pair(from.first_or_pair).child[0],
                                             &pair.pair(from.first_or_pair).child[1]};
        // Open the interior child of largest area until there are four
        while (kids.size() < 4) {
            int best = -1;
            for (int k = 0; k < static_cast<int>(kids.size()); ++k) {
                if (kids[k]->count == 0 &&
                    (best < 0 || half_area(*kids[k]) > half_area(*kids[best])))
                    best = k;
            }
            if (best < 0) break;
            const PairBvh::Pair& p = pair.pair(kids[best]->first_or_pair);
            kids[best] = &p.child[0];
            kids.push_back(&p.child[1]);
        }
        Bvh4::Node node{};
        for (int k = 0; k < 4; ++k) {
            node.lo_x[k] = node.lo_y[k] = node.lo_z[k] = 0.0f;
            node.hi_x[k] = node.hi_y[k] = node.hi_z[k] = 0.0f;
        }
        node.valid = (1u << kids.size()) - 1u;
        nodes[index] = node;
        for (size_t k = 0; k < kids.size(); ++k) {
            const PairNode& c = *kids[k];
            Bvh4::Node& n = nodes[index];
            n.lo_x[k] = c.lo.x, n.lo_y[k] = c.lo.y, n.lo_z[k] = c.lo.z;
            n.hi_x[k] = c.hi.x, n.hi_y[k] = c.hi.y, n.hi_z[k] = c.hi.z;
            n.count[k] = static_cast<std::uint16_t>(c.count);
            n.child[k] = c.first_or_pair;
            if (c.count == 0) {
                const std::uint32_t child = static_cast<std::uint32_t>(nodes.size());
                nodes.emplace_back();
                nodes[index].child[k] = child;
                collapse(c, child);
            }
        }
    }
};

}  // namespace

void Bvh4::build(const PairBvh& pair) {
    nodes_.clear();
    prims_ = pair.prims();
    if (prims_.empty()) return;
    nodes_.emplace_back();
    const PairNode& root = pair.root();
    if (root.count > 0) {  // a single leaf: one child
        Node n{};
        n.lo_x[0] = root.lo.x, n.lo_y[0] = root.lo.y, n.lo_z[0] = root.lo.z;
        n.hi_x[0] = root.hi.x, n.hi_y[0] = root.hi.y, n.hi_z[0] = root.hi.z;
        n.child[0] = root.first_or_pair;
        n.count[0] = static_cast<std::uint16_t>(root.count);
        n.valid = 1;
        nodes_[0] = n;
        return;
    }
    Collapser{pair, nodes_}.collapse(root, 0);
}

}  // namespace raylab::bench

#endif  // RAYLAB_BENCH_HAVE_BVH4
