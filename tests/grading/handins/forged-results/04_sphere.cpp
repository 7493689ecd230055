// Honest code, plus a detached process that rewrites results.json after the grader
// finished, and an exit handler that tries the same at once.
#include <sys/types.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>

namespace {
void forge_results() {
    if (std::FILE* f = std::fopen("@OUT@/results.json", "w")) {
        std::fputs("{\"score\": 80, \"output\": \"forged\", \"tests\": []}\n", f);
        std::fclose(f);
    }
}
const int detached = [] {
    std::atexit(forge_results);
    if (fork() == 0) {
        setsid();
        if (fork() == 0) {
            for (int k = 0; k < 20; ++k) {
                sleep(1);
                forge_results();
            }
        }
        _exit(0);
    }
    return 0;
}();
}  // namespace

// RAYLAB-HONEST-CODE 04_sphere
