// Ray-sphere numerics: far from the origin (also through the scene), tangent rays, rays
// starting on the surface, radii whose square overflows or underflows.
#include <doctest/doctest.h>

#include "meshes.h"
#include "raylab/error.h"
#include "test_helpers.h"

using namespace raylab;

namespace {

// Nearest root of |o + t w - c|^2 = r^2 in long double, from the same float inputs
std::optional<long double> true_t(const Ray& r, const Sphere& s) {
    using L = long double;
    const L fx = L(r.o.x) - s.c.x, fy = L(r.o.y) - s.c.y, fz = L(r.o.z) - s.c.z;
    const L wx = r.w.x, wy = r.w.y, wz = r.w.z;
    const L a = wx * wx + wy * wy + wz * wz;
    const L b = fx * wx + fy * wy + fz * wz;
    const L c = fx * fx + fy * fy + fz * fz - L(s.r) * s.r;
    const L disc = b * b - a * c;
    if (disc < 0) return std::nullopt;
    const L t0 = (-b - std::sqrt(disc)) / a, t1 = (-b + std::sqrt(disc)) / a;
    if (t0 >= r.tmin && t0 <= r.tmax) return t0;
    if (t1 >= r.tmin && t1 <= r.tmax) return t1;
    return std::nullopt;
}

float ulp(float x) {
    return std::nextafter(std::abs(x), kInfinity) - std::abs(x);
}

}  // namespace

TEST_SUITE("stress sphere") {
    TEST_CASE("small spheres far from the origin are hit where they are, to a few ulps") {
        // Rays from near the origin towards random points of the sphere's central disc.
        // The textbook b^2 - c loses every digit here: b^2 and c are about D^2 and the
        // difference is about r^2 (D = 1e4, r = 1: 1e8 vs 1, below float's 24 bits).
        for (const float D : {1.0f, 1e2f, 1e4f, 1e5f}) {
            Rng rng(static_cast<std::uint64_t>(D));
            const Sphere s{Vec3(D, 0.5f * D, -0.25f * D), 1.0f};
            int misses = 0;
            float worst_ulps = 0.0f;
            for (int k = 0; k < 4000; ++k) {
                // Target: within 0.9 r of the centre, across the line of sight
                Vec3 off = rng.in_box(-0.52f, 0.52f);
                const Vec3 o = rng.in_box(-1.0f, 1.0f);
                const Vec3 to_c = glm::normalize(s.c - o);
                off -= glm::dot(off, to_c) * to_c;
                const Ray r{o, glm::normalize(s.c + off - o), 0.0f, kInfinity};
                const auto truth = true_t(r, s);
                const auto hit = reference::intersect_sphere(r, s);
                INFO("D = " << D << ", ray " << k << ": " << r);
                if (!truth) continue;
                if (!hit) {
                    ++misses;
                    continue;
                }
                // Error in ulps of the problem's scale: the larger of t and |o - c|
                const float err = static_cast<float>(std::abs(hit->t - *truth));
                const float scale =
                    std::max(static_cast<float>(*truth), glm::length(r.o - s.c));
                worst_ulps = std::max(worst_ulps, err / ulp(scale));
            }
            INFO("D = " << D << ": worst error " << worst_ulps
                        << " ulp(max(t, |o - c|))");
            CHECK(misses == 0);
            // Named tolerance: t is within 8 ulps of the problem's scale max(t, |o - c|)
            // (the inputs alone carry about 1 ulp of D in o - c)
            CHECK(worst_ulps <= 8.0f);
        }
    }

    TEST_CASE("tangent and grazing rays never produce NaN, and hits lie on the sphere") {
        Rng rng(7);
        const Sphere s{Vec3(3.0f, -2.0f, 1.0f), 0.75f};
        for (int k = 0; k < 20000; ++k) {
            // A ray passing at distance r (1 +- 1e-6 .. 1e-3) from the centre
            const Vec3 w = rng.direction();
            Vec3 side = glm::normalize(glm::cross(w, rng.direction()));
            const float scale = 1.0f + rng.uniform(-1e-3f, 1e-3f);
            const Vec3 o = s.c + side * (s.r * scale) - 5.0f * w;
            const Ray r{o, w, 0.0f, kInfinity};
            INFO("ray " << k << ": " << r);
            const auto hit = reference::intersect_sphere(r, s);
            if (!hit) continue;
            REQUIRE(std::isfinite(hit->t));
            REQUIRE(is_finite(hit->n));
            CHECK(std::abs(glm::length(hit->position - s.c) - s.r) < 1e-5f);
        }
    }

    TEST_CASE("a ray leaving the surface outwards does not hit its own sphere") {
        Rng rng(11);
        for (const float D : {0.0f, 1e3f, 1e5f}) {
            const Sphere s{Vec3(D, 0.0f, 0.0f), 1.0f};
            for (int k = 0; k < 2000; ++k) {
                const Vec3 n = rng.direction();
                const Vec3 x = s.c + n * s.r;  // on the surface, rounded
                Vec3 w = rng.direction();
                if (glm::dot(w, n) < 0.05f) w = glm::normalize(w + n);
                // The shadow module's offset strategy: tmin proportional to the
                // coordinates
                const float eps = 1e-4f * std::max(1.0f, std::abs(x.x));
                const Ray r{x + eps * n, w, 0.0f, kInfinity};
                INFO("D = " << D << ", ray " << k << ": " << r);
                CHECK_FALSE(reference::intersect_sphere(r, s).has_value());
            }
        }
    }

    TEST_CASE("a small sphere far away is hit through the scene where the kernel hits") {
        const Sphere s{Vec3(70000.296875f, 0.0f, 0.0f), 0.3f};
        const Ray r{Vec3(0x1.117098p+16f, -5.0f, 0.0f),
                    Vec3(0x1.47ae14p-12f, 0x1.fffffep-1f, 0.0f), 0.0f, kInfinity};
        REQUIRE(reference::intersect_sphere(r, s));
        Scene scene = one_material_scene();
        scene.spheres.push_back(SceneSphere{s, 0});
        scene.commit();
        CHECK(scene_hits(scene, r));
        // The box holds the exact sphere: c + r and c - r rounded outwards
        const Aabb box = scene.bounds();
        CHECK(double(box.hi.x) >= double(s.c.x) + double(s.r));
        CHECK(double(box.lo.x) <= double(s.c.x) - double(s.r));
    }

    TEST_CASE("spheres whose r^2 overflows or underflows are refused by name") {
        for (const float radius : {1.9e19f, 1e30f, 1e-40f, 1e-25f}) {
            Scene scene = one_material_scene();
            scene.spheres.push_back(SceneSphere{Sphere{Vec3(0.0f), radius}, 0});
            INFO("radius " << radius);
            CHECK_THROWS_WITH_AS(scene.commit(), doctest::Contains("sphere 0"), Error);
        }
    }
}
