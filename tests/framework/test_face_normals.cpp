// The triangle normals a scene keeps (Scene::face_normal, up to kFaceNormalsUpTo
// triangles), which the engine reads instead of computing them: the engine against the
// module path at the limit and one triangle above it, with degenerate, tiny and huge
// triangles, spheres and a plane mixed in, across re-commits, and on non-finite rays.
#include <doctest/doctest.h>

#include <cmath>

#include "raylab/engine.h"
#include "raylab/error.h"
#include "test_engine_scenes.h"
#include "test_helpers.h"

using namespace raylab;

TEST_SUITE("face normals") {
    TEST_CASE("engine and module path agree at kFaceNormalsUpTo and one triangle more") {
        const int limit = int(Scene::kFaceNormalsUpTo);
        for (int n : {limit, limit + 1}) {
            INFO("triangles " << n);
            std::vector<Vec3> targets;
            const Scene scene = boundary_scene(31, n, targets);
            CHECK(scene.has_face_normals() == (n <= limit));
            compare_paths(scene, targets, 7, 4000);
        }
    }

    TEST_CASE("face normals follow re-commits across the limit") {
        const int limit = int(Scene::kFaceNormalsUpTo);
        std::vector<Vec3> targets;
        Scene scene = boundary_scene(41, 600, targets);
        REQUIRE(scene.has_face_normals());
        // Above the limit: no normals kept
        std::vector<Vec3> more;
        const Scene big = boundary_scene(42, limit + 1, more);
        const size_t small_count = scene.triangles.size();
        scene.triangles.insert(scene.triangles.end(), big.triangles.begin(),
                               big.triangles.end());
        scene.commit();
        CHECK_FALSE(scene.has_face_normals());
        compare_paths(scene, targets, 8, 1500);
        // Back below, with the triangles' vertices reversed (every normal flips)
        scene.triangles.resize(small_count);
        for (SceneTriangle& t : scene.triangles)
            std::swap(t.v1, t.v2);
        scene.commit();
        CHECK(scene.has_face_normals());
        compare_paths(scene, targets, 9, 1500);
    }

    // Subnormal-sized and near-float-max triangles (their double cross products neither
    // underflow nor overflow), hit by axis-aligned rays; and rays with NaN or infinite
    // parts, which the scene's queries accept
    TEST_CASE("tiny, huge and non-finite cases agree on both paths") {
        const ModuleTable fast = engine_table(), slow = module_path_table();
        for (const float s : {0x1p-140f, 0x1p-126f, 1e-30f, 1.0f, 1e30f, 0x1p126f}) {
            INFO("scale " << s);
            Scene scene;
            scene.materials.push_back(Material{});
            scene.spheres.push_back({Sphere{Vec3(5.0f), 1.0f}, 0});
            scene.triangles.push_back({Vec3(0.0f), Vec3(s, 0, 0), Vec3(0, s, 0)});
            scene.triangles.push_back({Vec3(0.0f), Vec3(s, 0, s), Vec3(0, s, 0)});
            scene.triangles.push_back({Vec3(0.0f), Vec3(0, s, 0), Vec3(s, 0, 0)});
            scene.triangles.push_back({Vec3(0, 0, 0), Vec3(s, s, s), Vec3(s, s, s)});
            scene.commit();
            REQUIRE(scene.has_face_normals());
            int hits = 0;
            for (const Vec3& w :
                 {Vec3(0, 0, -1), Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0, -1, 0)}) {
                const Vec3 o = Vec3(0.25f * s, 0.25f * s, 0.125f * s) - 2.0f * s * w;
                const Ray r{o, w, 0.0f, kInfinity};
                INFO("ray " << r);
                TraceCounters cf, cs;
                const auto a = scene.closest_hit(fast, r, cf);
                check_same_hit(a, scene.closest_hit(slow, r, cs));
                CHECK(cf.intersection_tests == cs.intersection_tests);
                hits += a.has_value();
            }
            CHECK(hits >= 2);
        }
        const Scene box = [] {
            std::vector<Vec3> targets;
            return boundary_scene(5, 64, targets);
        }();
        const float nan = NAN, inf = kInfinity;
        for (const Ray& r : {Ray{Vec3(nan, 0, 0), Vec3(0, 0, -1), 0.0f, inf},
                             Ray{Vec3(0, 0, 20), Vec3(nan, 0, -1), 0.0f, inf},
                             Ray{Vec3(0, 0, 20), Vec3(0, 0, -1), nan, inf},
                             Ray{Vec3(0, 0, 20), Vec3(0, 0, -1), 0.0f, nan},
                             Ray{Vec3(0, 0, 20), Vec3(0, 0, -1), -inf, inf},
                             Ray{Vec3(0, 0, 20), Vec3(0, inf, -1), 0.0f, inf},
                             Ray{Vec3(0, 0, 20), Vec3(0, 0, -inf), 0.0f, inf},
                             Ray{Vec3(inf, 0, 20), Vec3(-1, 0, 0), 0.0f, inf},
                             Ray{Vec3(0, 0, 20), Vec3(0, 0, 0), 0.0f, inf}}) {
            INFO("ray " << r);
            TraceCounters cf, cs;
            check_same_hit(box.closest_hit(fast, r, cf), box.closest_hit(slow, r, cs));
            CHECK(box.any_hit(fast, r, cf) == box.any_hit(slow, r, cs));
            CHECK(cf.intersection_tests == cs.intersection_tests);
            CHECK(cf.bvh_nodes == cs.bvh_nodes);
        }
    }
}
