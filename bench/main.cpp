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
#include <filesystem>
#include <system_error>

#include <unistd.h>

#include "options.h"
#include "peer.h"
#include "raylab/error.h"
#include "report.h"
#include "sections.h"

namespace {

// Section 5 writes its CSV and plots into --out at the end of the run: the folder is
// made, and checked writable, before anything is measured, so that a bad --out fails at
// once, not after minutes of measuring
void prepare_out_dir(const raylab::bench::BenchOptions& o) {
    if (!o.sampling || !o.sampling_csv.empty()) return;
    std::error_code ec;
    std::filesystem::create_directories(o.out_dir, ec);
    if (ec || !std::filesystem::is_directory(o.out_dir, ec))
        throw raylab::Error("--out " + o.out_dir + ": cannot make this folder" +
                            (ec ? " (" + ec.message() + ")" : std::string()));
    if (access(o.out_dir.c_str(), W_OK) != 0)
        throw raylab::Error("--out " + o.out_dir + ": this folder is not writable");
}

}  // namespace

int main(int argc, char** argv) {
    using namespace raylab::bench;
    try {
        const BenchOptions options = parse_bench_options(argc, argv);
        if (options.help) {
            std::printf("%s", bench_help().c_str());
            return 0;
        }
        prepare_out_dir(options);
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
