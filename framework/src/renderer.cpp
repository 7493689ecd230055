// The renderer (raylab/renderer.h): tiles on all cores, one camera ray per pixel (or the
// sampling passes of render_sampling.cpp), each camera hit from a CameraHitSource
// (raylab/camera_hit_sources.h: cast, traced ahead or kept), shading by the chosen mode.
#include "raylab/renderer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <memory>
#include <thread>

#include "raylab/camera_hit_sources.h"
#include "raylab/error.h"
#include "raylab/input_checks.h"
#include "render_sampling.h"

namespace raylab {

const char* to_string(ShadingMode mode) {
    switch (mode) {
        case ShadingMode::lambert:
            return "lambert";
        case ShadingMode::normals:
            return "normals";
        case ShadingMode::base:
            return "base";
        case ShadingMode::depth:
            return "depth";
    }
    return "?";
}

ShadingMode parse_shading_mode(const std::string& word) {
    for (ShadingMode m : {ShadingMode::lambert, ShadingMode::normals, ShadingMode::base,
                          ShadingMode::depth}) {
        if (word == to_string(m)) return m;
    }
    throw Error("unknown shading mode '" + word + "' (lambert, normals, base, depth)");
}

void validate(const RenderSettings& s) {
    if (s.width < 1 || s.height < 1 || s.width > kMaxImageSide ||
        s.height > kMaxImageSide || std::int64_t{s.width} * s.height > kMaxImagePixels) {
        throw Error("resolution " + std::to_string(s.width) + "x" +
                    std::to_string(s.height) + " is outside 1x1 .. " +
                    std::to_string(kMaxImageSide) + " per side and " +
                    std::to_string(kMaxImagePixels >> 20) + " megapixels in all");
    }
    if (s.threads < 0 || s.threads > 1024)
        throw Error("thread count " + std::to_string(s.threads) + " is outside 0..1024");
    if (!is_finite(s.background)) throw Error("background colour is not finite");
    check_samples_per_pixel(s.spp, "samples per pixel");
    check_aa_threshold(s.aa_threshold, "adaptive threshold");
    check_light_size(s.light_size, "light size");
    check_light_samples(s.light_samples, "light samples");
}

namespace {

// The tiles of one pass over the image
int tiles_in_a_pass(const RenderSettings& s) {
    return ((s.width + kTileSize - 1) / kTileSize) *
           ((s.height + kTileSize - 1) / kTileSize);
}

}  // namespace

std::int64_t render_tile_total(const RenderSettings& s) {
    const std::int64_t tiles = tiles_in_a_pass(s);
    const bool two_passes =
        detail::supersampled(s) && s.sampling == PixelSampling::adaptive;
    return two_passes ? 2 * tiles : tiles;
}

PinholeCamera make_camera(const ModuleTable& modules, const View& view) {
    validate(view);
    PinholeCamera camera;
    camera.eye = view.eye;
    camera.frame = modules.camera_frame(view.eye, view.lookat, view.up);
    camera.d = modules.camera_constant(radians(view.fov));
    return camera;
}

namespace {

using detail::CameraHitSource;
using detail::CameraSample;
using detail::KeptFrame;
using detail::WorkCounters;

// What the shading of a frame's hits reads
struct FrameInputs {
    const Scene& scene;
    const ModuleTable& modules;
    const PinholeCamera camera;
    const RenderSettings& settings;
    const float depth_range;  // the depth view turns black there
};

// How a camera sample is shaded: the framework's per-pixel work after the hit, by the
// chosen mode (where the hit comes from is the CameraHitSource's part)
class PixelShader {
  public:
    PixelShader(const FrameInputs& frame, WorkCounters& counters)
        : frame_(frame),
          counters_(counters),
          occluder_(frame.scene, frame.modules, counters.trace),
          centre_(frame.scene.bounds().centre()) {}

    // The shadow rays of the next pixels start without the last blocker's hint
    void forget_blocker() { occluder_.forget_blocker(); }

