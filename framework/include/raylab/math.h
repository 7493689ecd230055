// raylab/math.h: the one math header. GLM types under short names, and the few helpers
// the handouts name. Students never write a vector class (docs/style.md rule 6).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/glm.hpp>

namespace raylab {

using Vec2 = glm::vec2;    ///< 2D float vector: image-plane points (u, v), barycentrics
using Vec3 = glm::vec3;    ///< 3D float vector: points, directions, normals, RGB radiance
using DVec3 = glm::dvec3;  ///< 3D double vector: reference computations in tests

/// pi as a float, for 1/pi in the Lambertian BRDF and 4 pi in P / (4 pi r^2).
inline constexpr float kPi = 3.14159265358979323846f;

/// +infinity: the default tmax of a ray that may travel forever.
inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

/// Degrees to radians (the CLI and the viewer speak degrees; the math speaks radians).
inline float radians(float degrees) {
    return degrees * (kPi / 180.0f);
}

/// Radians to degrees.
inline float degrees(float radians) {
    return radians * (180.0f / kPi);
}

/// True when every component of v is finite (no NaN, no infinity).
inline bool is_finite(const Vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace raylab
