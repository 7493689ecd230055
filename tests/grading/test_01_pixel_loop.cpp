// Graders of module 01_pixel_loop (docs/handouts/01_pixel_loop.md).
//
// Pixel (i, j) is column i from the left and row j from the top; its centre is the
// image-plane point u = (i + 1/2 - W/2) / H, v = (H/2 - j - 1/2) / H.
#include <mutex>
#include <vector>

#include "grading.h"

using namespace raylab;
using namespace raylab::grading;

namespace {

// Compares an image-plane point with the expected (u, v)
std::string diff_uv(const Vec2& got, double u, double v) {
    if (close(got.x, u, tol::kImagePlane) && close(got.y, v, tol::kImagePlane)) return "";
    return "expected (u, v) = " + show(Vec2(float(u), float(v))) + ", got " + show(got);
}

/// The pixel loop's output under a known radiance function: each call returns
/// (u, v, call number), so the stored image says which call wrote each pixel and where
/// that call sampled. The image lives inside a larger buffer whose margins must stay
/// untouched.
struct TileRun {
    int W, H;
    Tile tile;
    std::vector<Vec3> buffer;  // kMargin sentinels, W * H pixels, kMargin sentinels
    int calls = 0;
    static constexpr int kMargin = 64;
    static constexpr float kSentinel = -7.0f;

    TileRun(int W_, int H_, Tile tile_)
        : W(W_),
          H(H_),
          tile(tile_),
          buffer(size_t(W_ * H_ + 2 * kMargin), Vec3(kSentinel)) {
        std::mutex mutex;
        const PixelRadiance radiance = [&](const Vec2& uv) {
            const std::lock_guard<std::mutex> lock(mutex);
            return Vec3(uv.x, uv.y, float(calls++));
        };
        under_test::render_tile(tile, radiance, ImageView{buffer.data() + kMargin, W, H});
    }
    const Vec3& pixel(int i, int j) const { return buffer[size_t(kMargin + j * W + i)]; }
    bool inside(int i, int j) const {
        return i >= tile.x0 && i < tile.x1 && j >= tile.y0 && j < tile.y1;
    }
    int area() const { return (tile.x1 - tile.x0) * (tile.y1 - tile.y0); }
};

// Companion of the cases a constant passes: image_plane_point at random pixels of
// random images, against the formula in double
std::string work_image_plane_point() {
    for (int seed = 0; seed < 8; ++seed) {
        Rng rng(9100 + seed);
        const int W = rng.integer(2, 1000), H = rng.integer(2, 1000);
        const int i = rng.integer(0, W - 1), j = rng.integer(0, H - 1);
        const double u = (i + 0.5 - W / 2.0) / H, v = (H / 2.0 - j - 0.5) / H;
        const std::string why = diff_uv(under_test::image_plane_point(i, j, W, H), u, v);
        if (!why.empty())
            return "image_plane_point(" + std::to_string(i) + ", " + std::to_string(j) +
                   ", " + std::to_string(W) + ", " + std::to_string(H) + "): " + why;
    }
    return "";
}

// Companion of the cases a render_tile that does nothing passes: every pixel of a tile
// holds the radiance sampled at its own centre
std::string work_render_tile() {
    const TileRun run(20, 12, Tile{3, 2, 11, 9});
    for (int j = run.tile.y0; j < run.tile.y1; ++j) {
        for (int i = run.tile.x0; i < run.tile.x1; ++i) {
            const double u = (i + 0.5 - 10.0) / 12.0, v = (6.0 - j - 0.5) / 12.0;
            const std::string why = diff_uv(Vec2(run.pixel(i, j)), u, v);
            if (!why.empty())
                return show(run.tile) + " of a 20 x 12 image, pixel (" +
                       std::to_string(i) + ", " + std::to_string(j) + "): " + why;
        }
    }
    return "";
}

}  // namespace

