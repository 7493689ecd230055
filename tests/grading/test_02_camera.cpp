// Graders of module 02_camera (docs/handouts/02_camera.md).
//
// Basis: n = normalize(lookat - eye), x = normalize(n x up), y = x x n. Camera constant:
// d = 1 / (2 tan(fov / 2)). Eye ray: o = eye, w = normalize(u x + v y + d n).
#include "grading.h"

using namespace raylab;
using namespace raylab::grading;

namespace {

std::string diff_frame(const CameraFrame& got, const CameraFrame& want) {
    std::string why;
    for (const auto& [name, g, w] :
         {std::tuple<const char*, Vec3, Vec3>{"x", got.x, want.x},
          {"y", got.y, want.y},
          {"n", got.n, want.n}}) {
        const std::string d = diff_vec(name, g, w, tol::kDirection);
        if (!d.empty()) why += (why.empty() ? "" : "; ") + d;
    }
    return why;
}

// Where a direction w meets the image plane, in image-plane coordinates: (w . x, w . y)
// scaled so that w . n = d. A correct eye ray through (u, v) meets it at (u, v).
Vec2 image_plane_hit(const Vec3& w, const PinholeCamera& c) {
    const float along = glm::dot(w, c.frame.n);
    return Vec2(glm::dot(w, c.frame.x), glm::dot(w, c.frame.y)) * (c.d / along);
}

std::string diff_direction(const Ray& got, const Vec3& want) {
    return diff_vec("w", got.w, want, tol::kDirection);
}

// A camera whose basis is not the world's axes: looking along -x, x = -z, y = +y
const PinholeCamera kSideCamera{
    Vec3(1.0f, 2.0f, 3.0f),
    {Vec3(0.0f, 0.0f, -1.0f), Vec3(0.0f, 1.0f, 0.0f), Vec3(-1.0f, 0.0f, 0.0f)},
    2.0f};

// A random camera: orthonormal basis, eye in [-10, 10]^3, d in [0.3, 3]
PinholeCamera random_camera(Rng& rng) {
    const Vec3 n = rng.direction();
    const Vec3 x = glm::normalize(glm::cross(n, rng.direction_near(n, -0.9f, 0.9f)));
    const Vec3 eye = rng.in_box(-10.0f, 10.0f);
    return PinholeCamera{eye, {x, glm::cross(x, n), n}, rng.uniform(0.3f, 3.0f)};
}

// A random image-plane point of an image up to twice as wide as high
Vec2 random_uv(Rng& rng) {
    const float u = rng.uniform(-1.0f, 1.0f);
    return Vec2(u, rng.uniform(-0.5f, 0.5f));
}

// ---- Companions of the cases a constant passes: fresh random input, formulas in double

std::string work_camera_frame() {
    for (int seed = 0; seed < 8; ++seed) {
        Rng rng(9200 + seed);
        const Vec3 eye = rng.in_box(-10.0f, 10.0f);
        const Vec3 lookat = eye + rng.uniform(0.5f, 10.0f) * rng.direction();
        const Vec3 up = rng.uniform(0.5f, 2.0f) *
                        rng.direction_near(glm::normalize(lookat - eye), -0.9f, 0.9f);
        const glm::dvec3 n = glm::normalize(glm::dvec3(lookat) - glm::dvec3(eye));
        const glm::dvec3 x = glm::normalize(glm::cross(n, glm::dvec3(up)));
        const CameraFrame want{Vec3(x), Vec3(glm::cross(x, n)), Vec3(n)};
        const std::string why =
            diff_frame(under_test::camera_frame(eye, lookat, up), want);
        if (!why.empty())
            return "camera_frame(eye " + show(eye) + ", lookat " + show(lookat) +
                   ", up " + show(up) + "): " + why;
    }
    return "";
}

std::string work_camera_constant() {
    for (int seed = 0; seed < 8; ++seed) {
        Rng rng(9300 + seed);
        const float fov = rng.uniform(0.2f, 2.8f);
        const double want = 0.5 / std::tan(0.5 * double(fov));
        const float d = under_test::camera_constant(fov);
        if (!close(d, want, tol::kCameraConstant))
            return "camera_constant(" + show(fov) + "): expected d = " + show(want) +
                   ", got " + show(d);
    }
    return "";
}

std::string work_camera_ray() {
    for (int seed = 0; seed < 8; ++seed) {
        Rng rng(9400 + seed);
        const PinholeCamera c = random_camera(rng);
        const Vec2 uv = random_uv(rng);
        const glm::dvec3 w = glm::normalize(double(uv.x) * glm::dvec3(c.frame.x) +
                                            double(uv.y) * glm::dvec3(c.frame.y) +
                                            double(c.d) * glm::dvec3(c.frame.n));
        const Ray got = under_test::camera_ray(c, uv);
        const std::string why = diff_vec("o", got.o, c.eye, 0.0) +
                                diff_vec(" w", got.w, Vec3(w), tol::kDirection);
        if (!why.empty())
            return show(c) + "; camera_ray through " + show(uv) + ": " + why;
    }
    return "";
}

bool frame_work() {
    return needs_work("camera_frame of random cameras", work_camera_frame());
}
bool constant_work() {
    return needs_work("camera_constant of random angles", work_camera_constant());
}
bool ray_work() {
    return needs_work("camera_ray of random cameras", work_camera_ray());
}

}  // namespace

