// Where raylab's closest-hit and any-hit time goes (bench/what_if.h). Every variant walks
// the scene's own BVH with Bvh::traverse; only the leaf test changes:
//   shipped     Scene::closest_hit / any_hit: the module table's intersect_triangle, a
//               full Hit per accepted primitive, then material and shading normal
//   direct      traverse + reference::intersect_triangle through a pointer: no Scene
//               bookkeeping (planes, shading normal)
//   double t    traverse + the reference's double edge functions inlined, t only
//   float edge  traverse + edge functions in float inlined (still watertight), t only,
//               vertices in a compact array (36 bytes instead of 76 per triangle)
//   float MT    traverse + Moeller-Trumbore in float inlined, t only, precomputed edges
//   pair BVH    the float MT leaf test on a prototype traversal (bench/proto_bvh.h): both
//               children tested at the parent, nearer first by entry distance
//   BVH4 SSE    the float MT leaf test on a 4-wide BVH collapsed from the pair BVH, four
//               boxes per SSE test (bench/proto_bvh4.h)
#include "what_if.h"

#include <cmath>
#include <functional>
#include <utility>

#include "proto_bvh.h"
#include "proto_bvh4.h"

namespace raylab::bench {

namespace {

struct Tri3 {
    Vec3 v0, v1, v2;
};
struct TriMT {
    Vec3 v0, e1, e2;
};

// t of the hit in [tmin, tmax], or NaN
inline float edge_double_t(const Ray& r, const SceneTriangle& tri, float tmax) {
    const DVec3 o(r.o), w(r.w);
    const DVec3 a = DVec3(tri.v0) - o, b = DVec3(tri.v1) - o, c = DVec3(tri.v2) - o;
    const double e0 = glm::dot(glm::cross(b, c), w), e1 = glm::dot(glm::cross(c, a), w),
                 e2 = glm::dot(glm::cross(a, b), w);
    if ((e0 < 0 || e1 < 0 || e2 < 0) && (e0 > 0 || e1 > 0 || e2 > 0)) return NAN;
    const double det = e0 + e1 + e2;
    if (det == 0.0) return NAN;
    const float t = static_cast<float>(glm::dot(glm::cross(b - a, c - a), a) / det);
    return t >= r.tmin && t <= tmax ? t : NAN;
}

inline float edge_float_t(const Ray& r, const Tri3& tri, float tmax) {
    const Vec3 a = tri.v0 - r.o, b = tri.v1 - r.o, c = tri.v2 - r.o;
    const float e0 = glm::dot(glm::cross(b, c), r.w),
                e1 = glm::dot(glm::cross(c, a), r.w),
                e2 = glm::dot(glm::cross(a, b), r.w);
    if ((e0 < 0 || e1 < 0 || e2 < 0) && (e0 > 0 || e1 > 0 || e2 > 0)) return NAN;
    const float det = e0 + e1 + e2;
    if (det == 0.0f) return NAN;
    const float t = glm::dot(glm::cross(b - a, c - a), a) / det;
    return t >= r.tmin && t <= tmax ? t : NAN;
}

inline float moeller_trumbore_t(const Ray& r, const TriMT& tri, float tmax) {
    const Vec3 p = glm::cross(r.w, tri.e2);
    const float det = glm::dot(tri.e1, p);
    if (det == 0.0f) return NAN;
    const float inv_det = 1.0f / det;
    const Vec3 s = r.o - tri.v0;
    const float beta = glm::dot(s, p) * inv_det;
    if (beta < 0.0f || beta > 1.0f) return NAN;
    const Vec3 q = glm::cross(s, tri.e1);
    const float gamma = glm::dot(r.w, q) * inv_det;
    if (gamma < 0.0f || beta + gamma > 1.0f) return NAN;
    const float t = glm::dot(tri.e2, q) * inv_det;
    return t >= r.tmin && t <= tmax ? t : NAN;
}

// Runs test(ray, prim, tmax) -> t or NaN over the BVH for every ray: the closest t
// (closest) or whether any t exists (any hit). Returns t per ray (kInfinity: miss).
template <class Test>
std::vector<float> trace(const Bvh& bvh, const std::vector<Ray>& rays, bool closest,
                         Test&& test) {
    std::vector<float> out(rays.size(), kInfinity);
    std::uint64_t nodes = 0;
    for (size_t k = 0; k < rays.size(); ++k) {
        const Ray& r = rays[k];
        float best = kInfinity;
        bvh.traverse(
            r,
            [&](std::uint32_t prim, float& tmax) {
                const float t = test(r, prim, tmax);
                if (!(t == t)) return false;  // NaN: no hit
                best = t;
                tmax = t;
                return !closest;
            },
            nodes);
        out[k] = best;
    }
    return out;
}

// The scene in every layout the variants use
struct Layouts {
    const Scene& scene;
    const ModuleTable& modules;
    std::vector<Tri3> tri3;
    std::vector<TriMT> mt;
    PairBvh pair_bvh;
#if RAYLAB_BENCH_HAVE_BVH4
    Bvh4 bvh4;
#endif

