// raylab/options.h: the command-line flags shared by raylab-render and the viewer.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "raylab/modules.h"
#include "raylab/renderer.h"
#include "raylab/scene.h"
#include "raylab/scenes.h"

namespace raylab {

/// What the flags ask for. Unset optionals keep the scene's own defaults.
struct Options {
    std::string scene = "cornell";        ///< --scene cornell|dtu|FILE.obj
    std::optional<Vec3> eye, lookat, up;  ///< --eye, --lookat, --up
    std::optional<float> fov;             ///< --fov DEGREES (vertical)
    std::vector<PointLight> lights;       ///< --light x,y,z:r,g,b (repeatable)
    std::optional<float> ambient;         ///< --ambient A
    RenderSettings settings;              ///< --width --height --mode --shadows --threads
    float exposure = 0.0f;                ///< --exposure EV (stops)
    std::string output;                   ///< --output FILE.png|FILE.pfm
    ModuleSelection modules;              ///< --student / --reference, after auto
    bool modules_given = false;           ///< any --student or --reference seen
    int repeat = 1;                  ///< --repeat N: render N times, report the median
    bool help = false;               ///< --help
    std::vector<std::string> extra;  ///< flags the caller handles itself (viewer)
};

/// Parses argv. Flags the viewer adds (--frames, --screenshot, ...) are collected in
/// extra when allow_extra is true, rejected otherwise. Throws raylab::Error naming the
/// flag.
Options parse_options(int argc, const char* const* argv, bool allow_extra = false);

/// The one parser of the numbers flags take (both binaries): a decimal of any length
/// (`12`, `-2.5`, `3e-4`, `+.5`), finite as a float. No blanks, hex, `inf`, `nan`.
/// Throws raylab::Error "FLAG: 'TEXT' is not a finite number".
float parse_flag_number(const std::string& flag, const std::string& text);

/// A whole decimal number (any number of leading zeros) in lo..hi. Throws raylab::Error
/// naming the flag and the range.
long long parse_flag_whole(const std::string& flag, const std::string& text, long long lo,
                           long long hi);

/// The help text for the shared flags.
std::string options_help();

/// The scene the options name, with their view, lights and ambient applied and checked.
/// Throws raylab::Error.
Scene make_scene(const Options& options, const LoadProgress& progress = {});

/// Modules whose student code is still a stub: bit k for module k + 1. Calls each
/// contract function of the student's code once, through the registry's probes
/// (framework/src/stub_probes.cpp).
std::uint32_t detect_stubs();

/// The default selection: the student's code for every module the student has started,
/// the reference for stubs (when this build has it). Explicit flags override it.
ModuleSelection auto_selection();

/// The modules in selection that are still stubs, as a comma-separated list of names.
std::string stub_modules_running(const ModuleSelection& selection);

}  // namespace raylab
