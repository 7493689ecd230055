// The reference's geometry engine (raylab/engine.h): the scene's closest-hit and any-hit
// queries with the reference's intersection tests inlined into the BVH traversal.
//
// Not a module: no student writes it, and it ships only compiled, inside the reference
// library, because it repeats the reference's numerics. Each test (engine_kernels.h)
// computes only t, with exactly the operations of its module (solutions/03_plane.cpp,
// 04_sphere.cpp, 05_triangle.cpp; -ffp-contract=off keeps them unfused), so it accepts
// exactly the primitives the module accepts, and builds the nearest one's Hit with the
// module's expressions. engine/tests/test_engine.cpp renders scenes both ways and
// compares, and tests/stress runs on both paths. The tests are repeated in
// engine_kernels.h, which the engine's files share, not shared with the modules: each
// module file of solutions/ must stay self-contained, since the class tests grade copies
// of them as hand-ins (tests/class), and a hand-in has no header beside it. The packet
// query is in engine_packet.cpp.
#include "engine_kernels.h"
#include "engine_simd.h"

namespace raylab::reference {

namespace engine_kernels {

namespace {

// The single-ray queries read the BVH slots' primitives from a Source: SlotPrimitives
// (the scene's copy in slot order, in small scenes), SlotOrderTriangles (a larger scene
// without spheres, whose triangles are in slot order) or Primitives (through the
// primitive order). Avx: the walk tests a node's eight boxes in one AVX register (only in
// the AVX2 version, engine_simd.h)

// The nearest primitive and its Hit as its module returns it: t, position, normal, uv
// (material and shading normal are the scene's to fill)
template <bool Avx, class Source>
RAYLAB_INLINE void closest_hit_from(const Scene& scene, const Source& source,
                                    const Ray& r, TraceCounters& counters, Hit& hit,
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
    const WoopRay q(r, WoopRay::Unpredictable{});
    Ray ray = r;
    ray.tmax = best_t;
    std::uint32_t best_slot = 0;
    bool in_bvh = false;
    // A triangle's test writes its extra only when it accepts, so straight into
    // best_extra: a copy from a local just written stalled the load on the two stores it
    // spans (store-to-load forwarding fails; docs/decisions/0001)
    TriangleExtra best_extra;
    // The leaf visit inlined into the walk (GCC left it a call, with a prologue and an
    // epilogue per leaf; docs/decisions/0001)
    const auto visit = [&](std::uint32_t first, std::uint32_t count, float& tmax)
        __attribute__((always_inline)) {
        counters.intersection_tests += count;
        for (std::uint32_t k = first; k < first + count; ++k) {
            const float t = source.t(r, q, k, tmax, best_extra);
            if (!std::isnan(t)) {
                tmax = best_t = t;
                best_slot = k;
                in_bvh = true;
            }
        }
        return false;
    };
    walk<true, Avx>(scene.bvh(), ray, visit, counters.bvh_nodes);
    if (best.kind == PrimRef::Kind::none && !in_bvh) return;
    finish_hit(scene, Primitives(scene), r, best_t, in_bvh,
               in_bvh ? source.prim(best_slot) : 0, best_extra, hit, best);
}

template <bool Avx>
RAYLAB_INLINE void closest_hit_query(const Scene& scene, const Ray& r,
                                     TraceCounters& counters, Hit& hit, PrimRef& best) {
    if (const SceneData::SlotPrimitive* slots = scene_data(scene).slot_primitives())
        closest_hit_from<Avx>(scene, SlotPrimitives{slots}, r, counters, hit, best);
    else if (scene.spheres.empty())
        closest_hit_from<Avx>(scene, SlotOrderTriangles(scene), r, counters, hit, best);
    else
        closest_hit_from<Avx>(scene, Primitives(scene), r, counters, hit, best);
}

// True when anything lies on r in [tmin, tmax]: the module path's tests in its order
// (Scene::any_hit), the hint's slot first
template <bool Avx, class Source>
RAYLAB_INLINE bool any_hit_from(const Scene& scene, const Source& source, const Ray& r,
                                TraceCounters& counters, AnyHitHint* hint) {
    const WoopRay q(r);
    // The test of slot k
    const auto blocks = [&](std::uint32_t k) __attribute__((always_inline)) {
        ++counters.intersection_tests;
        TriangleExtra extra;
        return !std::isnan(source.t(r, q, k, r.tmax, extra));
    };
    if (hint && hint->slot < scene.bvh().prims().size() && blocks(hint->slot))
        return true;
    for (const ScenePlane& p : scene.planes) {
        ++counters.intersection_tests;
        if (!std::isnan(plane_t(r, p.plane, r.tmax))) return true;
    }
    std::uint32_t stopped = AnyHitHint::kNone;  // the slot that blocks r, once found
    const auto visit = [&](std::uint32_t first, std::uint32_t count, float&) {
        for (std::uint32_t k = first; k < first + count; ++k) {
            if (blocks(k)) {
                stopped = k;
                return true;
            }
        }
        return false;
    };
    walk<false, Avx>(scene.bvh(), r, visit, counters.bvh_nodes);
    if (hint) hint->slot = stopped;
    return stopped != AnyHitHint::kNone;
}

template <bool Avx>
RAYLAB_INLINE bool any_hit_query(const Scene& scene, const Ray& r,
                                 TraceCounters& counters, AnyHitHint* hint) {
    if (const SceneData::SlotPrimitive* slots = scene_data(scene).slot_primitives())
        return any_hit_from<Avx>(scene, SlotPrimitives{slots}, r, counters, hint);
    if (scene.spheres.empty())
        return any_hit_from<Avx>(scene, SlotOrderTriangles(scene), r, counters, hint);
    return any_hit_from<Avx>(scene, Primitives(scene), r, counters, hint);
}

// The module path's walk (GeometryEngine::module_walk): the visit is the scene's, which
// calls the table's functions, so only the walk is the engine's
template <bool Avx>
RAYLAB_INLINE void module_walk_query(const Bvh& bvh, const Ray& r, bool sorted,
                                     GeometryEngine::LeafVisit call, void* context,
                                     std::uint64_t& nodes_visited) {
    const auto visit = [&](std::uint32_t first, std::uint32_t count, float& tmax) {
        return call(context, first, count, tmax);
    };
    if (sorted)
        walk<true, Avx>(bvh, r, visit, nodes_visited);
    else
        walk<false, Avx>(bvh, r, visit, nodes_visited);
}

// The queries compiled for the baseline and, on x86-64, for AVX2 and AVX-512
// (engine_simd.h)
RAYLAB_ENGINE_VERSIONS(closest_hit_query, void, closest_hit_versions,
                       (const Scene& scene, const Ray& r, TraceCounters& counters,
                        Hit& hit, PrimRef& best),
                       (scene, r, counters, hit, best))
RAYLAB_ENGINE_VERSIONS(any_hit_query, bool, any_hit_versions,
                       (const Scene& scene, const Ray& r, TraceCounters& counters,
                        AnyHitHint* hint),
                       (scene, r, counters, hint))
RAYLAB_ENGINE_VERSIONS(module_walk_query, void, module_walk_versions,
                       (const Bvh& bvh, const Ray& r, bool sorted,
                        GeometryEngine::LeafVisit call, void* context,
                        std::uint64_t& nodes_visited),
                       (bvh, r, sorted, call, context, nodes_visited))

}  // namespace

void closest_hit(const Scene& scene, const Ray& r, TraceCounters& counters, Hit& hit,
                 PrimRef& best) {
    static const auto chosen = closest_hit_versions_chosen();
    chosen(scene, r, counters, hit, best);
}

}  // namespace engine_kernels

const GeometryEngine* geometry_engine() {
    // The queries' versions chosen once, here (engine_simd.h)
    static const GeometryEngine engine{&intersect_plane,
                                       &intersect_sphere,
                                       &intersect_triangle,
                                       &engine_kernels::prepare_scene,
                                       engine_kernels::closest_hit_versions_chosen(),
                                       engine_kernels::any_hit_versions_chosen(),
                                       engine_kernels::chosen_packet_query(),
                                       engine_kernels::engine_versions(),
                                       engine_kernels::module_walk_versions_chosen()};
    return &engine;
}

namespace {
// The scenes committed from now on prepare the engine's data (raylab/engine.h): the
// engine registers itself before main() in every program that links it
[[maybe_unused]] const bool registered = [] {
    register_geometry_engine(geometry_engine());
    return true;
}();
}  // namespace

}  // namespace raylab::reference
