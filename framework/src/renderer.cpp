// The renderer (raylab/renderer.h): tiles on all cores, one camera ray per pixel (or the
// sampling passes of render_sampling.cpp), closest hit, shading by the chosen mode.
#include "raylab/renderer.h"

#include <atomic>
#include <chrono>
#include <exception>
#include <thread>

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

std::int64_t render_tile_total(const RenderSettings& s) {
    const std::int64_t tiles = std::int64_t{(s.width + kTileSize - 1) / kTileSize} *
                               ((s.height + kTileSize - 1) / kTileSize);
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

// Per-thread work counters, summed after the frame
struct alignas(64) Counters {  // one cache line each: no false sharing
    TraceCounters trace;
    std::uint64_t camera_rays = 0;
    std::uint64_t camera_rays_reused = 0;
    std::uint64_t shadow_rays = 0;
    std::uint64_t backfacing = 0;
    std::uint64_t disabled = 0;
    bool hits_overflow = false;  // the pixel loop asked more than kKeptPerPixel per pixel
};

// A tile keeps at most this many camera samples per pixel (CameraHits): a pixel loop that
// asks more (a student's supersampling in module 01) keeps none in that frame, instead of
// 68 bytes a call (1.1 GB at 16 a pixel in 1280 x 800)
constexpr size_t kKeptPerPixel = 2;

// The framework's per-pixel work, given to the pixel loop as PixelRadiance
class PixelShader {
  public:
    PixelShader(const Scene& scene, const ModuleTable& modules,
                const PinholeCamera& camera, const RenderSettings& settings,
                float depth_range, Counters& counters)
        : scene_(scene),
          modules_(modules),
          camera_(camera),
          settings_(settings),
          depth_range_(depth_range),
          counters_(counters),
          occluder_(scene, modules, counters.trace),
          centre_(scene.bounds().centre()) {}

    // The shadow rays of the next pixels start without the last blocker's hint
    void forget_blocker() { occluder_.forget_blocker(); }

    // The next tile's kept camera hits (CameraHits): reuse them in order, or keep them
    void begin_tile(std::vector<CameraHits::Sample>* hits, bool reuse, bool keep,
                    const Tile& tile) {
        const size_t pixels = size_t(tile.x1 - tile.x0) * size_t(tile.y1 - tile.y0);
        if (keep) hits->reserve(pixels);
        keep_limit_ = kKeptPerPixel * pixels;
        tile_hits_ = hits;
        source_ = hits;
        cursor_ = 0;
        reuse_ = reuse;
        keep_ = keep;
        last_frame_ = reuse;
    }

    // Traces the tile's camera rays ahead of its pixel loop, in packets of 4 x 4 pixels
    // (Scene::closest_hits): the pixel loop then takes them as it takes kept hits, in the
    // reference loop's order (rows top to bottom, columns left to right), while it asks
    // for the same points. Only where the scene traces packets (the reference's engine),
    // and not over hits kept from the last frame. A pixel loop that asks in another order
    // takes the rest of the tile one ray at a time, and this thread stops tracing ahead
    // for the rest of the frame.
    void trace_ahead(const Tile& tile) {
        if (last_frame_ || ahead_off_ || !scene_.traces_packets(modules_)) return;
        const int W = settings_.width, H = settings_.height;
        const int tw = tile.x1 - tile.x0, th = tile.y1 - tile.y0;
        ahead_.resize(size_t(tw) * size_t(th));
        rays_.clear();
        slots_.clear();
        // Row-major samples; rays gathered block by block
        for (int by = 0; by < th; by += 4)
            for (int bx = 0; bx < tw; bx += 4)
                for (int y = by; y < std::min(by + 4, th); ++y)
                    for (int x = bx; x < std::min(bx + 4, tw); ++x) {
                        const size_t slot = size_t(y) * size_t(tw) + size_t(x);
                        CameraHits::Sample& s = ahead_[slot];
                        s.uv = modules_.image_plane_point(tile.x0 + x, tile.y0 + y, W, H);
                        // Made in place: a Ray written by field and then copied whole
                        // stalls on the copy (store-to-load forwarding fails), which
                        // was a quarter of this loop
                        s.traced = camera_ray(s.uv, rays_.emplace_back());
                        s.hit.reset();
                        if (!s.traced) {
                            rays_.pop_back();
                            continue;
                        }
                        slots_.push_back(slot);
                    }
        hits_.resize(rays_.size());
        scene_.closest_hits(modules_, rays_.data(), static_cast<int>(rays_.size()),
                            counters_.trace, hits_.data());
        counters_.camera_rays += rays_.size();
        for (size_t k = 0; k < slots_.size(); ++k)
            ahead_[slots_[k]].hit = hits_[k];
        source_ = &ahead_;
        cursor_ = 0;
        reuse_ = true;
    }

    // After the tile's pixel loop: did it take every ray traced ahead, in order? The
    // samples it took in order are the ones to keep: all of them change places with the
    // tile's kept array (no copy, and the array's memory goes round for the next tile)
    void end_tile() {
        if (source_ != &ahead_) return;
        if (cursor_ != ahead_.size()) ahead_off_ = true;
        if (keep_ && reuse_) {
            if (cursor_ == ahead_.size()) {
                tile_hits_->swap(ahead_);
            } else {
                keep_taken_ahead();
            }
        }
        source_ = tile_hits_;
        reuse_ = false;
    }

    Vec3 radiance(const Vec2& uv, std::optional<Hit>* hit_out = nullptr,
                  Ray* ray_out = nullptr) {
        uv_ = uv;
        Ray ray;
        bool traced = false;
        // The hit is initialised from the query's result, not assigned: an assignment
        // copied it 16 bytes at a time while the engine's narrower stores to it were
        // still in the store buffer, which cannot forward them (3 % of a Cornell frame)
        const CameraHits::Sample* kept = kept_sample(uv);
        const std::optional<Hit> hit =
            kept ? kept->hit : cast_camera_ray(uv, ray, traced);
        if (kept) traced = kept->traced;  // (the ray is not kept: shading needs the hit)
        // A sample taken from those traced ahead is kept at end_tile (or when the pixel
        // loop leaves their order), all at once
        if (keep_ && !(kept && source_ == &ahead_)) {
            if (tile_hits_->size() < keep_limit_) {
                tile_hits_->push_back({uv, traced, hit});
            } else {
                keep_ = false;  // this frame keeps nothing (render() sees the flag)
                counters_.hits_overflow = true;
            }
        }
        if (!traced) return settings_.background;
        if (ray_out) *ray_out = ray;
        if (hit_out) *hit_out = hit;
        if (!hit) return settings_.background;
        const Material& material = scene_.materials[hit->material];
        switch (settings_.mode) {
            case ShadingMode::normals:
                return 0.5f * (hit->ns + Vec3(1.0f));
            case ShadingMode::base:
                return material.rho;
            case ShadingMode::depth:
                return Vec3(std::clamp(1.0f - hit->t / depth_range_, 0.0f, 1.0f));
            case ShadingMode::lambert:
                break;
        }
        return direct_light(*hit, material);
    }

  private:
    // The kept camera hit of uv while the pixel loop asks for the kept points in the
    // same order; nullptr once out of step (the rest of the tile is cast)
    const CameraHits::Sample* kept_sample(const Vec2& uv) {
        if (reuse_ && cursor_ < source_->size() && (*source_)[cursor_].uv == uv) {
            // (a point whose camera ray was not valid was not a ray)
            if (last_frame_ && (*source_)[cursor_].traced) ++counters_.camera_rays_reused;
            return &(*source_)[cursor_++];
        }
        if (reuse_ && keep_ && source_ == &ahead_) keep_taken_ahead();
        reuse_ = false;
        return nullptr;
    }

    // Keeps the samples traced ahead that the pixel loop has taken in order so far
    void keep_taken_ahead() {
        tile_hits_->insert(tile_hits_->end(), ahead_.begin(),
                           ahead_.begin() + static_cast<std::ptrdiff_t>(cursor_));
    }

    // The camera module's ray through uv, its w normalised (the framework boundary,
    // docs/style.md rule 9); false when the ray is not valid (not traced). The module's
    // ray is read by component: a copy of the whole waits for the module's stores to
    // finish (a failed store-to-load forwarding), 6 % of a Cornell frame on one thread
    // (raylab-bench section 3)
    bool camera_ray(const Vec2& uv, Ray& ray) const {
        const Ray r = modules_.camera_ray(camera_, uv);
        const float len = glm::length(r.w);
        if (!(len > 0.0f && std::isfinite(len) && is_finite(r.o))) return false;
        ray.o = r.o;
        ray.w = r.w / len;
        ray.tmin = r.tmin;
        ray.tmax = r.tmax;
        return true;
    }

    // The camera ray through uv and its closest hit; traced: false when the camera
    // module's ray is not valid
    std::optional<Hit> cast_camera_ray(const Vec2& uv, Ray& ray, bool& traced) {
        traced = camera_ray(uv, ray);
        if (!traced) return std::nullopt;
        ++counters_.camera_rays;
        return scene_.closest_hit(modules_, ray, counters_.trace);
    }

    // Lights that reach the hit point, then the Lambert module; shadow rays only where
    // needed
    Vec3 direct_light(const Hit& hit, const Material& material) {
        visible_.clear();
        for (size_t k = 0; k < scene_.lights.size(); ++k) {
            const PointLight& light = scene_.lights[k];
            if (settings_.light_size > 0.0f) {
                area_light(hit, light, k);
                continue;
            }
            add_if_visible(hit, modules_.sample_point_light(light, hit.position));
        }
        return modules_.lambert(material.rho, material.Le, hit.ns, visible_) +
               scene_.ambient * material.rho;
    }

    // The area light that stands in for point light k (module 10): N samples, each with
    // the backfacing skip and the shadow test of a point light
    void area_light(const Hit& hit, const PointLight& light, size_t k) {
        const AreaLight area = area_light_for(light, settings_.light_size, centre_);
        const int N = settings_.light_samples;
        xi_ = modules_.light_sample_points(N, settings_.light_stratified,
                                           detail::light_rng(settings_, uv_, k));
        for (const Vec2& xi : xi_)
            add_if_visible(hit, modules_.sample_area_light(area, hit.position, xi, N));
    }

    // One light sample, point or area: a light behind the surface contributes nothing
    // and costs no shadow ray; with shadows on, the shadow module decides
    void add_if_visible(const Hit& hit, const LightSample& sample) {
        if (!(glm::dot(hit.ns, sample.wi) > 0.0f)) {
            ++counters_.backfacing;
            return;
        }
        if (!settings_.shadows) {
            ++counters_.disabled;
        } else {
            const std::uint64_t before = occluder_.shadow_rays;
            const bool blocked =
                modules_.in_shadow(occluder_, hit.position, hit.ns, sample);
            counters_.shadow_rays += occluder_.shadow_rays - before;
            if (blocked) return;
        }
        visible_.push_back(sample);
    }

    const Scene& scene_;
    const ModuleTable& modules_;
    const PinholeCamera& camera_;
    const RenderSettings& settings_;
    float depth_range_;
    Counters& counters_;
    SceneOccluder occluder_;
    std::vector<LightSample> visible_;  // reused: no allocation per pixel
    Vec3 centre_;                       // area lights face the scene's centre
    Vec2 uv_{0.0f};                     // the camera sample being shaded
    std::vector<Vec2> xi_;              // light sample points
    std::vector<CameraHits::Sample>* tile_hits_ = nullptr;     // this tile's kept hits
    const std::vector<CameraHits::Sample>* source_ = nullptr;  // hits taken in order
    size_t cursor_ = 0;                                        // the next one to take
    size_t keep_limit_ = 0;  // at most this many kept in the tile (kKeptPerPixel)
    bool reuse_ = false, keep_ = false;
    bool last_frame_ = false;  // source_ holds the last frame's hits (CameraHits)
    // The tile's camera rays traced ahead in packets (trace_ahead)
    std::vector<CameraHits::Sample> ahead_;
    std::vector<Ray> rays_;
    std::vector<size_t> slots_;
    std::vector<std::optional<Hit>> hits_;
    bool ahead_off_ = false;  // the pixel loop asked out of order: no more for this frame
};

// What CameraHits are keyed on besides the view and size: the functions that make camera
// rays and hits. An intersection module counts only where the scene has its primitives
// (a sphere module cannot change the hits of a scene without spheres), and the engine
// not at all: it gives the module path's hits bit for bit
// (tests/framework/test_engine.cpp)
std::vector<const void*> camera_hit_modules(const ModuleTable& m, const Scene& scene) {
    const auto p = [](auto f) { return reinterpret_cast<const void*>(f); };
    return {p(m.image_plane_point),
            p(m.render_tile),
            p(m.camera_frame),
            p(m.camera_constant),
            p(m.camera_ray),
            scene.planes.empty() ? nullptr : p(m.intersect_plane),
            scene.spheres.empty() ? nullptr : p(m.intersect_sphere),
            scene.triangles.empty() ? nullptr : p(m.intersect_triangle)};
}

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

}  // namespace

