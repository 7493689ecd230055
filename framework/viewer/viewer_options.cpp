// The viewer's own flags (viewer/viewer_options.h).
#include "viewer_options.h"

#include "raylab/error.h"
#include "raylab/input_checks.h"
#include "raylab/input_file.h"
#include "raylab/options.h"

namespace raylab::viewer {

namespace {

bool is_flag(const std::string& word) {
    return word.rfind("--", 0) == 0;
}

int parse_count(const std::string& flag, const std::string& text, int lo, int hi) {
    return static_cast<int>(parse_flag_whole(flag, text, lo, hi));
}

float parse_scale(const std::string& text) {
    const float x = parse_flag_number("--ui-scale", text);
    if (!(x >= kMinUiScale && x <= kMaxUiScale))
        throw Error("--ui-scale: " + printable(text) + " is outside 0.5..3");
    return x;
}

void parse_window(const std::string& text, ViewerOptions& o) {
    const size_t x = text.find('x');
    if (x == std::string::npos)
        throw Error("--window: '" + printable(text) + "' is not WxH");
    o.window_width = parse_count("--window", text.substr(0, x), 320, 8192);
    o.window_height = parse_count("--window", text.substr(x + 1), 240, 8192);
}

}  // namespace

ViewerOptions parse_viewer_options(const std::vector<std::string>& extra, int image_width,
                                   int image_height) {
    ViewerOptions o;
    for (size_t k = 0; k < extra.size(); ++k) {
        const std::string& flag = extra[k];
        const bool has_value = k + 1 < extra.size() && !is_flag(extra[k + 1]);
        const auto value = [&]() -> std::string {
            if (!has_value) throw Error(flag + " needs a value (see --help)");
            return extra[++k];
        };
        const auto no_value = [&]() {
            if (has_value)
                throw Error(flag + " takes no value, got '" + printable(extra[k + 1]) +
                            "'");
        };
        if (flag == "--frames") {
            o.frames = parse_count(flag, value(), 1, 1000000);
        } else if (flag == "--screenshot") {
            o.screenshot = value();
            check_output_path(o.screenshot, OutputKind::png, flag);
        } else if (flag == "--save-image") {
            o.save_image = value();
            check_output_path(o.save_image, OutputKind::image, flag);
        } else if (flag == "--save-view") {
            o.save_view = value();
            check_output_path(o.save_view, OutputKind::text, flag);
        } else if (flag == "--load-view") {
            o.load_view = value();
        } else if (flag == "--report") {
            o.report = value();
            check_output_path(o.report, OutputKind::folder, flag);
        } else if (flag == "--window") {
            parse_window(value(), o);
        } else if (flag == "--image-scale") {
            o.image_scale = parse_count(flag, value(), 0, 16);
        } else if (flag == "--debug-view") {
            no_value();
            o.debug_view = true;
        } else if (flag == "--pin") {
            const std::string text = value();
            const size_t comma = text.find(',');
            if (comma == std::string::npos)
                throw Error("--pin: '" + printable(text) + "' is not I,J");
            // A pixel of the image: I in 0..width-1, J in 0..height-1
            o.pin_i = parse_count("--pin: I", text.substr(0, comma), 0, image_width - 1);
            o.pin_j =
                parse_count("--pin: J", text.substr(comma + 1), 0, image_height - 1);
        } else if (flag == "--ui-scale") {
            o.ui_scale = parse_scale(value());
        } else if (flag == "--compare") {
            no_value();
            o.compare = true;
        } else if (flag == "--show-samples") {
            no_value();
            o.show_samples = true;
        } else if (flag == "--run-tests") {
            no_value();
            o.run_tests = true;
        } else {
            throw Error("unknown option '" + printable(flag) + "' (see --help)");
        }
    }
    if (!o.screenshot.empty() && o.frames == 0) o.frames = 3;
    return o;
}

std::string viewer_options_help() {
    return R"(Viewer:
  --window WxH          window size (default 1280x800)
  --image-scale S       window pixels per image pixel (default 0: fit the window)
  --ui-scale F          text and widget size, 0.5..3 (default 1; 1.5 for projectors)
  --debug-view          open the 3D debug view (scene, pinned pixel's rays)
  --pin I,J             pin pixel (I, J) in the inspector (shadow rays, debug view)
  --compare             start with the difference to the reference shown
  --show-samples        start with the samples per pixel shown as a heat map
  --run-tests           run the graders of every module at start
  --load-view FILE      camera and lights from a view file (see docs/viewer.md)
Scripted runs (CI):
  --frames N            quit after N frames of the finished full-size image
  --repeat N            render the full frame N times (no reuse), log the median
                        render time and time from the change to the screen
  --screenshot FILE     write the window as FILE.png at the last frame (implies
                        --frames 3 unless given)
  --save-image FILE     write the rendered image (.png or .pfm) at exit
  --save-view FILE      write camera and lights at exit
  --report DIR          write a bug-report folder (view, settings, image, log) at exit
)";
}

}  // namespace raylab::viewer
