// raylab-render: renders a scene headless and writes the image.
//
//   raylab-render --scene cornell --width 640 --height 480 --output cornell.png
//
// Prints the modules in use, the render time, rays per second and the frame's counters.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <vector>

#include "raylab/error.h"
#include "raylab/options.h"
#include "raylab/renderer.h"

namespace {

void print_help() {
    std::printf(
        "raylab-render: render a scene with the raylab ray caster, without a window.\n\n"
        "Usage: raylab-render [options]\n\n%s"
        "Output:\n"
        "  --output FILE         write FILE.png (8-bit sRGB) or FILE.pfm (linear float)\n"
        "                        (default: raylab.png)\n"
        "  --repeat N            render N times and report the median time\n"
        "  --help                this text\n\n"
        "Example: raylab-render --scene dtu --fov 40 --reference all --output dtu.png\n",
        raylab::options_help().c_str());
}

}  // namespace

int main(int argc, char** argv) {
    using namespace raylab;
    try {
        Options options = parse_options(argc, argv);
        if (options.help) {
            print_help();
            return 0;
        }
        if (options.output.empty()) options.output = "raylab.png";
        check_image_extension(options.output);
        const Scene scene = make_scene(options);
        const ModuleTable modules = ModuleTable::make(options.modules);
        std::printf("scene %s: %zu triangles, %zu spheres, %zu planes, %zu lights\n",
                    scene.name.c_str(), scene.triangles.size(), scene.spheres.size(),
                    scene.planes.size(), scene.lights.size());
        std::printf("modules: %s\n", describe(options.modules).c_str());
        const std::string stubs = stub_modules_running(options.modules);
        if (!stubs.empty()) {
            std::printf(
                "note: still stubs (not started): %s; use --reference to compare\n",
                stubs.c_str());
        }

        // Render, several times when asked, and keep the median time
        Image image;
        std::vector<double> times;
        FrameStats stats;
        for (int k = 0; k < options.repeat; ++k) {
            stats = render(scene, scene.view, options.settings, modules, image);
            times.push_back(stats.milliseconds);
        }
        std::sort(times.begin(), times.end());
        const double median = times[times.size() / 2];
        write_image(options.output, image, options.exposure);

        std::printf(
            "rendered %dx%d (%s, shadows %s) in %.2f ms%s on %d threads: %.2f Mrays/s\n",
            image.width, image.height, to_string(options.settings.mode),
            options.settings.shadows ? "on" : "off", median,
            options.repeat > 1 ? " (median)" : "", stats.threads,
            static_cast<double>(stats.rays()) / (median * 1e3));
        std::printf(
            "rays: %llu camera, %llu shadow; shadow rays skipped: %llu light behind "
            "surface, %llu shadows off\n",
            static_cast<unsigned long long>(stats.camera_rays),
            static_cast<unsigned long long>(stats.shadow_rays),
            static_cast<unsigned long long>(stats.shadow_rays_backfacing),
            static_cast<unsigned long long>(stats.shadow_rays_disabled));
        std::printf("work: %llu intersection tests, %llu BVH nodes visited\n",
                    static_cast<unsigned long long>(stats.intersection_tests),
                    static_cast<unsigned long long>(stats.bvh_nodes));
        if (stats.non_finite_pixels > 0) {
            std::printf(
                "warning: %llu pixels are NaN or infinite (NaN writes as 0, +inf as "
                "255): a module "
                "returned an invalid value\n",
                static_cast<unsigned long long>(stats.non_finite_pixels));
        }
        std::printf("wrote %s\n", options.output.c_str());
        return 0;
    } catch (const Error& e) {
        std::fprintf(stderr, "raylab-render: error: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "raylab-render: internal error: %s\n", e.what());
        return 3;
    }
}
