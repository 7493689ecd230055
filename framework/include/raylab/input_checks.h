// raylab/input_checks.h: one rule per quantity, shared by the command line, the view file
// and the viewer's panel, so a value is refused the same way wherever it enters.
//
// Each check throws raylab::Error "WHAT: value ... (the rule)"; WHAT names the flag,
// the file line or the panel field.
#pragma once

#include <string>

#include "raylab/scene.h"

namespace raylab {

constexpr float kFovMin = 0.1f;           ///< degrees; below it rays vanish
constexpr float kFovMax = 179.9f;         ///< degrees
constexpr float kMaxCoordinate = 1.0e6f;  ///< |x| of eye, look-at, up, light, vertex
constexpr float kMaxIntensity = 1.0e6f;   ///< W/sr per channel
constexpr float kMaxAmbient = 100.0f;     ///< times rho
constexpr float kMaxExposure = 40.0f;     ///< |EV|
constexpr int kMaxSamplesPerSide = 32;    ///< samples per pixel at most 32^2
constexpr int kMaxLightSamples = 1024;    ///< shadow rays per area light and point
constexpr float kMaxLightSize = 1.0e3f;   ///< side of an area light

void check_fov(float fov, const std::string& what);
/// A point (eye, look-at, light position): finite, every |coordinate| <= kMaxCoordinate.
void check_point(const Vec3& p, const std::string& what);
/// Light intensity: finite, non-negative, at most kMaxIntensity per channel.
void check_intensity(const Vec3& I, const std::string& what);
void check_ambient(float ambient, const std::string& what);
void check_exposure(float ev, const std::string& what);
/// eye, look-at and up within kMaxCoordinate, the fov rule, then validate(view).
/// Samples per pixel: a square n^2 with 1 <= n <= kMaxSamplesPerSide.
void check_samples_per_pixel(int spp, const std::string& what);
/// Adaptive threshold: a contrast, finite and in [0, 1].
void check_aa_threshold(float threshold, const std::string& what);
/// Area light side: finite, in [0, kMaxLightSize]; 0 keeps point lights.
void check_light_size(float size, const std::string& what);
/// Light samples: 1 .. kMaxLightSamples.
void check_light_samples(int n, const std::string& what);
void check_view(const View& view, const std::string& what);
void check_light(const PointLight& light, const std::string& what);

/// What an output path may be.
enum class OutputKind {
    image,   ///< .png or .pfm
    png,     ///< .png only (window screenshots)
    text,    ///< any name (view files)
    folder,  ///< a folder, made if missing (reports)
};

/// Checks an output path before any work: not empty, the type from the extension
/// (refused when unknown), not a folder, its folder exists and is writable.
void check_output_path(const std::string& path, OutputKind kind, const std::string& what);

}  // namespace raylab
