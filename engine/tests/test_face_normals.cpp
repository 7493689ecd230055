// The triangle normals the engine prepares for a scene (SceneData::face_normal, up to
// kFaceNormalsUpTo triangles), which the engine reads instead of computing them: the
// engine against the module path at the limit and one triangle above it, with degenerate,
// tiny and huge triangles, spheres and a plane mixed in, across re-commits, and on
// non-finite rays.
#include <doctest/doctest.h>

#include <cmath>

#include "raylab/engine.h"
#include "raylab/error.h"
#include "test_engine_scenes.h"
#include "engine_test_data.h"
#include "test_helpers.h"

using namespace raylab;

namespace {

// The triangle's unit normal, (v1 - v0) x (v2 - v0) normalised
Vec3 face_normal(const SceneTriangle& t) {
    return glm::normalize(glm::cross(t.v1 - t.v0, t.v2 - t.v0));
}

// Random triangles in [-10, 10]^3
Scene random_scene(std::uint64_t seed, int triangles) {
    Rng rng(seed);
    Scene scene;
    scene.materials.push_back(Material{"grey", Vec3(0.5f), Vec3(0.0f)});
    for (int k = 0; k < triangles; ++k) {
        SceneTriangle t;
        t.v0 = rng.in_box(-10, 10);
        t.v1 = t.v0 + rng.in_box(-2, 2);
        t.v2 = t.v0 + rng.in_box(-2, 2);
        scene.triangles.push_back(t);
    }
    scene.commit();
    return scene;
}

}  // namespace

TEST_SUITE("face normals") {
    TEST_CASE("engine and module path agree at kFaceNormalsUpTo and one triangle more") {
        const int limit = int(SceneData::kFaceNormalsUpTo);
        for (int n : {limit, limit + 1}) {
            INFO("triangles " << n);
            std::vector<Vec3> targets;
            const Scene scene = boundary_scene(31, n, targets);
            CHECK(engine_data(scene).has_face_normals() == (n <= limit));
            compare_paths(scene, targets, 7, 4000);
        }
    }

    TEST_CASE("face normals follow re-commits across the limit") {
        const int limit = int(SceneData::kFaceNormalsUpTo);
        std::vector<Vec3> targets;
        Scene scene = boundary_scene(41, 600, targets);
        REQUIRE(engine_data(scene).has_face_normals());
        // Above the limit: no normals kept
        std::vector<Vec3> more;
        const Scene big = boundary_scene(42, limit + 1, more);
        const size_t small_count = scene.triangles.size();
        scene.triangles.insert(scene.triangles.end(), big.triangles.begin(),
                               big.triangles.end());
        scene.commit();
        CHECK_FALSE(engine_data(scene).has_face_normals());
        compare_paths(scene, targets, 8, 1500);
        // Back below, with the triangles' vertices reversed (every normal flips)
        scene.triangles.resize(small_count);
        for (SceneTriangle& t : scene.triangles)
            std::swap(t.v1, t.v2);
        scene.commit();
        CHECK(engine_data(scene).has_face_normals());
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
            REQUIRE(engine_data(scene).has_face_normals());
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

    TEST_CASE("the engine keeps the module's triangle normals in small scenes only") {
        // Small: every normal as the reference module returns it, bit for bit (the
        // engine reads them instead), and zero for a degenerate triangle
        Scene small = random_scene(5, 300);
        small.triangles.push_back({Vec3(1.0f), Vec3(2.0f), Vec3(3.0f), 0});  // collinear
        small.commit();
        REQUIRE(engine_data(small).has_face_normals());
        const ModuleTable& m = reference_modules();
        int compared = 0;
        for (size_t k = 0; k < small.triangles.size(); ++k) {
            const SceneTriangle& t = small.triangles[k];
            if (engine_data(small).degenerate(k)) {
                CHECK(engine_data(small).face_normal(k) == Vec3(0.0f));
                continue;
            }
            // A ray at the centroid along the normal's reverse meets the triangle
            const Vec3 c = (t.v0 + t.v1 + t.v2) / 3.0f, n = face_normal(t);
            const auto hit =
                m.intersect_triangle(Ray{c + n, -n, 0.0f, kInfinity}, t.v0, t.v1, t.v2);
            if (!hit) continue;
            CHECK(engine_data(small).face_normal(k) == hit->n);
            ++compared;
        }
        // The collinear triangle, added 301st, wherever commit() has moved it
        size_t collinear = 0;
        while (small.triangle_source(collinear) != 300)
            ++collinear;
        CHECK(engine_data(small).degenerate(collinear));
        CHECK(compared > 250);
        // BVH, source indices, flags, normals and the slot copy
        const size_t n = small.triangles.size(), flags = (n + 7) / 8;
        CHECK(small.acceleration_bytes() == small.bvh().bytes() + 4 * n + flags + 12 * n +
                                                sizeof(SceneData::SlotPrimitive) * n);
        // Large: none kept (the array would miss the cache), and no bytes counted
        const Scene large = random_scene(6, int(SceneData::kFaceNormalsUpTo) + 1);
        CHECK_FALSE(engine_data(large).has_face_normals());
        CHECK(engine_data(random_scene(6, int(SceneData::kFaceNormalsUpTo)))
                  .has_face_normals());
        CHECK(large.acceleration_bytes() <=
              large.bvh().bytes() + 5 * large.triangles.size());
    }
}
