// Graders of module 04_sphere (docs/handouts/04_sphere.md).
//
// |o + t w - c|^2 = r^2 is t^2 + 2 b t + c' = 0 with f = o - c, b = f . w,
// c' = f . f - r^2: roots t = -b -+ sqrt(b^2 - c'). The hit is the nearest root in
// [tmin, tmax]; its normal (p - c) / r points outwards, also seen from inside.
#include "grading.h"

using namespace raylab;
using namespace raylab::grading;

namespace {

const Sphere kUnit{Vec3(0.0f), 1.0f};
const Vec3 kDown(0, 0, -1);  // along -z

bool check(const Ray& r, const Sphere& s, const std::optional<Hit>& want) {
    INFO(show(r) << "; " << show(s));
    const std::optional<Hit> got = under_test::intersect_sphere(r, s);
    return RAYLAB_CHECK_SAME(diff_hit(got, want, scale_of({r.o, s.c}, s.r)));
}

// Companion of the cases a constant or a table passes: rays from outside through a chosen
// point of a fresh random sphere, towards its inside, hit it there
std::string work_sphere() {
    for (int seed = 0; seed < 8; ++seed) {
        Rng rng(9600 + seed);
        const Sphere s{rng.in_box(-5.0f, 5.0f), rng.uniform(0.2f, 3.0f)};
        const Vec3 n = rng.direction();
        const Vec3 p = s.c + s.r * n;
        const Vec3 w = rng.direction_near(n, -1.0f, -0.3f);
        const float t = s.r * rng.uniform(0.5f, 5.0f);
        const Ray r{p - t * w, w};
        const std::string why = diff_hit(under_test::intersect_sphere(r, s),
                                         make_hit(t, p, n), scale_of({r.o, s.c}, s.r));
        if (!why.empty()) return show(r) + "; " + show(s) + ": " + why;
    }
    return "";
}

bool sphere_work() {
    return needs_work("rays aimed at points of fresh random spheres", work_sphere());
}

}  // namespace

