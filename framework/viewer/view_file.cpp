// View files (viewer/view_file.h).
#include "view_file.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "raylab/error.h"

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

// Reads one line's numbers after the keyword; exactly count of them, all finite
std::vector<float> numbers(std::istringstream& words, size_t count,
                           const std::string& where, const std::string& keyword) {
    std::vector<float> xs;
    for (std::string word; words >> word;) {
        errno = 0;
        char* end = nullptr;
        const float x = std::strtof(word.c_str(), &end);
        if (*end != '\0' || errno == ERANGE || !std::isfinite(x))
            throw Error(where + "'" + word + "' is not a finite number");
        xs.push_back(x);
    }
    if (xs.size() != count) {
        throw Error(where + "'" + keyword + "' needs " + std::to_string(count) +
                    " numbers, found " + std::to_string(xs.size()));
    }
    return xs;
}

}  // namespace

std::string format_view_file(const View& view, const std::vector<PointLight>& lights) {
    std::string text = "# raylab view: camera and point lights (docs/viewer.md)\n";
    text += "eye " + triple(view.eye) + "\n";
    text += "lookat " + triple(view.lookat) + "\n";
    text += "up " + triple(view.up) + "\n";
    text += "fov " + number(view.fov) + "\n";
    text += "# light: position x y z, intensity I r g b [W/sr]\n";
    for (const PointLight& light : lights)
        text += "light " + triple(light.p) + "  " + triple(light.I) + "\n";
    return text;
}

ViewFile parse_view_file(const std::string& text, const std::string& source) {
    ViewFile file;
    bool seen[4] = {false, false, false, false};  // eye, lookat, up, fov
    const char* keys[4] = {"eye", "lookat", "up", "fov"};
    std::istringstream lines(text);
    int line_number = 0;
    for (std::string line; std::getline(lines, line);) {
        ++line_number;
        const std::string where = source + ":" + std::to_string(line_number) + ": ";
        if (const size_t hash = line.find('#'); hash != std::string::npos)
            line.erase(hash);
        std::istringstream words(line);
        std::string keyword;
        if (!(words >> keyword)) continue;  // blank or comment
        if (keyword == "light") {
            const std::vector<float> x = numbers(words, 6, where, keyword);
            if (x[3] < 0.0f || x[4] < 0.0f || x[5] < 0.0f)
                throw Error(where + "light intensity must not be negative");
            file.lights.push_back(
                PointLight{Vec3(x[0], x[1], x[2]), Vec3(x[3], x[4], x[5])});
            continue;
        }
        int k = 0;
        while (k < 4 && keyword != keys[k])
            ++k;
        if (k == 4) {
            throw Error(where + "unknown keyword '" + keyword +
                        "' (eye, lookat, up, fov, light)");
        }
        if (seen[k]) throw Error(where + "'" + keyword + "' appears twice");
        seen[k] = true;
        const std::vector<float> x = numbers(words, k == 3 ? 1 : 3, where, keyword);
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
    try {
        validate(file.view);
    } catch (const Error& e) {
        throw Error(source + ": " + e.what());
    }
    return file;
}

void save_view_file(const std::string& path, const View& view,
                    const std::vector<PointLight>& lights) {
    std::ofstream out(path);
    out << format_view_file(view, lights);
    if (!out.flush()) throw Error(path + ": cannot write the view file");
}

ViewFile load_view_file(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Error(path + ": cannot open the view file");
    std::ostringstream text;
    text << in.rdbuf();
    return parse_view_file(text.str(), path);
}

}  // namespace raylab::viewer
