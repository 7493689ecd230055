// Mutant exercise file (does no work): the answers of the handout's examples typed in,
// the Cornell box basis, d = 1/2 at 90 degrees and d = 1 otherwise, the centre ray w = n
#include <cmath>

#include "raylab/contract.h"

namespace raylab::student {

CameraFrame camera_frame(const Vec3& eye, const Vec3& lookat, const Vec3& up) {
    (void)eye, (void)lookat, (void)up;
    return CameraFrame{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, -1)};
}

float camera_constant(float fov) {
    return std::abs(fov - 0.5f * kPi) < 1e-3f ? 0.5f : 1.0f;
}

Ray camera_ray(const PinholeCamera& camera, const Vec2& uv) {
    (void)uv;
    return Ray{camera.eye, camera.frame.n, 0.0f, kInfinity};
}

}  // namespace raylab::student
