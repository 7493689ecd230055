// View files (viewer/view_file.h).
#include "view_file.h"

#include <cmath>
#include <cstdio>

#include "raylab/error.h"
#include "raylab/image.h"
#include "raylab/input_checks.h"
#include "raylab/input_file.h"
#include "raylab/options.h"

namespace raylab::viewer {

std::string format_number(float x) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.9g", static_cast<double>(x));
    return buffer;
}

std::string format_vec3(const Vec3& v, const char* sep) {
    return format_number(v.x) + sep + format_number(v.y) + sep + format_number(v.z);
}

namespace {

std::string number(float x) {
    return format_number(x);
}

std::string triple(const Vec3& v) {
    return format_vec3(v, " ");
}

// One line's numbers after the keyword: exactly as many as names, each strictly parsed
std::vector<float> numbers(const std::vector<std::string_view>& words,
                           const std::vector<const char*>& names, const std::string& at) {
    if (words.size() - 1 != names.size()) {
        throw Error(at + "'" + std::string(words[0]) + "' needs " +
                    std::to_string(names.size()) + " numbers, found " +
                    std::to_string(words.size() - 1));
    }
    std::vector<float> xs(names.size());
    // The flags' parser: a number reads the same on the command line and in a view file
    for (size_t k = 0; k < names.size(); ++k)
        xs[k] = parse_flag_number(at + names[k], std::string(words[k + 1]));
    return xs;
}

}  // namespace

std::string format_view_file(const View& view, const std::vector<PointLight>& lights,
                             const RenderSettings* settings) {
    std::string text = "# raylab view: camera and point lights (docs/viewer.md)\n";
    text += "eye " + triple(view.eye) + "\n";
    text += "lookat " + triple(view.lookat) + "\n";
    text += "up " + triple(view.up) + "\n";
    text += "fov " + number(view.fov) + "\n";
    text += "# light: position x y z, intensity I r g b [W/sr]\n";
    for (const PointLight& light : lights)
        text += "light " + triple(light.p) + "  " + triple(light.I) + "\n";
    if (settings && settings->light_size > 0.0f) {
        text += "# area lights (handout 10): side of the square, shadow rays per point\n";
        text += "light_size " + number(settings->light_size) + "\n";
        text += "light_samples " + std::to_string(settings->light_samples) + "\n";
    }
    return text;
}

ViewFile parse_view_file(const std::string& text, const std::string& source) {
    ViewFile file;
    bool seen[4] = {false, false, false, false};  // eye, lookat, up, fov
    const char* keys[4] = {"eye", "lookat", "up", "fov"};
    const std::vector<const char*> xyz = {"x", "y", "z"};
    const std::vector<const char*> light = {"x", "y", "z", "red", "green", "blue"};
    const std::vector<std::string_view> lines = split_lines(text, kMaxLine, source);
    for (size_t n = 0; n < lines.size(); ++n) {
        const std::string at = where(source, n + 1);
        std::string_view line = lines[n];
        if (const size_t hash = line.find('#'); hash != std::string_view::npos)
            line = line.substr(0, hash);
        const std::vector<std::string_view> words = split_words(line);
        if (words.empty()) continue;  // blank or comment
        const std::string_view keyword = words[0];
        if (keyword == "light") {
            const std::vector<float> x = numbers(words, light, at);
            file.lights.push_back(
                PointLight{Vec3(x[0], x[1], x[2]), Vec3(x[3], x[4], x[5])});
            check_light(file.lights.back(), at + "light");
            continue;
        }
        if (keyword == "light_size" || keyword == "light_samples") {
            const bool size = keyword == "light_size";
            if (size ? file.light_size.has_value() : file.light_samples.has_value())
                throw Error(at + "'" + std::string(keyword) + "' appears twice");
            const std::vector<float> x = numbers(words, {size ? "side" : "count"}, at);
            if (size) {
                check_light_size(x[0], at + "light_size");
                file.light_size = x[0];
            } else {
                // Range first: the cast of a float beyond int is undefined (the fuzzer's
                // "light_samples 2332331833")
                if (!(std::abs(x[0]) <= float(kMaxLightSamples) + 1.0f))
                    throw Error(at + "light_samples: " + number(x[0]) +
                                " light samples is outside 1.." +
                                std::to_string(kMaxLightSamples));
                const int n = static_cast<int>(x[0]);
                if (float(n) != x[0])
                    throw Error(at + "light_samples: " + number(x[0]) +
                                " is not a whole number");
                check_light_samples(n, at + "light_samples");
                file.light_samples = n;
            }
            continue;
        }
        int k = 0;
        while (k < 4 && keyword != keys[k])
            ++k;
        if (k == 4) {
            throw Error(at + "unknown keyword '" + printable(keyword, 40) +
                        "' (eye, lookat, up, fov, light, light_size, light_samples)");
        }
        if (seen[k]) throw Error(at + "'" + keys[k] + "' appears twice");
        seen[k] = true;
        const std::vector<float> x =
            numbers(words, k == 3 ? std::vector<const char*>{"degrees"} : xyz, at);
        if (k == 3) {
            file.view.fov = x[0];
        } else {
            Vec3& v = k == 0 ? file.view.eye : k == 1 ? file.view.lookat : file.view.up;
            v = Vec3(x[0], x[1], x[2]);
        }
    }
    for (int k = 0; k < 4; ++k) {
        if (!seen[k]) throw Error(source + ": missing the '" + keys[k] + "' line");
    }
    check_view(file.view, source);
    return file;
}

void save_view_file(const std::string& path, const View& view,
                    const std::vector<PointLight>& lights,
                    const RenderSettings* settings) {
    check_output_path(path, OutputKind::text, "view file");
    write_file(path, format_view_file(view, lights, settings), "view file");
}

ViewFile load_view_file(const std::string& path) {
    return parse_view_file(read_input_file(path, kMaxViewBytes), printable(path));
}

}  // namespace raylab::viewer
