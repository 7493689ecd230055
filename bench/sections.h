// bench/sections.h: the three sections of raylab-bench, each printing its own tables.
#pragma once

#include "options.h"

namespace raylab::bench {

/// Section 1: ray-sphere and ray-triangle formulations, ns per test against the error of
/// t and the hit/miss errors, on seeded ray sets at growing distance, grazing and through
/// shared edges.
void run_kernel_section(const BenchOptions& options);

/// Section 2: raylab (reference modules, Scene::closest_hit/any_hit) against Embree on
/// the same rays: Mrays/s, ratio, build times, agreement; then where raylab's time goes.
void run_scene_section(const BenchOptions& options);

/// Section 3: render() of the Cornell box and the DTU scene, shadows on and off, 1 and
/// all threads: time, Mrays/s, speed-up and the shadow rays skipped.
void run_render_section(const BenchOptions& options);

/// Section 4: meshes of 1e3 .. max_triangles triangles: build time against Embree's
/// MEDIUM build on 1 and 2 threads, bytes per triangle, and time per ray against size.
void run_scaling_section(const BenchOptions& options);
/// Section 5: RMSE against a converged image versus render time for the pixel sampling
/// schemes and uniform against stratified area-light samples; writes CSV and SVG and
/// prints every table of docs/sampling-benchmarks.md. With options.sampling_csv it
/// renders nothing and prints the tables from that CSV (section_sampling.cpp).
void run_sampling_section(const BenchOptions& options);

}  // namespace raylab::bench
