// raylab/refine.h: hit points moved back onto the primitive they lie on.
//
// A hit point o + t w computed in float is off its surface by the rounding error of o, t
// and w, which grows with the camera's distance, not with |x| (issue 8, B4: a camera 1e4
// away puts hits 5e-4 below a plane at the origin). Scene::closest_hit recomputes every
// hit in double, whichever module (student or reference) found it: the intersection of
// the (float) ray with the primitive it hit (as its float parameters define it), the
// root nearest the module's t, projected onto the surface. Rounded to float, it is
// within half an ulp per coordinate of that exact point: its distance from the surface
// is at most hit_error_bound(x), and its distance along the surface no more, whatever the
// camera's distance. The shadow module offsets its ray by a few times that bound
// (handout 08 §3). Where double finds no intersection (a grazing ray the module hit in
// float), the module's point is projected onto the surface instead. The reference's
// engine computes a triangle's point itself, from its intersection test's t in double,
// when that test's error bound puts it within 2^-30 of its size of the same exact point
// (solutions/engine_geometry.cpp; PrimRef::refined): 1/64 of an ulp at most more.
#pragma once

#include "raylab/contract.h"

namespace raylab {

/// The bound on the distance of a refined hit point x from its surface: one ulp of its
/// largest coordinate, 2^-23 max|x_i|. Rounding each coordinate of an exact surface point
/// to float moves it by at most half an ulp of that coordinate, sqrt(3)/2 ulps in all;
/// the double arithmetic before it adds about 2^-50 |x|.
float hit_error_bound(const Vec3& x);

/// Where r meets the plane p . n + d = 0, in double, rounded (or x projected onto it).
Vec3 refine_on_plane(const Vec3& x, const Ray& r, const Plane& plane);
/// Where r meets the sphere at the root nearest t (or x projected onto it).
Vec3 refine_on_sphere(const Vec3& x, const Ray& r, float t, const Sphere& sphere);
/// Where r meets the triangle's plane (or x projected onto it).
Vec3 refine_on_triangle(const Vec3& x, const Ray& r, const Vec3& v0, const Vec3& v1,
                        const Vec3& v2);

/// The sphere's normal at the refined point x, (x - c) / r in double, oriented like the
/// module's normal n: a float hit point from a camera 1e5 away is off by about 0.01, and
/// so is a normal derived from it, enough to turn a point just past the terminator
/// towards the light. Only when n is a unit vector within 60 degrees of it (either
/// orientation): otherwise n itself, so that a student's wrong normal stays visible.
Vec3 refine_sphere_normal(const Vec3& x, const Vec3& n, const Sphere& sphere);

/// The refined point when it is finite and close to x (a move of at most 2^-8 of the
/// scale |o|_inf + t + |x|_inf of the ray that found x, far beyond any rounding error);
/// otherwise x itself: a wrong hit point from a student's module stays wrong, visibly,
/// instead of being pulled onto the surface, and a degenerate primitive (x at a sphere's
/// centre, a triangle of zero area) keeps its hit.
Vec3 accept_refined(const Vec3& x, const Vec3& refined, const Ray& r, float t);

}  // namespace raylab
