// viewer/render_worker.h: renders in the background so that the window never freezes.
//
// The main thread submits jobs; the worker renders the newest one and hands back the
// result, then calls wake() (the viewer posts an empty GLFW event, so a main loop that
// sleeps in glfwWaitEvents draws it). A new job cancels a settled render in flight (the
// renderer stops after its tiles in flight); an interactive one (a preview while a value
// is dragged) is allowed to finish, so that a continuous drag still shows pictures.
//
// Work that is not needed is skipped: the worker keeps its last few full frames, and a
// job with the same inputs as one of them (a module switched back, shadows off and on
// again, compare turned off) gets that frame back without a render. A slow frame can
// start coarse (RenderJob::coarse) and refine.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "compare.h"
#include "raylab/renderer.h"
#include "raylab/scene.h"

namespace raylab::viewer {

/// What to render. The scene's lights and ambient are taken from the job, not the scene.
struct RenderJob {
    std::uint64_t id = 0;
    /// A new scene (geometry) for the worker to keep; null: the previous one.
    std::shared_ptr<Scene> scene;
    std::uint64_t scene_version = 0;  ///< the geometry's version, for the reference cache
    std::vector<PointLight> lights;
    float ambient = 0.0f;
    View view;
    RenderSettings settings;  ///< full size; a preview divides it by preview_factor
    ModuleSelection modules;
    int preview_factor = 1;  ///< > 1: a coarse preview, width / factor x height / factor
    bool interactive = false;  ///< a value is being dragged: never cancelled (see above)
    bool compare = false;      ///< also render the full reference and compare (full only)
    bool show_samples = false;  ///< show the samples each pixel took (heat map)
    bool reuse = true;  ///< a kept frame with the same inputs may answer (not --repeat)
    /// Before the full frame, previews at these factors, coarsest first (e.g. 8, 2).
    std::vector<int> coarse;
};

/// True when jobs a and b give the same image: scene, lights, view, settings (threads
/// too), modules and heat map. preview_factor, compare and the flags do not count.
bool same_inputs(const RenderJob& a, const RenderJob& b);

struct RenderResult {
    std::uint64_t job_id = 0;
    bool preview = false;
    int factor = 1;       ///< a preview's factor (1: full size)
    bool reused = false;  ///< a kept frame with the same inputs, not rendered again
    /// Full frames: the 16 x 16 tiles that differ from the previous full frame of the
    /// same size (-1: none to compare with), of tiles_total
    int tiles_changed = -1;
    int tiles_total = 0;
    std::shared_ptr<const Image> image;  ///< shared with the worker's kept frames
    FrameStats stats;
    std::optional<Difference> difference;  ///< with compare, for full frames
    std::string error;                     ///< not empty: the frame failed, image empty
    std::chrono::steady_clock::time_point finished;  ///< when the worker handed it over
};

/// A full frame the worker keeps, with the job that made it (its scene pointer empty).
struct KeptFrame {
    RenderJob job;
    std::shared_ptr<const Image> image;
    FrameStats stats;
};

class RenderWorker {
  public:
    explicit RenderWorker(std::function<void()> wake);
    ~RenderWorker();
    RenderWorker(const RenderWorker&) = delete;
    RenderWorker& operator=(const RenderWorker&) = delete;

    /// Queues job, replacing a queued one that has not started.
    void submit(RenderJob job);
    /// The newest finished result, once; older unread results are dropped.
    std::optional<RenderResult> take_result();
    /// True while a job is queued or being rendered.
    bool busy() const;

  private:
    void run();
    RenderResult render_job(RenderJob& job);
    void render_reference(const RenderJob& job, const RenderSettings& settings,
                          RenderResult& result);
    void post(RenderResult result);  // hands over a preview while the job goes on
    // Renders job's preview at factor (1: full size, one sample) and posts it; false
    // when a newer job cancelled it
    bool preview(const RenderJob& job, const RenderSettings& settings,
                 const ModuleTable& modules, int factor);
    // The full frame with its previews first; result.stats.cancelled when cancelled
    void render_full(const RenderJob& job, RenderSettings settings,
                     const ModuleTable& modules, RenderResult& result);
    const KeptFrame* find_kept(const RenderJob& job) const;
    void keep(const RenderJob& job, std::shared_ptr<const Image> image,
              const FrameStats& stats);

    std::function<void()> wake_;
    mutable std::mutex mutex_;
    std::condition_variable wanted_;
    std::optional<RenderJob> queued_;
    std::optional<RenderResult> finished_;
    bool in_flight_ = false;
    bool in_flight_interactive_ = false;
    bool stop_ = false;
    std::atomic<bool> cancel_{false};

    // Owned by the worker thread
    Scene scene_;
    std::uint64_t scene_version_ = 0;
    std::vector<KeptFrame> kept_;            // the last full frames, newest first
    std::shared_ptr<const Image> previous_;  // the last full frame (tiles_changed)
    CameraHits camera_hits_;  // the last full frame's camera hits (raylab/renderer.h)
    std::thread thread_;      // last: starts after the members above exist
};

}  // namespace raylab::viewer
