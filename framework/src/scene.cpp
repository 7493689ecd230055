// Scene validation and queries (raylab/scene.h).
#include "raylab/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <utility>

#include <glm/gtc/type_ptr.hpp>

#include "raylab/engine.h"
#include "raylab/error.h"
#include "raylab/refine.h"

namespace raylab {

namespace {

// The engine whose prepare() commit() calls (register_geometry_engine)
const GeometryEngine* registered_engine = nullptr;

std::string str(const Vec3& v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%g, %g, %g)", v.x, v.y, v.z);
    return buf;
}

// c - r and c + r rounded outwards (one step from the nearest float): the box holds the
// exact sphere even when it is small and far from the origin
Aabb sphere_box(const Sphere& s) {
    const auto down = [](float x) { return std::nextafter(x, -kInfinity); };
    const auto up = [](float x) { return std::nextafter(x, kInfinity); };
    const Vec3 lo = s.c - Vec3(s.r), hi = s.c + Vec3(s.r);
    return Aabb{Vec3(down(lo.x), down(lo.y), down(lo.z)),
                Vec3(up(hi.x), up(hi.y), up(hi.z))};
}

Aabb triangle_box(const SceneTriangle& t) {
    Aabb box;
    box.grow(t.v0);
    box.grow(t.v1);
    box.grow(t.v2);
    return box;
}

// Completes a primitive's hit: material, and the shading normal on the side of the
// surface the ray meets. The geometric normal decides the side (pbrt's rule): an
// interpolated normal can face away from a ray that meets the front of its face at a
// grazing angle, and turned to face the ray it would point behind the face, where the
// lights the face sees are behind it
void finish(Hit& hit, const Ray& r, int material, const Vec3& shading_normal) {
    hit.material = material;
    // The sign bits flipped or not, without a branch between -n and n: random rays meet
    // both sides of the Cornell box's walls
    const std::uint32_t flip = std::uint32_t{glm::dot(hit.n, r.w) > 0.0f} << 31;
    std::uint32_t bits[3];
    std::memcpy(bits, glm::value_ptr(shading_normal), sizeof bits);
    for (std::uint32_t& b : bits)
        b ^= flip;
    std::memcpy(glm::value_ptr(hit.ns), bits, sizeof bits);
}

// The hit's point recomputed in double on the primitive it lies on (raylab/refine.h),
// kept only where the module's own point agrees with it within the module's rounding:
// the module's normal is never replaced. source is -1 - index for a plane, the BVH
// primitive index for a sphere or triangle
void refine_hit(const Scene& s, std::int64_t source, Hit& hit, const Ray& r) {
    const Vec3 x = hit.position;
    const std::int64_t sphere_count = static_cast<std::int64_t>(s.spheres.size());
    Vec3 on = x, n(0.0f);
    if (source < 0) {
        const Plane& plane = s.planes[static_cast<size_t>(-1 - source)].plane;
        on = refine_on_plane(x, r, plane);
        n = plane.n;
    } else if (source < sphere_count) {
        const Sphere& sphere = s.spheres[static_cast<size_t>(source)].sphere;
        on = refine_on_sphere(x, r, hit.t, sphere);
        n = Vec3((DVec3(on) - DVec3(sphere.c)) / double(sphere.r));
    } else {
        const size_t k = static_cast<size_t>(source - sphere_count);
        const SceneTriangle& t = s.triangles[k];
        on = refine_on_triangle(x, r, t.v0, t.v1, t.v2);
        n = unit_normal(t);
    }
    hit.position = accept_refined(x, on, n, r, hit.t);
}

Vec3 interpolated_normal(const VertexNormals& tri, const Hit& hit) {
    if (tri.n0 == Vec3(0.0f)) return hit.n;
    const Vec3 n =
        (1.0f - hit.uv.x - hit.uv.y) * tri.n0 + hit.uv.x * tri.n1 + hit.uv.y * tri.n2;
    const float len = glm::length(n);
    if (!(len > 0.0f)) return hit.n;
    // Keep the interpolated normal on the geometric normal's side
    const Vec3 ns = n / len;
    return glm::dot(ns, hit.n) < 0.0f ? -ns : ns;
}

// The module path's walk of bvh (Bvh::traverse when Sorted, else traverse_any): the
// engine's, the same leaves in the same order with vector node tests, when the table
// has an engine; the plain one without
template <bool Sorted, class Visit>
void module_walk(const Bvh& bvh, const GeometryEngine* engine, const Ray& r, Visit& visit,
                 std::uint64_t& nodes_visited) {
    if (engine && engine->module_walk) {
        const GeometryEngine::LeafVisit call = [](void* context, std::uint32_t first,
                                                  std::uint32_t count, float& tmax) {
            return (*static_cast<Visit*>(context))(first, count, tmax);
        };
        engine->module_walk(bvh, r, Sorted, call, &visit, nodes_visited);
    } else if (Sorted) {
        bvh.traverse(r, visit, nodes_visited);
    } else {
        bvh.traverse_any(r, visit, nodes_visited);
    }
}

}  // namespace

