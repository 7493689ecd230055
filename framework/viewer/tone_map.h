// viewer/tone_map.h: the image to 8-bit sRGB for the texture, fast and exact.
//
// raylab::to_srgb8 calls exp2 and pow for every channel, on the main thread a large
// part of a small render. tone_map (raylab/image.h) only grows
// with L, so for one exposure it is fixed by the 255 values of L where it steps up;
// ToneMapper finds them once per exposure and then only compares: the same bytes.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "raylab/image.h"

namespace raylab::viewer {

class ToneMapper {
  public:
    /// The bytes raylab::to_srgb8(image, exposure) gives, into out (resized).
    void convert(const Image& image, float exposure, std::vector<std::uint8_t>& out);
    /// One value: raylab::tone_map(L, exposure) for the exposure of the last convert.
    std::uint8_t map(float L) const;
    /// Prepares the tables for exposure (convert calls it when the exposure changes).
    void set_exposure(float exposure);

  private:
    bool ready_ = false;
    float exposure_ = 0.0f;
    // step_[k]: the bits of the smallest L >= 0 with tone_map(L) >= k (k = 1 .. 255);
    // floats >= 0 order as their bits
    std::array<std::uint32_t, 256> step_{};
    // first_[b]: tone_map of the float with bits b << 16 (buckets of 2^16 floats)
    std::vector<std::uint8_t> first_;
};

}  // namespace raylab::viewer
