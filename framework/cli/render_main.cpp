// raylab-render: renders a scene headless and writes the image.
//
//   raylab-render --scene cornell --width 640 --height 480 --output cornell.png
//
// Prints the modules in use, the render time, rays per second and the frame's counters.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <future>
#include <string>
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

// A progress line on stderr, only when stderr is a terminal (logs stay clean)
class ProgressLine {
  public:
    ProgressLine() : tty_(::isatty(2) == 1) {}
    ~ProgressLine() { clear(); }
    void show(const char* stage, double fraction, double seconds) {
        if (!tty_) return;
        const auto now = std::chrono::steady_clock::now();
        // At most ten updates a second, but every new stage at once
        if (shown_ && stage == last_stage_ &&
            now - last_ < std::chrono::milliseconds(100))
            return;
        last_ = now;
        last_stage_ = stage;
        shown_ = true;
        if (fraction >= 0.0) {
            std::fprintf(stderr, "\r\x1b[K%s %3.0f%% (%.1f s)", stage, 100.0 * fraction,
                         seconds);
        } else {
            std::fprintf(stderr, "\r\x1b[K%s (%.1f s)", stage, seconds);
        }
        std::fflush(stderr);
    }
    void clear() {
        if (!shown_) return;
        std::fprintf(stderr, "\r\x1b[K");
        std::fflush(stderr);
        shown_ = false;
    }

  private:
    bool tty_;
    bool shown_ = false;
    std::chrono::steady_clock::time_point last_;
    std::string last_stage_;
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

raylab::Scene load_with_progress(const raylab::Options& options) {
    ProgressLine line;
    const auto t0 = std::chrono::steady_clock::now();
    raylab::LoadProgress progress;
    progress.report = [&](const char* stage, float fraction) {
        line.show((std::string("loading: ") + stage).c_str(), fraction,
                  seconds_since(t0));
    };
    progress.warn = [&](const std::string& message) {
        line.clear();
        std::fprintf(stderr, "raylab-render: warning: %s\n", message.c_str());
    };
    return make_scene(options, progress);
}

// Renders on a worker thread while this one shows the elapsed time on a terminal
raylab::FrameStats render_with_progress(const raylab::Scene& scene,
                                        const raylab::Options& options,
                                        const raylab::ModuleTable& modules,
                                        raylab::Image& image) {
    ProgressLine line;
    const auto t0 = std::chrono::steady_clock::now();
    auto job = std::async(std::launch::async, [&] {
        return raylab::render(scene, scene.view, options.settings, modules, image);
    });
    while (job.wait_for(std::chrono::milliseconds(200)) != std::future_status::ready) {
        char text[96];
        std::snprintf(text, sizeof text, "rendering %dx%d", options.settings.width,
                      options.settings.height);
        line.show(text, -1.0, seconds_since(t0));
    }
    return job.get();
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
        const Scene scene = load_with_progress(options);
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
            stats = render_with_progress(scene, options, modules, image);
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
            "rays: %llu camera (%llu in packets), %llu shadow; shadow rays skipped: %llu "
            "light behind surface, %llu shadows off\n",
            static_cast<unsigned long long>(stats.camera_rays),
            static_cast<unsigned long long>(stats.camera_rays_in_packets),
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
