// Module 07_lambert: Lambertian shading (docs/handouts/07_lambert.md).
//
// Your work is the function below; `grep -n "TODO(student)" exercises/` lists every step.
// Delete a function's RAYLAB_STUB line when you start on that function: while a module's
// functions still call it, the viewer runs the reference for that module and the graders
// report it as not started.
#include "raylab/contract.h"

namespace raylab::student {

/// Radiance leaving a Lambertian surface (handout 07 §2, Lambert's cosine law):
///   L = Le + rho / pi * sum_i Li max(n . wi, 0).
/// lights may hold lights below the horizon (n . wi < 0): they add nothing.
/// Precondition: |n| = 1 and every wi is unit.
Vec3 lambert(const Vec3& rho, const Vec3& Le, const Vec3& n,
             const std::vector<LightSample>& lights) {
    // TODO(student) 07_lambert: Irradiance E: each light's Li weighted by the cosine
    //   n . wi, clamped at zero for lights below the horizon, summed over lights
    // TODO(student) 07_lambert: The Lambertian BRDF is rho / pi: return Le + rho / pi * E
    RAYLAB_STUB("07_lambert");
    (void)rho, (void)Le, (void)n, (void)lights;
    return Vec3(0.0f);
}

}  // namespace raylab::student
