// Keys and mouse (viewer/input.h).
#include "input.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "actions.h"
#include "camera_control.h"

namespace raylab::viewer {

namespace {

constexpr int kCameraKeys[] = {GLFW_KEY_UP, GLFW_KEY_DOWN, GLFW_KEY_LEFT, GLFW_KEY_RIGHT,
                               GLFW_KEY_W,  GLFW_KEY_S,    GLFW_KEY_A,    GLFW_KEY_D,
                               GLFW_KEY_Q,  GLFW_KEY_E};

Viewer& viewer_of(GLFWwindow* window) {
    return *static_cast<Viewer*>(glfwGetWindowUserPointer(window));
}

void on_key(GLFWwindow* window, int key, int, int action, int mods) {
    Viewer& v = viewer_of(window);
    v.input.events = true;
    // Ctrl+Q quits; its Q is no light key, even when Ctrl is up again by the next frame
    const bool ctrl = (mods & GLFW_MOD_CONTROL) != 0;
    if (action == GLFW_PRESS && key == GLFW_KEY_Q && ctrl) v.quit = true;
    if (action == GLFW_PRESS && key == GLFW_KEY_F12) v.screenshot_requested = true;
    if (action == GLFW_PRESS && !ctrl && key >= 0 && key < 512)
        v.input.tapped[key] = true;
}

void on_event(GLFWwindow* window) {
    viewer_of(window).input.events = true;
}

// Keys held, or tapped since the last frame, move the camera for dt seconds
bool key_active(Viewer& v, int key) {
    return glfwGetKey(v.window, key) == GLFW_PRESS || v.input.tapped[key];
}

void keys_move_camera(Viewer& v, float dt) {
    ViewerState& s = v.state;
    const float size = scene_size(s.scene, s.view);
    const float step = 0.3f * size * dt;      // walking: 0.3 scene sizes per second
    const float angle = radians(60.0f) * dt;  // turning: 60 degrees per second
    View view = s.view;
    if (key_active(v, GLFW_KEY_UP)) view = walk(view, step);
    if (key_active(v, GLFW_KEY_DOWN)) view = walk(view, -step);
    if (key_active(v, GLFW_KEY_LEFT)) view = turn(view, angle);
    if (key_active(v, GLFW_KEY_RIGHT)) view = turn(view, -angle);
    if (view.eye != s.view.eye || view.lookat != s.view.lookat) {
        if (apply_view(v, view)) v.panel.view_edit = view;
    }

    // The selected light, in the camera's walking frame
    if (s.scene.lights.empty()) return;
    s.selected_light = std::clamp(s.selected_light, 0, int(s.scene.lights.size()) - 1);
    const float right =
        float(key_active(v, GLFW_KEY_D)) - float(key_active(v, GLFW_KEY_A));
    const float up = float(key_active(v, GLFW_KEY_Q)) - float(key_active(v, GLFW_KEY_E));
    const float forward =
        float(key_active(v, GLFW_KEY_W)) - float(key_active(v, GLFW_KEY_S));
    if (right != 0.0f || up != 0.0f || forward != 0.0f) {
        Vec3& p = s.scene.lights[s.selected_light].p;
        p = move_in_view(s.view, p, right * step, up * step, forward * step);
        s.dirty = true;
    }
}

void mouse_moves_camera(Viewer& v) {
    const ImGuiIO& io = ImGui::GetIO();
    ViewerState& s = v.state;
    if (ImGui::IsMouseClicked(ImGuiMouseButton_Left) && !io.WantCaptureMouse)
        v.input.dragging = true;
    if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) v.input.dragging = false;
    View view = s.view;
    if (v.input.dragging && (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f)) {
        // Drag right: the scene turns right with the mouse; drag down: the eye rises
        const float per_pixel = radians(0.4f);
        view = orbit(view, -io.MouseDelta.x * per_pixel, io.MouseDelta.y * per_pixel);
    }
    if (!io.WantCaptureMouse && io.MouseWheel != 0.0f) {
        view = dolly(view, std::pow(0.9f, io.MouseWheel), scene_size(s.scene, s.view));
    }
    if (view.eye != s.view.eye) {
        if (apply_view(v, view)) v.panel.view_edit = view;
    }
}

}  // namespace

void install_callbacks(Viewer& v) {
    glfwSetWindowUserPointer(v.window, &v);
    glfwSetKeyCallback(v.window, on_key);
    glfwSetCharCallback(v.window, [](GLFWwindow* w, unsigned) { on_event(w); });
    glfwSetCursorPosCallback(v.window, [](GLFWwindow* w, double x, double y) {
        on_event(w);
        // The pointer's position when the window opens is no hover (a tooltip would
        // cover scripted screenshots): only a move counts
        InputState& in = viewer_of(w).input;
        if (in.first_x < 0) in.first_x = x, in.first_y = y;
        if (x != in.first_x || y != in.first_y) in.mouse_moved = true;
    });
    glfwSetMouseButtonCallback(v.window,
                               [](GLFWwindow* w, int, int, int) { on_event(w); });
    glfwSetScrollCallback(v.window, [](GLFWwindow* w, double, double) { on_event(w); });
    glfwSetWindowFocusCallback(v.window, [](GLFWwindow* w, int) { on_event(w); });
    glfwSetCursorEnterCallback(v.window, [](GLFWwindow* w, int) { on_event(w); });
    glfwSetFramebufferSizeCallback(v.window,
                                   [](GLFWwindow* w, int, int) { on_event(w); });
    glfwSetWindowRefreshCallback(v.window, on_event);
}

void handle_input(Viewer& v, float dt) {
    const ImGuiIO& io = ImGui::GetIO();
    // A frame after a long sleep must not jump: clamp the step to [1/60, 1/20] s
    dt = std::clamp(dt, 1.0f / 60.0f, 1.0f / 20.0f);
    if (!io.WantCaptureKeyboard && !io.KeyCtrl) keys_move_camera(v, dt);
    std::fill(std::begin(v.input.tapped), std::end(v.input.tapped), false);
    mouse_moves_camera(v);
    // Dragging a slider or the camera, or holding a key: coarse previews. A text field
    // with the keyboard is active too, but typing is not a drag
    const bool dragging_item =
        ImGui::IsAnyItemActive() && ImGui::IsMouseDown(ImGuiMouseButton_Left);
    v.state.interacting = camera_keys_held(v) || v.input.dragging || dragging_item;
}

bool camera_keys_held(const Viewer& v) {
    for (int key : kCameraKeys) {
        if (glfwGetKey(v.window, key) == GLFW_PRESS) return true;
    }
    return false;
}

}  // namespace raylab::viewer
