// The viewer's logic without a window: view files, camera controls, the comparison and
// the viewer's flags.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "camera_control.h"
#include "compare.h"
#include "raylab/error.h"
#include "raylab/scenes.h"
#include "view_file.h"
#include "viewer_options.h"

using namespace raylab;
using namespace raylab::viewer;

namespace {

// The message parse_view_file throws for text, or "" when it accepts it
std::string view_error(const std::string& text) {
    try {
        parse_view_file(text, "v.txt");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

const std::string kGoodView = "eye 0 0 3\nlookat 0 0 0\nup 0 1 0\nfov 53.13\n";

// Positions agree to a few float ulps of unit-sized values
constexpr float kPositionTolerance = 1e-5f;

}  // namespace

TEST_SUITE("viewer") {
    TEST_CASE("a saved view file reads back exactly, lights included") {
        const View view{Vec3(0.1f, -0.2f, 2.9f), Vec3(0.01f, 0.02f, -0.3f),
                        Vec3(0, 1, 0.1f), 47.3f};
        const std::vector<PointLight> lights = {
            {Vec3(0, 0.5f, 0.7f), Vec3(14.0f / 12.566f)},
            {Vec3(-1, 2, 3), Vec3(0.5f, 0.25f, 0.125f)}};
        const ViewFile file = parse_view_file(format_view_file(view, lights), "v.txt");
        // %.9g is enough digits for every float to read back to the same bits
        CHECK(file.view.eye == view.eye);
        CHECK(file.view.lookat == view.lookat);
        CHECK(file.view.up == view.up);
        CHECK(file.view.fov == view.fov);
        REQUIRE(file.lights.size() == 2);
        CHECK(file.lights[1].p == lights[1].p);
        CHECK(file.lights[1].I == lights[1].I);
    }

    TEST_CASE("a view file carries the area-light size and samples when they are set") {
        // Point lights (size 0) write no area-light lines; a size of 0.4 with 16 samples
        // reads back, and the values pass the same rules as --light-size/--light-samples
        const View view{Vec3(0, 0, 3), Vec3(0.0f), Vec3(0, 1, 0), 50.0f};
        RenderSettings settings;
        CHECK(
            !parse_view_file(format_view_file(view, {}, &settings), "v.txt").light_size);
        settings.light_size = 0.4f;
        settings.light_samples = 16;
        const ViewFile file =
            parse_view_file(format_view_file(view, {}, &settings), "v.txt");
        REQUIRE(file.light_size);
        REQUIRE(file.light_samples);
        CHECK(*file.light_size == 0.4f);
        CHECK(*file.light_samples == 16);
        CHECK(view_error(kGoodView + "light_samples 0\n") ==
              "v.txt:5: light_samples: 0 light samples is outside 1..1024");
        // Beyond int: the fuzzer's case, once an undefined float-to-int cast
        CHECK(view_error(kGoodView + "light_samples 2332331833\n") ==
              "v.txt:5: light_samples: 2.33233178e+09 light samples is outside 1..1024");
        CHECK(view_error(kGoodView + "light_samples -1e30\n") ==
              "v.txt:5: light_samples: -1.00000002e+30 light samples is outside 1..1024");
        CHECK(
            view_error(kGoodView + "light_size -1\n") ==
            "v.txt:5: light_size: light size -1 is outside [0, 1000] (0: point lights)");
    }

    TEST_CASE("a malformed view file is rejected with a message naming the line") {
        CHECK(view_error(kGoodView) == "");
        CHECK(view_error("# comment\neye 0 0\nlookat 0 0 0\nup 0 1 0\nfov 50\n") ==
              "v.txt:2: 'eye' needs 3 numbers, found 2");
        CHECK(view_error("eye 0 0 3\nlookat 0 x 0\n") ==
              "v.txt:2: y: 'x' is not a finite number");
        CHECK(view_error("eye 0 0 3\nlookat 0 inf 0\n") ==
              "v.txt:2: y: 'inf' is not a finite number");
        CHECK(view_error(kGoodView + "zoom 2\n") ==
              "v.txt:5: unknown keyword 'zoom' (eye, lookat, up, fov, light, light_size, "
              "light_samples)");
        CHECK(view_error(kGoodView + "fov 40\n") == "v.txt:5: 'fov' appears twice");
        CHECK(view_error(kGoodView + "light 0 1 0  1 -1 1\n") ==
              "v.txt:5: light: intensity (1, -1, 1) must not be negative");
        CHECK(view_error(kGoodView + "light 0 1 0  1 1\n") ==
              "v.txt:5: 'light' needs 6 numbers, found 5");
        CHECK(view_error("eye 0 0 3\nlookat 0 0 0\nup 0 1 0\n") ==
              "v.txt: missing the 'fov' line");
        // A camera the renderer cannot use: named with the file
        const std::string same =
            view_error("eye 1 1 1\nlookat 1 1 1\nup 0 1 0\nfov 50\n");
        CHECK(same.rfind("v.txt: ", 0) == 0);
        CHECK(view_error("eye 0 0 3\nlookat 0 0 0\nup 0 1 0\nfov 180\n")
                  .rfind("v.txt: ", 0) == 0);
    }

    TEST_CASE("a view file that does not exist is named in the error") {
        CHECK_THROWS_WITH_AS(
            load_view_file("/no/such/view.txt"),
            "/no/such/view.txt: cannot open file (No such file or directory)", Error);
    }

    TEST_CASE(
        "walking moves eye and look-at together along the horizontal view direction") {
        // Looking down at 45 degrees along -z: walking 1 moves both by (0, 0, -1)
        const View view{Vec3(0, 1, 1), Vec3(0, 0, 0), Vec3(0, 1, 0), 50.0f};
        const View v = walk(view, 1.0f);
        CHECK(glm::length(v.eye - Vec3(0, 1, 0)) < kPositionTolerance);
        CHECK(glm::length(v.lookat - Vec3(0, 0, -1)) < kPositionTolerance);
        const View back = walk(v, -1.0f);
        CHECK(glm::length(back.eye - view.eye) < kPositionTolerance);
    }

    TEST_CASE("turning left rotates the look-at point about the eye, counter-clockwise") {
        // Eye at 0 looking along -z; +90 degrees about +y turns the view to -x (left)
        const View view{Vec3(0), Vec3(0, 0, -2), Vec3(0, 1, 0), 50.0f};
        const View v = turn(view, radians(90.0f));
        CHECK(v.eye == view.eye);
        CHECK(glm::length(v.lookat - Vec3(-2, 0, 0)) < kPositionTolerance);
    }

    TEST_CASE("orbiting keeps the distance to the look-at point and never reaches up") {
        const View view{Vec3(0, 0, 3), Vec3(0), Vec3(0, 1, 0), 50.0f};
        const View yawed = orbit(view, radians(90.0f), 0.0f);
        CHECK(glm::length(yawed.eye - Vec3(3, 0, 0)) < kPositionTolerance);
        const View raised = orbit(view, 0.0f, radians(30.0f));
        // Positive pitch: the eye rises on its circle of radius 3
        CHECK(raised.eye.y ==
              doctest::Approx(3.0f * std::sin(radians(30.0f))).epsilon(1e-5));
        CHECK(glm::length(raised.eye) == doctest::Approx(3.0f).epsilon(1e-5));
        // Far past the pole: clamped 2 degrees short of up, the camera stays valid
        const View top = orbit(view, 0.0f, radians(170.0f));
        const float polar = std::acos(glm::dot(glm::normalize(top.eye), Vec3(0, 1, 0)));
        CHECK(degrees(polar) == doctest::Approx(2.0f).epsilon(1e-3));
        CHECK_NOTHROW(validate(top));
    }

    TEST_CASE("the wheel moves the eye towards the look-at point, never onto it") {
        const View view{Vec3(0, 0, 3), Vec3(0), Vec3(0, 1, 0), 50.0f};
        CHECK(dolly(view, 0.5f, 2.0f).eye.z == doctest::Approx(1.5f));
        // A tiny factor stops at 1e-3 of the scene size
        CHECK(dolly(view, 1e-9f, 2.0f).eye.z == doctest::Approx(2e-3f));
    }

    TEST_CASE("light keys move in the camera's walking frame") {
        const View view{Vec3(0, 0, 3), Vec3(0), Vec3(0, 1, 0), 50.0f};
        // right = +x, up = +y, forward = -z for this camera
        const Vec3 p = move_in_view(view, Vec3(0), 1.0f, 2.0f, 3.0f);
        CHECK(glm::length(p - Vec3(1, 2, -3)) < kPositionTolerance);
    }

    TEST_CASE("the scene size is the diagonal of the Cornell box") {
        const Scene scene = cornell_box();
        // The box spans [-1, 1]^3: diagonal 2 sqrt(3)
        CHECK(scene_size(scene, scene.view) == doctest::Approx(2.0f * std::sqrt(3.0f)));
    }

    TEST_CASE("comparing an image with itself finds no difference") {
        Image a(4, 3, Vec3(0.25f, 0.5f, 0.75f));
        const Difference d = compare_images(a, a);
        CHECK(d.rmse == 0.0);
        CHECK(d.max_error == 0.0);
        CHECK(d.differing == 0);
        CHECK(d.heat.size() == 4 * 3 * 3);
        CHECK(d.heat[0] == 0);  // black: no error
    }

    TEST_CASE("one wrong channel gives its error as max and sqrt(e^2 / 3n) as RMSE") {
        Image a(2, 1, Vec3(0.5f)), b(2, 1, Vec3(0.5f));
        a.at(1, 0).y = 0.8f;  // error 0.3 in one of 2 pixels x 3 channels
        const Difference d = compare_images(a, b);
        CHECK(d.max_error == doctest::Approx(0.3).epsilon(1e-6));
        CHECK(d.rmse == doctest::Approx(std::sqrt(0.09 / 6.0)).epsilon(1e-6));
        CHECK(d.differing == 1);
        // The worst pixel is white, the right one black
        CHECK(d.heat[3] == 255);
        CHECK(d.heat[5] == 255);
        CHECK(d.heat[0] == 0);
    }

    TEST_CASE("NaN pixels are counted and shown in magenta, and sizes must match") {
        Image a(2, 1, Vec3(0.5f)), b(2, 1, Vec3(0.5f));
        a.at(0, 0).x = std::nanf("");
        const Difference d = compare_images(a, b);
        CHECK(d.non_finite == 1);
        CHECK(d.heat[0] == 255);
        CHECK(d.heat[1] == 0);
        CHECK(d.heat[2] == 255);
        CHECK_THROWS_AS(compare_images(a, Image(3, 1)), Error);
    }

    TEST_CASE("the viewer's own flags are parsed, and bad ones are named") {
        const ViewerOptions o =
            parse_viewer_options({"--frames", "5", "--screenshot", "s.png", "--window",
                                  "800x600", "--compare"});
        CHECK(o.frames == 5);
        CHECK(o.screenshot == "s.png");
        CHECK(o.window_width == 800);
        CHECK(o.window_height == 600);
        CHECK(o.compare);
        // A screenshot alone implies a few frames
        CHECK(parse_viewer_options({"--screenshot", "s.png"}).frames == 3);
        CHECK_THROWS_WITH_AS(parse_viewer_options({"--frames"}),
                             "--frames needs a value (see --help)", Error);
        CHECK_THROWS_WITH_AS(parse_viewer_options({"--frames", "-1"}),
                             "--frames: '-1' is not a whole number in 1..1000000", Error);
        CHECK_THROWS_WITH_AS(parse_viewer_options({"--compare", "yes"}),
                             "--compare takes no value, got 'yes'", Error);
        CHECK_THROWS_WITH_AS(parse_viewer_options({"--window", "big"}),
                             "--window: 'big' is not WxH", Error);
        CHECK_THROWS_WITH_AS(parse_viewer_options({"--zoom", "2"}),
                             "unknown option '--zoom' (see --help)", Error);
    }
}
