// The panel's actions and the scripted runs' steps (viewer/actions.h).
#include "actions.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "raylab/error.h"
#include "raylab/input_checks.h"
#include "raylab/input_file.h"
#include "raylab/scenes.h"
#include "view_file.h"

namespace raylab::viewer {

namespace {

std::string fmt(const char* format, double a, double b = 0.0, double c = 0.0) {
    char text[256];
    std::snprintf(text, sizeof text, format, a, b, c);
    return text;
}

}  // namespace

std::string view_line(const View& view) {
    const auto t = [](const Vec3& p) { return fmt("%.6g,%.6g,%.6g", p.x, p.y, p.z); };
    return "eye " + t(view.eye) + " lookat " + t(view.lookat) + " up " + t(view.up) +
           " fov " + fmt("%.6g", view.fov);
}

int preview_factor(double full_ms) {
    if (!(full_ms > 25.0)) return 1;
    return std::clamp(static_cast<int>(std::ceil(std::sqrt(full_ms / 25.0))), 2, 8);
}

std::vector<int> coarse_levels(const FrameState& f, const RenderJob& job) {
    if (job.preview_factor > 1 || !f.have_full) return {};
    const int factor = preview_factor(f.last_full.milliseconds);
    if (factor < 3) return {};  // a full frame near preview speed needs no preview
    std::vector<int> levels{factor};
    if (factor >= 4) levels.push_back(2);
    // A drag that just ended left a preview of these inputs: start finer than it
    if (f.sent.preview_factor > 1 && same_inputs(f.sent, job)) {
        levels.erase(std::remove_if(levels.begin(), levels.end(),
                                    [&](int k) { return k >= f.sent.preview_factor; }),
                     levels.end());
    }
    return levels;
}

void report_error(Viewer& v, const std::string& raw) {
    const std::string message = printable(raw, 4 * raw.size() + 1);
    v.panel.error = message;
    v.log.add("error: " + message);
    std::fprintf(stderr, "raylab: error: %s\n", message.c_str());
}

bool apply_view(Viewer& v, const View& view) {
    try {
        check_view(view, "camera");
    } catch (const Error& e) {
        v.panel.view_error = std::string("not applied: ") + e.what();
        return false;
    }
    v.panel.view_error.clear();
    v.state.view = view;
    v.state.dirty = true;
    return true;
}

bool load_view(Viewer& v, const std::string& path) {
    try {
        const ViewFile file = load_view_file(path);
        v.state.view = file.view;
        v.state.scene.lights = file.lights;
        file.apply_to(v.state.settings);
        v.state.selected_light = 0;
        v.state.dirty = true;
        v.panel.view_edit = file.view;
        v.panel.view_error.clear();
        v.panel.error.clear();
        v.log.add("loaded view " + path + ": " + view_line(file.view) + ", " +
                  std::to_string(file.lights.size()) + " lights");
        return true;
    } catch (const std::exception& e) {
        report_error(v, e.what());
        return false;
    }
}

bool save_view(Viewer& v, const std::string& path) {
    try {
        save_view_file(path, v.state.view, v.state.scene.lights, &v.state.settings);
        v.log.add("saved view " + path + ": " + view_line(v.state.view));
        return true;
    } catch (const std::exception& e) {
        report_error(v, e.what());
        return false;
    }
}

bool save_image(Viewer& v, const std::string& path) {
    if (!v.frames.have_full) {
        report_error(v, "no full image rendered yet: nothing to save");
        return false;
    }
    try {
        write_image(path, *v.frames.full, v.state.exposure);
        v.log.add("saved image " + path);
        return true;
    } catch (const std::exception& e) {
        report_error(v, e.what());
        return false;
    }
}

ReportInput report_input(const Viewer& v) {
    ReportInput in;
    in.scene_source = v.state.scene_source;
    in.view = v.state.view;
    in.lights = v.state.scene.lights;
    in.ambient = v.state.scene.ambient;
    in.settings = v.state.settings;
    in.exposure = v.state.exposure;
    in.modules = v.state.modules;
    in.stats = v.frames.last_full;
    in.image = v.frames.have_full ? v.frames.full.get() : nullptr;
    in.grades = grades_text(v);
    in.log = v.log.text();
    return in;
}

bool save_report(Viewer& v, const std::string& dir) {
    try {
        write_report(dir, report_input(v));
        v.log.add("saved report " + dir +
                  "/ (view.txt, settings.txt, image.png, log.txt)");
        return true;
    } catch (const std::exception& e) {
        report_error(v, e.what());
        return false;
    }
}

void run_tests(Viewer& v) {
    if (v.grading_binary.empty()) {
        report_error(
            v,
            "no scripts/grade.sh in the source tree of this build (set "
            "RAYLAB_GRADING_TESTS to a raylab-grading-tests binary to grade with it)");
        return;
    }
    if (v.grading->running()) return;
    v.log.add("running the graders of every module: " + v.grading_binary);
    v.grading->start(v.grading_binary);
    v.grading_logged = false;
}

void poll_grading(Viewer& v) {
    if (v.grading_logged || v.grading->running()) return;
    v.grading_logged = true;
    v.log.add("graders of the student's code (exercises/):\n" + grades_text(v));
    // The driver's own table, as `./scripts/dev.sh grade` prints it
    if (const std::string table = grades_table(v.grading->grades()); !table.empty())
        v.log.add(table);
}

std::string grades_text(const Viewer& v) {
    if (!v.grading) return "";
    const auto grades = v.grading->grades();
    std::string text;
    for (const ModuleInfo& info : module_infos()) {
        const ModuleGrade& g = grades[static_cast<int>(info.module)];
        if (g.status == ModuleGrade::Status::not_run) continue;
        char line[160];
        std::snprintf(line, sizeof line, "  %-15s %-28s (the viewer runs the %s)\n",
                      info.id, g.summary.c_str(),
                      v.state.modules[info.module] == Impl::student ? "student's code"
                                                                    : "reference");
        text += line;
    }
    return text;
}

void submit_if_dirty(Viewer& v) {
    ViewerState& s = v.state;
    if (!s.dirty) return;
    RenderJob job;
    job.id = v.frames.next_job++;
    if (s.sent_version != s.scene_version) {
        job.scene = std::make_shared<Scene>(s.scene);  // the worker's own copy
        s.sent_version = s.scene_version;
    }
    job.scene_version = s.scene_version;
    job.lights = s.scene.lights;
    job.ambient = s.scene.ambient;
    job.view = s.view;
    job.settings = s.settings;
    job.modules = s.modules;
    job.compare = s.compare;
    job.show_samples = s.show_samples;
    job.interactive = s.interacting;
    job.preview_factor =
        s.interacting ? preview_factor(v.frames.last_full.milliseconds) : 1;
    job.reuse = !s.force_render;
    job.coarse = coarse_levels(v.frames, job);
    v.frames.sent = job;
    v.frames.sent.scene.reset();
    v.frames.last_job = job.id;
    v.frames.last_job_preview = job.preview_factor > 1;
    v.frames.submitted = std::chrono::steady_clock::now();
    s.force_render = false;
    v.worker->submit(std::move(job));
    s.dirty = false;
}

bool take_result(Viewer& v) {
    std::optional<RenderResult> r = v.worker->take_result();
    if (!r) return false;
    FrameState& f = v.frames;
    f.failed = !r->error.empty();
    if (f.failed) {
        report_error(v, "render failed: " + r->error);
        return true;
    }
    f.history_ms.push_back(r->reused ? 0.0f : static_cast<float>(r->stats.milliseconds));
    if (f.history_ms.size() > 240) f.history_ms.erase(f.history_ms.begin());
    f.shown = std::move(r->image);
    f.shown_preview = r->preview;
    f.shown_factor = r->factor;
    f.shown_job = r->job_id;
    f.last = r->stats;
    v.state.retone = true;
    if (r->preview) return true;
    f.full = f.shown;
    f.have_full = true;
    f.last_full = r->stats;
    f.difference = std::move(r->difference);
    ++f.full_frames;
    ++(r->reused ? f.frames_reused : f.frames_rendered);
    f.last_reused = r->reused;
    if (!r->reused) {
        f.tiles_changed = r->tiles_changed;
        f.tiles_total = r->tiles_total;
    }
    f.on_screen_pending = r->job_id == f.last_job;
    f.finished = r->finished;
    f.taken = std::chrono::steady_clock::now();  // timed at the swap (frame_shown)
    const FrameStats& st = r->stats;
    const std::string what = std::to_string(f.full->width) + "x" +
                             std::to_string(f.full->height) + " (" +
                             to_string(v.state.settings.mode) + ", shadows " +
                             (v.state.settings.shadows ? "on" : "off") + ")";
    std::string line =
        r->reused ? "reused " + what +
                        fmt(": the same inputs as a kept frame, no render (it took "
                            "%.2f ms)",
                            st.milliseconds)
                  : "rendered " + what + " in " +
                        fmt("%.2f ms on %.0f threads: %.2f Mrays/s", st.milliseconds,
                            st.threads, st.rays_per_second() * 1e-6);
    if (!r->reused && st.camera_rays_reused > 0) {
        line += fmt("; camera hits reused: %.0f", double(st.camera_rays_reused));
    }
    if (f.difference) {
        line += fmt("; vs reference: RMSE %.3g, max error %.3g", f.difference->rmse,
                    f.difference->max_error);
    }
    v.log.add(line);
    if (st.non_finite_pixels > 0) {
        report_error(v, std::to_string(st.non_finite_pixels) +
                            " pixels are NaN or infinite (shown black): a module "
                            "returned an invalid value");
    }
    return true;
}

namespace {

double median(std::vector<double> x) {
    std::sort(x.begin(), x.end());
    return x.empty() ? 0.0 : x[x.size() / 2];
}

}  // namespace

void frame_shown(Viewer& v) {
    FrameState& f = v.frames;
    if (!f.on_screen_pending) return;
    f.on_screen_pending = false;
    f.latency_ms = std::chrono::duration<double, std::milli>(
                       std::chrono::steady_clock::now() - f.submitted)
                       .count();
    if (f.repeat <= 1 || repeat_done(v)) return;
    f.repeat_render_ms.push_back(f.last_full.milliseconds);
    f.repeat_latency_ms.push_back(f.latency_ms);
    if (!repeat_done(v)) {
        v.state.dirty = true;  // the same inputs again
        v.state.force_render = true;
        return;
    }
    v.log.add(
        fmt("--repeat: %.0f full frames, render time median %.2f ms, change to "
            "screen median %.2f ms",
            double(f.repeat), median(f.repeat_render_ms), median(f.repeat_latency_ms)));
}

bool repeat_done(const Viewer& v) {
    return v.frames.repeat <= 1 ||
           int(v.frames.repeat_render_ms.size()) >= v.frames.repeat;
}

namespace {

// Probes pixel (i, j) into report unless it already holds that pixel of the newest frame
void probe_into(const Viewer& v, int i, int j, PixelReport& report) {
    if (report.i == i && report.j == j && report.job == v.frames.last_job) return;
    report.i = i, report.j = j, report.job = v.frames.last_job;
    report.probe.reset();
    report.reference.reset();
    try {
        const ViewerState& s = v.state;
        report.probe =
            probe_pixel(s.scene, s.view, s.settings, ModuleTable::make(s.modules), i, j);
        const ModuleSelection all = ModuleSelection::all(Impl::reference);
        if (reference_available() && s.modules.impl != all.impl) {
            report.reference =
                probe_pixel(s.scene, s.view, s.settings, ModuleTable::make(all), i, j);
        }
    } catch (const std::exception&) {
        report.probe.reset();  // e.g. the size changed under the mouse: nothing to show
    }
}

}  // namespace

void update_probes(Viewer& v) {
    InspectorState& in = v.inspector;
    if (in.hovering && v.state.inspector) {
        probe_into(v, in.i, in.j, in.hover);
    } else {
        in.hover = PixelReport{};
    }
    if (in.pinned) {
        probe_into(v, in.pin_i, in.pin_j, in.pin);
    } else {
        in.pin = PixelReport{};
    }
}

}  // namespace raylab::viewer
