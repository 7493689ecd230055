// viewer/view_file.h: camera and lights as a small text file (save / load view).
//
//   # raylab view
//   eye 0 0 3
//   lookat 0 0 0
//   up 0 1 0
//   fov 53.1301
//   light 0 0.5 0.7  1.11408 1.11408 1.11408
//
// One keyword and its numbers per line; '#' starts a comment. eye, lookat, up and fov
// appear exactly once; each light line is a position and an RGB intensity [W/sr]; the
// lights replace the scene's (no light line: no lights).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "raylab/renderer.h"
#include "raylab/scene.h"

namespace raylab::viewer {

struct ViewFile {
    View view;
    std::vector<PointLight> lights;
    /// Optional "light_size S" and "light_samples N" lines (handout 10): each point light
    /// as a square area light of side S, sampled with N shadow rays.
    std::optional<float> light_size;
    std::optional<int> light_samples;

    /// Puts the optional keys that are present into settings.
    void apply_to(RenderSettings& settings) const {
        if (light_size) settings.light_size = *light_size;
        if (light_samples) settings.light_samples = *light_samples;
    }
};

/// The text of a view file; floats are written with 9 digits, so they read back exactly.
/// A float with 9 significant digits: reads back to the same float.
std::string format_number(float x);

/// x, y, z with 9 significant digits each, separated by sep.
std::string format_vec3(const Vec3& v, const char* sep);

/// With settings, the area-light keys are written when settings.light_size > 0.
std::string format_view_file(const View& view, const std::vector<PointLight>& lights,
                             const RenderSettings* settings = nullptr);

/// Parses the text of a view file. Throws raylab::Error as "SOURCE:LINE: problem" (or
/// "SOURCE: problem" for a missing line or an invalid camera).
ViewFile parse_view_file(const std::string& text, const std::string& source);

/// Writes and reads view files. Throw raylab::Error naming the file.
void save_view_file(const std::string& path, const View& view,
                    const std::vector<PointLight>& lights,
                    const RenderSettings* settings = nullptr);
ViewFile load_view_file(const std::string& path);

}  // namespace raylab::viewer
