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
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "raylab/modules.h"

namespace {

using raylab::ModuleInfo;

constexpr const char* kUsage = R"(Usage: raylab-grade --tests FILE --out DIR [options]
  --tests FILE          the raylab-grading-tests binary
  --out DIR             where summary.txt, junit.xml, results.json, logs/ and images/ go
  --reference           grade the reference solutions instead of the student's code
  --timeout SECONDS     time limit per module (default 10)
  --points N            points per module (default 10)
  --module-error ID=FILE  module ID failed to build: score 0, FILE holds the message
  --label TEXT          what is graded, for the reports (default: the implementation)
  --expect MODE         exit 1 unless: full (every module full marks), not-started (every
                        module a stub), faults (modules in RAYLAB_GRADE_FAULT score 0 by
                        the right cause, the others full marks)
)";

struct Options {
    std::string tests, out, label, expect;
    bool reference = false;
    double timeout = 10.0;
    double points = 10.0;
    std::map<std::string, std::string> module_errors;  // ID -> file with the message
};

struct CaseResult {
    std::string name;
    std::string status = "not run";  // pass, fail, stub, crash, not run
    std::string message;
};

struct ModuleResult {
    const ModuleInfo* info = nullptr;
    std::vector<CaseResult> cases;
    std::string status;  // passed, failed, not started, crashed (SIG...), time limit, ...
    std::string first_failure;
    std::string build_error;
    int passed = 0;
    double score = 0.0, max_score = 0.0;
    double seconds = 0.0;
};

[[noreturn]] void die(const std::string& message) {
    std::cerr << "raylab-grade: " << message << "\n";
    std::exit(2);
}

std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    std::string item;
    std::istringstream in(s);
    while (std::getline(in, item, sep))
        out.push_back(item);
    return out;
}

std::string unescape(const std::string& s) {
    std::string out;
    for (size_t k = 0; k < s.size(); ++k) {
        if (s[k] == '\\' && k + 1 < s.size()) {
            out += s[k + 1] == 'n' ? '\n' : s[k + 1];
            ++k;
        } else {
            out += s[k];
        }
    }
    return out;
}

std::string first_line(const std::string& s) {
    return s.substr(0, s.find('\n'));
}

std::string shorten(const std::string& s, size_t n) {
    return s.size() <= n ? s : s.substr(0, n - 3) + "...";
}

// ---- Running one process with a time limit --------------------------------------------

struct RunOutcome {
    bool timed_out = false;
    int exit_code = -1;  // when it exited
    int signal = 0;      // when a signal ended it
    double seconds = 0.0;
};

