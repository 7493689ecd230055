#include "raylab/contract.h"

namespace raylab::student {

std::optional<Hit> intersect_triangle(const Ray& r, const Vec3& v0, const Vec3& v1,
                                      const Vec3& v2) {
    // TODO(student) 05_triangle: ray-triangle intersection.
    RAYLAB_STUB("05_triangle");
    (void)r, (void)v0, (void)v1, (void)v2;
    return std::nullopt;
}

}  // namespace raylab::student
