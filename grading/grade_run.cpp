// raylab-grade: running the graders, one process per module with a time limit.
#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <thread>

#include "grade.h"

namespace raylab::grade {

namespace {

// A module's clock time may reach this many times its CPU time limit (--timeout)
constexpr double kWallFactor = 6.0;

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
    bool cpu_limit = false;  // timed out by its CPU time, not the clock
    int exit_code = -1;      // when it exited
    int signal = 0;          // when a signal ended it
    double seconds = 0.0, cpu_seconds = 0.0;
};

// CPU time (user + system, its waited-for children's included) of root and every
// process below it, from /proc; the grading worker is one of them (under bubblewrap too)
double tree_cpu_seconds(pid_t root) {
    struct Proc {
        pid_t pid, ppid;
        double ticks;
    };
    std::vector<Proc> procs;
    if (DIR* dir = opendir("/proc")) {
        while (const dirent* e = readdir(dir)) {
            char* end = nullptr;
            const long pid = std::strtol(e->d_name, &end, 10);
            if (pid <= 0 || *end != '\0') continue;
            std::ifstream in("/proc/" + std::string(e->d_name) + "/stat");
            std::string stat;
            std::getline(in, stat);
            const size_t close = stat.rfind(')');
            if (close == std::string::npos) continue;
            std::istringstream fields(stat.substr(close + 2));
            std::string f[15];  // fields 3..17: state ppid ... utime stime cutime cstime
            for (std::string& x : f)
                fields >> x;
            procs.push_back({pid_t(pid), pid_t(std::atol(f[1].c_str())),
                             std::atof(f[11].c_str()) + std::atof(f[12].c_str()) +
                                 std::atof(f[13].c_str()) + std::atof(f[14].c_str())});
        }
        closedir(dir);
    }
    double ticks = 0.0;
    std::vector<pid_t> todo = {root};
    while (!todo.empty()) {
        const pid_t p = todo.back();
        todo.pop_back();
        for (const Proc& q : procs) {
            if (q.pid == p) ticks += q.ticks;
            if (q.ppid == p && q.pid != p) todo.push_back(q.pid);
        }
    }
    return ticks / double(sysconf(_SC_CLK_TCK));
}

// Runs args with output to the file output. The time limit counts CPU time (the graders'
// and the worker's), which a busy machine does not stretch: a whole render is tens of
// thousands of calls across the worker's socket, and at a load of 10-17 on 2 cores the
// reference's own 03_plane and 08_shadows took more than 10 s, and more than 30 s, of
// clock time. Code that sleeps uses no CPU: wall_limit bounds the clock time (and each
// call has its own clock limit in worker_client.cpp).
RunOutcome run(const std::vector<std::string>& args,
               const std::vector<std::pair<std::string, std::string>>& env,
               const std::string& output, double timeout, double wall_limit) {
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
    for (int tick = 0;; ++tick) {
        const pid_t done = waitpid(pid, &status, WNOHANG);
        if (done == pid) break;
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                .count();
        if (tick % 20 == 0 && elapsed > timeout)
            outcome.cpu_seconds = tree_cpu_seconds(pid);
        outcome.cpu_limit = outcome.cpu_seconds > timeout;
        if (outcome.cpu_limit || elapsed > wall_limit) {
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

std::vector<std::pair<std::string, std::string>> child_env(const Options& o,
                                                           const std::string& log,
                                                           const std::string& id = "") {
    std::vector<std::pair<std::string, std::string>> env = {
        {"RAYLAB_GRADE_LOG", log},
        {"RAYLAB_GRADE_IMPL", o.reference ? "reference" : "student"},
        {"RAYLAB_GRADE_IMAGES", o.out + "/images"},
        // The trusted side reports a hang itself before the driver's limit strikes
        {"RAYLAB_WORKER_TIMEOUT", std::to_string(o.timeout * 0.8)}};
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
                             o.out + "/logs/list.log", 60.0, 60.0);
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
            child_env(o, log, id), o.out + "/logs/" + id + ".log", o.timeout,
            o.timeout * kWallFactor);
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
        if (r.cpu_limit)
            s << "more than " << o.timeout << " s of CPU time (an endless loop?)";
        else
            s << "no result after " << o.timeout * kWallFactor
              << " s (waiting or sleeping, with " << r.cpu_seconds << " s of CPU time)";
        s << (first_running.empty() ? "" : " in \"" + first_running + "\"");
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
