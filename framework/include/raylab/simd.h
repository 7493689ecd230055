// raylab/simd.h: whether the SSE2 paths of the BVH's build (framework/src) and of the
// geometry engine (engine/: its node tests and walks, the hit point's shared coordinates)
// are compiled. Every x86-64 compiler has SSE2; with RAYLAB_NO_SIMD defined, or on
// another architecture, each takes its scalar twin, which gives the same results. CI
// builds the stress suite and the unit tests both ways (scripts/stress-matrix.sh), so
// neither twin goes untested. The teaching path (raylab/bvh.h's walk, solutions/) has
// no SIMD.
#pragma once

#if defined(__SSE2__) && !defined(RAYLAB_NO_SIMD)
#define RAYLAB_SSE2 1
#include <emmintrin.h>
#else
#define RAYLAB_SSE2 0
#endif

#if RAYLAB_SSE2 && defined(__x86_64__)
#define RAYLAB_AVX_NODES 1
#include <immintrin.h>
#else
#define RAYLAB_AVX_NODES 0
#endif
