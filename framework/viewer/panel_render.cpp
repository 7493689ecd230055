// Panel sections: rendering settings, frame statistics, files, log (viewer/panel.h).
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

#include "actions.h"
#include "panel.h"
#include "raylab/error.h"
#include "raylab/input_checks.h"

namespace raylab::viewer {

namespace {

constexpr int kSizes[][2] = {{160, 120}, {320, 240},  {640, 480},
                             {800, 600}, {1280, 720}, {1920, 1080}};

void resolution(Viewer& v) {
    RenderSettings& settings = v.state.settings;
    char current[32];
    std::snprintf(current, sizeof current, "%d x %d", settings.width, settings.height);
    if (ImGui::BeginCombo("resolution", current)) {
        for (const auto& size : kSizes) {
            char label[32];
            std::snprintf(label, sizeof label, "%d x %d", size[0], size[1]);
            const bool now = size[0] == settings.width && size[1] == settings.height;
            if (ImGui::Selectable(label, now)) {
                v.panel.size_edit[0] = size[0];
                v.panel.size_edit[1] = size[1];
                settings.width = size[0];
                settings.height = size[1];
                v.state.dirty = true;
            }
        }
        ImGui::EndCombo();
    }
    const bool enter = ImGui::InputInt2("W x H (Enter)", v.panel.size_edit,
                                        ImGuiInputTextFlags_EnterReturnsTrue);
    if (enter || ImGui::IsItemDeactivatedAfterEdit()) {
        RenderSettings wanted = settings;
        wanted.width = v.panel.size_edit[0];
        wanted.height = v.panel.size_edit[1];
        try {
            validate(wanted);
            settings = wanted;
            v.state.dirty = true;
        } catch (const Error& e) {
            report_error(v, std::string(e.what()) + ": not applied");
            v.panel.size_edit[0] = settings.width;
            v.panel.size_edit[1] = settings.height;
        }
    }
}

constexpr int kSpp[] = {1, 4, 9, 16, 25, 36, 64, 100, 256};
constexpr int kLightSamples[] = {1, 2, 4, 8, 16, 32, 64, 128, 256};

// A combo of the values in list; true when the user picked one
template <size_t N>
bool value_combo(const char* label, int& value, const int (&list)[N]) {
    bool picked = false;
    if (ImGui::BeginCombo(label, std::to_string(value).c_str())) {
        for (int x : list) {
            if (ImGui::Selectable(std::to_string(x).c_str(), x == value)) {
                value = x;
                picked = true;
            }
        }
        ImGui::EndCombo();
    }
    return picked;
}

// Samples per pixel, scheme, threshold, light size and samples (modules 09 and 10). Each
// value passes the same rule as on the command line before it is applied
void sampling(Viewer& v) {
    RenderSettings& s = v.state.settings;
    const auto apply = [&](auto check, auto value, auto& field, const char* what) {
        try {
            check(value, what);
            field = value;
            v.state.dirty = true;
        } catch (const Error& e) {
            report_error(v, std::string(e.what()) + ": not applied");
        }
    };
    int spp = s.spp;
    if (value_combo("samples per pixel", spp, kSpp))
        apply(check_samples_per_pixel, spp, s.spp, "samples per pixel");
    const char* schemes[] = {"grid", "stratified", "adaptive"};
    int scheme = static_cast<int>(s.sampling);
    if (ImGui::Combo("pixel sampling", &scheme, schemes, 3)) {
        s.sampling = static_cast<PixelSampling>(scheme);
        v.state.dirty = true;
    }
    float threshold = s.aa_threshold;
    if (ImGui::SliderFloat("adaptive threshold", &threshold, 0.0f, 1.0f, "%.3f",
                           ImGuiSliderFlags_Logarithmic))
        apply(check_aa_threshold, threshold, s.aa_threshold, "adaptive threshold");
    float size = s.light_size;
    if (ImGui::SliderFloat("light size (0: point)", &size, 0.0f, 4.0f, "%.2f"))
        apply(check_light_size, size, s.light_size, "light size");
    int n = s.light_samples;
    if (value_combo("light samples", n, kLightSamples))
        apply(check_light_samples, n, s.light_samples, "light samples");
    if (ImGui::Checkbox("stratified light samples", &s.light_stratified))
        v.state.dirty = true;
    if (ImGui::Checkbox("show samples per pixel (heat map)", &v.state.show_samples))
        v.state.dirty = true;
    if (v.state.show_samples)
        ImGui::TextDisabled("blue: 1 sample, green: about sqrt(N), red: N = %d", s.spp);
}

void stat_row(const char* name, unsigned long long value) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(name);
    ImGui::TableNextColumn();
    ImGui::Text("%llu", value);
}

// What the viewer did not redo: reused frames, tone mapping only, unchanged tiles
void work_skipped(const Viewer& v) {
    const FrameState& f = v.frames;
    ImGui::TextUnformatted("Work skipped");
    if (!ImGui::BeginTable("skipped", 2,
                           ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp))
        return;
    stat_row("full frames rendered", static_cast<unsigned long long>(f.frames_rendered));
    stat_row("reused: same inputs as a kept frame",
             static_cast<unsigned long long>(f.frames_reused));
    stat_row("tone mapping only (exposure, heat map)",
             static_cast<unsigned long long>(f.retones));
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted("tiles changed since the last frame");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "16x16 tiles with any pixel different from the previous full frame. The\n"
            "renderer still traces every tile; one that kept each tile's inputs could\n"
            "skip the others.");
    ImGui::TableNextColumn();
    if (f.tiles_changed >= 0) {
        ImGui::Text("%d of %d (%.0f%%)", f.tiles_changed, f.tiles_total,
                    100.0 * f.tiles_changed / std::max(1, f.tiles_total));
    } else {
        ImGui::TextDisabled("-");
    }
    ImGui::EndTable();
}

}  // namespace

