// The viewer's table tone mapping gives the bytes of raylab::to_srgb8
// (viewer/tone_map.h).
#include <doctest/doctest.h>

#include <cstring>
#include <limits>

#include "tone_map.h"

using namespace raylab;
using namespace raylab::viewer;

namespace {

float float_of(std::uint32_t b) {
    float x = 0.0f;
    std::memcpy(&x, &b, sizeof x);
    return x;
}

}  // namespace

TEST_SUITE("viewer") {
    TEST_CASE("the table tone mapping equals tone_map at every step and between") {
        for (const float exposure : {0.0f, -2.5f, 1.0f, 6.0f, -6.0f, 0.1f}) {
            ToneMapper tone;
            tone.set_exposure(exposure);
            INFO("exposure " << exposure);
            // Where tone_map steps up, found by scanning: the floats on both sides of
            // each step, then a sweep over all floats >= 0 (one in 4099: 520k values)
            int mismatches = 0;
            std::uint32_t first_bad = 0;
            const auto check = [&](std::uint32_t b) {
                const float L = float_of(b);
                if (tone.map(L) != tone_map(L, exposure)) {
                    if (mismatches++ == 0) first_bad = b;
                }
            };
            for (std::uint32_t b = 0; b <= 0x7F800000u; b += 4099)
                check(b);
            for (int k = 1; k < 256; ++k) {
                // Bisect the step from below (tone_map grows with L)
                std::uint32_t lo = 0, hi = 0x7F800000u;
                while (lo < hi) {
                    const std::uint32_t mid = lo + (hi - lo) / 2;
                    if (tone_map(float_of(mid), exposure) >= k) {
                        hi = mid;
                    } else {
                        lo = mid + 1;
                    }
                }
                for (std::uint32_t d = 0; d < 3; ++d) {
                    check(lo + d);
                    if (lo >= d) check(lo - d);
                }
            }
            INFO("first mismatch at float bits " << first_bad);
            CHECK(mismatches == 0);
            // Specials: NaN, negatives, zero, infinities, denormals, huge
            const float inf = std::numeric_limits<float>::infinity();
            for (const float L : {std::numeric_limits<float>::quiet_NaN(), -1.0f, -0.0f,
                                  0.0f, inf, -inf, 1e-42f, 3e38f, 1.0f, 0.5f}) {
                INFO("L = " << L);
                CHECK(tone.map(L) == tone_map(L, exposure));
            }
        }
    }

    TEST_CASE("a converted image has to_srgb8's bytes") {
        Image image(7, 5);
        for (size_t k = 0; k < image.pixels.size(); ++k) {
            const float x = 0.013f * float(k * k) - 0.1f;  // negatives, 0..1, above 1
            image.pixels[k] = Vec3(x, 0.5f * x, 3.0f * x);
        }
        ToneMapper tone;
        std::vector<std::uint8_t> bytes;
        for (const float exposure : {0.0f, 1.5f, -1.0f}) {
            INFO("exposure " << exposure);
            tone.convert(image, exposure, bytes);
            CHECK(bytes == to_srgb8(image, exposure));
        }
    }
}
