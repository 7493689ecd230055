// Grading in child processes (viewer/grader.h).
#include "grader.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>

extern char** environ;

namespace raylab::viewer {

std::optional<DoctestSummary> parse_doctest_summary(std::string_view output) {
    // The last such line wins (doctest prints one per run)
    static const std::regex line(
        R"(test cases:\s*(\d+)\s*\|\s*(\d+)\s*passed\s*\|\s*(\d+)\s*failed(?:\s*\|\s*(\d+)\s*skipped)?)");
    std::optional<DoctestSummary> summary;
    const std::string text(output);
    for (auto it = std::sregex_iterator(text.begin(), text.end(), line);
         it != std::sregex_iterator(); ++it) {
        const std::smatch& m = *it;
        DoctestSummary s;
        s.cases = std::stoi(m[1]);
        s.passed = std::stoi(m[2]);
        s.failed = std::stoi(m[3]);
        s.skipped = m[4].matched ? std::stoi(m[4]) : 0;
        summary = s;
    }
    return summary;
}

namespace {

// Reads the child's output until it closes the pipe or the deadline passes
bool read_until_eof(int fd, std::string& output, double timeout_seconds,
                    const std::atomic<bool>* cancel) {
    constexpr size_t kMaxOutput = size_t{1} << 20;
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_seconds);
    char buffer[4096];
    for (;;) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
            deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0 || (cancel && cancel->load())) return false;
        pollfd p{fd, POLLIN, 0};
        const int slice = static_cast<int>(std::min<long long>(left.count(), 100));
        const int ready = poll(&p, 1, slice);
        if (ready == 0 || (ready < 0 && errno == EINTR)) continue;
        if (ready < 0) return true;
        const ssize_t n = read(fd, buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return true;
        if (output.size() < kMaxOutput) output.append(buffer, static_cast<size_t>(n));
    }
}

}  // namespace

ChildResult run_child(const std::vector<std::string>& argv,
                      const std::vector<std::string>& env, double timeout_seconds,
                      const std::atomic<bool>* cancel) {
    ChildResult result;
    // Everything the child needs is built before fork: after it, only exec
    std::vector<char*> args;
    for (const std::string& a : argv)
        args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    std::vector<char*> envp;
    for (char** e = environ; *e; ++e) {
        // A variable set in env replaces the inherited one (getenv takes the first)
        const std::string_view inherited(*e);
        const bool replaced =
            std::any_of(env.begin(), env.end(), [&](const std::string& x) {
                const size_t eq = x.find('=');
                return eq != std::string::npos &&
                       inherited.substr(0, eq + 1) == x.substr(0, eq + 1);
            });
        if (!replaced) envp.push_back(*e);
    }
    for (const std::string& e : env)
        envp.push_back(const_cast<char*>(e.c_str()));
    envp.push_back(nullptr);

    int fds[2];
    if (argv.empty() || pipe2(fds, O_CLOEXEC) != 0) {
        result.output = "cannot create a pipe for the child process";
        return result;
    }
    const pid_t pid = fork();
    if (pid == 0) {
        setpgid(0, 0);
        const int null = open("/dev/null", O_RDONLY);
        dup2(null, 0);
        dup2(fds[1], 1);
        dup2(fds[1], 2);
        execve(args[0], args.data(), envp.data());
        const char message[] = "cannot execute the grading binary\n";
        (void)!write(2, message, sizeof message - 1);
        _exit(127);
    }
    close(fds[1]);
    if (pid < 0) {
        close(fds[0]);
        result.output = std::string("fork failed: ") + std::strerror(errno);
        return result;
    }
    result.started = true;
    if (!read_until_eof(fds[0], result.output, timeout_seconds, cancel)) {
        result.timed_out = true;
        kill(-pid, SIGKILL);
        kill(pid, SIGKILL);
    }
    close(fds[0]);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
    return result;
}

