#include "raylab/contract.h"

namespace raylab::student {

bool in_shadow(const Occluder& scene, const Vec3& x, const Vec3& n,
               const LightSample& sample) {
    // TODO(student) 08_shadows: shadow ray with the any-hit query.
    RAYLAB_STUB("08_shadows");
    (void)scene, (void)x, (void)n, (void)sample;
    return false;
}

}  // namespace raylab::student
