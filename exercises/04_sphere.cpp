// Module 04_sphere: ray-sphere intersection (docs/handouts/04_sphere.md).
//
// Your work is the function below; `grep -n "TODO(student)" exercises/` lists every step.
// Delete a function's RAYLAB_STUB line when you start on that function: while a module's
// functions still call it, the viewer runs the reference for that module and the graders
// report it as not started.
#include "raylab/contract.h"

namespace raylab::student {

/// Nearest t in [tmin, tmax] with |o + t w - c|^2 = r^2 (handout 04 §2), with outward
/// normal (p - c) / r, also when the ray starts inside the sphere. Returns std::nullopt
/// on a miss. Precondition: |w| = 1, so the quadratic's leading coefficient is 1.
///
/// Numerics (handout 04 §4, optional): b^2 - c cancels badly for small spheres far away;
/// r^2 - |f - b w|^2 is the same number computed accurately.
std::optional<Hit> intersect_sphere(const Ray& r, const Sphere& sphere) {
    // TODO(student) 04_sphere: Half-coefficients of t^2 + 2 b t + c = 0, with f = o - c:
    //   b = f . w, c = f . f - r^2
    // TODO(student) 04_sphere: Discriminant disc = b^2 - c; a miss when it is negative
    // TODO(student) 04_sphere: Both roots t0 = -b - sqrt(disc) <= t1 = -b + sqrt(disc)
    // TODO(student) 04_sphere: Nearest root inside [tmin, tmax]:
    //   t = t0 if accepted, else t1 if accepted (the ray starts inside), else a miss
    // TODO(student) 04_sphere: The hit: hit.t = t, hit.position = o + t w,
    //   hit.n = (hit.position - c) / r
    RAYLAB_STUB("04_sphere");
    (void)r, (void)sphere;
    return std::nullopt;
}

}  // namespace raylab::student
