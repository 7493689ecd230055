// The reference engine's packet query (GeometryEngine::closest_hit_packet, through
// Scene::closest_hits) against its single-ray query: every ray's hit bit for bit, on
// camera blocks, on packets chosen to share edges, vertices and ties, and on packets that
// must fall back to single rays.
#include <doctest/doctest.h>

#include <vector>

#include "raylab/engine.h"
#include "raylab/renderer.h"
#include "raylab/sample_scenes.h"
#include "raylab/scenes.h"
#include "test_helpers.h"

using namespace raylab;

namespace {

// Sixteen rays from one origin o to the points of a 4 x 4 grid of integer coordinates
// in the plane z = z0: exactly through the shared vertices and edges of a triangulated
// grid there
std::vector<Ray> grid_rays(const Vec3& o, float z0, float x0, float y0) {
    std::vector<Ray> rays;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            const Vec3 target(x0 + float(i), y0 + float(j), z0);
            rays.push_back({o, glm::normalize(target - o), 0.0f, kInfinity});
        }
    return rays;
}

// A grid of unit squares, two triangles each, in the plane z = z0, and a second copy of
// each square's first triangle with another material one unit behind it
Scene grid_scene(float z0, bool with_twins) {
    Scene scene = cornell_box();  // materials and lights
    scene.triangles.clear();
    scene.normals.clear();
    for (int y = -4; y < 4; ++y)
        for (int x = -4; x < 4; ++x) {
            const Vec3 a(float(x), float(y), z0), b(float(x + 1), float(y), z0),
                c(float(x + 1), float(y + 1), z0), d(float(x), float(y + 1), z0);
            scene.add_triangle({a, b, c, (x + y) & 1});
            scene.add_triangle({a, c, d, 2});
            if (with_twins) scene.add_triangle({a, b, c, 3});  // an exact tie
        }
    scene.commit();
    return scene;
}

}  // namespace

TEST_SUITE("packets") {
    TEST_CASE("the reference's engine traces packets") {
        REQUIRE(engine_table().engine != nullptr);
        CHECK((engine_table().engine->closest_hit_packet != nullptr));
    }

    TEST_CASE("camera blocks hit what single rays hit, bit for bit") {
        for (const char* name : {"cornell", "dtu", "terrain", "room"}) {
            INFO("scene " << name);
            const std::optional<Scene> loaded =
                std::string(name) == "cornell" ? std::optional<Scene>(cornell_box())
                : std::string(name) == "dtu"   ? std::optional<Scene>(dtu_scene())
                                               : sample_scene(name);
            REQUIRE(loaded);
            const Scene& scene = *loaded;
            TraceCounters counters;
            const std::vector<Ray> rays = camera_blocks(scene.view, 160, 120);
            const int hits = check_packets(scene, rays, counters);
            CHECK(hits > 1000);  // the comparison means something
            // The packets ran: fewer node visits than one walk per ray would make
            TraceCounters single;
            for (const Ray& r : rays)
                (void)scene.closest_hit(engine_table(), r, single);
            CHECK(counters.bvh_nodes < single.bvh_nodes);
        }
    }

    TEST_CASE("rays exactly through shared vertices and edges, with exact ties") {
        // The grid's vertices and edges lie on integer coordinates; the twins make every
        // hit on a square's first triangle a tie that the visit order decides: those rays
        // must be traced again alone (the packet marks them)
        for (const bool twins : {false, true}) {
            for (const float z0 : {-3.0f, 5.0f}) {
                INFO("twins " << twins << ", plane z = " << z0);
                const Scene scene = grid_scene(z0, twins);
                TraceCounters counters;
                int hits = 0;
                for (const Vec3 o : {Vec3(0.5f, 0.25f, 0.0f), Vec3(0, 0, 0),
                                     Vec3(-0.75f, 1.0f, 1.0f), Vec3(3, -2, -10)}) {
                    for (float x0 : {-4.0f, -2.0f, 0.0f})
                        for (float y0 : {-4.0f, -1.0f, 0.0f})
                            hits +=
                                check_packets(scene, grid_rays(o, z0, x0, y0), counters);
                }
                CHECK(hits > 400);
            }
        }
    }

    TEST_CASE("planes, spheres and triangles in one packet") {
        Scene scene = cornell_box();
        scene.planes.push_back({Plane{Vec3(0, 1, 0), 0.9f}, 0});
        scene.planes.push_back({Plane{Vec3(0, 1, 0), 0.9f}, 1});  // a tie of planes
        scene.spheres.push_back({Sphere{Vec3(-0.4f, -0.6f, -0.3f), 0.35f}, 1});
        scene.spheres.push_back({Sphere{Vec3(0.5f, -0.7f, 0.2f), 0.25f}, 2});
        // A triangle in the plane y = -0.9: ties between a plane and a triangle
        scene.add_triangle(
            {Vec3(-1, -0.9f, -1), Vec3(1, -0.9f, -1), Vec3(0, -0.9f, 1), 3});
        scene.commit();
        TraceCounters counters;
        const int hits =
            check_packets(scene, camera_blocks(scene.view, 96, 72), counters);
        CHECK(hits > 3000);
    }

    TEST_CASE("packets that cannot travel together fall back to single rays") {
        const Scene scene = cornell_box();
        Rng rng(91);
        TraceCounters counters;
        std::vector<Ray> rays;
        // Other origins; a zero direction component; components of both signs; another
        // dominant axis; per-ray tmin and tmax; fewer rays than a packet
        for (int k = 0; k < 16; ++k)
            rays.push_back({rng.in_box(-0.5f, 0.5f), rng.direction(), 0.0f, kInfinity});
        check_packets(scene, rays, counters);
        const Vec3 eye = scene.view.eye;
        rays.clear();
        for (int k = 0; k < 16; ++k) {
            Vec3 w = glm::normalize(Vec3(0.01f * float(k - 8), 0.1f, -1.0f));
            if (k == 5) w = Vec3(0, 0, -1);  // zero x and y
            rays.push_back({eye, w, 0.0f, kInfinity});
        }
        check_packets(scene, rays, counters);
        rays.clear();
        for (int k = 0; k < 16; ++k) {
            const Vec3 w = glm::normalize(Vec3(k < 8 ? 1.5f : 0.1f, 0.2f, -1.0f));
            rays.push_back({eye, w, 0.1f * float(k % 3), k % 4 == 0 ? 3.5f : kInfinity});
        }
        check_packets(scene, rays, counters);
        // A NaN or infinite range in one ray of a packet that could travel together
        std::vector<Ray> together;
        for (int k = 0; k < 16; ++k)
            together.push_back({eye,
                                glm::normalize(Vec3(0.01f * float(k + 1), 0.1f, -1.0f)),
                                0.0f, kInfinity});
        for (const float bad : {NAN, -kInfinity, kInfinity}) {
            for (const int k : {0, 3}) {  // the first ray sets up the frustum
                std::vector<Ray> one = together;
                one[k].tmin = bad;
                check_packets(scene, one, counters);
                one[k].tmin = 0.0f;
                one[k].tmax = bad;
                check_packets(scene, one, counters);
            }
        }
        rays.resize(5);
        check_packets(scene, rays, counters);
        rays.resize(1);
        check_packets(scene, rays, counters);
    }

    TEST_CASE("random packets from one origin, near and far from the world's origin") {
        for (const Vec3 by : {Vec3(0.0f), Vec3(1e4f, -5e3f, 3e3f)}) {
            INFO("scene moved by " << by);
            const Scene scene = translated(cornell_box(), by);
            Rng rng(123);
            TraceCounters counters;
            int hits = 0;
            for (int p = 0; p < 300; ++p) {
                const Vec3 o = by + rng.in_box(-0.9f, 0.9f);
                const Vec3 centre = rng.direction();
                const float spread = p % 3 == 0 ? 0.001f : 0.05f;
                std::vector<Ray> rays;
                for (int k = 0; k < 16; ++k) {
                    const Vec3 w = glm::normalize(centre + spread * rng.in_box(-1, 1));
                    rays.push_back(
                        {o, w, p % 5 == 0 ? 0.01f : 0.0f, p % 7 == 0 ? 0.7f : kInfinity});
                }
                hits += check_packets(scene, rays, counters);
            }
            CHECK(hits > 2000);
        }
    }
}

