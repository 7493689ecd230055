// Graders of module 09_antialiasing (docs/handouts/09_antialiasing.md).
//
// A pixel's value is L = sum_k w_k L(u_k, v_k) over samples at offsets (s_k, t_k) in
// [0, 1)^2, (0, 0) the top-left corner, with weights summing to 1. The grid puts sample
// (a, b) of n x n at ((a + 1/2) / n, (b + 1/2) / n); stratified sampling puts it at a
// random place in that cell. The adaptive test refines where the contrast
// (max - min) / (max + min) of a channel exceeds the threshold.
//
// The image the error cases render is a straight edge between two radiance values, whose
// exact pixel values are the areas of the pixel on either side of the edge (a polygon
// clipped by a line): the converged image, known exactly. Every case also fails a
// constant answer (no samples, all samples at the centre, always or never refining).
#include <algorithm>
#include <cmath>

#include "grading.h"

using namespace raylab;
using namespace raylab::grading;

namespace {

/// Offsets and weights are exact up to the rounding of (a + 1/2) / n.
constexpr double kOffset = 1e-6;
/// The weights of a pixel sum to 1 within float rounding of n^2 terms.
constexpr double kWeightSum = 1e-5;
/// A constant image stays constant: relative, float rounding of up to 1024 terms.
constexpr double kConstant = 1e-5;

using grading::show;
std::string show(const PixelSample& p) {
    return "{offset " + grading::show(p.offset) + ", weight " + grading::show(p.weight) +
           "}";
}

// The cell (a, b) of the n x n grid holding offset, or (-1, -1) outside [0, 1)^2
std::pair<int, int> cell_of(const Vec2& offset, int n) {
    if (!(offset.x >= 0.0f && offset.x < 1.0f && offset.y >= 0.0f && offset.y < 1.0f))
        return {-1, -1};
    return {std::min(int(offset.x * float(n)), n - 1),
            std::min(int(offset.y * float(n)), n - 1)};
}

// n^2 samples, every one inside [0, 1)^2 and exactly one in each cell
bool check_one_per_cell(const std::vector<PixelSample>& samples, int n) {
    if (!RAYLAB_CHECK(samples.size() == size_t(n * n),
                      "expected n^2 = " << n * n << " samples, got " << samples.size()))
        return false;
    std::vector<int> count(size_t(n * n), 0);
    for (const PixelSample& p : samples) {
        // Not a structured binding: C++17 lambdas (RAYLAB_CHECK) cannot capture one
        const std::pair<int, int> cell = cell_of(p.offset, n);
        const int a = cell.first, b = cell.second;
        if (!RAYLAB_CHECK(a >= 0, "expected every sample inside the pixel [0, 1)^2, got "
                                      << show(p)))
            return false;
        if (!RAYLAB_CHECK(++count[size_t(b * n + a)] == 1,
                          "expected one sample in each cell, but cell ("
                              << a << ", " << b << ") holds two, the second " << show(p)))
            return false;
    }
    return true;
}

bool check_weights(const std::vector<PixelSample>& samples, int n) {
    double sum = 0.0;
    for (const PixelSample& p : samples)
        sum += p.weight;
    return RAYLAB_CHECK(!samples.empty() && std::abs(sum - 1.0) <= kWeightSum,
                        "the " << samples.size() << " weights sum to " << show(sum)
                               << ", expected 1 (n = " << n << ")");
}

PixelRng rng_for(std::uint64_t seed) {
    return PixelRng::make(seed, 7, 11, 0);
}

// ---- The edge image -----------------------------------------------------------------
// Radiance L_bright where u cos(phi) + v sin(phi) > c, L_dark elsewhere
struct Edge {
    double phi, c;
    Vec3 bright{0.9f, 0.6f, 0.3f}, dark{0.05f, 0.1f, 0.2f};
    Vec3 at(const Vec2& uv) const {
        return uv.x * std::cos(phi) + uv.y * std::sin(phi) > c ? bright : dark;
    }
    // The exact share of the square [u0, u1] x [v0, v1] on the bright side: the square
    // clipped by the half-plane (Sutherland-Hodgman), then the shoelace area
    double bright_share(double u0, double v0, double u1, double v1) const {
        const double nx = std::cos(phi), ny = std::sin(phi);
        const double in[4][2] = {{u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}};
        std::vector<std::pair<double, double>> poly;
        for (int k = 0; k < 4; ++k) {
            const double* p = in[k];
            const double* q = in[(k + 1) % 4];
            const double fp = p[0] * nx + p[1] * ny - c, fq = q[0] * nx + q[1] * ny - c;
            if (fp > 0) poly.emplace_back(p[0], p[1]);
            if ((fp > 0) != (fq > 0)) {
                const double s = fp / (fp - fq);
                poly.emplace_back(p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1]));
            }
        }
        double area = 0.0;
        for (size_t k = 0; k < poly.size(); ++k) {
            const auto& p = poly[k];
            const auto& q = poly[(k + 1) % poly.size()];
            area += p.first * q.second - q.first * p.second;
        }
        return std::abs(area) / 2.0 / ((u1 - u0) * (v1 - v0));
    }
};

