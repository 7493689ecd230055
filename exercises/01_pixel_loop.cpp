#include "raylab/contract.h"

namespace raylab::student {

Vec2 image_plane_point(int i, int j, int W, int H) {
    // TODO(student) 01_pixel_loop: image-plane point of the centre of pixel (i, j).
    RAYLAB_STUB("01_pixel_loop");
    (void)i, (void)j, (void)W, (void)H;
    return Vec2(0.0f);
}

void render_tile(const Tile& tile, const PixelRadiance& radiance,
                 const ImageView& image) {
    // TODO(student) 01_pixel_loop: call radiance for every pixel of tile and store it.
    RAYLAB_STUB("01_pixel_loop");
    (void)tile, (void)radiance, (void)image;
}

}  // namespace raylab::student
