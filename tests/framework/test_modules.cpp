// The run-time module switch.
#include <doctest/doctest.h>

#include <string>

#include "raylab/error.h"
#include "raylab/modules.h"
#include "test_helpers.h"

using namespace raylab;

TEST_SUITE("modules") {
    TEST_CASE("module names, IDs and numbers all select the same module") {
        for (const char* word : {"sphere", "04_sphere", "4", "04"}) {
            INFO("word: " << word);
            ModuleSelection s;
            apply_module_list(s, word, Impl::reference);
            for (const ModuleInfo& info : module_infos()) {
                CHECK((s[info.module] == Impl::reference) ==
                      (info.module == Module::sphere));
            }
        }
    }

    TEST_CASE("lists apply in order and 'all' covers every module") {
        ModuleSelection s;
        apply_module_list(s, "all", Impl::reference);
        apply_module_list(s, " camera , point-light", Impl::student);
        CHECK(s[Module::camera] == Impl::student);
        CHECK(s[Module::point_light] == Impl::student);
        CHECK(s[Module::sphere] == Impl::reference);
        // Every other module of the registry, in its order: a new module needs no edit
        // here
        std::string others;
        for (const ModuleInfo& info : module_infos()) {
            if (info.module == Module::camera || info.module == Module::point_light)
                continue;
            others += (others.empty() ? "" : ",") + std::string(info.name);
        }
        CHECK(others.rfind("pixel-loop,plane,sphere,", 0) == 0);
        CHECK(describe(s) == "reference: " + others + "; student: camera,point-light");
    }

    TEST_CASE("an unknown module name is an error that lists the valid names") {
        ModuleSelection s;
        CHECK_THROWS_WITH_AS(apply_module_list(s, "camera,spheres", Impl::student),
                             doctest::Contains("unknown module 'spheres'"), Error);
        CHECK_THROWS_WITH_AS(apply_module_list(s, "", Impl::student),
                             doctest::Contains("empty module list"), Error);
    }

    TEST_CASE("the table points at the chosen implementation of each module") {
        ModuleSelection s = ModuleSelection::all(Impl::student);
        s[Module::sphere] = Impl::reference;
        const ModuleTable t = ModuleTable::make(s);
        CHECK((t.intersect_sphere == &reference::intersect_sphere));
        CHECK((t.intersect_plane == &student::intersect_plane));
        CHECK((t.render_tile == &student::render_tile));
        CHECK((t.in_shadow == &student::in_shadow));
    }

    TEST_CASE("every module ID is NN_name in teaching order") {
        int k = 1;
        for (const ModuleInfo& info : module_infos()) {
            const std::string id = info.id;
            CHECK(std::stoi(id.substr(0, 2)) == k++);
            CHECK(id[2] == '_');
        }
    }
}
