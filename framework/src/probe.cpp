// The pixel probe's lights (raylab/renderer.h, probe_pixel): each light as the renderer's
// direct_light treats it, with the rays the shadow module asked about and what blocks
// them. Area lights are probed with the very sample points the renderer draws.
#include "raylab/error.h"
#include "render_sampling.h"

namespace raylab::detail {

namespace {

// The scene's any-hit query, recording each ray the shadow module asks about
class RecordingOccluder : public Occluder {
  public:
    RecordingOccluder(const Scene& scene, const ModuleTable& modules,
                      std::vector<Ray>& rays)
        : scene_(scene), modules_(modules), rays_(rays) {}
    bool occluded(const Ray& r) const override {
        rays_.push_back(r);
        return scene_.any_hit(modules_, r, counters_);
    }

  private:
    const Scene& scene_;
    const ModuleTable& modules_;
    std::vector<Ray>& rays_;
    mutable TraceCounters counters_;
};

// Names the closest primitive on r by testing every one (a probe, not a frame: the
// linear scan costs a millisecond on large meshes and needs no primitive ids in Hit).
// Of primitives hit at the same t, the first kind (planes, spheres, triangles) and in it
// the lowest index wins: triangles by their source, not where commit() moved them
void name_blocker(const Scene& scene, const ModuleTable& modules, const Ray& r,
                  LightProbe& out) {
    const char* best_kind = nullptr;
    size_t best = 0;
    const auto keep = [&](const std::optional<Hit>& h, const char* kind, size_t k) {
        if (!h || !(h->t >= r.tmin && h->t <= r.tmax)) return;
        if (out.blocker && !(h->t < out.blocker->t) &&
            !(h->t == out.blocker->t && kind == best_kind && k < best))
            return;
        out.blocker = h, best_kind = kind, best = k;
        out.blocker_name = std::string(kind) + " " + std::to_string(k);
    };
    for (size_t k = 0; k < scene.planes.size(); ++k)
        keep(modules.intersect_plane(r, scene.planes[k].plane), "plane", k);
    for (size_t k = 0; k < scene.spheres.size(); ++k)
        keep(modules.intersect_sphere(r, scene.spheres[k].sphere), "sphere", k);
    for (size_t k = 0; k < scene.triangles.size(); ++k) {
        const SceneTriangle& tri = scene.triangles[k];
        keep(modules.intersect_triangle(r, tri.v0, tri.v1, tri.v2), "triangle",
             scene.triangle_source(k));
    }
}

// One point light: its sample, the backfacing skip, the shadow test
LightProbe probe_point_light(const Scene& scene, const RenderSettings& settings,
                             const ModuleTable& modules, const Hit& hit, size_t k) {
    LightProbe lp;
    lp.light = int(k);
    lp.sample = modules.sample_point_light(scene.lights[k], hit.position);
    lp.backfacing = !(glm::dot(hit.ns, lp.sample.wi) > 0.0f);
    if (!lp.backfacing && settings.shadows) {
        RecordingOccluder occluder(scene, modules, lp.rays);
        lp.tested = true;
        lp.blocked = modules.in_shadow(occluder, hit.position, hit.ns, lp.sample);
        if (!lp.rays.empty()) name_blocker(scene, modules, lp.rays.front(), lp);
    }
    return lp;
}

// The area light that stands in for point light k: the renderer's N sample points (the
// same generator, seeded from the camera sample uv), each skipped or tested as there
LightProbe probe_area_light(const Scene& scene, const RenderSettings& settings,
                            const ModuleTable& modules, const Hit& hit, const Vec2& uv,
                            size_t k) {
    LightProbe lp;
    lp.light = int(k);
    const AreaLight area =
        area_light_for(scene.lights[k], settings.light_size, scene.bounds().centre());
    const int N = settings.light_samples;
    const std::vector<Vec2> xi = modules.light_sample_points(N, settings.light_stratified,
                                                             light_rng(settings, uv, k));
    lp.area = true;
    lp.samples = int(xi.size());
    bool tested_one = false, shown = false;  // shown: lp.sample is a blocked sample
    for (const Vec2& p : xi) {
        const LightSample sample = modules.sample_area_light(area, hit.position, p, N);
        if (&p == &xi.front()) lp.sample = sample;
        if (!(glm::dot(hit.ns, sample.wi) > 0.0f)) {
            ++lp.backfacing_samples;
            continue;
        }
        bool blocked = false;
        if (settings.shadows) {
            std::vector<Ray> rays;
            RecordingOccluder occluder(scene, modules, rays);
            lp.tested = true;
            blocked = modules.in_shadow(occluder, hit.position, hit.ns, sample);
            if (!shown && (blocked || !tested_one)) {
                lp.sample = sample;
                lp.rays = std::move(rays);
                shown = blocked;
            }
            tested_one = true;
        }
        if (blocked) {
            ++lp.blocked_samples;
            continue;
        }
        ++lp.visible_samples;
        lp.Li_visible += sample.Li;
    }
    lp.backfacing = !xi.empty() && lp.backfacing_samples == int(xi.size());
    lp.blocked = lp.blocked_samples > 0;
    if (!lp.rays.empty()) name_blocker(scene, modules, lp.rays.front(), lp);
    return lp;
}

}  // namespace

void probe_lights(const Scene& scene, const RenderSettings& settings,
                  const ModuleTable& modules, PixelProbe& probe) {
    if (settings.mode != ShadingMode::lambert || !probe.hit) return;
    for (size_t k = 0; k < scene.lights.size(); ++k) {
        probe.lights.push_back(
            settings.light_size > 0.0f
                ? probe_area_light(scene, settings, modules, *probe.hit, probe.uv, k)
                : probe_point_light(scene, settings, modules, *probe.hit, k));
    }
}

}  // namespace raylab::detail
