// Bug-report folders (viewer/report.h).
#include "report.h"

#include <cstdio>
#include <ctime>
#include <filesystem>

#include "raylab/error.h"
#include "raylab/image.h"
#include "raylab/input_file.h"
#include "view_file.h"

namespace raylab::viewer {

namespace {

std::string number(float x) {
    return format_number(x);
}

std::string triple(const Vec3& v) {
    return format_vec3(v, ",");
}

// Quotes a word for a POSIX shell when it holds anything but safe characters
std::string shell_word(const std::string& word) {
    const std::string safe =
        "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
        "0123456789_-.,/:=+";
    if (!word.empty() && word.find_first_not_of(safe) == std::string::npos) return word;
    std::string quoted = "'";
    for (char c : word)
        quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

// "--student all --reference camera,sphere": the selection as module flags
std::string module_flags(const ModuleSelection& modules) {
    std::string student, reference;
    for (const ModuleInfo& info : module_infos()) {
        std::string& list = modules[info.module] == Impl::student ? student : reference;
        list += (list.empty() ? "" : ",") + std::string(info.name);
    }
    if (reference.empty()) return "--student all";
    if (student.empty()) return "--reference all";
    return "--student all --reference " + reference;
}

void write_text(const std::string& path, const std::string& text) {
    write_file(path, text, "report file");
}

std::string frame_text(const FrameStats& s) {
    char text[512];
    std::snprintf(
        text, sizeof text,
        "frame: %.2f ms on %d threads, %.2f Mrays/s\n"
        "rays: %llu camera (%llu in packets, %llu more reused), %llu shadow; skipped "
        "shadow rays: %llu light behind surface, %llu shadows off\n"
        "work: %llu intersection tests, %llu BVH nodes; %llu non-finite pixels\n",
        s.milliseconds, s.threads, s.rays_per_second() * 1e-6,
        static_cast<unsigned long long>(s.camera_rays),
        static_cast<unsigned long long>(s.camera_rays_in_packets),
        static_cast<unsigned long long>(s.camera_rays_reused),
        static_cast<unsigned long long>(s.shadow_rays),
        static_cast<unsigned long long>(s.shadow_rays_backfacing),
        static_cast<unsigned long long>(s.shadow_rays_disabled),
        static_cast<unsigned long long>(s.intersection_tests),
        static_cast<unsigned long long>(s.bvh_nodes),
        static_cast<unsigned long long>(s.non_finite_pixels));
    return text;
}

}  // namespace

std::string render_command(const ReportInput& in, const std::string& output) {
    const View& v = in.view;
    std::string c = "raylab-render --scene " + shell_word(in.scene_source);
    c += " --eye " + triple(v.eye) + " --lookat " + triple(v.lookat) + " --up " +
         triple(v.up) + " --fov " + number(v.fov);
    for (const PointLight& light : in.lights)
        c += " --light " + triple(light.p) + ":" + triple(light.I);
    // No lights: a black light renders the same picture (raylab-render has no flag for
    // "no lights", and without --light it keeps the scene's own)
    if (in.lights.empty()) c += " --light 0,0,0:0,0,0";
    c += " --ambient " + number(in.ambient);
    c += " --width " + std::to_string(in.settings.width) + " --height " +
         std::to_string(in.settings.height);
    c += std::string(" --mode ") + to_string(in.settings.mode) + " --shadows " +
         (in.settings.shadows ? "on" : "off") + " --exposure " + number(in.exposure);
    // Sampling (modules 09 and 10), only when it differs from one ray per pixel and
    // point lights
    const RenderSettings& s = in.settings;
    if (s.spp > 1) {
        c += " --spp " + std::to_string(s.spp) + " --aa " + to_string(s.sampling);
        if (s.sampling == PixelSampling::adaptive)
            c += " --aa-threshold " + number(s.aa_threshold);
    }
    if (s.light_size > 0.0f)
        c += " --light-size " + number(s.light_size) + " --light-samples " +
             std::to_string(s.light_samples) + " --light-sampling " +
             (s.light_stratified ? "stratified" : "uniform");
    if (s.seed != 1 && (s.spp > 1 || s.light_size > 0.0f))
        c += " --seed " + std::to_string(s.seed);
    c += " " + module_flags(in.modules) + " --output " + shell_word(output);
    return c;
}

std::string default_report_dir() {
    const std::time_t now = std::time(nullptr);
    std::tm local{};
    localtime_r(&now, &local);
    char name[64];
    std::strftime(name, sizeof name, "raylab-report-%Y%m%d-%H%M%S", &local);
    return name;
}

void write_report(const std::string& dir, const ReportInput& in) {
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    if (error)
        throw Error(printable(dir) +
                    ": cannot create the report folder: " + error.message());
    save_view_file(dir + "/view.txt", in.view, in.lights, &in.settings);

    std::string settings = "# raylab viewer report\n";
    settings += "scene: " + in.scene_source + "\n";
    settings += "resolution: " + std::to_string(in.settings.width) + "x" +
                std::to_string(in.settings.height) + "\n";
    settings += std::string("mode: ") + to_string(in.settings.mode) +
                "\nshadows: " + (in.settings.shadows ? "on" : "off") +
                "\nexposure: " + number(in.exposure) +
                "\nambient: " + number(in.ambient) + "\n";
    settings += "modules: " + describe(in.modules) + "\n";
    settings += in.image ? frame_text(in.stats) : "frame: none rendered yet\n";
    if (!in.grades.empty()) settings += "tests:\n" + in.grades;
    settings +=
        "\nReproduce without a window:\n  " + render_command(in, "image.png") + "\n";
    write_text(dir + "/settings.txt", settings);
    if (in.image && in.image->width > 0)
        write_png(dir + "/image.png", *in.image, in.exposure);
    write_text(dir + "/log.txt", in.log);
}

}  // namespace raylab::viewer
