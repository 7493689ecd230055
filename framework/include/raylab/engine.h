// raylab/engine.h: the interface of a geometry engine, a faster way to run the
// reference's intersection tests inside the scene's queries.
//
// Scene::closest_hit and Scene::any_hit normally call the module table once per
// primitive. When the table selects the reference for planes, spheres and triangles,
// they hand the whole query to the engine instead: the same BVH traversal with the
// reference's tests inlined, computing only t (and, for an accepted triangle, its
// normal and uv), and the Hit built once, for the nearest primitive. The engine
// (engine/, its README says why it exists) is compiled into the reference library,
// which ships compiled only, so its copy of the reference's numerics is not readable
// source in a student release; ModuleTable::make (the glue, linked with the reference)
// puts it in the table. A build without it (RAYLAB_WITH_ENGINE=OFF) gives the same
// images from the module path. With a student's module in the table the scene calls the
// modules, but walks the BVH with the engine's walk (module_walk) when there is one.
//
// The engine keeps what it reads besides the scene's own data (flags, normals, copies in
// the BVH's order) in an EngineData of its own, which Scene::commit() asks the
// registered engine to prepare (GeometryEngine::prepare) and the scene holds for it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>

#include "raylab/contract.h"

namespace raylab {

class Bvh;
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

/// What an engine prepares from a committed scene and reads in its queries: its own
/// type, opaque to the scene, which keeps it until the next commit() (copies of the
/// scene share it: it holds no pointer into the scene).
struct EngineData {
    virtual ~EngineData() = default;
    /// Bytes it holds (Scene::acceleration_bytes counts them).
    virtual size_t bytes() const = 0;
};

struct GeometryEngine {
    /// The module functions whose results the engine reproduces: the scene uses the
    /// engine only when the table holds exactly these.
    decltype(&student::intersect_plane) intersect_plane;
    decltype(&student::intersect_sphere) intersect_sphere;
    decltype(&student::intersect_triangle) intersect_triangle;
    /// The engine's data for scene, called by scene.commit() once it has validated the
    /// scene, built its BVH and put its triangles in the BVH's slot order; null: none
    /// (the scene's queries then call the modules). The queries below find it in
    /// scene.engine_data().
    std::shared_ptr<const EngineData> (*prepare)(const Scene& scene);
    /// prim: the primitive whose hit the module path would return, counting the same
    /// tests (kind none when there is none); when there is one, hit holds what its
    /// module returns (t, position, n, uv), or with PrimRef::refined the refined position
    /// instead of the module's. (An out-parameter, not a return value: GCC assembles a
    /// returned PrimRef from its fields' stores on the stack and loads it back whole,
    /// which the store buffer cannot forward: docs/decisions/0001.)
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
    /// The walk of the module path, whose queries call the table's functions (a
    /// student's): Bvh::traverse (sorted) or Bvh::traverse_any, the same leaves in the
    /// same order and the same count of nodes, with the engine's vector node tests.
    /// visit(context, first, count, tmax) is the leaf visit of Bvh::traverse; tmax is
    /// whatever the visit leaves in it, as in Bvh::traverse (a module may return any t).
    using LeafVisit = bool (*)(void* context, std::uint32_t first, std::uint32_t count,
                               float& tmax);
    void (*module_walk)(const Bvh& bvh, const Ray& r, bool sorted, LeafVisit visit,
                        void* context, std::uint64_t& nodes_visited);
};

/// Makes engine the one whose prepare() every later Scene::commit() calls (null: none).
/// The reference library registers its engine before main() when it has one and the
/// program uses it (reference::geometry_engine(), which links the engine's object file).
void register_geometry_engine(const GeometryEngine* engine);

namespace reference {
/// The reference's engine, or null in a build without one; defined in the reference
/// library.
const GeometryEngine* geometry_engine();
}  // namespace reference

/// Arrays from this size on are backed by huge pages (back_with_huge_pages).
inline constexpr size_t kHugePagesFrom = size_t{4} << 20;

/// Asks the kernel to back the huge pages (2 MiB on x86-64) lying wholly inside
/// [data, data + bytes) with huge pages, when bytes >= kHugePagesFrom: on Linux,
/// madvise(MADV_HUGEPAGE) for the range, then MADV_COLLAPSE (kernel 6.1 on; retried on
/// EAGAIN) to do it at once instead of whenever khugepaged comes by. The engine asks it
/// for the BVH's nodes and primitive order and the scene's triangles when it prepares a
/// scene: a random ray through a million-triangle mesh loads nodes and triangles from
/// tens of megabytes, and with 4 KiB pages nearly every one of those loads also missed
/// the TLB. Only a hint: the data is unchanged, and a kernel that declines (built
/// without transparent huge pages, older than 6.1, short of free memory) leaves the
/// pages as they are. The collapse is synchronous: on a machine short of free huge
/// pages it may compact memory first, and commit() waits for it. MADV_COLLAPSE does not
/// depend on the system's transparent huge page mode. Returns true when the kernel
/// collapsed the range now. Defined with the engine (false in a build without one).
bool back_with_huge_pages(const void* data, size_t bytes);

}  // namespace raylab
