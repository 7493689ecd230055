// Shared helpers of the graders (tests/grading/test_NN_name.cpp).
//
// - under_test::*  calls the implementation being graded (the student's by default, the
//   reference with RAYLAB_GRADE_IMPL=reference) and turns a stub into one clear failure,
//   "not started", instead of a wrong answer.
// - expected<T>()  gives the reference's answer for a case: from the reference when this
//   build has solutions/, else from the golden data in tests/data/golden/ that the
//   reference wrote at release time.
// - show() prints inputs and results so that every failure can be reproduced; the diff_*
//   helpers compare with the named tolerances of namespace tol and say what differs.
// - Rng is a small deterministic generator; every random case prints its seed.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "raylab/contract.h"
#include "raylab/image.h"
#include "raylab/modules.h"

namespace raylab::grading {

// ---------------------------------------------------------------------------------------
// Tolerances, one per quantity (docs/style.md rule 11). They are loose enough for float,
// double, Cramer's rule, Moeller-Trumbore, the geometric sphere test and any reasonable
// epsilon, and tight enough that every real mistake is far outside them.
namespace tol {
/// Image-plane coordinates u, v (relative above 1, absolute below; |u| <= aspect / 2).
inline constexpr double kImagePlane = 1e-6;
/// Pixel values of the pixel loop's test pattern image (absolute; values in [0, 1]).
inline constexpr double kPatternImage = 1e-4;
/// Components of unit vectors computed from exact input: camera basis, ray and light
/// directions (absolute).
inline constexpr double kDirection = 1e-5;
/// Camera constant d (relative).
inline constexpr double kCameraConstant = 1e-5;
/// Angles between rays, in degrees (absolute).
inline constexpr double kAngleDegrees = 1e-3;
/// The (u, v) where a returned eye ray crosses the image plane (absolute): the
/// direction's rounding error magnified by up to 1 / d.
inline constexpr double kImagePlaneFromRay = 1e-4;
/// Distances t and hit positions, relative to the size of the problem: the largest of
/// 1, |o|, t and the primitive's coordinates.
inline constexpr double kDistance = 1e-4;
/// Components of a hit's unit normal (absolute).
inline constexpr double kNormal = 1e-4;
/// Barycentric weights (beta, gamma) of a triangle hit (absolute).
inline constexpr double kBarycentric = 1e-4;
/// Radiance, irradiance and intensity per channel (relative, with 1e-7 absolute floor).
inline constexpr double kRadiance = 1e-5;
}  // namespace tol

// ---------------------------------------------------------------------------------------
// The implementation under test

/// Student or reference, from RAYLAB_GRADE_IMPL ("student" when unset).
Impl impl_under_test();
/// "student" or "reference".
const char* impl_name();
/// True when expected values come from tests/data/golden/ rather than the reference.
bool using_golden();
/// The golden data folder (RAYLAB_GOLDEN_DIR, else tests/data/golden/ of the sources).
std::string golden_dir();
/// Where this run records the reference's answers as golden data (RAYLAB_GOLDEN_WRITE),
/// or "".
std::string golden_record_dir();
/// Where save_image() writes (RAYLAB_GRADE_IMAGES), or "".
std::string images_dir();

/// Reads the environment and prints one line saying what is graded against what.
/// Returns false (after printing why) when the request cannot be met.
bool setup();
/// Writes the golden data recorded in this run (RAYLAB_GOLDEN_WRITE=DIR), if any.
bool finish();
/// The part of finish() that writes golden data (golden.cpp).
bool write_golden();

/// Calls of the implementation under test. A stub fails the current test case with
/// "not started: ..."; fault injection (RAYLAB_GRADE_FAULT, for the grader's own tests of
/// crash isolation) happens here too.
namespace under_test {
// One per RAYLAB_FUNCTION of the registry, with the contract's signature: a function
// pointer, so under_test::intersect_sphere(r, s) and render(under_test::render_tile) read
// as before
#define RAYLAB_FUNCTION(m, f) extern const decltype(&student::f) f;
#include "raylab/modules.def"
}  // namespace under_test

/// The reference's function table; only valid when the build has solutions/ (expected()
/// never calls it otherwise).
const ModuleTable& reference_modules();

// ---------------------------------------------------------------------------------------
// Expected values from the reference or the golden data

/// Numbers that identify a case's input or encode a result; written with 9 significant
/// digits, which reproduces every float exactly.
using Floats = std::vector<float>;

void put(Floats& f, float x);
void put(Floats& f, int x);
void put(Floats& f, bool x);
void put(Floats& f, const Vec2& v);
void put(Floats& f, const Vec3& v);
void put(Floats& f, const Ray& r);
void put(Floats& f, const std::optional<Hit>& hit);
void put(Floats& f, const CameraFrame& frame);
void put(Floats& f, const LightSample& s);

/// Reads back what put() wrote, in the same order.
class FloatReader {
  public:
    explicit FloatReader(const Floats& f) : f_(f) {}
    float next();
    void get(float& x) { x = next(); }
    void get(bool& x) { x = next() != 0.0f; }
    void get(Vec2& v);
    void get(Vec3& v);
    void get(Ray& r);
    void get(std::optional<Hit>& hit);
    void get(CameraFrame& frame);
    void get(LightSample& s);

