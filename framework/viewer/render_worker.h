// viewer/render_worker.h: renders in the background so that the window never freezes.
//
// The main thread submits jobs; the worker renders the newest one and hands back the
// result, then calls wake() (the viewer posts an empty GLFW event, so a main loop that
// sleeps in glfwWaitEvents draws it). A new job cancels a settled render in flight (the
// renderer stops after its tiles in flight); an interactive one (a preview while a value
// is dragged) is allowed to finish, so that a continuous drag still shows pictures.
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
};

struct RenderResult {
    std::uint64_t job_id = 0;
    bool preview = false;
    Image image;
    FrameStats stats;
    std::optional<Difference> difference;  ///< with compare, for full frames
    std::string error;                     ///< not empty: the frame failed, image empty
    std::chrono::steady_clock::time_point finished;  ///< when the worker handed it over
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
    Image reference_;                         // the cached full reference image
    std::optional<RenderJob> reference_key_;  // the frame it shows
    std::thread thread_;  // last: starts after the members above exist
};

}  // namespace raylab::viewer
