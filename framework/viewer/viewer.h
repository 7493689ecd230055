// viewer/viewer.h: the viewer's state, one plain struct of plain parts.
//
// docs/style.md rule 13: the panel edits ViewerState, the renderer reads it, and a widget
// that returns true marks it dirty. The main loop (app.cpp) draws the panel
// (panel_*.cpp), handles keys and the mouse (input.cpp), shows the image
// (image_view.cpp) and sends a job to the background renderer when something changed
// (actions.cpp).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "debug_view.h"
#include "grader.h"
#include "log.h"
#include "raylab/renderer.h"
#include "raylab/scene.h"
#include "render_worker.h"
#include "tone_map.h"
#include "view_file.h"
#include "viewer_options.h"

struct GLFWwindow;

namespace raylab::viewer {

/// What the panel edits and the renderer reads.
struct ViewerState {
    Scene scene;  ///< geometry, lights, ambient (main thread's copy)
    std::string scene_source = "cornell";  ///< "cornell", "dtu" or the OBJ path
    std::uint64_t scene_version = 1;       ///< bumped whenever the geometry changes
    std::uint64_t sent_version = 0;        ///< the version the worker has
    View view;
    int selected_light = 0;  ///< the light W/A/S/D/Q/E move
    RenderSettings settings;
    float exposure = 0.0f;  ///< stops
    ModuleSelection modules;
    std::uint32_t stubs = 0;      ///< bit k: module k + 1 is still a stub
    bool compare = false;         ///< render the reference too and compare
    bool show_difference = true;  ///< with compare: show the heat map, not the image
    bool inspector = true;        ///< tooltip of the pixel under the mouse
    bool show_samples = false;    ///< show samples per pixel as a heat map
    int image_scale = 0;          ///< window pixels per image pixel; 0: fit
    float ui_scale = 1.0f;        ///< text and widget size (panel, --ui-scale)
    bool dirty = true;            ///< the image is out of date: render again
    bool interacting = false;     ///< a value is being dragged: coarse previews
    bool retone = true;           ///< the texture is out of date: upload again
    bool force_render = false;    ///< render even a frame the worker has (--repeat)
};

/// The panel's text fields and messages.
struct PanelState {
    std::string obj_path;
    std::string view_path = "view.txt";
    std::string image_path = "raylab.png";
    std::string report_dir;
    std::string error;       ///< shown in red until the next successful action
    View view_edit;          ///< the camera fields; applied only when valid
    std::string view_error;  ///< why view_edit is not applied
    int size_edit[2] = {640, 480};
    int scene_choice = 0;                     ///< index into builtin_scene_names()
    float modules_top = 0, modules_end = 0;   ///< the Modules section (log)
    float scroll_max = 0, window_height = 0;  ///< panel layout (log)
    bool hint_dismissed = false;              ///< the first-run hint's "Got it"
    std::set<std::string> widgets_logged;     ///< note_widget's names
    bool scroll_to_inspector = false;  ///< --pin: show the inspector at the panel's top
    float ui_scale_edit = 0.0f;        ///< the UI scale slider while it is dragged
    int grade_shown = -1;              ///< module whose grader output is shown; -1: none
};

/// The frames the renderer sent back.
struct FrameState {
    std::shared_ptr<const Image> shown;  ///< newest image, preview or full
    bool shown_preview = false;
    int shown_factor = 1;         ///< a preview's factor (1: full size)
    std::uint64_t shown_job = 0;  ///< the job shown belongs to (< last_job: out of date)
    std::shared_ptr<const Image> full;  ///< newest full-size image (save, report)
    bool have_full = false;
    FrameStats last;                ///< of shown
    FrameStats last_full;           ///< of full
    std::vector<float> history_ms;  ///< render times, oldest first
    std::optional<Difference> difference;
    std::uint64_t next_job = 1;
    std::uint64_t last_job = 0;  ///< the newest job submitted
    RenderJob sent;              ///< that job (without its scene)
    bool last_job_preview = false;
    int full_frames = 0;  ///< full frames received
    // What the viewer did not do (frame statistics): frames with the same inputs as a
    // kept one, exposure changes that only tone-mapped again, and the tiles of the last
    // full frame that changed (-1: nothing to compare with)
    int frames_rendered = 0, frames_reused = 0, retones = 0;
    bool last_reused = false;
    int tiles_changed = -1, tiles_total = 0;
    bool failed = false;     ///< the newest frame failed to render
    int settled_frames = 0;  ///< frames drawn with the finished image (--frames)
    std::chrono::steady_clock::time_point submitted;  ///< when last_job was sent
    std::chrono::steady_clock::time_point finished;   ///< when the worker handed it
    std::chrono::steady_clock::time_point taken;      ///< when the main loop took it
    bool on_screen_pending = false;  ///< a full frame is uploaded: time it at the swap
    double latency_ms = 0.0;  ///< last full frame: change to screen (submit .. swap)
    double tone_ms = 0.0;     ///< last tone mapping and texture upload (main thread)
    int repeat = 1;           ///< --repeat N: render the same full frame N times
    std::vector<double> repeat_render_ms, repeat_latency_ms;  ///< --repeat's times
};

/// What the inspector knows about one pixel.
struct PixelReport {
    int i = -1, j = -1;                   ///< full-size pixel; -1: none
    std::uint64_t job = 0;                ///< the frame the probes belong to
    std::optional<PixelProbe> probe;      ///< with the current modules
    std::optional<PixelProbe> reference;  ///< with all reference modules (if available)
};

/// The pixel inspector: the pixel under the mouse (tooltip) and a pinned one (panel).
struct InspectorState {
    bool hovering = false;
    int i = 0, j = 0;  ///< full-size pixel under the mouse
    bool pinned = false;
    int pin_i = 0, pin_j = 0;
    PixelReport hover, pin;
};

/// Keys and mouse between frames (input.cpp).
struct InputState {
    bool events = false;       ///< any input since the last frame
    bool tapped[512] = {};     ///< pressed since the last frame (quick taps count)
    bool mouse_moved = false;  ///< the pointer moved since the window opened
    double first_x = -1, first_y = -1;  ///< where the pointer was first seen
    bool dragging = false;              ///< orbiting with the left button
    double drag_x = 0, drag_y = 0;
    double wheel = 0;  ///< scroll since the last frame, over the image
};

/// Where the image is drawn, in window coordinates.
struct ImageRect {
    float x = 0, y = 0, width = 0, height = 0;
};

/// Progress of the scene loading in the background: written by the loading thread, read
/// by the UI thread (actions.cpp)
struct LoadStatus {
    std::atomic<const char*> stage{"reading"};
    std::atomic<float> fraction{0.0f};
    std::atomic<bool> cancel{false};
    bool initial = false;  ///< the --scene of the command line (errors end scripted runs)
    std::optional<ViewFile> view;  ///< --load-view, applied when the scene is in
};

struct Viewer {
    GLFWwindow* window = nullptr;
    std::string exe_path;  ///< /proc/self/exe, to find the graders
    ViewerOptions options;
    ViewerState state;
    PanelState panel;
    FrameState frames;
    InspectorState inspector;
    InputState input;
    ImageRect image_rect;
    Log log;
    std::unique_ptr<RenderWorker> worker;
    std::unique_ptr<GradingRun> grading;
    std::string grading_binary;  ///< empty: not built
    bool grading_logged = true;  ///< the last run's results are in the log
    std::future<Scene> loading;  ///< an OBJ being loaded in the background
    std::string loading_source;
    std::shared_ptr<LoadStatus> load_status;  ///< the progress of loading
    std::function<void()> wake;  ///< wakes the UI thread (posts an empty GLFW event)
    DebugView debug;             ///< the 3D debug view window
    unsigned texture = 0;        ///< GL texture of the shown image or heat map
    ToneMapper tone;             ///< the shown image to sRGB bytes for the texture
    std::vector<std::uint8_t> texture_bytes;  ///< the bytes last uploaded
    int texture_width = 0;                    ///< 0: nothing uploaded yet
    int texture_height = 0;
    bool texture_is_heat = false;   ///< the texture shows the difference heat map
    float panel_width = 430.0f;     ///< at this frame's UI scale and window width
    float overlay_height = 0.0f;    ///< the timing strip above the image
    float applied_ui_scale = 0.0f;  ///< the scale the ImGui style has now
    int extra_frames = 2;           ///< frames to draw before sleeping (ImGui settles)
    bool screenshot_requested = false;  ///< F12: write the window at the end of a frame
    bool quit = false;
    bool initial_scene_failed = false;  ///< the command line's OBJ did not load
};

}  // namespace raylab::viewer