// The renderer traces each tile's camera rays ahead in packets (PixelShader::trace_ahead)
// and the pixel loop takes them while it asks for the same points in the same order
TEST_SUITE("packets in render") {
    TEST_CASE("render() traces the camera rays ahead once, with the same image") {
        const Scene scene = cornell_box();
        RenderSettings settings;
        settings.width = 80;
        settings.height = 60;  // tiles of 16 x 16 and of 16 x 12: partial blocks
        Image fast, slow;
        const FrameStats a = render(scene, scene.view, settings, engine_table(), fast);
        const FrameStats b =
            render(scene, scene.view, settings, module_path_table(), slow);
        CHECK(a.camera_rays == 80 * 60);
        CHECK(b.camera_rays == 80 * 60);
        CHECK(fast.pixels == slow.pixels);
        // Nearly all in packets (ties on the edges between triangles, and blocks whose
        // rays' x changes sign, go alone); none on the module path
        CHECK(a.camera_rays_in_packets > 80 * 60 * 9 / 10);
        CHECK(a.camera_rays_in_packets < 80 * 60);
        CHECK(b.camera_rays_in_packets == 0);
    }

    // A student's pixel loop may visit a tile's pixels in another order: it gets the
    // rays traced ahead up to the first pixel out of order, the rest one at a time, and
    // the thread stops tracing ahead for the rest of the frame
    TEST_CASE("a pixel loop in another order gets the same image") {
        static const ModuleTable* table = nullptr;
        struct Loop {
            static void render_tile(const Tile& tile, const PixelRadiance& radiance,
                                    const ImageView& image) {
                for (int i = tile.x0; i < tile.x1; ++i)  // columns first
                    for (int j = tile.y0; j < tile.y1; ++j)
                        image.set(i, j,
                                  radiance(table->image_plane_point(i, j, image.width,
                                                                    image.height)));
            }
        };
        const Scene scene = cornell_box();
        ModuleTable columns = engine_table();
        columns.render_tile = &Loop::render_tile;
        table = &columns;
        RenderSettings settings;
        settings.width = 64;
        settings.height = 48;
        settings.threads = 2;
        Image image, expected;
        const FrameStats s = render(scene, scene.view, settings, columns, image);
        render(scene, scene.view, settings, engine_table(), expected);
        CHECK(image.pixels == expected.pixels);
        // One tile per thread traced ahead in vain, at the most
        CHECK(s.camera_rays >= 64 * 48);
        CHECK(s.camera_rays <= 64 * 48 + 2 * kTileSize * kTileSize);
    }
}
