// libFuzzer target: OBJ + MTL text through raylab's whole loading path (checks,
// tinyobjloader, triangles, BVH). The input is the OBJ text, then optionally a NUL byte
// and the text every mtllib line gets.
#include <cstddef>
#include <cstdint>
#include <string>

#include "raylab/error.h"
#include "raylab/scenes.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string input(reinterpret_cast<const char*>(data), size);
    const std::size_t nul = input.find('\0');
    const std::string obj = input.substr(0, nul);
    const std::string mtl = nul == std::string::npos ? "" : input.substr(nul + 1);
    raylab::LoadProgress quiet;
    quiet.warn = [](const std::string&) {};
    try {
        (void)raylab::load_obj_text(
            obj, "fuzz.obj", [&](const std::string&) { return mtl; }, quiet);
    } catch (const raylab::Error&) {
        // refused with a message: the expected outcome for most inputs
    }
    return 0;
}
