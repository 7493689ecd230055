// The copy of a small scene's primitives in BVH slot order (SceneData::slot_primitives,
// up to kSlotCopyUpTo spheres and triangles), which the engine's single-ray queries read
// instead of going through the primitive order: what it holds, the engine against the
// module path at the limit and one primitive above it, and across re-commits that move,
// flip, flatten and add primitives.
#include <doctest/doctest.h>

#include <cstdlib>
#include <cstring>
#include <string>

#include "raylab/engine.h"
#include "raylab/error.h"
#include "test_engine_scenes.h"
#include "engine_cases.h"
#include "test_helpers.h"

using namespace raylab;
using namespace raylab::engine_cases;

TEST_SUITE("slot copy") {
    TEST_CASE("the copy holds each slot's primitive, flags included") {
        std::vector<Vec3> targets;
        const Scene scene = boundary_scene(51, 300, targets);
        check_slots(scene);
        CHECK(scene.acceleration_bytes() ==
              scene.bvh().bytes() + 4 * scene.triangles.size() +
                  (scene.triangles.size() + 7) / 8 +
                  sizeof(Vec3) * scene.triangles.size() +
                  sizeof(Slot) * (scene.spheres.size() + scene.triangles.size()));
        // The flags stay clear of every index the BVH can name
        CHECK(Slot::kIndexMask >= Bvh::kFirstMask);
    }

    TEST_CASE("engine and module path agree at kSlotCopyUpTo primitives and one more") {
        // boundary_scene has 7 spheres besides its triangles; the limit counts both
        const int limit = int(SceneData::kSlotCopyUpTo);
        for (int n : {limit - 7, limit - 6}) {
            INFO("triangles " << n);
            std::vector<Vec3> targets;
            const Scene scene = boundary_scene(61, n, targets);
            CHECK((engine_data(scene).slot_primitives() != nullptr) == (n <= limit - 7));
            compare_paths(scene, targets, 17, 3000);
        }
        // Spheres alone over the limit
        Scene spheres;
        spheres.materials.push_back(Material{});
        Rng rng(3);
        for (int k = 0; k <= limit; ++k)
            spheres.spheres.push_back({Sphere{rng.in_box(-10, 10), 0.2f}, 0});
        spheres.commit();
        CHECK(engine_data(spheres).slot_primitives() == nullptr);
        spheres.spheres.pop_back();
        spheres.commit();
        check_slots(spheres);
    }

    TEST_CASE("the copy follows re-commits") {
        std::vector<Vec3> targets;
        Scene scene = boundary_scene(71, 400, targets);
        compare_paths(scene, targets, 18, 1500);
        // Every triangle moved and flipped, every sphere moved and grown, some triangles
        // made degenerate and one made whole again: a stale copy would hit the old ones
        for (size_t k = 0; k < scene.triangles.size(); ++k) {
            SceneTriangle& t = scene.triangles[k];
            std::swap(t.v1, t.v2);
            t.v0 += Vec3(0.5f, -0.25f, 0.125f), t.v1 += Vec3(0.5f, -0.25f, 0.125f),
                t.v2 += Vec3(0.5f, -0.25f, 0.125f);
            if (k % 16 == 5) t.v2 = t.v1;
        }
        for (SceneSphere& s : scene.spheres) {
            s.sphere.c += Vec3(-1.0f, 0.5f, 0.0f);
            s.sphere.r *= 1.5f;
        }
        scene.commit();
        check_slots(scene);
        std::vector<Vec3> moved;
        for (size_t k = 0; k < scene.triangles.size(); ++k) {
            if (engine_data(scene).degenerate(k)) continue;
            const SceneTriangle& t = scene.triangles[k];
            moved.push_back(t.v0 + 0.3f * (t.v1 - t.v0) + 0.3f * (t.v2 - t.v0));
        }
        compare_paths(scene, moved, 19, 1500);
        // A commit that throws keeps the last good copy, and the queries take the module
        // path until a commit succeeds (the engine would read the copy's old vertices)
        scene.triangles[3].v0 += Vec3(3.0f);
        scene.spheres[0].sphere.r = -1.0f;
        CHECK_THROWS_AS(scene.commit(), Error);
        CHECK_FALSE(scene.traces_packets(engine_table()));
        scene.spheres[0].sphere.r = 1.0f;
        scene.commit();
        check_slots(scene);
        compare_paths(scene, moved, 20, 1500);
    }
}

