// Scenes, views, the BVH queries and the built-in Cornell box.
#include <doctest/doctest.h>

#include "raylab/error.h"
#include "raylab/scenes.h"
#include "test_helpers.h"

using namespace raylab;

namespace {

// Closest hit by testing every primitive, with no BVH: the truth the BVH must reproduce
std::optional<Hit> brute_force_closest(const Scene& scene, Ray r) {
    const ModuleTable& m = reference_modules();
    std::optional<Hit> best;
    for (const ScenePlane& p : scene.planes)
        if (auto h = m.intersect_plane(r, p.plane)) r.tmax = h->t, best = h;
    for (const SceneSphere& s : scene.spheres)
        if (auto h = m.intersect_sphere(r, s.sphere)) r.tmax = h->t, best = h;
    for (const SceneTriangle& t : scene.triangles)
        if (auto h = m.intersect_triangle(r, t.v0, t.v1, t.v2)) r.tmax = h->t, best = h;
    return best;
}

// Random spheres and triangles in [-10, 10]^3
Scene random_scene(std::uint64_t seed, int spheres, int triangles) {
    Rng rng(seed);
    Scene scene;
    scene.materials.push_back(Material{"grey", Vec3(0.5f), Vec3(0.0f)});
    for (int k = 0; k < spheres; ++k)
        scene.spheres.push_back(
            {Sphere{rng.in_box(-10, 10), rng.uniform(0.05f, 1.0f)}, 0});
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

// The triangle of scene whose hit record is hit (by position of the hit on its plane)
Vec3 face_normal(const SceneTriangle& t) {
    return glm::normalize(glm::cross(t.v1 - t.v0, t.v2 - t.v0));
}

}  // namespace

TEST_SUITE("scene") {
    TEST_CASE(
        "a view with NaN, a zero or parallel up vector, or FOV 0 or 180 is rejected") {
        View v;
        CHECK_NOTHROW(validate(v));
        View bad = v;
        bad.up = Vec3(0.0f);
        CHECK_THROWS_WITH_AS(validate(bad), doctest::Contains("up vector is zero"),
                             Error);
        bad = v;
        bad.up = Vec3(0.0f, 0.0f, -2.0f);  // along lookat - eye = (0, 0, -3)
        CHECK_THROWS_WITH_AS(validate(bad), doctest::Contains("parallel"), Error);
        for (float fov : {0.0f, 180.0f, -5.0f, 200.0f, std::nanf("")}) {
            INFO("fov = " << fov);
            bad = v;
            bad.fov = fov;
            CHECK_THROWS_WITH_AS(validate(bad), doctest::Contains("field of view"),
                                 Error);
        }
        bad = v;
        bad.eye.x = std::nanf("");
        CHECK_THROWS_WITH_AS(validate(bad), doctest::Contains("not finite"), Error);
        bad = v;
        bad.lookat = bad.eye;
        CHECK_THROWS_WITH_AS(validate(bad), doctest::Contains("same point"), Error);
    }

    TEST_CASE("commit rejects bad geometry by naming the element") {
        Scene s;
        s.materials.push_back(Material{});
        s.spheres.push_back({Sphere{Vec3(0.0f), -1.0f}, 0});
        CHECK_THROWS_WITH_AS(s.commit(), doctest::Contains("sphere 0"), Error);
        s.spheres.clear();
        SceneTriangle t;
        t.v0 = Vec3(std::nanf(""));
        s.triangles.push_back(t);
        CHECK_THROWS_WITH_AS(
            s.commit(), doctest::Contains("triangle 0: vertex is not finite"), Error);
        s.triangles[0].v0 = Vec3(0.0f);
        s.triangles[0].material = 3;
        CHECK_THROWS_WITH_AS(s.commit(), doctest::Contains("material index 3"), Error);
        // Vertex normals: none, or one entry per triangle, finite
        s.triangles[0].material = 0;
        s.triangles.push_back(s.triangles[0]);
        s.normals.resize(1);
        CHECK_THROWS_WITH_AS(
            s.commit(), doctest::Contains("vertex normals: 1 entries for 2 triangles"),
            Error);
        s.normals.resize(2);
        s.normals[1].n2 = Vec3(0.0f, kInfinity, 0.0f);
        CHECK_THROWS_WITH_AS(s.commit(),
                             doctest::Contains("triangle 1: vertex normal is not finite"),
                             Error);
        // The first bad triangle is named, whether its vertex or its normal is bad
        s.triangles[0].v1 = Vec3(NAN);
        CHECK_THROWS_WITH_AS(
            s.commit(), doctest::Contains("triangle 0: vertex is not finite"), Error);
    }

    TEST_CASE("vertex normals from an OBJ file shade smooth triangles, and only those") {
        // Two triangles of the plane z = 0; the first has vertex normals tilted towards
        // +x, the second none (flat)
        const Scene scene = load_obj_text(
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 1 0 1\n"
            "f 1//1 2//1 3//1\nf 2 4 3\n",
            "two.obj", [](const std::string&) { return std::string(); });
        REQUIRE(scene.triangles.size() == 2);
        REQUIRE(scene.normals.size() == 2);
        CHECK(scene.normals[1].n0 == Vec3(0.0f));
        const ModuleTable& m = reference_modules();
        TraceCounters c;
        const float h = std::sqrt(0.5f);
        const auto smooth =
            scene.closest_hit(m, Ray{Vec3(0.25f, 0.25f, 2.0f), Vec3(0, 0, -1)}, c);
        REQUIRE(smooth.has_value());
        CHECK(smooth->ns.x == doctest::Approx(h));
        CHECK(smooth->ns.z == doctest::Approx(h));
        const auto flat =
            scene.closest_hit(m, Ray{Vec3(0.75f, 0.75f, 2.0f), Vec3(0, 0, -1)}, c);
        REQUIRE(flat.has_value());
        CHECK(flat->ns == Vec3(0.0f, 0.0f, 1.0f));
        // The flat face first: the normals start at the smooth one and are padded before
        const Scene flat_first = load_obj_text(
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 1 0 1\n"
            "f 2 4 3\nf 1//1 2//1 3//1\nf 2 4 3\n",
            "three.obj", [](const std::string&) { return std::string(); });
        REQUIRE(flat_first.normals.size() == 3);
        CHECK(flat_first.normals[0].n0 == Vec3(0.0f));
        CHECK(flat_first.normals[1].n0.x == doctest::Approx(h));
        CHECK(flat_first.normals[2].n2 == Vec3(0.0f));
    }

    TEST_CASE("BVH closest hit equals brute force on random scenes") {
        for (std::uint64_t seed = 1; seed <= 4; ++seed) {
            const Scene scene = random_scene(seed, 40, 300);
            Rng rng(1000 + seed);
            TraceCounters counters;
            for (int k = 0; k < 2000; ++k) {
                const Ray r{rng.in_box(-12, 12), rng.direction(), 0.0f, kInfinity};
                const auto bvh = scene.closest_hit(reference_modules(), r, counters);
                const auto brute = brute_force_closest(scene, r);
                INFO("seed " << seed << ", ray " << k << ": " << r);
                REQUIRE(bvh.has_value() == brute.has_value());
                if (bvh) CHECK(bvh->t == brute->t);
                CHECK(scene.any_hit(reference_modules(), r, counters) ==
                      brute.has_value());
            }
            // The BVH must prune: far fewer primitive tests than 340 per ray
            CHECK(counters.intersection_tests < 2u * 2000u * 60u);
        }
    }

    TEST_CASE("the SIMD slab test keeps rays lying in a box face's plane") {
        // A 16 x 16 grid of quads in x in [-1, 0], y in [-1, 1] at z = 0, with the axes
        // rotated so that x is each axis in turn: enough for interior nodes, whose child
        // boxes have faces at x = 0. Rays at x = 0 along w.x = +-0 give 0 * inf = NaN for
        // that axis, which must not cull the box
        for (int axis = 0; axis < 3; ++axis) {
            const auto rotate = [axis](float x, float y, float z) {
                Vec3 v;
                v[axis] = x, v[(axis + 1) % 3] = y, v[(axis + 2) % 3] = z;
                return v;
            };
            Scene scene;
            scene.materials.push_back(Material{"grey", Vec3(0.5f), Vec3(0.0f)});
            for (int i = 0; i < 16; ++i) {
                for (int j = 0; j < 16; ++j) {
                    const float x0 = -1.0f + i / 16.0f, x1 = -1.0f + (i + 1) / 16.0f;
                    const float y0 = -1.0f + j / 8.0f, y1 = -1.0f + (j + 1) / 8.0f;
                    const Vec3 a = rotate(x0, y0, 0), b = rotate(x1, y0, 0),
                               c = rotate(x1, y1, 0), d = rotate(x0, y1, 0);
                    scene.triangles.push_back(SceneTriangle{a, b, c});
                    scene.triangles.push_back(SceneTriangle{a, c, d});
                }
            }
            scene.commit();
            REQUIRE(scene.bvh().node_count() > 1);
            int hits = 0;
            for (const float zero : {0.0f, -0.0f}) {
                for (int k = 0; k <= 40; ++k) {
                    const Ray r{rotate(0.0f, -0.95f + k * 0.0475f, 3.0f),
                                rotate(zero, 0, -1), 0.0f, kInfinity};
                    INFO("axis " << axis << ": " << r);
                    TraceCounters c;
                    const bool brute = brute_force_closest(scene, r).has_value();
                    CHECK(scene.closest_hit(reference_modules(), r, c).has_value() ==
                          brute);
                    CHECK(scene.any_hit(reference_modules(), r, c) == brute);
                    hits += brute;
                }
            }
            CHECK(hits > 40);  // the kernel hits the edge x = 0: the rays test the BVH
        }
    }

    TEST_CASE(
        "closest hit respects tmin and tmax and fills material and a facing normal") {
        Scene scene;
        scene.materials = {Material{"a", Vec3(0.1f), Vec3(0.0f)},
                           Material{"b", Vec3(0.2f), Vec3(0.0f)}};
        scene.spheres.push_back({Sphere{Vec3(0, 0, -5), 1.0f}, 0});
        scene.spheres.push_back({Sphere{Vec3(0, 0, -10), 1.0f}, 1});
        scene.commit();
        TraceCounters c;
        const ModuleTable& m = reference_modules();
        auto hit =
            scene.closest_hit(m, Ray{Vec3(0.0f), Vec3(0, 0, -1), 0.0f, kInfinity}, c);
        REQUIRE(hit);
        CHECK(hit->t == doctest::Approx(4.0));
        CHECK(hit->material == 0);
        CHECK(hit->ns == Vec3(0, 0, 1));
        // tmin past the first sphere: the inside of sphere 0 (far side at t = 6)
        hit = scene.closest_hit(m, Ray{Vec3(0.0f), Vec3(0, 0, -1), 4.5f, kInfinity}, c);
        REQUIRE(hit);
        CHECK(hit->t == doctest::Approx(6.0));
        CHECK(hit->n == Vec3(0, 0, -1));  // outward
        CHECK(hit->ns == Vec3(0, 0, 1));  // faces the ray
        hit = scene.closest_hit(m, Ray{Vec3(0.0f), Vec3(0, 0, -1), 6.5f, kInfinity}, c);
        REQUIRE(hit);
        CHECK(hit->material == 1);
        CHECK_FALSE(scene.closest_hit(m, Ray{Vec3(0.0f), Vec3(0, 0, -1), 0.0f, 3.9f}, c));
        CHECK_FALSE(scene.any_hit(m, Ray{Vec3(0.0f), Vec3(0, 0, -1), 0.0f, 3.9f}, c));
    }

    TEST_CASE("the Cornell box fills [-1, 1]^3 with normals facing into the room") {
        const Scene scene = cornell_box();
        REQUIRE(scene.triangles.size() == 30);
        // The triangles in the order cornell_box() added them (commit() moved them)
        Scene box;
        box.materials = scene.materials;
        box.triangles.resize(30);
        for (size_t k = 0; k < 30; ++k)
            box.triangles.at(scene.triangle_source(k)) = scene.triangles[k];
        const Aabb b = scene.bounds();
        CHECK(b.lo == Vec3(-1.0f));
        CHECK(b.hi == Vec3(1.0f));
        // Room: the first ten triangles; each normal points towards the centre
        for (int k = 0; k < 10; ++k) {
            const SceneTriangle& t = box.triangles[k];
            const Vec3 centre = (t.v0 + t.v1 + t.v2) / 3.0f;
            INFO("room triangle " << k << " (" << box.materials[t.material].name << ")");
            CHECK(glm::dot(face_normal(t), -centre) > 0.0f);
        }
        // Blocks: normals point away from the block's own centre
        for (int k = 10; k < 30; ++k) {
            const int first = k < 20 ? 10 : 20;
            Vec3 block_centre(0.0f);
            for (int q = first; q < first + 10; ++q)
                block_centre +=
                    (box.triangles[q].v0 + box.triangles[q].v1 + box.triangles[q].v2);
            block_centre /= 30.0f;
            const SceneTriangle& t = box.triangles[k];
            const Vec3 centre = (t.v0 + t.v1 + t.v2) / 3.0f;
            INFO("block triangle " << k);
            CHECK(glm::dot(face_normal(t), centre - block_centre) > 0.0f);
        }
    }

    TEST_CASE("the Cornell box is oriented as in the lab's figure") {
        const Scene box = cornell_box();
        const auto material_at = [&](Vec3 o, Vec3 w) {
            TraceCounters c;
            const auto hit =
                box.closest_hit(reference_modules(), Ray{o, w, 0.0f, kInfinity}, c);
            REQUIRE(hit);
            return box.materials[hit->material].name;
        };
        // From the centre: purple on the left (-x), yellow on the right, green floor,
        // cyan ceiling, white back wall (-z); the tall blue block stands left of the red
        // one
        CHECK(material_at(Vec3(0, 0.9f, 0), Vec3(-1, 0, 0)) == "purple");
        CHECK(material_at(Vec3(0, 0.9f, 0), Vec3(1, 0, 0)) == "yellow");
        CHECK(material_at(Vec3(0, 0.9f, 0), Vec3(0, -1, 0)) == "green");
        CHECK(material_at(Vec3(0, 0.9f, 0), Vec3(0, 1, 0)) == "cyan");
        CHECK(material_at(Vec3(0, 0.9f, 0), Vec3(0, 0, -1)) == "white");
        CHECK(material_at(Vec3(-0.3f, -0.5f, 3.0f), Vec3(0, 0, -1)) == "blue");
        CHECK(material_at(Vec3(0.35f, -0.8f, 3.0f), Vec3(0, 0, -1)) == "red");
    }

    TEST_CASE("load_scene names what it cannot load") {
        CHECK_THROWS_WITH_AS(load_scene("kitchen"),
                             doctest::Contains("unknown scene 'kitchen'"), Error);
        CHECK_THROWS_WITH_AS(load_scene("/no/such/file.obj"),
                             doctest::Contains("cannot open"), Error);
    }
}
