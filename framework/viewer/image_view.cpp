// The image right of the panel, and the pixel under the mouse (viewer/panel.h).
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

#include "gl_image.h"
#include "panel.h"
#include "raylab/image.h"

namespace raylab::viewer {

void refresh_texture(Viewer& v) {
    ViewerState& s = v.state;
    if (!s.retone) return;
    s.retone = false;
    FrameState& f = v.frames;
    const bool heat = s.compare && s.show_difference && f.difference && !f.shown_preview;
    if (heat) {
        upload_texture(v.texture, f.difference->width, f.difference->height,
                       f.difference->heat);
        v.texture_width = f.difference->width;
        v.texture_height = f.difference->height;
    } else if (f.shown && f.shown->width > 0) {
        const auto start = std::chrono::steady_clock::now();
        v.tone.convert(*f.shown, s.exposure, v.texture_bytes);
        upload_texture(v.texture, f.shown->width, f.shown->height, v.texture_bytes);
        v.texture_width = f.shown->width;
        v.texture_height = f.shown->height;
        f.tone_ms = std::chrono::duration<double, std::milli>(
                        std::chrono::steady_clock::now() - start)
                        .count();
    }
    v.texture_is_heat = heat;
}

namespace {

// The image's place: centred right of the panel, fitted or at a fixed scale
ImageRect layout(const Viewer& v) {
    const ImGuiIO& io = ImGui::GetIO();
    const float x0 = v.panel_width, area_w = std::max(1.0f, io.DisplaySize.x - x0);
    const float y0 = v.overlay_height;  // the timing strip (frame_overlay)
    const float area_h = std::max(1.0f, io.DisplaySize.y - y0);
    const float W = float(v.state.settings.width), H = float(v.state.settings.height);
    const float scale = v.state.image_scale > 0 ? float(v.state.image_scale)
                                                : std::min(area_w / W, area_h / H);
    ImageRect r;
    r.width = W * scale;
    r.height = H * scale;
    r.x = std::floor(x0 + std::max(0.0f, (area_w - r.width) / 2.0f));
    r.y = std::floor(y0 + std::max(0.0f, (area_h - r.height) / 2.0f));
    return r;
}

void track_mouse(Viewer& v, const ImageRect& r) {
    const ImGuiIO& io = ImGui::GetIO();
    InspectorState& in = v.inspector;
    const ImVec2 m = io.MousePos;
    const bool inside = m.x >= r.x && m.y >= r.y && m.x < r.x + r.width &&
                        m.y < r.y + r.height && !io.WantCaptureMouse &&
                        v.input.mouse_moved;  // not the pointer's start position
    in.hovering = inside && !v.input.dragging;
    if (!inside) return;
    in.i = std::clamp(int((m.x - r.x) / r.width * float(v.state.settings.width)), 0,
                      v.state.settings.width - 1);
    in.j = std::clamp(int((m.y - r.y) / r.height * float(v.state.settings.height)), 0,
                      v.state.settings.height - 1);
    if (ImGui::IsMouseClicked(ImGuiMouseButton_Right)) {
        const bool same = in.pinned && in.pin_i == in.i && in.pin_j == in.j;
        in.pinned = !same;
        in.pin_i = in.i;
        in.pin_j = in.j;
    }
}

// A stub renders black or nothing: say so on the image instead of leaving a student
// with a black picture (docs/style.md anti-pattern 2)
void stub_note(const Viewer& v, const ImageRect& r) {
    std::string names;
    for (const ModuleInfo& info : module_infos()) {
        const bool stub = v.state.stubs & (1u << static_cast<int>(info.module));
        if (stub && v.state.modules[info.module] == Impl::student)
            names += (names.empty() ? "" : ", ") + std::string(info.name);
    }
    if (names.empty()) return;
    const std::string text = "still stubs (not started): " + names;
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    // Below the image where there is room (the image itself stays clean for
    // screenshots), else over its bottom edge
    const float below = r.y + r.height + 6.0f;
    const bool room = below + 20.0f <= ImGui::GetIO().DisplaySize.y;
    const ImVec2 at(r.x + 6.0f, room ? below : r.y + r.height - 22.0f);
    const ImVec2 size = ImGui::CalcTextSize(text.c_str());
    draw->AddRectFilled(ImVec2(at.x - 3, at.y - 2),
                        ImVec2(at.x + size.x + 3, at.y + size.y + 2),
                        IM_COL32(0, 0, 0, 170));
    draw->AddText(at, IM_COL32(255, 190, 90, 255), text.c_str());
}

}  // namespace

void draw_image(Viewer& v) {
    const ImageRect r = layout(v);
    v.image_rect = r;
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    const ImVec2 p0(r.x, r.y), p1(r.x + r.width, r.y + r.height);
    if (v.texture_width > 0) {
        draw->AddImage(
            reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(v.texture)), p0, p1);
    } else {
        draw->AddRect(p0, p1, IM_COL32(90, 90, 90, 255));
        draw->AddText(ImVec2(r.x + 10, r.y + 10), IM_COL32(200, 200, 200, 255),
                      "rendering ...");
    }
    // Never an old image as if it were current: a preview says so, and so does a full
    // frame while the worker renders a change (not during a drag: the picture moves)
    const FrameState& f = v.frames;
    const bool stale = !f.shown_preview && f.shown_job != f.last_job && !f.failed &&
                       !v.state.interacting && v.worker->busy();
    if (f.shown_preview || stale) {
        char label[64] = "out of date: rendering the change ...";
        if (!stale && f.shown_factor > 1) {
            std::snprintf(label, sizeof label, "preview 1/%d", f.shown_factor);
        } else if (!stale) {
            std::snprintf(label, sizeof label, "preview: 1 sample per pixel");
        }
        const ImVec2 size = ImGui::CalcTextSize(label);
        draw->AddRectFilled(ImVec2(r.x + 3, r.y + 2),
                            ImVec2(r.x + size.x + 9, r.y + size.y + 6),
                            IM_COL32(0, 0, 0, 140));
        draw->AddText(ImVec2(r.x + 6, r.y + 4), IM_COL32(255, 255, 255, 220), label);
    }
    stub_note(v, r);
    track_mouse(v, r);

    // The pinned pixel, outlined
    const InspectorState& in = v.inspector;
    if (in.pinned) {
        const float sx = r.width / float(v.state.settings.width);
        const float sy = r.height / float(v.state.settings.height);
        const ImVec2 a(r.x + in.pin_i * sx - 2, r.y + in.pin_j * sy - 2);
        const ImVec2 b(r.x + (in.pin_i + 1) * sx + 2, r.y + (in.pin_j + 1) * sy + 2);
        draw->AddRect(a, b, IM_COL32(255, 255, 0, 255), 0.0f, 0, 2.0f);
    }
    if (in.hovering && v.state.inspector && in.hover.probe) {
        ImGui::BeginTooltip();
        probe_lines(v, in.hover);
        light_tooltip(in.hover);
        ImGui::EndTooltip();
    }
}

}  // namespace raylab::viewer