constexpr int kW = 24, kH = 16;  // a small image with a wide aspect ratio

// The converged value of pixel (i, j): the bright and dark radiance mixed by area
Vec3 converged(const Edge& edge, int i, int j) {
    const double aspect = double(kW) / kH;
    const double u0 = (double(i) / kW - 0.5) * aspect,
                 u1 = (double(i + 1) / kW - 0.5) * aspect;
    const double v1 = 0.5 - double(j) / kH, v0 = 0.5 - double(j + 1) / kH;
    const double a = edge.bright_share(u0, v0, u1, v1);
    return float(a) * edge.bright + float(1.0 - a) * edge.dark;
}

double rmse(const std::vector<Vec3>& got, const std::vector<Vec3>& want) {
    double sum = 0.0;
    for (size_t k = 0; k < got.size(); ++k) {
        const Vec3 d = got[k] - want[k];
        sum += double(glm::dot(d, d)) / 3.0;
    }
    return std::sqrt(sum / double(got.size()));
}

std::vector<Vec3> converged_image(const Edge& edge) {
    std::vector<Vec3> image;
    for (int j = 0; j < kH; ++j)
        for (int i = 0; i < kW; ++i)
            image.push_back(converged(edge, i, j));
    return image;
}

// The estimate of pixel (i, j) from samples, computed here (pixel_radiance has cases of
// its own; computing it here keeps the suite within its time limit)
Vec3 estimate(const Edge& edge, int i, int j, const std::vector<PixelSample>& samples) {
    Vec3 L(0.0f);
    for (const PixelSample& p : samples) {
        const Vec2 uv(((i + p.offset.x) / float(kW) - 0.5f) * float(kW) / float(kH),
                      0.5f - (j + p.offset.y) / float(kH));
        L += p.weight * edge.at(uv);
    }
    return L;
}

// The image from the code under test's samples(i, j) per pixel
template <class Samples>
std::vector<Vec3> render_edge(const Edge& edge, const Samples& samples) {
    std::vector<Vec3> image;
    for (int j = 0; j < kH; ++j)
        for (int i = 0; i < kW; ++i)
            image.push_back(estimate(edge, i, j, samples(i, j)));
    return image;
}

// RMSE against the converged image of stratified sampling with n x n samples, averaged
// over a few edges
double stratified_error(int n, std::uint64_t seed) {
    double sum = 0.0;
    for (int e = 0; e < 3; ++e) {
        const Edge edge{0.3 + 1.1 * e, 0.05 * e - 0.04};
        const auto image = render_edge(edge, [&](int i, int j) {
            return under_test::stratified_samples(n, PixelRng::make(seed + e, i, j, 0));
        });
        sum += rmse(image, converged_image(edge));
    }
    return sum / 3.0;
}

// Companions of the cases a constant passes (one sample of weight 1, a constant image)

// n x n samples, one in each cell, for n = 2 and 3, from both functions
std::string work_samples() {
    for (int n = 2; n <= 3; ++n) {
        for (int stratified = 0; stratified <= 1; ++stratified) {
            const auto samples = stratified
                                     ? under_test::stratified_samples(n, rng_for(77))
                                     : under_test::grid_samples(n);
            const std::string call =
                stratified
                    ? "stratified_samples(" + std::to_string(n) + ", PixelRng seed 77)"
                    : "grid_samples(" + std::to_string(n) + ")";
            if (samples.size() != size_t(n * n))
                return call + ": expected " + std::to_string(n * n) + " samples, got " +
                       std::to_string(samples.size());
            std::vector<int> count(size_t(n * n), 0);
            for (const PixelSample& p : samples) {
                const auto [a, b] = cell_of(p.offset, n);
                if (a < 0 || count[size_t(b * n + a)]++ > 0)
                    return call + ": expected one sample in each cell, but " + show(p) +
                           (a < 0 ? " lies outside the pixel" : " shares its cell");
            }
        }
    }
    return "";
}

