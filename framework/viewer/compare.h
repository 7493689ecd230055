// viewer/compare.h: the difference between the student's image and the reference's.
#pragma once

#include <cstdint>
#include <vector>

#include "raylab/image.h"

namespace raylab::viewer {

/// Per-pixel error between two renders of the same frame, in linear radiance.
struct Difference {
    int width = 0;
    int height = 0;
    double rmse = 0.0;             ///< sqrt of the mean squared channel difference
    double max_error = 0.0;        ///< largest absolute channel difference
    std::uint64_t differing = 0;   ///< pixels whose error exceeds the threshold
    std::uint64_t non_finite = 0;  ///< pixels with NaN or Inf in either image
    /// Heat map as 8-bit RGB, row 0 on top: black (no error) through red and yellow to
    /// white (max_error); magenta marks non-finite pixels.
    std::vector<std::uint8_t> heat;
};

/// Compares image with reference, pixel by pixel. A pixel "differs" when its largest
/// channel error exceeds threshold. Throws raylab::Error when the sizes differ.
Difference compare_images(const Image& image, const Image& reference,
                          float threshold = 1e-4f);

/// The heat-map colour of t in [0, 1] (black, red, yellow, white), 8-bit RGB.
void heat_colour(float t, std::uint8_t rgb[3]);

}  // namespace raylab::viewer
