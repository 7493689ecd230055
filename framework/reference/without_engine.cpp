// The reference library's geometry engine when it is built without one
// (RAYLAB_WITH_ENGINE=OFF, or a tree without engine/): none, so the scene's queries call
// the reference modules one primitive at a time, with the same results.
#include "raylab/engine.h"

namespace raylab::reference {

const GeometryEngine* geometry_engine() {
    return nullptr;
}

}  // namespace raylab::reference

namespace raylab {

// Huge pages are asked for by the engine only
bool back_with_huge_pages(const void*, size_t) {
    return false;
}

}  // namespace raylab