void validate(const View& view) {
    if (!is_finite(view.eye))
        throw Error("camera eye " + str(view.eye) + " is not finite");
    if (!is_finite(view.lookat))
        throw Error("camera look-at point " + str(view.lookat) + " is not finite");
    if (!is_finite(view.up))
        throw Error("camera up vector " + str(view.up) + " is not finite");
    if (!std::isfinite(view.fov) || !(view.fov > 0.0f && view.fov < 180.0f)) {
        throw Error("field of view " + std::to_string(view.fov) +
                    " degrees is outside (0, 180)");
    }
    const Vec3 n = view.lookat - view.eye;
    if (glm::length(n) == 0.0f)
        throw Error("camera eye and look-at point are the same point");
    if (glm::length(view.up) == 0.0f) throw Error("camera up vector is zero");
    const float sine =
        glm::length(glm::cross(glm::normalize(n), glm::normalize(view.up)));
    if (!(sine > 1e-4f)) {
        throw Error("camera up vector " + str(view.up) +
                    " is parallel to the view direction " + str(n));
    }
}

void Scene::commit() {
    // Until this commit() succeeds, the queries call the modules: one that throws leaves
    // the last good BVH, but the triangles may have changed since, and the engine's
    // data (degenerate flags, normals) would be the old triangles'.
    committed_ = false;
    const int material_count = static_cast<int>(materials.size());
    const auto check_material = [&](int m, const std::string& what) {
        if (m < 0 || m >= material_count)
            throw Error(what + ": material index " + std::to_string(m) + " out of range");
    };
    for (size_t k = 0; k < materials.size(); ++k) {
        const Material& m = materials[k];
        if (!is_finite(m.rho) || !is_finite(m.Le))
            throw Error("material '" + m.name + "' has a non-finite colour");
    }
    for (size_t k = 0; k < planes.size(); ++k) {
        const Plane& p = planes[k].plane;
        const std::string what = "plane " + std::to_string(k);
        if (!is_finite(p.n) || !std::isfinite(p.d) ||
            std::abs(glm::length(p.n) - 1.0f) > 1e-4f)
            throw Error(what + ": normal must be a finite unit vector, offset finite");
        check_material(planes[k].material, what);
    }
    std::vector<Aabb> boxes;
    boxes.reserve(spheres.size() + triangles.size());
    for (size_t k = 0; k < spheres.size(); ++k) {
        const Sphere& s = spheres[k].sphere;
        const std::string what = "sphere " + std::to_string(k);
        if (!is_finite(s.c) || !std::isfinite(s.r) || !(s.r > 0.0f))
            throw Error(what + ": centre must be finite and radius positive");
        // The sphere test squares r: r^2 must be a finite normal float, and c +- r finite
        const float r2 = s.r * s.r;
        if (!std::isfinite(r2) || r2 < std::numeric_limits<float>::min() ||
            !is_finite(s.c + Vec3(s.r)) || !is_finite(s.c - Vec3(s.r)))
            throw Error(what + ": radius " + std::to_string(s.r) +
                        " is outside what float can square (about 1e-19 .. 1e19)");
        check_material(spheres[k].material, what);
        boxes.push_back(sphere_box(s));
    }
    if (!normals.empty() && normals.size() != triangles.size())
        throw Error("vertex normals: " + std::to_string(normals.size()) +
                    " entries for " + std::to_string(triangles.size()) +
                    " triangles (none, or one per triangle)");
    for (size_t k = 0; k < triangles.size(); ++k) {
        const SceneTriangle& t = triangles[k];
        const std::string what = "triangle " + std::to_string(triangle_source(k));
        if (!is_finite(t.v0) || !is_finite(t.v1) || !is_finite(t.v2))
            throw Error(what + ": vertex is not finite");
        if (!normals.empty()) {
            const VertexNormals& n = normals[k];
            if (!is_finite(n.n0) || !is_finite(n.n1) || !is_finite(n.n2))
                throw Error(what + ": vertex normal is not finite");
        }
        check_material(t.material, what);
        boxes.push_back(triangle_box(t));
    }
    for (size_t k = 0; k < lights.size(); ++k) {
        if (!is_finite(lights[k].p) || !is_finite(lights[k].I))
            throw Error("light " + std::to_string(k) +
                        ": position and intensity must be finite");
    }
    if (!std::isfinite(ambient) || ambient < 0.0f)
        throw Error("ambient term must be finite and non-negative");
    bvh_.build(boxes);
    store_in_slot_order();
    // The engine's data is the new scene's or none: a prepare() that throws leaves none
    engine_data_.reset();
    data_engine_ = registered_engine;
    if (data_engine_) engine_data_ = data_engine_->prepare(*this);
    committed_ = true;
}

