// The reference engine's four-lane triangle test and its vectors, for the packet query
// (four rays against one triangle at a time, engine_packet.cpp). Not a module. (The same
// test on one ray against a leaf's four triangles was measured for the single-ray query
// and not kept: gathering the leaf's vertices into lanes cost more than the branches it
// saved: docs/decisions/0009.)
//
// Each lane runs exactly triangle_t's IEEE operations (engine_kernels.h) on its own
// values, in vectors of four doubles (GCC and clang vector extensions: two SSE2 registers
// on the x86-64 baseline, one where the target has AVX2), so each lane decides what
// triangle_t decides and gives its t, uv and bound to the bit. -ffp-contract=off keeps
// every product unfused.
#pragma once

#include <cstdlib>
#include <cstring>
#include <limits>

#include "engine_kernels.h"

// Vectors of four doubles pass between these helpers, which are always inlined (so never
// called across the AVX2 and the baseline versions below, whose ABIs for them differ):
// g++ and clang warn about that ABI all the same
#pragma GCC diagnostic ignored "-Wpsabi"

// On x86-64 the query is compiled three times, for the baseline (SSE2), AVX2 and AVX2
// with AVX-512's registers, and the processor chooses at run time, as Embree does. The
// same IEEE operations every way (-ffp-contract=off: no FMA, though the AVX-512
// target has it), so the same bits; tests/stress runs each (the stress matrix's
// -march=native builds take the widest throughout, its -DRAYLAB_NO_SIMD build the
// baseline, and its other builds run again with RAYLAB_NO_AVX2 and RAYLAB_NO_AVX512)
#if defined(__x86_64__) && !defined(__AVX2__) && !defined(RAYLAB_NO_SIMD)
#define RAYLAB_ENGINE_AVX2 1
#else
#define RAYLAB_ENGINE_AVX2 0
#endif
#define RAYLAB_INLINE inline __attribute__((always_inline))
// x86-64-v4's AVX-512 subsets, on top of AVX2; for GCC, vectors of at most 256 bits in
// what it vectorises itself (it had made the packets' padding loop 512 bits wide)
#if defined(__clang__)
#define RAYLAB_ENGINE_AVX512_TARGET "avx2,avx512f,avx512vl,avx512bw,avx512dq,avx512cd"
#else
#define RAYLAB_ENGINE_AVX512_TARGET \
    "avx2,avx512f,avx512vl,avx512bw,avx512dq,avx512cd,prefer-vector-width=256"
#endif

// RAYLAB_ENGINE_VERSIONS compiles QUERY<Avx>(ARGS), an always-inlined function
// template, three times: for the baseline (Avx = false), for AVX2 (Avx = true), and for
// AVX2 on a processor with x86-64-v4's AVX-512 (the same code, Avx = true). It defines
// NAME_chosen(), which returns the version for this processor: the widest it has. The
// engine stores the chosen versions in its GeometryEngine when it is first asked for, so
// a query pays no choice per call. flatten asks the compiler to inline every call of a
// version, so that the query is compiled for the version's target; it does not always
// (objdump: GCC keeps the any-hit query's leaf visit a function of its own,
// compiled for the baseline, and clang keeps place_sorted_avx out of line, compiled
// for AVX2), which costs speed, never results. Avx lets a query use instructions that
// only the AVX2 versions may (the AVX node test of walk<Sorted, true>, engine_walk.h).
// The AVX-512 version uses no 512-bit vector of its own: what it gains is the compiler's
// 32 vector registers instead of 16. The query inlined whole needs more than 16 (the
// walk's ray, the watertight test's shear and its nine coordinates): GCC's AVX2
// closest-hit query moves vector registers to and from the stack in 363 instructions, its
// AVX-512 one in 234, which makes camera and random rays faster (docs/decisions/0007). A
// build for a target with AVX2 (-march=native here) has one version, with Avx = true, and
// the registers its target has. The environment variable RAYLAB_NO_AVX2 (any value) makes
// the choice the baseline and RAYLAB_NO_AVX512 at most AVX2, so that tests can run every
// version on one machine (scripts/stress-matrix.sh and the engine-*-versions ctest runs
// of engine/tests and tests/framework do).
#if RAYLAB_ENGINE_AVX2
#define RAYLAB_ENGINE_VERSIONS(QUERY, RESULT, NAME, PARAMS, ARGS)                \
    __attribute__((flatten)) RESULT NAME##_baseline PARAMS {                     \
        return QUERY<false> ARGS;                                                \
    }                                                                            \
    __attribute__((target("avx2"), flatten)) RESULT NAME##_avx2 PARAMS {         \
        return QUERY<true> ARGS;                                                 \
    }                                                                            \
    __attribute__((target(RAYLAB_ENGINE_AVX512_TARGET), flatten))                \
    RESULT NAME##_avx512 PARAMS {                                                \
        return QUERY<true> ARGS;                                                 \
    }                                                                            \
    auto NAME##_chosen() {                                                       \
        /* by EngineLevel */                                                     \
        decltype(&NAME##_baseline)                                               \
            const versions[] = {&NAME##_baseline, &NAME##_avx2, &NAME##_avx512}; \
        return versions[static_cast<int>(                                        \
            ::raylab::reference::engine_kernels::engine_level())];               \
    }
#else
#define RAYLAB_ENGINE_VERSIONS(QUERY, RESULT, NAME, PARAMS, ARGS)           \
    __attribute__((flatten)) RESULT NAME PARAMS {                           \
        return QUERY<::raylab::reference::engine_kernels::kAvxTarget> ARGS; \
    }                                                                       \
    auto NAME##_chosen() {                                                  \
        return &NAME;                                                       \
    }
