// The trusted side of the grading worker (worker_client.h): the sandbox and the calls.
#include "worker_client.h"

#include <fcntl.h>
#include <grp.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace raylab::grading {

namespace {

std::string env_or(const char* name, const std::string& fallback) {
    const char* v = std::getenv(name);
    return v && *v ? std::string(v) : fallback;
}

double call_timeout() {
    const double t = std::atof(env_or("RAYLAB_WORKER_TIMEOUT", "10").c_str());
    return t > 0.0 ? t : 10.0;
}

// Limits of the worker process, set before exec so that they hold for the student's
// static initializers too
void limit(int resource, rlim_t value) {
    const rlimit r{value, value};
    setrlimit(resource, &r);
}

// How bubblewrap makes the worker's namespaces. A user namespace first; where the kernel
// refuses one (a chroot, some containers) but the grader is root, the other namespaces
// without it and with every capability dropped, so that the worker is a powerless root
// that sees /usr and its own files only.
bool root_namespaces = false;

// Either way the worker is not root inside: nobody in its own user namespace, or (without
// one) setpriv's nobody, which keeps no capability. --new-session and --unshare-ipc
// (part of --unshare-all) keep it from the grader's terminal and SysV IPC objects.
std::vector<std::string> namespace_args() {
    if (!root_namespaces) return {"--unshare-all", "--uid", "65534", "--gid", "65534"};
    return {"--unshare-pid",        "--unshare-net", "--unshare-ipc", "--unshare-uts",
            "--unshare-cgroup-try", "--cap-drop",    "ALL",           "--cap-add",
            "CAP_SETUID",           "--cap-add",     "CAP_SETGID"};
}

std::vector<std::string> bwrap_args(const std::string& worker) {
    std::vector<std::string> args = {"/usr/bin/bwrap"};
    for (const std::string& a : namespace_args())
        args.push_back(a);
    const std::vector<std::string> rest = {"--die-with-parent",
                                           "--new-session",
                                           "--ro-bind",
                                           "/usr",
                                           "/usr",
                                           "--symlink",
                                           "usr/lib",
                                           "/lib",
                                           "--symlink",
                                           "usr/lib64",
                                           "/lib64",
                                           "--symlink",
                                           "usr/bin",
                                           "/bin",
                                           "--ro-bind-try",
                                           "/etc/ld.so.cache",
                                           "/etc/ld.so.cache",
                                           "--proc",
                                           "/proc",
                                           "--dev",
                                           "/dev",
                                           "--tmpfs",
                                           "/tmp",
                                           "--ro-bind",
                                           worker,
                                           "/worker/raylab-worker",
                                           "--chdir",
                                           "/tmp",
                                           "--clearenv",
                                           "--setenv",
                                           "PATH",
                                           "/usr/bin",
                                           "--setenv",
                                           "HOME",
                                           "/tmp",
                                           "--setenv",
                                           "LANG",
                                           "C.UTF-8"};
    args.insert(args.end(), rest.begin(), rest.end());
    if (root_namespaces) {
        for (const char* a :
             {"/usr/bin/setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"})
            args.push_back(a);
    }
    args.push_back("/worker/raylab-worker");
    return args;
}

// Starts argv with fd as its file descriptor 3 and the limits of a worker; returns its
// pid. The child's output goes to log (or /dev/null).
pid_t spawn(const std::vector<std::string>& argv, int fd, const std::string& log,
            const std::string& private_dir) {
    const bool sanitized_worker = !env_or("RAYLAB_WORKER_SANITIZED", "").empty();
    // Without namespaces grade.sh hands over a copy of raylab-sandbox: the worker then
    // runs under Landlock too, able to read /usr and the workers only and to write its
    // private folder, so that even code that ran before its seccomp filter (a slip in
    // grade.sh's checks) could read no other file
    std::vector<std::string> full = argv;
    const std::string landlock = env_or("RAYLAB_WORKER_LANDLOCK", "");
    if (!private_dir.empty() && !landlock.empty()) {
        const std::string folder = std::filesystem::path(argv[0]).parent_path().string();
        full = {landlock, "run",  "--ro", "/usr",      "--ro", "/etc/ld.so.cache",
                "--ro",   folder, "--rw", private_dir, "--"};
        full.insert(full.end(), argv.begin(), argv.end());
    }
    std::vector<char*> args;
    for (const std::string& a : full)
        args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    const pid_t pid = fork();
    if (pid != 0) return pid;
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    setpgid(0, 0);  // its own process group: killing it ends whatever it started
    const int null = open("/dev/null", O_RDWR);
    const int out =
        log.empty() ? null : open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    dup2(null, 0);
    dup2(out >= 0 ? out : null, 1);
    dup2(out >= 0 ? out : null, 2);
    dup2(fd, 3);
    for (int k = 4; k < 1024; ++k)
        close(k);
    limit(RLIMIT_CPU, rlim_t(call_timeout() * 4 + 2));
    // 2 GiB, except for this build's own sanitizer-instrumented workers (ASan reserves
    // terabytes of address space for its shadow memory)
    if (!sanitized_worker) limit(RLIMIT_AS, rlim_t(1) << 31);
    limit(RLIMIT_FSIZE, rlim_t(1) << 20);  // 1 MiB: the log and any file it writes
    limit(RLIMIT_CORE, 0);
    // Past 1 MiB a write fails instead of killing the worker: debug prints cost nothing
    signal(SIGXFSZ, SIG_IGN);
    limit(RLIMIT_NOFILE, 64);
    clearenv();
    setenv("PATH", "/usr/bin", 1);
    setenv("LANG", "C.UTF-8", 1);
    if (!private_dir.empty()) {
        setenv("HOME", private_dir.c_str(), 1);
        setenv("TMPDIR", private_dir.c_str(), 1);
        if (chdir(private_dir.c_str()) != 0) _exit(126);
        // Without namespaces, a root grader runs the worker as nobody: it can then write
        // its private folder only, not the checkout or the reports
        if (geteuid() == 0) {
            if (chown(private_dir.c_str(), 65534, 65534) != 0 ||
                setgroups(0, nullptr) != 0 || setgid(65534) != 0 || setuid(65534) != 0)
                _exit(126);
        }
    }
    execv(args[0], args.data());
    _exit(127);
}

bool bwrap_works() {
    static const bool works = [] {
        const std::string mode = env_or("RAYLAB_SANDBOX", "auto");
        if (mode == "none") return false;
        const auto probe_ok = [] {
            std::vector<std::string> probe = bwrap_args("/usr/bin/true");
            int fds[2];
            if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) != 0)
                return false;
            const pid_t pid = spawn(probe, fds[1], "", "");
            close(fds[0]);
            close(fds[1]);
            int status = 0;
            waitpid(pid, &status, 0);
            return WIFEXITED(status) && WEXITSTATUS(status) == 0;
        };
        bool ok = probe_ok();
        if (!ok && geteuid() == 0) {
            root_namespaces = true;
            ok = probe_ok();
        }
        if (!ok && mode == "bwrap")
            worker_lost("crash",
                        "RAYLAB_SANDBOX=bwrap, but bubblewrap cannot start here");
        return ok;
    }();
    return works;
}

