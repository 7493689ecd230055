// The engine's data of a committed scene (engine_data.h).
#include "engine_data.h"

#include "raylab/refine.h"  // unit_normal

namespace raylab::reference::engine_kernels {

std::shared_ptr<const EngineData> prepare_scene(const Scene& scene) {
    auto data = std::make_shared<SceneData>();
    const std::vector<SceneTriangle>& triangles = scene.triangles;
    if (triangles.size() <= SceneData::kFaceNormalsUpTo)
        data->face_normals_.resize(triangles.size());
    for (size_t k = 0; k < triangles.size(); ++k) {
        // A unit normal in double has a component of at least 1/sqrt(3): zero only when
        // degenerate
        const Vec3 n = unit_normal(triangles[k]);
        if (n == Vec3(0.0f)) {
            data->degenerate_.resize(triangles.size());
            data->degenerate_[k] = true;
        } else if (!data->face_normals_.empty()) {
            data->face_normals_[k] = n;
        }
    }
    const Bvh& bvh = scene.bvh();
    if (bvh.prims().size() <= SceneData::kSlotCopyUpTo) {
        const std::uint32_t sphere_count =
            static_cast<std::uint32_t>(scene.spheres.size());
        data->slots_.reserve(bvh.prims().size());
        for (const std::uint32_t p : bvh.prims()) {
            SceneData::SlotPrimitive s{};
            if (p < sphere_count) {
                s.a = scene.spheres[p].sphere.c;
                s.b = DVec3(scene.spheres[p].sphere.r, 0.0, 0.0);
                s.prim = p | SceneData::SlotPrimitive::kSphere;
            } else {
                const SceneTriangle& t = triangles[p - sphere_count];
                s.a = DVec3(t.v0), s.b = DVec3(t.v1), s.c = DVec3(t.v2);
                s.prim = p | (data->degenerate(p - sphere_count)
                                  ? SceneData::SlotPrimitive::kDegenerate
                                  : 0u);
            }
            data->slots_.push_back(s);
        }
    }
    // Large arrays on huge pages (a random ray's loads of nodes and triangles missed the
    // TLB); only advice, the data is unchanged
    back_with_huge_pages(bvh.nodes().data(), bvh.nodes().size() * sizeof(Bvh::Node));
    back_with_huge_pages(bvh.prims().data(), bvh.prims().size() * sizeof(std::uint32_t));
    back_with_huge_pages(triangles.data(), triangles.size() * sizeof(SceneTriangle));
    return data;
}

}  // namespace raylab::reference::engine_kernels
