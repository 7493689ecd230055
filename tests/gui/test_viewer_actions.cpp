// The viewer's actions without a window: graders in child processes, reports, the
// background renderer and the panel's error handling.
#include <doctest/doctest.h>

#include <condition_variable>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>

#include <unistd.h>

#include "actions.h"
#include "grader.h"
#include "raylab/error.h"
#include "raylab/options.h"
#include "raylab/scenes.h"
#include "report.h"

using namespace raylab;
using namespace raylab::viewer;

namespace {

// A fresh folder per test case and process (ctest runs test cases in parallel)
std::string temp_dir(const std::string& name) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() /
        ("raylab-viewer-tests-" + std::to_string(getpid()) + "-" + name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir.string();
}

// A stand-in for raylab-grading-tests: a shell script that passes 03_plane, fails one
// case of 04_sphere and crashes in 05_triangle. doctest counts the cases of the other
// suites, filtered out by --test-suite, as "skipped"
// A stand-in for raylab-grading-tests speaking the grade driver's protocol (the case
// lines it writes to $RAYLAB_GRADE_LOG): 03_plane passes, 04_sphere fails a case, the
// worker of 05_triangle crashes, and the graders themselves crash on any other module
std::string fake_grader(const std::string& test) {
    const std::string path = temp_dir(test) + "/fake-grader.sh";
    std::ofstream(path)
        << "#!/bin/sh\n"
           "case \"$1\" in\n"
           "--list-test-cases) printf 'list\\t03_plane\\ta\\nlist\\t03_plane\\tb\\n"
           "list\\t04_sphere\\ta\\nlist\\t04_sphere\\tb\\nlist\\t05_triangle\\ta\\n"
           "list\\t01_pixel_loop\\ta\\n' > \"$RAYLAB_GRADE_LOG\";;\n"
           "--test-suite=03_plane) printf 'case\\t03_plane\\ta\\tpass\\n"
           "case\\t03_plane\\tb\\tpass\\n' > \"$RAYLAB_GRADE_LOG\";;\n"
           "--test-suite=04_sphere) printf 'case\\t04_sphere\\ta\\tpass\\n"
           "case\\t04_sphere\\tb\\tfail\\tt is NOT correct\\n' > "
           "\"$RAYLAB_GRADE_LOG\";;\n"
           "--test-suite=05_triangle) printf 'crash\\t05_triangle\\ta\\tthe worker "
           "crashed (SIGSEGV, Segmentation fault)\\n' > \"$RAYLAB_GRADE_LOG\";;\n"
           "*) kill -SEGV $$;;\n"
           "esac\n";
    std::filesystem::permissions(path, std::filesystem::perms::owner_all);
    return path;
}

Options parse(std::vector<const char*> args) {
    args.insert(args.begin(), "raylab");
    return parse_options(int(args.size()), args.data(), true);
}

// A viewer without a window whose worker signals results through a condition variable
struct Headless {
    std::mutex mutex;
    std::condition_variable cv;
    int wakes = 0;
    Viewer v;

    explicit Headless(const Options& options) {
        v.log.echo = false;
        init_viewer(v, options, ViewerOptions{}, [this] {
            std::lock_guard<std::mutex> lock(mutex);
            ++wakes;
            cv.notify_all();
        });
    }
    // Submits the state and waits for the worker's answer (no time limit: no timing)
    void render() {
        submit_if_dirty(v);
        for (;;) {
            {
                std::unique_lock<std::mutex> lock(mutex);
                cv.wait(lock, [this] { return wakes > 0; });
                wakes = 0;
            }
            if (take_result(v) && !v.worker->busy()) return;
        }
    }
};

}  // namespace

