// OBJ loading and command-line options: good input works, bad input gets a clear error.
#include <cstdio>
#include <fstream>

#include <doctest/doctest.h>

#include "raylab/error.h"
#include "raylab/options.h"
#include "raylab/scenes.h"
#include "test_helpers.h"

using namespace raylab;

namespace {

// Writes text to a file in the working directory and removes it at scope exit
struct TempFile {
    std::string path;
    TempFile(std::string name, const std::string& text) : path(std::move(name)) {
        std::ofstream(path) << text;
    }
    ~TempFile() { std::remove(path.c_str()); }
};

Options parse(std::vector<const char*> args) {
    args.insert(args.begin(), "raylab-render");
    return parse_options(static_cast<int>(args.size()), args.data());
}

}  // namespace

TEST_SUITE("obj") {
    TEST_CASE("an OBJ quad with an MTL file loads as two triangles with Kd as rho") {
        const TempFile mtl("raylab-test-quad.mtl", "newmtl orange\nKd 0.9 0.5 0.1\n");
        const TempFile obj(
            "raylab-test-quad.obj",
            "mtllib raylab-test-quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
            "usemtl orange\nf 1 2 3 4\n");
        const Scene scene = load_obj(obj.path);
        REQUIRE(scene.triangles.size() == 2);
        const Material& m = scene.materials[scene.triangles[0].material];
        CHECK(m.name == "orange");
        CHECK(m.rho == Vec3(0.9f, 0.5f, 0.1f));
        // No normals in the file: flat shading from the geometric normal
        CHECK(scene.normals.empty());
        // The default view looks at the model's centre from the front, with one light
        CHECK(scene.view.lookat == Vec3(0.5f, 0.5f, 0.0f));
        CHECK(scene.view.eye.z > 1.0f);
        CHECK(scene.lights.size() == 1);
        CHECK_NOTHROW(validate(scene.view));
    }

    TEST_CASE("malformed OBJ files are rejected with the file name and the problem") {
        const TempFile bad_index("raylab-test-bad-index.obj",
                                 "v 0 0 0\nv 1 0 0\nf 1 2 9\n");
        CHECK_THROWS_WITH_AS(load_obj(bad_index.path),
                             doctest::Contains("raylab-test-bad-index.obj"), Error);
        const TempFile empty("raylab-test-empty.obj", "# nothing\nv 0 0 0\n");
        CHECK_THROWS_WITH_AS(load_obj(empty.path), doctest::Contains("holds no faces"),
                             Error);
        // 1e40 overflows float (and a literal "nan" is refused as well)
        const TempFile nan("raylab-test-nan.obj",
                           "v 1e40 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        CHECK_THROWS_WITH_AS(load_obj(nan.path),
                             doctest::Contains("is not a finite number"), Error);
        const TempFile garbage("raylab-test-garbage.obj",
                               std::string("\x01\x02\xff garbage", 11));
        CHECK_THROWS_AS(load_obj(garbage.path), Error);
    }
}

TEST_SUITE("options") {
    TEST_CASE("flags set the view, lights, size, mode and modules") {
        const Options o =
            parse({"--scene",  "dtu",         "--eye",       "1,2,3",     "--fov",
                   "30",       "--light",     "0,5,0:1,2,3", "--width",   "320",
                   "--height", "200",         "--mode",      "normals",   "--shadows",
                   "off",      "--reference", "all",         "--student", "camera"});
        CHECK(o.scene == "dtu");
        CHECK(*o.eye == Vec3(1, 2, 3));
        CHECK(*o.fov == 30.0f);
        REQUIRE(o.lights.size() == 1);
        CHECK(o.lights[0].I == Vec3(1, 2, 3));
        CHECK(o.settings.width == 320);
        CHECK(o.settings.mode == ShadingMode::normals);
        CHECK_FALSE(o.settings.shadows);
        CHECK(o.modules[Module::camera] == Impl::student);
        CHECK(o.modules[Module::sphere] == Impl::reference);
        const Scene s = make_scene(o);
        CHECK(s.view.eye == Vec3(1, 2, 3));
        CHECK(s.lights.size() == 1);
    }

    TEST_CASE("bad values name the flag and the problem") {
        const std::vector<std::pair<std::vector<const char*>, const char*>> cases = {
            {{"--fov", "0"}, "outside [0.1, 179.9]"},
            {{"--fov", "180"}, "outside [0.1, 179.9]"},
            {{"--fov", "nan"}, "not a finite number"},
            {{"--eye", "1,2"}, "not three numbers"},
            {{"--eye", "1,2,inf"}, "not a finite number"},
            {{"--width", "0"}, "resolution"},
            {{"--width", "100000", "--height", "100000"}, "resolution"},
            {{"--width", "12x"}, "not a whole number"},
            {{"--mode", "phong"}, "unknown shading mode"},
            {{"--shadows", "maybe"}, "neither on nor off"},
            {{"--light", "1,2,3"}, "X,Y,Z:R,G,B"},
            {{"--student", "spheres"}, "unknown module"},
            {{"--bogus"}, "unknown option"},
            {{"--scene"}, "needs a value"},
        };
        for (const auto& [args, message] : cases) {
            // INFO captures in a lambda, which clang 14 refuses for a structured binding
            const std::string shown = std::string(args[0]) +
                                      (args.size() > 1 ? std::string(" ") + args[1] : "");
            INFO("args: " << shown);
            CHECK_THROWS_WITH_AS(parse(args), doctest::Contains(message), Error);
        }
    }

    TEST_CASE("a zero or parallel up vector is caught when the scene is made") {
        CHECK_THROWS_WITH_AS(make_scene(parse({"--up", "0,0,0"})),
                             doctest::Contains("up vector is zero"), Error);
        CHECK_THROWS_WITH_AS(make_scene(parse({"--eye", "0,5,0", "--lookat", "0,0,0"})),
                             doctest::Contains("parallel"), Error);
    }

    TEST_CASE("module flags change the automatic choice only for the modules they name") {
        const ModuleSelection automatic = auto_selection();
        const Options o = parse({"--student", "sphere"});
        for (const ModuleInfo& info : module_infos()) {
            INFO(info.id);
            const Impl expected =
                info.module == Module::sphere ? Impl::student : automatic[info.module];
            CHECK(o.modules[info.module] == expected);
        }
        CHECK(o.modules_given);
    }

    TEST_CASE(
        "without module flags, started modules run the student's code, stubs the "
        "reference") {
        const std::uint32_t stubs = detect_stubs();
        const ModuleSelection s = auto_selection();
        for (const ModuleInfo& info : module_infos()) {
            const bool stub = stubs & (1u << static_cast<int>(info.module));
            INFO(info.id);
            CHECK(s[info.module] == (stub ? Impl::reference : Impl::student));
        }
    }
}
