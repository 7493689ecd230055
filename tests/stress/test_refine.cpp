// The hit refinement of raylab/refine.h, attacked directly: degenerate primitives, NaN,
// parallel rays, wrong hit points from a student's module. Never a non-finite point,
// never a wrong point pulled onto the surface; the reference's modules' points within
// the bound that lets their refined points in.
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
            // The reference module's float hit, off the plane by a few ulps of 2e4
            const std::optional<Hit> hit = reference::intersect_plane(r, p);
            REQUIRE(hit.has_value());
            const Vec3 x = accept_refined(
                hit->position, refine_on_plane(hit->position, r, p), p.n, r, hit->t);
            const double s = glm::dot(DVec3(x), DVec3(p.n)) + double(p.d);
            CHECK(std::abs(s) <= double(hit_error_bound(x)));
        }
    }

    // The bound that lets a refined point in must hold every correct float module's
    // point: the reference's modules, from cameras 1 to 1e5 away, measured across the
    // surface (from the exact point, in double) and across the ray, in ulps of the ray's
    // scale
    TEST_CASE("the reference's modules' hits lie within module_error_bound") {
        double worst[3] = {0.0, 0.0, 0.0};
        int accepted = 0, cases = 0;
        const Plane plane{glm::normalize(Vec3(0.1f, 1.0f, 0.05f)), 0.3f};
        const Sphere sphere{Vec3(0.3f, -0.2f, 0.1f), 0.7f};
        const Vec3 v0(-1.0f, -0.5f, 0.2f), v1(1.2f, -0.3f, -0.1f), v2(0.1f, 1.1f, 0.3f);
        for (int seed = 0; seed < 3000; ++seed) {
            Rng rng(seed);
            const float far = std::pow(10.0f, rng.uniform(0.0f, 5.0f));
            const Vec3 o = (2.0f + far) * rng.direction();
            const Vec3 target = rng.in_box(-1.0f, 1.0f);
            const Ray r{o, glm::normalize(target - o), 0.0f, kInfinity};
            for (int kind = 0; kind < 3; ++kind) {
                std::optional<Hit> hit;
                Vec3 on, n;
                if (kind == 0) {
                    hit = reference::intersect_plane(r, plane);
                    if (!hit) continue;
                    on = refine_on_plane(hit->position, r, plane);
                    n = plane.n;
                } else if (kind == 1) {
                    hit = reference::intersect_sphere(r, sphere);
                    if (!hit) continue;
                    on = refine_on_sphere(hit->position, r, hit->t, sphere);
                    n = glm::normalize(on - sphere.c);
                } else {
                    hit = reference::intersect_triangle(r, v0, v1, v2);
                    if (!hit) continue;
                    on = refine_on_triangle(hit->position, r, v0, v1, v2);
                    n = unit_normal(SceneTriangle{v0, v1, v2});
                }
                ++cases;
                const Vec3 x = hit->position;
                const double ulps = module_error_bound(r, hit->t, x) / 8.0;
                const DVec3 d = DVec3(on) - DVec3(x);
                const double across =
                    glm::length(glm::cross(DVec3(x) - DVec3(r.o), DVec3(r.w))) /
                    glm::length(DVec3(r.w));
                worst[kind] = std::max(
                    {worst[kind], std::abs(glm::dot(d, DVec3(n))) / ulps, across / ulps});
                accepted += accept_refined(x, on, n, r, hit->t) == on;
            }
        }
        MESSAGE(
            "largest distance of the reference's hits from the surface or the ray, in "
            "ulps of the ray's scale: plane "
            << worst[0] << ", sphere " << worst[1] << ", triangle " << worst[2]
            << "; refined points accepted: " << accepted << " of " << cases);
        CHECK(cases > 4000);
        for (const double w : worst)
            CHECK(w <= 8.0);
        CHECK(accepted == cases);
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
        CHECK(same(accept_refined(x, got, Vec3(0, 0, 1), nan_ray, 4.0f), x));
        CHECK(same(accept_refined(x, Vec3(kNaN), Vec3(0, 0, 1), r, 4.0f), x));
        CHECK(same(accept_refined(x, Vec3(0.0f), Vec3(kNaN), r, 4.0f), x));
    }

    TEST_CASE("a wrong hit point from a module is not pulled onto the surface") {
        // A module that reports position = o + t (forgetting w): 5 units off the plane
        const Ray r{Vec3(0, 0, 5), Vec3(0, 0, -1), 0.0f, kInfinity};
        const Plane p{Vec3(0, 0, 1), 0.0f};
        const Vec3 n = p.n;
        const Vec3 wrong = r.o + Vec3(5.0f);
        CHECK(
            same(accept_refined(wrong, refine_on_plane(wrong, r, p), n, r, 5.0f), wrong));
        // 1e-3 off the plane, on the ray: far beyond rounding (8 ulps of 10 is 1e-5)
        const Vec3 above(0.0f, 0.0f, 1e-3f);
        CHECK(
            same(accept_refined(above, refine_on_plane(above, r, p), n, r, 5.0f), above));
        // On the plane, 1e-3 off the ray (a wrong direction)
        const Vec3 aside(1e-3f, 0.0f, 0.0f);
        CHECK(
            same(accept_refined(aside, refine_on_plane(aside, r, p), n, r, 5.0f), aside));
        // The right point, a few ulps off, is refined
        const Vec3 close(0.0f, 0.0f, 3e-7f);
        CHECK(accept_refined(close, refine_on_plane(close, r, p), n, r, 5.0f).z == 0.0f);
        // Just inside and just outside the bound, 8 ulps of the ray's scale 5 + 5 + 0
        const float bound = module_error_bound(r, 5.0f, Vec3(0.0f));
        const Vec3 in(0.0f, 0.0f, 0.99f * bound), out(0.0f, 0.0f, 1.1f * bound);
        CHECK(accept_refined(in, refine_on_plane(in, r, p), n, r, 5.0f).z == 0.0f);
        CHECK(same(accept_refined(out, refine_on_plane(out, r, p), n, r, 5.0f), out));
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
