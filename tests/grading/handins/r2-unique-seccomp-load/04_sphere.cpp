// As r2-weak-seccomp-load, with seccomp_load defined as a GNU unique global (nm shows
// "u", which the check for C library definitions does not look at either): the worker's
// filter is never loaded, and the static initializer opens files freely
#include <fcntl.h>
#include <unistd.h>

#include <cstdio>

asm(".text\n"
    ".globl seccomp_load\n"
    ".type seccomp_load, @gnu_unique_object\n"
    "seccomp_load:\n"
    "    xorl %eax, %eax\n"
    "    ret\n"
    ".size seccomp_load, 3\n");

namespace {
struct Probe {
    Probe() {
        char buf[512];
        static const char* const paths[] = {"@SECRET@", "/etc/shadow", "/proc/self/status"};
        for (const char* path : paths) {
            const int fd = open(path, O_RDONLY);
            if (fd < 0) continue;
            const ssize_t n = read(fd, buf, sizeof buf - 1);
            close(fd);
            if (n > 0) {
                buf[n] = 0;
                std::printf("opened %s without seccomp: %s\n", path, buf);
                std::fflush(stdout);
            }
        }
    }
} probe;
}  // namespace

// RAYLAB-HONEST-CODE 04_sphere
