// The renderer against analytic answers, and the work it skips.
#include <algorithm>
#include <atomic>

#include <doctest/doctest.h>

#include "raylab/error.h"
#include "raylab/renderer.h"
#include "raylab/scenes.h"
#include "test_helpers.h"

using namespace raylab;

namespace {

// A grey Lambertian floor y = 0 under one point light, seen from above at an angle
Scene lit_plane(const Vec3& light_p, const Vec3& I) {
    Scene scene;
    scene.materials.push_back(Material{"floor", Vec3(0.8f, 0.5f, 0.25f), Vec3(0.0f)});
    scene.planes.push_back({Plane{Vec3(0.0f, 1.0f, 0.0f), 0.0f}, 0});
    scene.lights.push_back(PointLight{light_p, I});
    scene.view = View{Vec3(0.3f, 2.0f, 3.0f), Vec3(0.0f, 0.0f, 0.0f),
                      Vec3(0.0f, 1.0f, 0.0f), 50.0f};
    scene.commit();
    return scene;
}

}  // namespace

TEST_SUITE("render") {
    TEST_CASE(
        "a Lambertian plane under a point light matches rho/pi I cos(theta) / r^2") {
        // Expected radiance per pixel, computed independently in double precision from
        // the handouts' formulas: the camera ray through the pixel centre, the plane hit,
        // then L = rho / pi * I * cos(theta) / r^2 with cos(theta) = n . (p - x) / r
        const Vec3 light_p(0.4f, 1.5f, -0.2f), I(3.0f, 2.0f, 1.0f);
        const Scene scene = lit_plane(light_p, I);
        RenderSettings settings;
        settings.width = 160;
        settings.height = 120;
        Image image;
        const FrameStats stats =
            render(scene, scene.view, settings, reference_modules(), image);
        REQUIRE(stats.non_finite_pixels == 0);

        const DVec3 eye(scene.view.eye), lookat(scene.view.lookat), up(scene.view.up);
        const DVec3 n = glm::normalize(lookat - eye);
        const DVec3 x = glm::normalize(glm::cross(n, up));
        const DVec3 y = glm::cross(x, n);
        const double d =
            0.5 / std::tan(0.5 * scene.view.fov * 3.14159265358979323846 / 180.0);
        const double W = settings.width, H = settings.height;
        const DVec3 rho(scene.materials[0].rho);
        // Relative error allowed per pixel: float32 rays and hit points carry about 1e-7
        // relative error, amplified a few times by cos / r^2
        const double kRelativeTolerance = 1e-5;
        double worst = 0.0;
        int lit_pixels = 0;
        for (int j = 0; j < settings.height; ++j) {
            for (int i = 0; i < settings.width; ++i) {
                const double u = ((i + 0.5) / W - 0.5) * (W / H), v = 0.5 - (j + 0.5) / H;
                const DVec3 w = glm::normalize(u * x + v * y + d * n);
                DVec3 expected(0.0);
                if (w.y < 0.0) {
                    const DVec3 hit = eye + (-eye.y / w.y) * w;
                    const DVec3 to_light = DVec3(light_p) - hit;
                    const double r = glm::length(to_light);
                    const double cos_theta = to_light.y / r;
                    expected =
                        rho / 3.14159265358979323846 * DVec3(I) * cos_theta / (r * r);
                    ++lit_pixels;
                }
                const DVec3 got(image.at(i, j));
                for (int c = 0; c < 3; ++c) {
                    const double err =
                        std::abs(got[c] - expected[c]) / std::max(expected[c], 1e-30);
                    worst = std::max(worst, expected[c] > 0.0 ? err : std::abs(got[c]));
                }
            }
        }
        INFO("worst relative error " << worst);
        CHECK(lit_pixels > settings.width * settings.height / 2);
        CHECK(worst < kRelativeTolerance);
        MESSAGE("lit plane: worst relative error " << worst << " over " << lit_pixels
                                                   << " lit pixels");
    }

    TEST_CASE(
        "the Cornell box renders finite, with shadows exactly where the light is "
        "blocked") {
        const Scene box = cornell_box();
        RenderSettings settings;
        settings.width = 128;
        settings.height = 96;
        Image image;
        const ModuleTable& m = reference_modules();
        const FrameStats stats = render(box, box.view, settings, m, image);
        CHECK(stats.non_finite_pixels == 0);
        CHECK(stats.camera_rays == 128u * 96u);
        // For every pixel that sees a surface facing the light, the pixel is black
        // exactly when the segment from its hit point to the light is blocked (checked by
        // brute force here)
        int shadowed = 0, lit = 0, mismatched = 0;
        const PointLight& light = box.lights[0];
        for (int j = 0; j < settings.height; ++j) {
            for (int i = 0; i < settings.width; ++i) {
                const PixelProbe p = probe_pixel(box, box.view, settings, m, i, j);
                if (!p.hit) continue;  // outside the box
                const Vec3 to_light = light.p - p.hit->position;
                if (glm::dot(p.hit->ns, to_light) <= 0.0f) continue;
                bool blocked = false;
                for (const SceneTriangle& t : box.triangles) {
                    const Vec3 o = p.hit->position + 1e-3f * p.hit->ns;
                    const Ray r{o, glm::normalize(light.p - o), 1e-3f,
                                glm::length(light.p - o) - 1e-3f};
                    blocked =
                        blocked || m.intersect_triangle(r, t.v0, t.v1, t.v2).has_value();
                }
                const bool black = image.at(i, j) == Vec3(0.0f);
                (blocked ? shadowed : lit) += 1;
                if (black != blocked) ++mismatched;
            }
        }
        INFO("shadowed " << shadowed << ", lit " << lit << ", mismatched " << mismatched);
        CHECK(shadowed > 200);  // the blocks cast visible shadows on the floor and walls
        CHECK(lit > 5000);
        // Pixels right at a shadow edge may differ by the two tests' offsets
        CHECK(mismatched < shadowed / 100 + 3);
    }

    TEST_CASE("no shadow rays with shadows off or with the light behind the surface") {
        Scene box = cornell_box();
        RenderSettings settings;
        settings.width = 64;
        settings.height = 48;
        Image image;
        settings.shadows = false;
        FrameStats stats = render(box, box.view, settings, reference_modules(), image);
        CHECK(stats.shadow_rays == 0);
        CHECK(stats.shadow_rays_disabled > 0);
        settings.shadows = true;
        stats = render(box, box.view, settings, reference_modules(), image);
        CHECK(stats.shadow_rays > 0);
        // Every camera ray that hits either casts one shadow ray or skips it for a reason
        settings.mode = ShadingMode::base;
        Image base;
        render(box, box.view, settings, reference_modules(), base);
        settings.mode = ShadingMode::lambert;
        const auto hits = static_cast<std::uint64_t>(
            std::count_if(base.pixels.begin(), base.pixels.end(),
                          [](const Vec3& p) { return p != Vec3(0.0f); }));
        CHECK(hits > stats.camera_rays / 2);
        CHECK(stats.shadow_rays + stats.shadow_rays_backfacing == hits);
        box.lights.clear();
        stats = render(box, box.view, settings, reference_modules(), image);
        CHECK(stats.shadow_rays == 0);
        CHECK(stats.shadow_rays_backfacing == 0);
        // A light under the floor lights only the floor's back: no shadow ray is cast
        const Scene floor = lit_plane(Vec3(0.0f, -1.0f, 0.0f), Vec3(1.0f));
        stats = render(floor, floor.view, settings, reference_modules(), image);
        CHECK(stats.shadow_rays == 0);
        CHECK(stats.shadow_rays_backfacing > stats.camera_rays / 2);
    }

    TEST_CASE("thread count does not change the image or the work counts") {
        for (const Scene& scene : {dtu_scene(), cornell_box()}) {
            INFO("scene " << scene.name);
            RenderSettings settings;
            // Not a multiple of the tile size; large enough that tiles end on shadow
            // rays that something blocks
            settings.width = 641;
            settings.height = 481;
            Image one, many;
            settings.threads = 1;
            const FrameStats a =
                render(scene, scene.view, settings, reference_modules(), one);
            settings.threads = 3;
            const FrameStats b =
                render(scene, scene.view, settings, reference_modules(), many);
            CHECK(one.pixels == many.pixels);
            // Each tile starts its shadow rays without a hint (AnyHitHint), whichever
            // thread rendered which tile before (a hint that crossed tiles made the
            // counts change from run to run)
            CHECK(a.intersection_tests == b.intersection_tests);
            CHECK(a.bvh_nodes == b.bvh_nodes);
        }
    }

    TEST_CASE("shading modes show normals, base colour and depth") {
        const Scene scene = lit_plane(Vec3(0.0f, 1.0f, 0.0f), Vec3(1.0f));
        RenderSettings settings;
        settings.width = 32;
        settings.height = 24;
        Image image;
        settings.mode = ShadingMode::normals;
        render(scene, scene.view, settings, reference_modules(), image);
        // Bottom row sees the floor: normal (0, 1, 0) maps to (0.5, 1, 0.5)
        CHECK(image.at(16, 23) == Vec3(0.5f, 1.0f, 0.5f));
        settings.mode = ShadingMode::base;
        render(scene, scene.view, settings, reference_modules(), image);
        CHECK(image.at(16, 23) == scene.materials[0].rho);
        settings.mode = ShadingMode::depth;
        render(scene, scene.view, settings, reference_modules(), image);
        // Nearer is brighter
        CHECK(image.at(16, 23).x > image.at(16, 12).x);
        CHECK(image.at(16, 12).x >= 0.0f);
    }

    TEST_CASE("bad settings are rejected before any work") {
        const Scene scene = dtu_scene();
        Image image;
        RenderSettings settings;
        for (auto [w, h] : {std::pair{0, 10}, {10, -1}, {100000, 10}, {16384, 16384}}) {
            settings.width = w;
            settings.height = h;
            INFO(settings.width << "x" << settings.height);
            CHECK_THROWS_WITH_AS(
                render(scene, scene.view, settings, reference_modules(), image),
                doctest::Contains("resolution"), Error);
        }
    }

    TEST_CASE("a raised cancel flag stops the render early") {
        const Scene scene = dtu_scene();
        std::atomic<bool> cancel{true};
        RenderSettings settings;
        settings.cancel = &cancel;
        Image image;
        const FrameStats stats =
            render(scene, scene.view, settings, reference_modules(), image);
        CHECK(stats.cancelled);
        CHECK(stats.camera_rays == 0);
    }
}
