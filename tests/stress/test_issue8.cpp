// Regression tests for the numerical bugs of issue 8 (B1-B3, B6): the exact inputs that
// reproduced each one, through the bare kernel and through Scene.
#include <doctest/doctest.h>

#include "raylab/bvh.h"
#include "raylab/error.h"
#include "raylab/scene.h"
#include "test_helpers.h"

using namespace raylab;

namespace {

Scene one_material_scene() {
    Scene s;
    s.materials.push_back(Material{});
    return s;
}

bool scene_hits(const Scene& s, const Ray& r) {
    TraceCounters counters;
    return s.closest_hit(reference_modules(), r, counters).has_value();
}

}  // namespace

TEST_SUITE("stress issue 8") {
    TEST_CASE(
        "B1: a ray exactly through a shared vertex hits one of the fan's triangles") {
        const Vec3 v175(-0x1.48ac54p+0f, 0x1.2ec458p+0f, 0x1.eb851ep-2f);
        const Vec3 v176(-0x1.4a2ecap+0f, 0x1.2b0a36p+0f, 0x1.eb851ep-2f);
        const Vec3 v177(-0x1.4ba238p+0f, 0x1.274a2p+0f, 0x1.eb851ep-2f);
        const Vec3 top(-0x1.70a3d8p-2f, 0x1.99999ap-1f, 0x1.ae147ap+0f);
        const Vec3 bot(-0x1.70a3d8p-2f, 0x1.99999ap-1f, -0x1.70a3d8p-1f);
        const Vec3 tris[4][3] = {
            {v175, v176, top}, {v176, v177, top}, {v176, v175, bot}, {v177, v176, bot}};
        const Ray r{Vec3(-0x1.9a46f6p+1f, 0x1.96f784p+0f, 0x1.be1302p-1f),
                    Vec3(0x1.ea5f22p-1f, -0x1.afb538p-3f, -0x1.90a0e6p-3f), 0.0f,
                    kInfinity};
        int hits = 0;
        Scene scene = one_material_scene();
        for (const auto& t : tris) {
            if (reference::intersect_triangle(r, t[0], t[1], t[2])) ++hits;
            scene.triangles.push_back(SceneTriangle{t[0], t[1], t[2]});
        }
        scene.commit();
        CHECK(hits >= 1);
        CHECK(scene_hits(scene, r));
    }

    TEST_CASE("B2: a ray in a box face's plane along a +-0 component is not culled") {
        const Aabb box{Vec3(0.0f), Vec3(1.0f)};
        for (const float zero : {0.0f, -0.0f}) {
            for (const float x : {0.0f, 1.0f}) {
                const Ray r{Vec3(x, 0.5f, -1.0f), Vec3(zero, 0.0f, 1.0f), 0.0f,
                            kInfinity};
                INFO("x = " << x << ", w.x = " << zero);
                CHECK(box_entry(RaySlabs(r), box, r.tmin, r.tmax) == 1.0f);
                const Ray shadow{r.o, r.w, 1e-3f, 10.0f};
                CHECK(box_entry(RaySlabs(shadow), box, shadow.tmin, shadow.tmax) == 1.0f);
            }
        }
        // The quad x in [-1, 0], y in [-1, 1] at z = 0 seen from (0, 0, 3): the column
        // x = 0 lies in the box's face; every ray towards it must hit through the BVH
        Scene scene = one_material_scene();
        const Vec3 a(-1, -1, 0), b(0, -1, 0), c(0, 1, 0), d(-1, 1, 0);
        scene.triangles.push_back(SceneTriangle{a, b, c});
        scene.triangles.push_back(SceneTriangle{a, c, d});
        scene.commit();
        // Brute force (the kernel on both triangles) decides; the scene must agree
        int hits = 0, brute = 0;
        for (int k = 0; k <= 40; ++k) {
            const float y = -1.0f + k / 20.0f;
            const Ray r{Vec3(0, 0, 3), glm::normalize(Vec3(0.0f, y, -3.0f)), 0.0f,
                        kInfinity};
            const bool kernel = reference::intersect_triangle(r, a, b, c).has_value() ||
                                reference::intersect_triangle(r, a, c, d).has_value();
            if (kernel) ++brute;
            if (scene_hits(scene, r)) ++hits;
            CHECK(scene_hits(scene, r) == kernel);
        }
        CHECK(brute >= 39);  // the two corner rays may round outside the quad
        CHECK(hits == brute);
    }

    TEST_CASE(
        "B3: a small sphere far away is hit through the scene where the kernel hits") {
        const Sphere s{Vec3(70000.296875f, 0.0f, 0.0f), 0.3f};
        const Ray r{Vec3(0x1.117098p+16f, -5.0f, 0.0f),
                    Vec3(0x1.47ae14p-12f, 0x1.fffffep-1f, 0.0f), 0.0f, kInfinity};
        REQUIRE(reference::intersect_sphere(r, s));
        Scene scene = one_material_scene();
        scene.spheres.push_back(SceneSphere{s, 0});
        scene.commit();
        CHECK(scene_hits(scene, r));
        // The box holds the exact sphere: c + r and c - r rounded outwards
        const Aabb box = scene.bounds();
        CHECK(double(box.hi.x) >= double(s.c.x) + double(s.r));
        CHECK(double(box.lo.x) <= double(s.c.x) - double(s.r));
    }

    TEST_CASE("B6: spheres whose r^2 overflows or underflows are refused by name") {
        for (const float radius : {1.9e19f, 1e30f, 1e-40f, 1e-25f}) {
            Scene scene = one_material_scene();
            scene.spheres.push_back(SceneSphere{Sphere{Vec3(0.0f), radius}, 0});
            INFO("radius " << radius);
            CHECK_THROWS_WITH_AS(scene.commit(), doctest::Contains("sphere 0"), Error);
        }
    }

    TEST_CASE("B6: a nearly parallel ray never hits a plane at t = inf") {
        const Plane p{Vec3(0.0f, 1.0f, 0.0f), 0.0f};
        const Ray r{Vec3(0.0f, 1.0f, 0.0f), Vec3(1.0f, -1e-40f, 0.0f), 0.0f, kInfinity};
        const auto hit = reference::intersect_plane(r, p);
        CHECK((!hit || std::isfinite(hit->t)));
    }
}
