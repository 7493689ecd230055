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
#include <sstream>

#include "grade.h"

extern char** environ;

namespace raylab::viewer {

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

namespace {

// A fresh temporary folder, or "" when none can be made
std::string make_temp_dir() {
    std::string dir = (std::filesystem::temp_directory_path() / "raylab-viewer-XXXXXX");
    return mkdtemp(dir.data()) ? dir : std::string();
}

// The driver's cases.json in dir, read by the grading library (empty when missing)
std::vector<grade::ModuleResult> read_cases(const std::string& dir) {
    std::ifstream in(dir + "/cases.json");
    std::ostringstream text;
    text << in.rdbuf();
    return grade::read_cases_json(text.str());
}

// One module of the driver's cases.json, in the words the driver used
ModuleGrade grade_from_cases(const grade::ModuleResult& m) {
    ModuleGrade grade;
    for (const grade::CaseResult& c : m.cases)
        grade.cases.push_back({c.name, c.status, c.message});
    const std::string counts =
        std::to_string(m.passed) + "/" + std::to_string(m.cases.size()) + " passed";
    if (m.status == "passed") {
        grade.status = ModuleGrade::Status::passed;
        grade.summary = counts;
    } else if (m.status == "failed") {
        grade.status = ModuleGrade::Status::failed;
        grade.summary = counts;
    } else if (m.status == "not started") {
        grade.status = ModuleGrade::Status::not_started;
        grade.summary = "not started";
    } else if (m.status == "time limit" || m.status.rfind("crashed", 0) == 0) {
        grade.status = ModuleGrade::Status::crashed;
        grade.summary = m.status;
    } else {
        grade.status = ModuleGrade::Status::error;
        grade.summary = m.status;
    }
    grade.output = m.build_error.empty() ? m.first_failure : m.build_error;
    grade.result = m;
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
    const std::vector<grade::ModuleResult> modules = read_cases(dir);
    std::filesystem::remove_all(dir);
    if (!child.started || child.timed_out || modules.empty()) {
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
    const std::vector<grade::ModuleResult> modules = read_cases(dir);
    std::filesystem::remove_all(dir);
    if (!child.started || child.timed_out || child.exit_code != 0 || modules.empty()) {
        const std::string why =
            child.timed_out
                ? "timed out after " + std::to_string(int(timeout_seconds)) + " s"
                : last_line(child.output);
        return fail_all(
            "grading failed: " + why + " (./scripts/dev.sh grade shows the whole output)",
            child.output);
    }
    for (const grade::ModuleResult& m : modules)
        grades[static_cast<int>(m.info->module)] = grade_from_cases(m);
    return grades;
}

std::string grades_table(const std::array<ModuleGrade, kModuleCount>& grades) {
    std::vector<grade::ModuleResult> graded;
    for (const ModuleGrade& g : grades)
        if (g.result.info) graded.push_back(g.result);
    return graded.empty() ? std::string()
                          : grade::table(graded, "exercises/ (Run tests)");
}

std::string find_runner() {
    const std::string path = RAYLAB_GRADE_RUNNER;
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
    return find_grade_script(viewer_path);
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
            const std::string runner = find_runner();
            ModuleGrade grade;
            if (runner.empty()) {
                grade.status = ModuleGrade::Status::error;
                grade.summary = "raylab-grade is not built";
                grade.output = std::string(
                                   "build it: cmake --build <build> --target "
                                   "raylab-grade (expected at ") +
                               RAYLAB_GRADE_RUNNER + ")";
            } else {
                grade =
                    grade_with_runner(runner, binary, info.id, timeout_seconds, &cancel_);
            }
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
