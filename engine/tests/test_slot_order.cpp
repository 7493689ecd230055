// Scene::commit() moves the triangles into the BVH's slot order (a leaf's triangles side
// by side in memory, which the engine reads without the primitive order: its
// SlotOrderTriangles) and names each by the index it was added at (triangle_source).
// Then every query against brute force, and the triangles' names through edits, failed
// commits and the probe.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "engine_test_data.h"
#include "raylab/error.h"
#include "raylab/refine.h"  // unit_normal
#include "raylab/renderer.h"
#include "test_helpers.h"

using namespace raylab;

namespace raylab {
// The scene's test hook (raylab/scene.h): its count of names, set near its end
struct SceneTestAccess {
    static void set_next_source(Scene& s, std::uint32_t next) { s.next_source_ = next; }
};
}  // namespace raylab

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
        CHECK(engine_data(scene).degenerate(k) == (s % 50 == 0));
        if (engine_data(scene).has_face_normals())
            CHECK(engine_data(scene).face_normal(k) == unit_normal(scene.triangles[k]));
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
                                 std::pair{int(SceneData::kSlotCopyUpTo) + 100, 0},
                                 std::pair{int(SceneData::kFaceNormalsUpTo) + 10, 5}}) {
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
        const Scene added = added_scene(int(SceneData::kSlotCopyUpTo) + 100, 0, 5);
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

// ---- Against brute force, through edits and failed commits ----------------------------

namespace against_brute_force {

namespace {

const size_t kCopy = SceneData::kSlotCopyUpTo;

// Bit for bit (a NaN vertex is the same as itself)
template <class T>
bool same(const T& a, const T& b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

SceneTriangle random_triangle(Rng& rng, float scale, int material) {
    SceneTriangle t;
    t.v0 = rng.in_box(-10, 10) * scale;
    t.v1 = t.v0 + rng.in_box(-2, 2) * scale;
    t.v2 = t.v0 + rng.in_box(-2, 2) * scale;
    t.material = material;
    return t;
}

// n random triangles with vertex normals, every 37th degenerate, every 41st a copy of
// the one before in another material (exact ties); spheres first; mixed: the triangles
// scaled by 1e-20, 1 and 1e20 in turn (the SAH's depth limit, then split by index). Not
// committed
Scene soup(int n, int spheres, std::uint64_t seed, bool mixed = false) {
    Rng rng(seed);
    Scene scene;
    scene.materials = {Material{}, Material{}, Material{}};
    for (int k = 0; k < spheres; ++k)
        scene.spheres.push_back(
            {Sphere{rng.in_box(-10, 10), rng.uniform(0.2f, 1.5f)}, 1});
    for (int k = 0; k < n; ++k) {
        const float scale = !mixed || k % 3 == 1 ? 1.0f : k % 3 ? 1e20f : 1e-20f;
        SceneTriangle t = random_triangle(rng, scale, k % 3);
        if (k % 37 == 5) t.v2 = 0.5f * (t.v0 + t.v1);
        if (k % 41 == 40) t = scene.triangles.back(), t.material = (t.material + 1) % 3;
        scene.add_triangle(t, {rng.direction(), rng.direction(), rng.direction()});
    }
    return scene;
}

// The nearest hit on r, every primitive tested by the reference's modules; ties: how
// many primitives are hit at its t
struct Truth {
    std::optional<Hit> hit;
    int material = -1, ties = 0;
};
Truth brute(const Scene& s, const Ray& r) {
    static const ModuleTable m = module_path_table();
    Ray q = r;
    Truth out;
    const auto keep = [&](const std::optional<Hit>& h, int material) {
        if (h && out.hit && h->t == out.hit->t) ++out.ties;
        if (!h || (out.hit && h->t == out.hit->t)) return;
        out.hit = h, out.material = material, out.ties = 1, q.tmax = h->t;
    };
    for (const ScenePlane& p : s.planes)
        keep(m.intersect_plane(q, p.plane), p.material);
    for (const SceneSphere& sp : s.spheres)
        keep(m.intersect_sphere(q, sp.sphere), sp.material);
    for (const SceneTriangle& t : s.triangles)
        keep(m.intersect_triangle(q, t.v0, t.v1, t.v2), t.material);
    return out;
}

// r on the engine and on the module path against brute force: closest hit (t; with no
// tie material, normal and uv), the same work counted, any hit with and without a hint
// (the same answer, the same slot left in the hint, and that slot's triangle blocks r)
int check_query(const Scene& scene, const Ray& r, AnyHitHint& shared) {
    static const ModuleTable fast = engine_table(), slow = module_path_table();
    INFO("ray " << r);
    TraceCounters cf, cs;
    const Truth truth = brute(scene, r);
    const std::optional<Hit> a = scene.closest_hit(fast, r, cf);
    check_same_hit(a, scene.closest_hit(slow, r, cs));
    CHECK(cf.intersection_tests == cs.intersection_tests);
    CHECK(cf.bvh_nodes == cs.bvh_nodes);
    REQUIRE(a.has_value() == truth.hit.has_value());
    if (a) {
        CHECK(a->t == truth.hit->t);
        if (truth.ties == 1) CHECK(a->material == truth.material);
        if (truth.ties == 1 && scene.spheres.empty()) {  // (a sphere's n is refined)
            CHECK(a->n == truth.hit->n);
            CHECK(a->uv == truth.hit->uv);
        }
    }
    CHECK(scene.any_hit(fast, r, cf) == a.has_value());
    CHECK(scene.any_hit(slow, r, cs) == a.has_value());
    AnyHitHint hf = shared, hs = shared;
    CHECK(scene.any_hit(fast, r, cf, &hf) == a.has_value());
    CHECK(scene.any_hit(slow, r, cs, &hs) == a.has_value());
    CHECK(hf.slot == hs.slot);
    if (hf.slot == AnyHitHint::kNone) return a.has_value();
    const size_t p = scene.bvh().prims().at(hf.slot), spheres = scene.spheres.size();
    if (p >= spheres) {
        const SceneTriangle& t = scene.triangles.at(p - spheres);
        CHECK(slow.intersect_triangle(r, t.v0, t.v1, t.v2).has_value());
    }
    shared = hf;
    return a.has_value();
}

// n rays at the scene's triangles (a vertex, an edge's midpoint, the centroid) or at
// random points; every fifth ends before its target. Returns the hits
int check_rays(const Scene& scene, int n, std::uint64_t seed, float size = 12.0f,
               AnyHitHint* carried = nullptr) {
    Rng rng(seed);
    AnyHitHint own;
    AnyHitHint& hint = carried ? *carried : own;
    int hits = 0;
    for (int k = 0; k < n; ++k) {
        Vec3 target = rng.in_box(-size, size);
        if (!scene.triangles.empty() && k % 4 != 3) {
            const SceneTriangle& t = scene.triangles[rng.next() % scene.triangles.size()];
            const Vec3 at[] = {t.v1, 0.5f * (t.v0 + t.v2), (t.v0 + t.v1 + t.v2) / 3.0f};
            target = at[k % 4];
        }
        const Vec3 o = rng.in_box(-1.4f * size, 1.4f * size), d = target - o;
        // Scaled first: d . d overflows (or underflows) at huge (tiny) sizes
        const float m = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
        if (!(m > 0.0f)) continue;
        Ray r{o, glm::normalize(d / m), 0.0f, kInfinity};
        if (k % 5 == 4) r.tmax = 0.5f * glm::length(d / m) * m;
        hits += check_query(scene, r, hint);
    }
    return hits;
}

// Each triangle is the one added as its source (with its normals), no two share one, the
// flags and face normals are the moved triangles'; the BVH names the triangles in
// increasing slot order, and without spheres slot s is triangle s. Committed again, a
// copy moves nothing
void check_sources(const Scene& scene, const std::vector<SceneTriangle>& by_source,
                   const std::vector<VertexNormals>& normals_by_source = {}) {
    std::vector<int> seen(by_source.size(), 0);
    for (size_t k = 0; k < scene.triangles.size(); ++k) {
        const size_t s = scene.triangle_source(k);
        INFO("triangle " << k << ", source " << s);
        REQUIRE(s < by_source.size());
        REQUIRE(seen[s]++ == 0);
        CHECK(same(scene.triangles[k], by_source[s]));
        if (!scene.normals.empty()) CHECK(same(scene.normals[k], normals_by_source[s]));
        const Vec3 n = unit_normal(scene.triangles[k]);
        CHECK(engine_data(scene).degenerate(k) == (n == Vec3(0.0f)));
        if (engine_data(scene).has_face_normals())
            CHECK(engine_data(scene).face_normal(k) == n);
    }
    const size_t spheres = scene.spheres.size();
    size_t next = spheres;
    for (size_t s = 0; s < scene.bvh().prims().size(); ++s) {
        const size_t p = scene.bvh().prims()[s];
        if (p >= spheres) REQUIRE(p == next++);
        if (spheres == 0) REQUIRE(p == s);
    }
    CHECK(next == spheres + scene.triangles.size());
    Scene again = scene;
    again.commit();
    CHECK(again.bvh().prims() == scene.bvh().prims());
    for (size_t k = 0; k < scene.triangles.size(); ++k) {
        REQUIRE(same(again.triangles[k], scene.triangles[k]));
        REQUIRE(again.triangle_source(k) == scene.triangle_source(k));
    }
}

size_t moved(const Scene& scene) {
    size_t n = 0;
    for (size_t k = 0; k < scene.triangles.size(); ++k)
        n += scene.triangle_source(k) != k;
    return n;
}

// No two triangles share a name (triangle_source)
bool names_distinct(const Scene& scene) {
    std::vector<size_t> names;
    for (size_t k = 0; k < scene.triangles.size(); ++k)
        names.push_back(scene.triangle_source(k));
    std::sort(names.begin(), names.end());
    return std::adjacent_find(names.begin(), names.end()) == names.end();
}

int check_camera(const Scene& scene, const Vec3& eye, const Vec3& at, float fov) {
    TraceCounters counters;
    const auto rays = camera_blocks(View{eye, at, Vec3(0, 1, 0), fov}, 24, 24);
    return check_packets(scene, rays, counters);
}

}  // namespace

TEST_SUITE("slot order") {
    TEST_CASE("around the slot-copy limit, with and without spheres: brute force") {
        // Slot copy, SlotOrderTriangles, slot copy with a sphere, Primitives (twice),
        // SlotOrderTriangles without face normals, with huge and tiny triangles, spheres
        // only
        const int C = int(kCopy), F = int(SceneData::kFaceNormalsUpTo) + 16;
        const int configs[][3] = {{C, 0, 0},    {C + 1, 0, 0},  {C - 1, 1, 0},
                                  {C, 1, 0},    {6000, 4, 0},   {F, 0, 0},
                                  {4400, 0, 1}, {0, C + 100, 0}};
        for (const auto& c : configs) {
            const int n = c[0], spheres = c[1];
            const bool mixed = c[2] == 1;
            INFO(n << " triangles, " << spheres << " spheres, mixed scales: " << mixed);
            const Scene added = soup(n, spheres, 11 + n + spheres, mixed);
            Scene scene = added;
            scene.commit();
            CHECK((engine_data(scene).slot_primitives() != nullptr) ==
                  (size_t(n + spheres) <= kCopy));
            CHECK(2 * moved(scene) >= (mixed ? 100 : scene.triangles.size()));
            check_sources(scene, added.triangles, added.normals);
            CHECK(check_rays(scene, 150, 3 + n) > 40);
            CHECK(check_camera(scene, Vec3(3, 4, 30), Vec3(0.0f), 45.0f) > 150);
            if (!mixed) continue;
            CHECK(check_rays(scene, 100, 2, 12e20f) > 20);
            CHECK(check_rays(scene, 100, 3, 12e-20f) > 20);
        }
    }

    TEST_CASE("exact ties on a coplanar grid: shared vertices and edges, duplicates") {
        // 48 x 48 unit quads in z = 0, added scrambled: a ray straight down through a
        // vertex meets six triangles at one t, through an edge two
        const int N = 48;
        std::vector<SceneTriangle> grid;
        for (int j = 0; j < N; ++j)
            for (int i = 0; i < N; ++i) {
                const Vec3 a(i - N / 2, j - N / 2, 0),
                    b = a + Vec3(1, 0, 0), c = a + Vec3(0, 1, 0), d = a + Vec3(1, 1, 0);
                grid.push_back({a, b, d, (i + j) % 2});
                grid.push_back({a, d, c, (i + j) % 2});
            }
        Scene scene;
        scene.materials = {Material{}, Material{}};
        for (size_t k = 0; k < grid.size(); ++k)
            scene.add_triangle(grid[(k * 2311) % grid.size()]);  // 2311: a prime
        const std::vector<SceneTriangle> added = scene.triangles;
        scene.commit();
        REQUIRE(engine_data(scene).slot_primitives() == nullptr);
        CHECK(moved(scene) > scene.triangles.size() / 2);
        check_sources(scene, added);
        Rng rng(4);
        AnyHitHint hint;
        int ties = 0;
        for (int k = 0; k < 400; ++k) {
            const Vec3 at(float(int(rng.next() % N) - N / 2) + (k % 3 == 1 ? 0.5f : 0.0f),
                          float(int(rng.next() % N) - N / 2) + (k % 3 == 2 ? 0.5f : 0.0f),
                          0);
            const Ray r{at + Vec3(0, 0, rng.uniform(1, 30)), Vec3(0, 0, -1), 0,
                        kInfinity};
            ties += brute(scene, r).ties > 1;
            check_query(scene, r, hint);
        }
        CHECK(ties > 350);
        // Packets from above a vertex, and grazing
        CHECK(check_camera(scene, Vec3(0, 0, 20), Vec3(0, 0.001f, 0), 30) > 500);
        CHECK(check_camera(scene, Vec3(0, -40, 2), Vec3(0.5f, 0, 0), 60) > 20);
    }

    TEST_CASE("re-commits after edits keep every triangle with its source") {
        Scene scene = soup(5000, 0, 21);
        std::vector<SceneTriangle> by_source = scene.triangles;
        std::vector<VertexNormals> normals = scene.normals;
        Rng rng(77);
        AnyHitHint hint;  // carried from commit to commit, slots renamed under it
        const auto step = [&](const std::string& what) {
            INFO("after: " << what);
            scene.commit();
            check_sources(scene, by_source, normals);
            const std::uint64_t seed = by_source.size() + scene.spheres.size();
            CHECK(check_rays(scene, 40, seed, 12.0f, &hint) > 10);
        };
        step("the first commit");
        for (int k = 0; k < 300; ++k) {  // new vertices, named by where they now are
            const size_t at = rng.next() % scene.triangles.size();
            scene.triangles[at] = random_triangle(rng, 1.0f, k % 3);
            if (k % 50 == 0) scene.triangles[at].v1 = scene.triangles[at].v0;
            by_source[scene.triangle_source(at)] = scene.triangles[at];
        }
        step("vertex changes");
        for (int k = 0; k < 300; ++k) {
            const SceneTriangle t = random_triangle(rng, 1.0f, 2);
            const VertexNormals n{rng.direction(), rng.direction(), rng.direction()};
            scene.add_triangle(t, n);
            CHECK(scene.triangle_source(scene.triangles.size() - 1) == by_source.size());
            by_source.push_back(t);
            normals.push_back(n);
        }
        step("appends");
        step("appends, twice");
        scene.normals.clear();
        step("normals cleared");
        for (int k = 0; k < 3; ++k)
            scene.spheres.push_back({Sphere{rng.in_box(-8, 8), 1.0f}, 0});
        step("spheres added");
        scene.spheres.clear();
        step("spheres removed");
        scene.triangles.resize(4000);
        step("the last 1,300 erased");
        // A copy edited and committed leaves the original as it was
        Scene copy = scene;
        copy.triangles[0].v0 += Vec3(100.0f);
        copy.commit();
        check_sources(scene, by_source, normals);
        CHECK(check_rays(scene, 40, 5) > 10);
    }

    TEST_CASE("a commit that throws moves nothing and names the triangle's source") {
        Scene scene = soup(4500, 0, 31);
        const Scene added = scene;
        scene.commit();
        const size_t k = 123, s = scene.triangle_source(k);
        REQUIRE(s != k);
        const std::string name = "triangle " + std::to_string(s) + ": ";
        const std::pair<std::function<void(Scene&)>, std::string> bad[] = {
            {[&](Scene& e) { e.triangles[k].v1.y = NAN; }, name + "vertex is not finite"},
            {[&](Scene& e) { e.normals[k].n2.x = kInfinity; },
             name + "vertex normal is not finite"},
            {[&](Scene& e) { e.triangles[k].material = -1; }, name + "material index -1"},
            {[&](Scene& e) { e.normals.pop_back(); }, "vertex normals: 4499 entries"},
            {[&](Scene& e) { e.ambient = -1.0f; }, "ambient"},
        };
        for (const auto& b : bad) {
            INFO("expected: " << b.second);
            Scene edited = scene;
            b.first(edited);
            const std::vector<SceneTriangle> before = edited.triangles;
            CHECK_THROWS_WITH_AS(edited.commit(), doctest::Contains(b.second.c_str()),
                                 Error);
            CHECK_FALSE(edited.traces_packets(engine_table()));
            for (size_t j = 0; j < before.size(); ++j) {
                REQUIRE(same(edited.triangles[j], before[j]));
                REQUIRE(edited.triangle_source(j) == scene.triangle_source(j));
            }
            // The module path, on the last good BVH, still finds what brute force does
            CHECK(check_rays(edited, 30, 17) > 5);
            // Put back and committed: the engine again, and nothing moved
            edited.triangles = scene.triangles, edited.normals = scene.normals;
            edited.ambient = 0.0f;
            edited.commit();
            CHECK(edited.traces_packets(engine_table()));
            check_sources(edited, added.triangles, added.normals);
            for (size_t j = 0; j < before.size(); ++j)
                REQUIRE(edited.triangle_source(j) == scene.triangle_source(j));
        }
        // A bad triangle added after the commit: named by the index it was added at
        scene.add_triangle({Vec3(0.0f), Vec3(1, 0, 0), Vec3(0, 1, 0), 9});
        CHECK_THROWS_WITH_AS(scene.commit(),
                             doctest::Contains("triangle 4500: material index 9"), Error);
    }

    TEST_CASE("triangles added after clear() are named by the index they were added at") {
        // DEFECT: source_ outlives a clear() of the public vector, and the new triangles
        // take the old ones' names (scene.h: "a triangle added after the last commit()
        // keeps its index"); commit()'s message names the wrong triangle
        Scene scene = soup(300, 0, 41);
        scene.commit();
        REQUIRE(moved(scene) > 100);
        scene.triangles.clear();
        scene.normals.clear();
        Rng rng(5);
        for (size_t k = 0; k < 10; ++k) {
            scene.add_triangle(random_triangle(rng, 1.0f, 0));
            CHECK(scene.triangle_source(k) == k);
        }
        scene.triangles[3].material = 7;
        CHECK_THROWS_WITH_AS(scene.commit(),
                             doctest::Contains("triangle 3: material index 7"), Error);
    }

    TEST_CASE("after cuts and appends no two triangles share a name") {
        // DEFECT: after commit() had moved them, a cut from the end kept a random half of
        // the names, and the triangles appended after it were named by their place:
        // 200 triangles, 153 distinct names
        Scene scene = soup(300, 0, 43);
        std::vector<SceneTriangle> by_source = scene.triangles;
        std::vector<VertexNormals> normals = scene.normals;
        scene.commit();
        REQUIRE(moved(scene) > 100);
        Rng rng(6);
        const auto append = [&](size_t n, bool with_add_triangle) {
            for (size_t k = 0; k < n; ++k) {
                const SceneTriangle t = random_triangle(rng, 1.0f, 1);
                const VertexNormals vn{rng.direction(), rng.direction(), rng.direction()};
                if (with_add_triangle) {
                    scene.add_triangle(t, vn);
                } else {
                    scene.triangles.push_back(t);
                    scene.normals.push_back(vn);
                }
                CHECK(scene.triangle_source(scene.triangles.size() - 1) ==
                      by_source.size());
                by_source.push_back(t);
                normals.push_back(vn);
            }
        };
        std::vector<size_t> kept;
        for (size_t k = 0; k < 100; ++k)
            kept.push_back(scene.triangle_source(k));
        scene.triangles.resize(100);
        scene.normals.resize(100);
        append(100, true);
        for (size_t k = 0; k < 100; ++k)
            CHECK(scene.triangle_source(k) == kept[k]);
        CHECK(names_distinct(scene));  // 200 names
        CHECK_THROWS_WITH_AS(          // a bad one among them: named by its own index
            [&] {
                Scene bad = scene;
                bad.triangles[150].material = 9;
                bad.commit();
            }(),
            doctest::Contains("triangle 350: material index 9"), Error);
        scene.commit();
        check_sources(scene, by_source, normals);
        CHECK(check_rays(scene, 40, 3) > 10);
        // Cut again with pop_back and committed, then pushed, not added: the same
        scene.triangles.pop_back(), scene.normals.pop_back();
        scene.commit();
        append(3, false);
        scene.commit();
        check_sources(scene, by_source, normals);
        // Emptied: the count starts again at 0
        scene.triangles.clear(), scene.normals.clear();
        scene.commit();
        by_source.clear(), normals.clear();
        append(5, false);
        scene.commit();
        check_sources(scene, by_source, normals);
    }

    TEST_CASE("no two triangles share a name, whatever is done to the list") {
        // Random edits of the public vector, the untracked ones (erase and insert in
        // the middle, push_back after a cut) included: names may go stale, never double
        Scene scene = soup(200, 0, 45);
        scene.normals.clear();
        Rng rng(8);
        for (int step = 0; step < 3000; ++step) {
            std::vector<SceneTriangle>& t = scene.triangles;
            const size_t at = t.empty() ? 0 : rng.next() % t.size();
            switch (rng.next() % 9) {
                case 0:
                    scene.add_triangle(random_triangle(rng, 1.0f, 0));
                    break;
                case 1:
                    t.push_back(random_triangle(rng, 1.0f, 1));
                    break;
                case 2:
                    if (!t.empty()) t.pop_back();
                    break;
                case 3:
                    t.resize(t.size() / 2 + t.size() / 4);
                    break;
                case 4:
                    if (!t.empty()) t.erase(t.begin() + long(at));
                    break;
                case 5:
                    t.insert(t.begin() + long(at), random_triangle(rng, 1.0f, 2));
                    break;
                case 6:
                    if (rng.next() % 20 == 0) t.clear();
                    break;
                case 7:
                    if (!t.empty()) t[at] = random_triangle(rng, 1.0f, 0);
                    break;
                default:
                    scene.commit();
                    break;
            }
            INFO("step " << step);
            REQUIRE(names_distinct(scene));
        }
    }

    TEST_CASE("names past 2^32 are handed out afresh, never twice") {
        // A 32-bit count would wrap after 2^32 names (billions of cuts and
        // appends), and a commit() would then give 80 triangles 60 names
        Scene scene = soup(300, 0, 47);
        scene.normals.clear();
        scene.commit();
        REQUIRE(moved(scene) > 100);
        SceneTestAccess::set_next_source(scene, 0xfffffff6u);
        Rng rng(9);
        for (int k = 0; k < 30; ++k)
            scene.add_triangle(random_triangle(rng, 1.0f, 0));
        CHECK(scene.triangle_source(329) == size_t{0xfffffff6u} + 29);
        CHECK(names_distinct(scene));
        scene.commit();
        CHECK(names_distinct(scene));
        size_t largest = 0;
        for (size_t k = 0; k < scene.triangles.size(); ++k)
            largest = std::max(largest, scene.triangle_source(k));
        CHECK(largest == 329);  // named afresh: 0 to 329
        for (int k = 0; k < 5; ++k)
            scene.add_triangle(random_triangle(rng, 1.0f, 0));
        CHECK(scene.triangle_source(334) == 334);
        scene.commit();
        CHECK(names_distinct(scene));
    }

    TEST_CASE("coincident centres: split by index, ties at the centre") {
        // Triangles in z = 0 and small spheres whose boxes are centred on 0 (split by
        // index, spheres and triangles together), interleaved with a soup below them: a
        // ray straight down near 0 meets many at one t
        Rng rng(9);
        Scene scene;
        scene.materials = {Material{}, Material{}};
        const auto below = [](SceneTriangle t) {  // the soup below z = -1, out of the way
            for (Vec3* v : {&t.v0, &t.v1, &t.v2})
                v->z -= 13.0f;
            return t;
        };
        for (int k = 0; k < 4600; ++k) {
            const float a = rng.uniform(0.5f, 3.0f);
            if (k % 6 == 0)
                scene.spheres.push_back({Sphere{Vec3(0.0f), 0.3f}, k % 4 / 2});
            scene.add_triangle(k % 2 ? below(random_triangle(rng, 1.0f, 0))
                                     : SceneTriangle{Vec3(-a, -a, 0), Vec3(a, -a, 0),
                                                     Vec3(0, a, 0), k % 4 / 2});
        }
        const std::vector<SceneTriangle> added = scene.triangles;
        scene.commit();
        check_sources(scene, added);
        AnyHitHint hint;
        int ties = 0;
        for (int k = 0; k < 150; ++k) {
            const float x = rng.uniform(-0.4f, 0.4f);  // (in order: the same rays from
            const float y = rng.uniform(-0.4f, 0.4f);  // every compiler)
            const Vec3 at(x, y, 0.0f);
            const Vec3 o = k % 2 ? at + Vec3(0, 0, 15) : rng.in_box(-15, 15);
            const Ray r{o, glm::normalize(at - o), 0.0f, kInfinity};
            ties += brute(scene, r).ties > 1;
            check_query(scene, r, hint);
        }
        MESSAGE(ties, " of 150 rays meet ties");
        CHECK(ties > 100);
        CHECK(check_camera(scene, Vec3(0, 0, 15), Vec3(0.0f), 5) == 576);
    }

    TEST_CASE("the light probe names a shadow blocker by its source") {
        // A floor, a blocker above its centre added as triangle 3000, a soup far beside
        // them: commit() moves the blocker
        Scene scene = soup(4600, 0, 51);
        scene.normals.clear();
        for (SceneTriangle& t : scene.triangles)
            t.v0.x += 40.0f, t.v1.x += 40.0f, t.v2.x += 40.0f;
        scene.triangles[0] = {Vec3(-5, -5, 0), Vec3(5, -5, 0), Vec3(5, 5, 0), 0};
        scene.triangles[1] = {Vec3(-5, -5, 0), Vec3(5, 5, 0), Vec3(-5, 5, 0), 0};
        scene.triangles[3000] = {Vec3(-1, -1, 5), Vec3(1, -1, 5), Vec3(0, 1, 5), 1};
        scene.lights.push_back(PointLight{Vec3(0, 0, 10), Vec3(10.0f)});
        scene.commit();
        REQUIRE(scene.triangle_source(3000) != 3000);
        RenderSettings settings;
        settings.width = settings.height = 3;
        const View view{Vec3(4, 0, 8), Vec3(0.0f), Vec3(0, 0, 1), 10.0f};
        const PixelProbe p = probe_pixel(scene, view, settings, engine_table(), 1, 1);
        REQUIRE(p.hit.has_value());
        REQUIRE(p.lights.size() == 1);
        CHECK(p.lights[0].blocked);
        CHECK(p.lights[0].blocker_name == "triangle 3000");
        // A second blocker in the same plane, added as triangle 2500 and stored after
        // 3000 (out of the camera ray's way): of the two hit at one t, the probe names
        // the one added first
        std::vector<size_t> at(4600);
        for (size_t k = 0; k < 4600; ++k)
            at[scene.triangle_source(k)] = k;
        scene.triangles[at[2500]] = {Vec3(-3, -3, 5), Vec3(1, -3, 5), Vec3(-3, 30, 5), 1};
        scene.commit();
        for (size_t k = 0; k < 4600; ++k)
            at[scene.triangle_source(k)] = k;
        REQUIRE(at[3000] < at[2500]);
        const PixelProbe q = probe_pixel(scene, view, settings, engine_table(), 1, 1);
        REQUIRE(q.lights.size() == 1);
        CHECK(q.lights[0].blocker_name == "triangle 2500");
    }

    TEST_CASE("empty scenes, and scenes emptied after a commit that moved triangles") {
        Scene scene;
        scene.materials = {Material{}};
        scene.commit();
        CHECK(scene.triangle_source(5) == 5);
        const Ray r{Vec3(0, 0, 5), Vec3(0, 0, -1), 0.0f, kInfinity};
        AnyHitHint hint;
        CHECK(check_query(scene, r, hint) == 0);
        CHECK(check_camera(scene, Vec3(0, 0, 5), Vec3(0.0f), 40) == 0);
        // A plane only: nothing in the BVH, no slot copy, no spheres (SlotOrderTriangles)
        scene.planes.push_back({Plane{Vec3(0, 0, 1), 1.0f}, 0});
        scene.commit();
        CHECK(check_query(scene, r, hint) == 1);
        CHECK(check_camera(scene, Vec3(0, 0, 5), Vec3(0.0f), 40) == 576);
        // Emptied and committed: triangles added then are named by their index
        Scene emptied = soup(300, 2, 61);
        emptied.commit();
        emptied.triangles.clear();
        emptied.normals.clear();
        emptied.commit();
        std::vector<SceneTriangle> added;
        for (size_t k = 0; k < 4; ++k) {
            CHECK(emptied.triangle_source(k) == k);
            added.push_back({Vec3(float(k)), Vec3(k + 1.0f, 0, 0), Vec3(0, 1, 0), 0});
            emptied.add_triangle(added.back());
        }
        emptied.commit();
        check_sources(emptied, added);
        CHECK(check_rays(emptied, 30, 8) > 0);
    }
}

}  // namespace against_brute_force
