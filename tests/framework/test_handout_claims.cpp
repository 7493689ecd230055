// The handouts' "if you see X, check Y" claims, each rendered from a mutant of the
// reference with mistake Y: the image must show X. The claims of docs/handouts/: 01's
// hints and 02 §1 (upside down, mirrored, turned 180 degrees, squeezed), and the Expected
// image sections of 03 (ground missing, white sky), 06 (black but for crescents, gentle
// falloff) and 07 (pi times too bright).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <vector>

#include <doctest/doctest.h>

#include "raylab/image.h"
#include "raylab/renderer.h"
#include "raylab/scenes.h"
#include "test_helpers.h"

using namespace raylab;

namespace {

constexpr int W = 96, H = 64;

// Module 01 with v of the wrong sign
Vec2 v_negated(int i, int j, int w, int h) {
    const Vec2 p = reference::image_plane_point(i, j, w, h);
    return Vec2(p.x, -p.y);
}
// Module 01 with u of the wrong sign
Vec2 u_negated(int i, int j, int w, int h) {
    const Vec2 p = reference::image_plane_point(i, j, w, h);
    return Vec2(-p.x, p.y);
}
// Module 01 with u missing the aspect factor a = W / H (divided by W instead of H)
Vec2 u_without_aspect(int i, int j, int w, int h) {
    const Vec2 p = reference::image_plane_point(i, j, w, h);
    return Vec2(p.x * float(h) / float(w), p.y);
}
// Module 01's render_tile calling the mutant's own image_plane_point, as a student's does
template <Vec2 (*point)(int, int, int, int)>
void tile_with(const Tile& tile, const PixelRadiance& radiance, const ImageView& image) {
    for (int j = tile.y0; j < tile.y1; ++j)
        for (int i = tile.x0; i < tile.x1; ++i)
            image.set(i, j, radiance(point(i, j, image.width, image.height)));
}

// Module 02 with x = u x n (y = x x n as the handout says): handout 02 §1
CameraFrame x_from_u_cross_n(const Vec3& eye, const Vec3& lookat, const Vec3& up) {
    const Vec3 n = glm::normalize(lookat - eye);
    const Vec3 x = glm::normalize(glm::cross(up, n));
    return {x, glm::cross(x, n), n};
}
// Module 02 with y = n x x
CameraFrame y_from_n_cross_x(const Vec3& eye, const Vec3& lookat, const Vec3& up) {
    const Vec3 n = glm::normalize(lookat - eye);
    const Vec3 x = glm::normalize(glm::cross(n, up));
    return {x, glm::cross(n, x), n};
}
// Module 02 with both orders swapped: x = u x n, y = n x x
CameraFrame both_swapped(const Vec3& eye, const Vec3& lookat, const Vec3& up) {
    const Vec3 n = glm::normalize(lookat - eye);
    const Vec3 x = glm::normalize(glm::cross(up, n));
    return {x, glm::cross(n, x), n};
}

// Module 03 with t of the wrong sign: t = (o . n + d) / (w . n)
std::optional<Hit> plane_t_sign(const Ray& r, const Plane& plane) {
    Ray mirrored = r;  // the reference's t for -w is minus its t for w
    mirrored.w = -r.w;
    std::optional<Hit> hit = reference::intersect_plane(mirrored, plane);
    if (hit) hit->position = r.o + hit->t * r.w;
    return hit;
}
// Module 03 whose acceptance test lets negative t through: t <= tmax only
std::optional<Hit> plane_negative_t(const Ray& r, const Plane& plane) {
    Ray unbounded = r;
    unbounded.tmin = -std::numeric_limits<float>::infinity();
    return reference::intersect_plane(unbounded, plane);
}
// Module 06 with wi pointing from the light to x
LightSample light_wi_reversed(const PointLight& light, const Vec3& x) {
    LightSample s = reference::sample_point_light(light, x);
    s.wi = -s.wi;
    return s;
}
// Module 06 without the square: Li = I / r
LightSample light_without_square(const PointLight& light, const Vec3& x) {
    LightSample s = reference::sample_point_light(light, x);
    s.Li *= s.r;
    return s;
}
// Module 07 without the 1 / pi of the BRDF
Vec3 lambert_without_pi(const Vec3& rho, const Vec3& Le, const Vec3& n,
                        const std::vector<LightSample>& lights) {
    return Le + kPi * (reference::lambert(rho, Le, n, lights) - Le);
}

Image render_with(const ModuleTable& m, const Scene& scene, int w, int h,
                  ShadingMode mode = ShadingMode::base) {
    RenderSettings settings;
    settings.width = w;
    settings.height = h;
    settings.mode = mode;
    settings.shadows = false;  // the handouts' pictures of modules 06 and 07
    Image image;
    render(scene, scene.view, settings, m, image);
    return image;
}

float largest(const Vec3& a, const Vec3& b) {
    const Vec3 d = glm::abs(a - b);
    return std::max({d.x, d.y, d.z});
}

// Pixels where a and b differ, b read turned as flip_h and flip_v say
int differing(const Image& a, const Image& b, bool flip_h, bool flip_v) {
    int count = 0;
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i)
            count += largest(a.at(i, j), b.at(flip_h ? W - 1 - i : i,
                                              flip_v ? H - 1 - j : j)) > 1e-3f;
    return count;
}

