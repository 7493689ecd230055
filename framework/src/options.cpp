// Command-line flags (raylab/options.h).
#include "raylab/options.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <tuple>

#include "raylab/error.h"
#include "raylab/input_checks.h"
#include "raylab/input_file.h"
#include "raylab/scenes.h"

namespace raylab {

float parse_flag_number(const std::string& flag, const std::string& text) {
    float x = 0.0f;
    switch (parse_decimal(text, x)) {
        case Decimal::ok:
            return x;
        case Decimal::out_of_range:
            throw Error(flag + ": '" + printable(text) +
                        "' is not a finite number (beyond +-3.4e38, a float's range)");
        case Decimal::not_decimal:
            break;
    }
    throw Error(flag + ": '" + printable(text) + "' is not a finite number");
}

long long parse_flag_whole(const std::string& flag, const std::string& text, long long lo,
                           long long hi) {
    long long x = 0;
    if (!parse_whole(text, lo, hi, x))
        throw Error(flag + ": '" + printable(text) + "' is not a whole number in " +
                    std::to_string(lo) + ".." + std::to_string(hi));
    return x;
}

namespace {

float parse_float(const std::string& flag, const std::string& text) {
    return parse_flag_number(flag, text);
}

int parse_int(const std::string& flag, const std::string& text) {
    return static_cast<int>(parse_flag_whole(flag, text, -1000000000LL, 1000000000LL));
}

Vec3 parse_vec3(const std::string& flag, const std::string& text) {
    std::vector<std::string> parts;
    std::stringstream ss(text);
    for (std::string part; std::getline(ss, part, ',');)
        parts.push_back(part);
    if (parts.size() != 3 || text.back() == ',')
        throw Error(flag + ": '" + printable(text) + "' is not three numbers x,y,z");
    // One at a time, so the first bad number is the one named
    const float x = parse_float(flag, parts[0]);
    const float y = parse_float(flag, parts[1]);
    const float z = parse_float(flag, parts[2]);
    return Vec3(x, y, z);
}

// A word parse() knows (a shading mode, a sampling scheme); its error names the flag
// and shows the word escaped
template <typename Parse>
auto parse_word(const std::string& flag, const std::string& word, Parse parse) {
    try {
        return parse(word);
    } catch (const Error& e) {
        throw Error(flag + ": " + printable(e.what(), 400));
    }
}

bool parse_on_off(const std::string& flag, const std::string& text) {
    if (text == "on" || text == "true" || text == "1") return true;
    if (text == "off" || text == "false" || text == "0") return false;
    throw Error(flag + ": '" + printable(text) + "' is neither on nor off");
}

}  // namespace

namespace {

// "Modules (names: ..., IDs such as 04_sphere, numbers 1-N, or all):" from the registry,
// wrapped at 88 columns
std::string module_names_help() {
    const auto& infos = module_infos();
    std::string text = "Modules (names:";
    for (const ModuleInfo& info : infos)
        text += std::string(" ") + info.name;
    text += ", IDs such as " + std::string(infos[std::min(3, kModuleCount - 1)].id) +
            ", numbers 1-" + std::to_string(kModuleCount) + ", or all):";
    std::string wrapped, line;
    std::istringstream words(text);
    for (std::string word; words >> word;) {
        if (!line.empty() && line.size() + 1 + word.size() > 88) {
            wrapped += line + "\n";
            line.clear();
        }
        line += (line.empty() ? "" : " ") + word;
    }
    return wrapped + line;
}

}  // namespace

std::string options_help() {
    std::string help = R"(Scene and view:
  --scene NAME          cornell (default), dtu, or a Wavefront FILE.obj (+ .mtl)
  --eye X,Y,Z           eye point (default: the scene's view)
  --lookat X,Y,Z        look-at point
  --up X,Y,Z            up direction (must not be parallel to lookat - eye)
  --fov DEGREES         vertical field of view in [0.1, 179.9]; d = 1/(2 tan(fov/2))
  --light X,Y,Z:R,G,B   point light at X,Y,Z with intensity R,G,B [W/sr]; repeatable;
                        replaces the scene's lights
  --ambient A           constant indirect light, times rho (the COMS30115 lab's 0.5
                        without its missing 1/pi is 0.159; see docs/conventions.md)
Rendering:
  --width W --height H  image size in pixels (default 640 x 480)
  --mode MODE           lambert (default), normals, base, depth
  --shadows on|off      hard shadows (default on)
  --exposure EV         tone-mapping exposure in stops (default 0)
  --threads N           worker threads (default: all cores)
Sampling (modules 09 and 10; the defaults are one ray per pixel and point lights):
  --spp N               samples per pixel, a square 1, 4, 9, 16, ... 1024 (default 1)
  --aa SCHEME           grid, stratified (default) or adaptive: one sample everywhere,
                        N where a pixel and its neighbours disagree
  --aa-threshold C      adaptive: refine where the contrast exceeds C in [0, 1]
                        (default 0.1)
  --light-size S        replace each point light by a square area light of side S
                        facing the scene (default 0: point lights)
  --light-samples N     shadow rays per area light and point, 1..1024 (default 1)
  --light-sampling S    stratified (default) or uniform
  --seed N              seed of the random samples (default 1)
@MODULES@
  --student LIST        run the student's exercises/ code for these modules
  --reference LIST      run the reference solutions/ for these modules
                        (default: the student's code where started, else the reference;
                        the lists change that default in the order given)
)";
    help.replace(help.find("@MODULES@"), 9, module_names_help());
    return help;
}

Options parse_options(int argc, const char* const* argv, bool allow_extra) {
    Options o;
    std::vector<std::tuple<std::string, std::string, Impl>> module_lists;
    for (int k = 1; k < argc; ++k) {
        const std::string flag = argv[k];
        const auto value = [&]() -> std::string {
            if (k + 1 >= argc) throw Error(flag + " needs a value (see --help)");
            return argv[++k];
        };
        if (flag == "--help" || flag == "-h") {
            o.help = true;
        } else if (flag == "--scene") {
            o.scene = value();
        } else if (flag == "--eye") {
            o.eye = parse_vec3(flag, value());
            check_point(*o.eye, flag);
        } else if (flag == "--lookat") {
            o.lookat = parse_vec3(flag, value());
            check_point(*o.lookat, flag);
        } else if (flag == "--up") {
            o.up = parse_vec3(flag, value());
            check_point(*o.up, flag);
        } else if (flag == "--fov") {
            o.fov = parse_float(flag, value());
            check_fov(*o.fov, flag);
        } else if (flag == "--light") {
            const std::string text = value();
            const size_t colon = text.find(':');
            if (colon == std::string::npos)
                throw Error("--light: '" + printable(text) + "' is not X,Y,Z:R,G,B");
            o.lights.push_back(PointLight{parse_vec3(flag, text.substr(0, colon)),
                                          parse_vec3(flag, text.substr(colon + 1))});
            check_light(o.lights.back(), flag);
        } else if (flag == "--ambient") {
            o.ambient = parse_float(flag, value());
            check_ambient(*o.ambient, flag);
        } else if (flag == "--width") {
            o.settings.width = parse_int(flag, value());
        } else if (flag == "--height") {
            o.settings.height = parse_int(flag, value());
        } else if (flag == "--mode") {
            o.settings.mode = parse_word(flag, value(), parse_shading_mode);
        } else if (flag == "--shadows") {
            o.settings.shadows = parse_on_off(flag, value());
        } else if (flag == "--exposure") {
            o.exposure = parse_float(flag, value());
            check_exposure(o.exposure, flag);
        } else if (flag == "--threads") {
            o.settings.threads = parse_int(flag, value());
        } else if (flag == "--spp") {
            o.settings.spp = parse_int(flag, value());
            check_samples_per_pixel(o.settings.spp, flag);
        } else if (flag == "--aa") {
            o.settings.sampling = parse_word(flag, value(), parse_pixel_sampling);
        } else if (flag == "--aa-threshold") {
            o.settings.aa_threshold = parse_float(flag, value());
            check_aa_threshold(o.settings.aa_threshold, flag);
        } else if (flag == "--light-size") {
            o.settings.light_size = parse_float(flag, value());
            check_light_size(o.settings.light_size, flag);
        } else if (flag == "--light-samples") {
            o.settings.light_samples = parse_int(flag, value());
            check_light_samples(o.settings.light_samples, flag);
        } else if (flag == "--light-sampling") {
            const std::string word = value();
            if (word != "uniform" && word != "stratified")
                throw Error(flag + ": '" + printable(word) +
                            "' is neither uniform nor stratified");
            o.settings.light_stratified = word == "stratified";
        } else if (flag == "--seed") {
            o.settings.seed = std::uint64_t(std::uint32_t(parse_int(flag, value())));
        } else if (flag == "--output" || flag == "-o") {
            o.output = value();
            check_output_path(o.output, OutputKind::image, flag);
        } else if (flag == "--repeat") {
            o.repeat = static_cast<int>(parse_flag_whole(flag, value(), 1, 1000));
        } else if (flag == "--student" || flag == "--reference") {
            module_lists.emplace_back(
                flag, value(), flag == "--student" ? Impl::student : Impl::reference);
        } else if (allow_extra && flag.rfind("--", 0) == 0) {
            o.extra.push_back(flag);
            // A following word that is not a flag is this flag's value
            if (k + 1 < argc && std::string(argv[k + 1]).rfind("--", 0) != 0)
                o.extra.push_back(argv[++k]);
        } else {
            throw Error("unknown option '" + printable(flag) + "' (see --help)");
        }
    }
    validate(o.settings);
    if (o.help) return o;
    // The lists apply in order on top of the automatic choice, so "--student sphere" runs
    // the student's sphere and leaves the other modules as they were; "--student all
    // --reference camera" runs everything but the camera from exercises/. The automatic
    // choice calls the student's code (detect_stubs): only when a module is left to it
    const auto apply_lists = [&](ModuleSelection s) {
        for (const auto& [flag, list, impl] : module_lists) {
            try {
                apply_module_list(s, list, impl);
            } catch (const Error& e) {
                throw Error(flag + ": " + printable(e.what(), 400));
            }
        }
        return s;
    };
    const ModuleSelection from_student = apply_lists(ModuleSelection::all(Impl::student));
    const bool all_given =
        from_student.impl == apply_lists(ModuleSelection::all(Impl::reference)).impl;
    o.modules = all_given ? from_student : apply_lists(auto_selection());
    o.modules_given = !module_lists.empty();
    return o;
}

Scene make_scene(const Options& o, const LoadProgress& progress) {
    Scene scene = load_scene(o.scene, progress);
    if (o.eye) scene.view.eye = *o.eye;
    if (o.lookat) scene.view.lookat = *o.lookat;
    if (o.up) scene.view.up = *o.up;
    if (o.fov) scene.view.fov = *o.fov;
    if (!o.lights.empty()) scene.lights = o.lights;
    if (o.ambient) scene.ambient = *o.ambient;
    check_view(scene.view, "camera");
    return scene;
}

}  // namespace raylab
