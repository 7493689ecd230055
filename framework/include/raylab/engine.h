// raylab/engine.h: the interface of a geometry engine, a faster way to run the
// reference's intersection tests inside the scene's queries.
//
// Scene::closest_hit and Scene::any_hit normally call the module table once per
// primitive. When the table selects the reference for planes, spheres and triangles,
// they hand the whole query to the engine instead: the same BVH traversal with the
// reference's tests inlined, computing only t (and, for an accepted triangle, its
// normal and uv), and the Hit built once, for the nearest primitive. The engine lives in
// the reference library (solutions/engine_geometry.cpp), which ships compiled only, so
// its copy of the reference's numerics is not readable source in a student release;
// ModuleTable::make (the glue, linked with the reference) puts it in the table.
#pragma once

#include <cstdint>

#include "raylab/contract.h"

namespace raylab {

class Scene;
struct TraceCounters;
struct AnyHitHint;

/// The primitive a query found nearest.
struct PrimRef {
    enum class Kind : std::uint8_t { none, plane, sphere, triangle };
    Kind kind = Kind::none;
    std::uint32_t index = 0;  ///< into Scene::planes, spheres or triangles
    /// The engine set the hit's position to the refined point (raylab/refine.h) itself.
    bool refined = false;
};

struct GeometryEngine {
    /// The module functions whose results the engine reproduces: the scene uses the
    /// engine only when the table holds exactly these.
    decltype(&student::intersect_plane) intersect_plane;
    decltype(&student::intersect_sphere) intersect_sphere;
    decltype(&student::intersect_triangle) intersect_triangle;
    /// prim: the primitive whose hit the module path would return, counting the same
    /// tests (kind none when there is none); when there is one, hit holds what its
    /// module returns (t, position, n, uv), or with PrimRef::refined the refined position
    /// instead of the module's. (An out-parameter, not a return value: GCC assembles a
    /// returned PrimRef from its fields' stores on the stack and loads it back whole,
    /// which the store buffer cannot forward: 4 % of a Cornell box camera ray.)
    void (*closest_hit)(const Scene& scene, const Ray& r, TraceCounters& counters,
                        Hit& hit, PrimRef& prim);
    /// What the module path's any-hit returns, counting the same tests, and leaving the
    /// hint (null: none) as it leaves it (Scene::any_hit, AnyHitHint).
    bool (*any_hit)(const Scene& scene, const Ray& r, TraceCounters& counters,
                    AnyHitHint* hint);
    /// closest_hit for each of n <= kPacketSize rays at once (hits[k], prims[k] for
    /// rays[k], bit for bit): a packet of rays from one origin, as a block of a tile's
    /// camera rays, shares one walk of the BVH (a frustum test per node) and runs each
    /// triangle's test on four rays at a time. Rays that cannot travel together (other
    /// origins, a direction component of either sign or zero, another dominant axis, a
    /// tmin below 0 or a NaN range) and rays whose nearest hit is a tie between
    /// primitives (the order of the visit decides it) take closest_hit. Counters count
    /// the tests and nodes it runs.
    void (*closest_hit_packet)(const Scene& scene, const Ray* rays, int n,
                               TraceCounters& counters, Hit* hits, PrimRef* prims);
    static constexpr int kPacketSize = 16;
    /// Which compiled versions of the queries run: "avx512", "avx2" or "baseline"
    /// (x86-64, chosen once at start: the widest the processor has, AVX-512 meaning
    /// x86-64-v4's subsets; the environment variable RAYLAB_NO_AVX512 rules out
    /// "avx512", RAYLAB_NO_AVX2 both), or "native" (a build whose own target decides, as
    /// with -march=native, or -DRAYLAB_NO_SIMD).
    const char* versions;
};

namespace reference {
/// The reference's engine; defined in the reference library.
const GeometryEngine* geometry_engine();
}  // namespace reference

}  // namespace raylab
