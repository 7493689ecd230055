// The whole-render check of every module: the DTU scene rendered with this module's
// functions from the code under test (through the worker, tens of thousands of calls)
// and every other module from the reference, compared with the reference's image. Code
// that is right only for its first calls, or only for the graders' hand-picked inputs,
// fails here.
//
// Hidden tests: the "[private]" cases render from a viewpoint drawn from the instructor's
// secret seed (scripts/grade.sh --private DIR, DIR/seed); raylab-grade leaves them out
// unless it is given --private, and reports which part each point came from.
//
// A module joins this check with one RAYLAB_WHOLE_RENDER line below (modules the
// renderer never calls, such as a new sampling module, check their own images in their
// test file instead).
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "grading.h"
#include "raylab/renderer.h"
#include "raylab/scenes.h"

namespace raylab::grading {
namespace {

constexpr int kWidth = 128, kHeight = 96;
/// A pixel agrees when every channel is within this of the reference (relative above 1).
constexpr double kPixel = 1e-3;
/// At most this share of the pixels may disagree: a different but correct formula can
/// flip a few silhouette pixels, a wrong one flips whole surfaces.
constexpr double kShareOff = 0.01;

// The reference's table with module m's functions replaced by the code under test
ModuleTable mixed(Module m) {
    ModuleTable t = reference_modules();
#define RAYLAB_FUNCTION(e, f) \
    if (m == Module::e) t.f = under_test::f;
#include "raylab/modules.def"
    return t;
}

// Module 09 is called only when a pixel takes several samples: its render takes 2 x 2
// grid samples at half the size, the same number of rays (the grid alone: stratified
// samples may draw their numbers in any order, so their image need not match the
// reference's)
Image render_with(const ModuleTable& table, Module m, const View* view = nullptr) {
    const Scene scene = dtu_scene();
    RenderSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.threads = 1;  // one call at a time through the worker
    if (m == Module::antialiasing) {
        settings.width = kWidth / 2;
        settings.height = kHeight / 2;
        settings.spp = 4;
        settings.sampling = PixelSampling::grid;
    }
    Image image;
    render(scene, view ? *view : scene.view, settings, table, image);
    return image;
}

// The instructor's secret seed (RAYLAB_GRADE_PRIVATE=DIR, file DIR/seed), or a fixed one
// when there is none, so that the private cases are checked against the reference in CI
std::uint64_t private_seed() {
    const char* dir = std::getenv("RAYLAB_GRADE_PRIVATE");
    if (!dir || !*dir) return 20261124;
    std::ifstream in(std::string(dir) + "/seed");
    std::uint64_t seed = 0;
    if (!(in >> seed)) FAIL("cannot read a number from " << dir << "/seed");
    return seed;
}

// A viewpoint the student cannot know: around the DTU scene, from the secret seed
View hidden_view(Module m) {
    Rng rng(private_seed() * 31 + std::uint64_t(m));
    View view = dtu_scene().view;
    Vec3 dir = rng.direction();
    dir.y = std::abs(dir.y) * 0.6f + 0.15f;
    view.eye = view.lookat + glm::normalize(dir) * rng.uniform(3.0f, 6.0f);
    view.fov = rng.uniform(35.0f, 70.0f);
    return view;
}

void check_whole_render(Module m, bool hidden = false) {
    const ModuleInfo& info = module_info(m);
    const View view = hidden ? hidden_view(m) : dtu_scene().view;
    if (hidden && using_golden())
        FAIL("the private cases need the reference solutions in the build");
    // One golden image for modules 01-08, the reference's own render of the scene, and
    // one for 09's sampled render
    const bool sampled = m == Module::antialiasing;
    const Image want =
        hidden ? render_with(reference_modules(), m, &view)
               : expected_image("dtu", sampled ? "whole-render-grid4" : "whole-render",
                                [&] { return render_with(reference_modules(), m); });
    const Image got = render_with(mixed(m), m, &view);
    RAYLAB_REQUIRE(got.width == want.width && got.height == want.height,
                   "the image is " << got.width << " x " << got.height << ", expected "
                                   << want.width << " x " << want.height);
    int off = 0, first_i = -1, first_j = -1;
    for (int j = 0; j < got.height; ++j) {
        for (int i = 0; i < got.width; ++i) {
            const Vec3 a = got.at(i, j), b = want.at(i, j);
            bool same = true;
            for (int c = 0; c < 3; ++c)
                same = same && std::isfinite(a[c]) && close(a[c], b[c], kPixel);
            if (!same && off++ == 0) first_i = i, first_j = j;
        }
    }
    const double share = double(off) / (double(got.width) * got.height);
    std::ostringstream why;
    why << off << " of " << got.width * got.height << " pixels of the DTU scene ("
        << got.width << " x " << got.height << ", module " << info.id
        << " from your code, the rest from the reference) differ from the reference's "
           "image by more than "
        << kPixel << " (at most " << kShareOff * 100 << "% may); first at pixel ("
        << first_i << ", " << first_j << ")";
    if (share > kShareOff) {
        const std::string path = save_image(std::string(info.id) + "-whole-render", got);
        if (!path.empty()) why << "; your image: " << path;
    }
    RAYLAB_CHECK(share <= kShareOff, why.str());
}

}  // namespace

// Two test cases per module (on separate lines: doctest tells cases apart by line)
#define RAYLAB_WHOLE_RENDER(id, e)                                          \
    TEST_SUITE(id) {                                                        \
        TEST_CASE(                                                          \
            "a whole render of the DTU scene with this module matches the " \
            "reference's image") {                                          \
            check_whole_render(Module::e);                                  \
        }                                                                   \
    }
#define RAYLAB_PRIVATE_RENDER(id, e)                                             \
    TEST_SUITE(id) {                                                             \
        TEST_CASE(                                                               \
            "[private] a whole render of the DTU scene from a hidden viewpoint " \
            "matches the reference's image") {                                   \
            check_whole_render(Module::e, true);                                 \
        }                                                                        \
    }
RAYLAB_WHOLE_RENDER("01_pixel_loop", pixel_loop)
RAYLAB_PRIVATE_RENDER("01_pixel_loop", pixel_loop)
RAYLAB_WHOLE_RENDER("02_camera", camera)
RAYLAB_PRIVATE_RENDER("02_camera", camera)
RAYLAB_WHOLE_RENDER("03_plane", plane)
RAYLAB_PRIVATE_RENDER("03_plane", plane)
RAYLAB_WHOLE_RENDER("04_sphere", sphere)
RAYLAB_PRIVATE_RENDER("04_sphere", sphere)
RAYLAB_WHOLE_RENDER("05_triangle", triangle)
RAYLAB_PRIVATE_RENDER("05_triangle", triangle)
RAYLAB_WHOLE_RENDER("06_point_light", point_light)
RAYLAB_PRIVATE_RENDER("06_point_light", point_light)
RAYLAB_WHOLE_RENDER("07_lambert", lambert)
RAYLAB_PRIVATE_RENDER("07_lambert", lambert)
RAYLAB_WHOLE_RENDER("08_shadows", shadows)
RAYLAB_PRIVATE_RENDER("08_shadows", shadows)
RAYLAB_WHOLE_RENDER("09_antialiasing", antialiasing)
RAYLAB_PRIVATE_RENDER("09_antialiasing", antialiasing)

}  // namespace raylab::grading
