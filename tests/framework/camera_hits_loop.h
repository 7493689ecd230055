// The helpers of the camera hit sources' tests (raylab/camera_hit_sources.h;
// test_camera_hits_cast.cpp, _ahead.cpp, _kept.cpp, _kept_key.cpp): a student's module 01
// with state, which asks for its tile's points in one of several orders, may throw or
// raise the cancel flag, and counts its calls; scenes and modules; bitwise comparisons.
#pragma once

#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "raylab/camera_hit_sources.h"
#include "raylab/renderer.h"
#include "raylab/scenes.h"
#include "test_helpers.h"

namespace raylab::camera_hits_test {

// How the adversarial pixel loop walks a tile (k is a pixel's row-major index in it)
enum class Order {
    reference_like,         // rows top to bottom, columns left to right: all taken ahead
    backwards_from_middle,  // k = n/2 down to 0, then n-1 down to n/2+1
    columns,                // column by column
    other_tiles,            // each pixel, then the point-mirrored pixel (another tile)
    skip_rows,              // every third image row left black
    many_times,             // each pixel twice: as many points as a tile may keep
    off_grid,               // a quarter pixel up and left of each centre
    cut_short,              // the first half of the tile only
    leave_midway,           // in order, then off the grid from the middle on, then again
    tiles_differ,           // tiles in turn: reference_like, backwards, none asked
    over_the_bound,         // each pixel three times (not in kOrders): a tile keeps none
};
constexpr Order kOrders[] = {Order::reference_like, Order::backwards_from_middle,
                             Order::columns,        Order::other_tiles,
                             Order::skip_rows,      Order::many_times,
                             Order::off_grid,       Order::cut_short,
                             Order::leave_midway,   Order::tiles_differ};

inline const char* name(Order o) {
    static const char* const names[] = {"reference_like", "backwards_from_middle",
                                        "columns",        "other_tiles",
                                        "skip_rows",      "many_times",
                                        "off_grid",       "cut_short",
                                        "leave_midway",   "tiles_differ",
                                        "over_the_bound"};
    return names[static_cast<int>(o)];
}

// The loop's state, set by a test between frames (a student's loop with state: the same
// function pointer, so the same CameraHits key, whatever order it takes)
struct LoopState {
    Order order = Order::reference_like;
    const ModuleTable* table = nullptr;  // image_plane_point comes from here
    std::atomic<std::int64_t> calls{0};  // radiance calls this frame (threads add)
    std::int64_t throw_at = -1;          // the call that throws (-1: none)
    std::int64_t cancel_at = -1;         // the call that raises *cancel (-1: none)
    std::atomic<bool>* cancel = nullptr;
};
inline LoopState& loop_state() {
    static LoopState state;
    return state;
}
// Back to the reference-like order, no throw, no cancel (between test cases)
inline void reset_loop() {
    LoopState& st = loop_state();
    st.order = Order::reference_like;
    st.table = nullptr;
    st.calls = 0;
    st.throw_at = st.cancel_at = -1;
    st.cancel = nullptr;
}

struct LoopThrew : std::runtime_error {
    LoopThrew() : std::runtime_error("the pixel loop threw") {}
};

inline void adversarial_loop(const Tile& tile, const PixelRadiance& radiance,
                             const ImageView& image) {
    LoopState& st = loop_state();
    const int W = image.width, H = image.height;
    const auto ask = [&](const Vec2& uv) {
        const std::int64_t call = st.calls++;
        if (call == st.throw_at) throw LoopThrew();
        if (call == st.cancel_at) st.cancel->store(true);
        return radiance(uv);
    };
    const auto centre = [&](int i, int j) {
        return st.table->image_plane_point(i, j, W, H);
    };
    const auto shade = [&](int i, int j) { image.set(i, j, ask(centre(i, j))); };
    // A quarter pixel up and left: pixel (2i, 2j) of the image twice as fine
    const auto shade_off_grid = [&](int i, int j) {
        image.set(i, j, ask(st.table->image_plane_point(2 * i, 2 * j, 2 * W, 2 * H)));
    };
    const int w = tile.x1 - tile.x0, n = w * (tile.y1 - tile.y0);
    const auto i_of = [&](int k) { return tile.x0 + k % w; };
    const auto j_of = [&](int k) { return tile.y0 + k / w; };
    switch (st.order) {
        case Order::reference_like:
            for (int k = 0; k < n; ++k)
                shade(i_of(k), j_of(k));
            break;
        case Order::backwards_from_middle:
            for (int k = n / 2; k >= 0; --k)
                shade(i_of(k), j_of(k));
            for (int k = n - 1; k > n / 2; --k)
                shade(i_of(k), j_of(k));
            break;
        case Order::columns:
            for (int i = tile.x0; i < tile.x1; ++i)
                for (int j = tile.y0; j < tile.y1; ++j)
                    shade(i, j);
            break;
        case Order::other_tiles:
            for (int k = 0; k < n; ++k) {
                shade(i_of(k), j_of(k));
                ask(centre(W - 1 - i_of(k), H - 1 - j_of(k)));  // (not written)
            }
            break;
        case Order::skip_rows:
            for (int k = 0; k < n; ++k)
                if (j_of(k) % 3 != 1) shade(i_of(k), j_of(k));
            break;
        case Order::many_times:
        case Order::over_the_bound:
            for (int k = 0; k < n; ++k)
                for (int r = 0; r < (st.order == Order::many_times ? 2 : 3); ++r)
                    shade(i_of(k), j_of(k));
            break;
        case Order::off_grid:
            for (int k = 0; k < n; ++k)
                shade_off_grid(i_of(k), j_of(k));
            break;
        case Order::cut_short:
            for (int k = 0; k < (n + 1) / 2; ++k)
                shade(i_of(k), j_of(k));
            break;
        case Order::leave_midway:
            for (int k = 0; k < n; ++k) {
                if (k >= n / 2 && k % 2 == 1) {
                    shade_off_grid(i_of(k), j_of(k));
                } else {
                    shade(i_of(k), j_of(k));
                }
            }
            shade(tile.x0, tile.y0);
            break;
        case Order::tiles_differ:
            // A thread that met a backwards tile traces no more ahead: its next
            // reference_like tiles are kept pixel by pixel, the other threads' whole
            switch ((tile.x0 / kTileSize + tile.y0 / kTileSize) % 3) {
                case 0:
                    for (int k = 0; k < n; ++k)
                        shade(i_of(k), j_of(k));
                    break;
                case 1:
                    for (int k = n - 1; k >= 0; --k)
                        shade(i_of(k), j_of(k));
                    break;
            }
            break;
    }
}

// How many pixels differ in their bits (memcmp: -0 and 0 differ too); a size that differs
// counts as the largest number
inline size_t differing_pixels(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height) return size_t(-1);
    size_t diff = 0;
    for (size_t k = 0; k < a.pixels.size(); ++k)
        diff += std::memcmp(&a.pixels[k], &b.pixels[k], sizeof(Vec3)) != 0;
    return diff;
}