enum class Shows { upside_down, mirrored, turned_180 };

// The mutant's image is the reference's turned as `shows` says, and not the reference's
// own or any other turn of it. A turned ray visits the BVH in another order, so where
// two walls meet at the same t (an edge of the box) the other wall may win: a few pixels
void check_shows(const ModuleTable& mutant, Shows shows) {
    const Scene box = cornell_box();
    const Image want = render_with(engine_table(), box, W, H);
    const Image got = render_with(mutant, box, W, H);
    const bool h = shows != Shows::upside_down, v = shows != Shows::mirrored;
    CHECK(differing(got, want, h, v) <= W * H / 200);
    // The Cornell box has no symmetry that hides a turn: every other one differs
    for (int k = 0; k < 4; ++k) {
        const bool fh = k & 1, fv = k & 2;
        if (fh == h && fv == v) continue;
        CHECK(differing(got, want, fh, fv) >= W * H / 5);
    }
}

// The handouts' DTU pictures are 480 x 360: a fifth of that
constexpr int PW = 96, PH = 72;

Scene without_ground(Scene scene) {
    scene.planes.clear();
    scene.commit();
    return scene;
}

// The reference's camera ray through pixel (i, j) of a PW x PH image
Ray pixel_ray(const Scene& scene, int i, int j) {
    const PinholeCamera camera = make_camera(engine_table(), scene.view);
    return reference::camera_ray(camera, reference::image_plane_point(i, j, PW, PH));
}

bool same(const Image& a, const Image& b, int i, int j) {
    return largest(a.at(i, j), b.at(i, j)) <= 1e-3f;
}
bool black(const Image& a, int i, int j) {
    return largest(a.at(i, j), Vec3(0.0f)) <= 1e-3f;
}

// Handout 03's regions of the DTU depth picture: the ground the reference shows below
// the horizon, and the empty sky above it
struct DepthRegions {
    Image reference, no_ground;
    std::vector<bool> ground, sky;
    int ground_count = 0, sky_count = 0;
};

DepthRegions depth_regions() {
    const Scene dtu = dtu_scene();
    DepthRegions r;
    r.reference = render_with(engine_table(), dtu, PW, PH, ShadingMode::depth);
    r.no_ground =
        render_with(engine_table(), without_ground(dtu), PW, PH, ShadingMode::depth);
    r.ground.assign(PW * PH, false);
    r.sky.assign(PW * PH, false);
    for (int j = 0; j < PH; ++j)
        for (int i = 0; i < PW; ++i) {
            const bool up = pixel_ray(dtu, i, j).w.y > 0.0f;
            const bool ground = !up && !same(r.reference, r.no_ground, i, j);
            const bool sky = up && black(r.reference, i, j);
            r.ground[j * PW + i] = ground;
            r.sky[j * PW + i] = sky;
            r.ground_count += ground;
            r.sky_count += sky;
        }
    return r;
}

// Pixels of the region where the mutant's picture is `want`'s
int agreeing(const Image& got, const Image& want, const std::vector<bool>& region) {
    int count = 0;
    for (int j = 0; j < PH; ++j)
        for (int i = 0; i < PW; ++i)
            count += region[j * PW + i] && same(got, want, i, j);
    return count;
}
int lit(const Image& got, const std::vector<bool>& region) {
    int count = 0;
    for (int j = 0; j < PH; ++j)
        for (int i = 0; i < PW; ++i)
            count += region[j * PW + i] && !black(got, i, j);
    return count;
}

