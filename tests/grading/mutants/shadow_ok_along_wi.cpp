// Mutant exercise file: CORRECT: offset along wi, tmin = 0, stop short of the light
#include <algorithm>
#include <limits>

#include "raylab/contract.h"

namespace raylab::student {

bool in_shadow(const Occluder& scene, const Vec3& x, const Vec3& n,
               const LightSample& sample) {
    const float scale = std::max({std::abs(x.x), std::abs(x.y), std::abs(x.z)});
    const float eps = 1e-3f + 16.0f * std::numeric_limits<float>::epsilon() * scale;
    (void)n;
    return scene.occluded(
        Ray{x + eps * sample.wi, sample.wi, 0.0f, sample.r - 2.0f * eps});
}

}  // namespace raylab::student