// Two camera samples the same, bit for bit: the point, traced, and every field of the hit
inline bool same_sample(const CameraHits::Sample& a, const CameraHits::Sample& b) {
    if (std::memcmp(&a.uv, &b.uv, sizeof(Vec2)) != 0 || a.traced != b.traced ||
        a.hit.has_value() != b.hit.has_value())
        return false;
    return !a.hit || std::memcmp(&*a.hit, &*b.hit, sizeof(Hit)) == 0;
}

// The tiles of a width x height image, as render() cuts it
inline std::vector<Tile> image_tiles(int width, int height) {
    std::vector<Tile> tiles;
    for (int y0 = 0; y0 < height; y0 += kTileSize)
        for (int x0 = 0; x0 < width; x0 += kTileSize)
            tiles.push_back(Tile{x0, y0, std::min(x0 + kTileSize, width),
                                 std::min(y0 + kTileSize, height)});
    return tiles;
}

// The pixel centres of tile in the reference loop's order (rows top to bottom, columns
// left to right)
inline std::vector<Vec2> tile_points(const ModuleTable& modules, const Tile& tile,
                                     int width, int height) {
    std::vector<Vec2> points;
    for (int j = tile.y0; j < tile.y1; ++j)
        for (int i = tile.x0; i < tile.x1; ++i)
            points.push_back(modules.image_plane_point(i, j, width, height));
    return points;
}

// A floor under one light: frames of any size, cheap
inline Scene lit_floor() {
    Scene scene;
    scene.materials.push_back(Material{"floor", Vec3(0.8f, 0.5f, 0.25f), Vec3(0.0f)});
    scene.planes.push_back({Plane{Vec3(0.0f, 1.0f, 0.0f), 0.0f}, 0});
    scene.lights.push_back(PointLight{Vec3(0.0f, 2.0f, 0.0f), Vec3(1.0f)});
    scene.view = View{Vec3(0.3f, 2.0f, 3.0f), Vec3(0.0f, 0.0f, 0.0f),
                      Vec3(0.0f, 1.0f, 0.0f), 50.0f};
    scene.commit();
    return scene;
}