// The weighted sum of a radiance that varies over the pixel, at samples of random places
// and weights
std::string work_pixel_radiance() {
    Rng rng(9950);
    std::vector<PixelSample> samples(5);
    for (PixelSample& p : samples)
        p = PixelSample{Vec2(rng.uniform(0.0f, 1.0f), rng.uniform(0.0f, 1.0f)),
                        rng.uniform(0.05f, 0.4f)};
    const PixelRadiance ramp = [](const Vec2& uv) {
        return Vec3(1.0f + uv.x, 2.0f - uv.y, 3.0f + uv.x * uv.y);
    };
    glm::dvec3 want(0.0);
    for (const PixelSample& p : samples) {
        const double u = ((7 + double(p.offset.x)) / kW - 0.5) * kW / kH,
                     v = 0.5 - (4 + double(p.offset.y)) / kH;
        want += double(p.weight) * glm::dvec3(1 + u, 2 - v, 3 + u * v);
    }
    const std::string why = diff_radiance(
        "L", under_test::pixel_radiance(7, 4, kW, kH, samples, ramp), Vec3(want));
    return why.empty() ? ""
                       : "pixel_radiance(7, 4, 24, 16, five samples of random "
                         "places and weights, radiance (1 + u, 2 - v, 3 + u v)): " +
                             why;
}

}  // namespace

