// Mutant exercise file: an intersector that never hits
#include "raylab/contract.h"

namespace raylab::student {

std::optional<Hit> intersect_plane(const Ray& r, const Plane& plane) {
    (void)r, (void)plane;
    return std::nullopt;
}

}  // namespace raylab::student
