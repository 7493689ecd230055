// One rule per quantity (raylab/input_checks.h).
#include "raylab/input_checks.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <cstdio>

#include "raylab/error.h"
#include "raylab/input_file.h"

namespace raylab {

namespace {

std::string num(float x) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", static_cast<double>(x));
    return text;
}

std::string vec(const Vec3& v) {
    return "(" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + ")";
}

bool within(const Vec3& v, float limit) {
    return std::fabs(v.x) <= limit && std::fabs(v.y) <= limit && std::fabs(v.z) <= limit;
}

std::string lower_extension(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    const size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
        return "";
    std::string ext = path.substr(dot);
    for (char& c : ext)
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return ext;
}

void check_writable_folder(const std::string& folder, const std::string& what) {
    struct stat st {};
    if (::stat(folder.c_str(), &st) != 0)
        throw Error(what + ": folder '" + printable(folder) + "' does not exist");
    if (!S_ISDIR(st.st_mode))
        throw Error(what + ": '" + printable(folder) + "' is not a folder");
    if (::access(folder.c_str(), W_OK | X_OK) != 0)
        throw Error(what + ": folder '" + printable(folder) + "' is not writable");
}

}  // namespace

void check_fov(float fov, const std::string& what) {
    if (!std::isfinite(fov) || fov < kFovMin || fov > kFovMax)
        throw Error(what + ": field of view " + num(fov) + " is outside [" +
                    num(kFovMin) + ", " + num(kFovMax) + "] degrees");
}

void check_samples_per_pixel(int spp, const std::string& what) {
    int n = 1;
    while (n * n < spp && n <= kMaxSamplesPerSide)
        ++n;
    if (spp < 1 || n > kMaxSamplesPerSide || n * n != spp)
        throw Error(what + ": " + std::to_string(spp) +
                    " samples per pixel is not a square n^2 with n in 1.." +
                    std::to_string(kMaxSamplesPerSide) + " (1, 4, 9, 16, ...)");
}

void check_aa_threshold(float threshold, const std::string& what) {
    if (!std::isfinite(threshold) || threshold < 0.0f || threshold > 1.0f)
        throw Error(what + ": adaptive threshold " + num(threshold) +
                    " is outside [0, 1] (a contrast (max - min) / (max + min))");
}

void check_light_size(float size, const std::string& what) {
    if (!std::isfinite(size) || size < 0.0f || size > kMaxLightSize)
        throw Error(what + ": light size " + num(size) + " is outside [0, " +
                    num(kMaxLightSize) + "] (0: point lights)");
}

void check_light_samples(int n, const std::string& what) {
    if (n < 1 || n > kMaxLightSamples)
        throw Error(what + ": " + std::to_string(n) + " light samples is outside 1.." +
                    std::to_string(kMaxLightSamples));
}

void check_point(const Vec3& p, const std::string& what) {
    if (!is_finite(p)) throw Error(what + ": " + vec(p) + " is not finite");
    if (!within(p, kMaxCoordinate))
        throw Error(what + ": " + vec(p) + " is too large (each coordinate within +-" +
                    num(kMaxCoordinate) + ")");
}

void check_intensity(const Vec3& I, const std::string& what) {
    if (!is_finite(I)) throw Error(what + ": intensity " + vec(I) + " is not finite");
    if (I.x < 0.0f || I.y < 0.0f || I.z < 0.0f)
        throw Error(what + ": intensity " + vec(I) + " must not be negative");
    if (!within(I, kMaxIntensity))
        throw Error(what + ": intensity " + vec(I) + " is above the maximum " +
                    num(kMaxIntensity) + " W/sr");
}

void check_ambient(float a, const std::string& what) {
    if (!std::isfinite(a) || a < 0.0f || a > kMaxAmbient)
        throw Error(what + ": ambient " + num(a) + " is outside [0, " + num(kMaxAmbient) +
                    "]");
}

void check_exposure(float ev, const std::string& what) {
    if (!std::isfinite(ev) || std::fabs(ev) > kMaxExposure)
        throw Error(what + ": exposure " + num(ev) + " EV is outside [-" +
                    num(kMaxExposure) + ", " + num(kMaxExposure) + "]");
}

void check_view(const View& view, const std::string& what) {
    check_point(view.eye, what + ": eye");
    check_point(view.lookat, what + ": look-at point");
    check_point(view.up, what + ": up vector");
    check_fov(view.fov, what);
    try {
        validate(view);
    } catch (const Error& e) {
        throw Error(what + ": " + e.what());
    }
}

void check_light(const PointLight& light, const std::string& what) {
    check_point(light.p, what + ": position");
    check_intensity(light.I, what);
}

void check_output_path(const std::string& path, OutputKind kind,
                       const std::string& what) {
    if (path.empty()) throw Error(what + ": an empty file name");
    const std::string name = printable(path);
    const std::string ext = lower_extension(path);
    if (kind == OutputKind::image && ext != ".png" && ext != ".pfm")
        throw Error(what + ": '" + name + "': unknown image type (use .png or .pfm)");
    if (kind == OutputKind::png && ext != ".png")
        throw Error(what + ": '" + name + "': screenshots are PNG (use .png)");
    struct stat st {};
    errno = 0;
    const bool exists = ::stat(path.c_str(), &st) == 0;
    // A name too long, a loop of links, ... (a missing folder or a file taken for one is
    // named by the folder check below)
    if (!exists && errno != ENOENT && errno != ENOTDIR)
        throw Error(what + ": '" + name + "': " + std::strerror(errno));
    if (!exists && ::lstat(path.c_str(), &st) == 0)
        throw Error(what + ": '" + name + "' is a symbolic link to nothing");
    if (kind == OutputKind::folder) {
        if (exists) {
            check_writable_folder(path, what);
            return;
        }
    } else if (exists && S_ISDIR(st.st_mode)) {
        throw Error(what + ": '" + name + "' is a folder");
    } else if (exists && !S_ISREG(st.st_mode)) {
        // Writing would wait on a FIFO forever or fill a device
        throw Error(what + ": '" + name + "' is " +
                    (S_ISFIFO(st.st_mode)                         ? "a FIFO"
                     : S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) ? "a device"
                     : S_ISSOCK(st.st_mode)                       ? "a socket"
                                            : "not a regular file") +
                    ", not a regular file");
    } else if (exists && ::access(path.c_str(), W_OK) != 0) {
        throw Error(what + ": '" + name + "' is not writable");
    }
    std::string folder = path;
    while (folder.size() > 1 && folder.back() == '/')
        folder.pop_back();
    const size_t slash = folder.find_last_of('/');
    folder = slash == std::string::npos ? "."
             : slash == 0               ? "/"
                                        : folder.substr(0, slash);
    check_writable_folder(folder, what);
}

}  // namespace raylab
