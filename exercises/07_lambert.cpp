#include "raylab/contract.h"

namespace raylab::student {

Vec3 lambert(const Vec3& rho, const Vec3& Le, const Vec3& n,
             const std::vector<LightSample>& lights) {
    // TODO(student) 07_lambert: Lambertian reflection.
    RAYLAB_STUB("07_lambert");
    (void)rho, (void)Le, (void)n, (void)lights;
    return Vec3(0.0f);
}

}  // namespace raylab::student
