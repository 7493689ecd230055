// Camera hits cast per call (CastHits, raylab/camera_hit_sources.h): each point's hit is
// the scene's closest hit on the camera module's ray, normalised; a point without a valid
// ray is not traced; what a tile keeps for the next frame is bounded. Every pass of
// render() falls back to this source, so its answers are the ones the other sources are
// held to.
#include <doctest/doctest.h>

#include "camera_hits_loop.h"

using namespace raylab;
using namespace raylab::camera_hits_test;
using detail::CameraSample;
using detail::CastHits;
using detail::WorkCounters;

TEST_SUITE("camera hits cast") {
    // Expected: Scene::closest_hit on the module's ray with w / |w|, which the renderer
    // promises its shading (docs/style.md rule 9), on both paths and two scenes, with
    // the rays and the queries' work counted once per point
    TEST_CASE("a cast sample is the closest hit of the camera module's ray, normalised") {
        const Scene scenes[] = {cornell_box(), spheres_on_a_plane()};
        for (const bool engine : {true, false}) {
            const ModuleTable modules = engine ? engine_table() : module_path_table();
            for (const Scene& scene : scenes) {
                INFO("engine " << engine << ", triangles " << scene.triangles.size());
                const PinholeCamera camera = make_camera(modules, scene.view);
                WorkCounters counters;
                CastHits cast(scene, modules, camera, counters);
                TraceCounters expected_work;
                int hits = 0;
                const int W = 23, H = 17;
                for (int j = 0; j < H; ++j) {
                    for (int i = 0; i < W; ++i) {
                        const Vec2 uv = modules.image_plane_point(i, j, W, H);
                        Ray r = modules.camera_ray(camera, uv);
                        r.w = r.w / glm::length(r.w);
                        const CameraSample expected{
                            uv, true, scene.closest_hit(modules, r, expected_work)};
                        Ray ray;
                        const CameraSample s = cast.take(uv, &ray);
                        CAPTURE(i);
                        CAPTURE(j);
                        CHECK(same_sample(s, expected));
                        CHECK(std::memcmp(&ray.w, &r.w, sizeof(Vec3)) == 0);
                        hits += s.hit.has_value();
                    }
                }
                CHECK(hits > W * H / 2);  // (a scene in view)
                CHECK(counters.camera_rays == std::uint64_t(W * H));
                CHECK(counters.trace.intersection_tests ==
                      expected_work.intersection_tests);
                CHECK(counters.trace.bvh_nodes == expected_work.bvh_nodes);
                CHECK(counters.camera_rays_reused == 0);
            }
        }
    }

    // holed_camera_ray gives w = 0 left of u = -0.3 and an infinite origin at v = 0:
    // neither is a ray, so the point is not traced, casts nothing, counts nothing and
    // leaves the caller's ray as it was
    TEST_CASE("a point without a valid camera ray is not traced, cast or counted") {
        const Scene scene = cornell_box();
        ModuleTable modules = engine_table();
        modules.camera_ray = &holed_camera_ray;
        const PinholeCamera camera = make_camera(modules, scene.view);
        WorkCounters counters;
        CastHits cast(scene, modules, camera, counters);
        const Ray untouched{Vec3(7.0f), Vec3(0.0f, 0.0f, 1.0f), 0.5f, 2.0f};
        for (const Vec2 uv : {Vec2(-0.4f, 0.1f), Vec2(0.2f, 0.0f), Vec2(-0.31f, 0.0f)}) {
            INFO("uv " << uv.x << ", " << uv.y);
            Ray ray = untouched;
            const CameraSample s = cast.take(uv, &ray);
            CHECK_FALSE(s.traced);
            CHECK_FALSE(s.hit.has_value());
            CHECK(std::memcmp(&ray, &untouched, sizeof(Ray)) == 0);
        }
        CHECK(counters.camera_rays == 0);
        CHECK(counters.trace.intersection_tests == 0);
        const CameraSample s = cast.take(Vec2(0.1f, 0.1f));
        CHECK(s.traced);
        CHECK(counters.camera_rays == 1);
    }

    // A tile of 3 x 2 pixels keeps at most 2 x 6 samples (kKeptPerPixel): the first 12
    // in the order taken, whatever points they are; the 13th stops the keeping for the
    // tile and flags the frame, while every answer stays the cast one. The next tile
    // keeps again (the bound is per tile); a tile given nowhere to keep keeps nothing
    TEST_CASE("a tile keeps the samples taken in their order, at most two a pixel") {
        const Scene scene = cornell_box();
        const ModuleTable modules = engine_table();
        const PinholeCamera camera = make_camera(modules, scene.view);
        WorkCounters counters;
        CastHits cast(scene, modules, camera, counters);
        WorkCounters other;
        CastHits reference(scene, modules, camera, other);  // keeps nothing
        const int W = 40, H = 30;
        const Tile tile{5, 7, 8, 9};
        std::vector<Vec2> asked;  // each pixel twice, the second round backwards
        for (int round = 0; round < 2; ++round)
            for (int k = 0; k < 6; ++k) {
                const int kk = round == 0 ? k : 5 - k;
                asked.push_back(
                    modules.image_plane_point(tile.x0 + kk % 3, tile.y0 + kk / 3, W, H));
            }
        asked.push_back(Vec2(0.0f));  // the 13th: one too many
        asked.push_back(Vec2(0.1f, 0.2f));
        std::vector<CameraSample> kept;
        cast.begin_tile(tile, &kept);
        for (size_t k = 0; k < asked.size(); ++k) {
            CAPTURE(k);
            CHECK(same_sample(cast.take(asked[k]), reference.take(asked[k])));
            CHECK(kept.size() == std::min<size_t>(k + 1, 12));
            CHECK(counters.hits_overflow == (k >= 12));
        }
        cast.end_tile();
        for (size_t k = 0; k < kept.size(); ++k)
            CHECK(same_sample(kept[k], reference.take(asked[k])));
        // The next tile keeps again; the frame stays flagged
        std::vector<CameraSample> next;
        cast.begin_tile(Tile{0, 0, 1, 1}, &next);
        cast.take(asked[0]);
        cast.take(asked[1]);
        cast.take(asked[2]);
        cast.end_tile();
        CHECK(next.size() == 2);
        CHECK(counters.hits_overflow);
        cast.begin_tile(tile, nullptr);
        cast.take(asked[0]);
        cast.end_tile();
        CHECK(next.size() == 2);
        CHECK(kept.size() == 12);
    }

    // A pixel loop that asks for more than twice a tile's pixels (a student's
    // supersampling in module 01) keeps nothing in that frame: what a tile holds stays
    // bounded (68 bytes a point), the next frames cast again and give the fresh image,
    // and a loop within the bound keeps and reuses as before (unbounded, 16 points a
    // pixel at 1280 x 800 would keep 1.1 GB)
    TEST_CASE("a pixel loop that asks too many points a pixel keeps none of them") {
        const Scene scene = cornell_box();
        LoopState& st = loop_state();
        for (const bool engine : {true, false}) {
            const ModuleTable modules = adversarial_table(engine);
            st.table = &modules;
            for (const int threads : {1, 2}) {
                INFO("engine " << engine << ", " << threads << " threads");
                RenderSettings settings;
                settings.width = 37;  // full tiles and cut ones
                settings.height = 21;
                settings.threads = threads;
                st.order = Order::over_the_bound;
                Image fresh, image;
                const std::int64_t calls =
                    render_frame(scene, settings, modules, fresh).calls;
                CHECK(calls == 3 * 37 * 21);
                CameraHits kept;
                settings.camera_hits = &kept;
                for (int frame = 0; frame < 4; ++frame) {
                    CAPTURE(frame);
                    const Frame f = render_frame(scene, settings, modules, image);
                    CHECK(differing_pixels(image, fresh) == 0);
                    CHECK(f.stats.camera_rays_reused == 0);
                    CHECK_FALSE(kept.valid);
                    CHECK(kept.keyed);
                    const int tiles_x = (37 + kTileSize - 1) / kTileSize;
                    for (size_t t = 0; t < kept.tiles.size(); ++t) {
                        const int x0 = int(t) % tiles_x * kTileSize;
                        const int y0 = int(t) / tiles_x * kTileSize;
                        const size_t pixels = size_t(std::min(kTileSize, 37 - x0)) *
                                              size_t(std::min(kTileSize, 21 - y0));
                        CHECK(kept.tiles[t].size() <= 2 * pixels);
                    }
                }
                // Within the bound, the same CameraHits keeps and reuses again
                st.order = Order::many_times;
                render_frame(scene, settings, modules, fresh);  // keeps: same key
                REQUIRE(kept.valid);
                const Frame f = render_frame(scene, settings, modules, image);
                CHECK(f.stats.camera_rays_reused == std::uint64_t(2 * 37 * 21));
                CHECK(differing_pixels(image, fresh) == 0);
            }
        }
        reset_loop();
    }
}
