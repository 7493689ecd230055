// raylab-grade's parts (grade_main.cpp): results of a grading run, running the graders,
// and the reports.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "raylab/modules.h"

namespace raylab::grade {

/// The name prefix of the hidden test cases (graded only with --private).
inline constexpr const char* kPrivate = "[private]";

/// What the driver was asked to do (the command line).
struct Options {
    std::string tests, out, label, expect;
    std::string workers;      // folder with one worker per module ID (scripts/grade.sh)
    std::string private_dir;  // the instructor's private cases (hidden tests)
    std::string only;         // grade this module only (the viewer's "Run tests")
    bool reference = false;
    double timeout = 10.0;
    double points = 10.0;
    std::map<std::string, std::string> module_errors;  // ID -> file with the message
    std::map<std::string, std::string> sources;        // ID -> the hand-in's file graded
    std::map<std::string, std::vector<std::string>>
        notes;  // ID ("-": the hand-in) -> notes
};

/// The outcome of one test case.
struct CaseResult {
    std::string name;
    std::string status = "not run";  // pass, fail, stub, crash, not run
    std::string message;
};

/// The outcome of one module: its cases, status, score and first failure.
struct ModuleResult {
    const ModuleInfo* info = nullptr;
    std::vector<CaseResult> cases;
    std::string status;  // passed, failed, not started, crashed (SIG...), time limit, ...
    std::string first_failure;
    std::string build_error;
    std::string sandbox;  // how the worker was protected
    std::string source;   // the hand-in's file that was graded
    std::string reason;   // why it lost points, in the words every report uses (reason())
    std::vector<std::string> notes;
    int passed = 0;
    double score = 0.0, max_score = 0.0;
    double seconds = 0.0;
};

/// Prints "raylab-grade: message" and exits with status 2.
[[noreturn]] void die(const std::string& message);
std::string read_file(const std::string& path);
/// Writes text to path; dies on failure.
void write_file(const std::string& path, const std::string& text);
/// mkdir -p
void make_dirs(const std::string& path);
std::vector<std::string> split(const std::string& s, char sep);
std::string first_line(const std::string& s);
std::string shorten(const std::string& s, size_t n);
/// Two decimals.
std::string fixed(double x);
/// x rounded to two decimals, as every report prints it (the total adds these).
double rounded(double x);
/// Why a module lost points, one wording for every report: "" (full marks), missing,
/// refused, did not compile, did not link, not allowed, not started, crashed with signal
/// SIGxxx, no answer in N s, NaN, wrong, grader error.
std::string reason(const ModuleResult& m, double timeout);
/// Every line of s indented by two spaces: student text never starts a report's line.
std::string indented(const std::string& s);

// grade_run.cpp
/// The test case names of each suite (raylab-grading-tests --list-test-cases).
std::map<std::string, std::vector<std::string>> list_cases(const Options& o);
/// Runs one module's suite in its own process with the time limit and scores it.
ModuleResult grade_module(const Options& o, const ModuleInfo& info,
                          const std::vector<std::string>& names);

// grade_report.cpp
/// s as valid UTF-8 without terminal escapes or control characters other than newline and
/// tab: student output reaches every report only through this.
std::string clean_text(const std::string& s);
/// The score table.
std::string table(const std::vector<ModuleResult>& modules, const std::string& label);
/// What a student reads about one module: status and every failure with its message.
std::string module_output(const ModuleResult& m, size_t max_cases = 12);
/// JUnit XML: one testsuite per module, one testcase per test case.
std::string junit(const std::vector<ModuleResult>& modules);
/// Every case of every module with its status and message, for the viewer's "Run tests".
std::string cases_json(const std::vector<ModuleResult>& modules);
/// The modules of a cases_json text, as the viewer reads them: id, status, counts, score,
/// reason, first failure, build error and cases. A module the registry does not know is
/// left out; text that is not such a list gives none.
std::vector<ModuleResult> read_cases_json(const std::string& text);
/// Gradescope's results.json: score, output, one test per module (extra_data: its reason
/// and notes), and the notes on the whole hand-in (extra_data.notes).
std::string results_json(const std::vector<ModuleResult>& modules,
                         const std::string& summary,
                         const std::vector<std::string>& hand_in_notes);

}  // namespace raylab::grade
