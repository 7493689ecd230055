// Reference for module 07_lambert (docs/handouts/07_lambert.md).
#include "raylab/contract.h"

namespace raylab::reference {

/// Radiance leaving a Lambertian surface (handout 07 §2, Lambert's cosine law):
///   L = Le + rho / pi * sum_i Li max(n . wi, 0).
/// Precondition: |n| = 1 and every wi is unit.
Vec3 lambert(const Vec3& rho, const Vec3& Le, const Vec3& n,
             const std::vector<LightSample>& lights) {
    // Irradiance: each light weighted by the cosine, clamped for lights below the horizon
    Vec3 E(0.0f);
    for (const LightSample& light : lights) {
        E += light.Li * std::max(glm::dot(n, light.wi), 0.0f);
    }
    // The Lambertian BRDF is rho / pi
    return Le + rho / kPi * E;
}

}  // namespace raylab::reference