// The processes the worker's sandbox runs (pid, the launcher, and all it started):
// bubblewrap's own processes aside, each must be confined by the worker's seccomp filter
// and no_new_privs. The worker's "hello" alone proves nothing: a hand-in that replaces a
// library function the filter's setup calls can make the worker report a filter that was
// never loaded. The kernel's view cannot be faked. Returns what is wrong, or "".
std::string confinement_problem(pid_t launcher, bool launcher_is_bwrap) {
    std::vector<pid_t> pending = {launcher}, seen;
    while (!pending.empty() && seen.size() < 4096) {
        const pid_t p = pending.back();
        pending.pop_back();
        seen.push_back(p);
        std::error_code ec;
        for (const auto& task : std::filesystem::directory_iterator(
                 "/proc/" + std::to_string(p) + "/task", ec)) {
            FILE* f = std::fopen((task.path() / "children").c_str(), "r");
            if (!f) continue;
            long child = 0;
            while (std::fscanf(f, "%ld", &child) == 1)
                pending.push_back(pid_t(child));
            std::fclose(f);
        }
    }
    int confined = 0;
    for (const pid_t p : seen) {
        const std::string proc = "/proc/" + std::to_string(p);
        std::error_code ec;
        // bubblewrap's processes (it cannot be replaced: exe changes only with execve)
        if (launcher_is_bwrap &&
            std::filesystem::read_symlink(proc + "/exe", ec) == "/usr/bin/bwrap")
            continue;
        FILE* f = std::fopen((proc + "/status").c_str(), "r");
        if (!f) continue;  // it has just exited
        int seccomp = -1, no_new_privs = -1;
        char line[256];
        while (std::fgets(line, sizeof line, f)) {
            std::sscanf(line, "Seccomp: %d", &seccomp);
            std::sscanf(line, "NoNewPrivs: %d", &no_new_privs);
        }
        std::fclose(f);
        if (seccomp != 2 || no_new_privs != 1)
            return "the worker runs without the grader's seccomp filter (process " +
                   std::to_string(p) + ": Seccomp " + std::to_string(seccomp) +
                   ", NoNewPrivs " + std::to_string(no_new_privs) +
                   "): the hand-in's code interfered with the sandbox's setup, e.g. by "
                   "defining a C library or libseccomp function";
        ++confined;
    }
    return confined > 0 ? "" : "the worker's process was not found after it started";
}

