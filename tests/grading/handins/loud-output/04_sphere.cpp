// An honest mistake: debug prints left in, 20 MB of them (stdout and stderr) before the
// first call and more on every call. Only 1 MiB is kept; the grade is the code's.
#include <cstdio>
#include <string>

namespace {
const int loud = [] {
    const std::string line(1000, 'x');
    for (int k = 0; k < 10000; ++k) {
        std::printf("%s\n", line.c_str());
        std::fprintf(stderr, "%s\n", line.c_str());
    }
    return 0;
}();
}  // namespace

#define intersect_sphere honest_intersect_sphere
// RAYLAB-HONEST-CODE 04_sphere
#undef intersect_sphere

namespace raylab::student {
std::optional<Hit> intersect_sphere(const Ray& r, const Sphere& s) {
    std::printf("intersect_sphere called\n");
    return honest_intersect_sphere(r, s);
}
}  // namespace raylab::student