TEST_SUITE("04_sphere") {
    TEST_CASE("a ray towards the centre hits the near side at t = |o - c| - r") {
        // From z = 5 towards the unit sphere: roots t = 4 and t = 6; the near one
        check(Ray{Vec3(0, 0, 5), kDown}, kUnit,
              make_hit(4.0f, Vec3(0, 0, 1), Vec3(0, 0, 1)));
    }

    TEST_CASE("an off-centre ray hits the nearer of the two roots") {
        // x = 0.6 meets the unit sphere at z = +-0.8: t = 5 - 0.8 = 4.2 (not 5.8)
        check(Ray{Vec3(0.6f, 0, 5), kDown}, kUnit,
              make_hit(4.2f, Vec3(0.6f, 0, 0.8f), Vec3(0.6f, 0, 0.8f)));
    }

    TEST_CASE("a ray from inside the sphere hits the far side, with the outward normal") {
        // o = (0, 0, 0.5) inside the sphere of radius 2, looking away from the centre:
        // roots t = -2.5 and t = 1.5; only 1.5 >= tmin, at (0, 0, 2), n = (0, 0, 1)
        check(Ray{Vec3(0, 0, 0.5f), Vec3(0, 0, 1)}, Sphere{Vec3(0.0f), 2.0f},
              make_hit(1.5f, Vec3(0, 0, 2), Vec3(0, 0, 1)));
    }

    TEST_CASE("a sphere behind the ray's origin is not hit") {
        sphere_work();
        // Both roots negative (t = -6 and t = -4)
        check(Ray{Vec3(0, 0, 5), Vec3(0, 0, 1)}, kUnit, std::nullopt);
    }

    TEST_CASE("a ray passing beside the sphere misses it") {
        sphere_work();
        // Distance 2 from the centre of the unit sphere: b^2 - c' = 25 - 28 < 0
        check(Ray{Vec3(2, 0, 5), kDown}, kUnit, std::nullopt);
    }

    TEST_CASE("rays just inside and just outside the silhouette hit and miss") {
        // x = 0.999: z = sqrt(1 - 0.999^2) = 0.0447102, t = 5 - 0.0447102 = 4.9552898
        check(Ray{Vec3(0.999f, 0, 5), kDown}, kUnit,
              make_hit(4.9552898f, Vec3(0.999f, 0, 0.0447102f),
                       Vec3(0.999f, 0, 0.0447102f)));
        check(Ray{Vec3(1.001f, 0, 5), kDown}, kUnit, std::nullopt);
    }

    TEST_CASE("a tangent ray touches the sphere at one point and hits it") {
        // x = 1 grazes the unit sphere: b^2 - c' = 25 - 25 = 0 exactly (and r^2 - |f - b
        // w|^2 = 1 - 1 = 0), a double root t = 5 at (1, 0, 0). A test disc <= 0 loses the
        // silhouette; the contract counts it as a hit (disc < 0 misses)
        check(Ray{Vec3(1, 0, 5), kDown}, kUnit,
              make_hit(5.0f, Vec3(1, 0, 0), Vec3(1, 0, 0)));
        check(Ray{Vec3(0, -2, 10), kDown}, Sphere{Vec3(0, 0, 2), 2.0f},
              make_hit(8.0f, Vec3(0, -2, 2), Vec3(0, -1, 0)));
    }

    TEST_CASE("a hit exactly at tmin or at tmax counts: both ends are included") {
        // Roots 4 and 6, exact in float: tmin <= t <= tmax, not <
        check(Ray{Vec3(0, 0, 5), kDown, 4.0f, kInfinity}, kUnit,
              make_hit(4.0f, Vec3(0, 0, 1), Vec3(0, 0, 1)));
        check(Ray{Vec3(0, 0, 5), kDown, 0.0f, 4.0f}, kUnit,
              make_hit(4.0f, Vec3(0, 0, 1), Vec3(0, 0, 1)));
        check(Ray{Vec3(0, 0, 5), kDown, 4.5f, 6.0f}, kUnit,
              make_hit(6.0f, Vec3(0, 0, -1), Vec3(0, 0, -1)));
    }

    TEST_CASE("the far root is returned when tmin excludes the near one") {
        // Roots 4 and 6; tmin = 4.5 leaves t = 6 at the back, n = (0, 0, -1)
        check(Ray{Vec3(0, 0, 5), kDown, 4.5f, kInfinity}, kUnit,
              make_hit(6.0f, Vec3(0, 0, -1), Vec3(0, 0, -1)));
    }

    TEST_CASE("a hit beyond tmax is rejected, the same hit inside tmax is accepted") {
        check(Ray{Vec3(0, 0, 5), kDown, 0.0f, 3.9f}, kUnit, std::nullopt);
        check(Ray{Vec3(0, 0, 5), kDown, 0.0f, 4.1f}, kUnit,
              make_hit(4.0f, Vec3(0, 0, 1), Vec3(0, 0, 1)));
    }

    TEST_CASE("no hit when both roots lie outside [tmin, tmax]") {
        sphere_work();
        // Roots 4 and 6 around the interval [4.5, 5.5]
        check(Ray{Vec3(0, 0, 5), kDown, 4.5f, 5.5f}, kUnit, std::nullopt);
    }

    TEST_CASE("a sphere away from the origin is hit where it is") {
        // c = (10, -20, 30), r = 2, from 12 units above it along z: t = 10, p = c + (0,
        // 0, 2)
        const Sphere s{Vec3(10, -20, 30), 2.0f};
        check(Ray{Vec3(10, -20, 42), kDown}, s,
              make_hit(10.0f, Vec3(10, -20, 32), Vec3(0, 0, 1)));
    }

    TEST_CASE("the normal of a large sphere has unit length") {
        // r = 5: p - c = (0, 0, 5), n = (p - c) / r = (0, 0, 1)
        check(Ray{Vec3(0, 0, 20), kDown}, Sphere{Vec3(0.0f), 5.0f},
              make_hit(15.0f, Vec3(0, 0, 5), Vec3(0, 0, 1)));
    }

    TEST_CASE("random rays and spheres agree with the reference") {
        sphere_work();
        // Rays through two chosen points of the sphere (a chord at least 0.3 r long),
        // from outside, from inside, with tmin between the roots, tmax before them, past
        // the sphere, or beside it at 1.05 r or more from the centre
        for (int seed = 0; seed < 300; ++seed) {
            Rng rng(seed);
            const Sphere s{rng.in_box(-5.0f, 5.0f), rng.uniform(0.2f, 3.0f)};
            const Vec3 d0 = rng.direction();
            const Vec3 d1 = rng.direction_near(d0, -1.0f, 0.95f);
            const Vec3 p0 = s.c + s.r * d0, p1 = s.c + s.r * d1;
            const float chord = glm::length(p1 - p0);
            const Vec3 w = (p1 - p0) / chord;
            const float out = s.r * rng.uniform(0.2f, 5.0f);  // distance before p0
            Ray r{p0 - out * w, w, 0.0f, kInfinity};
            switch (rng.integer(0, 5)) {
                case 1:
                    r.o = p0 + rng.uniform(0.2f, 0.8f) * chord * w;
                    break;  // inside
                case 2:
                    r.tmin = out + 0.5f * chord;
                    break;  // between the roots
                case 3:
                    r.tmax = 0.9f * out;
                    break;  // ends before the sphere
                case 4:
                    r.o = p1 + out * w;
                    break;  // sphere behind
                case 5: {   // beside it
                    const Vec3 q = s.c + s.r * rng.uniform(1.05f, 3.0f) * d0;
                    r.w = glm::normalize(
                        glm::cross(d0, rng.direction_near(d0, -0.9f, 0.9f)));
                    r.o = q - out * r.w;
                    break;
                }
                default:
                    break;
            }
            INFO("seed " << seed << ": " << show(r) << "; " << show(s));
            const auto want = expected<std::optional<Hit>>(
                "04_sphere/random rays/" + std::to_string(seed), inputs(r, s.c, s.r),
                [&] { return reference_modules().intersect_sphere(r, s); });
            const auto got = under_test::intersect_sphere(r, s);
            if (!RAYLAB_CHECK_SAME(diff_hit(got, want, scale_of({r.o, s.c}, s.r)))) break;
        }
    }
}
