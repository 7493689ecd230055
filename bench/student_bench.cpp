// raylab-student-bench: run time against error of the student's own plane, sphere and
// triangle tests (exercises/ as built into raylab_student), beside the reference and the
// textbook float formulations, on the ray sets of raylab-bench's kernel section.
//
//   raylab-student-bench            32768 rays per set
//   raylab-student-bench --quick    8192 rays per set, fewer repeats
//
// The student's code runs in this process: it is the student's own code on the student's
// own machine, and nothing here decides a grade.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "kernel_cases.h"
#include "kernels.h"
#include "raylab/contract.h"
#include "report.h"
#include "student_cases.h"

namespace raylab::bench {

namespace {

// ---------------------------------------------------------------------------------------
// Options

struct StudentOptions {
    bool help = false;
    int rays = 1 << 15;  ///< rays per set
    int repeats = 5;     ///< timed passes per kernel (median reported)
    std::vector<double> distances{1.0, 1e2, 1e4, 1e6};
    std::uint64_t seed = 20240601;  ///< raylab-bench's default: the same ray sets
    int module_timeout = 120;       ///< seconds one module's section may run
};

const char* const kHelp =
    "Usage: raylab-student-bench [--quick] [--rays N] [--repeats N] [--seed N]\n"
    "Measures your intersect_plane, intersect_sphere and intersect_triangle "
    "(exercises/)\n"
    "beside the reference and the textbook float versions on the same seeded rays:\n"
    "ns per test, the error of t in ulps against a long double truth, missed and false\n"
    "hits at growing distance D, grazing rays, and rays through shared edges and "
    "vertices.\n"
    "A module that still calls RAYLAB_STUB is reported as not started and skipped.\n"
    "  --quick       8192 rays per set and 3 repeats (default 32768 and 5)\n"
    "  --rays N      rays per set, 1000 to 10000000\n"
    "  --repeats N   timed passes per kernel, 1 to 100; the median is reported\n"
    "  --seed N      master seed of the ray sets\n"
    "  --module-timeout S  stop when one module's tests run S seconds (default 120)\n";

long parse_number(const char* flag, const char* text, long lo, long hi) {
    char* end = nullptr;
    const long v = std::strtol(text, &end, 10);
    if (end == text || *end != '\0' || v < lo || v > hi)
        throw std::runtime_error(
            fmt("%s wants a whole number from %ld to %ld, got '%s'", flag, lo, hi, text));
    return v;
}

StudentOptions parse_options(int argc, char** argv) {
    StudentOptions opt;
    for (int k = 1; k < argc; ++k) {
        const std::string a = argv[k];
        const auto value = [&]() -> const char* {
            if (k + 1 >= argc) throw std::runtime_error(a + " needs a value");
            return argv[++k];
        };
        if (a == "--help" || a == "-h") {
            opt.help = true;
        } else if (a == "--quick") {
            opt.rays = 1 << 13;
            opt.repeats = 3;
        } else if (a == "--rays") {
            opt.rays = static_cast<int>(parse_number("--rays", value(), 1000, 10000000));
        } else if (a == "--repeats") {
            opt.repeats = static_cast<int>(parse_number("--repeats", value(), 1, 100));
        } else if (a == "--module-timeout") {
            opt.module_timeout =
                static_cast<int>(parse_number("--module-timeout", value(), 1, 86400));
        } else if (a == "--seed") {
            const char* text = value();
            char* end = nullptr;
            opt.seed = std::strtoull(text, &end, 10);
            if (end == text || *end != '\0' || text[0] == '-')
                throw std::runtime_error(
                    fmt("--seed wants a whole number, got '%s'", text));
        } else {
            throw std::runtime_error("unknown option '" + a + "' (--help lists them)");
        }
    }
    return opt;
}

// ---------------------------------------------------------------------------------------
// The kernels compared

using PlaneKernel = std::optional<Hit> (*)(const Ray&, const Plane&);

std::optional<Hit> call(PlaneKernel fn, const PlaneCase& c) {
    PlaneKernel volatile hidden =
        fn;  // one indirect call per test, as through ModuleTable
    return PlaneKernel(hidden)(c.r, c.p);
}
std::optional<Hit> call(SphereKernel fn, const SphereCase& c) {
    SphereKernel volatile hidden = fn;
    return SphereKernel(hidden)(c.r, c.s);
}
std::optional<Hit> call(TriangleKernel fn, const TriangleCase& c) {
    TriangleKernel volatile hidden = fn;
    return TriangleKernel(hidden)(c.r, c.v0, c.v1, c.v2);
}

template <class Fn>
struct Kernel {
    std::string name;
    Fn fn;
};

template <class Named>
auto find_kernel(const std::vector<Named>& list, const char* prefix) {
    for (const Named& k : list) {
        if (std::strncmp(k.name, prefix, std::strlen(prefix)) == 0) return k.fn;
    }
    throw std::runtime_error(fmt("no kernel named '%s' in bench/kernels.cpp", prefix));
}

// Did the student start module `number`? Its function runs once on a harmless ray; a stub
// marks itself (RAYLAB_STUB)
template <class Work>
bool started(int number, Work work) {
    stub::called.store(0);
    work();
    return (stub::called.load() & (std::uint32_t{1} << (number - 1))) == 0;
}

const Ray kDown{Vec3(0.0f, 1.0f, 0.0f), Vec3(0.0f, -1.0f, 0.0f), 0.0f, kInfinity};

// ---------------------------------------------------------------------------------------
// Error in ulps and one kernel's outcome on one ray set

// |t - truth| in units of the last place of a float of truth's size
double ulps(float t, long double truth) {
    if (!std::isfinite(t)) return INFINITY;
    const int e = truth == 0 ? -126 : std::max(-126, std::ilogb(truth));
    return static_cast<double>(std::fabs(static_cast<long double>(t) - truth) /
                               std::ldexp(1.0L, e - 23));
}

struct Outcome {
    std::string kernel;
    double ns = NAN;
    size_t rays = 0, truth_hits = 0, missed = 0, false_hits = 0;
    std::vector<double> err;  // ulps where both hit
    double wrong_percent() const {
        return 100.0 * static_cast<double>(missed + false_hits) /
               static_cast<double>(rays);
    }
};

// Median ns per call of each kernel over all cases, the kernels' passes interleaved so
// that a change of the machine's load falls on all of them alike
template <class Case, class Fn>
std::vector<double> time_kernels(const std::vector<Case>& cases,
                                 const std::vector<Kernel<Fn>>& kernels, int repeats) {
    std::vector<std::function<void()>> works;
    for (const Kernel<Fn>& k : kernels) {
        const Fn fn = k.fn;
        works.push_back([&cases, fn] {
            float sum = 0.0f;
            for (const Case& c : cases) {
                if (const auto hit = call(fn, c)) sum += hit->t;
            }
            g_sink = sum;
        });
    }
    std::vector<double> ns = interleaved_median_seconds(repeats, works);
    for (double& v : ns)
        v *= 1e9 / static_cast<double>(cases.size());
    return ns;
}

template <class Case, class Fn>
std::vector<Outcome> run_set(const std::vector<Case>& cases,
                             const std::vector<std::optional<long double>>& truth,
                             const std::vector<Kernel<Fn>>& kernels, int repeats) {
    const std::vector<double> ns = time_kernels(cases, kernels, repeats);
    std::vector<Outcome> out;
    for (size_t k = 0; k < kernels.size(); ++k) {
        Outcome o;
        o.kernel = kernels[k].name;
        o.ns = ns[k];
        o.rays = cases.size();
        for (size_t i = 0; i < cases.size(); ++i) {
            const auto hit = call(kernels[k].fn, cases[i]);
            const auto& t = truth[i];
            o.truth_hits += t.has_value();
            o.missed += t && !hit;
            o.false_hits += !t && hit;
            if (t && hit) o.err.push_back(ulps(hit->t, *t));
        }
        out.push_back(std::move(o));
    }
    return out;
}

std::string ulp_cell(double v) {
    if (std::isnan(v)) return "-";
    if (std::isinf(v)) return "inf";
    return v < 1e4 ? fmt("%.1f", v) : sci(v);
}

Table outcome_table() {
    return Table({"rays", "D", "kernel", "ns/test", "x ref", "truth hits", "missed",
                  "false hits", "median ulps", "p99 ulps", "max ulps"},
                 3);
}

void add_rows(Table& table, const std::string& set, double D,
              const std::vector<Outcome>& outcomes) {
    const double ref_ns = outcomes[1].ns;  // the reference is always second
    for (const Outcome& o : outcomes) {
        table.row({set, fmt("%g", D), o.kernel, fmt("%.1f", o.ns),
                   fmt("%.2f", o.ns / ref_ns), fmt("%zu", o.truth_hits),
                   fmt("%zu", o.missed), fmt("%zu", o.false_hits),
                   ulp_cell(median(o.err)), ulp_cell(quantile(o.err, 0.99)),
                   ulp_cell(quantile(o.err, 1.0))});
    }
}

// ---------------------------------------------------------------------------------------
// The text plot: median ulps against D, one bar per kernel, log scale

struct PlotPoint {
    double D;
    std::vector<Outcome> outcomes;
};

void print_plot(const std::string& title, const std::vector<PlotPoint>& points) {
    std::printf(
        "%s: median error of t in ulps against distance D (each # doubles it; "
        "wrong: missed + false hits)\n\n```\n",
        title.c_str());
    for (const PlotPoint& p : points) {
        bool first = true;
        for (const Outcome& o : p.outcomes) {
            const double m = median(o.err);
            int bars = 0;
            if (std::isinf(m)) {
                bars = 40;
            } else if (!std::isnan(m)) {
                bars = std::min(40, 1 + static_cast<int>(std::floor(std::log2(1.0 + m))));
            }
            std::printf("%-9s %-24s |%-40s %9s  wrong %6.2f%%\n",
                        first ? fmt("D = %g", p.D).c_str() : "", o.kernel.c_str(),
                        std::string(static_cast<size_t>(bars), '#').c_str(),
                        ulp_cell(m).c_str(), o.wrong_percent());
            first = false;
        }
    }
    std::printf("```\n\n");
}

// ---------------------------------------------------------------------------------------
// The three modules

// A student's test that never returns would hang the run: a watchdog ends it after
// --module-timeout seconds in one module's section, naming the module
int g_module_seconds = 120;
std::atomic<const char*> g_module{nullptr};
std::atomic<int> g_module_generation{0};

void start_watchdog() {
    std::thread([] {
        int generation = -1, seconds = 0;
        for (;;) {
            std::this_thread::sleep_for(std::chrono::seconds(1));
            const int now = g_module_generation.load();
            seconds = now == generation ? seconds + 1 : 0;
            generation = now;
            const char* module = g_module.load();
            if (module != nullptr && seconds >= g_module_seconds) {
                std::fprintf(stderr,
                             "raylab-student-bench: exercises/%s.cpp has run for %d s: "
                             "does your test loop forever, or print on every call? "
                             "(--quick runs fewer rays)\n",
                             module, g_module_seconds);
                std::_Exit(3);
            }
        }
    }).detach();
}

// Marks the start of a module's section for the watchdog
void entering(const char* module) {
    g_module.store(module);
    g_module_generation.fetch_add(1);
}

constexpr const char* kYours = "yours";
constexpr const char* kReference = "reference";

void not_started(const char* module, const char* fn) {
    std::printf(
        "Not started: exercises/%s.cpp's %s still calls RAYLAB_STUB; skipped.\n\n",
        module, fn);
}

void plane_section(const StudentOptions& opt) {
    entering("03_plane");
    std::printf("## Ray-plane (exercises/03_plane.cpp)\n\n");
    if (!started(3, [] {
            (void)student::intersect_plane(kDown, Plane{Vec3(0, 1, 0), 0});
        })) {
        not_started("03_plane", "intersect_plane");
        return;
    }
    const std::vector<Kernel<PlaneKernel>> kernels{
        {kYours, &student::intersect_plane},
        {kReference, &reference::intersect_plane},
        {"textbook float", &plane_textbook_float}};
    Table table = outcome_table();
    std::vector<PlotPoint> plot;
    std::uint64_t stream = 500;
    for (const PlaneSet set :
         {PlaneSet::far_plane, PlaneSet::far_origin, PlaneSet::grazing}) {
        for (const double D : opt.distances) {
            Rng rng(opt.seed, stream++);
            const auto cases = plane_cases(rng, D, opt.rays, set);
            std::vector<std::optional<long double>> truth;
            for (const PlaneCase& c : cases)
                truth.push_back(exact_plane_t(c.r, c.p));
            auto outcomes = run_set(cases, truth, kernels, opt.repeats);
            add_rows(table, to_string(set), D, outcomes);
            if (set == PlaneSet::far_origin) plot.push_back({D, std::move(outcomes)});
        }
    }
    table.print();
    print_plot("Ray-plane, origins far from the world origin", plot);
}

void sphere_section(const StudentOptions& opt) {
    entering("04_sphere");
    std::printf("## Ray-sphere (exercises/04_sphere.cpp)\n\n");
    if (!started(4, [] {
            (void)student::intersect_sphere(kDown, Sphere{Vec3(0), 0.5f});
        })) {
        not_started("04_sphere", "intersect_sphere");
        return;
    }
    const std::vector<Kernel<SphereKernel>> kernels{
        {kYours, &student::intersect_sphere},
        {kReference, find_kernel(sphere_kernels(), "reference")},
        {"textbook float (b^2 - c)", find_kernel(sphere_kernels(), "naive float")}};
    Table table = outcome_table();
    std::vector<PlotPoint> plot;
    std::uint64_t stream = 100;  // raylab-bench's sphere sets
    for (const bool grazing : {false, true}) {
        for (const double D : opt.distances) {
            Rng rng(opt.seed, stream++);
            const auto cases = sphere_cases(rng, D, opt.rays, grazing);
            std::vector<std::optional<long double>> truth;
            for (const SphereCase& c : cases)
                truth.push_back(exact_sphere_t(c.r, c.s));
            auto outcomes = run_set(cases, truth, kernels, opt.repeats);
            add_rows(table, grazing ? "grazing" : "random", D, outcomes);
            if (!grazing) plot.push_back({D, std::move(outcomes)});
        }
    }
    table.print();
    print_plot("Ray-sphere, random rays", plot);
}

// Rays through shared edges or vertices: each case is a ray and the triangles around
// the point it aims at
struct Group {
    Ray r;
    std::vector<TriangleCase> tests;
};

Table group_table() {
    return Table({"rays", "D", "kernel", "ns/test", "x ref", "truth hits",
                  "hit none (leak)", "max ulps"},
                 3);
}

void group_rows(Table& table, const char* set, double D, const std::vector<Group>& groups,
                const std::vector<Kernel<TriangleKernel>>& kernels, int repeats) {
    std::vector<TriangleCase> tests;
    for (const Group& g : groups)
        tests.insert(tests.end(), g.tests.begin(), g.tests.end());
    const std::vector<double> ns = time_kernels(tests, kernels, repeats);
    for (size_t k = 0; k < kernels.size(); ++k) {
        size_t truth_hits = 0, leaks = 0;
        std::vector<double> err;
        for (const Group& g : groups) {
            std::optional<long double> t;
            std::optional<float> h;
            for (const TriangleCase& c : g.tests) {
                if (const auto e = exact_triangle_t(c.r, c.v0, c.v1, c.v2))
                    t = t ? std::min(*t, *e) : *e;
                if (const auto hit = call(kernels[k].fn, c))
                    h = h ? std::min(*h, hit->t) : hit->t;
            }
            truth_hits += t.has_value();
            leaks += t && !h;
            if (t && h) err.push_back(ulps(*h, *t));
        }
        table.row({set, fmt("%g", D), kernels[k].name, fmt("%.1f", ns[k]),
                   fmt("%.2f", ns[k] / ns[1]), fmt("%zu", truth_hits), fmt("%zu", leaks),
                   ulp_cell(quantile(err, 1.0))});
    }
}

void triangle_section(const StudentOptions& opt) {
    entering("05_triangle");
    std::printf("## Ray-triangle (exercises/05_triangle.cpp)\n\n");
    if (!started(5, [] {
            (void)student::intersect_triangle(kDown, Vec3(-1, 0, -1), Vec3(0, 0, 1),
                                              Vec3(1, 0, -1));
        })) {
        not_started("05_triangle", "intersect_triangle");
        return;
    }
    const std::vector<Kernel<TriangleKernel>> kernels{
        {kYours, &student::intersect_triangle},
        {kReference, find_kernel(triangle_kernels(), "reference")},
        {"Moeller-Trumbore float", find_kernel(triangle_kernels(), "Moeller-Trumbore")},
        {"Cramer float", find_kernel(triangle_kernels(), "Cramer")}};
    Table table = outcome_table();
    std::vector<PlotPoint> plot;
    std::uint64_t stream = 200;  // raylab-bench's random and grazing triangle sets
    for (const TriangleSet set : {TriangleSet::random, TriangleSet::grazing}) {
        for (const double D : opt.distances) {
            Rng rng(opt.seed, stream++);
            const auto cases = triangle_cases(rng, D, opt.rays, set);
            std::vector<std::optional<long double>> truth;
            for (const TriangleCase& c : cases)
                truth.push_back(exact_triangle_t(c.r, c.v0, c.v1, c.v2));
            auto outcomes = run_set(cases, truth, kernels, opt.repeats);
            add_rows(table, to_string(set), D, outcomes);
            if (set == TriangleSet::random) plot.push_back({D, std::move(outcomes)});
        }
    }
    table.print();
    print_plot("Ray-triangle, random rays", plot);

    std::printf(
        "Rays aimed at an edge shared by two triangles, or at a vertex shared by a fan "
        "of "
        "5 to 8: a watertight test hits at least one triangle wherever the truth does "
        "(leak: it hits none). ns/test is per triangle.\n\n");
    Table shared = group_table();
    std::uint64_t edge_stream = 300, fan_stream = 600;
    for (const double D : opt.distances) {
        Rng rng(opt.seed, edge_stream++);
        std::vector<Group> groups;
        for (const SharedEdgeCase& c : shared_edge_cases(rng, D, opt.rays))
            groups.push_back({c.r, {{c.r, c.a, c.b, c.c1}, {c.r, c.b, c.a, c.c2}}});
        group_rows(shared, "shared edge", D, groups, kernels, opt.repeats);
    }
    for (const double D : opt.distances) {
        Rng rng(opt.seed, fan_stream++);
        std::vector<Group> groups;
        for (const FanCase& c : fan_cases(rng, D, opt.rays / 2)) {
            Group g{c.r, {}};
            for (size_t i = 0; i < c.ring.size(); ++i)
                g.tests.push_back({c.r, c.v, c.ring[i], c.ring[(i + 1) % c.ring.size()]});
            groups.push_back(std::move(g));
        }
        group_rows(shared, "shared vertex", D, groups, kernels, opt.repeats);
    }
    shared.print();
}

// Where and how the run was made: timings mean little in a debug build or under load
void print_header(const StudentOptions& opt) {
    std::ifstream cpuinfo("/proc/cpuinfo");
    std::string line, cpu = "unknown CPU";
    while (std::getline(cpuinfo, line)) {
        if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) {
            cpu = line.substr(line.find(':') + 2);
            break;
        }
    }
#ifdef NDEBUG
    const char* build = "optimised";
#else
    const char* build = "NOT optimised (assertions on): the timings mean little";
#endif
    std::printf("# raylab-student-bench\n\n");
    std::printf("- CPU: %s, %u hardware threads; load average at start: %.2f\n",
                cpu.c_str(), std::thread::hardware_concurrency(), load_average());
    std::printf("- compiler: %s, build: %s\n", __VERSION__, build);
    std::printf("- seed: %llu (--seed %llu gives the same rays)\n\n",
                static_cast<unsigned long long>(opt.seed),
                static_cast<unsigned long long>(opt.seed));
}

}  // namespace

}  // namespace raylab::bench

int main(int argc, char** argv) {
    using namespace raylab::bench;
    try {
        const StudentOptions opt = parse_options(argc, argv);
        if (opt.help) {
            std::printf("%s", kHelp);
            return 0;
        }
        const auto start = std::chrono::steady_clock::now();
        print_header(opt);
        print_heading(
            "Your intersection tests: run time against error",
            fmt("%d rays per set; ray origins in [-1/8, 1/8]^3, targets of size about "
                "1/4 "
                "at distance D. Truth: long double (64-bit significand) for the float "
                "rays "
                "and geometry as stored. ns/test: median of %d timed passes, one call "
                "through a function pointer per test (as the renderer calls your "
                "module); "
                "x ref: over the reference's ns/test on the same rays. ulps: |t - "
                "t_true| "
                "in units of the last place of a float at t_true, where both hit. "
                "missed: "
                "the truth hits, the test does not; false hits: the reverse.",
                opt.rays, opt.repeats));
        g_module_seconds = opt.module_timeout;
        start_watchdog();
        plane_section(opt);
        sphere_section(opt);
        triangle_section(opt);
        std::printf("Total %.1f s\n", seconds_since(start));
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "raylab-student-bench: %s\n", e.what());
        return 2;
    }
}