ModuleGrade grade_module(const std::string& binary, const std::string& id,
                         double timeout_seconds, const std::atomic<bool>* cancel) {
    ModuleGrade grade;
    const ChildResult child =
        run_child({binary, "--test-suite=" + id}, {}, timeout_seconds, cancel);
    grade.output = child.output;
    const std::optional<DoctestSummary> summary = parse_doctest_summary(child.output);
    if (summary) grade.counts = *summary;
    if (!child.started || child.exit_code == 127) {
        grade.status = ModuleGrade::Status::error;
        grade.summary = "could not start the graders";
    } else if (child.timed_out) {
        grade.status = ModuleGrade::Status::crashed;
        grade.summary = "timed out after " + std::to_string(int(timeout_seconds)) + " s";
    } else if (child.signal != 0) {
        grade.status = ModuleGrade::Status::crashed;
        grade.summary = std::string("crashed (") + strsignal(child.signal) + ")";
    } else if (!summary) {
        grade.status = ModuleGrade::Status::error;
        grade.summary =
            "no doctest summary (exit code " + std::to_string(child.exit_code) + ")";
    } else if (summary->cases == 0) {  // "skipped" counts the other suites' cases
        grade.status = ModuleGrade::Status::no_tests;
        grade.summary = "no tests";
    } else {
        const bool all = summary->failed == 0 && child.exit_code == 0;
        grade.status = all ? ModuleGrade::Status::passed : ModuleGrade::Status::failed;
        grade.summary = std::to_string(summary->passed) + "/" +
                        std::to_string(summary->cases) + " passed";
    }
    return grade;
}

namespace {

// A fresh temporary folder, or "" when none can be made
std::string make_temp_dir() {
    std::string dir = (std::filesystem::temp_directory_path() / "raylab-viewer-XXXXXX");
    return mkdtemp(dir.data()) ? dir : std::string();
}

// The runner's cases.json in dir (an array of modules), or null
nlohmann::json read_cases(const std::string& dir) {
    try {
        std::ifstream in(dir + "/cases.json");
        nlohmann::json modules = nlohmann::json::parse(in);
        if (modules.is_array()) return modules;
    } catch (const std::exception&) {
    }
    return nullptr;
}

// One module of the runner's cases.json, in the words the runner used
ModuleGrade grade_from_cases(const nlohmann::json& m) {
    ModuleGrade grade;
    for (const nlohmann::json& c : m.value("cases", nlohmann::json::array()))
        grade.cases.push_back(
            {c.value("name", ""), c.value("status", ""), c.value("message", "")});
    const std::string status = m.value("status", "error");
    grade.counts.cases = int(grade.cases.size());
    grade.counts.passed = m.value("passed", 0);
    grade.counts.failed = grade.counts.cases - grade.counts.passed;
    const std::string counts = std::to_string(grade.counts.passed) + "/" +
                               std::to_string(grade.counts.cases) + " passed";
    if (status == "passed") {
        grade.status = ModuleGrade::Status::passed;
        grade.summary = counts;
    } else if (status == "failed") {
        grade.status = ModuleGrade::Status::failed;
        grade.summary = counts;
    } else if (status == "not started") {
        grade.status = ModuleGrade::Status::not_started;
        grade.summary = "not started";
    } else if (status == "time limit" || status.rfind("crashed", 0) == 0) {
        grade.status = ModuleGrade::Status::crashed;
        grade.summary = status;
    } else {
        grade.status = ModuleGrade::Status::error;
        grade.summary = status;
    }
    const std::string first = m.value("first_failure", "");
    const std::string build = m.value("build_error", "");
    grade.output = build.empty() ? first : build;
    return grade;
}

// The last non-empty line of text
std::string last_line(const std::string& text) {
    size_t end = text.find_last_not_of(" \n\r\t");
    if (end == std::string::npos) return "";
    const size_t start = text.rfind('\n', end);
    return text.substr(start == std::string::npos ? 0 : start + 1,
                       end + 1 - (start == std::string::npos ? 0 : start + 1));
}

// The value of KEY in a CMakeCache.txt ("KEY:TYPE=value"), or ""
std::string cache_value(const std::string& cache_file, const std::string& key) {
    std::ifstream in(cache_file);
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind(key + ":", 0) != 0) continue;
        const size_t eq = line.find('=');
        if (eq != std::string::npos) return line.substr(eq + 1);
    }
    return "";
}