void register_geometry_engine(const GeometryEngine* engine) {
    registered_engine = engine;
}

// The triangles and their normals moved into the BVH's slot order, and the BVH's names
// for them changed to match (a leaf's triangles then lie side by side in memory);
// source_ follows each triangle to the index it was added at
void Scene::store_in_slot_order() {
    forget_removed_sources();
    const std::uint32_t sphere_count = static_cast<std::uint32_t>(spheres.size());
    // Triangle k's place in slot order: order[j] is the triangle in the j-th triangle
    // slot
    std::vector<std::uint32_t> order;
    order.reserve(triangles.size());
    bool in_place = true;
    for (const std::uint32_t p : bvh_.prims()) {
        if (p < sphere_count) continue;
        in_place = in_place && p - sphere_count == order.size();
        order.push_back(p - sphere_count);
    }
    // Already in slot order, or added since (they keep the index they arrived at)
    if (in_place) return;
    // Every array moved into a new one first, then all swapped in: an allocation that
    // throws leaves the scene as it was
    const auto gathered = [&](const auto& values) {
        std::remove_const_t<std::remove_reference_t<decltype(values)>> moved(
            values.size());
        if (!values.empty())
            for (size_t j = 0; j < order.size(); ++j)
                moved[j] = values[order[j]];
        return moved;
    };
    auto moved_triangles = gathered(triangles);
    auto moved_normals = gathered(normals);
    std::vector<std::uint32_t> source(order.size());
    std::vector<std::uint32_t> name(sphere_count + order.size());
    for (std::uint32_t k = 0; k < sphere_count; ++k)
        name[k] = k;
    // Names are 32 bits: a commit() that would hand out more (after billions of cuts and
    // appends) names the triangles afresh, by their places before the move
    const std::uint64_t handed =
        std::uint64_t{next_source_} + (triangles.size() - source_.size());
    const bool afresh = handed > kLastSource;
    for (size_t j = 0; j < order.size(); ++j) {
        source[j] =
            afresh ? order[j] : static_cast<std::uint32_t>(triangle_source(order[j]));
        name[sphere_count + order[j]] = sphere_count + static_cast<std::uint32_t>(j);
    }
    next_source_ = static_cast<std::uint32_t>(afresh ? triangles.size() : handed);
    triangles.swap(moved_triangles);
    normals.swap(moved_normals);
    source_.swap(source);
    bvh_.rename(name);
}

Aabb Scene::bounds() const {
    return bvh_.empty() ? Aabb{} : bvh_.bounds();
}

// The engine, when the table runs the reference's intersection tests it reproduces and
// the last commit() succeeded
const GeometryEngine* Scene::engine_for(const ModuleTable& m) const {
    const GeometryEngine* e = m.engine;
    if (committed_ && e && e == data_engine_ && engine_data_ &&
        m.intersect_plane == e->intersect_plane &&
        m.intersect_sphere == e->intersect_sphere &&
        m.intersect_triangle == e->intersect_triangle)
        return e;
    return nullptr;
}

// Material and shading normal of the nearest hit, from the primitive it belongs to, and
// its point refined on that primitive (refine_hit)
void Scene::complete(Hit& hit, const Ray& r, const PrimRef& prim) const {
    const std::int64_t sphere_count = static_cast<std::int64_t>(spheres.size());
    int material = 0;
    Vec3 ns = hit.n;
    std::int64_t source = 0;
    switch (prim.kind) {
        case PrimRef::Kind::plane:
            material = planes[prim.index].material;
            source = -1 - static_cast<std::int64_t>(prim.index);
            break;
        case PrimRef::Kind::sphere:
            material = spheres[prim.index].material;
            source = prim.index;
            break;
        default: {
            const SceneTriangle& t = triangles[prim.index];
            material = t.material;
            // Bounded: normals may have been resized since commit()
            if (prim.index < normals.size())
                ns = interpolated_normal(normals[prim.index], hit);
            source = sphere_count + prim.index;
        }
    }
    if (!prim.refined) refine_hit(*this, source, hit, r);
    finish(hit, r, material, ns);
}

// The engine finds the nearest primitive and its module's Hit
std::optional<Hit> Scene::engine_closest_hit(const GeometryEngine& engine, const Ray& r,
                                             TraceCounters& counters) const {
    // The engine writes straight into the returned optional (named return value): a
    // local Hit copied into it was loaded 16 bytes at a time over the engine's narrower
    // stores, which the store buffer cannot forward (docs/decisions/0001)
    std::optional<Hit> hit(std::in_place);
    PrimRef prim;
    engine.closest_hit(*this, r, counters, *hit, prim);
    if (prim.kind == PrimRef::Kind::none)
        hit.reset();
    else
        complete(*hit, r, prim);
    return hit;
}

