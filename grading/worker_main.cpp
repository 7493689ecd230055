// raylab-worker: serves the contract functions of one build of student code (or, for the
// grader's own tests, of the reference) to the trusted grader over file descriptor 3.
//
// This program holds no test logic and no reference (grade.sh links it from the staged
// student files, raylab_core and this file only), and nothing it prints, writes or exits
// with is read as a verdict: the trusted side decides from the values it returns. It runs
// inside the sandbox the trusted side sets up (worker_client.cpp); here it adds a seccomp
// filter, installed before any student static initializer runs, that forbids starting
// processes and opening sockets.
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <system_error>
#include <thread>
#include <tuple>

#include "rpc.h"

#if RAYLAB_HAVE_SECCOMP
#include <fcntl.h>
#include <sched.h>
#include <seccomp.h>

#include <cerrno>
#endif

#if RAYLAB_WORKER_REFERENCE
namespace impl = raylab::reference;
#else
namespace impl = raylab::student;
#endif

namespace raylab::rpc {
namespace {

constexpr int kChannel = 3;
bool seccomp_active = false;

#if RAYLAB_HAVE_SECCOMP
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kSanitized = true;  // this build's own instrumented workers
#else
constexpr bool kSanitized = false;
#endif

// Runs before the default-priority static initializers of every file, the student's
// included (grade.sh refuses student objects with constructor priorities, .init code or
// ifuncs, which would run earlier). The filter is an allow-list: the system calls a
// worker needs to compute, allocate, keep time and talk over the descriptors it was
// given; every other call fails with EPERM. So it cannot open or change a file, start a
// process or a thread, open a socket, reach another process, use SysV IPC or the mount
// API (fsopen, fsmount, open_tree, move_mount, mount_setattr), whatever the kernel adds
// later. The namespaces of bubblewrap already hide the file system; where there are none
// (a container without them) these rules are the barrier.
__attribute__((constructor(101))) void install_seccomp() {
    // The sanitizers' runtimes need more (threads, /proc/self/maps): their own workers
    // keep the calls allowed and deny the dangerous ones
    scmp_filter_ctx ctx =
        seccomp_init(kSanitized ? SCMP_ACT_ALLOW : SCMP_ACT_ERRNO(EPERM));
    if (!ctx) return;
    bool ok = true;
    const auto rule = [&](std::uint32_t action, int call) {
        ok = ok && seccomp_rule_add(ctx, action, call, 0) == 0;
    };
    const auto self = static_cast<scmp_datum_t>(getpid());
    if (!kSanitized) {
        for (const int call : {SCMP_SYS(read),
                               SCMP_SYS(write),
                               SCMP_SYS(readv),
                               SCMP_SYS(writev),
                               SCMP_SYS(pread64),
                               SCMP_SYS(pwrite64),
                               SCMP_SYS(lseek),
                               SCMP_SYS(close),
                               SCMP_SYS(fstat),
                               SCMP_SYS(fcntl),
                               SCMP_SYS(poll),
                               SCMP_SYS(ppoll),
                               SCMP_SYS(mmap),
                               SCMP_SYS(munmap),
                               SCMP_SYS(mremap),
                               SCMP_SYS(mprotect),
                               SCMP_SYS(madvise),
                               SCMP_SYS(brk),
                               SCMP_SYS(futex),
                               SCMP_SYS(set_robust_list),
                               SCMP_SYS(get_robust_list),
                               SCMP_SYS(rseq),
                               SCMP_SYS(sched_yield),
                               SCMP_SYS(sched_getaffinity),
                               SCMP_SYS(getcpu),
                               SCMP_SYS(clock_gettime),
                               SCMP_SYS(clock_getres),
                               SCMP_SYS(gettimeofday),
                               SCMP_SYS(time),
                               SCMP_SYS(nanosleep),
                               SCMP_SYS(clock_nanosleep),
                               SCMP_SYS(getpid),
                               SCMP_SYS(gettid),
                               SCMP_SYS(getuid),
                               SCMP_SYS(geteuid),
                               SCMP_SYS(getgid),
                               SCMP_SYS(getegid),
                               SCMP_SYS(rt_sigaction),
                               SCMP_SYS(rt_sigprocmask),
                               SCMP_SYS(rt_sigreturn),
                               SCMP_SYS(sigaltstack),
                               SCMP_SYS(exit),
                               SCMP_SYS(exit_group),
                               SCMP_SYS(getrandom),
                               SCMP_SYS(getrusage),
                               SCMP_SYS(times),
                               SCMP_SYS(uname),
                               SCMP_SYS(sysinfo)})
            rule(SCMP_ACT_ALLOW, call);
        // fstat of an open descriptor (glibc's fstat is fstatat(fd, "", AT_EMPTY_PATH)),
        // never of a path
        for (const int call : {SCMP_SYS(newfstatat), SCMP_SYS(statx)})
            ok = ok && seccomp_rule_add(ctx, SCMP_ACT_ALLOW, call, 1,
                                        SCMP_A2(SCMP_CMP_MASKED_EQ, AT_EMPTY_PATH,
                                                AT_EMPTY_PATH)) == 0;
        // Signals to itself only (abort() and raise() use tgkill on their own pid),
        // limits of itself only (getrlimit and setrlimit name no process: pid 0)
        for (const int call : {SCMP_SYS(kill), SCMP_SYS(tgkill)})
            ok = ok && seccomp_rule_add(ctx, SCMP_ACT_ALLOW, call, 1,
                                        SCMP_A0(SCMP_CMP_EQ, self)) == 0;
        ok = ok && seccomp_rule_add(ctx, SCMP_ACT_ALLOW, SCMP_SYS(prlimit64), 1,
                                    SCMP_A0(SCMP_CMP_EQ, 0)) == 0;
        // No threads: each takes a process ID, and a root grader has no per-user process
        // limit, so a few thousand small-stack threads would use up the machine's PIDs.
        // The worker answers one call at a time (a hand-in's std::thread gets an
        // exception, and the report says threads are not available)
        rule(SCMP_ACT_ERRNO(EAGAIN), SCMP_SYS(clone));
        rule(SCMP_ACT_ERRNO(ENOSYS), SCMP_SYS(clone3));  // glibc falls back to clone
    } else {
        for (const int call : {SCMP_SYS(open),
                               SCMP_SYS(openat),
                               SCMP_SYS(openat2),
                               SCMP_SYS(creat),
                               SCMP_SYS(open_by_handle_at),
                               SCMP_SYS(unlink),
                               SCMP_SYS(unlinkat),
                               SCMP_SYS(rename),
                               SCMP_SYS(renameat),
                               SCMP_SYS(renameat2),
                               SCMP_SYS(mkdir),
                               SCMP_SYS(mkdirat),
                               SCMP_SYS(link),
                               SCMP_SYS(linkat),
                               SCMP_SYS(symlink),
                               SCMP_SYS(symlinkat),
                               SCMP_SYS(chmod),
                               SCMP_SYS(fchmodat),
                               SCMP_SYS(truncate),
                               SCMP_SYS(execve),
                               SCMP_SYS(execveat),
                               SCMP_SYS(fork),
                               SCMP_SYS(vfork),
                               SCMP_SYS(socket),
                               SCMP_SYS(socketpair),
                               SCMP_SYS(ptrace),
                               SCMP_SYS(mount),
                               SCMP_SYS(fsopen),
                               SCMP_SYS(fsmount),
                               SCMP_SYS(open_tree),
                               SCMP_SYS(move_mount),
                               SCMP_SYS(mount_setattr),
                               SCMP_SYS(shmget),
                               SCMP_SYS(semget),
                               SCMP_SYS(msgget),
                               SCMP_SYS(unshare),
                               SCMP_SYS(setns)})
            rule(SCMP_ACT_ERRNO(EPERM), call);
        for (const int call : {SCMP_SYS(kill), SCMP_SYS(tgkill)})
            ok = ok && seccomp_rule_add(ctx, SCMP_ACT_ERRNO(EPERM), call, 1,
                                        SCMP_A0(SCMP_CMP_NE, self)) == 0;
        // Threads for the sanitizers' runtimes; clone without CLONE_THREAD is a process
        ok = ok && seccomp_rule_add(ctx, SCMP_ACT_ERRNO(EPERM), SCMP_SYS(clone), 1,
                                    SCMP_A0(SCMP_CMP_MASKED_EQ, CLONE_THREAD, 0)) == 0;
        rule(SCMP_ACT_ERRNO(ENOSYS), SCMP_SYS(clone3));
    }
    seccomp_active = ok && seccomp_load(ctx) == 0;
    seccomp_release(ctx);
}
#endif

[[noreturn]] void lost() {
    _exit(0);  // the trusted side is gone: nothing to answer
}

// A callback to the trusted side: sends arg, waits for the reply
template <class R, class A>
R callback(Kind kind, const A& arg) {
    Buffer out;
    put_value(out, arg);
    if (!send(kChannel, kind, 0, 0, out)) lost();
    Header h{};
    if (!read_all(kChannel, &h, sizeof h) || h.kind != Kind::reply || h.size > 1024)
        lost();
    Buffer in;
    in.bytes.resize(h.size);
    if (!read_all(kChannel, in.bytes.data(), h.size)) lost();
    R value{};
    get_value(in, value);
    return value;
}

// ---- Arguments, decoded --------------------------------------------------------------

template <class T>
struct Arg {
    std::decay_t<T> value{};
    void read(Buffer& b) { get_value(b, value); }
    const std::decay_t<T>& get() const { return value; }
    void write_out(Buffer&) const {}
};

template <>
struct Arg<const PixelRadiance&> {
    PixelRadiance fn = [](const Vec2& uv) { return callback<Vec3>(Kind::radiance, uv); };
    void read(Buffer&) {}
    const PixelRadiance& get() const { return fn; }
    void write_out(Buffer&) const {}
};

class RemoteOccluder : public Occluder {
  public:
    bool occluded(const Ray& r) const override {
        return callback<bool>(Kind::occluded, r);
    }
};

template <>
struct Arg<const Occluder&> {
    RemoteOccluder occluder;
    void read(Buffer&) {}
    const Occluder& get() const { return occluder; }
    void write_out(Buffer&) const {}
};

// The image crosses both ways: the trusted side's pixels in, the written pixels out.
// Guard pixels on either side catch a pixel loop that writes outside the image.
template <>
struct Arg<const ImageView&> {
    static constexpr size_t kGuard = 256;
    static constexpr float kMark = -12345.0f;
    std::vector<Vec3> pixels;
    ImageView view{nullptr, 0, 0};
    void read(Buffer& b) {
        view.width = b.get<int>();
        view.height = b.get<int>();
        if (view.width < 0 || view.height < 0 ||
            double(view.width) * view.height * sizeof(Vec3) > kMaxPayload)
            throw std::runtime_error("rpc: image too large");
        const size_t n = size_t(view.width) * size_t(view.height);
        pixels.assign(n + 2 * kGuard, Vec3(kMark));
        b.get_raw(pixels.data() + kGuard, n * sizeof(Vec3));
        view.pixels = pixels.data() + kGuard;
    }
    const ImageView& get() const { return view; }
    void write_out(Buffer& b) const {
        const size_t n = pixels.size() - 2 * kGuard;
        for (size_t k = 0; k < kGuard; ++k) {
            if (pixels[k] != Vec3(kMark) || pixels[kGuard + n + k] != Vec3(kMark))
                throw std::runtime_error(
                    "the pixel loop wrote outside the image's pixels");
        }
        b.put_raw(pixels.data() + kGuard, n * sizeof(Vec3));
    }
};

// ---- Serving one call
// ------------------------------------------------------------------

template <class R, class... A>
void serve(R (*fn)(A...), Buffer& in, Buffer& out) {
    std::tuple<Arg<A>...> args;
    std::apply([&](auto&... a) { (a.read(in), ...); }, args);
    if constexpr (std::is_void_v<R>) {
        std::apply([&](const auto&... a) { fn(a.get()...); }, args);
    } else {
        const R result =
            std::apply([&](const auto&... a) { return fn(a.get()...); }, args);
        put_value(out, result);
    }
    std::apply([&](const auto&... a) { (a.write_out(out), ...); }, args);
}

void inject(std::uint32_t fault) {
    if (fault == kSegv) raise(SIGSEGV);
    if (fault == kThrow) throw std::runtime_error("fault injected by RAYLAB_GRADE_FAULT");
    if (fault == kHang) {
        for (;;)
            std::this_thread::sleep_for(std::chrono::seconds(1));
    }
}

void dispatch(std::uint32_t function, Buffer& in, Buffer& out) {
    switch (static_cast<Function>(function)) {
#define RAYLAB_FUNCTION(m, f)     \
    case Function::f:             \
        serve(&impl::f, in, out); \
        return;
#include "raylab/modules.def"
        default:
            throw std::runtime_error("rpc: unknown function");
    }
}

void answer(const Header& h, Buffer& in) {
    Buffer out;
    std::string error;
    try {
        inject(h.flags);
        stub::called.store(0);
        dispatch(h.function, in, out);
    } catch (const std::system_error& e) {
        error = e.what();
        // std::thread's error where the filter refuses clone: say why
        if (e.code() == std::errc::resource_unavailable_try_again)
            error +=
                " (the grader runs your code on one thread: std::thread and other "
                "threads cannot start here, though the viewer runs them)";
    } catch (const std::exception& e) {
        error = e.what();
    } catch (...) {
        error = "an exception that is not a std::exception";
    }
    if (!error.empty()) {
        Buffer message;
        message.put_raw(error.data(), std::min<size_t>(error.size(), 4096));
        if (!send(kChannel, Kind::exception, h.function, 0, message)) lost();
        return;
    }
    const std::uint32_t stubbed = stub::called.load() != 0 ? 1 : 0;
    if (!send(kChannel, Kind::result, h.function, stubbed, out)) lost();
}

}  // namespace
}  // namespace raylab::rpc

int main() {
    using namespace raylab::rpc;
    signal(SIGPIPE, SIG_IGN);
    if (!send(kChannel, Kind::hello, 0, seccomp_active ? 1 : 0, Buffer{})) return 0;
    for (;;) {
        Header h{};
        if (!read_all(kChannel, &h, sizeof h)) return 0;
        if (h.kind != Kind::call || h.size > kMaxPayload) return 0;
        Buffer in;
        in.bytes.resize(h.size);
        if (!read_all(kChannel, in.bytes.data(), h.size)) return 0;
        answer(h, in);
    }
}
