// viewer/viewer_options.h: the flags only the viewer has (--frames, --screenshot, ...).
//
// The shared flags (--scene, --eye, --width, --student, ...) are parsed by
// raylab::parse_options; what it does not know lands in Options::extra and is parsed
// here, so the viewer and raylab-render accept the same scene, camera and module flags.
#pragma once

#include <string>
#include <vector>

namespace raylab::viewer {

constexpr float kMinUiScale = 0.5f;  ///< --ui-scale and the panel's slider
constexpr float kMaxUiScale = 3.0f;

struct ViewerOptions {
    int frames = 0;           ///< --frames N: quit after N frames of the finished image
    std::string screenshot;   ///< --screenshot FILE.png: the window, at the last frame
    std::string save_image;   ///< --save-image FILE: the rendered image, at exit
    std::string save_view;    ///< --save-view FILE: camera and lights, at exit
    std::string load_view;    ///< --load-view FILE: camera and lights, at start
    std::string report;       ///< --report DIR: a bug-report folder, at exit
    int window_width = 1280;  ///< --window WxH
    int window_height = 800;
    bool debug_view = false;     ///< --debug-view: open the 3D debug view at start
    int pin_i = -1, pin_j = -1;  ///< --pin I,J: pixel pinned in the inspector at start
    float ui_scale = 1.0f;  ///< --ui-scale F: text and widget size (projectors, high DPI)
    int image_scale = 0;    ///< --image-scale S: window pixels per image pixel; 0 fits
    bool compare = false;   ///< --compare: start with the difference to the reference
    bool show_samples = false;  ///< --show-samples: the samples-per-pixel heat map
    bool run_tests = false;     ///< --run-tests: run the graders at start
};

/// Parses the flags parse_options left in Options::extra; --pin must name a pixel of the
/// image_width x image_height image. Throws raylab::Error naming the flag.
ViewerOptions parse_viewer_options(const std::vector<std::string>& extra,
                                   int image_width = 640, int image_height = 480);

/// The help text of the viewer's own flags.
std::string viewer_options_help();

}  // namespace raylab::viewer