TEST_SUITE("09_antialiasing") {
    TEST_CASE("grid samples sit at the centres of the n x n cells, weights 1 / n^2") {
        // n = 3: offsets 1/6, 1/2, 5/6 in each coordinate, weights 1/9
        for (int n = 1; n <= 6; ++n) {
            INFO("grid_samples(n = " << n << ")");
            const auto samples = under_test::grid_samples(n);
            if (!check_one_per_cell(samples, n)) break;
            for (const PixelSample& p : samples) {
                const auto [a, b] = cell_of(p.offset, n);
                const Vec2 centre((a + 0.5f) / float(n), (b + 0.5f) / float(n));
                RAYLAB_CHECK(std::abs(p.offset.x - centre.x) <= kOffset &&
                                 std::abs(p.offset.y - centre.y) <= kOffset &&
                                 std::abs(p.weight - 1.0 / (n * n)) <= kOffset,
                             "got " << show(p) << ", expected the cell centre "
                                    << grading::show(centre) << " and weight 1/"
                                    << n * n);
            }
        }
    }

    TEST_CASE("stratified samples put one sample inside each cell of the n x n grid") {
        for (int n = 1; n <= 8; ++n) {
            for (std::uint64_t seed = 1; seed <= 20; ++seed) {
                INFO("stratified_samples(n = " << n << ", PixelRng seed " << seed << ")");
                if (!check_one_per_cell(under_test::stratified_samples(n, rng_for(seed)),
                                        n))
                    return;
            }
        }
    }

    TEST_CASE("the weights of a pixel's samples sum to 1") {
        needs_work("n x n samples, one in each cell", work_samples());
        for (int n = 1; n <= 8; ++n) {
            INFO("n = " << n << ", PixelRng seed 3");
            check_weights(under_test::grid_samples(n), n);
            check_weights(under_test::stratified_samples(n, rng_for(3)), n);
        }
    }

    TEST_CASE("stratified samples are random: the same seed repeats them, others move") {
        // Over 400 seeds the sample of the 1 x 1 grid must cover the pixel: mean 1/2 and
        // variance 1/12 = 0.0833 of each coordinate, to 0.05 and 0.02 (about 6 and 4
        // standard errors)
        const auto a = under_test::stratified_samples(4, rng_for(5));
        const auto b = under_test::stratified_samples(4, rng_for(5));
        const auto c = under_test::stratified_samples(4, rng_for(6));
        INFO("n = 4, PixelRng seeds 5, 5 and 6");
        RAYLAB_REQUIRE(a.size() == 16, "expected 16 samples, got " << a.size());
        RAYLAB_REQUIRE(b.size() == 16, "expected 16 samples, got " << b.size());
        RAYLAB_REQUIRE(c.size() == 16, "expected 16 samples, got " << c.size());
        bool same = true, moved = false;
        for (size_t k = 0; k < 16; ++k) {
            same = same && a[k].offset == b[k].offset;
            moved = moved || a[k].offset != c[k].offset;
        }
        RAYLAB_CHECK(same, "the same seed gave different samples");
        RAYLAB_CHECK(moved, "seeds 5 and 6 gave the same samples: use rng.uniform()");
        double mean[2] = {0, 0}, square[2] = {0, 0};
        const int count = 400;
        for (int seed = 0; seed < count; ++seed) {
            const auto one = under_test::stratified_samples(1, rng_for(100 + seed));
            RAYLAB_REQUIRE(one.size() == 1,
                           "n = 1: expected 1 sample, got " << one.size());
            for (int d = 0; d < 2; ++d) {
                mean[d] += one[0].offset[d] / count;
                square[d] += one[0].offset[d] * one[0].offset[d] / count;
            }
        }
        for (int d = 0; d < 2; ++d) {
            const double var = square[d] - mean[d] * mean[d];
            INFO("coordinate " << d << " over seeds 100..499: mean " << show(mean[d])
                               << ", variance " << show(var));
            RAYLAB_CHECK(
                std::abs(mean[d] - 0.5) < 0.05 && std::abs(var - 1.0 / 12) < 0.02,
                "the samples are not uniform over their cell");
        }
    }

    TEST_CASE("each cell of a stratified pixel is jittered independently") {
        // The place inside its cell, offset n - (a, b), must differ from cell to cell: a
        // copy of the generator per cell (PixelRng passed or copied by value) jitters
        // every cell alike, and the pattern repeats in each cell
        for (std::uint64_t seed = 1; seed <= 20; ++seed) {
            const int n = 4;
            const auto samples = under_test::stratified_samples(n, rng_for(seed));
            INFO("stratified_samples(n = 4, PixelRng seed " << seed << ")");
            RAYLAB_REQUIRE(samples.size() == size_t(n * n),
                           "expected 16 samples, got " << samples.size());
            std::vector<Vec2> jitter;
            for (const PixelSample& p : samples) {
                const auto [a, b] = cell_of(p.offset, n);
                jitter.push_back(p.offset * float(n) - Vec2(float(a), float(b)));
            }
            for (size_t k = 0; k < jitter.size(); ++k) {
                for (size_t m = k + 1; m < jitter.size(); ++m) {
                    const Vec2 d = glm::abs(jitter[k] - jitter[m]);
                    if (!RAYLAB_CHECK(d.x > 1e-5f || d.y > 1e-5f,
                                      "expected a different place in each cell, but "
                                          << show(samples[k]) << " and "
                                          << show(samples[m]) << " sit at the same place "
                                          << grading::show(jitter[k])
                                          << " of their cells: draw every cell's numbers "
                                             "from the one generator, in turn"))
                        return;
                }
            }
        }
    }

    TEST_CASE("a sample looks through the image-plane point of its place in the pixel") {
        // Pixel (5, 2) of a 24 x 16 image: u = ((5 + s) / 24 - 1/2) 1.5,
        // v = 1/2 - (2 + t) / 16. Offset (1/2, 1/2) is module 01's pixel centre
        // (-0.4063, 0.34375); (0, 0) the top-left corner (-0.4375, 0.375)
        const std::vector<PixelSample> samples = {{Vec2(0.5f, 0.5f), 0.25f},
                                                  {Vec2(0.0f, 0.0f), 0.25f},
                                                  {Vec2(0.75f, 0.25f), 0.5f}};
        std::vector<Vec2> asked;
        const PixelRadiance record = [&](const Vec2& uv) {
            asked.push_back(uv);
            return Vec3(1.0f);
        };
        (void)under_test::pixel_radiance(5, 2, kW, kH, samples, record);
        INFO("pixel_radiance(5, 2, 24, 16, three samples)");
        RAYLAB_REQUIRE(asked.size() == 3,
                       "expected radiance to be called 3 times, once per sample, got "
                           << asked.size() << " calls");
        for (size_t k = 0; k < 3; ++k) {
            const Vec2 st = samples[k].offset;
            const Vec2 want(((5 + st.x) / 24.0f - 0.5f) * 1.5f,
                            0.5f - (2 + st.y) / 16.0f);
            RAYLAB_CHECK(close(asked[k].x, want.x, tol::kImagePlane) &&
                             close(asked[k].y, want.y, tol::kImagePlane),
                         "the sample " << show(samples[k]) << " looked through "
                                       << grading::show(asked[k]) << ", expected "
                                       << grading::show(want));
        }
    }

    TEST_CASE("the pixel's value is the weighted sum of its samples' radiance") {
        // Radiance (1, 2, 4) at the first sample, (8, 16, 32) at the second; weights 0.75
        // and 0.25: L = (2.75, 5.5, 11)
        const std::vector<PixelSample> samples = {{Vec2(0.25f, 0.5f), 0.75f},
                                                  {Vec2(0.75f, 0.5f), 0.25f}};
        const PixelRadiance radiance = [](const Vec2& uv) {
            return uv.x < -0.65625f ? Vec3(1, 2, 4) : Vec3(8, 16, 32);
        };
        INFO("pixel_radiance(1, 3, 24, 16, two samples)");
        RAYLAB_CHECK_SAME(diff_radiance(
            "L", under_test::pixel_radiance(1, 3, kW, kH, samples, radiance),
            Vec3(2.75f, 5.5f, 11.0f)));
    }

    TEST_CASE("a constant image stays exact with any number of samples") {
        needs_work("n x n samples, one in each cell", work_samples());
        needs_work("the weighted sum over a radiance that varies", work_pixel_radiance());
        const Vec3 c(0.3f, 0.7f, 1.9f);
        const PixelRadiance constant = [&](const Vec2&) { return c; };
        for (int n = 1; n <= 8; ++n) {
            INFO("n = " << n << ", PixelRng seed 9, pixel (3, 4)");
            const Vec3 grid = under_test::pixel_radiance(
                3, 4, kW, kH, under_test::grid_samples(n), constant);
            const Vec3 jittered = under_test::pixel_radiance(
                3, 4, kW, kH, under_test::stratified_samples(n, rng_for(9)), constant);
            RAYLAB_CHECK(close_abs(grid, c, kConstant * 2) &&
                             close_abs(jittered, c, kConstant * 2),
                         "grid gave " << grading::show(grid) << ", stratified "
                                      << grading::show(jittered) << ", expected "
                                      << grading::show(c));
        }
    }

    TEST_CASE("the error against the converged image falls as samples grow") {
        // Edges between two colours over a 24 x 16 image, exact pixel values from the
        // area on each side. Stratified error falls like N^(-3/4) (handout 09 §3): from
        // n = 1 to n = 8 by about 22; the reference measures 0.052, 0.019, 0.0063,
        // 0.0025. Required: each doubling of n cuts it to 0.8 at most, n = 8 to 1/6 of n
        // = 1
        const std::uint64_t seed = 42;
        INFO("PixelRng seeds 42..44, per pixel PixelRng::make(seed, i, j, 0)");
        double last = 0.0, first = 0.0;
        for (int n = 1; n <= 8; n *= 2) {
            const double e = stratified_error(n, seed);
            INFO("n = " << n << ": RMSE " << show(e) << ", previous " << show(last));
            if (n == 1) first = e;
            if (n > 1 && !RAYLAB_CHECK(e < 0.8 * last, "the error did not fall")) break;
            if (n == 8) RAYLAB_CHECK(e < first / 6.0, "the error fell too little");
            last = e;
        }
    }
}