    Layouts(const Scene& s, const ModuleTable& m) : scene(s), modules(m) {
        std::vector<Aabb> boxes;
        for (const SceneTriangle& t : scene.triangles) {
            tri3.push_back({t.v0, t.v1, t.v2});
            mt.push_back({t.v0, t.v1 - t.v0, t.v2 - t.v0});
            Aabb b;
            b.grow(t.v0);
            b.grow(t.v1);
            b.grow(t.v2);
            boxes.push_back(b);
        }
        pair_bvh.build(boxes);
#if RAYLAB_BENCH_HAVE_BVH4
        bvh4.build(pair_bvh);
#endif
    }
};

using Tracer = std::function<std::vector<float>()>;
using NamedTracer = std::pair<const char*, Tracer>;

// The shipped query and raylab's BVH with cheaper leaf tests
void binary_bvh_variants(const Layouts& L, const std::vector<Ray>& rays, bool closest,
                         std::vector<NamedTracer>& out) {
    out.emplace_back("shipped (Scene query)", [&L, &rays, closest] {
        std::vector<float> t(rays.size(), kInfinity);
        TraceCounters counters;
        for (size_t k = 0; k < rays.size(); ++k) {
            if (closest) {
                if (auto hit = L.scene.closest_hit(L.modules, rays[k], counters))
                    t[k] = hit->t;
            } else if (L.scene.any_hit(L.modules, rays[k], counters)) {
                t[k] = 0.0f;
            }
        }
        return t;
    });
    using ReferenceFn = decltype(&reference::intersect_triangle);
    ReferenceFn volatile hidden = &reference::intersect_triangle;
    const ReferenceFn reference_fn = hidden;
    const Bvh& bvh = L.scene.bvh();
    out.emplace_back("direct: reference fn, full Hit", [&, reference_fn, closest] {
        return trace(bvh, rays, closest, [&](const Ray& r, std::uint32_t p, float tmax) {
            const SceneTriangle& tri = L.scene.triangles[p];
            Ray s = r;
            s.tmax = tmax;
            const auto hit = reference_fn(s, tri.v0, tri.v1, tri.v2);
            return hit ? hit->t : NAN;
        });
    });
    out.emplace_back("inline double edge fns, t only", [&, closest] {
        return trace(bvh, rays, closest, [&](const Ray& r, std::uint32_t p, float tmax) {
            return edge_double_t(r, L.scene.triangles[p], tmax);
        });
    });
    out.emplace_back("inline float edge fns, compact", [&, closest] {
        return trace(bvh, rays, closest, [&](const Ray& r, std::uint32_t p, float tmax) {
            return edge_float_t(r, L.tri3[p], tmax);
        });
    });
    out.emplace_back("inline float MT, compact", [&, closest] {
        return trace(bvh, rays, closest, [&](const Ray& r, std::uint32_t p, float tmax) {
            return moeller_trumbore_t(r, L.mt[p], tmax);
        });
    });
}

// The float MT leaf test on a prototype BVH (pair or 4-wide)
template <class PrototypeBvh>
Tracer prototype_tracer(const PrototypeBvh& bvh, const Layouts& L,
                        const std::vector<Ray>& rays, bool closest) {
    return [&bvh, &L, &rays, closest] {
        std::vector<float> t(rays.size(), kInfinity);
        for (size_t k = 0; k < rays.size(); ++k) {
            const Ray& r = rays[k];
            bvh.traverse(r, [&](std::uint32_t p, float& tmax) {
                const float th = moeller_trumbore_t(r, L.mt[p], tmax);
                if (!(th == th)) return false;
                t[k] = tmax = th;
                return !closest;
            });
        }
        return t;
    };
}

}  // namespace

Table what_if_table() {
    return Table({"scene", "rays", "query", "leaf test", "Mrays/s", "speed-up",
                  "hit/miss differs"},
                 4);
}

void add_what_if_rows(Table& table, const std::string& scene_name, const Scene& scene,
                      const ModuleTable& modules, const std::vector<Ray>& closest_rays,
                      const std::string& closest_name,
                      const std::vector<Ray>& shadow_rays, int repeats, size_t max_rays) {
    if (!scene.planes.empty() || !scene.spheres.empty()) return;  // triangles only
    const Layouts layouts(scene, modules);
    for (const bool closest : {true, false}) {
        const std::vector<Ray>& all_rays = closest ? closest_rays : shadow_rays;
        if (all_rays.empty()) continue;
        std::vector<Ray> rays;
        const size_t stride = (all_rays.size() + max_rays - 1) / max_rays;
        for (size_t k = 0; k < all_rays.size(); k += stride)
            rays.push_back(all_rays[k]);
        std::vector<NamedTracer> tracers;
        binary_bvh_variants(layouts, rays, closest, tracers);
        tracers.emplace_back("pair BVH prototype + float MT",
                             prototype_tracer(layouts.pair_bvh, layouts, rays, closest));
#if RAYLAB_BENCH_HAVE_BVH4
        tracers.emplace_back("BVH4 SSE prototype + float MT",
                             prototype_tracer(layouts.bvh4, layouts, rays, closest));
#endif
        // Interleaved timing; the first result of each is kept for the comparison
        std::vector<std::vector<float>> t(tracers.size());
        std::vector<std::function<void()>> works;
        for (size_t v = 0; v < tracers.size(); ++v)
            works.push_back([&, v] { t[v] = tracers[v].second(); });
        const std::vector<double> s = interleaved_median_seconds(repeats, works);
        for (size_t v = 0; v < tracers.size(); ++v) {
            size_t differs = 0;
            for (size_t k = 0; k < rays.size(); ++k)
                differs += (t[v][k] < kInfinity) != (t[0][k] < kInfinity);
            table.row({scene_name, closest ? closest_name : "shadow",
                       closest ? "closest" : "any", tracers[v].first,
                       fmt("%.2f", static_cast<double>(rays.size()) / s[v] / 1e6),
                       fmt("%.2fx", s[0] / s[v]), fmt("%zu", differs)});
        }
    }
}

}  // namespace raylab::bench