TEST_SUITE("viewer") {
    TEST_CASE("a child process reports exit codes, signals and time-outs") {
        const ChildResult ok =
            run_child({"/bin/sh", "-c", "echo hello; exit 3"}, {}, 30.0);
        CHECK(ok.started);
        CHECK(ok.exit_code == 3);
        CHECK(ok.output == "hello\n");
        const ChildResult env =
            run_child({"/bin/sh", "-c", "echo $RAYLAB_X"}, {"RAYLAB_X=7"}, 30.0);
        CHECK(env.output == "7\n");
        const ChildResult crash = run_child({"/bin/sh", "-c", "kill -SEGV $$"}, {}, 30.0);
        CHECK(crash.signal == SIGSEGV);
        // A hang is killed (the limit is short; the check is that it was killed)
        const ChildResult hang = run_child({"/bin/sh", "-c", "sleep 30"}, {}, 0.3);
        CHECK(hang.timed_out);
        CHECK(hang.signal == SIGKILL);
        const ChildResult missing = run_child({"/no/such/binary"}, {}, 30.0);
        CHECK(missing.exit_code == 127);
    }

    TEST_CASE("graders that pass, fail or crash are told apart") {
        const std::string grader = fake_grader("grades");
        const std::string runner = find_runner();
        REQUIRE(runner != "");
        const ModuleGrade plane = grade_with_runner(runner, grader, "03_plane", 30.0);
        CHECK(plane.status == ModuleGrade::Status::passed);
        CHECK(plane.summary == "2/2 passed");
        const ModuleGrade sphere = grade_with_runner(runner, grader, "04_sphere", 30.0);
        CHECK(sphere.status == ModuleGrade::Status::failed);
        CHECK(sphere.summary == "1/2 passed");
        CHECK(sphere.output.find("NOT correct") != std::string::npos);
        const ModuleGrade triangle =
            grade_with_runner(runner, grader, "05_triangle", 30.0);
        CHECK(triangle.status == ModuleGrade::Status::crashed);
        CHECK(triangle.summary == "crashed (SIGSEGV)");
        const ModuleGrade other =
            grade_with_runner(runner, grader, "01_pixel_loop", 30.0);
        CHECK(other.status == ModuleGrade::Status::error);
    }

    TEST_CASE("RAYLAB_GRADING_TESTS names the grading binary") {
        const std::string grader = fake_grader("find");
        setenv("RAYLAB_GRADING_TESTS", grader.c_str(), 1);
        CHECK(find_grading_binary("/anywhere/raylab") == grader);
        setenv("RAYLAB_GRADING_TESTS", "/no/such/grader", 1);
        CHECK(find_grading_binary("/anywhere/raylab") == "");
        unsetenv("RAYLAB_GRADING_TESTS");
    }

    TEST_CASE(
        "Run tests runs scripts/grade.sh of the viewer's source tree, on its exercises") {
        // A build folder whose cache names the source tree and the exercises, as CMake's
        const std::string dir = temp_dir("grade-script");
        std::filesystem::create_directories(dir + "/src/scripts");
        std::filesystem::create_directories(dir + "/build/framework/viewer");
        std::ofstream(dir + "/build/CMakeCache.txt")
            << "CMAKE_HOME_DIRECTORY:INTERNAL=" << dir << "/src\n"
            << "RAYLAB_EXERCISES_DIR:PATH=" << dir << "/handin\n";
        // A stand-in for grade.sh: writes the runner's cases.json into $GRADE_OUT, naming
        // the hand-in it was given
        const std::string script = dir + "/src/scripts/grade.sh";
        std::ofstream(script)
            << "cat > \"$GRADE_OUT/cases.json\" <<EOF\n"
               "[{\"id\": \"03_plane\", \"status\": \"passed\", \"passed\": 2, \"cases\":"
               " [{\"name\": \"a\", \"status\": \"pass\"}, {\"name\": \"b\", \"status\": "
               "\"pass\"}]},\n"
               " {\"id\": \"04_sphere\", \"status\": \"not started\", \"passed\": 0, "
               "\"cases\": [],"
               " \"first_failure\": \"$SUBMISSION\"}]\n"
               "EOF\n";
        const std::string viewer = dir + "/build/framework/viewer/raylab";
        unsetenv("RAYLAB_GRADING_TESTS");
        CHECK(find_grade_script(viewer) == script);
        CHECK(find_grading_binary(viewer) == script);
        CHECK(find_exercises_dir(viewer) == dir + "/handin");
        CHECK(find_grade_script("/no/build/framework/viewer/raylab") == "");

        setenv("SUBMISSION", "/inherited/must/not/win", 1);
        const auto grades = grade_with_script(script, dir + "/handin", 60.0);
        unsetenv("SUBMISSION");
        const ModuleGrade& plane = grades[static_cast<int>(Module::plane)];
        CHECK(plane.status == ModuleGrade::Status::passed);
        CHECK(plane.summary == "2/2 passed");
        const ModuleGrade& sphere = grades[static_cast<int>(Module::sphere)];
        CHECK(sphere.status == ModuleGrade::Status::not_started);
        CHECK(sphere.output == dir + "/handin");
        // The exercises beside the script are graded as `grade` does: SUBMISSION empty
        std::filesystem::create_directories(dir + "/src/exercises");
        const auto own = grade_with_script(script, dir + "/src/exercises", 60.0);
        CHECK(own[static_cast<int>(Module::sphere)].output == "");

        // A script that fails: every module says so, with its last line
        std::ofstream(script) << "echo 'cmake is missing'; exit 1\n";
        const auto failed = grade_with_script(script, "", 60.0);
        CHECK(failed[0].status == ModuleGrade::Status::error);
        CHECK(failed[0].summary.find("cmake is missing") != std::string::npos);
    }

    TEST_CASE("a report's render command reproduces the frame's flags") {
        ReportInput in;
        in.scene_source = "dtu";
        in.view = View{Vec3(0.5f, 1.25f, 4.0f), Vec3(0, 0.4f, 0), Vec3(0, 1, 0), 40.5f};
        in.lights = {{Vec3(1, 3, 2), Vec3(20, 10, 5)}};
        in.ambient = 0.25f;
        in.settings.width = 64;
        in.settings.height = 48;
        in.settings.mode = ShadingMode::normals;
        in.settings.shadows = false;
        in.modules = ModuleSelection::all(Impl::student);
        const std::string command = render_command(in, "out.png");
        // Split the command into words (it has no quoted words here) and parse them back
        std::istringstream words(command);
        std::vector<std::string> args;
        for (std::string w; words >> w;)
            args.push_back(w);
        std::vector<const char*> argv;
        for (const std::string& a : args)
            argv.push_back(a.c_str());
        const Options o = parse_options(int(argv.size()), argv.data());
        CHECK(args[0] == "raylab-render");
        CHECK(o.scene == "dtu");
        CHECK(*o.eye == in.view.eye);
        CHECK(*o.fov == in.view.fov);
        REQUIRE(o.lights.size() == 1);
        CHECK(o.lights[0].I == in.lights[0].I);
        CHECK(*o.ambient == 0.25f);
        CHECK(o.settings.mode == ShadingMode::normals);
        CHECK_FALSE(o.settings.shadows);
        CHECK(o.settings.width == 64);
        CHECK(o.output == "out.png");
        CHECK(o.modules.impl == in.modules.impl);
    }

    TEST_CASE("the viewer renders the same image as render() and reports into a folder") {
        const Options options =
            parse({"--width", "32", "--height", "24", "--eye", "0.3,0.2,3"});
        Headless h(options);
        h.render();
        REQUIRE(h.v.frames.have_full);
        const Scene scene = make_scene(options);
        Image expected;
        render(scene, scene.view, options.settings, ModuleTable::make(options.modules),
               expected);
        CHECK(h.v.frames.full->pixels == expected.pixels);

        const std::string dir = temp_dir("report") + "/report";
        CHECK(save_report(h.v, dir));
        for (const char* file : {"view.txt", "settings.txt", "image.png", "log.txt"})
            CHECK_MESSAGE(std::filesystem::exists(dir + "/" + file), file);
        std::ifstream settings(dir + "/settings.txt");
        std::stringstream text;
        text << settings.rdbuf();
        CHECK(text.str().find(
                  "raylab-render --scene cornell --eye 0.300000012,0.200000003,3") !=
              std::string::npos);
    }

    TEST_CASE("panel errors leave the previous scene and view running") {
        Headless h(parse({"--width", "16", "--height", "12"}));
        const View before = h.v.state.view;
        const std::uint64_t version = h.v.state.scene_version;

        // A view file with a bad line: message names the line, nothing changes
        const std::string dir = temp_dir("errors");
        std::ofstream(dir + "/bad.txt") << "eye 0 0 3\nlookat 0 0\n";
        CHECK_FALSE(load_view(h.v, dir + "/bad.txt"));
        CHECK(h.v.panel.error == dir + "/bad.txt:2: 'lookat' needs 3 numbers, found 2");
        CHECK(h.v.state.view.eye == before.eye);

        // An OBJ that does not exist: loaded in the background, fails, scene stays
        start_loading_scene(h.v, dir + "/missing.obj");
        h.v.loading.wait();
        finish_loading(h.v);
        CHECK(h.v.state.scene_version == version);
        CHECK(h.v.panel.error.find("missing.obj") != std::string::npos);
        CHECK(h.v.panel.error.find("still showing cornell") != std::string::npos);

        // A typed camera with eye == look-at is not applied
        View bad = before;
        bad.lookat = bad.eye;
        CHECK_FALSE(apply_view(h.v, bad));
        CHECK(h.v.panel.view_error.rfind("not applied: ", 0) == 0);
        CHECK(h.v.state.view.lookat == before.lookat);

        // A built-in scene loads at once and becomes the scene
        start_loading_scene(h.v, "dtu");
        CHECK(h.v.state.scene_version == version + 1);
        CHECK(h.v.state.scene.spheres.size() == 3);
    }

    TEST_CASE("an OBJ loads in the background and replaces the scene") {
        Headless h(parse({"--width", "16", "--height", "12"}));
        const std::uint64_t version = h.v.state.scene_version;
        const std::string path = temp_dir("obj") + "/triangle.obj";
        std::ofstream(path) << "v -1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        start_loading_scene(h.v, path);
        REQUIRE(h.v.loading.valid());
        h.v.loading.wait();
        finish_loading(h.v);
        CHECK(h.v.panel.error == "");
        CHECK(h.v.state.scene_version == version + 1);
        CHECK(h.v.state.scene.triangles.size() == 1);
        CHECK(h.v.state.scene_source == path);
        h.render();  // the worker receives the new geometry with the job
        CHECK(h.v.frames.have_full);
        CHECK(h.v.frames.full->width == 16);  // (stubs in a student release cast no rays)
    }

    TEST_CASE("a preview renders at a fraction of the size while a value is dragged") {
        CHECK(preview_factor(10.0) == 1);
        CHECK(preview_factor(100.0) == 2);
        CHECK(preview_factor(1e6) == 8);
        Headless h(parse({"--width", "64", "--height", "48"}));
        h.v.frames.last_full.milliseconds = 100.0;  // as if a full frame took 100 ms
        h.v.state.interacting = true;
        h.render();
        CHECK(h.v.frames.shown_preview);
        CHECK(h.v.frames.shown->width == 32);
        CHECK_FALSE(h.v.frames.have_full);
    }
}

