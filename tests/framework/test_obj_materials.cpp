// OBJ and MTL files as exporters write them: material names with spaces or none, missing
// material libraries, and text in UTF-16 or UTF-32.
#include <map>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "raylab/error.h"
#include "raylab/input_file.h"
#include "raylab/scenes.h"

using namespace raylab;

namespace {

// Two triangles of the unit square, lower left (1 2 3) and upper right (2 4 3)
const std::string kSquare = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n";

// A loader whose MTL files are the map's; a name not in it cannot be opened
struct Load {
    std::map<std::string, std::string> mtl;
    std::vector<std::string> warnings;

    Scene operator()(const std::string& obj) {
        LoadProgress progress;
        progress.warn = [&](const std::string& w) { warnings.push_back(w); };
        const auto read = [&](const std::string& name) {
            const auto it = mtl.find(name);
            if (it == mtl.end()) throw Error(name + ": cannot open file (test)");
            return it->second;
        };
        return load_obj_text(obj, "t.obj", read, progress);
    }
};

// The material names of the lower-left and the upper-right triangle (the BVH may have
// reordered the triangles)
std::vector<std::string> corner_materials(const Scene& scene) {
    std::vector<std::string> names(2);
    for (const SceneTriangle& t : scene.triangles) {
        const bool upper = t.v0.x + t.v1.x + t.v2.x > 1.5f;
        names[upper] = scene.materials[t.material].name;
    }
    return names;
}

std::string utf16le(const std::string& ascii) {
    std::string out;
    for (const char c : ascii)
        out += std::string(1, c) + '\0';
    return out;
}

}  // namespace

