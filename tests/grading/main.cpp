// raylab-grading-tests: the doctest runner of the graders, one TEST_SUITE per module.
//
//   raylab-grading-tests                         every module, the student's code
//   raylab-grading-tests --test-suite=04_sphere  one module
//   RAYLAB_GRADE_IMPL=reference raylab-grading-tests   the reference solutions
//
// Environment (all optional): RAYLAB_GRADE_IMPL=student|reference; RAYLAB_GRADE_ORACLE=
// golden (expected values from the golden data even when the reference is in the build);
// RAYLAB_GOLDEN_DIR=DIR (where the golden data is); RAYLAB_GOLDEN_WRITE=DIR (record the
// reference's answers as golden data); RAYLAB_GRADE_IMAGES=DIR (save the images the tests
// compare); RAYLAB_GRADE_LOG=FILE (one line per test case for scripts/grade.sh, written
// by the listener below).
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

#include "grading.h"
#include "worker_client.h"

namespace {

// One line, tabs and newlines escaped, for the log's tab-separated fields
std::string escape(const std::string& s) {
    std::string out;
    for (const char c : s) {
        if (c == '\n')
            out += "\\n";
        else if (c == '\t')
            out += ' ';
        else if (c == '\\')
            out += "\\\\";
        else
            out += c;
    }
    return out;
}

/// Writes the outcome of every test case to RAYLAB_GRADE_LOG, one line each, flushed at
/// once so that the grade driver knows how far a run that crashed or hung got:
///   list <TAB> suite <TAB> name            (--list-test-cases)
///   case <TAB> suite <TAB> name <TAB> pass|fail|stub <TAB> first failure
///   crash <TAB> suite <TAB> name <TAB> signal
struct GradeLog;
GradeLog* the_log = nullptr;

struct GradeLog : doctest::IReporter {
    std::FILE* file = nullptr;
    const doctest::TestCaseData* current = nullptr;
    std::string first_failure;

    explicit GradeLog(const doctest::ContextOptions&) {
        if (const char* path = std::getenv("RAYLAB_GRADE_LOG"))
            file = std::fopen(path, "w");
        the_log = this;
    }
    ~GradeLog() override {
        the_log = nullptr;
        if (file) std::fclose(file);
    }

    void line(const std::string& text) {
        if (!file) return;
        std::fputs((text + "\n").c_str(), file);
        std::fflush(file);
    }

    // The failure text with the INFO context that was active, as the console shows it
    void note_failure(const std::string& what) {
        if (!first_failure.empty()) return;
        std::ostringstream s;
        s << what;
        const int n = get_num_active_contexts();
        const doctest::IContextScope* const* contexts = get_active_contexts();
        for (int k = 0; k < n; ++k) {
            s << "\n  ";
            contexts[k]->stringify(&s);
        }
        first_failure = s.str();
    }

    void report_query(const doctest::QueryData& q) override {
        for (unsigned k = 0; k < q.num_data; ++k)
            line(std::string("list\t") + q.data[k]->m_test_suite + "\t" +
                 q.data[k]->m_name);
    }
    void test_run_start() override {}
    void test_run_end(const doctest::TestRunStats&) override {}
    void test_case_start(const doctest::TestCaseData& tc) override {
        current = &tc;
        first_failure.clear();
    }
    void test_case_reenter(const doctest::TestCaseData&) override {}
    void test_case_end(const doctest::CurrentTestCaseStats& stats) override {
        if (!current) return;
        const bool stub = first_failure.rfind("not started:", 0) == 0;
        const char* status = stats.testCaseSuccess ? "pass" : stub ? "stub" : "fail";
        line(std::string("case\t") + current->m_test_suite + "\t" + current->m_name +
             "\t" + status + "\t" + escape(first_failure));
    }
    void test_case_exception(const doctest::TestCaseException& e) override {
        if (e.is_crash && current) {
            line(std::string("crash\t") + current->m_test_suite + "\t" + current->m_name +
                 "\t" + escape(e.error_string.c_str()));
        } else {
            // The INFO context that was active when it was thrown
            std::string what = std::string("exception thrown: ") + e.error_string.c_str();
            const int n = get_num_stringified_contexts();
            const doctest::String* contexts = get_stringified_contexts();
            for (int k = n - 1; k >= 0; --k)
                what += std::string("\n  ") + contexts[k].c_str();
            note_failure(what);
        }
    }
    void subcase_start(const doctest::SubcaseSignature&) override {}
    void subcase_end() override {}
    void log_assert(const doctest::AssertData& a) override {
        if (!a.m_failed) return;
        std::string what = a.m_expr;
        if (a.m_threw)
            what += " threw " + std::string(a.m_exception.c_str());
        else if (a.m_decomp.size())
            what += " is " + std::string(a.m_decomp.c_str());
        note_failure(what);
    }
    void log_message(const doctest::MessageData& m) override {
        if (m.m_severity & doctest::assertType::is_warn) return;
        note_failure(m.m_string.c_str());
    }
    void test_case_skipped(const doctest::TestCaseData&) override {}
};

}  // namespace

namespace raylab::grading {

std::string current_case() {
    return the_log && the_log->current ? the_log->current->m_name : "";
}

void log_line(const std::string& text) {
    if (the_log) the_log->line(text);
}

// The worker crashed or hung: the case under way fails with kind, the module stops there
// (raylab-grade reads the line), as a crash of the old in-process graders did
void worker_lost(const std::string& kind, const std::string& message) {
    shutdown_worker();
    std::printf("[raylab] %s\n", message.c_str());
    std::fflush(stdout);
    if (the_log && the_log->current)
        the_log->line(kind + "\t" + the_log->current->m_test_suite + "\t" +
                      the_log->current->m_name + "\t" + escape(message));
    std::_Exit(3);
}

}  // namespace raylab::grading

REGISTER_LISTENER("raylab-grade-log", 1, GradeLog);

int main(int argc, char** argv) {
    if (!raylab::grading::setup()) return 2;
    doctest::Context context;
    context.applyCommandLine(argc, argv);
    const int failed = context.run();
    if (failed && raylab::grading::using_golden() &&
        raylab::grading::impl_under_test() == raylab::Impl::reference) {
        std::printf(
            "[raylab] the reference disagrees with the golden data in %s. If the "
            "reference "
            "changed on purpose, regenerate the data: ninja -C <build> "
            "raylab-update-golden\n",
            raylab::grading::golden_dir().c_str());
    }
    if (!raylab::grading::finish()) return 2;
    return failed;
}