    // The radiance of the camera sample the pixel loop asked for at uv
    Vec3 shade(const Vec2& uv, const CameraSample& sample) {
        const RenderSettings& settings = frame_.settings;
        uv_ = uv;
        if (!sample.traced || !sample.hit) return settings.background;
        const Hit& hit = *sample.hit;
        const Material& material = frame_.scene.materials[hit.material];
        switch (settings.mode) {
            case ShadingMode::normals:
                return 0.5f * (hit.ns + Vec3(1.0f));
            case ShadingMode::base:
                return material.rho;
            case ShadingMode::depth:
                return Vec3(std::clamp(1.0f - hit.t / frame_.depth_range, 0.0f, 1.0f));
            case ShadingMode::lambert:
                break;
        }
        return direct_light(hit, material);
    }

  private:
    // Lights that reach the hit point, then the Lambert module; shadow rays only where
    // needed
    Vec3 direct_light(const Hit& hit, const Material& material) {
        const Scene& scene = frame_.scene;
        visible_.clear();
        for (size_t k = 0; k < scene.lights.size(); ++k) {
            const PointLight& light = scene.lights[k];
            if (frame_.settings.light_size > 0.0f) {
                area_light(hit, light, k);
                continue;
            }
            add_if_visible(hit, frame_.modules.sample_point_light(light, hit.position));
        }
        return frame_.modules.lambert(material.rho, material.Le, hit.ns, visible_) +
               scene.ambient * material.rho;
    }

    // The area light that stands in for point light k (module 10): N samples, each with
    // the backfacing skip and the shadow test of a point light
    void area_light(const Hit& hit, const PointLight& light, size_t k) {
        const RenderSettings& settings = frame_.settings;
        const AreaLight area = area_light_for(light, settings.light_size, centre_);
        const int N = settings.light_samples;
        xi_ = frame_.modules.light_sample_points(N, settings.light_stratified,
                                                 detail::light_rng(settings, uv_, k));
        for (const Vec2& xi : xi_)
            add_if_visible(hit,
                           frame_.modules.sample_area_light(area, hit.position, xi, N));
    }

    // One light sample, point or area: a light behind the surface contributes nothing
    // and costs no shadow ray; with shadows on, the shadow module decides
    void add_if_visible(const Hit& hit, const LightSample& sample) {
        if (!(glm::dot(hit.ns, sample.wi) > 0.0f)) {
            ++counters_.backfacing;
            return;
        }
        if (!frame_.settings.shadows) {
            ++counters_.disabled;
        } else {
            const std::uint64_t before = occluder_.shadow_rays;
            const bool blocked =
                frame_.modules.in_shadow(occluder_, hit.position, hit.ns, sample);
            counters_.shadow_rays += occluder_.shadow_rays - before;
            if (blocked) return;
        }
        visible_.push_back(sample);
    }

    const FrameInputs& frame_;
    WorkCounters& counters_;
    SceneOccluder occluder_;
    std::vector<LightSample> visible_;  // reused: no allocation per pixel
    Vec3 centre_;                       // area lights face the scene's centre
    Vec2 uv_{0.0f};         // the camera sample being shaded (seeds the light samples)
    std::vector<Vec2> xi_;  // light sample points
};

// Distance at which the depth view turns black: the far side of the scene's bounds
float depth_range(const Scene& scene, const View& view) {
    const Aabb box = scene.bounds();
    float range = 10.0f * glm::length(view.lookat - view.eye);
    if (box.lo.x <= box.hi.x) {
        range =
            glm::length(box.centre() - view.eye) + 0.5f * glm::length(box.hi - box.lo);
    }
    return std::max(range, 1e-6f);
}

int thread_count(const RenderSettings& settings) {
    if (settings.threads > 0) return settings.threads;
    return std::max(1u, std::thread::hardware_concurrency());
}

// The image at the settings' size, black
void clear_image(const RenderSettings& settings, Image& image) {
    if (image.width != settings.width || image.height != settings.height) {
        image = Image(settings.width, settings.height);
    } else {
        std::fill(image.pixels.begin(), image.pixels.end(), Vec3(0.0f));
    }
    if (settings.samples_map)
        settings.samples_map->assign(size_t(settings.width) * size_t(settings.height), 1);
}

// Which source gives a pass's camera hits
enum class HitSource { cast, traced_ahead, kept };

// The frame's tiles on all threads, pass by pass, and the threads' work counts. Tiles are
// handed out by an atomic counter: threads that finish early take more
class TilePasses {
  public:
    TilePasses(const FrameInputs& frame, const KeptFrame& kept)
        : frame_(frame),
          kept_(kept),
          tiles_x_((frame.settings.width + kTileSize - 1) / kTileSize),
          tile_count_(tiles_in_a_pass(frame.settings)),
          counters_(size_t(std::min(thread_count(frame.settings), tile_count_))) {}

