// Camera hits traced ahead in packets (TracedAheadHits, raylab/camera_hit_sources.h):
// where the scene's engine traces packets, a tile's camera rays are traced before its
// pixel loop runs and handed out while the loop asks for the same points in the
// reference loop's order. The samples are the cast ones bit for bit; a loop that leaves
// the order is cast from there on and stops the tracing ahead for its thread; what the
// loop took in order is kept at once for the next frame.
#include <doctest/doctest.h>

#include "camera_hits_loop.h"

using namespace raylab;
using namespace raylab::camera_hits_test;
using detail::CameraSample;
using detail::CastHits;
using detail::TracedAheadHits;
using detail::WorkCounters;

namespace {

// A source traced ahead and the cast one it is held to, on one scene and table
struct Sources {
    Sources(const Scene& scene, const ModuleTable& modules, int width, int height)
        : camera(make_camera(modules, scene.view)),
          settings(size(width, height)),
          ahead(scene, modules, camera, settings, counters),
          cast(scene, modules, camera, cast_counters) {}
    static RenderSettings size(int width, int height) {
        RenderSettings s;
        s.width = width;
        s.height = height;
        return s;
    }
    PinholeCamera camera;
    RenderSettings settings;
    WorkCounters counters, cast_counters;
    TracedAheadHits ahead;
    CastHits cast;
};

}  // namespace