// Kills every process this one started and has not reaped. This process is a child
// subreaper (start() makes it one), so a process the worker left behind, even one that
// forked twice and called setsid, is re-parented here instead of to init: none outlives
// the grade
void kill_leftovers() {
    for (int round = 0; round < 100; ++round) {
        std::vector<pid_t> children;
        std::error_code ec;
        for (const auto& task :
             std::filesystem::directory_iterator("/proc/self/task", ec)) {
            FILE* f = std::fopen((task.path() / "children").c_str(), "r");
            if (!f) continue;
            long child = 0;
            while (std::fscanf(f, "%ld", &child) == 1)
                children.push_back(pid_t(child));
            std::fclose(f);
        }
        if (children.empty()) return;
        for (const pid_t c : children)
            kill(c, SIGKILL);
        for (const pid_t c : children)
            waitpid(c, nullptr, 0);
    }
}

std::string signal_text(int sig) {
    const char* name = sigabbrev_np(sig);
    const char* what = sigdescr_np(sig);
    return std::string("SIG") + (name ? name : "?") + ", " + (what ? what : "signal");
}

class Worker {
  public:
    ~Worker() { stop(); }

    int fd() {
        if (pid_ <= 0) start();
        return fd_;
    }

    // Waits for n bytes until the deadline; ends the grade (worker_lost) when the
    // worker died or took too long
    void read(void* data, size_t n, const char* doing) {
        char* p = static_cast<char*>(data);
        while (n > 0) {
            const double left = deadline_ - now();
            pollfd pfd{fd_, POLLIN, 0};
            const int ready = left > 0 ? poll(&pfd, 1, int(left * 1000) + 1) : 0;
            if (ready == 0) {
                stop();
                char limit[32];
                std::snprintf(limit, sizeof limit, "%g", call_timeout());
                worker_lost("timeout", std::string("no answer after ") + limit + " s " +
                                           doing + " (an endless loop?)");
            }
            if (ready < 0) continue;
            const ssize_t k = ::read(fd_, p, n);
            if (k <= 0) died(doing);
            p += k;
            n -= size_t(k);
        }
    }

    void restart_clock() { deadline_ = now() + call_timeout(); }

    // The worker is out of step (a callback of the trusted side threw): start afresh
    void stop() {
        if (pid_ <= 0) return;
        kill(-pid_, SIGKILL);
        kill(pid_, SIGKILL);
        waitpid(pid_, nullptr, 0);
        kill_leftovers();
        close(fd_);
        pid_ = -1;
        remove_private_dir();
    }

    void remove_private_dir() {
        std::error_code ignored;
        if (!private_dir_.empty()) std::filesystem::remove_all(private_dir_, ignored);
        private_dir_.clear();
    }

    bool seccomp() const { return seccomp_; }

  private:
    static double now() {
        return std::chrono::duration<double>(
                   std::chrono::steady_clock::now().time_since_epoch())
            .count();
    }

    void start() {
        const std::string worker = env_or("RAYLAB_WORKER", "");
        if (worker.empty() || access(worker.c_str(), X_OK) != 0)
            worker_lost("crash", "the worker " + worker + " is missing");
        int fds[2];
        if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) != 0)
            worker_lost("crash", "socketpair failed");
        const std::string log = env_or("RAYLAB_WORKER_LOG", "");
        prctl(PR_SET_CHILD_SUBREAPER, 1);
        const bool bwrap = bwrap_works();
        if (bwrap) {
            pid_ = spawn(bwrap_args(worker), fds[1], log, "");
        } else {
            char dir[] = "/tmp/raylab-worker-XXXXXX";
            private_dir_ = mkdtemp(dir) ? dir : "";
            pid_ = spawn({worker}, fds[1], log, private_dir_);
        }
        close(fds[1]);
        fd_ = fds[0];
        restart_clock();
        rpc::Header h{};
        read(&h, sizeof h, "while starting (in a static initializer?)");
        if (h.kind != rpc::Kind::hello) died("while starting");
        seccomp_ = h.flags & 1;
