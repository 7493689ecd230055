// Reference for module 08_shadows (docs/handouts/08_shadows.md).
#include "raylab/contract.h"

namespace raylab::reference {

/// Shadow test (handout 08 §2): the light is blocked when the any-hit query finds
/// something on the segment from x towards the light, strictly before the light.
///
/// Self-intersection (handout 08 §3): x carries rounding error, so the ray starts a
/// little off the surface, on the light's side, and stops a little short of the light.
/// The offset is a small absolute margin plus 8 ulps of the largest coordinate of x, so
/// it grows with the rounding error of positions far from the origin and stays tiny near
/// it.
bool in_shadow(const Occluder& scene, const Vec3& x, const Vec3& n,
               const LightSample& sample) {
    // Offset along the normal, towards the light's side of the surface
    const float scale = std::max({std::abs(x.x), std::abs(x.y), std::abs(x.z)});
    const float eps = 1e-4f + 8.0f * std::numeric_limits<float>::epsilon() * scale;
    const Vec3 side = glm::dot(n, sample.wi) >= 0.0f ? n : -n;
    const Vec3 o = x + eps * side;
    // Segment to the light, stopping short of it. tmin = eps too: at an inside corner the
    // offset origin lies in the neighbouring face's plane, which would block at t = 0
    const Ray shadow_ray{o, sample.wi, eps,
                         glm::length(sample.wi * sample.r + x - o) - eps};
    return scene.occluded(shadow_ray);
}

}  // namespace raylab::reference