    // One pass over all tiles; pass(tile, radiance) renders a tile. A pixel loop's
    // exception is rethrown here, after every thread has stopped
    template <class Pass>
    void run(HitSource source, const Pass& pass) {
        std::atomic<int> next{0};
        std::vector<std::exception_ptr> errors(counters_.size());
        const auto work = [&](int k) {
            try {
                const std::unique_ptr<CameraHitSource> hits = make_source(source, k);
                PixelShader shader(frame_, counters_[size_t(k)]);
                const PixelRadiance radiance = [&](const Vec2& uv) {
                    return shader.shade(uv, hits->take(uv));
                };
                for (int t = next++; t < tile_count_; t = next++) {
                    if (cancelled()) break;
                    const Tile tile = tile_at(t);
                    hits->begin_tile(tile, kept_.keep(t));
                    // Each tile starts without a shadow hint: which thread had the tile
                    // before must not change its work counts
                    shader.forget_blocker();
                    pass(tile, radiance);
                    hits->end_tile();
                    if (frame_.settings.tiles_done) ++*frame_.settings.tiles_done;
                }
            } catch (...) {
                errors[size_t(k)] = std::current_exception();
            }
        };
        std::vector<std::thread> pool;
        for (int k = 1; k < static_cast<int>(counters_.size()); ++k)
            pool.emplace_back(work, k);
        work(0);
        for (std::thread& t : pool)
            t.join();
        for (const std::exception_ptr& e : errors) {
            if (e) std::rethrow_exception(e);
        }
    }

    bool cancelled() const {
        return frame_.settings.cancel &&
               frame_.settings.cancel->load(std::memory_order_relaxed);
    }

    // The threads' counts summed
    FrameStats sums() const {
        FrameStats stats;
        stats.threads = static_cast<int>(counters_.size());
        for (const WorkCounters& c : counters_) {
            stats.camera_rays += c.camera_rays;
            stats.camera_rays_reused += c.camera_rays_reused;
            stats.camera_rays_in_packets +=
                c.trace.packet_rays;  // only camera rays go in them
            stats.shadow_rays += c.shadow_rays;
            stats.shadow_rays_backfacing += c.backfacing;
            stats.shadow_rays_disabled += c.disabled;
            stats.intersection_tests += c.trace.intersection_tests;
            stats.bvh_nodes += c.trace.bvh_nodes;
        }
        return stats;
    }

    // A tile's pixel loop asked more points than it may keep
    bool hits_overflow() const {
        return std::any_of(counters_.begin(), counters_.end(),
                           [](const WorkCounters& c) { return c.hits_overflow; });
    }

  private:
    Tile tile_at(int t) const {
        const RenderSettings& s = frame_.settings;
        const int x0 = (t % tiles_x_) * kTileSize, y0 = (t / tiles_x_) * kTileSize;
        return Tile{x0, y0, std::min(x0 + kTileSize, s.width),
                    std::min(y0 + kTileSize, s.height)};
    }

