// The handouts' "if you see X, check Y" claims, each rendered from a mutant of the
// reference with mistake Y: the image must show X. Handout 01's hints and handout 02 §1
// (docs/handouts/): upside down, mirrored, turned 180 degrees, squeezed.
#include <algorithm>
#include <cmath>

#include <doctest/doctest.h>

#include "raylab/image.h"
#include "raylab/renderer.h"
#include "raylab/scenes.h"
#include "test_helpers.h"

using namespace raylab;

namespace {

constexpr int W = 96, H = 64;

// Module 01 with v of the wrong sign
Vec2 v_negated(int i, int j, int w, int h) {
    const Vec2 p = reference::image_plane_point(i, j, w, h);
    return Vec2(p.x, -p.y);
}
// Module 01 with u of the wrong sign
Vec2 u_negated(int i, int j, int w, int h) {
    const Vec2 p = reference::image_plane_point(i, j, w, h);
    return Vec2(-p.x, p.y);
}
// Module 01 with u missing the aspect factor a = W / H (divided by W instead of H)
Vec2 u_without_aspect(int i, int j, int w, int h) {
    const Vec2 p = reference::image_plane_point(i, j, w, h);
    return Vec2(p.x * float(h) / float(w), p.y);
}
// Module 01's render_tile calling the mutant's own image_plane_point, as a student's does
template <Vec2 (*point)(int, int, int, int)>
void tile_with(const Tile& tile, const PixelRadiance& radiance, const ImageView& image) {
    for (int j = tile.y0; j < tile.y1; ++j)
        for (int i = tile.x0; i < tile.x1; ++i)
            image.set(i, j, radiance(point(i, j, image.width, image.height)));
}

// Module 02 with x = u x n (y = x x n as the handout says): handout 02 §1
CameraFrame x_from_u_cross_n(const Vec3& eye, const Vec3& lookat, const Vec3& up) {
    const Vec3 n = glm::normalize(lookat - eye);
    const Vec3 x = glm::normalize(glm::cross(up, n));
    return {x, glm::cross(x, n), n};
}
// Module 02 with y = n x x
CameraFrame y_from_n_cross_x(const Vec3& eye, const Vec3& lookat, const Vec3& up) {
    const Vec3 n = glm::normalize(lookat - eye);
    const Vec3 x = glm::normalize(glm::cross(n, up));
    return {x, glm::cross(n, x), n};
}
// Module 02 with both orders swapped: x = u x n, y = n x x
CameraFrame both_swapped(const Vec3& eye, const Vec3& lookat, const Vec3& up) {
    const Vec3 n = glm::normalize(lookat - eye);
    const Vec3 x = glm::normalize(glm::cross(up, n));
    return {x, glm::cross(n, x), n};
}

Image render_with(const ModuleTable& m, const Scene& scene, int w, int h) {
    RenderSettings settings;
    settings.width = w;
    settings.height = h;
    settings.mode = ShadingMode::base;
    Image image;
    render(scene, scene.view, settings, m, image);
    return image;
}

float largest(const Vec3& a, const Vec3& b) {
    const Vec3 d = glm::abs(a - b);
    return std::max({d.x, d.y, d.z});
}

// Pixels where a and b differ, b read turned as flip_h and flip_v say
int differing(const Image& a, const Image& b, bool flip_h, bool flip_v) {
    int count = 0;
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i)
            count += largest(a.at(i, j), b.at(flip_h ? W - 1 - i : i,
                                              flip_v ? H - 1 - j : j)) > 1e-3f;
    return count;
}

enum class Shows { upside_down, mirrored, turned_180 };

// The mutant's image is the reference's turned as `shows` says, and not the reference's
// own or any other turn of it. A turned ray visits the BVH in another order, so where
// two walls meet at the same t (an edge of the box) the other wall may win: a few pixels
void check_shows(const ModuleTable& mutant, Shows shows) {
    const Scene box = cornell_box();
    const Image want = render_with(engine_table(), box, W, H);
    const Image got = render_with(mutant, box, W, H);
    const bool h = shows != Shows::upside_down, v = shows != Shows::mirrored;
    CHECK(differing(got, want, h, v) <= W * H / 200);
    // The Cornell box has no symmetry that hides a turn: every other one differs
    for (int k = 0; k < 4; ++k) {
        const bool fh = k & 1, fv = k & 2;
        if (fh == h && fv == v) continue;
        CHECK(differing(got, want, fh, fv) >= W * H / 5);
    }
}

}  // namespace

TEST_SUITE("handout claims") {
    TEST_CASE(
        "handout 01: v of the wrong sign turns the image upside down, not mirrored") {
        ModuleTable m = engine_table();
        m.image_plane_point = v_negated;
        m.render_tile = tile_with<v_negated>;
        check_shows(m, Shows::upside_down);
    }

    TEST_CASE("handout 01: u of the wrong sign mirrors the image") {
        ModuleTable m = engine_table();
        m.image_plane_point = u_negated;
        m.render_tile = tile_with<u_negated>;
        check_shows(m, Shows::mirrored);
    }

    TEST_CASE("handout 02 §1: x = u x n (with y = x x n) turns the image 180 degrees") {
        ModuleTable m = engine_table();
        m.camera_frame = x_from_u_cross_n;
        check_shows(m, Shows::turned_180);
    }

    TEST_CASE("handout 02 §1: y = n x x turns the image upside down") {
        ModuleTable m = engine_table();
        m.camera_frame = y_from_n_cross_x;
        check_shows(m, Shows::upside_down);
    }

    TEST_CASE("handout 02 §1: x = u x n and y = n x x mirror the image") {
        ModuleTable m = engine_table();
        m.camera_frame = both_swapped;
        check_shows(m, Shows::mirrored);
    }

    TEST_CASE("handout 01: u without the aspect factor squeezes the image sideways") {
        // Pixel i of the mutant sees what the reference's pixel at u * H / W sees: the
        // box's middle third spread over the whole width. At width 3 H the mutant's
        // column 3 k + 1 is the reference's column k + H
        const Scene box = cornell_box();
        ModuleTable m = engine_table();
        m.image_plane_point = u_without_aspect;
        m.render_tile = tile_with<u_without_aspect>;
        const Image want = render_with(engine_table(), box, 3 * H, H);
        const Image got = render_with(m, box, 3 * H, H);
        // u is rounded another way: a pixel on an edge may see the other side of it
        int differ = 0, differ_plain = 0;
        for (int j = 0; j < H; ++j)
            for (int k = 0; k < H; ++k) {
                differ += largest(got.at(3 * k + 1, j), want.at(k + H, j)) > 1e-3f;
                differ_plain +=
                    largest(got.at(3 * k + 1, j), want.at(3 * k + 1, j)) > 1e-3f;
            }
        CHECK(differ <= H * H / 50);
        CHECK(differ_plain >= H * H / 5);
    }
}