namespace {

bool check_refine(const std::vector<Vec3>& L, float threshold, bool want) {
    std::string values;
    for (const Vec3& v : L)
        values += " " + grading::show(v);
    INFO("needs_more_samples(L =" << values << ", threshold " << show(threshold) << ")");
    const bool got = under_test::needs_more_samples(L, threshold);
    return RAYLAB_CHECK(got == want, "expected " << (want ? "true" : "false") << ", got "
                                                 << (got ? "true" : "false"));
}

}  // namespace

TEST_SUITE("09_antialiasing") {
    TEST_CASE("the adaptive test refines where the contrast exceeds the threshold") {
        // Contrast (x - 0.5) / (x + 0.5) against threshold 0.1: x = 0.62 gives 0.108
        // (refine), x = 0.6 gives 0.091 (do not)
        check_refine({Vec3(0.5f), Vec3(0.5f), Vec3(0.62f)}, 0.1f, true);
        check_refine({Vec3(0.5f), Vec3(0.5f), Vec3(0.6f)}, 0.1f, false);
        check_refine({Vec3(0.5f), Vec3(0.5f), Vec3(0.5f)}, 0.1f, false);
        // The same values with a threshold of 0.05: 0.091 > 0.05
        check_refine({Vec3(0.5f), Vec3(0.5f), Vec3(0.6f)}, 0.05f, true);
    }

    TEST_CASE("a contrast exactly at the threshold does not refine: C > threshold") {
        // (0.75 - 0.25) / (0.75 + 0.25) = 0.5 and (0.625 - 0.375) / 1 = 0.25, exact in
        // float: refine only where the contrast exceeds the threshold
        check_refine({Vec3(0.25f), Vec3(0.75f)}, 0.5f, false);
        check_refine({Vec3(0.375f), Vec3(0.625f)}, 0.25f, false);
        // Paired: just below the contrast, both refine
        check_refine({Vec3(0.25f), Vec3(0.75f)}, 0.4375f, true);
        check_refine({Vec3(0.375f), Vec3(0.625f)}, 0.1875f, true);
    }

    TEST_CASE("the contrast is relative: the same step is larger in the dark") {
        // A step of 0.1 is contrast 0.1 / 1.9 = 0.053 between 0.9 and 1.0 but 0.1 / 0.3 =
        // 0.33 between 0.1 and 0.2
        check_refine({Vec3(0.9f), Vec3(1.0f)}, 0.2f, false);
        check_refine({Vec3(0.1f), Vec3(0.2f)}, 0.2f, true);
    }

    TEST_CASE("the contrast is taken per channel") {
        // Only green differs: (0.2, 0.2, 0.2) and (0.2, 0.6, 0.2) have green contrast 0.5
        check_refine({Vec3(0.2f), Vec3(0.2f, 0.6f, 0.2f)}, 0.3f, true);
        check_refine({Vec3(0.2f, 0.4f, 0.6f), Vec3(0.6f, 0.4f, 0.2f)}, 0.3f, true);
        check_refine({Vec3(0.2f, 0.4f, 0.6f), Vec3(0.2f, 0.4f, 0.6f)}, 0.3f, false);
    }

    TEST_CASE("black next to black needs no more samples, black next to grey does") {
        // max + min = 0 has contrast 0 (no division by zero); 0 and 0.01 have contrast 1
        check_refine({Vec3(0.0f), Vec3(0.0f), Vec3(0.0f)}, 0.1f, false);
        check_refine({Vec3(0.0f), Vec3(0.0f), Vec3(0.01f)}, 0.1f, true);
        check_refine({Vec3(0.3f)}, 0.1f, false);
    }

    TEST_CASE("adaptive sampling refines the pixels along an edge and cuts the error") {
        // First pass: one sample at each pixel centre (grid_samples(1)). A pixel whose
        // first sample and its 8 neighbours' disagree (threshold 0.1) gets 4 x 4
        // stratified samples. The edge crosses about one pixel per column of 24, so a
        // 3-pixel-wide band, under 40% of the 384 pixels, is refined; and the error falls
        // to under 1/3 of the 1-sample image's (the reference refines 42 pixels, RMSE
        // 0.033 -> 0.0059)
        const Edge edge{0.35, 0.02};
        const std::vector<Vec3> want = converged_image(edge);
        const std::vector<PixelSample> centre = under_test::grid_samples(1);
        const auto first = render_edge(edge, [&](int, int) { return centre; });
        std::vector<Vec3> adaptive = first;
        int refined = 0, missed_edge = 0;
        for (int j = 0; j < kH; ++j) {
            for (int i = 0; i < kW; ++i) {
                std::vector<Vec3> L = {first[size_t(j * kW + i)]};
                for (int b = std::max(j - 1, 0); b <= std::min(j + 1, kH - 1); ++b)
                    for (int a = std::max(i - 1, 0); a <= std::min(i + 1, kW - 1); ++a)
                        if (a != i || b != j) L.push_back(first[size_t(b * kW + a)]);
                const bool refine = under_test::needs_more_samples(L, 0.1f);
                const Vec3 exact = want[size_t(j * kW + i)];
                const bool on_edge = exact != edge.bright && exact != edge.dark;
                missed_edge += on_edge && !refine;
                if (!refine) continue;
                ++refined;
                adaptive[size_t(j * kW + i)] = estimate(
                    edge, i, j,
                    under_test::stratified_samples(4, PixelRng::make(7, i, j, 1)));
            }
        }
        const double e1 = rmse(first, want), ea = rmse(adaptive, want);
        INFO("PixelRng seed 7; refined " << refined << " of " << kW * kH
                                         << " pixels; RMSE 1 sample " << show(e1)
                                         << ", adaptive " << show(ea));
        RAYLAB_CHECK(missed_edge == 0,
                     missed_edge << " pixels the edge crosses were not refined");
        RAYLAB_CHECK(refined > 0 && refined < 0.4 * kW * kH,
                     "expected a band of pixels along the edge to be refined");
        RAYLAB_CHECK(ea < e1 / 3.0,
                     "the adaptive image is not much closer to the "
                     "converged one");
    }
}
