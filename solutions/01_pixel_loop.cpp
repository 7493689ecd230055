// Reference for module 01_pixel_loop (docs/handouts/01_pixel_loop.md).
#include "raylab/contract.h"

namespace raylab::reference {

/// Image-plane point (u, v) of the centre of pixel (i, j) in a W x H image (handout 01
/// §2):
///   u = ((i + 1/2) / W - 1/2) * W / H,   v = 1/2 - (j + 1/2) / H.
/// Row j = 0 is the top of the image, so v decreases as j grows.
Vec2 image_plane_point(int i, int j, int W, int H) {
    // Pixel centre in [0, 1]^2, measured from the top-left corner
    const float s = (static_cast<float>(i) + 0.5f) / static_cast<float>(W);
    const float q = (static_cast<float>(j) + 0.5f) / static_cast<float>(H);
    // Image-plane units: the visible height is 1, the width is the aspect ratio
    const float aspect = static_cast<float>(W) / static_cast<float>(H);
    return Vec2((s - 0.5f) * aspect, 0.5f - q);
}

/// Calls radiance once per pixel (i, j) of tile at its centre and stores the result
/// (handout 01 §3). The framework hands each thread its own tiles.
void render_tile(const Tile& tile, const PixelRadiance& radiance,
                 const ImageView& image) {
    // Rows top to bottom, columns left to right
    for (int j = tile.y0; j < tile.y1; ++j) {
        for (int i = tile.x0; i < tile.x1; ++i) {
            const Vec2 uv = image_plane_point(i, j, image.width, image.height);
            image.set(i, j, radiance(uv));
        }
    }
}

}  // namespace raylab::reference
