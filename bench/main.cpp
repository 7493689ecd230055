// raylab-bench: how fast and how accurate raylab's ray casting is, and what it skips.
//
//   raylab-bench --quick                  a run of about 30 s
//   raylab-bench --sections kernels      one section
//
// Prints Markdown tables (docs/benchmarks.md explains them). Speeds are reported as
// figures and ratios, never asserted.
#include <chrono>
#include <cstdio>
#include <exception>

#include "options.h"
#include "peer.h"
#include "raylab/error.h"
#include "report.h"
#include "sections.h"

int main(int argc, char** argv) {
    using namespace raylab::bench;
    try {
        const BenchOptions options = parse_bench_options(argc, argv);
        if (options.help) {
            std::printf("%s", bench_help().c_str());
            return 0;
        }
        const auto start = std::chrono::steady_clock::now();
        print_machine(options.seed, options.repeats);
        std::printf("%s\n\n", peer_description().c_str());
        if (options.kernels) run_kernel_section(options);
        if (options.scenes) run_scene_section(options);
        if (options.render) run_render_section(options);
        if (options.scaling) run_scaling_section(options);
        if (options.sampling) run_sampling_section(options);
        print_targets();
        std::printf("Total %.1f s; load average at the end: %.2f\n", seconds_since(start),
                    load_average());
        return 0;
    } catch (const raylab::Error& e) {
        std::fprintf(stderr, "raylab-bench: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "raylab-bench: unexpected error: %s\n", e.what());
        return 1;
    }
}
