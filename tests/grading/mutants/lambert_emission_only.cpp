// Mutant exercise file: a Lambert that returns only the emission (it did earn 3 of 12
// cases, a quarter of the points)
#include "raylab/contract.h"

namespace raylab::student {
Vec3 lambert(const Vec3&, const Vec3& Le, const Vec3&, const std::vector<LightSample>&) {
    return Le;
}
}  // namespace raylab::student
