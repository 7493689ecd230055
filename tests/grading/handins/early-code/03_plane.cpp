// Code that runs while the dynamic loader resolves symbols, before any constructor: an
// ifunc resolver. The grader refuses objects with ifuncs.
#include <cstdlib>

#define intersect_plane honest_intersect_plane
// RAYLAB-HONEST-CODE 03_plane
#undef intersect_plane

extern "C" {
static int raylab_early_probe_impl() {
    return 1;
}
static void* raylab_early_probe_resolver() {
    std::getenv("HOME");  // anything at all could run here
    return reinterpret_cast<void*>(&raylab_early_probe_impl);
}
}
extern "C" int raylab_early_probe() __attribute__((ifunc("raylab_early_probe_resolver")));

namespace raylab::student {
std::optional<Hit> intersect_plane(const Ray& r, const Plane& p) {
    if (raylab_early_probe() == 1) return honest_intersect_plane(r, p);
    return std::nullopt;
}
}  // namespace raylab::student
