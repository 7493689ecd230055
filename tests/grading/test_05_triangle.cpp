// Graders of module 05_triangle (docs/handouts/05_triangle.md).
//
// The hit point is (1 - beta - gamma) v0 + beta v1 + gamma v2 with beta, gamma >= 0 and
// beta + gamma <= 1; hit.uv = (beta, gamma); hit.n = normalize((v1 - v0) x (v2 - v0)),
// whichever side the ray comes from. Any correct method passes: Cramer's rule,
// Moeller-Trumbore, edge functions, float or double.
#include "grading.h"

using namespace raylab;
using namespace raylab::grading;

namespace {

// The unit right triangle in the plane z = 0; counter-clockwise seen from +z, n = (0, 0,
// 1)
const Vec3 kV0(0, 0, 0), kV1(1, 0, 0), kV2(0, 1, 0);
const Vec3 kDown(0, 0, -1);

bool check(const Ray& r, const Vec3& v0, const Vec3& v1, const Vec3& v2,
           const std::optional<Hit>& want) {
    INFO(show(r) << "; " << show_triangle(v0, v1, v2));
    const std::optional<Hit> got = under_test::intersect_triangle(r, v0, v1, v2);
    return RAYLAB_CHECK_SAME(diff_hit(got, want, scale_of({r.o, v0, v1, v2}), true));
}

// A ray straight down onto the point (x, y, 0) of the unit triangle, from height 2
bool check_down(float x, float y, bool hits) {
    const Ray r{Vec3(x, y, 2), kDown};
    return check(r, kV0, kV1, kV2,
                 hits ? std::optional<Hit>(
                            make_hit(2.0f, Vec3(x, y, 0), Vec3(0, 0, 1), Vec2(x, y)))
                      : std::nullopt);
}

// Companion of the cases a constant or a table passes: rays aimed at a chosen inner point
// of a fresh random triangle, from either side, hit it there with its weights
std::string work_triangle() {
    for (int seed = 0; seed < 8; ++seed) {
        Rng rng(9700 + seed);
        const Vec3 v0 = rng.in_box(-5.0f, 5.0f);
        const Vec3 e1 = rng.uniform(1.0f, 4.0f) * rng.direction();
        const Vec3 side = glm::normalize(
            glm::cross(e1, rng.direction_near(glm::normalize(e1), -0.5f, 0.5f)));
        const Vec3 e2 =
            0.5f * e1 + rng.uniform(1.0f, 4.0f) * glm::cross(side, glm::normalize(e1));
        const Vec3 v1 = v0 + e1, v2 = v0 + e2;
        const float beta = rng.uniform(0.1f, 0.45f), gamma = rng.uniform(0.1f, 0.45f);
        const Vec3 p = v0 + beta * (v1 - v0) + gamma * (v2 - v0);
        const Vec3 n = glm::normalize(glm::cross(v1 - v0, v2 - v0));
        const Vec3 w = rng.direction_near(rng.integer(0, 1) ? n : -n, 0.3f, 1.0f);
        const float t = rng.uniform(0.5f, 10.0f);
        const Ray r{p - t * w, w};
        const std::string why = diff_hit(under_test::intersect_triangle(r, v0, v1, v2),
                                         make_hit(t, p, n, Vec2(beta, gamma)),
                                         scale_of({r.o, v0, v1, v2}), true);
        if (!why.empty()) return show(r) + "; " + show_triangle(v0, v1, v2) + ": " + why;
    }
    return "";
}

bool triangle_work() {
    return needs_work("rays aimed at points of fresh random triangles", work_triangle());
}

}  // namespace

