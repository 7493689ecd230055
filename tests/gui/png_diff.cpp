// raylab-png-diff: compares two PNGs (or a region of the first) channel by channel.
//
//   raylab-png-diff A.png B.png [--crop X,Y,W,H] [--tolerance N]
//
// Prints the largest and mean absolute difference of the 8-bit channels and exits 0 when
// the largest is at most N (default 0), 1 when it is larger, 2 on bad input. The GUI
// tests compare the viewer's screenshot region and saved image with raylab-render's.
#include <stb_image.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr,
                     "usage: raylab-png-diff A.png B.png [--crop X,Y,W,H] "
                     "[--tolerance N]\n");
        return 2;
    }
    int cx = 0, cy = 0, cw = -1, ch = -1, tolerance = 0;
    for (int k = 3; k + 1 < argc; k += 2) {
        const std::string flag = argv[k];
        if (flag == "--crop" &&
            std::sscanf(argv[k + 1], "%d,%d,%d,%d", &cx, &cy, &cw, &ch) == 4)
            continue;
        if (flag == "--tolerance") {
            tolerance = std::atoi(argv[k + 1]);
            continue;
        }
        std::fprintf(stderr, "raylab-png-diff: bad argument '%s'\n", argv[k]);
        return 2;
    }
    int wa, ha, wb, hb, n;
    unsigned char* a = stbi_load(argv[1], &wa, &ha, &n, 3);
    unsigned char* b = stbi_load(argv[2], &wb, &hb, &n, 3);
    if (!a || !b) {
        std::fprintf(stderr, "raylab-png-diff: cannot read %s\n", a ? argv[2] : argv[1]);
        return 2;
    }
    if (cw < 0) cw = wa, ch = ha;
    if (cw != wb || ch != hb || cx < 0 || cy < 0 || cx + cw > wa || cy + ch > ha) {
        std::fprintf(stderr, "raylab-png-diff: region %dx%d at %d,%d of %dx%d vs %dx%d\n",
                     cw, ch, cx, cy, wa, ha, wb, hb);
        return 2;
    }
    int worst = 0;
    double sum = 0.0;
    for (int y = 0; y < ch; ++y) {
        for (int x = 0; x < cw * 3; ++x) {
            const int d =
                std::abs(int(a[((cy + y) * wa + cx) * 3 + x]) - int(b[y * wb * 3 + x]));
            worst = std::max(worst, d);
            sum += d;
        }
    }
    std::printf(
        "compared %dx%d pixels: max channel difference %d, mean %.4f (tolerance %d)\n",
        cw, ch, worst, sum / (3.0 * cw * ch), tolerance);
    stbi_image_free(a);
    stbi_image_free(b);
    return worst <= tolerance ? 0 : 1;
}