#endif

namespace raylab::reference::engine_kernels {

#if RAYLAB_ENGINE_AVX2
// The versions, in the order of RAYLAB_ENGINE_VERSIONS's table and of their names
enum class EngineLevel { baseline, avx2, avx512 };
constexpr const char* kEngineLevelNames[] = {"baseline", "avx2", "avx512"};
// The widest versions the processor runs, unless RAYLAB_NO_AVX2 or RAYLAB_NO_AVX512 asks
// for less (__builtin_cpu_supports also asks whether the system saves the AVX-512
// registers)
inline EngineLevel engine_level() {
    static const EngineLevel level = [] {
        if (!__builtin_cpu_supports("avx2") || std::getenv("RAYLAB_NO_AVX2"))
            return EngineLevel::baseline;
        const bool avx512 =
            __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
            __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
            __builtin_cpu_supports("avx512cd");
        return avx512 && !std::getenv("RAYLAB_NO_AVX512") ? EngineLevel::avx512
                                                          : EngineLevel::avx2;
    }();
    return level;
}
#endif
// The versions that run, as GeometryEngine::versions names them
inline const char* engine_versions() {
#if RAYLAB_ENGINE_AVX2
    return kEngineLevelNames[static_cast<int>(engine_level())];
#else
    return "native";
#endif
}
// The build's own target has AVX2 (one version of each query)
#if defined(__AVX2__) && RAYLAB_AVX_NODES
constexpr bool kAvxTarget = true;
#else
constexpr bool kAvxTarget = false;
#endif

}  // namespace raylab::reference::engine_kernels

