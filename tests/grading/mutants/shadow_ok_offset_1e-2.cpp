// Mutant exercise file: CORRECT: a normal offset of 1e-2 plus ulps of |x|
#include <algorithm>
#include <limits>

#include "raylab/contract.h"

namespace raylab::student {

bool in_shadow(const Occluder& scene, const Vec3& x, const Vec3& n,
               const LightSample& sample) {
    const float scale = std::max({std::abs(x.x), std::abs(x.y), std::abs(x.z)});
    const float eps = 1e-2f + 8.0f * std::numeric_limits<float>::epsilon() * scale;
    const Vec3 o = x + eps * (glm::dot(n, sample.wi) >= 0.0f ? n : -n);
    return scene.occluded(
        Ray{o, sample.wi, eps, glm::length(sample.wi * sample.r + x - o) - eps});
}

}  // namespace raylab::student
