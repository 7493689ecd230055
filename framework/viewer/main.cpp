// raylab: the live viewer. The ray-cast image in a window, and a panel that changes
// everything the exercises are about while the student watches the result.
//
//   raylab --scene cornell --reference camera
//   raylab --width 320 --height 240 --frames 5 --screenshot shot.png   (CI, under Xvfb)
//
// Accepts the flags of raylab-render, plus the viewer's own (viewer_options.h).
#include <cstdio>
#include <exception>

#include "app.h"
#include "raylab/error.h"
#include "raylab/input_file.h"
#include "raylab/options.h"
#include "viewer_options.h"

namespace {

void print_help() {
    std::printf(
        "raylab: the live viewer of the raylab ray caster.\n\n"
        "Usage: raylab [options]\n\n%s%s"
        "Keys: arrows walk and turn the camera, W/A/S/D/Q/E move the selected light,\n"
        "left drag orbits, the wheel moves closer, right click pins a pixel in the\n"
        "inspector, F12 saves a screenshot of the window, Ctrl+Q quits.\n"
        "See docs/viewer.md.\n",
        raylab::options_help().c_str(), raylab::viewer::viewer_options_help().c_str());
}

}  // namespace

int main(int argc, char** argv) {
    using namespace raylab;
    try {
        const Options options = parse_options(argc, argv, /*allow_extra=*/true);
        if (options.help) {
            print_help();
            return 0;
        }
        if (!options.output.empty())
            throw Error("--output is raylab-render's; the viewer has --save-image FILE");
        const viewer::ViewerOptions viewer_options = viewer::parse_viewer_options(
            options.extra, options.settings.width, options.settings.height);
        return viewer::run_viewer(options, viewer_options);
    } catch (const Error& e) {
        std::fprintf(stderr, "raylab: error: %s\n", printable(e.what(), 4000).c_str());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "raylab: internal error: %s\n",
                     printable(e.what(), 4000).c_str());
        return 3;
    }
}
