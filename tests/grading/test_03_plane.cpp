// Graders of module 03_plane (docs/handouts/03_plane.md).
//
// The plane p . n + d = 0 meets r(t) = o + t w at t = -(o . n + d) / (w . n); the hit
// counts when tmin <= t <= tmax, and its normal is the plane's n from either side.
#include <cmath>

#include "grading.h"

using namespace raylab;
using namespace raylab::grading;

namespace {

const Plane kFloor{Vec3(0, 1, 0), 0.0f};  // y = 0

// Checks one ray against one plane, printing both
bool check(const Ray& r, const Plane& plane, const std::optional<Hit>& want) {
    INFO(show(r) << "; " << show(plane));
    const std::optional<Hit> got = under_test::intersect_plane(r, plane);
    return RAYLAB_CHECK_SAME(diff_hit(got, want, scale_of({r.o}, want ? want->t : 0.0)));
}

// Companion of the cases a constant or a table passes: rays aimed at a chosen point of a
// fresh random plane hit it there
std::string work_plane() {
    for (int seed = 0; seed < 8; ++seed) {
        Rng rng(9500 + seed);
        const Vec3 n = rng.direction();
        const Plane plane{n, rng.uniform(-3.0f, 3.0f)};
        const Vec3 a = glm::normalize(glm::cross(n, rng.direction_near(n, -0.9f, 0.9f)));
        const Vec3 p = -plane.d * n + rng.uniform(-5.0f, 5.0f) * a +
                       rng.uniform(-5.0f, 5.0f) * glm::cross(n, a);
        const Vec3 w = rng.direction_near(n, -1.0f, -0.2f);
        const float t = rng.uniform(0.5f, 10.0f);
        const Ray r{p - t * w, w};
        const std::string why = diff_hit(under_test::intersect_plane(r, plane),
                                         make_hit(t, p, n), scale_of({r.o, p}, t));
        if (!why.empty()) return show(r) + "; " + show(plane) + ": " + why;
    }
    return "";
}

}  // namespace

