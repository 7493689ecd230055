// The reference's geometry engine (raylab/engine.h): the scene's closest-hit and any-hit
// queries with the reference's intersection tests inlined into the BVH traversal.
//
// Not a module: no student writes it, and it ships only compiled, inside the reference
// library, because it repeats the reference's numerics. Each test below computes only t,
// with exactly the operations of its module (solutions/03_plane.cpp, 04_sphere.cpp;
// -ffp-contract=off keeps them unfused; the triangle's are the same functions, in
// watertight_triangle.h), so it accepts exactly the primitives the module accepts, and
// builds the nearest one's Hit with the module's expressions.
// tests/framework/test_engine.cpp renders scenes both ways and compares, and
// tests/stress runs on both paths.
#include <algorithm>
#include <cmath>

#include "raylab/engine.h"
#include "raylab/scene.h"
#include "watertight_triangle.h"

namespace raylab::reference {

namespace {

// intersect_plane's t, or NaN when it returns nullopt
inline float plane_t(const Ray& r, const Plane& plane, float tmax) {
    const float wn = glm::dot(r.w, plane.n);
    if (wn == 0.0f) return NAN;
    const double dist =
        glm::dot(DVec3(r.o), DVec3(plane.n)) + static_cast<double>(plane.d);
    const float t = static_cast<float>(-dist / static_cast<double>(wn));
    if (!(t >= r.tmin && t <= tmax) || std::isinf(t)) return NAN;
    return t;
}

// intersect_sphere's t (Ray Tracing Gems ch. 7; rays starting on the sphere in double,
// issue 8 B5), or NaN
inline float sphere_t(const Ray& r, const Vec3& centre, float radius, float tmax) {
    const Vec3 f = r.o - centre;
    const float rr = radius * radius, ff = glm::dot(f, f);
    float c = ff - rr;
    float b, disc;
    if (std::abs(c) > 0x1p-16f * (ff + rr)) {
        b = glm::dot(f, r.w);
        const Vec3 l = f - b * r.w;
        disc = rr - glm::dot(l, l);
    } else {
        const DVec3 fd = DVec3(r.o) - DVec3(centre), w(r.w);
        const double rrd = double(radius) * double(radius), bd = glm::dot(fd, w);
        const DVec3 l = fd - bd * w;
        c = static_cast<float>(glm::dot(fd, fd) - rrd);
        b = static_cast<float>(bd);
        disc = static_cast<float>(rrd - glm::dot(l, l));
    }
    if (disc < 0.0f) return NAN;
    const float q = -b - std::copysign(std::sqrt(disc), b);
    float t0 = q;
    float t1 = q != 0.0f ? c / q : 0.0f;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 >= r.tmin && t0 <= tmax) return t0;
    if (t1 >= r.tmin && t1 <= tmax) return t1;
    return NAN;
}

using watertight::WoopRay;

// What intersect_triangle's Hit holds besides t, position and normal
struct TriangleExtra {
    Vec2 uv;
};

// intersect_triangle's normal (the same function)
inline Vec3 triangle_normal(const Scene::Slot& tri) {
    double len;
    return watertight::unit_normal(tri.a, tri.b, tri.c, len);
}

// intersect_triangle's t, or NaN: the same functions (and the same decisions); on a hit,
// its uv in extra
inline float triangle_t(const Ray& r, const WoopRay& q, const Scene::Slot& tri,
                        float tmax, TriangleExtra& extra) {
    watertight::Candidate c;
    if (!watertight::candidate(q, tri.a, tri.b, tri.c, c)) return NAN;
    // The module's last two tests, t's range and then t > 0, in the other order: a
    // candidate behind the nearest hit so far is refused before the bound
    const float t = static_cast<float>(c.t);
    if (!(t >= r.tmin && t <= tmax)) return NAN;
    if (!watertight::in_front(c)) return NAN;
    // The module also refuses a triangle whose normal has no length: the scene gives such
    // a triangle NaN vertices (Scene::Slot), which fail the range test above. The
    // nearest hit's normal is computed once, by triangle_normal
    extra.uv = watertight::uv(c);
    return t;
}

// t of the primitive in slot k, or NaN (a scene without spheres skips the load of the
// slot's primitive index)
inline float slot_t(const Scene& scene, const Ray& r, const WoopRay& q, std::uint32_t k,
                    float tmax, TriangleExtra& extra) {
    const Scene::Slot& slot = scene.slots()[k];
    if (!scene.spheres.empty() && scene.bvh().prims()[k] < scene.spheres.size())
        return sphere_t(r, slot.a, slot.b.x, tmax);
    return triangle_t(r, q, slot, tmax, extra);
}

// The nearest primitive and its Hit as its module returns it: t, position, normal, uv
// (material and shading normal are the scene's to fill)
PrimRef closest_hit(const Scene& scene, const Ray& r, TraceCounters& counters, Hit& hit) {
    PrimRef best;
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
    std::uint32_t best_slot = 0;
    bool in_bvh = false;
    TriangleExtra extra, best_extra;
    scene.bvh().traverse(
        ray,
        [&](std::uint32_t first, std::uint32_t count, float& tmax) {
            counters.intersection_tests += count;
            for (std::uint32_t k = first; k < first + count; ++k) {
                const float t = slot_t(scene, r, q, k, tmax, extra);
                if (!std::isnan(t)) {
                    tmax = best_t = t;
                    best_slot = k;
                    best_extra = extra;
                    in_bvh = true;
                }
            }
            return false;
        },
        counters.bvh_nodes);
    if (best.kind == PrimRef::Kind::none && !in_bvh) return best;
    // The module's Hit, from the values of the accepted test (same expressions)
    hit = Hit{};
    hit.t = best_t;
    hit.position = r.o + best_t * r.w;
    if (!in_bvh) {
        hit.n = scene.planes[best.index].plane.n;
        return best;
    }
    const std::uint32_t p = scene.bvh().prims()[best_slot];
    const std::uint32_t sphere_count = static_cast<std::uint32_t>(scene.spheres.size());
    if (p < sphere_count) {
        const Sphere& sphere = scene.spheres[p].sphere;
        hit.n = (hit.position - sphere.c) / sphere.r;
        return {PrimRef::Kind::sphere, p};
    }
    hit.n = triangle_normal(scene.slots()[best_slot]);
    hit.uv = best_extra.uv;
    return {PrimRef::Kind::triangle, p - sphere_count};
}

bool any_hit(const Scene& scene, const Ray& r, TraceCounters& counters) {
    for (const ScenePlane& p : scene.planes) {
        ++counters.intersection_tests;
        if (!std::isnan(plane_t(r, p.plane, r.tmax))) return true;
    }
    const WoopRay q(r);
    bool hit = false;
    scene.bvh().traverse(
        r,
        [&](std::uint32_t first, std::uint32_t count, float&) {
            for (std::uint32_t k = first; k < first + count && !hit; ++k) {
                ++counters.intersection_tests;
                TriangleExtra extra;
                const float t = slot_t(scene, r, q, k, r.tmax, extra);
                hit = !std::isnan(t);
            }
            return hit;
        },
        counters.bvh_nodes);
    return hit;
}

}  // namespace

const GeometryEngine* geometry_engine() {
    static const GeometryEngine engine{&intersect_plane, &intersect_sphere,
                                       &intersect_triangle, &closest_hit, &any_hit};
    return &engine;
}

}  // namespace raylab::reference
