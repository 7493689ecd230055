// The copy of a small scene's primitives in BVH slot order (Scene::slot_primitives, up to
// kSlotCopyUpTo spheres and triangles), which the engine's single-ray queries read
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
#include "test_helpers.h"

using namespace raylab;

using Slot = Scene::SlotPrimitive;

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
        const int limit = int(Scene::kSlotCopyUpTo);
        for (int n : {limit - 7, limit - 6}) {
            INFO("triangles " << n);
            std::vector<Vec3> targets;
            const Scene scene = boundary_scene(61, n, targets);
            CHECK((scene.slot_primitives() != nullptr) == (n <= limit - 7));
            compare_paths(scene, targets, 17, 3000);
        }
        // Spheres alone over the limit
        Scene spheres;
        spheres.materials.push_back(Material{});
        Rng rng(3);
        for (int k = 0; k <= limit; ++k)
            spheres.spheres.push_back({Sphere{rng.in_box(-10, 10), 0.2f}, 0});
        spheres.commit();
        CHECK(spheres.slot_primitives() == nullptr);
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
            if (scene.degenerate(k)) continue;
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

TEST_SUITE("engine versions") {
    // The engine's versions as solutions/engine_simd.h chooses them: on x86-64 built for
    // the baseline, AVX-512 (x86-64-v4's subsets) where the processor has it unless
    // RAYLAB_NO_AVX512 or RAYLAB_NO_AVX2 is set, AVX2 where it has that unless
    // RAYLAB_NO_AVX2 is set (the ctest runs framework/engine-avx2-versions and
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
