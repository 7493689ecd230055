// The renderer's sampling passes (modules 09 and 10, framework/src/render_sampling.cpp):
// defaults unchanged, thread-count independent, constant images exact, and the rules on
// the new settings.
#include <doctest/doctest.h>

#include <memory>
#include <vector>

#include "raylab/error.h"
#include "raylab/renderer.h"
#include "raylab/scenes.h"
#include "test_helpers.h"

using namespace raylab;

namespace {

Image draw(const Scene& scene, const RenderSettings& settings) {
    Image image;
    render(scene, scene.view, settings, reference_modules(), image);
    return image;
}

RenderSettings small(int threads) {
    RenderSettings s;
    s.width = 67;  // not a multiple of the tile size
    s.height = 45;
    s.threads = threads;
    return s;
}

}  // namespace

TEST_SUITE("sampling") {
    TEST_CASE("one grid sample per pixel is module 01's image, bit for bit") {
        const Scene scene = dtu_scene();
        RenderSettings grid = small(2);
        grid.sampling = PixelSampling::grid;
        grid.aa_threshold = 0.5f;
        CHECK(draw(scene, small(2)).pixels == draw(scene, grid).pixels);
    }

    TEST_CASE("sampled images do not depend on the thread count") {
        const Scene scene = dtu_scene();
        for (PixelSampling sampling :
             {PixelSampling::grid, PixelSampling::stratified, PixelSampling::adaptive}) {
            RenderSettings one = small(1), three = small(3);
            for (RenderSettings* s : {&one, &three}) {
                s->spp = 9;
                s->sampling = sampling;
                s->light_size = 1.0f;
                s->light_samples = 4;
            }
            INFO("pixel sampling " << to_string(sampling));
            CHECK(draw(scene, one).pixels == draw(scene, three).pixels);
        }
    }

    TEST_CASE("the seed changes stratified samples, and the same seed repeats them") {
        const Scene scene = cornell_box();
        RenderSettings a = small(2);
        a.spp = 4;
        a.light_size = 0.4f;
        a.light_samples = 4;
        RenderSettings b = a;
        b.seed = 2;
        CHECK(draw(scene, a).pixels == draw(scene, a).pixels);
        CHECK(draw(scene, a).pixels != draw(scene, b).pixels);
    }

    TEST_CASE("the adaptive pass refines only where neighbours disagree") {
        const Scene scene = dtu_scene();
        RenderSettings s = small(2);
        s.spp = 16;
        s.sampling = PixelSampling::adaptive;
        std::vector<std::uint16_t> samples;
        s.samples_map = &samples;
        const FrameStats stats =
            render(scene, scene.view, s, reference_modules(), *std::make_unique<Image>());
        REQUIRE(samples.size() == size_t(s.width * s.height));
        size_t refined = 0, total = 0;
        for (std::uint16_t n : samples) {
            CHECK((n == 1 || n == 17));
            refined += n == 17;
            total += n;
        }
        CHECK(refined > 0);
        CHECK(refined < samples.size() / 2);
        CHECK(stats.camera_rays == total);
    }

    TEST_CASE("a tiny area light renders like its point light") {
        // Le = I / A facing the scene's centre: straight below the light the two agree
        const Scene scene = dtu_scene();
        RenderSettings point = small(2), area = small(2);
        area.light_size = 1e-3f;
        area.light_samples = 4;
        const Image p = draw(scene, point), a = draw(scene, area);
        double sum_p = 0.0, sum_a = 0.0;
        for (size_t k = 0; k < p.pixels.size(); ++k) {
            sum_p += p.pixels[k].x;
            sum_a += a.pixels[k].x;
        }
        // The flat emitter is dimmer off its axis (cos theta_y), never brighter
        CHECK(sum_a <= sum_p * 1.001);
        CHECK(sum_a > 0.3 * sum_p);
    }

    TEST_CASE("bad sampling settings are rejected, naming the setting") {
        RenderSettings s = small(1);
        s.spp = 8;
        CHECK_THROWS_WITH_AS(validate(s), doctest::Contains("samples per pixel"), Error);
        s = small(1);
        s.aa_threshold = -0.1f;
        CHECK_THROWS_WITH_AS(validate(s), doctest::Contains("adaptive threshold"), Error);
        s = small(1);
        s.light_size = -1.0f;
        CHECK_THROWS_WITH_AS(validate(s), doctest::Contains("light size"), Error);
        s = small(1);
        s.light_samples = 0;
        CHECK_THROWS_WITH_AS(validate(s), doctest::Contains("light samples"), Error);
    }
}

TEST_SUITE("sampling") {
    // Faint vertical stripes were reported on the Cornell box's red block (16-64 light
    // samples). Light samples drawn alike for a whole column (a generator seeded from the
    // column only, say) would make them; this checks that the noise of two seeds'
    // images is independent from pixel to pixel: the column and row means of their
    // difference vary as much as independent noise's, no more.
    TEST_CASE("soft-shadow noise is independent from pixel to pixel: no stripes") {
        const Scene scene = cornell_box();
        RenderSettings a;
        a.width = 160;
        a.height = 120;
        a.threads = 2;
        a.light_size = 0.4f;
        a.light_samples = 16;
        RenderSettings b = a;
        b.seed = 2;
        const Image x = draw(scene, a), y = draw(scene, b);
        const int W = a.width, H = a.height;
        std::vector<double> col(static_cast<size_t>(W)), row(static_cast<size_t>(H));
        double sum2 = 0.0;
        for (int j = 0; j < H; ++j) {
            for (int i = 0; i < W; ++i) {
                const double v = double(x.at(i, j).x) - double(y.at(i, j).x);
                col[size_t(i)] += v / H;
                row[size_t(j)] += v / W;
                sum2 += v * v;
            }
        }
        const double var = sum2 / (double(W) * H);
        REQUIRE(var > 0.0);
        const auto mean_square = [](const std::vector<double>& m) {
            double s = 0.0;
            for (double v : m)
                s += v * v;
            return s / double(m.size());
        };
        // Independent noise: a mean of n values has a variance of var / n (ratio 1);
        // a stripe pattern gives up to n
        const double col_ratio = mean_square(col) / (var / H);
        const double row_ratio = mean_square(row) / (var / W);
        INFO("column means " << col_ratio << " x, row means " << row_ratio
                             << " x the variance of independent noise");
        CHECK(col_ratio < 2.0);
        CHECK(row_ratio < 2.0);
    }
}
