// What the camera hits kept from the last frame depend on (CameraHits' key,
// raylab/renderer.h): the image size, the view, the primitive counts and the modules that
// make hits, and the owner's clear(). A change after the hit (a light, the shading mode,
// shadows) reuses them; anything they depend on, by as little as one float step, casts
// afresh; hits kept on the engine serve the module path bit for bit. Every frame must
// give the image of a fresh render.
#include <doctest/doctest.h>

#include "camera_hits_loop.h"

using namespace raylab;
using namespace raylab::camera_hits_test;

TEST_SUITE("camera hits kept") {
    // CameraHits: a change after the hit shades the kept hits, casting no camera ray,
    // and gives the image of a frame rendered afresh; anything a hit depends on casts
    TEST_CASE("kept camera hits serve a light change and nothing they depend on") {
        Scene scene = cornell_box();
        const ModuleTable modules = reference_modules();
        RenderSettings settings;
        settings.width = 64;
        settings.height = 48;
        const std::uint64_t pixels = 64 * 48;
        CameraHits kept;
        settings.camera_hits = &kept;
        Image first, image, fresh;
        // A first frame notes its key and keeps no hit; the next of the same key keeps
        // them (both cast every camera ray)
        FrameStats s = render(scene, scene.view, settings, modules, first);
        CHECK(s.camera_rays == pixels);
        CHECK(s.camera_rays_reused == 0);
        CHECK(kept.keyed);
        CHECK_FALSE(kept.valid);
        s = render(scene, scene.view, settings, modules, first);
        CHECK(s.camera_rays == pixels);
        CHECK(s.camera_rays_reused == 0);
        REQUIRE(kept.valid);

        // The light moves, shadows off and on, normals mode: hits reused, same image as
        // a render without kept hits
        RenderSettings plain = settings;
        plain.camera_hits = nullptr;
        scene.lights[0].p += Vec3(0.3f, -0.2f, 0.1f);
        for (const bool shadows : {true, false}) {
            for (const ShadingMode mode : {ShadingMode::lambert, ShadingMode::normals}) {
                settings.shadows = plain.shadows = shadows;
                settings.mode = plain.mode = mode;
                s = render(scene, scene.view, settings, modules, image);
                render(scene, scene.view, plain, modules, fresh);
                CHECK(s.camera_rays == 0);
                CHECK(s.camera_rays_reused == pixels);
                CHECK(image.pixels == fresh.pixels);
            }
        }
        CHECK(image.pixels != first.pixels);  // the light did move

        // The view, the size, a module that makes hits, the geometry's counts: a new key,
        // cast again. A new key's first frame keeps nothing (a camera that moves every
        // frame would never reuse it); its second keeps, and the third reuses
        View moved = scene.view;
        moved.eye.x += 0.01f;
        s = render(scene, moved, settings, modules, image);
        CHECK(s.camera_rays == pixels);
        CHECK(s.camera_rays_reused == 0);
        CHECK_FALSE(kept.valid);
        s = render(scene, moved, settings, modules, image);
        CHECK(s.camera_rays == pixels);
        CHECK(kept.valid);
        s = render(scene, moved, settings, modules, image);
        CHECK(s.camera_rays_reused == pixels);
        // The module path gives the engine's hits bit for bit: kept hits serve it
        ModuleTable module_path = modules;
        module_path.engine = nullptr;
        s = render(scene, moved, settings, module_path, image);
        CHECK(s.camera_rays_reused == pixels);
        // Another triangle module casts; another sphere module does not, while the scene
        // has no spheres
        ModuleTable other = module_path;
        other.intersect_triangle = &reference_triangle_elsewhere;
        s = render(scene, moved, settings, other, image);
        CHECK(s.camera_rays == pixels);
        render(scene, moved, settings, other, image);  // keeps for other
        other.intersect_sphere = &reference_sphere_elsewhere;
        s = render(scene, moved, settings, other, image);
        CHECK(s.camera_rays_reused == pixels);
        settings.width = 63;
        s = render(scene, moved, settings, other, image);
        CHECK(s.camera_rays == 63 * 48);
        render(scene, moved, settings, other, image);  // keeps for other at 63 x 48
        scene.spheres.push_back({Sphere{Vec3(0.0f), 0.3f}, 0});
        scene.commit();
        s = render(scene, moved, settings, module_path, image);
        CHECK(s.camera_rays == 63 * 48);
        render(scene, moved, settings, module_path, image);  // keeps with the sphere
        ModuleTable other_sphere_only = module_path;  // the sphere module counts now
        other_sphere_only.intersect_sphere = &reference_sphere_elsewhere;
        s = render(scene, moved, settings, other_sphere_only, image);
        CHECK(s.camera_rays == 63 * 48);
        render(scene, moved, settings, module_path, image);  // module_path's key again
        render(scene, moved, settings, module_path, image);  // and its hits kept
        plain = settings;
        plain.camera_hits = nullptr;
        render(scene, moved, plain, module_path, fresh);
        s = render(scene, moved, settings, module_path, image);
        CHECK(s.camera_rays_reused == 63 * 48);
        CHECK(image.pixels == fresh.pixels);  // the sphere is in both

        // Supersampled frames neither use nor fill them
        settings.spp = 4;
        s = render(scene, moved, settings, module_path, image);
        CHECK(s.camera_rays_reused == 0);
        CHECK(kept.valid);

        // Nor do frames above CameraHits::kMaxPixels (68 bytes a pixel)
        const Scene floor = lit_floor();
        RenderSettings big;
        big.width = 1025;
        big.height = 1024;
        big.camera_hits = &kept;
        render(floor, floor.view, big, modules, image);
        s = render(floor, floor.view, big, modules, image);
        CHECK(s.camera_rays == 1025 * 1024);
        CHECK(s.camera_rays_reused == 0);

        // A cancelled frame leaves no kept hits behind
        settings.spp = 1;
        settings.height = 40;
        std::atomic<bool> cancel{true};
        settings.cancel = &cancel;
        render(scene, moved, settings, module_path, image);
        CHECK_FALSE(kept.valid);
    }

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
