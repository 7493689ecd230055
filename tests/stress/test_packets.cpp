// The engine's packets (GeometryEngine::closest_hit_packet) on the kernels' hard cases:
// rays from one point exactly through the vertices and edges of closed meshes, at scales
// 0.01-10 and offsets up to 1e5, grouped so that they travel as packets (one octant, one
// dominant axis); and the camera blocks of cameras far from the scene and the origin.
// Every ray's hit equals the single-ray query's bit for bit, and no ray leaves a closed
// mesh.
#include <doctest/doctest.h>

#include <map>
#include <string>

#include "meshes.h"
#include "raylab/scene.h"
#include "raylab/scenes.h"
#include "test_helpers.h"

using namespace raylab;

namespace {

// Rays grouped by the signs of their components and their dominant axis, in packets of
// 16: the groups a packet accepts (a component of zero goes with the others, which the
// packet sends back to single rays)
std::vector<std::vector<Ray>> as_packets(const std::vector<Ray>& rays) {
    std::map<int, std::vector<Ray>> groups;
    for (const Ray& r : rays) {
        const Vec3 a = glm::abs(r.w);
        const int kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
        const bool zero = r.w.x == 0.0f || r.w.y == 0.0f || r.w.z == 0.0f;
        const int key =
            zero ? -1 : kz * 8 + (r.w.x < 0.0f) + 2 * (r.w.y < 0.0f) + 4 * (r.w.z < 0.0f);
        groups[key].push_back(r);
    }
    std::vector<std::vector<Ray>> packets;
    for (const auto& entry : groups) {
        const std::vector<Ray>& g = entry.second;
        for (size_t first = 0; first < g.size(); first += 16)
            packets.emplace_back(g.begin() + long(first),
                                 g.begin() + long(std::min(first + 16, g.size())));
    }
    return packets;
}

}  // namespace

TEST_SUITE("stress packets") {
    TEST_CASE("packets from inside closed meshes through vertices and edges never leak") {
        const std::pair<const char*, Mesh> meshes[] = {
            {"octahedron", octahedron()}, {"cube", cube()}, {"icosphere", icosphere()}};
        int rays = 0, packed = 0;
        for (const auto& entry : meshes) {
            const char* name = entry.first;
            for (const float scale : {0.01f, 1.0f, 10.0f}) {
                for (const float D : {1.0f, 1e3f, 1e5f}) {
                    const std::uint64_t seed =
                        std::hash<std::string>{}(name) ^ std::uint64_t(scale * 1e3f + D);
                    INFO(name << " scale " << scale << " at " << D << ": seed " << seed);
                    Rng rng(seed);
                    const Vec3 at(D, -0.5f * D, 0.25f * D);
                    const Mesh m = placed(entry.second, scale, at);
                    const Scene scene = scene_of(m);
                    // Targets: every vertex and points along every edge
                    const std::vector<Vec3> targets = vertex_and_edge_points(m);
                    for (int k = 0; k < 4; ++k) {
                        // One origin per packet: the centre, or a random inside point
                        const Vec3 o =
                            k == 0 ? at : at + 0.3f * scale * rng.in_box(-1.0f, 1.0f);
                        std::vector<Ray> all;
                        for (const Vec3& target : targets) {
                            const Vec3 d = target - o;
                            if (glm::length(d) > 0.0f)
                                all.push_back({o, glm::normalize(d), 0.0f, kInfinity});
                        }
                        for (const std::vector<Ray>& packet : as_packets(all)) {
                            TraceCounters counters;
                            const int hits = check_packets(scene, packet, counters);
                            CHECK(hits == int(packet.size()));  // from inside: no leak
                            rays += int(packet.size());
                            packed += packet.size() > 1 ? int(packet.size()) : 0;
                        }
                    }
                }
            }
        }
        MESSAGE(rays << " rays in packets from inside closed meshes");
        CHECK(packed > 5000);
    }

    TEST_CASE("camera blocks of cameras far from the scene and from the origin") {
        for (const float D : {0.0f, 1e4f, 1e5f}) {
            for (const float back : {1.0f, 1e3f}) {
                INFO("scene at " << D << ", camera " << back << " times farther back");
                Scene scene = translated(cornell_box(), Vec3(D, -0.5f * D, 0.25f * D));
                View view = scene.view;
                view.eye = view.lookat + back * (view.eye - view.lookat);
                view.fov = view.fov / back;
                TraceCounters counters;
                const int hits =
                    check_packets(scene, camera_blocks(view, 64, 48), counters);
                // Seen from afar the box fills less of the image (its open front nearly
                // square-on): a third of the pixels
                CHECK(hits > 1000);
            }
        }
    }
}
