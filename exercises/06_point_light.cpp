// Module 06_point_light: light from a point light (docs/handouts/06_point_light.md).
//
// Your work is the two functions below; `grep -n "TODO(student)" exercises/` lists every
// step. Delete a function's RAYLAB_STUB line when you start on that function: while a
// module's functions still call it, the viewer runs the reference for that module and the
// graders report it as not started.
#include "raylab/contract.h"

namespace raylab::student {

/// Light arriving at x from a point light (handout 06 §2, Kepler's inverse-square law):
///   wi = (p - x) / r,  r = |p - x|,  Li = I / r^2.
/// wi points from x towards the light. Precondition: x != p.
LightSample sample_point_light(const PointLight& light, const Vec3& x) {
    // TODO(student) 06_point_light: to_light = p - x and its length r
    // TODO(student) 06_point_light: return LightSample{to_light / r, r, I / r^2}
    RAYLAB_STUB("06_point_light");
    (void)light, (void)x;
    return LightSample{Vec3(0.0f, 1.0f, 0.0f), 1.0f, Vec3(0.0f)};
}

/// Radiant intensity of an isotropic point light of power P (handout 06 §3): the power
/// spreads evenly over the 4 pi steradians of the sphere, I = P / (4 pi).
Vec3 intensity_from_power(const Vec3& P) {
    // TODO(student) 06_point_light: I = P / (4 pi) (kPi is in raylab/math.h)
    RAYLAB_STUB("06_point_light");
    (void)P;
    return Vec3(0.0f);
}

}  // namespace raylab::student
