// A ray from inside a closed mesh can never escape it.
// Closed meshes (octahedron: fans of 4, cube, icosphere) at scales 0.01-10 and offsets up
// to 1e5, rays from inside aimed exactly at vertices and at edge points, from random and
// axis-aligned directions, through the bare kernel and through Scene: 0 leaks.
#include <doctest/doctest.h>

#include <string>

#include "meshes.h"
#include "raylab/scene.h"
#include "test_helpers.h"

using namespace raylab;

namespace {

bool kernel_hits(const Mesh& m, const Ray& r) {
    for (const auto& t : m.f)
        if (reference::intersect_triangle(r, m.v[t[0]], m.v[t[1]], m.v[t[2]]))
            return true;
    return false;
}

}  // namespace

TEST_SUITE("stress closed meshes") {
    TEST_CASE("rays from inside aimed at vertices and edges never leave a closed mesh") {
        const std::pair<const char*, Mesh> meshes[] = {
            {"octahedron", octahedron()}, {"cube", cube()}, {"icosphere", icosphere()}};
        int rays = 0;
        for (const auto& entry : meshes) {
            // Not a structured binding: clang 14 cannot capture one in INFO's lambda
            const char* name = entry.first;
            const Mesh& unit = entry.second;
            for (const float scale : {0.01f, 1.0f, 10.0f}) {
                for (const float D : {1.0f, 1e3f, 1e5f}) {
                    const std::uint64_t seed =
                        std::hash<std::string>{}(name) ^ std::uint64_t(scale * 1e3f + D);
                    MESSAGE(name << " scale " << scale << " at " << D << ": seed "
                                 << seed);
                    Rng rng(seed);
                    const Vec3 at(D, -0.5f * D, 0.25f * D);
                    const Mesh m = placed(unit, scale, at);
                    const Scene scene = scene_of(m);
                    // Targets: every vertex and points along every edge
                    const std::vector<Vec3> targets = vertex_and_edge_points(m);
                    for (const Vec3& target : targets) {
                        // Origins inside: the centre (axis-aligned rays through the
                        // octahedron's vertices) and random points within 0.3 scale of it
                        for (int k = 0; k < 3; ++k) {
                            const Vec3 o =
                                k == 0 ? at : at + 0.3f * scale * rng.in_box(-1.0f, 1.0f);
                            const Vec3 d = target - o;
                            if (glm::length(d) == 0.0f) continue;
                            const Ray r{o, glm::normalize(d), 0.0f, kInfinity};
                            ++rays;
                            TraceCounters counters;
                            const bool through_scene =
                                scene.closest_hit(reference_modules(), r, counters)
                                    .has_value();
                            if (!kernel_hits(m, r) || !through_scene) {
                                INFO(name << " leak: " << r);
                                CHECK(kernel_hits(m, r));
                                CHECK(through_scene);
                            }
                        }
                    }
                    // Rays from outside entering the convex mesh at a vertex or an edge
                    // point: they cross the surface, so they must hit
                    for (const Vec3& target : targets) {
                        for (int k = 0; k < 8; ++k) {
                            // Towards a point inside: the line leaves the convex
                            // mesh at the target, so the origin behind it is outside
                            const Vec3 inside =
                                at + 0.3f * scale * rng.in_box(-1.0f, 1.0f);
                            const Vec3 w = glm::normalize(inside - target);
                            const Ray r{target - 3.0f * scale * w, w, 0.0f, kInfinity};
                            ++rays;
                            TraceCounters counters;
                            const bool through_scene =
                                scene.closest_hit(reference_modules(), r, counters)
                                    .has_value();
                            if (!kernel_hits(m, r) || !through_scene) {
                                INFO(name << " entry leak: " << r);
                                CHECK(kernel_hits(m, r));
                                CHECK(through_scene);
                            }
                        }
                    }
                    // Axis-aligned rays from the centre and from random inside points
                    for (int axis = 0; axis < 6; ++axis) {
                        Vec3 w(0.0f);
                        w[axis / 2] = axis % 2 ? -1.0f : 1.0f;
                        for (int k = 0; k < 20; ++k) {
                            const Vec3 o =
                                k == 0 ? at : at + 0.3f * scale * rng.in_box(-1.0f, 1.0f);
                            const Ray r{o, w, 0.0f, kInfinity};
                            ++rays;
                            TraceCounters counters;
                            INFO(name << " axis leak: " << r);
                            CHECK(kernel_hits(m, r));
                            CHECK(scene.closest_hit(reference_modules(), r, counters));
                        }
                    }
                }
            }
        }
        MESSAGE(rays << " rays into and out of closed meshes");
        CHECK(rays > 10000);
    }
}
