// raylab/contract.h: the exercise contract.
//
// Every type a student function sees, and the signature of every student function, is
// declared here and nowhere else. exercises/NN_name.cpp defines the functions in
// namespace raylab::student, solutions/NN_name.cpp defines the same functions in
// raylab::reference; the framework picks one or the other per module at run time
// (raylab/modules.h).
//
// Conventions (docs/conventions.md): right-handed world, y up; float32 radiance in linear
// RGB; rays r(t) = o + t w with |w| = 1 and tmin <= t <= tmax.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "raylab/math.h"

namespace raylab {

// ---------------------------------------------------------------------------------------
// Rays and hits (handout 03 §1)

/// A ray r(t) = o + t w, valid for tmin <= t <= tmax.
struct Ray {
    Vec3 o;  ///< origin o
    Vec3 w;  ///< unit direction w (the framework normalises it where rays are made)
    float tmin = 0.0f;       ///< smallest accepted distance along w
    float tmax = kInfinity;  ///< largest accepted distance along w
};

/// What a primitive reports about the point where a ray meets it.
struct Hit {
    float t = kInfinity;  ///< distance along the ray: position = o + t w
    Vec3 position{0.0f};  ///< world-space hit point
    Vec3 n{0.0f};   ///< unit geometric normal, oriented by the primitive (see handouts)
    Vec3 ns{0.0f};  ///< unit shading normal (framework's), on n's side facing the ray
    Vec2 uv{0.0f};  ///< surface coordinates; triangles: barycentric weights of v1, v2
    int material = -1;  ///< material index; filled by the framework
};

// ---------------------------------------------------------------------------------------
// Primitives (handouts 03, 04, 05)

/// The plane of points p with p . n + d = 0 (d is the plane offset, not the camera's d).
struct Plane {
    Vec3 n;   ///< unit normal n
    float d;  ///< plane offset d: the plane holds p = -d n
};

/// The sphere of points p with |p - c| = r.
struct Sphere {
    Vec3 c;   ///< centre c
    float r;  ///< radius r > 0
};

// ---------------------------------------------------------------------------------------
// Camera (handout 02)

/// The orthonormal camera basis of the DTU pinhole camera.
struct CameraFrame {
    Vec3 x;  ///< image-plane right
    Vec3 y;  ///< image-plane up
    Vec3 n;  ///< viewing direction (image-plane normal)
};

/// A pinhole camera: eye point, basis and camera constant d (distance to the image plane,
/// whose visible part spans v in [-1/2, 1/2] and u in [-aspect/2, aspect/2]).
struct PinholeCamera {
    Vec3 eye;           ///< eye point e: the origin of every camera ray
    CameraFrame frame;  ///< basis x, y, n
    float d;            ///< camera constant d (not the plane offset)
};

// ---------------------------------------------------------------------------------------
// Pixel loop (handout 01)

/// A rectangle of pixels [x0, x1) x [y0, y1); row 0 is the top of the image.
struct Tile {
    int x0, y0;  ///< first column and row (inclusive)
    int x1, y1;  ///< end column and row (exclusive)
};

/// Where the pixel loop writes: width x height linear RGB values, row-major, row 0 on
/// top.
struct ImageView {
    Vec3* pixels;  ///< width * height values; pixel (i, j) is pixels[j * width + i]
    int width;     ///< W, in pixels
    int height;    ///< H, in pixels

    /// Stores the radiance L of pixel (i, j): column i, row j (0 = top row).
    void set(int i, int j, const Vec3& L) const { pixels[j * width + i] = L; }
};

/// The framework's per-pixel work: radiance arriving through image-plane point (u, v).
using PixelRadiance = std::function<Vec3(const Vec2& uv)>;

// ---------------------------------------------------------------------------------------
// Lights and shading (handouts 06, 07, 08)

/// An isotropic point light.
struct PointLight {
    Vec3 p;  ///< position p
    Vec3 I;  ///< radiant intensity I per RGB channel [W/sr]
};

/// The light one point light sends to a surface point x.
struct LightSample {
    Vec3 wi;  ///< unit direction from x towards the light
    float r;  ///< distance r from x to the light
    Vec3 Li;  ///< incident light at x, I / r^2 [W/m^2 per unit projected area]
};

/// The scene's any-hit query, given to the shadow module.
class Occluder {
  public:
    virtual ~Occluder() = default;
    /// True when something lies on the ray for some t in [tmin, tmax].
    virtual bool occluded(const Ray& r) const = 0;
};

// ---------------------------------------------------------------------------------------
// Sampling (handouts 09, 10)

/// The framework's seeded random generator (splitmix64). The renderer seeds one per
/// pixel, sample and light from the render's seed, so an image is the same on every run
/// and for any number of threads. Pass it by value and draw with uniform().
struct PixelRng {
    std::uint64_t state = 0;

    /// The generator for the numbers a, b, c (say a pixel's column, row and a stream).
    static PixelRng make(std::uint64_t seed, std::uint64_t a, std::uint64_t b,
                         std::uint64_t c) {
        PixelRng rng{seed ^ 0x9E3779B97F4A7C15ull};
        for (std::uint64_t x : {a, b, c})
            rng.state = rng.next() ^ x;
        (void)rng.next();
        return rng;
    }
    /// The next 64 random bits.
    std::uint64_t next() {
        std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    /// Uniform in [0, 1): 24 random bits, so the result is never 1.
    float uniform() { return static_cast<float>(next() >> 40) * 0x1p-24f; }
};

/// One sample of a pixel (handout 09 §1): where it lies inside the pixel and how much it
/// counts.
struct PixelSample {
    Vec2 offset;   ///< (0, 0) the pixel's top-left corner, (1, 1) its bottom-right
    float weight;  ///< w_k in L = sum_k w_k L_k; a pixel's weights sum to 1
};

/// A rectangular area light (handout 10 §1): the points p + s e1 + t e2, s, t in [0, 1],
/// emitting radiance Le on the side of n = (e1 x e2) / |e1 x e2| only.
struct AreaLight {
    Vec3 p;   ///< corner p
    Vec3 e1;  ///< first edge e1
    Vec3 e2;  ///< second edge e2 (perpendicular to e1)
    Vec3 Le;  ///< emitted radiance Le per RGB channel [W/(m^2 sr)]
};

// ---------------------------------------------------------------------------------------
// Stubs (docs/style.md rule 10): a stub calls RAYLAB_STUB("NN_name") so that the grader
// and the viewer can say "not started" instead of reporting every failing case.

namespace stub {
/// Bit k set: module k+1 ran its stub since the last reset.
inline std::atomic<std::uint32_t> called{0};
/// Marks module "NN_name" as a stub; the two leading digits give the module number.
inline void mark(const char* id) {
    const int k = (id[0] - '0') * 10 + (id[1] - '0') - 1;
    if (k >= 0 && k < 32)
        called.fetch_or(std::uint32_t{1} << k, std::memory_order_relaxed);
}
}  // namespace stub

}  // namespace raylab

/// Marks a function as an unfinished stub; delete this line when you implement it.
#define RAYLAB_STUB(module_id) ::raylab::stub::mark(module_id)

// The student functions, declared once for each implementation.
namespace raylab::student {
#include "raylab/contract_functions.inc"
}  // namespace raylab::student
namespace raylab::reference {
#include "raylab/contract_functions.inc"
}  // namespace raylab::reference
