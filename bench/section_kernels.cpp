// Section 1: intersection kernels, run time against error (bench/sections.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "kernel_cases.h"
#include "kernels.h"
#include "report.h"
#include "sections.h"

namespace raylab::bench {

namespace {

// What one kernel did on one ray set
struct Outcome {
    double ns = 0.0;              // median ns per test
    size_t truth_hits = 0;        // rays the ground truth says hit
    size_t missed = 0;            // truth hits, kernel misses
    size_t false_hits = 0;        // kernel hits, truth misses
    std::vector<double> rel_err;  // |t - t_true| / t_true where both hit
};

bool is_reference(const char* kernel_name) {
    return std::string(kernel_name).rfind("reference", 0) == 0;
}

// One kernel, called through a function pointer the compiler cannot see through (as
// through ModuleTable): no inlining into the timed loop
struct SphereCall {
    SphereKernel fn;
    std::optional<Hit> operator()(const SphereCase& c) const {
        SphereKernel volatile hidden = fn;
        return SphereKernel(hidden)(c.r, c.s);
    }
};
struct TriangleCall {
    TriangleKernel fn;
    std::optional<Hit> operator()(const TriangleCase& c) const {
        TriangleKernel volatile hidden = fn;
        return TriangleKernel(hidden)(c.r, c.v0, c.v1, c.v2);
    }
};

// Compares call(case) with the truth on every case (the time is measured separately, all
// kernels of a ray set interleaved: time_kernels)
template <class Case, class Call>
Outcome evaluate(const std::vector<Case>& cases,
                 const std::vector<std::optional<long double>>& truth, Call call) {
    Outcome out;
    for (size_t k = 0; k < cases.size(); ++k) {
        const auto hit = call(cases[k]);
        const auto& t = truth[k];
        out.truth_hits += t.has_value();
        if (t && !hit) ++out.missed;
        if (!t && hit) ++out.false_hits;
        if (t && hit && *t > 0) {
            const long double err = std::fabs(static_cast<long double>(hit->t) - *t) / *t;
            out.rel_err.push_back(static_cast<double>(err));
        }
    }
    return out;
}

// Median ns per case of each kernel's pass over all cases, the kernels' passes
// interleaved (k1, k2, ..., k1, k2, ...) so that a change in the machine's load falls on
// all of them alike; the ratios to the first (float) kernel are the fair comparison
template <class Case, class Call>
std::vector<double> time_kernels(const std::vector<Case>& cases,
                                 const std::vector<Call>& calls, int repeats) {
    std::vector<std::function<void()>> works;
    for (const Call& call : calls) {
        works.push_back([&cases, call] {
            float sum = 0.0f;
            for (const Case& c : cases) {
                if (const auto hit = call(c)) sum += hit->t;
            }
            g_sink = sum;
        });
    }
    std::vector<double> ns = interleaved_median_seconds(repeats, works);
    for (double& v : ns)
        v *= 1e9 / static_cast<double>(cases.size());
    return ns;
}

std::vector<std::string> outcome_cells(const std::string& set, double D, const char* name,
                                       const Outcome& o, double baseline_ns) {
    return {set,
            fmt("%g", D),
            name,
            fmt("%.1f", o.ns),
            fmt("%.2f", o.ns / baseline_ns),
            fmt("%zu", o.truth_hits),
            fmt("%zu", o.missed),
            fmt("%zu", o.false_hits),
            sci(median(o.rel_err)),
            sci(quantile(o.rel_err, 0.99)),
            sci(quantile(o.rel_err, 1.0))};
}

Table outcome_table() {
    return Table({"rays", "D", "kernel", "ns/test", "x float", "truth hits", "missed",
                  "false hits", "median rel err t", "p99 rel err t", "max rel err t"},
                 3);
}

// Times the kernels on one ray set (interleaved), checks each against the truth, adds
// their rows, and returns the reference kernel's ratio to the first (float) kernel
template <class Case, class Named, class Call>
double kernel_rows(Table& table, const char* set, double D,
                   const std::vector<Case>& cases,
                   const std::vector<std::optional<long double>>& truth,
                   const std::vector<Named>& kernels, int repeats) {
    std::vector<Call> calls;
    for (const Named& k : kernels)
        calls.push_back(Call{k.fn});
    const std::vector<double> ns = time_kernels(cases, calls, repeats);
    double reference_ratio = NAN;
    for (size_t k = 0; k < calls.size(); ++k) {
        Outcome o = evaluate(cases, truth, calls[k]);
        o.ns = ns[k];
        table.row(outcome_cells(set, D, kernels[k].name, o, ns[0]));
        if (is_reference(kernels[k].name)) reference_ratio = ns[k] / ns[0];
    }
    return reference_ratio;
}

void sphere_table(const BenchOptions& opt) {
    Table table = outcome_table();
    double worst = 0.0;  // the reference's largest ratio to the float formulation
    std::uint64_t stream = 100;
    for (const bool grazing : {false, true}) {
        for (const double D : opt.distances) {
            Rng rng(opt.seed, stream++);
            const auto cases = sphere_cases(rng, D, opt.kernel_rays, grazing);
            std::vector<std::optional<long double>> truth;
            for (const SphereCase& c : cases)
                truth.push_back(exact_sphere_t(c.r, c.s));
            worst =
                std::max(worst, kernel_rows<SphereCase, NamedSphereKernel, SphereCall>(
                                    table, grazing ? "grazing" : "random", D, cases,
                                    truth, sphere_kernels(), opt.repeats));
        }
    }
    table.print();
    record_target("ray-sphere: reference / textbook float quadratic, worst ray set",
                  worst, 1.5, false, "x");
}

void triangle_table(const BenchOptions& opt) {
    Table table = outcome_table();
    double worst = 0.0, worst_sparse = 0.0;  // the reference's largest ratios to MT
    // Seed streams: random and grazing from 200, sparse from 400 (spheres: 100, shared
    // edges: 300); --distances takes at most 50 values, so no two sets share one
    std::uint64_t stream = 200;
    for (const TriangleSet set :
         {TriangleSet::random, TriangleSet::grazing, TriangleSet::sparse}) {
        if (set == TriangleSet::sparse) stream = 400;
        for (const double D : opt.distances) {
            Rng rng(opt.seed, stream++);
            const auto cases = triangle_cases(rng, D, opt.kernel_rays, set);
            std::vector<std::optional<long double>> truth;
            for (const TriangleCase& c : cases)
                truth.push_back(exact_triangle_t(c.r, c.v0, c.v1, c.v2));
            double& w = set == TriangleSet::sparse ? worst_sparse : worst;
            w = std::max(w, kernel_rows<TriangleCase, NamedTriangleKernel, TriangleCall>(
                                table, to_string(set), D, cases, truth,
                                triangle_kernels(), opt.repeats));
        }
    }
    table.print();
    record_target(
        "ray-triangle: reference / float Moeller-Trumbore, worst random or "
        "grazing set",
        worst, 1.5, false, "x");
    record_target("ray-triangle: the same, worst sparse set (mostly misses)",
                  worst_sparse, 1.5, false, "x");
}

// Rays through a shared edge: a watertight kernel hits at least one of the two triangles
// wherever the truth hits one (a ray aimed at the edge may pass beyond its end: its float
// direction is rounded, by up to D * 6e-8 across)
struct EdgeTruth {
    std::optional<long double> t;  // the nearer exact hit of the two triangles
};

std::vector<EdgeTruth> edge_truth(const std::vector<SharedEdgeCase>& cases) {
    std::vector<EdgeTruth> truth;
    for (const SharedEdgeCase& c : cases) {
        const auto t1 = exact_triangle_t(c.r, c.a, c.b, c.c1);
        const auto t2 = exact_triangle_t(c.r, c.b, c.a, c.c2);
        truth.push_back({t1 && t2 ? std::min(t1, t2) : (t1 ? t1 : t2)});
    }
    return truth;
}

// One kernel's row for rays through shared edges; ns: its time per test, ratio: to the
// first (float) kernel's
std::vector<std::string> edge_row(double D, const NamedTriangleKernel& k,
                                  const std::vector<SharedEdgeCase>& cases,
                                  const std::vector<EdgeTruth>& truth, double ns,
                                  double ratio) {
    const TriangleCall call{k.fn};
    size_t truth_hits = 0, leaks = 0, both = 0;
    std::vector<double> err;
    for (size_t i = 0; i < cases.size(); ++i) {
        const SharedEdgeCase& c = cases[i];
        const auto h1 = call({c.r, c.a, c.b, c.c1}), h2 = call({c.r, c.b, c.a, c.c2});
        const auto& t = truth[i].t;
        truth_hits += t.has_value();
        leaks += t && !h1 && !h2;
        both += h1 && h2;
        const auto h = h1 && h2 ? (h1->t < h2->t ? h1 : h2) : (h1 ? h1 : h2);
        if (t && h)
            err.push_back(
                static_cast<double>(std::fabs(static_cast<long double>(h->t) - *t) / *t));
    }
    const double n = static_cast<double>(truth_hits);
    return {fmt("%g", D),
            k.name,
            fmt("%.1f", ns),
            fmt("%.2f", ratio),
            fmt("%zu", truth_hits),
            fmt("%zu", leaks),
            fmt("%.3f", 100.0 * static_cast<double>(leaks) / n),
            fmt("%zu", both),
            sci(quantile(err, 1.0))};
}

void shared_edge_table(const BenchOptions& opt) {
    Table table({"D", "kernel", "ns/test", "x float", "truth hits", "hit neither (leak)",
                 "leak %", "hit both", "max rel err t"},
                2);
    std::uint64_t stream = 300;
    for (const double D : opt.distances) {
        Rng rng(opt.seed, stream++);
        const auto cases = shared_edge_cases(rng, D, opt.kernel_rays);
        const auto truth = edge_truth(cases);
        // Each case is two tests, one per triangle of the fold: the kernels interleaved
        std::vector<TriangleCase> tests;
        tests.reserve(2 * cases.size());
        for (const SharedEdgeCase& c : cases) {
            tests.push_back({c.r, c.a, c.b, c.c1});
            tests.push_back({c.r, c.b, c.a, c.c2});
        }
        std::vector<TriangleCall> calls;
        for (const NamedTriangleKernel& k : triangle_kernels())
            calls.push_back(TriangleCall{k.fn});
        const std::vector<double> ns = time_kernels(tests, calls, opt.repeats);
        for (size_t k = 0; k < calls.size(); ++k)
            table.row(
                edge_row(D, triangle_kernels()[k], cases, truth, ns[k], ns[k] / ns[0]));
    }
    table.print();
}

}  // namespace

void run_kernel_section(const BenchOptions& opt) {
    print_heading(
        "1. Kernels: run time against error",
        fmt("%d rays per set; origins in [-1/8, 1/8]^3, targets of size 1/4 at distance "
            "D. Ground "
            "truth: long double (64-bit significand), cancellation-free formulas, for "
            "the "
            "float ray and geometry as stored. ns/test: median of %d timed passes, one "
            "call through a function pointer per test (as through ModuleTable), full Hit "
            "returned; the kernels of a ray set are timed interleaved, and x float is "
            "ns/test over the first row's (the float formulation the targets compare "
            "with). missed: the truth hits, the kernel does not; false hits: the "
            "reverse. rel err t: |t - t_true| / t_true where both hit.",
            opt.kernel_rays, opt.repeats));
    std::printf("### Ray-sphere (radius 1/4)\n\n");
    sphere_table(opt);
    std::printf("### Ray-triangle (vertices within 1/4 of a centre)\n\n");
    triangle_table(opt);
    std::printf("### Rays through an edge shared by two triangles\n\n");
    shared_edge_table(opt);
}

}  // namespace raylab::bench
