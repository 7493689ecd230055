// Shadow rays from the hit point's error bound, through Scene and
// the reference modules: far cameras cause no acne, close occluders are found, the
// Lambert image of a lit plane matches its analytic value far from the origin.
//
// The bound used here is the one the framework promises for its hit points (raylab/
// refine.h), written out again so that these tests also run against code without it:
// delta(x) = 2^-23 max|x_i|, one ulp of the largest coordinate.
#include <doctest/doctest.h>

#include "meshes.h"
#include "raylab/renderer.h"
#include "raylab/scene.h"
#include "test_helpers.h"

using namespace raylab;

namespace {

constexpr float kUlp = 0x1p-23f;  // FLT_EPSILON: relative spacing of floats

float delta(const Vec3& x) {
    return kUlp * std::max({std::abs(x.x), std::abs(x.y), std::abs(x.z)});
}

// Exact (hexadecimal) coordinates, so that a failure can be replayed
std::string show(const Vec3& v) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "(%a, %a, %a)", double(v.x), double(v.y), double(v.z));
    return buf;
}

enum class Seen { miss, backfacing, lit, shadowed };

// What the renderer does with a camera ray in Lambert mode with one light
Seen shade(const Scene& scene, const Ray& r, const Vec3& light, Hit* out = nullptr) {
    const ModuleTable& m = reference_modules();
    TraceCounters counters;
    const SceneOccluder occluder(scene, m, counters);
    const auto hit = scene.closest_hit(m, r, counters);
    if (!hit) return Seen::miss;
    if (out) *out = *hit;
    const LightSample s =
        m.sample_point_light(PointLight{light, Vec3(1.0f)}, hit->position);
    if (!(glm::dot(s.wi, hit->ns) > 0.0f)) return Seen::backfacing;
    // A sphere's normal is the module's, from its float point: a camera 1e5 away puts it
    // up to about 0.01 off (the framework never replaces a module's normal). Where the
    // exact normal at the refined point turns away from the light, the point faces away
    // and its shadow ray rightly meets the sphere: not acne
    for (const SceneSphere& sphere : scene.spheres) {
        const DVec3 f = DVec3(hit->position) - DVec3(sphere.sphere.c);
        if (std::abs(glm::length(f) - double(sphere.sphere.r)) > 1e-3 * sphere.sphere.r)
            continue;
        const DVec3 exact = glm::dot(f, DVec3(hit->ns)) < 0.0 ? -f : f;
        if (!(glm::dot(exact, DVec3(s.wi)) > 0.0)) return Seen::backfacing;
    }
    return m.in_shadow(occluder, hit->position, hit->ns, s) ? Seen::shadowed : Seen::lit;
}

bool shadowed_at(const Scene& scene, const Vec3& x, const Vec3& n, const Vec3& light) {
    const ModuleTable& m = reference_modules();
    TraceCounters counters;
    const SceneOccluder occluder(scene, m, counters);
    const LightSample s = m.sample_point_light(PointLight{light, Vec3(1.0f)}, x);
    return m.in_shadow(occluder, x, n, s);
}

Scene empty_scene() {
    Scene s;
    s.materials.push_back(Material{"grey", Vec3(0.5f), Vec3(0.0f)});
    return s;
}

void add_mesh(Scene& s, const Mesh& m) {
    for (const auto& f : m.f)
        s.triangles.push_back(SceneTriangle{m.v[f[0]], m.v[f[1]], m.v[f[2]]});
}

// A unit vector u with u . n >= cos_min (and < 1), from rng
Vec3 direction_near(Rng& rng, const Vec3& n, float cos_min) {
    for (;;) {
        const Vec3 u = rng.direction();
        if (glm::dot(u, n) >= cos_min) return u;
    }
}

// Two unit vectors orthogonal to n
std::pair<Vec3, Vec3> tangents(const Vec3& n) {
    const Vec3 a = std::abs(n.x) < 0.6f ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    const Vec3 t = glm::normalize(glm::cross(n, a));
    return {t, glm::cross(n, t)};
}

}  // namespace