namespace raylab::reference::engine_kernels {

// Four lanes of doubles, their comparison masks, four floats and their masks
using D4 = double __attribute__((vector_size(32)));
using M4 = long long __attribute__((vector_size(32)));
using F4 = float __attribute__((vector_size(16)));
using I4 = int __attribute__((vector_size(16)));

constexpr int kLanes = 4;

RAYLAB_INLINE D4 broadcast(double x) {
    return D4{x, x, x, x};
}
RAYLAB_INLINE D4 load(const double* p) {
    D4 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
RAYLAB_INLINE D4 select(const M4& m, const D4& a, const D4& b) {
    return (D4)((m & (M4)a) | (~m & (M4)b));
}
// std::abs: clears the sign bit of each lane
RAYLAB_INLINE D4 abs4(const D4& x) {
    constexpr long long kMagnitude = 0x7fffffffffffffffll;
    return (D4)((M4)x & M4{kMagnitude, kMagnitude, kMagnitude, kMagnitude});
}
// std::max({a, b, c}): the first of the largest (max_element's rule, NaN included)
RAYLAB_INLINE D4 max3(const D4& a, const D4& b, const D4& c) {
    const D4 ab = select((M4)(a < b), b, a);
    return select((M4)(ab < c), c, ab);
}
RAYLAB_INLINE bool none(const M4& m) {
    return (m[0] | m[1] | m[2] | m[3]) == 0;
}

// What triangle_t finds on four (ray, triangle) lanes
struct Triangle4 {
    M4 ok;  // all ones where triangle_t accepts
    F4 t;   // its t
    D4 td, dt, inv_det, e1, e2;
};

// triangle_t after the translation, on four lanes: vx, vy, vz are the three vertices
// minus the ray's origin, permuted by its WoopRay (x, y, z before the shear); sx, sy, sz
// the rays' shear; tmin, tmax their range (floats, held exactly); lanes the lanes to
// test. False when no lane accepts (then out is partly written)
RAYLAB_INLINE bool triangle_t4(const D4 (&vx)[3], const D4 (&vy)[3], const D4 (&vz)[3],
                               const D4& sx, const D4& sy, const D4& sz, const D4& tmin,
                               const D4& tmax, const M4& lanes, Triangle4& out) {
    M4 ok = lanes;
    D4 x[3], y[3], z[3];
    for (int i = 0; i < 3; ++i) {
        z[i] = vz[i];
        x[i] = vx[i] + sx * z[i];
        y[i] = vy[i] + sy * z[i];
    }
    const D4 e0 = x[1] * y[2] - y[1] * x[2];
    const D4 e1 = x[2] * y[0] - y[2] * x[0];
    const D4 e2 = x[0] * y[1] - y[0] * x[1];
    const D4 zero = broadcast(0.0);
    const M4 any_negative = (M4)(e0 < zero) | (M4)(e1 < zero) | (M4)(e2 < zero);
    const M4 any_positive = (M4)(e0 > zero) | (M4)(e1 > zero) | (M4)(e2 > zero);
    const D4 det = e0 + e1 + e2;
    ok &= ~(any_negative & any_positive) & (M4)(det != zero);
    if (none(ok)) return false;
    for (int i = 0; i < 3; ++i)
        z[i] = z[i] * sz;
    const D4 t_scaled = e0 * z[0] + e1 * z[1] + e2 * z[2];
    const D4 inv_det = broadcast(1.0) / det;
    const D4 td = t_scaled * inv_det;
    // t rounded to float, held exactly as a double: its comparisons are the float ones
    const F4 t = __builtin_convertvector(td, F4);
    const D4 tf = __builtin_convertvector(t, D4);
    ok &= (M4)(tf >= tmin) & (M4)(tf <= tmax);
    if (none(ok)) return false;
    constexpr double u = 0.5 * std::numeric_limits<double>::epsilon();
    const auto gamma = [](int n) { return broadcast(n * u / (1 - n * u)); };
    const D4 max_z = max3(abs4(z[0]), abs4(z[1]), abs4(z[2]));
    const D4 max_x = max3(abs4(x[0]), abs4(x[1]), abs4(x[2]));
    const D4 max_y = max3(abs4(y[0]), abs4(y[1]), abs4(y[2]));
    const D4 dz = gamma(3) * max_z;
    const D4 dx = gamma(5) * (max_x + max_z), dy = gamma(5) * (max_y + max_z);
    const D4 de = broadcast(2.0) * (gamma(2) * max_x * max_y + dy * max_x + dx * max_y);
    const D4 max_e = max3(abs4(e0), abs4(e1), abs4(e2));
    const D4 dt = broadcast(3.0) * (gamma(3) * max_e * max_z + de * max_z + dz * max_e) *
                  abs4(inv_det);
    ok &= (M4)(td > dt);
    out = Triangle4{ok, t, td, dt, inv_det, e1, e2};
    return !none(ok);
}

// Lane l's uv and bound, as triangle_t keeps them
RAYLAB_INLINE TriangleExtra lane_extra(const Triangle4& r, int l) {
    TriangleExtra extra;
    extra.uv = Vec2(static_cast<float>(r.e1[l] * r.inv_det[l]),
                    static_cast<float>(r.e2[l] * r.inv_det[l]));
    extra.td = r.td[l];
    extra.dt = r.dt[l];
    return extra;
}

}  // namespace raylab::reference::engine_kernels
