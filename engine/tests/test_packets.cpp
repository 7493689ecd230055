// The engine's packet query (GeometryEngine::closest_hit_packet, through
// Scene::closest_hits and the renderer): every ray's hit bit for bit as the single-ray
// query gives it, on grids of rays, on rays chosen to break the packet's bounds (ranges
// at float's limits, ties between primitives, rays that must leave the packet), and in
// rendered images.
#include <doctest/doctest.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "engine_test_data.h"
#include "raylab/engine.h"
#include "raylab/renderer.h"
#include "raylab/sample_scenes.h"
#include "raylab/scenes.h"
#include "test_helpers.h"

using namespace raylab;

namespace {

// Sixteen rays from one origin o to the points of a 4 x 4 grid of integer coordinates
// in the plane z = z0: exactly through the shared vertices and edges of a triangulated
// grid there
std::vector<Ray> grid_rays(const Vec3& o, float z0, float x0, float y0) {
    std::vector<Ray> rays;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            const Vec3 target(x0 + float(i), y0 + float(j), z0);
            rays.push_back({o, glm::normalize(target - o), 0.0f, kInfinity});
        }
    return rays;
}

// A grid of unit squares, two triangles each, in the plane z = z0, and a second copy of
// each square's first triangle with another material one unit behind it
Scene grid_scene(float z0, bool with_twins) {
    Scene scene = cornell_box();  // materials and lights
    scene.triangles.clear();
    scene.normals.clear();
    for (int y = -4; y < 4; ++y)
        for (int x = -4; x < 4; ++x) {
            const Vec3 a(float(x), float(y), z0), b(float(x + 1), float(y), z0),
                c(float(x + 1), float(y + 1), z0), d(float(x), float(y + 1), z0);
            scene.add_triangle({a, b, c, (x + y) & 1});
            scene.add_triangle({a, c, d, 2});
            if (with_twins) scene.add_triangle({a, b, c, 3});  // an exact tie
        }
    scene.commit();
    return scene;
}

}  // namespace