TEST_SUITE("02_camera") {
    TEST_CASE(
        "a camera at (0, 0, 3) looking at the origin has x = +x, y = +y and n = -z") {
        frame_work();
        // n = (0, 0, -3) / 3; x = n x up = (0, 0, -1) x (0, 1, 0) = (1, 0, 0); y = x x n
        INFO("camera_frame(eye (0, 0, 3), lookat (0, 0, 0), up (0, 1, 0))");
        const CameraFrame got =
            under_test::camera_frame(Vec3(0, 0, 3), Vec3(0.0f), Vec3(0, 1, 0));
        RAYLAB_CHECK_SAME(
            diff_frame(got, {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, -1)}));
    }

    TEST_CASE("n is the unit vector from the eye towards the look-at point") {
        frame_work();
        // lookat - eye = (3, 4, 0), of length 5
        INFO("camera_frame(eye (1, 2, 3), lookat (4, 6, 3), up (0, 0, 1))");
        const CameraFrame got =
            under_test::camera_frame(Vec3(1, 2, 3), Vec3(4, 6, 3), Vec3(0, 0, 1));
        RAYLAB_CHECK_SAME(diff_vec("n", got.n, Vec3(0.6f, 0.8f, 0.0f), tol::kDirection));
    }

    TEST_CASE("x is normalized when up is not perpendicular to the viewing direction") {
        frame_work();
        // Looking down at 45 degrees: n = (0, -1, -1) / sqrt 2, n x up = (1, 0, 0) / sqrt
        // 2, so x = (1, 0, 0) only after normalizing
        INFO("camera_frame(eye (0, 0, 0), lookat (0, -1, -1), up (0, 1, 0))");
        const CameraFrame got =
            under_test::camera_frame(Vec3(0.0f), Vec3(0, -1, -1), Vec3(0, 1, 0));
        RAYLAB_CHECK_SAME(diff_vec("x", got.x, Vec3(1, 0, 0), tol::kDirection));
    }

    TEST_CASE("y is perpendicular to n: a tilted camera's y is not the up hint") {
        frame_work();
        // The same camera: y = x x n = (1, 0, 0) x (0, -1, -1) / sqrt 2 = (0, 1, -1) /
        // sqrt 2
        INFO("camera_frame(eye (0, 0, 0), lookat (0, -1, -1), up (0, 1, 0))");
        const CameraFrame got =
            under_test::camera_frame(Vec3(0.0f), Vec3(0, -1, -1), Vec3(0, 1, 0));
        const float h = 0.70710678f;
        RAYLAB_CHECK_SAME(diff_vec("y", got.y, Vec3(0, h, -h), tol::kDirection));
    }

    TEST_CASE(
        "random cameras have an orthonormal basis with x right and y up on screen") {
        // Whatever the eye, look-at point and up hint: |x| = |y| = |n| = 1, all three
        // perpendicular, x x y = -n (x right, y up, n into the screen), x perpendicular
        // to up and y on up's side
        for (int seed = 0; seed < 200; ++seed) {
            Rng rng(seed);
            const Vec3 eye = rng.in_box(-10.0f, 10.0f);
            const float distance = rng.uniform(0.5f, 10.0f);
            const Vec3 lookat = eye + distance * rng.direction();
            const Vec3 n = glm::normalize(lookat - eye);
            const float length = rng.uniform(0.5f, 2.0f);
            const Vec3 up = length * rng.direction_near(n, -0.9f, 0.9f);
            INFO("seed " << seed << ": camera_frame(eye " << show(eye) << ", lookat "
                         << show(lookat) << ", up " << show(up) << ")");
            const CameraFrame f = under_test::camera_frame(eye, lookat, up);
            INFO("got " << show(f));
            const double e = tol::kDirection;
            const bool unit = close(glm::length(f.x), 1.0, e) &&
                              close(glm::length(f.y), 1.0, e) &&
                              close(glm::length(f.n), 1.0, e);
            const bool orthogonal = std::abs(glm::dot(f.x, f.y)) <= e &&
                                    std::abs(glm::dot(f.x, f.n)) <= e &&
                                    std::abs(glm::dot(f.y, f.n)) <= e;
            const bool handed = close_abs(glm::cross(f.x, f.y), -f.n, 2 * e);
            const bool level = std::abs(glm::dot(f.x, glm::normalize(up))) <= e &&
                               glm::dot(f.y, up) > 0.0f;
            RAYLAB_CHECK(unit, "x, y and n must have length 1");
            RAYLAB_CHECK(orthogonal, "x, y and n must be perpendicular to each other");
            RAYLAB_CHECK(handed, "x x y must be -n (x right, y up, n forward)");
            RAYLAB_CHECK(level, "x must be perpendicular to up, and y on the side of up");
            if (!(unit && orthogonal && handed && level)) break;
        }
    }

    TEST_CASE("random cameras agree with the reference basis") {
        frame_work();
        for (int seed = 0; seed < 100; ++seed) {
            Rng rng(1000 + seed);
            const Vec3 eye = rng.in_box(-10.0f, 10.0f);
            const float distance = rng.uniform(0.5f, 10.0f);
            const Vec3 lookat = eye + distance * rng.direction();
            const Vec3 up = rng.direction_near(glm::normalize(lookat - eye), -0.9f, 0.9f);
            INFO("seed " << seed << ": camera_frame(eye " << show(eye) << ", lookat "
                         << show(lookat) << ", up " << show(up) << ")");
            const CameraFrame want = expected<CameraFrame>(
                "02_camera/random frames/" + std::to_string(seed),
                inputs(eye, lookat, up),
                [&] { return reference_modules().camera_frame(eye, lookat, up); });
            if (!RAYLAB_CHECK_SAME(
                    diff_frame(under_test::camera_frame(eye, lookat, up), want)))
                break;
        }
    }

    TEST_CASE("a 90-degree field of view gives the camera constant d = 1/2") {
        constant_work();
        // tan(45 degrees) = 1, so d = 1 / (2 * 1)
        INFO("camera_constant(pi / 2)");
        const float d = under_test::camera_constant(0.5f * kPi);
        RAYLAB_CHECK(close(d, 0.5, tol::kCameraConstant),
                     "expected d = 0.5, got " << show(d));
    }

    TEST_CASE("the lab's 53.13-degree field of view gives d = 1") {
        constant_work();
        // fov = 2 atan(1/2) = 0.9272952 rad: d = 1 / (2 tan(atan(1/2))) = 1
        INFO("camera_constant(0.9272952) (radians)");
        const float d = under_test::camera_constant(0.9272952f);
        RAYLAB_CHECK(close(d, 1.0, tol::kCameraConstant),
                     "expected d = 1, got " << show(d));
    }

    TEST_CASE(
        "the camera constant satisfies fov = 2 atan(1 / (2 d)) from 1 to 170 degrees") {
        // The fov argument is in radians and is the full vertical angle
        for (int degrees = 1; degrees <= 170; degrees += 13) {
            const float fov = radians(float(degrees));
            const double want = 0.5 / std::tan(0.5 * double(fov));
            INFO("camera_constant(" << show(fov) << ") (" << degrees << " degrees)");
            const float d = under_test::camera_constant(fov);
            if (!RAYLAB_CHECK(close(d, want, tol::kCameraConstant),
                              "expected d = " << show(want) << ", got " << show(d)))
                break;
        }
    }

    TEST_CASE("an eye ray starts at the eye") {
        ray_work();
        INFO(show(kSideCamera) << "; camera_ray through (u, v) = (0.3, -0.2)");
        const Ray r = under_test::camera_ray(kSideCamera, Vec2(0.3f, -0.2f));
        RAYLAB_CHECK_SAME(diff_vec("o", r.o, kSideCamera.eye, 0.0));
    }

    TEST_CASE("an eye ray is valid from t = 0 to infinity") {
        ray_work();
        INFO(show(kSideCamera) << "; camera_ray through (u, v) = (0.3, -0.2)");
        const Ray r = under_test::camera_ray(kSideCamera, Vec2(0.3f, -0.2f));
        INFO("got " << show(r));
        // The contract (handout 02): eye rays start exactly at the eye, tmin = 0. Nothing
        // lies at the eye to hit again, and any positive tmin clips the surfaces nearer
        // than it
        RAYLAB_CHECK(r.tmin == 0.0f, "expected tmin = 0, got tmin = " << show(r.tmin));
        RAYLAB_CHECK(r.tmax >= 1e30f,
                     "expected tmax = infinity (kInfinity), got tmax = " << show(r.tmax));
    }

    TEST_CASE("the eye ray through the image-plane centre points along n") {
        ray_work();
        INFO(show(kSideCamera) << "; camera_ray through (u, v) = (0, 0)");
        RAYLAB_CHECK_SAME(diff_direction(under_test::camera_ray(kSideCamera, Vec2(0.0f)),
                                         kSideCamera.frame.n));
    }

    TEST_CASE("an eye ray has a unit direction") {
        ray_work();
        // Through the top-right corner of a 4:3 image: |u x + v y + d n| = sqrt(0.444 +
        // 0.25 + 4) = 2.17, not 1
        INFO(show(kSideCamera) << "; camera_ray through (u, v) = (0.6667, 0.5)");
        const Ray r = under_test::camera_ray(kSideCamera, Vec2(0.6666667f, 0.5f));
        RAYLAB_CHECK(close(glm::length(r.w), 1.0, tol::kDirection),
                     "expected |w| = 1, got |w| = " << show(glm::length(r.w))
                                                    << " for w = " << show(r.w));
    }

    TEST_CASE("an eye ray through (u, v) points along u x + v y + d n") {
        ray_work();
        // u x + v y + d n = 0.5 (0, 0, -1) + 0.25 (0, 1, 0) + 2 (-1, 0, 0) = (-2, 0.25,
        // -0.5), of length sqrt(4.3125) = 2.0766560: w = (-0.9630868, 0.1203859,
        // -0.2407717)
        INFO(show(kSideCamera) << "; camera_ray through (u, v) = (0.5, 0.25)");
        RAYLAB_CHECK_SAME(
            diff_direction(under_test::camera_ray(kSideCamera, Vec2(0.5f, 0.25f)),
                           Vec3(-0.9630868f, 0.1203859f, -0.2407717f)));
    }

    TEST_CASE(
        "eye rays through the top and bottom edges span the vertical field of view") {
        // d = 1 / (2 tan 30 degrees) = 0.8660254: the rays through v = +-1/2 are 60
        // degrees apart, the top one above the bottom one
        PinholeCamera c = kSideCamera;
        c.d = 0.8660254f;
        INFO(show(c) << "; camera_ray through (0, 0.5) and (0, -0.5)");
        const Ray top = under_test::camera_ray(c, Vec2(0.0f, 0.5f));
        const Ray bottom = under_test::camera_ray(c, Vec2(0.0f, -0.5f));
        INFO("top w = " << show(top.w) << ", bottom w = " << show(bottom.w));
        const double cosine = glm::dot(glm::normalize(top.w), glm::normalize(bottom.w));
        const double angle = degrees(float(std::acos(std::clamp(cosine, -1.0, 1.0))));
        RAYLAB_CHECK(std::abs(angle - 60.0) < tol::kAngleDegrees,
                     "expected 60 degrees between them, got " << show(angle));
        RAYLAB_CHECK(glm::dot(top.w, c.frame.y) > glm::dot(bottom.w, c.frame.y),
                     "the ray through v = +1/2 must lean towards y (up)");
    }

    TEST_CASE(
        "eye rays through the left and right edges span the horizontal field of view") {
        // A 16:9 image with d = 1: u = +-16/18, and 2 atan(16 / 18) = 83.267 degrees
        PinholeCamera c = kSideCamera;
        c.d = 1.0f;
        const float u = 16.0f / 18.0f;
        INFO(show(c) << "; camera_ray through (-" << show(u) << ", 0) and (" << show(u)
                     << ", 0)");
        const Ray left = under_test::camera_ray(c, Vec2(-u, 0.0f));
        const Ray right = under_test::camera_ray(c, Vec2(u, 0.0f));
        INFO("left w = " << show(left.w) << ", right w = " << show(right.w));
        const double cosine = glm::dot(glm::normalize(left.w), glm::normalize(right.w));
        const double angle = degrees(float(std::acos(std::clamp(cosine, -1.0, 1.0))));
        RAYLAB_CHECK(std::abs(angle - 83.267488) < tol::kAngleDegrees,
                     "expected 83.2675 degrees between them, got " << show(angle));
        RAYLAB_CHECK(glm::dot(right.w, c.frame.x) > glm::dot(left.w, c.frame.x),
                     "the ray through u > 0 must lean towards x (right)");
    }

    TEST_CASE("random eye rays meet the image plane at their (u, v)") {
        // Follow w back to the plane w . n = d: it must cross it at (u, v) itself
        for (int seed = 0; seed < 200; ++seed) {
            Rng rng(2000 + seed);
            const PinholeCamera c = random_camera(rng);
            const Vec2 uv = random_uv(rng);
            INFO("seed " << seed << ": " << show(c) << "; camera_ray through "
                         << show(uv));
            const Ray r = under_test::camera_ray(c, uv);
            INFO("got " << show(r));
            const Vec2 at = image_plane_hit(r.w, c);
            const bool ok = glm::dot(r.w, c.frame.n) > 0.0f &&
                            std::abs(at.x - uv.x) <= tol::kImagePlaneFromRay &&
                            std::abs(at.y - uv.y) <= tol::kImagePlaneFromRay;
            if (!RAYLAB_CHECK(ok, "w crosses the image plane at "
                                      << show(at) << ", not at " << show(uv)))
                break;
        }
    }

    TEST_CASE("random eye rays agree with the reference") {
        ray_work();
        for (int seed = 0; seed < 100; ++seed) {
            Rng rng(3000 + seed);
            const PinholeCamera c = random_camera(rng);
            const Vec2 uv = random_uv(rng);
            INFO("seed " << seed << ": " << show(c) << "; camera_ray through "
                         << show(uv));
            const Ray want =
                expected<Ray>("02_camera/random rays/" + std::to_string(seed),
                              inputs(c.eye, c.frame.x, c.frame.y, c.frame.n, c.d, uv),
                              [&] { return reference_modules().camera_ray(c, uv); });
            const Ray got = under_test::camera_ray(c, uv);
            const std::string why = diff_vec("o", got.o, want.o, 0.0) +
                                    diff_vec(" w", got.w, want.w, tol::kDirection);
            if (!RAYLAB_CHECK_SAME(why)) break;
        }
    }
}
