// Scene::commit() moves the triangles into the BVH's slot order (a leaf's triangles side
// by side in memory) and names each by the index it was added at (triangle_source).
#include <doctest/doctest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "raylab/error.h"
#include "raylab/refine.h"  // unit_normal
#include "test_helpers.h"

using namespace raylab;

namespace {

// n random triangles in [-10, 10]^3 with three materials, vertex normals and, every
// 50th, a degenerate one (two vertices the same); spheres first when asked. Not
// committed
Scene added_scene(int n, int spheres, std::uint64_t seed) {
    Rng rng(seed);
    Scene scene;
    for (const char* name : {"a", "b", "c"})
        scene.materials.push_back(Material{name, Vec3(0.5f), Vec3(0.0f)});
    for (int k = 0; k < spheres; ++k)
        scene.spheres.push_back(
            {Sphere{rng.in_box(-10, 10), rng.uniform(0.1f, 1.0f)}, 1});
    for (int k = 0; k < n; ++k) {
        SceneTriangle t;
        t.v0 = rng.in_box(-10, 10);
        t.v1 = t.v0 + rng.in_box(-2, 2);
        t.v2 = k % 50 == 0 ? t.v1 : t.v0 + rng.in_box(-2, 2);
        t.material = k % 3;
        scene.add_triangle(t, {rng.direction(), rng.direction(), rng.direction()});
    }
    return scene;
}

bool same(const SceneTriangle& a, const SceneTriangle& b) {
    return a.v0 == b.v0 && a.v1 == b.v1 && a.v2 == b.v2 && a.material == b.material;
}
bool same(const VertexNormals& a, const VertexNormals& b) {
    return a.n0 == b.n0 && a.n1 == b.n1 && a.n2 == b.n2;
}

// Every triangle of the committed scene is the one added at its source index, with its
// normals and flag; the sources name each added triangle once
void check_moved(const Scene& scene, const Scene& added) {
    const size_t n = added.triangles.size();
    REQUIRE(scene.triangles.size() == n);
    REQUIRE(scene.normals.size() == n);
    std::vector<int> seen(n, 0);
    for (size_t k = 0; k < n; ++k) {
        const size_t s = scene.triangle_source(k);
        INFO("triangle " << k << ", added as " << s);
        REQUIRE(s < n);
        ++seen[s];
        CHECK(same(scene.triangles[k], added.triangles[s]));
        CHECK(same(scene.normals[k], added.normals[s]));
        CHECK(scene.degenerate(k) == (s % 50 == 0));
        if (scene.has_face_normals())
            CHECK(scene.face_normal(k) == unit_normal(scene.triangles[k]));
    }
    CHECK(std::count(seen.begin(), seen.end(), 1) == static_cast<long>(n));
}

// The BVH's slots name the triangles in increasing order (the spheres keep theirs)
void check_slot_order(const Scene& scene) {
    const std::uint32_t spheres = static_cast<std::uint32_t>(scene.spheres.size());
    std::uint32_t next = spheres;
    std::vector<int> sphere_seen(spheres, 0);
    for (const std::uint32_t p : scene.bvh().prims()) {
        if (p < spheres) {
            ++sphere_seen[p];
        } else {
            CHECK(p == next);
            ++next;
        }
    }
    CHECK(next == spheres + scene.triangles.size());
    CHECK(std::count(sphere_seen.begin(), sphere_seen.end(), 1) ==
          static_cast<long>(spheres));
}

}  // namespace

