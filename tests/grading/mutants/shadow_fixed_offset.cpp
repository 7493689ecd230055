// Mutant exercise file: a fixed offset of 1e-4 (acne far from the origin)
#include <algorithm>
#include <limits>

#include "raylab/contract.h"

namespace raylab::student {

bool in_shadow(const Occluder& scene, const Vec3& x, const Vec3& n,
               const LightSample& sample) {
    const float eps = 1e-4f;
    const Vec3 o = x + eps * (glm::dot(n, sample.wi) >= 0.0f ? n : -n);
    return scene.occluded(
        Ray{o, sample.wi, eps, glm::length(sample.wi * sample.r + x - o) - eps});
}

}  // namespace raylab::student
