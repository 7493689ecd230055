// What the walk and slot copy tests share (test_walk.cpp, test_slot_copy.cpp): lattices
// of primitives whose box planes the rays lie in, random scenes at the slot copy's limit,
// the walks recorded leaf by leaf, and the engine against the module path ray by ray.
#pragma once

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "engine_test_data.h"
#include "engine_walk.h"
#include "raylab/bvh.h"
#include "raylab/error.h"
#include "test_engine_scenes.h"
#include "test_helpers.h"

namespace raylab::engine_cases {

namespace engine_kernels = reference::engine_kernels;

using Slot = SceneData::SlotPrimitive;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kDenorm = std::numeric_limits<float>::denorm_min();

inline bool same_bits(float a, float b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

// Equal, or both NaN, per component
inline bool same_vec(const Vec3& a, const Vec3& b) {
    for (int k = 0; k < 3; ++k)
        if (!(a[k] == b[k] || (std::isnan(a[k]) && std::isnan(b[k])))) return false;
    return true;
}

// check_same_hit, where a NaN on both sides counts as the same (rays with tmin = -inf
// at huge spheres give NaN points on both paths)
inline void check_same_hit_nan(const std::optional<Hit>& a, const std::optional<Hit>& b) {
    REQUIRE(a.has_value() == b.has_value());
    if (!a) return;
    CHECK(same_bits(a->t, b->t));
    float size = 0.0f;
    for (int k = 0; k < 3; ++k)
        size = std::fmax(size, std::abs(b->position[k]));
    INFO("engine point " << a->position.x << " " << a->position.y << " " << a->position.z
                         << ", module path point " << b->position.x << " "
                         << b->position.y << " " << b->position.z << ", t " << a->t);
    bool close = true;
    for (int k = 0; k < 3; ++k) {
        const float pa = a->position[k], pb = b->position[k];
        close &= pa == pb || (std::isnan(pa) && std::isnan(pb)) ||
                 std::abs(pa - pb) <= 0x1p-23f * size;
    }
    CHECK(close);
    CHECK(same_vec(a->n, b->n));
    CHECK(same_vec(a->ns, b->ns));
    CHECK(same_vec(Vec3(a->uv, 0.0f), Vec3(b->uv, 0.0f)));
    CHECK(a->material == b->material);
}

// One ray on both paths: the same hit (check_same_hit), the same any-hit answer, and the
// same counters for this ray alone (compare_paths only compares the totals)
inline void check_ray(const Scene& scene, const Ray& r) {
    static const ModuleTable fast = engine_table(), slow = module_path_table();
    INFO("ray " << r);
    TraceCounters cf, cs;
    const auto a = scene.closest_hit(fast, r, cf);
    const auto b = scene.closest_hit(slow, r, cs);
    check_same_hit_nan(a, b);
    CHECK(cf.intersection_tests == cs.intersection_tests);
    CHECK(cf.bvh_nodes == cs.bvh_nodes);
    TraceCounters af, as;
    CHECK(scene.any_hit(fast, r, af) == scene.any_hit(slow, r, as));
    CHECK(af.intersection_tests == as.intersection_tests);
    CHECK(af.bvh_nodes == as.bvh_nodes);
}

// Unit cubes of 12 triangles each on the integer lattice, every other cell of an
// n x n x n block at [-n/2, n/2]^3: every BVH box has faces on integer planes
inline Scene lattice_scene(int n, bool with_spheres) {
    Scene scene;
    scene.materials.push_back(Material{"a", Vec3(0.5f), Vec3(0.0f)});
    scene.materials.push_back(Material{"b", Vec3(0.25f), Vec3(0.0f)});
    const float h = n / 2.0f;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) {
                if ((i + j + k) % 2) continue;
                const Vec3 lo(i - h, j - h, k - h);
                if (with_spheres && (i + 2 * j + 3 * k) % 5 == 0) {
                    scene.spheres.push_back({Sphere{lo + Vec3(0.5f), 0.5f}, 1});
                    continue;
                }
                Vec3 c[8];
                for (int v = 0; v < 8; ++v)
                    c[v] = lo + Vec3(float(v & 1), float(v >> 1 & 1), float(v >> 2 & 1));
                const int faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                                         {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
                for (const auto& f : faces) {
                    scene.triangles.push_back(
                        SceneTriangle{c[f[0]], c[f[1]], c[f[2]], (i + j) % 2});
                    scene.triangles.push_back(
                        SceneTriangle{c[f[0]], c[f[2]], c[f[3]], (j + k) % 2});
                }
            }
    scene.commit();
    return scene;
}

// Rays whose origins lie on the lattice's planes (integer and half-integer coordinates)
// along directions with +-0, +-denormal and +-1 components: 0 * inf = NaN in the slab
// test on every axis where the direction is +-0, and rays along box faces and edges
inline std::vector<Ray> lattice_rays(int n) {
    const float comps[] = {0.0f, -0.0f, 1.0f, -1.0f, kDenorm, -kDenorm, 0.5f, -0.75f};
    const float coords[] = {-float(n), -n / 2.0f, -1.0f, -0.5f,
                            0.0f,      0.5f,      1.0f,  n / 2.0f};
    std::vector<Ray> rays;
    Rng rng(4242);
    for (int k = 0; k < 6000; ++k) {
        Vec3 o, w;
        for (int a = 0; a < 3; ++a) {
            o[a] = coords[rng.next() % 8];
            w[a] = comps[rng.next() % 8];
        }
        if (w == Vec3(0.0f)) w[int(rng.next() % 3)] = 1.0f;
        if (rng.next() % 2) {
            // unit, where the length is not 0 (denormals alone give 0)
            const float l = glm::length(w);
            if (l > 0.0f && std::isfinite(l)) w /= l;
        }
        Ray r{o, w, 0.0f, kInfinity};
        switch (rng.next() % 8) {
            case 0:
                r.tmin = -kInfinity;
                break;
            case 1:
                r.tmin = -3.0f;
                break;
            case 2:
                r.tmax = 0.0f;
                break;
            case 3:
                r.tmax = 2.0f;
                break;
            case 4:
                r.tmin = 1.0f, r.tmax = 1.0f;
                break;
            case 5:
                r.tmin = -0.0f, r.tmax = -0.0f;
                break;
            default:
                break;
        }
        rays.push_back(r);
    }
    return rays;
}

// What a walk sees: per ray the leaves in order and the nodes tested
struct Walk {
    std::vector<std::uint32_t> leaves;
    std::uint64_t nodes = 0;
    bool operator==(const Walk& o) const {
        return leaves == o.leaves && nodes == o.nodes;
    }
};

// What the visit does after recording a leaf. three: shrinks tmax after some leaves and
// stops at the third (for any hit), so the pruning with the entry distances is exercised
// too; all: never stops; all_pruned: never stops, and each leaf sets tmax to a stand-in
// for its distance (1 + first / 64), so entry distances past it are skipped
enum class Visits { three, all, all_pruned };

struct Recorder {
    Walk& w;
    Visits mode;
    int visits = 0;
    bool operator()(std::uint32_t first, std::uint32_t count, float& tmax) {
        w.leaves.push_back(first);
        w.leaves.push_back(count);
        switch (mode) {
            case Visits::three:
                if (first % 3 == 0) tmax = tmax * 0.75f;
                return ++visits == 3;
            case Visits::all_pruned:
                tmax = std::fmin(tmax, 1.0f + float(first) / 64.0f);
                return false;
            case Visits::all:
                break;
        }
        return false;
    }
};

// (unused where the AVX walk it is compared with is not compiled: RAYLAB_NO_SIMD)
[[maybe_unused]] inline Walk sse_walk(const Bvh& bvh, const std::vector<Ray>& rays,
                                      bool sorted, Visits mode = Visits::three) {
    Walk w;
    for (const Ray& r : rays) {
        Recorder visit{w, mode};
        if (sorted)
            engine_kernels::walk<true, false>(bvh, r, visit, w.nodes);
        else
            engine_kernels::walk<false, false>(bvh, r, visit, w.nodes);
        w.leaves.push_back(~0u);
    }
    return w;
}

#if RAYLAB_AVX_NODES
__attribute__((target("avx2"), flatten)) inline Walk avx_walk(
    const Bvh& bvh, const std::vector<Ray>& rays, bool sorted,
    Visits mode = Visits::three) {
    Walk w;
    for (const Ray& r : rays) {
        Recorder visit{w, mode};
        if (sorted)
            engine_kernels::walk<true, true>(bvh, r, visit, w.nodes);
        else
            engine_kernels::walk<false, true>(bvh, r, visit, w.nodes);
        w.leaves.push_back(~0u);
    }
    return w;
}
#endif

// The module path's walk (Bvh::traverse, traverse_any)
inline Walk plain_walk(const Bvh& bvh, const std::vector<Ray>& rays, bool sorted,
                       Visits mode = Visits::three) {
    Walk w;
    for (const Ray& r : rays) {
        Recorder visit{w, mode};
        if (sorted)
            bvh.traverse(r, visit, w.nodes);
        else
            bvh.traverse_any(r, visit, w.nodes);
        w.leaves.push_back(~0u);
    }
    return w;
}

// The engine's SSE walk against the module path's walk, leaf by leaf, and its AVX walk
// against its SSE walk where the processor has AVX2; the AVX walk's count of nodes (0
// where there is none)
inline std::uint64_t check_walks_agree(const Bvh& bvh, const std::vector<Ray>& rays,
                                       bool sorted, Visits mode = Visits::three) {
    {
        INFO("sorted " << sorted << ", visits " << int(mode));
        const Walk plain = plain_walk(bvh, rays, sorted, mode);
        const Walk sse = sse_walk(bvh, rays, sorted, mode);
        CHECK(plain.nodes == sse.nodes);
        CHECK(plain.leaves == sse.leaves);
    }
#if RAYLAB_AVX_NODES
    if (!__builtin_cpu_supports("avx2")) return 0;
    INFO("sorted " << sorted << ", visits " << int(mode));
    const Walk a = avx_walk(bvh, rays, sorted, mode);
    const Walk b = sse_walk(bvh, rays, sorted, mode);
    CHECK(a.nodes == b.nodes);
    CHECK(a.leaves == b.leaves);
    return a.nodes;
#else
    (void)bvh, (void)rays, (void)sorted, (void)mode;
    return 0;
#endif
}

inline Scene sphere_scene(int n, std::uint64_t seed) {
    Scene scene;
    scene.materials.push_back(Material{});
    scene.planes.push_back({Plane{Vec3(0, 1, 0), 12.0f}, 0});
    Rng rng(seed);
    for (int k = 0; k < n; ++k)
        scene.spheres.push_back(
            {Sphere{rng.in_box(-10, 10), rng.uniform(0.05f, 0.5f)}, 0});
    scene.commit();
    return scene;
}

inline Scene triangle_scene(int n, std::uint64_t seed) {
    Scene scene;
    scene.materials.push_back(Material{});
    scene.materials.push_back(Material{"b", Vec3(0.2f), Vec3(0.0f)});
    Rng rng(seed);
    for (int k = 0; k < n; ++k) {
        SceneTriangle t;
        t.v0 = rng.in_box(-10, 10);
        t.v1 = t.v0 + rng.in_box(-1.5f, 1.5f);
        t.v2 = k % 7 == 0 ? t.v0 + 2.0f * (t.v1 - t.v0) : t.v0 + rng.in_box(-1.5f, 1.5f);
        t.material = k % 2;
        scene.triangles.push_back(t);
    }
    scene.commit();
    return scene;
}

// Random rays at the scene's primitives (their centres), one in four random
inline std::vector<Ray> rays_at(const Scene& scene, std::uint64_t seed, int n) {
    Rng rng(seed);
    std::vector<Ray> rays;
    for (int k = 0; k < n; ++k) {
        const Vec3 o = rng.in_box(-14, 14);
        Vec3 target;
        const size_t total = scene.spheres.size() + scene.triangles.size();
        const size_t p = rng.next() % total;
        if (p < scene.spheres.size()) {
            target = scene.spheres[p].sphere.c;
        } else {
            const SceneTriangle& t = scene.triangles[p - scene.spheres.size()];
            target = (t.v0 + t.v1 + t.v2) / 3.0f;
        }
        const Vec3 d = target - o;
        const Vec3 w =
            k % 4 == 3 || glm::dot(d, d) == 0.0f ? rng.direction() : glm::normalize(d);
        rays.push_back(Ray{o, w, 0.0f, kInfinity});
    }
    return rays;
}

inline void check_rays(const Scene& scene, const std::vector<Ray>& rays) {
    for (size_t k = 0; k < rays.size(); ++k) {
        INFO("ray " << k);
        check_ray(scene, rays[k]);
    }
}

}  // namespace raylab::engine_cases
