// Shared helpers of the graders (grading.h).
#include "grading.h"

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <type_traits>

#include "raylab/error.h"

namespace raylab::grading {

namespace {

// ---- What this run grades -------------------------------------------------------------

struct Settings {
    Impl impl = Impl::student;
    bool golden = false;                // expected values from tests/data/golden/
    std::string golden_dir;             // where the golden data is read
    std::string record_dir;             // RAYLAB_GOLDEN_WRITE: where this run writes it
    std::string images_dir;             // RAYLAB_GRADE_IMAGES: where images are saved
    std::map<int, std::string> faults;  // module index -> segv | hang | throw | nan
};

Settings& settings() {
    static Settings s;
    return s;
}

std::string env(const char* name) {
    const char* v = std::getenv(name);
    return v ? std::string(v) : std::string();
}

// ---- Fault injection (RAYLAB_GRADE_FAULT="04_sphere=segv,05_triangle=hang")
// ------------- Lets the grader's own tests prove that a crash, a hang, an exception or a
// NaN in one module fails that module only. Never set in normal grading.

void inject_fault(Module m) {
    const auto it = settings().faults.find(static_cast<int>(m));
    if (it == settings().faults.end()) return;
    if (it->second == "segv") std::raise(SIGSEGV);
    if (it->second == "throw")
        throw std::runtime_error("fault injected by RAYLAB_GRADE_FAULT");
    if (it->second == "hang") {
        for (;;)
            std::this_thread::sleep_for(std::chrono::seconds(1));
    }
}

bool nan_fault(Module m) {
    const auto it = settings().faults.find(static_cast<int>(m));
    return it != settings().faults.end() && it->second == "nan";
}

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

void poison(Vec2& v) {
    v = Vec2(kNaN);
}
void poison(Vec3& v) {
    v = Vec3(kNaN);
}
void poison(float& x) {
    x = kNaN;
}
void poison(bool& b) {
    b = !b;
}
void poison(CameraFrame& f) {
    f.x = f.y = f.n = Vec3(kNaN);
}
void poison(Ray& r) {
    r.w = Vec3(kNaN);
}
void poison(LightSample& s) {
    s.Li = Vec3(kNaN);
}
void poison(std::optional<Hit>& hit) {
    if (!hit) hit = Hit{};
    hit->t = kNaN;
    hit->position = hit->n = Vec3(kNaN);
}

// ---- Stub detection ------------------------------------------------------------------

[[noreturn]] void fail_stub(Module m, const char* function) {
    const std::string id = module_info(m).id;
    const std::string message =
        "not started: " + std::string(function) + " of " + id +
        " still calls RAYLAB_STUB (delete that line in exercises/" + id +
        ".cpp when you implement it)";
    FAIL(message);
    std::abort();  // not reached: FAIL throws
}

template <class F>
auto call(Module m, const char* function, F&& f) -> decltype(f()) {
    inject_fault(m);
    const std::uint32_t bit = std::uint32_t{1} << static_cast<int>(m);
    stub::called.fetch_and(~bit);
    if constexpr (std::is_void_v<decltype(f())>) {
        f();
        if (stub::called.load() & bit) fail_stub(m, function);
    } else {
        auto result = f();
        if (stub::called.load() & bit) fail_stub(m, function);
        if (nan_fault(m)) poison(result);
        return result;
    }
}

const ModuleTable& tested() {
    static const ModuleTable table =
        ModuleTable::make(ModuleSelection::all(impl_under_test()));
    return table;
}

// ---- Number formatting
// -----------------------------------------------------------------

// The shortest of 6..9 significant digits that reads back as the same float
std::string format_float(float x) {
    char buf[32];
    for (int digits = 6; digits <= 9; ++digits) {
        std::snprintf(buf, sizeof buf, "%.*g", digits, static_cast<double>(x));
        if (std::strtof(buf, nullptr) == x || x != x) break;
    }
    return buf;
}

std::string format_floats(const Floats& f) {
    std::string s;
    for (size_t k = 0; k < f.size(); ++k) {
        if (k) s += ' ';
        s += format_float(f[k]);
    }
    return s;
}

Floats parse_floats(const std::string& s) {
    Floats f;
    std::istringstream in(s);
    std::string word;
    while (in >> word)
        f.push_back(std::strtof(word.c_str(), nullptr));
    return f;
}

// ---- Golden data
// -------------------------------------------------------------------------

struct GoldenEntry {
    std::string input, output;
};

std::mutex golden_mutex;
std::map<std::string, std::map<std::string, GoldenEntry>> golden_loaded;  // suite -> key
std::map<std::string, std::map<std::string, GoldenEntry>> golden_recorded;

std::string golden_path(const std::string& suite) {
    return settings().golden_dir + "/" + suite + ".txt";
}

const std::map<std::string, GoldenEntry>& golden_suite(const std::string& suite) {
    auto it = golden_loaded.find(suite);
    if (it != golden_loaded.end()) return it->second;
    std::map<std::string, GoldenEntry>& entries = golden_loaded[suite];
    std::ifstream in(golden_path(suite));
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        const size_t a = line.find('\t'), b = line.find('\t', a + 1);
        if (a == std::string::npos || b == std::string::npos) continue;
        entries[line.substr(0, a)] = {line.substr(a + 1, b - a - 1), line.substr(b + 1)};
    }
    return entries;
}

}  // namespace

