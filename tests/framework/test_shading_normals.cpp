// Shading normals on the side of the surface the ray meets (pbrt's rule: the side of the
// geometric normal that faces the ray), on a low-poly smooth mesh and the sample scenes.
// Turned to face the ray by themselves, interpolated normals of a grazing ray's front
// face pointed behind it, and a light the face sees was taken as behind the surface.
#include <cmath>

#include <doctest/doctest.h>

#include "raylab/renderer.h"
#include "raylab/sample_scenes.h"
#include "test_helpers.h"

using namespace raylab;

namespace {

// The icosahedron (level 0) on the unit sphere, each vertex's normal the sphere's there
Scene smooth_icosahedron() {
    const float p = 1.618034f;
    const Vec3 v[12] = {{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0},
                        {0, -1, p}, {0, 1, p}, {0, -1, -p}, {0, 1, -p},
                        {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
    const int f[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                          {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                          {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                          {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    Scene scene;
    scene.materials.push_back(Material{});
    for (const auto& t : f) {
        const Vec3 a = glm::normalize(v[t[0]]), b = glm::normalize(v[t[1]]),
                   c = glm::normalize(v[t[2]]);
        scene.add_triangle(SceneTriangle{a, b, c}, VertexNormals{a, b, c});
    }
    scene.lights.push_back(PointLight{Vec3(2.0f, 3.0f, 1.0f), Vec3(10.0f)});
    scene.commit();
    return scene;
}

struct Count {
    int hits = 0;
    int behind = 0;  // shading normal on the far side of the face from the ray
    int dark = 0;    // the face and its interpolated normal see the light; ns does not
};

// One hit: its shading normal against the side of the face that the ray meets
void count(const Hit& hit, const Ray& r, const Scene& scene, Count& c) {
    ++c.hits;
    const Vec3 facing = glm::dot(hit.n, r.w) > 0.0f ? -hit.n : hit.n;
    const bool behind = glm::dot(hit.ns, facing) < 0.0f;
    c.behind += behind;
    for (const PointLight& light : scene.lights) {
        const Vec3 l = light.p - hit.position;
        // The interpolated normal on the facing side sees the light: -ns then does not
        const Vec3 ns = behind ? -hit.ns : hit.ns;
        if (glm::dot(facing, l) > 0.0f && glm::dot(ns, l) > 0.0f &&
            !(glm::dot(hit.ns, l) > 0.0f))
            ++c.dark;
    }
}

// The scene's camera rays at W x H, normalised as the renderer casts them (the camera
// is made once: probe_pixel makes it and the depth range again for every pixel)
Count camera_count(const Scene& scene, const ModuleTable& m, int W, int H) {
    const PinholeCamera camera = make_camera(m, scene.view);
    Count c;
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i) {
            Ray r = m.camera_ray(camera, m.image_plane_point(i, j, W, H));
            r.w = r.w / glm::length(r.w);
            TraceCounters counters;
            if (const auto hit = scene.closest_hit(m, r, counters))
                count(*hit, r, scene, c);
        }
    return c;
}

}  // namespace

TEST_SUITE("shading normals") {
    TEST_CASE(
        "an icosahedron with vertex normals: every shading normal on the ray's side") {
        const Scene ico = smooth_icosahedron();
        for (const ModuleTable& m : {engine_table(), module_path_table()}) {
            // Rays from a sphere of radius 3 towards points within 1.2 of the centre:
            // many meet the faces at grazing angles near the silhouette
            Rng rng(34);
            Count c;
            for (int k = 0; k < 6000; ++k) {
                const Vec3 o = 3.0f * rng.direction();
                const Vec3 target = 1.2f * rng.in_box(-1.0f, 1.0f);
                const Ray r{o, glm::normalize(target - o), 0.0f, kInfinity};
                TraceCounters counters;
                if (const auto hit = ico.closest_hit(m, r, counters))
                    count(*hit, r, ico, c);
            }
            MESSAGE("icosahedron (" << std::string(m.engine ? "engine" : "module path")
                                    << "): " << c.behind << " of " << c.hits
                                    << " shading normals behind the face, " << c.dark
                                    << " lit points dark");
            CHECK(c.hits > 2000);
            CHECK(c.behind == 0);
            CHECK(c.dark == 0);
        }
    }

    TEST_CASE(
        "the sample scenes blob and terrain: every shading normal on the ray's side") {
        for (const char* name : {"blob", "terrain"}) {
            const std::optional<Scene> scene = sample_scene(name);
            REQUIRE(scene.has_value());
            REQUIRE(!scene->normals.empty());
            const Count c = camera_count(*scene, engine_table(), 320, 240);
            MESSAGE(std::string(name) << ": " << c.behind << " of " << c.hits
                                      << " shading normals behind the face, " << c.dark
                                      << " lit points dark");
            CHECK(c.hits > 10000);
            CHECK(c.behind == 0);
            CHECK(c.dark == 0);
        }
    }
}
