// Graders of module 06_point_light (docs/handouts/06_point_light.md).
//
// At x, a point light at p with intensity I gives wi = (p - x) / r, r = |p - x| and
// Li = I / r^2 (Kepler's inverse-square law); a light of power P has I = P / (4 pi).
#include "grading.h"

using namespace raylab;
using namespace raylab::grading;

namespace {

std::string diff_sample(const LightSample& got, const LightSample& want) {
    std::string why = diff_vec("wi", got.wi, want.wi, tol::kDirection);
    if (!close(got.r, want.r, tol::kDistance))
        why += std::string(why.empty() ? "" : "; ") + "r: expected " + show(want.r) +
               ", got " + show(got.r);
    const std::string li = diff_radiance("Li", got.Li, want.Li);
    if (!li.empty()) why += (why.empty() ? "" : "; ") + li;
    return why;
}

bool check(const PointLight& light, const Vec3& x, const LightSample& want) {
    INFO(show(light) << "; surface point x = " << show(x));
    return RAYLAB_CHECK_SAME(diff_sample(under_test::sample_point_light(light, x), want));
}

// Companion of the cases a table passes: fresh random lights and points, the formulas in
// double
std::string work_point_light() {
    for (int seed = 0; seed < 8; ++seed) {
        Rng rng(9800 + seed);
        const PointLight light{rng.in_box(-50.0f, 50.0f), rng.in_box(0.1f, 100.0f)};
        const Vec3 x = rng.in_box(-50.0f, 50.0f);
        const glm::dvec3 d = glm::dvec3(light.p) - glm::dvec3(x);
        const double r = glm::length(d);
        const LightSample want{Vec3(d / r), float(r),
                               Vec3(glm::dvec3(light.I) / (r * r))};
        const std::string why =
            diff_sample(under_test::sample_point_light(light, x), want);
        if (!why.empty()) return show(light) + "; x = " + show(x) + ": " + why;
    }
    return "";
}

}  // namespace

TEST_SUITE("06_point_light") {
    TEST_CASE("a light 2 units above the point gives wi = up, r = 2 and Li = I / 4") {
        // I = (4, 8, 12): Li = I / 2^2 = (1, 2, 3); I / r would give (2, 4, 6)
        check(PointLight{Vec3(0, 2, 0), Vec3(4, 8, 12)}, Vec3(0.0f),
              LightSample{Vec3(0, 1, 0), 2.0f, Vec3(1, 2, 3)});
    }

    TEST_CASE("incident light falls off with the square of the distance") {
        // p - x = (3, 4, 0): r = 5, wi = (0.6, 0.8, 0), Li = 50 / 25 = 2
        check(PointLight{Vec3(4, 5, 1), Vec3(50.0f)}, Vec3(1, 1, 1),
              LightSample{Vec3(0.6f, 0.8f, 0), 5.0f, Vec3(2.0f)});
    }

    TEST_CASE("wi points from the surface point towards the light, not away from it") {
        // The light is 3 units along -z of x: wi = (0, 0, -1)
        check(PointLight{Vec3(1, 1, -2), Vec3(9.0f)}, Vec3(1, 1, 1),
              LightSample{Vec3(0, 0, -1), 3.0f, Vec3(1.0f)});
    }

    TEST_CASE("wi is a unit vector and x + r wi is the light's position") {
        for (int seed = 0; seed < 200; ++seed) {
            Rng rng(seed);
            const PointLight light{rng.in_box(-10.0f, 10.0f), rng.in_box(0.1f, 100.0f)};
            const float r = rng.uniform(0.1f, 20.0f);
            const Vec3 x = light.p + r * rng.direction();
            INFO("seed " << seed << ": " << show(light) << "; x = " << show(x));
            const LightSample s = under_test::sample_point_light(light, x);
            INFO("got " << show(s));
            const bool unit = close(glm::length(s.wi), 1.0, tol::kDirection);
            const bool reaches = close_abs(x + s.r * s.wi, light.p,
                                           tol::kDistance * scale_of({x, light.p}));
            RAYLAB_CHECK(unit, "|wi| = " << show(glm::length(s.wi)) << ", expected 1");
            RAYLAB_CHECK(reaches, "x + r wi = " << show(x + s.r * s.wi)
                                                << " should be the light's position");
            if (!unit || !reaches) break;
        }
    }

    TEST_CASE("a light 128 units away still lights the point, and one 500 units away") {
        // Li = I / r^2 at any distance: r = 128 gives I / 16384, r = 500 (p - x = (-300,
        // 400, 0), exact) I / 250000. A light has no range beyond which it stops
        check(PointLight{Vec3(0, 128, 0), Vec3(16384, 32768, 49152)}, Vec3(0.0f),
              LightSample{Vec3(0, 1, 0), 128.0f, Vec3(1, 2, 3)});
        check(PointLight{Vec3(-300, 400, 0), Vec3(250000.0f)}, Vec3(0.0f),
              LightSample{Vec3(-0.6f, 0.8f, 0), 500.0f, Vec3(1.0f)});
    }

    TEST_CASE("random lights and points agree with the reference") {
        // The release's golden data holds these answers: they count with fresh lights
        needs_work("fresh random lights and points", work_point_light());
        for (int seed = 0; seed < 200; ++seed) {
            Rng rng(1000 + seed);
            const PointLight light{rng.in_box(-10.0f, 10.0f), rng.in_box(0.1f, 100.0f)};
            const float r = rng.uniform(0.1f, 20.0f);
            const Vec3 x = light.p + r * rng.direction();
            INFO("seed " << seed << ": " << show(light) << "; x = " << show(x));
            const LightSample want = expected<LightSample>(
                "06_point_light/random lights/" + std::to_string(seed),
                inputs(light.p, light.I, x),
                [&] { return reference_modules().sample_point_light(light, x); });
            if (!RAYLAB_CHECK_SAME(
                    diff_sample(under_test::sample_point_light(light, x), want)))
                break;
        }
    }

    TEST_CASE("a light's power spreads over 4 pi steradians: I = P / (4 pi)") {
        // P = (4 pi, 8 pi, 2): I = (1, 2, 2 / (4 pi) = 0.15915494)
        const Vec3 P(4 * kPi, 8 * kPi, 2.0f);
        INFO("intensity_from_power(P = " << show(P) << ")");
        RAYLAB_CHECK_SAME(diff_radiance("I", under_test::intensity_from_power(P),
                                        Vec3(1, 2, 0.15915494f)));
    }

    TEST_CASE("the lab's 14 W light has an intensity of 14 / (4 pi) = 1.114 W/sr") {
        INFO("intensity_from_power(P = (14, 14, 14))");
        RAYLAB_CHECK_SAME(diff_radiance(
            "I", under_test::intensity_from_power(Vec3(14.0f)), Vec3(1.1140846f)));
    }

    TEST_CASE("together the two functions give the lab's P / (4 pi r^2)") {
        // P = 14 W, r = 2: Li = 14 / (16 pi) = 0.27852115
        const Vec3 I = under_test::intensity_from_power(Vec3(14.0f));
        INFO("intensity_from_power(14) = " << show(I) << "; light at (0, 2, 0), x = 0");
        const LightSample s =
            under_test::sample_point_light({Vec3(0, 2, 0), I}, Vec3(0.0f));
        RAYLAB_CHECK_SAME(diff_radiance("Li", s.Li, Vec3(0.27852115f)));
    }
}
