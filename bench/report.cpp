// Tables, statistics and the machine header of raylab-bench (bench/report.h).
#include "report.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <limits>
#include <thread>
#include <vector>

#include "raylab/bvh.h"
#include "raylab/engine.h"

namespace raylab::bench {

std::string fmt(const char* format, ...) {
    va_list args, copy;
    va_start(args, format);
    va_copy(copy, args);
    const int n = std::vsnprintf(nullptr, 0, format, copy);
    va_end(copy);
    std::string out(static_cast<size_t>(std::max(n, 0)) + 1, '\0');
    std::vsnprintf(out.data(), out.size(), format, args);
    va_end(args);
    out.resize(static_cast<size_t>(std::max(n, 0)));
    return out;
}

std::string sci(double v) {
    if (std::isnan(v)) return "-";
    if (v == 0.0) return "0";
    return fmt("%.2e", v);
}

Table::Table(std::vector<std::string> headers, int left_columns)
    : headers_(std::move(headers)), left_columns_(left_columns) {}

void Table::row(std::vector<std::string> cells) {
    cells.resize(headers_.size());
    rows_.push_back(std::move(cells));
}

void Table::print() const {
    std::vector<size_t> width(headers_.size(), 3);
    for (size_t c = 0; c < headers_.size(); ++c) {
        width[c] = std::max(width[c], headers_[c].size());
        for (const auto& r : rows_)
            width[c] = std::max(width[c], r[c].size());
    }
    const auto line = [&](const std::vector<std::string>& cells) {
        std::string s = "|";
        for (size_t c = 0; c < cells.size(); ++c) {
            const std::string pad(width[c] - cells[c].size(), ' ');
            const bool left = static_cast<int>(c) < left_columns_;
            s += " " + (left ? cells[c] + pad : pad + cells[c]) + " |";
        }
        std::printf("%s\n", s.c_str());
    };
    line(headers_);
    std::string rule = "|";
    for (size_t c = 0; c < headers_.size(); ++c) {
        const bool left = static_cast<int>(c) < left_columns_;
        rule += left ? " " + std::string(width[c], '-') + " |"
                     : " " + std::string(width[c] - 1, '-') + ": |";
    }
    std::printf("%s\n", rule.c_str());
    for (const auto& r : rows_)
        line(r);
    std::printf("\n");
    std::fflush(stdout);
}

void print_heading(const std::string& title, const std::string& text) {
    std::printf("## %s\n\n", title.c_str());
    if (!text.empty()) std::printf("%s\n\n", text.c_str());
    std::fflush(stdout);
}

double median(std::vector<double> v) {
    return quantile(std::move(v), 0.5);
}

double quantile(std::vector<double> v, double q) {
    if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
    const size_t k = std::min(v.size() - 1, static_cast<size_t>(q * v.size()));
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return v[k];
}

RoundTimes interleaved_seconds(int repeats,
                               const std::vector<std::function<void()>>& works) {
    for (const auto& work : works)
        work();
    RoundTimes t;
    t.seconds.resize(works.size());
    for (int k = 0; k < repeats; ++k) {
        for (size_t w = 0; w < works.size(); ++w) {
            const auto start = std::chrono::steady_clock::now();
            works[w]();
            t.seconds[w].push_back(seconds_since(start));
        }
    }
    return t;
}

std::vector<double> RoundTimes::medians() const {
    std::vector<double> out;
    for (const std::vector<double>& work : seconds)
        out.push_back(median(work));
    return out;
}

std::vector<double> RoundTimes::ratios(size_t num, size_t den) const {
    std::vector<double> out;
    for (size_t k = 0; k < seconds.at(num).size() && k < seconds.at(den).size(); ++k)
        out.push_back(seconds[num][k] / seconds[den][k]);
    return out;
}

std::vector<double> interleaved_median_seconds(
    int repeats, const std::vector<std::function<void()>>& works) {
    return interleaved_seconds(repeats, works).medians();
}

double load_average() {
    std::ifstream in("/proc/loadavg");
    double load = std::numeric_limits<double>::quiet_NaN();
    in >> load;
    return load;
}

namespace {

std::string cpu_model() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("model name", 0) == 0) {
            const size_t colon = line.find(':');
            if (colon != std::string::npos) return line.substr(colon + 2);
        }
    }
    return "unknown";
}

// The kernel's transparent huge page mode, the bracketed word of
// /sys/kernel/mm/transparent_hugepage/enabled ("always", "madvise" or "never")
std::string huge_page_mode() {
    std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string line;
    std::getline(in, line);
    const size_t open = line.find('['), close = line.find(']');
    if (open == std::string::npos || close == std::string::npos || close < open)
        return "unknown (no /sys/kernel/mm/transparent_hugepage/enabled)";
    return line.substr(open + 1, close - open - 1);
}

}  // namespace

