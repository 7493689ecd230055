#include "raylab/contract.h"

namespace raylab::student {

std::optional<Hit> intersect_sphere(const Ray& r, const Sphere& sphere) {
    // TODO(student) 04_sphere: ray-sphere intersection.
    RAYLAB_STUB("04_sphere");
    (void)r, (void)sphere;
    return std::nullopt;
}

}  // namespace raylab::student
