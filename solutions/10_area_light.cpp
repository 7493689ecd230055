// Reference for module 10_area_light (docs/handouts/10_area_light.md).
#include <algorithm>
#include <cmath>

#include "raylab/contract.h"

namespace raylab::reference {

/// Points on the unit square (handout 10 §3). Uniform: N independent points (xi_1, xi_2).
/// Stratified: N_y = the largest divisor of N with N_y^2 <= N, N_x = N / N_y, and one
/// point in each cell (a, b) of the N_x x N_y grid: ((a + xi_1) / N_x, (b + xi_2) / N_y).
std::vector<Vec2> light_sample_points(int N, bool stratified, PixelRng rng) {
    std::vector<Vec2> xi;
    if (N < 1) return xi;
    xi.reserve(static_cast<size_t>(N));
    if (!stratified) {
        for (int k = 0; k < N; ++k) {
            const float xi_1 = rng.uniform();
            const float xi_2 = rng.uniform();
            xi.emplace_back(xi_1, xi_2);
        }
        return xi;
    }
    int N_y = 1;
    for (int d = 1; d * d <= N; ++d) {
        if (N % d == 0) N_y = d;
    }
    const int N_x = N / N_y;
    const float below_one = std::nextafter(1.0f, 0.0f);
    for (int b = 0; b < N_y; ++b) {
        for (int a = 0; a < N_x; ++a) {
            const float xi_1 = rng.uniform();
            const float xi_2 = rng.uniform();
            xi.emplace_back(std::min((float(a) + xi_1) / float(N_x), below_one),
                            std::min((float(b) + xi_2) / float(N_y), below_one));
        }
    }
    return xi;
}

/// One of N samples of an area light (handout 10 §2): the light point
///   y = p + xi_1 e1 + xi_2 e2,
/// seen from x at distance r = |y - x| in direction wi = (y - x) / r, brings
///   Li = Le A cos(theta_y) / (N r^2),   A = |e1 x e2|,   cos(theta_y) = max(-n . wi, 0)
/// with n = (e1 x e2) / A the side that emits. The cosine at x is Lambert's (module 07).
LightSample sample_area_light(const AreaLight& light, const Vec3& x, const Vec2& xi,
                              int N) {
    const Vec3 y = light.p + xi.x * light.e1 + xi.y * light.e2;
    const Vec3 normal = glm::cross(light.e1, light.e2);
    const float A = glm::length(normal);
    const Vec3 to_light = y - x;
    const float r = glm::length(to_light);
    if (!(r > 0.0f) || !(A > 0.0f) || N < 1)
        return LightSample{Vec3(0, 1, 0), 1.0f, Vec3(0.0f)};
    const Vec3 wi = to_light / r;
    const float cos_theta_y = std::max(-glm::dot(normal / A, wi), 0.0f);
    const Vec3 Li = light.Le * (A * cos_theta_y / (static_cast<float>(N) * r * r));
    return LightSample{wi, r, Li};
}

}  // namespace raylab::reference
