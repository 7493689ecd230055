// Section 4: build time, memory and time per ray against mesh size (bench/sections.h).
#include <cmath>
#include <cstdio>

#include "mesh.h"
#include "peer.h"
#include "report.h"
#include "sections.h"

namespace raylab::bench {

namespace {

struct Tables {
    Table build{{"triangles", "raylab commit ms", "Embree 1 thread ms",
                 "Embree 2 threads ms", "raylab/Embree 2 threads", "BVH nodes",
                 "acceleration B/tri", "total B/tri"}};
    Table speed{{"triangles", "rays", "query", "raylab ns/ray", "Embree ns/ray",
                 "raylab/Embree", "nodes/ray", "tests/ray"}};
};

// Embree's MEDIUM (default) build of scene on a device with that many threads: median
// seconds; the last scene stays in peer
double embree_build(const Scene& scene, int threads, int repeats,
                    std::unique_ptr<PeerScene>& peer) {
    std::vector<double> s;
    for (int k = 0; k < repeats; ++k) {
        peer.reset();
        peer = make_peer_scene(scene.triangles, false, threads);
        s.push_back(peer->build_seconds);
    }
    return median(s);
}

void build_row(Scene& scene, int repeats, std::unique_ptr<PeerScene>& peer,
               Tables& tables) {
    // Both builds from the triangles in the order they were generated
    const double commit_s = commit_seconds(scene, repeats);
    const double n = static_cast<double>(scene.triangles.size());
    double embree_s[2] = {NAN, NAN};
    const Scene added = as_added(scene);
    for (int threads = 1; threads <= 2 && peer_available(); ++threads)
        embree_s[threads - 1] = embree_build(added, threads, repeats, peer);
    const double accel = static_cast<double>(scene.acceleration_bytes());
    const double mesh =
        static_cast<double>(scene.triangles.size() * sizeof(SceneTriangle) +
                            scene.normals.size() * sizeof(VertexNormals));
    const auto ms = [](double s) { return std::isnan(s) ? "-" : fmt("%.1f", 1e3 * s); };
    // The targets for meshes of 80k triangles and more
    if (n >= 80000) {
        if (!std::isnan(embree_s[1]))
            record_target(fmt("%zu triangles: build, raylab / Embree MEDIUM (2 threads)",
                              scene.triangles.size()),
                          commit_s / embree_s[1], 2.0, false, "x");
        record_target(fmt("%zu triangles: bytes per triangle, BVH and mesh",
                          scene.triangles.size()),
                      (accel + mesh) / n, 100.0, false, " B");
    }
    tables.build.row({fmt("%zu", scene.triangles.size()), ms(commit_s), ms(embree_s[0]),
                      ms(embree_s[1]),
                      std::isnan(embree_s[1]) ? "-" : fmt("%.2f", commit_s / embree_s[1]),
                      fmt("%zu", scene.bvh().node_count()), fmt("%.1f", accel / n),
                      fmt("%.1f", (accel + mesh) / n)});
}

void speed_rows(const Scene& scene, const ModuleTable& modules, const PeerScene* peer,
                const std::string& name, const std::vector<Ray>& rays, int repeats,
                Tables& tables) {
    TraceCounters counters, scratch;
    std::vector<float> t(rays.size());
    const auto mine = [&](TraceCounters& c) {
        for (size_t k = 0; k < rays.size(); ++k) {
            const std::optional<Hit> hit = scene.closest_hit(modules, rays[k], c);
            t[k] = hit ? hit->t : kInfinity;
        }
    };
    mine(counters);
    std::vector<std::function<void()>> works{[&] { mine(scratch); }};
    std::vector<float> theirs;
    if (peer) works.push_back([&] { peer->closest_hit(rays, theirs); });
    const RoundTimes rounds = interleaved_seconds(repeats, works);
    const std::vector<double> s = rounds.medians();
    const double n = static_cast<double>(rays.size());
    // The target for meshes of 80k to 1M triangles
    const size_t triangles = scene.triangles.size();
    if (peer && triangles >= 80000 && triangles <= 1000000)
        record_target(fmt("%zu triangles, %s rays, 1 thread: raylab / Embree", triangles,
                          name.c_str()),
                      s[1] / s[0], 0.6, true, "", rounds.ratios(1, 0));
    tables.speed.row({fmt("%zu", triangles), name, "closest", fmt("%.0f", 1e9 * s[0] / n),
                      peer ? fmt("%.0f", 1e9 * s[1] / n) : "-",
                      peer ? fmt("%.3f", s[1] / s[0]) : "-",
                      fmt("%.1f", static_cast<double>(counters.bvh_nodes) / n),
                      fmt("%.1f", static_cast<double>(counters.intersection_tests) / n)});
}

}  // namespace

void run_scaling_section(const BenchOptions& opt) {
    const int rays = opt.quick ? 16384 : 65536;
    print_heading(
        "4. Scaling: build, memory and time per ray against mesh size",
        fmt("%s. Meshes: the displaced sphere of section 2 at 1e3 .. %d triangles. "
            "raylab commit: validation, BVH build (all cores from 4,096 primitives, one "
            "per 2,048) and the degenerate-triangle flags, median of %d. Embree: "
            "rtcCommitScene at the default (MEDIUM) build quality on a device with "
            "threads=1 and 2. Bytes: acceleration = BVH nodes + primitive order; total "
            "adds the scene's own triangles (40 bytes each: vertices, material) and "
            "vertex normals when the mesh has them (36 bytes per triangle). Time per "
            "ray: the camera rays of a %dx%d image of the scene's view and %d random "
            "rays, one thread, raylab and Embree interleaved, median of %d.",
            peer_description().c_str(), opt.max_triangles, opt.repeats, 256, rays / 256,
            rays, opt.repeats));
    const ModuleTable modules = ModuleTable::make(ModuleSelection::all(Impl::reference));
    Tables tables;
    for (const double size : {1e3, 1e4, 1e5, 1e6, 2e6}) {
        if (size > opt.max_triangles) break;
        Scene scene = displaced_sphere(static_cast<int>(size));
        std::unique_ptr<PeerScene> peer;
        build_row(scene, opt.repeats, peer, tables);
        Rng rng(opt.seed, 500 + static_cast<std::uint64_t>(std::log10(size)));
        speed_rows(scene, modules, peer.get(), "camera",
                   camera_rays(scene, modules, 256, rays / 256), opt.repeats, tables);
        speed_rows(scene, modules, peer.get(), "random", random_rays(scene, rng, rays),
                   opt.repeats, tables);
    }
    std::printf("### Build and memory\n\n");
    tables.build.print();
    std::printf("### Time per ray against size (one thread)\n\n");
    tables.speed.print();
}

}  // namespace raylab::bench