RunOutcome run(const std::vector<std::string>& args,
               const std::vector<std::pair<std::string, std::string>>& env,
               const std::string& output, double timeout) {
    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = fork();
    if (pid < 0) die("fork failed");
    if (pid == 0) {
        // Child: own process group (so that a time limit ends everything it started),
        // output to the log, then the test binary
        setpgid(0, 0);
        const int fd = open(output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd >= 0) {
            dup2(fd, 1);
            dup2(fd, 2);
            close(fd);
        }
        for (const auto& [name, value] : env)
            setenv(name.c_str(), value.c_str(), 1);
        std::vector<char*> argv;
        for (const std::string& a : args)
            argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        execv(argv[0], argv.data());
        std::perror("raylab-grade: cannot start the graders");
        _exit(127);
    }
    setpgid(pid, pid);
    RunOutcome outcome;
    int status = 0;
    for (;;) {
        const pid_t done = waitpid(pid, &status, WNOHANG);
        if (done == pid) break;
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                .count();
        if (elapsed > timeout) {
            kill(-pid, SIGKILL);
            kill(pid, SIGKILL);
            waitpid(pid, &status, 0);
            outcome.timed_out = true;
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    outcome.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!outcome.timed_out) {
        if (WIFEXITED(status)) outcome.exit_code = WEXITSTATUS(status);
        if (WIFSIGNALED(status)) outcome.signal = WTERMSIG(status);
    }
    return outcome;
}

std::string signal_short(int sig) {
    switch (sig) {
        case SIGSEGV:
            return "SIGSEGV";
        case SIGABRT:
            return "SIGABRT";
        case SIGFPE:
            return "SIGFPE";
        case SIGILL:
            return "SIGILL";
        case SIGBUS:
            return "SIGBUS";
        default:
            return "signal " + std::to_string(sig);
    }
}

std::string signal_name(int sig) {
    switch (sig) {
        case SIGSEGV:
            return "SIGSEGV, segmentation fault";
        case SIGABRT:
            return "SIGABRT, abort";
        case SIGFPE:
            return "SIGFPE, arithmetic error";
        case SIGILL:
            return "SIGILL, illegal instruction";
        case SIGBUS:
            return "SIGBUS, bus error";
        default:
            return "signal " + std::to_string(sig);
    }
}

// ---- Grading
// ---------------------------------------------------------------------------

std::vector<std::pair<std::string, std::string>> child_env(const Options& o,
                                                           const std::string& log) {
    return {{"RAYLAB_GRADE_LOG", log},
            {"RAYLAB_GRADE_IMPL", o.reference ? "reference" : "student"},
            {"RAYLAB_GRADE_IMAGES", o.out + "/images"}};
}

// Test case names per suite, from --list-test-cases
std::map<std::string, std::vector<std::string>> list_cases(const Options& o) {
    const std::string log = o.out + "/logs/list.tsv";
    const RunOutcome r = run({o.tests, "--list-test-cases"}, child_env(o, log),
                             o.out + "/logs/list.log", 60.0);
    if (r.exit_code != 0)
        die("listing the test cases failed; see " + o.out + "/logs/list.log:\n" +
            read_file(o.out + "/logs/list.log"));
    std::map<std::string, std::vector<std::string>> cases;
    std::istringstream in(read_file(log));
    std::string line;
    while (std::getline(in, line)) {
        const std::vector<std::string> f = split(line, '\t');
        if (f.size() >= 3 && f[0] == "list") cases[f[1]].push_back(f[2]);
    }
    return cases;
}

ModuleResult grade_module(const Options& o, const ModuleInfo& info,
                          const std::vector<std::string>& names) {
    ModuleResult m;
    m.info = &info;
    m.max_score = o.points;
    for (const std::string& name : names)
        m.cases.push_back({name, "not run", ""});
    const auto find = [&](const std::string& name) -> CaseResult* {
        for (CaseResult& c : m.cases)
            if (c.name == name) return &c;
        return nullptr;
    };

    // A module that did not build: every case fails with the compiler's message
    const auto error = o.module_errors.find(info.id);
    if (error != o.module_errors.end()) {
        m.build_error = read_file(error->second);
        m.status = "build error";
        m.first_failure = first_line(m.build_error);
        for (CaseResult& c : m.cases) {
            c.status = "fail";
            c.message = "the module did not build: " + m.first_failure;
        }
        return m;
    }

    const std::string id = info.id;
    const std::string log = o.out + "/logs/" + id + ".tsv";
    std::remove(log.c_str());
    const RunOutcome r =
        run({o.tests, "--test-suite=" + id, "--no-colors"}, child_env(o, log),
            o.out + "/logs/" + id + ".log", o.timeout);
    m.seconds = r.seconds;
    std::string crashed_in;
    std::istringstream in(read_file(log));
    std::string line;
    while (std::getline(in, line)) {
        const std::vector<std::string> f = split(line, '\t');
        if (f.size() >= 4 && f[0] == "case") {
            if (CaseResult* c = find(f[2])) {
                c->status = f[3];
                c->message = f.size() >= 5 ? unescape(f[4]) : "";
            }
        } else if (f.size() >= 3 && f[0] == "crash") {
            crashed_in = f[2];
            if (CaseResult* c = find(f[2])) {
                c->status = "crash";
                c->message = "crashed: " + (f.size() >= 4 ? f[3] : std::string());
            }
        }
    }

    int stubs = 0, running = 0;
    std::string first_running;
    for (CaseResult& c : m.cases) {
        if (c.status == "pass") ++m.passed;
        if (c.status == "stub") ++stubs;
        if (c.status == "not run" && first_running.empty()) first_running = c.name;
        if (c.status == "not run") ++running;
    }
    const auto first_failed = [&]() -> std::string {
        for (const CaseResult& c : m.cases)
            if (c.status == "fail" || c.status == "stub" || c.status == "crash")
                return "\"" + c.name + "\": " + first_line(c.message);
        return "";
    };
    if (r.timed_out) {
        m.status = "time limit";
        std::ostringstream s;
        s << "no result after " << o.timeout << " s (an endless loop?)"
          << (first_running.empty() ? "" : " in \"" + first_running + "\"");
        m.first_failure = s.str();
        for (CaseResult& c : m.cases)
            if (c.status == "not run") c.message = "not run: the time limit was reached";
    } else if (r.signal != 0 || !crashed_in.empty()) {
        m.status = "crashed (" + signal_short(r.signal) + ")";
        m.first_failure =
            "crashed (" + signal_name(r.signal) + ")" +
            (crashed_in.empty() ? std::string() : " in \"" + crashed_in + "\"");
        for (CaseResult& c : m.cases)
            if (c.status == "not run") c.message = "not run: the module crashed earlier";
    } else if (running > 0) {
        m.status = "error";
        m.first_failure = "the graders stopped early (exit code " +
                          std::to_string(r.exit_code) + "); see logs/" + id + ".log";
    } else if (m.passed == int(m.cases.size())) {
        m.status = "passed";
    } else if (m.passed == 0 && stubs == int(m.cases.size())) {
        m.status = "not started";
        m.first_failure = "not started: every function still calls RAYLAB_STUB";
    } else {
        m.status = "failed";
        m.first_failure = first_failed();
    }
    const bool counts = m.status == "passed" || m.status == "failed";
    m.score =
        counts && !m.cases.empty() ? o.points * m.passed / double(m.cases.size()) : 0.0;
    return m;
}

// ---- Reports
// ---------------------------------------------------------------------------

std::string fixed(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", x);
    return buf;
}

std::string pad(const std::string& s, size_t n) {
    return s.size() >= n ? s : s + std::string(n - s.size(), ' ');
}

std::string table(const std::vector<ModuleResult>& modules, const std::string& label) {
    std::ostringstream s;
    s << "raylab grade: " << label << "\n\n"
      << pad("module", 16) << pad("tests", 8) << pad("points", 14) << "first failure\n";
    double total = 0, max_total = 0;
    int passed = 0, cases = 0;
    for (const ModuleResult& m : modules) {
        const std::string tests =
            std::to_string(m.passed) + "/" + std::to_string(m.cases.size());
        s << pad(m.info->id, 16) << pad(tests, 8)
          << pad(fixed(m.score) + " / " + fixed(m.max_score), 14)
          << (m.status == "passed" ? "-" : shorten(m.first_failure, 110)) << "\n";
        total += m.score;
        max_total += m.max_score;
        passed += m.passed;
        cases += int(m.cases.size());
    }
    s << pad("total", 16) << pad(std::to_string(passed) + "/" + std::to_string(cases), 8)
      << fixed(total) << " / " << fixed(max_total) << "\n";
    return s.str();
}

// The text a student reads for one module: status, then every failed case with its
// message
std::string module_output(const ModuleResult& m, size_t max_cases = 12) {
    std::ostringstream s;
    s << m.info->id << " (" << m.info->title << "): " << m.passed << "/" << m.cases.size()
      << " tests passed, " << fixed(m.score) << " of " << fixed(m.max_score)
      << " points [" << m.status << "]\n";
    if (!m.build_error.empty()) {
        s << "\n" << shorten(m.build_error, 4000) << "\n";
        return s.str();
    }
    if (m.status == "time limit" || m.status.rfind("crashed", 0) == 0)
        s << m.first_failure << "\n";
    if (m.status == "not started") {
        s << "Every test stopped at a function that still calls RAYLAB_STUB.\n";
        return s.str();
    }
    size_t shown = 0;
    for (const CaseResult& c : m.cases) {
        if (c.status == "pass" || c.status == "not run") continue;
        if (shown++ == max_cases) {
            s << "(more failures in logs/" << m.info->id << ".log)\n";
            break;
        }
        s << "\nFAILED: " << c.name << "\n  " << shorten(c.message, 1500) << "\n";
    }
    return s.str();
}

std::string xml_escape(const std::string& s) {
    std::string out;
    for (const char c : s) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            default:
                // Control characters other than tab and newline are not allowed in XML
                if (static_cast<unsigned char>(c) >= 0x20 || c == '\n' || c == '\t')
                    out += c;
        }
    }
    return out;
}

