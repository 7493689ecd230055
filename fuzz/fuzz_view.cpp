// libFuzzer target: the viewer's view-file parser (camera and lights).
#include <cstddef>
#include <cstdint>
#include <string>

#include "raylab/error.h"
#include "view_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const raylab::viewer::ViewFile file =
            raylab::viewer::parse_view_file(text, "fuzz");
        // What parses must write and read back to the same view
        const std::string again =
            raylab::viewer::format_view_file(file.view, file.lights);
        (void)raylab::viewer::parse_view_file(again, "round trip");
    } catch (const raylab::Error&) {
    }
    return 0;
}
