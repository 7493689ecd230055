// Small helpers shared by the framework tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ostream>
#include <optional>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "raylab/contract.h"
#include "raylab/engine.h"
#include "raylab/modules.h"
#include "raylab/renderer.h"
#include "raylab/scene.h"

namespace raylab {

inline std::ostream& operator<<(std::ostream& os, const Vec3& v) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "(%.9g, %.9g, %.9g)", v.x, v.y, v.z);
    return os << buf;
}

inline std::ostream& operator<<(std::ostream& os, const Ray& r) {
    return os << "Ray{o=" << r.o << ", w=" << r.w << ", tmin=" << r.tmin
              << ", tmax=" << r.tmax << "}";
}

/// The table with every module switched to the reference. The scene's queries run in
/// the reference's engine (raylab/engine.h); with RAYLAB_TEST_PATH=module in the
/// environment they call the modules per primitive instead, so one test binary checks
/// both paths (tests/stress/CMakeLists.txt runs the stress suite both ways).
inline const ModuleTable& reference_modules() {
    static const ModuleTable table = [] {
        ModuleTable t = ModuleTable::make(ModuleSelection::all(Impl::reference));
        const char* path = std::getenv("RAYLAB_TEST_PATH");
        if (path && std::string(path) == "module") t.engine = nullptr;
        return t;
    }();
    return table;
}

/// True when this build has the geometry engine (RAYLAB_WITH_ENGINE, engine/README.md):
/// what only the engine does (packets, camera rays traced ahead) is tested only then.
inline bool engine_built() {
    return reference::geometry_engine() != nullptr;
}

/// Both paths side by side, whatever RAYLAB_TEST_PATH says: the reference's table with
/// its engine, and the same table calling the modules once per primitive test.
inline ModuleTable engine_table() {
    return ModuleTable::make(ModuleSelection::all(Impl::reference));
}
inline ModuleTable module_path_table() {
    ModuleTable t = engine_table();
    t.engine = nullptr;
    return t;
}

/// The engine's hit (a) against the module path's (b): the same hit, bit for bit, but
/// for the point. The engine computes a triangle's refined point from its t in double,
/// the module path from the plane: the same point within 2^-30 of its size, which rounds
/// to the same float but where that point lies within 2^-30 of a rounding boundary.
inline void check_same_hit(const std::optional<Hit>& a, const std::optional<Hit>& b) {
    REQUIRE(a.has_value() == b.has_value());
    if (!a) return;
    CHECK(a->t == b->t);
    const float size = std::max(
        {std::abs(b->position.x), std::abs(b->position.y), std::abs(b->position.z)});
    const Vec3 d = glm::abs(a->position - b->position);
    CHECK(std::max({d.x, d.y, d.z}) <= 0x1p-23f * size);
    CHECK(a->n == b->n);
    CHECK(a->ns == b->ns);
    CHECK(a->uv == b->uv);
    CHECK(a->material == b->material);
}

/// A small deterministic generator (PCG32, O'Neill 2014): tests print the seed they use.
class Rng {
  public:
    explicit Rng(std::uint64_t seed)
        : state_(seed * 6364136223846793005ull + 1442695040888963407ull) {}
    std::uint32_t next() {
        const std::uint64_t old = state_;
        state_ = old * 6364136223846793005ull + 1442695040888963407ull;
        const std::uint32_t shifted =
            static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
        const std::uint32_t rot = static_cast<std::uint32_t>(old >> 59u);
        return (shifted >> rot) | (shifted << ((32u - rot) & 31u));
    }
    /// Uniform in [lo, hi).
    float uniform(float lo, float hi) {
        return lo + (hi - lo) * (next() >> 8) * 0x1p-24f;
    }
    Vec3 in_box(float lo, float hi) {
        // One statement each: the order of a call's arguments is unspecified (g++ and
        // clang differ), and every compiler must draw the same cases
        const float x = uniform(lo, hi);
        const float y = uniform(lo, hi);
        return Vec3(x, y, uniform(lo, hi));
    }
    Vec3 direction() {
        for (;;) {
            const Vec3 v = in_box(-1.0f, 1.0f);
            const float l2 = glm::dot(v, v);
            if (l2 > 1e-4f && l2 <= 1.0f) return v / std::sqrt(l2);
        }
    }

