// Calls a helper defined in another .cpp file, which is not part of the hand-in format
#include "raylab/contract.h"
float helper_t();
namespace raylab::student {
std::optional<Hit> intersect_sphere(const Ray&, const Sphere&) {
    Hit h{};
    h.t = helper_t();
    return h;
}
}  // namespace raylab::student