void rendering_section(Viewer& v) {
    ViewerState& s = v.state;
    resolution(v);
    const char* modes[] = {"Lambert (lit)", "normals", "base colour (rho)", "depth (t)"};
    int mode = static_cast<int>(s.settings.mode);
    if (ImGui::Combo("shading", &mode, modes, 4)) {
        s.settings.mode = static_cast<ShadingMode>(mode);
        s.dirty = true;
    }
    if (ImGui::Checkbox("shadows", &s.settings.shadows)) s.dirty = true;
    note_widget(v, "shadows");
    ImGui::SameLine();
    const int cores = int(std::max(1u, std::thread::hardware_concurrency()));
    ImGui::SetNextItemWidth(120.0f);
    if (ImGui::SliderInt("threads (0: all)", &s.settings.threads, 0, cores))
        s.dirty = true;
    // The value beside the slider, not on it: a slider centred on 0 has its knob in the
    // middle, where ImGui draws the value text
    if (ImGui::SliderFloat("##exposure", &s.exposure, -6.0f, 6.0f, "")) {
        s.retone = true;  // tone mapping only: no new render
        ++v.frames.retones;
    }
    note_widget(v, "exposure");
    ImGui::SameLine(0.0f, ImGui::GetStyle().ItemInnerSpacing.x);
    ImGui::Text("exposure %+.1f EV", double(s.exposure));
    sampling(v);
    int scale = s.image_scale;
    ImGui::RadioButton("fit window", &scale, 0);
    ImGui::SameLine();
    ImGui::RadioButton("1:1", &scale, 1);
    ImGui::SameLine();
    ImGui::RadioButton("2:1", &scale, 2);
    s.image_scale = scale;
    // Applied at the next frame (app.cpp): fonts and sizes, for projectors and high DPI
    // (on release: rescaling under a dragged slider would move it away from the mouse)
    float& edit = v.panel.ui_scale_edit;
    if (!ImGui::IsAnyItemActive() || edit <= 0.0f) edit = s.ui_scale;
    ImGui::SliderFloat("UI scale", &edit, 0.5f, 3.0f, "%.2f",
                       ImGuiSliderFlags_AlwaysClamp);
    if (ImGui::IsItemDeactivatedAfterEdit()) s.ui_scale = edit;
}

