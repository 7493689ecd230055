// raylab/scene.h: what a scene holds, and its closest-hit and any-hit queries.
//
// Planes are unbounded and tested one by one; spheres and triangles live in one BVH.
// Every intersection goes through the ModuleTable (the BVH walked by the engine's vector
// node tests when the build has it), and the counters record a query's work. When the
// table holds the reference's three intersect_* functions, the query runs in the
// reference's engine instead (raylab/engine.h): same hits, same counts, fewer calls.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "raylab/bvh.h"
#include "raylab/contract.h"
#include "raylab/engine.h"
#include "raylab/modules.h"

namespace raylab {

/// A Lambertian surface with optional emission.
struct Material {
    std::string name;
    Vec3 rho{0.75f};  ///< diffuse reflectance rho per channel, in [0, 1]
    Vec3 Le{0.0f};    ///< emitted radiance Le
};

struct ScenePlane {
    Plane plane;
    int material = 0;
};

struct SceneSphere {
    Sphere sphere;
    int material = 0;
};

/// A triangle: its vertices and material (40 bytes). Vertex normals, for smooth shading,
/// are in Scene::normals, so that a flat-shaded mesh does not pay for them.
struct SceneTriangle {
    Vec3 v0{0.0f}, v1{0.0f}, v2{0.0f};
    int material = 0;
};

/// A triangle's vertex normals: its shading normal is interpolated from them with the
/// hit's uv. All three zero: flat shading (the geometric normal).
struct VertexNormals {
    Vec3 n0{0.0f}, n1{0.0f}, n2{0.0f};
};

/// Where the camera is and what it sees: the DTU camera's extrinsic parameters and FOV.
struct View {
    Vec3 eye{0.0f, 0.0f, 3.0f};  ///< eye point e
    Vec3 lookat{0.0f};           ///< look-at point p
    Vec3 up{0.0f, 1.0f, 0.0f};   ///< up hint u
    float fov = 53.130102f;      ///< vertical field of view [degrees]; 53.13 is d = 1
};

/// The same eye, look-at point, up hint and field of view, bit for bit.
inline bool operator==(const View& a, const View& b) {
    return a.eye == b.eye && a.lookat == b.lookat && a.up == b.up && a.fov == b.fov;
}
inline bool operator!=(const View& a, const View& b) {
    return !(a == b);
}

/// Checks a view: finite values, eye != lookat, up not zero and not parallel to the view
/// direction, fov in (0, 180). Throws raylab::Error naming the problem.
void validate(const View& view);

/// A shadow cache for Scene::any_hit (Haines and Greenberg's "last object hit", 1986):
/// the BVH slot whose primitive stopped the last query that found something. The shadow
/// rays of neighbouring pixels towards one light are often stopped by the same
/// primitive, so a query given a hint tests that primitive first and walks the BVH only
/// when it does not block the ray. The answer is the same either way (any primitive in
/// [tmin, tmax] blocks the ray, and the walk would have found one), and so are the tests
/// on the module path and in the reference's engine, which both take the hint. A slot
/// outside the scene's (after a commit() with fewer primitives) is not tried.
struct AnyHitHint {
    static constexpr std::uint32_t kNone = 0xffffffffu;
    std::uint32_t slot = kNone;  ///< the slot to try first, or kNone
};

/// Work counters of the queries; one per thread, summed per frame.
struct TraceCounters {
    std::uint64_t intersection_tests = 0;  ///< primitive tests (plane, sphere, triangle)
    std::uint64_t bvh_nodes = 0;           ///< BVH nodes whose child boxes were tested
    /// Rays closest_hits traced in packets (the others went alone).
    std::uint64_t packet_rays = 0;
};

class Scene {
  public:
    std::string name;
    std::vector<Material> materials;
    std::vector<ScenePlane> planes;
    std::vector<SceneSphere> spheres;
    /// The triangles. commit() moves them, with their normals, into the order in which
    /// the BVH's leaves hold them (a leaf's triangles then lie side by side in memory):
    /// triangle_source names each by the index it was added at.
    std::vector<SceneTriangle> triangles;
    /// Vertex normals by triangle: empty (every triangle flat-shaded) or exactly one
    /// entry per triangle (commit() checks; call it again after changing them).
    std::vector<VertexNormals> normals;
    /// The index at which triangle k was added (its place in add_triangle's order; an OBJ
    /// file's triangles in file order), though commit() has moved it since. Messages
    /// name triangles by it. The names follow the triangles through commit(), changes in
    /// place, and appends and cuts at the end (pop_back, resize), and no two triangles
    /// share one: a triangle appended after a cut may take a cut triangle's name, never
    /// a present one's. After clear(), once add_triangle or commit() has seen the empty
    /// list, the names start again at 0; a commit() that would hand out more than 2^32
    /// names (billions of cuts and appends) names the triangles afresh, 0 to n - 1.
    /// Erasing or inserting elsewhere in `triangles` after a commit() is not tracked:
    /// build the list afresh instead.
    size_t triangle_source(size_t k) const {
        return k < source_.size() ? source_[k] : next_source_ + (k - source_.size());
    }
    /// Appends a triangle, keeping normals one per triangle: the first smooth triangle
    /// (n not all zero) gives the flat ones before it entries of zeros, and once normals
    /// holds entries every triangle gets one. A flat mesh never allocates normals.
    void add_triangle(const SceneTriangle& t, const VertexNormals& n = {}) {
        forget_removed_sources();
        if (!normals.empty() || n.n0 != Vec3(0.0f)) {
            normals.resize(triangles.size());
            normals.push_back(n);
        }
        triangles.push_back(t);
    }
    std::vector<PointLight> lights;
    View view;  ///< a good default view of this scene
    float ambient =
        0.0f;  ///< constant indirect light (COMS30115's 0.5 option), times rho

