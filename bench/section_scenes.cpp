// Section 2: raylab against Embree on the same rays (bench/sections.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <thread>

#include "mesh.h"
#include "peer.h"
#include "raylab/engine.h"
#include "raylab/scenes.h"
#include "report.h"
#include "sections.h"

namespace raylab::bench {

namespace {

// One set of rays and the query it is traced with
struct QuerySet {
    std::string name;
    bool closest;  // closest hit; otherwise any hit
    std::vector<Ray> rays;
};

// What one tracer returned for a query set
struct Traced {
    std::vector<float> t;   // closest hit: t or kInfinity
    std::vector<char> hit;  // hit or miss (both queries)
};

// One pass of raylab over the set
void raylab_pass(const Scene& scene, const ModuleTable& modules, const QuerySet& q,
                 Traced& out, TraceCounters& counters) {
    const size_t n = q.rays.size();
    out.t.assign(n, kInfinity);
    out.hit.assign(n, 0);
    // Shadow rays as the renderer asks: one hint (the last blocker) for the pass's rays
    AnyHitHint hint;
    for (size_t k = 0; k < n; ++k) {
        if (q.closest) {
            const std::optional<Hit> hit =
                scene.closest_hit(modules, q.rays[k], counters);
            out.t[k] = hit ? hit->t : kInfinity;
            out.hit[k] = hit.has_value();
        } else {
            out.hit[k] = scene.any_hit(modules, q.rays[k], counters, &hint);
        }
    }
}

// One pass of the peer over the set
void peer_pass(const PeerScene& peer, const QuerySet& q, Traced& out) {
    if (q.closest) {
        peer.closest_hit(q.rays, out.t);
        out.hit.resize(out.t.size());
        for (size_t k = 0; k < out.t.size(); ++k)
            out.hit[k] = out.t[k] < kInfinity;
    } else {
        peer.any_hit(q.rays, out.hit);
    }
}

// Hit/miss agreement by direction, and where both hit: how often t differs by more than
// 1e-4 relative (another surface) and the largest |t_a - t_b| / t_b
std::vector<std::string> agreement_cells(const QuerySet& q, const Traced& a,
                                         const Traced& b) {
    size_t agree = 0, only_a = 0, only_b = 0, other_surface = 0;
    double max_dt = 0.0;
    for (size_t k = 0; k < q.rays.size(); ++k) {
        agree += a.hit[k] == b.hit[k];
        only_a += a.hit[k] && !b.hit[k];
        only_b += !a.hit[k] && b.hit[k];
        if (q.closest && a.hit[k] && b.hit[k] && b.t[k] > 0.0f) {
            const double dt = std::fabs(static_cast<double>(a.t[k]) - b.t[k]) / b.t[k];
            max_dt = std::max(max_dt, dt);
            other_surface += dt > 1e-4;
        }
    }
    const double n = static_cast<double>(q.rays.size());
    return {fmt("%.4f %%", 100.0 * static_cast<double>(agree) / n), fmt("%zu", only_a),
            fmt("%zu", only_b), q.closest ? fmt("%zu", other_surface) : "n/a",
            q.closest ? sci(max_dt) : "n/a"};
}

double mrays(size_t rays, double seconds) {
    return static_cast<double>(rays) / seconds / 1e6;
}

struct Tables {
    Table build{{"scene", "triangles", "raylab commit ms", "raylab BVH nodes",
                 "Embree build ms", "Embree robust build ms"}};
    Table speed{{"scene", "rays", "query", "count", "raylab Mrays/s",
                 "module path Mrays/s", "Embree Mrays/s", "raylab/Embree",
                 "Embree robust Mrays/s", "raylab/robust", "nodes/ray", "tests/ray"},
                3};
    Table speed2{{"scene", "rays", "query", "count", "raylab Mrays/s", "Embree Mrays/s",
                  "raylab/Embree"},
                 3};
    Table packets{{"scene", "threads", "raylab single Mrays/s", "raylab packets Mrays/s",
                   "Embree rtcIntersect1 Mrays/s", "Embree rtcIntersect16 Mrays/s",
                   "packets/Embree 1", "packets/Embree 16", "nodes/ray single",
                   "nodes/ray packets", "differ from single"},
                  2};
    Table parts{
        {"scene", "rays", "query", "Embree ns/ray", "raylab ns/ray", "engine ns/ray",
         "BVH walk ns/ray", "walk %", "leaf tests and engine %", "completion %"},
        3};
    Table agree{{"scene", "rays", "peer", "hit/miss agree", "raylab hits only",
                 "peer hits only", "both hit, |dt|/t > 1e-4", "max |dt|/t"},
                3};
};

std::vector<QuerySet> query_sets(const Scene& scene, const ModuleTable& modules,
                                 const BenchOptions& opt, std::uint64_t stream) {
    std::vector<QuerySet> sets;
    sets.push_back({"camera", true, camera_rays(scene, modules, opt.width, opt.height)});
    sets.push_back({"shadow", false, shadow_rays(scene, modules, sets[0].rays)});
    Rng rng(opt.seed, stream);
    sets.push_back({"random", true, random_rays(scene, rng, opt.width * opt.height)});
    return sets;
}

// Build times: raylab's commit (validation + binned SAH build), Embree's
// rtcCommitScene on a one-thread device, with and without RTC_SCENE_FLAG_ROBUST. Leaves
// the last Embree scenes in peer (null without Embree).
void bench_build(const std::string& name, Scene& scene, const BenchOptions& opt,
                 std::unique_ptr<PeerScene> (&peer)[2], Tables& tables) {
    // Both builds from the triangles in the order they were generated
    const double commit_s = commit_seconds(scene, opt.repeats);
    const std::vector<SceneTriangle> added = as_added(scene).triangles;
    double build_s[2] = {NAN, NAN};
    for (int robust = 0; robust < 2 && peer_available(); ++robust) {
        std::vector<double> s;
        for (int k = 0; k < opt.repeats; ++k) {
            peer[robust] = make_peer_scene(added, robust == 1, 1);
            s.push_back(peer[robust]->build_seconds);
        }
        build_s[robust] = median(s);
    }
    tables.build.row({name, fmt("%zu", scene.triangles.size()),
                      fmt("%.2f", 1e3 * commit_s), fmt("%zu", scene.bvh().node_count()),
                      peer[0] ? fmt("%.2f", 1e3 * build_s[0]) : "-",
                      peer[1] ? fmt("%.2f", 1e3 * build_s[1]) : "-"});
}

// The target for raylab's speed over Embree's: the Cornell box >= 1, meshes of
// 80k to 1M triangles >= 0.6
double embree_target(const std::string& scene_name) {
    return scene_name == "cornell" ? 1.0 : 0.6;
}

// The rays dealt to `threads` threads (1 or 2) in runs of 16 in turn, a packet each
// (not a contiguous half each: the halves of an image differ in cost, so one thread would
// wait on the other, which measures the split more than the tracer)
std::vector<std::vector<Ray>> deal_runs(const std::vector<Ray>& rays, int threads) {
    std::vector<std::vector<Ray>> part(static_cast<size_t>(threads));
    for (size_t first = 0; first < rays.size(); first += 16) {
        std::vector<Ray>& to = part[(first / 16) % part.size()];
        to.insert(to.end(), rays.begin() + long(first),
                  rays.begin() + long(std::min(rays.size(), first + 16)));
    }
    return part;
}

// work(k) for each thread k of `threads` (1 or 2), the second on a thread of its own
void on_threads(int threads, const std::function<void(int)>& work) {
    if (threads == 1) return work(0);
    std::thread helper(work, 1);
    work(0);
    helper.join();
}

// One cache line per thread's counters: written per ray, they must not share one
struct alignas(64) ThreadCounters {
    TraceCounters c;
};

// The set traced by two threads, each taking every other run of 16 rays, raylab's and
// Embree's passes interleaved: one row of the two-thread table
void two_thread_row(const std::string& name, const Scene& scene,
                    const ModuleTable& modules, const PeerScene* peer, const QuerySet& q,
                    int repeats, Table& table) {
    const std::vector<std::vector<Ray>> rays = deal_runs(q.rays, 2);
    const QuerySet parts[2] = {{q.name, q.closest, rays[0]},
                               {q.name, q.closest, rays[1]}};
    Traced out[2];
    ThreadCounters counters[2];
    std::vector<std::function<void()>> works{[&] {
        on_threads(2, [&](int k) {
            raylab_pass(scene, modules, parts[k], out[k], counters[k].c);
        });
    }};
    if (peer)
        works.push_back(
            [&] { on_threads(2, [&](int k) { peer_pass(*peer, parts[k], out[k]); }); });
    const RoundTimes rounds = interleaved_seconds(repeats, works);
    const std::vector<double> s = rounds.medians();
    const size_t n = q.rays.size();
    table.row({name, q.name, q.closest ? "closest" : "any", fmt("%zu", n),
               fmt("%.2f", mrays(n, s[0])), peer ? fmt("%.2f", mrays(n, s[1])) : "-",
               peer ? fmt("%.3f", s[1] / s[0]) : "-"});
    if (peer)
        record_target(name + ", " + q.name + " rays, 2 threads: raylab / Embree",
                      s[1] / s[0], embree_target(name), true, "", rounds.ratios(1, 0));
}

// The camera rays reordered into blocks of 4 x 4 pixels, the order in which the
// renderer traces a tile's camera rays (GeometryEngine::closest_hit_packet)
std::vector<Ray> in_blocks(const std::vector<Ray>& rays, int W, int H) {
    std::vector<Ray> out;
    out.reserve(rays.size());
    for (int by = 0; by < H; by += 4)
        for (int bx = 0; bx < W; bx += 4)
            for (int j = by; j < std::min(by + 4, H); ++j)
                for (int i = bx; i < std::min(bx + 4, W); ++i)
                    out.push_back(rays[size_t(j) * size_t(W) + size_t(i)]);
    return out;
}

// One pass of raylab's packets over rays: Scene::closest_hits, 16 rays at a time
void packet_pass(const Scene& scene, const ModuleTable& modules, const Ray* rays,
                 size_t n, float* t, TraceCounters& counters) {
    constexpr int P = GeometryEngine::kPacketSize;
    std::optional<Hit> hits[P];
    for (size_t first = 0; first < n; first += P) {
        const int m = static_cast<int>(std::min<size_t>(P, n - first));
        scene.closest_hits(modules, rays + first, m, counters, hits);
        for (int k = 0; k < m; ++k)
            t[first + size_t(k)] = hits[k] ? hits[k]->t : kInfinity;
    }
}

// Camera rays in 4 x 4 blocks on 1 and 2 threads (half of the blocks each): raylab one
// ray at a time and in packets, Embree one ray at a time and in packets of 16, all
// interleaved; and whether the packets' t equals the single rays' t everywhere
void packet_rows(const std::string& name, const Scene& scene, const ModuleTable& modules,
                 const PeerScene* peer, const QuerySet& camera, const BenchOptions& opt,
                 Table& table) {
    const std::vector<Ray> rays = in_blocks(camera.rays, opt.width, opt.height);
    const size_t n = rays.size();
    std::vector<float> packed(n);
    TraceCounters cs, cp;
    const QuerySet blocks{camera.name, true, rays};
    Traced traced;
    raylab_pass(scene, modules, blocks, traced, cs);
    packet_pass(scene, modules, rays.data(), n, packed.data(), cp);
    size_t differ = 0;
    for (size_t k = 0; k < n; ++k)
        differ += std::memcmp(&traced.t[k], &packed[k], sizeof(float)) != 0;
    for (const int threads : {1, 2}) {
        // The blocks dealt to the threads in turn, the same for all four
        const std::vector<std::vector<Ray>> part = deal_runs(rays, threads);
        std::vector<float> out[2][4];
        for (int k = 0; k < threads; ++k)
            for (std::vector<float>& o : out[k])
                o.resize(part[size_t(k)].size());
        ThreadCounters counters[2];
        std::vector<std::function<void()>> works{
            [&] {
                on_threads(threads, [&](int k) {
                    for (size_t i = 0; i < part[k].size(); ++i) {
                        const std::optional<Hit> hit =
                            scene.closest_hit(modules, part[k][i], counters[k].c);
                        out[k][0][i] = hit ? hit->t : kInfinity;
                    }
                });
            },
            [&] {
                on_threads(threads, [&](int k) {
                    packet_pass(scene, modules, part[k].data(), part[k].size(),
                                out[k][1].data(), counters[k].c);
                });
            }};
        if (peer) {
            works.push_back([&] {
                on_threads(threads,
                           [&](int k) { peer->closest_hit(part[k], out[k][2]); });
            });
            works.push_back([&] {
                on_threads(threads,
                           [&](int k) { peer->closest_hit16(part[k], out[k][3]); });
            });
        }
        const RoundTimes rounds = interleaved_seconds(opt.repeats, works);
        const std::vector<double> s = rounds.medians();
        const auto speed = [&](size_t k) {
            return k < s.size() ? fmt("%.2f", mrays(n, s[k])) : std::string("-");
        };
        table.row({name, fmt("%d", threads), speed(0), speed(1), speed(2), speed(3),
                   peer ? fmt("%.3f", s[2] / s[1]) : "-",
                   peer ? fmt("%.3f", s[3] / s[1]) : "-",
                   fmt("%.2f", double(cs.bvh_nodes) / double(n)),
                   fmt("%.2f", double(cp.bvh_nodes) / double(n)), fmt("%zu", differ)});
        if (peer)
            record_target(name + ", camera rays in packets, " + fmt("%d", threads) +
                              (threads == 1 ? " thread" : " threads") +
                              ": raylab packets / Embree rtcIntersect1",
                          s[2] / s[1], embree_target(name), true, "",
                          rounds.ratios(2, 1));
    }
}

// Where raylab's time per ray goes, one thread, all passes interleaved with Embree's:
// - raylab: Scene::closest_hit / any_hit, as in the speed table;
// - engine: the reference engine's query alone (raylab/engine.h), without completing
//   the nearest hit (material, shading normal, the hit point refined in double);
// - BVH walk: the query's walk (Bvh::traverse, traverse_any) over the same rays with
//   leaves that test nothing, for a closest hit with tmax set to the hit's t (about the
//   nodes the query visits); for any hit the whole ray (an upper bound: the query stops
//   at its first hit).
// walk %, leaf tests and engine %, completion %: the shares of raylab's time.
void parts_row(const std::string& name, const Scene& scene, const ModuleTable& modules,
               const PeerScene* peer, const QuerySet& q, const Traced& mine, int repeats,
               Table& table) {
    const GeometryEngine* engine = modules.engine;
    if (!engine) return;
    std::vector<Ray> walk_rays = q.rays;
    if (q.closest) {
        for (size_t k = 0; k < walk_rays.size(); ++k)
            if (mine.hit[k]) walk_rays[k].tmax = mine.t[k];
    }
    Traced full, peer_out;
    TraceCounters counters;
    std::vector<std::function<void()>> works{
        [&] { raylab_pass(scene, modules, q, full, counters); },
        [&] {
            float found = 0.0f;
            AnyHitHint hint;
            for (const Ray& r : q.rays) {
                Hit hit;
                PrimRef prim;
                if (q.closest) engine->closest_hit(scene, r, counters, hit, prim);
                found +=
                    q.closest ? prim.index : engine->any_hit(scene, r, counters, &hint);
            }
            g_sink = found;
        },
        [&] {
            std::uint64_t nodes = 0;
            std::uint32_t leaves = 0;
            const auto leaf = [&](std::uint32_t first, std::uint32_t count, float&) {
                leaves += first + count;
                return false;
            };
            for (const Ray& r : walk_rays) {
                if (q.closest) {
                    scene.bvh().traverse(r, leaf, nodes);
                } else {
                    scene.bvh().traverse_any(r, leaf, nodes);
                }
            }
            g_sink = static_cast<float>(leaves);
        }};
    if (peer) works.push_back([&] { peer_pass(*peer, q, peer_out); });
    const std::vector<double> s = interleaved_median_seconds(repeats, works);
    const double n = static_cast<double>(q.rays.size());
    const auto ns = [&](double seconds) { return fmt("%.1f", 1e9 * seconds / n); };
    const auto pct = [&](double part) { return fmt("%.0f", 100.0 * part / s[0]); };
    table.row({name, q.name, q.closest ? "closest" : "any", peer ? ns(s[3]) : "-",
               ns(s[0]), ns(s[1]), ns(s[2]), pct(std::min(s[2], s[1])),
               pct(s[1] - std::min(s[2], s[1])), pct(s[0] - s[1])});
}

// One line naming the scene's size, view and lights, as the tables use them
std::string describe(const std::string& name, const Scene& scene) {
    const auto v = [](const Vec3& p) { return fmt("(%g, %g, %g)", p.x, p.y, p.z); };
    std::string lights;
    for (const PointLight& l : scene.lights)
        lights += (lights.empty() ? "" : ", ") + v(l.p);
    return fmt(
        "- **%s**: %zu triangles, %zu spheres, %zu planes; eye %s, look-at %s, up %s, "
        "vertical field of view %g degrees; point light%s at %s\n",
        name.c_str(), scene.triangles.size(), scene.spheres.size(), scene.planes.size(),
        v(scene.view.eye).c_str(), v(scene.view.lookat).c_str(), v(scene.view.up).c_str(),
        scene.view.fov, scene.lights.size() == 1 ? "" : "s", lights.c_str());
}

// The reference's geometry behind function pointers of their own, as a student's modules
// are: the scene's queries then take the module path, the engine's walk calling them once
// per primitive test, which is where a class's own modules 03-05 run
std::optional<Hit> own_plane(const Ray& r, const Plane& plane) {
    return reference::intersect_plane(r, plane);
}
std::optional<Hit> own_sphere(const Ray& r, const Sphere& sphere) {
    return reference::intersect_sphere(r, sphere);
}
std::optional<Hit> own_triangle(const Ray& r, const Vec3& v0, const Vec3& v1,
                                const Vec3& v2) {
    return reference::intersect_triangle(r, v0, v1, v2);
}

void bench_scene(const std::string& name, Scene& scene, const ModuleTable& modules,
                 const BenchOptions& opt, std::uint64_t stream, Tables& tables) {
    std::unique_ptr<PeerScene> peer[2];
    bench_build(name, scene, opt, peer, tables);
    const std::vector<QuerySet> sets = query_sets(scene, modules, opt, stream);
    // The same reference modules on the module path, as a student's run
    ModuleTable slow = modules;
    slow.intersect_plane = own_plane;
    slow.intersect_sphere = own_sphere;
    slow.intersect_triangle = own_triangle;
    for (const QuerySet& q : sets) {
        // Work counts from one untimed pass; then raylab and the peers interleaved
        Traced mine, theirs[2];
        TraceCounters counters, scratch;
        raylab_pass(scene, modules, q, mine, counters);
        Traced module_path;
        std::vector<std::function<void()>> works{
            [&] { raylab_pass(scene, modules, q, mine, scratch); },
            [&] { raylab_pass(scene, slow, q, module_path, scratch); }};
        for (int robust = 0; robust < 2; ++robust) {
            if (peer[robust])
                works.push_back(
                    [&, robust] { peer_pass(*peer[robust], q, theirs[robust]); });
        }
        const RoundTimes rounds = interleaved_seconds(opt.repeats, works);
        const std::vector<double> s = rounds.medians();
        const double n = static_cast<double>(q.rays.size());
        std::vector<std::string> row{name,
                                     q.name,
                                     q.closest ? "closest" : "any",
                                     fmt("%zu", q.rays.size()),
                                     fmt("%.2f", mrays(q.rays.size(), s[0])),
                                     fmt("%.2f", mrays(q.rays.size(), s[1]))};
        for (int robust = 0; robust < 2; ++robust) {
            if (!peer[robust]) {
                row.insert(row.end(), {"-", "-"});
                continue;
            }
            const double theirs_s = s[static_cast<size_t>(2 + robust)];
            row.push_back(fmt("%.2f", mrays(q.rays.size(), theirs_s)));
            row.push_back(fmt("%.3f", theirs_s / s[0]));
            if (!robust)
                record_target(name + ", " + q.name + " rays, 1 thread: raylab / Embree",
                              theirs_s / s[0], embree_target(name), true, "",
                              rounds.ratios(2, 0));
            std::vector<std::string> a{name, q.name, robust ? "Embree robust" : "Embree"};
            for (std::string& cell : agreement_cells(q, mine, theirs[robust]))
                a.push_back(std::move(cell));
            tables.agree.row(a);
        }
        row.push_back(fmt("%.1f", static_cast<double>(counters.bvh_nodes) / n));
        row.push_back(fmt("%.1f", static_cast<double>(counters.intersection_tests) / n));
        tables.speed.row(row);
        parts_row(name, scene, modules, peer[0].get(), q, mine, opt.repeats,
                  tables.parts);
    }
    for (const QuerySet& q : sets)
        two_thread_row(name, scene, modules, peer[0].get(), q, opt.repeats,
                       tables.speed2);
    packet_rows(name, scene, modules, peer[0].get(), sets[0], opt, tables.packets);
}

}  // namespace

void run_scene_section(const BenchOptions& opt) {
    print_heading(
        "2. Scenes: raylab against Embree on the same rays",
        fmt("%s. raylab: reference modules through Scene::closest_hit / any_hit, which "
            "run the reference's engine (raylab/engine.h); module path: the same "
            "modules behind function pointers of their own, as a student's modules "
            "are, so that the engine's walk calls them once per primitive test through "
            "the same BVH (the speed a class's own modules 03-05 get). raylab "
            "commit: validation and BVH build (all cores from 4,096 primitives). Embree: "
            "default (MEDIUM) build quality, scene flags none or "
            "RTC_SCENE_FLAG_ROBUST, a device with threads=1. Camera rays: %dx%d pixel "
            "centres; shadow rays: the ones render() casts from those hits (recorded "
            "from the shadow module), in its order, and raylab asks any_hit as render() "
            "does, with the hint of the ray before (AnyHitHint: the primitive that "
            "stopped the last blocked ray is tested first; Embree has no such hint); "
            "random: as many incoherent rays from a sphere "
            "around the scene. Mrays/s: median of %d passes, raylab's and Embree's "
            "interleaved; raylab/Embree: raylab's speed divided by Embree's (1 = as "
            "fast). nodes/ray, tests/ray: raylab's 8-wide BVH nodes visited and "
            "primitive tests. Two threads: the rays dealt to them in runs of 16 in turn, "
            "raylab (engine) and Embree (no flags) interleaved.",
            peer_description().c_str(), opt.width, opt.height, opt.repeats));
    const ModuleTable modules = ModuleTable::make(ModuleSelection::all(Impl::reference));
    Tables tables;
    // The icosphere and the soup: a quarter of the other meshes' triangles
    const int quarter = std::max(1000, opt.mesh_triangles / 4);
    // Each scene with its name in the tables and the stream of its random rays. Streams
    // from 600: section 1 takes 100-449 (its sparse sets one per distance from 400),
    // section 4 takes 500-506
    Rng soup_rng(opt.seed, 603);
    struct Benched {
        const char* name;
        Scene scene;
        std::uint64_t stream;
    } scenes[] = {
        {"cornell", cornell_box(), 600},
        {"icosphere", icosphere(quarter), 605},
        {"displaced sphere", displaced_sphere(opt.mesh_triangles), 601},
        {"terrain", terrain(opt.mesh_triangles), 602},
        {"random soup", random_soup(quarter, soup_rng), 604},
    };
    std::printf(
        "The scenes (bench/mesh.h generates the four meshes; camera rays through "
        "the view, shadow rays towards the light):\n\n");
    for (const Benched& b : scenes)
        std::printf("%s", describe(b.name, b.scene).c_str());
    std::printf("\n");
    for (Benched& b : scenes)
        bench_scene(b.name, b.scene, modules, opt, b.stream, tables);

    std::printf("### Build\n\n");
    tables.build.print();
    std::printf("### Speed (one thread)\n\n");
    tables.speed.print();
    std::printf(
        "### Where the time goes (one thread)\n\n"
        "ns per ray, all columns timed interleaved. raylab: Scene::closest_hit / any_hit "
        "as above. engine: the reference engine's query alone (raylab/engine.h), "
        "without completing the nearest hit (material, shading normal, the hit point "
        "refined in double, raylab/refine.h). BVH walk: the query's walk "
        "(Bvh::traverse, traverse_any) over the same rays with leaves that test nothing, "
        "for a closest hit with tmax at the hit "
        "(about the nodes the query visits), for any hit the whole ray (an upper "
        "bound). The shares are of raylab's time: walk, then leaf tests and the rest "
        "of the engine (engine - walk), then completion (raylab - engine).\n\n");
    tables.parts.print();
    std::printf("### Speed (two threads, every other run of 16 rays each)\n\n");
    tables.speed2.print();
    std::printf(
        "### Camera rays in packets\n\n"
        "The camera rays of section 2 in blocks of 4 x 4 pixels, the order in which the "
        "renderer traces a tile (raylab/engine.h, closest_hit_packet). raylab single: "
        "Scene::closest_hit per ray; raylab packets: Scene::closest_hits, 16 rays from "
        "one origin sharing one frustum walk of the BVH and each triangle's "
        "translation, the rest of each test four rays at a time (bit for bit the "
        "single-ray query: \"differ from single\" counts the rays whose t is not "
        "identical). Embree: rtcIntersect1 per ray (incoherent context), and "
        "rtcIntersect16 per block (coherent context), Embree's own packets. Two "
        "threads: the blocks dealt to them in turn. All four interleaved, median of %d "
        "passes.\n\n",
        opt.repeats);
    tables.packets.print();
    if (peer_available()) {
        std::printf("### Agreement of raylab with Embree\n\n");
        tables.agree.print();
    }
}

}  // namespace raylab::bench