TEST_SUITE("viewer") {
    TEST_CASE("the inspector probes the pinned pixel as the renderer traces it") {
        Headless h(parse({"--width", "16", "--height", "12"}));
        h.v.inspector.pinned = true;
        h.v.inspector.pin_i = 8;
        h.v.inspector.pin_j = 6;
        update_probes(h.v);
        REQUIRE(h.v.inspector.pin.probe);
        const ViewerState& s = h.v.state;
        const PixelProbe direct =
            probe_pixel(s.scene, s.view, s.settings, ModuleTable::make(s.modules), 8, 6);
        CHECK(h.v.inspector.pin.probe->uv == direct.uv);
        CHECK(h.v.inspector.pin.probe->L == direct.L);
        CHECK(h.v.inspector.pin.probe->hit.has_value() == direct.hit.has_value());
        // Nothing hovered: no tooltip probe; unpinned: the pinned probe goes
        CHECK_FALSE(h.v.inspector.hover.probe);
        h.v.inspector.pinned = false;
        update_probes(h.v);
        CHECK_FALSE(h.v.inspector.pin.probe);
    }
}

TEST_SUITE("viewer") {
    TEST_CASE("the probe records each light's shadow ray and names its blocker") {
#if RAYLAB_HAVE_REFERENCE
        const Scene box = load_scene("cornell");
        RenderSettings settings;
        settings.width = 320;
        settings.height = 240;
        // Pixel (240, 225) is on the floor in the short block's shadow
        const ModuleTable ref = ModuleTable::make(ModuleSelection::all(Impl::reference));
        const PixelProbe p = probe_pixel(box, box.view, settings, ref, 240, 225);
        REQUIRE(p.hit);
        REQUIRE(p.lights.size() == 1);
        const LightProbe& lp = p.lights[0];
        CHECK(lp.tested);
        CHECK(lp.blocked);
        REQUIRE(lp.rays.size() >= 1);
        REQUIRE(lp.blocker);
        CHECK(lp.blocker_name.rfind("triangle ", 0) == 0);
        CHECK(lp.blocker->t > lp.rays[0].tmin);
        CHECK(lp.blocker->t < lp.rays[0].tmax);
        // The shadow stub casts no ray and answers "lit"
        ModuleSelection stub_shadows = ModuleSelection::all(Impl::reference);
        stub_shadows[Module::shadows] = Impl::student;
        const PixelProbe s = probe_pixel(box, box.view, settings,
                                         ModuleTable::make(stub_shadows), 240, 225);
        REQUIRE(s.lights.size() == 1);
        CHECK(s.lights[0].tested);
        CHECK_FALSE(s.lights[0].blocked);
        CHECK(s.lights[0].rays.empty());
        CHECK_FALSE(s.lights[0].blocker);
        // Shadows off: sampled, not tested; other modes: no lights recorded
        settings.shadows = false;
        const PixelProbe off = probe_pixel(box, box.view, settings, ref, 240, 225);
        REQUIRE(off.lights.size() == 1);
        CHECK_FALSE(off.lights[0].tested);
        settings.mode = ShadingMode::normals;
        CHECK(probe_pixel(box, box.view, settings, ref, 240, 225).lights.empty());
#endif
    }
}

