// The implementation under test and the settings of a run (grading.h).
#include "grading.h"

#include "worker_client.h"

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <type_traits>

namespace raylab::grading {

namespace {

// ---- What this run grades -------------------------------------------------------------

struct Settings {
    Impl impl = Impl::student;
    bool golden = false;                // expected values from tests/data/golden/
    std::string golden_dir;             // where the golden data is read
    std::string record_dir;             // RAYLAB_GOLDEN_WRITE: where this run writes it
    std::string images_dir;             // RAYLAB_GRADE_IMAGES: where images are saved
    std::map<int, std::string> faults;  // module index -> segv | hang | throw | nan
};

Settings& settings() {
    static Settings s;
    return s;
}

std::string env(const char* name) {
    const char* v = std::getenv(name);
    return v ? std::string(v) : std::string();
}

// ---- Fault injection ------------------------------------------------------------------
// RAYLAB_GRADE_FAULT="04_sphere=segv,05_triangle=hang" lets the grader's own tests prove
// that a crash, a hang, an exception or a NaN in one module fails that module only. Never
// set in normal grading.

// segv, hang and throw happen in the worker; nan here, on the value it returned
std::uint32_t worker_fault(Module m) {
    const auto it = settings().faults.find(static_cast<int>(m));
    if (it == settings().faults.end()) return rpc::kNoFault;
    if (it->second == "segv") return rpc::kSegv;
    if (it->second == "hang") return rpc::kHang;
    if (it->second == "throw") return rpc::kThrow;
    return rpc::kNoFault;
}

bool nan_fault(Module m) {
    const auto it = settings().faults.find(static_cast<int>(m));
    return it != settings().faults.end() && it->second == "nan";
}

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

void poison(Vec2& v) {
    v = Vec2(kNaN);
}
void poison(Vec3& v) {
    v = Vec3(kNaN);
}
void poison(float& x) {
    x = kNaN;
}
void poison(bool& b) {
    b = !b;
}
void poison(CameraFrame& f) {
    f.x = f.y = f.n = Vec3(kNaN);
}
void poison(Ray& r) {
    r.w = Vec3(kNaN);
}
void poison(LightSample& s) {
    s.Li = Vec3(kNaN);
}
void poison(std::optional<Hit>& hit) {
    if (!hit) hit = Hit{};
    hit->t = kNaN;
    hit->position = hit->n = Vec3(kNaN);
}
void poison(PixelSample& p) {
    p.offset = Vec2(kNaN);
    p.weight = kNaN;
}
// Lists of results: every element poisoned, and an empty list gets one
template <class T>
void poison(std::vector<T>& list) {
    if (list.empty()) list.resize(1);
    for (T& x : list)
        poison(x);
}

// ---- Stub detection -------------------------------------------------------------------

[[noreturn]] void fail_stub(Module m, const char* function) {
    const std::string id = module_info(m).id;
    const std::string message =
        "not started: " + std::string(function) + " of " + id +
        " still calls RAYLAB_STUB (delete that line in exercises/" + id +
        ".cpp when you implement it)";
    FAIL(message);
    std::abort();  // not reached: FAIL throws
}

// Calls function f of module m in the worker (sig gives its type only; the student's
// code is never linked into this process)
template <class R, class... A, class... P>
R call(Module m, const char* function, rpc::Function f, R (*sig)(A...),
       const P&... args) {
    bool stubbed = false;
    if constexpr (std::is_void_v<R>) {
        remote(f, worker_fault(m), sig, stubbed, args...);
        if (stubbed) fail_stub(m, function);
    } else {
        R result = remote(f, worker_fault(m), sig, stubbed, args...);
        if (stubbed) fail_stub(m, function);
        if (nan_fault(m)) poison(result);
        return result;
    }
}

constexpr bool kHaveReference = RAYLAB_HAVE_REFERENCE;

}  // namespace

// ---- Settings -------------------------------------------------------------------------

Impl impl_under_test() {
    return settings().impl;
}

const char* impl_name() {
    return settings().impl == Impl::student ? "student" : "reference";
}

bool using_golden() {
    return settings().golden;
}

std::string golden_dir() {
    return settings().golden_dir;
}

bool setup() {
    Settings& s = settings();
    const std::string impl = env("RAYLAB_GRADE_IMPL");
    if (impl.empty() || impl == "student") {
        s.impl = Impl::student;
    } else if (impl == "reference") {
        if (!kHaveReference) {
            std::printf(
                "[raylab] RAYLAB_GRADE_IMPL=reference, but this build has no reference "
                "solutions (solutions/ is absent)\n");
            return false;
        }
        s.impl = Impl::reference;
    } else {
        std::printf(
            "[raylab] RAYLAB_GRADE_IMPL must be 'student' or 'reference', not '%s'\n",
            impl.c_str());
        return false;
    }
    const std::string oracle = env("RAYLAB_GRADE_ORACLE");
    s.golden = oracle == "golden" || !kHaveReference;
    s.golden_dir = env("RAYLAB_GOLDEN_DIR");
    if (s.golden_dir.empty()) s.golden_dir = RAYLAB_GOLDEN_DIR_DEFAULT;
    s.record_dir = env("RAYLAB_GOLDEN_WRITE");
    s.images_dir = env("RAYLAB_GRADE_IMAGES");
    if (!s.record_dir.empty() && s.golden) {
        std::printf(
            "[raylab] RAYLAB_GOLDEN_WRITE needs the reference solutions in the build\n");
        return false;
    }
    // RAYLAB_GRADE_FAULT: "04_sphere=segv,05_triangle=hang"
    std::istringstream faults(env("RAYLAB_GRADE_FAULT"));
    std::string item;
    while (std::getline(faults, item, ',')) {
        const size_t eq = item.find('=');
        bool known = false;
        for (const ModuleInfo& info : module_infos()) {
            if (eq != std::string::npos && item.substr(0, eq) == info.id) {
                s.faults[static_cast<int>(info.module)] = item.substr(eq + 1);
                known = true;
            }
        }
        if (!known) {
            std::printf("[raylab] RAYLAB_GRADE_FAULT: cannot read '%s'\n", item.c_str());
            return false;
        }
    }
    if (std::getenv("RAYLAB_WORKER") == nullptr) {
        setenv("RAYLAB_WORKER",
               s.impl == Impl::student ? RAYLAB_WORKER_STUDENT : RAYLAB_WORKER_REFERENCE,
               1);
#if RAYLAB_SANITIZED_WORKERS
        setenv("RAYLAB_WORKER_SANITIZED", "1",
               1);  // this build's workers: no memory limit
#endif
    }
    std::printf("[raylab] grading the %s code against %s\n",
                s.impl == Impl::student ? "student's" : "reference",
                s.golden ? ("the golden data in " + s.golden_dir).c_str()
                         : "the reference solutions");
    std::fflush(stdout);
    return true;
}

std::string golden_record_dir() {
    return settings().record_dir;
}

std::string images_dir() {
    return settings().images_dir;
}

bool finish() {
    return write_golden();
}

// ---- Calls of the implementation under test -------------------------------------------

namespace {
// The call of function F of module M in the worker, with the contract's signature Sig
template <Module M, rpc::Function F, class Sig>
struct Remote;
template <Module M, rpc::Function F, class R, class... A>
struct Remote<M, F, R (*)(A...)> {
    static R call(A... args) {
        return grading::call(M, rpc::function_name(static_cast<std::uint32_t>(F)), F,
                             static_cast<R (*)(A...)>(nullptr), args...);
    }
};
}  // namespace

namespace under_test {
#define RAYLAB_FUNCTION(m, f)       \
    const decltype(&student::f) f = \
        &Remote<Module::m, rpc::Function::f, decltype(&student::f)>::call;
#include "raylab/modules.def"
}  // namespace under_test

const ModuleTable& reference_modules() {
    // Filled from raylab::reference directly: this process never links student code
    static const ModuleTable table = [] {
        ModuleTable t{};
#if RAYLAB_HAVE_REFERENCE
#define RAYLAB_FUNCTION(m, f) t.f = &reference::f;
#include "raylab/modules.def"
#endif
        return t;
    }();
    return table;
}

}  // namespace raylab::grading
