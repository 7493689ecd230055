// raylab-grade: runs the graders one module at a time and reports the scores.
//
//   raylab-grade --tests BUILD/tests/grading/raylab-grading-tests --out DIR [options]
//
// Each module's suite runs in its own process with a time limit, so a crash, an
// exception, a NaN or an endless loop in one module fails that module only. The driver
// prints a table (module, tests passed / total, points, first failure) and writes
// DIR/summary.txt, DIR/junit.xml, DIR/results.json (Gradescope's format),
// DIR/logs/NN_name.log (the console output of each module's run) and DIR/images/ (images
// the tests compared). scripts/grade.sh builds the graders and calls this; ctest calls it
// directly.
#include <cstdlib>
#include <iostream>
#include <map>
#include <string>

#include "grade.h"

using namespace raylab::grade;
using raylab::ModuleInfo;

namespace {

constexpr const char* kUsage = R"(Usage: raylab-grade --tests FILE --out DIR [options]
  --tests FILE          the raylab-grading-tests binary
  --out DIR             where summary.txt, junit.xml, results.json, logs/ and images/ go
  --reference           grade the reference solutions instead of the student's code
  --timeout SECONDS     CPU time limit per module (default 10; 6 times that on the clock)
  --points N            points per module (default 10)
  --module-error ID=FILE  module ID failed to build: score 0, FILE holds the message
  --source ID=FILE      the hand-in's file graded for module ID (for the reports)
  --note ID=TEXT        a note for module ID's report (ID "-": the whole hand-in's)
  --workers DIR         DIR/NN_name is the worker (student code) graded for module NN_name
                        (default: the worker of this build's exercises/)
  --only ID             grade module ID only (the viewer's "Run tests" does this)
  --private DIR         the instructor's private cases (hidden tests), kept out of releases
  --label TEXT          what is graded, for the reports (default: the implementation)
  --expect MODE         exit 1 unless: full (every module full marks), not-started (every
                        module a stub), faults (modules in RAYLAB_GRADE_FAULT score 0 by
                        the right cause, the others full marks)
)";

// ---- Expectations (CI) ----------------------------------------------------------------

bool check_expectation(const Options& o, const std::vector<ModuleResult>& modules) {
    std::map<std::string, std::string> faults;
    if (const char* f = std::getenv("RAYLAB_GRADE_FAULT")) {
        for (const std::string& item : split(f, ',')) {
            const size_t eq = item.find('=');
            if (eq != std::string::npos) faults[item.substr(0, eq)] = item.substr(eq + 1);
        }
    }
    bool ok = true;
    for (const ModuleResult& m : modules) {
        std::string want;
        bool good = true;
        if (o.expect == "full") {
            want = "full marks";
            good = m.status == "passed" && m.score == m.max_score;
        } else if (o.expect == "not-started") {
            want = "not started, 0 points";
            good = m.status == "not started" && m.score == 0.0;
        } else if (o.expect == "faults") {
            const auto it = faults.find(m.info->id);
            if (it == faults.end()) {
                want = "full marks";
                good = m.status == "passed" && m.score == m.max_score;
            } else {
                const std::string& kind = it->second;
                want = "0 points (" + kind + ")";
                good = m.score == 0.0;
                if (kind == "segv") good = good && m.status.rfind("crashed", 0) == 0;
                if (kind == "hang") good = good && m.status == "time limit";
                if (kind == "throw")
                    good = good && m.first_failure.find("exception") != std::string::npos;
            }
        } else {
            die("unknown --expect mode '" + o.expect + "'");
        }
        if (!good) {
            std::cout << "EXPECTATION FAILED: " << m.info->id << " should score " << want
                      << ", got " << fixed(m.score) << " [" << m.status << "] "
                      << m.first_failure << "\n";
            ok = false;
        }
    }
    std::cout << (ok ? "expectation met: " : "expectation NOT met: ") << o.expect << "\n";
    return ok;
}

Options parse(int argc, char** argv) {
    Options o;
    for (int k = 1; k < argc; ++k) {
        const std::string a = argv[k];
        const auto value = [&]() -> std::string {
            if (k + 1 >= argc) die(a + " needs a value\n" + kUsage);
            return argv[++k];
        };
        if (a == "--tests") {
            o.tests = value();
        } else if (a == "--out") {
            o.out = value();
        } else if (a == "--reference") {
            o.reference = true;
        } else if (a == "--timeout") {
            o.timeout = std::atof(value().c_str());
        } else if (a == "--points") {
            o.points = std::atof(value().c_str());
        } else if (a == "--source") {
            const std::string v = value();
            const size_t eq = v.find('=');
            if (eq == std::string::npos) die("--source needs ID=FILE");
            o.sources[v.substr(0, eq)] = v.substr(eq + 1);
        } else if (a == "--note") {
            const std::string v = value();
            const size_t eq = v.find('=');
            if (eq == std::string::npos) die("--note needs ID=TEXT");
            o.notes[v.substr(0, eq)].push_back(v.substr(eq + 1));
        } else if (a == "--workers") {
            o.workers = value();
        } else if (a == "--only") {
            o.only = value();
        } else if (a == "--private") {
            o.private_dir = value();
        } else if (a == "--label") {
            o.label = value();
        } else if (a == "--expect") {
            o.expect = value();
        } else if (a == "--module-error") {
            const std::string v = value();
            const size_t eq = v.find('=');
            if (eq == std::string::npos) die("--module-error needs ID=FILE");
            o.module_errors[v.substr(0, eq)] = v.substr(eq + 1);
        } else if (a == "--help" || a == "-h") {
            std::cout << kUsage;
            std::exit(0);
        } else {
            die("unknown option '" + a + "'\n" + kUsage);
        }
    }
    if (o.tests.empty() || o.out.empty())
        die(std::string("--tests and --out are needed\n") + kUsage);
    if (!(o.timeout > 0.0) || !(o.points > 0.0))
        die("--timeout and --points must be positive");
    if (o.label.empty()) o.label = o.reference ? "reference solutions" : "student code";
    return o;
}

}  // namespace