TEST_SUITE("viewer") {
    TEST_CASE("with area lights the probe counts each light's samples as the renderer") {
#if RAYLAB_HAVE_REFERENCE
        const Scene box = load_scene("cornell");
        RenderSettings settings;
        settings.width = 320;
        settings.height = 240;
        settings.light_size = 0.4f;
        settings.light_samples = 16;
        const ModuleTable ref = ModuleTable::make(ModuleSelection::all(Impl::reference));
        Image image;
        render(box, box.view, settings, ref, image);
        // Along row 225 (the floor through the short block's shadow): lit, penumbra,
        // umbra
        int lit = 0, penumbra = 0, umbra = 0;
        for (int i = 200; i < 280; ++i) {
            INFO("pixel (" << i << ", 225)");
            const PixelProbe p = probe_pixel(box, box.view, settings, ref, i, 225);
            REQUIRE(p.hit);
            CHECK(p.L == image.at(i, 225));  // the probe traces what the renderer did
            REQUIRE(p.lights.size() == 1);
            const LightProbe& lp = p.lights[0];
            CHECK(lp.area);
            CHECK(lp.samples == 16);
            CHECK(lp.tested);
            CHECK(lp.backfacing_samples + lp.blocked_samples + lp.visible_samples == 16);
            CHECK(lp.blocked == (lp.blocked_samples > 0));
            // No visible sample: only the ambient term (0 here) is left
            CHECK((lp.visible_samples == 0) == (p.L == Vec3(0.0f)));
            if (lp.visible_samples == 0) CHECK(lp.Li_visible == Vec3(0.0f));
            if (lp.visible_samples > 0) CHECK(lp.Li_visible.x > 0.0f);
            if (lp.blocked) {
                // The sample shown is a blocked one: its ray meets the named blocker
                REQUIRE(lp.rays.size() >= 1);
                REQUIRE(lp.blocker);
                CHECK(lp.blocker_name.rfind("triangle ", 0) == 0);
                CHECK(lp.blocker->t < lp.rays[0].tmax);
                CHECK(glm::dot(lp.rays[0].w, lp.sample.wi) > 0.999f);
            }
            lit += lp.blocked_samples == 0;
            umbra += lp.visible_samples == 0;
            penumbra += lp.blocked_samples > 0 && lp.visible_samples > 0;
        }
        CHECK(lit > 0);
        CHECK(penumbra > 0);
        CHECK(umbra > 0);
        // The student's stub of module 10 gives no point: an area light of 0 samples
        ModuleSelection stub = ModuleSelection::all(Impl::reference);
        stub[Module::area_light] = Impl::student;
        const PixelProbe s =
            probe_pixel(box, box.view, settings, ModuleTable::make(stub), 240, 225);
        REQUIRE(s.lights.size() == 1);
        CHECK(s.lights[0].area);
        CHECK(s.lights[0].samples == 0);
        CHECK(s.lights[0].visible_samples == 0);
        // Point lights (size 0) keep the point-light probe
        settings.light_size = 0.0f;
        CHECK_FALSE(probe_pixel(box, box.view, settings, ref, 240, 225).lights[0].area);
#endif
    }
}

