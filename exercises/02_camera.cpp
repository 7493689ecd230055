#include "raylab/contract.h"

namespace raylab::student {

CameraFrame camera_frame(const Vec3& eye, const Vec3& lookat, const Vec3& up) {
    // TODO(student) 02_camera: camera basis.
    RAYLAB_STUB("02_camera");
    (void)eye, (void)lookat, (void)up;
    return CameraFrame{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, -1)};
}

float camera_constant(float fov) {
    // TODO(student) 02_camera: camera constant from the field of view.
    RAYLAB_STUB("02_camera");
    (void)fov;
    return 1.0f;
}

Ray camera_ray(const PinholeCamera& camera, const Vec2& uv) {
    // TODO(student) 02_camera: eye ray through (u, v).
    RAYLAB_STUB("02_camera");
    (void)uv;
    return Ray{camera.eye, camera.frame.n, 0.0f, kInfinity};
}

}  // namespace raylab::student
