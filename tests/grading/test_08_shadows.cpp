// Graders of module 08_shadows (docs/handouts/08_shadows.md).
//
// The light counts at x only if the any-hit query finds nothing on the segment from x to
// the light. The shadow ray must leave the surface without hitting it again (no shadow
// acne) and stop before the light (blockers beyond the light cast no shadow).
//
// The scenes here are fakes of the Occluder interface that record every ray they are
// asked about: small balls on or off the segment, and the surface x lies on. Any correct
// shadow ray passes: offset origin or tmin, cast from x or from the light, any reasonable
// epsilon (up to 0.01 near the origin, growing with |x|). Every case that expects "lit"
// also expects "in shadow" once a blocker is put on the segment, and every case that
// expects "in shadow" also expects "lit" once the blockers are gone, so a constant
// answer earns nothing.
#include <vector>

#include "grading.h"

using namespace raylab;
using namespace raylab::grading;

namespace {

using DVec = glm::dvec3;

/// A scene of small balls and, optionally, the plane of the surface x lies on. Every ray
/// it is asked about is recorded.
class FakeScene : public Occluder {
  public:
    struct Ball {
        Vec3 b;      ///< centre
        double rho;  ///< radius
    };
    std::vector<Ball> balls;
    bool has_surface = false;
    Vec3 surface_point{0.0f}, surface_n{0.0f};  ///< the plane (p - point) . n = 0
    struct Plane {
        Vec3 point, n;
        double touch;  ///< a segment ending within this distance of the plane meets it
    };
    std::vector<Plane> planes;  ///< other surfaces: a wall at a corner, a ceiling
    mutable std::vector<Ray> rays;

    bool occluded(const Ray& r) const override {
        rays.push_back(r);
        for (const Ball& ball : balls) {
            if (segment_distance(r, ball.b) <= ball.rho) return true;
        }
        for (const Plane& p : planes) {
            if (crosses(r, p.point, p.n, p.touch)) return true;
        }
        return has_surface && crosses(r, surface_point, surface_n, 0.0);
    }

    std::string describe() const {
        std::string s;
        for (const Ball& ball : balls)
            s += "ball at " + show(ball.b) + " of radius " + show(ball.rho) + "; ";
        if (has_surface)
            s += "the surface through " + show(surface_point) + " with normal " +
                 show(surface_n) + "; ";
        for (const Plane& p : planes)
            s +=
                "the plane through " + show(p.point) + " with normal " + show(p.n) + "; ";
        return s.empty() ? std::string("nothing") : s;
    }

