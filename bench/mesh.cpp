// The procedural mesh and the scene section's ray sets (bench/mesh.h).
#include "mesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "raylab/renderer.h"
#include "report.h"

namespace raylab::bench {

namespace {

constexpr double kPiD = 3.14159265358979323846;

// Radius of the bumpy sphere at polar angle theta, azimuth phi; integer frequencies in
// phi keep it continuous across phi = 0, and sin(theta) factors keep the poles round
double displaced_radius(double theta, double phi) {
    return 1.0 + 0.06 * std::sin(7.0 * theta) * std::cos(5.0 * phi) +
           0.03 * std::sin(theta) * std::sin(19.0 * phi + 11.0 * theta) +
           0.01 * std::sin(theta) * std::cos(53.0 * phi - 37.0 * theta);
}

// Adds triangle (a, b, c) wound counter-clockwise seen from outside (the centre is 0)
void add_outward(Scene& scene, const Vec3& a, Vec3 b, Vec3 c) {
    const Vec3 n = glm::cross(b - a, c - a);
    if (glm::dot(n, a + b + c) < 0.0f) std::swap(b, c);
    SceneTriangle t;
    t.v0 = a;
    t.v1 = b;
    t.v2 = c;
    scene.triangles.push_back(t);
}

// The shadow module's any-hit query, recording its rays instead of answering them
class RecordingOccluder : public Occluder {
  public:
    explicit RecordingOccluder(std::vector<Ray>& out) : out_(out) {}
    bool occluded(const Ray& r) const override {
        out_.push_back(r);
        return false;
    }

  private:
    std::vector<Ray>& out_;
};

}  // namespace

Scene icosphere(int triangles) {
    int level = 0;
    while (std::int64_t{20} << (2 * (level + 1)) <= triangles)
        ++level;
    // The icosahedron's twelve vertices (0, +-1, +-phi) cyclically, on the unit sphere
    const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<DVec3> vertices;
    for (const DVec3 v :
         {DVec3(-1, phi, 0), DVec3(1, phi, 0), DVec3(-1, -phi, 0), DVec3(1, -phi, 0),
          DVec3(0, -1, phi), DVec3(0, 1, phi), DVec3(0, -1, -phi), DVec3(0, 1, -phi),
          DVec3(phi, 0, -1), DVec3(phi, 0, 1), DVec3(-phi, 0, -1), DVec3(-phi, 0, 1)})
        vertices.push_back(glm::normalize(v));
    struct Face {
        std::uint32_t a, b, c;
    };
    std::vector<Face> faces = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10},
                               {0, 10, 11}, {1, 5, 9},  {5, 11, 4}, {11, 10, 2},
                               {10, 7, 6},  {7, 1, 8},  {3, 9, 4},  {3, 4, 2},
                               {3, 2, 6},   {3, 6, 8},  {3, 8, 9},  {4, 9, 5},
                               {2, 4, 11},  {6, 2, 10}, {8, 6, 7},  {9, 8, 1}};
    for (int k = 0; k < level; ++k) {
        // Each edge's midpoint once, whichever face asks first
        std::unordered_map<std::uint64_t, std::uint32_t> midpoints;
        const auto midpoint = [&](std::uint32_t i, std::uint32_t j) {
            const std::uint64_t key =
                std::uint64_t{std::min(i, j)} << 32 | std::max(i, j);
            const auto found = midpoints.find(key);
            if (found != midpoints.end()) return found->second;
            const auto m = static_cast<std::uint32_t>(vertices.size());
            vertices.push_back(glm::normalize(vertices[i] + vertices[j]));
            midpoints.emplace(key, m);
            return m;
        };
        std::vector<Face> finer;
        finer.reserve(4 * faces.size());
        for (const Face& f : faces) {
            const std::uint32_t ab = midpoint(f.a, f.b), bc = midpoint(f.b, f.c),
                                ca = midpoint(f.c, f.a);
            finer.insert(finer.end(),
                         {{f.a, ab, ca}, {f.b, bc, ab}, {f.c, ca, bc}, {ab, bc, ca}});
        }
        faces = std::move(finer);
    }
    // Each vertex rounded to float once, so that its triangles share it bit for bit
    std::vector<Vec3> points(vertices.begin(), vertices.end());
    Scene scene;
    scene.name = "icosphere";
    scene.materials.push_back(Material{"porcelain", Vec3(0.8f, 0.8f, 0.75f), Vec3(0.0f)});
    scene.triangles.reserve(faces.size());
    for (const Face& f : faces)
        add_outward(scene, points[f.a], points[f.b], points[f.c]);
    scene.view = View{Vec3(0.0f, 0.8f, 3.0f), Vec3(0.0f), Vec3(0.0f, 1.0f, 0.0f), 45.0f};
    scene.lights.push_back(PointLight{Vec3(3.0f, 4.0f, 3.0f), Vec3(40.0f)});
    scene.commit();
    return scene;
}