// A strip above the image area (image_view.cpp lays the image out below it), so the
// timing never covers a pixel
void frame_overlay(Viewer& v) {
    const FrameState& f = v.frames;
    const ImGuiIO& io = ImGui::GetIO();
    const float line = ImGui::GetTextLineHeightWithSpacing();
    // The plot beside the two lines of text where it has room for its title, else below
    // them (UI scale 1.5 at 1280x800)
    const float text_width =
        ImGui::CalcTextSize(
            "9999.99 ms  full 9999x9999, on screen 9999.9 ms after the "
            "change")
            .x;
    const bool stacked = io.DisplaySize.x - v.panel_width <
                         text_width +
                             ImGui::CalcTextSize("render time [ms], max 9999.9").x +
                             4.0f * ImGui::GetStyle().WindowPadding.x;
    v.overlay_height =
        (stacked ? 4.0f : 2.0f) * line + 2.0f * ImGui::GetStyle().WindowPadding.y;
    ImGui::SetNextWindowPos(ImVec2(v.panel_width, 0.0f), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(io.DisplaySize.x - v.panel_width, v.overlay_height),
                             ImGuiCond_Always);
    ImGui::SetNextWindowBgAlpha(0.6f);
    const ImGuiWindowFlags flags =
        ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
        ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
        ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs;
    ImGui::Begin("frame", nullptr, flags);
    if (f.history_ms.empty()) {
        ImGui::TextUnformatted(v.worker->busy() ? "rendering the first frame ..."
                                                : "no frame yet");
        ImGui::End();
        return;
    }
    ImGui::BeginGroup();
    const char* busy = v.worker->busy() ? "  (rendering)" : "";
    if (f.shown_preview && f.shown_factor > 1) {
        ImGui::Text("%.2f ms  preview 1/%d, %dx%d%s", f.last.milliseconds, f.shown_factor,
                    f.shown->width, f.shown->height, busy);
    } else if (f.shown_preview) {
        ImGui::Text("%.2f ms  preview (1 sample) %dx%d%s", f.last.milliseconds,
                    f.shown->width, f.shown->height, busy);
    } else if (f.last_reused) {
        ImGui::Text("no render: full %dx%d reused (same inputs as a kept frame)%s",
                    f.shown->width, f.shown->height, busy);
    } else {
        ImGui::Text("%.2f ms  full %dx%d, on screen %.1f ms after the change%s",
                    f.last.milliseconds, f.shown->width, f.shown->height, f.latency_ms,
                    busy);
    }
    if (f.last_reused && !f.shown_preview) {
        ImGui::Text("no rays cast (the kept frame took %.2f ms)", f.last.milliseconds);
    } else {
        // With kept camera hits its rays are the shadow rays alone: say why they are
        // fewer
        ImGui::Text("%.2f Mrays/s on %d threads%s", f.last.rays_per_second() * 1e-6,
                    f.last.threads,
                    f.last.camera_rays_reused > 0
                        ? "; camera hits reused, no camera ray cast"
                        : "");
    }
    ImGui::EndGroup();
    if (!stacked) ImGui::SameLine();
    const float top = *std::max_element(f.history_ms.begin(), f.history_ms.end());
    // The plot's title in full, or shorter where the window is narrow: never clipped
    const float width = ImGui::GetContentRegionAvail().x;
    char overlay[64];
    std::snprintf(overlay, sizeof overlay, "render time [ms], max %.1f", top);
    if (ImGui::CalcTextSize(overlay).x + ImGui::GetStyle().FramePadding.x * 2 > width)
        std::snprintf(overlay, sizeof overlay, "max %.0f ms", top);
    if (ImGui::CalcTextSize(overlay).x + ImGui::GetStyle().FramePadding.x * 2 > width)
        overlay[0] = '\0';
    ImGui::PlotLines("##history", f.history_ms.data(), int(f.history_ms.size()), 0,
                     overlay, 0.0f, top * 1.1f,
                     ImVec2(width, (stacked ? 1.8f : 2.0f) * line));
    ImGui::End();
}

// The student's geometry modules' share of a frame, estimated: the renderer counts
// intersection tests but does not time them (a clock read per test would cost more than
// many tests), so each selected student intersect_* is timed here, once per selection,
// on rays at a primitive of unit size, and the frame's tests are weighted by the scene's
// count of each kind of primitive
struct StudentTestTimes {
    ModuleSelection selection;
    bool measured = false;
    double ns[3] = {NAN, NAN, NAN};  ///< plane, sphere, triangle; NaN: not the student's
};

constexpr int kTimedRays = 4096;
volatile float g_timing_sink = 0.0f;  // keeps the timed calls' results alive

