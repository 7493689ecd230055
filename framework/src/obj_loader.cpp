// OBJ loading with Debian's tinyobjloader (raylab/scenes.h). Every line is checked first
// (obj_text.cpp), materials are read there too; the library then triangulates and
// builds the shapes.
#include <cmath>
#include <map>
#include <sstream>

#include <tiny_obj_loader.h>

#include "obj_text.h"
#include "raylab/error.h"
#include "raylab/input_file.h"
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

// The one material library tinyobjloader sees: slot names "0", "1", ... for the usemtl
// names the checks found (obj_text.h); the materials themselves are read there
class MaterialSlots : public tinyobj::MaterialReader {
  public:
    explicit MaterialSlots(size_t slots) : slots_(slots) {}
    bool operator()(const std::string& name, std::vector<tinyobj::material_t>*,
                    std::map<std::string, int>* ids, std::string*,
                    std::string* err) override {
        if (name != obj::kMaterialSlots) {
            if (err) *err += "mtllib '" + printable(name) + "' was not checked\n";
            return false;
        }
        for (size_t k = 0; k < slots_; ++k)
            (*ids)[std::to_string(k)] = static_cast<int>(k);
        return true;
    }

  private:
    size_t slots_;
};

void add_materials(Scene& scene, const std::vector<Material>& materials) {
    for (const Material& m : materials) {
        scene.materials.push_back(m);
        scene.materials.back().rho = glm::clamp(m.rho, Vec3(0.0f), Vec3(1.0f));
    }
    scene.materials.push_back(
        Material{"default", Vec3(obj::kDefaultDiffuse), Vec3(0.0f)});
}

// One triangle of the mesh, or false when it has no area (it could never be hit)
bool make_triangle(const tinyobj::attrib_t& attrib, const tinyobj::index_t* idx,
                   const std::string& source, SceneTriangle& t, VertexNormals& normals) {
    Vec3* v[3] = {&t.v0, &t.v1, &t.v2};
    Vec3* vn[3] = {&normals.n0, &normals.n1, &normals.n2};
    bool has_normals = true;
    for (size_t k = 0; k < 3; ++k) {
        *v[k] = vertex(attrib.vertices, idx[k].vertex_index, source, "vertex");
        if (idx[k].normal_index < 0) {
            has_normals = false;
        } else {
            *vn[k] = vertex(attrib.normals, idx[k].normal_index, source, "normal");
        }
    }
    const float area = glm::length(glm::cross(t.v1 - t.v0, t.v2 - t.v0));
    if (!(area > 0.0f) || !std::isfinite(area)) return false;
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
    if (!has_normals) normals = VertexNormals{};
    return true;
}

void add_triangles(Scene& scene, const tinyobj::attrib_t& attrib,
                   const std::vector<tinyobj::shape_t>& shapes,
                   const std::vector<int>& slot_material, const std::string& source,
                   const LoadProgress& progress) {
    const int default_material = static_cast<int>(scene.materials.size()) - 1;
    size_t faces = 0, degenerate = 0, total = 0;
    for (const tinyobj::shape_t& shape : shapes)
        total += shape.mesh.num_face_vertices.size();
    for (const tinyobj::shape_t& shape : shapes) {
        const tinyobj::mesh_t& mesh = shape.mesh;
        size_t offset = 0;
        for (size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
            const size_t n = mesh.num_face_vertices[f];
            if ((++faces & 0xffff) == 0) {
                if (progress.cancel && progress.cancel->load()) throw LoadCancelled();
                if (progress.report)
                    progress.report("triangles", static_cast<float>(faces) / total);
            }
            SceneTriangle t;
            VertexNormals tn;
            if (n != 3 || offset + 3 > mesh.indices.size() ||
                !make_triangle(attrib, &mesh.indices[offset], source, t, tn)) {
                ++degenerate;
                offset += n;
                continue;
            }
            // tinyobjloader's material id is the slot of the face's usemtl name
            const int slot = f < mesh.material_ids.size() ? mesh.material_ids[f] : -1;
            const int m = slot >= 0 && static_cast<size_t>(slot) < slot_material.size()
                              ? slot_material[slot]
                              : -1;
            t.material = m >= 0 && m < default_material ? m : default_material;
            scene.add_triangle(t, tn);
            offset += n;
        }
    }
    if (scene.triangles.empty()) {
        throw Error(source + ": no valid triangle" +
                    (degenerate
                         ? " (" + std::to_string(degenerate) + " faces without area)"
                         : std::string(" (the file holds no faces)")));
    }
    if (degenerate > 0)
        obj::warn(progress, source + ": skipped " + std::to_string(degenerate) +
                                " faces without area");
}

}  // namespace

Scene load_obj_text(const std::string& text, const std::string& source,
                    const std::function<std::string(const std::string&)>& read_mtl,
                    const LoadProgress& progress) {
    const obj::CheckedObj checked = obj::check_obj(text, source, read_mtl, progress);
    if (progress.report) progress.report("parsing", 0.0f);
    if (progress.cancel && progress.cancel->load()) throw LoadCancelled();
    // ObjReader has no stream entry with a material reader: call LoadObj directly
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warnings, errors;
    std::istringstream in(checked.obj);
    MaterialSlots mtl_files(checked.slot_material.size());
    if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warnings, &errors, &in,
                          &mtl_files, true, false)) {
        throw Error(
            source + ": " +
            printable(errors.empty() ? "not a valid OBJ file" : first_line(errors)));
    }
    std::istringstream lines(warnings);
    for (std::string line; std::getline(lines, line);)
        if (!line.empty()) obj::warn(progress, source + ": " + printable(line));
    Scene scene;
    scene.name = source;
    add_materials(scene, checked.materials);
    add_triangles(scene, attrib, shapes, checked.slot_material, source, progress);
    if (progress.cancel && progress.cancel->load()) throw LoadCancelled();
    if (progress.report) progress.report("BVH", 0.0f);
    scene.commit();
    if (progress.report) progress.report("BVH", 1.0f);
    frame_model(scene);
    return scene;
}

Scene load_obj(const std::string& path, const LoadProgress& progress) {
    const std::string text = read_input_file(path, kMaxObjBytes);
    const std::string source = printable(path);
    const size_t slash = path.find_last_of('/');
    const std::string folder =
        slash == std::string::npos ? "" : path.substr(0, slash + 1);
    const auto read_mtl = [&](const std::string& name) {
        return read_input_file(name.empty() || name[0] == '/' ? name : folder + name,
                               kMaxMtlBytes);
    };
    return load_obj_text(text, source, read_mtl, progress);
}

}  // namespace raylab
