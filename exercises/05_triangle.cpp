// Module 05_triangle: ray-triangle intersection (docs/handouts/05_triangle.md).
//
// Your work is the function below; `grep -n "TODO(student)" exercises/` lists every step.
// Delete a function's RAYLAB_STUB line when you start on that function: while a module's
// functions still call it, the viewer runs the reference for that module and the graders
// report it as not started.
#include "raylab/contract.h"

namespace raylab::student {

/// Ray-triangle intersection (handout 05 §2-§4). The hit point is
///   r(t) = (1 - beta - gamma) v0 + beta v1 + gamma v2,  beta, gamma >= 0,
///   beta + gamma <= 1,
/// hit.uv = (beta, gamma), hit.n = normalize((v1 - v0) x (v2 - v0)) (counter-clockwise
/// vertices face the viewer; do not flip n towards the ray). Both sides are hit.
/// Degenerate triangles (zero area) and rays parallel to the plane are never hit.
///
/// The steps follow the edge functions of handout 05 §4; Cramer's rule (§2) and
/// Moeller-Trumbore (§3) are just as good: replace the steps by theirs if you use them.
std::optional<Hit> intersect_triangle(const Ray& r, const Vec3& v0, const Vec3& v1,
                                      const Vec3& v2) {
    // TODO(student) 05_triangle: Vertices relative to the ray origin: a = v0 - o,
    //   b = v1 - o, c = v2 - o (in double, DVec3, for accuracy)
    // TODO(student) 05_triangle: Edge functions, one barycentric weight each:
    //   e0 = (b x c) . w (v0), e1 = (c x a) . w (v1, beta), e2 = (a x b) . w (v2, gamma)
    // TODO(student) 05_triangle: Inside when no two edge functions have opposite signs
    // TODO(student) 05_triangle: The weights sum to det = e0 + e1 + e2: a miss when it is
    //   zero (parallel ray or degenerate triangle)
    // TODO(student) 05_triangle: Distance along w to the triangle's plane,
    //   N = (b - a) x (c - a), t = (N . a) / (N . w) (a miss when N . w is zero), and
    //   conditional acceptance
    //   (tmin <= t <= tmax)
    // TODO(student) 05_triangle: The hit: t, position o + t w, n = normalize(N),
    //   uv = (e1 / det, e2 / det)
    RAYLAB_STUB("05_triangle");
    (void)r, (void)v0, (void)v1, (void)v2;
    return std::nullopt;
}

}  // namespace raylab::student
