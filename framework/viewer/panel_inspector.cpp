// Pixel inspector, lights part (viewer/panel.h): for the pinned pixel, each light's
// sample and shadow ray with what blocked it, the student's modules beside the
// reference, so that a pixel black from a wrong shadow test can be explained.
#include <imgui.h>

#include <cstdio>

#include "panel.h"

namespace raylab::viewer {

namespace {

const ImVec4 kRed(1.0f, 0.45f, 0.4f, 1.0f);
const ImVec4 kGreen(0.5f, 0.9f, 0.5f, 1.0f);

// Percentage of an area light's samples that reach the point
double visible_percent(const LightProbe& lp) {
    return lp.samples > 0 ? 100.0 * lp.visible_samples / lp.samples : 0.0;
}

// An area light's counts; then the cell shows its first blocked (or first) sample
bool area_lines(const LightProbe& lp) {
    ImGui::Text("area light: %d samples", lp.samples);
    if (lp.samples == 0) {
        ImGui::TextColored(kRed, "light_sample_points gave no point");
        return false;
    }
    ImGui::Text("behind %d  blocked %d  visible %d (%.0f%%)", lp.backfacing_samples,
                lp.blocked_samples, lp.visible_samples, visible_percent(lp));
    ImGui::Text("Li of the visible %.3g", lp.Li_visible.x);
    if (lp.backfacing || !lp.tested) return true;
    ImGui::TextDisabled(lp.blocked ? "first blocked sample:" : "first sample tested:");
    return true;
}

// One cell: what one side's code did with one light
void light_cell(const LightProbe& lp) {
    if (lp.area && !area_lines(lp)) return;
    const LightSample& s = lp.sample;
    ImGui::Text("wi (%.3f, %.3f, %.3f)", s.wi.x, s.wi.y, s.wi.z);
    ImGui::Text("r %.4f  Li %.3g", s.r, s.Li.x);
    if (lp.backfacing) {
        ImGui::TextDisabled("light behind the surface: no shadow ray");
        return;
    }
    if (!lp.tested) {
        ImGui::TextDisabled("shadows off: lit");
        return;
    }
    if (lp.rays.empty()) {
        ImGui::TextColored(kRed, "in_shadow cast no ray");
    } else {
        const Ray& r = lp.rays.front();
        ImGui::Text("shadow ray o (%.3f, %.3f, %.3f)", r.o.x, r.o.y, r.o.z);
        ImGui::Text("  t in [%.3g, %.4g]%s", r.tmin, r.tmax,
                    lp.rays.size() > 1 ? " (first of several)" : "");
    }
    if (lp.blocker) {
        ImGui::TextColored(lp.blocked ? kRed : kGreen, "%s: blocked by %s at t %.4g",
                           lp.blocked ? "shadow" : "lit", lp.blocker_name.c_str(),
                           lp.blocker->t);
    } else {
        ImGui::TextColored(lp.blocked ? kRed : kGreen, "%s",
                           lp.blocked ? "shadow (nothing on the ray!)" : "lit: ray free");
    }
}

const LightProbe* find_light(const std::optional<PixelProbe>& p, int k) {
    if (!p) return nullptr;
    for (const LightProbe& lp : p->lights)
        if (lp.light == k) return &lp;
    return nullptr;
}

// One line per light: the shadow test's verdict and its blocker (the tooltip)
void light_summary(const PixelProbe& p, const char* who) {
    for (const LightProbe& lp : p.lights) {
        if (!lp.tested) continue;
        if (lp.area) {
            ImGui::TextColored(lp.blocked ? kRed : kGreen,
                               "%s light %d: %.0f%% visible, %d of %d blocked%s%s", who,
                               lp.light + 1, visible_percent(lp), lp.blocked_samples,
                               lp.samples, lp.blocker ? ", first by " : "",
                               lp.blocker ? lp.blocker_name.c_str() : "");
        } else if (lp.blocker) {
            ImGui::TextColored(lp.blocked ? kRed : kGreen,
                               "%s light %d: %s, %s at t %.4g", who, lp.light + 1,
                               lp.blocked ? "shadow" : "lit", lp.blocker_name.c_str(),
                               lp.blocker->t);
        } else {
            ImGui::TextColored(lp.blocked ? kRed : kGreen, "%s light %d: %s", who,
                               lp.light + 1, lp.blocked ? "shadow, ray free" : "lit");
        }
    }
}

}  // namespace

void light_tooltip(const PixelReport& report) {
    if (report.probe) light_summary(*report.probe, "yours:");
    if (report.reference) light_summary(*report.reference, "reference:");
}

void light_lines(const Viewer& v, const PixelReport& report) {
    if (!report.probe || !report.probe->hit) return;
    const int lights = int(v.state.scene.lights.size());
    if (lights == 0 || v.state.settings.mode != ShadingMode::lambert) return;
    const bool both = report.reference.has_value();
    const ImGuiTableFlags flags =
        ImGuiTableFlags_Borders | ImGuiTableFlags_SizingStretchSame;
    if (!ImGui::BeginTable("lights", both ? 2 : 1, flags)) return;
    ImGui::TableSetupColumn("your modules");
    if (both) ImGui::TableSetupColumn("reference");
    ImGui::TableHeadersRow();
    for (int k = 0; k < lights; ++k) {
        ImGui::TableNextRow();
        for (int side = 0; side < (both ? 2 : 1); ++side) {
            ImGui::TableNextColumn();
            ImGui::PushID(k * 2 + side);
            ImGui::Text("light %d", k + 1);
            const LightProbe* lp =
                find_light(side == 0 ? report.probe : report.reference, k);
            ImGui::PushTextWrapPos(0.0f);  // wrap in narrow columns (UI scale)
            if (lp) {
                light_cell(*lp);
            } else {
                ImGui::TextDisabled("no hit here");
            }
            ImGui::PopTextWrapPos();
            ImGui::PopID();
        }
    }
    ImGui::EndTable();
}

}  // namespace raylab::viewer