Scene displaced_sphere(int triangles) {
    // 2 nu (nv - 1) triangles with nu = 2 nv
    const int nv = std::max(3, static_cast<int>(std::lround(std::sqrt(triangles / 4.0))));
    const int nu = 2 * nv;
    std::vector<Vec3> grid(static_cast<size_t>(nu) * (nv + 1));
    const auto at = [&](int iu, int iv) -> Vec3& {
        return grid[static_cast<size_t>(iv) * nu + static_cast<size_t>(iu % nu)];
    };
    for (int iv = 0; iv <= nv; ++iv) {
        for (int iu = 0; iu < nu; ++iu) {
            const double theta = kPiD * iv / nv, phi = 2.0 * kPiD * iu / nu;
            const double r = displaced_radius(theta, phi);
            at(iu, iv) = Vec3(DVec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                    std::sin(theta) * std::sin(phi)) *
                              r);
            // One vertex per pole, so the caps close exactly
            if (iv == 0) at(iu, iv) = Vec3(0.0f, 1.0f, 0.0f);
            if (iv == nv) at(iu, iv) = Vec3(0.0f, -1.0f, 0.0f);
        }
    }
    Scene scene;
    scene.name = "displaced sphere";
    scene.materials.push_back(Material{"clay", Vec3(0.7f, 0.6f, 0.5f), Vec3(0.0f)});
    scene.triangles.reserve(static_cast<size_t>(2 * nu * (nv - 1)));
    for (int iv = 0; iv < nv; ++iv) {
        for (int iu = 0; iu < nu; ++iu) {
            const Vec3 &a = at(iu, iv), &b = at(iu + 1, iv);
            const Vec3 &c = at(iu, iv + 1), &d = at(iu + 1, iv + 1);
            if (iv > 0) add_outward(scene, a, b, d);
            if (iv < nv - 1) add_outward(scene, a, d, c);
        }
    }
    scene.view = View{Vec3(0.0f, 0.8f, 3.0f), Vec3(0.0f), Vec3(0.0f, 1.0f, 0.0f), 45.0f};
    scene.lights.push_back(PointLight{Vec3(3.0f, 4.0f, 3.0f), Vec3(40.0f)});
    scene.commit();
    return scene;
}

Scene terrain(int triangles) {
    // 2 n^2 triangles over [-1, 1]^2
    const int n = std::max(2, static_cast<int>(std::lround(std::sqrt(triangles / 2.0))));
    const auto height = [](double x, double z) {
        return 0.15 * std::sin(3.1 * x + 1.3) * std::cos(2.7 * z) +
               0.06 * std::sin(9.3 * x - 7.1 * z) + 0.02 * std::cos(23.0 * x + 19.0 * z) +
               0.008 * std::sin(61.0 * x + 0.5) * std::sin(57.0 * z);
    };
    std::vector<Vec3> grid(static_cast<size_t>(n + 1) * (n + 1));
    const auto at = [&](int i, int k) -> Vec3& {
        return grid[static_cast<size_t>(k) * (n + 1) + static_cast<size_t>(i)];
    };
    for (int k = 0; k <= n; ++k) {
        for (int i = 0; i <= n; ++i) {
            const double x = -1.0 + 2.0 * i / n, z = -1.0 + 2.0 * k / n;
            at(i, k) = Vec3(DVec3(x, height(x, z), z));
        }
    }
    Scene scene;
    scene.name = "terrain";
    scene.materials.push_back(Material{"grass", Vec3(0.35f, 0.55f, 0.25f), Vec3(0.0f)});
    scene.triangles.reserve(static_cast<size_t>(2 * n * n));
    for (int k = 0; k < n; ++k) {
        for (int i = 0; i < n; ++i) {
            // Counter-clockwise seen from above (+y)
            SceneTriangle t;
            t.v0 = at(i, k), t.v1 = at(i, k + 1), t.v2 = at(i + 1, k + 1);
            scene.triangles.push_back(t);
            t.v1 = at(i + 1, k + 1), t.v2 = at(i + 1, k);
            scene.triangles.push_back(t);
        }
    }
    scene.view = View{Vec3(0.0f, 0.6f, 2.0f), Vec3(0.0f, 0.0f, -0.2f),
                      Vec3(0.0f, 1.0f, 0.0f), 50.0f};
    scene.lights.push_back(PointLight{Vec3(1.5f, 3.0f, 1.0f), Vec3(60.0f)});
    scene.commit();
    return scene;
}

