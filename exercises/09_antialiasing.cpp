// Module 09_antialiasing: anti-aliasing (docs/handouts/09_antialiasing.md).
//
// Your work is the functions below; `grep -n "TODO(student)" exercises/` lists every
// step. Delete a function's RAYLAB_STUB line when you start on that function: while a
// module's functions still call it, the viewer runs the reference for that module and the
// graders report it as not started.
#include "raylab/contract.h"

namespace raylab::student {

/// Uniform grid (handout 09 §2): sample (a, b) of the n x n grid, a, b = 0 .. n-1, sits
/// at the centre of its cell:
///   offset = ((a + 1/2) / n, (b + 1/2) / n),   weight w = 1 / n^2.
/// Return no samples when n < 1.
std::vector<PixelSample> grid_samples(int n) {
    // TODO(student) 09_antialiasing: w = 1 / n^2; for each row b and column a of the
    //   grid, push PixelSample{Vec2((a + 0.5) / n, (b + 0.5) / n), w}
    RAYLAB_STUB("09_antialiasing");
    (void)n;
    return {};
}

/// Stratified (jittered) samples (handout 09 §3): one sample in each cell (a, b) of the
/// n x n grid, at a uniformly random place inside it:
///   offset = ((a + xi_1) / n, (b + xi_2) / n),   xi_1, xi_2 = rng.uniform() in [0, 1),
///   weight w = 1 / n^2.
/// Return no samples when n < 1.
std::vector<PixelSample> stratified_samples(int n, PixelRng rng) {
    // TODO(student) 09_antialiasing: as grid_samples, with 0.5 replaced by a fresh
    //   rng.uniform() for each coordinate of each sample
    RAYLAB_STUB("09_antialiasing");
    (void)n, (void)rng;
    return {};
}

/// Pixel estimate (handout 09 §1): the sample at offset (s, t) of pixel (i, j) in a
/// W x H image looks through the image-plane point
///   u = ((i + s) / W - 1/2) W / H,   v = 1/2 - (j + t) / H
/// (module 01's formula with the pixel centre 1/2 replaced by the offset), and the pixel
/// gets L = sum_k w_k radiance(u_k, v_k).
Vec3 pixel_radiance(int i, int j, int W, int H, const std::vector<PixelSample>& samples,
                    const PixelRadiance& radiance) {
    // TODO(student) 09_antialiasing: L = 0; for each sample: (u, v) from the formula,
    //   L += weight * radiance(Vec2(u, v)); return L
    RAYLAB_STUB("09_antialiasing");
    (void)i, (void)j, (void)W, (void)H, (void)samples, (void)radiance;
    return Vec3(0.0f);
}

/// Refinement test of the adaptive scheme (handout 09 §4). L holds the first sample of a
/// pixel and of its neighbours. Per channel c:
///   C_c = (max_k L_k,c - min_k L_k,c) / (max_k L_k,c + min_k L_k,c),
/// taken as 0 where max + min = 0. Return true when some C_c > threshold (and false for
/// an empty L).
bool needs_more_samples(const std::vector<Vec3>& L, float threshold) {
    // TODO(student) 09_antialiasing: per channel, the smallest and largest value in L
    // TODO(student) 09_antialiasing: contrast C = (max - min) / (max + min), or 0 when
    //   max + min = 0; return true as soon as one channel's C > threshold
    RAYLAB_STUB("09_antialiasing");
    (void)L, (void)threshold;
    return false;
}

}  // namespace raylab::student
