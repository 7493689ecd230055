// Module 01_pixel_loop: the loop over the pixels (docs/handouts/01_pixel_loop.md).
//
// Your work is the two functions below; `grep -n "TODO(student)" exercises/` lists every
// step. Delete a function's RAYLAB_STUB line when you start on that function: while a
// module's functions still call it, the viewer runs the reference for that module and the
// graders report it as not started.
#include "raylab/contract.h"

namespace raylab::student {

/// Image-plane point (u, v) of the centre of pixel (i, j) in a W x H image (handout 01
/// §2):
///   u = ((i + 1/2) / W - 1/2) * W / H,   v = 1/2 - (j + 1/2) / H.
/// Row j = 0 is the top of the image, so v decreases as j grows.
Vec2 image_plane_point(int i, int j, int W, int H) {
    // TODO(student) 01_pixel_loop: Pixel centre in [0, 1]^2, measured from the top-left
    //   corner: s = (i + 1/2) / W, q = (j + 1/2) / H (in float: beware integer division)
    // TODO(student) 01_pixel_loop: Image-plane units: the visible height is 1, the
    //   width is the aspect ratio aspect = W / H; return ((s - 1/2) * aspect, 1/2 - q)
    RAYLAB_STUB("01_pixel_loop");
    (void)i, (void)j, (void)W, (void)H;
    return Vec2(0.0f);
}

/// Calls radiance once per pixel (i, j) of tile at its centre and stores the result
/// (handout 01 §3). The tile covers columns [x0, x1) and rows [y0, y1) of the whole
/// image; the framework hands each thread its own tiles.
void render_tile(const Tile& tile, const PixelRadiance& radiance,
                 const ImageView& image) {
    // TODO(student) 01_pixel_loop: Rows top to bottom, columns left to right: for every
    //   pixel (i, j) of the tile, uv = image_plane_point(i, j, image.width,
    //   image.height), then image.set(i, j, radiance(uv))
    RAYLAB_STUB("01_pixel_loop");
    (void)tile, (void)radiance, (void)image;
}

}  // namespace raylab::student