// ---- Settings
// --------------------------------------------------------------------------

Impl impl_under_test() {
    return settings().impl;
}

const char* impl_name() {
    return settings().impl == Impl::student ? "student" : "reference";
}

bool using_golden() {
    return settings().golden;
}

std::string golden_dir() {
    return settings().golden_dir;
}

bool setup() {
    Settings& s = settings();
    const std::string impl = env("RAYLAB_GRADE_IMPL");
    if (impl.empty() || impl == "student") {
        s.impl = Impl::student;
    } else if (impl == "reference") {
        if (!reference_available()) {
            std::printf(
                "[raylab] RAYLAB_GRADE_IMPL=reference, but this build has no reference "
                "solutions (solutions/ is absent)\n");
            return false;
        }
        s.impl = Impl::reference;
    } else {
        std::printf(
            "[raylab] RAYLAB_GRADE_IMPL must be 'student' or 'reference', not '%s'\n",
            impl.c_str());
        return false;
    }
    const std::string oracle = env("RAYLAB_GRADE_ORACLE");
    s.golden = oracle == "golden" || !reference_available();
    s.golden_dir = env("RAYLAB_GOLDEN_DIR");
    if (s.golden_dir.empty()) s.golden_dir = RAYLAB_GOLDEN_DIR_DEFAULT;
    s.record_dir = env("RAYLAB_GOLDEN_WRITE");
    s.images_dir = env("RAYLAB_GRADE_IMAGES");
    if (!s.record_dir.empty() && s.golden) {
        std::printf(
            "[raylab] RAYLAB_GOLDEN_WRITE needs the reference solutions in the build\n");
        return false;
    }
    // RAYLAB_GRADE_FAULT: "04_sphere=segv,05_triangle=hang"
    std::istringstream faults(env("RAYLAB_GRADE_FAULT"));
    std::string item;
    while (std::getline(faults, item, ',')) {
        const size_t eq = item.find('=');
        bool known = false;
        for (const ModuleInfo& info : module_infos()) {
            if (eq != std::string::npos && item.substr(0, eq) == info.id) {
                s.faults[static_cast<int>(info.module)] = item.substr(eq + 1);
                known = true;
            }
        }
        if (!known) {
            std::printf("[raylab] RAYLAB_GRADE_FAULT: cannot read '%s'\n", item.c_str());
            return false;
        }
    }
    std::printf("[raylab] grading the %s code against %s\n",
                s.impl == Impl::student ? "student's" : "reference",
                s.golden ? ("the golden data in " + s.golden_dir).c_str()
                         : "the reference solutions");
    std::fflush(stdout);
    return true;
}

bool finish() {
    const Settings& s = settings();
    if (s.record_dir.empty()) return true;
    size_t cases = 0;
    for (const auto& [suite, entries] : golden_recorded) {
        const std::string path = s.record_dir + "/" + suite + ".txt";
        std::ofstream out(path);
        out << "# Golden data of the " << suite
            << " graders: the reference's answer to each\n"
            << "# case, for builds without solutions/. Written by raylab-grading-tests "
               "with\n"
            << "# RAYLAB_GOLDEN_WRITE (scripts/make-student-release.sh); do not edit.\n"
            << "# case<TAB>input<TAB>reference's answer\n";
        for (const auto& [key, entry] : entries)
            out << key << '\t' << entry.input << '\t' << entry.output << '\n';
        cases += entries.size();
        if (!out) {
            std::printf("[raylab] cannot write %s\n", path.c_str());
            return false;
        }
    }
    std::printf("[raylab] wrote golden data for %zu cases of %zu modules to %s\n", cases,
                golden_recorded.size(), s.record_dir.c_str());
    return true;
}

