// The texture's tone mapping (viewer/tone_map.h).
#include "tone_map.h"

#include <cstring>

namespace raylab::viewer {

namespace {

constexpr std::uint32_t kInfBits = 0x7F800000u;  // +infinity; above it: NaN

std::uint32_t bits_of(float x) {
    std::uint32_t b = 0;
    std::memcpy(&b, &x, sizeof b);
    return b;
}

float float_of(std::uint32_t b) {
    float x = 0.0f;
    std::memcpy(&x, &b, sizeof x);
    return x;
}

}  // namespace

void ToneMapper::set_exposure(float exposure) {
    if (ready_ && exposure == exposure_) return;
    // Binary search over the bits of 0 .. +inf for each step of tone_map
    step_[0] = 0;
    for (int k = 1; k < 256; ++k) {
        std::uint32_t lo = step_[k - 1], hi = kInfBits;  // tone_map(+inf) = 255 >= k
        while (lo < hi) {
            const std::uint32_t mid = lo + (hi - lo) / 2;
            if (tone_map(float_of(mid), exposure) >= k) {
                hi = mid;
            } else {
                lo = mid + 1;
            }
        }
        step_[k] = lo;
    }
    first_.resize((kInfBits >> 16) + 1);
    for (size_t b = 0; b < first_.size(); ++b)
        first_[b] = tone_map(float_of(static_cast<std::uint32_t>(b) << 16), exposure);
    exposure_ = exposure;
    ready_ = true;
}

std::uint8_t ToneMapper::map(float L) const {
    const std::uint32_t b = bits_of(L);
    if (b > kInfBits) return 0;  // negative (sign bit) or NaN, as tone_map
    // The bucket's value, then the at most few steps inside the bucket
    int k = first_[b >> 16];
    while (k < 255 && b >= step_[k + 1])
        ++k;
    return static_cast<std::uint8_t>(k);
}

void ToneMapper::convert(const Image& image, float exposure,
                         std::vector<std::uint8_t>& out) {
    set_exposure(exposure);
    out.resize(image.pixels.size() * 3);
    std::uint8_t* o = out.data();
    for (const Vec3& p : image.pixels) {
        *o++ = map(p.x);
        *o++ = map(p.y);
        *o++ = map(p.z);
    }
}

}  // namespace raylab::viewer
