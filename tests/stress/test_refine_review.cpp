// The refinement of hit points (framework/src/refine.cpp) on far, huge and thin
// triangles, on both paths (the engine's own refined point, PrimRef::refined, is tested
// in engine/tests/test_engine.cpp); each case failed before its mend. Each expected point
// is the exact intersection of the float ray with the plane of the float vertices (Python
// fractions), rounded to float. The bound is the one raylab/refine.h promises: delta =
// 2^-23 max|x_i|.
#include <doctest/doctest.h>

#include <optional>

#include "raylab/engine.h"
#include "raylab/modules.h"
#include "raylab/scene.h"
#include "test_helpers.h"

using namespace raylab;

namespace {

Vec3 hex3(const char* x, const char* y, const char* z) {
    return Vec3(std::strtof(x, nullptr), std::strtof(y, nullptr),
                std::strtof(z, nullptr));
}

float max_abs(const Vec3& v) {
    return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

// Distance (max norm) from the exact point, in units of delta(exact)
float error_in_delta(const Vec3& got, const Vec3& exact) {
    return max_abs(got - exact) / (0x1p-23f * max_abs(exact));
}

Scene one_triangle(const Vec3& v0, const Vec3& v1, const Vec3& v2) {
    Scene s;
    s.materials.push_back(Material{"grey", Vec3(0.5f), Vec3(0.0f)});
    s.triangles.push_back(SceneTriangle{v0, v1, v2});
    return s;
}

// On both paths: the refined point within delta of the exact one, and with a light
// (above the surface) a shadow ray toward it that the surface itself does not stop
void check_both_paths(const Scene& s, const Ray& r, const Vec3& exact,
                      const std::optional<Vec3>& light = std::nullopt) {
    for (const ModuleTable& m : {engine_table(), module_path_table()}) {
        INFO((m.engine ? "engine path" : "module path"));
        TraceCounters c;
        const auto h = s.closest_hit(m, r, c);
        REQUIRE(h.has_value());
        CHECK(error_in_delta(h->position, exact) <= 1.0f);
        if (!light) continue;
        const SceneOccluder occluder(s, m, c);
        const LightSample ls =
            m.sample_point_light(PointLight{*light, Vec3(1.0f)}, h->position);
        REQUIRE(glm::dot(ls.wi, h->ns) > 0.0f);
        CHECK_FALSE(m.in_shadow(occluder, h->position, h->ns, ls));  // acne
    }
}

// Two vertices 2^35 from the origin, and a ray that passes near it, shared by the cases
// of triangles far larger than the distance of their hit from the origin
Vec3 far_v0() {
    return hex3("0x1.831c2p+34", "0x1.43d012p+35", "0x1.af6ce2p+34");
}
Vec3 far_v1() {
    return hex3("0x1.2773e6p+34", "-0x1.16b0d4p+35", "0x1.4960e6p+34");
}
Ray ray_near_origin() {
    return Ray{hex3("0x1.37c0cep+2", "0x1.29dba6p+2", "-0x1.b109dp-3"),
               hex3("-0x1.71c644p-1", "-0x1.61c214p-1", "0x1.04f7aep-5"), 0.0f,
               kInfinity};
}

}  // namespace

TEST_SUITE("refine") {
    TEST_CASE("refinement: a huge triangle seen near the origin (both paths)") {
        // |v| ~ 2^35, |x| ~ 0.83: k = v0 . n rounds at u |v0| |n|, so the refined point
        // was 45 delta from the exact point and 35 delta below the plane, seen from the
        // camera, and shadowed itself (the engine falls back: its dt is large). The
        // offset is now taken at the vertex nearest x (v2, 2^30 away)
        Scene s =
            one_triangle(far_v0(), far_v1(),
                         hex3("-0x1.ad49aap+30", "-0x1.ee7ef4p+30", "-0x1.de741cp+30"));
        // A small triangle next to the hit, in the same plane (vertices rounded to float,
        // within 1e-7 of it), where the shadow ray from 35 delta below crosses the plane
        s.triangles.push_back(
            SceneTriangle{hex3("-0x1.a8410cp-1", "-0x1.990faep-1", "0x1.47a85ep-5"),
                          hex3("-0x1.a83f12p-1", "-0x1.98fffap-1", "0x1.47cb98p-5"),
                          hex3("-0x1.a83056p-1", "-0x1.990c44p-1", "0x1.48d282p-5")});
        s.commit();
        check_both_paths(s, ray_near_origin(),
                         hex3("-0x1.a84464p-1", "-0x1.99069ap-1", "0x1.476cc4p-5"),
                         hex3("0x1.7d8664p+2", "-0x1.531fa4p+1", "0x1.c93c8ap+2"));
    }

    TEST_CASE("refinement: every vertex 2^35 away, the hit at 0.006 (both paths)") {
        // The triangle above with a third vertex 2^35 away, chosen (by a search over
        // exact planes) so that the plane passes 0.0025 from the origin: the hit lies
        // 0.006 from it. In double the plane there is known to about 2^-52 2^35 = 2^-17,
        // thousands of delta; the offset is computed in double-double
        const Vec3 far_v2 = hex3("-0x1.8c11d6p+35", "-0x1.4e242ap+32", "-0x1.b978bep+35");
        Scene s = one_triangle(far_v0(), far_v1(), far_v2);
        s.commit();
        // The light 10 above the plane, on the ray's side
        const Vec3 n = glm::normalize(glm::cross(far_v1() - far_v0(), far_v2 - far_v0()));
        const Vec3 exact = hex3("0x1.942eb4p-8", "-0x1.d48986p-13", "0x1.9c5508p-9");
        const float side = glm::dot(n, ray_near_origin().w) < 0.0f ? 10.0f : -10.0f;
        check_both_paths(s, ray_near_origin(), exact, exact + side * n + Vec3(3, 0, 0));
    }

    TEST_CASE("refinement: a sliver with one far vertex (both paths)") {
        // v0 2^18 away, the hit near v1 v2: cross(v1 - v0, v2 - v0) of two long, nearly
        // parallel edges cancels (n off by 1.3e-10 relative) and tilted the plane about
        // v0: the refined point was 21,809 delta from the exact point, 362 delta off the
        // plane (1.3e-3 in all, at |x| = 0.51; the module's float t is 3e-14 off). The
        // normal now comes from the edges at the vertex opposite the longest edge
        Scene s = one_triangle(hex3("-0x1.62a7bp+18", "0x1.f16bc6p+18", "0x1.9dc1f8p+17"),
                               hex3("-0x1.80f032p-2", "0x1.6e2b12p-1", "0x1.a0fdp-3"),
                               hex3("0x1.319fcap-1", "-0x1.3beba6p-2", "-0x1.271f68p-1"));
        s.commit();
        check_both_paths(s,
                         Ray{hex3("-0x1.bb5856p+3", "-0x1.38bb9ap+4", "0x1.f82e5ap+4"),
                             hex3("0x1.61a436p-2", "0x1.016288p-1", "-0x1.95bf7ep-1"),
                             0.0f, kInfinity},
                         hex3("-0x1.383812p-4", "0x1.054182p-1", "-0x1.b06c2ap-4"));
    }
}