TEST_SUITE("stress shadows") {
    TEST_CASE("a camera ray from 1e4 away hits a bare plane that is lit there") {
        Scene scene = empty_scene();
        scene.planes.push_back({Plane{Vec3(0, 1, 0), 0.0f}, 0});
        scene.commit();
        const Ray r{Vec3(6000, 7000, 3000),
                    Vec3(-0x1.3cd83ep-1f, -0x1.71a806p-1f, -0x1.3ce866p-2f), 0.0f,
                    kInfinity};
        Hit hit;
        const Seen seen = shade(scene, r, Vec3(0.5f, 2.0f, -0.3f), &hit);
        INFO("hit at " << show(hit.position) << ", t = " << hit.t);
        // Before the fix: 4.9e-4 below the plane, and shadowed by nothing but the plane
        CHECK(std::abs(hit.position.y) <= delta(hit.position));
        CHECK(seen == Seen::lit);
    }

    TEST_CASE("an occluder 1e-4 above a point at |p| = 1 (1e-2 at 1e4) is found") {
        for (const float scale : {1.0f, 1e4f}) {
            const float gap = scale == 1.0f ? 1e-4f : 1e-2f;
            const Vec3 x = scale * Vec3(0.6f, 0.0f, 0.8f), up(0, 1, 0);
            const Vec3 light = x + Vec3(0.5f, 2.0f, -0.3f);
            INFO("x = " << show(x) << ", gap " << gap);
            // Each kind of occluder alone above the floor y = 0
            Scene plane = empty_scene(), quad = empty_scene(), ball = empty_scene();
            plane.planes.push_back({Plane{Vec3(0, 1, 0), 0.0f}, 0});
            quad.planes = ball.planes = plane.planes;
            plane.planes.push_back({Plane{Vec3(0, -1, 0), gap}, 0});
            const Vec3 a = x + Vec3(-1, gap, -1), b = x + Vec3(1, gap, -1),
                       c = x + Vec3(1, gap, 1), d = x + Vec3(-1, gap, 1);
            quad.triangles = {SceneTriangle{a, b, c}, SceneTriangle{a, c, d}};
            ball.spheres.push_back({Sphere{x + Vec3(0.0f, gap + 10.0f, 0.0f), 10.0f}, 0});
            for (Scene* s : {&plane, &quad, &ball})
                s->commit();
            CHECK(shadowed_at(plane, x, up, light));
            CHECK(shadowed_at(quad, x, up, light));
            CHECK(shadowed_at(ball, x, up, light));
        }
    }

    TEST_CASE("cameras 1e4 and 1e5 from planes, spheres and meshes see no shadow acne") {
        // Each object alone is convex (or a plane), so every point that faces the light
        // is lit: a shadowed one is acne. Objects near the origin and at 1e3; cameras
        // 1e4 and 1e5 from them in random directions on the visible side, lights 1 to 10
        // from the object at random, grazing ones included (any cos > 0 counts)
        const std::string kinds[] = {"plane", "sphere", "icosphere"};
        for (int kind = 0; kind < 3; ++kind) {
            for (const float at : {0.0f, 1e3f}) {
                for (const float far : {1e4f, 1e5f}) {
                    const std::uint64_t seed =
                        std::uint64_t(kind) * 100 + (at > 0 ? 10 : 0) + (far > 1e4f);
                    Rng rng(seed);
                    INFO(kinds[kind] << " at " << at << ", camera " << far
                                     << " away, seed " << seed);
                    const Vec3 centre = at * glm::normalize(Vec3(0.3f, -0.5f, 0.8f));
                    const Vec3 up = glm::normalize(Vec3(0.1f, 1.0f, -0.2f));
                    Scene scene = empty_scene();
                    if (kind == 0)
                        scene.planes.push_back({Plane{up, -glm::dot(up, centre)}, 0});
                    if (kind == 1) scene.spheres.push_back({Sphere{centre, 1.0f}, 0});
                    if (kind == 2) add_mesh(scene, placed(icosphere(), 1.0f, centre));
                    scene.commit();
                    int lit = 0, acne = 0;
                    for (int k = 0; k < 3000; ++k) {
                        const Vec3 side = kind == 0 ? up : rng.direction();
                        const Vec3 eye = centre + far * direction_near(rng, side, 0.3f);
                        const Vec3 target = centre + rng.in_box(-1.0f, 1.0f);
                        // Drawn one per statement: argument order is unspecified
                        const float dist = rng.uniform(1.5f, 10.0f);
                        const Vec3 light =
                            centre + dist * (kind == 0 ? direction_near(rng, up, 0.01f)
                                                       : rng.direction());
                        const Ray r{eye, glm::normalize(target - eye), 0.0f, kInfinity};
                        Hit hit;
                        const Seen seen = shade(scene, r, light, &hit);
                        lit += seen == Seen::lit;
                        acne += seen == Seen::shadowed;
                        if (seen == Seen::shadowed)
                            MESSAGE("ray " << show(r.o) << " " << show(r.w) << " hits "
                                           << show(hit.position) << ", light "
                                           << show(light) << " ns " << show(hit.ns)
                                           << " n " << show(hit.n));
                    }
                    MESSAGE(kinds[kind] << " at " << at << ", camera " << far << ": "
                                        << acne << " of " << lit + acne
                                        << " lit points shadowed");
                    CHECK(lit > 300);
                    CHECK(acne == 0);
                }
            }
        }
    }

    TEST_CASE("occluders 20 error bounds above the point are found, at any distance") {
        // x on a plane of random orientation, as the framework returns hit points (within
        // delta = delta(x) of the surface), an occluder (plane, triangle, sphere) 20
        // delta above it, the light within 60 degrees of n. The reference's shadow ray
        // starts 4 delta off the surface and ignores t < 8 delta, so it looks for
        // occluders from at most delta (x below or above the surface) + 4 delta (offset)
        // + delta (rounding of the origin) + 8 delta cos (tmin) <= 14 delta above the
        // surface; every occluder whose rounded position is at least 15 delta high must
        // be found
        for (int seed = 0; seed < 400; ++seed) {
            Rng rng(7000 + seed);
            const float scale = std::pow(10.0f, float(seed % 6));  // 1 .. 1e5
            const Vec3 n = rng.direction();
            const Vec3 x0 = scale * rng.in_box(-1.0f, 1.0f);
            const Plane surface{n, -glm::dot(n, x0)};
            // The surface point nearest x0, rounded: within delta of the surface
            const DVec3 nd(n);
            const DVec3 exact =
                DVec3(x0) - (glm::dot(DVec3(x0), nd) + surface.d) / glm::dot(nd, nd) * nd;
            const Vec3 x(exact);
            const float d = delta(x);
            const float gap = 20.0f * d;
            const float dist = rng.uniform(0.5f, 20.0f);
            const Vec3 light = x + dist * scale * direction_near(rng, n, 0.5f);
            const int kind = seed / 6 % 3;
            INFO("seed " << seed << ": x = " << show(x) << ", n = " << show(n)
                         << ", delta " << d << ", gap " << gap << ", occluder kind "
                         << kind);
            Scene scene = empty_scene();
            scene.planes.push_back({surface, 0});
            const Vec3 above = x + gap * n;
            double actual = 0.0;  // the occluder's distance from the surface, in double
            const auto height = [&](const Vec3& p) {
                return (glm::dot(DVec3(p), nd) + double(surface.d)) / glm::length(nd);
            };
            if (kind == 0) {
                const Plane occ{-n, glm::dot(n, above)};
                scene.planes.push_back({occ, 0});
                actual = (double(occ.d) + double(surface.d)) / glm::length(nd);
            } else if (kind == 1) {
                const auto [t, b] = tangents(n);
                const float size = 1e3f * gap + 1.0f;
                const Vec3 v0 = above + size * (-t - b), v1 = above + size * (t - b),
                           v2 = above + size * (t + b), v3 = above + size * (b - t);
                scene.triangles = {SceneTriangle{v0, v1, v2}, SceneTriangle{v0, v2, v3}};
                actual = std::min({height(v0), height(v1), height(v2), height(v3)});
            } else {
                const float radius = 1e3f * gap + 1.0f;
                const Sphere ball{above + radius * n, radius};
                scene.spheres.push_back({ball, 0});
                actual = glm::length(DVec3(ball.c) - DVec3(x)) - double(ball.r) - d;
            }
            scene.commit();
            if (actual < 15.0 * d) continue;  // rounding moved the occluder too close
            CHECK(shadowed_at(scene, x, n, light));
        }
    }

    TEST_CASE("inside corners of empty rooms near and far stay lit") {
        // A room of six planes (inward normals) or twelve triangles, light inside: no
        // point inside sees anything between it and the light. Camera rays aimed exactly
        // at points on the edges where two walls meet, the worst case. The closest-hit
        // query compares float t's: where two walls are hit within ulp(t) of each other
        // it may pick the farther one, whose exact point lies up to ulp(t) |w . n| past
        // the nearer wall. The shadow ray crosses that wall at t <= ulp(t) / cos, which
        // tmin = 4 delta(x) covers unless the light grazes the wall; with the light 0.3
        // half-widths from every wall about 0.1 % of exact edge points stay dark near the
        // origin (where t > |x|), none from 1e2 on. A shadow ray with tmin = 0 blackens
        // 66-100 % of them. Bound: 0.5 %
        for (const float at : {0.0f, 1e2f, 1e4f}) {
            for (const bool triangles : {false, true}) {
                const std::uint64_t seed = std::uint64_t(at) + triangles;
                Rng rng(seed);
                const std::string what =
                    std::string(triangles ? "triangle" : "plane") + " room at ";
                INFO(what << at << ", seed " << seed);
                const Vec3 c = at * glm::normalize(Vec3(1.0f, 0.4f, -0.7f));
                Scene scene = empty_scene();
                if (triangles) {
                    add_mesh(scene, placed(cube(), 2.0f, c));
                } else {
                    for (int axis = 0; axis < 3; ++axis)
                        for (const float s : {-1.0f, 1.0f}) {
                            Vec3 nrm(0.0f);
                            nrm[axis] = -s;
                            scene.planes.push_back(
                                {Plane{nrm, 2.0f - glm::dot(nrm, c)}, 0});
                        }
                }
                scene.lights.push_back(
                    PointLight{c + Vec3(0.3f, 1.2f, -0.4f), Vec3(5.0f)});
                scene.commit();
                int lit = 0, dark = 0;
                for (int k = 0; k < 3000; ++k) {
                    const Vec3 eye = c + rng.in_box(-1.5f, 1.5f);
                    const Vec3 light = c + rng.in_box(-1.4f, 1.4f);
                    // A point on one of the 12 edges: two coordinates at +-2, one free
                    const int free = int(rng.next() % 3);
                    Vec3 e(rng.uniform(-2.0f, 2.0f));
                    e[(free + 1) % 3] = rng.uniform(0.0f, 1.0f) < 0.5f ? -2.0f : 2.0f;
                    e[(free + 2) % 3] = rng.uniform(0.0f, 1.0f) < 0.5f ? -2.0f : 2.0f;
                    const Vec3 target = c + e;
                    const Ray r{eye, glm::normalize(target - eye), 0.0f, kInfinity};
                    Hit hit;
                    const Seen seen = shade(scene, r, light, &hit);
                    lit += seen == Seen::lit;
                    dark += seen == Seen::shadowed;
                    if (seen == Seen::shadowed)
                        MESSAGE("edge point " << show(target) << " seen from "
                                              << show(eye) << " at " << show(hit.position)
                                              << " shadowed from " << show(light));
                }
                MESSAGE(what << at << ": " << dark << " of " << lit + dark
                             << " edge points shadowed");
                CHECK(lit > 1000);
                CHECK(dark * 200 <= lit + dark);
                // A whole image (pixel centres, corners and edges in view): shadows on
                // and off give the same picture, pixel for pixel
                RenderSettings settings;
                settings.width = 96;
                settings.height = 96;
                const View view{c + Vec3(1.9f, 1.9f, 1.9f), c - Vec3(2.0f), Vec3(0, 1, 0),
                                100.0f};
                Image on, off;
                render(scene, view, settings, reference_modules(), on);
                settings.shadows = false;
                render(scene, view, settings, reference_modules(), off);
                int differ = 0;
                for (size_t k = 0; k < on.pixels.size(); ++k)
                    differ += on.pixels[k] != off.pixels[k];
                CHECK(differ == 0);
            }
        }
    }

    TEST_CASE("the Lambert image of a lit plane 1e2-1e5 from the origin is analytic") {
        // L = rho / pi I cos / r^2 at the exact intersection of each (float) camera ray
        // with the (float) plane, in double. The framework's hit point lies within e =
        // delta(x) of that point (raylab/refine.h: the exact intersection, rounded).
        // Moving x by e changes cos / r^2 = n . (p - x) / r^3 by at most e (1 / (r cos)
        // + 3 / r) relative: <= 7 e with cos >= 1/4 and r >= 1, the cases kept here. The
        // light sample and the Lambert sum add about 30 float roundings of u / 2 each.
        // Bound: rel <= 8 delta(x) + 16 u, growing with |p| through delta: 1e-5 at 1e2,
        // 1e-3 at 1e5. A shadowed point (acne) gives L = 0 and fails it outright. Cameras
        // 3 and 1e4 away: a hit point's float error from a far camera is ulp(1e4), far
        // above delta(x) for D <= 1e3
        constexpr float kRho = 0.5f;
        const Vec3 kI(7.0f);
        for (const float D : {1e2f, 1e3f, 1e4f, 1e5f})
            for (const float far : {3.0f, 1e4f}) {
                const Vec3 n = glm::normalize(Vec3(0.1f, 1.0f, 0.05f));
                const Vec3 p0 = D * Vec3(0.6f, 0.0f, 0.8f);
                Scene scene = empty_scene();
                scene.materials[0].rho = Vec3(kRho);
                scene.planes.push_back({Plane{n, -glm::dot(n, p0)}, 0});
                const Plane& plane = scene.planes[0].plane;
                scene.commit();
                const Vec3 light = p0 + Vec3(0.3f, 2.0f, -0.2f);
                const Vec3 eye = p0 + far * glm::normalize(Vec3(1.0f, 3.0f, 2.0f));
                const std::uint64_t seed = std::uint64_t(D) + std::uint64_t(far);
                Rng rng(seed);
                const ModuleTable& m = reference_modules();
                TraceCounters counters;
                const SceneOccluder occluder(scene, m, counters);
                double worst = 0.0;
                int checked = 0;
                for (int k = 0; k < 2000; ++k) {
                    const float u = rng.uniform(-3, 3);
                    const Vec3 target = p0 + Vec3(u, 0.0f, rng.uniform(-3, 3));
                    const Ray r{eye, glm::normalize(target - eye), 0.0f, kInfinity};
                    const auto hit = scene.closest_hit(m, r, counters);
                    REQUIRE(hit);
                    // The exact point and radiance, in double
                    const DVec3 o(r.o), w(r.w), nd(plane.n);
                    const double t = -(glm::dot(o, nd) + plane.d) / glm::dot(w, nd);
                    const DVec3 x = o + t * w, to_light = DVec3(light) - x;
                    const double dist = glm::length(to_light);
                    const double cos = glm::dot(nd, to_light) / (glm::length(nd) * dist);
                    if (cos < 0.25 || dist < 1.0) continue;
                    const double exact = kRho / kPi * kI.x * cos / (dist * dist);
                    // The renderer's radiance for this hit
                    const LightSample s =
                        m.sample_point_light(PointLight{light, kI}, hit->position);
                    std::vector<LightSample> visible;
                    if (!m.in_shadow(occluder, hit->position, hit->ns, s))
                        visible.push_back(s);
                    const Vec3 L = m.lambert(Vec3(kRho), Vec3(0.0f), hit->ns, visible);
                    const double rel = std::abs(double(L.x) - exact) / exact;
                    const double bound =
                        8.0 * double(delta(hit->position)) + 16.0 * double(kUlp);
                    INFO("seed " << seed << ", ray " << k
                                 << ": x = " << show(hit->position) << ", L = " << L.x
                                 << ", exact " << exact);
                    CHECK(rel <= bound);
                    worst = std::max(worst, rel / bound);
                    ++checked;
                }
                MESSAGE("plane at " << D << ", camera " << far << " away: " << checked
                                    << " points, worst error " << worst
                                    << " of the bound");
                CHECK(checked > 500);
            }
    }
}
