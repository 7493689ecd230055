// Panel sections: module list and graders, compare view, pixel inspector
// (viewer/panel.h).
#include <imgui.h>

#include <cstdio>

#include "actions.h"
#include "compare.h"
#include "panel.h"
#include "raylab/image.h"

namespace raylab::viewer {

namespace {

const ImVec4 kGreen(0.45f, 0.9f, 0.45f, 1.0f), kRed(1.0f, 0.4f, 0.35f, 1.0f),
    kGrey(0.6f, 0.6f, 0.6f, 1.0f);

ImVec4 grade_colour(ModuleGrade::Status status) {
    switch (status) {
        case ModuleGrade::Status::passed:
            return kGreen;
        case ModuleGrade::Status::failed:
        case ModuleGrade::Status::crashed:
        case ModuleGrade::Status::error:
            return kRed;
        default:
            return kGrey;
    }
}

// One row: ID, student/reference switch, stub note, test result
void module_row(Viewer& v, const ModuleInfo& info, const ModuleGrade& grade) {
    ViewerState& s = v.state;
    const int k = static_cast<int>(info.module);
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(info.id);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", info.title);
    ImGui::TableNextColumn();
    int impl = static_cast<int>(s.modules.impl[k]);
    ImGui::PushID(k);
    bool changed = ImGui::RadioButton("student", &impl, 0);
    ImGui::SameLine();
    ImGui::BeginDisabled(!reference_available());
    changed |= ImGui::RadioButton("ref", &impl, 1);
    ImGui::EndDisabled();
    if (changed) {
        s.modules.impl[k] = static_cast<Impl>(impl);
        s.dirty = true;
    }
    ImGui::TableNextColumn();
    if (s.stubs & (1u << k)) {
        ImGui::TextColored(kGrey, "stub");
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("exercises/%s.cpp is not started (RAYLAB_STUB)", info.id);
        ImGui::SameLine();
    }
    if (grade.status != ModuleGrade::Status::not_run) {
        ImGui::PushStyleColor(ImGuiCol_Text, grade_colour(grade.status));
        if (ImGui::Selectable(grade.summary.c_str(), v.panel.grade_shown == k))
            v.panel.grade_shown = v.panel.grade_shown == k ? -1 : k;
        ImGui::PopStyleColor();
    }
    ImGui::PopID();
}

ImVec4 case_colour(const std::string& status) {
    if (status == "pass") return kGreen;
    if (status == "fail" || status == "crash") return kRed;
    return kGrey;  // stub (not started), not run
}

// The result box of one module: every case in its colour, the messages wrapped, scrolled
void grade_box(const ModuleInfo& info, const ModuleGrade& grade) {
    ImGui::TextDisabled("tests of %s (click its result to hide):", info.id);
    ImGui::BeginChild("grader output", ImVec2(0.0f, 220.0f), true);
    ImGui::PushTextWrapPos(0.0f);
    if (!grade.output.empty() && grade.status != ModuleGrade::Status::passed)
        ImGui::TextUnformatted(grade.output.c_str());
    for (const CaseGrade& c : grade.cases) {
        const std::string mark = c.status == "stub" ? "not started" : c.status;
        ImGui::PushStyleColor(ImGuiCol_Text, case_colour(c.status));
        ImGui::TextWrapped("%s: %s", mark.c_str(), c.name.c_str());
        ImGui::PopStyleColor();
        if (!c.message.empty() && c.status != "pass" && c.status != "stub") {
            ImGui::Indent();
            ImGui::TextUnformatted(c.message.c_str());
            ImGui::Unindent();
        }
    }
    ImGui::PopTextWrapPos();
    ImGui::EndChild();
}

void set_all(Viewer& v, const ModuleSelection& selection) {
    v.state.modules = selection;
    v.state.dirty = true;
}

}  // namespace

void modules_section(Viewer& v) {
    const auto grades = v.grading->grades();
    const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit;
    if (ImGui::BeginTable("modules", 3, flags)) {
        for (const ModuleInfo& info : module_infos())
            module_row(v, info, grades[static_cast<int>(info.module)]);
        ImGui::EndTable();
    }
    if (!reference_available()) {
        ImGui::TextWrapped(
            "Reference switch off: this build has no solutions/ "
            "(student release).");
    } else {
        if (ImGui::Button("All student")) set_all(v, ModuleSelection::all(Impl::student));
        ImGui::SameLine();
        if (ImGui::Button("All reference"))
            set_all(v, ModuleSelection::all(Impl::reference));
        ImGui::SameLine();
        if (ImGui::Button("Reference for stubs")) set_all(v, auto_selection());
    }
    ImGui::BeginDisabled(v.grading->running());
    if (ImGui::Button(v.grading->running() ? "Running tests ..." : "Run tests"))
        run_tests(v);
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::TextDisabled(v.grading_binary.empty() ? "(graders not built)"
                                                 : "(student code, child process)");
    const int shown = v.panel.grade_shown;
    if (shown >= 0 && (!grades[shown].output.empty() || !grades[shown].cases.empty()))
        grade_box(module_infos()[shown], grades[shown]);
}

void compare_section(Viewer& v) {
    ViewerState& s = v.state;
    if (!reference_available()) {
        ImGui::TextWrapped("Needs the reference solutions; this build has none.");
        return;
    }
    if (ImGui::Checkbox("compare with the full reference", &s.compare)) {
        s.dirty = true;
        s.retone = true;
    }
    if (!s.compare) return;
    if (ImGui::Checkbox("show the difference heat map", &s.show_difference)) {
        s.retone = true;  // the texture only: no new render
        ++v.frames.retones;
    }
    const std::optional<Difference>& d = v.frames.difference;
    if (!d) {
        ImGui::TextDisabled("computed with the next full frame ...");
        return;
    }
    if (s.modules.impl == ModuleSelection::all(Impl::reference).impl)
        ImGui::TextDisabled("all modules run the reference: nothing differs");
    ImGui::Text("RMSE %.4g   max error %.4g", d->rmse, d->max_error);
    ImGui::Text("%llu of %d pixels differ (> 1e-4)",
                static_cast<unsigned long long>(d->differing), d->width * d->height);
    if (d->non_finite > 0)
        ImGui::TextColored(kRed, "%llu NaN/Inf pixels (magenta)",
                           static_cast<unsigned long long>(d->non_finite));
    // Legend: the heat ramp from 0 to the max error
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const float w = ImGui::GetContentRegionAvail().x, h = 12.0f;
    ImDrawList* draw = ImGui::GetWindowDrawList();
    for (int x = 0; x < int(w); ++x) {
        std::uint8_t rgb[3];
        heat_colour(float(x) / w, rgb);
        draw->AddRectFilled(ImVec2(p.x + x, p.y), ImVec2(p.x + x + 1, p.y + h),
                            IM_COL32(rgb[0], rgb[1], rgb[2], 255));
    }
    ImGui::Dummy(ImVec2(w, h));
    ImGui::Text("0");
    ImGui::SameLine(w - 80.0f);
    ImGui::Text("%.3g", d->max_error);
    ImGui::TextDisabled("linear radiance, largest channel error per pixel");
}

void probe_lines(const Viewer& v, const PixelReport& report) {
    if (!report.probe) {
        ImGui::TextDisabled("hover the image; right click pins a pixel");
        return;
    }
    const PixelProbe& p = *report.probe;
    ImGui::Text("pixel (%d, %d)  uv (%.4f, %.4f)", report.i, report.j, p.uv.x, p.uv.y);
    ImGui::Text("ray o (%.3f, %.3f, %.3f)", p.ray.o.x, p.ray.o.y, p.ray.o.z);
    ImGui::Text("    w (%.4f, %.4f, %.4f)", p.ray.w.x, p.ray.w.y, p.ray.w.z);
    if (report.reference) {
        // The reference's camera ray for the same pixel, red where it differs
        const Ray& r = report.reference->ray;
        const auto near = [](const Vec3& a, const Vec3& b) {
            return glm::all(glm::lessThanEqual(glm::abs(a - b), Vec3(1e-4f)));
        };
        const bool same = near(r.o, p.ray.o) && near(r.w, p.ray.w);
        const ImVec4 colour = same ? kGrey : kRed;
        ImGui::TextColored(colour, "ref o (%.3f, %.3f, %.3f)", r.o.x, r.o.y, r.o.z);
        ImGui::TextColored(colour, "    w (%.4f, %.4f, %.4f)%s", r.w.x, r.w.y, r.w.z,
                           same ? "" : "  differs");
    }
    if (p.hit) {
        const Hit& h = *p.hit;
        const std::string& material = v.state.scene.materials[h.material].name;
        ImGui::Text("hit t = %.5f  material %s", h.t, material.c_str());
        ImGui::Text("position (%.3f, %.3f, %.3f)", h.position.x, h.position.y,
                    h.position.z);
        ImGui::Text("normal n (%.3f, %.3f, %.3f)", h.n.x, h.n.y, h.n.z);
        ImGui::Text("shading ns (%.3f, %.3f, %.3f)", h.ns.x, h.ns.y, h.ns.z);
    } else {
        ImGui::Text("no hit: background");
    }
    ImGui::Text("radiance L (%.4f, %.4f, %.4f)", p.L.x, p.L.y, p.L.z);
    if (report.reference) {
        const PixelProbe& r = *report.reference;
        // Wrapped: at UI scale 1.5 the line is wider than the panel
        ImGui::PushStyleColor(ImGuiCol_Text, kGrey);
        if (r.hit) {
            ImGui::TextWrapped("reference: hit t = %.5f, L (%.4f, %.4f, %.4f)", r.hit->t,
                               r.L.x, r.L.y, r.L.z);
        } else {
            ImGui::TextWrapped("reference: no hit, L (%.4f, %.4f, %.4f)", r.L.x, r.L.y,
                               r.L.z);
        }
        ImGui::PopStyleColor();
    }
}

void inspector_section(Viewer& v) {
    ImGui::Checkbox("tooltip over the image", &v.state.inspector);
    if (!v.inspector.pinned) {
        ImGui::TextDisabled("right click a pixel to pin it here");
        return;
    }
    ImGui::SameLine();
    if (ImGui::SmallButton("Unpin")) v.inspector.pinned = false;
    probe_lines(v, v.inspector.pin);
}

}  // namespace raylab::viewer