TEST_SUITE("packets") {
    TEST_CASE("the reference's engine traces packets") {
        REQUIRE(engine_table().engine != nullptr);
        CHECK((engine_table().engine->closest_hit_packet != nullptr));
    }

    TEST_CASE("camera blocks hit what single rays hit, bit for bit") {
        for (const char* name : {"cornell", "dtu", "terrain", "room"}) {
            INFO("scene " << name);
            const std::optional<Scene> loaded =
                std::string(name) == "cornell" ? std::optional<Scene>(cornell_box())
                : std::string(name) == "dtu"   ? std::optional<Scene>(dtu_scene())
                                               : sample_scene(name);
            REQUIRE(loaded);
            const Scene& scene = *loaded;
            TraceCounters counters;
            const std::vector<Ray> rays = camera_blocks(scene.view, 160, 120);
            const int hits = check_packets(scene, rays, counters);
            CHECK(hits > 1000);  // the comparison means something
            // The packets ran: fewer node visits than one walk per ray would make
            TraceCounters single;
            for (const Ray& r : rays)
                (void)scene.closest_hit(engine_table(), r, single);
            CHECK(counters.bvh_nodes < single.bvh_nodes);
        }
    }

    TEST_CASE("rays exactly through shared vertices and edges, with exact ties") {
        // The grid's vertices and edges lie on integer coordinates; the twins make every
        // hit on a square's first triangle a tie that the visit order decides: those rays
        // must be traced again alone (the packet marks them)
        for (const bool twins : {false, true}) {
            for (const float z0 : {-3.0f, 5.0f}) {
                INFO("twins " << twins << ", plane z = " << z0);
                const Scene scene = grid_scene(z0, twins);
                TraceCounters counters;
                int hits = 0;
                for (const Vec3 o : {Vec3(0.5f, 0.25f, 0.0f), Vec3(0, 0, 0),
                                     Vec3(-0.75f, 1.0f, 1.0f), Vec3(3, -2, -10)}) {
                    for (float x0 : {-4.0f, -2.0f, 0.0f})
                        for (float y0 : {-4.0f, -1.0f, 0.0f})
                            hits +=
                                check_packets(scene, grid_rays(o, z0, x0, y0), counters);
                }
                CHECK(hits > 400);
            }
        }
    }

    TEST_CASE("planes, spheres and triangles in one packet") {
        Scene scene = cornell_box();
        scene.planes.push_back({Plane{Vec3(0, 1, 0), 0.9f}, 0});
        scene.planes.push_back({Plane{Vec3(0, 1, 0), 0.9f}, 1});  // a tie of planes
        scene.spheres.push_back({Sphere{Vec3(-0.4f, -0.6f, -0.3f), 0.35f}, 1});
        scene.spheres.push_back({Sphere{Vec3(0.5f, -0.7f, 0.2f), 0.25f}, 2});
        // A triangle in the plane y = -0.9: ties between a plane and a triangle
        scene.add_triangle(
            {Vec3(-1, -0.9f, -1), Vec3(1, -0.9f, -1), Vec3(0, -0.9f, 1), 3});
        scene.commit();
        TraceCounters counters;
        const int hits =
            check_packets(scene, camera_blocks(scene.view, 96, 72), counters);
        CHECK(hits > 3000);
    }

    TEST_CASE("packets that cannot travel together fall back to single rays") {
        const Scene scene = cornell_box();
        Rng rng(91);
        TraceCounters counters;
        std::vector<Ray> rays;
        // Other origins; a zero direction component; components of both signs; another
        // dominant axis; per-ray tmin and tmax; fewer rays than a packet
        for (int k = 0; k < 16; ++k)
            rays.push_back({rng.in_box(-0.5f, 0.5f), rng.direction(), 0.0f, kInfinity});
        check_packets(scene, rays, counters);
        const Vec3 eye = scene.view.eye;
        rays.clear();
        for (int k = 0; k < 16; ++k) {
            Vec3 w = glm::normalize(Vec3(0.01f * float(k - 8), 0.1f, -1.0f));
            if (k == 5) w = Vec3(0, 0, -1);  // zero x and y
            rays.push_back({eye, w, 0.0f, kInfinity});
        }
        check_packets(scene, rays, counters);
        rays.clear();
        for (int k = 0; k < 16; ++k) {
            const Vec3 w = glm::normalize(Vec3(k < 8 ? 1.5f : 0.1f, 0.2f, -1.0f));
            rays.push_back({eye, w, 0.1f * float(k % 3), k % 4 == 0 ? 3.5f : kInfinity});
        }
        check_packets(scene, rays, counters);
        // A NaN or infinite range in one ray of a packet that could travel together
        std::vector<Ray> together;
        for (int k = 0; k < 16; ++k)
            together.push_back({eye,
                                glm::normalize(Vec3(0.01f * float(k + 1), 0.1f, -1.0f)),
                                0.0f, kInfinity});
        for (const float bad : {NAN, -kInfinity, kInfinity}) {
            for (const int k : {0, 3}) {  // the first ray sets up the frustum
                std::vector<Ray> one = together;
                one[k].tmin = bad;
                check_packets(scene, one, counters);
                one[k].tmin = 0.0f;
                one[k].tmax = bad;
                check_packets(scene, one, counters);
            }
        }
        rays.resize(5);
        check_packets(scene, rays, counters);
        rays.resize(1);
        check_packets(scene, rays, counters);
    }

    TEST_CASE("random packets from one origin, near and far from the world's origin") {
        for (const Vec3 by : {Vec3(0.0f), Vec3(1e4f, -5e3f, 3e3f)}) {
            INFO("scene moved by " << by);
            const Scene scene = translated(cornell_box(), by);
            Rng rng(123);
            TraceCounters counters;
            int hits = 0;
            for (int p = 0; p < 300; ++p) {
                const Vec3 o = by + rng.in_box(-0.9f, 0.9f);
                const Vec3 centre = rng.direction();
                const float spread = p % 3 == 0 ? 0.001f : 0.05f;
                std::vector<Ray> rays;
                for (int k = 0; k < 16; ++k) {
                    const Vec3 w = glm::normalize(centre + spread * rng.in_box(-1, 1));
                    rays.push_back(
                        {o, w, p % 5 == 0 ? 0.01f : 0.0f, p % 7 == 0 ? 0.7f : kInfinity});
                }
                hits += check_packets(scene, rays, counters);
            }
            CHECK(hits > 2000);
        }
    }
}