bool is_grade_script(const std::string& path) {
    const std::string name = "/scripts/grade.sh";
    return path.size() >= name.size() &&
           path.compare(path.size() - name.size(), name.size(), name) == 0;
}

// The build folder of a viewer at <build>/framework/viewer/raylab
std::string build_dir_of(const std::string& viewer_path) {
    const size_t slash = viewer_path.rfind('/');
    const std::string dir =
        slash == std::string::npos ? "." : viewer_path.substr(0, slash);
    return dir + "/../..";
}

}  // namespace

ModuleGrade grade_with_runner(const std::string& runner, const std::string& tests,
                              const std::string& id, double timeout_seconds,
                              const std::atomic<bool>* cancel) {
    ModuleGrade grade;
    const std::string dir = make_temp_dir();
    if (dir.empty()) {
        grade.status = ModuleGrade::Status::error;
        grade.summary = "cannot create a temporary folder";
        return grade;
    }
    const ChildResult child =
        run_child({runner, "--tests", tests, "--out", dir, "--only", id, "--timeout",
                   std::to_string(int(timeout_seconds / 2))},
                  {}, timeout_seconds, cancel);
    const nlohmann::json modules = read_cases(dir);
    std::filesystem::remove_all(dir);
    if (!child.started || child.timed_out || modules.is_null() || modules.empty()) {
        grade.output = child.output;
        grade.status =
            child.timed_out ? ModuleGrade::Status::crashed : ModuleGrade::Status::error;
        grade.summary = child.timed_out ? "timed out" : "the runner failed";
        return grade;
    }
    return grade_from_cases(modules[0]);
}

std::array<ModuleGrade, kModuleCount> grade_with_script(const std::string& script,
                                                        const std::string& exercises,
                                                        double timeout_seconds,
                                                        const std::atomic<bool>* cancel) {
    std::array<ModuleGrade, kModuleCount> grades;
    const auto fail_all = [&](const std::string& summary, const std::string& output) {
        for (ModuleGrade& g : grades) {
            g = ModuleGrade{};
            g.status = ModuleGrade::Status::error;
            g.summary = summary;
            g.output = output;
        }
        return grades;
    };
    const std::string dir = make_temp_dir();
    if (dir.empty()) return fail_all("cannot create a temporary folder", "");
    // The hand-in is the exercises this viewer was built with: exercises/ beside the
    // script, as `./scripts/dev.sh grade` (SUBMISSION empty), or another folder; the
    // reports go to dir
    std::string submission;
    if (!exercises.empty()) {
        std::error_code ec;
        const auto root = std::filesystem::path(script).parent_path().parent_path();
        const auto own = std::filesystem::weakly_canonical(root / "exercises", ec);
        if (std::filesystem::weakly_canonical(exercises, ec) != own)
            submission = exercises;
    }
    const ChildResult child =
        run_child({"/bin/bash", script}, {"GRADE_OUT=" + dir, "SUBMISSION=" + submission},
                  timeout_seconds, cancel);
    const nlohmann::json modules = read_cases(dir);
    std::filesystem::remove_all(dir);
    if (!child.started || child.timed_out || child.exit_code != 0 || modules.is_null()) {
        const std::string why =
            child.timed_out
                ? "timed out after " + std::to_string(int(timeout_seconds)) + " s"
                : last_line(child.output);
        return fail_all(
            "grading failed: " + why + " (./scripts/dev.sh grade shows the whole output)",
            child.output);
    }
    for (const nlohmann::json& m : modules) {
        const std::string id = m.value("id", "");
        for (const ModuleInfo& info : module_infos()) {
            if (id == info.id)
                grades[static_cast<int>(info.module)] = grade_from_cases(m);
        }
    }
    return grades;
}

