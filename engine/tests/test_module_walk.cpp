// The module path on the engine's walk (GeometryEngine::module_walk): with a student's
// geometry modules the scene calls them from the engine's vector walk, and every answer
// must be the plain walk's (Bvh::traverse), bit for bit, whatever the modules return.
// The modules here are the graders' mutants and function pointers that return odd
// things (NaN, infinite or negative t, t beyond tmax, hits that change with the call
// number, so a different order of tests shows); each query runs with the table's engine
// (the engine's walk) and without it (the plain walk): the same hit in every bit, the
// same counts of tests and nodes, the same any-hit answer and hint.
#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "engine_cases.h"
#include "raylab/contract.h"

// The graders' geometry mutants, each in a namespace of its own (the files define
// raylab::student's functions; contract.h is included above, so only the mutants'
// namespaces are renamed)
#define student mutant_plane_always_miss
#include "../../tests/grading/mutants/plane_always_miss.cpp"
#undef student
#define student mutant_plane_parallel_epsilon
#include "../../tests/grading/mutants/plane_parallel_epsilon.cpp"
#undef student
#define student mutant_plane_parallel_inf
#include "../../tests/grading/mutants/plane_parallel_inf.cpp"
#undef student
#define student mutant_sphere_ok_textbook
#include "../../tests/grading/mutants/sphere_ok_textbook.cpp"
#undef student
#define student mutant_sphere_open_interval
#include "../../tests/grading/mutants/sphere_open_interval.cpp"
#undef student
#define student mutant_sphere_tangent_missed
#include "../../tests/grading/mutants/sphere_tangent_missed.cpp"
#undef student
#define student mutant_triangle_det_threshold
#include "../../tests/grading/mutants/triangle_det_threshold.cpp"
#undef student
#define student mutant_triangle_ok_moller_trumbore
#include "../../tests/grading/mutants/triangle_ok_moller_trumbore.cpp"
#undef student

using namespace raylab;
using namespace raylab::engine_cases;

