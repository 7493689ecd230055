// bench/options.h: the command line of raylab-bench.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace raylab::bench {

/// What to run and how big. Defaults give a run of a few minutes on 2 cores; --quick one
/// of about 30 s.
struct BenchOptions {
    bool help = false;
    bool kernels = true;       ///< section 1: kernels, run time against error
    bool scenes = true;        ///< section 2: raylab against Embree on the same rays
    bool render = true;        ///< section 3: render() and the work it skips
    bool scaling = true;       ///< section 4: build, memory and time against size
    bool sampling = true;      ///< section 5: sampling schemes, time against error
    int sampling_width = 240;  ///< image size of section 5 (quick: 160 x 120)
    int sampling_height = 180;
    std::string out_dir = ".";  ///< where section 5 writes sampling.csv and .svg
    std::string sampling_csv;   ///< section 5 prints its tables from this CSV, no renders
    bool quick = false;         ///< fewer rays, repeats and triangles
    int repeats = 5;            ///< timed repeats per measurement (median reported)
    int kernel_rays = 1 << 17;  ///< rays per kernel ray set
    std::vector<double> distances{1.0, 1e2, 1e4, 1e5, 1e6};  ///< target distances
    int mesh_triangles = 400000;  ///< displaced sphere and terrain; the soup a quarter
    int max_triangles = 2000000;  ///< largest mesh of the scaling section
    int width = 640;              ///< image size of camera rays and renders
    int height = 480;
    int threads = 0;  ///< "all" threads of the render section; 0: hardware threads
    std::uint64_t seed = 20240601;  ///< master seed of every random ray set
};

/// Parses argv. Throws raylab::Error naming a bad option or value.
BenchOptions parse_bench_options(int argc, char** argv);

/// The --help text.
std::string bench_help();

/// The thread count that "all" means.
int all_threads(const BenchOptions& options);

}  // namespace raylab::bench
