// viewer/input.h: keys and mouse (COMS30115 controls).
//
//   Up / Down      walk forward / back          Left / Right   turn (yaw)
//   W / S          light forward / back         A / D          light left / right
//   Q / E          light up / down              Ctrl+Q         quit
//   left drag      orbit about the look-at      wheel          closer / farther
//   right click    pin the pixel in the inspector
//   F12            screenshot of the window: raylab-window.png
//
// Keys do nothing while an ImGui field has the keyboard (io.WantCaptureKeyboard), the
// mouse nothing while it is over the panel (io.WantCaptureMouse).
#pragma once

#include "viewer.h"

namespace raylab::viewer {

/// Installs the GLFW callbacks that wake the loop and record quick key taps. Call before
/// ImGui_ImplGlfw_InitForOpenGL(window, true), which chains them.
void install_callbacks(Viewer& v);

/// Applies keys and mouse to the camera and the selected light; dt is the time since
/// the previous frame [s]. Call between ImGui::NewFrame and the panel.
void handle_input(Viewer& v, float dt);

/// True while a camera or light key is held (the loop then draws at a steady rate).
bool camera_keys_held(const Viewer& v);

}  // namespace raylab::viewer
