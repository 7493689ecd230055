// The engine's walks of the BVH (engine_walk.h) against the module path's
// (Bvh::traverse): the SSE walk leaf by leaf against the plain one, the AVX node test
// and the AVX placing of hit children against the SSE walk, on rays in box planes with
// zero, denormal, NaN and infinite components. The ctest runs
// engine/engine-baseline-versions and engine-avx2-versions repeat the suite on the
// engine's narrower versions.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "engine_cases.h"

using namespace raylab;
using namespace raylab::engine_cases;

TEST_SUITE("walk") {
    // The module path's walk (Bvh::traverse, a child at a time) and the engine's SSE walk
    // on every processor: the same leaves in the same order and the same count of nodes,
    // on the lattices' rays through box planes and on random rays
    TEST_CASE("the engine's walk visits what Bvh::traverse visits") {
        for (const bool spheres : {false, true}) {
            INFO("spheres " << spheres);
            const Scene lattice = lattice_scene(8, spheres);
            std::vector<Ray> rays = lattice_rays(8);
            rays.push_back(Ray{Vec3(kNaN, 0, 0), Vec3(0, 0, 1), 0.0f, kInfinity});
            rays.push_back(Ray{Vec3(0.5f), Vec3(0, 0, 1), kNaN, kInfinity});
            rays.push_back(Ray{Vec3(0.5f), Vec3(0, -0.0f, 1), 2.0f, 1.0f});
            for (const Visits mode : {Visits::three, Visits::all, Visits::all_pruned})
                for (const bool sorted : {true, false})
                    check_walks_agree(lattice.bvh(), rays, sorted, mode);
            const Scene random = triangle_scene(3000, 7);
            for (const bool sorted : {true, false})
                check_walks_agree(random.bvh(), rays_at(random, 8, 2000), sorted,
                                  Visits::all_pruned);
        }
    }

    // The AVX node test against the SSE one directly (the engine's tests compare whole
    // queries, which reach only the version the processor chooses), and with it the AVX
    // walk's placing of three or more hit children (place_sorted_avx) against the SSE
    // walk's insertion sort: with ties among them put the other way round, or left out
    // of the count, this case and the next fail
    TEST_CASE("the AVX walk visits exactly what the SSE walk visits") {
#if RAYLAB_AVX_NODES
        if (!__builtin_cpu_supports("avx2")) {
            MESSAGE("no AVX2 here: nothing to compare");
            return;
        }
        for (const bool spheres : {false, true}) {
            const Scene scene = lattice_scene(8, spheres);
            REQUIRE(scene.bvh().node_count() > 8);
            std::vector<Ray> rays = lattice_rays(8);
            // Origins NaN or infinite, directions NaN: nothing defined, but both tests
            // must still agree (the same operations on the same lanes)
            rays.push_back(Ray{Vec3(kNaN, 0, 0), Vec3(0, 0, 1), 0.0f, kInfinity});
            rays.push_back(Ray{Vec3(0.5f), Vec3(kNaN, 0, 1), 0.0f, kInfinity});
            rays.push_back(Ray{Vec3(kInfinity, 0, 0), Vec3(-1, 0, 0), 0.0f, kInfinity});
            rays.push_back(Ray{Vec3(0.5f), Vec3(0, 0, 1), 0.0f, kNaN});
            rays.push_back(Ray{Vec3(0.5f), Vec3(0, 0, 1), kNaN, kInfinity});
            // Infinite direction components (1 / w = 0: 0 * inf where the origin is
            // infinite), origins at +-inf and at the largest floats
            const float big = std::numeric_limits<float>::max();
            for (const Vec3 w : {Vec3(kInfinity, 0, 1), Vec3(-kInfinity, 1, -0.0f),
                                 Vec3(0.0f, -0.0f, kInfinity), Vec3(1, -1, 1)})
                for (const Vec3 o : {Vec3(0.0f), Vec3(-kInfinity, 0.5f, 0.5f),
                                     Vec3(1.0f, kInfinity, -kInfinity),
                                     Vec3(big, -big, 0), Vec3(-4.0f, 0.0f, -big)})
                    rays.push_back(Ray{o, w, 0.0f, kInfinity});
            INFO("spheres " << spheres);
            for (const bool sorted : {true, false})
                check_walks_agree(scene.bvh(), rays, sorted);
        }
#else
        MESSAGE("RAYLAB_AVX_NODES is 0 in this build");
#endif
    }

    // Random triangles: every BVH box's faces lie at vertex coordinates, so rays whose
    // origin takes its coordinates from vertices, along +-0 components, meet NaN in the
    // slab tests of many nodes. The AVX walk against the SSE one, then both query paths
    TEST_CASE("origins on vertex planes of random triangles, zero components") {
        const Scene scene = triangle_scene(1500, 31);
        REQUIRE(engine_data(scene).slot_primitives() != nullptr);
        Rng rng(32);
        std::vector<Ray> rays;
        const float comps[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.6f, -0.8f};
        for (int k = 0; k < 4000; ++k) {
            Vec3 o, w;
            for (int a = 0; a < 3; ++a) {
                const SceneTriangle& t =
                    scene.triangles[rng.next() % scene.triangles.size()];
                const Vec3 v =
                    rng.next() % 3 == 0 ? t.v0 : (rng.next() % 2 ? t.v1 : t.v2);
                o[a] = v[a];
                w[a] = comps[rng.next() % 6];
            }
            if (w == Vec3(0.0f)) w.z = -1.0f;
            rays.push_back(Ray{o, w, k % 5 == 0 ? -kInfinity : 0.0f, kInfinity});
        }
        for (const bool sorted : {true, false})
            check_walks_agree(scene.bvh(), rays, sorted);
        check_rays(scene, rays);
    }

    // The AVX2 walk's placing of three or more hit children against the insertion sort
    // of the SSE walk, on its own: every mask of three or more children, with
    // entry distances drawn from values that tie (+-0, +-inf, denormals) and NaN in the
    // lanes that are not hit (a hit child's t is never NaN)
    TEST_CASE("the AVX walk places hit children as the insertion sort does") {
#if RAYLAB_AVX_NODES
        if (!__builtin_cpu_supports("avx2")) {
            MESSAGE("no AVX2 here: nothing to compare");
            return;
        }
        struct Entry {
            std::uint32_t child;
            float t_enter;
        };
        const Bvh bvh;  // the leaves' children are never prefetched: no nodes needed
        Bvh::Node node{};
        for (int k = 0; k < Bvh::kWidth; ++k)
            node.child[k] = Bvh::kLeaf | 1u << Bvh::kCountShift | std::uint32_t(k);
        const float values[] = {-kInfinity, -1.0f, -0.0f, 0.0f,      kDenorm,
                                -kDenorm,   0.5f,  1.0f,  kInfinity, 0x1p-126f};
        Rng rng(77);
        int masks = 0, cases = 0, ties = 0;
        for (int mask = 0; mask < 256; ++mask) {
            if (__builtin_popcount(unsigned(mask)) < 3) continue;
            ++masks;
            for (int draw = 0; draw < 400; ++draw) {
                alignas(32) float t[Bvh::kWidth];
                for (int k = 0; k < Bvh::kWidth; ++k) {
                    // the first ten draws: every hit lane the same value
                    const float v = draw < 10 ? values[draw] : values[rng.next() % 10];
                    t[k] = mask >> k & 1 ? v : kNaN;
                }
                // The insertion sort, as Bvh::walk runs it
                Entry want[Bvh::kWidth];
                int top = 0;
                for (int m = mask; m != 0; m &= m - 1) {
                    const int k = __builtin_ctz(unsigned(m));
                    const Entry e{node.child[k], t[k]};
                    int j = top++;
                    for (; j > 0 && want[j - 1].t_enter < e.t_enter; --j)
                        want[j] = want[j - 1];
                    want[j] = e;
                }
                Entry got[Bvh::kWidth];
                for (Entry& e : got)
                    e = Entry{0u, kNaN};
                REQUIRE(engine_kernels::place_sorted_avx(bvh, node, t, mask, got) == top);
                INFO("mask " << mask << ", draw " << draw);
                for (int j = 0; j < top; ++j) {
                    CHECK(got[j].child == want[j].child);
                    CHECK(same_bits(got[j].t_enter, want[j].t_enter));
                    if (j > 0 && want[j].t_enter == want[j - 1].t_enter) ++ties;
                }
                ++cases;
            }
        }
        CHECK(masks == 219);
        CHECK(ties > 50000);
        MESSAGE(cases << " cases, " << ties << " ties");
#else
        MESSAGE("RAYLAB_AVX_NODES is 0 in this build");
#endif
    }

    // Eight cubes, one in each octant with a corner at the origin: the root's eight
    // children all touch the origin, so rays from it (and along the planes through it)
    // enter three to eight of them at the same t, 0 or -0 or with tmin below 0 at
    // distances that tie. Every leaf each walk visits, in order, AVX against SSE, with
    // no stop and no pruning, then with the nearest hit so far shrinking tmax
    TEST_CASE("eight cubes around the origin, every child entered at once") {
        Scene scene;
        scene.materials.push_back(Material{});
        for (int o = 0; o < 8; ++o) {
            const Vec3 s(o & 1 ? 1.0f : -1.0f, o & 2 ? 1.0f : -1.0f,
                         o & 4 ? 1.0f : -1.0f);
            Vec3 c[8];
            for (int v = 0; v < 8; ++v)
                c[v] = s * Vec3(float(v & 1), float(v >> 1 & 1), float(v >> 2 & 1));
            const int faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                                     {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
            for (const auto& f : faces) {
                scene.triangles.push_back(SceneTriangle{c[f[0]], c[f[1]], c[f[2]], 0});
                scene.triangles.push_back(SceneTriangle{c[f[0]], c[f[2]], c[f[3]], 0});
            }
        }
        scene.commit();
        // The root and one node per cube: the root's children are the eight cubes
        REQUIRE(scene.bvh().node_count() == 9);
        const float comps[] = {1.0f, -1.0f, 0.0f, -0.0f, 0.5f, -0.25f};
        const float tmins[] = {0.0f, -0.0f, -3.0f, -kInfinity};
        std::vector<Ray> rays;
        for (int k = 0; k < 6 * 6 * 6 * 4; ++k) {
            Vec3 w(comps[k % 6], comps[k / 6 % 6], comps[k / 36 % 6]);
            if (w == Vec3(0.0f)) continue;
            const float tmin = tmins[k / 216];
            rays.push_back(Ray{Vec3(0.0f), w, tmin, kInfinity});
            rays.push_back(Ray{Vec3(0.0f, 0.0f, 0.5f), w, tmin, kInfinity});
            rays.push_back(Ray{Vec3(0.5f, -0.0f, 0.0f), w, tmin, kInfinity});
        }
        for (const Visits mode : {Visits::all, Visits::all_pruned}) {
            const std::uint64_t nodes = check_walks_agree(scene.bvh(), rays, true, mode);
            // Where it ran: every ray tests the root at least
            CHECK((nodes == 0 || nodes >= rays.size()));
        }
        check_rays(scene, rays);
    }
}
