// Module 02_camera: the pinhole camera (docs/handouts/02_camera.md).
//
// Your work is the three functions below; `grep -n "TODO(student)" exercises/` lists
// every step. Delete a function's RAYLAB_STUB line when you start on that function: while
// a module's functions still call it, the viewer runs the reference for that module and
// the graders report it as not started.
#include "raylab/contract.h"

namespace raylab::student {

/// Basis of the DTU pinhole camera (handout 02 §1):
///   n = normalize(lookat - eye),  x = normalize(n x up),  y = x x n.
/// x points right on screen, y up, n into the scene. Precondition: eye != lookat and up
/// not parallel to n (the framework checks both).
CameraFrame camera_frame(const Vec3& eye, const Vec3& lookat, const Vec3& up) {
    // TODO(student) 02_camera: n = normalize(lookat - eye)
    // TODO(student) 02_camera: x = normalize(n x up) (up is only a hint: normalize)
    // TODO(student) 02_camera: y = x x n (x and n are unit and orthogonal, so y is unit
    //   too); return {x, y, n}
    RAYLAB_STUB("02_camera");
    (void)eye, (void)lookat, (void)up;
    return CameraFrame{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, -1)};
}

/// Camera constant from the vertical field of view fov in radians (handout 02 §2): the
/// image plane spans v in [-1/2, 1/2] at distance d, so tan(fov / 2) = (1/2) / d and
///   d = 1 / (2 tan(fov / 2)).
float camera_constant(float fov) {
    // TODO(student) 02_camera: d = 1 / (2 tan(fov / 2))
    RAYLAB_STUB("02_camera");
    (void)fov;
    return 1.0f;
}

/// Eye ray through image-plane point (u, v) (handout 02 §3): o = e,
/// w = normalize(u x + v y + d n), valid from t = 0 to infinity.
Ray camera_ray(const PinholeCamera& camera, const Vec2& uv) {
    // TODO(student) 02_camera: w = normalize(uv.x * x + uv.y * y + d * n), with x, y, n
    //   from camera.frame and d = camera.d
    // TODO(student) 02_camera: return Ray{camera.eye, w, 0.0f, kInfinity}
    RAYLAB_STUB("02_camera");
    (void)uv;
    return Ray{camera.eye, camera.frame.n, 0.0f, kInfinity};
}

}  // namespace raylab::student