TEST_SUITE("camera hits traced ahead") {
    // Every tile of a 37 x 21 image (16 x 16, 5 x 16, 16 x 5 and 5 x 5 pixels: packets
    // cut on both sides) and of 1 x 1 and 3 x 17, asked in the reference order: each
    // sample is the cast one, bit for bit; every valid point is one camera ray, traced
    // in packets before the loop asks, and none more when it asks. With the holed
    // camera, the points without a ray stay untraced
    TEST_CASE(
        "samples traced ahead are the cast ones, bit for bit, in every tile shape") {
        if (!engine_built()) return;  // without the engine nothing is traced ahead
        const Scene scenes[] = {cornell_box(), spheres_on_a_plane()};
        const int sizes[][2] = {{37, 21}, {1, 1}, {3, 17}};
        for (const bool holed : {false, true}) {
            ModuleTable modules = engine_table();
            if (holed) modules.camera_ray = &holed_camera_ray;
            for (const Scene& scene : scenes) {
                REQUIRE(scene.traces_packets(modules));
                for (const auto& size : sizes) {
                    INFO("holed " << holed << ", triangles " << scene.triangles.size()
                                  << ", " << size[0] << "x" << size[1]);
                    Sources s(scene, modules, size[0], size[1]);
                    for (const Tile& tile : image_tiles(size[0], size[1])) {
                        const std::vector<Vec2> points =
                            tile_points(modules, tile, size[0], size[1]);
                        s.ahead.begin_tile(tile, nullptr);
                        const std::uint64_t traced = s.counters.camera_rays;
                        for (const Vec2& uv : points)
                            CHECK(same_sample(s.ahead.take(uv), s.cast.take(uv)));
                        CHECK(s.counters.camera_rays == traced);  // none cast
                        s.ahead.end_tile();
                    }
                    CHECK(s.counters.camera_rays == s.cast_counters.camera_rays);
                    CHECK(s.counters.camera_rays_reused == 0);
                    if (size[0] >= 4 && size[1] >= 4)
                        CHECK(s.counters.trace.packet_rays > 0);
                    CHECK(s.cast_counters.trace.packet_rays == 0);
                }
            }
        }
    }

    // A 16 x 16 tile whose loop takes 100 points in order and then asks for point 150:
    // from there every point is cast (one camera ray each, even point 100, next in the
    // order), and the thread's next tiles trace nothing ahead: their points are cast as
    // asked. A loop that takes every point in order and then asks one again, or asks
    // nothing at all in a tile, is a different case: the first keeps its thread tracing
    // ahead, the second stops it
    TEST_CASE("a loop that leaves the order is cast from there, and its thread stops") {
        const Scene scene = cornell_box();
        const ModuleTable modules = engine_table();
        const int W = 48, H = 32;
        const std::vector<Tile> tiles = image_tiles(W, H);
        REQUIRE(tiles.size() == 6);
        const auto points = [&](int t) { return tile_points(modules, tiles[t], W, H); };
        // Leaves the order midway
        {
            Sources s(scene, modules, W, H);
            const std::vector<Vec2> p = points(0);
            s.ahead.begin_tile(tiles[0], nullptr);
            for (int k = 0; k < 100; ++k)
                CHECK(same_sample(s.ahead.take(p[k]), s.cast.take(p[k])));
            CHECK(s.counters.camera_rays == 256);
            CHECK(same_sample(s.ahead.take(p[150]), s.cast.take(p[150])));
            for (int k = 100; k < 256; ++k)
                CHECK(same_sample(s.ahead.take(p[k]), s.cast.take(p[k])));
            CHECK(s.counters.camera_rays == 256 + 1 + 156);
            s.ahead.end_tile();
            const std::uint64_t packets = s.counters.trace.packet_rays;
            const std::vector<Vec2> q = points(1);
            s.ahead.begin_tile(tiles[1], nullptr);
            CHECK(s.counters.camera_rays == 256 + 1 + 156);  // nothing traced ahead
            for (const Vec2& uv : q)
                CHECK(same_sample(s.ahead.take(uv), s.cast.take(uv)));
            s.ahead.end_tile();
            CHECK(s.counters.camera_rays == 256 + 1 + 156 + 256);
            CHECK(s.counters.trace.packet_rays == packets);
        }
        // Every point in order, then one again: the next tile is traced ahead
        {
            Sources s(scene, modules, W, H);
            const std::vector<Vec2> p = points(2);
            s.ahead.begin_tile(tiles[2], nullptr);
            for (const Vec2& uv : p)
                s.ahead.take(uv);
            CHECK(same_sample(s.ahead.take(p[0]), s.cast.take(p[0])));
            CHECK(s.counters.camera_rays == 257);
            s.ahead.end_tile();
            s.ahead.begin_tile(tiles[3], nullptr);
            CHECK(s.counters.camera_rays == 257 + 256);
            s.ahead.end_tile();
        }
        // Nothing asked in a tile (or a tile cut short): the next is not traced ahead
        for (const int asked : {0, 255}) {
            CAPTURE(asked);
            Sources s(scene, modules, W, H);
            const std::vector<Vec2> p = points(4);
            s.ahead.begin_tile(tiles[4], nullptr);
            for (int k = 0; k < asked; ++k)
                s.ahead.take(p[k]);
            s.ahead.end_tile();
            s.ahead.begin_tile(tiles[5], nullptr);
            CHECK(s.counters.camera_rays == 256);
            s.ahead.end_tile();
        }
    }

    // What a tile keeps for the next frame is what its loop took, in its order: all the
    // samples traced ahead when it took them all (handed over whole), the ones taken in
    // order and then the cast ones when it left the order, the ones taken when it
    // stopped short, all and the extra one when it asked again. A tile kept whole must
    // stay whole while the next tiles are traced (the arrays change hands)
    TEST_CASE("a tile keeps the samples its loop took, in order, traced ahead or cast") {
        const Scene scene = spheres_on_a_plane();
        const ModuleTable modules = engine_table();
        const int W = 40, H = 40;
        const std::vector<Tile> tiles = image_tiles(W, H);
        enum class Loop { all, leave, short_, again };
        for (const Loop loop : {Loop::all, Loop::leave, Loop::short_, Loop::again}) {
            CAPTURE(static_cast<int>(loop));
            Sources s(scene, modules, W, H);
            std::vector<std::vector<CameraSample>> kept(tiles.size());
            std::vector<std::vector<Vec2>> asked(tiles.size());
            for (size_t t = 0; t < tiles.size(); ++t) {
                const std::vector<Vec2> p = tile_points(modules, tiles[t], W, H);
                std::vector<Vec2>& a = asked[t];
                switch (loop) {
                    case Loop::all:
                        a = p;
                        break;
                    case Loop::leave:  // in order to the middle, then backwards
                        a.assign(p.begin(), p.begin() + long(p.size() / 2));
                        a.insert(a.end(), p.rbegin(), p.rend() - long(p.size() / 2));
                        break;
                    case Loop::short_:
                        a.assign(p.begin(), p.begin() + long(p.size() / 3));
                        break;
                    case Loop::again:
                        a = p;
                        a.push_back(p.back());
                        break;
                }
                s.ahead.begin_tile(tiles[t], &kept[t]);
                for (const Vec2& uv : a)
                    s.ahead.take(uv);
                s.ahead.end_tile();
            }
            for (size_t t = 0; t < tiles.size(); ++t) {
                CAPTURE(t);
                REQUIRE(kept[t].size() == asked[t].size());
                for (size_t k = 0; k < kept[t].size(); ++k)
                    CHECK(same_sample(kept[t][k], s.cast.take(asked[t][k])));
            }
            CHECK_FALSE(s.counters.hits_overflow);
        }
    }

    // The frame that keeps the hits traces a tile's camera rays ahead in packets and
    // keeps those its pixel loop takes in order all at once (at the tile's end, or where
    // the loop leaves their order). Pixel loops that leave it, stop early or ask again:
    // the next frame takes every point the loop asks for from the kept hits, in the
    // loop's order, and gives a fresh render's image
    TEST_CASE(
        "kept camera hits hold every point the pixel loop asked for, in its order") {
        enum class Order { forward, half_backwards, skip_last, again };
        static Order order = Order::forward;
        static const ModuleTable* table = nullptr;
        static std::atomic<std::uint64_t> calls{0};  // (two threads render tiles)
        struct Loop {
            static void render_tile(const Tile& tile, const PixelRadiance& radiance,
                                    const ImageView& image) {
                const auto shade = [&](int i, int j) {
                    ++calls;
                    image.set(i, j,
                              radiance(table->image_plane_point(i, j, image.width,
                                                                image.height)));
                };
                const int w = tile.x1 - tile.x0, h = tile.y1 - tile.y0;
                for (int y = 0; y < h; ++y) {
                    for (int x = 0; x < w; ++x) {
                        // half_backwards: the tile's lower half right to left
                        const bool back = order == Order::half_backwards && 2 * y >= h;
                        if (order == Order::skip_last && y == h - 1 && x == w - 1)
                            continue;
                        shade(tile.x0 + (back ? w - 1 - x : x), tile.y0 + y);
                    }
                }
                if (order == Order::again) shade(tile.x0, tile.y0);
            }
        };
        const Scene scene = cornell_box();
        ModuleTable modules = reference_modules();
        modules.render_tile = &Loop::render_tile;
        table = &modules;
        REQUIRE(scene.traces_packets(modules) == engine_built());
        for (const Order o :
             {Order::forward, Order::half_backwards, Order::skip_last, Order::again}) {
            CAPTURE(static_cast<int>(o));
            order = o;
            RenderSettings settings;
            settings.width = 40;  // tiles of the full size and narrower ones
            settings.height = 24;
            CameraHits kept;
            settings.camera_hits = &kept;
            Image image, fresh;
            render(scene, scene.view, settings, modules, image);  // notes the key
            calls = 0;
            FrameStats s = render(scene, scene.view, settings, modules, image);
            const std::uint64_t asked = calls;
            CHECK(s.camera_rays_reused == 0);
            CHECK((s.camera_rays_in_packets > 0) ==
                  engine_built());  // the kept frame traced ahead
            REQUIRE(kept.valid);
            calls = 0;
            s = render(scene, scene.view, settings, modules, image);
            CHECK(calls == asked);
            CHECK(s.camera_rays == 0);
            CHECK(s.camera_rays_reused == asked);
            settings.camera_hits = nullptr;
            render(scene, scene.view, settings, modules, fresh);
            CHECK(image.pixels == fresh.pixels);
            // And again from a CameraHits cleared after a frame (its arrays' memory kept)
            kept.clear();
            settings.camera_hits = &kept;
            s = render(scene, scene.view, settings, modules, image);
            CHECK(s.camera_rays_reused == 0);
            s = render(scene, scene.view, settings, modules, image);
            CHECK(s.camera_rays_reused == 0);
            s = render(scene, scene.view, settings, modules, image);
            CHECK(s.camera_rays_reused == asked);
            CHECK(image.pixels == fresh.pixels);
        }
    }

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
                REQUIRE(scene.traces_packets(modules) == (engine && engine_built()));
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
}
