// raylab/renderer.h: from a scene, a view and the chosen modules to an image.
//
// The same renderer serves the CLI, the viewer, the tests and the benchmarks. It splits
// the image into tiles, runs the pixel loop module on every tile on all cores, and for
// each pixel traces the camera ray, finds the closest hit and shades it.
#pragma once

#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "raylab/image.h"
#include "raylab/modules.h"
#include "raylab/scene.h"

namespace raylab {

/// What a pixel shows.
enum class ShadingMode {
    lambert,  ///< direct light from the point lights (modules 06-08), plus ambient
    normals,  ///< shading normal mapped from [-1, 1] to [0, 1]
    base,     ///< the material's rho, unlit
    depth,    ///< distance t along the camera ray, white near, black far
};

/// "lambert", "normals", "base", "depth"; parse_shading_mode throws raylab::Error
/// otherwise.
const char* to_string(ShadingMode mode);
ShadingMode parse_shading_mode(const std::string& word);

/// How the samples of a pixel are placed (module 09): the cells' centres, one at random
/// in each cell, or one centre sample everywhere and stratified samples where the
/// neighbourhood disagrees.
enum class PixelSampling { grid, stratified, adaptive };

/// "grid", "stratified", "adaptive"; parse_pixel_sampling throws raylab::Error
/// otherwise.
const char* to_string(PixelSampling sampling);
PixelSampling parse_pixel_sampling(const std::string& word);

/// Largest accepted image side and pixel count (about 64 megapixels: 768 MiB of float
/// RGB).
inline constexpr int kMaxImageSide = 16384;
/// The side of the square tiles render() hands to the pixel loop (the last row and column
/// of tiles may be smaller).
inline constexpr int kTileSize = 16;
inline constexpr std::int64_t kMaxImagePixels = std::int64_t{1} << 26;

/// Camera rays and their closest hits, kept from one frame for the next (the viewer's):
/// when only what lies after the hit changes (lights, ambient, shadows, shading mode, the
/// light and shading modules), render() shades the kept hits and casts no camera ray.
/// What the hits depend on is the frame's key: the image size, the view, the scene's
/// primitive counts and the modules 01-05 (an intersection module only where the scene
/// has its primitives). render() notes each frame's key; it fills the hits in a frame
/// whose key is the last frame's (the camera has stopped: the next change may well be a
/// light), and shades them in the frames after that, while the key stays and each
/// pixel's (u, v) is the one kept (a pixel loop that calls in another order casts
/// afresh). A frame with a new key (a camera move) keeps nothing: filling the hits writes
/// 68 bytes a pixel, which only a frame that reuses them repays. Where the hits come from
/// is raylab/camera_hit_sources.h (internal). Modules are taken to be functions of their
/// arguments (the contract). The owner calls clear() when the scene's geometry changes in
/// place. One sample per pixel and at most kMaxPixels pixels (68 bytes each): larger or
/// supersampled frames neither fill nor use it, and a frame whose pixel loop asks more
/// than two points a pixel of a tile (a student's supersampling in module 01) keeps none.
struct CameraHits {
    static constexpr std::int64_t kMaxPixels = std::int64_t{1} << 20;  // 1280 x 800
    struct Sample {
        Vec2 uv;                 ///< the image-plane point the pixel loop asked for
        bool traced = false;     ///< false: the camera module's ray was not valid
        std::optional<Hit> hit;  ///< the camera ray's closest hit
    };
    /// Forgets the hits and the key. Each tile's array keeps its memory for the next
    /// frame's: a frame that fills them again neither allocates nor faults in fresh pages
    void clear() {
        for (std::vector<Sample>& t : tiles)
            t.clear();
        valid = keyed = false;
    }

    bool valid = false;  ///< tiles hold the hits of a frame of the key below
    bool keyed = false;  ///< the key below is the last frame's (its hits kept or not)
    int width = 0, height = 0;
    View view;
    size_t primitives[3] = {0, 0, 0};  ///< planes, spheres, triangles
    std::vector<const void*> modules;  ///< the functions of modules 01-05 that matter
    std::vector<std::vector<Sample>> tiles;  ///< per tile, in the pixel loop's call order
};

struct RenderSettings {
    int width = 640;
    int height = 480;
    ShadingMode mode = ShadingMode::lambert;
    bool shadows = true;
    int threads = 0;  ///< 0: all hardware threads
    Vec3 background{0.0f};
    /// When set and it turns true, render() stops after the tiles in flight (viewer).
    const std::atomic<bool>* cancel = nullptr;
    /// When set: counts the tiles rendered, of render_tile_total() (a progress line).
    std::atomic<std::int64_t>* tiles_done = nullptr;