TEST_SUITE("05_triangle") {
    TEST_CASE("a ray through the interior hits with barycentrics (beta, gamma)") {
        // Onto (0.2, 0.3, 0): t = 2, and the point is 0.5 v0 + 0.2 v1 + 0.3 v2
        check_down(0.2f, 0.3f, true);
    }

    TEST_CASE("uv holds the weights of v1 and v2, near each vertex") {
        // Near v1 uv is near (1, 0), near v2 near (0, 1), near v0 near (0, 0)
        check_down(0.9f, 0.05f, true);
        check_down(0.05f, 0.9f, true);
        check_down(0.05f, 0.05f, true);
    }

    TEST_CASE("a point beyond the long edge misses although beta and gamma are below 1") {
        triangle_work();
        // (0.6, 0.6): beta = gamma = 0.6 <= 1, but beta + gamma = 1.2 > 1
        check_down(0.6f, 0.6f, false);
    }

    TEST_CASE("points just outside each of the three edges miss") {
        triangle_work();
        // beta < 0, gamma < 0, beta + gamma > 1, each by 0.001
        check_down(-0.001f, 0.5f, false);
        check_down(0.5f, -0.001f, false);
        check_down(0.5005f, 0.5005f, false);
    }

    TEST_CASE("points just inside each of the three edges hit") {
        check_down(0.001f, 0.5f, true);
        check_down(0.5f, 0.001f, true);
        check_down(0.4995f, 0.4995f, true);
    }

    TEST_CASE("rays through an edge or a vertex hit: the borders are included") {
        // Points whose beta, gamma or beta + gamma are exactly 0 or 1 (exact in float)
        check_down(0.5f, 0.0f, true);
        check_down(0.0f, 0.25f, true);
        check_down(0.5f, 0.5f, true);
        check_down(1.0f, 0.0f, true);
        check_down(0.0f, 1.0f, true);
    }

    TEST_CASE("the triangle is hit from behind too, and its normal does not flip") {
        // From below, upwards: triangles are two-sided; n follows the winding, (0, 0, 1)
        check(Ray{Vec3(0.2f, 0.3f, -2), Vec3(0, 0, 1)}, kV0, kV1, kV2,
              make_hit(2.0f, Vec3(0.2f, 0.3f, 0), Vec3(0, 0, 1), Vec2(0.2f, 0.3f)));
    }

    TEST_CASE("the normal follows the winding: clockwise seen from the ray points away") {
        // Vertices (v0, v2, v1): (v2 - v0) x (v1 - v0) = (0, 0, -1); beta and gamma are
        // now the weights of (0, 1, 0) and (1, 0, 0): (0.3, 0.2)
        check(Ray{Vec3(0.2f, 0.3f, 2), kDown}, kV0, kV2, kV1,
              make_hit(2.0f, Vec3(0.2f, 0.3f, 0), Vec3(0, 0, -1), Vec2(0.3f, 0.2f)));
    }

    TEST_CASE("the normal of a large triangle has unit length") {
        // Edges of length 10: (v1 - v0) x (v2 - v0) = (0, 0, 100) before normalizing
        check(Ray{Vec3(2, 3, 5), kDown}, kV0, 10.0f * kV1, 10.0f * kV2,
              make_hit(5.0f, Vec3(2, 3, 0), Vec3(0, 0, 1), Vec2(0.2f, 0.3f)));
    }

    TEST_CASE("a triangle away from the origin is hit where it is") {
        // The unit triangle moved by m = (100, -50, 30): the hit moves with it
        const Vec3 m(100, -50, 30);
        check(Ray{m + Vec3(0.2f, 0.3f, 2), kDown}, kV0 + m, kV1 + m, kV2 + m,
              make_hit(2.0f, m + Vec3(0.2f, 0.3f, 0), Vec3(0, 0, 1), Vec2(0.2f, 0.3f)));
    }

    TEST_CASE("a triangle behind the ray's origin is not hit") {
        triangle_work();
        check(Ray{Vec3(0.2f, 0.3f, 2), Vec3(0, 0, 1)}, kV0, kV1, kV2, std::nullopt);
    }

    TEST_CASE("hits outside [tmin, tmax] are rejected, hits inside accepted") {
        // The triangle is at t = 2 along this ray
        const Vec3 o(0.2f, 0.3f, 2);
        const Hit at2 =
            make_hit(2.0f, Vec3(0.2f, 0.3f, 0), Vec3(0, 0, 1), Vec2(0.2f, 0.3f));
        check(Ray{o, kDown, 0.0f, 1.9f}, kV0, kV1, kV2, std::nullopt);
        check(Ray{o, kDown, 2.1f, kInfinity}, kV0, kV1, kV2, std::nullopt);
        check(Ray{o, kDown, 1.9f, 2.1f}, kV0, kV1, kV2, at2);
    }

    TEST_CASE("a ray parallel to the triangle's plane misses it") {
        triangle_work();
        // w . n = 0: the determinant is zero (no division by it, no NaN hit)
        check(Ray{Vec3(-1, 0.2f, 1), Vec3(1, 0, 0)}, kV0, kV1, kV2, std::nullopt);
        check(Ray{Vec3(-1, 0.2f, 0), Vec3(1, 0, 0)}, kV0, kV1, kV2, std::nullopt);
    }

    TEST_CASE("small triangles, legs down to 1e-3, are hit") {
        // The determinant shrinks with the square of the size (1e-6 here): a fixed
        // threshold on it such as 1e-3 makes every triangle with legs below about 0.03
        // vanish. Near the origin and away from it
        for (const float s : {1e-3f, 1e-2f}) {
            for (const Vec3& at : {Vec3(0.0f), Vec3(1, 1, 0)}) {
                const Vec3 v0 = at, v1 = at + Vec3(s, 0, 0), v2 = at + Vec3(0, s, 0);
                const Vec3 p = at + Vec3(0.25f * s, 0.25f * s, 0);
                const Ray r{p + Vec3(0, 0, 2), kDown};
                check(
                    r, v0, v1, v2,
                    make_hit(2.0f, r.o + 2.0f * r.w, Vec3(0, 0, 1), Vec2(0.25f, 0.25f)));
            }
        }
    }

    TEST_CASE("a degenerate triangle with collinear vertices is never hit") {
        triangle_work();
        // All three vertices on the x axis: zero area, no normal
        check(Ray{Vec3(0.5f, 0, 1), kDown}, Vec3(0.0f), Vec3(1, 0, 0), Vec3(2, 0, 0),
              std::nullopt);
        check(Ray{Vec3(0.5f, 0, 1), kDown}, Vec3(0.0f), Vec3(0.0f), Vec3(1, 0, 0),
              std::nullopt);
    }

    TEST_CASE("random rays and triangles agree with the reference") {
        triangle_work();
        // Random triangles that are not slivers; rays aimed at a chosen point at least
        // 0.02 inside or outside in barycentric terms, from either side, at least 11
        // degrees off the plane, with [tmin, tmax] containing the hit or missing it by
        // 10% or more
        for (int seed = 0; seed < 300; ++seed) {
            Rng rng(seed);
            Vec3 v0, v1, v2, N;
            do {
                v0 = rng.in_box(-5.0f, 5.0f);
                v1 = rng.in_box(-5.0f, 5.0f);
                v2 = rng.in_box(-5.0f, 5.0f);
                N = glm::cross(v1 - v0, v2 - v0);
            } while (glm::length(N) < 0.2f * std::max({glm::dot(v1 - v0, v1 - v0),
                                                       glm::dot(v2 - v0, v2 - v0),
                                                       glm::dot(v2 - v1, v2 - v1)}));
            const bool inside = rng.integer(0, 2) != 0;
            float beta, gamma;
            for (;;) {
                beta = rng.uniform(-0.5f, 1.5f);
                gamma = rng.uniform(-0.5f, 1.5f);
                const float margin = std::min({beta, gamma, 1.0f - beta - gamma});
                if (inside ? margin >= 0.02f : margin <= -0.02f) break;
            }
            const Vec3 p = v0 + beta * (v1 - v0) + gamma * (v2 - v0);
            Vec3 w = rng.direction_near(glm::normalize(N), 0.2f, 1.0f);
            if (rng.integer(0, 1)) w = -w;
            const float t = rng.uniform(0.2f, 10.0f);
            const Ray r = random_ray_through(rng, p, w, t);
            INFO("seed " << seed << ": " << show(r) << "; " << show_triangle(v0, v1, v2));
            const auto want = expected<std::optional<Hit>>(
                "05_triangle/random rays/" + std::to_string(seed), inputs(r, v0, v1, v2),
                [&] { return reference_modules().intersect_triangle(r, v0, v1, v2); });
            const auto got = under_test::intersect_triangle(r, v0, v1, v2);
            if (!RAYLAB_CHECK_SAME(
                    diff_hit(got, want, scale_of({r.o, v0, v1, v2}), true)))
                break;
        }
    }
}
