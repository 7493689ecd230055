// viewer/grader.h: runs the graders of each module in a child process.
//
// The panel's "Run tests" runs scripts/grade.sh of the source tree the viewer was built
// from, on the exercises it was built with: the same command as `./scripts/dev.sh grade`,
// so the same staging, sandbox, table and words, and it builds the graders when they are
// not built yet. With $RAYLAB_GRADING_TESTS (a graders binary) it runs this build's
// raylab-grade (grading/) on it, one module at a time. Either way it reads the driver's
// cases.json with the grading library. Child processes keep a crashing or hanging module
// from taking the viewer down.
#pragma once

#include <array>
#include <atomic>
#include <functional>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "grade.h"
#include "raylab/modules.h"

namespace raylab::viewer {

/// How a child process ended.
struct ChildResult {
    bool started = false;    ///< false: it could not be started (message in output)
    int exit_code = -1;      ///< when it exited normally
    int signal = 0;          ///< when a signal ended it (SIGSEGV, SIGABRT, ...)
    bool timed_out = false;  ///< killed after the time limit
    std::string output;      ///< stdout and stderr, interleaved, at most 1 MiB
};

/// Runs argv[0] with arguments argv[1...], extra environment variables env ("NAME=value")
/// and stdin from /dev/null; kills its process group after timeout_seconds, or as soon as
/// *cancel turns true (reported as timed out).
ChildResult run_child(const std::vector<std::string>& argv,
                      const std::vector<std::string>& env, double timeout_seconds,
                      const std::atomic<bool>* cancel = nullptr);

/// One test case's outcome, as the runner reports it.
struct CaseGrade {
    std::string name;
    std::string status;  ///< pass, fail, stub, crash, not run
    std::string message;
};

/// One module's grading outcome.
struct ModuleGrade {
    enum class Status {
        not_run,
        running,
        passed,
        failed,
        no_tests,
        crashed,
        error,
        not_started
    };
    Status status = Status::not_run;
    std::string summary;           ///< one line for the panel, e.g. "12/14 passed"
    std::string output;            ///< the grader's console output
    std::vector<CaseGrade> cases;  ///< per case, when the runner graded it
    grade::ModuleResult result;    ///< the driver's result (result.info null: none)
};

/// The grade driver's score table (grade::table, as `./scripts/dev.sh grade` prints it)
/// of the modules in grades that the driver graded, or "" when none was.
std::string grades_table(const std::array<ModuleGrade, kModuleCount>& grades);

/// Grades module id with the runner (raylab-grade) and the grading binary tests, in a
/// child process; the runner's words and per-case results.
ModuleGrade grade_with_runner(const std::string& runner, const std::string& tests,
                              const std::string& id, double timeout_seconds,
                              const std::atomic<bool>* cancel = nullptr);

/// Grades every module with scripts/grade.sh (as `./scripts/dev.sh grade`), the hand-in
/// being the folder exercises, in a child process; reads the runner's cases.json. When
/// the script fails, every module says so with its last line.
std::array<ModuleGrade, kModuleCount> grade_with_script(
    const std::string& script, const std::string& exercises, double timeout_seconds,
    const std::atomic<bool>* cancel = nullptr);

/// This build's grade driver (grading/raylab-grade, built with the viewer), or "" when
/// it is missing.
std::string find_runner();

/// scripts/grade.sh of the source tree of the build holding the viewer at viewer_path
/// (<build>/framework/viewer/raylab; the tree is CMakeCache.txt's CMAKE_HOME_DIRECTORY),
/// or "" when there is none.
std::string find_grade_script(const std::string& viewer_path);

/// The exercises the viewer at viewer_path was built with (RAYLAB_EXERCISES_DIR of its
/// build), or "".
std::string find_exercises_dir(const std::string& viewer_path);

/// What "Run tests" runs: $RAYLAB_GRADING_TESTS when set (a graders binary), else the
/// source tree's scripts/grade.sh (find_grade_script). Empty when neither is there.
std::string find_grading_binary(const std::string& viewer_path);

/// Grades every module in a background thread; the panel reads snapshots.
class GradingRun {
  public:
    explicit GradingRun(std::function<void()> wake) : wake_(std::move(wake)) {}
    ~GradingRun();
    GradingRun(const GradingRun&) = delete;
    GradingRun& operator=(const GradingRun&) = delete;

    /// Starts grading all modules with binary (unless a run is under way): a graders
    /// binary, through raylab-grade, timeout_seconds per module; or scripts/grade.sh on
    /// the folder exercises (default: the exercises/ beside the script), kScriptTimeout
    /// in all.
    void start(const std::string& binary, double timeout_seconds = 120.0,
               const std::string& exercises = "");
    /// The time limit of a whole scripts/grade.sh run (its first run builds the graders)
    static constexpr double kScriptTimeout = 3600.0;
    bool running() const;
    std::array<ModuleGrade, kModuleCount> grades() const;

  private:
    std::function<void()> wake_;
    mutable std::mutex mutex_;
    std::array<ModuleGrade, kModuleCount> grades_;
    bool running_ = false;
    std::atomic<bool> cancel_{false};  // set by the destructor: kill the child, stop
    std::thread thread_;
};

}  // namespace raylab::viewer