  private:
    const Floats& f_;
    size_t at_ = 0;
};

/// Encodes any mix of inputs as the key's check data.
template <class... Args>
Floats inputs(const Args&... args) {
    Floats f;
    (put(f, args), ...);
    return f;
}

/// The name of the test case under way ("" outside one).
std::string current_case();

/// The raw golden mechanism: the reference's encoded answer for the case named key
/// ("NN_name/what/seed"). With the reference in the build, runs compute() and, when
/// recording, stores the answer; otherwise looks key up in the golden data and checks
/// that it was made for the same input. Fails the test case if the data is missing, and
/// in a "[private]" case: a release ships the golden data, so it must not hold the
/// inputs of the hidden cases.
Floats expected_floats(const std::string& key, const Floats& input,
                       const std::function<Floats()>& compute);

/// The reference's answer for case key with the given input. compute calls
/// grading::reference_modules() and is not called in a build without solutions/.
template <class T>
T expected(const std::string& key, const Floats& input,
           const std::function<T()>& compute) {
    const Floats f = expected_floats(key, input, [&] {
        Floats out;
        put(out, compute());
        return out;
    });
    T value{};
    FloatReader reader(f);
    reader.get(value);
    return value;
}

/// The reference's image for the golden file NN_name-stem.pfm.
Image expected_image(const std::string& suite, const std::string& stem,
                     const std::function<Image()>& compute);

/// Writes image to RAYLAB_GRADE_IMAGES/name.png and name.pfm when that folder is set, so
/// that a student can look at what the test saw. Returns the paths for a message, or ""
/// when not written.
std::string save_image(const std::string& name, const Image& image);

// ---------------------------------------------------------------------------------------
// Printing, for INFO and failure messages

/// The shortest decimal form (6 to 9 digits) that reads back as the same float.
std::string format_float(float x);

std::string show(double x);
std::string show(const Vec2& v);
std::string show(const Vec3& v);
std::string show(const Ray& r);
std::string show(const Plane& p);
std::string show(const Sphere& s);
std::string show_triangle(const Vec3& v0, const Vec3& v1, const Vec3& v2);
std::string show(const std::optional<Hit>& hit);
std::string show(const CameraFrame& f);
std::string show(const PinholeCamera& c);
std::string show(const PointLight& l);
std::string show(const LightSample& s);
std::string show(const Tile& t);

// ---------------------------------------------------------------------------------------
// Comparisons: "" when equal within tolerance, else what differs

/// |got - want| <= tolerance * max(1, |want|) (relative above 1, absolute below).
bool close(double got, double want, double tolerance);
/// Component-wise close() with absolute tolerance.
bool close_abs(const Vec3& got, const Vec3& want, double tolerance);

/// Compares hits: presence, t and position (kDistance, relative to scale), n (kNormal)
/// and, when check_uv, uv (kBarycentric).
std::string diff_hit(const std::optional<Hit>& got, const std::optional<Hit>& want,
                     double scale, bool check_uv = false);
/// "name: expected X, got Y" when the vectors differ by more than tolerance.
std::string diff_vec(const char* name, const Vec3& got, const Vec3& want,
                     double tolerance);
/// The same for radiance: relative per channel (tol::kRadiance).
std::string diff_radiance(const char* name, const Vec3& got, const Vec3& want);
/// The size of a problem for relative tolerances: the largest of 1 and |each point|.
double scale_of(std::initializer_list<Vec3> points, double t = 0.0);

/// Reports diff as a failed check when it is not empty; true when it was empty.
#define RAYLAB_CHECK_SAME(diff)           \
    [&](const std::string& raylab_why_) { \
        if (!raylab_why_.empty()) {       \
            FAIL_CHECK(raylab_why_);      \
            return false;                 \
        }                                 \
        return true;                      \
    }(diff)

/// Like CHECK_MESSAGE, but the message is the failure itself and the result is returned,
/// so that a loop over random cases can stop at its first failure.
#define RAYLAB_CHECK(cond, ...)  \
    [&]() {                      \
        if (cond) return true;   \
        FAIL_CHECK(__VA_ARGS__); \
        return false;            \
    }()

/// Stops the test case with the message (its words say what was expected and what came)
/// when cond is false. Test files use this and RAYLAB_CHECK, never doctest's CHECK or
/// REQUIRE, whose failure shows the raw expression ("++count[k] == 1 is 2 == 1"): the
/// ctest grading/messages-in-words checks it.
#define RAYLAB_REQUIRE(cond, ...)       \
    do {                                \
        if (!(cond)) FAIL(__VA_ARGS__); \
    } while (false)

// ---------------------------------------------------------------------------------------
// Cases that code doing no work could pass

/// Some cases expect an answer that code doing no work gives too: the centre pixel maps
/// to (0, 0), the Cornell box camera's basis is the world's axes, d = 1, a miss, "in
/// shadow", weights that sum to 1, or an input whose answer the release's golden data
/// holds. Such a case earns its point only together with a companion: cases of the same
/// function on fresh random input (seeds no other case and no golden file uses), checked
/// against the formula, whose answers no constant and no table gives. `companion` says
/// what they check; `why_not` is their first failure ("" when they pass). A failed
/// companion fails the case with a message naming both, and the case's own checks still
/// run and report. Returns true when the companion passed.
bool needs_work(const std::string& companion, const std::string& why_not);

// ---------------------------------------------------------------------------------------
// Random cases

/// A small deterministic generator (splitmix64): the same seed gives the same case on
/// every machine, so a failure message's seed reproduces it.
class Rng {
  public:
    explicit Rng(std::uint64_t seed) : state_(seed * 0x2545F4914F6CDD1Dull + 1) {}
    std::uint64_t next();
    /// Uniform in [lo, hi).
    float uniform(float lo, float hi);
    /// Uniform integer in [lo, hi].
    int integer(int lo, int hi);
    /// Uniform in the box [lo, hi)^3.
    Vec3 in_box(float lo, float hi);
    /// A uniformly random unit vector.
    Vec3 direction();
    /// A random unit vector whose cosine with axis lies in [min_cos, max_cos].
    Vec3 direction_near(const Vec3& axis, float min_cos, float max_cos);

  private:
    std::uint64_t state_;
};

/// A ray that meets point p at distance t along the unit direction w, with one of five
/// intervals drawn from rng: the whole ray; ending 10% before p; starting 10% after p; a
/// window from t/2 to 3t/2; or the ray turned around, pointing away from p.
Ray random_ray_through(Rng& rng, const Vec3& p, const Vec3& w, float t);

/// A hit record with the fields a primitive fills.
Hit make_hit(float t, const Vec3& position, const Vec3& n, const Vec2& uv = Vec2(0.0f));

}  // namespace raylab::grading
