// Built-in scenes (raylab/scenes.h).
#include "raylab/scenes.h"

#include "raylab/error.h"
#include "raylab/input_file.h"
#include "raylab/sample_scenes.h"

namespace raylab {

namespace {

// Lab units to our world: scale to [-1, 1]^3 with s = v 2 / L - 1, then turn 180 degrees
// about y (x -> -x, z -> -z) so that the lab's camera, which looks along +z, becomes ours
// at z = +3 looking along -z. The lab's own x and y flips serve its y-down screen; a
// rotation keeps triangle windings, so the picture matches the lab's figure.
constexpr float kL = 555.0f;
Vec3 lab(float x, float y, float z) {
    const Vec3 s = Vec3(x, y, z) * (2.0f / kL) - Vec3(1.0f);
    return Vec3(-s.x, s.y, -s.z);
}

// The lab lists faces clockwise as seen from the front; ours are counter-clockwise
void add_face(Scene& scene, const Vec3& a, const Vec3& b, const Vec3& c, int material) {
    SceneTriangle t;
    t.v0 = a;
    t.v1 = c;
    t.v2 = b;
    t.material = material;
    scene.triangles.push_back(t);
}

// A block of the lab: A-D on the floor, E-H the same at height h, five faces (no bottom)
void add_block(Scene& scene, const Vec3 (&floor)[4], float h, int material) {
    Vec3 p[8];
    for (int k = 0; k < 4; ++k) {
        p[k] = lab(floor[k].x, 0.0f, floor[k].z);
        p[k + 4] = lab(floor[k].x, h, floor[k].z);
    }
    enum { A, B, C, D, E, F, G, H };
    const int faces[10][3] = {{E, B, A}, {E, F, B}, {F, D, B}, {F, H, D}, {H, C, D},
                              {H, G, C}, {G, E, C}, {E, A, C}, {G, F, E}, {G, H, F}};
    for (const auto& f : faces)
        add_face(scene, p[f[0]], p[f[1]], p[f[2]], material);
}

int add_material(Scene& scene, const char* name, Vec3 rho) {
    scene.materials.push_back(Material{name, rho, Vec3(0.0f)});
    return static_cast<int>(scene.materials.size()) - 1;
}

}  // namespace

Scene cornell_box() {
    Scene scene;
    scene.name = "cornell";
    // Colours of TestModel.h
    const int red = add_material(scene, "red", {0.75f, 0.15f, 0.15f});
    const int yellow = add_material(scene, "yellow", {0.75f, 0.75f, 0.15f});
    const int green = add_material(scene, "green", {0.15f, 0.75f, 0.15f});
    const int cyan = add_material(scene, "cyan", {0.15f, 0.75f, 0.75f});
    const int blue = add_material(scene, "blue", {0.15f, 0.15f, 0.75f});
    const int purple = add_material(scene, "purple", {0.75f, 0.15f, 0.75f});
    const int white = add_material(scene, "white", {0.75f, 0.75f, 0.75f});

    // Room
    const Vec3 A = lab(kL, 0, 0), B = lab(0, 0, 0), C = lab(kL, 0, kL), D = lab(0, 0, kL);
    const Vec3 E = lab(kL, kL, 0), F = lab(0, kL, 0), G = lab(kL, kL, kL),
               H = lab(0, kL, kL);
    add_face(scene, C, B, A, green);  // floor
    add_face(scene, C, D, B, green);
    add_face(scene, A, E, C, purple);  // left wall
    add_face(scene, C, E, G, purple);
    add_face(scene, F, B, D, yellow);  // right wall
    add_face(scene, H, F, D, yellow);
    add_face(scene, E, F, G, cyan);  // ceiling
    add_face(scene, F, H, G, cyan);
    add_face(scene, G, D, C, white);  // back wall
    add_face(scene, G, H, D, white);

    // Blocks (A-D: x and z of the floor corners)
    const Vec3 short_block[4] = {
        {290, 0, 114}, {130, 0, 65}, {240, 0, 272}, {82, 0, 225}};
    const Vec3 tall_block[4] = {
        {423, 0, 247}, {265, 0, 296}, {472, 0, 406}, {314, 0, 456}};
    add_block(scene, short_block, 165.0f, red);
    add_block(scene, tall_block, 330.0f, blue);

    // The lab's camera and light: eye 3 in front of the centre, focal length = image
    // height (d = 1); light 0.5 above the centre and 0.7 towards the camera, P = 14 W
    scene.view =
        View{Vec3(0.0f, 0.0f, 3.0f), Vec3(0.0f), Vec3(0.0f, 1.0f, 0.0f), 53.130102f};
    scene.lights.push_back(
        PointLight{Vec3(0.0f, 0.5f, 0.7f), Vec3(14.0f) / (4.0f * kPi)});
    scene.commit();
    return scene;
}

Scene dtu_scene() {
    Scene scene;
    scene.name = "dtu";
    const int ground = add_material(scene, "ground", {0.6f, 0.6f, 0.6f});
    const int red = add_material(scene, "red", {0.8f, 0.2f, 0.15f});
    const int blue = add_material(scene, "blue", {0.15f, 0.3f, 0.8f});
    const int green = add_material(scene, "green", {0.2f, 0.7f, 0.25f});
    const int yellow = add_material(scene, "yellow", {0.85f, 0.75f, 0.2f});

    // Ground plane y = 0: p . n + d = 0 with n = (0, 1, 0), d = 0
    scene.planes.push_back(ScenePlane{Plane{Vec3(0.0f, 1.0f, 0.0f), 0.0f}, ground});
    scene.spheres.push_back(SceneSphere{Sphere{Vec3(0.0f, 0.5f, 0.0f), 0.5f}, red});
    scene.spheres.push_back(SceneSphere{Sphere{Vec3(-1.2f, 0.3f, 0.7f), 0.3f}, blue});
    scene.spheres.push_back(SceneSphere{Sphere{Vec3(1.1f, 0.4f, -0.6f), 0.4f}, green});
    // An upright triangle behind the spheres, counter-clockwise towards the camera
    SceneTriangle t;
    t.v0 = Vec3(-1.6f, 0.0f, -1.5f);
    t.v1 = Vec3(0.4f, 0.0f, -1.5f);
    t.v2 = Vec3(-0.6f, 1.6f, -1.5f);
    t.material = yellow;
    scene.triangles.push_back(t);

    scene.view = View{Vec3(0.0f, 1.6f, 4.5f), Vec3(0.0f, 0.4f, 0.0f),
                      Vec3(0.0f, 1.0f, 0.0f), 45.0f};
    scene.lights.push_back(PointLight{Vec3(1.5f, 3.0f, 2.0f), Vec3(25.0f)});
    scene.commit();
    return scene;
}

std::vector<std::string> builtin_scene_names() {
    std::vector<std::string> names = {"cornell", "dtu"};
    for (const std::string& name : sample_scene_names())  // generated (sample_scenes.h)
        names.push_back(name);
    return names;
}

Scene load_scene(const std::string& name_or_path, const LoadProgress& progress) {
    if (name_or_path == "cornell") return cornell_box();
    if (name_or_path == "dtu") return dtu_scene();
    if (auto sample = sample_scene(name_or_path)) return std::move(*sample);
    const std::string& p = name_or_path;
    const bool obj = p.size() > 4 && (p.compare(p.size() - 4, 4, ".obj") == 0 ||
                                      p.compare(p.size() - 4, 4, ".OBJ") == 0);
    if (obj) return load_obj(p, progress);
    std::string known;
    for (const std::string& name : builtin_scene_names())
        known += name + ", ";
    throw Error("unknown scene '" + printable(p) + "' (" + known + "or a .obj file)");
}

}  // namespace raylab
