// Mutant exercise file (does no work): looks the reference up with dlsym, finds nothing
// (the worker never links it) and answers "no hit"
#include <dlfcn.h>

#include "raylab/contract.h"

namespace raylab::student {

std::optional<Hit> intersect_sphere(const Ray& r, const Sphere& s) {
    using Fn = std::optional<Hit> (*)(const Ray&, const Sphere&);
    const auto fn = reinterpret_cast<Fn>(dlsym(
        RTLD_DEFAULT, "_ZN6raylab9reference16intersect_sphereERKNS_3RayERKNS_6SphereE"));
    if (fn) return fn(r, s);
    return std::nullopt;
}

}  // namespace raylab::student
