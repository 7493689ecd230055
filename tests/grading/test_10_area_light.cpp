// Graders of module 10_area_light (docs/handouts/10_area_light.md).
//
// A rectangular light p + s e1 + t e2 of radiance Le, sampled at N points y_k, gives a
// surface point x the samples wi_k = (y_k - x) / r_k and Li_k = Le A cos(theta_y) /
// (N r_k^2). Summed with the cosine at x, they estimate the irradiance
//   E = sum_k Li_k max(n . wi_k, 0)  ~  Le * integral of cos(theta_x) cos(theta_y) / r^2
//   dA,
// which these tests compare with closed forms: a tiny light is a point light of intensity
// Le A cos(theta_y); a large parallel light has the closed form of a differential area
// facing a rectangle (derived below); and the penumbra of a straight edge has the width
// similar triangles give. Every case fails a constant answer (no points, Li = 0, or every
// sample at one place on the light).
#include <algorithm>
#include <cmath>

#include "grading.h"

using namespace raylab;
using namespace raylab::grading;

namespace {

/// Irradiance of a tiny light against the point light it approximates (relative): the
/// light's size over its distance squared, 1e-5 here, plus float rounding.
constexpr double kSmallLight = 1e-3;
/// Irradiance of 2048 stratified samples against the closed form (relative); the
/// reference is within 6e-4.
constexpr double kStratified = 2e-3;
/// The same for 2048 uniform samples: about 4 standard errors of the estimate (the
/// reference is off by 0.012 with seed 11).
constexpr double kUniform = 0.06;
/// Visible share of the light in the penumbra (absolute): one cell of the 16 x 16 strata.
constexpr double kShare = 0.08;

PixelRng rng_for(std::uint64_t seed) {
    return PixelRng::make(seed, 3, 5, 1);
}

std::string show(const AreaLight& l) {
    return "AreaLight{p " + grading::show(l.p) + ", e1 " + grading::show(l.e1) + ", e2 " +
           grading::show(l.e2) + ", Le " + grading::show(l.Le) + "}";
}
using grading::show;

// A square light of side a, centred at c, facing down (e1 x e2 = -a^2 y)
AreaLight ceiling_light(const Vec3& c, float a, const Vec3& Le) {
    const Vec3 e1(a, 0, 0), e2(0, 0, a);
    return AreaLight{c - 0.5f * (e1 + e2), e1, e2, Le};
}

// E = sum_k Li_k max(n . wi_k, 0) with the code under test's points and samples
double irradiance(const AreaLight& light, const Vec3& x, const Vec3& n, int N,
                  bool stratified, std::uint64_t seed) {
    const auto xi = under_test::light_sample_points(N, stratified, rng_for(seed));
    RAYLAB_REQUIRE(xi.size() == size_t(N), "light_sample_points(" << N << "): expected "
                                                                  << N << " points, got "
                                                                  << xi.size());
    double E = 0.0;
    for (const Vec2& p : xi) {
        const LightSample s = under_test::sample_area_light(light, x, p, N);
        E += double(s.Li.x) * std::max(0.0, double(glm::dot(n, s.wi)));
    }
    return E;
}

// The closed form. A differential area at x facing a parallel rectangle [0, a] x [0, b]
// at height c, x under its corner: cos(theta_x) = cos(theta_y) = c / r,
// r^2 = u^2 + v^2 + c^2, so
//   E = Le int_0^a int_0^b c^2 / (u^2 + v^2 + c^2)^2 du dv.
// The inner integral over v is, with q^2 = u^2 + c^2,
//   c^2 [v / (2 q^2 (v^2 + q^2)) + atan(v / q) / (2 q^3)]_0^b,
// and integrating over u (substituting u = sqrt(c^2 + b^2) tan t in the first term and
// parts in the second) gives, with X = a / c and Y = b / c,
//   E = Le / 2 [X / sqrt(1 + X^2) atan(Y / sqrt(1 + X^2))
//               + Y / sqrt(1 + Y^2) atan(X / sqrt(1 + Y^2))],
// Le times pi F, F the view factor of a differential area to a parallel rectangle in
// Howell's catalogue of configuration factors. Checks: X, Y -> inf gives
// Le / 2 (pi/4 + pi/4) = pi Le / 4, a quarter of the whole sky's pi Le; for a = 1, b = 2,
// c = 1.5 a 1500 x 1500 midpoint sum of the integral agrees to 3e-8.
double corner_irradiance(double Le, double a, double b, double c) {
    const double X = a / c, Y = b / c;
    const double sx = std::sqrt(1 + X * X), sy = std::sqrt(1 + Y * Y);
    return Le / 2 * (X / sx * std::atan(Y / sx) + Y / sy * std::atan(X / sy));
}

bool check_E(double got, double want, double tolerance, const std::string& what) {
    INFO(what);
    return RAYLAB_CHECK(std::abs(got - want) <= tolerance * std::abs(want),
                        "E = " << show(got) << ", expected " << show(want)
                               << " (relative tolerance " << show(tolerance) << ")");
}

bool check_sample(const AreaLight& light, const Vec3& x, const Vec2& xi, int N,
                  const LightSample& want) {
    INFO("sample_area_light(" << show(light) << ", x = " << show(x)
                              << ", xi = " << show(xi) << ", N = " << N << ")");
    const LightSample got = under_test::sample_area_light(light, x, xi, N);
    std::string why = diff_vec("wi", got.wi, want.wi, tol::kDirection);
    if (!close(got.r, want.r, tol::kDistance))
        why += "; r: expected " + show(want.r) + ", got " + show(got.r);
    const std::string li = diff_radiance("Li", got.Li, want.Li);
    if (!li.empty()) why += "; " + li;
    return RAYLAB_CHECK_SAME(why);
}

// The share of N samples whose segment from x to the light passes the half-plane
// {y = h, x > 0} (a blocker with a straight edge along z)
double visible_share(const AreaLight& light, const Vec3& x, float h, int N) {
    const auto xi = under_test::light_sample_points(N, true, rng_for(77));
    RAYLAB_REQUIRE(xi.size() == size_t(N),
                   "light_sample_points: expected " << N << " points, got " << xi.size());
    int visible = 0;
    for (const Vec2& p : xi) {
        const LightSample s = under_test::sample_area_light(light, x, p, N);
        const Vec3 y = x + s.r * s.wi;  // the point on the light
        const float t = (h - x.y) / (y.y - x.y);
        const bool blocked = t > 0 && t < 1 && x.x + t * (y.x - x.x) > 0.0f;
        visible += !blocked && s.Li.x > 0.0f;
    }
    return double(visible) / N;
}

}  // namespace

