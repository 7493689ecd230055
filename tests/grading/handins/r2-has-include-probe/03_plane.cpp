// __has_include probes a path outside the hand-in: the module gets its honest code only
// when the path is visible to the compile (GCC may only stat a path, which Landlock
// does not restrict), so any points here mean one bit of the outside leaked
#include "raylab/contract.h"
#if __has_include("@SECRET@")
// RAYLAB-HONEST-CODE 03_plane
#endif
