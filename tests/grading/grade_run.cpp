// raylab-grade: running the graders, one process per module with a time limit.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <thread>

#include "grade.h"

namespace raylab::grade {

namespace {

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

}  // namespace

// ---- Grading --------------------------------------------------------------------------

// The wall-clock backstop for a whole module. Hangs are caught per call (--timeout, by
// the trusted side) and CPU burn by the worker's RLIMIT_CPU; the module's wall time also
// counts every socket round trip of the whole-render checks, which a loaded machine
// (a class graded with -j N) stretches many times over: a correct module took 6-9 s of
// wall time with 4 gradings on 2 cores, and failed a 10 s module limit.
static double module_wall_limit(const Options& o) {
    return std::max(6.0 * o.timeout, 60.0);
}

std::vector<std::pair<std::string, std::string>> child_env(const Options& o,
                                                           const std::string& log,
                                                           const std::string& id = "") {
    std::vector<std::pair<std::string, std::string>> env = {
        {"RAYLAB_GRADE_LOG", log},
        {"RAYLAB_GRADE_IMPL", o.reference ? "reference" : "student"},
        {"RAYLAB_GRADE_IMAGES", o.out + "/images"},
        // The per-call limit: the trusted side reports a hang in student code itself,
        // long before the module's wall-clock backstop (module_wall_limit) strikes
        {"RAYLAB_WORKER_TIMEOUT", std::to_string(o.timeout)}};
    if (!id.empty())
        env.push_back({"RAYLAB_WORKER_LOG", o.out + "/logs/" + id + ".worker.log"});
    if (!o.workers.empty() && !id.empty())
        env.push_back({"RAYLAB_WORKER", o.workers + "/" + id});
    if (!o.private_dir.empty()) env.push_back({"RAYLAB_GRADE_PRIVATE", o.private_dir});
    return env;
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
        // The private cases count only when the instructor gives their secret
        const bool hidden = f.size() >= 3 && f[2].rfind(kPrivate, 0) == 0;
        if (f.size() >= 3 && f[0] == "list" && (!hidden || !o.private_dir.empty()))
            cases[f[1]].push_back(f[2]);
    }
    return cases;
}

ModuleResult grade_module(const Options& o, const ModuleInfo& info,
                          const std::vector<std::string>& names) {
    ModuleResult m;
    m.info = &info;
    m.max_score = o.points;
    if (const auto src = o.sources.find(info.id); src != o.sources.end())
        m.source = src->second;
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
        run({o.tests, "--test-suite=" + id, "--no-colors",
             o.private_dir.empty() ? "--test-case-exclude=" + std::string(kPrivate) + "*"
                                   : "--test-case-exclude="},
            child_env(o, log, id), o.out + "/logs/" + id + ".log", module_wall_limit(o));
    m.seconds = r.seconds;
    std::string crashed_in, hung_in, lost_why;
    std::istringstream in(read_file(log));
    std::string line;
    while (std::getline(in, line)) {
        const std::vector<std::string> f = split(line, '\t');
        if (f.size() >= 4 && f[0] == "case") {
            if (CaseResult* c = find(f[2])) {
                c->status = f[3];
                c->message = f.size() >= 5 ? unescape(f[4]) : "";
            }
        } else if (f.size() >= 3 && (f[0] == "crash" || f[0] == "timeout")) {
            // The worker crashed or hung in this case (worker_client.cpp)
            (f[0] == "crash" ? crashed_in : hung_in) = f[2];
            lost_why = f.size() >= 4 ? unescape(f[3]) : f[0];
            if (CaseResult* c = find(f[2])) {
                c->status = "crash";
                c->message = lost_why;
            }
        } else if (f.size() >= 2 && f[0] == "sandbox") {
            m.sandbox = f[1];
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
    if (r.timed_out || !hung_in.empty()) {
        m.status = "time limit";
        std::ostringstream s;
        s << "no result after " << module_wall_limit(o) << " s (an endless loop?)"
          << (first_running.empty() ? "" : " in \"" + first_running + "\"");
        m.first_failure = hung_in.empty() ? s.str() : "\"" + hung_in + "\": " + lost_why;
        for (CaseResult& c : m.cases)
            if (c.status == "not run") c.message = "not run: the time limit was reached";
    } else if (!crashed_in.empty()) {
        const size_t open = lost_why.find("(SIG");
        m.status =
            open == std::string::npos
                ? "crashed"
                : "crashed (" +
                      lost_why.substr(open + 1, lost_why.find(',', open) - open - 1) +
                      ")";
        m.first_failure = "\"" + crashed_in + "\": " + lost_why;
        for (CaseResult& c : m.cases)
            if (c.status == "not run") c.message = "not run: the module crashed earlier";
    } else if (r.signal != 0) {
        // The trusted grader itself crashed: a defect of the graders, not the student's
        m.status = "error";
        m.first_failure = "the graders crashed (" + signal_name(r.signal) +
                          "); see logs/" + id + ".log";
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

}  // namespace raylab::grade