TEST_SUITE("viewer") {
    // (These two need the reference: in a student release the stubs draw black frames)
    TEST_CASE("a frame with the inputs of a kept one is reused, not rendered again" *
              doctest::skip(!reference_available())) {
        Headless h(parse({"--width", "48", "--height", "36", "--reference", "all"}));
        h.render();
        REQUIRE(h.v.frames.have_full);
        const Image first = *h.v.frames.full;
        CHECK(h.v.frames.frames_rendered == 1);

        // Shadows off: a new frame; on again: the first frame's inputs, no render
        h.v.state.settings.shadows = false;
        h.v.state.dirty = true;
        h.render();
        CHECK(h.v.frames.frames_rendered == 2);
        CHECK(h.v.frames.full->pixels != first.pixels);
        h.v.state.settings.shadows = true;
        h.v.state.dirty = true;
        h.render();
        CHECK(h.v.frames.frames_rendered == 2);
        CHECK(h.v.frames.frames_reused == 1);
        CHECK(h.v.frames.last_reused);
        CHECK(h.v.frames.full->pixels == first.pixels);
        CHECK(h.v.log.text().find("reused 48x36") != std::string::npos);

        // --repeat forces a render of the same inputs: every tile as before
        h.v.state.force_render = true;
        h.v.state.dirty = true;
        h.render();
        CHECK(h.v.frames.frames_rendered == 3);
        CHECK_FALSE(h.v.frames.last_reused);
        CHECK(h.v.frames.full->pixels == first.pixels);
        CHECK(h.v.frames.tiles_total == 3 * 3);  // 48x36 in 16x16 tiles
        CHECK(h.v.frames.tiles_changed == 0);
        // and a full frame's work: every camera ray cast, none of the kept hits shaded
        CHECK(h.v.frames.last_full.camera_rays == 48 * 36);
        CHECK(h.v.frames.last_full.camera_rays_reused == 0);

        // A light moved: the frame changes, and the statistics count changed tiles. The
        // frame before had the same camera, so this one keeps its camera hits
        // (CameraHits)
        h.v.state.scene.lights[0].p.x += 0.2f;
        h.v.state.dirty = true;
        h.render();
        CHECK(h.v.frames.frames_rendered == 4);
        CHECK(h.v.frames.tiles_changed > 0);
        CHECK(h.v.frames.tiles_changed <= 9);
        CHECK(h.v.frames.last_full.camera_rays == 48 * 36);
        // and the next light move shades them again, casting no camera ray, and says so
        h.v.state.scene.lights[0].p.x += 0.2f;
        h.v.state.dirty = true;
        h.render();
        CHECK(h.v.frames.frames_rendered == 5);
        CHECK(h.v.frames.last_full.camera_rays == 0);
        CHECK(h.v.frames.last_full.camera_rays_reused == 48 * 36);
        CHECK(h.v.log.text().find("camera hits reused: 1728") != std::string::npos);
    }

    TEST_CASE("compare turned on reuses the frame and renders only the reference" *
              doctest::skip(!reference_available())) {
        // Reference modules everywhere: the frame is the reference, so the difference
        // is zero; the compare switch alone changes no input of the image
        Headless h(parse({"--width", "32", "--height", "24", "--reference", "all"}));
        h.render();
        h.v.state.compare = true;
        h.v.state.dirty = true;
        h.render();
        CHECK(h.v.frames.last_reused);
        REQUIRE(h.v.frames.difference);
        CHECK(h.v.frames.difference->rmse == 0.0);
        h.v.state.compare = false;
        h.v.state.dirty = true;
        h.render();
        CHECK(h.v.frames.frames_rendered == 1);
        CHECK(h.v.frames.frames_reused == 2);
    }

    TEST_CASE("a slow frame starts coarse and refines: 1/f, then 1/2, then full") {
        FrameState f;
        RenderJob job;
        CHECK(coarse_levels(f, job).empty());  // no full frame yet: nothing to go by
        f.have_full = true;
        f.last_full.milliseconds = 60.0;  // fast enough: the full frame at once
        CHECK(coarse_levels(f, job).empty());
        f.last_full.milliseconds = 1000.0;  // preview_factor 7 (7 x 7 x 25 ms > 1 s)
        CHECK(coarse_levels(f, job) == std::vector<int>{7, 2});
        f.last_full.milliseconds = 150.0;  // factor 3: one preview
        CHECK(coarse_levels(f, job) == std::vector<int>{3});
        // A drag ended on these inputs with a 1/7 preview: only 1/2 is left to show
        f.last_full.milliseconds = 1000.0;
        f.sent = job;
        f.sent.preview_factor = 7;
        CHECK(coarse_levels(f, job) == std::vector<int>{2});
        f.sent.view.fov += 1.0f;  // another view: all levels again
        CHECK(coarse_levels(f, job) == std::vector<int>{7, 2});

        // The worker shows them coarsest first and ends with the full frame of render()
        const Options options = parse({"--width", "64", "--height", "48"});
        Headless h(options);
        h.render();
        h.v.frames.last_full.milliseconds = 1000.0;  // as if the full frame took 1 s
        h.v.state.view.eye.x += 0.1f;
        h.v.state.dirty = true;
        submit_if_dirty(h.v);
        int last_factor = 1000;
        for (;;) {
            {
                std::unique_lock<std::mutex> lock(h.mutex);
                h.cv.wait(lock, [&] { return h.wakes > 0; });
                h.wakes = 0;
            }
            if (take_result(h.v)) {
                INFO("factor " << h.v.frames.shown_factor << " after " << last_factor);
                CHECK(h.v.frames.shown_factor <= last_factor);  // never coarser again
                CHECK(h.v.frames.shown_job == h.v.frames.last_job);
                last_factor = h.v.frames.shown_factor;
                if (!h.v.frames.shown_preview) break;
                CHECK(h.v.frames.shown->width == 64 / h.v.frames.shown_factor);
            }
        }
        CHECK(h.v.frames.frames_rendered == 2);
        Image expected;
        const Scene scene = make_scene(options);
        render(scene, h.v.state.view, options.settings,
               ModuleTable::make(options.modules), expected);
        CHECK(h.v.frames.full->pixels == expected.pixels);
    }
}
