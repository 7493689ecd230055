// Mutant exercise file: a right point light that gives no light beyond distance 100
#include "raylab/contract.h"

namespace raylab::student {

LightSample sample_point_light(const PointLight& light, const Vec3& x) {
    const Vec3 to_light = light.p - x;
    const float r = glm::length(to_light);
    if (r > 100.0f) return LightSample{to_light / r, r, Vec3(0.0f)};
    return LightSample{to_light / r, r, light.I / (r * r)};
}

Vec3 intensity_from_power(const Vec3& P) {
    return P / (4.0f * kPi);
}

}  // namespace raylab::student
