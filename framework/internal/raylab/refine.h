// raylab/refine.h: hit points moved back onto the primitive they lie on, when the module
// that found them only rounded.
//
// Internal to the framework (framework/internal/, library raylab_refine): not among the
// public headers a hand-in compiles against, and not linked into a grading worker, so
// that no hand-in can call these functions to do the work of modules 03-05.
//
// A hit point o + t w computed in float is off its surface by the rounding error of o, t
// and w, which grows with the camera's distance, not with |x| (a camera 1e4 away puts
// hits 5e-4 below a plane at the origin). Scene::closest_hit recomputes every hit in
// double, whichever module (student or reference) found it: the intersection of the
// (float) ray with the primitive it hit (as its float parameters define it), the root
// nearest the module's t, projected onto the surface. Rounded to float, it is within half
// an ulp per coordinate of that exact point: its distance from the surface is at most
// hit_error_bound(x), and its distance along the surface no more, whatever the camera's
// distance. The shadow module offsets its ray by a few times that bound (handout 08 §3).
// Where double finds no intersection (a grazing ray the module hit in float), the
// module's point is projected onto the surface instead.
//
// The refined point replaces the module's only when the module's point lies within the
// module's own rounding bound (module_error_bound) of both the surface and the ray: a
// module that rounds is repaired, a module with a mistake (a point off its surface, a t
// too large) is shown as it computed it. The module's normal is never replaced. The
// reference's engine computes a triangle's point itself, from its intersection test's t
// in double, when that test's error bound puts it within 2^-30 of its size of the same
// exact point (engine/src/engine_kernels.h; PrimRef::refined): 1/64 of an ulp at most
// more.
#pragma once

#include "raylab/contract.h"
#include "raylab/scene.h"

namespace raylab {

/// The bound on the distance of a refined hit point x from its surface: one ulp of its
/// largest coordinate, 2^-23 max|x_i|. Rounding each coordinate of an exact surface point
/// to float moves it by at most half an ulp of that coordinate, sqrt(3)/2 ulps in all;
/// the double arithmetic before it adds about 2^-50 |x|.
float hit_error_bound(const Vec3& x);

/// The rounding bound of a correct float module's hit x for ray r at t: 8 ulps of the
/// ray's scale, 8 * 2^-23 (|o|_inf + |t| |w|_inf + |x|_inf). Computing o + t w in float
/// rounds each coordinate by half an ulp of |o_i| + |t w_i|; a t rounded to float, or
/// computed in float from float inputs (the reference's modules), moves the point across
/// the surface by a few more ulps of that scale. The reference's modules stay within
/// 2 ulps in the stress suite (tests/stress/test_refine.cpp measures it).
float module_error_bound(const Ray& r, float t, const Vec3& x);

/// Where r meets the plane p . n + d = 0, in double, rounded (or x projected onto it).
Vec3 refine_on_plane(const Vec3& x, const Ray& r, const Plane& plane);
/// Where r meets the sphere at the root nearest t (or x projected onto it).
Vec3 refine_on_sphere(const Vec3& x, const Ray& r, float t, const Sphere& sphere);
/// Where r meets the triangle's plane (or x projected onto it).
Vec3 refine_on_triangle(const Vec3& x, const Ray& r, const Vec3& v0, const Vec3& v1,
                        const Vec3& v2);

/// The refined point when it is finite and the module's point x agrees with it, within
/// module_error_bound(r, t, x): x lies that close to the surface, measured along the
/// surface's unit normal n at the refined point, and that close to the ray's line; and
/// the two are within 2^-8 of the ray's scale along the ray (where a grazing ray meets
/// the surface, t itself is ill-conditioned). Otherwise x itself: a wrong hit point from
/// a student's module stays wrong, visibly, and a degenerate primitive (x at a sphere's
/// centre, a triangle of zero area) keeps its hit.
Vec3 accept_refined(const Vec3& x, const Vec3& refined, const Vec3& n, const Ray& r,
                    float t);

/// Triangle t's unit normal as the contract defines hit.n: (v1 - v0) x (v2 - v0) in
/// double, divided by its length, rounded to float; zero when the cross product has no
/// length (a degenerate triangle, never hit). The reference module computes the same.
Vec3 unit_normal(const SceneTriangle& t);

}  // namespace raylab
