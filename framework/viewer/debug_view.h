// viewer/debug_view.h: the 3D debug view, a window that rasterises the scene with OpenGL
// 3.3 (triangles, spheres as low-poly meshes, planes as large quads, lights as markers)
// and draws the pinned pixel's camera ray, normal and shadow rays as lines; drag orbits.
#pragma once

#include <cstdint>
#include <vector>

namespace raylab::viewer {

struct Viewer;

/// GL objects and the orbit of the debug view (one per viewer).
struct DebugView {
    bool open = false;
    float yaw = 0.6f, pitch = 0.35f, zoom = 1.0f;  ///< orbit about the scene's centre
    unsigned program = 0, vao = 0, vbo = 0, fbo = 0, colour = 0, depth = 0;
    int width = 0, height = 0;    ///< of the offscreen target
    std::uint64_t version = 0;    ///< scene version the mesh was built from
    int scene_vertices = 0;       ///< triangles' vertices at the front of the buffer
    std::vector<float> vertices;  ///< x y z r g b, triangles then lines
};

/// The "3D debug view" window (opened from the panel); draws nothing when closed.
void debug_view_window(Viewer& v);

/// Frees the GL objects (before the context goes).
void debug_view_free(DebugView& d);

}  // namespace raylab::viewer
