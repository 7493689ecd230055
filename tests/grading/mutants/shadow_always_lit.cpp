// Mutant exercise file: in_shadow always answers lit
#include <algorithm>
#include <limits>

#include "raylab/contract.h"

namespace raylab::student {

bool in_shadow(const Occluder& scene, const Vec3& x, const Vec3& n,
               const LightSample& sample) {
    (void)scene, (void)x, (void)n, (void)sample;
    return false;
}

}  // namespace raylab::student