  private:
    // Distance from b to the points o + t w with tmin <= t <= tmax (w need not be unit)
    static double segment_distance(const Ray& r, const Vec3& b) {
        const DVec o(r.o), w(r.w), to_b = DVec(b) - o;
        const double ww = glm::dot(w, w);
        if (!(ww > 0.0) || !(r.tmin <= r.tmax)) return kInfinity;
        const double t =
            std::clamp(glm::dot(to_b, w) / ww, double(r.tmin), double(r.tmax));
        return glm::length(o + t * w - DVec(b));
    }
    // Does the segment touch or cross the plane through point with normal n?
    static bool crosses(const Ray& r, const Vec3& point, const Vec3& normal,
                        double touch) {
        const DVec n(normal), w(r.w);
        if (!std::isfinite(r.tmin) || std::isnan(r.tmax)) return true;
        const double s0 = glm::dot(DVec(r.o) + double(r.tmin) * w - DVec(point), n);
        const double wn = glm::dot(w, n);
        double s1;
        if (std::isinf(r.tmax))
            s1 = wn > 0 ? kInfinity : wn < 0 ? -kInfinity : s0;
        else
            s1 = glm::dot(DVec(r.o) + double(r.tmax) * w - DVec(point), n);
        return (s0 <= touch && s1 >= -touch) || (s0 >= -touch && s1 <= touch);
    }
};

const Vec3 kUp(0, 1, 0);
// The light 4 units above the origin, seen from the origin
const LightSample kAbove{kUp, 4.0f, Vec3(1.0f)};

bool check(const FakeScene& scene, const Vec3& x, const Vec3& n, const LightSample& s,
           bool want) {
    INFO("in_shadow(x = " << show(x) << ", n = " << show(n) << ", " << show(s)
                          << ") in a scene of " << scene.describe());
    const bool got = under_test::in_shadow(scene, x, n, s);
    std::string rays;
    for (const Ray& r : scene.rays)
        rays += "\n    " + show(r);
    const std::string verdict[] = {"lit", "in shadow"};
    if (rays.empty()) rays = " none";
    return RAYLAB_CHECK(got == want, "expected " << verdict[want] << ", got "
                                                 << verdict[got]
                                                 << "; the shadow rays were:" << rays);
}

// The same scene with a ball of radius 0.02 halfway between x and the light: now x is in
// shadow. Every "lit" expectation is paired with this one, so that a module that always
// answers "lit" earns nothing
FakeScene with_blocker(const FakeScene& base, const Vec3& x, const LightSample& s) {
    FakeScene scene;
    scene.has_surface = base.has_surface;
    scene.surface_point = base.surface_point;
    scene.surface_n = base.surface_n;
    scene.planes.reserve(base.planes.size());
    for (const FakeScene::Plane& p : base.planes)
        scene.planes.push_back(p);
    scene.balls.reserve(base.balls.size() + 1);
    for (const FakeScene::Ball& b : base.balls)
        scene.balls.push_back(b);
    scene.balls.push_back({x + 0.5f * s.r * s.wi, 0.02});
    return scene;
}

// "lit" for scene, and "in shadow" once a blocker is put halfway to the light
bool check_lit(const FakeScene& scene, const Vec3& x, const Vec3& n,
               const LightSample& s) {
    return check(scene, x, n, s, false) &&
           check(with_blocker(scene, x, s), x, n, s, true);
}

// "in shadow" for scene, and "lit" once its balls are taken away: a module that always
// answers "in shadow" earns nothing either
bool check_dark(const FakeScene& scene, const Vec3& x, const Vec3& n,
                const LightSample& s) {
    FakeScene open = scene;
    open.balls.clear();
    open.rays.clear();
    return check(scene, x, n, s, true) && check(open, x, n, s, false);
}

// Companion of the cases that only look at the shadow rays: with nothing in the way the
// point is lit
std::string work_lit() {
    const FakeScene empty;
    const LightSample s{Vec3(0.6f, 0.8f, 0.0f), 5.0f, Vec3(1.0f)};
    if (under_test::in_shadow(empty, Vec3(1, 2, 3), Vec3(0, 1, 0), s))
        return "in_shadow(x = (1, 2, 3), n = (0, 1, 0), " + show(s) +
               ") in an empty scene: expected lit, got in shadow";
    return "";
}

FakeScene balls(std::initializer_list<FakeScene::Ball> list) {
    FakeScene scene;
    scene.balls = list;
    return scene;
}

// A surface point as the intersection modules produce it: x_true lies on the surface, the
// float x that comes back is a few ulps of its largest coordinate below it
struct SurfacePoint {
    Vec3 x;
    double below;  ///< how far x lies below the surface
};
SurfacePoint below_surface(const Vec3& x_true, const Vec3& n) {
    const float m =
        std::max({std::abs(x_true.x), std::abs(x_true.y), std::abs(x_true.z)});
    const float ulp = std::nextafter(m, kInfinity) - m;
    for (float k = 2.0f;; k += 1.0f) {
        const Vec3 x = x_true - k * ulp * n;
        const double s = glm::dot(DVec(x) - DVec(x_true), DVec(n));
        if (s < 0.0) return {x, -s};
    }
}

// A random case around centre: the surface point, its normal, a light at most 75 degrees
// from the normal and 0.5 to 20 units away, and the float x a few ulps below the surface
struct Setup {
    Vec3 x_true, n;
    LightSample s;
    SurfacePoint x;
};
Setup random_setup(Rng& rng, const Vec3& centre, float spread) {
    Setup c;
    c.x_true = centre + rng.in_box(-spread, spread);
    c.n = rng.direction();
    const Vec3 wi = rng.direction_near(c.n, 0.25f, 1.0f);
    c.s = LightSample{wi, rng.uniform(0.5f, 20.0f), Vec3(1.0f)};
    c.x = below_surface(c.x_true, c.n);
    return c;
}

FakeScene surface_of(const Setup& c) {
    FakeScene scene;
    scene.has_surface = true;
    scene.surface_point = c.x_true;
    scene.surface_n = c.n;
    return scene;
}

}  // namespace