TEST_SUITE("obj") {
    TEST_CASE("material names are the rest of the line, spaces and tabs inside kept") {
        Load load;
        load.mtl["m.mtl"] =
            "newmtl Hard Shiny Plastic White\nKd 0.9 0.9 0.9\n"
            "newmtl \tTwo  Spaces\tand a tab \r\nKd 0.1 0.2 0.3\r\n"
            "newmtl Hard\nKd 0.5 0 0\n";
        const Scene scene = load("mtllib m.mtl\n" + kSquare +
                                 "usemtl   Hard Shiny Plastic White \nf 1 2 3\n"
                                 "usemtl Two  Spaces\tand a tab\t\r\nf 2 4 3\n");
        CHECK(load.warnings.empty());
        CHECK(corner_materials(scene) ==
              std::vector<std::string>{"Hard Shiny Plastic White",
                                       "Two  Spaces\tand a tab"});
        REQUIRE(scene.materials.size() == 4);  // three and the default
        CHECK(scene.materials[1].rho == Vec3(0.1f, 0.2f, 0.3f));
    }

    TEST_CASE("a '#' in a material name is part of it") {
        Load load;
        load.mtl["m.mtl"] =
            "newmtl Material #1\nKd 1 0 0\nnewmtl Material #2\nKd 0 0 1\n";
        const Scene scene =
            load("mtllib m.mtl # the library\n" + kSquare +
                 "usemtl Material #1\nf 1 2 3\nusemtl Material #2\nf 2 4 3\n");
        CHECK(load.warnings.empty());
        CHECK(corner_materials(scene) ==
              std::vector<std::string>{"Material #1", "Material #2"});
    }

    TEST_CASE("a material without a name is called 'unnamed', with a warning") {
        Load load;
        load.mtl["m.mtl"] = "newmtl\nKd 0.5 0.25 0\nnewmtl b\nKd 0 0 1\n";
        const Scene scene =
            load("mtllib m.mtl\n" + kSquare + "usemtl\nf 1 2 3\nusemtl b\nf 2 4 3\n");
        CHECK(corner_materials(scene) == std::vector<std::string>{"unnamed", "b"});
        CHECK(load.warnings ==
              std::vector<std::string>{
                  "m.mtl:1: 'newmtl' without a name: the material is called 'unnamed'",
                  "t.obj:6: 'usemtl' without a name: read as the material 'unnamed'"});

        // No such material: the default, and one warning for all such lines
        Load bare;
        const Scene plain = bare(kSquare + "usemtl\t\nf 1 2 3\nusemtl   \nf 2 4 3\n");
        CHECK(corner_materials(plain) == std::vector<std::string>{"default", "default"});
        CHECK(bare.warnings == std::vector<std::string>{
                                   "t.obj:5: 'usemtl' without a name (and 1 more "
                                   "such lines); its faces get the default material"});
    }

    TEST_CASE("a missing material library is one warning and the geometry loads") {
        Load load;
        const Scene scene = load("mtllib x.mat\n" + kSquare +
                                 "usemtl Red\nf 1 2 3\nusemtl Blue\nf 2 4 3\n");
        CHECK(scene.triangles.size() == 2);
        CHECK(corner_materials(scene) == std::vector<std::string>{"default", "default"});
        CHECK(load.warnings ==
              std::vector<std::string>{
                  "t.obj:1: mtllib: x.mat: cannot open file (test); faces "
                  "using its materials get the default material"});

        // Several on one line, some missing: each missing one is named once; the others'
        // materials are used
        Load some;
        some.mtl["b.mtl"] = "newmtl Red\nKd 1 0 0\n";
        const Scene mixed = some("mtllib a.mtl b.mtl c.mtl\nmtllib a.mtl\n" + kSquare +
                                 "usemtl Red\nf 1 2 3\nusemtl Blue\nf 2 4 3\n");
        CHECK(corner_materials(mixed) == std::vector<std::string>{"Red", "default"});
        REQUIRE(some.warnings.size() == 2);
        CHECK(some.warnings[0].rfind("t.obj:1: mtllib: a.mtl: cannot open file", 0) == 0);
        CHECK(some.warnings[1].rfind("t.obj:1: mtllib: c.mtl: cannot open file", 0) == 0);
    }

    TEST_CASE("a material without a Kd line gets the default grey, with a warning") {
        // Textured exports often give only map_Kd, which raylab ignores: with
        // tinyobjloader's diffuse of 0 such a model rendered black without a word
        Load load;
        load.mtl["m.mtl"] =
            "# textures only\nnewmtl Skin Tone\nNs 10\nmap_Kd skin.png\n"
            "newmtl Black\nKd 0 0 0\nnewmtl Dark\nKd 0\nnewmtl Red\nKd 1 0 0\n"
            "newmtl Glow\nKe 2 2 2\n";
        const Scene scene = load("mtllib m.mtl\n" + kSquare +
                                 "usemtl Skin Tone\nf 1 2 3\nusemtl Black\nf 2 4 3\n");
        REQUIRE(scene.materials.size() == 6);  // five and the default
        const Vec3 grey = scene.materials.back().rho;
        CHECK(scene.materials.back().name == "default");
        CHECK(grey == Vec3(0.75f));
        CHECK(scene.materials[0].rho == grey);
        CHECK(scene.materials[1].rho == Vec3(0.0f));  // Kd 0 0 0: what the file says
        CHECK(scene.materials[2].rho == Vec3(0.0f));
        CHECK(scene.materials[3].rho == Vec3(1.0f, 0.0f, 0.0f));
        CHECK(scene.materials[4].rho == grey);  // the last material, closed by the end
        CHECK(scene.materials[4].Le == Vec3(2.0f));
        CHECK(load.warnings ==
              std::vector<std::string>{
                  "m.mtl:2: material 'Skin Tone' has no Kd: it gets the default diffuse "
                  "colour (0.75 0.75 0.75)",
                  "m.mtl:11: material 'Glow' has no Kd: it gets the default diffuse "
                  "colour (0.75 0.75 0.75)",
                  "m.mtl: ignored 1 line(s) raylab does not use (first: line 4, "
                  "'map_Kd')"});

        // Many: one warning each for the first eight, then one for the rest
        Load many;
        std::string mtl;
        for (int k = 0; k < 20; ++k)
            mtl += "newmtl m" + std::to_string(k) + "\n";
        many.mtl["m.mtl"] = mtl;
        const Scene bare = many("mtllib m.mtl\n" + kSquare + "usemtl m19\nf 1 2 3\n");
        CHECK(bare.materials[bare.triangles[0].material].rho == Vec3(0.75f));
        REQUIRE(many.warnings.size() == 9);
        CHECK(many.warnings[7] ==
              "m.mtl:8: material 'm7' has no Kd: it gets the default "
              "diffuse colour (0.75 0.75 0.75)");
        CHECK(many.warnings[8] ==
              "m.mtl:9: and 12 more material(s) without Kd: they get "
              "the default diffuse colour (0.75 0.75 0.75) too");
    }

    TEST_CASE("a material library that is read must be valid") {
        Load load;
        load.mtl["m.mtl"] = "newmtl a\nKd 0.5 nan 0\n";
        CHECK_THROWS_WITH_AS(load("mtllib m.mtl\n" + kSquare + "usemtl a\nf 1 2 3\n"),
                             "m.mtl:2: green: 'nan' is not a finite number", Error);
        load.mtl["m.mtl"] = utf16le("newmtl a\nKd 1 1 1\n");
        CHECK_THROWS_WITH_AS(load("mtllib m.mtl\n" + kSquare + "usemtl a\nf 1 2 3\n"),
                             doctest::Contains("m.mtl: the file is UTF-16LE text"),
                             Error);
    }

    TEST_CASE("usemtl names resolve after every mtllib, unknown ones in one warning") {
        Load load;
        load.mtl["m.mtl"] = "newmtl Red\nKd 1 0 0\nnewmtl Red\nKd 0 1 0\n";
        std::string obj = kSquare + "usemtl Red\nf 1 2 3\n";
        for (int k = 0; k < 500; ++k)
            obj += "usemtl Nosuch " + std::to_string(k) + "\n";
        obj += "f 2 4 3\nmtllib m.mtl\n";
        const Scene scene = load(obj);
        // The first material of a name wins, as in tinyobjloader
        const std::vector<std::string> names = corner_materials(scene);
        CHECK(names == std::vector<std::string>{"Red", "default"});
        for (const SceneTriangle& t : scene.triangles)
            if (scene.materials[t.material].name == "Red")
                CHECK(scene.materials[t.material].rho == Vec3(1.0f, 0.0f, 0.0f));
        CHECK(load.warnings == std::vector<std::string>{
                                   "t.obj:7: usemtl 'Nosuch 0': no material of that name "
                                   "(nor of 499 other name(s) used); its faces get the "
                                   "default material"});
    }

    TEST_CASE("a file of material names is refused before it fills the memory") {
        std::string obj = kSquare + "f 1 2 3\n";
        for (int k = 0; k <= 65536; ++k)
            obj += "usemtl m" + std::to_string(k) + "\n";
        Load load;
        CHECK_THROWS_WITH_AS(
            load(obj), "t.obj:65542: usemtl: more than 65536 material names", Error);
        Load fits;
        obj.resize(obj.rfind("usemtl"));
        CHECK(fits(obj).triangles.size() == 1);
    }

    TEST_CASE("UTF-16 and UTF-32 are named, with or without a byte order mark") {
        const std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        std::string le16, be16, le32, be32;
        for (const char c : text) {
            le16 += std::string(1, c) + '\0';
            be16 += std::string(1, '\0') + c;
            le32 += std::string(1, c) + std::string(3, '\0');
            be32 += std::string(3, '\0') + c;
        }
        CHECK(text_encoding(le16) == "UTF-16LE");
        CHECK(text_encoding("\xFF\xFE" + le16) == "UTF-16LE");
        CHECK(text_encoding(le16.substr(0, le16.size() - 1)) ==
              "UTF-16LE");  // odd length
        CHECK(text_encoding(be16) == "UTF-16BE");
        CHECK(text_encoding("\xFE\xFF" + be16) == "UTF-16BE");
        CHECK(text_encoding(le32) == "UTF-32LE");
        CHECK(text_encoding(std::string("\xFF\xFE\0\0", 4) + le32) == "UTF-32LE");
        CHECK(text_encoding(be32) == "UTF-32BE");
        CHECK(text_encoding(std::string("\0\0\xFE\xFF", 4) + be32) == "UTF-32BE");
        // UTF-8, with a byte order mark or a stray NUL, is not mistaken for them
        CHECK(text_encoding(text) == "");
        CHECK(text_encoding("\xEF\xBB\xBF" + text) == "");
        CHECK(text_encoding(std::string("v\0 0 0 0\n", 9)) == "");
        CHECK(text_encoding(std::string("# \0\n", 4) + text) == "");
        CHECK(text_encoding("") == "");
        CHECK(text_encoding("v") == "");

        CHECK_THROWS_WITH_AS(
            split_lines("\xFF\xFE" + le16, 100, "a.obj"),
            "a.obj: the file is UTF-16LE text; raylab reads UTF-8 (or "
            "ASCII): convert it, e.g. iconv -f UTF-16LE -t UTF-8 OLD > NEW",
            Error);
        Load load;
        CHECK_THROWS_WITH_AS(load(be32), doctest::Contains("t.obj: the file is UTF-32BE"),
                             Error);
        // A Windows file (CRLF) in UTF-16 is named as such, not as a stray CR
        std::string crlf;
        for (const char c : std::string("v 0 0 0\r\nv 1 0 0\r\n"))
            crlf += std::string(1, c) + '\0';
        CHECK_THROWS_WITH_AS(load("\xFF\xFE" + crlf),
                             doctest::Contains("t.obj: the file is UTF-16LE"), Error);
    }
}
