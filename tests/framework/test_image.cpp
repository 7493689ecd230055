// Images: tone mapping, PFM round trip, file errors.
#include <cstdio>

#include <doctest/doctest.h>

#include "raylab/error.h"
#include "raylab/image.h"
#include "test_helpers.h"

using namespace raylab;

TEST_SUITE("image") {
    TEST_CASE("tone map sends 0 to 0, 1 and above to 255, NaN to 0") {
        CHECK(tone_map(0.0f, 0.0f) == 0);
        CHECK(tone_map(1.0f, 0.0f) == 255);
        CHECK(tone_map(7.0f, 0.0f) == 255);
        CHECK(tone_map(-1.0f, 0.0f) == 0);
        CHECK(tone_map(std::nanf(""), 0.0f) == 0);
    }

    TEST_CASE("tone map applies the sRGB curve and the exposure in stops") {
        // sRGB(0.5) = 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354 -> 187.5 -> 188
        CHECK(tone_map(0.5f, 0.0f) == 188);
        // One stop up doubles the radiance: 0.25 at +1 EV looks like 0.5
        CHECK(tone_map(0.25f, 1.0f) == 188);
        // The linear toe: 0.002 -> 12.92 * 0.002 = 0.02584 -> 6.6 -> 7
        CHECK(tone_map(0.002f, 0.0f) == 7);
    }

    TEST_CASE("a PFM file round-trips every float exactly, rows in place") {
        Image image(3, 2);
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 3; ++i)
                image.at(i, j) = Vec3(i + 0.125f, j * 1e-7f, 1e30f);
        const std::string path = "raylab-test-roundtrip.pfm";
        write_pfm(path, image);
        const Image back = read_pfm(path);
        std::remove(path.c_str());
        REQUIRE(back.width == 3);
        REQUIRE(back.height == 2);
        for (size_t k = 0; k < image.pixels.size(); ++k)
            CHECK(back.pixels[k] == image.pixels[k]);
    }

    TEST_CASE("writing to an unknown extension or an impossible path names the problem") {
        const Image image(2, 2);
        CHECK_THROWS_WITH_AS(write_image("out.bmp", image),
                             doctest::Contains("unknown image type"), Error);
        CHECK_THROWS_WITH_AS(write_image("/nonexistent-dir/x.png", image),
                             doctest::Contains("cannot write PNG"), Error);
        CHECK_THROWS_AS(read_pfm("/nonexistent-dir/x.pfm"), Error);
    }

    TEST_CASE("non-finite pixels are counted") {
        Image image(2, 2);
        CHECK(count_non_finite(image) == 0);
        image.at(1, 1) = Vec3(std::nanf(""), 0.0f, 0.0f);
        image.at(0, 1) = Vec3(0.0f, kInfinity, 0.0f);
        CHECK(count_non_finite(image) == 2);
    }
}