Scene random_soup(int triangles, Rng& rng) {
    // Vertices up to 20 / sqrt(n) from the centre: the soup's area, n times a mean of
    // 0.243 size^2 (numerically), makes a line of length 2 through the cube of volume 8
    // cross n A L / (2 V), about 12 triangles, whatever n
    const double size = 20.0 / std::sqrt(static_cast<double>(std::max(triangles, 1)));
    Scene scene;
    scene.name = "random soup";
    scene.materials.push_back(Material{"confetti", Vec3(0.8f, 0.5f, 0.3f), Vec3(0.0f)});
    scene.triangles.reserve(static_cast<size_t>(triangles));
    for (int k = 0; k < triangles; ++k) {
        const DVec3 centre = rng.in_cube(1.0);
        SceneTriangle t;
        Vec3* v[3] = {&t.v0, &t.v1, &t.v2};
        for (Vec3* p : v)
            *p = Vec3(centre + size * rng.uniform(0.2, 1.0) * rng.unit_vector());
        scene.triangles.push_back(t);
    }
    scene.view = View{Vec3(0.6f, 0.9f, 4.2f), Vec3(0.0f), Vec3(0.0f, 1.0f, 0.0f), 45.0f};
    scene.lights.push_back(PointLight{Vec3(3.0f, 4.0f, 3.0f), Vec3(40.0f)});
    scene.commit();
    return scene;
}

Scene as_added(const Scene& scene) {
    Scene added;
    added.name = scene.name;
    added.materials = scene.materials;
    added.planes = scene.planes;
    added.spheres = scene.spheres;
    added.triangles.resize(scene.triangles.size());
    added.normals.resize(scene.normals.size());
    for (size_t k = 0; k < scene.triangles.size(); ++k) {
        const size_t at = scene.triangle_source(k);
        added.triangles.at(at) = scene.triangles[k];
        if (!scene.normals.empty()) added.normals.at(at) = scene.normals[k];
    }
    added.lights = scene.lights;
    added.view = scene.view;
    added.ambient = scene.ambient;
    return added;
}

double commit_seconds(const Scene& scene, int repeats) {
    const Scene added = as_added(scene);
    std::vector<double> s;
    for (int k = 0; k <= repeats; ++k) {
        Scene fresh = added;
        const auto start = std::chrono::steady_clock::now();
        fresh.commit();
        if (k > 0) s.push_back(seconds_since(start));  // the first: warm-up
    }
    return median(s);
}

std::vector<Ray> camera_rays(const Scene& scene, const ModuleTable& modules, int width,
                             int height) {
    const PinholeCamera camera = make_camera(modules, scene.view);
    std::vector<Ray> rays;
    rays.reserve(static_cast<size_t>(width) * height);
    for (int j = 0; j < height; ++j) {
        for (int i = 0; i < width; ++i) {
            Ray r = modules.camera_ray(camera,
                                       modules.image_plane_point(i, j, width, height));
            r.w = glm::normalize(r.w);
            rays.push_back(r);
        }
    }
    return rays;
}

std::vector<Ray> shadow_rays(const Scene& scene, const ModuleTable& modules,
                             const std::vector<Ray>& camera) {
    std::vector<Ray> rays;
    const RecordingOccluder recorder(rays);
    TraceCounters counters;
    for (const Ray& r : camera) {
        const std::optional<Hit> hit = scene.closest_hit(modules, r, counters);
        if (!hit) continue;
        for (const PointLight& light : scene.lights) {
            const LightSample sample = modules.sample_point_light(light, hit->position);
            // As the renderer: no shadow ray towards a light behind the surface
            if (glm::dot(hit->ns, sample.wi) > 0.0f)
                modules.in_shadow(recorder, hit->position, hit->ns, sample);
        }
    }
    return rays;
}

std::vector<Ray> random_rays(const Scene& scene, Rng& rng, int n) {
    const Aabb box = scene.bounds();
    const DVec3 lo(box.lo), hi(box.hi), centre = 0.5 * (lo + hi);
    const double radius = glm::length(hi - lo);
    std::vector<Ray> rays;
    rays.reserve(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k) {
        const DVec3 o = centre + radius * rng.unit_vector();
        const DVec3 p(rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y),
                      rng.uniform(lo.z, hi.z));
        Ray r;
        r.o = Vec3(o);
        r.w = Vec3(glm::normalize(p - DVec3(r.o)));
        rays.push_back(r);
    }
    return rays;
}

}  // namespace raylab::bench
