// The background renderer (viewer/render_worker.h).
#include "render_worker.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "raylab/error.h"

namespace raylab::viewer {

namespace {

bool same_lights(const std::vector<PointLight>& a, const std::vector<PointLight>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                      [](const PointLight& x, const PointLight& y) {
                          return x.p == y.p && x.I == y.I;
                      });
}

// A field added to these must be compared below, or a kept frame would answer for a job
// that differs in it (sizes with 64-bit pointers). Not compared, because they are not
// inputs of the image: cancel, tiles_done, samples_map (heat map: show_samples),
// camera_hits
static_assert(sizeof(void*) != 8 || (sizeof(RenderSettings) == 96 && sizeof(View) == 40 &&
                                     sizeof(PointLight) == 24),
              "a new field in RenderSettings, View or PointLight: compare it in "
              "same_frame (viewer/render_worker.cpp; View: its operator== in "
              "raylab/scene.h), then update these sizes");

// True when the reference of job a also serves job b
bool same_frame(const RenderJob& a, const RenderJob& b) {
    const RenderSettings &s = a.settings, &t = b.settings;
    return a.scene_version == b.scene_version && same_lights(a.lights, b.lights) &&
           a.ambient == b.ambient && a.view == b.view && s.width == t.width &&
           s.height == t.height && s.mode == t.mode && s.shadows == t.shadows &&
           s.background == t.background && s.spp == t.spp && s.sampling == t.sampling &&
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

namespace {

// The settings of a preview at factor: width / factor x height / factor, one sample
RenderSettings preview_settings(const RenderSettings& full, int factor) {
    RenderSettings s = first_pass(full);
    s.width = std::max(1, full.width / factor);
    s.height = std::max(1, full.height / factor);
    return s;
}

// The tiles of a that differ from b in any pixel (same size), in the renderer's tiles
int changed_tiles(const Image& a, const Image& b, int& total) {
    const int tiles_x = (a.width + kTileSize - 1) / kTileSize;
    const int tiles_y = (a.height + kTileSize - 1) / kTileSize;
    total = tiles_x * tiles_y;
    std::vector<char> changed(static_cast<size_t>(total), 0);
    for (int j = 0; j < a.height; ++j) {
        const Vec3* ra = &a.pixels[size_t(j) * size_t(a.width)];
        const Vec3* rb = &b.pixels[size_t(j) * size_t(b.width)];
        char* row = &changed[size_t(j / kTileSize) * size_t(tiles_x)];
        for (int tx = 0; tx < tiles_x; ++tx) {
            if (row[tx]) continue;
            const int i0 = tx * kTileSize, n = std::min(kTileSize, a.width - i0);
            row[tx] = std::memcmp(ra + i0, rb + i0, sizeof(Vec3) * size_t(n)) != 0;
        }
    }
    return int(std::count(changed.begin(), changed.end(), 1));
}

constexpr size_t kKeptFrames = 6;         // the full frames the worker keeps
constexpr size_t kKeptBytes = 96u << 20;  // and at most this much of them (1080p: 3)

}  // namespace

bool same_inputs(const RenderJob& a, const RenderJob& b) {
    return same_frame(a, b) && a.settings.threads == b.settings.threads &&
           a.modules.impl == b.modules.impl && a.show_samples == b.show_samples;
}

const KeptFrame* RenderWorker::find_kept(const RenderJob& job) const {
    for (const KeptFrame& k : kept_) {
        if (same_inputs(k.job, job)) return &k;
    }
    return nullptr;
}

void RenderWorker::keep(const RenderJob& job, std::shared_ptr<const Image> image,
                        const FrameStats& stats) {
    KeptFrame frame{job, std::move(image), stats};
    frame.job.scene.reset();
    kept_.insert(kept_.begin(), std::move(frame));
    // Oldest out first, above the count or the bytes (the newest always stays)
    size_t bytes = 0, n = 0;
    while (n < kept_.size() && n < kKeptFrames) {
        bytes += kept_[n].image->pixels.size() * sizeof(Vec3);
        if (n > 0 && bytes > kKeptBytes) break;
        ++n;
    }
    kept_.resize(n);
}

void RenderWorker::post(RenderResult result) {
    result.finished = std::chrono::steady_clock::now();
    {
        std::lock_guard<std::mutex> lock(mutex_);
        finished_ = std::move(result);
    }
    wake_();
}

bool RenderWorker::preview(const RenderJob& job, const RenderSettings& settings,
                           const ModuleTable& modules, int factor) {
    RenderResult early;
    early.job_id = job.id;
    early.preview = true;
    early.factor = factor;
    auto image = std::make_shared<Image>();
    early.stats =
        render(scene_, job.view, preview_settings(settings, factor), modules, *image);
    if (early.stats.cancelled) return false;
    early.image = std::move(image);
    post(std::move(early));
    return true;
}

void RenderWorker::render_full(const RenderJob& job, RenderSettings settings,
                               const ModuleTable& modules, RenderResult& result) {
    // A slow frame starts coarse, coarsest first; a sampled one with one sample per
    // pixel at full size, shown while the rest renders
    for (const int factor : job.coarse) {
        if (!preview(job, settings, modules, factor)) {
            result.stats.cancelled = true;
            return;
        }
    }
    if (sampled(settings) && !preview(job, settings, modules, 1)) {
        result.stats.cancelled = true;
        return;
    }
    std::vector<std::uint16_t> samples;
    if (job.show_samples) settings.samples_map = &samples;
    // A change after the hit (a light, ambient, shadows, shading) shades the camera hits
    // of the last full frame instead of casting them again (the renderer checks the
    // rest). A job that must render (--repeat) casts them afresh: its time is a full
    // frame's
    settings.camera_hits = &camera_hits_;
    if (!job.reuse) camera_hits_.clear();
    auto image = std::make_shared<Image>();
    result.stats = render(scene_, job.view, settings, modules, *image);
    if (result.stats.cancelled) return;
    if (job.show_samples)
        *image = heat_map(samples, settings.width, settings.height, settings.spp + 1);
    if (previous_ && previous_->width == image->width &&
        previous_->height == image->height)
        result.tiles_changed = changed_tiles(*image, *previous_, result.tiles_total);
    result.image = std::move(image);
    keep(job, result.image, result.stats);
}

RenderResult RenderWorker::render_job(RenderJob& job) {
    RenderResult result;
    result.job_id = job.id;
    result.preview = job.preview_factor > 1;
    result.factor = std::max(1, job.preview_factor);
    try {
        if (job.scene) {
            scene_ = std::move(*job.scene);
            job.scene.reset();
            scene_version_ = job.scene_version;
            kept_.clear();  // (the version tells scenes apart; this frees memory early)
            camera_hits_.clear();  // new geometry: no kept camera hit holds
        }
        scene_.lights = job.lights;
        scene_.ambient = job.ambient;
        RenderSettings settings = job.settings;
        settings.cancel = &cancel_;
        const ModuleTable modules = ModuleTable::make(job.modules);
        if (result.preview) {
            auto image = std::make_shared<Image>();
            result.stats =
                render(scene_, job.view, preview_settings(settings, result.factor),
                       modules, *image);
            result.image = std::move(image);
            return result;
        }
        if (const KeptFrame* kept = job.reuse ? find_kept(job) : nullptr) {
            // The same inputs as a kept frame: no render at all
            result.image = kept->image;
            result.stats = kept->stats;
            result.reused = true;
        } else {
            render_full(job, settings, modules, result);
            if (result.stats.cancelled) return result;
        }
        previous_ = result.image;
        if (job.compare) render_reference(job, job.settings, result);
    } catch (const std::exception& e) {
        result.error = e.what();
        result.image.reset();
    }
    return result;
}

void RenderWorker::render_reference(const RenderJob& job, const RenderSettings& settings,
                                    RenderResult& result) {
    const ModuleSelection all = ModuleSelection::all(Impl::reference);
    if (job.modules.impl == all.impl) {
        // Nothing to compare: the frame already is the reference
        result.difference = compare_images(*result.image, *result.image);
        return;
    }
    // The reference frame is a frame like any other: kept, and found again
    RenderJob reference = job;
    reference.scene.reset();
    reference.modules = all;
    reference.show_samples = false;
    if (!find_kept(reference)) {
        RenderSettings s = settings;
        s.cancel = &cancel_;
        auto image = std::make_shared<Image>();
        const FrameStats stats =
            render(scene_, job.view, s, ModuleTable::make(all), *image);
        if (stats.cancelled) {
            result.stats.cancelled = true;
            return;
        }
        keep(reference, std::move(image), stats);
    }
    result.difference = compare_images(*result.image, *find_kept(reference)->image);
}

}  // namespace raylab::viewer
