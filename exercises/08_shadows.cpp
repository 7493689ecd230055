// Module 08_shadows: hard shadows (docs/handouts/08_shadows.md).
//
// Your work is the function below; `grep -n "TODO(student)" exercises/` lists every step.
// Delete a function's RAYLAB_STUB line when you start on that function: while a module's
// functions still call it, the viewer runs the reference for that module and the graders
// report it as not started.
#include "raylab/contract.h"

namespace raylab::student {

/// Shadow test (handout 08 §2): the light is blocked when the any-hit query
/// scene.occluded(ray) finds something on the segment from x towards the light, strictly
/// before the light.
///
/// Self-intersection (handout 08 §3): x carries rounding error and may lie just below its
/// own surface, so the ray starts a little off the surface, on the light's side, and
/// stops a little short of the light. The framework has already recomputed x in double
/// on the surface it hit, so its error is about one ulp of its largest coordinate: the
/// offset eps should be a few of those ulps (it must grow with |x|; a fixed 1e-4 added to
/// it also passes, but hides occluders closer than that).
bool in_shadow(const Occluder& scene, const Vec3& x, const Vec3& n,
               const LightSample& sample) {
    // TODO(student) 08_shadows: Offset along the normal, towards the light's side of the
    //   surface: scale = largest |coordinate| of x, eps = a few ulps of it (4 or more
    //   times epsilon() * scale: x may lie up to about 3 ulps below), side = n or -n (the
    //   one with side . wi >= 0), o = x + eps side
    // TODO(student) 08_shadows: Segment to the light, stopping short of it:
    //   shadow_ray{o, wi, eps, (distance from o to the light) - margin} (tmin = eps, not
    //   0: at an inside corner o lies in the neighbouring face's plane, which blocks at
    //   t = 0; the margin grows with |x| + r, the light's rounding error) return
    //   scene.occluded(shadow_ray)
    RAYLAB_STUB("08_shadows");
    (void)scene, (void)x, (void)n, (void)sample;
    return false;
}

}  // namespace raylab::student
