// Camera hits kept from the last frame (KeptHits, raylab/camera_hit_sources.h, and
// RenderSettings::camera_hits): a frame whose key is the last frame's takes the hits that
// frame kept while its pixel loop asks for the kept points in the kept order, and casts
// the rest. Module 01 is the students': it may ask in any order, skip pixels, ask one
// many times, ask points off the grid or in other tiles, stop early, change its order
// from frame to frame, throw or raise the cancel flag midway. Every frame must give the
// image of a fresh render (camera_hits = nullptr) bit for bit, and true counts. What the
// hits depend on (the key) is tested in test_camera_hits_kept_key.cpp.
#include <doctest/doctest.h>

#include "camera_hits_loop.h"

using namespace raylab;
using namespace raylab::camera_hits_test;
using detail::CameraSample;
using detail::CastHits;
using detail::KeptHits;
using detail::WorkCounters;

TEST_SUITE("camera hits kept") {
    // Hits kept by two frames of the reference loop at 40 x 24 (six tiles, three of them
    // cut): each tile's source hands out that tile's own samples (found by the tile's
    // place) while asked in order, counting a reused ray for each point that had one and
    // casting none; the first point out of step and all after it are cast, one ray each
    TEST_CASE("kept samples are handed out in the kept order, then cast") {
        const Scene scene = cornell_box();
        for (const bool holed : {false, true}) {
            CAPTURE(holed);
            ModuleTable modules = engine_table();
            if (holed) modules.camera_ray = &holed_camera_ray;
            RenderSettings settings;
            settings.width = 40;
            settings.height = 24;
            CameraHits kept;
            settings.camera_hits = &kept;
            Image image;
            render(scene, scene.view, settings, modules, image);
            render(scene, scene.view, settings, modules, image);
            REQUIRE(kept.valid);
            const PinholeCamera camera = make_camera(modules, scene.view);
            WorkCounters counters, cast_counters;
            KeptHits source(kept, scene, modules, camera, counters);
            CastHits cast(scene, modules, camera, cast_counters);
            const std::vector<Tile> tiles = image_tiles(40, 24);
            REQUIRE(kept.tiles.size() == tiles.size());
            std::uint64_t valid = 0;
            for (size_t t = 0; t < tiles.size(); ++t) {
                CAPTURE(t);
                const std::vector<Vec2> p = tile_points(modules, tiles[t], 40, 24);
                REQUIRE(kept.tiles[t].size() == p.size());
                source.begin_tile(tiles[t], nullptr);
                for (size_t k = 0; k < p.size(); ++k) {
                    const CameraSample s = source.take(p[k]);
                    CHECK(same_sample(s, kept.tiles[t][k]));
                    CHECK(same_sample(s, cast.take(p[k])));
                    valid += s.traced;
                }
                source.end_tile();
            }
            CHECK(counters.camera_rays == 0);
            CHECK(counters.camera_rays_reused == valid);
            CHECK(valid == (holed ? cast_counters.camera_rays : 40u * 24u));
            // Out of step after 10 points: the rest of the tile is cast, even the
            // points that follow in the kept order
            const std::vector<Vec2> p = tile_points(modules, tiles[0], 40, 24);
            source.begin_tile(tiles[0], nullptr);
            for (int k = 0; k < 10; ++k)
                source.take(p[k]);
            const std::uint64_t reused = counters.camera_rays_reused;
            CHECK(same_sample(source.take(p[20]), cast.take(p[20])));
            for (int k = 10; k < 30; ++k)
                CHECK(same_sample(source.take(p[k]), cast.take(p[k])));
            source.end_tile();
            CHECK(counters.camera_rays_reused == reused);
            CHECK(counters.camera_rays > 0);
            // The next tile starts in step again
            source.begin_tile(tiles[1], nullptr);
            source.take(tile_points(modules, tiles[1], 40, 24)[0]);
            source.end_tile();
            CHECK(counters.camera_rays_reused == reused + 1);
        }
    }

    // A pixel loop that asks for the pixels in another order than the frame that kept
    // the hits (the same function: say a student's with state) casts afresh where the
    // points differ, and the image is still right
    TEST_CASE("kept camera hits follow the pixel loop's points, not its order") {
        static bool backwards = false;
        static const ModuleTable* table = nullptr;
        struct Loop {
            static void render_tile(const Tile& tile, const PixelRadiance& radiance,
                                    const ImageView& image) {
                for (int j = tile.y0; j < tile.y1; ++j) {
                    for (int n = 0; n < tile.x1 - tile.x0; ++n) {
                        const int i = backwards ? tile.x1 - 1 - n : tile.x0 + n;
                        image.set(i, j,
                                  radiance(table->image_plane_point(i, j, image.width,
                                                                    image.height)));
                    }
                }
            }
        };
        const Scene scene = cornell_box();
        ModuleTable modules = reference_modules();
        modules.render_tile = &Loop::render_tile;
        table = &modules;
        RenderSettings settings;
        settings.width = 48;
        settings.height = 32;
        CameraHits kept;
        settings.camera_hits = &kept;
        Image image, fresh;
        render(scene, scene.view, settings, modules, image);
        render(scene, scene.view, settings, modules, image);  // the second keeps the hits
        REQUIRE(kept.valid);
        backwards = true;
        const FrameStats s = render(scene, scene.view, settings, modules, image);
        backwards = false;
        CHECK(s.camera_rays == 48 * 32);
        CHECK(s.camera_rays_reused == 0);
        settings.camera_hits = nullptr;
        render(scene, scene.view, settings, modules, fresh);
        CHECK(image.pixels == fresh.pixels);
    }

    // Hits kept by one order serve another order's frame where its points are the kept
    // ones in the kept order, and are cast where not; the frame after it, in the keeping
    // order again, still reuses all (a frame that reuses keeps nothing new). Every pair
    // of orders, on both paths, at 40x27 (full and cut tiles) on 2 threads
    TEST_CASE("a pixel loop that changes its order between frames gets fresh images") {
        const Scene scene = cornell_box();
        LoopState& st = loop_state();
        for (const bool engine : {true, false}) {
            const ModuleTable modules = adversarial_table(engine);
            st.table = &modules;
            RenderSettings settings;
            settings.width = 40;
            settings.height = 27;
            settings.threads = 2;
            // The fresh image of each order
            std::vector<Image> fresh(std::size(kOrders));
            for (const Order o : kOrders) {
                st.order = o;
                render_frame(scene, settings, modules, fresh[size_t(o)]);
            }
            CameraHits kept;
            settings.camera_hits = &kept;
            for (const Order keeper : kOrders) {
                st.order = keeper;
                kept.clear();  // (the key is the same for every order)
                Image image;
                render_frame(scene, settings, modules, image);  // notes the key
                const Frame keeping = render_frame(scene, settings, modules, image);
                REQUIRE(kept.valid);
                for (const Order other : kOrders) {
                    INFO("engine " << engine << ", kept by " << std::string(name(keeper))
                                   << ", then " << std::string(name(other)));
                    st.order = other;
                    const Frame f = render_frame(scene, settings, modules, image);
                    CHECK(differing_pixels(image, fresh[size_t(other)]) == 0);
                    check_counts(f);
                    if (other == keeper)
                        CHECK(f.stats.camera_rays_reused == std::uint64_t(f.calls));
                    st.order = keeper;
                    const Frame back = render_frame(scene, settings, modules, image);
                    CHECK(differing_pixels(image, fresh[size_t(keeper)]) == 0);
                    CHECK(back.stats.camera_rays_reused == std::uint64_t(keeping.calls));
                    CHECK(back.stats.camera_rays == 0);
                }
            }
        }
        reset_loop();
    }

    // A pixel loop that throws (a student's loop may) in the frame that notes the key,
    // the one that keeps or the one that reuses, at its first, middle or last call: the
    // frame throws, and no later frame shades a hit it left half kept. The frames after
    // it give the fresh image; they start the round (note, keep, reuse) again, but after
    // a frame that reused, whose kept hits stay whole and serve the next frame
    TEST_CASE("a pixel loop that throws midway leaves no hit a later frame misuses") {
        const Scene scene = cornell_box();
        LoopState& st = loop_state();
        for (const bool engine : {true, false}) {
            const ModuleTable modules = adversarial_table(engine);
            st.table = &modules;
            for (const Order order : {Order::reference_like, Order::leave_midway}) {
                st.order = order;
                for (const int threads : {1, 3}) {
                    RenderSettings settings;
                    settings.width = 37;
                    settings.height = 21;
                    settings.threads = threads;
                    Image fresh, image;
                    const std::int64_t calls =
                        render_frame(scene, settings, modules, fresh).calls;
                    CameraHits kept;
                    settings.camera_hits = &kept;
                    for (int thrower = 0; thrower < 3; ++thrower) {
                        for (const std::int64_t at :
                             {std::int64_t{0}, calls / 2, calls - 1}) {
                            INFO("engine " << engine << ", " << std::string(name(order))
                                           << ", " << threads << " threads, frame "
                                           << thrower << " throws at call " << at);
                            kept.clear();
                            for (int frame = 0; frame < thrower; ++frame)
                                render_frame(scene, settings, modules, image);
                            st.throw_at = at;
                            CHECK_THROWS_AS(render_frame(scene, settings, modules, image),
                                            LoopThrew);
                            st.throw_at = -1;
                            CHECK(kept.valid == (thrower == 2));
                            check_frames_after(scene, settings, modules, fresh, calls,
                                               thrower == 2);
                        }
                    }
                }
            }
        }
        reset_loop();
    }

    // The cancel flag raised from inside the pixel loop (as the viewer raises it from
    // another thread while tiles are in flight) in each of the three frames: the frame
    // says it was cancelled, the flag lowered again the next frames give the fresh image,
    // and only a frame whose hits were all kept is reused from
    TEST_CASE("a frame cancelled midway leaves no hit a later frame misuses") {
        const Scene scene = spheres_on_a_plane();
        LoopState& st = loop_state();
        std::atomic<bool> cancel{false};
        st.cancel = &cancel;
        for (const bool engine : {true, false}) {
            const ModuleTable modules = adversarial_table(engine);
            st.table = &modules;
            for (const Order order : {Order::reference_like, Order::many_times}) {
                st.order = order;
                for (const int threads : {1, 2, 8}) {
                    RenderSettings settings;
                    settings.width = 50;
                    settings.height = 35;
                    settings.threads = threads;
                    settings.cancel = &cancel;
                    Image fresh, image;
                    const std::int64_t calls =
                        render_frame(scene, settings, modules, fresh).calls;
                    CameraHits kept;
                    settings.camera_hits = &kept;
                    for (int cancelled = 0; cancelled < 3; ++cancelled) {
                        for (const std::int64_t at :
                             {std::int64_t{0}, calls / 2, calls - 1}) {
                            INFO("engine " << engine << ", " << std::string(name(order))
                                           << ", " << threads << " threads, frame "
                                           << cancelled << " cancelled at call " << at);
                            kept.clear();
                            for (int frame = 0; frame < cancelled; ++frame)
                                render_frame(scene, settings, modules, image);
                            st.cancel_at = at;
                            CHECK(render_frame(scene, settings, modules, image)
                                      .stats.cancelled);
                            st.cancel_at = -1;
                            cancel = false;
                            CHECK(kept.valid == (cancelled == 2));
                            check_frames_after(scene, settings, modules, fresh, calls,
                                               cancelled == 2);
                        }
                    }
                }
            }
        }
        reset_loop();
    }

    // Points whose camera ray is not valid are kept as such (no hit) and shaded with
    // the background of the frame that reuses them, which may differ from the keeping
    // frame's
    TEST_CASE("points without a valid camera ray show the reusing frame's background") {
        const Scene scene = cornell_box();
        LoopState& st = loop_state();
        for (const bool engine : {true, false}) {
            ModuleTable modules = adversarial_table(engine);
            modules.camera_ray = &holed_camera_ray;
            st.table = &modules;
            for (const Order order : {Order::reference_like, Order::leave_midway}) {
                st.order = order;
                INFO("engine " << engine << ", " << std::string(name(order)));
                RenderSettings settings;
                settings.width = 41;
                settings.height = 33;
                settings.threads = 2;
                Image fresh, image;
                CameraHits kept;
                settings.camera_hits = &kept;
                render_frame(scene, settings, modules, image);
                render_frame(scene, settings, modules, image);
                REQUIRE(kept.valid);
                settings.background = Vec3(0.25f, 0.5f, 1.0f);
                const Frame f = render_frame(scene, settings, modules, image);
                CHECK(f.stats.camera_rays == 0);
                settings.camera_hits = nullptr;
                render_frame(scene, settings, modules, fresh);
                CHECK(differing_pixels(image, fresh) == 0);
                CHECK(image.at(0, 0) == settings.background);  // (w = 0 there)
            }
        }
        reset_loop();
    }

    // A point without a valid camera ray casts no ray in a fresh frame (camera_rays
    // leaves it out), so a frame that reuses it reuses no camera ray either: its
    // camera_rays_reused must be the rays a fresh frame casts, as the viewer's log line
    // 'camera hits reused: N' and FrameStats ("hits taken from settings.camera_hits")
    // say. Expected: the pixels whose ray holed_camera_ray leaves valid
    TEST_CASE("a frame that reuses counts as reused only points that had a camera ray") {
        const Scene scene = cornell_box();
        LoopState& st = loop_state();
        st.order = Order::reference_like;
        RenderSettings settings;
        settings.width = 41;
        settings.height = 33;
        std::uint64_t valid = 0;  // pixels with a valid ray (holed_camera_ray)
        const ModuleTable& ref = reference_modules();
        for (int j = 0; j < settings.height; ++j) {
            for (int i = 0; i < settings.width; ++i) {
                const Vec2 uv =
                    ref.image_plane_point(i, j, settings.width, settings.height);
                valid += uv.x >= -0.3f && uv.y != 0.0f;
            }
        }
        REQUIRE(valid < std::uint64_t(settings.width * settings.height));
        for (const bool engine : {true, false}) {
            ModuleTable modules = adversarial_table(engine);
            modules.camera_ray = &holed_camera_ray;
            st.table = &modules;
            INFO("engine " << engine);
            settings.camera_hits = nullptr;
            Image image;
            CHECK(render_frame(scene, settings, modules, image).stats.camera_rays ==
                  valid);
            CameraHits kept;
            settings.camera_hits = &kept;
            render_frame(scene, settings, modules, image);
            render_frame(scene, settings, modules, image);
            const Frame f = render_frame(scene, settings, modules, image);
            CHECK(f.stats.camera_rays == 0);
            CHECK(f.stats.camera_rays_reused == valid);
        }
        reset_loop();
    }
}
