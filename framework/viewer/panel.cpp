// The panel (viewer/panel.h): a fixed window at the left edge, sections in teaching
// order of what a student changes most.
#include "panel.h"

#include <imgui.h>

#include <cstdio>

#include "raylab/modules.h"

namespace raylab::viewer {

namespace {

void error_banner(Viewer& v) {
    if (v.panel.error.empty()) return;
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.35f, 0.3f, 1.0f));
    ImGui::TextWrapped("%s", v.panel.error.c_str());
    ImGui::PopStyleColor();
    if (ImGui::SmallButton("Dismiss")) v.panel.error.clear();
    ImGui::Separator();
}

// Where to start, while a module is still a stub: the first one not started, its file
// and handout, and the two buttons that show progress
void first_run_hint(Viewer& v) {
    if (v.state.stubs == 0 || v.panel.hint_dismissed) return;
    for (const ModuleInfo& info : module_infos()) {
        if (!(v.state.stubs & (1u << static_cast<int>(info.module)))) continue;
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.85f, 0.4f, 1.0f));
        ImGui::TextWrapped(
            "Start here: module %s. Write exercises/%s.cpp (see "
            "docs/handouts/%s.md), rebuild, then press Run tests below.",
            info.id, info.id, info.id);
        ImGui::PopStyleColor();
        if (ImGui::SmallButton("Got it")) v.panel.hint_dismissed = true;
        ImGui::Separator();
        return;
    }
}

}  // namespace

void note_widget(Viewer& v, const char* name) {
    // From the third frame: the panel's scroll bar, known after the first, narrows items
    if (ImGui::GetFrameCount() < 3 || !v.panel.widgets_logged.insert(name).second) return;
    const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
    char line[128];
    std::snprintf(line, sizeof line, "panel: widget %s at %.0f,%.0f size %.0fx%.0f", name,
                  a.x, a.y, b.x - a.x, b.y - a.y);
    v.log.add(line);
}

void draw_panel(Viewer& v) {
    const ImGuiIO& io = ImGui::GetIO();
    ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(v.panel_width, io.DisplaySize.y), ImGuiCond_Always);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                                   ImGuiWindowFlags_NoCollapse |
                                   ImGuiWindowFlags_NoSavedSettings;
    ImGui::Begin("raylab", nullptr, flags);
    ImGui::PushItemWidth(-150.0f * v.state.ui_scale);  // room for the labels
    error_banner(v);
    first_run_hint(v);
    // Modules first: the student's main control, visible without scrolling at 1280x800
    // and UI scale 1.5 (the screenshot test logs where it starts and ends)
    v.panel.modules_top = ImGui::GetCursorPosY();
    if (ImGui::CollapsingHeader("Modules", ImGuiTreeNodeFlags_DefaultOpen))
        modules_section(v);
    v.panel.modules_end = ImGui::GetCursorPosY();
    v.panel.scroll_max = ImGui::GetScrollMaxY();
    v.panel.window_height = ImGui::GetWindowHeight();
    if (ImGui::CollapsingHeader("Scene", ImGuiTreeNodeFlags_DefaultOpen))
        scene_section(v);
    if (ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen))
        camera_section(v);
    // Closed at start: the keys move the selected light (its line says which)
    if (ImGui::CollapsingHeader("Lights")) lights_section(v);
    if (ImGui::CollapsingHeader("Rendering", ImGuiTreeNodeFlags_DefaultOpen))
        rendering_section(v);
    if (ImGui::CollapsingHeader("Frame statistics")) stats_section(v);
    // Open at start when the command line asked for them
    if (v.state.compare) ImGui::SetNextItemOpen(true, ImGuiCond_Once);
    if (ImGui::CollapsingHeader("Compare with the reference")) compare_section(v);
    if (v.inspector.pinned) ImGui::SetNextItemOpen(true, ImGuiCond_Once);
    const bool inspector_open = ImGui::CollapsingHeader("Pixel inspector");
    if (v.panel.scroll_to_inspector) {
        ImGui::SetScrollHereY(0.0f);
        const ImGuiIO& io = ImGui::GetIO();
        if (io.MouseWheel != 0.0f || io.MouseClicked[0])
            v.panel.scroll_to_inspector = false;
    }
    if (inspector_open) {
        inspector_section(v);
        if (v.inspector.pinned) light_lines(v, v.inspector.pin);
        ImGui::Checkbox("3D debug view (scene and this pixel's rays)", &v.debug.open);
    }
    if (ImGui::CollapsingHeader("Files and report")) files_section(v);
    if (ImGui::CollapsingHeader("Log")) log_section(v);
    ImGui::PopItemWidth();
    ImGui::End();
    frame_overlay(v);
}

}  // namespace raylab::viewer