// A floor plane, three spheres and no triangle, under two lights. The engine still traces
// its camera rays ahead in packets (Scene::traces_packets asks the modules, not the
// primitives), through a BVH of spheres alone
inline Scene spheres_on_a_plane() {
    Scene scene;
    scene.materials.push_back(Material{"floor", Vec3(0.7f, 0.6f, 0.5f), Vec3(0.0f)});
    scene.materials.push_back(Material{"ball", Vec3(0.2f, 0.4f, 0.8f), Vec3(0.0f)});
    scene.planes.push_back({Plane{Vec3(0.0f, 1.0f, 0.0f), 0.0f}, 0});
    scene.spheres.push_back({Sphere{Vec3(0.0f, 0.5f, 0.0f), 0.5f}, 1});
    scene.spheres.push_back({Sphere{Vec3(-1.1f, 0.3f, 0.6f), 0.3f}, 1});
    scene.spheres.push_back({Sphere{Vec3(0.9f, 0.4f, -0.5f), 0.4f}, 0});
    scene.lights.push_back(PointLight{Vec3(1.5f, 3.0f, 2.0f), Vec3(20.0f)});
    scene.lights.push_back(PointLight{Vec3(-2.0f, 2.0f, 1.0f), Vec3(5.0f)});
    scene.view = View{Vec3(0.0f, 1.5f, 4.0f), Vec3(0.0f, 0.4f, 0.0f),
                      Vec3(0.0f, 1.0f, 0.0f), 50.0f};
    scene.commit();
    return scene;
}

// The reference's sphere test under another address: not the engine's, so a table with
// it leaves the engine off (Scene::traces_packets)
inline std::optional<Hit> reference_sphere_elsewhere(const Ray& r, const Sphere& sphere) {
    return reference_modules().intersect_sphere(r, sphere);
}

// The reference's triangle test under another address: a module the key must tell apart
inline std::optional<Hit> reference_triangle_elsewhere(const Ray& r, const Vec3& v0,
                                                       const Vec3& v1, const Vec3& v2) {
    return reference_modules().intersect_triangle(r, v0, v1, v2);
}

// The reference camera ray, but not a valid ray (w = 0) left of u = -0.3 and through
// every point of the image's middle row (v = 0, odd heights; its origin not finite): a
// student's camera module with holes, whose pixels show the background
inline Ray holed_camera_ray(const PinholeCamera& camera, const Vec2& uv) {
    Ray r = reference_modules().camera_ray(camera, uv);
    if (uv.x < -0.3f) r.w = Vec3(0.0f);
    if (uv.y == 0.0f) r.o.x = std::numeric_limits<float>::infinity();
    return r;
}

// The reference camera seen in a mirror: the ray of (-u, v). Another camera module, with
// other hits at the same points
inline Ray mirrored_camera_ray(const PinholeCamera& camera, const Vec2& uv) {
    return reference_modules().camera_ray(camera, Vec2(-uv.x, uv.y));
}

// The table whose pixel loop is adversarial_loop, on the engine or the module path
inline ModuleTable adversarial_table(bool engine) {
    ModuleTable t = engine ? engine_table() : module_path_table();
    t.render_tile = &adversarial_loop;
    return t;
}

// What one frame did
struct Frame {
    FrameStats stats;
    std::int64_t calls = 0;  // radiance calls of the pixel loop
};

inline Frame render_frame(const Scene& scene, const RenderSettings& settings,
                          const ModuleTable& modules, Image& image) {
    loop_state().calls = 0;
    Frame f;
    f.stats = render(scene, scene.view, settings, modules, image);
    f.calls = loop_state().calls;
    return f;
}

// The counts of a frame whose every camera ray is valid: a frame that reuses takes each
// point it asks for from the kept hits or casts it, one ray each (it traces nothing
// ahead); any other frame casts at least one ray per point (more where rays traced ahead
// went untaken)
inline void check_counts(const Frame& f) {
    INFO("calls " << f.calls << ", camera rays " << f.stats.camera_rays << ", reused "
                  << f.stats.camera_rays_reused);
    if (f.stats.camera_rays_reused > 0) {
        CHECK(f.stats.camera_rays + f.stats.camera_rays_reused ==
              static_cast<std::uint64_t>(f.calls));
        CHECK(f.stats.camera_rays_in_packets == 0);
    } else {
        CHECK(f.stats.camera_rays >= static_cast<std::uint64_t>(f.calls));
    }
}

// The three frames after one that threw or was cancelled, with the loop behaving again:
// each gives the fresh image with true counts, and reuses every point it asks for when
// the frame before had kept them all (kept_all), otherwise only the third does (the
// first notes the key, the second keeps)
inline void check_frames_after(const Scene& scene, const RenderSettings& settings,
                               const ModuleTable& modules, const Image& fresh,
                               std::int64_t calls, bool kept_all) {
    Image image;
    for (int frame = 0; frame < 3; ++frame) {
        CAPTURE(frame);
        const Frame f = render_frame(scene, settings, modules, image);
        CHECK_FALSE(f.stats.cancelled);
        CHECK(differing_pixels(image, fresh) == 0);
        check_counts(f);
        const bool reuses = kept_all || frame == 2;
        CHECK(f.stats.camera_rays_reused == (reuses ? std::uint64_t(calls) : 0u));
    }
}

}  // namespace raylab::camera_hits_test