void print_machine(unsigned long long seed, int repeats) {
    char date[64];
    const std::time_t now = std::time(nullptr);
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M %Z", std::localtime(&now));
#ifdef NDEBUG
    const char* build = "optimised (NDEBUG)";
#else
    const char* build = "NOT optimised (assertions on): timings mean little";
#endif
    std::printf("# raylab-bench\n\n");
    std::printf("- date: %s\n", date);
    std::printf("- CPU: %s, %u hardware threads\n", cpu_model().c_str(),
                std::thread::hardware_concurrency());
    std::printf("- load average at start: %.2f (others' work makes timings noisy)\n",
                load_average());
    std::printf("- compiler: g++-compatible %s, build: %s\n", __VERSION__, build);
    std::printf(
        "- reference engine: the %s versions of its queries (chosen at run time; "
        "RAYLAB_NO_AVX512=1 forces at most the avx2 ones, RAYLAB_NO_AVX2=1 the "
        "baseline)\n",
        reference::geometry_engine()->versions);
    // raylab's request, tried once on an array of its own
    std::vector<char> probe(2 * kHugePagesFrom, 1);
    const bool granted = back_with_huge_pages(probe.data(), probe.size());
    std::printf(
        "- huge pages: raylab's arrays of 4 MiB or more (MADV_COLLAPSE, whatever the "
        "mode below): %s; Embree's BVH (MADV_HUGEPAGE): unless the mode is never; "
        "the kernel's transparent huge page mode: %s\n",
        granted ? "granted here" : "declined here", huge_page_mode().c_str());
    std::printf("- seed: %llu (rerun with --seed %llu for the same rays)\n", seed, seed);
    std::printf("- timings: median of %d repeats after one warm-up run\n\n", repeats);
    std::fflush(stdout);
}

namespace {

struct TargetRecord {
    std::string what;
    double measured;
    double target;
    bool higher_is_better;
    std::string unit;
    std::vector<double> per_round;

    bool meets(double v) const { return higher_is_better ? v >= target : v <= target; }
};

std::vector<TargetRecord>& target_records() {
    static std::vector<TargetRecord> records;
    return records;
}

}  // namespace

void record_target(const std::string& what, double measured, double target,
                   bool higher_is_better, const std::string& unit,
                   std::vector<double> per_round) {
    target_records().push_back(
        {what, measured, target, higher_is_better, unit, std::move(per_round)});
}

void print_targets() {
    if (target_records().empty()) return;
    print_heading(
        "Targets",
        "The targets against this run's figures (the kernels' cost; speed against "
        "Embree, frame time, build, memory). A ratio "
        "to Embree is raylab's speed over Embree's (1 = as fast); a kernel's is "
        "its ns/test over the float formulation's, on the worst ray set. measured "
        "is the figure of the tables above (from the medians of the rounds); rounds "
        "met counts the rounds whose own times give a figure that meets the target, "
        "and per round gives those figures' median and, in brackets, the smallest "
        "and largest (with one round, all three are the figure): a target met in "
        "some rounds and missed in others is on its line, and the machine's load "
        "decides the run; one missed in every round is not. - : not timed in rounds "
        "(memory; a build, timed apart from Embree's; a worst case over ray sets).");
    Table table({"what", "measured", "target", "met", "rounds met", "per round"});
    for (const TargetRecord& r : target_records()) {
        const std::string bound = r.higher_is_better ? ">= " : "<= ";
        std::string rounds = "-", spread = "-";
        if (!r.per_round.empty()) {
            const auto met = std::count_if(r.per_round.begin(), r.per_round.end(),
                                           [&](double v) { return r.meets(v); });
            const auto [lo, hi] =
                std::minmax_element(r.per_round.begin(), r.per_round.end());
            rounds = fmt("%td of %zu", met, r.per_round.size());
            spread = fmt("%.3g", median(r.per_round)) + r.unit + " (" + fmt("%.3g", *lo) +
                     " - " + fmt("%.3g", *hi) + ")";
        }
        table.row(
            {r.what, fmt("%.3g", r.measured) + r.unit,
             bound + fmt("%g", r.target) + r.unit,
             std::isnan(r.measured) ? "-" : (r.meets(r.measured) ? "yes" : "**no**"),
             rounds, spread});
    }
    table.print();
}

}  // namespace raylab::bench
