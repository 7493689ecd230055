// bench/report.h: Markdown tables, number formatting, medians and timing for
// raylab-bench.
#pragma once

#include <chrono>
#include <functional>
#include <string>
#include <vector>

namespace raylab::bench {

/// printf into a std::string.
std::string fmt(const char* format, ...) __attribute__((format(printf, 1, 2)));

/// A value in 3 significant digits ("0.000123" style avoided: 1.23e-04), or "-" for NaN.
std::string sci(double v);

/// A table printed as aligned Markdown, so that the output pastes into docs as it is.
class Table {
  public:
    /// The first left_columns columns are left-aligned (labels), the rest right-aligned.
    Table(std::vector<std::string> headers, int left_columns = 1);
    void row(std::vector<std::string> cells);
    void print() const;

  private:
    std::vector<std::string> headers_;
    std::vector<std::vector<std::string>> rows_;
    int left_columns_;
};

/// Prints "## title" and an optional explanation, as the sections' headings.
void print_heading(const std::string& title, const std::string& text = "");

/// Median of v (v is copied); NaN for an empty v.
double median(std::vector<double> v);

/// The q-quantile (0..1) of v by nearest rank; NaN for an empty v.
double quantile(std::vector<double> v, double q);

/// Where timed loops store a result, so that the compiler keeps the work that made it.
inline volatile float g_sink = 0.0f;

/// Wall-clock seconds since start.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
        .count();
}

/// Runs work once untimed (warm-up), then repeats times, and returns the median time of
/// one run in seconds.
template <class Work>
double median_seconds(int repeats, Work&& work) {
    work();
    std::vector<double> s;
    for (int k = 0; k < repeats; ++k) {
        const auto start = std::chrono::steady_clock::now();
        work();
        s.push_back(seconds_since(start));
    }
    return median(s);
}

/// Times several works round-robin: each once untimed (warm-up), then `repeats` rounds
/// of one run each. Returns the median seconds of each work. Interleaving spreads a
/// change of machine load over all works alike, so their ratios stay fair.
std::vector<double> interleaved_median_seconds(
    int repeats, const std::vector<std::function<void()>>& works);

/// The same timing, kept round by round: seconds[w][k] is work w's time in round k.
/// A round runs every work once, one after the other, so two works' times of the same
/// round were taken a moment apart, under nearly the same load.
struct RoundTimes {
    std::vector<std::vector<double>> seconds;

    /// Each work's median over the rounds, as interleaved_median_seconds returns them
    std::vector<double> medians() const;
    /// seconds[num][k] / seconds[den][k] for each round k: a speed ratio of one round
    /// (Embree's time over raylab's is raylab's speed over Embree's)
    std::vector<double> ratios(size_t num, size_t den) const;
};
RoundTimes interleaved_seconds(int repeats,
                               const std::vector<std::function<void()>>& works);

/// A figure the run measured against the target set for it. The sections
/// record them as they go; print_targets() closes the run with one table, so the targets
/// table in docs/benchmarks.md comes from the same run as the tables above it.
/// higher_is_better: the target is a lower bound (a speed ratio), else an upper bound.
/// per_round: the same figure computed from each round's times alone (RoundTimes), for
/// the table's "rounds met" and "per round" columns; empty for a figure not timed in
/// rounds (memory, a build timed apart from its peer's, a worst case over sets).
void record_target(const std::string& what, double measured, double target,
                   bool higher_is_better, const std::string& unit = "",
                   std::vector<double> per_round = {});
/// Prints "## Targets" with every recorded figure, or nothing when none was recorded.
void print_targets();

/// Date, CPU, threads, load, compiler and seed: the header of every run.
void print_machine(unsigned long long seed, int repeats);

/// The 1-minute load average, from /proc/loadavg (NaN when unavailable).
double load_average();

}  // namespace raylab::bench
