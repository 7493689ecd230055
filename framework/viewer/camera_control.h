// viewer/camera_control.h: how keys and the mouse move the camera and the lights.
//
// The COMS30115 lab's controls on the DTU camera (eye e, look-at p, up u): the arrow keys
// walk forward and back and turn the camera about its up axis (yaw), W/A/S/D/Q/E move
// the selected light, a mouse drag orbits the eye about the look-at point and the wheel
// moves the eye towards it. Pure functions of the view: the viewer's input code calls
// them, and the tests check them without a window.
#pragma once

#include "raylab/scene.h"

namespace raylab::viewer {

/// Moves eye and look-at together by distance along the viewing direction projected on
/// the plane normal to up (walking: the height stays the same). Negative: backwards.
View walk(const View& view, float distance);

/// Turns the camera about the up axis through the eye by angle radians (positive: to the
/// left, counter-clockwise seen from above). The eye stays put.
View turn(const View& view, float angle);

/// Orbits the eye about the look-at point: yaw radians about up, pitch radians about the
/// camera's x axis (positive: the eye rises), keeping the distance and keeping the view
/// direction at least 2 degrees away from up.
View orbit(const View& view, float yaw, float pitch);

/// Moves the eye towards the look-at point: the distance is multiplied by factor (< 1:
/// closer), and never falls below 1e-3 times the scene size.
View dolly(const View& view, float factor, float scene_size);

/// A light position moved in the camera's walking frame: right along x, up along u,
/// forward along the horizontal viewing direction.
Vec3 move_in_view(const View& view, const Vec3& p, float right, float up, float forward);

/// A length for speeds: the diagonal of the scene's bounds, or the eye's distance to the
/// look-at point when the scene has no bounded primitives.
float scene_size(const Scene& scene, const View& view);

}  // namespace raylab::viewer
