#include "raylab/contract.h"

namespace raylab::student {

LightSample sample_point_light(const PointLight& light, const Vec3& x) {
    // TODO(student) 06_point_light: direction, distance and incident light.
    RAYLAB_STUB("06_point_light");
    (void)light, (void)x;
    return LightSample{Vec3(0.0f, 1.0f, 0.0f), 1.0f, Vec3(0.0f)};
}

Vec3 intensity_from_power(const Vec3& P) {
    // TODO(student) 06_point_light: intensity from power.
    RAYLAB_STUB("06_point_light");
    (void)P;
    return Vec3(0.0f);
}

}  // namespace raylab::student
