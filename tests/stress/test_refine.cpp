// The hit refinement of raylab/refine.h, attacked directly: degenerate primitives, NaN,
// parallel rays, wrong hit points from a student's module. Never a non-finite point,
// never a wrong point pulled onto the surface.
#include <doctest/doctest.h>

#include "raylab/refine.h"
#include "test_helpers.h"

using namespace raylab;

namespace {

const float kNaN = std::numeric_limits<float>::quiet_NaN();

bool same(const Vec3& a, const Vec3& b) {
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

}  // namespace

TEST_SUITE("stress refine") {
    TEST_CASE("a plane hit from far away lands within delta of the plane") {
        const Plane p{glm::normalize(Vec3(0.1f, 1.0f, 0.05f)), 0.3f};
        for (int seed = 0; seed < 200; ++seed) {
            Rng rng(seed);
            INFO("seed " << seed);
            const Vec3 o = 1e4f * rng.direction() + Vec3(0.0f, 2e4f, 0.0f);
            const Vec3 target = rng.in_box(-3.0f, 3.0f);
            const Ray r{o, glm::normalize(target - o), 0.0f, kInfinity};
            const float t = glm::length(target - o);  // about right, as a module's t
            const Vec3 x =
                accept_refined(r.o + t * r.w, refine_on_plane(r.o + t * r.w, r, p), r, t);
            const double s = glm::dot(DVec3(x), DVec3(p.n)) + double(p.d);
            CHECK(std::abs(s) <= double(hit_error_bound(x)));
        }
    }

    TEST_CASE("degenerate input keeps the module's point, finite") {
        const Ray r{Vec3(0, 0, 5), Vec3(0, 0, -1), 0.0f, kInfinity};
        const Vec3 x(0.0f, 0.0f, 1.0f);
        // A ray that misses in double and x at the sphere's centre: nowhere to go
        const Ray miss{Vec3(5, 5, 5), Vec3(0, 0, -1), 0.0f, kInfinity};
        CHECK(same(refine_on_sphere(Vec3(0.0f), miss, 5.0f, Sphere{Vec3(0.0f), 1.0f}),
                   Vec3(0.0f)));
        // The same x on a ray that does hit: the ray's point on the sphere
        CHECK(same(refine_on_sphere(Vec3(0.0f), r, 5.0f, Sphere{Vec3(0.0f), 1.0f}),
                   Vec3(0.0f, 0.0f, 1.0f)));
        // A triangle of zero area
        CHECK(
            same(refine_on_triangle(x, r, Vec3(0.0f), Vec3(1, 0, 0), Vec3(2, 0, 0)), x));
        // A ray parallel to the plane: x is projected instead
        const Ray parallel{Vec3(0, 1, 0), Vec3(1, 0, 0), 0.0f, kInfinity};
        CHECK(
            refine_on_plane(Vec3(3.0f, 1e-3f, 0.0f), parallel, Plane{Vec3(0, 1, 0), 0.0f})
                .y == 0.0f);
        // NaN anywhere: the module's point comes back
        const Ray nan_ray{Vec3(kNaN, 0.0f, 5.0f), Vec3(0, 0, -1), 0.0f, kInfinity};
        const Vec3 got = refine_on_plane(x, nan_ray, Plane{Vec3(0, 0, 1), -1.0f});
        CHECK(same(accept_refined(x, got, nan_ray, 4.0f), x));
        CHECK(same(accept_refined(x, Vec3(kNaN), r, 4.0f), x));
    }

    TEST_CASE("a wrong hit point from a module is not pulled onto the surface") {
        // A module that reports position = o + t (forgetting w): 5 units off the plane
        const Ray r{Vec3(0, 0, 5), Vec3(0, 0, -1), 0.0f, kInfinity};
        const Plane p{Vec3(0, 0, 1), 0.0f};
        const Vec3 wrong = r.o + Vec3(5.0f);
        CHECK(same(accept_refined(wrong, refine_on_plane(wrong, r, p), r, 5.0f), wrong));
        // The right point, a few ulps off, is refined
        const Vec3 close(0.0f, 0.0f, 3e-7f);
        CHECK(accept_refined(close, refine_on_plane(close, r, p), r, 5.0f).z == 0.0f);
    }

    TEST_CASE("a sphere's normal follows the refined point, a wrong one stays wrong") {
        const Sphere s{Vec3(1.0f, 2.0f, 3.0f), 2.0f};
        const Vec3 x = s.c + Vec3(0.0f, 2.0f, 0.0f);
        // Off by 0.01 (from a float hit 1e5 away), outward or inward: the exact normal
        const Vec3 off = glm::normalize(Vec3(0.01f, 1.0f, 0.0f));
        CHECK(same(refine_sphere_normal(x, off, s), Vec3(0, 1, 0)));
        CHECK(same(refine_sphere_normal(x, -off, s), Vec3(0, -1, 0)));
        // Not unit (x - c without dividing by r), or far from the sphere's: kept
        CHECK(same(refine_sphere_normal(x, Vec3(0, 2, 0), s), Vec3(0, 2, 0)));
        CHECK(same(refine_sphere_normal(x, Vec3(1, 0, 0), s), Vec3(1, 0, 0)));
        CHECK(!is_finite(refine_sphere_normal(x, Vec3(kNaN), s)));
    }
    // refine_on_triangle promises the float rounding of where r meets the plane. A
    // triangle and a ray direction of subnormal size make w.n n.n underflow (here w.n n.n
    // is about 2^-1030): with one division 1 / (w.n n.n) the reciprocal overflows and the
    // refinement fell back to projecting the module's point x, 2^10 subnormal ulps away
    // (x is off by an ulp of o, 2^-138). Two divisions, (k - o.n) / w.n and (p.n - k) /
    // n.n, stay in range
    TEST_CASE(
        "a subnormal triangle and ray: where the ray meets the plane, not x projected") {
        const Vec3 v0(0x1.cp-147f, -0x1p-148f, 0x1.8p-148f),
            v1(0x1p-146f, 0x1p-146f, 0x1p-147f), v2(0x1.cp-147f, 0.0f, 0x1.8p-148f);
        const Ray r{Vec3(0x1.271c5ap-115f, 0x1.baaa88p-115f, 0x1.8p-148f),
                    Vec3(-0x1p-138f, -0x1.8p-138f, 0.0f), 0.0f, kInfinity};
        const Vec3 x(0.0f, 0.0f, 0x1.8p-148f);  // o + t w in float, t = 0x1.271c5ap+23
        // The exact point (rational arithmetic on the float inputs), to double
        const DVec3 exact(0x1.cp-147, 0x1.02ap-139, 0x1.8p-148);
        const Vec3 p = refine_on_triangle(x, r, v0, v1, v2);
        INFO("refined (" << p.x << ", " << p.y << ", " << p.z << ")");
        const double ulp = 0x1p-149;
        CHECK(std::abs(double(p.x) - exact.x) <= ulp);
        CHECK(std::abs(double(p.y) - exact.y) <= ulp);
        CHECK(std::abs(double(p.z) - exact.z) <= ulp);
    }
}