    std::unique_ptr<CameraHitSource> make_source(HitSource source, int k) {
        const FrameInputs& f = frame_;
        WorkCounters& c = counters_[size_t(k)];
        switch (source) {
            case HitSource::kept:
                return std::make_unique<detail::KeptHits>(*kept_.reused(), f.scene,
                                                          f.modules, f.camera, c);
            case HitSource::traced_ahead:
                return std::make_unique<detail::TracedAheadHits>(f.scene, f.modules,
                                                                 f.camera, f.settings, c);
            case HitSource::cast:
                break;
        }
        return std::make_unique<detail::CastHits>(f.scene, f.modules, f.camera, c);
    }

    const FrameInputs& frame_;
    const KeptFrame& kept_;
    const int tiles_x_, tile_count_;
    std::vector<WorkCounters> counters_;  // one per thread
};

}  // namespace

FrameStats render(const Scene& scene, const View& view, const RenderSettings& settings,
                  const ModuleTable& modules, Image& image) {
    // Validate
    validate(settings);
    const auto start = std::chrono::steady_clock::now();
    // Camera
    const FrameInputs frame{scene, modules, make_camera(modules, view), settings,
                            depth_range(scene, view)};
    clear_image(settings, image);
    const ImageView out = image.view();

    // Tiles: module 01's pixel loop with the camera hits of the fastest source that
    // serves it, or module 09's samples; the adaptive scheme refines in a second pass
    KeptFrame kept(scene, view, settings, modules, size_t(tiles_in_a_pass(settings)));
    TilePasses tiles(frame, kept);
    const bool sampled = detail::supersampled(settings);
    const bool adaptive = sampled && settings.sampling == PixelSampling::adaptive;
    if (!sampled || adaptive) {
        const HitSource source = kept.reused()                   ? HitSource::kept
                                 : scene.traces_packets(modules) ? HitSource::traced_ahead
                                                                 : HitSource::cast;
        tiles.run(source, [&](const Tile& tile, const PixelRadiance& radiance) {
            modules.render_tile(tile, radiance, out);
        });
    } else {
        tiles.run(HitSource::cast, [&](const Tile& tile, const PixelRadiance& radiance) {
            detail::render_tile_sampled(tile, radiance, out, settings, modules);
        });
    }
    if (adaptive) {
        const Image first = image;
        tiles.run(HitSource::cast, [&](const Tile& tile, const PixelRadiance& radiance) {
            detail::refine_tile(tile, radiance, first, out, settings, modules);
        });
    }

    // Sums
    FrameStats stats = tiles.sums();
    stats.cancelled = settings.cancel && settings.cancel->load();
    kept.finish(stats.cancelled, tiles.hits_overflow());
    stats.non_finite_pixels = count_non_finite(image);
    stats.milliseconds = std::chrono::duration<double, std::milli>(
                             std::chrono::steady_clock::now() - start)
                             .count();
    return stats;
}

PixelProbe probe_pixel(const Scene& scene, const View& view,
                       const RenderSettings& settings, const ModuleTable& modules, int i,
                       int j) {
    validate(settings);
    if (i < 0 || j < 0 || i >= settings.width || j >= settings.height)
        throw Error("pixel (" + std::to_string(i) + ", " + std::to_string(j) +
                    ") is outside the image");
    const FrameInputs frame{scene, modules, make_camera(modules, view), settings,
                            depth_range(scene, view)};
    WorkCounters counters;
    detail::CastHits cast(scene, modules, frame.camera, counters);
    PixelShader shader(frame, counters);
    PixelProbe probe;
    probe.uv = modules.image_plane_point(i, j, settings.width, settings.height);
    const CameraSample sample = cast.take(probe.uv, &probe.ray);
    probe.hit = sample.hit;
    probe.L = shader.shade(probe.uv, sample);
    detail::probe_lights(scene, settings, modules, probe);
    return probe;
}

}  // namespace raylab
