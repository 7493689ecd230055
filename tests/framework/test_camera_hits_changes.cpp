// Adversarial cases for the camera hits render() keeps (RenderSettings::camera_hits),
// continued from test_camera_hits_orders.cpp: clear(), invalid camera rays and their
// count, the engine against the module path, changed views, modules and geometry, and
// the bound on what a tile keeps.
#include <doctest/doctest.h>

#include "camera_hits_loop.h"

using namespace raylab;
using namespace raylab::camera_hits_test;

TEST_SUITE("kept camera hits adversarial") {
    // clear() on a CameraHits never used, twice in a row, between the frame that keeps
    // and the one that would reuse, and after a frame that reused: each time the next
    // frame reuses nothing, and the round after it reuses all, with the fresh image
    TEST_CASE("clear() as often as the owner likes forgets the hits and the key") {
        const Scene scene = spheres_on_a_plane();
        LoopState& st = loop_state();
        const ModuleTable modules = adversarial_table(true);
        st.table = &modules;
        st.order = Order::leave_midway;
        RenderSettings settings;
        settings.width = 45;
        settings.height = 19;
        settings.threads = 2;
        Image fresh, image;
        const std::int64_t calls = render_frame(scene, settings, modules, fresh).calls;
        CameraHits kept;
        kept.clear();
        kept.clear();
        CHECK_FALSE(kept.keyed);
        settings.camera_hits = &kept;
        const auto round = [&](const char* when) {
            INFO("after clear() " << when);
            for (int frame = 0; frame < 3; ++frame) {
                CAPTURE(frame);
                const Frame f = render_frame(scene, settings, modules, image);
                CHECK(differing_pixels(image, fresh) == 0);
                CHECK(f.stats.camera_rays_reused ==
                      (frame == 2 ? std::uint64_t(calls) : 0u));
            }
        };
        round("on a new CameraHits");
        kept.clear();
        kept.clear();
        round("twice after a reuse");
        render_frame(scene, settings, modules, image);  // reuses once more
        kept.clear();
        CHECK_FALSE(kept.valid);
        CHECK_FALSE(kept.keyed);
        round("after a frame that reused");
        kept.clear();
        render_frame(scene, settings, modules, image);  // notes the key
        render_frame(scene, settings, modules, image);  // keeps
        REQUIRE(kept.valid);
        kept.clear();  // between keeping and reusing
        round("between the frame that kept and the one that would reuse");
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

    // The engine is not part of the key: hits kept on it serve the module path (a table
    // without the engine, or one whose module of a primitive the scene lacks is not the
    // reference's, which turns the engine off) and the other way round. Each reused
    // frame must be the fresh image of the path that reuses, bit for bit, also far from
    // the origin where points are coarse
    TEST_CASE("hits kept on the engine serve the module path and back, bit for bit") {
        LoopState& st = loop_state();
        st.order = Order::reference_like;
        const Scene scenes[] = {cornell_box(), spheres_on_a_plane(), dtu_scene(),
                                translated(cornell_box(), Vec3(900.0f, -250.0f, 60.0f)),
                                translated(dtu_scene(), Vec3(-3000.0f, 40.0f, 2000.0f))};
        struct Table {
            const char* name;
            ModuleTable modules;
        };
        const Table engine{"engine", adversarial_table(true)};
        const Table module_path{"module path", adversarial_table(false)};
        Table other_sphere{"another sphere module (no engine)", engine.modules};
        other_sphere.modules.intersect_sphere = &reference_sphere_elsewhere;
        int k = 0;
        for (const Scene& scene : scenes) {
            std::vector<std::pair<const Table*, const Table*>> pairs = {
                {&engine, &module_path}, {&module_path, &engine}};
            if (scene.spheres.empty()) {
                REQUIRE_FALSE(scene.traces_packets(other_sphere.modules));
                pairs.push_back({&engine, &other_sphere});
                pairs.push_back({&other_sphere, &engine});
            }
            // (Not a structured binding: INFO captures the names, which C++17 forbids)
            for (const auto& pair : pairs) {
                const Table* keeper = pair.first;
                const Table* reuser = pair.second;
                INFO("scene " << k << ", kept on the " << std::string(keeper->name)
                              << ", reused on the " << std::string(reuser->name));
                RenderSettings settings;
                settings.width = 161;
                settings.height = 121;
                st.table = &reuser->modules;
                Image fresh, image;
                const Frame plain = render_frame(scene, settings, reuser->modules, fresh);
                CameraHits kept;
                settings.camera_hits = &kept;
                st.table = &keeper->modules;
                render_frame(scene, settings, keeper->modules, image);
                render_frame(scene, settings, keeper->modules, image);
                REQUIRE(kept.valid);
                st.table = &reuser->modules;
                const Frame f = render_frame(scene, settings, reuser->modules, image);
                CHECK(f.stats.camera_rays_reused == std::uint64_t(plain.calls));
                CHECK(differing_pixels(image, fresh) == 0);
            }
            ++k;
        }
        reset_loop();
    }

    // Whatever the hits depend on changes, by as little as one float step: the eye, the
    // look-at point, the field of view, the camera module, the primitive counts (a
    // sphere added), and the geometry in place with the owner's clear(). Each state
    // renders three frames (note, keep, reuse), then the next; the states come back in
    // turn. Every frame must be the state's fresh image, which differs from the last
    // state's (so a stale hit would show)
    TEST_CASE("a new view, camera module or geometry never reuses the last one's hits") {
        LoopState& st = loop_state();
        st.order = Order::tiles_differ;
        const ModuleTable engine = adversarial_table(true);
        ModuleTable mirrored = engine;
        mirrored.camera_ray = &mirrored_camera_ray;
        const Scene base = spheres_on_a_plane();
        Scene more = base;  // one sphere more
        more.spheres.push_back({Sphere{Vec3(0.3f, 1.2f, 0.8f), 0.2f}, 0});
        more.commit();
        const auto step = [](float x) { return std::nextafter(x, 1e9f); };
        View eye = base.view, lookat = base.view, fov = base.view;
        eye.eye.y = step(eye.eye.y);
        lookat.lookat.y = step(lookat.lookat.y);
        fov.fov = step(fov.fov);
        struct State {
            const char* what;
            const Scene* scene;
            View view;
            const ModuleTable* modules;
        };
        // Each state differs from the one before in one thing only (the first from
        // the last in all)
        const State states[] = {{"base", &base, base.view, &engine},
                                {"mirrored camera module", &base, base.view, &mirrored},
                                {"one sphere more", &more, base.view, &mirrored},
                                {"eye one step up", &more, eye, &mirrored},
                                {"look-at one step up", &more, lookat, &mirrored},
                                {"field of view one step wider", &more, fov, &mirrored}};
        RenderSettings settings;
        settings.width = 47;
        settings.height = 31;
        settings.threads = 2;
        CameraHits kept;
        Image last;
        for (int round = 0; round < 2; ++round) {
            for (const State& state : states) {
                st.table = state.modules;
                settings.camera_hits = nullptr;
                Image fresh, image;
                loop_state().calls = 0;
                render(*state.scene, state.view, settings, *state.modules, fresh);
                const std::int64_t calls = loop_state().calls;
                INFO("round " << round << ", " << std::string(state.what));
                CHECK(differing_pixels(fresh, last) > 0);
                settings.camera_hits = &kept;
                for (int frame = 0; frame < 3; ++frame) {
                    CAPTURE(frame);
                    loop_state().calls = 0;
                    const FrameStats s =
                        render(*state.scene, state.view, settings, *state.modules, image);
                    CHECK(differing_pixels(image, fresh) == 0);
                    CHECK(s.camera_rays_reused ==
                          (frame == 2 ? std::uint64_t(calls) : 0u));
                }
                last = fresh;
            }
        }
        // The geometry moved in place, counts unchanged: the owner's clear() (CameraHits)
        // makes the next frames cast
        Scene moved = base;
        settings.camera_hits = &kept;
        st.table = &engine;
        render(moved, moved.view, settings, engine, last);
        render(moved, moved.view, settings, engine, last);
        REQUIRE(kept.valid);
        moved.spheres[0].sphere.c.x += 0.25f;
        moved.commit();
        kept.clear();
        settings.camera_hits = nullptr;
        Image fresh, image;
        render(moved, moved.view, settings, engine, fresh);
        CHECK(differing_pixels(fresh, last) > 0);
        settings.camera_hits = &kept;
        for (int frame = 0; frame < 3; ++frame) {
            CAPTURE(frame);
            render(moved, moved.view, settings, engine, image);
            CHECK(differing_pixels(image, fresh) == 0);
        }
        reset_loop();
    }

    // A pixel loop that asks for more than twice a tile's pixels (a student's
    // supersampling in module 01) keeps nothing in that frame: what a tile holds stays
    // bounded (68 bytes a point), the next frames cast again and give the fresh image,
    // and a loop within the bound keeps and reuses as before (found in review: nothing
    // bounded it, and 16 points a pixel at 1280 x 800 would have kept 1.1 GB)
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