TEST_SUITE("slot copy") {
    // Per-ray counters, and rays on the BVH's planes with +-0 and denormal direction
    // components, negative tmin, tmax = 0, tmin = tmax
    TEST_CASE("rays on box planes with zero components, both paths, per ray") {
        for (const bool spheres : {false, true}) {
            INFO("spheres " << spheres);
            const Scene scene = lattice_scene(8, spheres);
            REQUIRE(engine_data(scene).slot_primitives() != nullptr);
            check_rays(scene, lattice_rays(8));
        }
    }

    TEST_CASE("rays through shared vertices and edges of the lattice") {
        const Scene scene = lattice_scene(6, false);
        std::vector<Ray> rays;
        // From outside through lattice points (vertices of up to 8 cubes) and through
        // edge midpoints, in directions whose components are 0, +-1 and +-1/2
        for (int x = -3; x <= 3; ++x)
            for (int y = -3; y <= 3; ++y) {
                for (const Vec3 w :
                     {Vec3(0, 0, -1), Vec3(0.5f, 0.5f, -1), Vec3(-1, 1, -1),
                      Vec3(1, 0, -1), Vec3(0.0f, -0.0f, 1)}) {
                    const Vec3 through(float(x), float(y), 0.0f);
                    const Vec3 mid(x + 0.5f, float(y), 1.0f);
                    rays.push_back(Ray{through - 10.0f * w, w, 0.0f, kInfinity});
                    rays.push_back(
                        Ray{through - 10.0f * w, glm::normalize(w), 0.0f, kInfinity});
                    rays.push_back(Ray{mid - 10.0f * w, w, 0.0f, kInfinity});
                    // starting on the vertex itself
                    rays.push_back(Ray{through, w, 0.0f, kInfinity});
                    rays.push_back(Ray{through, w, 1e-4f, kInfinity});
                }
            }
        check_rays(scene, rays);
    }

    // Spheres only and triangles only at the limit and over it
    // (test_slot_copy.cpp's scenes always mix 7 spheres in), each with counters per ray
    TEST_CASE("spheres only and triangles only at kSlotCopyUpTo and one more") {
        const int limit = int(SceneData::kSlotCopyUpTo);
        for (const int n : {limit, limit + 1}) {
            INFO("primitives " << n);
            const Scene s = sphere_scene(n, 7);
            CHECK((engine_data(s).slot_primitives() != nullptr) == (n <= limit));
            if (engine_data(s).slot_primitives()) check_slots(s);
            check_rays(s, rays_at(s, 8, 600));
            const Scene t = triangle_scene(n, 9);
            CHECK((engine_data(t).slot_primitives() != nullptr) == (n <= limit));
            if (engine_data(t).slot_primitives()) check_slots(t);
            check_rays(t, rays_at(t, 10, 600));
        }
    }

    // Re-commits that cross the limit both ways, and a commit that
    // throws while crossing it
    TEST_CASE("re-commits across the limit, and a failed commit across it") {
        const int limit = int(SceneData::kSlotCopyUpTo);
        Scene scene = triangle_scene(limit - 1, 11);
        REQUIRE(engine_data(scene).slot_primitives() != nullptr);
        const ModuleTable fast = engine_table();
        // Grow over: no copy
        scene.spheres.push_back({Sphere{Vec3(0.5f), 0.75f}, 1});
        scene.spheres.push_back({Sphere{Vec3(-0.5f), 0.75f}, 0});
        scene.commit();
        CHECK(engine_data(scene).slot_primitives() == nullptr);
        check_rays(scene, rays_at(scene, 12, 300));
        // Shrink back to exactly the limit: a copy again, and the spheres are in it
        scene.triangles.pop_back();
        scene.commit();
        REQUIRE(engine_data(scene).slot_primitives() != nullptr);
        check_slots(scene);
        check_rays(scene, rays_at(scene, 13, 300));
        // A commit that throws after growing over the limit and moving every triangle:
        // the module path, never the old copy
        for (SceneTriangle& t : scene.triangles)
            t.v0 += Vec3(0.25f), t.v1 += Vec3(0.25f), t.v2 += Vec3(0.25f);
        scene.triangles.push_back(
            SceneTriangle{Vec3(0), Vec3(1, 0, 0), Vec3(0, 1, 0), 7});
        CHECK_THROWS_AS(scene.commit(), Error);
        CHECK_FALSE(scene.traces_packets(fast));
        scene.triangles.back().material = 0;
        scene.commit();
        CHECK(engine_data(scene).slot_primitives() == nullptr);
        CHECK(scene.traces_packets(fast));
        check_rays(scene, rays_at(scene, 14, 300));
        // and back under it, through a failed commit again
        scene.triangles.resize(size_t(limit) - 10);
        scene.spheres[0].sphere.r = kNaN;
        CHECK_THROWS_AS(scene.commit(), Error);
        CHECK_FALSE(scene.traces_packets(fast));
        check_rays(scene, rays_at(scene, 15, 100));  // both on the module path
        scene.spheres[0].sphere.r = 0.5f;
        scene.commit();
        REQUIRE(engine_data(scene).slot_primitives() != nullptr);
        check_slots(scene);
        check_rays(scene, rays_at(scene, 16, 300));
    }

    // A copied or moved scene reads its own copy
    TEST_CASE("copied and moved scenes read their own slot copy") {
        std::vector<Vec3> targets;
        Scene original = boundary_scene(81, 200, targets);
        Scene copy = original;
        REQUIRE(engine_data(copy).slot_primitives() != nullptr);
        // The copy shares the engine's data, which nothing changes, until one of the two
        // is committed again
        CHECK(engine_data(copy).slot_primitives() ==
              engine_data(original).slot_primitives());
        check_slots(copy);
        // The original changes (and is re-committed); the copy must not see it
        for (SceneTriangle& t : original.triangles)
            std::swap(t.v0, t.v1);
        for (SceneSphere& s : original.spheres)
            s.sphere.c += Vec3(2.0f);
        original.commit();
        CHECK(engine_data(copy).slot_primitives() !=
              engine_data(original).slot_primitives());
        check_slots(copy);
        check_slots(original);
        compare_paths(copy, targets, 82, 400);
        // Moved: the new scene has the data; a scene assigned over keeps no stale copy
        const Slot* before = engine_data(copy).slot_primitives();
        Scene moved = std::move(copy);
        CHECK(engine_data(moved).slot_primitives() == before);
        check_slots(moved);
        compare_paths(moved, targets, 83, 400);
        Scene big = triangle_scene(int(SceneData::kSlotCopyUpTo) + 5, 84);
        REQUIRE(engine_data(big).slot_primitives() == nullptr);
        moved = big;  // copy-assigned from a scene with no copy
        CHECK(engine_data(moved).slot_primitives() == nullptr);
        check_rays(moved, rays_at(moved, 85, 200));
        big = original;  // and from one with a copy
        check_slots(big);
        check_rays(big, rays_at(big, 86, 200));
    }

    // A triangle flat at one commit and whole at the next, and the
    // reverse, in one scene, at the same slot; a flat triangle that a ray hits exactly
    TEST_CASE("degenerate flags follow re-commits, both ways") {
        Scene scene;
        scene.materials.push_back(Material{});
        // Two triangles in the plane z = 0 and a collinear one across them
        scene.triangles.push_back({Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(0, 1, 0), 0});
        scene.triangles.push_back({Vec3(-1, -1, 0), Vec3(0, 0, 0), Vec3(1, 1, 0), 0});
        scene.triangles.push_back({Vec3(2, 2, 1), Vec3(3, 2, 1), Vec3(2, 3, 1), 0});
        for (int k = 0; k < 40; ++k)  // enough for interior nodes
            scene.triangles.push_back(
                {Vec3(5.0f + k, 5, 5), Vec3(6.0f + k, 5, 5), Vec3(5.0f + k, 6, 5), 0});
        std::vector<Ray> rays;
        Rng rng(91);
        for (int k = 0; k < 300; ++k) {
            const Vec3 at = rng.in_box(-1.2f, 3.2f) * Vec3(1, 1, 0) + Vec3(0, 0, k % 2);
            rays.push_back(Ray{at + Vec3(0, 0, 4), Vec3(0, 0, -1), 0.0f, kInfinity});
            rays.push_back(Ray{at - Vec3(0, 0, 4), Vec3(0, 0, 1), 0.0f, kInfinity});
        }
        for (int round = 0; round < 4; ++round) {
            INFO("round " << round);
            scene.commit();
            CHECK(engine_data(scene).degenerate(1) == (round % 2 == 0));
            CHECK(engine_data(scene).degenerate(2) == (round % 2 == 1));
            check_slots(scene);
            check_rays(scene, rays);
            // Flip: 1 whole, 2 flat (collinear along x = y), and back
            if (round % 2 == 0) {
                scene.triangles[1].v2 = Vec3(1, 0, 0);
                scene.triangles[2].v2 = Vec3(4, 2, 1);
            } else {
                scene.triangles[1].v2 = Vec3(1, 1, 0);
                scene.triangles[2].v2 = Vec3(2, 3, 1);
            }
        }
    }

    // Spheres at the radii commit() still accepts
    TEST_CASE("spheres with extreme radii") {
        Scene scene;
        scene.materials.push_back(Material{});
        scene.spheres.push_back({Sphere{Vec3(0.0f), 1.2e-19f}, 0});
        scene.spheres.push_back({Sphere{Vec3(1.0f, 0, 0), 3e-19f}, 0});
        scene.spheres.push_back({Sphere{Vec3(0, 0, -3e19f), 1e19f}, 0});
        scene.spheres.push_back({Sphere{Vec3(1e19f, 0, 0), 1e18f}, 0});
        for (int k = 0; k < 60; ++k)
            scene.spheres.push_back({Sphere{Vec3(float(k), 2, 0), 0.4f}, 0});
        scene.commit();
        REQUIRE(engine_data(scene).slot_primitives() != nullptr);
        check_slots(scene);
        std::vector<Ray> rays;
        for (const Vec3 o : {Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0.0f), Vec3(1e-19f, 0, 1),
                             Vec3(0, 0, -2e19f), Vec3(1e19f, 0, 2e18f)}) {
            for (const Vec3 w : {Vec3(0, 0, -1), Vec3(0, 0, 1), Vec3(1, 0, 0),
                                 Vec3(-0.0f, 0.0f, -1.0f)}) {
                rays.push_back(Ray{o, w, 0.0f, kInfinity});
                rays.push_back(Ray{o, w, -kInfinity, kInfinity});
                rays.push_back(Ray{o, w, 1e-20f, 1e20f});
            }
        }
        check_rays(scene, rays);
    }

    // Scenes of 0 to 9 spheres and triangles (no BVH, a root that
    // is one leaf, a root node), with and without a plane, on rays along the axes
    TEST_CASE("empty and tiny scenes") {
        for (int n = 0; n <= 9; ++n) {
            for (const bool plane : {false, true}) {
                INFO("primitives " << n << ", plane " << plane);
                Scene scene;
                scene.materials.push_back(Material{});
                if (plane) scene.planes.push_back({Plane{Vec3(0, 0, 1), 3.0f}, 0});
                for (int k = 0; k < n; ++k) {
                    const Vec3 c(float(k % 3) - 1.0f, float(k / 3) - 1.0f, 0.0f);
                    if (k % 2)
                        scene.spheres.push_back({Sphere{c, 0.5f}, 0});
                    else
                        scene.triangles.push_back({c - Vec3(0.5f, 0.5f, 0),
                                                   c + Vec3(0.5f, -0.5f, 0),
                                                   c + Vec3(0, 0.5f, 0), 0});
                }
                scene.commit();
                CHECK((engine_data(scene).slot_primitives() != nullptr) == (n > 0));
                if (n > 0) check_slots(scene);
                std::vector<Ray> rays;
                for (int i = -3; i <= 3; ++i)
                    for (int j = -3; j <= 3; ++j) {
                        const Vec3 o(i * 0.5f, j * 0.5f, 5.0f);
                        rays.push_back(Ray{o, Vec3(0, 0, -1), 0.0f, kInfinity});
                        rays.push_back(Ray{o, Vec3(-0.0f, 0.0f, -1), -kInfinity, 0.0f});
                        rays.push_back(
                            Ray{Vec3(o.x, o.y, 0), Vec3(1, 0, 0), 0, kInfinity});
                        rays.push_back(Ray{Vec3(o.x, o.y, 0), Vec3(0, -1, -0.0f), 0, 2});
                    }
                check_rays(scene, rays);
            }
        }
    }

    // Closest_hits (packets, whose rays fall back to the single-ray
    // query on ties) at and just over the limit, on spheres and triangles
    TEST_CASE("packets at the limit agree with the single-ray query") {
        const int limit = int(SceneData::kSlotCopyUpTo);
        for (const int n : {limit, limit + 1}) {
            INFO("primitives " << n);
            const Scene s = triangle_scene(n, 21);
            Scene v = s;
            v.view.eye = Vec3(0, 0, 14);
            v.view.lookat = Vec3(0.0f);
            TraceCounters c;
            CHECK(check_packets(v, camera_blocks(v.view, 32, 32), c) > 100);
        }
    }
}

TEST_SUITE("engine versions") {
    // The engine's versions as engine_simd.h chooses them: on x86-64 built for the
    // baseline, AVX-512 (x86-64-v4's subsets) where the processor has it unless
    // RAYLAB_NO_AVX512 or RAYLAB_NO_AVX2 is set, AVX2 where it has that unless
    // RAYLAB_NO_AVX2 is set (the ctest runs engine/engine-avx2-versions and
    // engine-baseline-versions set them), else the build's own
    TEST_CASE("the engine names the versions it runs") {
        const std::string versions = reference::geometry_engine()->versions;
#if defined(__x86_64__) && !defined(__AVX2__) && !defined(RAYLAB_NO_SIMD)
        const bool avx2 =
            __builtin_cpu_supports("avx2") && std::getenv("RAYLAB_NO_AVX2") == nullptr;
        const bool avx512 =
            avx2 && __builtin_cpu_supports("avx512f") &&
            __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw") &&
            __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512cd") &&
            std::getenv("RAYLAB_NO_AVX512") == nullptr;
        CHECK(versions == (avx512 ? "avx512" : avx2 ? "avx2" : "baseline"));
#else
        CHECK(versions == "native");
#endif
    }
}
