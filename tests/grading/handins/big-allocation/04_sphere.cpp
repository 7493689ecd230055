// Honest code that first takes 4 GB of memory and touches every page. Were the
// allocation to succeed (no memory limit), every answer of this module is wrong.
#include <cstdlib>
#include <cstring>

namespace {
const bool got_memory = [] {
    const size_t n = size_t(4) << 30;
    void* p = std::malloc(n);
    if (!p) return false;
    std::memset(p, 1, n);
    return true;
}();
}  // namespace

#define intersect_sphere honest_intersect_sphere
// RAYLAB-HONEST-CODE 04_sphere
#undef intersect_sphere

namespace raylab::student {
std::optional<Hit> intersect_sphere(const Ray& r, const Sphere& s) {
    if (got_memory) return std::nullopt;
    return honest_intersect_sphere(r, s);
}
}  // namespace raylab::student