TEST_SUITE("03_plane") {
    TEST_CASE("a ray straight down hits the floor y = 0 at t = 2") {
        // t = -((0, 2, 0) . (0, 1, 0) + 0) / ((0, -1, 0) . (0, 1, 0)) = -2 / -1 = 2
        check(Ray{Vec3(0, 2, 0), Vec3(0, -1, 0)}, kFloor,
              make_hit(2.0f, Vec3(0.0f), Vec3(0, 1, 0)));
    }

    TEST_CASE("the plane offset d = 1 puts the plane at y = -1, below the origin") {
        // p . n + d = 0 with n = (0, 1, 0), d = 1 is y = -1: t = -(2 + 1) / -1 = 3.
        // Writing p . n = d instead puts the plane at y = +1 (t = 1).
        check(Ray{Vec3(0, 2, 0), Vec3(0, -1, 0)}, Plane{Vec3(0, 1, 0), 1.0f},
              make_hit(3.0f, Vec3(0, -1, 0), Vec3(0, 1, 0)));
    }

    TEST_CASE("an oblique ray hits at t = -(o . n + d) / (w . n), at o + t w") {
        // The plane z = 2 is n = (0, 0, 1), d = -2. From o = (1, 1, 0) along
        // w = (1, 2, 2) / 3: t = -(0 - 2) / (2/3) = 3, position (1, 1, 0) + 3 w = (2, 3,
        // 2)
        check(Ray{Vec3(1, 1, 0), Vec3(1.0f / 3, 2.0f / 3, 2.0f / 3)},
              Plane{Vec3(0, 0, 1), -2.0f}, make_hit(3.0f, Vec3(2, 3, 2), Vec3(0, 0, 1)));
    }

    TEST_CASE("a plane behind the ray's origin is not hit") {
        // Pointing up, away from the floor: t = -2 < tmin = 0
        check(Ray{Vec3(0, 2, 0), Vec3(0, 1, 0)}, kFloor, std::nullopt);
        // and the same ray turned round hits it
        check(Ray{Vec3(0, 2, 0), Vec3(0, -1, 0)}, kFloor,
              make_hit(2.0f, Vec3(0.0f), Vec3(0, 1, 0)));
    }

    TEST_CASE("a ray parallel to the plane misses it, from either side") {
        // w . n = 0: no t solves the equation. Above the floor t = -1 / 0 = -inf, below
        // it t = +inf, which a test t >= tmin && t <= tmax with tmax = inf accepts. The
        // same rays tilted towards the floor hit it (a module that never hits earns
        // nothing)
        check(Ray{Vec3(0, 1, 0), Vec3(1, 0, 0)}, kFloor, std::nullopt);
        check(Ray{Vec3(0, -1, 0), Vec3(1, 0, 0)}, kFloor, std::nullopt);
        check(Ray{Vec3(0, 1, 0), Vec3(0.6f, -0.8f, 0)}, kFloor,
              make_hit(1.25f, Vec3(0.75f, 0, 0), Vec3(0, 1, 0)));
        check(Ray{Vec3(0, -1, 0), Vec3(0.6f, 0.8f, 0)}, kFloor,
              make_hit(1.25f, Vec3(0.75f, 0, 0), Vec3(0, 1, 0)));
    }

    TEST_CASE("a ray inside the plane and parallel to it gives no NaN distance") {
        // o . n + d = 0 and w . n = 0: t = 0 / 0. A miss is expected; a hit, if any, must
        // at least have a finite t inside [tmin, tmax].
        const Ray r{Vec3(0.0f), Vec3(1, 0, 0)};
        INFO(show(r) << "; " << show(kFloor));
        const std::optional<Hit> got = under_test::intersect_plane(r, kFloor);
        RAYLAB_CHECK(
            !got || (std::isfinite(got->t) && got->t >= r.tmin && got->t <= r.tmax),
            "expected a miss, got " << show(got));
        // Tilted out of the plane from just above it, the ray hits it
        check(Ray{Vec3(0, 0.5f, 0), Vec3(0.6f, -0.8f, 0)}, kFloor,
              make_hit(0.625f, Vec3(0.375f, 0, 0), Vec3(0, 1, 0)));
    }

    TEST_CASE("the normal is the plane's n whichever side the ray comes from") {
        // From below the floor, upwards: t = -(-2) / 1 = 2, and n stays (0, 1, 0)
        check(Ray{Vec3(0, -2, 0), Vec3(0, 1, 0)}, kFloor,
              make_hit(2.0f, Vec3(0.0f), Vec3(0, 1, 0)));
    }

    TEST_CASE("a hit beyond tmax is rejected, the same hit inside tmax is accepted") {
        // The floor is at t = 2 along this ray
        check(Ray{Vec3(0, 2, 0), Vec3(0, -1, 0), 0.0f, 1.9f}, kFloor, std::nullopt);
        check(Ray{Vec3(0, 2, 0), Vec3(0, -1, 0), 0.0f, 2.1f}, kFloor,
              make_hit(2.0f, Vec3(0.0f), Vec3(0, 1, 0)));
    }

    TEST_CASE("a hit before tmin is rejected, the same hit after tmin is accepted") {
        check(Ray{Vec3(0, 2, 0), Vec3(0, -1, 0), 2.1f, kInfinity}, kFloor, std::nullopt);
        check(Ray{Vec3(0, 2, 0), Vec3(0, -1, 0), 1.9f, kInfinity}, kFloor,
              make_hit(2.0f, Vec3(0.0f), Vec3(0, 1, 0)));
    }

    TEST_CASE("a hit exactly at tmin or at tmax counts: both ends are included") {
        // t = 2 exactly (in float and double alike): tmin <= t <= tmax, not <
        check(Ray{Vec3(0, 2, 0), Vec3(0, -1, 0), 0.0f, 2.0f}, kFloor,
              make_hit(2.0f, Vec3(0.0f), Vec3(0, 1, 0)));
        check(Ray{Vec3(0, 2, 0), Vec3(0, -1, 0), 2.0f, kInfinity}, kFloor,
              make_hit(2.0f, Vec3(0.0f), Vec3(0, 1, 0)));
    }

    TEST_CASE("a ray at a grazing angle (w . n = -2^-12) still hits the plane") {
        // 0.014 degrees from parallel: t = -(2^-9) / (-2^-12) = 8, at (8, 0, 0), all
        // exact in float. Only w . n = 0 is parallel; an epsilon such as |w . n| < 1e-3
        // loses every ray within 0.06 degrees of the floor (the horizon of a large floor)
        const float y = std::ldexp(1.0f, -9), wy = -std::ldexp(1.0f, -12);
        check(Ray{Vec3(0, y, 0), Vec3(1, wy, 0)}, kFloor,
              make_hit(8.0f, Vec3(8, 0, 0), Vec3(0, 1, 0)));
        check(Ray{Vec3(0, -y, 0), Vec3(1, -wy, 0)}, kFloor,
              make_hit(8.0f, Vec3(8, 0, 0), Vec3(0, 1, 0)));
    }

    TEST_CASE("random rays and planes agree with the reference") {
        // The release's golden data holds these answers: they count with fresh rays
        needs_work("rays aimed at points of fresh random planes", work_plane());
        // Rays aimed at a chosen point of a random plane, at least 8 degrees off
        // parallel, with [tmin, tmax] containing the hit or missing it by 10% or more;
        // some point away
        for (int seed = 0; seed < 300; ++seed) {
            Rng rng(seed);
            const Vec3 n = rng.direction();
            const Plane plane{n, rng.uniform(-3.0f, 3.0f)};
            const Vec3 a =
                glm::normalize(glm::cross(n, rng.direction_near(n, -0.9f, 0.9f)));
            const Vec3 b = glm::cross(n, a);
            const float pa = rng.uniform(-5.0f, 5.0f), pb = rng.uniform(-5.0f, 5.0f);
            const Vec3 p = -plane.d * n + pa * a + pb * b;
            Vec3 w = rng.direction_near(n, 0.15f, 1.0f);
            if (rng.integer(0, 1)) w = -w;
            const float t = rng.uniform(0.2f, 10.0f);
            const Ray r = random_ray_through(rng, p, w, t);
            INFO("seed " << seed << ": " << show(r) << "; " << show(plane));
            const auto want = expected<std::optional<Hit>>(
                "03_plane/random rays/" + std::to_string(seed),
                inputs(r, plane.n, plane.d),
                [&] { return reference_modules().intersect_plane(r, plane); });
            const auto got = under_test::intersect_plane(r, plane);
            if (!RAYLAB_CHECK_SAME(diff_hit(got, want, scale_of({r.o, p}, t)))) break;
        }
    }
}