// Median ns per call of test(k) for k < kTimedRays, over three passes after a warm-up
template <class Test>
double ns_per_test(Test test) {
    double best[3];
    for (int pass = -1; pass < 3; ++pass) {
        const auto start = std::chrono::steady_clock::now();
        float sum = 0.0f;
        for (int k = 0; k < kTimedRays; ++k) {
            if (const auto hit = test(k)) sum += hit->t;
        }
        const std::chrono::duration<double, std::nano> took =
            std::chrono::steady_clock::now() - start;
        g_timing_sink = sum;
        if (pass >= 0) best[pass] = took.count() / kTimedRays;
    }
    std::sort(best, best + 3);
    return best[1];
}

// Rays from above the primitive at (0, 0, 0) aimed at points of [-1.25, 1.25]^2 in y = 0
std::vector<Ray> timing_rays() {
    std::vector<Ray> rays;
    std::uint64_t state = 0x9E3779B97F4A7C15ull;
    const auto uniform = [&state] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return static_cast<float>(state >> 40) * 0x1p-24f;
    };
    for (int k = 0; k < kTimedRays; ++k) {
        Ray r;
        r.o = Vec3(4.0f * uniform() - 2.0f, 3.0f + uniform(), 4.0f * uniform() - 2.0f);
        const Vec3 aim(2.5f * uniform() - 1.25f, 0.0f, 2.5f * uniform() - 1.25f);
        r.w = glm::normalize(aim - r.o);
        rays.push_back(r);
    }
    return rays;
}

const StudentTestTimes& student_test_times(const ModuleSelection& selection) {
    static StudentTestTimes times;
    if (times.measured && times.selection.impl == selection.impl) return times;
    times = StudentTestTimes{selection, true, {NAN, NAN, NAN}};
    ModuleTable table;
    try {
        table = ModuleTable::make(selection);
    } catch (const Error&) {
        return times;
    }
    const std::vector<Ray> rays = timing_rays();
    if (selection[Module::plane] == Impl::student) {
        auto volatile fn = table.intersect_plane;
        const Plane plane{Vec3(0.0f, 1.0f, 0.0f), 0.0f};
        times.ns[0] = ns_per_test([&](int k) { return fn(rays[k], plane); });
    }
    if (selection[Module::sphere] == Impl::student) {
        auto volatile fn = table.intersect_sphere;
        const Sphere sphere{Vec3(0.0f), 1.0f};
        times.ns[1] = ns_per_test([&](int k) { return fn(rays[k], sphere); });
    }
    if (selection[Module::triangle] == Impl::student) {
        auto volatile fn = table.intersect_triangle;
        const Vec3 a(-1.0f, 0.0f, 1.0f), b(1.0f, 0.0f, 1.0f), c(0.0f, 0.0f, -1.0f);
        times.ns[2] = ns_per_test([&](int k) { return fn(rays[k], a, b, c); });
    }
    return times;
}

// "your modules (estimate): ..." under the frame's counters, when any geometry module
// of the frame is the student's
void student_share(Viewer& v, const FrameStats& st) {
    const StudentTestTimes& times = student_test_times(v.frames.sent.modules);
    const Scene& scene = v.state.scene;
    const double counts[3] = {static_cast<double>(scene.planes.size()),
                              static_cast<double>(scene.spheres.size()),
                              static_cast<double>(scene.triangles.size())};
    double total = 0.0, weighted_ns = 0.0;
    bool any = false;
    for (int k = 0; k < 3; ++k) {
        total += counts[k];
        if (!std::isnan(times.ns[k])) {
            weighted_ns += counts[k] * times.ns[k];
            any = any || counts[k] > 0;
        }
    }
    if (!any || total == 0.0 || st.milliseconds <= 0.0) return;
    const double ns = weighted_ns / total;  // per test, over all kinds
    const double student_ms = static_cast<double>(st.intersection_tests) * ns * 1e-6;
    const double frame_ms = st.milliseconds * std::max(1, st.threads);
    ImGui::Text("your modules (estimate): %.1f ms of %.1f thread-ms (%.0f %%)",
                student_ms, frame_ms, 100.0 * student_ms / frame_ms);
    if (ImGui::IsItemHovered()) {
        std::string lines;
        const char* names[3] = {"plane", "sphere", "triangle"};
        for (int k = 0; k < 3; ++k) {
            if (!std::isnan(times.ns[k]))
                lines += "\n  " + std::string(names[k]) + ": " +
                         std::to_string(static_cast<int>(std::lround(times.ns[k]))) +
                         " ns per test";
        }
        ImGui::SetTooltip(
            "An estimate, not a measurement: the frame's intersection tests times the "
            "ns\n"
            "per test of your geometry modules, timed once here on %d rays at a\n"
            "primitive of unit size and weighted by the scene's count of each kind:%s\n"
            "The rest of the frame (BVH, shading, shadows, the reference's modules) is\n"
            "the remainder. ./scripts/dev.sh bench --student measures your tests on\n"
            "harder rays.",
            kTimedRays, lines.c_str());
    }
}