    /// Validates the contents (finite values, material indices, radii) and builds the
    /// BVH. Call after every geometry change; camera and light changes need no rebuild.
    /// Throws raylab::Error naming the first bad element; the scene then keeps its last
    /// good BVH, and its queries call the modules (no engine) until a commit() succeeds:
    /// query only after edits that keep the primitives' count, since that BVH indexes the
    /// spheres and triangles it was built over. The registered geometry engine then
    /// prepares its own data from the scene (engine_data), and reads it beside the
    /// current triangles: an edit without a commit() leaves it a mix of both.
    void commit();

    /// Bounds of spheres and triangles (planes excluded); empty box when there are none.
    Aabb bounds() const;

    /// Nearest hit along r in [tmin, tmax], with material and a shading normal that faces
    /// the ray; std::nullopt when nothing is hit.
    std::optional<Hit> closest_hit(const ModuleTable& modules, const Ray& r,
                                   TraceCounters& counters) const;

    /// closest_hit of each of n rays: out[k] is closest_hit(modules, rays[k], counters),
    /// bit for bit. With the reference's engine, rays from one origin (a block of camera
    /// rays) travel in packets of GeometryEngine::kPacketSize (raylab/engine.h).
    void closest_hits(const ModuleTable& modules, const Ray* rays, int n,
                      TraceCounters& counters, std::optional<Hit>* out) const;

    /// True when closest_hits traces packets for this table: the reference's engine runs
    /// its queries.
    bool traces_packets(const ModuleTable& modules) const {
        return engine_for(modules) != nullptr;
    }

    /// True when anything lies on r in [tmin, tmax]; stops at the first hit.
    bool any_hit(const ModuleTable& modules, const Ray& r,
                 TraceCounters& counters) const {
        return any_hit(modules, r, counters, nullptr);
    }
    /// The same, trying hint's slot first (counted as a test like any other); the hint
    /// then names the slot that stopped r, is left as it was when a plane did, or is
    /// cleared when nothing did. The shadow module's occluder (SceneOccluder) keeps one.
    bool any_hit(const ModuleTable& modules, const Ray& r, TraceCounters& counters,
                 AnyHitHint* hint) const;

    const Bvh& bvh() const { return bvh_; }

    /// The data the registered geometry engine prepared at the last successful commit()
    /// (raylab/engine.h: GeometryEngine::prepare), for the engine's queries; null when
    /// there is none (no engine, or no commit() yet).
    const EngineData* engine_data() const { return engine_data_.get(); }

    /// Bytes of the acceleration data: BVH nodes, primitive order, the triangles' source
    /// indices and the engine's data.
    size_t acceleration_bytes() const {
        return bvh_.bytes() + source_.size() * sizeof(std::uint32_t) +
               (engine_data_ ? engine_data_->bytes() : 0);
    }

  private:
    const GeometryEngine* engine_for(const ModuleTable& modules) const;
    void complete(Hit& hit, const Ray& r, const PrimRef& prim) const;
    std::optional<Hit> engine_closest_hit(const GeometryEngine& engine, const Ray& r,
                                          TraceCounters& counters) const;

    void store_in_slot_order();
    // Triangles cleared or cut since the last commit(): their sources go with them (and
    // the count of names starts again once none is left)
    void forget_removed_sources() {
        if (triangles.empty()) source_.clear(), next_source_ = 0;
        if (source_.size() > triangles.size()) source_.resize(triangles.size());
    }

    Bvh bvh_;  // over spheres (first) and triangles (after them)
    std::vector<std::uint32_t> source_;  // by triangle: triangle_source, or empty
    // Names handed out to the triangles in source_: those after it follow on from this
    std::uint32_t next_source_ = 0;
    static constexpr std::uint64_t kLastSource = 0xffffffffu;  // the largest name kept
    friend struct SceneTestAccess;  // engine/tests: the count of names near its end
    // The engine that prepared engine_data_ at the last successful commit(), and its data
    const GeometryEngine* data_engine_ = nullptr;
    std::shared_ptr<const EngineData> engine_data_;
    bool committed_ = false;  // the last commit() succeeded: the engine may run
};

/// The Occluder the shadow module receives: the scene's any-hit query, counted, with
/// the hint of the last shadow ray this object asked about (AnyHitHint). The renderer
/// keeps one per thread and clears its hint at each tile, so a tile's pixels share it.
class SceneOccluder : public Occluder {
  public:
    SceneOccluder(const Scene& scene, const ModuleTable& modules, TraceCounters& counters)
        : scene_(scene), modules_(modules), counters_(counters) {}
    bool occluded(const Ray& r) const override {
        ++shadow_rays;
        return scene_.any_hit(modules_, r, counters_, &hint_);
    }
    mutable std::uint64_t shadow_rays = 0;  ///< any-hit queries made through this object
    /// The next ray starts without a hint (the renderer: at each tile, so that the work
    /// counts do not depend on which thread rendered the tile before).
    void forget_blocker() { hint_ = AnyHitHint{}; }

  private:
    const Scene& scene_;
    const ModuleTable& modules_;
    TraceCounters& counters_;
    mutable AnyHitHint hint_;
};

}  // namespace raylab
