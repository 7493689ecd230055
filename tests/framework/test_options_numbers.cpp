// The command line's one number parser and its escaped messages (raylab/options.h).
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "raylab/error.h"
#include "raylab/options.h"

using namespace raylab;

namespace {

Options parse_args(const std::vector<std::string>& args) {
    std::vector<const char*> argv = {"raylab-render"};
    for (const std::string& a : args)
        argv.push_back(a.c_str());
    return parse_options(static_cast<int>(argv.size()), argv.data());
}

std::string error_of(const std::vector<std::string>& args) {
    try {
        (void)parse_args(args);
    } catch (const Error& e) {
        return e.what();
    }
    return "(accepted)";
}

bool has_control(const std::string& text) {
    for (const char c : text)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return true;
    return false;
}

}  // namespace

TEST_SUITE("options") {
    TEST_CASE("a decimal of any length parses (1 MB here; argv itself allows 128 KiB)") {
        const std::string zeros(1 << 20, '0');
        CHECK(parse_flag_number("--fov", "45." + zeros + "1") == 45.0f);
        CHECK(parse_flag_number("--fov", zeros + "45") == 45.0f);
        CHECK(parse_flag_number("--fov", "0." + zeros + "1e1048576") ==
              doctest::Approx(0.1f));
        CHECK(*parse_args({"--fov", "45." + zeros}).fov == 45.0f);
        CHECK(parse_flag_whole("--width", zeros + "64", 1, 100) == 64);
        CHECK(parse_args({"--width", zeros + "64"}).settings.width == 64);
        // Beyond the range: named, not "not a number"
        CHECK_THROWS_WITH_AS(parse_flag_number("--fov", "1" + zeros),
                             doctest::Contains("beyond +-3.4e38"), Error);
        CHECK_THROWS_WITH_AS(parse_flag_whole("--width", "1" + zeros, 1, 100),
                             doctest::Contains("not a whole number in 1..100"), Error);
    }

    TEST_CASE("the number parser takes the decimal form only, for every flag") {
        for (const char* good : {"1", "-2.5", "+.5", "5.", "3e-4", "1E+2", "007"})
            CHECK_NOTHROW(parse_flag_number("--x", good));
        for (const char* bad : {"", " 1", "1 ", "0x10", "0x1p0", "inf", "nan", "1,5", ".",
                                "e5", "1e", "1e+", "--1", "1..2", "12abc", "1.5.2"}) {
            INFO("text: '" << bad << "'");
            CHECK_THROWS_WITH_AS(parse_flag_number("--x", bad),
                                 doctest::Contains("is not a finite number"), Error);
        }
        for (const char* bad : {"", " 1", "1.0", "1e3", "+", "0x10", "-"}) {
            INFO("text: '" << bad << "'");
            CHECK_THROWS_AS(parse_flag_whole("--x", bad, -10, 10), Error);
        }
        CHECK(parse_flag_whole("--x", "-0010", -10, 10) == -10);
        CHECK(parse_flag_whole("--x", "+10", -10, 10) == 10);
        CHECK_THROWS_AS(parse_flag_whole("--x", "11", -10, 10), Error);
        CHECK_THROWS_AS(parse_flag_whole("--x", "-11", -10, 10), Error);
        CHECK_THROWS_AS(parse_flag_whole("--x", "9999999999999999999", -10, 10), Error);
    }

    TEST_CASE("hostile values reach the message escaped, whatever the flag") {
        const std::string hostile = "x\x1b[31m\x07";
        for (const char* flag :
             {"--aa", "--mode", "--student", "--reference", "--fov", "--width", "--eye",
              "--light", "--shadows", "--light-sampling", "--output"}) {
            INFO("flag: " << flag);
            const std::string message = error_of({flag, hostile});
            CHECK(message.find("x\\x1b[31m\\x07") != std::string::npos);
            CHECK_FALSE(has_control(message));
        }
        CHECK_FALSE(has_control(error_of({hostile})));
    }
}
