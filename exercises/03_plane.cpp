#include "raylab/contract.h"

namespace raylab::student {

std::optional<Hit> intersect_plane(const Ray& r, const Plane& plane) {
    // TODO(student) 03_plane: ray-plane intersection.
    RAYLAB_STUB("03_plane");
    (void)r, (void)plane;
    return std::nullopt;
}

}  // namespace raylab::student
