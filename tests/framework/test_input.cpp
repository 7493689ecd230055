// The validated input path: strict numbers, lines, large polygons, progress and cancel.
#include <atomic>
#include <cmath>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "raylab/error.h"
#include "raylab/input_file.h"
#include "raylab/scenes.h"

using namespace raylab;

namespace {

std::string no_mtl(const std::string& name) {
    throw Error(name + ": no MTL files here");
}

// A regular polygon with n corners in the z = 0 plane, as one face
std::string polygon(int n) {
    std::string text;
    for (int k = 0; k < n; ++k) {
        const double a = 2.0 * 3.14159265358979 * k / n;
        text += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) +
                " 0\n";
    }
    text += "f";
    for (int k = 1; k <= n; ++k)
        text += " " + std::to_string(k);
    return text + "\n";
}

}  // namespace

TEST_SUITE("input") {
    TEST_CASE("parse_real takes decimal finite numbers only") {
        float x = 0.0f;
        for (const char* good : {"0", "-2.5", "+3e-4", "1.", ".5", "1E+3"}) {
            CAPTURE(good);
            CHECK(parse_real(good, x));
        }
        CHECK(parse_real("-2.5", x));
        CHECK(x == -2.5f);
        for (const char* bad : {"", "nan", "inf", "-inf", "0x10", "1,5", "12abc", "1e",
                                "1e400", " 1", "1 ", "e5", ".", "-"}) {
            CAPTURE(bad);
            CHECK_FALSE(parse_real(bad, x));
        }
    }

    TEST_CASE(
        "parse_decimal reads decimals of any length and names a value out of range") {
        float x = 0.0f;
        // 100,000 digits after the point still read as the decimal they are
        CHECK(parse_decimal("0.5" + std::string(100000, '0'), x) == Decimal::ok);
        CHECK(x == 0.5f);
        CHECK(parse_decimal(std::string(60, '0') + "3e" + std::string(50, '0') + "1",
                            x) == Decimal::ok);
        CHECK(x == 30.0f);
        CHECK(parse_decimal("1e400", x) == Decimal::out_of_range);
        CHECK(parse_decimal("-3.5e38", x) == Decimal::out_of_range);
        CHECK(parse_decimal("0x1p0", x) == Decimal::not_decimal);
    }

    TEST_CASE("parse_whole takes leading zeros of any length") {
        long long x = 0;
        CHECK(parse_whole(std::string(100, '0') + "7", 1, 100, x));
        CHECK(x == 7);
        CHECK_FALSE(parse_whole("1" + std::string(40, '0'), 1, 100, x));
        CHECK(x > 100);
        CHECK(parse_whole("+0", 0, 0, x));
    }

    TEST_CASE("parse_whole reports the number it read, also out of range") {
        long long x = 0;
        CHECK_FALSE(parse_whole("99999999999", 1, 100, x));
        CHECK(x == 99999999999LL);
        CHECK_FALSE(parse_whole("7x", 1, 100, x));
        CHECK(parse_whole("-7", -10, 10, x));
        CHECK(x == -7);
    }

    TEST_CASE("split_lines drops a byte order mark and CR, and caps line length") {
        const auto lines = split_lines(
            "\xEF\xBB\xBF"
            "a\r\nb\n\nc",
            10, "t");
        REQUIRE(lines.size() == 4);
        CHECK(lines[0] == "a");
        CHECK(lines[1] == "b");
        CHECK(lines[3] == "c");
        CHECK_THROWS_WITH_AS(split_lines("ok\n" + std::string(11, 'x'), 10, "t"),
                             "t:2: line longer than 10 bytes", Error);
        // Classic Mac line ends (CR alone) are named, not read as one line of words
        CHECK_THROWS_WITH_AS(
            split_lines("ok\neye 0 0 3\rfov 40\r", 100, "t"),
            "t:2: a carriage return (CR) inside the line: line ends must "
            "be LF or CRLF, not CR alone",
            Error);
    }

    TEST_CASE("printable escapes control characters and bytes above 0x7e") {
        CHECK(printable("a\x1b[2Jb\xff") == "a\\x1b[2Jb\\xff");
        CHECK(printable(std::string(300, 'x'), 10) == "xxxxxxxxxx...");
    }

    TEST_CASE("a polygon with 100,000 corners loads as a fan of triangles") {
        LoadProgress quiet;
        quiet.warn = [](const std::string&) {};
        const Scene scene = load_obj_text(polygon(100000), "big.obj", no_mtl, quiet);
        // n - 2 triangles, less the few whose float corners fall on one line
        CHECK(scene.triangles.size() > 99000);
        CHECK(scene.triangles.size() <= 99998);
    }

    TEST_CASE("loading reports its stages and stops when cancelled") {
        std::vector<std::string> stages;
        LoadProgress progress;
        progress.report = [&](const char* stage, float fraction) {
            CHECK(fraction >= 0.0f);
            CHECK(fraction <= 1.0f);
            if (stages.empty() || stages.back() != stage) stages.push_back(stage);
        };
        (void)load_obj_text(polygon(40), "p.obj", no_mtl, progress);
        CHECK(stages == std::vector<std::string>{"reading", "parsing", "BVH"});

        std::atomic<bool> cancel{true};
        progress.cancel = &cancel;
        CHECK_THROWS_AS(load_obj_text(polygon(40), "p.obj", no_mtl, progress),
                        LoadCancelled);
    }

    TEST_CASE("warnings name what was dropped") {
        std::vector<std::string> warnings;
        LoadProgress progress;
        progress.warn = [&](const std::string& w) { warnings.push_back(w); };
        (void)load_obj_text("vw 0 1e38 1\nl 1 2\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
                            "w.obj", no_mtl, progress);
        REQUIRE(warnings.size() == 2);
        CHECK(warnings[0] ==
              "w.obj: ignored 1 line(s) raylab does not use (first: line 2, 'l')");
        CHECK(warnings[1] == "w.obj: ignored 1 vertex weight (vw) line(s)");
    }
}
