// raylab-input-check: the viewer's input paths without a window, for the bad-input table.
//
//   raylab-input-check view FILE        load a view file (--load-view)
//   raylab-input-check viewer FLAGS...  the viewer's flag parsing (shared and viewer
//   flags,
//                                       then the --load-view file when one is given)
//
// Exit code 0 and "ok" when accepted; 2 and "raylab: error: ..." as the viewer prints it.
#include <cstdio>
#include <cstring>
#include <exception>

#include "raylab/error.h"
#include "raylab/options.h"
#include "view_file.h"
#include "viewer_options.h"

int main(int argc, char** argv) {
    using namespace raylab;
    try {
        if (argc >= 3 && std::strcmp(argv[1], "view") == 0) {
            const viewer::ViewFile file = viewer::load_view_file(argv[2]);
            std::printf("ok: %zu lights\n", file.lights.size());
            return 0;
        }
        if (argc >= 2 && std::strcmp(argv[1], "viewer") == 0) {
            const Options options = parse_options(argc - 1, argv + 1, true);
            const viewer::ViewerOptions o = viewer::parse_viewer_options(
                options.extra, options.settings.width, options.settings.height);
            if (!o.load_view.empty()) (void)viewer::load_view_file(o.load_view);
            std::printf("ok\n");
            return 0;
        }
        std::fprintf(stderr, "usage: raylab-input-check view FILE | viewer FLAGS...\n");
        return 64;
    } catch (const Error& e) {
        std::fprintf(stderr, "raylab: error: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "raylab: internal error: %s\n", e.what());
        return 3;
    }
}