float mean(const Vec3& v) {
    return (v.x + v.y + v.z) / 3.0f;
}

}  // namespace

TEST_SUITE("handout claims") {
    TEST_CASE(
        "handout 01: v of the wrong sign turns the image upside down, not mirrored") {
        ModuleTable m = engine_table();
        m.image_plane_point = v_negated;
        m.render_tile = tile_with<v_negated>;
        check_shows(m, Shows::upside_down);
    }

    TEST_CASE("handout 01: u of the wrong sign mirrors the image") {
        ModuleTable m = engine_table();
        m.image_plane_point = u_negated;
        m.render_tile = tile_with<u_negated>;
        check_shows(m, Shows::mirrored);
    }

    TEST_CASE("handout 02 §1: x = u x n (with y = x x n) turns the image 180 degrees") {
        ModuleTable m = engine_table();
        m.camera_frame = x_from_u_cross_n;
        check_shows(m, Shows::turned_180);
    }

    TEST_CASE("handout 02 §1: y = n x x turns the image upside down") {
        ModuleTable m = engine_table();
        m.camera_frame = y_from_n_cross_x;
        check_shows(m, Shows::upside_down);
    }

    TEST_CASE("handout 02 §1: x = u x n and y = n x x mirror the image") {
        ModuleTable m = engine_table();
        m.camera_frame = both_swapped;
        check_shows(m, Shows::mirrored);
    }

    TEST_CASE("handout 01: u without the aspect factor squeezes the image sideways") {
        // Pixel i of the mutant sees what the reference's pixel at u * H / W sees: the
        // box's middle third spread over the whole width. At width 3 H the mutant's
        // column 3 k + 1 is the reference's column k + H
        const Scene box = cornell_box();
        ModuleTable m = engine_table();
        m.image_plane_point = u_without_aspect;
        m.render_tile = tile_with<u_without_aspect>;
        const Image want = render_with(engine_table(), box, 3 * H, H);
        const Image got = render_with(m, box, 3 * H, H);
        // u is rounded another way: a pixel on an edge may see the other side of it
        int differ = 0, differ_plain = 0;
        for (int j = 0; j < H; ++j)
            for (int k = 0; k < H; ++k) {
                differ += largest(got.at(3 * k + 1, j), want.at(k + H, j)) > 1e-3f;
                differ_plain +=
                    largest(got.at(3 * k + 1, j), want.at(3 * k + 1, j)) > 1e-3f;
            }
        CHECK(differ <= H * H / 50);
        CHECK(differ_plain >= H * H / 5);
    }
    TEST_CASE("handout 03: t of the wrong sign: the ground is missing") {
        const DepthRegions r = depth_regions();
        REQUIRE(r.ground_count >= PW * PH / 4);
        REQUIRE(r.sky_count >= PW * PH / 20);
        ModuleTable m = engine_table();
        m.intersect_plane = plane_t_sign;
        const Image got = render_with(m, dtu_scene(), PW, PH, ShadingMode::depth);
        INFO("ground as without it " << agreeing(got, r.no_ground, r.ground) << " of "
                                     << r.ground_count << "; sky lit " << lit(got, r.sky)
                                     << " of " << r.sky_count);
        CHECK(agreeing(got, r.no_ground, r.ground) >= r.ground_count * 99 / 100);
        // and nothing takes its place: the other mistake's white sky does not show
        CHECK(lit(got, r.sky) <= r.sky_count / 100);
    }

    TEST_CASE("handout 03: negative t accepted: a white band fills the sky") {
        const DepthRegions r = depth_regions();
        ModuleTable m = engine_table();
        m.intersect_plane = plane_negative_t;
        const Image got = render_with(m, dtu_scene(), PW, PH, ShadingMode::depth);
        INFO("ground as reference " << agreeing(got, r.reference, r.ground) << " of "
                                    << r.ground_count << "; sky lit " << lit(got, r.sky)
                                    << " of " << r.sky_count);
        CHECK(agreeing(got, r.reference, r.ground) >= r.ground_count * 99 / 100);
        CHECK(lit(got, r.sky) >= r.sky_count * 99 / 100);
    }

    TEST_CASE("handout 06: wi reversed: black but for crescents away from the light") {
        // The renderer drops a light behind the surface: with wi reversed only points
        // that face away from the light are lit, and the camera sees few of them
        const Scene dtu = dtu_scene();
        ModuleTable m = engine_table();
        m.sample_point_light = light_wi_reversed;
        const Image got = render_with(m, dtu, PW, PH, ShadingMode::lambert);
        const Image want = render_with(engine_table(), dtu, PW, PH, ShadingMode::lambert);
        const std::vector<bool> all(PW * PH, true);
        REQUIRE(lit(want, all) >= PW * PH / 2);
        INFO("lit " << lit(got, all) << " of " << PW * PH);
        CHECK(lit(got, all) <= PW * PH / 40);
        const Vec3 light = dtu.lights.at(0).p;
        int towards_light = 0;
        for (int j = 0; j < PH; ++j)
            for (int i = 0; i < PW; ++i) {
                if (black(got, i, j)) continue;
                TraceCounters counters;
                const std::optional<Hit> hit =
                    dtu.closest_hit(engine_table(), pixel_ray(dtu, i, j), counters);
                REQUIRE(hit);
                towards_light += glm::dot(hit->ns, light - hit->position) >= 0.0f;
            }
        CHECK(towards_light == 0);
    }

    TEST_CASE("handout 06: Li = I / r: the falloff is too gentle") {
        const Scene dtu = dtu_scene();
        ModuleTable m = engine_table();
        m.sample_point_light = light_without_square;
        const Image got = render_with(m, dtu, PW, PH, ShadingMode::lambert);
        const Image want = render_with(engine_table(), dtu, PW, PH, ShadingMode::lambert);
        // Two ground points: in the bottom row (near the light, front right) and farther
        // back at the left; r and cos from where the rays meet the ground. The reference
        // falls off as cos / r^2, the mutant as cos / r
        struct Point {
            int i, j;
            float r, cos;
        };
        Point p[2] = {{PW * 3 / 4, PH - 1, 0, 0}, {PW / 8, 0, 0, 0}};
        for (int j = 0; j < PH && !p[1].j; ++j)
            if (pixel_ray(dtu, p[1].i, j).w.y < -0.1f) p[1].j = j;
        const PointLight& light = dtu.lights.at(0);
        for (Point& q : p) {
            TraceCounters counters;
            const std::optional<Hit> hit =
                dtu.closest_hit(engine_table(), pixel_ray(dtu, q.i, q.j), counters);
            REQUIRE(hit);
            REQUIRE(std::abs(hit->position.y) < 1e-4f);  // the ground, nothing on it
            q.r = glm::length(light.p - hit->position);
            q.cos = light.p.y / q.r;
        }
        const float ratio_cos = p[0].cos / p[1].cos, ratio_r = p[1].r / p[0].r;
        const float falloff_got =
            mean(got.at(p[0].i, p[0].j)) / mean(got.at(p[1].i, p[1].j));
        const float falloff_want =
            mean(want.at(p[0].i, p[0].j)) / mean(want.at(p[1].i, p[1].j));
        INFO("r " << p[0].r << " " << p[1].r << " falloff got " << falloff_got << " want "
                  << falloff_want << " 1/r " << ratio_r * ratio_cos << " 1/r^2 "
                  << ratio_r * ratio_r * ratio_cos);
        REQUIRE(ratio_r >= 1.5f);
        CHECK(falloff_want ==
              doctest::Approx(ratio_r * ratio_r * ratio_cos).epsilon(0.01));
        CHECK(falloff_got == doctest::Approx(ratio_r * ratio_cos).epsilon(0.01));
    }

    TEST_CASE("handout 07: without the 1/pi the picture is pi times too bright") {
        const Scene box = cornell_box();
        ModuleTable m = engine_table();
        m.lambert = lambert_without_pi;
        const Image got = render_with(m, box, H, H, ShadingMode::lambert);
        const Image want = render_with(engine_table(), box, H, H, ShadingMode::lambert);
        double sum_got = 0.0, sum_want = 0.0;
        int count = 0;
        for (int j = 0; j < H; ++j)
            for (int i = 0; i < H; ++i)
                if (mean(want.at(i, j)) > 0.0f) {
                    sum_got += mean(got.at(i, j));
                    sum_want += mean(want.at(i, j));
                    ++count;
                }
        INFO("lit " << count << " ratio " << sum_got / sum_want);
        REQUIRE(count >= H * H / 2);
        CHECK(sum_got / sum_want == doctest::Approx(kPi).epsilon(0.01));
    }
}
