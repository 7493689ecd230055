// What the engine keeps of a committed scene (raylab/engine.h: EngineData), prepared by
// prepare_scene when Scene::commit() succeeds: the triangles' degenerate flags and, in
// small scenes, their normals and a copy of the primitives in the BVH's slot order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "raylab/engine.h"
#include "raylab/scene.h"

namespace raylab::reference::engine_kernels {

struct SceneData final : EngineData {
    /// True for triangle k when its normal (v1 - v0) x (v2 - v0), in double, has no
    /// length: the contract says such a triangle is never hit, and the engine refuses it
    /// by this flag instead of computing the normal.
    bool degenerate(size_t k) const { return !degenerate_.empty() && degenerate_[k]; }

    /// Triangles up to which the engine keeps every triangle's normal (face_normal): the
    /// array, 12 bytes a triangle, then stays in the cache.
    static constexpr size_t kFaceNormalsUpTo = size_t{1} << 14;
    /// True when the engine kept the triangles' normals: a scene of at most
    /// kFaceNormalsUpTo triangles. The engine reads its nearest hit's normal there
    /// instead of computing it (a square root and a division); in a larger scene an
    /// incoherent ray's read of it would miss the cache, and the engine computes it from
    /// the vertices its test has just read.
    bool has_face_normals() const { return !face_normals_.empty(); }
    /// Unit normal of triangle k as the contract defines hit.n: (v1 - v0) x (v2 - v0) in
    /// double, divided by its length, rounded to float; zero when degenerate(k). Only
    /// when has_face_normals().
    const Vec3& face_normal(size_t k) const { return face_normals_[k]; }

    /// A BVH slot's primitive as the engine reads it in a small scene: a triangle's
    /// vertices (a, b, c), or a sphere's centre (a) and radius (b.x), in double (exactly
    /// the float values, converted once instead of at every test); prim names the
    /// primitive as the BVH does (spheres first, then triangles), with kSphere set for a
    /// sphere and kDegenerate for a degenerate triangle. 80 bytes.
    struct SlotPrimitive {
        static constexpr std::uint32_t kSphere = 0x80000000u;
        static constexpr std::uint32_t kDegenerate = 0x40000000u;
        static constexpr std::uint32_t kIndexMask = kDegenerate - 1;
        DVec3 a, b, c;
        std::uint32_t prim;
    };
    /// Spheres and triangles up to which the engine keeps a copy of them in the BVH's
    /// slot order (slot_primitives, at most 320 KiB): its single-ray queries then read a
    /// leaf's primitives side by side, with no load of the primitive order before each.
    /// A larger scene keeps none: memory per triangle stays what the BVH and the mesh
    /// need.
    static constexpr size_t kSlotCopyUpTo = size_t{1} << 12;
    /// The copy, one SlotPrimitive per BVH slot, or nullptr (a larger scene).
    const SlotPrimitive* slot_primitives() const {
        return slots_.empty() ? nullptr : slots_.data();
    }

    size_t bytes() const override {
        return (degenerate_.size() + 7) / 8 + face_normals_.size() * sizeof(Vec3) +
               slots_.size() * sizeof(SlotPrimitive);
    }

    std::vector<bool> degenerate_;      // by triangle; empty when none is degenerate
    std::vector<Vec3> face_normals_;    // by triangle, or empty (has_face_normals)
    std::vector<SlotPrimitive> slots_;  // by BVH slot, or empty (slot_primitives)
};

/// The engine's data of a scene that commit() has just built (GeometryEngine::prepare).
std::shared_ptr<const EngineData> prepare_scene(const Scene& scene);

/// The data of a scene whose queries run in the engine (Scene::engine_for checks that
/// the engine prepared it)
inline const SceneData& scene_data(const Scene& scene) {
    return *static_cast<const SceneData*>(scene.engine_data());
}

}  // namespace raylab::reference::engine_kernels
