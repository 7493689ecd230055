// Section 3: the renderer, its scaling and the work it skips (bench/sections.h).
#include <cstdio>
#include <functional>

#include "raylab/renderer.h"
#include "raylab/scenes.h"
#include "report.h"
#include "sections.h"

namespace raylab::bench {

namespace {

struct Case {
    ShadingMode mode;
    bool shadows;
};

std::string count(std::uint64_t n) {
    return fmt("%llu", static_cast<unsigned long long>(n));
}

// Renders one case with 1 and `all` threads, interleaved, and adds a row for each
void render_rows(Table& table, const Scene& scene, const Case& c, int all,
                 const BenchOptions& opt, const ModuleTable& modules) {
    std::vector<int> thread_counts{1};
    if (all > 1) thread_counts.push_back(all);
    std::vector<FrameStats> frames(thread_counts.size());
    std::vector<Image> images(thread_counts.size());
    std::vector<std::function<void()>> works;
    for (size_t k = 0; k < thread_counts.size(); ++k) {
        works.push_back([&, k] {
            RenderSettings settings;
            settings.width = opt.width;
            settings.height = opt.height;
            settings.mode = c.mode;
            settings.shadows = c.shadows;
            settings.threads = thread_counts[k];
            frames[k] = render(scene, scene.view, settings, modules, images[k]);
        });
    }
    const RoundTimes rounds = interleaved_seconds(opt.repeats, works);
    const std::vector<double> s = rounds.medians();
    // The frame target: the Cornell box at 640x480 with shadows, two threads
    if (scene.name == "cornell" && c.mode == ShadingMode::lambert && c.shadows &&
        opt.width == 640 && opt.height == 480 && thread_counts.back() == 2) {
        std::vector<double> ms;
        for (const double seconds : rounds.seconds.back())
            ms.push_back(1e3 * seconds);
        record_target("cornell 640x480, shadows on, 2 threads: frame ms", 1e3 * s.back(),
                      16.0, false, " ms", ms);
    }
    for (size_t k = 0; k < thread_counts.size(); ++k) {
        const FrameStats& f = frames[k];
        const double rays = static_cast<double>(f.rays());
        table.row({scene.name, to_string(c.mode), c.shadows ? "on" : "off",
                   fmt("%d", f.threads), fmt("%.1f", 1e3 * s[k]),
                   fmt("%.2f", rays / s[k] / 1e6), fmt("%.2fx", s[0] / s[k]),
                   count(f.camera_rays), count(f.shadow_rays),
                   count(f.shadow_rays_backfacing), count(f.shadow_rays_disabled),
                   fmt("%.1f", static_cast<double>(f.intersection_tests) / rays),
                   fmt("%.1f", static_cast<double>(f.bvh_nodes) / rays)});
    }
}

}  // namespace

void run_render_section(const BenchOptions& opt) {
    const int all = all_threads(opt);
    print_heading(
        "3. Renderer: time, scaling and skipped work",
        fmt("render() at %dx%d with the reference modules, threads 1 and %d. ms: median "
            "of %d frames (wall clock around render(), the thread counts interleaved); "
            "speed-up: 1-thread ms / this ms. Skipped shadow rays: light "
            "behind the surface (never cast) and shadows off (not needed). The normals "
            "mode runs no light loop at all.",
            opt.width, opt.height, all, opt.repeats));
    const ModuleTable modules = ModuleTable::make(ModuleSelection::all(Impl::reference));
    Table table({"scene", "mode", "shadows", "threads", "ms", "Mrays/s", "speed-up",
                 "camera rays", "shadow rays", "skipped: behind", "skipped: shadows off",
                 "tests/ray", "nodes/ray"},
                3);
    const Case cases[] = {{ShadingMode::lambert, true},
                          {ShadingMode::lambert, false},
                          {ShadingMode::normals, false}};
    for (const Scene& scene : {cornell_box(), dtu_scene()}) {
        for (const Case& c : cases)
            render_rows(table, scene, c, all, opt, modules);
    }
    table.print();
}

}  // namespace raylab::bench
