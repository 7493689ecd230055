// raylab-render: renders a scene headless and writes the image.
//
//   raylab-render --scene cornell --width 640 --height 480 --output cornell.png
//
// Prints the modules in use, the render time, rays per second and the frame's counters.
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <future>
#include <string>
#include <vector>

#include "raylab/error.h"
#include "raylab/input_checks.h"
#include "raylab/input_file.h"
#include "raylab/options.h"
#include "raylab/renderer.h"

namespace {

// Above this many rays a render says what it will cost before it starts
constexpr double kRayBudget = 1e10;

// Ctrl+C: the render stops after the tiles in flight, nothing is written (a second
// Ctrl+C ends the process at once, SA_RESETHAND)
std::atomic<bool> interrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free, "set from a signal handler");

extern "C" void on_interrupt(int) {
    interrupted.store(true);
}

void catch_interrupt() {
    struct sigaction action {};
    action.sa_handler = on_interrupt;
    action.sa_flags = SA_RESETHAND;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, nullptr);
}

void print_help() {
    std::printf(
        "raylab-render: render a scene with the raylab ray caster, without a window.\n\n"
        "Usage: raylab-render [options]\n\n%s"
        "Output:\n"
        "  --output FILE         write FILE.png (8-bit sRGB) or FILE.pfm (linear float)\n"
        "                        (default: raylab.png)\n"
        "  --repeat N            render N times and report the median time\n"
        "  --help                this text\n\n"
        "A render of more than 1e10 rays prints its estimate first; on a terminal a\n"
        "progress line shows the fraction done and the time left; Ctrl+C stops it\n"
        "and writes nothing (exit code 130).\n\n"
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
    progress.cancel = &interrupted;
    progress.report = [&](const char* stage, float fraction) {
        line.show((std::string("loading: ") + stage).c_str(), fraction,
                  seconds_since(t0));
    };
    progress.warn = [&](const std::string& message) {
        line.clear();
        std::fprintf(stderr, "raylab-render: warning: %s\n",
                     raylab::printable(message, 4000).c_str());
    };
    return make_scene(options, progress);
}

// The rays a render casts at most: every sample's camera ray and, in Lambert mode with
// shadows, a shadow ray per light and light sample (the adaptive scheme's first pass adds
// one camera ray a pixel)
double ray_estimate(const raylab::Scene& scene, const raylab::Options& options) {
    const raylab::RenderSettings& s = options.settings;
    const double camera =
        double(s.width) * s.height *
        (s.spp + (s.sampling == raylab::PixelSampling::adaptive ? 1 : 0));
    const bool shadows = s.shadows && s.mode == raylab::ShadingMode::lambert;
    const double shadow_per_ray =
        shadows
            ? double(scene.lights.size()) * (s.light_size > 0.0f ? s.light_samples : 1)
            : 0.0;
    return camera * (1.0 + shadow_per_ray) * options.repeat;
}

// Renders on a worker thread while this one shows, on a terminal, the fraction done and
// the time left at the pace so far
raylab::FrameStats render_with_progress(const raylab::Scene& scene,
                                        const raylab::Options& options,
                                        const raylab::ModuleTable& modules,
                                        raylab::Image& image) {
    ProgressLine line;
    const auto t0 = std::chrono::steady_clock::now();
    std::atomic<std::int64_t> done{0};
    raylab::RenderSettings settings = options.settings;
    settings.tiles_done = &done;
    settings.cancel = &interrupted;
    const double total = double(raylab::render_tile_total(settings));
    auto job = std::async(std::launch::async, [&] {
        return raylab::render(scene, scene.view, settings, modules, image);
    });
    while (job.wait_for(std::chrono::milliseconds(200)) != std::future_status::ready) {
        const double fraction = double(done.load()) / total;
        const double elapsed = seconds_since(t0);
        char text[128];
        if (fraction > 0.0) {
            std::snprintf(text, sizeof text, "rendering %dx%d, %.0f s left",
                          settings.width, settings.height,
                          elapsed * (1.0 - fraction) / fraction);
        } else {
            std::snprintf(text, sizeof text, "rendering %dx%d", settings.width,
                          settings.height);
        }
        line.show(text, fraction, elapsed);
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
        if (options.output.empty()) {
            options.output = "raylab.png";
            check_output_path(options.output, OutputKind::image, "--output");
        }
        const std::string output = printable(options.output);
        catch_interrupt();
        const Scene scene = load_with_progress(options);
        const ModuleTable modules = ModuleTable::make(options.modules);
        std::printf("scene %s: %zu triangles, %zu spheres, %zu planes, %zu lights\n",
                    printable(scene.name).c_str(), scene.triangles.size(),
                    scene.spheres.size(), scene.planes.size(), scene.lights.size());
        std::printf("modules: %s\n", describe(options.modules).c_str());
        const std::string stubs = stub_modules_running(options.modules);
        if (!stubs.empty()) {
            std::printf(
                "note: still stubs (not started): %s; use --reference to compare\n",
                stubs.c_str());
        }

        const double rays = ray_estimate(scene, options);
        if (rays > kRayBudget) {
            std::printf(
                "note: this render casts up to %.2g rays (%dx%d pixels, %d samples, %zu "
                "lights x %d light samples, %d times); Ctrl+C stops it\n",
                rays, options.settings.width, options.settings.height,
                options.settings.spp, scene.lights.size(),
                options.settings.light_size > 0.0f ? options.settings.light_samples : 1,
                options.repeat);
        }
        std::fflush(stdout);

        // Render, several times when asked, and keep the median time
        Image image;
        std::vector<double> times;
        FrameStats stats;
        for (int k = 0; k < options.repeat; ++k) {
            stats = render_with_progress(scene, options, modules, image);
            if (stats.cancelled) {
                std::fprintf(stderr,
                             "raylab-render: interrupted (Ctrl+C): nothing written\n");
                return 130;
            }
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
        std::printf("wrote %s\n", output.c_str());
        return 0;
    } catch (const LoadCancelled&) {
        std::fprintf(stderr, "raylab-render: interrupted (Ctrl+C) while loading\n");
        return 130;
    } catch (const Error& e) {
        std::fprintf(stderr, "raylab-render: error: %s\n",
                     printable(e.what(), 4000).c_str());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "raylab-render: internal error: %s\n",
                     printable(e.what(), 4000).c_str());
        return 3;
    }
}
