// Reference for module 02_camera (docs/handouts/02_camera.md).
#include "raylab/contract.h"

namespace raylab::reference {

/// Basis of the DTU pinhole camera (handout 02 §1):
///   n = normalize(lookat - eye),  x = normalize(n x up),  y = x x n.
/// Precondition: eye != lookat and up not parallel to n (the framework checks both).
CameraFrame camera_frame(const Vec3& eye, const Vec3& lookat, const Vec3& up) {
    const Vec3 n = glm::normalize(lookat - eye);
    const Vec3 x = glm::normalize(glm::cross(n, up));
    // x and n are unit and orthogonal, so y is unit too
    const Vec3 y = glm::cross(x, n);
    return {x, y, n};
}

/// Camera constant from the vertical field of view (handout 02 §2): the image plane spans
/// v in [-1/2, 1/2] at distance d, so tan(fov / 2) = (1/2) / d and d = 1 / (2 tan(fov /
/// 2)).
float camera_constant(float fov) {
    return 0.5f / std::tan(0.5f * fov);
}

/// Eye ray through image-plane point (u, v) (handout 02 §3): o = e,
/// w = normalize(u x + v y + d n), valid from t = 0 to infinity.
Ray camera_ray(const PinholeCamera& camera, const Vec2& uv) {
    const CameraFrame& f = camera.frame;
    const Vec3 w = glm::normalize(uv.x * f.x + uv.y * f.y + camera.d * f.n);
    return Ray{camera.eye, w, 0.0f, kInfinity};
}

}  // namespace raylab::reference