    // Sampling (modules 09 and 10). The defaults are one ray through each pixel centre
    // and point lights: the renderer of modules 01-08, bit for bit.
    int spp = 1;  ///< samples per pixel n^2 (adaptive: in the pixels it refines)
    PixelSampling sampling = PixelSampling::stratified;  ///< used when spp > 1
    float aa_threshold = 0.1f;  ///< adaptive: refine where the contrast exceeds this
    float light_size = 0.0f;  ///< side of the square area light per point light; 0: none
    int light_samples = 1;    ///< shadow rays per area light and shading point
    bool light_stratified = true;  ///< stratified (true) or uniform light samples
    std::uint64_t seed = 1;        ///< seeds every PixelRng of the frame
    /// When set: resized to width * height and filled with the camera samples each pixel
    /// took (the viewer's heat map).
    std::vector<std::uint16_t>* samples_map = nullptr;
    /// When set (one sample per pixel): camera hits reused from, or kept for, the next
    /// frame (CameraHits).
    CameraHits* camera_hits = nullptr;
};

/// Checks sizes and thread count; throws raylab::Error naming the problem.
void validate(const RenderSettings& settings);

/// The tiles render() renders with these settings, over all its passes (the adaptive
/// scheme has two): what settings.tiles_done counts up to.
std::int64_t render_tile_total(const RenderSettings& settings);

/// What a frame cost. Rays are counted by kind; skipped shadow rays are the ones the
/// renderer did not need to cast.
struct FrameStats {
    double milliseconds = 0.0;             ///< wall-clock render time
    std::uint64_t camera_rays = 0;         ///< one per pixel, but for reused ones
    std::uint64_t camera_rays_reused = 0;  ///< hits taken from settings.camera_hits
    /// Camera rays traced in packets of 4 x 4 pixels (the reference's engine; the others,
    /// of camera_rays, one at a time).
    std::uint64_t camera_rays_in_packets = 0;
    std::uint64_t shadow_rays = 0;  ///< any-hit queries cast by the shadow module
    std::uint64_t shadow_rays_backfacing = 0;  ///< skipped: light behind the surface
    std::uint64_t shadow_rays_disabled = 0;    ///< skipped: shadows off
    std::uint64_t intersection_tests = 0;      ///< primitive tests of all rays
    std::uint64_t bvh_nodes = 0;               ///< BVH nodes visited by all rays
    std::uint64_t non_finite_pixels = 0;       ///< NaN or Inf radiance (a module bug)
    int threads = 1;                           ///< threads used
    bool cancelled = false;                    ///< stopped early by settings.cancel

    std::uint64_t rays() const { return camera_rays + shadow_rays; }
    double rays_per_second() const {
        return milliseconds > 0.0 ? 1000.0 * static_cast<double>(rays()) / milliseconds
                                  : 0.0;
    }
};

/// The square area light of side size that stands in for light (handout 10 §4): centred
/// on light.p, facing target (down when target is light.p), with Le = I / A so that its
/// intensity along the normal is the point light's I.
AreaLight area_light_for(const PointLight& light, float size, const Vec3& target);

/// The pinhole camera of view for a width x height image, built with the camera module.
PinholeCamera make_camera(const ModuleTable& modules, const View& view);

/// Renders scene as seen from view into image (resized to the settings). Thread-safe for
/// concurrent calls on different images. Throws raylab::Error for invalid settings or
/// view.
FrameStats render(const Scene& scene, const View& view, const RenderSettings& settings,
                  const ModuleTable& modules, Image& image);

/// One light seen from a probed hit point: its sample and the shadow test's rays.
struct LightProbe {
    int light = 0;               ///< index into scene.lights
    LightSample sample{};        ///< sample_point_light at the hit point
    bool backfacing = false;     ///< light behind the surface: no shadow ray cast
    bool tested = false;         ///< in_shadow ran (shadows on, light in front)
    bool blocked = false;        ///< in_shadow's answer
    std::vector<Ray> rays;       ///< the rays in_shadow asked the scene about
    std::optional<Hit> blocker;  ///< closest hit on the first ray: what blocks it
    std::string blocker_name;    ///< e.g. "triangle 12" (empty: nothing on the ray)
    // An area light (light_size > 0): its N samples as the renderer draws them for this
    // camera sample. sample, rays and blocker are then those of the first blocked sample
    // (none blocked: of the first tested one), blocked says whether any was blocked, and
    // backfacing whether all were behind the surface.
    bool area = false;           ///< an area light
    int samples = 0;             ///< the points light_sample_points gave (N if right)
    int backfacing_samples = 0;  ///< behind the surface: no shadow ray
    int blocked_samples = 0;     ///< in_shadow said blocked
    int visible_samples = 0;     ///< passed to lambert; visible fraction = visible / N
    Vec3 Li_visible{0.0f};       ///< the sum of the visible samples' Li
};

/// Everything about one pixel, for the viewer's inspector and for debugging.
struct PixelProbe {
    Vec2 uv{0.0f};                   ///< image-plane point of the pixel centre
    Ray ray;                         ///< the camera ray
    std::optional<Hit> hit;          ///< its closest hit
    Vec3 L{0.0f};                    ///< the radiance the renderer stores
    std::vector<LightProbe> lights;  ///< per light, in Lambert mode with a hit
};

/// Traces the centre of pixel (i, j) exactly as render() does.
PixelProbe probe_pixel(const Scene& scene, const View& view,
                       const RenderSettings& settings, const ModuleTable& modules, int i,
                       int j);

}  // namespace raylab