// The renderer traces each tile's camera rays ahead in packets (PixelShader::trace_ahead)
// and the pixel loop takes them while it asks for the same points in the same order
TEST_SUITE("packets in render") {
    TEST_CASE("render() traces the camera rays ahead once, with the same image") {
        const Scene scene = cornell_box();
        RenderSettings settings;
        settings.width = 80;
        settings.height = 60;  // tiles of 16 x 16 and of 16 x 12: partial blocks
        Image fast, slow;
        const FrameStats a = render(scene, scene.view, settings, engine_table(), fast);
        const FrameStats b =
            render(scene, scene.view, settings, module_path_table(), slow);
        CHECK(a.camera_rays == 80 * 60);
        CHECK(b.camera_rays == 80 * 60);
        CHECK(fast.pixels == slow.pixels);
        // Nearly all in packets (ties on the edges between triangles, and blocks whose
        // rays' x changes sign, go alone); none on the module path
        CHECK(a.camera_rays_in_packets > 80 * 60 * 9 / 10);
        CHECK(a.camera_rays_in_packets < 80 * 60);
        CHECK(b.camera_rays_in_packets == 0);
    }

    // A student's pixel loop may visit a tile's pixels in another order: it gets the
    // rays traced ahead up to the first pixel out of order, the rest one at a time, and
    // the thread stops tracing ahead for the rest of the frame
    TEST_CASE("a pixel loop in another order gets the same image") {
        static const ModuleTable* table = nullptr;
        struct Loop {
            static void render_tile(const Tile& tile, const PixelRadiance& radiance,
                                    const ImageView& image) {
                for (int i = tile.x0; i < tile.x1; ++i)  // columns first
                    for (int j = tile.y0; j < tile.y1; ++j)
                        image.set(i, j,
                                  radiance(table->image_plane_point(i, j, image.width,
                                                                    image.height)));
            }
        };
        const Scene scene = cornell_box();
        ModuleTable columns = engine_table();
        columns.render_tile = &Loop::render_tile;
        table = &columns;
        RenderSettings settings;
        settings.width = 64;
        settings.height = 48;
        settings.threads = 2;
        Image image, expected;
        const FrameStats s = render(scene, scene.view, settings, columns, image);
        render(scene, scene.view, settings, engine_table(), expected);
        CHECK(image.pixels == expected.pixels);
        // One tile per thread traced ahead in vain, at the most
        CHECK(s.camera_rays >= 64 * 48);
        CHECK(s.camera_rays <= 64 * 48 + 2 * kTileSize * kTileSize);
    }
}

// ---- Rays chosen to break the packet's bounds -----------------------------------------

