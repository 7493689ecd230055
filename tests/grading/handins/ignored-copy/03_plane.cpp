// An old copy in the hand-in's root, beside the real one in exercises/: the root's is
// graded (the shallowest), and the report names the one it ignored
#include "raylab/contract.h"
namespace raylab::student {
std::optional<Hit> intersect_plane(const Ray&, const Plane&) { return std::nullopt; }
}  // namespace raylab::student