TEST_SUITE("08_shadows") {
    TEST_CASE("a blocker halfway to the light casts a shadow") {
        // x = 0, light at (0, 4, 0), a ball of radius 0.05 at (0, 2, 0)
        check_dark(balls({{Vec3(0, 2, 0), 0.05}}), Vec3(0.0f), kUp, kAbove);
    }

    TEST_CASE("with nothing in the way the point is lit, and the scene is asked") {
        const FakeScene empty;
        check_lit(empty, Vec3(0.0f), kUp, kAbove);
        RAYLAB_CHECK(!empty.rays.empty(),
                     "expected in_shadow to ask scene.occluded(ray), but it never did");
    }

    TEST_CASE("a blocker beyond the light casts no shadow") {
        // The ball at (0, 6, 0) is 2 units past the light: the shadow ray must stop at it
        check_lit(balls({{Vec3(0, 6, 0), 0.05}}), Vec3(0.0f), kUp, kAbove);
    }

    TEST_CASE(
        "a blocker just before the light casts a shadow, one just past it does not") {
        // Balls of radius 0.02 at 1% of the distance before and after the light at 4
        check_dark(balls({{Vec3(0, 3.96f, 0), 0.02}}), Vec3(0.0f), kUp, kAbove);
        check(balls({{Vec3(0, 4.04f, 0), 0.02}}), Vec3(0.0f), kUp, kAbove, false);
    }

    TEST_CASE("a blocker in the last 1% before a far light casts a shadow") {
        // The light 64 units above x, a ball of radius 1/8 at 63.5 (0.8% before it): the
        // shadow ray must reach to within an epsilon of the light, not stop at a share
        // of the distance such as 0.99 r = 63.36 (all numbers exact in float)
        const LightSample far{kUp, 64.0f, Vec3(1.0f)};
        check_dark(balls({{Vec3(0, 63.5f, 0), 0.125}}), Vec3(0.0f), kUp, far);
        check_dark(balls({{Vec3(0.5f, 63.5f, 0), 0.125}}), Vec3(0.5f, 0, 0), kUp, far);
    }

    TEST_CASE("a blocker behind the surface point casts no shadow") {
        // Below the floor, on the far side from the light; the light lies between the two
        // blockers of the second scene
        check_lit(balls({{Vec3(0, -1, 0), 0.05}}), Vec3(0.0f), kUp, kAbove);
        check_lit(balls({{Vec3(0, -1, 0), 0.05}, {Vec3(0, 5, 0), 0.05}}), Vec3(0.0f), kUp,
                  kAbove);
    }

    TEST_CASE("a blocker close to the surface still casts a shadow") {
        // A ball of radius 0.005 at height 0.02: an offset of 0.01 still sees it
        check_dark(balls({{Vec3(0, 0.02f, 0), 0.005}}), Vec3(0.0f), kUp, kAbove);
    }

    TEST_CASE("the surface does not shadow its own point (no shadow acne)") {
        // x lies a few ulps below the surface it was found on, as float hit points do;
        // the only thing in the scene is that surface
        for (int seed = 0; seed < 100; ++seed) {
            Rng rng(seed);
            const Setup c = random_setup(rng, Vec3(0.0f), 4.0f);
            INFO("seed " << seed << ": x lies " << show(c.x.below)
                         << " below the surface");
            if (!check_lit(surface_of(c), c.x.x, c.n, c.s)) break;
        }
    }

    TEST_CASE("a point 100 units from the origin shows no shadow acne either") {
        // Here x's rounding error is about 1e-5: a fixed offset must exceed it
        for (int seed = 0; seed < 100; ++seed) {
            Rng rng(1000 + seed);
            const Setup c = random_setup(rng, Vec3(100, -60, 80), 1.0f);
            INFO("seed " << seed << ": x lies " << show(c.x.below)
                         << " below the surface");
            if (!check_lit(surface_of(c), c.x.x, c.n, c.s)) break;
        }
    }

    TEST_CASE("a point 10^4 units from the origin shows no shadow acne either") {
        // x's rounding error is about 1e-3 here (handout 08 §3: the offset grows with
        // |x|), so a fixed offset of 1e-4 or 1e-3 gives acne
        for (int seed = 0; seed < 100; ++seed) {
            Rng rng(4000 + seed);
            const Setup c = random_setup(rng, Vec3(9000, -6000, 4000), 1000.0f);
            INFO("seed " << seed << ": x lies " << show(c.x.below)
                         << " below the surface");
            if (!check_lit(surface_of(c), c.x.x, c.n, c.s)) break;
        }
    }

    TEST_CASE("at an inside corner the wall does not shadow the floor (tmin > 0)") {
        // x on the floor y = 0, on the edge where the wall x = 0 meets it. Offset along
        // n, the ray starts in the wall's plane: with tmin = 0 the wall blocks at t = 0
        // and inside corners turn black (handout 08 §3)
        FakeScene scene;
        scene.has_surface = true;
        scene.surface_point = Vec3(0.0f);
        scene.surface_n = kUp;
        scene.planes.push_back({Vec3(0.0f), Vec3(1, 0, 0), 0.0});
        const Vec3 x(0, 0, 0.3f);
        for (const Vec3& wi :
             {Vec3(0.6f, 0.8f, 0), Vec3(0.8f, 0.6f, 0), Vec3(0.28f, 0.96f, 0)}) {
            if (!check_lit(scene, x, kUp, LightSample{wi, 4.0f, Vec3(1.0f)})) break;
        }
    }

    TEST_CASE("a light lying in a surface's plane is not shadowed by that surface") {
        // The light sits in the ceiling y = 4 (as a lamp mounted on it does): a shadow
        // segment that reaches the light itself meets the ceiling there
        FakeScene scene;
        scene.planes.push_back({Vec3(0, 4, 0), Vec3(0, -1, 0), 1e-5});
        for (const Vec3& x : {Vec3(0.0f), Vec3(1, 0, 0), Vec3(0, 2, 0)}) {
            const Vec3 light(0, 4, 0);
            const LightSample s{glm::normalize(light - x), glm::length(light - x),
                                Vec3(1.0f)};
            if (!check_lit(scene, x, kUp, s)) break;
        }
    }

    TEST_CASE("one shadow test asks the scene one any-hit query") {
        needs_work("a point with nothing in the way being lit", work_lit());
        const FakeScene empty;
        (void)under_test::in_shadow(empty, Vec3(0.0f), kUp, kAbove);
        RAYLAB_CHECK(empty.rays.size() == 1, "scene.occluded was called "
                                                 << empty.rays.size()
                                                 << " times, expected once");
    }

    TEST_CASE("the shadow ray has a unit direction") {
        needs_work("a point with nothing in the way being lit", work_lit());
        // Rays have |w| = 1 (the intersection modules rely on it), also towards a light 4
        // units away
        const FakeScene empty;
        (void)under_test::in_shadow(empty, Vec3(0.0f), kUp, kAbove);
        RAYLAB_REQUIRE(!empty.rays.empty(),
                       "expected in_shadow to ask scene.occluded(ray), but it never did");
        for (const Ray& r : empty.rays) {
            INFO(show(r));
            RAYLAB_CHECK(close(glm::length(r.w), 1.0, tol::kDirection),
                         "|w| = " << show(glm::length(r.w)) << ", expected 1");
        }
    }

    TEST_CASE("the shadow ray runs along the line between the point and the light") {
        needs_work("a point with nothing in the way being lit", work_lit());
        // Its direction is +-wi, and it starts near x or near the light
        const Vec3 x(1, 2, 3), light = x + 4.0f * Vec3(0.6f, 0.8f, 0.0f);
        const LightSample s{Vec3(0.6f, 0.8f, 0.0f), 4.0f, Vec3(1.0f)};
        const FakeScene empty;
        (void)under_test::in_shadow(empty, x, Vec3(0, 0.6f, 0.8f), s);
        RAYLAB_REQUIRE(!empty.rays.empty(),
                       "expected in_shadow to ask scene.occluded(ray), but it never did");
        for (const Ray& r : empty.rays) {
            INFO(show(r) << " for x = " << show(x) << " and the light at "
                         << show(light));
            const Vec3 w = glm::normalize(r.w);
            // Along +-wi to 1e-4 in cosine; starting within 0.02, the largest offset a
            // reasonable epsilon gives here
            RAYLAB_CHECK(std::abs(std::abs(glm::dot(w, s.wi)) - 1.0f) < 1e-4f,
                         "the direction is not along wi = " << show(s.wi));
            RAYLAB_CHECK(glm::length(r.o - x) < 0.02f || glm::length(r.o - light) < 0.02f,
                         "the ray starts neither at x nor at the light");
        }
    }

    TEST_CASE("random points, lights and blockers cast the right shadows") {
        // Each case has the surface x lies on and, at random, a ball of radius 0.015
        // between x and the light, past the light, behind x, or none. An offset of up to
        // 0.01 along n moves the ray less than the radius sideways, so it still meets the
        // ball between x and the light
        for (int seed = 0; seed < 300; ++seed) {
            Rng rng(2000 + seed);
            const Setup c = random_setup(rng, Vec3(0.0f), 10.0f);
            FakeScene scene = surface_of(c);
            const int kind = rng.integer(0, 3);
            const float r = c.s.r;
            if (kind == 0) {
                const float s = rng.uniform(std::max(0.05f, 0.1f * r), 0.9f * r);
                scene.balls.push_back({c.x_true + s * c.s.wi, 0.015});
            } else if (kind == 1) {
                const float s = rng.uniform(1.1f * r, 2.0f * r);
                scene.balls.push_back({c.x_true + s * c.s.wi, 0.015});
            } else if (kind == 2) {
                const float s = rng.uniform(0.05f, 2.0f);
                scene.balls.push_back({c.x_true - s * c.s.wi, 0.015});
            }
            INFO("seed " << seed);
            if (kind == 0 ? !check(scene, c.x.x, c.n, c.s, true)
                          : !check_lit(scene, c.x.x, c.n, c.s))
                break;
        }
    }
}