namespace packet_bounds {

namespace {

bool same_bits(const void* a, const void* b, size_t n) {
    return std::memcmp(a, b, n) == 0;
}

std::string hexray(const Ray& r) {
    char buf[512];
    std::snprintf(buf, sizeof buf, "o=(%a,%a,%a) w=(%a,%a,%a) tmin=%a tmax=%a", r.o.x,
                  r.o.y, r.o.z, r.w.x, r.w.y, r.w.z, r.tmin, r.tmax);
    return buf;
}

std::string hexhit(const std::optional<Hit>& h) {
    if (!h) return "none";
    char buf[512];
    std::snprintf(buf, sizeof buf, "t=%a p=(%a,%a,%a) n=(%a,%a,%a) uv=(%a,%a) mat=%d",
                  h->t, h->position.x, h->position.y, h->position.z, h->n.x, h->n.y,
                  h->n.z, h->uv.x, h->uv.y, h->material);
    return buf;
}

// Strict: every field bitwise (including the sign of zeros); returns number of mismatches
int compare_packets(const Scene& scene, const std::vector<Ray>& rays, bool print = true) {
    const ModuleTable modules = engine_table();
    std::vector<std::optional<Hit>> out(rays.size());
    TraceCounters c;
    scene.closest_hits(modules, rays.data(), static_cast<int>(rays.size()), c,
                       out.data());
    int bad = 0;
    TraceCounters single;
    for (size_t k = 0; k < rays.size(); ++k) {
        const std::optional<Hit> one = scene.closest_hit(modules, rays[k], single);
        const std::optional<Hit>& a = out[k];
        bool ok = a.has_value() == one.has_value();
        if (ok && a) {
            ok = same_bits(&a->t, &one->t, 4) &&
                 same_bits(&a->position, &one->position, 12) &&
                 same_bits(&a->n, &one->n, 12) && same_bits(&a->ns, &one->ns, 12) &&
                 same_bits(&a->uv, &one->uv, 8) && a->material == one->material;
        }
        if (!ok) {
            ++bad;
            if (print && bad <= 5)
                MESSAGE("mismatch, ray " << k << " of " << rays.size() << ": "
                                         << hexray(rays[k]) << "\n  packet: " << hexhit(a)
                                         << "\n  single: " << hexhit(one));
        }
    }
    return bad;
}

Scene base_scene() {
    Scene s = cornell_box();
    s.triangles.clear();
    s.normals.clear();
    s.spheres.clear();
    s.planes.clear();
    return s;
}

float pick_range(Rng& rng, bool lo) {
    switch (rng.next() % 12) {
        case 0:
            return -kInfinity;
        case 1:
            return kInfinity;
        case 2:
            return 0.0f;
        case 3:
            return -0.0f;
        case 4:
            return rng.uniform(-20.0f, 20.0f);
        case 5:
            return rng.uniform(0.0f, 1e-3f);
        case 6:
            return 1e-30f;
        case 7:
            return -rng.uniform(0.0f, 5.0f);
        default:
            return lo ? 0.0f : kInfinity;
    }
}

}  // namespace

TEST_SUITE("packets") {
    TEST_CASE("random mixed scenes, random packets with wild ranges") {
        int total_bad = 0, rays_run = 0, hits = 0;
        for (std::uint64_t seed = 1; seed <= 60; ++seed) {
            Rng rng(seed * 7919);
            Scene scene = base_scene();
            const float off =
                (seed % 4 == 0) ? 1e5f
                                : (seed % 4 == 1 ? 0.0f : (seed % 4 == 2 ? 3e3f : 1e6f));
            const Vec3 O(off, -0.5f * off, 0.25f * off);
            const int ntri = int(rng.next() % 60);
            const int nsph = int(rng.next() % 12);
            const int npl = int(rng.next() % 3);
            std::vector<SceneTriangle> tris;
            for (int i = 0; i < ntri; ++i) {
                const Vec3 c = O + rng.in_box(-3.0f, 3.0f);
                SceneTriangle t{c + rng.in_box(-1, 1), c + rng.in_box(-1, 1),
                                c + rng.in_box(-1, 1), int(rng.next() % 4)};
                if (rng.next() % 7 == 0)
                    t.v2 = t.v0 + 2.0f * (t.v1 - t.v0);  // ~collinear
                if (rng.next() % 9 == 0) {               // axis aligned
                    t.v1.x = t.v0.x;
                    t.v2.x = t.v0.x;
                }
                tris.push_back(t);
                if (rng.next() % 3 == 0) {  // twin, other material, rotated order
                    tris.push_back({t.v1, t.v2, t.v0, int(rng.next() % 4)});
                }
            }
            // shuffle so that twins tend to land in different leaves
            for (size_t i = tris.size(); i > 1; --i)
                std::swap(tris[i - 1], tris[rng.next() % i]);
            for (const SceneTriangle& t : tris)
                scene.add_triangle(t);
            for (int i = 0; i < nsph; ++i) {
                const Sphere s{O + rng.in_box(-3.0f, 3.0f), rng.uniform(0.05f, 1.5f)};
                scene.spheres.push_back({s, int(rng.next() % 4)});
                if (rng.next() % 3 == 0)
                    scene.spheres.push_back({s, int(rng.next() % 4)});
            }
            for (int i = 0; i < npl; ++i) {
                const Vec3 n = rng.direction();
                scene.planes.push_back(
                    {Plane{n, -glm::dot(n, O + rng.in_box(-4, 4))}, i});
            }
            scene.commit();
            for (int p = 0; p < 60; ++p) {
                Vec3 o = O + rng.in_box(-6.0f, 6.0f);
                const int where = int(rng.next() % 6);
                if (where == 0 && !tris.empty()) o = tris[rng.next() % tris.size()].v0;
                if (where == 1 && !scene.spheres.empty()) {
                    const Sphere& s =
                        scene.spheres[rng.next() % scene.spheres.size()].sphere;
                    o = s.c + s.r * rng.direction();
                }
                if (where == 2 && !tris.empty()) {
                    const SceneTriangle& t = tris[rng.next() % tris.size()];
                    o = 0.5f * (t.v0 + t.v1);
                }
                // aim at the middle of the scene or a random direction
                Vec3 d = (rng.next() % 2) ? glm::normalize(O - o + rng.in_box(-1, 1))
                                          : rng.direction();
                const float spread = (rng.next() % 2) ? 0.02f : 0.3f;
                const int n = 1 + int(rng.next() % 40);
                std::vector<Ray> rays;
                const bool same_range = rng.next() % 2;
                const float t0 = pick_range(rng, true), t1 = pick_range(rng, false);
                for (int k = 0; k < n; ++k) {
                    Vec3 w = d + spread * rng.in_box(-1, 1);
                    if (!tris.empty() && rng.next() % 4 == 0) {
                        const SceneTriangle& t = tris[rng.next() % tris.size()];
                        const Vec3 target =
                            (rng.next() % 2) ? t.v1 : 0.5f * (t.v1 + t.v2);
                        if (target != o) w = target - o;
                    }
                    w = glm::normalize(w);
                    Ray r{o, w, same_range ? t0 : pick_range(rng, true),
                          same_range ? t1 : pick_range(rng, false)};
                    rays.push_back(r);
                }
                const int bad = compare_packets(scene, rays);
                if (bad) MESSAGE("seed " << seed << ", packet " << p);
                total_bad += bad;
                rays_run += n;
            }
            (void)hits;
        }
        MESSAGE(rays_run << " rays in random mixed scenes");
        CHECK(total_bad == 0);
    }
}

namespace {
float ulps(float x, int k) {
    for (int i = 0; i < k; ++i)
        x = std::nextafter(x, kInfinity);
    for (int i = 0; i > k; --i)
        x = std::nextafter(x, -kInfinity);
    return x;
}
}  // namespace

TEST_SUITE("packets") {
    // Near-duplicate spheres (ulps apart) in different leaves: hits within a few ulps of
    // each other, both in front of (tmin 0) and behind the origin (tmin -inf, where the
    // slab test's margin kSlabGrow shrinks a negative exit instead of growing it)
    TEST_CASE("near-duplicate spheres, hits ulps apart, positive and negative t") {
        int total_bad = 0, rays_run = 0;
        for (std::uint64_t seed = 1; seed <= 400; ++seed) {
            Rng rng(seed * 104729);
            Scene scene = base_scene();
            const float off = (seed % 3 == 0) ? 0.0f : (seed % 3 == 1 ? 1e3f : 1e5f);
            const Vec3 O(off, 0.3f * off, -0.7f * off);
            const Vec3 c0 = O + rng.in_box(-2.0f, 2.0f);
            const float r0 = rng.uniform(0.2f, 1.0f);
            const int count = 4 + int(rng.next() % 24);
            for (int i = 0; i < count; ++i) {
                Vec3 c = c0;
                if (rng.next() % 2) c.x = ulps(c.x, int(rng.next() % 7) - 3);
                if (rng.next() % 2) c.y = ulps(c.y, int(rng.next() % 7) - 3);
                if (rng.next() % 2) c.z = ulps(c.z, int(rng.next() % 7) - 3);
                const float r = ulps(r0, int(rng.next() % 9) - 4);
                scene.spheres.push_back({Sphere{c, r}, i % 4});
                if (rng.next() % 3 ==
                    0) {  // a big sphere off to the side: big leaf boxes
                    scene.spheres.push_back(
                        {Sphere{c0 + rng.in_box(-8.0f, 8.0f), rng.uniform(1.0f, 4.0f)},
                         3});
                }
            }
            scene.commit();
            for (int p = 0; p < 40; ++p) {
                const Vec3 o = O + rng.in_box(-10.0f, 10.0f);
                const Vec3 d = glm::normalize(c0 - o);
                const float spread = (rng.next() % 2) ? 0.005f : 0.08f;
                const int n = 2 + int(rng.next() % 15);
                const int mode = int(rng.next() % 4);
                std::vector<Ray> rays;
                for (int k = 0; k < n; ++k) {
                    Vec3 w = glm::normalize(d + spread * rng.in_box(-1, 1));
                    Ray r{o, w, 0.0f, kInfinity};
                    if (mode == 1) r.w = -r.w, r.tmin = -kInfinity;  // spheres behind
                    if (mode == 2) r.w = -r.w, r.tmin = -kInfinity, r.tmax = 0.0f;
                    if (mode == 3) r.tmin = -kInfinity;
                    rays.push_back(r);
                }
                const int bad = compare_packets(scene, rays);
                if (bad)
                    MESSAGE("seed " << seed << ", packet " << p << ", mode " << mode);
                total_bad += bad;
                rays_run += n;
            }
        }
        MESSAGE(rays_run << " rays at near-duplicate spheres");
        CHECK(total_bad == 0);
    }
}

namespace {
std::optional<Hit> alone(const Sphere& s, const Ray& r) {
    Scene one = base_scene();
    one.spheres.push_back({s, 0});
    one.commit();
    TraceCounters c;
    return one.closest_hit(engine_table(), r, c);
}
}  // namespace

TEST_SUITE("packets") {
    // Negative t: kSlabGrow shrinks a negative exit, so a leaf whose box is entered
    // within a few ulps before the current (negative) hit is culled. The single ray and
    // the packet visit leaves in different orders (per-ray tmin clamps the ray's own
    // entry distances, the frustum uses the smallest tmin), so they cull different
    // leaves.
    TEST_CASE("negative t: near-tied spheres behind the origin, per-ray tmin") {
        int bad_total = 0, tried = 0;
        Rng rng(12345);
        for (int iter = 0; iter < 400; ++iter) {
            const Vec3 o(0.0f);
            const Vec3 wk = glm::normalize(
                Vec3(1.0f, rng.uniform(1e-5f, 1e-3f), rng.uniform(1e-5f, 1e-3f)));
            // A: big sphere off the axis, entered late relative to its box
            const float R = rng.uniform(2.0f, 10.0f);
            const float h = rng.uniform(0.3f, 0.95f) * R;
            const Sphere A{Vec3(-10.0f - R, h * 0.6f, h * 0.8f), R};
            Ray rk{o, wk, -kInfinity, kInfinity};
            const auto ha = alone(A, rk);
            if (!ha || !(ha->t < 0.0f)) continue;
            const float Ta = ha->t;
            // B: small sphere on the ray, its hit a few ulps before Ta
            const float rb = rng.uniform(0.1f, 1.0f);
            float xb = ha->position.x + rb;
            std::optional<Hit> hb;
            Sphere B{};
            bool found = false;
            for (int step = -40; step <= 40 && !found; ++step) {
                B = Sphere{Vec3(ulps(xb, step), ha->position.y, ha->position.z), rb};
                hb = alone(B, rk);
                if (hb && hb->t < Ta && hb->t > Ta * kSlabGrow) found = true;
            }
            if (!found) continue;
            const float Tb = hb->t;
            for (int order = 0; order < 2; ++order) {
                Scene scene = base_scene();
                if (order == 0) {
                    scene.spheres.push_back({A, 1});
                    scene.spheres.push_back({B, 2});
                } else {
                    scene.spheres.push_back({B, 2});
                    scene.spheres.push_back({A, 1});
                }
                for (int f = 0; f < int(rng.next() % 12); ++f)  // fillers
                    scene.spheres.push_back(
                        {Sphere{rng.in_box(-40.0f, 40.0f) + Vec3(0, 0, 60.0f), 0.5f}, 3});
                scene.commit();
                for (int variant = 0; variant < 3; ++variant) {
                    std::vector<Ray> rays;
                    Ray k = rk;
                    k.tmin =
                        variant == 0 ? Tb : (variant == 1 ? ulps(Tb, -1) : -kInfinity);
                    rays.push_back(k);
                    for (int j = 0; j < 3; ++j) {
                        const Vec3 wj = glm::normalize(Vec3(
                            1.0f, rng.uniform(1e-5f, 0.3f), rng.uniform(1e-5f, 0.3f)));
                        rays.push_back({o, wj, -kInfinity, kInfinity});
                    }
                    if (variant == 2) std::swap(rays[0], rays[3]);
                    ++tried;
                    const int bad = compare_packets(scene, rays);
                    if (bad)
                        MESSAGE("iter " << iter << ", order " << order << ", variant "
                                        << variant);
                    bad_total += bad;
                }
            }
        }
        MESSAGE(tried << " packets at spheres behind the origin");
        CHECK(bad_total == 0);
    }
}

TEST_SUITE("packets") {
    // A case the one above found: two spheres behind
    // the origin, hits 2 ulps apart at t ~ -27.4; ray 0 has tmin = its own hit on B, ray
    // 1 tmin = -inf. The single ray takes B (the nearer); the packet kept A, before
    // packets needed tmin >= 0.
    TEST_CASE(
        "two spheres behind the origin, hits 2 ulps apart: the nearer one is kept") {
        Scene scene = base_scene();
        scene.spheres.push_back(
            {Sphere{Vec3(-0x1.39af06p+4f, 0x1.aa4c1ep+1f, 0x1.1c32bep+2f),
                    0x1.335e0cp+3f},
             1});
        scene.spheres.push_back(
            {Sphere{Vec3(-0x1.b0f0aap+4f, -0x1.b6f9acp-9f, -0x1.471a54p-10f),
                    0x1.888914p-2f},
             2});
        for (const Vec3 c : {Vec3(0x1.59778p+0f, 0x1.e5cda8p+4f, 0x1.23d6bp+5f),
                             Vec3(0x1.281bc8p+3f, -0x1.145642p+5f, 0x1.48e95cp+5f),
                             Vec3(0x1.490b98p+3f, -0x1.659cf2p+4f, 0x1.0c78e4p+6f),
                             Vec3(0x1.b5455p+3f, -0x1.0835fp+3f, 0x1.0ab7b8p+5f),
                             Vec3(-0x1.276b3ap+5f, -0x1.e558p-5f, 0x1.bbbc94p+4f)})
            scene.spheres.push_back({Sphere{c, 0.5f}, 3});
        scene.commit();
        const Vec3 o(0.0f);
        const std::vector<Ray> rays = {
            {o, Vec3(0x1p+0f, 0x1.ffe2bcp-14f, 0x1.7d6e9ep-15f), -0x1.b712cep+4f,
             kInfinity},
            {o, Vec3(0x1.ea4926p-1f, 0x1.9e0b1ep-5f, 0x1.227a2cp-2f), -kInfinity,
             kInfinity},
            {o, Vec3(0x1.fcc3bcp-1f, 0x1.5577fp-8f, 0x1.cb3fa8p-4f), -kInfinity,
             kInfinity},
            {o, Vec3(0x1.ff58b2p-1f, 0x1.6c9e02p-6f, 0x1.7372bap-5f), -kInfinity,
             kInfinity}};
        const ModuleTable m = engine_table();
        std::optional<Hit> out[4];
        TraceCounters c;
        scene.closest_hits(m, rays.data(), 4, c, out);
        const std::optional<Hit> one = scene.closest_hit(m, rays[0], c);
        REQUIRE(one);
        REQUIRE(out[0]);
        CHECK(one->material == 2);                 // B, t = -0x1.b712cep+4
        CHECK(out[0]->material == one->material);  // was A, t = -0x1.b712c6p+4
        CHECK(out[0]->t == one->t);
    }
}

TEST_SUITE("packets in render") {
    TEST_CASE(
        "render: engine vs module path, odd sizes, threads, modes, odd pixel loops") {
        static const ModuleTable* table = nullptr;
        struct Loops {
            // reverse order within the tile
            static void reverse(const Tile& tile, const PixelRadiance& radiance,
                                const ImageView& image) {
                for (int j = tile.y1 - 1; j >= tile.y0; --j)
                    for (int i = tile.x1 - 1; i >= tile.x0; --i)
                        image.set(i, j,
                                  radiance(table->image_plane_point(i, j, image.width,
                                                                    image.height)));
            }
            // row-major but every pixel asked twice, and the first pixel skipped
            static void twice_skip(const Tile& tile, const PixelRadiance& radiance,
                                   const ImageView& image) {
                for (int j = tile.y0; j < tile.y1; ++j)
                    for (int i = tile.x0; i < tile.x1; ++i) {
                        if (i == tile.x0 && j == tile.y0) continue;
                        const Vec2 uv =
                            table->image_plane_point(i, j, image.width, image.height);
                        image.set(i, j, radiance(uv));
                        image.set(i, j, radiance(uv));
                    }
            }
        };
        const Scene scenes[] = {cornell_box(),
                                translated(cornell_box(), Vec3(1e5f, -3e4f, 2e4f))};
        for (const Scene& scene : scenes)
            for (const auto& wh : {std::pair<int, int>{1, 1}, {17, 3}, {33, 65}, {3, 17}})
                for (const ShadingMode mode :
                     {ShadingMode::normals, ShadingMode::depth, ShadingMode::lambert})
                    for (const int threads : {1, 2, 3}) {
                        RenderSettings s;
                        s.width = wh.first;
                        s.height = wh.second;
                        s.mode = mode;
                        s.threads = threads;
                        Image fast, slow;
                        render(scene, scene.view, s, engine_table(), fast);
                        render(scene, scene.view, s, module_path_table(), slow);
                        INFO(wh.first << "x" << wh.second << " threads " << threads);
                        CHECK(same_bits(fast.pixels.data(), slow.pixels.data(),
                                        fast.pixels.size() * sizeof(fast.pixels[0])));
                        for (int loop = 0; loop < 2; ++loop) {
                            ModuleTable custom = engine_table();
                            custom.render_tile =
                                loop ? &Loops::twice_skip : &Loops::reverse;
                            ModuleTable custom_slow = module_path_table();
                            custom_slow.render_tile = custom.render_tile;
                            table = &custom;
                            Image a, b;
                            render(scene, scene.view, s, custom, a);
                            render(scene, scene.view, s, custom_slow, b);
                            CHECK(same_bits(a.pixels.data(), b.pixels.data(),
                                            a.pixels.size() * sizeof(a.pixels[0])));
                        }
                    }
    }
}

}  // namespace packet_bounds
