// OBJ loading with Debian's tinyobjloader (raylab/scenes.h). We use the library rather
// than a parser of our own: it handles MTL files, negative indices, polygons and line
// continuations, and reports errors with line numbers.
#include <cmath>
#include <fstream>

#include <tiny_obj_loader.h>

#include "raylab/error.h"
#include "raylab/scenes.h"

namespace raylab {

namespace {

// tinyobjloader's messages end in newlines and may hold several lines: keep the first
std::string first_line(const std::string& text) {
    std::string line = text.substr(0, text.find('\n'));
    while (!line.empty() && (line.back() == '\r' || line.back() == ' '))
        line.pop_back();
    return line;
}

Vec3 vertex(const std::vector<tinyobj::real_t>& array, int index, const std::string& path,
            const char* what) {
    if (index < 0 || static_cast<size_t>(index) * 3 + 2 >= array.size()) {
        throw Error(path + ": a face refers to " + what + " " +
                    std::to_string(index + 1) + ", which does not exist");
    }
    return Vec3(array[3 * index], array[3 * index + 1], array[3 * index + 2]);
}

// A view that frames the model from the front, and a light above the eye
void frame_model(Scene& scene) {
    const Aabb box = scene.bounds();
    const Vec3 centre = box.centre();
    const float radius = std::max(0.5f * glm::length(box.hi - box.lo), 1e-3f);
    scene.view.lookat = centre;
    scene.view.fov = 45.0f;
    const float distance = radius / std::tan(radians(0.5f * scene.view.fov)) * 1.1f;
    scene.view.eye = centre + Vec3(0.0f, 0.25f * radius, distance);
    scene.view.up = Vec3(0.0f, 1.0f, 0.0f);
    // Intensity that gives about the irradiance of a unit light at distance 1
    const Vec3 p = scene.view.eye + Vec3(0.3f * radius, 1.2f * radius, 0.0f);
    const float r = glm::length(p - centre);
    scene.lights.push_back(PointLight{p, Vec3(3.0f * r * r)});
}

}  // namespace

Scene load_obj(const std::string& path) {
    if (!std::ifstream(path)) throw Error(path + ": cannot open file");
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path, config)) {
        const std::string why = first_line(reader.Error());
        throw Error(path + ": " + (why.empty() ? "not a valid OBJ file" : why));
    }
    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    Scene scene;
    scene.name = path;

    // Materials: Kd is rho, Ke emission; one grey default for faces without a material
    for (const tinyobj::material_t& m : reader.GetMaterials()) {
        Material mat;
        mat.name = m.name;
        mat.rho = Vec3(m.diffuse[0], m.diffuse[1], m.diffuse[2]);
        mat.Le = Vec3(m.emission[0], m.emission[1], m.emission[2]);
        if (!is_finite(mat.rho) || !is_finite(mat.Le))
            throw Error(path + ": material '" + m.name + "' has a non-finite colour");
        mat.rho = glm::clamp(mat.rho, Vec3(0.0f), Vec3(1.0f));
        scene.materials.push_back(mat);
    }
    const int default_material = static_cast<int>(scene.materials.size());
    scene.materials.push_back(Material{"default", Vec3(0.75f), Vec3(0.0f)});

    // Triangles (the reader triangulated every face)
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        const tinyobj::mesh_t& mesh = shape.mesh;
        size_t offset = 0;
        for (size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
            const size_t n = mesh.num_face_vertices[f];
            if (n != 3) {
                offset += n;
                continue;  // degenerate polygon the triangulator left alone
            }
            SceneTriangle t;
            Vec3* v[3] = {&t.v0, &t.v1, &t.v2};
            Vec3* vn[3] = {&t.n0, &t.n1, &t.n2};
            bool has_normals = true;
            for (size_t k = 0; k < 3; ++k) {
                const tinyobj::index_t idx = mesh.indices[offset + k];
                *v[k] = vertex(attrib.vertices, idx.vertex_index, path, "vertex");
                if (idx.normal_index < 0) {
                    has_normals = false;
                } else {
                    *vn[k] = vertex(attrib.normals, idx.normal_index, path, "normal");
                }
            }
            if (!is_finite(t.v0) || !is_finite(t.v1) || !is_finite(t.v2))
                throw Error(path + ": shape '" + shape.name +
                            "' has a non-finite vertex");
            // Normals: the file's, normalised, or none (flat shading from the geometry)
            if (has_normals) {
                for (Vec3* nk : vn) {
                    const float len = glm::length(*nk);
                    if (!(len > 0.0f) || !std::isfinite(len)) {
                        has_normals = false;
                        break;
                    }
                    *nk /= len;
                }
            }
            if (!has_normals) t.n0 = t.n1 = t.n2 = Vec3(0.0f);
            const int m = f < mesh.material_ids.size() ? mesh.material_ids[f] : -1;
            t.material = m >= 0 && m < default_material ? m : default_material;
            scene.triangles.push_back(t);
            offset += n;
        }
    }
    if (scene.triangles.empty()) throw Error(path + ": the file holds no faces");
    scene.commit();
    frame_model(scene);
    return scene;
}

}  // namespace raylab