std::string json_escape(const std::string& s) {
    std::string out;
    for (const char c : s) {
        switch (c) {
            case '"':
                out += "\\\"";
                break;
            case '\\':
                out += "\\\\";
                break;
            case '\n':
                out += "\\n";
                break;
            case '\t':
                out += "\\t";
                break;
            default:
                if (static_cast<unsigned char>(c) < 0x20) {
                    char buf[8];
                    std::snprintf(buf, sizeof buf, "\\u%04x", c);
                    out += buf;
                } else {
                    out += c;
                }
        }
    }
    return out;
}

std::string junit(const std::vector<ModuleResult>& modules) {
    std::ostringstream s;
    int tests = 0, failures = 0, errors = 0;
    std::ostringstream suites;
    for (const ModuleResult& m : modules) {
        int f = 0, e = 0;
        std::ostringstream cases;
        for (const CaseResult& c : m.cases) {
            cases << "    <testcase classname=\"" << m.info->id << "\" name=\""
                  << xml_escape(c.name) << "\"";
            if (c.status == "pass") {
                cases << "/>\n";
                continue;
            }
            const bool error = c.status == "crash" || c.status == "not run";
            (error ? e : f)++;
            const char* tag = error ? "error" : "failure";
            const std::string message = c.message.empty() ? m.first_failure : c.message;
            cases << ">\n      <" << tag << " message=\""
                  << xml_escape(first_line(message)) << "\">" << xml_escape(message)
                  << "</" << tag << ">\n    </testcase>\n";
        }
        suites << "  <testsuite name=\"" << m.info->id << "\" tests=\"" << m.cases.size()
               << "\" failures=\"" << f << "\" errors=\"" << e << "\" time=\""
               << m.seconds << "\">\n"
               << cases.str() << "  </testsuite>\n";
        tests += int(m.cases.size());
        failures += f;
        errors += e;
    }
    s << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"raylab-grade\" "
         "tests=\""
      << tests << "\" failures=\"" << failures << "\" errors=\"" << errors << "\">\n"
      << suites.str() << "</testsuites>\n";
    return s.str();
}

