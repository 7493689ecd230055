// Section 5: run time against error of the sampling schemes of modules 09 and 10
// (bench/sections.h, docs/sampling-benchmarks.md).
//
// For the Cornell box and the DTU scene, every scheme renders at growing sample counts
// and each image's RMSE against a converged image of the same scene is set against its
// render time and rays. Anti-aliasing (point lights, hard shadows): grid, stratified and
// adaptive pixel samples; the converged image has 32 x 32 stratified samples per pixel.
// Area lights (one ray per pixel centre): 1..256 uniform against stratified light
// samples; the converged image has 1024 stratified ones. Writes the table, a CSV and an
// SVG plot (log-log, one line per scheme).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>

#include "raylab/error.h"
#include "raylab/renderer.h"
#include "raylab/scenes.h"
#include "report.h"
#include "sections.h"

namespace raylab::bench {

namespace {

struct Point {
    std::string scene, study, scheme;
    double parameter;  ///< samples per pixel, light samples, or the adaptive threshold
    int spp;           ///< samples per pixel in refined pixels (adaptive) or all
    double rays;       ///< camera rays (anti-aliasing) or shadow rays (area light)
    double ms, rmse;
};

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

void write_csv(const std::string& path, const std::vector<Point>& points) {
    std::ofstream out(path);
    if (!out) throw Error("cannot write " + path);
    out << "scene,study,scheme,parameter,spp,rays,ms,rmse\n";
    for (const Point& p : points)
        out << p.scene << "," << p.study << "," << p.scheme << "," << p.parameter << ","
            << p.spp << "," << p.rays << "," << fmt("%.3f", p.ms) << ","
            << fmt("%.6g", p.rmse) << "\n";
}

}  // namespace

namespace {

// The anti-aliasing study of one scene: point lights, the pixel samples vary
void aa_study(const Scene& scene, const BenchOptions& opt, const ModuleTable& modules,
              std::vector<Point>& points) {
    RenderSettings base;
    base.width = opt.sampling_width;
    base.height = opt.sampling_height;
    base.threads = all_threads(opt);
    RenderSettings converged = base;
    converged.spp = opt.quick ? 256 : 1024;
    converged.sampling = PixelSampling::stratified;
    converged.seed = 999;
    Image reference;
    render(scene, scene.view, converged, modules, reference);
    const int repeats = std::min(opt.repeats, 3);
    for (PixelSampling sampling : {PixelSampling::grid, PixelSampling::stratified}) {
        for (int n : {1, 2, 3, 4, 6, 8}) {
            RenderSettings s = base;
            s.spp = n * n;
            s.sampling = sampling;
            Point p = measure(scene, s, reference, modules, repeats, false);
            p.study = "aa", p.scheme = to_string(sampling), p.parameter = n * n;
            p.spp = n * n;
            points.push_back(p);
        }
    }
    for (int n : {4, 5, 8}) {
        for (float threshold : {0.8f, 0.4f, 0.2f, 0.1f, 0.05f}) {
            RenderSettings s = base;
            s.spp = n * n;
            s.sampling = PixelSampling::adaptive;
            s.aa_threshold = threshold;
            Point p = measure(scene, s, reference, modules, repeats, false);
            p.study = "aa", p.scheme = fmt("adaptive %d", n * n), p.parameter = threshold;
            p.spp = n * n;
            points.push_back(p);
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
    converged.light_samples = 1024;
    converged.seed = 999;
    Image reference;
    render(scene, scene.view, converged, modules, reference);
    const int repeats = std::min(opt.repeats, 3);
    for (bool stratified : {false, true}) {
        for (int N = 1; N <= 256; N *= 2) {
            RenderSettings s = base;
            s.light_samples = N;
            s.light_stratified = stratified;
            Point p = measure(scene, s, reference, modules, repeats, true);
            p.study = "light", p.scheme = stratified ? "stratified" : "uniform";
            p.parameter = N, p.spp = 1;
            points.push_back(p);
        }
    }
}

const Point* find(const std::vector<Point>& points, const std::string& scene,
                  const std::string& study, const std::string& scheme, double parameter) {
    for (const Point& p : points)
        if (p.scene == scene && p.study == study && p.scheme == scheme &&
            p.parameter == parameter)
            return &p;
    return nullptr;
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

}  // namespace

void run_sampling_section(const BenchOptions& opt) {
    print_heading(
        "4. Sampling: run time against error (modules 09 and 10)",
        fmt("render() at %dx%d with the reference modules on %d threads; ms: median of "
            "%d "
            "frames. RMSE over the linear RGB radiance against a converged image of the "
            "same scene: %d stratified samples per pixel (anti-aliasing, point lights) "
            "or "
            "1024 stratified light samples (area light, one ray per pixel centre). Rays: "
            "camera rays (anti-aliasing) or shadow rays (area light). Adaptive N: one "
            "sample everywhere, N stratified ones where the contrast exceeds the "
            "threshold (the parameter). CSV and SVG in %s.",
            opt.sampling_width, opt.sampling_height, all_threads(opt),
            std::min(opt.repeats, 3), opt.quick ? 256 : 1024, opt.out_dir.c_str()));
    const ModuleTable modules = ModuleTable::make(ModuleSelection::all(Impl::reference));
    std::vector<Point> points;
    const Scene scenes[] = {cornell_box(), dtu_scene()};
    const float light_sizes[] = {0.4f, 1.5f};  // about a tenth of each scene's size
    for (int k = 0; k < 2; ++k) {
        aa_study(scenes[k], opt, modules, points);
        light_study(scenes[k], light_sizes[k], opt, modules, points);
    }
    Table table({"scene", "study", "scheme", "parameter", "rays", "ms", "RMSE"}, 3);
    for (const Point& p : points)
        table.row({p.scene, p.study, p.scheme, fmt("%g", p.parameter),
                   fmt("%.0f", p.rays), fmt("%.1f", p.ms), sci(p.rmse)});
    table.print();

    // The targets
    std::printf("\nTargets:\n");
    for (const Scene& scene : scenes) {
        if (const Point* s16 = find(points, scene.name, "aa", "stratified", 16)) {
            const Point* a = cheapest_match(points, *s16, "adaptive");
            if (a)
                std::printf(
                    "- %s: adaptive (%s, threshold %g) reaches stratified-16's "
                    "RMSE %s with %.0f camera rays, %.2f of its %.0f (target <= "
                    "1/3: %s)\n",
                    scene.name.c_str(), a->scheme.c_str(), a->parameter,
                    sci(s16->rmse).c_str(), a->rays, a->rays / s16->rays, s16->rays,
                    a->rays * 3 <= s16->rays ? "met" : "missed");
            else
                std::printf(
                    "- %s: no adaptive setting reaches stratified-16's RMSE %s "
                    "(target missed)\n",
                    scene.name.c_str(), sci(s16->rmse).c_str());
        }
        if (const Point* u256 = find(points, scene.name, "light", "uniform", 256)) {
            const Point* st = cheapest_match(points, *u256, "stratified");
            if (st)
                std::printf(
                    "- %s: stratified light sampling reaches uniform-256's RMSE %s "
                    "with %g samples, %.3f of 256 (target <= 1/4: %s)\n",
                    scene.name.c_str(), sci(u256->rmse).c_str(), st->parameter,
                    st->parameter / 256.0, st->parameter * 4 <= 256 ? "met" : "missed");
        }
    }
    write_csv(opt.out_dir + "/sampling.csv", points);
    write_svg(opt.out_dir + "/sampling.svg", points, false);
    write_svg(opt.out_dir + "/sampling-rays.svg", points, true);
    std::printf(
        "\nWrote sampling.csv, sampling.svg (RMSE against time) and "
        "sampling-rays.svg (against rays) in %s\n\n",
        opt.out_dir.c_str());
}

}  // namespace raylab::bench