int main(int argc, char** argv) {
    const Options o = parse(argc, argv);
    for (const std::string& dir : {o.out + "/logs", o.out + "/images"})
        make_dirs(dir);
    const std::map<std::string, std::vector<std::string>> names = list_cases(o);
    std::vector<ModuleResult> modules;
    for (const ModuleInfo& info : raylab::module_infos()) {
        if (!o.only.empty() && o.only != info.id) continue;
        const auto it = names.find(info.id);
        if (it == names.end()) die(std::string("the graders have no suite ") + info.id);
        modules.push_back(grade_module(o, info, it->second));
        ModuleResult& m = modules.back();
        m.score = rounded(m.score);
        m.reason = reason(m, o.timeout);
        if (const auto n = o.notes.find(info.id); n != o.notes.end()) m.notes = n->second;
    }
    std::string summary = table(modules, o.label);
    if (const auto n = o.notes.find("-"); n != o.notes.end()) {
        summary += "\nnotes on the hand-in:\n";
        for (const std::string& line : n->second)
            summary += indented(line);
    }
    summary = clean_text(summary);
    std::cout << summary << std::flush;
    std::string details;
    for (const ModuleResult& m : modules)
        details += "\n" + clean_text(module_output(m));
    write_file(o.out + "/summary.txt", summary + details);
    write_file(o.out + "/junit.xml", junit(modules));
    write_file(o.out + "/cases.json", cases_json(modules));
    const auto hand_in = o.notes.find("-");
    write_file(o.out + "/results.json",
               results_json(modules, summary,
                            hand_in == o.notes.end() ? std::vector<std::string>{}
                                                     : hand_in->second));
    std::cout << "\nDetails: " << o.out << "/summary.txt; JUnit: " << o.out
              << "/junit.xml; Gradescope: " << o.out << "/results.json\n";
    if (!o.expect.empty()) return check_expectation(o, modules) ? 0 : 1;
    return 0;
}
