// The viewer's window and main loop (viewer/app.h), after the Dear ImGui v1.86
// GLFW + OpenGL 3 example: Setup / Main loop / Rendering / Cleanup.
#include "app.h"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "actions.h"
#include "gl_image.h"
#include "input.h"
#include "panel.h"
#include "viewer.h"

namespace raylab::viewer {

namespace {

std::string glfw_last_error;

void on_glfw_error(int code, const char* text) {
    glfw_last_error = "GLFW error " + std::to_string(code) + ": " + text;
}

std::string self_path() {
    char path[4096];
    const ssize_t n = readlink("/proc/self/exe", path, sizeof path - 1);
    return n > 0 ? std::string(path, static_cast<size_t>(n)) : std::string("raylab");
}

GLFWwindow* open_window(const ViewerOptions& o, const std::string& scene) {
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    const std::string title = "raylab - " + scene;
    return glfwCreateWindow(o.window_width, o.window_height, title.c_str(), nullptr,
                            nullptr);
}

// Sleep until something happens: a key held needs a steady frame rate; the render
// worker and the graders wake us with an empty event when they have news, so a frame in
// flight costs no UI frames (a scripted run too: with Mesa's software GL a frame of the
// window costs as much CPU as a tenth of a 640x480 render); nothing at all sleeps (idle
// CPU near zero)
void wait_for_events(Viewer& v) {
    if (v.options.frames > 0) {
        if (v.loading.valid()) {
            glfwWaitEventsTimeout(0.25);
        } else if (v.worker->busy() || v.grading->running()) {
            glfwWaitEventsTimeout(1.0);  // they wake us; the timeout is a safety net
        } else {
            glfwPollEvents();
        }
    } else if (camera_keys_held(v)) {
        glfwWaitEventsTimeout(1.0 / 60.0);
    } else if (v.extra_frames > 0) {
        // ImGui settles over a frame or two. While the worker renders a settled change,
        // it has the CPU first: its result wakes us and that frame settles ImGui too (a
        // slow one: after 0.1 s). With Mesa's software GL a window frame costs both
        // cores a noticeable part of a render
        if (v.worker->busy() && !v.state.interacting) {
            glfwWaitEventsTimeout(0.1);
        } else {
            glfwPollEvents();
        }
    } else if (v.loading.valid()) {
        glfwWaitEventsTimeout(0.25);  // a loading OBJ posts no event: look now and then
    } else {
        glfwWaitEvents();
    }
    if (v.input.events) {
        v.extra_frames = 2;  // ImGui settles hover and layout over a frame or two
        v.input.events = false;
    } else if (v.extra_frames > 0) {
        --v.extra_frames;
    }
}

// --frames: count the frames that show the finished image; at the last, screenshot
bool scripted_run_done(Viewer& v, int& exit_code) {
    if (v.options.frames <= 0) return false;
    const bool settled = v.frames.have_full && !v.frames.shown_preview &&
                         repeat_done(v) && !v.state.dirty && !v.worker->busy() &&
                         !v.loading.valid() && !v.grading->running();
    if (v.frames.failed && !v.worker->busy()) {
        exit_code = 1;
        return true;
    }
    if (!settled || ++v.frames.settled_frames < v.options.frames) return false;
    if (!v.options.screenshot.empty()) {
        int w = 0, h = 0;
        glfwGetFramebufferSize(v.window, &w, &h);
        try {
            write_screenshot(v.options.screenshot, w, h);
            const ImageRect& r = v.image_rect;
            char line[256];
            std::snprintf(
                line, sizeof line,
                "screenshot %s: window %dx%d, image at %.0f,%.0f size %.0fx%.0f",
                v.options.screenshot.c_str(), w, h, r.x, r.y, r.width, r.height);
            v.log.add(line);
            std::snprintf(
                line, sizeof line,
                "panel: modules start at %.0f, end at %.0f, window %.0f, scroll "
                "max %.0f",
                v.panel.modules_top, v.panel.modules_end, v.panel.window_height,
                v.panel.scroll_max);
            v.log.add(line);
            if (v.debug.open) {
                std::snprintf(
                    line, sizeof line, "debug view: %d triangles, %d lines",
                    v.debug.scene_vertices / 3,
                    int(v.debug.vertices.size() / 6 - v.debug.scene_vertices) / 2);
                v.log.add(line);
            }
        } catch (const std::exception& e) {
            report_error(v, e.what());
            exit_code = 2;
        }
    }
    return true;
}

// F12: the window as it is now, before the buffers swap
void take_screenshot(Viewer& v) {
    v.screenshot_requested = false;
    const std::string path = "raylab-window.png";
    int w = 0, h = 0;
    glfwGetFramebufferSize(v.window, &w, &h);
    try {
        write_screenshot(path, w, h);
        v.log.add("saved window screenshot " + path);
    } catch (const std::exception& e) {
        report_error(v, e.what());
    }
}

// The pinned pixel's shadow tests, one line per light and side (scripted checks)
void log_pinned_lights(Viewer& v) {
    const PixelReport& pin = v.inspector.pin;
    if (!v.inspector.pinned || !pin.probe) return;
    const auto add = [&](const PixelProbe& p, const char* who) {
        char ray[256];
        std::snprintf(ray, sizeof ray,
                      "pinned (%d, %d) %s ray o (%.3f, %.3f, %.3f) w (%.4f, %.4f, %.4f)",
                      pin.i, pin.j, who, p.ray.o.x, p.ray.o.y, p.ray.o.z, p.ray.w.x,
                      p.ray.w.y, p.ray.w.z);
        v.log.add(ray);
        for (const LightProbe& lp : p.lights) {
            char line[256];
            std::snprintf(line, sizeof line, "pinned (%d, %d) %s light %d: %s%s%s", pin.i,
                          pin.j, who, lp.light + 1,
                          !lp.tested   ? "not tested"
                          : lp.blocked ? "shadow"
                                       : "lit",
                          lp.blocker ? ", blocked by " : "", lp.blocker_name.c_str());
            std::string text = line;
            if (lp.area) {  // area light: the sample counts; the blocker is the first's
                std::snprintf(
                    line, sizeof line,
                    " (area light: %d samples, %d behind, %d blocked, %d visible)",
                    lp.samples, lp.backfacing_samples, lp.blocked_samples,
                    lp.visible_samples);
                text += line;
            }
            v.log.add(text);
        }
    };
    add(*pin.probe, "yours");
    if (pin.reference) add(*pin.reference, "reference");
}

// What the command line asked for at exit; a failed write is exit code 2, as in
// raylab-render. Nothing is saved when the command line's scene did not load (its error
// is the one message)
int exit_actions(Viewer& v, bool save) {
    int code = 0;
    if (save && !v.options.save_image.empty() && !save_image(v, v.options.save_image))
        code = 2;
    if (save && !v.options.save_view.empty() && !save_view(v, v.options.save_view))
        code = 2;
    if (save && !v.options.report.empty() && !save_report(v, v.options.report)) code = 2;
    v.log.add("final view: " + view_line(v.state.view));
    log_pinned_lights(v);
    return code;
}

}  // namespace

namespace {

// Setup: GLFW window with an OpenGL 3.3 core context, then Dear ImGui with the GLFW and
// OpenGL 3 backends. False (with a message) when there is no display or no context
bool setup_window(Viewer& v) {
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit()) {
        const char* display = std::getenv("DISPLAY");
        std::fprintf(
            stderr,
            "raylab: error: cannot open a window: %s (%s). Render without a "
            "window with raylab-render, or start the viewer under xvfb-run.\n",
            display && *display ? "no usable display" : "no display, DISPLAY is not set",
            glfw_last_error.c_str());
        return false;
    }
    v.window = open_window(v.options, v.state.scene_source);
    if (!v.window) {
        std::fprintf(stderr, "raylab: error: cannot open an OpenGL 3.3 window (%s)\n",
                     glfw_last_error.c_str());
        glfwTerminate();
        return false;
    }
    glfwMakeContextCurrent(v.window);
    glfwSwapInterval(1);   // vsync where the display has it
    install_callbacks(v);  // before the backend, which chains them

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the student's folder
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(v.window, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");
    v.texture = create_texture();
    return true;
}

// A progress bar over the image while a scene loads in the background; Cancel stops it
void draw_loading(Viewer& v) {
    if (!v.loading.valid() || !v.load_status) return;
    const ImVec2 size = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(size.x * 0.5f, size.y * 0.5f), ImGuiCond_Always,
                            ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowSize(ImVec2(std::min(420.0f, size.x * 0.8f), 0.0f));
    ImGui::Begin("Loading", nullptr,
                 ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoResize |
                     ImGuiWindowFlags_NoSavedSettings);
    ImGui::TextWrapped("%s", v.loading_source.c_str());
    char label[64];
    std::snprintf(label, sizeof label, "%s %.0f%%", v.load_status->stage.load(),
                  100.0 * v.load_status->fraction.load());
    ImGui::ProgressBar(v.load_status->fraction.load(), ImVec2(-1.0f, 0.0f), label);
    if (ImGui::Button("Cancel")) cancel_loading(v);
    ImGui::End();
}

// The UI scale (panel or --ui-scale): fonts and every size of the style, from the
// unscaled dark style so that repeated changes do not compound; the panel takes at most
// 45% of the window so the image keeps room at 1024x640
void apply_ui_scale(Viewer& v) {
    const float scale = v.state.ui_scale;
    if (scale != v.applied_ui_scale) {
        ImGuiStyle style;
        ImGui::StyleColorsDark(&style);
        style.ScaleAllSizes(scale);
        ImGui::GetStyle() = style;
        ImGui::GetIO().FontGlobalScale = scale;
        v.applied_ui_scale = scale;
    }
    const float window_w = ImGui::GetIO().DisplaySize.x;
    v.panel_width = std::min(430.0f * scale, std::max(200.0f, 0.45f * window_w));
}

// Cleanup: stop the threads (they post GLFW events) before GLFW goes
void cleanup(Viewer& v) {
    delete_texture(v.texture);
    debug_view_free(v.debug);
    v.worker.reset();
    v.grading.reset();
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(v.window);
    glfwTerminate();
}

}  // namespace

int run_viewer(const Options& options, const ViewerOptions& viewer_options) {
    // Setup: flags and files first, so that their errors come before any window
    auto v = std::make_unique<Viewer>();
    v->exe_path = self_path();
    init_viewer(*v, options, viewer_options, [] { glfwPostEmptyEvent(); });
    v->state.ui_scale = viewer_options.ui_scale;
    v->debug.open = viewer_options.debug_view;
    if (viewer_options.pin_i >= 0) {
        v->inspector.pinned = true;
        v->inspector.pin_i = std::min(viewer_options.pin_i, options.settings.width - 1);
        v->inspector.pin_j = std::min(viewer_options.pin_j, options.settings.height - 1);
        v->panel.scroll_to_inspector = true;
    }
    if (!setup_window(*v)) return 2;
    if (viewer_options.run_tests) run_tests(*v);

    // Main loop
    int exit_code = 0;
    double last_time = glfwGetTime();
    while (!glfwWindowShouldClose(v->window) && !v->quit) {
        wait_for_events(*v);
        if (v->quit) break;
        if (!finish_loading(*v)) {
            exit_code = 2;
            v->quit = true;
        }
        poll_grading(*v);
        take_result(*v);

        // Start the Dear ImGui frame; input, panel, image
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        apply_ui_scale(*v);  // after the backend set DisplaySize
        ImGui::NewFrame();
        const double now = glfwGetTime();
        handle_input(*v, static_cast<float>(now - last_time));
        last_time = now;
        draw_panel(*v);
        draw_image(*v);
        draw_loading(*v);
        debug_view_window(*v);
        update_probes(*v);

        // A drag ended: replace the coarse preview with the full image
        if (!v->state.interacting && v->frames.last_job_preview) v->state.dirty = true;
        refresh_texture(*v);

        // Rendering
        ImGui::Render();
        int width = 0, height = 0;
        glfwGetFramebufferSize(v->window, &width, &height);
        glViewport(0, 0, width, height);
        glClearColor(0.12f, 0.12f, 0.13f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        // A new job starts once this window frame is drawn (before the swap, which may
        // wait for the display): with a software OpenGL (Mesa's llvmpipe, as under
        // Xvfb) the frame's drawing otherwise runs on the render's cores while it
        // starts and slows it (docs/decisions/0010)
        if (v->state.dirty) glFinish();
        submit_if_dirty(*v);
        if (v->screenshot_requested) take_screenshot(*v);
        if (scripted_run_done(*v, exit_code)) v->quit = true;
        glfwSwapBuffers(v->window);
        frame_shown(*v);
    }
    const int exit_status = exit_actions(*v, !v->initial_scene_failed);
    const int code = exit_code != 0 ? exit_code : exit_status;
    // A load still running (tinyobjloader's parse and the BVH build cannot stop midway):
    // ask it to stop, and do not wait long for it, so Ctrl+Q always exits
    cancel_loading(*v);
    if (v->loading.valid() && v->loading.wait_for(std::chrono::milliseconds(500)) !=
                                  std::future_status::ready) {
        std::fflush(nullptr);
        std::_Exit(code);
    }
    cleanup(*v);
    return code;
}

}  // namespace raylab::viewer
