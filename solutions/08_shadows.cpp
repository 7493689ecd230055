// Reference for module 08_shadows (docs/handouts/08_shadows.md).
#include "raylab/contract.h"

namespace raylab::reference {

/// Shadow test (handout 08 §2): the light is blocked when the any-hit query finds
/// something on the segment from x towards the light, strictly before the light.
///
/// Self-intersection (handout 08 §3): the framework moves every hit point back onto the
/// primitive it hit, in double (raylab/refine.h), so x lies within delta = 2^-23
/// max|x_i| (one ulp of its largest coordinate) of its surface, however far the camera
/// is. The ray starts eps = 4 delta off the surface on the light's side, ignores t < eps
/// (inside corners), and stops short of the light by the rounding error of the light's
/// position as x + r wi. No absolute margin: an occluder a few times delta above the
/// surface casts its shadow.
bool in_shadow(const Occluder& scene, const Vec3& x, const Vec3& n,
               const LightSample& sample) {
    constexpr float ulp = std::numeric_limits<float>::epsilon();  // 2^-23
    // Offset along the normal, towards the light's side of the surface. 4 delta: x may
    // lie delta below the surface and x + eps n rounds by up to another delta, so the
    // origin is at least 2 delta above it, beyond what the intersection tests (double
    // or error-bounded) can confuse with t = 0. The floor keeps eps > 0 at x = 0
    const float scale = std::max(
        {std::abs(x.x), std::abs(x.y), std::abs(x.z), std::numeric_limits<float>::min()});
    const float eps = 4.0f * ulp * scale;
    const Vec3 side = glm::dot(n, sample.wi) >= 0.0f ? n : -n;
    const Vec3 o = x + eps * side;
    // tmin = eps: at an inside corner o lies in the neighbouring face's plane, or past
    // it by the rounding of the camera ray's t (about ulp(t) along the ray), which would
    // block at t = 0 (or t = ulp(t) / cos, below tmin unless the light grazes the wall).
    // The light at x + r wi carries the rounding of r, wi and the sum, about 8 ulps of
    // |x| + r; stopping 32 ulps short of it means a surface the light sits on (a lamp
    // on the ceiling) never counts as a blocker
    const float margin = 32.0f * ulp * (scale + sample.r);
    const Ray shadow_ray{o, sample.wi, eps,
                         glm::length(sample.wi * sample.r + x - o) - margin};
    return scene.occluded(shadow_ray);
}

}  // namespace raylab::reference
