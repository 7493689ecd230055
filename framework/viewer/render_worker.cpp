// The background renderer (viewer/render_worker.h).
#include "render_worker.h"

#include <algorithm>
#include <cmath>

#include "raylab/error.h"

namespace raylab::viewer {

namespace {

bool same_lights(const std::vector<PointLight>& a, const std::vector<PointLight>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                      [](const PointLight& x, const PointLight& y) {
                          return x.p == y.p && x.I == y.I;
                      });
}

// True when the reference of job a also serves job b
bool same_frame(const RenderJob& a, const RenderJob& b) {
    const RenderSettings &s = a.settings, &t = b.settings;
    return a.scene_version == b.scene_version && same_lights(a.lights, b.lights) &&
           a.ambient == b.ambient && a.view.eye == b.view.eye &&
           a.view.lookat == b.view.lookat && a.view.up == b.view.up &&
           a.view.fov == b.view.fov && s.width == t.width && s.height == t.height &&
           s.mode == t.mode && s.shadows == t.shadows && s.background == t.background &&
           s.spp == t.spp && s.sampling == t.sampling &&
           s.aa_threshold == t.aa_threshold && s.light_size == t.light_size &&
           s.light_samples == t.light_samples &&
           s.light_stratified == t.light_stratified && s.seed == t.seed;
}

// One sample per pixel and per light: the first pass of a sampled frame, and previews
RenderSettings first_pass(RenderSettings s) {
    s.spp = 1;
    s.light_samples = 1;
    return s;
}

bool sampled(const RenderSettings& s) {
    return s.spp > 1 || (s.light_size > 0.0f && s.light_samples > 1);
}

// The samples each pixel took as colours: dark blue for 1, through green, to red for the
// most the settings allow (log scale)
Image heat_map(const std::vector<std::uint16_t>& samples, int width, int height,
               int most) {
    Image image(width, height);
    const float top = std::log2(float(std::max(most, 2)));
    for (size_t k = 0; k < samples.size() && k < image.pixels.size(); ++k) {
        const float t =
            std::clamp(std::log2(float(std::max<int>(samples[k], 1))) / top, 0.0f, 1.0f);
        const Vec3 blue(0.02f, 0.02f, 0.3f), green(0.05f, 0.6f, 0.1f),
            red(1.0f, 0.1f, 0.02f);
        image.pixels[k] = t < 0.5f ? glm::mix(blue, green, 2.0f * t)
                                   : glm::mix(green, red, 2.0f * t - 1.0f);
    }
    return image;
}

}  // namespace

RenderWorker::RenderWorker(std::function<void()> wake)
    : wake_(std::move(wake)), thread_([this] { run(); }) {}

RenderWorker::~RenderWorker() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
        cancel_ = true;
    }
    wanted_.notify_one();
    thread_.join();
}

void RenderWorker::submit(RenderJob job) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        // A queued job that never started still owes the worker its new scene
        if (queued_ && queued_->scene && !job.scene) {
            job.scene = std::move(queued_->scene);
        }
        queued_ = std::move(job);
        if (in_flight_ && !in_flight_interactive_) cancel_ = true;
    }
    wanted_.notify_one();
}

std::optional<RenderResult> RenderWorker::take_result() {
    std::lock_guard<std::mutex> lock(mutex_);
    std::optional<RenderResult> result = std::move(finished_);
    finished_.reset();
    return result;
}

bool RenderWorker::busy() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return in_flight_ || queued_.has_value();
}

void RenderWorker::run() {
    for (;;) {
        RenderJob job;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wanted_.wait(lock, [this] { return stop_ || queued_.has_value(); });
            if (stop_) return;
            job = std::move(*queued_);
            queued_.reset();
            in_flight_ = true;
            in_flight_interactive_ = job.interactive;
            cancel_ = false;
        }
        RenderResult result = render_job(job);
        {
            std::lock_guard<std::mutex> lock(mutex_);
            in_flight_ = false;
            // A cancelled frame is incomplete: keep the previous picture instead
            result.finished = std::chrono::steady_clock::now();
            if (!result.stats.cancelled) finished_ = std::move(result);
        }
        wake_();
    }
}

RenderResult RenderWorker::render_job(RenderJob& job) {
    RenderResult result;
    result.job_id = job.id;
    result.preview = job.preview_factor > 1;
    try {
        if (job.scene) {
            scene_ = std::move(*job.scene);
            job.scene.reset();
            scene_version_ = job.scene_version;
        }
        scene_.lights = job.lights;
        scene_.ambient = job.ambient;
        RenderSettings settings = job.settings;
        settings.width = std::max(1, settings.width / job.preview_factor);
        settings.height = std::max(1, settings.height / job.preview_factor);
        settings.cancel = &cancel_;
        const ModuleTable modules = ModuleTable::make(job.modules);
        if (result.preview) settings = first_pass(settings);
        if (!result.preview && sampled(settings)) {
            // Progressive: one sample everywhere first, shown while the rest renders
            RenderResult early;
            early.job_id = job.id;
            early.preview = true;
            early.stats =
                render(scene_, job.view, first_pass(settings), modules, early.image);
            if (early.stats.cancelled) return early;
            {
                std::lock_guard<std::mutex> lock(mutex_);
                early.finished = std::chrono::steady_clock::now();
                finished_ = std::move(early);
            }
            wake_();
        }
        std::vector<std::uint16_t> samples;
        if (job.show_samples) settings.samples_map = &samples;
        result.stats = render(scene_, job.view, settings, modules, result.image);
        if (job.show_samples && !result.stats.cancelled)
            result.image =
                heat_map(samples, settings.width, settings.height, settings.spp + 1);
        if (job.compare && !result.preview && !result.stats.cancelled)
            render_reference(job, settings, result);
    } catch (const std::exception& e) {
        result.error = e.what();
        result.image = Image();
    }
    return result;
}

void RenderWorker::render_reference(const RenderJob& job, const RenderSettings& settings,
                                    RenderResult& result) {
    const ModuleSelection all = ModuleSelection::all(Impl::reference);
    if (job.modules.impl == all.impl) {
        // Nothing to compare: the frame already is the reference
        result.difference = compare_images(result.image, result.image);
        return;
    }
    if (!reference_key_ || !same_frame(*reference_key_, job)) {
        const FrameStats stats =
            render(scene_, job.view, settings, ModuleTable::make(all), reference_);
        if (stats.cancelled) {
            reference_key_.reset();
            result.stats.cancelled = true;
            return;
        }
        reference_key_ = job;
        reference_key_->scene.reset();
    }
    result.difference = compare_images(result.image, reference_);
}

}  // namespace raylab::viewer
