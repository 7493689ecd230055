// raylab/camera_hit_sources.h: where the renderer's camera hits come from, kept apart
// from how a hit is shaded (renderer.cpp). A thread's pixel loop (module 01, a student's
// with any order) asks for image-plane points; a CameraHitSource answers each with its
// camera ray's closest hit, and every source gives the same bits for the same point:
//   CastHits         casts the camera ray of each point as it is asked (every pass)
//   TracedAheadHits  traces a tile's camera rays ahead in packets, where the scene's
//                    engine does (Scene::traces_packets), and hands them out while the
//                    pixel loop asks in the reference loop's order
//   KeptHits         hands out the hits the last frame kept (CameraHits), while the
//                    pixel loop asks for the kept points in the kept order
// The two that hand out hits made before the call cast the rest of a tile once the loop
// leaves their order. A source also keeps what a frame's loop takes for the next frame
// (CameraHits): each tile's samples in the loop's order, at most kKeptPerPixel a pixel;
// KeptFrame decides from the frame's key whether a frame takes, keeps or neither.
//
// Internal to the framework (framework/internal/): the renderer and its tests use it.
#pragma once

#include <cstdint>
#include <vector>

#include "raylab/renderer.h"

namespace raylab::detail {

/// One thread's work counts, summed after the frame into FrameStats.
struct alignas(64) WorkCounters {  // one cache line each: no false sharing
    TraceCounters trace;
    std::uint64_t camera_rays = 0;
    std::uint64_t camera_rays_reused = 0;
    std::uint64_t shadow_rays = 0;
    std::uint64_t backfacing = 0;
    std::uint64_t disabled = 0;
    bool hits_overflow = false;  ///< a pixel loop asked more than it may keep
};

/// A tile keeps at most this many camera samples per pixel: a pixel loop that asks more
/// (a student's supersampling in module 01) keeps none in that frame, instead of 68 bytes
/// a call (1.1 GB at 16 a pixel in 1280 x 800).
inline constexpr size_t kKeptPerPixel = 2;

using CameraSample = CameraHits::Sample;

/// Where one thread's camera hits come from, tile by tile. Not thread-safe: one per
/// thread.
class CameraHitSource {
  public:
    virtual ~CameraHitSource() = default;
    /// Before tile's pixel loop. keep: where the samples the loop takes go, in its order
    /// (nullptr: nowhere); a loop that takes more than kKeptPerPixel a pixel stops the
    /// keeping and sets WorkCounters::hits_overflow.
    virtual void begin_tile(const Tile& tile, std::vector<CameraSample>* keep) = 0;
    /// The camera sample of uv: its hit, or traced = false when the camera module's ray
    /// is not a valid ray.
    virtual CameraSample take(const Vec2& uv) = 0;
    /// After the tile's pixel loop (not called when the loop threw).
    virtual void end_tile() = 0;
};

/// Casts each point's camera ray as the pixel loop asks for it.
class CastHits final : public CameraHitSource {
  public:
    CastHits(const Scene& scene, const ModuleTable& modules, const PinholeCamera& camera,
             WorkCounters& counters)
        : scene_(scene), modules_(modules), camera_(camera), counters_(counters) {}
    void begin_tile(const Tile& tile, std::vector<CameraSample>* keep) override;
    CameraSample take(const Vec2& uv) override { return take(uv, nullptr); }
    /// take, and the camera ray in *ray when it is valid (probe_pixel's)
    CameraSample take(const Vec2& uv, Ray* ray);
    void end_tile() override { keep_ = nullptr; }

    /// The camera module's ray through uv, its w normalised (the framework boundary,
    /// docs/style.md rule 9); false, and ray untouched, when it is not a valid ray.
    bool camera_ray(const Vec2& uv, Ray& ray) const;

