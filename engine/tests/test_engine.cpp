// The reference's engine (raylab/engine.h) against the module path: the same hits, the
// same counts and the same images, and the module path whenever a module is not the
// reference's.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include "raylab/engine.h"
#include "raylab/renderer.h"
#include "raylab/sample_scenes.h"
#include "raylab/scenes.h"
#include "engine_test_data.h"
#include "test_helpers.h"

using namespace raylab;

namespace {

// A floor plane under the Cornell box's triangles and a few spheres: all three kinds
Scene mixed_scene() {
    Scene scene = cornell_box();
    scene.planes.push_back({Plane{Vec3(0, 1, 0), 1.0f}, 0});
    scene.spheres.push_back({Sphere{Vec3(-0.4f, -0.6f, -0.3f), 0.35f}, 1});
    scene.spheres.push_back({Sphere{Vec3(0.5f, -0.7f, 0.2f), 0.25f}, 2});
    scene.commit();
    return scene;
}

std::vector<std::pair<std::string, Scene>> test_scenes() {
    std::vector<std::pair<std::string, Scene>> scenes;
    scenes.emplace_back("cornell", cornell_box());
    scenes.emplace_back("dtu", dtu_scene());
    scenes.emplace_back("mixed", mixed_scene());
    scenes.emplace_back("mixed at 1e4",
                        translated(mixed_scene(), Vec3(1e4f, -5e3f, 3e3f)));
    scenes.emplace_back("terrain", *sample_scene("terrain"));
    scenes.emplace_back("room", *sample_scene("room"));
    return scenes;
}

// A collinear triangle (v2 - v0 = 2 (v1 - v0)) and a ray from far away that ends exactly
// at its vertex v2: the watertight test and its t > 0 bound pass it (e0 = e1 = 0, e2 a
// rounding residue); only the module's normal test and the scene's degenerate flag refuse
const SceneTriangle kCollinear{Vec3(-0x1p-6f, 0x1.6p-1f, 0x1.bp-2f),
                               Vec3(0x1.7p-2f, 0x1.4p-2f, 0x1.08p-1f),
                               Vec3(0x1.78p-1f, -0x1p-4f, 0x1.38p-1f)};
const Ray kThroughVertex{Vec3(0x1.5d08dcp+13f, 0x1.9bb8p+15f, 0x1.664acep+13f),
                         Vec3(-0x1.5d02fcp+13f, -0x1.9bb82p+15f, -0x1.6645eep+13f), 0.0f,
                         kInfinity};

Vec3 hex3(const char* x, const char* y, const char* z) {
    return Vec3(std::strtof(x, nullptr), std::strtof(y, nullptr),
                std::strtof(z, nullptr));
}

float max_abs(const Vec3& v) {
    return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

// Distance (max norm) from the exact point, in units of delta(exact) (raylab/refine.h)
float error_in_delta(const Vec3& got, const Vec3& exact) {
    return max_abs(got - exact) / (0x1p-23f * max_abs(exact));
}

Scene one_triangle(const Vec3& v0, const Vec3& v1, const Vec3& v2) {
    Scene s;
    s.materials.push_back(Material{"grey", Vec3(0.5f), Vec3(0.0f)});
    s.triangles.push_back(SceneTriangle{v0, v1, v2});
    return s;
}

}  // namespace

TEST_SUITE("engine") {
    TEST_CASE("the reference's table carries the engine") {
        REQUIRE(engine_table().engine != nullptr);
        const GeometryEngine& e = *engine_table().engine;
        const ModuleTable t = engine_table();
        CHECK((e.intersect_plane == t.intersect_plane));
        CHECK((e.intersect_sphere == t.intersect_sphere));
        CHECK((e.intersect_triangle == t.intersect_triangle));
    }

    TEST_CASE("engine and module path give the same hits and counts") {
        const ModuleTable fast = engine_table(), slow = module_path_table();
        // The engine reads the nearest triangle's normal from the scene where the scene
        // keeps the normals, and computes it where it does not: both are compared
        bool kept = false, computed = false;
        for (const auto& [name, scene] : test_scenes()) {
            // INFO captures in a lambda, which clang 14 refuses for a structured binding
            const std::string& scene_name = name;
            INFO("scene " << scene_name);
            (engine_data(scene).has_face_normals() ? kept : computed) = true;
            const Aabb box = scene.bounds();
            const Vec3 centre = box.centre(), size = box.hi - box.lo;
            Rng rng(77);
            TraceCounters cf, cs;
            int hits = 0;
            for (int k = 0; k < 3000; ++k) {
                const Vec3 o = centre + size * rng.in_box(-0.7f, 0.7f);
                const Ray r{o, rng.direction(), k % 3 == 0 ? 0.01f : 0.0f,
                            k % 5 == 0 ? 0.5f * glm::length(size) : kInfinity};
                INFO("ray " << k);
                hits += check_both_paths(scene, fast, slow, r, rng, cf, cs);
            }
            CHECK(hits > 500);  // the rays meet the scene: the comparison means something
            CHECK(cf.intersection_tests == cs.intersection_tests);
            CHECK(cf.bvh_nodes == cs.bvh_nodes);
        }
        CHECK(kept);
        CHECK(computed);
    }

    // The closest-hit query chooses the ray's dominant axis and takes 1 / w on it
    // without a branch (WoopRay's Unpredictable constructor): on ties between
    // components, signed zeros, subnormals, infinities and NaN it must choose what the
    // module does, or t differs in its last bits or a ray the module misses hits
    TEST_CASE("the engine's axis choice agrees with the module on ties, zeros and NaN") {
        const ModuleTable fast = engine_table(), slow = module_path_table();
        const float values[] = {0.0f,  -0.0f,     1.0f,       -1.0f, 0.5f,
                                -0.5f, 0x1p-140f, -0x1p-140f, 3.0f,  0x1.fffffep-1f,
                                NAN,   kInfinity, -kInfinity};
        const Scene scene = cornell_box();
        const Vec3 origins[] = {Vec3(0.0f), Vec3(0.3f, -0.2f, 0.1f),
                                Vec3(0.1f, 0.1f, 2.5f), scene.triangles[7].v1};
        TraceCounters cf, cs;
        int hits = 0, rays = 0;
        for (const Vec3& o : origins)
            for (const float x : values)
                for (const float y : values)
                    for (const float z : values) {
                        const Ray r{o, Vec3(x, y, z), 0.0f, kInfinity};
                        INFO("ray " << r);
                        const auto a = scene.closest_hit(fast, r, cf);
                        check_same_hit(a, scene.closest_hit(slow, r, cs));
                        hits += a.has_value(), ++rays;
                    }
        MESSAGE(hits, " of ", rays, " rays hit");
        CHECK(hits > 2000);
        CHECK(cf.intersection_tests == cs.intersection_tests);
    }

    // The engine skips the module's normal test: it flags degenerate triangles when it
    // prepares a committed scene instead (SceneData::degenerate). Rays exactly through
    // points of collinear and repeated-vertex triangles must miss them on both paths (the
    // conservative t > 0 bound refuses most of them anyway) and, past them, hit the wall
    // behind
    TEST_CASE("degenerate triangles are missed on both paths") {
        Scene scene;
        scene.materials.push_back(Material{});
        const float wall = -2.0f;
        scene.triangles.push_back(
            {Vec3(-40, -40, wall), Vec3(40, -40, wall), Vec3(0, 40, wall)});
        // Collinear in exact arithmetic (v2 - v0 = 2 (v1 - v0)) and repeated vertices
        const Vec3 a(-0.5f, -0.25f, 0.0f), d(0.25f, 0.125f, 0.0625f);
        scene.triangles.push_back({a, a + d, a + 2.0f * d});
        scene.triangles.push_back({a + d, a + 2.0f * d, a});
        scene.triangles.push_back({a, a, Vec3(0.3f, 0.1f, -0.2f)});
        scene.triangles.push_back({Vec3(0.3f, 0.1f, -0.2f), a, a});
        scene.commit();
        const ModuleTable fast = engine_table(), slow = module_path_table();
        Rng rng(5);
        TraceCounters cf, cs;
        for (int k = 0; k < 2000; ++k) {
            // A point of a degenerate triangle: on the segment a .. a + 2d, or a itself
            const float s = k % 4 == 0 ? 0.0f : std::ldexp(float(k % 64), -5);
            const Vec3 target = a + s * d;
            // Dyadic origins: w = target - o is exact, so the ray meets the triangle's
            // line exactly and only the test's own rounding decides its edge signs
            const Vec3 o =
                Vec3(0.0f, 0.0f, 3.0f) + glm::floor(rng.in_box(-64.0f, 64.0f)) / 64.0f;
            const Ray r{o, target - o, 0.0f, kInfinity};
            INFO("ray " << k << ": " << r);
            const auto h = scene.closest_hit(fast, r, cf);
            check_same_hit(h, scene.closest_hit(slow, r, cs));
            REQUIRE(h.has_value());
            CHECK(h->position.z == doctest::Approx(wall).epsilon(1e-5));
        }
    }

    // The test above still passes when the engine refuses nothing for a zero normal (no
    // flag, no normal test). A ray from far away exactly through a vertex of a
    // collinear triangle can pass the watertight test and its conservative t > 0 bound
    // (e0 = e1 = 0, e2 a rounding residue, uv = (0, 1), t = 1): only the module's normal
    // test, and the scene's flag on the engine's side, refuse it. Without them the
    // engine hit these with a NaN normal while the module path missed
    TEST_CASE("degenerate triangles hit through a vertex are missed on both paths") {
        const ModuleTable fast = engine_table(), slow = module_path_table();
        TraceCounters cf, cs;
        {
            // The case found first (v2 - v0 = 2 (v1 - v0), the ray ends at v2)
            Scene scene;
            scene.materials.push_back(Material{});
            scene.triangles.push_back(kCollinear);
            scene.commit();
            const Ray& r = kThroughVertex;
            CHECK_FALSE(scene.closest_hit(fast, r, cf).has_value());
            CHECK_FALSE(scene.closest_hit(slow, r, cs).has_value());
            CHECK_FALSE(scene.any_hit(fast, r, cf));
            CHECK_FALSE(scene.any_hit(slow, r, cs));
        }
        // Collinear dyadic triangles (and repeated vertices), rays through their vertices
        // from 1e2 .. 1e4 away: the scene holds nothing else, so every hit is wrong
        Rng rng(11);
        int rays = 0;
        for (int s = 0; s < 200; ++s) {
            Scene scene;
            scene.materials.push_back(Material{});
            const Vec3 a = glm::floor(rng.in_box(-64.0f, 64.0f)) / 64.0f;
            const Vec3 d = glm::floor(rng.in_box(-64.0f, 64.0f)) / 64.0f;
            for (int k = 0; k < 4; ++k) {
                const auto at = [&](int j) { return a + float(j) * d; };
                scene.triangles.push_back({at(k % 3 - 1), at(k - 2), at(2 - k % 2)});
            }
            scene.commit();
            for (int j = 0; j < 50; ++j, ++rays) {
                const SceneTriangle& t = scene.triangles[size_t(j) % 4];
                const Vec3 target = j % 3 == 0 ? t.v0 : j % 3 == 1 ? t.v1 : t.v2;
                const float far = j % 2 == 0 ? 1e4f : 1e2f;
                const Vec3 o = target + rng.in_box(-far, far);
                const Ray r{o, target - o, 0.0f, kInfinity};
                INFO("scene " << s << ", ray " << j << ": " << r);
                const auto h = scene.closest_hit(fast, r, cf);
                check_same_hit(h, scene.closest_hit(slow, r, cs));
                CHECK_FALSE(h.has_value());
                CHECK(scene.any_hit(fast, r, cf) == scene.any_hit(slow, r, cs));
                CHECK_FALSE(scene.any_hit(fast, r, cf));
            }
        }
        CHECK(rays == 10000);
    }

    // A commit() once cleared the degenerate flags before it
    // had checked every triangle, so one that threw left the old BVH with no flags, and
    // the engine hit the collinear triangle below (NaN normal) where the module path
    // missed it. A commit() that throws now changes nothing
    TEST_CASE(
        "a commit() that throws keeps the engine and the module path in agreement") {
        const ModuleTable fast = engine_table(), slow = module_path_table();
        Scene scene;
        scene.materials.push_back(Material{});
        scene.triangles.push_back({Vec3(-1, -1, -40), Vec3(1, -1, -40), Vec3(0, 1, -40)});
        scene.triangles.push_back(kCollinear);
        scene.commit();
        const Ray& r = kThroughVertex;
        const auto both = [&] {
            TraceCounters cf, cs;
            check_same_hit(scene.closest_hit(fast, r, cf),
                           scene.closest_hit(slow, r, cs));
            CHECK(scene.any_hit(fast, r, cf) == scene.any_hit(slow, r, cs));
            CHECK(cf.intersection_tests == cs.intersection_tests);
        };
        both();
        scene.triangles[0].material = 7;
        CHECK_THROWS_AS(scene.commit(), Error);
        scene.triangles[0].material = 0;
        both();
    }

    // The same, but before the throwing commit() a triangle was reversed (same box,
    // normal flipped): the module path reads the scene's triangles, so the engine must
    // not read the normals the last good commit() kept
    TEST_CASE(
        "a commit() that throws after a vertex change keeps both paths in agreement") {
        const ModuleTable fast = engine_table(), slow = module_path_table();
        Scene scene;
        scene.materials.push_back(Material{});
        scene.triangles.push_back({Vec3(-1, -1, -4), Vec3(1, -1, -4), Vec3(0, 1, -4)});
        scene.lights.push_back(PointLight{Vec3(0, 0, 5), Vec3(1)});
        scene.commit();
        const Ray r{Vec3(0.1f, 0.0f, 0.0f), Vec3(0, 0, -1), 0.0f, kInfinity};
        const auto both = [&] {
            TraceCounters cf, cs;
            check_same_hit(scene.closest_hit(fast, r, cf),
                           scene.closest_hit(slow, r, cs));
        };
        both();
        std::swap(scene.triangles[0].v1, scene.triangles[0].v2);  // a valid change
        scene.lights[0].p.x = NAN;                                // and an invalid one
        CHECK_THROWS_AS(scene.commit(), Error);
        scene.lights[0].p.x = 0.0f;  // (lights need no commit)
        both();
    }

    // And with a triangle made collinear before the throwing commit(): the old flags
    // say it is not degenerate, and the engine's test alone passes a ray through its
    // vertex v2, which the module's normal test refuses
    TEST_CASE(
        "a commit() that throws after a triangle turned degenerate keeps both paths "
        "in agreement") {
        const ModuleTable fast = engine_table(), slow = module_path_table();
        Scene scene;
        scene.materials.push_back(Material{});
        SceneTriangle before = kCollinear;
        before.v0.y += 0.25f;  // not collinear; the same box around v2
        scene.triangles.push_back(before);
        scene.commit();
        REQUIRE_FALSE(engine_data(scene).degenerate(0));
        scene.triangles[0] = kCollinear;
        scene.ambient = -1.0f;
        CHECK_THROWS_AS(scene.commit(), Error);
        scene.ambient = 0.0f;
        TraceCounters cf, cs;
        const auto a = scene.closest_hit(fast, kThroughVertex, cf);
        check_same_hit(a, scene.closest_hit(slow, kThroughVertex, cs));
        CHECK_FALSE(a.has_value());
        CHECK(scene.any_hit(fast, kThroughVertex, cf) ==
              scene.any_hit(slow, kThroughVertex, cs));
    }

    TEST_CASE("the engine refines a triangle hit itself only when its bound allows") {
        // A camera ray of the Cornell box: t's error bound is far below 2^-30 of the
        // point, so the engine sets the point, with the wall's shared coordinate exact
        // (o + t w alone leaves z 2^-51 off 0).
        // From 1e4 away the bound grows with the distance: the scene refines instead
        const GeometryEngine* engine = engine_table().engine;
        Scene scene;
        scene.materials.push_back(Material{});
        scene.triangles.push_back({Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(0, 1, 0)});
        scene.commit();
        TraceCounters c;
        Hit hit;
        const Ray near{Vec3(0.1f, 0.2f, 3.0f), glm::normalize(Vec3(-0.1f, -0.1f, -1.0f)),
                       0.0f, kInfinity};
        PrimRef a, b;
        engine->closest_hit(scene, near, c, hit, a);
        REQUIRE(a.kind == PrimRef::Kind::triangle);
        CHECK(a.refined);
        CHECK(hit.position.z == 0.0f);
        // The same wall on each axis: the shared coordinate is set on x, y and z alike
        // (a mutation that left x and y as o + t w passed the z case alone)
        for (int axis = 0; axis < 3; ++axis) {
            INFO("wall at " << std::string(1, "xyz"[axis]) << " = 0");
            // v with its z moved to the axis (a rotation of the components)
            const auto on = [axis](Vec3 v) {
                return axis == 2   ? v
                       : axis == 1 ? Vec3(v.y, v.z, v.x)
                                   : Vec3(v.z, v.x, v.y);
            };
            Scene wall;
            wall.materials.push_back(Material{});
            wall.triangles.push_back(
                {on(Vec3(-1, -1, 0)), on(Vec3(1, -1, 0)), on(Vec3(0, 1, 0))});
            wall.commit();
            const Ray ray{on(near.o), on(near.w), 0.0f, kInfinity};
            PrimRef ref;
            engine->closest_hit(wall, ray, c, hit, ref);
            REQUIRE(ref.kind == PrimRef::Kind::triangle);
            CHECK(ref.refined);
            CHECK(hit.position[axis] == 0.0f);
        }
        const Vec3 o(3e3f, 4e3f, 1e4f);
        const Ray far{o, glm::normalize(Vec3(0.1f, 0.05f, 0.0f) - o), 0.0f, kInfinity};
        engine->closest_hit(scene, far, c, hit, b);
        REQUIRE(b.kind == PrimRef::Kind::triangle);
        CHECK_FALSE(b.refined);
        // Either way the scene's hit lies on the wall
        const ModuleTable fast = engine_table();
        for (const Ray& r : {near, far}) {
            const auto h = scene.closest_hit(fast, r, c);
            REQUIRE(h.has_value());
            CHECK(h->position.z == 0.0f);
        }
    }

    TEST_CASE("engine and module path render the same image") {
        const ModuleTable fast = engine_table(), slow = module_path_table();
        RenderSettings settings;
        settings.width = 96;
        settings.height = 72;
        for (const auto& [name, scene] : test_scenes()) {
            // INFO captures in a lambda, which clang 14 refuses for a structured binding
            const std::string& scene_name = name;
            INFO("scene " << scene_name);
            Image a, b;
            const FrameStats sa = render(scene, scene.view, settings, fast, a);
            const FrameStats sb = render(scene, scene.view, settings, slow, b);
            CHECK(sa.camera_rays == sb.camera_rays);
            CHECK(sa.shadow_rays == sb.shadow_rays);
            // The engine's camera rays travel in packets (render() traces a tile ahead),
            // which visit leaves in their own order: a ray may test a primitive that its
            // own walk would have skipped behind a nearer hit, never many (each ray tests
            // only the leaves whose box it meets). Without that per-ray box test the
            // terrain's packets ran 14 times the tests
            CHECK(sa.intersection_tests >= sb.intersection_tests * 9 / 10);
            CHECK(sa.intersection_tests <= sb.intersection_tests * 5 / 4);
            size_t different = 0, lit = 0;
            for (size_t k = 0; k < a.pixels.size(); ++k) {
                const Vec3 d = glm::abs(a.pixels[k] - b.pixels[k]);
                const Vec3 m = glm::abs(b.pixels[k]);
                different += d.x > 1e-6f * m.x || d.y > 1e-6f * m.y || d.z > 1e-6f * m.z;
                lit += m.x + m.y + m.z > 0.0f;
            }
            CHECK(different == 0);
            CHECK(lit > a.pixels.size() / 4);
        }
    }

    TEST_CASE("a module that is not the reference's is called once per primitive test") {
        static std::uint64_t calls = 0;
        ModuleTable t = engine_table();
        t.intersect_triangle = [](const Ray& r, const Vec3& a, const Vec3& b,
                                  const Vec3& c) {
            ++calls;
            return reference::intersect_triangle(r, a, b, c);
        };
        const Scene scene = cornell_box();
        RenderSettings settings;
        settings.width = 32;
        settings.height = 24;
        settings.threads = 1;
        Image image, expected;
        calls = 0;
        const FrameStats stats = render(scene, scene.view, settings, t, image);
        CHECK(calls == stats.intersection_tests);
        CHECK(calls > 0);
        render(scene, scene.view, settings, engine_table(), expected);
        CHECK(image.pixels == expected.pixels);
    }

    TEST_CASE(
        "a hint (the last blocker) changes no answer, and both paths take it alike") {
        const ModuleTable fast = engine_table(), slow = module_path_table();
        for (const auto& [name, scene] : test_scenes()) {
            const std::string& scene_name = name;
            INFO("scene " << scene_name);
            const Aabb box = scene.bounds();
            const Vec3 centre = box.centre(), size = box.hi - box.lo;
            Rng rng(91);
            // Shadow-like rays: from points in the scene towards one light, neighbours
            // close together (runs of ten from nearby points), as a tile's are
            const Vec3 light = centre + Vec3(0.1f, 0.45f, 0.2f) * size;
            TraceCounters hf, hs, plain;
            AnyHitHint a, b;
            int blocked = 0, tried = 0;
            Vec3 base(0.0f);
            for (int k = 0; k < 4000; ++k) {
                if (k % 10 == 0) base = centre + size * rng.in_box(-0.45f, 0.45f);
                const Vec3 o = base + 0.002f * size * rng.in_box(-1.0f, 1.0f);
                const Vec3 d = light - o;
                const float len = glm::length(d);
                const Ray r{o, d / len, 1e-4f * len, len * (1.0f - 1e-4f)};
                INFO("ray " << k << ": " << r);
                tried += a.slot != AnyHitHint::kNone;
                const bool truth = scene.any_hit(slow, r, plain);
                const bool with_fast = scene.any_hit(fast, r, hf, &a);
                const bool with_slow = scene.any_hit(slow, r, hs, &b);
                CHECK(with_fast == truth);
                CHECK(with_slow == truth);
                // The same tests in the same order leave the same hint
                CHECK(a.slot == b.slot);
                blocked += truth;
            }
            // The rays meet blockers and the hints were tried: the check means something
            CHECK(blocked > 200);
            CHECK(tried > 200);
            CHECK(hf.intersection_tests == hs.intersection_tests);
            CHECK(hf.bvh_nodes == hs.bvh_nodes);
        }
    }

    TEST_CASE("a ray blocked again by its hint's primitive skips the walk") {
        const ModuleTable fast = engine_table(), slow = module_path_table();
        const Scene scene = cornell_box();
        // Down from under the ceiling onto the floor: the floor blocks it
        const Ray r{Vec3(0.0f, 0.9f, 0.0f), Vec3(0.0f, -1.0f, 0.0f), 1e-4f, 10.0f};
        for (const ModuleTable* m : {&fast, &slow}) {
            INFO((m == &fast ? "engine" : "module path"));
            AnyHitHint hint;
            TraceCounters first, second;
            REQUIRE(scene.any_hit(*m, r, first, &hint));
            REQUIRE(hint.slot != AnyHitHint::kNone);
            const std::uint32_t blocker = hint.slot;
            CHECK(scene.any_hit(*m, r, second, &hint));
            CHECK(second.intersection_tests == 1);
            CHECK(second.bvh_nodes == 0);
            CHECK(hint.slot == blocker);
            // A ray nothing blocks clears it, after trying it
            TraceCounters third;
            const Ray up{Vec3(0.0f, 0.0f, 0.0f), Vec3(0.0f, 1.0f, 0.0f), 1e-4f, 0.5f};
            CHECK_FALSE(scene.any_hit(*m, up, third, &hint));
            CHECK(hint.slot == AnyHitHint::kNone);
            CHECK(third.intersection_tests >= 1);
        }
    }

    TEST_CASE("a hint from before a commit() with fewer primitives is not tried") {
        const ModuleTable fast = engine_table(), slow = module_path_table();
        Scene scene = cornell_box();
        const Ray r{Vec3(0.0f, 0.9f, 0.0f), Vec3(0.0f, -1.0f, 0.0f), 1e-4f, 10.0f};
        AnyHitHint a, b;
        TraceCounters c;
        REQUIRE(scene.any_hit(fast, r, c, &a));
        REQUIRE(scene.any_hit(slow, r, c, &b));
        // The slot past the end of a scene of one triangle
        a.slot = b.slot = static_cast<std::uint32_t>(scene.bvh().prims().size() - 1);
        scene.triangles.resize(1);
        scene.commit();
        REQUIRE(scene.bvh().prims().size() == 1);
        TraceCounters hf, hs, plain;
        const bool truth = scene.any_hit(slow, r, plain);
        CHECK(scene.any_hit(fast, r, hf, &a) == truth);
        CHECK(scene.any_hit(slow, r, hs, &b) == truth);
        // Not tried: the same tests as without a hint
        CHECK(hf.intersection_tests == plain.intersection_tests);
        CHECK(hs.intersection_tests == plain.intersection_tests);
    }

    // The point exact to pbrt's deltaT, which the engine keeps instead of refining,
    // against the exact intersection (Python fractions), rounded to float
    TEST_CASE(
        "the engine's refined point: deltaT is no bound when |w| > 1 (grazing ray)") {
        // pbrt's dx = gamma(5) (max_x + max_z) uses the z already scaled by 1 / w_z: with
        // |w_z| = 1e6 the shear's rounding (about 3u |z| before scaling) is missed.
        // |td - t| was 2592 dt and the engine's point 4.9 delta (8.9 half-ulps) off
        // (module path: 0.08 delta). Ray::w is unit by contract, but nothing checks it:
        // the engine now refines only rays with |w|_max <= 1
        Scene s =
            one_triangle(hex3("-0x1.9e5d1ep+12", "-0x1.aa131cp+11", "-0x1.9d4b44p+13"),
                         hex3("-0x1.9e5d2ap+12", "-0x1.aa1316p+11", "-0x1.9d4b42p+13"),
                         hex3("0x1.9e797p+12", "0x1.a9edccp+11", "0x1.9d4054p+13"));
        s.commit();
        const Ray r{hex3("-0x1.2dcbe4p+14", "-0x1.364392p+13", "-0x1.2cfb0cp+15"),
                    hex3("0x1.aa8774p+18", "0x1.b6734ep+17", "0x1.a9596p+19"), 0.0f,
                    kInfinity};
        const Vec3 exact = hex3("0x1.1162e6p+3", "0x1.ad3de6p+1", "0x1.d2edb4p+3");
        const ModuleTable fast = engine_table(), slow = module_path_table();
        TraceCounters c;
        Hit hit;
        PrimRef p;
        fast.engine->closest_hit(s, r, c, hit, p);
        REQUIRE(p.kind == PrimRef::Kind::triangle);
        if (p.refined) CHECK(error_in_delta(hit.position, exact) <= 1.0f);
        const auto a = s.closest_hit(fast, r, c), b = s.closest_hit(slow, r, c);
        REQUIRE(a.has_value());
        REQUIRE(b.has_value());
        CHECK(error_in_delta(a->position, exact) <= 1.0f);
        CHECK(error_in_delta(b->position, exact) <= 1.0f);
        CHECK(max_abs(a->position - b->position) <= 0x1p-23f * max_abs(b->position));
    }
}
