// A student's plane module not started yet (the stub of exercises/03_plane.cpp): the
// student bench must report it as not started and skip it.
#include "raylab/contract.h"

namespace raylab::student {

std::optional<Hit> intersect_plane(const Ray& r, const Plane& plane) {
    RAYLAB_STUB("03_plane");
    (void)r, (void)plane;
    return std::nullopt;
}

}  // namespace raylab::student
