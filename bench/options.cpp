// The command line of raylab-bench (bench/options.h).
#include "options.h"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <thread>

#include "raylab/error.h"
#include "raylab/input_checks.h"

namespace raylab::bench {

namespace {

long long parse_integer(const std::string& option, const std::string& value, long long lo,
                        long long hi) {
    char* end = nullptr;
    const long long v = std::strtoll(value.c_str(), &end, 10);
    if (value.empty() || *end != '\0' || v < lo || v > hi) {
        throw Error(option + " expects an integer in " + std::to_string(lo) + ".." +
                    std::to_string(hi) + ", got '" + value + "'");
    }
    return v;
}

void parse_size(const std::string& option, const std::string& value, int& width,
                int& height) {
    const size_t x = value.find('x');
    if (x == std::string::npos) throw Error(option + " expects WxH, got '" + value + "'");
    width = static_cast<int>(parse_integer(option, value.substr(0, x), 1, 16384));
    height = static_cast<int>(parse_integer(option, value.substr(x + 1), 1, 16384));
}

std::vector<double> parse_distances(const std::string& value) {
    std::vector<double> out;
    size_t start = 0;
    while (start <= value.size()) {
        const size_t comma = std::min(value.find(',', start), value.size());
        const std::string word = value.substr(start, comma - start);
        char* end = nullptr;
        const double d = std::strtod(word.c_str(), &end);
        if (word.empty() || *end != '\0' || !(d >= 1.0 && d <= 1e12))
            throw Error(
                "--distances expects numbers in [1, 1e12] such as 1,1e2,1e4, got '" +
                word + "'");
        out.push_back(d);
        start = comma + 1;
    }
    // Each ray set takes one seed stream per distance from a block of 50 (section 1)
    if (out.size() > 50)
        throw Error("--distances takes at most 50 values, got " +
                    std::to_string(out.size()));
    return out;
}

void parse_sections(const std::string& value, BenchOptions& o) {
    o.kernels = o.scenes = o.render = o.scaling = o.sampling = false;
    size_t start = 0;
    while (start <= value.size()) {
        const size_t comma = std::min(value.find(',', start), value.size());
        const std::string word = value.substr(start, comma - start);
        if (word == "kernels") {
            o.kernels = true;
        } else if (word == "scenes") {
            o.scenes = true;
        } else if (word == "render") {
            o.render = true;
        } else if (word == "scaling") {
            o.scaling = true;
        } else if (word == "sampling") {
            o.sampling = true;
        } else if (word == "all") {
            o.kernels = o.scenes = o.render = o.scaling = o.sampling = true;
        } else {
            throw Error("unknown section '" + word +
                        "' (kernels, scenes, render, scaling, sampling, all)");
        }
        start = comma + 1;
    }
}

}  // namespace

std::string bench_help() {
    return "raylab-bench: run time against error of raylab's intersection kernels,\n"
           "raylab against Intel Embree on the same rays, and the renderer's cost.\n\n"
           "Usage: raylab-bench [options]\n\n"
           "  --sections LIST   kernels,scenes,render,scaling,sampling or all (default "
           "all)\n"
           "  --out DIR         where the sampling section writes sampling.csv/.svg, a\n"
           "                    folder made if missing (.)\n"
           "  --sampling-size WxH  renders of the sampling section (240x180; quick\n"
           "                    160x120)\n"
           "  --sampling-csv FILE  the sampling section prints its tables from FILE (a\n"
           "                    sampling.csv of an earlier run) instead of rendering\n"
           "  --quick           a run of about 30 s: fewer rays, repeats and triangles\n"
           "  --repeats N       timed repeats per measurement, median reported (5; quick "
           "3)\n"
           "  --rays N          rays per kernel ray set (131072; quick 16384)\n"
           "  --distances LIST  target distances from the origin, each >= 1, at most 50\n"
           "                    (1,1e2,1e4,1e5,1e6)\n"
           "  --mesh-tris N     triangles of the displaced sphere and the terrain; the\n"
           "                    random soup a quarter (at least 1000), the icosphere\n"
           "                    20 * 4^k of at most that many (400000; quick 100000)\n"
           "  --max-tris N      largest mesh of the scaling section (2000000; quick\n"
           "                    100000)\n"
           "  --size WxH        camera rays and renders (640x480)\n"
           "  --threads N       what 'all threads' means in the render section\n"
           "                    (default: hardware threads)\n"
           "  --seed S          master seed of every random ray set (20240601)\n"
           "  --help            this text\n\n"
           "Timings are medians of the repeats; run on a quiet machine. Speeds are\n"
           "reported, never asserted. See docs/benchmarks.md.\n";
}

BenchOptions parse_bench_options(int argc, char** argv) {
    BenchOptions o;
    // --quick changes the defaults; explicit options win whatever their order
    for (int k = 1; k < argc; ++k) {
        if (std::string(argv[k]) == "--quick") {
            o.quick = true;
            o.repeats = 3;
            o.kernel_rays = 1 << 14;
            o.mesh_triangles = 100000;
            o.max_triangles = 100000;
            o.sampling_width = 160;
            o.sampling_height = 120;
        }
    }
    for (int k = 1; k < argc; ++k) {
        const std::string arg = argv[k];
        const auto value = [&]() -> std::string {
            if (k + 1 >= argc) throw Error(arg + " needs a value (see --help)");
            return argv[++k];
        };
        if (arg == "--help" || arg == "-h") {
            o.help = true;
        } else if (arg == "--quick") {
        } else if (arg == "--sections") {
            parse_sections(value(), o);
        } else if (arg == "--out") {
            o.out_dir = value();
        } else if (arg == "--repeats") {
            o.repeats = static_cast<int>(parse_integer(arg, value(), 1, 1000));
        } else if (arg == "--rays") {
            o.kernel_rays = static_cast<int>(parse_integer(arg, value(), 16, 1 << 24));
        } else if (arg == "--distances") {
            o.distances = parse_distances(value());
        } else if (arg == "--mesh-tris") {
            o.mesh_triangles =
                static_cast<int>(parse_integer(arg, value(), 100, 20000000));
        } else if (arg == "--max-tris") {
            o.max_triangles =
                static_cast<int>(parse_integer(arg, value(), 1000, 20000000));
        } else if (arg == "--size") {
            parse_size(arg, value(), o.width, o.height);
        } else if (arg == "--sampling-size") {
            parse_size(arg, value(), o.sampling_width, o.sampling_height);
        } else if (arg == "--sampling-csv") {
            o.sampling_csv = value();
        } else if (arg == "--threads") {
            o.threads = static_cast<int>(parse_integer(arg, value(), 1, 1024));
        } else if (arg == "--seed") {
            o.seed = static_cast<std::uint64_t>(
                parse_integer(arg, value(), 0, std::numeric_limits<long long>::max()));
        } else {
            throw Error("unknown option '" + arg + "' (see --help)");
        }
    }
    // Section 5 writes into --out at the end of the run: checked now, by raylab's rule
    // for output folders (made if missing, inside a writable folder), so that a bad --out
    // fails before anything is measured
    if (o.sampling && o.sampling_csv.empty() && !o.help)
        check_output_path(o.out_dir, OutputKind::folder, "--out");
    return o;
}

int all_threads(const BenchOptions& options) {
    if (options.threads > 0) return options.threads;
    return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

}  // namespace raylab::bench
