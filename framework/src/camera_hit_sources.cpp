// The sources of the renderer's camera hits (raylab/camera_hit_sources.h): cast per call,
// traced ahead in packets, kept from the last frame.
#include "raylab/camera_hit_sources.h"

#include <algorithm>
#include <cmath>

#include "render_sampling.h"

namespace raylab::detail {

namespace {

size_t pixels_of(const Tile& tile) {
    return size_t(tile.x1 - tile.x0) * size_t(tile.y1 - tile.y0);
}

// What CameraHits are keyed on besides the view and size: the functions that make camera
// rays and hits. An intersection module counts only where the scene has its primitives
// (a sphere module cannot change the hits of a scene without spheres), and the engine
// not at all: it gives the module path's hits bit for bit
// (engine/tests/test_engine.cpp)
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

// One sample per pixel and at most kMaxPixels (CameraHits)
bool keepable(const RenderSettings& s) {
    return !supersampled(s) && std::int64_t{s.width} * s.height <= CameraHits::kMaxPixels;
}

}  // namespace

// ---- Cast per call --------------------------------------------------------------------

void CastHits::begin_tile(const Tile& tile, std::vector<CameraSample>* keep) {
    keep_ = keep;
    keep_limit_ = kKeptPerPixel * pixels_of(tile);
    if (keep) keep->reserve(pixels_of(tile));
}

// The module's ray is read by component: a copy of the whole would wait for the module's
// stores to finish (store-to-load forwarding fails)
bool CastHits::camera_ray(const Vec2& uv, Ray& ray) const {
    const Ray r = modules_.camera_ray(camera_, uv);
    const float len = glm::length(r.w);
    if (!(len > 0.0f && std::isfinite(len) && is_finite(r.o))) return false;
    ray.o = r.o;
    ray.w = r.w / len;
    ray.tmin = r.tmin;
    ray.tmax = r.tmax;
    return true;
}

CameraSample CastHits::take(const Vec2& uv, Ray* ray_out) {
    Ray ray;
    const bool traced = camera_ray(uv, ray);
    if (traced) ++counters_.camera_rays;
    // The hit is initialised from the query's result, not assigned: an assignment copies
    // it 16 bytes at a time while the engine's narrower stores to it are still in the
    // store buffer, which cannot forward them
    CameraSample sample{
        uv, traced,
        traced ? scene_.closest_hit(modules_, ray, counters_.trace) : std::nullopt};
    if (traced && ray_out) *ray_out = ray;
    if (keep_) {
        if (keep_->size() < keep_limit_) {
            keep_->push_back(sample);
        } else {
            keep_ = nullptr;  // this frame keeps nothing (render() sees the flag)
            counters_.hits_overflow = true;
        }
    }
    return sample;
}

// ---- Traced ahead in packets ----------------------------------------------------------

void TracedAheadHits::begin_tile(const Tile& tile, std::vector<CameraSample>* keep) {
    cast_.begin_tile(tile, keep);
    keep_ = keep;
    cursor_ = 0;
    traced_ = in_order_ = !off_;
    if (traced_) trace(tile);
}

// Row-major samples; rays gathered block by block of 4 x 4 pixels
void TracedAheadHits::trace(const Tile& tile) {
    const int W = settings_.width, H = settings_.height;
    const int tw = tile.x1 - tile.x0, th = tile.y1 - tile.y0;
    ahead_.resize(size_t(tw) * size_t(th));
    rays_.clear();
    slots_.clear();
    for (int by = 0; by < th; by += 4)
        for (int bx = 0; bx < tw; bx += 4)
            for (int y = by; y < std::min(by + 4, th); ++y)
                for (int x = bx; x < std::min(bx + 4, tw); ++x) {
                    const size_t slot = size_t(y) * size_t(tw) + size_t(x);
                    CameraSample& s = ahead_[slot];
                    s.uv = modules_.image_plane_point(tile.x0 + x, tile.y0 + y, W, H);
                    // Made in place: a Ray written by field and then copied whole
                    // stalls on the copy (store-to-load forwarding fails)
                    s.traced = cast_.camera_ray(s.uv, rays_.emplace_back());
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
}

CameraSample TracedAheadHits::take(const Vec2& uv) {
    if (in_order_) {
        if (cursor_ < ahead_.size() && ahead_[cursor_].uv == uv) return ahead_[cursor_++];
        leave_order();
    }
    return cast_.take(uv);
}

// The samples taken in order are kept all at once, here or at end_tile
void TracedAheadHits::leave_order() {
    if (keep_)
        keep_->insert(keep_->end(), ahead_.begin(),
                      ahead_.begin() + static_cast<std::ptrdiff_t>(cursor_));
    in_order_ = false;
}

// A loop that took every sample in order gives them all to the kept array by a swap (no
// copy, and the array's memory goes round for the next tile)
void TracedAheadHits::end_tile() {
    if (traced_) {
        if (cursor_ != ahead_.size()) off_ = true;
        if (in_order_ && keep_) {
            if (cursor_ == ahead_.size()) {
                keep_->swap(ahead_);
            } else {
                leave_order();
            }
        }
    }
    traced_ = in_order_ = false;
    keep_ = nullptr;
    cast_.end_tile();
}

// ---- Kept from the last frame ---------------------------------------------------------

void KeptHits::begin_tile(const Tile& tile, std::vector<CameraSample>* keep) {
    cast_.begin_tile(tile, keep);
    const int tiles_x = (kept_.width + kTileSize - 1) / kTileSize;
    tile_ = &kept_.tiles[size_t(tile.y0 / kTileSize) * size_t(tiles_x) +
                         size_t(tile.x0 / kTileSize)];
    cursor_ = 0;
    in_order_ = true;
}

CameraSample KeptHits::take(const Vec2& uv) {
    if (in_order_) {
        if (cursor_ < tile_->size() && (*tile_)[cursor_].uv == uv) {
            // (a point whose camera ray was not valid was not a ray)
            if ((*tile_)[cursor_].traced) ++counters_.camera_rays_reused;
            return (*tile_)[cursor_++];
        }
        in_order_ = false;
    }
    return cast_.take(uv);
}

// ---- The frame's key ------------------------------------------------------------------

KeptFrame::KeptFrame(const Scene& scene, const View& view, const RenderSettings& settings,
                     const ModuleTable& modules, size_t tile_count)
    : view_(view),
      settings_(settings),
      kept_(keepable(settings) ? settings.camera_hits : nullptr),
      primitives_{scene.planes.size(), scene.spheres.size(), scene.triangles.size()} {
    if (!kept_) return;
    modules_ = camera_hit_modules(modules, scene);
    const bool same_key = kept_->keyed && kept_->width == settings.width &&
                          kept_->height == settings.height && kept_->view == view &&
                          std::equal(primitives_, primitives_ + 3, kept_->primitives) &&
                          kept_->modules == modules_;
    reuse_ = same_key && kept_->valid && kept_->tiles.size() == tile_count;
    if (reuse_) return;
    keep_ = same_key;
    kept_->clear();
    if (keep_) kept_->tiles.resize(tile_count);
}

void KeptFrame::finish(bool cancelled, bool overflow) {
    if (!kept_ || reuse_ || cancelled) return;
    kept_->valid = keep_ && !overflow;
    kept_->keyed = true;
    kept_->width = settings_.width;
    kept_->height = settings_.height;
    kept_->view = view_;
    std::copy(primitives_, primitives_ + 3, kept_->primitives);
    kept_->modules = modules_;
}

}  // namespace raylab::detail