  private:
    const Scene& scene_;
    const ModuleTable& modules_;
    const PinholeCamera& camera_;
    WorkCounters& counters_;
    std::vector<CameraSample>* keep_ = nullptr;  // this tile's kept samples
    size_t keep_limit_ = 0;                      // kKeptPerPixel a pixel of the tile
};

/// Traces each tile's camera rays ahead in packets of 4 x 4 pixels (Scene::closest_hits)
/// and hands them out while the pixel loop asks for the same points in the reference
/// loop's order (rows top to bottom, columns left to right); the rest of a tile is cast.
/// A tile whose loop did not take every ray in that order stops the tracing ahead for
/// the rest of the frame (this thread's tiles): its loop asks in another order.
class TracedAheadHits final : public CameraHitSource {
  public:
    TracedAheadHits(const Scene& scene, const ModuleTable& modules,
                    const PinholeCamera& camera, const RenderSettings& settings,
                    WorkCounters& counters)
        : cast_(scene, modules, camera, counters),
          scene_(scene),
          modules_(modules),
          settings_(settings),
          counters_(counters) {}
    void begin_tile(const Tile& tile, std::vector<CameraSample>* keep) override;
    CameraSample take(const Vec2& uv) override;
    void end_tile() override;

  private:
    void trace(const Tile& tile);
    void leave_order();  // keeps the samples taken in order; the rest is cast

    CastHits cast_;
    const Scene& scene_;
    const ModuleTable& modules_;
    const RenderSettings& settings_;
    WorkCounters& counters_;
    std::vector<CameraSample>* keep_ = nullptr;
    std::vector<CameraSample> ahead_;  // the tile's samples, row-major
    size_t cursor_ = 0;                // the next one to hand out
    bool traced_ = false;              // this tile was traced ahead
    bool in_order_ = false;            // the loop has asked in ahead_'s order so far
    bool off_ = false;                 // the loop asked out of order: no more ahead
    // Scratch reused from tile to tile: no allocation per tile
    std::vector<Ray> rays_;
    std::vector<size_t> slots_;
    std::vector<std::optional<Hit>> hits_;
};

/// Hands out the hits kept by the last frame (CameraHits::tiles, valid for this frame's
/// key) while the pixel loop asks for the kept points in the kept order; the rest of a
/// tile is cast. A frame that takes them keeps nothing new.
class KeptHits final : public CameraHitSource {
  public:
    KeptHits(const CameraHits& kept, const Scene& scene, const ModuleTable& modules,
             const PinholeCamera& camera, WorkCounters& counters)
        : cast_(scene, modules, camera, counters), kept_(kept), counters_(counters) {}
    void begin_tile(const Tile& tile, std::vector<CameraSample>* keep) override;
    CameraSample take(const Vec2& uv) override;
    void end_tile() override { cast_.end_tile(); }

  private:
    CastHits cast_;
    const CameraHits& kept_;
    WorkCounters& counters_;
    const std::vector<CameraSample>* tile_ = nullptr;  // the kept samples of the tile
    size_t cursor_ = 0;                                // the next one to hand out
    bool in_order_ = false;  // the loop has asked for the kept points so far
};

/// What a frame does with settings.camera_hits (CameraHits): take the last frame's hits
/// (its key is this frame's and they were all kept: KeptHits), keep its own for the next
/// (the last frame had this key: the camera has stopped), or neither. The key is noted
/// by finish(), after the frame's tiles.
class KeptFrame {
  public:
    KeptFrame(const Scene& scene, const View& view, const RenderSettings& settings,
              const ModuleTable& modules, size_t tile_count);
    /// The last frame's hits to take, or nullptr
    const CameraHits* reused() const { return reuse_ ? kept_ : nullptr; }
    /// Where tile t's samples are kept for the next frame, or nullptr
    std::vector<CameraSample>* keep(int t) const {
        return keep_ ? &kept_->tiles[size_t(t)] : nullptr;
    }
    /// Notes the frame's key, and whether its hits are kept (overflow: a tile's loop
    /// asked more than it may keep). A cancelled frame leaves them forgotten, as its
    /// start left them (some tiles were never rendered)
    void finish(bool cancelled, bool overflow);

  private:
    const View& view_;
    const RenderSettings& settings_;
    CameraHits* const kept_;
    const size_t primitives_[3];
    std::vector<const void*> modules_;
    bool reuse_ = false, keep_ = false;
};

}  // namespace raylab::detail
