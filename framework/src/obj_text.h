// Internal: checks OBJ and MTL text line by line before tinyobjloader sees it, and
// rewrites it into the plain subset raylab uses (obj_loader.cpp, obj_text.cpp).
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "raylab/scene.h"
#include "raylab/scenes.h"

namespace raylab::obj {

/// Polygons with more corners than this are split into a fan here: tinyobjloader's
/// ear clipping costs O(n^2) per polygon (docs/decisions/0011).
constexpr size_t kMaxEarClipCorners = 32;

/// Material names are kept here, not in the text tinyobjloader reads: it reads a `usemtl`
/// name to the first space but a `newmtl` name to the end of the line.
struct CheckedObj {
    /// Text for tinyobjloader: `mtllib` replaced by one line naming kMaterialSlots, each
    /// `usemtl` naming a slot ("0", "1", ...) instead of the material
    std::string obj;
    std::vector<Material> materials;  ///< every checked MTL file's, in order
    /// Slot (a distinct usemtl name, in order of first use) -> index in materials, or -1
    /// for the default material (no material of that name)
    std::vector<int> slot_material;
};

/// The diffuse colour (rho, grey) of the default material, which faces without a
/// material get, and of an MTL material without a `Kd` line.
constexpr float kDefaultDiffuse = 0.75f;

/// The mtllib name the checked OBJ text gives tinyobjloader.
constexpr const char* kMaterialSlots = "raylab-material-slots";

/// Checks every line of an OBJ and the MTL files it names; throws raylab::Error
/// "SOURCE:LINE: field: problem". Lines raylab does not use (l, p, vw, curves, ...) are
/// dropped with one warning. An MTL file that cannot be read (missing, a folder, ...) is
/// one warning and its materials are missing: their faces get the default material. One
/// that is read must be valid.
CheckedObj check_obj(const std::string& text, const std::string& source,
                     const std::function<std::string(const std::string&)>& read_mtl,
                     const LoadProgress& progress);

/// An MTL file's materials (Kd and Ke). A material without a `Kd` line gets rho
/// kDefaultDiffuse, with a warning (tinyobjloader's 0 would render it black); `Kd 0 0 0`
/// stays black. Le defaults to 0. Throws raylab::Error "SOURCE:LINE: field: problem".
std::vector<Material> check_mtl(const std::string& text, const std::string& source,
                                const LoadProgress& progress);

/// Sends a warning to progress.warn, or to stderr.
void warn(const LoadProgress& progress, const std::string& message);

}  // namespace raylab::obj