  private:
    std::uint64_t state_;
};

/// Ray r on the engine (fast) and the module path (slow), closest and any hit; where it
/// hits, also a ray leaving the surface from the hit point in a random direction, as
/// shadow rays do (origins on a primitive take their own paths through the tests). True
/// when r hits.
inline bool check_both_paths(const Scene& scene, const ModuleTable& fast,
                             const ModuleTable& slow, const Ray& r, Rng& rng,
                             TraceCounters& cf, TraceCounters& cs) {
    INFO("ray " << r);
    const auto a = scene.closest_hit(fast, r, cf);
    check_same_hit(a, scene.closest_hit(slow, r, cs));
    CHECK(scene.any_hit(fast, r, cf) == scene.any_hit(slow, r, cs));
    if (!a) return false;
    const Ray leave{a->position, rng.direction(), 0.0f, kInfinity};
    INFO("leaving: " << leave);
    check_same_hit(scene.closest_hit(fast, leave, cf),
                   scene.closest_hit(slow, leave, cs));
    CHECK(scene.any_hit(fast, leave, cf) == scene.any_hit(slow, leave, cs));
    return true;
}

/// The same Hit to the bit (the packet must be the single-ray query, not close to it).
inline void check_identical(const std::optional<Hit>& a, const std::optional<Hit>& b) {
    REQUIRE(a.has_value() == b.has_value());
    if (!a) return;
    CHECK(std::memcmp(&a->t, &b->t, sizeof(float)) == 0);
    CHECK(a->position == b->position);
    CHECK(a->n == b->n);
    CHECK(a->ns == b->ns);
    CHECK(a->uv == b->uv);
    CHECK(a->material == b->material);
}

/// rays through Scene::closest_hits (packets, with the reference's engine) against each
/// through closest_hit, bit for bit; returns how many hit.
inline int check_packets(const Scene& scene, const std::vector<Ray>& rays,
                         TraceCounters& counters) {
    const ModuleTable modules = engine_table();
    std::vector<std::optional<Hit>> out(rays.size());
    scene.closest_hits(modules, rays.data(), static_cast<int>(rays.size()), counters,
                       out.data());
    int hits = 0;
    for (size_t k = 0; k < rays.size(); ++k) {
        INFO("ray " << k << ": " << rays[k]);
        TraceCounters single;
        const std::optional<Hit> one = scene.closest_hit(modules, rays[k], single);
        check_identical(out[k], one);
        hits += one.has_value();
    }
    return hits;
}

/// The reference camera's rays of a W x H image in blocks of 4 x 4 pixels (packets).
inline std::vector<Ray> camera_blocks(const View& view, int W, int H) {
    const ModuleTable m = engine_table();
    const PinholeCamera camera = make_camera(m, view);
    std::vector<Ray> rays;
    for (int by = 0; by < H; by += 4)
        for (int bx = 0; bx < W; bx += 4)
            for (int j = by; j < std::min(by + 4, H); ++j)
                for (int i = bx; i < std::min(bx + 4, W); ++i) {
                    Ray r = m.camera_ray(camera, m.image_plane_point(i, j, W, H));
                    r.w = r.w / glm::length(r.w);
                    rays.push_back(r);
                }
    return rays;
}

/// The scene moved by `by`, lights and view with it: far from the origin, where float
/// positions are coarse and the numerics matter
inline Scene translated(Scene scene, const Vec3& by) {
    for (ScenePlane& p : scene.planes)
        p.plane.d -= glm::dot(p.plane.n, by);
    for (SceneSphere& s : scene.spheres)
        s.sphere.c += by;
    for (SceneTriangle& t : scene.triangles)
        t.v0 += by, t.v1 += by, t.v2 += by;
    for (PointLight& l : scene.lights)
        l.p += by;
    scene.view.eye += by;
    scene.view.lookat += by;
    scene.commit();
    return scene;
}

}  // namespace raylab
