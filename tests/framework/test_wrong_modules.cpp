// A wrong intersection module shows in the image, the compare view and the pixel
// inspector as it computed its hit: the scene's refinement (raylab/refine.h) repairs
// rounding only, never a student's mistake. Each mutant is the reference's module with
// one mistake, rendered on the module path against the reference.
#include <cmath>
#include <cstdint>

#include <doctest/doctest.h>

#include "raylab/image.h"
#include "raylab/renderer.h"
#include "raylab/scenes.h"
#include "test_helpers.h"

using namespace raylab;

namespace {

std::optional<Hit> ref_plane(const Ray& r, const Plane& p) {
    return reference::intersect_plane(r, p);
}
std::optional<Hit> ref_sphere(const Ray& r, const Sphere& s) {
    return reference::intersect_sphere(r, s);
}
std::optional<Hit> ref_triangle(const Ray& r, const Vec3& a, const Vec3& b,
                                const Vec3& c) {
    return reference::intersect_triangle(r, a, b, c);
}

// Triangle: the point 1e-3 off its plane, along the normal
std::optional<Hit> triangle_off_plane(const Ray& r, const Vec3& a, const Vec3& b,
                                      const Vec3& c) {
    auto hit = ref_triangle(r, a, b, c);
    if (hit) hit->position += 1e-3f * hit->n;
    return hit;
}
// Triangle: the point 0.3 % too far along the ray (t itself right)
std::optional<Hit> triangle_too_far(const Ray& r, const Vec3& a, const Vec3& b,
                                    const Vec3& c) {
    auto hit = ref_triangle(r, a, b, c);
    if (hit) hit->position = r.o + (1.003f * hit->t) * r.w;
    return hit;
}
// Plane: the point 2e-3 off the plane
std::optional<Hit> plane_off(const Ray& r, const Plane& p) {
    auto hit = ref_plane(r, p);
    if (hit) hit->position += 2e-3f * hit->n;
    return hit;
}
// Sphere: the normal tilted 25 degrees (still unit)
std::optional<Hit> sphere_tilted_normal(const Ray& r, const Sphere& s) {
    auto hit = ref_sphere(r, s);
    if (hit) {
        const Vec3 n = hit->n;
        const Vec3 e = std::abs(n.x) < 0.9f ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
        const Vec3 side = glm::normalize(glm::cross(n, e));
        const float a = glm::radians(25.0f);
        hit->n = std::cos(a) * n + std::sin(a) * side;
    }
    return hit;
}
// Sphere: a normal of length 1.04
std::optional<Hit> sphere_long_normal(const Ray& r, const Sphere& s) {
    auto hit = ref_sphere(r, s);
    if (hit) hit->n *= 1.04f;
    return hit;
}

std::optional<Hit> no_plane(const Ray&, const Plane&) {
    return std::nullopt;
}
std::optional<Hit> no_sphere(const Ray&, const Sphere&) {
    return std::nullopt;
}
std::optional<Hit> no_triangle(const Ray&, const Vec3&, const Vec3&, const Vec3&) {
    return std::nullopt;
}

struct Difference {
    int hit = 0;        // pixels that see the mutated kind of primitive
    int any = 0;        // pixels whose radiance differs at all
    int visible = 0;    // pixels whose 8-bit sRGB value differs (exposure 0)
    int inspected = 0;  // of those that see the kind, pixels whose inspected hit is wrong
};

// The scene rendered with `mutated` on the module path against the reference's render;
// `without` is the reference's table without the mutated kind of primitive
Difference render_difference(const Scene& scene, const ModuleTable& mutated,
                             const ModuleTable& without) {
    RenderSettings settings;
    settings.width = 160;
    settings.height = 120;
    settings.threads = 1;
    Image want, got;
    render(scene, scene.view, settings, engine_table(), want);
    render(scene, scene.view, settings, mutated, got);
    const std::vector<std::uint8_t> a = to_srgb8(want, 0.0f), b = to_srgb8(got, 0.0f);
    Difference d;
    for (size_t k = 0; k < want.pixels.size(); ++k) {
        d.any += want.pixels[k] != got.pixels[k];
        d.visible += a[3 * k] != b[3 * k] || a[3 * k + 1] != b[3 * k + 1] ||
                     a[3 * k + 2] != b[3 * k + 2];
    }
    for (int j = 0; j < settings.height; ++j)
        for (int i = 0; i < settings.width; ++i) {
            const auto a = probe_pixel(scene, scene.view, settings, engine_table(), i, j);
            const auto b = probe_pixel(scene, scene.view, settings, without, i, j);
            if (!a.hit || (b.hit && b.hit->t == a.hit->t)) continue;
            ++d.hit;
            // The inspector (probe_pixel) shows the module's point and normal
            const auto m = probe_pixel(scene, scene.view, settings, mutated, i, j);
            const float moved = glm::length(m.hit->position - a.hit->position);
            const float turned = glm::length(m.hit->n - a.hit->n);
            d.inspected += moved > 5e-4f || turned > 1e-3f;
        }
    return d;
}

}  // namespace

TEST_SUITE("wrong modules") {
    TEST_CASE(
        "a wrong intersection module's error shows in the image and the inspector") {
        const Scene box = cornell_box();
        const Scene dtu = dtu_scene();
        struct Case {
            const char* name;
            const Scene& scene;
            ModuleTable table;
            ModuleTable without;
        };
        ModuleTable t = module_path_table();
        ModuleTable off = t, far = t, plane = t, tilted = t, longer = t;
        off.intersect_triangle = triangle_off_plane;
        far.intersect_triangle = triangle_too_far;
        plane.intersect_plane = plane_off;
        tilted.intersect_sphere = sphere_tilted_normal;
        longer.intersect_sphere = sphere_long_normal;
        ModuleTable no_p = t, no_s = t, no_t = t;
        no_p.intersect_plane = no_plane;
        no_s.intersect_sphere = no_sphere;
        no_t.intersect_triangle = no_triangle;
        const Case cases[] = {
            {"triangle point 1e-3 off its plane", box, off, no_t},
            {"triangle point 0.3 % too far along the ray", box, far, no_t},
            {"plane point 2e-3 off", dtu, plane, no_p},
            {"sphere normal tilted 25 degrees", dtu, tilted, no_s},
            {"sphere normal of length 1.04", dtu, longer, no_s},
        };
        for (const Case& c : cases) {
            const Difference d = render_difference(c.scene, c.table, c.without);
            MESSAGE(std::string(c.name)
                    << ": " << d.any << " pixels differ, " << d.visible
                    << " visibly (8-bit), of " << d.hit << " that see it; " << d.inspected
                    << " inspected hits differ");
            INFO(std::string(c.name));
            // Most of what the wrong primitive covers, not a stray pixel or two
            CHECK(d.any >= d.hit / 2);
            // All but the plane's farthest points (t of hundreds near the horizon), where
            // 2e-3 is within the rounding of a correct module (refine.h)
            CHECK(d.inspected >= d.hit * 49 / 50);
        }
        // The reference's modules on the module path: the same image as the engine's
        const Difference same = render_difference(box, t, no_t);
        CHECK(same.any == 0);
    }
}
