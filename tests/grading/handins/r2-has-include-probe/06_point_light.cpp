// __has_include probes a path outside the hand-in: the module gets its honest code only
// when the path is visible to the compile (GCC may only stat a path, which Landlock
// does not restrict), so any points here mean one bit of the outside leaked
#include "raylab/contract.h"
#if __has_include("@ROOT@/README.md") || __has_include("../03_plane/03_plane.cpp") || __has_include("/tmp/../usr/../@ROOT@/README.md")
// RAYLAB-HONEST-CODE 06_point_light
#endif
