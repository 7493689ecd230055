// Mutant exercise file: the reference's sampling, but stratified_samples draws each
// cell's jitter from a copy of the generator, so every cell of a pixel is jittered alike
#include <algorithm>

#include "raylab/contract.h"

namespace raylab::student {

/// Uniform grid (handout 09 §2): sample (a, b) of the n x n grid sits at the centre of
/// its cell, offset ((a + 1/2) / n, (b + 1/2) / n), with weight w = 1 / n^2.
std::vector<PixelSample> grid_samples(int n) {
    std::vector<PixelSample> samples;
    if (n < 1) return samples;
    const float w = 1.0f / static_cast<float>(n * n);
    samples.reserve(static_cast<size_t>(n) * static_cast<size_t>(n));
    for (int b = 0; b < n; ++b) {
        for (int a = 0; a < n; ++a) {
            const Vec2 offset((static_cast<float>(a) + 0.5f) / static_cast<float>(n),
                              (static_cast<float>(b) + 0.5f) / static_cast<float>(n));
            samples.push_back(PixelSample{offset, w});
        }
    }
    return samples;
}

/// Stratified (jittered) samples (handout 09 §3): one sample per cell of the n x n grid,
/// uniformly at random inside it: offset ((a + xi_1) / n, (b + xi_2) / n) with xi_1, xi_2
/// uniform in [0, 1), weight w = 1 / n^2.
std::vector<PixelSample> stratified_samples(int n, PixelRng rng) {
    std::vector<PixelSample> samples;
    if (n < 1) return samples;
    const float w = 1.0f / static_cast<float>(n * n);
    samples.reserve(static_cast<size_t>(n) * static_cast<size_t>(n));
    for (int b = 0; b < n; ++b) {
        for (int a = 0; a < n; ++a) {
            PixelRng cell = rng;  // the mistake: each cell draws from a copy
            const float xi_1 = cell.uniform();
            const float xi_2 = cell.uniform();
            // (a + xi) / n < (a + 1) / n in float too: xi <= 1 - 2^-24 and the division
            // rounds to nearest, so the sample stays in its cell; the min guards n > 2^23
            const float s =
                std::min((static_cast<float>(a) + xi_1) / static_cast<float>(n),
                         std::nextafter(1.0f, 0.0f));
            const float t =
                std::min((static_cast<float>(b) + xi_2) / static_cast<float>(n),
                         std::nextafter(1.0f, 0.0f));
            samples.push_back(PixelSample{Vec2(s, t), w});
        }
    }
    return samples;
}

/// Pixel estimate (handout 09 §1): the sample at offset (s, t) of pixel (i, j) looks
/// through the image-plane point
///   u = ((i + s) / W - 1/2) W / H,   v = 1/2 - (j + t) / H
/// (module 01's formula with the centre 1/2 replaced by the offset), and
///   L = sum_k w_k L(u_k, v_k).
Vec3 pixel_radiance(int i, int j, int W, int H, const std::vector<PixelSample>& samples,
                    const PixelRadiance& radiance) {
    const float aspect = static_cast<float>(W) / static_cast<float>(H);
    Vec3 L(0.0f);
    for (const PixelSample& sample : samples) {
        const float s = (static_cast<float>(i) + sample.offset.x) / static_cast<float>(W);
        const float q = (static_cast<float>(j) + sample.offset.y) / static_cast<float>(H);
        const Vec2 uv((s - 0.5f) * aspect, 0.5f - q);
        L += sample.weight * radiance(uv);
    }
    return L;
}

/// Refinement test of the adaptive scheme (handout 09 §4): per channel c the contrast
///   C_c = (max_k L_k,c - min_k L_k,c) / (max_k L_k,c + min_k L_k,c)
/// (0 where max + min = 0), and more samples are needed when some C_c > threshold.
bool needs_more_samples(const std::vector<Vec3>& L, float threshold) {
    if (L.empty()) return false;
    Vec3 lo = L.front(), hi = L.front();
    for (const Vec3& Lk : L) {
        lo = glm::min(lo, Lk);
        hi = glm::max(hi, Lk);
    }
    for (int c = 0; c < 3; ++c) {
        const float sum = hi[c] + lo[c];
        const float C = sum > 0.0f ? (hi[c] - lo[c]) / sum : 0.0f;
        if (C > threshold) return true;
    }
    return false;
}

}  // namespace raylab::student