TEST_SUITE("10_area_light") {
    TEST_CASE("the centre of a light straight above gives Li = Le A / (N r^2)") {
        // A 2 x 2 light at height 4 facing down, sample at its centre: wi = up, r = 4,
        // cos(theta_y) = 1, Li = Le 4 / 16 = (0.25, 0.5, 0.75) for Le = (1, 2, 3)
        const AreaLight light = ceiling_light(Vec3(0, 4, 0), 2.0f, Vec3(1, 2, 3));
        check_sample(light, Vec3(0.0f), Vec2(0.5f), 1,
                     LightSample{Vec3(0, 1, 0), 4.0f, Vec3(0.25f, 0.5f, 0.75f)});
    }

    TEST_CASE("the light point is y = p + xi_1 e1 + xi_2 e2") {
        // The corner xi = (0, 0) of the light above is y = (-1, 4, -1); xi = (1, 0.25)
        // is y = (1, 4, -0.5). Seen from x = (1, 0, -0.5) the second is straight up
        const AreaLight light = ceiling_light(Vec3(0, 4, 0), 2.0f, Vec3(1.0f));
        check_sample(light, Vec3(-1, 0, -1), Vec2(0.0f), 1,
                     LightSample{Vec3(0, 1, 0), 4.0f, Vec3(0.25f)});
        check_sample(light, Vec3(1, 0, -0.5f), Vec2(1.0f, 0.25f), 1,
                     LightSample{Vec3(0, 1, 0), 4.0f, Vec3(0.25f)});
    }

    TEST_CASE("Li carries the cosine at the light: seen at 60 degrees it halves") {
        // x = (-4 sqrt 3, 0, 0) sees the light's centre (0, 4, 0) at r = 8 and 60 degrees
        // from the light's normal: Li = Le 4 cos(60) / 64 = Le / 32
        const AreaLight light = ceiling_light(Vec3(0, 4, 0), 2.0f, Vec3(32.0f));
        const Vec3 x(-4.0f * std::sqrt(3.0f), 0, 0);
        check_sample(light, x, Vec2(0.5f), 1,
                     LightSample{glm::normalize(Vec3(4.0f * std::sqrt(3.0f), 4, 0)), 8.0f,
                                 Vec3(1.0f)});
    }

    TEST_CASE("one of N samples carries 1/N of the light") {
        // N = 4: Li = Le 4 / (4 * 16) = Le / 16
        const AreaLight light = ceiling_light(Vec3(0, 4, 0), 2.0f, Vec3(16.0f));
        check_sample(light, Vec3(0.0f), Vec2(0.5f), 4,
                     LightSample{Vec3(0, 1, 0), 4.0f, Vec3(1.0f)});
    }

    TEST_CASE("a point behind the light receives nothing from it") {
        // The light faces down; from x = (0, 5, 0) above it cos(theta_y) < 0, so Li = 0
        // (and from below it does light the point)
        const AreaLight light = ceiling_light(Vec3(0, 4, 0), 2.0f, Vec3(1.0f));
        check_sample(light, Vec3(0, 5, 0), Vec2(0.5f), 1,
                     LightSample{Vec3(0, -1, 0), 1.0f, Vec3(0.0f)});
        check_sample(light, Vec3(0, 3, 0), Vec2(0.5f), 1,
                     LightSample{Vec3(0, 1, 0), 1.0f, Vec3(4.0f)});
    }

    TEST_CASE("uniform light points lie in the unit square and are random") {
        // Over 2000 points: mean 1/2 and variance 1/12 of each coordinate, to 0.02 and
        // 0.01 (about 3 and 4 standard errors); the same seed repeats them
        const auto xi = under_test::light_sample_points(2000, false, rng_for(1));
        const auto again = under_test::light_sample_points(2000, false, rng_for(1));
        INFO("light_sample_points(2000, uniform, PixelRng seed 1)");
        RAYLAB_REQUIRE(xi.size() == 2000, "expected 2000 points, got " << xi.size());
        RAYLAB_CHECK(xi == again, "the same seed gave different points");
        double mean[2] = {0, 0}, square[2] = {0, 0};
        for (const Vec2& p : xi) {
            if (!RAYLAB_CHECK(p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 1,
                              "the point " << show(p) << " is outside [0, 1)^2"))
                return;
            for (int d = 0; d < 2; ++d) {
                mean[d] += p[d] / 2000.0;
                square[d] += p[d] * p[d] / 2000.0;
            }
        }
        for (int d = 0; d < 2; ++d) {
            const double var = square[d] - mean[d] * mean[d];
            INFO("coordinate " << d << ": mean " << show(mean[d]) << ", variance "
                               << show(var));
            RAYLAB_CHECK(
                std::abs(mean[d] - 0.5) < 0.02 && std::abs(var - 1.0 / 12) < 0.01,
                "the points are not uniform over the square");
        }
    }

    TEST_CASE(
        "stratified light points put one point in each cell of the N_x x N_y grid") {
        // N_y the largest divisor of N with N_y^2 <= N: 8 -> 4 x 2, 12 -> 4 x 3, 7 -> 7 x
        // 1
        for (int N : {1, 2, 4, 7, 8, 12, 16, 64, 256}) {
            int N_y = 1;
            for (int d = 1; d * d <= N; ++d)
                if (N % d == 0) N_y = d;
            const int N_x = N / N_y;
            for (std::uint64_t seed = 1; seed <= 5; ++seed) {
                INFO("light_sample_points(N = " << N << ", stratified, PixelRng seed "
                                                << seed << "): cells " << N_x << " x "
                                                << N_y);
                const auto xi = under_test::light_sample_points(N, true, rng_for(seed));
                RAYLAB_REQUIRE(xi.size() == size_t(N),
                               "expected " << N << " points, got " << xi.size());
                std::vector<int> count(size_t(N), 0);
                for (const Vec2& p : xi) {
                    const bool inside = p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 1;
                    RAYLAB_REQUIRE(inside,
                                   "expected every point inside the unit square "
                                   "[0, 1)^2, got "
                                       << show(p));
                    const int a = std::min(int(p.x * N_x), N_x - 1);
                    const int b = std::min(int(p.y * N_y), N_y - 1);
                    RAYLAB_REQUIRE(++count[size_t(b * N_x + a)] == 1,
                                   "expected one point in each cell, but cell ("
                                       << a << ", " << b << ") holds two, the second "
                                       << show(p));
                }
            }
        }
    }

    TEST_CASE("a small area light lights a point like a point light") {
        // A 0.01 x 0.01 light with Le = I / A at height 3 acts as a point light of
        // intensity I cos(theta_y) (a flat emitter is dimmer seen from the side):
        // E = I cos(theta_y) cos(theta_x) / r^2 at floor points 0 to 4 units aside
        const float a = 0.01f;
        const double I = 5.0;
        const AreaLight light = ceiling_light(Vec3(0, 3, 0), a, Vec3(float(I / (a * a))));
        for (float d : {0.0f, 1.0f, 2.5f, 4.0f}) {
            const Vec3 x(d, 0, 0.5f * d);
            const double r2 = double(glm::dot(x - Vec3(0, 3, 0), x - Vec3(0, 3, 0)));
            const double cos_theta = 3.0 / std::sqrt(r2);  // the same at both ends
            const double want = I * cos_theta * cos_theta / r2;
            for (bool stratified : {false, true}) {
                const double E = irradiance(light, x, Vec3(0, 1, 0), 16, stratified, 4);
                if (!check_E(E, want, kSmallLight,
                             "floor point " + show(x) + ", 16 " +
                                 (stratified ? "stratified" : "uniform") + " samples"))
                    return;
            }
        }
    }

    TEST_CASE("a large light gives the closed-form irradiance of a facing rectangle") {
        // A 2 x 3 light at height 1.5 facing down (e1 x e2 = (0, -6, 0)): under its
        // corner E = corner_irradiance(Le, 2, 3, 1.5); under its centre, four 1 x 1.5
        // quarters: E = 4 corner_irradiance(Le, 1, 1.5, 1.5). 2048 samples, PixelRng seed
        // 11
        const double Le = 2.0;
        const AreaLight light{Vec3(0, 1.5f, 0), Vec3(2, 0, 0), Vec3(0, 0, 3),
                              Vec3(float(Le))};
        const Vec3 up(0, 1, 0);
        const double corner = corner_irradiance(Le, 2, 3, 1.5);
        const double centre = 4 * corner_irradiance(Le, 1, 1.5, 1.5);
        check_E(irradiance(light, Vec3(0.0f), up, 2048, true, 11), corner, kStratified,
                "under the corner, stratified");
        check_E(irradiance(light, Vec3(1, 0, 1.5f), up, 2048, true, 11), centre,
                kStratified, "under the centre, stratified");
        check_E(irradiance(light, Vec3(1, 0, 1.5f), up, 2048, false, 11), centre,
                kUniform, "under the centre, uniform");
    }

    TEST_CASE("the penumbra of a straight edge has the width of similar triangles") {
        // A 1 x 1 light at height H = 4, a blocking half-plane x > 0 at height h = 1:
        // a floor point at X sees the light past the edge for
        // X < -(a/2) h / (H - h) = -1/6 and none of it for X > 1/6, so the penumbra is
        // a h / (H - h) = 1/3 wide, and the visible share falls linearly across it
        // (0.75 at X = -1/12, 0.5 at 0, 0.25 at 1/12). 256 stratified samples
        const AreaLight light = ceiling_light(Vec3(0, 4, 0), 1.0f, Vec3(1.0f));
        const double half = 1.0 / 6.0;
        for (double X : {-1.3 * half, -0.5 * half, 0.0, 0.5 * half, 1.3 * half}) {
            const double want = X < -half ? 1.0 : X > half ? 0.0 : 0.5 - X / (2 * half);
            const double got = visible_share(light, Vec3(float(X), 0, 0.2f), 1.0f, 256);
            INFO("floor point X = " << show(X) << ", PixelRng seed 77");
            if (!RAYLAB_CHECK(
                    std::abs(got - want) <= kShare,
                    "the light is " << show(got) << " visible, expected " << show(want)))
                break;
        }
    }
}
