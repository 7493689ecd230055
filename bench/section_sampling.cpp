// Section 5: run time against error of the sampling schemes of modules 09 and 10
// (bench/sections.h, docs/sampling-benchmarks.md).
//
// For the Cornell box and the DTU scene, every scheme renders at growing sample counts
// and each image's RMSE against a converged image of the same scene is set against its
// render time and rays. Anti-aliasing (point lights, hard shadows): grid, stratified and
// adaptive pixel samples. Area lights (one ray per pixel centre): uniform against
// stratified light samples. Writes a CSV and two SVG plots (log-log, one line per
// scheme) and prints, as Markdown, every table of docs/sampling-benchmarks.md: the
// targets, the convergence exponents, and each study's rows. The tables are computed from
// the points as the CSV stores them, so --sampling-csv FILE prints the same tables again
// from a CSV of an earlier run without rendering (tests/handouts/check_sampling_doc.py).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "raylab/error.h"
#include "raylab/renderer.h"
#include "raylab/scenes.h"
#include "report.h"
#include "sections.h"

namespace raylab::bench {

namespace {

// ---- What the studies sweep (the section's introduction lists them from here) ---------

constexpr int kGridN[] = {1, 2, 3, 4, 6, 8};  ///< grid and stratified: n x n per pixel
constexpr int kAdaptiveN[] = {4, 5, 8};       ///< adaptive: n x n in refined pixels
constexpr float kThresholds[] = {0.8f, 0.4f, 0.2f, 0.1f, 0.05f};  ///< adaptive contrast
constexpr int kMaxLightSamples = 256;          ///< light samples 1, 2, 4, .. this
constexpr int kConvergedLightSamples = 1024;   ///< the area light's converged image
constexpr float kLightSizes[] = {0.4f, 1.5f};  ///< per scene: about a tenth of its size
constexpr double kTargetSpp = 16;              ///< the anti-aliasing target's reference
constexpr double kTargetLightSamples = 256;    ///< the area-light target's reference
/// The exponent of the grid and stratified pixel samples is fitted from 4 samples on:
/// with 1 sample the grid is the pixel centre and the stratified sample one random point
constexpr double kFitFromSpp = 4;

int converged_spp(const BenchOptions& opt) {
    return opt.quick ? 256 : 1024;
}

struct Point {
    std::string scene, study, scheme;
    double parameter;  ///< samples per pixel, light samples, or the adaptive threshold
    int spp;           ///< samples per pixel in refined pixels (adaptive) or all
    double rays;       ///< camera rays (anti-aliasing) or shadow rays (area light)
    double ms, rmse;
};

// ---- The CSV: every table is computed from the points as it stores them ---------------

const char* const kCsvHeader = "scene,study,scheme,parameter,spp,rays,ms,rmse";

std::string csv_row(const Point& p) {
    return p.scene + "," + p.study + "," + p.scheme + "," + fmt("%g", p.parameter) + "," +
           std::to_string(p.spp) + "," + fmt("%.0f", p.rays) + "," + fmt("%.3f", p.ms) +
           "," + fmt("%.6g", p.rmse);
}

// One row of the CSV; where names the file and line for the error
Point parse_csv_row(const std::string& line, const std::string& where) {
    std::vector<std::string> f;
    std::stringstream in(line);
    for (std::string cell; std::getline(in, cell, ',');)
        f.push_back(cell);
    if (f.size() != 8)
        throw Error(where + ": expected 8 comma-separated fields (" + kCsvHeader +
                    "), got " + std::to_string(f.size()));
    const auto number = [&](int k) {
        char* end = nullptr;
        const double v = std::strtod(f[size_t(k)].c_str(), &end);
        if (f[size_t(k)].empty() || *end != '\0' || !std::isfinite(v))
            throw Error(where + ": field " + std::to_string(k + 1) + " '" + f[size_t(k)] +
                        "' is not a number");
        return v;
    };
    Point p;
    p.scene = f[0], p.study = f[1], p.scheme = f[2];
    p.parameter = number(3), p.spp = int(number(4)), p.rays = number(5);
    p.ms = number(6), p.rmse = number(7);
    if (p.study != "aa" && p.study != "light")
        throw Error(where + ": study '" + p.study + "' is neither aa nor light");
    return p;
}

/// p as the CSV stores it: tables computed live and from the CSV are then the same
Point quantised(const Point& p) {
    return parse_csv_row(csv_row(p), "quantised point");
}

std::vector<Point> read_csv(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Error("cannot read " + path);
    std::string line;
    if (!std::getline(in, line) || line != kCsvHeader)
        throw Error(path + ":1: expected the header " + kCsvHeader);
    std::vector<Point> points;
    for (int n = 2; std::getline(in, line); ++n)
        if (!line.empty())
            points.push_back(parse_csv_row(line, path + ":" + std::to_string(n)));
    if (points.empty()) throw Error(path + ": no measurements");
    return points;
}

void write_csv(const std::string& path, const std::vector<Point>& points) {
    std::ofstream out(path);
    if (!out) throw Error("cannot write " + path);
    out << kCsvHeader << "\n";
    for (const Point& p : points)
        out << csv_row(p) << "\n";
}

// ---- Measuring ------------------------------------------------------------------------

double rmse(const Image& a, const Image& b) {
    double sum = 0.0;
    for (size_t k = 0; k < a.pixels.size(); ++k) {
        const Vec3 d = a.pixels[k] - b.pixels[k];
        sum += double(glm::dot(d, d)) / 3.0;
    }
    return std::sqrt(sum / double(a.pixels.size()));
}

// One render timed (median of repeats), its rays and its error against reference
Point measure(const Scene& scene, const RenderSettings& settings, const Image& reference,
              const ModuleTable& modules, int repeats, bool light_study) {
    Image image;
    FrameStats stats;
    const double s = median_seconds(
        repeats, [&] { stats = render(scene, scene.view, settings, modules, image); });
    Point p;
    p.scene = scene.name;
    p.ms = 1e3 * s;
    p.rays = double(light_study ? stats.shadow_rays : stats.camera_rays);
    p.rmse = rmse(image, reference);
    return p;
}

// ---- The plot -------------------------------------------------------------------------

const char* const kColours[] = {"#1f77b4", "#d62728", "#2ca02c",
                                "#9467bd", "#ff7f0e", "#17becf"};
constexpr int kColourCount = 6;

// One panel per (scene, study): log10 of the cost across (ms, or rays when by_rays),
// log10 RMSE up
void write_svg(const std::string& path, const std::vector<Point>& points, bool by_rays) {
    const auto cost = [&](const Point& p) { return by_rays ? p.rays : p.ms; };
    std::vector<std::pair<std::string, std::string>> panels;
    for (const Point& p : points) {
        const auto key = std::make_pair(p.scene, p.study);
        if (std::find(panels.begin(), panels.end(), key) == panels.end())
            panels.push_back(key);
    }
    const int pw = 420, ph = 320, margin = 60;
    const int cols = 2, rows = int(panels.size() + 1) / 2;
    std::ofstream out(path);
    if (!out) throw Error("cannot write " + path);
    out << "<svg xmlns='http://www.w3.org/2000/svg' width='" << cols * pw << "' height='"
        << rows * ph << "' font-family='sans-serif' font-size='11'>\n"
        << "<rect width='100%' height='100%' fill='white'/>\n";
    for (size_t k = 0; k < panels.size(); ++k) {
        const int ox = int(k % cols) * pw, oy = int(k / cols) * ph;
        std::vector<const Point*> mine;
        for (const Point& p : points)
            if (p.scene == panels[k].first && p.study == panels[k].second)
                mine.push_back(&p);
        double x0 = 1e30, x1 = -1e30, y0 = 1e30, y1 = -1e30;
        for (const Point* p : mine) {
            x0 = std::min(x0, std::log10(cost(*p)));
            x1 = std::max(x1, std::log10(cost(*p)));
            y0 = std::min(y0, std::log10(p->rmse)),
            y1 = std::max(y1, std::log10(p->rmse));
        }
        x0 = std::floor(x0 * 2) / 2, x1 = std::ceil(x1 * 2) / 2;
        y0 = std::floor(y0 * 2) / 2, y1 = std::ceil(y1 * 2) / 2;
        const double w = pw - margin - 20, h = ph - margin - 30;
        const auto X = [&](double c) {
            return ox + margin + (std::log10(c) - x0) / (x1 - x0) * w;
        };
        const auto Y = [&](double e) {
            return oy + 30 + (y1 - std::log10(e)) / (y1 - y0) * h;
        };
        out << "<text x='" << ox + pw / 2 << "' y='" << oy + 18
            << "' text-anchor='middle' font-size='13'>" << panels[k].first << ": "
            << (panels[k].second == "aa" ? "anti-aliasing" : "area light") << "</text>\n";
        out << "<rect x='" << ox + margin << "' y='" << oy + 30 << "' width='" << w
            << "' height='" << h << "' fill='none' stroke='#888'/>\n";
        for (double e = x0; e <= x1 + 1e-9; e += 0.5) {
            const double x = ox + margin + (e - x0) / (x1 - x0) * w;
            out << "<text x='" << x << "' y='" << oy + 30 + h + 14
                << "' text-anchor='middle'>" << fmt("%.3g", std::pow(10.0, e))
                << "</text>\n";
        }
        for (double e = y0; e <= y1 + 1e-9; e += 0.5) {
            const double y = oy + 30 + (y1 - e) / (y1 - y0) * h;
            out << "<text x='" << ox + margin - 4 << "' y='" << y + 4
                << "' text-anchor='end'>" << fmt("%.2g", std::pow(10.0, e))
                << "</text>\n";
        }
        out << "<text x='" << ox + margin + w / 2 << "' y='" << oy + ph - 8
            << "' text-anchor='middle'>"
            << (by_rays ? (panels[k].second == "aa" ? "camera rays" : "shadow rays")
                        : "render time [ms]")
            << ", log scale</text>\n"
            << "<text x='" << ox + 12 << "' y='" << oy + 30 + h / 2
            << "' transform='rotate(-90 " << ox + 12 << " " << oy + 30 + h / 2
            << ")' text-anchor='middle'>RMSE, log scale</text>\n";
        std::vector<std::string> schemes;
        for (const Point* p : mine)
            if (std::find(schemes.begin(), schemes.end(), p->scheme) == schemes.end())
                schemes.push_back(p->scheme);
        for (size_t s = 0; s < schemes.size(); ++s) {
            std::vector<const Point*> line;
            for (const Point* p : mine)
                if (p->scheme == schemes[s]) line.push_back(p);
            // In order of samples: with noisy timings the line may turn back in time
            std::sort(line.begin(), line.end(),
                      [](const Point* a, const Point* b) { return a->rays < b->rays; });
            out << "<polyline fill='none' stroke='" << kColours[s % kColourCount]
                << "' stroke-width='1.5' points='";
            for (const Point* p : line)
                out << X(cost(*p)) << "," << Y(p->rmse) << " ";
            out << "'/>\n";
            for (const Point* p : line)
                out << "<circle cx='" << X(cost(*p)) << "' cy='" << Y(p->rmse)
                    << "' r='2.5' fill='" << kColours[s % kColourCount] << "'/>\n";
            out << "<text x='" << ox + pw - 30 << "' y='" << oy + 46 + 14 * int(s)
                << "' text-anchor='end' fill='" << kColours[s % kColourCount] << "'>"
                << schemes[s] << "</text>\n";
        }
    }
    out << "</svg>\n";
}

// ---- The studies ----------------------------------------------------------------------

// The anti-aliasing study of one scene: point lights, the pixel samples vary
void aa_study(const Scene& scene, const BenchOptions& opt, const ModuleTable& modules,
              std::vector<Point>& points) {
    RenderSettings base;
    base.width = opt.sampling_width;
    base.height = opt.sampling_height;
    base.threads = all_threads(opt);
    RenderSettings converged = base;
    converged.spp = converged_spp(opt);
    converged.sampling = PixelSampling::stratified;
    converged.seed = 999;
    Image reference;
    render(scene, scene.view, converged, modules, reference);
    const int repeats = std::min(opt.repeats, 3);
    for (PixelSampling sampling : {PixelSampling::grid, PixelSampling::stratified}) {
        for (int n : kGridN) {
            RenderSettings s = base;
            s.spp = n * n;
            s.sampling = sampling;
            Point p = measure(scene, s, reference, modules, repeats, false);
            p.study = "aa", p.scheme = to_string(sampling), p.parameter = n * n;
            p.spp = n * n;
            points.push_back(quantised(p));
        }
    }
    for (int n : kAdaptiveN) {
        for (float threshold : kThresholds) {
            RenderSettings s = base;
            s.spp = n * n;
            s.sampling = PixelSampling::adaptive;
            s.aa_threshold = threshold;
            Point p = measure(scene, s, reference, modules, repeats, false);
            p.study = "aa", p.scheme = fmt("adaptive %d", n * n), p.parameter = threshold;
            p.spp = n * n;
            points.push_back(quantised(p));
        }
    }
}

// The area-light study of one scene: one ray per pixel centre, the light samples vary
void light_study(const Scene& scene, float size, const BenchOptions& opt,
                 const ModuleTable& modules, std::vector<Point>& points) {
    RenderSettings base;
    base.width = opt.sampling_width;
    base.height = opt.sampling_height;
    base.threads = all_threads(opt);
    base.light_size = size;
    RenderSettings converged = base;
    converged.light_samples = kConvergedLightSamples;
    converged.seed = 999;
    Image reference;
    render(scene, scene.view, converged, modules, reference);
    const int repeats = std::min(opt.repeats, 3);
    for (bool stratified : {false, true}) {
        for (int N = 1; N <= kMaxLightSamples; N *= 2) {
            RenderSettings s = base;
            s.light_samples = N;
            s.light_stratified = stratified;
            Point p = measure(scene, s, reference, modules, repeats, true);
            p.study = "light", p.scheme = stratified ? "stratified" : "uniform";
            p.parameter = N, p.spp = 1;
            points.push_back(quantised(p));
        }
    }
}

// ---- The tables -----------------------------------------------------------------------

const Point* find(const std::vector<Point>& points, const std::string& scene,
                  const std::string& study, const std::string& scheme, double parameter) {
    for (const Point& p : points)
        if (p.scene == scene && p.study == study && p.scheme == scheme &&
            p.parameter == parameter)
            return &p;
    return nullptr;
}

// The points of one scene, study and scheme, in the CSV's order
std::vector<const Point*> line_of(const std::vector<Point>& points,
                                  const std::string& scene, const std::string& study,
                                  const std::string& scheme) {
    std::vector<const Point*> out;
    for (const Point& p : points)
        if (p.scene == scene && p.study == study && p.scheme == scheme) out.push_back(&p);
    return out;
}

// Distinct values of field over points, in order of first appearance
template <class Field>
std::vector<std::string> distinct(const std::vector<Point>& points, Field field) {
    std::vector<std::string> out;
    for (const Point& p : points)
        if (std::find(out.begin(), out.end(), field(p)) == out.end())
            out.push_back(field(p));
    return out;
}

std::vector<std::string> scenes_of(const std::vector<Point>& points) {
    return distinct(points, [](const Point& p) { return p.scene; });
}

// The cheapest point of study whose scheme starts with prefix and whose RMSE is at most
// target's
const Point* cheapest_match(const std::vector<Point>& points, const Point& target,
                            const std::string& prefix) {
    const Point* best = nullptr;
    for (const Point& p : points) {
        if (p.scene != target.scene || p.study != target.study ||
            p.scheme.rfind(prefix, 0) != 0 || p.rmse > target.rmse)
            continue;
        if (!best || p.rays < best->rays) best = &p;
    }
    return best;
}

std::string ratio(double a, double b) {
    return fmt("%.2f", a / b);
}

std::string ms_vs(const Point& a, const Point& b) {
    return fmt("%.0f ms vs %.0f ms", a.ms, b.ms);
}

void print_subheading(const char* title, const std::string& text) {
    std::printf("### %s\n\n%s\n\n", title, text.c_str());
}

// The sampling targets: the cheapest measured setting that reaches the reference's RMSE
void print_target_table(const std::vector<Point>& points) {
    print_subheading(
        "The targets",
        "For each target, the cheapest measured setting whose RMSE is at most the "
        "reference's, and its share of the reference's cost: camera rays (anti-aliasing) "
        "or light samples (area light). The time column is one run's and noisy; the "
        "share is deterministic.");
    Table table({"scene", "target", "reference", "cheapest with at most its RMSE",
                 "share", "time", "met"},
                4);
    int met = 0, targets = 0;
    for (const std::string& scene : scenes_of(points)) {
        if (const Point* s = find(points, scene, "aa", "stratified", kTargetSpp)) {
            const Point* a = cheapest_match(points, *s, "adaptive");
            const bool ok = a && a->rays * 3 <= s->rays;
            table.row({scene,
                       fmt("adaptive anti-aliasing: at most 1/3 of stratified %g's "
                           "camera rays",
                           kTargetSpp),
                       fmt("stratified %g: RMSE %s, %.0f rays", kTargetSpp,
                           sci(s->rmse).c_str(), s->rays),
                       a ? fmt("%s, threshold %g: RMSE %s, %.0f rays", a->scheme.c_str(),
                               a->parameter, sci(a->rmse).c_str(), a->rays)
                         : "none",
                       a ? ratio(a->rays, s->rays) : "-", a ? ms_vs(*a, *s) : "-",
                       ok ? "yes" : "no"});
            met += ok, ++targets;
        }
        if (const Point* u =
                find(points, scene, "light", "uniform", kTargetLightSamples)) {
            const Point* st = cheapest_match(points, *u, "stratified");
            const bool ok = st && st->parameter * 4 <= u->parameter;
            table.row(
                {scene,
                 fmt("stratified light samples: at most 1/4 of %g uniform ones",
                     kTargetLightSamples),
                 fmt("uniform %g: RMSE %s", kTargetLightSamples, sci(u->rmse).c_str()),
                 st ? fmt("stratified %g: RMSE %s", st->parameter, sci(st->rmse).c_str())
                    : "none",
                 st ? fmt("%.3f (%g of %g)", st->parameter / u->parameter, st->parameter,
                          u->parameter)
                    : "-",
                 st ? ms_vs(*st, *u) : "-", ok ? "yes" : "no"});
            met += ok, ++targets;
        }
    }
    table.print();
    std::printf("Targets met: %d of %d.\n\n", met, targets);
}

// How fast the error falls: the exponent of RMSE ~ N^e between the first and last count
void print_convergence(const std::vector<Point>& points) {
    print_subheading(
        "How fast the error falls",
        fmt("RMSE from the first to the last sample count of each scheme, and the "
            "exponent e "
            "of RMSE ~ N^e through those two points (N: samples per pixel, or light "
            "samples; anti-aliasing from %g samples). The handout's exponent is for a "
            "pixel on an edge or in a penumbra, where the error is.",
            kFitFromSpp));
    Table table({"scene", "scheme", "samples", "RMSE", "falls by", "exponent",
                 "handout's exponent"},
                3);
    struct Line {
        const char *study, *scheme, *label, *handout;
        double from;
    };
    const Line lines[] = {
        {"aa", "grid", "grid", "-1/2 (09 §2)", kFitFromSpp},
        {"aa", "stratified", "stratified", "-3/4 (09 §3)", kFitFromSpp},
        {"light", "uniform", "light, uniform", "-1/2 (10 §3)", 1},
        {"light", "stratified", "light, stratified", "-3/4 (10 §3)", 1}};
    for (const std::string& scene : scenes_of(points)) {
        for (const Line& l : lines) {
            const Point *a = nullptr, *b = nullptr;
            for (const Point* p : line_of(points, scene, l.study, l.scheme)) {
                if (p->parameter < l.from) continue;
                if (!a || p->parameter < a->parameter) a = p;
                if (!b || p->parameter > b->parameter) b = p;
            }
            if (!a || a == b) continue;
            const double e =
                std::log(b->rmse / a->rmse) / std::log(b->parameter / a->parameter);
            table.row({scene, l.label, fmt("%g to %g", a->parameter, b->parameter),
                       sci(a->rmse) + " to " + sci(b->rmse),
                       fmt("%.1f", a->rmse / b->rmse), fmt("%.2f", e), l.handout});
        }
    }
    table.print();
}

// Grid against stratified pixel samples, count by count
void print_grid_stratified(const std::vector<Point>& points) {
    print_subheading("Anti-aliasing: grid against stratified",
                     "Both schemes cast the same camera rays at each count. grid / "
                     "stratified above 1: stratified has the lower error.");
    Table table({"scene", "samples per pixel", "camera rays", "grid RMSE",
                 "stratified RMSE", "grid / stratified", "grid ms", "stratified ms"},
                1);
    for (const std::string& scene : scenes_of(points))
        for (const Point* g : line_of(points, scene, "aa", "grid"))
            if (const Point* s = find(points, scene, "aa", "stratified", g->parameter))
                table.row({scene, fmt("%g", g->parameter), fmt("%.0f", g->rays),
                           sci(g->rmse), sci(s->rmse), ratio(g->rmse, s->rmse),
                           fmt("%.1f", g->ms), fmt("%.1f", s->ms)});
    table.print();
}

// Adaptive against stratified with as many samples in every pixel
void print_adaptive(const std::vector<Point>& points) {
    print_subheading(
        "Anti-aliasing: adaptive",
        "Adaptive N at each threshold against stratified N (N samples in every pixel; "
        "'-' where that count was not measured): its share of the camera rays, and its "
        "RMSE over stratified N's (below 1: adaptive has the lower error).");
    Table table({"scene", "scheme", "threshold", "camera rays", "share of stratified N's",
                 "RMSE", "RMSE / stratified N's", "ms"},
                2);
    for (const std::string& scene : scenes_of(points))
        for (const std::string& scheme :
             distinct(points, [](const Point& p) { return p.scheme; })) {
            if (scheme.rfind("adaptive", 0) != 0) continue;
            for (const Point* a : line_of(points, scene, "aa", scheme)) {
                const Point* s = find(points, scene, "aa", "stratified", a->spp);
                table.row({scene, scheme, fmt("%g", a->parameter), fmt("%.0f", a->rays),
                           s ? ratio(a->rays, s->rays) : "-", sci(a->rmse),
                           s ? ratio(a->rmse, s->rmse) : "-", fmt("%.1f", a->ms)});
            }
        }
    table.print();
}

// Uniform against stratified light samples, count by count
void print_light(const std::vector<Point>& points) {
    print_subheading("Area light: uniform against stratified",
                     "uniform / stratified above 1: stratified has the lower error.");
    Table table({"scene", "light samples", "uniform shadow rays", "uniform RMSE",
                 "stratified shadow rays", "stratified RMSE", "uniform / stratified",
                 "uniform ms", "stratified ms"},
                1);
    for (const std::string& scene : scenes_of(points))
        for (const Point* u : line_of(points, scene, "light", "uniform"))
            if (const Point* s = find(points, scene, "light", "stratified", u->parameter))
                table.row({scene, fmt("%g", u->parameter), fmt("%.0f", u->rays),
                           sci(u->rmse), fmt("%.0f", s->rays), sci(s->rmse),
                           ratio(u->rmse, s->rmse), fmt("%.1f", u->ms),
                           fmt("%.1f", s->ms)});
    table.print();
}

// Every table of docs/sampling-benchmarks.md, from the points alone
void print_tables(const std::vector<Point>& points) {
    print_target_table(points);
    print_convergence(points);
    print_grid_stratified(points);
    print_adaptive(points);
    print_light(points);
}

// "1, 4 and 9": the values (or their squares) of [begin, end)
std::string list(const int* begin, const int* end, bool squares) {
    std::string out;
    for (const int* n = begin; n != end; ++n) {
        if (n != begin) out += n + 1 == end ? " and " : ", ";
        out += std::to_string(squares ? *n * *n : *n);
    }
    return out;
}

// What the run measured, with the settings it swept
std::string introduction(const BenchOptions& opt, const Scene* scenes, int count) {
    std::string thresholds, sizes;
    for (float t : kThresholds)
        thresholds += (thresholds.empty() ? "" : ", ") + fmt("%g", double(t));
    for (int k = 0; k < count; ++k)
        sizes += (k ? ", " : "") +
                 fmt("%g in %s", double(kLightSizes[k]), scenes[k].name.c_str());
    return fmt(
        "render() at %dx%d pixels with the reference modules on %d threads. "
        "**Anti-aliasing** (module 09; point lights, hard shadows): grid and stratified "
        "with %s samples per pixel, and adaptive N (one sample at every pixel centre, "
        "then N stratified samples in the pixels whose 3 x 3 neighbourhood has a "
        "contrast above the threshold) with N = %s and thresholds %s; converged image: "
        "%d stratified samples per pixel; cost: camera rays (the shadow rays grow with "
        "them). **Area light** (module 10; one ray through each pixel centre): each "
        "point light replaced by a square area light (side %s), 1 to %d uniform or "
        "stratified light samples; converged image: %d stratified light samples; cost: "
        "shadow rays. Error: the RMSE of the linear RGB radiance over all pixels and "
        "channels against the converged image of the same scene.\n\n"
        "Rays and RMSE are deterministic: every sample comes from the seeded PixelRng, "
        "so they are the same on every machine and every run of the same code. Times "
        "(ms) are not: each is the median of %d frames after a warm-up on this machine "
        "at its load, and changes from run to run.",
        opt.sampling_width, opt.sampling_height, all_threads(opt),
        list(std::begin(kGridN), std::end(kGridN), true).c_str(),
        list(std::begin(kAdaptiveN), std::end(kAdaptiveN), true).c_str(),
        thresholds.c_str(), converged_spp(opt), sizes.c_str(), kMaxLightSamples,
        kConvergedLightSamples, std::min(opt.repeats, 3));
}

}  // namespace

void run_sampling_section(const BenchOptions& opt) {
    const char* const title = "5. Sampling: run time against error (modules 09 and 10)";
    if (!opt.sampling_csv.empty()) {
        const std::vector<Point> points = read_csv(opt.sampling_csv);
        print_heading(title,
                      "Recomputed from " + opt.sampling_csv +
                          " (a sampling.csv of an earlier run); nothing rendered.");
        print_tables(points);
        return;
    }
    const ModuleTable modules = ModuleTable::make(ModuleSelection::all(Impl::reference));
    const Scene scenes[] = {cornell_box(), dtu_scene()};
    static_assert(std::size(kLightSizes) == std::size(scenes));
    print_heading(title, introduction(opt, scenes, int(std::size(scenes))));
    std::vector<Point> points;
    for (size_t k = 0; k < std::size(scenes); ++k) {
        aa_study(scenes[k], opt, modules, points);
        light_study(scenes[k], kLightSizes[k], opt, modules, points);
    }
    print_tables(points);
    std::error_code made;
    std::filesystem::create_directories(opt.out_dir, made);
    if (made) throw Error("--out " + opt.out_dir + ": " + made.message());
    write_csv(opt.out_dir + "/sampling.csv", points);
    write_svg(opt.out_dir + "/sampling.svg", points, false);
    write_svg(opt.out_dir + "/sampling-rays.svg", points, true);
    std::printf(
        "Wrote sampling.csv (all %zu measurements), sampling.svg (RMSE against time) and "
        "sampling-rays.svg (against rays) in %s\n\n",
        points.size(), opt.out_dir.c_str());
}

}  // namespace raylab::bench
