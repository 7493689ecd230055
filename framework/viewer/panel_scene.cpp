// Panel sections: scene, camera, lights (viewer/panel.h).
#include <imgui.h>
#include <imgui_stdlib.h>

#include <cmath>
#include <cstdio>

#include "actions.h"
#include "panel.h"
#include "raylab/scenes.h"

namespace raylab::viewer {

namespace {

void red_text(const std::string& text) {
    if (text.empty()) return;
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.35f, 0.3f, 1.0f));
    ImGui::TextWrapped("%s", text.c_str());
    ImGui::PopStyleColor();
}

// A light edit counts only when all its numbers are finite (a typed "1e99" is not)
bool finite_light(const PointLight& light) {
    return is_finite(light.p) && is_finite(light.I);
}

}  // namespace

void scene_section(Viewer& v) {
    ViewerState& s = v.state;
    const std::vector<std::string> names = builtin_scene_names();
    int& choice = v.panel.scene_choice;
    if (ImGui::BeginCombo("built-in scene", names[choice].c_str())) {
        for (int k = 0; k < int(names.size()); ++k) {
            if (ImGui::Selectable(names[k].c_str(), k == choice)) {
                choice = k;
                start_loading_scene(v, names[k]);
            }
        }
        ImGui::EndCombo();
    }
    const bool enter =
        ImGui::InputTextWithHint("##obj", "path/to/model.obj", &v.panel.obj_path,
                                 ImGuiInputTextFlags_EnterReturnsTrue);
    note_widget(v, "obj-path");
    ImGui::SameLine();
    if ((ImGui::Button("Open OBJ") || enter) && !v.panel.obj_path.empty())
        start_loading_scene(v, v.panel.obj_path);
    if (v.loading.valid()) {
        ImGui::TextDisabled("loading %s ...", v.loading_source.c_str());
    }
    ImGui::TextWrapped("%s: %zu triangles, %zu spheres, %zu planes",
                       s.scene_source.c_str(), s.scene.triangles.size(),
                       s.scene.spheres.size(), s.scene.planes.size());
    if (ImGui::SliderFloat("ambient", &s.scene.ambient, 0.0f, 1.0f, "%.2f"))
        s.dirty = true;
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "constant indirect light, times rho: the COMS30115 lab's 0.5 without its\n"
            "missing 1/pi is 0.159 (docs/conventions.md)");
}

void camera_section(Viewer& v) {
    ViewerState& s = v.state;
    View& edit = v.panel.view_edit;
    bool changed = false;
    changed |= ImGui::DragFloat3("eye e", &edit.eye.x, 0.01f, 0.0f, 0.0f, "%.3f");
    changed |= ImGui::DragFloat3("look-at p", &edit.lookat.x, 0.01f, 0.0f, 0.0f, "%.3f");
    changed |= ImGui::DragFloat3("up u", &edit.up.x, 0.01f, 0.0f, 0.0f, "%.3f");
    changed |= ImGui::SliderFloat("fov [deg]", &edit.fov, 1.0f, 179.0f, "%.2f");
    if (changed) apply_view(v, edit);

    // The camera constant beside the FOV: d = 1 / (2 tan(fov / 2)), handout 02
    const float d = 1.0f / (2.0f * std::tan(radians(s.view.fov) / 2.0f));
    ImGui::Text("camera constant d = 1 / (2 tan(fov/2)) = %.4f", d);
    if (s.modules[Module::camera] == Impl::student) {
        const float student_d =
            ModuleTable::make(s.modules).camera_constant(radians(s.view.fov));
        const bool same = std::fabs(student_d - d) <= 1e-4f * std::fabs(d);
        ImGui::TextColored(
            same ? ImVec4(0.5f, 0.9f, 0.5f, 1.0f) : ImVec4(1.0f, 0.6f, 0.3f, 1.0f),
            "your camera_constant(): %.4f%s", student_d, (s.stubs & 2u) ? " (stub)" : "");
    }
    red_text(v.panel.view_error);
    if (ImGui::Button("Scene's view")) {
        edit = s.scene.view;
        apply_view(v, edit);
    }
    ImGui::SameLine();
    ImGui::TextDisabled("arrows walk/turn, drag orbits, wheel");
}

void lights_section(Viewer& v) {
    ViewerState& s = v.state;
    std::vector<PointLight>& lights = s.scene.lights;
    if (lights.empty()) ImGui::TextDisabled("no lights: only ambient and emission");
    for (int k = 0; k < int(lights.size()); ++k) {
        char label[96];
        std::snprintf(label, sizeof label, "light %d at (%.2f, %.2f, %.2f)##%d", k + 1,
                      lights[k].p.x, lights[k].p.y, lights[k].p.z, k);
        if (ImGui::Selectable(label, k == s.selected_light)) s.selected_light = k;
    }
    if (ImGui::Button("Add light")) {
        // A copy of the selected light, or one above the look-at point
        PointLight light{s.view.lookat + Vec3(0.0f, 1.0f, 0.0f), Vec3(1.0f)};
        if (!lights.empty())
            light = lights[std::min(s.selected_light, int(lights.size()) - 1)];
        lights.push_back(light);
        s.selected_light = int(lights.size()) - 1;
        s.dirty = true;
    }
    ImGui::SameLine();
    ImGui::BeginDisabled(lights.empty());
    if (ImGui::Button("Remove light") && !lights.empty()) {
        lights.erase(lights.begin() + std::min(s.selected_light, int(lights.size()) - 1));
        s.selected_light = std::max(0, s.selected_light - 1);
        s.dirty = true;
    }
    ImGui::EndDisabled();
    if (lights.empty()) return;
    s.selected_light = std::min(s.selected_light, int(lights.size()) - 1);
    PointLight edit = lights[s.selected_light];
    bool changed = ImGui::DragFloat3("position p", &edit.p.x, 0.01f, 0.0f, 0.0f, "%.3f");
    changed |= ImGui::DragFloat3("intensity I [W/sr]", &edit.I.x, 0.01f, 0.0f, 1e4f,
                                 "%.3f", ImGuiSliderFlags_AlwaysClamp);
    if (changed) {
        if (finite_light(edit)) {
            lights[s.selected_light] = edit;
            s.dirty = true;
        } else {
            report_error(v, "light values must be finite numbers: not applied");
        }
    }
    const Vec3 P = 4.0f * kPi * edit.I;
    ImGui::TextDisabled("power P = 4 pi I = (%.1f, %.1f, %.1f) W", P.x, P.y, P.z);
    ImGui::TextDisabled("W/S forward/back, A/D left/right, Q/E up/down");
}

}  // namespace raylab::viewer
