// Mutant exercise file: a right camera whose eye rays start at t = 1e-3, not 0 (the
// contract: eye rays are valid from t = 0, so a surface nearer than 1e-3 is lost)
#include "raylab/contract.h"

namespace raylab::student {

CameraFrame camera_frame(const Vec3& eye, const Vec3& lookat, const Vec3& up) {
    const Vec3 n = glm::normalize(lookat - eye);
    const Vec3 x = glm::normalize(glm::cross(n, up));
    return CameraFrame{x, glm::cross(x, n), n};
}

float camera_constant(float fov) {
    return 1.0f / (2.0f * std::tan(0.5f * fov));
}

Ray camera_ray(const PinholeCamera& camera, const Vec2& uv) {
    const CameraFrame& f = camera.frame;
    const Vec3 w = glm::normalize(uv.x * f.x + uv.y * f.y + camera.d * f.n);
    return Ray{camera.eye, w, 1e-3f, kInfinity};
}

}  // namespace raylab::student