std::string find_runner(const std::string& grading_binary) {
    const size_t slash = grading_binary.rfind('/');
    const std::string path =
        (slash == std::string::npos ? std::string(".")
                                    : grading_binary.substr(0, slash)) +
        "/raylab-grade";
    return access(path.c_str(), X_OK) == 0 ? path : std::string();
}

std::string find_grade_script(const std::string& viewer_path) {
    const std::string root = cache_value(build_dir_of(viewer_path) + "/CMakeCache.txt",
                                         "CMAKE_HOME_DIRECTORY");
    if (root.empty()) return "";
    const std::string script = root + "/scripts/grade.sh";
    return access(script.c_str(), R_OK) == 0 ? script : std::string();
}

std::string find_exercises_dir(const std::string& viewer_path) {
    return cache_value(build_dir_of(viewer_path) + "/CMakeCache.txt",
                       "RAYLAB_EXERCISES_DIR");
}

std::string find_grading_binary(const std::string& viewer_path) {
    if (const char* env = std::getenv("RAYLAB_GRADING_TESTS"); env && *env) {
        return access(env, X_OK) == 0 ? std::string(env) : std::string();
    }
    if (std::string script = find_grade_script(viewer_path); !script.empty())
        return script;
    const std::string path =
        build_dir_of(viewer_path) + "/tests/grading/raylab-grading-tests";
    return access(path.c_str(), X_OK) == 0 ? path : std::string();
}

GradingRun::~GradingRun() {
    cancel_ = true;
    if (thread_.joinable()) thread_.join();
}

void GradingRun::start(const std::string& binary, double timeout_seconds,
                       const std::string& exercises) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (running_) return;
        running_ = true;
        for (ModuleGrade& g : grades_) {
            g = ModuleGrade{};
            g.status = ModuleGrade::Status::running;
            g.summary = "waiting";
        }
    }
    if (thread_.joinable()) thread_.join();
    if (is_grade_script(binary)) {
        // One run of scripts/grade.sh grades every module, as `grade` does; the first run
        // also builds the graders
        {
            std::lock_guard<std::mutex> lock(mutex_);
            for (ModuleGrade& g : grades_)
                g.summary = "running (scripts/grade.sh)";
        }
        std::string folder = exercises;
        if (folder.empty()) {  // the exercises of the running viewer's build
            std::error_code ec;
            folder =
                find_exercises_dir(std::filesystem::read_symlink("/proc/self/exe", ec));
        }
        thread_ = std::thread([this, binary, folder] {
            auto grades = grade_with_script(binary, folder, kScriptTimeout, &cancel_);
            {
                std::lock_guard<std::mutex> lock(mutex_);
                grades_ = std::move(grades);
                running_ = false;
            }
            wake_();
        });
        return;
    }
    thread_ = std::thread([this, binary, timeout_seconds] {
        for (const ModuleInfo& info : module_infos()) {
            if (cancel_) break;
            {
                std::lock_guard<std::mutex> lock(mutex_);
                grades_[static_cast<int>(info.module)].summary = "running";
            }
            wake_();
            const std::string runner = find_runner(binary);
            ModuleGrade grade =
                runner.empty() ? grade_module(binary, info.id, timeout_seconds, &cancel_)
                               : grade_with_runner(runner, binary, info.id,
                                                   timeout_seconds, &cancel_);
            {
                std::lock_guard<std::mutex> lock(mutex_);
                grades_[static_cast<int>(info.module)] = std::move(grade);
            }
            wake_();
        }
        {
            std::lock_guard<std::mutex> lock(mutex_);
            running_ = false;
        }
        wake_();
    });
}

bool GradingRun::running() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return running_;
}

std::array<ModuleGrade, kModuleCount> GradingRun::grades() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return grades_;
}

}  // namespace raylab::viewer
