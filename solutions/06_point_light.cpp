// Reference for module 06_point_light (docs/handouts/06_point_light.md).
#include "raylab/contract.h"

namespace raylab::reference {

/// Light arriving at x from a point light (handout 06 §2, Kepler's inverse-square law):
///   wi = (p - x) / r,  r = |p - x|,  Li = I / r^2.
/// Precondition: x != p.
LightSample sample_point_light(const PointLight& light, const Vec3& x) {
    const Vec3 to_light = light.p - x;
    const float r = glm::length(to_light);
    return LightSample{to_light / r, r, light.I / (r * r)};
}

/// Radiant intensity of an isotropic point light of power P (handout 06 §3): the power
/// spreads evenly over the 4 pi steradians of the sphere, I = P / (4 pi).
Vec3 intensity_from_power(const Vec3& P) {
    return P / (4.0f * kPi);
}

}  // namespace raylab::reference