#if RAYLAB_WORKER_SECCOMP
        const std::string problem = confinement_problem(pid_, bwrap);
        if (!problem.empty()) worker_lost("crash", problem);
#endif
        log_line("sandbox\t" + sandbox_description());
    }

    [[noreturn]] void died(const char* doing) {
        // Give it a second to finish dying, so that its status says how it died
        int status = 0;
        pid_t done = 0;
        for (int k = 0; k < 100 && done == 0; ++k) {
            done = waitpid(pid_, &status, WNOHANG);
            if (done == 0) usleep(10000);
        }
        if (done == 0) {
            kill(-pid_, SIGKILL);
            kill(pid_, SIGKILL);
            waitpid(pid_, &status, 0);
        }
        kill_leftovers();
        close(fd_);
        pid_ = -1;
        remove_private_dir();
        std::string how = "exited";
        int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        // bubblewrap reports a signal that ended the worker as 128 + signal
        if (WIFSIGNALED(status)) code = 128 + WTERMSIG(status);
        if (code > 128 && code < 128 + 65)
            how = "crashed (" + signal_text(code - 128) + ")";
        else
            how = "exited (status " + std::to_string(code) + ")";
        worker_lost("crash", "the student's code " + how + " " + doing);
    }

    pid_t pid_ = -1;
    int fd_ = -1;
    double deadline_ = 0.0;
    bool seccomp_ = false;
    std::string private_dir_;
};

Worker& worker() {
    static Worker w;
    return w;
}

rpc::Buffer read_message(rpc::Header& h, const char* doing) {
    worker().read(&h, sizeof h, doing);
    if (h.size > rpc::kMaxPayload) {
        worker().stop();
        throw std::runtime_error("the worker sent a message that is too large");
    }
    rpc::Buffer b;
    b.bytes.resize(h.size);
    worker().read(b.bytes.data(), h.size, doing);
    return b;
}

}  // namespace

void shutdown_worker() {
    worker().stop();
}

std::string sandbox_description() {
    std::string s = bwrap_works()
                        ? std::string("bubblewrap (own namespaces") +
                              (root_namespaces ? " but no user namespace: root without "
                                                 "capabilities"
                                               : "") +
                              ", read-only /usr, private /tmp, no network)"
                        : "no namespaces (bubblewrap unavailable): private temp folder, "
                          "clean environment";
    s += worker().seccomp() ? " + seccomp (no files, threads, fork, exec, sockets)"
                            : " (no seccomp)";
    return s + " + rlimits (CPU, 2 GiB memory, 1 MiB files)";
}

rpc::Buffer exchange(rpc::Function function, std::uint32_t fault, const rpc::Buffer& args,
                     const Callbacks& callbacks, bool& stubbed) {
    const int fd = worker().fd();
    const std::string doing =
        std::string("in ") + rpc::function_name(static_cast<std::uint32_t>(function));
    worker().restart_clock();
    if (!rpc::send(fd, rpc::Kind::call, static_cast<std::uint32_t>(function), fault,
                   args))
        worker().read(nullptr, 1, doing.c_str());  // reports how it died
    for (;;) {
        rpc::Header h{};
        rpc::Buffer in = read_message(h, doing.c_str());
        if (h.kind == rpc::Kind::result) {
            stubbed = h.flags & 1;
            return in;
        }
        if (h.kind == rpc::Kind::exception)
            throw std::runtime_error(std::string(in.bytes.begin(), in.bytes.end()));
        rpc::Buffer out;
        try {
            if (h.kind == rpc::Kind::radiance && callbacks.radiance) {
                Vec2 uv;
                rpc::get_value(in, uv);
                rpc::put_value(out, (*callbacks.radiance)(uv));
            } else if (h.kind == rpc::Kind::occluded && callbacks.occluder) {
                Ray r;
                rpc::get_value(in, r);
                rpc::put_value(out, callbacks.occluder->occluded(r));
            } else {
                throw std::runtime_error("the worker sent an unexpected message");
            }
        } catch (...) {
            worker().stop();
            throw;
        }
        if (!rpc::send(fd, rpc::Kind::reply, 0, 0, out))
            worker().read(nullptr, 1, doing.c_str());
        worker().restart_clock();
    }
}

}  // namespace raylab::grading
