// Ray-triangle and ray-plane numerics: shared edges and vertices (watertightness, through
// the kernel and through the BVH's boxes), degenerate triangles, grazing rays, planes far
// from the origin and nearly parallel to the ray.
#include <doctest/doctest.h>

#include "meshes.h"
#include "raylab/bvh.h"
#include "test_helpers.h"

using namespace raylab;

namespace {

// An n x n grid of quads in the plane z = 0 around centre, each split into two triangles
// along a diagonal; every interior edge is shared by two triangles
struct Grid {
    std::vector<Vec3> vertices;
    std::vector<std::array<int, 3>> faces;
};

Grid make_grid(int n, Vec3 centre, float size) {
    Grid g;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            g.vertices.push_back(centre + Vec3(size * (i / float(n) - 0.5f),
                                               size * (j / float(n) - 0.5f), 0.0f));
    const auto at = [n](int i, int j) { return j * (n + 1) + i; };
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            g.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            g.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    }
    return g;
}

bool hits_any(const Grid& g, const Ray& r) {
    for (const auto& f : g.faces) {
        if (reference::intersect_triangle(r, g.vertices[f[0]], g.vertices[f[1]],
                                          g.vertices[f[2]]))
            return true;
    }
    return false;
}

}  // namespace

TEST_SUITE("stress triangle") {
    TEST_CASE("rays through shared edges and vertices of a mesh never slip through") {
        // Targets: every vertex and points along every edge of an interior 6 x 6 grid,
        // hit from random directions; near and far from the origin
        for (const float D : {0.0f, 1e3f, 1e5f}) {
            const Grid g = make_grid(6, Vec3(D, -0.5f * D, 0.25f * D), 3.0f);
            Rng rng(static_cast<std::uint64_t>(D) + 1);
            int leaks = 0, rays = 0;
            for (const auto& f : g.faces) {
                for (int e = 0; e < 3; ++e) {
                    const Vec3 a = g.vertices[f[e]], b = g.vertices[f[(e + 1) % 3]];
                    for (const float s : {0.0f, 0.25f, 0.5f, 1.0f / 3.0f}) {
                        const Vec3 target = a + s * (b - a);
                        // Keep to the grid's inside: the outer boundary is not shared
                        const Vec3 rel = target - g.vertices[0];
                        if (rel.x <= 0.0f || rel.y <= 0.0f || rel.x >= 3.0f ||
                            rel.y >= 3.0f)
                            continue;
                        Vec3 w = rng.direction();
                        if (std::abs(w.z) < 0.1f) w.z = 0.5f;
                        w = glm::normalize(w);
                        const Ray r{target - 4.0f * w, w, 0.0f, kInfinity};
                        ++rays;
                        if (!hits_any(g, r)) {
                            ++leaks;
                            INFO("leak at D = " << D << ": " << r);
                            CHECK(leaks == 0);
                        }
                    }
                }
            }
            INFO("D = " << D << ": " << leaks << " leaks in " << rays << " rays");
            CHECK(rays > 300);
            CHECK(leaks == 0);
        }
    }

    TEST_CASE("degenerate triangles are never hit and never give NaN") {
        Rng rng(5);
        for (int k = 0; k < 5000; ++k) {
            const Vec3 a = rng.in_box(-1, 1), b = rng.in_box(-1, 1);
            // Collinear, two coincident vertices, all coincident
            const Vec3 tris[3][3] = {{a, b, a + 0.5f * (b - a)}, {a, a, b}, {a, a, a}};
            const Ray r{rng.in_box(-2, 2), rng.direction(), 0.0f, kInfinity};
            for (const auto& t : tris) {
                INFO("ray " << k << ": " << r);
                const auto hit = reference::intersect_triangle(r, t[0], t[1], t[2]);
                if (hit) {
                    // A collinear triangle rounded into a sliver: the hit must at least
                    // be sane
                    CHECK(std::isfinite(hit->t));
                    CHECK(is_finite(hit->n));
                }
            }
            CHECK_FALSE(reference::intersect_triangle(r, a, a, a).has_value());
            CHECK_FALSE(reference::intersect_triangle(r, a, a, b).has_value());
        }
    }

    TEST_CASE("grazing rays give finite hits or misses, never NaN") {
        Rng rng(9);
        const Vec3 v0(-1, 0, -1), v1(1, 0, -1), v2(0, 0, 1);
        for (int k = 0; k < 20000; ++k) {
            // Directions within 1e-7 .. 1e-3 rad of the triangle's plane
            const float angle = std::pow(10.0f, rng.uniform(-7.0f, -3.0f));
            const float phi = rng.uniform(0.0f, 2.0f * kPi);
            const Vec3 w = glm::normalize(Vec3(std::cos(phi), angle, std::sin(phi)));
            const Ray r{Vec3(0.0f, -angle * 0.5f, 0.0f) - 0.5f * w, w, 0.0f, kInfinity};
            INFO("ray " << k << ": " << r);
            if (const auto hit = reference::intersect_triangle(r, v0, v1, v2)) {
                REQUIRE(std::isfinite(hit->t));
                CHECK(std::abs(hit->position.y) < 1e-5f);
                CHECK(hit->uv.x >= 0.0f);
                CHECK(hit->uv.y >= 0.0f);
                CHECK(hit->uv.x + hit->uv.y <= 1.0f + 1e-6f);
            }
            const Ray in_plane{Vec3(0.0f, 0.0f, -3.0f),
                               glm::normalize(Vec3(0.1f, 0.0f, 1.0f)), 0.0f, kInfinity};
            const auto flat = reference::intersect_triangle(in_plane, v0, v1, v2);
            CHECK((!flat || std::isfinite(flat->t)));
        }
    }

    TEST_CASE("planes far from the origin give the exact distance of the float inputs") {
        // Plane y = Y at Y up to 1e6; origin 0.3 above it (as rounded in float). In
        // float, o . n + d cancels to the ulp of Y; the reference computes it in double
        for (const float Y : {1.0f, 1e3f, 1e5f, 1e6f}) {
            const Plane p{Vec3(0.0f, 1.0f, 0.0f), -Y};
            const Vec3 o(12.0f, Y + 0.3f, -7.0f);
            const double exact = static_cast<double>(o.y) - static_cast<double>(Y);
            const Ray r{o, Vec3(0.0f, -1.0f, 0.0f), 0.0f, kInfinity};
            const auto hit = reference::intersect_plane(r, p);
            INFO("Y = " << Y);
            REQUIRE(hit);
            CHECK(hit->t == static_cast<float>(exact));
        }
    }

    TEST_CASE("a ray exactly through a fan's shared vertex hits one of its triangles") {
        // The exact ray and mesh vertices that once slipped between the four triangles
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

    TEST_CASE("a ray in a BVH box's face plane along a +-0 component is not culled") {
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

    TEST_CASE("a nearly parallel ray never hits a plane at t = inf") {
        const Plane p{Vec3(0.0f, 1.0f, 0.0f), 0.0f};
        const Ray r{Vec3(0.0f, 1.0f, 0.0f), Vec3(1.0f, -1e-40f, 0.0f), 0.0f, kInfinity};
        const auto hit = reference::intersect_plane(r, p);
        CHECK((!hit || std::isfinite(hit->t)));
    }
}
