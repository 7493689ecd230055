// Mutant exercise file: a right shadow ray that stops at 99% of the distance to the
// light, so a blocker in the last 1% casts no shadow
#include <algorithm>
#include <limits>

#include "raylab/contract.h"

namespace raylab::student {

bool in_shadow(const Occluder& scene, const Vec3& x, const Vec3& n,
               const LightSample& sample) {
    const float scale = std::max({std::abs(x.x), std::abs(x.y), std::abs(x.z)});
    const float eps = 1e-4f + 8.0f * std::numeric_limits<float>::epsilon() * scale;
    const Vec3 o = x + eps * (glm::dot(n, sample.wi) >= 0.0f ? n : -n);
    return scene.occluded(Ray{o, sample.wi, eps, 0.99f * sample.r});
}

}  // namespace raylab::student
