// The run-time module switch.
#include <doctest/doctest.h>

#include <string>

#include "raylab/error.h"
#include "raylab/modules.h"
#include "raylab/options.h"
#include "test_helpers.h"

using namespace raylab;

TEST_SUITE("modules") {
    TEST_CASE("module names, IDs and numbers all select the same module") {
        // Every word of every module of the registry selects that module and no other
        for (const ModuleInfo& target : module_infos()) {
            const std::string id = target.id;
            const std::string number = std::to_string(std::stoi(id.substr(0, 2)));
            for (const std::string& word :
                 {std::string(target.name), id, id.substr(3), id.substr(0, 2), number}) {
                INFO("word: " << word);
                ModuleSelection s;
                apply_module_list(s, word, Impl::reference);
                for (const ModuleInfo& info : module_infos())
                    CHECK((s[info.module] == Impl::reference) ==
                          (info.module == target.module));
            }
        }
    }

    TEST_CASE("lists apply in order and 'all' covers every module") {
        // The first and the last module of the registry back to the student's code
        const ModuleInfo& first = module_infos().front();
        const ModuleInfo& last = module_infos().back();
        ModuleSelection s;
        apply_module_list(s, "all", Impl::reference);
        apply_module_list(s, std::string(" ") + first.name + " , " + last.id,
                          Impl::student);
        std::string others;
        for (const ModuleInfo& info : module_infos()) {
            const bool chosen = info.module == first.module || info.module == last.module;
            CHECK((s[info.module] == Impl::student) == chosen);
            if (!chosen) others += (others.empty() ? "" : ",") + std::string(info.name);
        }
        CHECK(describe(s) ==
              "reference: " + others + "; student: " + first.name + "," + last.name);
    }

    TEST_CASE("an unknown module name is an error that lists the valid names") {
        ModuleSelection s;
        CHECK_THROWS_WITH_AS(apply_module_list(s, "camera,spheres", Impl::student),
                             doctest::Contains("unknown module 'spheres'"), Error);
        CHECK_THROWS_WITH_AS(apply_module_list(s, "", Impl::student),
                             doctest::Contains("empty module list"), Error);
    }

    TEST_CASE("the table points at the chosen implementation of each module") {
        // One module of the registry from the reference at a time: its functions, and
        // only its, are the reference's
        for (const ModuleInfo& info : module_infos()) {
            INFO("module: " << info.id);
            ModuleSelection s = ModuleSelection::all(Impl::student);
            s[info.module] = Impl::reference;
            const ModuleTable t = ModuleTable::make(s);
#define RAYLAB_FUNCTION(e, f) \
    CHECK((t.f == (Module::e == info.module ? &reference::f : &student::f)));
#include "raylab/modules.def"
        }
    }

    TEST_CASE("the CLI help names every module of the registry") {
        std::string help = options_help();
        for (char& c : help)
            if (c == '\n') c = ' ';
        for (const ModuleInfo& info : module_infos()) {
            INFO("module: " << info.name);
            const bool named =
                help.find(std::string(" ") + info.name + " ") != std::string::npos ||
                help.find(std::string(" ") + info.name + ",") != std::string::npos;
            CHECK(named);
        }
        CHECK(help.find("numbers 1-" + std::to_string(kModuleCount) + ",") !=
              std::string::npos);
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