std::string results_json(const std::vector<ModuleResult>& modules,
                         const std::string& summary) {
    double total = 0;
    for (const ModuleResult& m : modules)
        total += m.score;
    std::ostringstream s;
    s << "{\n  \"score\": " << fixed(total) << ",\n  \"output\": \""
      << json_escape(summary) << "\",\n  \"tests\": [\n";
    for (size_t k = 0; k < modules.size(); ++k) {
        const ModuleResult& m = modules[k];
        s << "    {\n      \"name\": \"" << m.info->id << ": "
          << json_escape(m.info->title) << "\",\n      \"score\": " << fixed(m.score)
          << ",\n      \"max_score\": " << fixed(m.max_score) << ",\n      \"status\": \""
          << (m.status == "passed" ? "passed" : "failed") << "\",\n      \"output\": \""
          << json_escape(module_output(m)) << "\"\n    }"
          << (k + 1 < modules.size() ? "," : "") << "\n";
    }
    s << "  ]\n}\n";
    return s.str();
}

// mkdir -p
void make_dirs(const std::string& path) {
    size_t at = 0;
    do {
        at = path.find('/', at + 1);
        const std::string prefix = path.substr(0, at);
        if (mkdir(prefix.c_str(), 0755) != 0 && errno != EEXIST)
            die("cannot create " + prefix + ": " + std::strerror(errno));
    } while (at != std::string::npos);
}

void write_file(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    if (!out) die("cannot write " + path);
}

// ---- Expectations (CI)
// -------------------------------------------------------------------

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
        const auto it = names.find(info.id);
        if (it == names.end()) die(std::string("the graders have no suite ") + info.id);
        modules.push_back(grade_module(o, info, it->second));
    }
    const std::string summary = table(modules, o.label);
    std::cout << summary << std::flush;
    std::string details;
    for (const ModuleResult& m : modules)
        details += "\n" + module_output(m);
    write_file(o.out + "/summary.txt", summary + details);
    write_file(o.out + "/junit.xml", junit(modules));
    write_file(o.out + "/results.json", results_json(modules, summary));
    std::cout << "\nDetails: " << o.out << "/summary.txt; JUnit: " << o.out
              << "/junit.xml; Gradescope: " << o.out << "/results.json\n";
    if (!o.expect.empty()) return check_expectation(o, modules) ? 0 : 1;
    return 0;
}
