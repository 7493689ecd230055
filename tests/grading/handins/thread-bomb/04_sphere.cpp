// A thread bomb, kept small: a static initializer starts up to 200 idle threads with
// 64 KiB stacks. Every thread takes a process ID, and a root grader has no per-user
// process limit, so without the worker's seccomp rule against clone a few thousand of
// them would use up the grading machine's PIDs. This hand-in checks the limit itself: its
// honest sphere answers only if the sandbox let it start no thread at all.
#include <pthread.h>
#include <unistd.h>

namespace {
void* idle(void*) {
    for (;;)
        pause();
    return nullptr;
}
int started_threads() {
    pthread_attr_t a;
    pthread_attr_init(&a);
    pthread_attr_setstacksize(&a, 64 * 1024);
    int n = 0;
    for (; n < 200; ++n) {
        pthread_t t;
        if (pthread_create(&t, &a, idle, nullptr) != 0) break;
    }
    return n;
}
const int threads = started_threads();
}  // namespace

#define intersect_sphere honest_intersect_sphere
// RAYLAB-HONEST-CODE 04_sphere
#undef intersect_sphere

namespace raylab::student {
std::optional<Hit> intersect_sphere(const Ray& r, const Sphere& s) {
    if (threads > 0) return std::nullopt;
    return honest_intersect_sphere(r, s);
}
}  // namespace raylab::student
