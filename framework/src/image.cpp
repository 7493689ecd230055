// Images and their files (raylab/image.h).
#include "raylab/image.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>

#include <stb_image_write.h>

#include "raylab/error.h"
#include "raylab/input_file.h"

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

void write_file(const std::string& path, std::string_view bytes,
                const std::string& what) {
    const std::string name = what + " '" + printable(path) + "'";
    // O_NONBLOCK: a FIFO without a reader fails at once (ENXIO) instead of waiting
    const int fd =
        ::open(path.c_str(),
               O_WRONLY | O_CREAT | O_TRUNC | O_NONBLOCK | O_CLOEXEC | O_NOCTTY, 0666);
    if (fd < 0) throw Error("cannot write " + name + ": " + std::strerror(errno));
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        ::close(fd);
        throw Error("cannot write " + name + ": not a regular file");
    }
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const int error = n < 0 ? errno : EIO;
            ::close(fd);
            throw Error("cannot write " + name + ": " + std::strerror(error));
        }
        done += static_cast<size_t>(n);
    }
    if (::close(fd) != 0)
        throw Error("cannot write " + name + ": " + std::strerror(errno));
}

std::string encode_png(int width, int height, const std::uint8_t* rgb) {
    std::string bytes;
    const auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                                   static_cast<size_t>(size));
    };
    if (!stbi_write_png_to_func(append, &bytes, width, height, 3, rgb, width * 3))
        throw Error("cannot encode a " + std::to_string(width) + "x" +
                    std::to_string(height) + " PNG");
    return bytes;
}

void write_png(const std::string& path, const Image& image, float exposure) {
    const std::vector<std::uint8_t> bytes = to_srgb8(image, exposure);
    write_file(path, encode_png(image.width, image.height, bytes.data()), "PNG");
}

void write_pfm(const std::string& path, const Image& image) {
    // A negative scale marks little-endian data; rows go bottom to top
    std::string bytes = "PF\n" + std::to_string(image.width) + " " +
                        std::to_string(image.height) + "\n-1.0\n";
    const size_t row = sizeof(Vec3) * static_cast<size_t>(image.width);
    for (int j = image.height - 1; j >= 0; --j)
        bytes.append(reinterpret_cast<const char*>(&image.at(0, j)), row);
    write_file(path, bytes, "PFM");
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
        throw Error("output '" + printable(path) +
                    "': unknown image type (use .png or .pfm)");
}

void write_image(const std::string& path, const Image& image, float exposure) {
    check_image_extension(path);
    if (is_png(path)) return write_png(path, image, exposure);
    write_pfm(path, image);
}

}  // namespace raylab