FrameStats render(const Scene& scene, const View& view, const RenderSettings& settings,
                  const ModuleTable& modules, Image& image) {
    validate(settings);
    const auto start = std::chrono::steady_clock::now();
    const PinholeCamera camera = make_camera(modules, view);
    const float range = depth_range(scene, view);
    if (image.width != settings.width || image.height != settings.height) {
        image = Image(settings.width, settings.height);
    } else {
        std::fill(image.pixels.begin(), image.pixels.end(), Vec3(0.0f));
    }

    // Tiles handed out by an atomic counter: threads that finish early take more
    const int tiles_x = (settings.width + kTileSize - 1) / kTileSize;
    const int tiles_y = (settings.height + kTileSize - 1) / kTileSize;
    const int tile_count = tiles_x * tiles_y;
    const int threads = std::min(thread_count(settings), tile_count);
    std::vector<Counters> counters(static_cast<size_t>(threads));
    const ImageView view_out = image.view();
    if (settings.samples_map)
        settings.samples_map->assign(size_t(settings.width) * size_t(settings.height), 1);
    // Camera hits kept from the last frame, when nothing they depend on has changed
    const bool keepable =
        !detail::supersampled(settings) &&
        std::int64_t{settings.width} * settings.height <= CameraHits::kMaxPixels;
    CameraHits* const kept = keepable ? settings.camera_hits : nullptr;
    const size_t primitives[3] = {scene.planes.size(), scene.spheres.size(),
                                  scene.triangles.size()};
    const std::vector<const void*> hit_modules =
        kept ? camera_hit_modules(modules, scene) : std::vector<const void*>{};
    bool reuse = false, keep = false;
    if (kept) {
        const bool same_key = kept->keyed && kept->width == settings.width &&
                              kept->height == settings.height && kept->view == view &&
                              std::equal(primitives, primitives + 3, kept->primitives) &&
                              kept->modules == hit_modules;
        reuse = same_key && kept->valid &&
                kept->tiles.size() == static_cast<size_t>(tile_count);
        if (!reuse) {
            // Fill the hits only when the last frame had this key (CameraHits)
            keep = same_key;
            kept->clear();
            if (keep) kept->tiles.resize(static_cast<size_t>(tile_count));
        }
    }
    // One pass over all tiles on all threads; pass(tile, radiance, shader) renders a tile
    const auto run_pass = [&](const auto& pass) {
        std::atomic<int> next{0};
        std::vector<std::exception_ptr> errors(static_cast<size_t>(threads));
        const auto work = [&](int k) {
            try {
                PixelShader shader(scene, modules, camera, settings, range, counters[k]);
                const PixelRadiance radiance = [&](const Vec2& uv) {
                    return shader.radiance(uv);
                };
                for (int t = next++; t < tile_count; t = next++) {
                    if (settings.cancel &&
                        settings.cancel->load(std::memory_order_relaxed))
                        break;
                    const int x0 = (t % tiles_x) * kTileSize;
                    const int y0 = (t / tiles_x) * kTileSize;
                    const Tile tile{x0, y0, std::min(x0 + kTileSize, settings.width),
                                    std::min(y0 + kTileSize, settings.height)};
                    if (reuse || keep)
                        shader.begin_tile(&kept->tiles[size_t(t)], reuse, keep, tile);
                    // Each tile starts without a shadow hint: which thread had the tile
                    // before must not change its work counts
                    shader.forget_blocker();
                    pass(tile, radiance, shader);
                    if (settings.tiles_done) ++*settings.tiles_done;
                }
            } catch (...) {
                errors[k] = std::current_exception();
            }
        };
        std::vector<std::thread> pool;
        for (int k = 1; k < threads; ++k)
            pool.emplace_back(work, k);
        work(0);
        for (std::thread& t : pool)
            t.join();
        for (const std::exception_ptr& e : errors) {
            if (e) std::rethrow_exception(e);
        }
    };
    const bool adaptive = settings.sampling == PixelSampling::adaptive;
    if (!detail::supersampled(settings) || adaptive) {
        // Module 01's pixel loop: one ray through each pixel centre
        run_pass(
            [&](const Tile& tile, const PixelRadiance& radiance, PixelShader& shader) {
                shader.trace_ahead(tile);
                modules.render_tile(tile, radiance, view_out);
                shader.end_tile();
            });
    } else {
        run_pass([&](const Tile& tile, const PixelRadiance& radiance, PixelShader&) {
            detail::render_tile_sampled(tile, radiance, view_out, settings, modules);
        });
    }
    if (detail::supersampled(settings) && adaptive) {
        const Image first = image;
        run_pass([&](const Tile& tile, const PixelRadiance& radiance, PixelShader&) {
            detail::refine_tile(tile, radiance, first, view_out, settings, modules);
        });
    }

    // Sum the counters
    FrameStats stats;
    stats.threads = threads;
    stats.cancelled = settings.cancel && settings.cancel->load();
    bool overflow = false;  // a tile's pixel loop asked more than it may keep
    for (const Counters& c : counters) {
        overflow |= c.hits_overflow;
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
    // The frame's key, and whether its hits are kept. A cancelled frame leaves them
    // forgotten, as its start left them (some tiles were never rendered)
    if (kept && !reuse && !stats.cancelled) {
        kept->valid = keep && !overflow;
        kept->keyed = true;
        kept->width = settings.width;
        kept->height = settings.height;
        kept->view = view;
        std::copy(primitives, primitives + 3, kept->primitives);
        kept->modules = hit_modules;
    }
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
    const PinholeCamera camera = make_camera(modules, view);
    Counters counters;
    PixelShader shader(scene, modules, camera, settings, depth_range(scene, view),
                       counters);
    PixelProbe probe;
    probe.uv = modules.image_plane_point(i, j, settings.width, settings.height);
    probe.L = shader.radiance(probe.uv, &probe.hit, &probe.ray);
    detail::probe_lights(scene, settings, modules, probe);
    return probe;
}

}  // namespace raylab
