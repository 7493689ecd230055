// Mutant exercise file (does no work): one sample at the pixel centre, whatever n, and
// never more samples
#include "raylab/contract.h"

namespace raylab::student {

std::vector<PixelSample> grid_samples(int n) {
    (void)n;
    return {PixelSample{Vec2(0.5f), 1.0f}};
}

std::vector<PixelSample> stratified_samples(int n, PixelRng rng) {
    (void)n, (void)rng;
    return {PixelSample{Vec2(0.5f), 1.0f}};
}

Vec3 pixel_radiance(int i, int j, int W, int H, const std::vector<PixelSample>& samples,
                    const PixelRadiance& radiance) {
    (void)samples;
    const float aspect = float(W) / float(H);
    return radiance(Vec2(((float(i) + 0.5f) / float(W) - 0.5f) * aspect,
                         0.5f - (float(j) + 0.5f) / float(H)));
}

bool needs_more_samples(const std::vector<Vec3>& L, float threshold) {
    (void)L, (void)threshold;
    return false;
}

}  // namespace raylab::student
