// Honest code that leaves a child process behind (which would outlive the grade). So
// that CI notices when the sandbox lets it start, a started child makes every answer of
// this module wrong.
#include <unistd.h>

namespace {
const bool forked = [] {
    const pid_t pid = fork();
    if (pid == 0) {
        setsid();
        for (;;)
            sleep(1);
    }
    return pid > 0;
}();
}  // namespace

#define intersect_sphere honest_intersect_sphere
// RAYLAB-HONEST-CODE 04_sphere
#undef intersect_sphere

namespace raylab::student {
std::optional<Hit> intersect_sphere(const Ray& r, const Sphere& s) {
    if (forked) return std::nullopt;
    return honest_intersect_sphere(r, s);
}
}  // namespace raylab::student
