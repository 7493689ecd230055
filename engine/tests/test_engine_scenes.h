// Scenes of many mixed primitives near a size limit of what the engine keeps (the face
// normals, the slot copy), the comparison of the engine with the module path on them,
// and the check of the slot copy: test_face_normals.cpp and test_slot_copy.cpp.
#pragma once

#include <cmath>
#include <vector>

#include "raylab/scene.h"
#include "engine_test_data.h"
#include "test_helpers.h"

namespace raylab {

// n triangles in [-10, 10]^3 (some tiny, some degenerate), a few spheres and a plane.
// Each entry of `targets` is a point on a non-degenerate triangle
inline Scene boundary_scene(std::uint64_t seed, int n, std::vector<Vec3>& targets) {
    Rng rng(seed);
    Scene scene;
    scene.materials.push_back(Material{"a", Vec3(0.5f), Vec3(0.0f)});
    scene.materials.push_back(Material{"b", Vec3(0.25f), Vec3(0.0f)});
    scene.planes.push_back({Plane{Vec3(0, 1, 0), 12.0f}, 1});
    for (int k = 0; k < 7; ++k)
        scene.spheres.push_back(
            {Sphere{rng.in_box(-10, 10), rng.uniform(0.05f, 1.0f)}, 1});
    for (int k = 0; k < n; ++k) {
        SceneTriangle t;
        t.v0 = rng.in_box(-10, 10);
        switch (k % 8) {
            case 0:  // collinear: v2 - v0 = 2 (v1 - v0), exact for dyadic values
                t.v0 = glm::floor(t.v0 * 64.0f) / 64.0f;
                t.v1 = t.v0 + Vec3(0.25f, -0.125f, 0.5f);
                t.v2 = t.v0 + Vec3(0.5f, -0.25f, 1.0f);
                break;
            case 1:  // repeated vertex
                t.v1 = t.v0;
                t.v2 = t.v0 + rng.in_box(-1, 1);
                break;
            case 2: {  // tiny: a few ulps of v0
                const float u = std::nextafter(t.v0.x, 100.0f) - t.v0.x;
                t.v1 = t.v0 + Vec3(3 * u, 0, 0);
                t.v2 = t.v0 + Vec3(0, 2 * u, u);
                break;
            }
            default:
                t.v1 = t.v0 + rng.in_box(-2, 2);
                t.v2 = t.v0 + rng.in_box(-2, 2);
        }
        t.material = k % 2;
        scene.triangles.push_back(t);
    }
    scene.commit();
    for (size_t k = 0; k < scene.triangles.size(); ++k) {
        if (engine_data(scene).degenerate(k)) continue;
        const SceneTriangle& t = scene.triangles[k];
        targets.push_back(t.v0 + 0.3f * (t.v1 - t.v0) + 0.3f * (t.v2 - t.v0));
    }
    return scene;
}

// Rays from random points at the targets (and random rays), both paths compared
inline void compare_paths(const Scene& scene, const std::vector<Vec3>& targets,
                          std::uint64_t seed, int rays) {
    const ModuleTable fast = engine_table(), slow = module_path_table();
    Rng rng(seed);
    TraceCounters cf, cs;
    int hits = 0;
    for (int k = 0; k < rays; ++k) {
        const Vec3 o = rng.in_box(-14, 14);
        const Vec3 w = k % 4 == 3
                           ? rng.direction()
                           : glm::normalize(targets[size_t(k) % targets.size()] - o);
        INFO("ray " << k);
        hits +=
            check_both_paths(scene, fast, slow, Ray{o, w, 0.0f, kInfinity}, rng, cf, cs);
    }
    CHECK(hits > rays / 2);
    CHECK(cf.intersection_tests == cs.intersection_tests);
    CHECK(cf.bvh_nodes == cs.bvh_nodes);
}

// Every slot holds, to the bit, the primitive the BVH puts there
inline void check_slots(const Scene& scene) {
    const SceneData::SlotPrimitive* slots = engine_data(scene).slot_primitives();
    REQUIRE(slots != nullptr);
    const std::vector<std::uint32_t>& order = scene.bvh().prims();
    const std::uint32_t spheres = static_cast<std::uint32_t>(scene.spheres.size());
    REQUIRE(order.size() == scene.spheres.size() + scene.triangles.size());
    for (size_t k = 0; k < order.size(); ++k) {
        INFO("slot " << k);
        const std::uint32_t p = order[k];
        const SceneData::SlotPrimitive& s = slots[k];
        CHECK((s.prim & SceneData::SlotPrimitive::kIndexMask) == p);
        if (p < spheres) {
            const Sphere& sphere = scene.spheres[p].sphere;
            CHECK((s.prim & SceneData::SlotPrimitive::kSphere) != 0);
            CHECK((s.prim & SceneData::SlotPrimitive::kDegenerate) == 0);
            CHECK(Vec3(s.a) == sphere.c);
            CHECK(float(s.b.x) == sphere.r);
            continue;
        }
        const SceneTriangle& t = scene.triangles[p - spheres];
        CHECK((s.prim & SceneData::SlotPrimitive::kSphere) == 0);
        CHECK(((s.prim & SceneData::SlotPrimitive::kDegenerate) != 0) ==
              engine_data(scene).degenerate(p - spheres));
        CHECK(Vec3(s.a) == t.v0);
        CHECK(Vec3(s.b) == t.v1);
        CHECK(Vec3(s.c) == t.v2);
    }
}

}  // namespace raylab
