// Closed triangle meshes for the stress tests (octahedron: fans of 4, cube, icosphere),
// and scenes built by hand.
#pragma once

#include <array>
#include <map>
#include <vector>

#include "raylab/math.h"
#include "raylab/scene.h"
#include "test_helpers.h"

namespace raylab {

struct Mesh {
    std::vector<Vec3> v;
    std::vector<std::array<int, 3>> f;
};

inline Mesh octahedron() {
    return {{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}},
            {{0, 2, 4},
             {2, 1, 4},
             {1, 3, 4},
             {3, 0, 4},
             {2, 0, 5},
             {1, 2, 5},
             {3, 1, 5},
             {0, 3, 5}}};
}

inline Mesh cube() {
    Mesh m;
    for (int k = 0; k < 8; ++k)
        m.v.push_back(Vec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1));
    m.f = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
           {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    return m;
}

// Icosahedron subdivided once onto the unit sphere (valence 5 and 6 vertices)
inline Mesh icosphere() {
    const float p = 1.618034f;
    Mesh m{{{-1, p, 0},
            {1, p, 0},
            {-1, -p, 0},
            {1, -p, 0},
            {0, -1, p},
            {0, 1, p},
            {0, -1, -p},
            {0, 1, -p},
            {p, 0, -1},
            {p, 0, 1},
            {-p, 0, -1},
            {-p, 0, 1}},
           {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
            {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
            {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
            {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}}};
    Mesh s;
    std::map<std::pair<int, int>, int> mid;
    s.v = m.v;
    const auto middle = [&](int a, int b) {
        const auto key = std::minmax(a, b);
        auto it = mid.find(key);
        if (it != mid.end()) return it->second;
        s.v.push_back(0.5f * (m.v[a] + m.v[b]));
        return mid[key] = int(s.v.size()) - 1;
    };
    for (const auto& t : m.f) {
        const int a = middle(t[0], t[1]), b = middle(t[1], t[2]), c = middle(t[2], t[0]);
        s.f.push_back({t[0], a, c});
        s.f.push_back({t[1], b, a});
        s.f.push_back({t[2], c, b});
        s.f.push_back({a, b, c});
    }
    for (Vec3& x : s.v)
        x = glm::normalize(x);
    return s;
}

inline Mesh placed(Mesh m, float scale, const Vec3& at) {
    for (Vec3& x : m.v)
        x = at + scale * x;
    return m;
}

// The mesh as a committed scene of one material
inline Scene scene_of(const Mesh& m) {
    Scene scene;
    scene.materials.push_back(Material{});
    for (const auto& t : m.f)
        scene.triangles.push_back(SceneTriangle{m.v[t[0]], m.v[t[1]], m.v[t[2]]});
    scene.commit();
    return scene;
}

// Every vertex, and points at 1/4, 1/3 and 1/2 along every edge of every face: where rays
// slip between triangles if any test lets them
inline std::vector<Vec3> vertex_and_edge_points(const Mesh& m) {
    std::vector<Vec3> targets = m.v;
    for (const auto& t : m.f)
        for (int e = 0; e < 3; ++e)
            for (const float s : {0.5f, 0.25f, 1.0f / 3.0f})
                targets.push_back(m.v[t[e]] + s * (m.v[t[(e + 1) % 3]] - m.v[t[e]]));
    return targets;
}

// A scene with one default material, for primitives added by hand
inline Scene one_material_scene() {
    Scene s;
    s.materials.push_back(Material{});
    return s;
}

// Does the scene, on the reference's modules, hit anything along r?
inline bool scene_hits(const Scene& s, const Ray& r) {
    TraceCounters counters;
    return s.closest_hit(reference_modules(), r, counters).has_value();
}

}  // namespace raylab