// ---- Calls of the implementation under test
// --------------------------------------------

namespace under_test {
Vec2 image_plane_point(int i, int j, int W, int H) {
    return call(Module::pixel_loop, "image_plane_point",
                [&] { return tested().image_plane_point(i, j, W, H); });
}
void render_tile(const Tile& tile, const PixelRadiance& radiance,
                 const ImageView& image) {
    call(Module::pixel_loop, "render_tile",
         [&] { tested().render_tile(tile, radiance, image); });
}
CameraFrame camera_frame(const Vec3& eye, const Vec3& lookat, const Vec3& up) {
    return call(Module::camera, "camera_frame",
                [&] { return tested().camera_frame(eye, lookat, up); });
}
float camera_constant(float fov) {
    return call(Module::camera, "camera_constant",
                [&] { return tested().camera_constant(fov); });
}
Ray camera_ray(const PinholeCamera& camera, const Vec2& uv) {
    return call(Module::camera, "camera_ray",
                [&] { return tested().camera_ray(camera, uv); });
}
std::optional<Hit> intersect_plane(const Ray& r, const Plane& plane) {
    return call(Module::plane, "intersect_plane",
                [&] { return tested().intersect_plane(r, plane); });
}
std::optional<Hit> intersect_sphere(const Ray& r, const Sphere& sphere) {
    return call(Module::sphere, "intersect_sphere",
                [&] { return tested().intersect_sphere(r, sphere); });
}
std::optional<Hit> intersect_triangle(const Ray& r, const Vec3& v0, const Vec3& v1,
                                      const Vec3& v2) {
    return call(Module::triangle, "intersect_triangle",
                [&] { return tested().intersect_triangle(r, v0, v1, v2); });
}
LightSample sample_point_light(const PointLight& light, const Vec3& x) {
    return call(Module::point_light, "sample_point_light",
                [&] { return tested().sample_point_light(light, x); });
}
Vec3 intensity_from_power(const Vec3& P) {
    return call(Module::point_light, "intensity_from_power",
                [&] { return tested().intensity_from_power(P); });
}
Vec3 lambert(const Vec3& rho, const Vec3& Le, const Vec3& n,
             const std::vector<LightSample>& lights) {
    return call(Module::lambert, "lambert",
                [&] { return tested().lambert(rho, Le, n, lights); });
}
bool in_shadow(const Occluder& scene, const Vec3& x, const Vec3& n,
               const LightSample& sample) {
    return call(Module::shadows, "in_shadow",
                [&] { return tested().in_shadow(scene, x, n, sample); });
}
}  // namespace under_test

const ModuleTable& reference_modules() {
    static const ModuleTable table =
        reference_available() ? ModuleTable::make(ModuleSelection::all(Impl::reference))
                              : ModuleTable{};
    return table;
}

// ---- Encoding ------------------------------------------------------------------------

void put(Floats& f, float x) {
    f.push_back(x);
}
void put(Floats& f, int x) {
    f.push_back(static_cast<float>(x));
}
void put(Floats& f, bool x) {
    f.push_back(x ? 1.0f : 0.0f);
}
void put(Floats& f, const Vec2& v) {
    f.insert(f.end(), {v.x, v.y});
}
void put(Floats& f, const Vec3& v) {
    f.insert(f.end(), {v.x, v.y, v.z});
}
void put(Floats& f, const Ray& r) {
    put(f, r.o);
    put(f, r.w);
    f.insert(f.end(), {r.tmin, r.tmax});
}
void put(Floats& f, const std::optional<Hit>& hit) {
    put(f, hit.has_value());
    if (!hit) return;
    put(f, hit->t);
    put(f, hit->position);
    put(f, hit->n);
    put(f, hit->uv);
}
void put(Floats& f, const CameraFrame& frame) {
    put(f, frame.x);
    put(f, frame.y);
    put(f, frame.n);
}
void put(Floats& f, const LightSample& s) {
    put(f, s.wi);
    put(f, s.r);
    put(f, s.Li);
}

