// Camera and light controls (viewer/camera_control.h).
#include "camera_control.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace raylab::viewer {

namespace {

Vec3 unit_up(const View& view) {
    return glm::normalize(view.up);
}

// Viewing direction projected on the plane normal to up; the view direction itself when
// it is (nearly) parallel to up
Vec3 horizontal_forward(const View& view) {
    const Vec3 n = glm::normalize(view.lookat - view.eye);
    const Vec3 u = unit_up(view);
    const Vec3 h = n - glm::dot(n, u) * u;
    const float len = glm::length(h);
    return len > 1e-6f ? h / len : n;
}

Vec3 rotate(const Vec3& v, const Vec3& axis, float angle) {
    return Vec3(glm::rotate(glm::mat4(1.0f), angle, axis) * glm::vec4(v, 0.0f));
}

}  // namespace

View walk(const View& view, float distance) {
    const Vec3 step = distance * horizontal_forward(view);
    View v = view;
    v.eye += step;
    v.lookat += step;
    return v;
}

View turn(const View& view, float angle) {
    View v = view;
    v.lookat = view.eye + rotate(view.lookat - view.eye, unit_up(view), angle);
    return v;
}

View orbit(const View& view, float yaw, float pitch) {
    const Vec3 u = unit_up(view);
    Vec3 offset = rotate(view.eye - view.lookat, u, yaw);  // from look-at to eye
    // Pitch about the camera's x axis, clamped so the view never lines up with up
    const float r = glm::length(offset);
    const float polar = std::acos(std::clamp(glm::dot(offset / r, u), -1.0f, 1.0f));
    const float limit = radians(2.0f);
    const float target = std::clamp(polar - pitch, limit, kPi - limit);
    const Vec3 x = glm::normalize(glm::cross(-offset, u));
    offset = rotate(offset, x, target - polar);  // positive angle: the eye sinks
    View v = view;
    v.eye = view.lookat + offset;
    return v;
}

View dolly(const View& view, float factor, float scene_size) {
    const Vec3 offset = view.eye - view.lookat;
    const float r = glm::length(offset);
    const float r_new = std::max(r * factor, 1e-3f * scene_size);
    View v = view;
    v.eye = view.lookat + offset * (r_new / r);
    return v;
}

Vec3 move_in_view(const View& view, const Vec3& p, float right, float up, float forward) {
    const Vec3 f = horizontal_forward(view);
    const Vec3 u = unit_up(view);
    const Vec3 x = glm::normalize(glm::cross(f, u));
    return p + right * x + up * u + forward * f;
}

float scene_size(const Scene& scene, const View& view) {
    const Aabb box = scene.bounds();
    if (box.lo.x <= box.hi.x) {
        const float diagonal = glm::length(box.hi - box.lo);
        if (diagonal > 0.0f) return diagonal;
    }
    return std::max(glm::length(view.lookat - view.eye), 1e-3f);
}

}  // namespace raylab::viewer