TEST_SUITE("slot order") {
    TEST_CASE("commit() moves triangles, normals and flags into slot order") {
        // Small (the slot copy, face normals), large (neither), with spheres among them
        for (const auto& size : {std::pair{300, 0}, std::pair{300, 9},
                                 std::pair{int(Scene::kSlotCopyUpTo) + 100, 0},
                                 std::pair{int(Scene::kFaceNormalsUpTo) + 10, 5}}) {
            // Not a structured binding: clang's C++17 cannot capture one in INFO's lambda
            const int n = size.first, spheres = size.second;
            INFO(n << " triangles, " << spheres << " spheres");
            const Scene added = added_scene(n, spheres, 17 + n + spheres);
            Scene scene = added;
            scene.commit();
            check_moved(scene, added);
            check_slot_order(scene);
            if (spheres == 0) {
                // The engine reads slot s as triangle s: the BVH names it so
                for (size_t s = 0; s < scene.bvh().prims().size(); ++s)
                    REQUIRE(scene.bvh().prims()[s] == s);
            }
            // Random triangles seldom arrive in slot order: most of them moved
            size_t moved = 0;
            for (size_t k = 0; k < scene.triangles.size(); ++k)
                moved += scene.triangle_source(k) != k;
            CHECK(moved > scene.triangles.size() / 2);
            // Committed again, nothing moves and the sources stay
            Scene again = scene;
            again.commit();
            check_moved(again, added);
            for (size_t k = 0; k < scene.triangles.size(); ++k)
                REQUIRE(same(again.triangles[k], scene.triangles[k]));
        }
    }

    TEST_CASE("commit() twice moves nothing, also where centres coincide") {
        // 300 copies of one triangle (the build splits them by index) between spheres;
        // without the leaves' increasing order the second commit() moved triangles
        Scene scene;
        scene.materials.push_back(Material{});
        Rng rng(8);
        for (int k = 0; k < 300; ++k) {
            if (k % 30 == 0)
                scene.spheres.push_back({Sphere{rng.in_box(-3, 3), 0.5f}, 0});
            scene.triangles.push_back({Vec3(0.0f), Vec3(1, 0, 0), Vec3(0, 1, 0), 0});
            scene.triangles.back().material = 0;
        }
        scene.commit();
        check_slot_order(scene);
        Scene again = scene;
        again.commit();
        CHECK(again.bvh().prims() == scene.bvh().prims());
        for (size_t k = 0; k < scene.triangles.size(); ++k)
            CHECK(again.triangle_source(k) == scene.triangle_source(k));
    }

    TEST_CASE("the same hits as the triangles in the order they were added") {
        // A scene too large for the slot copy, without spheres, where the engine reads
        // triangles in slot order: both paths against every triangle tested as added
        const Scene added = added_scene(int(Scene::kSlotCopyUpTo) + 100, 0, 5);
        Scene scene = added;
        scene.commit();
        const ModuleTable fast = engine_table(), slow = module_path_table();
        const ModuleTable& m = slow;
        Rng rng(99);
        TraceCounters c;
        int hits = 0;
        for (int k = 0; k < 2000; ++k) {
            // At a triangle's vertex, edge midpoint or centre, or anywhere
            const SceneTriangle& t = added.triangles[rng.next() % added.triangles.size()];
            const Vec3 targets[] = {t.v0, 0.5f * (t.v1 + t.v2),
                                    (t.v0 + t.v1 + t.v2) / 3.0f, rng.in_box(-10, 10)};
            const Vec3 o = rng.in_box(-14, 14);
            const Vec3 d = targets[k % 4] - o;
            if (glm::dot(d, d) == 0.0f) continue;
            Ray r{o, glm::normalize(d), 0.0f, kInfinity};
            INFO("ray " << k << ": " << r);
            std::optional<Hit> truth;
            int material = -1;
            for (const SceneTriangle& u : added.triangles) {
                if (auto h = m.intersect_triangle(r, u.v0, u.v1, u.v2)) {
                    r.tmax = h->t, truth = h, material = u.material;
                }
            }
            r.tmax = kInfinity;
            for (const ModuleTable* table : {&fast, &slow}) {
                const std::optional<Hit> h = scene.closest_hit(*table, r, c);
                REQUIRE(h.has_value() == truth.has_value());
                CHECK(scene.any_hit(*table, r, c) == truth.has_value());
                if (!h) continue;
                CHECK(h->t == truth->t);
                CHECK(h->n == truth->n);
                CHECK(h->uv == truth->uv);
                CHECK(h->material == material);
            }
            hits += check_both_paths(scene, fast, slow, r, rng, c, c);
        }
        CHECK(hits > 1000);
    }

    TEST_CASE(
        "triangles added after a commit() keep their index; messages name sources") {
        const Scene added = added_scene(200, 0, 3);
        Scene scene = added;
        scene.commit();
        // One more, added at index 200: it keeps that name through the next commit()
        SceneTriangle extra{Vec3(20.0f), Vec3(21.0f, 20.0f, 20.0f),
                            Vec3(20.0f, 21.0f, 20.0f), 2};
        scene.add_triangle(extra, {Vec3(0, 0, 1), Vec3(0, 0, 1), Vec3(0, 0, 1)});
        CHECK(scene.triangle_source(200) == 200);
        scene.commit();
        check_slot_order(scene);
        size_t at = 0;
        while (scene.triangle_source(at) != 200)
            ++at;
        CHECK(same(scene.triangles[at], extra));
        // A bad triangle is named by the index it was added at, wherever it now is
        size_t seventh = 0;
        while (scene.triangle_source(seventh) != 7)
            ++seventh;
        REQUIRE(seventh != 7);  // moved, or the message could not tell the names apart
        const std::vector<SceneTriangle> before = scene.triangles;
        scene.triangles[seventh].v2 = Vec3(NAN);
        CHECK_THROWS_WITH_AS(
            scene.commit(), doctest::Contains("triangle 7: vertex is not finite"), Error);
        // A commit() that throws moves nothing
        for (size_t k = 0; k < before.size(); ++k)
            if (k != seventh) REQUIRE(same(scene.triangles[k], before[k]));
        scene.normals[seventh].n1 = Vec3(kInfinity);
        scene.triangles[seventh].v2 = before[seventh].v2;
        CHECK_THROWS_WITH_AS(scene.commit(),
                             doctest::Contains("triangle 7: vertex normal is not finite"),
                             Error);
        // Fewer triangles than were committed: the rest keep their names
        scene.normals[seventh].n1 = Vec3(0, 0, 1);
        scene.triangles.resize(100);
        scene.normals.resize(100);
        std::vector<size_t> sources;
        for (size_t k = 0; k < 100; ++k)
            sources.push_back(scene.triangle_source(k));
        scene.commit();
        check_slot_order(scene);
        for (size_t k = 0; k < 100; ++k)
            CHECK(std::count(sources.begin(), sources.end(), scene.triangle_source(k)) ==
                  1);
    }
}
