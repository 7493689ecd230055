// Scene loading for the viewer: the command line's scene, built-in scenes at once, OBJ
// files in the background with progress and cancel (viewer/actions.h).
#include <algorithm>
#include <chrono>
#include <cstdio>

#include "actions.h"
#include "raylab/error.h"
#include "raylab/input_checks.h"
#include "raylab/input_file.h"
#include "raylab/scenes.h"
#include "view_file.h"

namespace raylab::viewer {

namespace {

std::string scene_summary(const Scene& s) {
    return s.name + ": " + std::to_string(s.triangles.size()) + " triangles, " +
           std::to_string(s.spheres.size()) + " spheres, " +
           std::to_string(s.planes.size()) + " planes, " +
           std::to_string(s.lights.size()) + " lights";
}

void set_scene(Viewer& v, Scene scene, const std::string& source) {
    ViewerState& s = v.state;
    s.scene = std::move(scene);
    s.scene_source = source;
    ++s.scene_version;
    s.view = s.scene.view;
    s.selected_light = 0;
    s.dirty = true;
    v.panel.view_edit = s.view;
    v.panel.view_error.clear();
    v.panel.error.clear();
    v.inspector.pinned = false;
    v.log.add("scene " + scene_summary(s.scene));
}

// The loading thread's progress and warnings go to the status the UI reads
LoadProgress progress_of(const std::shared_ptr<LoadStatus>& status,
                         const std::function<void()>& wake) {
    LoadProgress p;
    p.cancel = &status->cancel;
    p.report = [status, wake](const char* stage, float fraction) {
        status->stage.store(stage);
        status->fraction.store(fraction);
        if (wake) wake();  // the UI sleeps until an event: show the new fraction
    };
    p.warn = [](const std::string& message) {
        std::fprintf(stderr, "raylab: warning: %s\n", message.c_str());
    };
    return p;
}

// Starts loading options.scene (with the flags' view and lights) in the background
void start_loading(Viewer& v, const Options& options, bool initial,
                   std::optional<ViewFile> view) {
    auto status = std::make_shared<LoadStatus>();
    status->initial = initial;
    status->view = std::move(view);
    v.load_status = status;
    v.loading_source = options.scene;
    v.log.add("loading " + options.scene + " ...");
    v.loading = std::async(std::launch::async, [options, status, wake = v.wake] {
        return make_scene(options, progress_of(status, wake));
    });
}

}  // namespace

void init_viewer(Viewer& v, const Options& options, const ViewerOptions& viewer_options,
                 std::function<void()> wake) {
    v.options = viewer_options;
    v.wake = wake;
    ViewerState& s = v.state;
    // A built-in scene at once; an OBJ in the background, so the window opens first and
    // shows its progress. A file that cannot be opened is an error before the window.
    std::optional<ViewFile> view;
    if (!viewer_options.load_view.empty())
        view = load_view_file(viewer_options.load_view);
    const auto& names = builtin_scene_names();
    const bool builtin =
        std::find(names.begin(), names.end(), options.scene) != names.end();
    if (builtin) {
        s.scene = make_scene(options);
    } else {
        check_input_file(options.scene, kMaxObjBytes);
        s.scene = cornell_box();  // shown under the progress bar until the model is in
        s.scene.lights.clear();
        s.scene.triangles.clear();
        s.scene.commit();
    }
    s.scene_source = options.scene;
    s.view = s.scene.view;
    s.settings = options.settings;
    s.exposure = options.exposure;
    v.frames.repeat = options.repeat;
    s.modules = options.modules;
    s.stubs = detect_stubs();  // before the worker runs student code
    s.image_scale = viewer_options.image_scale;
    if (viewer_options.compare && !reference_available())
        throw Error("--compare needs the reference solutions, and this build has none");
    s.compare = viewer_options.compare;
    s.show_samples = viewer_options.show_samples;
    if (view && builtin) {
        s.view = view->view;
        s.scene.lights = view->lights;
        view->apply_to(s.settings);
    }
    v.panel.view_edit = s.view;
    v.panel.size_edit[0] = s.settings.width;
    v.panel.size_edit[1] = s.settings.height;
    v.panel.report_dir = default_report_dir();
    for (size_t k = 0; k < names.size(); ++k) {
        if (names[k] == options.scene) v.panel.scene_choice = int(k);
    }
    v.grading_binary = find_grading_binary(v.exe_path);
    if (builtin) v.log.add("scene " + scene_summary(s.scene));
    v.log.add("modules: " + describe(s.modules));
    v.worker = std::make_unique<RenderWorker>(wake);
    v.grading = std::make_unique<GradingRun>(wake);
    if (!builtin) start_loading(v, options, true, std::move(view));
}

void start_loading_scene(Viewer& v, const std::string& source) {
    if (v.loading.valid()) {
        report_error(v,
                     "still loading " + v.loading_source + "; try again when it is done");
        return;
    }
    const auto& names = builtin_scene_names();
    if (std::find(names.begin(), names.end(), source) != names.end()) {
        set_scene(v, load_scene(source), source);
        return;
    }
    Options options;
    options.scene = source;
    start_loading(v, options, false, std::nullopt);
}

std::string loading_text(const Viewer& v) {
    if (!v.loading.valid() || !v.load_status) return "";
    char text[64];
    std::snprintf(text, sizeof text, "%s %.0f%%", v.load_status->stage.load(),
                  100.0 * v.load_status->fraction.load());
    return "loading " + v.loading_source + ": " + text;
}

void cancel_loading(Viewer& v) {
    if (v.load_status) v.load_status->cancel.store(true);
}

bool finish_loading(Viewer& v) {
    if (!v.loading.valid() ||
        v.loading.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
        return true;
    const std::shared_ptr<LoadStatus> status = std::move(v.load_status);
    try {
        set_scene(v, v.loading.get(), v.loading_source);
        if (status && status->view) {
            v.state.view = status->view->view;
            v.state.scene.lights = status->view->lights;
            status->view->apply_to(v.state.settings);
            v.panel.view_edit = v.state.view;
        }
        return true;
    } catch (const LoadCancelled&) {
        v.log.add("loading " + v.loading_source + " cancelled");
        return true;
    } catch (const std::exception& e) {
        // The command line's scene failed: the window shows an empty scene (one message)
        // and a scripted run ends with exit code 2
        const bool initial = status && status->initial;
        v.initial_scene_failed = v.initial_scene_failed || initial;
        report_error(v, initial ? std::string(e.what())
                                : std::string(e.what()) + " (still showing " +
                                      printable(v.state.scene_source) + ")");
        return !(initial && v.options.frames > 0);
    }
}

}  // namespace raylab::viewer
