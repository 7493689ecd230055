// Whole scenes far from the origin: the image must not fall apart.
#include <doctest/doctest.h>

#include "raylab/renderer.h"
#include "raylab/scenes.h"
#include "test_helpers.h"

using namespace raylab;

namespace {

// Fraction of pixels whose value differs from the reference by more than 2% of its range
double fraction_different(const Image& a, const Image& b) {
    size_t different = 0;
    for (size_t k = 0; k < a.pixels.size(); ++k) {
        const Vec3 d = glm::abs(a.pixels[k] - b.pixels[k]);
        const float m = std::max({a.pixels[k].x, a.pixels[k].y, a.pixels[k].z, 1e-3f});
        if (std::max({d.x, d.y, d.z}) > 0.02f * m) ++different;
    }
    return double(different) / double(a.pixels.size());
}

}  // namespace

TEST_SUITE("stress scene") {
    TEST_CASE("the Cornell box moved far from the origin renders like the original") {
        const Scene box = cornell_box();
        RenderSettings settings;
        settings.width = 160;
        settings.height = 120;
        Image near, far;
        render(box, box.view, settings, reference_modules(), near);
        // At 1e5 the box is only 256 ulps wide (ulp(1e5) = 1/128): its float vertices are
        // visibly quantised and about 4% of pixels change, a limit of float32 input
        // itself
        for (const float D : {1e2f, 1e3f, 1e4f}) {
            const Scene moved = translated(box, Vec3(D, -0.5f * D, 0.3f * D));
            const FrameStats stats =
                render(moved, moved.view, settings, reference_modules(), far);
            INFO("D = " << D);
            CHECK(stats.non_finite_pixels == 0);
            // Float positions near D carry errors of ulp(D) ~ D * 6e-8: only pixels on
            // edges and shadow boundaries may change. No acne: lit surfaces stay lit
            const double diff = fraction_different(near, far);
            MESSAGE("Cornell box at " << D << ": " << 100.0 * diff
                                      << "% of pixels differ by >2%");
            CHECK(diff < 0.01);
        }
    }

    TEST_CASE("an open plane under a light has no shadow acne, near or far") {
        for (const float D : {0.0f, 1e3f, 1e4f, 1e5f}) {
            Scene scene;
            scene.materials.push_back(Material{"floor", Vec3(0.5f), Vec3(0.0f)});
            scene.planes.push_back(
                {Plane{glm::normalize(Vec3(0.1f, 1.0f, 0.05f)), -D}, 0});
            const Vec3 n = scene.planes[0].plane.n;
            scene.lights.push_back(
                PointLight{n * D + Vec3(0.0f, 2.0f, 0.0f), Vec3(4.0f)});
            scene.commit();
            const ModuleTable& m = reference_modules();
            TraceCounters counters;
            const SceneOccluder occluder(scene, m, counters);
            Rng rng(static_cast<std::uint64_t>(D) + 3);
            int acne = 0;
            for (int k = 0; k < 5000; ++k) {
                // A camera-like ray from above hitting the plane; shade its hit
                const Vec3 o = n * (D + 1.5f) + rng.in_box(-3.0f, 3.0f);
                const Vec3 target = n * D + rng.in_box(-5.0f, 5.0f);
                const Ray r{o, glm::normalize(target - o), 0.0f, kInfinity};
                const auto hit = scene.closest_hit(m, r, counters);
                if (!hit) continue;
                const LightSample ls =
                    m.sample_point_light(scene.lights[0], hit->position);
                if (glm::dot(ls.wi, hit->ns) <= 0.0f) continue;
                if (m.in_shadow(occluder, hit->position, hit->ns, ls)) ++acne;
            }
            INFO("D = " << D << ": " << acne
                        << " of 5000 points shadowed by their own plane");
            CHECK(acne == 0);
        }
    }
}
