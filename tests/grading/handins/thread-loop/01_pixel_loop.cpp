// A correct pixel loop run on a std::thread: the worker starts no threads, and the report
// must say so instead of a bare "Resource temporarily unavailable".
#include <thread>

#include "raylab/contract.h"

#define render_tile honest_render_tile
// RAYLAB-HONEST-CODE 01_pixel_loop
#undef render_tile

namespace raylab::student {
void render_tile(const Tile& tile, const PixelRadiance& radiance, const ImageView& image) {
    std::thread worker([&] { honest_render_tile(tile, radiance, image); });
    worker.join();
}
}  // namespace raylab::student