TEST_SUITE("01_pixel_loop") {
    TEST_CASE("the centre pixel of an odd-sized image maps to the image-plane origin") {
        // W = 5, H = 3, pixel (2, 1): u = (2.5 - 2.5) / 3 = 0, v = (1.5 - 1.5) / 3 = 0
        needs_work("image_plane_point at random pixels", work_image_plane_point());
        INFO("image_plane_point(2, 1, 5, 3)");
        RAYLAB_CHECK_SAME(diff_uv(under_test::image_plane_point(2, 1, 5, 3), 0.0, 0.0));
    }

    TEST_CASE(
        "pixel (0, 0) samples its centre, half a pixel in from the top-left corner") {
        // W = 4, H = 2: u = (0.5 - 2) / 2 = -0.75, v = (1 - 0.5) / 2 = 0.25. Sampling the
        // corner instead would give (-1, 0.5); a bottom-up row order (-0.75, -0.25).
        INFO("image_plane_point(0, 0, 4, 2)");
        RAYLAB_CHECK_SAME(
            diff_uv(under_test::image_plane_point(0, 0, 4, 2), -0.75, 0.25));
    }

    TEST_CASE("row 0 is the top of the image, so v decreases as the row number grows") {
        // W = H = 10: v = (5 - j - 0.5) / 10, from 0.45 in row 0 to -0.45 in row 9
        for (int j = 0; j < 10; ++j) {
            INFO("image_plane_point(3, " << j << ", 10, 10)");
            if (!RAYLAB_CHECK_SAME(diff_uv(under_test::image_plane_point(3, j, 10, 10),
                                           -0.15, 0.45 - 0.1 * j)))
                break;
        }
    }

    TEST_CASE("the image plane is W / H wide and 1 high, symmetric about the centre") {
        // 640 x 480: the outermost pixel centres are half a pixel inside the edges,
        // u = +-(640 - 1) / (2 * 480) = +-0.665625, v = +-(480 - 1) / 960 = +-0.4989583
        const int W = 640, H = 480;
        const double u = 639.0 / 960.0, v = 479.0 / 960.0;
        const struct {
            int i, j;
            double u, v;
        } corners[] = {
            {0, 0, -u, v}, {W - 1, 0, u, v}, {0, H - 1, -u, -v}, {W - 1, H - 1, u, -v}};
        for (const auto& c : corners) {
            INFO("image_plane_point(" << c.i << ", " << c.j << ", 640, 480)");
            RAYLAB_CHECK_SAME(
                diff_uv(under_test::image_plane_point(c.i, c.j, W, H), c.u, c.v));
        }
    }

    TEST_CASE(
        "neighbouring pixel centres are 1 / H apart across and down (square pixels)") {
        // 300 x 100: every step in i adds 1/100 to u, every step in j subtracts 1/100
        // from v
        const Vec2 a = under_test::image_plane_point(17, 42, 300, 100);
        const Vec2 right = under_test::image_plane_point(18, 42, 300, 100);
        const Vec2 below = under_test::image_plane_point(17, 43, 300, 100);
        INFO("pixels (17, 42), (18, 42) and (17, 43) of a 300 x 100 image: "
             << show(a) << ", " << show(right) << ", " << show(below));
        RAYLAB_CHECK_SAME(diff_uv(right - a, 0.01, 0.0));
        RAYLAB_CHECK_SAME(diff_uv(below - a, 0.0, -0.01));
    }

    TEST_CASE("random pixels of random image sizes agree with the reference") {
        // The release's golden data holds these answers: they count with fresh pixels
        needs_work("image_plane_point at fresh random pixels", work_image_plane_point());
        for (int seed = 0; seed < 200; ++seed) {
            Rng rng(seed);
            const int W = rng.integer(1, 2000), H = rng.integer(1, 2000);
            const int i = rng.integer(0, W - 1), j = rng.integer(0, H - 1);
            INFO("seed " << seed << ": image_plane_point(" << i << ", " << j << ", " << W
                         << ", " << H << ")");
            const Vec2 want = expected<Vec2>(
                "01_pixel_loop/random pixels/" + std::to_string(seed), inputs(i, j, W, H),
                [&] { return reference_modules().image_plane_point(i, j, W, H); });
            const Vec2 got = under_test::image_plane_point(i, j, W, H);
            if (!RAYLAB_CHECK_SAME(diff_uv(got, want.x, want.y))) break;
        }
    }

    TEST_CASE("render_tile calls radiance exactly once for every pixel of the tile") {
        // A tile away from the image's corner: loops must start at x0, y0 and stop before
        // x1, y1
        const TileRun run(40, 30, Tile{16, 8, 32, 24});
        INFO(show(run.tile) << " of a 40 x 30 image");
        RAYLAB_CHECK(run.calls == run.area(), "radiance was called "
                                                  << run.calls << " times, expected "
                                                  << run.area());
        std::vector<int> writes(size_t(run.area()), 0);
        for (int j = run.tile.y0; j < run.tile.y1; ++j) {
            for (int i = run.tile.x0; i < run.tile.x1; ++i) {
                const int call = int(run.pixel(i, j).z);
                if (run.pixel(i, j).x == TileRun::kSentinel) {
                    FAIL_CHECK("pixel (" << i << ", " << j << ") was never written");
                    return;
                }
                if (call >= 0 && call < run.area() && ++writes[size_t(call)] > 1) {
                    FAIL_CHECK("pixel (" << i << ", " << j
                                         << ") holds the result of call " << call
                                         << ", which another pixel holds too");
                    return;
                }
            }
        }
    }

    TEST_CASE(
        "render_tile stores each pixel's radiance at that pixel, sampled at its centre") {
        // radiance returns its own (u, v): pixel (i, j) must hold the centre of pixel (i,
        // j). Swapped rows, swapped i and j or tile-relative coordinates all put another
        // pixel's centre there.
        const TileRun run(48, 20, Tile{8, 4, 24, 12});
        for (int j = run.tile.y0; j < run.tile.y1; ++j) {
            for (int i = run.tile.x0; i < run.tile.x1; ++i) {
                const double u = (i + 0.5 - 24.0) / 20.0, v = (10.0 - j - 0.5) / 20.0;
                INFO(show(run.tile) << " of a 48 x 20 image; pixel (" << i << ", " << j
                                    << ") holds the radiance sampled at (u, v) = "
                                    << show(Vec2(run.pixel(i, j))));
                if (!RAYLAB_CHECK_SAME(diff_uv(Vec2(run.pixel(i, j)), u, v))) return;
            }
        }
    }

    TEST_CASE("render_tile writes nothing outside its tile") {
        needs_work("render_tile storing each pixel's radiance", work_render_tile());
        const TileRun run(40, 30, Tile{16, 8, 32, 24});
        INFO(show(run.tile) << " of a 40 x 30 image");
        for (int k = 0; k < TileRun::kMargin; ++k) {
            const bool before = run.buffer[size_t(k)] == Vec3(TileRun::kSentinel);
            const bool after =
                run.buffer[run.buffer.size() - 1 - size_t(k)] == Vec3(TileRun::kSentinel);
            if (!before || !after) {
                FAIL_CHECK(
                    "render_tile wrote outside the image's pixels (before pixel 0 or "
                    "after the last one)");
                return;
            }
        }
        for (int j = 0; j < run.H; ++j) {
            for (int i = 0; i < run.W; ++i) {
                if (!run.inside(i, j) && run.pixel(i, j) != Vec3(TileRun::kSentinel)) {
                    FAIL_CHECK("pixel (" << i << ", " << j
                                         << ") lies outside the tile but "
                                         << "was written: " << show(run.pixel(i, j)));
                    return;
                }
            }
        }
    }

    TEST_CASE("a tile at the right and bottom border of an odd-sized image is filled") {
        // 50 x 37 in tiles of 16: the last tile is columns [48, 50), rows [32, 37)
        const TileRun run(50, 37, Tile{48, 32, 50, 37});
        INFO(show(run.tile) << " of a 50 x 37 image");
        RAYLAB_CHECK(run.calls == 10, "radiance was called "
                                          << run.calls << " times, expected 2 x 5 = 10");
        for (int j = 32; j < 37; ++j) {
            for (int i = 48; i < 50; ++i) {
                const double u = (i + 0.5 - 25.0) / 37.0, v = (18.5 - j - 0.5) / 37.0;
                INFO("pixel (" << i << ", " << j << ")");
                if (!RAYLAB_CHECK_SAME(diff_uv(Vec2(run.pixel(i, j)), u, v))) return;
            }
        }
    }

    TEST_CASE("the pixel loop renders the reference image of a test pattern") {
        // The release's golden data holds this image: it counts with a fresh tile
        needs_work("render_tile storing each pixel's radiance", work_render_tile());
        // A 37 x 23 image in 16 x 16 tiles, as the renderer cuts it, under a radiance
        // pattern of rings and stripes in (u, v); compared with the reference's image.
        const int W = 37, H = 23, S = 16;
        const PixelRadiance pattern = [](const Vec2& uv) {
            const float ring = std::cos(40.0f * glm::length(uv));
            return Vec3(0.5f + 0.5f * ring, uv.x + 0.5f, uv.y + 0.5f);
        };
        // The image sits inside a larger buffer, so that writes past its end are reported
        // instead of corrupting memory
        const int margin = W * S;
        bool outside = false;
        const auto render = [&](auto&& tile_fn) {
            std::vector<Vec3> buffer(size_t(W * H + 2 * margin), Vec3(-1.0f));
            for (int y0 = 0; y0 < H; y0 += S)
                for (int x0 = 0; x0 < W; x0 += S)
                    tile_fn(Tile{x0, y0, std::min(x0 + S, W), std::min(y0 + S, H)},
                            pattern, ImageView{buffer.data() + margin, W, H});
            for (int k = 0; k < margin; ++k)
                outside = outside || buffer[size_t(k)] != Vec3(-1.0f) ||
                          buffer[buffer.size() - 1 - size_t(k)] != Vec3(-1.0f);
            Image image(W, H);
            std::copy(buffer.begin() + margin, buffer.end() - margin,
                      image.pixels.begin());
            return image;
        };
        const Image want = expected_image("01_pixel_loop", "pattern", [&] {
            return render([](const Tile& t, const PixelRadiance& L, const ImageView& v) {
                reference_modules().render_tile(t, L, v);
            });
        });
        const Image got = render(under_test::render_tile);
        const std::string saved = save_image("01_pixel_loop-pattern", got);
        INFO("37 x 23 image in 16 x 16 tiles"
             << (saved.empty() ? "" : "; saved as " + saved));
        RAYLAB_CHECK(!outside, "the pixel loop wrote outside the image's pixels");
        RAYLAB_REQUIRE(want.width == W && want.height == H,
                       "the reference's image is " << want.width << " x " << want.height
                                                   << ", expected " << W << " x " << H);
        int bad = 0;
        std::string first;
        for (int j = 0; j < H; ++j) {
            for (int i = 0; i < W; ++i) {
                const std::string why =
                    diff_vec("value", got.at(i, j), want.at(i, j), tol::kPatternImage);
                if (!why.empty() && bad++ == 0)
                    first = "pixel (" + std::to_string(i) + ", " + std::to_string(j) +
                            ") " + why;
            }
        }
        RAYLAB_CHECK(bad == 0,
                     bad << " of " << W * H << " pixels differ; first: " << first);
    }
}
