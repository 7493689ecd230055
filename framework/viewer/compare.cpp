// Image comparison (viewer/compare.h).
#include "compare.h"

#include <algorithm>
#include <cmath>

#include "raylab/error.h"

namespace raylab::viewer {

void heat_colour(float t, std::uint8_t rgb[3]) {
    // Three ramps: red rises on [0, 1/3], green on [1/3, 2/3], blue on [2/3, 1]
    t = std::clamp(t, 0.0f, 1.0f);
    const float channels[3] = {std::clamp(3.0f * t, 0.0f, 1.0f),
                               std::clamp(3.0f * t - 1.0f, 0.0f, 1.0f),
                               std::clamp(3.0f * t - 2.0f, 0.0f, 1.0f)};
    for (int c = 0; c < 3; ++c)
        rgb[c] = static_cast<std::uint8_t>(std::lround(255.0f * channels[c]));
}

Difference compare_images(const Image& image, const Image& reference, float threshold) {
    if (image.width != reference.width || image.height != reference.height) {
        throw Error("cannot compare a " + std::to_string(image.width) + "x" +
                    std::to_string(image.height) + " image with a " +
                    std::to_string(reference.width) + "x" +
                    std::to_string(reference.height) + " reference");
    }
    Difference d;
    d.width = image.width;
    d.height = image.height;
    const size_t n = image.pixels.size();
    std::vector<float> error(n, 0.0f);  // largest channel error per pixel; -1: non-finite
    double sum_squares = 0.0;
    for (size_t k = 0; k < n; ++k) {
        const Vec3 a = image.pixels[k], b = reference.pixels[k];
        if (!is_finite(a) || !is_finite(b)) {
            ++d.non_finite;
            error[k] = -1.0f;
            continue;
        }
        const Vec3 e = glm::abs(a - b);
        sum_squares += double(e.x) * e.x + double(e.y) * e.y + double(e.z) * e.z;
        error[k] = std::max(e.x, std::max(e.y, e.z));
        d.max_error = std::max(d.max_error, double(error[k]));
        if (error[k] > threshold) ++d.differing;
    }
    const size_t finite = n - d.non_finite;
    d.rmse = finite > 0 ? std::sqrt(sum_squares / (3.0 * double(finite))) : 0.0;

    // Heat map, scaled to the largest error so that small mistakes still show
    d.heat.resize(3 * n);
    for (size_t k = 0; k < n; ++k) {
        std::uint8_t* rgb = &d.heat[3 * k];
        if (error[k] < 0.0f) {
            rgb[0] = 255, rgb[1] = 0, rgb[2] = 255;
        } else {
            heat_colour(d.max_error > 0.0 ? float(error[k] / d.max_error) : 0.0f, rgb);
        }
    }
    return d;
}

}  // namespace raylab::viewer
