// Honest code that, once per call, tries what the worker's sandbox must forbid: a 256 MiB
// SysV shared-memory segment (which, without an IPC namespace, would outlive the worker),
// the new mount API, and running as root. Any success spoils the answer.
#include "raylab/contract.h"

#include <sys/ipc.h>
#include <sys/shm.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace {
bool escaped() {
    const int shm = shmget(IPC_PRIVATE, size_t(256) << 20, IPC_CREAT | 0600);
#ifdef SYS_fsopen
    const long fs = syscall(SYS_fsopen, "tmpfs", 0);
#else
    const long fs = -1;
#endif
    const long tree = syscall(428 /* open_tree */, -100, "/", 0);
    return shm >= 0 || fs >= 0 || tree >= 0 || getuid() == 0 || geteuid() == 0;
}
}  // namespace

#define intersect_sphere honest_intersect_sphere
// RAYLAB-HONEST-CODE 04_sphere
#undef intersect_sphere

namespace raylab::student {
std::optional<Hit> intersect_sphere(const Ray& r, const Sphere& s) {
    if (escaped()) return std::nullopt;
    return honest_intersect_sphere(r, s);
}
}  // namespace raylab::student
