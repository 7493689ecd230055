// Adversarial cases (the pixel loop's orders, throws, cancels and sizes) for the camera
// hits render() keeps from one frame for the next (RenderSettings::camera_hits,
// CameraHits in raylab/renderer.h), written by a reviewer who did not write them, beyond
// test_render.cpp's "kept camera hits ..." cases. Module 01, the pixel loop, is the
// students': it may ask for the pixels in any order, skip them, ask one many times, ask
// points off the pixel grid or other tiles' points, stop a tile early, change its order
// from frame to frame, throw or raise the cancel flag midway. Each such loop runs on odd
// image sizes, sizes that change between frames, 1, 2, 3 and 8 threads, scenes with and
// without triangles, the engine (camera rays traced ahead in packets) and the module
// path, and after repeated clear(). Every frame must give the image of a fresh render
// (camera_hits = nullptr) bit for bit, and true counts: a frame that reuses casts exactly
// the points it could not take from the kept hits.
#include <doctest/doctest.h>

#include "camera_hits_loop.h"

using namespace raylab;
using namespace raylab::camera_hits_test;

TEST_SUITE("kept camera hits adversarial") {
    // Each loop's own three frames (notes the key, keeps, reuses) at 1x1, 17x3 and 3x17
    // (tiles lower or narrower than a packet of 4 x 4, one of them a single column or
    // row) and 33x49 (tiles of 16 and of 1 columns, of 16 and of 1 rows), on 1, 2, 3 and
    // 8 threads: every frame is the fresh image, and the third takes every point the loop
    // asks for from the kept hits, casting none
    TEST_CASE("every pixel loop's next frame reuses each point it asked for") {
        const Scene scenes[] = {cornell_box(), spheres_on_a_plane()};
        const int sizes[][2] = {{1, 1}, {17, 3}, {3, 17}, {33, 49}};
        LoopState& st = loop_state();
        for (const bool engine : {true, false}) {
            const ModuleTable modules = adversarial_table(engine);
            st.table = &modules;
            for (const Scene& scene : scenes) {
                REQUIRE(scene.traces_packets(modules) == engine);
                for (const auto& size : sizes) {
                    for (const int threads : {1, 2, 3, 8}) {
                        for (const Order order : kOrders) {
                            INFO("engine " << engine << ", triangles "
                                           << scene.triangles.size() << ", " << size[0]
                                           << "x" << size[1] << ", " << threads
                                           << " threads, " << std::string(name(order)));
                            st.order = order;
                            RenderSettings settings;
                            settings.width = size[0];
                            settings.height = size[1];
                            settings.threads = threads;
                            Image fresh, image;
                            const Frame plain =
                                render_frame(scene, settings, modules, fresh);
                            CameraHits kept;
                            settings.camera_hits = &kept;
                            for (int frame = 0; frame < 3; ++frame) {
                                CAPTURE(frame);
                                const Frame f =
                                    render_frame(scene, settings, modules, image);
                                CHECK(differing_pixels(image, fresh) == 0);
                                CHECK(f.calls == plain.calls);
                                check_counts(f);
                                if (frame < 2) CHECK(f.stats.camera_rays_reused == 0);
                                // One thread: the same tiles traced ahead as without
                                if (frame < 2 && threads == 1)
                                    CHECK(f.stats.camera_rays == plain.stats.camera_rays);
                                if (frame == 2)
                                    CHECK(f.stats.camera_rays_reused ==
                                          static_cast<std::uint64_t>(f.calls));
                            }
                            CHECK(kept.valid);
                        }
                    }
                }
            }
        }
        reset_loop();
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

    // Sizes that change the tile count both ways while the tiles' arrays keep their
    // memory (clear() keeps it), sizes of the same tile count, sizes that come back, and
    // two sizes of the same tile count in turn (a new key each frame: nothing kept,
    // nothing reused)
    TEST_CASE("image sizes that change between frames never reuse another size's hits") {
        const Scene scene = cornell_box();
        LoopState& st = loop_state();
        // 40x24, 33x24 and 33x29 have six tiles each: only the width, then only the
        // height tells their hits apart
        const int sizes[][2] = {{40, 24}, {33, 24}, {33, 29}, {17, 3}, {70, 50}, {1, 1},
                                {16, 16}, {15, 17}, {40, 24}, {3, 41}, {70, 50}, {64, 1}};
        for (const bool engine : {true, false}) {
            const ModuleTable modules = adversarial_table(engine);
            st.table = &modules;
            for (const Order order : {Order::reference_like, Order::backwards_from_middle,
                                      Order::leave_midway}) {
                st.order = order;
                RenderSettings settings;
                settings.threads = 3;
                CameraHits kept;
                for (const auto& size : sizes) {
                    settings.width = size[0];
                    settings.height = size[1];
                    settings.camera_hits = nullptr;
                    Image fresh, image;
                    const std::int64_t calls =
                        render_frame(scene, settings, modules, fresh).calls;
                    settings.camera_hits = &kept;
                    for (int frame = 0; frame < 3; ++frame) {
                        INFO("engine " << engine << ", " << std::string(name(order))
                                       << ", " << size[0] << "x" << size[1] << ", frame "
                                       << frame);
                        const Frame f = render_frame(scene, settings, modules, image);
                        CHECK(differing_pixels(image, fresh) == 0);
                        check_counts(f);
                        CHECK(f.stats.camera_rays_reused ==
                              (frame == 2 ? std::uint64_t(calls) : 0u));
                    }
                }
                // Two sizes in turn: each frame a new key
                for (int frame = 0; frame < 6; ++frame) {
                    const auto& size = sizes[frame % 2];
                    settings.width = size[0];
                    settings.height = size[1];
                    settings.camera_hits = nullptr;
                    Image fresh, image;
                    render_frame(scene, settings, modules, fresh);
                    settings.camera_hits = &kept;
                    INFO("engine " << engine << ", alternating sizes, frame " << frame);
                    const Frame f = render_frame(scene, settings, modules, image);
                    CHECK(differing_pixels(image, fresh) == 0);
                    CHECK(f.stats.camera_rays_reused == 0);
                    CHECK_FALSE(kept.valid);
                }
            }
        }
        reset_loop();
    }
}
