// Module 10 built on the student's own module 06, as the handouts' structure invites: each
// point of the area light is a point light. The worker links the hand-in's 06, not 06's
// stub, as the viewer does.
#include <algorithm>

#include "raylab/contract.h"

#define sample_area_light honest_sample_area_light
// RAYLAB-HONEST-CODE 10_area_light
#undef sample_area_light

namespace raylab::student {
LightSample sample_area_light(const AreaLight& light, const Vec3& x, const Vec2& xi, int N) {
    const Vec3 y = light.p + xi.x * light.e1 + xi.y * light.e2;
    const Vec3 normal = glm::cross(light.e1, light.e2);
    const float A = glm::length(normal);
    const float r = glm::length(y - x);
    if (!(r > 0.0f) || !(A > 0.0f) || N < 1) return LightSample{Vec3(0, 1, 0), 1.0f, Vec3(0.0f)};
    const float cos_theta_y = std::max(-glm::dot(normal / A, (y - x) / r), 0.0f);
    return sample_point_light(PointLight{y, light.Le * (A * cos_theta_y / float(N))}, x);
}
}  // namespace raylab::student
