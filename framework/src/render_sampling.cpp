// The renderer's sampling passes (render_sampling.h).
#include "render_sampling.h"

#include <cstring>

#include "raylab/error.h"

namespace raylab {

const char* to_string(PixelSampling sampling) {
    switch (sampling) {
        case PixelSampling::grid:
            return "grid";
        case PixelSampling::stratified:
            return "stratified";
        case PixelSampling::adaptive:
            return "adaptive";
    }
    return "?";
}

PixelSampling parse_pixel_sampling(const std::string& word) {
    for (PixelSampling s :
         {PixelSampling::grid, PixelSampling::stratified, PixelSampling::adaptive}) {
        if (word == to_string(s)) return s;
    }
    throw Error("unknown pixel sampling '" + word + "' (grid, stratified, adaptive)");
}

AreaLight area_light_for(const PointLight& light, float size, const Vec3& target) {
    // Facing target; a, b and n right-handed, so e1 x e2 = A n
    Vec3 n(0.0f, -1.0f, 0.0f);
    const Vec3 to_target = target - light.p;
    if (glm::length(to_target) > 1e-6f) n = glm::normalize(to_target);
    const Vec3 helper = std::abs(n.y) < 0.9f ? Vec3(0, 1, 0) : Vec3(1, 0, 0);
    const Vec3 a = glm::normalize(glm::cross(helper, n));
    const Vec3 b = glm::cross(n, a);
    const float A = size * size;
    AreaLight area;
    area.e1 = size * a;
    area.e2 = size * b;
    area.p = light.p - 0.5f * (area.e1 + area.e2);
    area.Le = A > 0.0f ? light.I / A : Vec3(0.0f);
    return area;
}

namespace detail {

int samples_per_side(int spp) {
    int n = 1;
    while ((n + 1) * (n + 1) <= spp)
        ++n;
    return n;
}

bool supersampled(const RenderSettings& settings) {
    return settings.spp > 1;
}

PixelRng pixel_rng(const RenderSettings& settings, int i, int j, std::uint64_t pass) {
    return PixelRng::make(settings.seed, std::uint64_t(std::uint32_t(i)),
                          std::uint64_t(std::uint32_t(j)), pass);
}

PixelRng light_rng(const RenderSettings& settings, const Vec2& uv, std::uint64_t k) {
    std::uint32_t u = 0, v = 0;
    std::memcpy(&u, &uv.x, sizeof u);
    std::memcpy(&v, &uv.y, sizeof v);
    return PixelRng::make(settings.seed, u, v, 0x100000000ull + k);
}

namespace {

void count_samples(const RenderSettings& settings, int i, int j, int n) {
    if (!settings.samples_map) return;
    (*settings.samples_map)[size_t(j) * size_t(settings.width) + size_t(i)] =
        static_cast<std::uint16_t>(n);
}

}  // namespace

void render_tile_sampled(const Tile& tile, const PixelRadiance& radiance,
                         const ImageView& image, const RenderSettings& settings,
                         const ModuleTable& modules) {
    const int n = samples_per_side(settings.spp);
    const bool grid = settings.sampling == PixelSampling::grid;
    const std::vector<PixelSample> grid_samples =
        grid ? modules.grid_samples(n) : std::vector<PixelSample>{};
    for (int j = tile.y0; j < tile.y1; ++j) {
        for (int i = tile.x0; i < tile.x1; ++i) {
            const std::vector<PixelSample> samples =
                grid ? grid_samples
                     : modules.stratified_samples(n, pixel_rng(settings, i, j, 0));
            image.set(i, j,
                      modules.pixel_radiance(i, j, image.width, image.height, samples,
                                             radiance));
            count_samples(settings, i, j, int(samples.size()));
        }
    }
}

void refine_tile(const Tile& tile, const PixelRadiance& radiance, const Image& first,
                 const ImageView& out, const RenderSettings& settings,
                 const ModuleTable& modules) {
    const int n = samples_per_side(settings.spp);
    std::vector<Vec3> L;
    L.reserve(9);
    for (int j = tile.y0; j < tile.y1; ++j) {
        for (int i = tile.x0; i < tile.x1; ++i) {
            // The pixel's first sample, then its neighbours' inside the image
            L.clear();
            L.push_back(first.at(i, j));
            for (int dj = -1; dj <= 1; ++dj) {
                for (int di = -1; di <= 1; ++di) {
                    const int a = i + di, b = j + dj;
                    if ((di || dj) && a >= 0 && b >= 0 && a < first.width &&
                        b < first.height)
                        L.push_back(first.at(a, b));
                }
            }
            if (!modules.needs_more_samples(L, settings.aa_threshold)) {
                out.set(i, j, first.at(i, j));
                count_samples(settings, i, j, 1);
                continue;
            }
            const std::vector<PixelSample> samples =
                modules.stratified_samples(n, pixel_rng(settings, i, j, 1));
            out.set(
                i, j,
                modules.pixel_radiance(i, j, out.width, out.height, samples, radiance));
            // The first sample was taken too
            count_samples(settings, i, j, int(samples.size()) + 1);
        }
    }
}

}  // namespace detail
}  // namespace raylab