namespace {

// ---- Odd modules: the reference's hit, or none, or one with an odd t, by call number --

std::uint32_t calls = 0;  // reset before each query, so both walks see the same numbers

std::uint32_t mix(std::uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    return x ^ (x >> 16);
}

std::optional<Hit> odd(std::optional<Hit> hit, const Ray& r) {
    const std::uint32_t h = mix(++calls);
    if (h % 4 == 0) return hit;  // the module's own answer
    if (h % 4 == 1) return std::nullopt;
    Hit out = hit ? *hit : Hit{};
    if (!hit) {
        out.position = r.o + r.w;
        out.n = Vec3(0, 0, 1);
    }
    const float values[] = {kNaN,
                            kInfinity,
                            -kInfinity,
                            -1.0f,
                            0.0f,
                            -0.0f,
                            r.tmin,
                            r.tmax,
                            std::nextafter(r.tmax, kInfinity),
                            2.0f * r.tmax + 1.0f,
                            0.5f * r.tmax,
                            hit ? hit->t : 3.0f,
                            std::numeric_limits<float>::max(),
                            kDenorm};
    out.t = values[(h >> 2) % (sizeof values / sizeof values[0])];
    return out;
}

std::optional<Hit> odd_plane(const Ray& r, const Plane& p) {
    return odd(reference::intersect_plane(r, p), r);
}
std::optional<Hit> odd_sphere(const Ray& r, const Sphere& s) {
    return odd(reference::intersect_sphere(r, s), r);
}
std::optional<Hit> odd_triangle(const Ray& r, const Vec3& v0, const Vec3& v1,
                                const Vec3& v2) {
    return odd(reference::intersect_triangle(r, v0, v1, v2), r);
}

// The reference's tests behind other pointers: the scene takes them for a student's
std::optional<Hit> as_student_plane(const Ray& r, const Plane& p) {
    return reference::intersect_plane(r, p);
}
std::optional<Hit> as_student_sphere(const Ray& r, const Sphere& s) {
    return reference::intersect_sphere(r, s);
}
std::optional<Hit> as_student_triangle(const Ray& r, const Vec3& v0, const Vec3& v1,
                                       const Vec3& v2) {
    return reference::intersect_triangle(r, v0, v1, v2);
}

// A hit on every test, t growing with the call number: each accepted hit moves tmax
// outwards, so boxes the plain walk dropped come back
std::optional<Hit> growing_sphere(const Ray& r, const Sphere&) {
    Hit hit;
    hit.t = r.tmax + float(++calls);
    hit.position = r.o;
    return hit;
}
std::optional<Hit> growing_triangle(const Ray& r, const Vec3&, const Vec3&, const Vec3&) {
    Hit hit;
    hit.t = r.tmax + float(++calls);
    hit.position = r.o;
    return hit;
}

// ---- The two walks side by side ------------------------------------------------------

struct Modules {
    std::string name;
    decltype(&student::intersect_plane) plane;
    decltype(&student::intersect_sphere) sphere;
    decltype(&student::intersect_triangle) triangle;
};

ModuleTable table(const Modules& m, const GeometryEngine* engine) {
    ModuleTable t = ModuleTable::make(ModuleSelection::all(Impl::reference));
    t.intersect_plane = m.plane;
    t.intersect_sphere = m.sphere;
    t.intersect_triangle = m.triangle;
    t.engine = engine;
    return t;
}

bool same_bits(const Vec3& a, const Vec3& b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

void check_identical_bits(const std::optional<Hit>& a, const std::optional<Hit>& b) {
    REQUIRE(a.has_value() == b.has_value());
    if (!a) return;
    CHECK(engine_cases::same_bits(a->t, b->t));
    CHECK(same_bits(a->position, b->position));
    CHECK(same_bits(a->n, b->n));
    CHECK(same_bits(a->ns, b->ns));
    CHECK(std::memcmp(&a->uv, &b->uv, sizeof a->uv) == 0);
    CHECK(a->material == b->material);
}

// Returns how many of rays hit on the plain walk
int check_walks(const Scene& scene, const Modules& m, const std::vector<Ray>& rays) {
    const ModuleTable fast = table(m, reference::geometry_engine());
    const ModuleTable plain = table(m, nullptr);
    int hits = 0;
    AnyHitHint hint_fast, hint_plain;
    for (const Ray& r : rays) {
        INFO(m.name << ", ray " << r);
        TraceCounters cf, cp;
        calls = 0;
        const std::optional<Hit> a = scene.closest_hit(fast, r, cf);
        calls = 0;
        const std::optional<Hit> b = scene.closest_hit(plain, r, cp);
        check_identical_bits(a, b);
        hits += b.has_value();
        calls = 0;
        const bool any_a = scene.any_hit(fast, r, cf, &hint_fast);
        calls = 0;
        const bool any_b = scene.any_hit(plain, r, cp, &hint_plain);
        CHECK(any_a == any_b);
        CHECK(hint_fast.slot == hint_plain.slot);
        CHECK(cf.intersection_tests == cp.intersection_tests);
        CHECK(cf.bvh_nodes == cp.bvh_nodes);
    }
    return hits;
}

const std::vector<Modules>& all_modules() {
    static const std::vector<Modules> list = {
        {"the reference as a student's", &as_student_plane, &as_student_sphere,
         &as_student_triangle},
        {"odd", &odd_plane, &odd_sphere, &odd_triangle},
        {"growing", &odd_plane, &growing_sphere, &growing_triangle},
        {"plane_always_miss, sphere_ok_textbook, triangle_det_threshold",
         &mutant_plane_always_miss::intersect_plane,
         &mutant_sphere_ok_textbook::intersect_sphere,
         &mutant_triangle_det_threshold::intersect_triangle},
        {"plane_parallel_epsilon, sphere_open_interval, triangle_ok_moller_trumbore",
         &mutant_plane_parallel_epsilon::intersect_plane,
         &mutant_sphere_open_interval::intersect_sphere,
         &mutant_triangle_ok_moller_trumbore::intersect_triangle},
        {"plane_parallel_inf, sphere_tangent_missed",
         &mutant_plane_parallel_inf::intersect_plane,
         &mutant_sphere_tangent_missed::intersect_sphere, &reference::intersect_triangle},
    };
    return list;
}

}  // namespace

TEST_SUITE("module walk") {
    TEST_CASE("the engine offers the module path its walk") {
        if (!engine_built()) {
            MESSAGE("no engine in this build: the module path walks Bvh::traverse");
            return;
        }
        CHECK(static_cast<bool>(reference::geometry_engine()->module_walk));
    }

    // The engine's walk against the plain one, leaf by leaf, with visits that leave any
    // tmax behind: NaN, infinities, negative, growing (a module's t is anything)
    TEST_CASE("the engine's module walk visits what Bvh::traverse visits, for any tmax") {
        if (!engine_built()) return;
        const GeometryEngine& engine = *reference::geometry_engine();
        const float values[] = {kNaN,  kInfinity, -kInfinity, -1.0f, 0.0f,
                                -0.0f, 0.5f,      2.0f,       1e30f, kDenorm};
        for (const bool spheres : {false, true}) {
            const Scene scenes[] = {lattice_scene(8, spheres), triangle_scene(3000, 11)};
            for (const Scene& scene : scenes) {
                std::vector<Ray> rays = lattice_rays(8);
                const std::vector<Ray> more = rays_at(scene, 5, 1000);
                rays.insert(rays.end(), more.begin(), more.end());
                for (const bool sorted : {true, false}) {
                    INFO("spheres " << spheres << ", sorted " << sorted);
                    for (const Ray& r : rays) {
                        std::vector<std::uint32_t> plain, fast;
                        std::uint64_t nodes_plain = 0, nodes_fast = 0;
                        std::uint32_t n = 0;
                        const auto record = [&](std::vector<std::uint32_t>& out) {
                            return [&out, &n, &values](std::uint32_t first,
                                                       std::uint32_t count, float& tmax) {
                                out.push_back(first);
                                out.push_back(count);
                                const std::uint32_t h = mix(++n);
                                if (h % 3 != 0)
                                    tmax = values[(h >> 2) %
                                                  (sizeof values / sizeof(float))];
                                return h % 61 == 0;
                            };
                        };
                        auto visit_plain = record(plain);
                        auto visit_fast = record(fast);
                        n = 0;
                        if (sorted)
                            scene.bvh().traverse(r, visit_plain, nodes_plain);
                        else
                            scene.bvh().traverse_any(r, visit_plain, nodes_plain);
                        n = 0;
                        engine.module_walk(
                            scene.bvh(), r, sorted,
                            [](void* c, std::uint32_t first, std::uint32_t count,
                               float& tmax) {
                                return (*static_cast<decltype(visit_fast)*>(c))(
                                    first, count, tmax);
                            },
                            &visit_fast, nodes_fast);
                        INFO("ray " << r);
                        CHECK(plain == fast);
                        CHECK(nodes_plain == nodes_fast);
                    }
                }
            }
        }
    }

    // Whole queries with the modules above, on the engine's walk and the plain one
    TEST_CASE("student modules: the same hits, counts and hints on both walks") {
        Scene mixed = sphere_scene(300, 3);
        const Scene triangles = triangle_scene(2000, 4);
        mixed.materials = triangles.materials;
        for (const SceneTriangle& t : triangles.triangles)
            mixed.triangles.push_back(t);
        mixed.commit();
        const Scene scenes[] = {sphere_scene(200, 1), triangles, mixed,
                                lattice_scene(6, true)};
        for (const Modules& m : all_modules()) {
            for (const Scene& scene : scenes) {
                std::vector<Ray> rays = rays_at(scene, 9, 1500);
                const std::vector<Ray> lattice = lattice_rays(6);
                rays.insert(rays.end(), lattice.begin(), lattice.end());
                // Rays leaving the reference's hits, as shadow rays do
                const ModuleTable reference = table(all_modules()[0], nullptr);
                TraceCounters ignored;
                for (size_t k = 0; k < 500; ++k) {
                    if (const auto hit = scene.closest_hit(reference, rays[k], ignored))
                        rays.push_back(Ray{hit->position, -rays[k].w, 0.0f, kInfinity});
                }
                CHECK(check_walks(scene, m, rays) > 0);
            }
        }
    }
}
