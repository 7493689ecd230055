// The reference's geometry engine (raylab/engine.h): the scene's closest-hit and any-hit
// queries with the reference's intersection tests inlined into the BVH traversal.
//
// Not a module: no student writes it, and it ships only compiled, inside the reference
// library, because it repeats the reference's numerics. Each test (engine_kernels.h)
// computes only t, with exactly the operations of its module (solutions/03_plane.cpp,
// 04_sphere.cpp, 05_triangle.cpp; -ffp-contract=off keeps them unfused), so it accepts
// exactly the primitives the module accepts, and builds the nearest one's Hit with the
// module's expressions. tests/framework/test_engine.cpp renders scenes both ways and
// compares, and tests/stress runs on both paths. The tests are repeated in
// engine_kernels.h, which the engine's files share, not shared with the modules: each
// module file of solutions/ must stay self-contained, since the class tests grade copies
// of them as hand-ins (tests/class), and a hand-in has no header beside it. The packet
// query is in engine_packet.cpp.
#include "engine_kernels.h"

namespace raylab::reference {

namespace engine_kernels {

// The nearest primitive and its Hit as its module returns it: t, position, normal, uv
// (material and shading normal are the scene's to fill)
void closest_hit(const Scene& scene, const Ray& r, TraceCounters& counters, Hit& hit,
                 PrimRef& best) {
    best = PrimRef{};
    float best_t = r.tmax;
    for (size_t k = 0; k < scene.planes.size(); ++k) {
        ++counters.intersection_tests;
        const float t = plane_t(r, scene.planes[k].plane, best_t);
        if (!std::isnan(t)) {
            best_t = t;
            best = {PrimRef::Kind::plane, static_cast<std::uint32_t>(k)};
        }
    }
    const WoopRay q(r);
    Ray ray = r;
    ray.tmax = best_t;
    const Primitives prims(scene);
    std::uint32_t best_prim = 0;
    bool in_bvh = false;
    // A triangle's test writes its extra only when it accepts, so straight into
    // best_extra: a copy from a local just written stalled the load on the two stores it
    // spans (store-to-load forwarding fails; 1 % of a Cornell box camera ray)
    TriangleExtra best_extra;
    // The leaf visit inlined into the walk (GCC left it a call: its prologue and
    // epilogue per leaf were 2 % of a Cornell box camera ray; the any-hit walk showed no
    // gain from the same)
    scene.bvh().traverse(
        ray,
        [&](std::uint32_t first, std::uint32_t count, float& tmax)
            __attribute__((always_inline)) {
                counters.intersection_tests += count;
                for (std::uint32_t k = first; k < first + count; ++k) {
                    const float t = prims.t(r, q, prims.order[k], tmax, best_extra);
                    if (!std::isnan(t)) {
                        tmax = best_t = t;
                        best_prim = prims.order[k];
                        in_bvh = true;
                    }
                }
                return false;
            },
        counters.bvh_nodes);
    if (best.kind == PrimRef::Kind::none && !in_bvh) return;
    finish_hit(scene, prims, r, best_t, in_bvh, best_prim, best_extra, hit, best);
}

}  // namespace engine_kernels

namespace {

using namespace engine_kernels;

bool any_hit(const Scene& scene, const Ray& r, TraceCounters& counters) {
    for (const ScenePlane& p : scene.planes) {
        ++counters.intersection_tests;
        if (!std::isnan(plane_t(r, p.plane, r.tmax))) return true;
    }
    const WoopRay q(r);
    const Primitives prims(scene);
    bool hit = false;
    scene.bvh().traverse_any(
        r,
        [&](std::uint32_t first, std::uint32_t count, float&) {
            for (std::uint32_t k = first; k < first + count && !hit; ++k) {
                ++counters.intersection_tests;
                TriangleExtra extra;
                const float t = prims.t(r, q, prims.order[k], r.tmax, extra);
                hit = !std::isnan(t);
            }
            return hit;
        },
        counters.bvh_nodes);
    return hit;
}

}  // namespace

const GeometryEngine* geometry_engine() {
    static const GeometryEngine engine{&intersect_plane,
                                       &intersect_sphere,
                                       &intersect_triangle,
                                       &engine_kernels::closest_hit,
                                       &any_hit,
                                       &engine_kernels::closest_hit_packet};
    return &engine;
}

}  // namespace raylab::reference
