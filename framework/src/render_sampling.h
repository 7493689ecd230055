// The renderer's sampling passes (modules 09 and 10), kept apart from renderer.cpp's one
// ray per pixel: several samples per pixel, the adaptive refinement pass, and the area
// lights that stand in for point lights. Internal to raylab_core.
#pragma once

#include <cstdint>

#include "raylab/image.h"
#include "raylab/renderer.h"

namespace raylab::detail {

/// n for spp = n^2 (settings are validated first).
int samples_per_side(int spp);

/// True when the settings ask for more than the one centred ray per pixel.
bool supersampled(const RenderSettings& settings);

/// The generator of camera samples of pixel (i, j) in pass.
PixelRng pixel_rng(const RenderSettings& settings, int i, int j, std::uint64_t pass);

/// The generator of light samples of light k for the camera sample through uv: seeded
/// from uv's bits, so it is the same for any number of threads.
PixelRng light_rng(const RenderSettings& settings, const Vec2& uv, std::uint64_t k);

/// Each pixel of tile from spp grid or stratified samples (module 09's functions).
void render_tile_sampled(const Tile& tile, const PixelRadiance& radiance,
                         const ImageView& image, const RenderSettings& settings,
                         const ModuleTable& modules);

/// The adaptive pass: pixels of tile whose first sample and its eight neighbours' (in
/// first) disagree get spp stratified samples in out; the others keep their first one.
void refine_tile(const Tile& tile, const PixelRadiance& radiance, const Image& first,
                 const ImageView& out, const RenderSettings& settings,
                 const ModuleTable& modules);

/// Each light of probe's hit as the renderer's direct_light sees it (probe.cpp): the
/// sample or, for area lights, the N samples, the backfacing skip and the shadow tests.
void probe_lights(const Scene& scene, const RenderSettings& settings,
                  const ModuleTable& modules, PixelProbe& probe);

}  // namespace raylab::detail