void Scene::closest_hits(const ModuleTable& modules, const Ray* rays, int n,
                         TraceCounters& counters, std::optional<Hit>* out) const {
    const GeometryEngine* engine = engine_for(modules);
    if (!engine) {
        for (int k = 0; k < n; ++k)
            out[k] = closest_hit(modules, rays[k], counters);
        return;
    }
    constexpr int P = GeometryEngine::kPacketSize;
    Hit hits[P];
    PrimRef prims[P];
    for (int first = 0; first < n; first += P) {
        const int m = std::min(P, n - first);
        engine->closest_hit_packet(*this, rays + first, m, counters, hits, prims);
        for (int k = 0; k < m; ++k) {
            std::optional<Hit>& hit = out[first + k];
            if (prims[k].kind == PrimRef::Kind::none) {
                hit.reset();
            } else {
                hit = hits[k];
                complete(*hit, rays[first + k], prims[k]);
            }
        }
    }
}

std::optional<Hit> Scene::closest_hit(const ModuleTable& modules, const Ray& r,
                                      TraceCounters& counters) const {
    if (const GeometryEngine* engine = engine_for(modules))
        return engine_closest_hit(*engine, r, counters);
    // Closest hit: every accepted hit shrinks tmax, so farther ones are rejected
    Ray ray = r;
    std::optional<Hit> best;
    PrimRef best_prim;
    for (size_t k = 0; k < planes.size(); ++k) {
        ++counters.intersection_tests;
        if (auto hit = modules.intersect_plane(ray, planes[k].plane)) {
            ray.tmax = hit->t;
            best = hit;
            best_prim = {PrimRef::Kind::plane, static_cast<std::uint32_t>(k)};
        }
    }
    const std::uint32_t sphere_count = static_cast<std::uint32_t>(spheres.size());
    const std::uint32_t* prims = bvh_.prims().data();
    auto visit = [&](std::uint32_t first, std::uint32_t count, float& tmax) {
        for (std::uint32_t k = first; k < first + count; ++k) {
            ++counters.intersection_tests;
            ray.tmax = tmax;
            const std::uint32_t p = prims[k];
            std::optional<Hit> hit;
            PrimRef prim;
            if (p < sphere_count) {
                hit = modules.intersect_sphere(ray, spheres[p].sphere);
                prim = {PrimRef::Kind::sphere, p};
            } else {
                const SceneTriangle& t = triangles[p - sphere_count];
                hit = modules.intersect_triangle(ray, t.v0, t.v1, t.v2);
                prim = {PrimRef::Kind::triangle, p - sphere_count};
            }
            if (hit) {
                tmax = hit->t;
                best = hit;
                best_prim = prim;
            }
        }
        return false;
    };
    module_walk<true>(bvh_, modules.engine, ray, visit, counters.bvh_nodes);
    if (best) complete(*best, r, best_prim);
    return best;
}

bool Scene::any_hit(const ModuleTable& modules, const Ray& r, TraceCounters& counters,
                    AnyHitHint* hint) const {
    if (const GeometryEngine* engine = engine_for(modules))
        return engine->any_hit(*this, r, counters, hint);
    const std::uint32_t sphere_count = static_cast<std::uint32_t>(spheres.size());
    const std::uint32_t* prims = bvh_.prims().data();
    // The module's answer for BVH slot k
    const auto blocks = [&](std::uint32_t k) {
        ++counters.intersection_tests;
        const std::uint32_t p = prims[k];
        if (p < sphere_count)
            return modules.intersect_sphere(r, spheres[p].sphere).has_value();
        const SceneTriangle& t = triangles[p - sphere_count];
        return modules.intersect_triangle(r, t.v0, t.v1, t.v2).has_value();
    };
    // The hint's slot first (the engine's query does the same, in the same order)
    if (hint && hint->slot < bvh_.prims().size() && blocks(hint->slot)) return true;
    for (const ScenePlane& p : planes) {
        ++counters.intersection_tests;
        if (modules.intersect_plane(r, p.plane)) return true;
    }
    std::uint32_t stopped = AnyHitHint::kNone;  // the slot that blocks r, once found
    auto visit = [&](std::uint32_t first, std::uint32_t count, float&) {
        for (std::uint32_t k = first; k < first + count; ++k) {
            if (blocks(k)) {
                stopped = k;
                return true;
            }
        }
        return false;
    };
    module_walk<false>(bvh_, modules.engine, r, visit, counters.bvh_nodes);
    if (hint) hint->slot = stopped;
    return stopped != AnyHitHint::kNone;
}

}  // namespace raylab
