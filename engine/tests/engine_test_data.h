// The engine's data of a scene (engine_data.h), for the engine's tests.
#pragma once

#include <doctest/doctest.h>

#include "engine_data.h"
#include "raylab/scene.h"

namespace raylab {

using reference::engine_kernels::SceneData;

/// What the engine prepared when scene was last committed (a committed scene has it in
/// every program that links the engine)
inline const SceneData& engine_data(const Scene& scene) {
    REQUIRE(scene.engine_data() != nullptr);
    return *static_cast<const SceneData*>(scene.engine_data());
}

}  // namespace raylab
