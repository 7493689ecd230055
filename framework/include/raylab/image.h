// raylab/image.h: float RGB images, tone mapping, PNG and PFM output.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "raylab/contract.h"

namespace raylab {

/// A width x height image of linear float RGB radiance, row 0 on top.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<Vec3> pixels;  ///< row-major, pixel (i, j) at j * width + i

    Image() = default;
    Image(int w, int h, Vec3 fill = Vec3(0.0f))
        : width(w), height(h), pixels(static_cast<size_t>(w) * h, fill) {}

    Vec3& at(int i, int j) { return pixels[static_cast<size_t>(j) * width + i]; }
    const Vec3& at(int i, int j) const {
        return pixels[static_cast<size_t>(j) * width + i];
    }
    /// The view the pixel loop writes through.
    ImageView view() { return ImageView{pixels.data(), width, height}; }
};

/// Linear radiance to an sRGB-encoded 8-bit value: scale by 2^exposure, clamp to [0, 1],
/// apply the sRGB transfer curve. NaN maps to 0.
std::uint8_t tone_map(float L, float exposure);

/// The image as 8-bit sRGB RGB bytes, row 0 first.
std::vector<std::uint8_t> to_srgb8(const Image& image, float exposure);

/// Counts pixels with a NaN or infinite component.
size_t count_non_finite(const Image& image);

/// Writes bytes to path, which must be or become a regular file: opened without blocking
/// (a FIFO or device is refused at once, never waited on), every write and the close
/// checked. Throws raylab::Error "cannot write WHAT 'PATH': reason" (a full disk, a file
/// size limit, ...).
void write_file(const std::string& path, std::string_view bytes, const std::string& what);

/// An 8-bit RGB image (rows of 3 * width bytes, top row first) as PNG file bytes.
std::string encode_png(int width, int height, const std::uint8_t* rgb);

/// Writes an 8-bit sRGB PNG (stb_image_write, then write_file). Throws raylab::Error on
/// failure.
void write_png(const std::string& path, const Image& image, float exposure = 0.0f);

/// Writes a little-endian float PFM ("PF"), linear radiance, bottom row first as the
/// format requires. Throws raylab::Error on failure.
void write_pfm(const std::string& path, const Image& image);

/// Reads a PFM written by write_pfm (or any 3-channel PFM). Throws raylab::Error.
Image read_pfm(const std::string& path);

/// Throws raylab::Error unless path ends in .png or .pfm (checked before a long render).
void check_image_extension(const std::string& path);

/// Writes PNG or PFM, chosen by the file's extension. Throws raylab::Error otherwise.
void write_image(const std::string& path, const Image& image, float exposure = 0.0f);

}  // namespace raylab
