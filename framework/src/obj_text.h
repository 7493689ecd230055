// Internal: checks OBJ and MTL text line by line before tinyobjloader sees it, and
// rewrites it into the plain subset raylab uses (obj_loader.cpp, obj_text.cpp).
#pragma once

#include <functional>
#include <map>
#include <string>

#include "raylab/scenes.h"

namespace raylab::obj {

/// Polygons with more corners than this are split into a fan here: tinyobjloader's
/// ear clipping costs O(n^2) per polygon (a 100k-corner polygon took 51 s).
constexpr size_t kMaxEarClipCorners = 32;

struct CheckedObj {
    std::string obj;                         ///< text for tinyobjloader
    std::map<std::string, std::string> mtl;  ///< mtllib name -> checked MTL text
};

/// Checks every line of an OBJ and the MTL files it names; throws raylab::Error
/// "SOURCE:LINE: field: problem". Lines raylab does not use (l, p, vw, curves, ...) are
/// dropped with one warning.
CheckedObj check_obj(const std::string& text, const std::string& source,
                     const std::function<std::string(const std::string&)>& read_mtl,
                     const LoadProgress& progress);

/// Checks an MTL file's text; returns the subset tinyobjloader gets.
std::string check_mtl(const std::string& text, const std::string& source,
                      const LoadProgress& progress);

/// Sends a warning to progress.warn, or to stderr.
void warn(const LoadProgress& progress, const std::string& message);

}  // namespace raylab::obj
