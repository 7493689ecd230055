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

#include <string>
#include <vector>

#include "raylab/scene.h"

namespace raylab::viewer {

struct ViewFile {
    View view;
    std::vector<PointLight> lights;
};

/// The text of a view file; floats are written with 9 digits, so they read back exactly.
/// A float with 9 significant digits: reads back to the same float.
std::string format_number(float x);

/// x, y, z with 9 significant digits each, separated by sep.
std::string format_vec3(const Vec3& v, const char* sep);

std::string format_view_file(const View& view, const std::vector<PointLight>& lights);

/// Parses the text of a view file. Throws raylab::Error as "SOURCE:LINE: problem" (or
/// "SOURCE: problem" for a missing line or an invalid camera).
ViewFile parse_view_file(const std::string& text, const std::string& source);

/// Writes and reads view files. Throw raylab::Error naming the file.
void save_view_file(const std::string& path, const View& view,
                    const std::vector<PointLight>& lights);
ViewFile load_view_file(const std::string& path);

}  // namespace raylab::viewer
