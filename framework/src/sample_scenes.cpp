// Generated sample scenes (raylab/sample_scenes.h).
#include "raylab/sample_scenes.h"

#include <cmath>

namespace raylab {

namespace {

// An indexed triangle mesh; smooth() gives every vertex the area-weighted mean of its
// faces' normals, as a modelling tool's "smooth shading" does
struct Mesh {
    std::vector<Vec3> p;
    std::vector<int> idx;  ///< three per triangle, counter-clockwise from outside
};

void add_mesh(Scene& scene, const Mesh& m, int material, bool smooth) {
    std::vector<Vec3> n(m.p.size(), Vec3(0.0f));
    for (size_t k = 0; k + 2 < m.idx.size(); k += 3) {
        const Vec3 &a = m.p[m.idx[k]], &b = m.p[m.idx[k + 1]], &c = m.p[m.idx[k + 2]];
        const Vec3 face = glm::cross(b - a, c - a);  // length: twice the area
        for (int j = 0; j < 3; ++j)
            n[m.idx[k + j]] += face;
    }
    for (Vec3& v : n) {
        const float len = glm::length(v);
        v = len > 0.0f ? v / len : Vec3(0.0f, 1.0f, 0.0f);
    }
    for (size_t k = 0; k + 2 < m.idx.size(); k += 3) {
        SceneTriangle t;
        t.v0 = m.p[m.idx[k]];
        t.v1 = m.p[m.idx[k + 1]];
        t.v2 = m.p[m.idx[k + 2]];
        t.material = material;
        scene.add_triangle(
            t, smooth ? VertexNormals{n[m.idx[k]], n[m.idx[k + 1]], n[m.idx[k + 2]]}
                      : VertexNormals{});
    }
}

// A grid of (cols + 1) x (rows + 1) vertices made by at(u, v), u, v in [0, 1]
template <class F>
Mesh grid(int cols, int rows, F at) {
    Mesh m;
    for (int r = 0; r <= rows; ++r)
        for (int c = 0; c <= cols; ++c)
            m.p.push_back(at(float(c) / float(cols), float(r) / float(rows)));
    for (int r = 0; r < rows; ++r) {
        for (int c = 0; c < cols; ++c) {
            const int a = r * (cols + 1) + c, b = a + 1, d = a + cols + 1, e = d + 1;
            m.idx.insert(m.idx.end(), {a, d, b, b, d, e});
        }
    }
    return m;
}

int material(Scene& scene, const char* name, Vec3 rho) {
    scene.materials.push_back(Material{name, rho, Vec3(0.0f)});
    return int(scene.materials.size()) - 1;
}

void add_box(Scene& scene, Vec3 lo, Vec3 hi, int mat) {
    const Vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z},
                       {lo.x, hi.y, lo.z}, {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z},
                       {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    const int q[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 4, 7, 3},
                         {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 7, 6, 2}};  // outward CCW
    Mesh m;
    m.p.assign(c, c + 8);
    for (const auto& f : q)
        m.idx.insert(m.idx.end(), {f[0], f[1], f[2], f[0], f[2], f[3]});
    add_mesh(scene, m, mat, false);
}

// A lumpy sphere, coarse on purpose: its smooth normals differ from the flat facets,
// which is what makes the shadow terminator visible
Scene blob() {
    Scene scene;
    scene.name = "blob";
    const int clay = material(scene, "clay", {0.8f, 0.55f, 0.4f});
    const int floor = material(scene, "floor", {0.6f, 0.6f, 0.6f});
    scene.planes.push_back(ScenePlane{Plane{Vec3(0.0f, 1.0f, 0.0f), 0.0f}, floor});
    const Mesh m = grid(48, 24, [](float u, float v) {
        const float phi = 2.0f * kPi * u, theta = kPi * v;
        const Vec3 d(std::sin(theta) * std::cos(phi), std::cos(theta),
                     -std::sin(theta) * std::sin(phi));
        const float r = 0.8f + 0.12f * std::sin(3.0f * phi) * std::sin(2.0f * theta) +
                        0.06f * std::cos(5.0f * theta);
        return Vec3(0.0f, 0.95f, 0.0f) + r * d;
    });
    add_mesh(scene, m, clay, true);
    scene.view = View{Vec3(0.0f, 1.4f, 3.6f), Vec3(0.0f, 0.8f, 0.0f),
                      Vec3(0.0f, 1.0f, 0.0f), 45.0f};
    scene.lights.push_back(PointLight{Vec3(2.5f, 2.6f, 2.0f), Vec3(14.0f)});
    scene.ambient = 0.05f;
    scene.commit();
    return scene;
}

// Rolling hills from a few sines: 128 x 128 quads
Scene terrain() {
    Scene scene;
    scene.name = "terrain";
    const int grass = material(scene, "grass", {0.35f, 0.6f, 0.3f});
    const Mesh m = grid(128, 128, [](float u, float v) {
        const float x = 8.0f * (u - 0.5f), z = 8.0f * (v - 0.5f);
        const float h = 0.45f * std::sin(0.9f * x) * std::cos(0.7f * z) +
                        0.2f * std::sin(2.3f * x + 1.0f) * std::sin(1.9f * z) +
                        0.06f * std::sin(7.0f * x) * std::cos(6.0f * z);
        return Vec3(x, h, z);
    });
    add_mesh(scene, m, grass, true);
    scene.view = View{Vec3(0.0f, 2.5f, 5.5f), Vec3(0.0f, 0.0f, 0.0f),
                      Vec3(0.0f, 1.0f, 0.0f), 50.0f};
    scene.lights.push_back(PointLight{Vec3(-4.0f, 3.0f, -1.0f), Vec3(30.0f)});
    scene.ambient = 0.05f;
    scene.commit();
    return scene;
}

// A room seen from the door: a table, a shelf, two spheres, two lights
Scene room() {
    Scene scene;
    scene.name = "room";
    const int wall = material(scene, "wall", {0.75f, 0.72f, 0.65f});
    const int wood = material(scene, "wood", {0.55f, 0.35f, 0.2f});
    const int blue = material(scene, "blue", {0.2f, 0.3f, 0.75f});
    const int white = material(scene, "white", {0.85f, 0.85f, 0.85f});
    const float W = 2.0f, H = 2.5f, D = 2.0f;
    scene.planes.push_back(ScenePlane{Plane{Vec3(0, 1, 0), 0.0f}, wall});  // floor
    scene.planes.push_back(ScenePlane{Plane{Vec3(0, -1, 0), H}, wall});    // ceiling
    scene.planes.push_back(ScenePlane{Plane{Vec3(1, 0, 0), W}, wall});     // left
    scene.planes.push_back(ScenePlane{Plane{Vec3(-1, 0, 0), W}, blue});    // right
    scene.planes.push_back(ScenePlane{Plane{Vec3(0, 0, 1), D}, wall});     // back
    add_box(scene, {-0.8f, 0.7f, -0.6f}, {0.8f, 0.78f, 0.4f}, wood);       // table top
    for (float x : {-0.75f, 0.7f})
        for (float z : {-0.55f, 0.3f})
            add_box(scene, {x, 0.0f, z}, {x + 0.05f, 0.7f, z + 0.05f}, wood);  // legs
    add_box(scene, {-1.95f, 0.0f, -1.9f}, {-1.3f, 1.8f, -1.4f}, wood);         // shelf
    scene.spheres.push_back(SceneSphere{Sphere{Vec3(0.2f, 0.98f, -0.1f), 0.2f}, white});
    scene.spheres.push_back(SceneSphere{Sphere{Vec3(1.3f, 0.35f, -1.2f), 0.35f}, blue});
    scene.view = View{Vec3(0.0f, 1.5f, 3.6f), Vec3(0.0f, 0.8f, -0.5f),
                      Vec3(0.0f, 1.0f, 0.0f), 55.0f};
    scene.lights.push_back(PointLight{Vec3(0.0f, 2.3f, 0.0f), Vec3(5.0f)});
    scene.lights.push_back(PointLight{Vec3(-1.5f, 1.8f, 1.5f), Vec3(2.0f, 1.6f, 1.0f)});
    scene.ambient = 0.03f;
    scene.commit();
    return scene;
}

}  // namespace

std::vector<std::string> sample_scene_names() {
    return {"blob", "terrain", "room"};
}

std::optional<Scene> sample_scene(const std::string& name) {
    if (name == "blob") return blob();
    if (name == "terrain") return terrain();
    if (name == "room") return room();
    return std::nullopt;
}

}  // namespace raylab
