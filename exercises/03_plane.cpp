// Module 03_plane: ray-plane intersection (docs/handouts/03_plane.md).
//
// Your work is the function below; `grep -n "TODO(student)" exercises/` lists every step.
// Delete a function's RAYLAB_STUB line when you start on that function: while a module's
// functions still call it, the viewer runs the reference for that module and the graders
// report it as not started.
#include "raylab/contract.h"

namespace raylab::student {

/// Ray-plane intersection (handout 03 §2): the plane p . n + d = 0 meets r(t) = o + t w
/// at
///   t = -(o . n + d) / (w . n),
/// accepted when tmin <= t <= tmax. Returns std::nullopt for rays parallel to the plane.
/// The geometric normal is the plane's n, whichever side the ray comes from (do not flip
/// it). plane.d is the plane offset, not the camera constant.
std::optional<Hit> intersect_plane(const Ray& r, const Plane& plane) {
    // TODO(student) 03_plane: Parallel rays never meet the plane: wn = w . n; a miss when
    //   wn == 0 (it would divide by zero)
    // TODO(student) 03_plane: Signed distance of o from the plane, dist = o . n + d, and
    //   t = -dist / wn (handout 03 §4: double precision helps far from the origin)
    // TODO(student) 03_plane: Conditional acceptance (tmin <= t <= tmax), written so that
    //   NaN fails it: if (!(t >= r.tmin && t <= r.tmax)) return std::nullopt;
    // TODO(student) 03_plane: The hit: hit.t = t, hit.position = o + t w, hit.n = plane.n
    RAYLAB_STUB("03_plane");
    (void)r, (void)plane;
    return std::nullopt;
}

}  // namespace raylab::student
