// The panel (viewer/panel.h): a fixed window at the left edge, sections in teaching
// order of what a student changes most.
#include "panel.h"

#include <imgui.h>

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

}  // namespace

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
    if (ImGui::CollapsingHeader("Scene", ImGuiTreeNodeFlags_DefaultOpen))
        scene_section(v);
    if (ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen))
        camera_section(v);
    if (ImGui::CollapsingHeader("Lights", ImGuiTreeNodeFlags_DefaultOpen))
        lights_section(v);
    if (ImGui::CollapsingHeader("Rendering", ImGuiTreeNodeFlags_DefaultOpen))
        rendering_section(v);
    if (ImGui::CollapsingHeader("Modules", ImGuiTreeNodeFlags_DefaultOpen))
        modules_section(v);
    // Where the module rows end, for the scripted check that they stay reachable
    v.panel.modules_end = ImGui::GetCursorPosY();
    v.panel.scroll_max = ImGui::GetScrollMaxY();
    v.panel.window_height = ImGui::GetWindowHeight();
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
