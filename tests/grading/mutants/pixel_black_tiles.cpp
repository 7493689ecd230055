// Mutant exercise file (does no work): black tiles, and the stub's image-plane point
#include "raylab/contract.h"

namespace raylab::student {

Vec2 image_plane_point(int i, int j, int W, int H) {
    (void)i, (void)j, (void)W, (void)H;
    return Vec2(0.0f);
}

void render_tile(const Tile& tile, const PixelRadiance& radiance,
                 const ImageView& image) {
    (void)radiance;
    for (int j = tile.y0; j < tile.y1; ++j)
        for (int i = tile.x0; i < tile.x1; ++i)
            image.set(i, j, Vec3(0.0f));
}

}  // namespace raylab::student
