// Module 10_area_light: area lights and soft shadows (docs/handouts/10_area_light.md).
//
// Your work is the functions below; `grep -n "TODO(student)" exercises/` lists every
// step. Delete a function's RAYLAB_STUB line when you start on that function: while a
// module's functions still call it, the viewer runs the reference for that module and the
// graders report it as not started.
#include "raylab/contract.h"

namespace raylab::student {

/// Points on the unit square (handout 10 §3), N of them (none when N < 1).
/// Uniform: N independent points (xi_1, xi_2), each coordinate rng.uniform().
/// Stratified: N_y = the largest divisor of N with N_y^2 <= N, N_x = N / N_y, and one
/// point in each cell (a, b) of the N_x x N_y grid: ((a + xi_1) / N_x, (b + xi_2) / N_y).
std::vector<Vec2> light_sample_points(int N, bool stratified, PixelRng rng) {
    // TODO(student) 10_area_light: uniform: N times push Vec2(rng.uniform(),
    //   rng.uniform())
    // TODO(student) 10_area_light: stratified: find N_y and N_x = N / N_y, then one
    //   jittered point per cell, rows b = 0 .. N_y-1, columns a = 0 .. N_x-1
    RAYLAB_STUB("10_area_light");
    (void)N, (void)stratified, (void)rng;
    return {};
}

/// One of N samples of an area light (handout 10 §2). The light point
///   y = p + xi_1 e1 + xi_2 e2
/// is seen from x at distance r = |y - x| in direction wi = (y - x) / r, and brings
///   Li = Le A cos(theta_y) / (N r^2),   A = |e1 x e2|,   cos(theta_y) = max(-n . wi, 0),
/// where n = (e1 x e2) / A is the side that emits. Return LightSample{wi, r, Li}. (The
/// cosine at x is applied by your lambert of module 07.)
LightSample sample_area_light(const AreaLight& light, const Vec3& x, const Vec2& xi,
                              int N) {
    // TODO(student) 10_area_light: the point y on the light, then r and wi
    // TODO(student) 10_area_light: A and n from the cross product of the edges,
    //   cos(theta_y), and Li (zero when x is behind the light)
    RAYLAB_STUB("10_area_light");
    (void)light, (void)x, (void)xi, (void)N;
    return LightSample{Vec3(0.0f, 1.0f, 0.0f), 1.0f, Vec3(0.0f)};
}

}  // namespace raylab::student
