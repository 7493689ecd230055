// Images and their files (raylab/image.h).
#include "raylab/image.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>

#include <stb_image_write.h>

#include "raylab/error.h"

namespace raylab {

std::uint8_t tone_map(float L, float exposure) {
    float x = L * std::exp2(exposure);
    if (!(x > 0.0f)) return 0;  // also NaN
    if (x >= 1.0f) return 255;
    // sRGB transfer curve (IEC 61966-2-1)
    x = x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
    return static_cast<std::uint8_t>(std::lround(x * 255.0f));
}

std::vector<std::uint8_t> to_srgb8(const Image& image, float exposure) {
    std::vector<std::uint8_t> bytes(image.pixels.size() * 3);
    for (size_t k = 0; k < image.pixels.size(); ++k) {
        for (int c = 0; c < 3; ++c)
            bytes[3 * k + c] = tone_map(image.pixels[k][c], exposure);
    }
    return bytes;
}

size_t count_non_finite(const Image& image) {
    size_t n = 0;
    for (const Vec3& p : image.pixels)
        n += is_finite(p) ? 0 : 1;
    return n;
}

void write_png(const std::string& path, const Image& image, float exposure) {
    const std::vector<std::uint8_t> bytes = to_srgb8(image, exposure);
    if (!stbi_write_png(path.c_str(), image.width, image.height, 3, bytes.data(),
                        image.width * 3)) {
        throw Error("cannot write PNG '" + path + "'");
    }
}

void write_pfm(const std::string& path, const Image& image) {
    std::ofstream out(path, std::ios::binary);
    if (!out) throw Error("cannot write PFM '" + path + "'");
    // A negative scale marks little-endian data; rows go bottom to top
    out << "PF\n" << image.width << " " << image.height << "\n-1.0\n";
    for (int j = image.height - 1; j >= 0; --j) {
        out.write(reinterpret_cast<const char*>(&image.at(0, j)),
                  static_cast<std::streamsize>(sizeof(Vec3)) * image.width);
    }
    if (!out) throw Error("cannot write PFM '" + path + "'");
}

Image read_pfm(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error("cannot open PFM '" + path + "'");
    std::string magic;
    int w = 0, h = 0;
    float scale = 0.0f;
    in >> magic >> w >> h >> scale;
    in.get();  // the single white-space character before the data
    if (!in || magic != "PF" || w <= 0 || h <= 0 || scale >= 0.0f || w > 65536 ||
        h > 65536) {
        throw Error(path + ": not a little-endian RGB PFM");
    }
    Image image(w, h);
    for (int j = h - 1; j >= 0; --j) {
        in.read(reinterpret_cast<char*>(&image.at(0, j)),
                static_cast<std::streamsize>(sizeof(Vec3)) * w);
    }
    if (!in) throw Error(path + ": PFM data ends early");
    return image;
}

namespace {

bool ends_with(const std::string& path, const char* ext) {
    const size_t n = std::strlen(ext);
    return path.size() >= n && path.compare(path.size() - n, n, ext) == 0;
}

bool is_png(const std::string& path) {
    return ends_with(path, ".png") || ends_with(path, ".PNG");
}
bool is_pfm(const std::string& path) {
    return ends_with(path, ".pfm") || ends_with(path, ".PFM");
}

}  // namespace

void check_image_extension(const std::string& path) {
    if (!is_png(path) && !is_pfm(path))
        throw Error("output '" + path + "': unknown image type (use .png or .pfm)");
}

void write_image(const std::string& path, const Image& image, float exposure) {
    check_image_extension(path);
    if (is_png(path)) return write_png(path, image, exposure);
    write_pfm(path, image);
}

}  // namespace raylab