float FloatReader::next() {
    if (at_ >= f_.size()) {
        FAIL("golden data: a case has fewer numbers than its type needs");
    }
    return f_[at_++];
}
void FloatReader::get(Vec2& v) {
    v.x = next();
    v.y = next();
}
void FloatReader::get(Vec3& v) {
    v.x = next();
    v.y = next();
    v.z = next();
}
void FloatReader::get(Ray& r) {
    get(r.o);
    get(r.w);
    r.tmin = next();
    r.tmax = next();
}
void FloatReader::get(std::optional<Hit>& hit) {
    bool present = false;
    get(present);
    if (!present) {
        hit.reset();
        return;
    }
    Hit h;
    h.t = next();
    get(h.position);
    get(h.n);
    get(h.uv);
    hit = h;
}
void FloatReader::get(CameraFrame& frame) {
    get(frame.x);
    get(frame.y);
    get(frame.n);
}
void FloatReader::get(LightSample& s) {
    get(s.wi);
    s.r = next();
    get(s.Li);
}

Floats expected_floats(const std::string& key, const Floats& input,
                       const std::function<Floats()>& compute) {
    const std::string suite = key.substr(0, key.find('/'));
    const std::string in = format_floats(input);
    const Settings& s = settings();
    if (!s.golden) {
        Floats out = compute();
        if (!s.record_dir.empty()) {
            const std::lock_guard<std::mutex> lock(golden_mutex);
            golden_recorded[suite][key] = {in, format_floats(out)};
        }
        return out;
    }
    std::string stored_in, stored_out;
    bool found = false;
    {
        const std::lock_guard<std::mutex> lock(golden_mutex);
        const auto& entries = golden_suite(suite);
        const auto it = entries.find(key);
        if (it != entries.end()) {
            found = true;
            stored_in = it->second.input;
            stored_out = it->second.output;
        }
    }
    if (!found) {
        FAIL(
            "no golden data for case '"
            << key << "' in " << golden_path(suite)
            << ": the golden data does not belong to these tests (regenerate it with the "
               "reference: scripts/make-student-release.sh)");
    }
    if (stored_in != in) {
        FAIL("the golden data of case '" << key << "' was made for the input "
                                         << stored_in << ", but this test generated "
                                         << in);
    }
    return parse_floats(stored_out);
}

Image expected_image(const std::string& suite, const std::string& stem,
                     const std::function<Image()>& compute) {
    const Settings& s = settings();
    const std::string name = suite + "-" + stem + ".pfm";
    if (!s.golden) {
        Image image = compute();
        if (!s.record_dir.empty()) write_pfm(s.record_dir + "/" + name, image);
        return image;
    }
    try {
        return read_pfm(s.golden_dir + "/" + name);
    } catch (const Error& e) {
        FAIL("golden image missing: " << e.what());
    }
    return Image();
}

std::string save_image(const std::string& name, const Image& image) {
    const Settings& s = settings();
    if (s.images_dir.empty()) return "";
    const std::string path = s.images_dir + "/" + name + ".pfm";
    try {
        write_pfm(path, image);
    } catch (const Error&) {
        return "";
    }
    return path;
}

// ---- Printing
// --------------------------------------------------------------------------

std::string show(double x) {
    return format_float(static_cast<float>(x));
}
std::string show(const Vec2& v) {
    return "(" + format_float(v.x) + ", " + format_float(v.y) + ")";
}
std::string show(const Vec3& v) {
    return "(" + format_float(v.x) + ", " + format_float(v.y) + ", " + format_float(v.z) +
           ")";
}
std::string show(const Ray& r) {
    return "ray o = " + show(r.o) + ", w = " + show(r.w) + ", tmin = " + show(r.tmin) +
           ", tmax = " + show(r.tmax);
}
std::string show(const Plane& p) {
    return "plane n = " + show(p.n) + ", d = " + show(p.d);
}
std::string show(const Sphere& s) {
    return "sphere c = " + show(s.c) + ", r = " + show(s.r);
}
std::string show_triangle(const Vec3& v0, const Vec3& v1, const Vec3& v2) {
    return "triangle v0 = " + show(v0) + ", v1 = " + show(v1) + ", v2 = " + show(v2);
}
std::string show(const std::optional<Hit>& hit) {
    if (!hit) return "a miss (std::nullopt)";
    return "a hit at t = " + show(hit->t) + ", position " + show(hit->position) +
           ", n = " + show(hit->n) + ", uv = " + show(hit->uv);
}
std::string show(const CameraFrame& f) {
    return "x = " + show(f.x) + ", y = " + show(f.y) + ", n = " + show(f.n);
}
std::string show(const PinholeCamera& c) {
    return "camera eye = " + show(c.eye) + ", " + show(c.frame) + ", d = " + show(c.d);
}
std::string show(const PointLight& l) {
    return "light p = " + show(l.p) + ", I = " + show(l.I);
}
std::string show(const LightSample& s) {
    return "wi = " + show(s.wi) + ", r = " + show(s.r) + ", Li = " + show(s.Li);
}
std::string show(const Tile& t) {
    return "tile columns [" + std::to_string(t.x0) + ", " + std::to_string(t.x1) +
           "), rows [" + std::to_string(t.y0) + ", " + std::to_string(t.y1) + ")";
}

