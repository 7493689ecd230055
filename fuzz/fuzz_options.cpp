// libFuzzer target: the command-line parsers of raylab-render and the viewer. The input
// is split at NUL bytes into arguments.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "raylab/error.h"
#include "raylab/options.h"
#include "viewer_options.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size > 4096) return 0;
    std::vector<std::string> args{"raylab"};
    std::string word;
    for (std::size_t k = 0; k < size; ++k) {
        if (data[k] == 0) {
            args.push_back(word);
            word.clear();
        } else {
            word += static_cast<char>(data[k]);
        }
    }
    args.push_back(word);
    if (args.size() > 64) return 0;
    std::vector<const char*> argv;
    for (const std::string& a : args)
        argv.push_back(a.c_str());
    try {
        const raylab::Options o =
            raylab::parse_options(static_cast<int>(argv.size()), argv.data(), true);
        (void)raylab::viewer::parse_viewer_options(o.extra);
    } catch (const raylab::Error&) {
    }
    return 0;
}
