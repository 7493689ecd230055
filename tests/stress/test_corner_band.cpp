// The known limit of the shadow offset at concave corners (handout 08 §3, "Concave
// corners"; docs/architecture.md, hit refinement): a floor point within about
// 4 delta / tan(alpha) of a crease of interior angle alpha starts its shadow ray behind
// the other face, which then blocks it. The band's width is held to that bound, and
// points farther out are never shadowed.
#include <cmath>

#include <doctest/doctest.h>

#include "test_helpers.h"

using namespace raylab;

namespace {

struct Band {
    double widest = 0.0;  // the farthest falsely shadowed point from the crease, in delta
    int shadowed = 0, tested = 0;
};

// A floor y = 0 (x >= 1) and a wall rising from the crease x = 1 at interior angle
// alpha, a light inside the wedge that both faces see: nothing blocks any floor point,
// and every shadow is false
Band corner_band(double alpha_degrees, const ModuleTable& m) {
    const double a = alpha_degrees * 3.14159265358979323846 / 180.0;
    const float L = 10.0f;
    const Vec3 c(1.0f, 0.0f, 0.0f);  // on the crease: delta there is 2^-23
    const Vec3 up(float(std::cos(a)), float(std::sin(a)), 0.0f);
    Scene scene;
    scene.materials.push_back(Material{});
    const Vec3 f0 = c + Vec3(0, 0, -L), f1 = c + Vec3(0, 0, L);
    scene.triangles.push_back({f0, f1, f0 + Vec3(L, 0, 0)});
    scene.triangles.push_back({f1, f1 + Vec3(L, 0, 0), f0 + Vec3(L, 0, 0)});
    scene.triangles.push_back({f0, f0 + L * up, f1});
    scene.triangles.push_back({f1, f0 + L * up, f1 + L * up});
    scene.commit();
    const Vec3 mid(float(std::cos(a / 2)), float(std::sin(a / 2)), 0.0f);
    const PointLight light{c + 2.0f * mid + Vec3(0.0f, 0.0f, 0.3f), Vec3(1.0f)};
    TraceCounters counters;
    SceneOccluder occluder(scene, m, counters);
    Band band;
    const double delta = 0x1p-23;
    const double reach =
        std::max(4.0 / std::tan(a), 0.0) + 8.0;  // in delta: the bound and more
    Rng rng(7);
    for (int k = 0; k < 4000; ++k) {
        const double s = reach * delta * rng.uniform(0.0f, 2.0f);
        const Vec3 x(float(1.0 + s), 0.0f, rng.uniform(-1.0f, 1.0f));
        const double from_crease = (double(x.x) - 1.0) / delta;
        if (!(from_crease > 0.0)) continue;
        ++band.tested;
        const LightSample sample = m.sample_point_light(light, x);
        if (m.in_shadow(occluder, x, Vec3(0, 1, 0), sample)) {
            ++band.shadowed;
            band.widest = std::max(band.widest, from_crease);
        }
    }
    return band;
}

}  // namespace

TEST_SUITE("stress corner band") {
    TEST_CASE(
        "false shadows at a concave corner stay within 4 delta / tan(alpha) + delta") {
        for (const ModuleTable& m : {engine_table(), module_path_table()})
            for (const double alpha : {2.0, 10.0, 45.0, 90.0, 135.0, 179.0}) {
                const Band b = corner_band(alpha, m);
                const double bound =
                    4.0 / std::tan(alpha * 3.14159265358979323846 / 180.0);
                MESSAGE("alpha " << alpha << " ("
                                 << std::string(m.engine ? "engine" : "module path")
                                 << "): " << b.shadowed << " of " << b.tested
                                 << " floor points shadowed, the farthest " << b.widest
                                 << " delta from the crease");
                INFO("alpha " << alpha);
                CHECK(b.tested > 3000);
                CHECK(b.widest <= std::max(bound, 0.0) + 1.0);
            }
    }
}