// ---- Comparisons
// -----------------------------------------------------------------------

bool close(double got, double want, double tolerance) {
    return std::abs(got - want) <= tolerance * std::max(1.0, std::abs(want));
}

bool close_abs(const Vec3& got, const Vec3& want, double tolerance) {
    for (int k = 0; k < 3; ++k) {
        if (!(std::abs(double(got[k]) - double(want[k])) <= tolerance)) return false;
    }
    return true;
}

double scale_of(std::initializer_list<Vec3> points, double t) {
    double s = std::max(1.0, std::abs(t));
    for (const Vec3& p : points)
        s = std::max(s, double(glm::length(p)));
    return s;
}

std::string diff_hit(const std::optional<Hit>& got, const std::optional<Hit>& want,
                     double scale, bool check_uv) {
    if (!want && !got) return "";
    if (!want || !got) return "expected " + show(want) + ", got " + show(got);
    std::string why;
    const auto add = [&](const std::string& what) {
        why += (why.empty() ? "" : "; ") + what;
    };
    if (!(std::abs(double(got->t) - want->t) <= tol::kDistance * scale))
        add("t: expected " + show(want->t) + ", got " + show(got->t));
    if (!close_abs(got->position, want->position, tol::kDistance * scale))
        add("position: expected " + show(want->position) + ", got " +
            show(got->position));
    if (!close_abs(got->n, want->n, tol::kNormal))
        add("n: expected " + show(want->n) + ", got " + show(got->n));
    if (check_uv) {
        const Vec3 g(got->uv, 0.0f), w(want->uv, 0.0f);
        if (!close_abs(g, w, tol::kBarycentric))
            add("uv (beta, gamma): expected " + show(want->uv) + ", got " +
                show(got->uv));
    }
    return why;
}

std::string diff_vec(const char* name, const Vec3& got, const Vec3& want,
                     double tolerance) {
    if (close_abs(got, want, tolerance)) return "";
    return std::string(name) + ": expected " + show(want) + ", got " + show(got);
}

std::string diff_radiance(const char* name, const Vec3& got, const Vec3& want) {
    for (int k = 0; k < 3; ++k) {
        const double g = got[k], w = want[k];
        if (!(std::abs(g - w) <= tol::kRadiance * std::abs(w) + 1e-7))
            return std::string(name) + ": expected " + show(want) + ", got " + show(got);
    }
    return "";
}

// ---- Rng -----------------------------------------------------------------------------

std::uint64_t Rng::next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

float Rng::uniform(float lo, float hi) {
    const float u = static_cast<float>(next() >> 40) * 0x1p-24f;  // [0, 1), 24 bits
    return lo + (hi - lo) * u;
}

int Rng::integer(int lo, int hi) {
    const std::uint64_t span = static_cast<std::uint64_t>(hi - lo) + 1;
    return lo + static_cast<int>(next() % span);
}

Vec3 Rng::in_box(float lo, float hi) {
    const float x = uniform(lo, hi), y = uniform(lo, hi), z = uniform(lo, hi);
    return Vec3(x, y, z);
}

Vec3 Rng::direction() {
    for (;;) {
        const Vec3 v = in_box(-1.0f, 1.0f);
        const float l2 = glm::dot(v, v);
        if (l2 > 1e-4f && l2 <= 1.0f) return v / std::sqrt(l2);
    }
}

Vec3 Rng::direction_near(const Vec3& axis, float min_cos, float max_cos) {
    for (;;) {
        const Vec3 v = direction();
        const float c = glm::dot(v, axis);
        if (c >= min_cos && c <= max_cos) return v;
    }
}

}  // namespace raylab::grading