void stats_section(Viewer& v) {
    const FrameState& f = v.frames;
    if (f.history_ms.empty()) {
        ImGui::TextDisabled("no frame yet");
        return;
    }
    const FrameStats& st = f.last;
    const bool reused = f.last_reused && !f.shown_preview;
    if (reused) {
        ImGui::Text("last frame: reused, full %dx%d", f.shown->width, f.shown->height);
    } else {
        ImGui::Text("last frame: %.2f ms, %s %dx%d", st.milliseconds,
                    f.shown_preview ? "preview" : "full", f.shown->width,
                    f.shown->height);
    }
    if (f.have_full) {
        ImGui::TextWrapped(
            "last full frame: %s %.2f ms; on screen %.1f ms after the change (tone "
            "mapping and texture upload %.1f ms)",
            f.last_reused ? "reused, its render took" : "render",
            f.last_full.milliseconds, f.latency_ms, f.tone_ms);
    }
    if (reused)
        ImGui::TextWrapped(
            "No ray was cast for this frame: its inputs equal a kept frame's. The "
            "numbers below are that frame's.");
    ImGui::Text("%.2f Mrays/s on %d threads", st.rays_per_second() * 1e-6, st.threads);
    if (ImGui::BeginTable("stats", 2,
                          ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
        stat_row("camera rays", st.camera_rays);
        stat_row("of which in packets", st.camera_rays_in_packets);
        stat_row("skipped: camera hits reused", st.camera_rays_reused);
        stat_row("shadow rays", st.shadow_rays);
        stat_row("skipped: light behind surface", st.shadow_rays_backfacing);
        stat_row("skipped: shadows off", st.shadow_rays_disabled);
        stat_row("intersection tests", st.intersection_tests);
        stat_row("BVH nodes visited", st.bvh_nodes);
        ImGui::EndTable();
    }
    student_share(v, st);
    work_skipped(v);
    if (st.non_finite_pixels > 0) {
        ImGui::TextColored(ImVec4(1.0f, 0.35f, 0.3f, 1.0f), "%llu NaN/Inf pixels (black)",
                           static_cast<unsigned long long>(st.non_finite_pixels));
    }
}

void files_section(Viewer& v) {
    PanelState& p = v.panel;
    ImGui::InputText("##image", &p.image_path);
    ImGui::SameLine();
    if (ImGui::Button("Save image")) save_image(v, p.image_path);
    ImGui::InputText("##view", &p.view_path);
    ImGui::SameLine();
    if (ImGui::Button("Save view")) save_view(v, p.view_path);
    ImGui::SameLine();
    if (ImGui::Button("Load")) load_view(v, p.view_path);
    ImGui::InputText("##report", &p.report_dir);
    ImGui::SameLine();
    if (ImGui::Button("Save report")) {
        if (save_report(v, p.report_dir)) p.report_dir = default_report_dir();
    }
    ImGui::TextDisabled("report: view, settings, image and log in one folder");
}

void log_section(Viewer& v) {
    ImGui::BeginChild("log", ImVec2(0.0f, 160.0f), true,
                      ImGuiWindowFlags_HorizontalScrollbar);
    for (const std::string& line : v.log.lines())
        ImGui::TextUnformatted(line.c_str());
    if (ImGui::GetScrollY() >= ImGui::GetScrollMaxY()) ImGui::SetScrollHereY(1.0f);
    ImGui::EndChild();
}

}  // namespace raylab::viewer
