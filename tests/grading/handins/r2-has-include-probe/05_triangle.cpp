// __has_include probes a path outside the hand-in: the module gets its honest code only
// when the path is visible to the compile (GCC may only stat a path, which Landlock
// does not restrict), so any points here mean one bit of the outside leaked
#include "raylab/contract.h"
#if __has_include("/etc/passwd") || __has_include("/proc/self/environ") || __has_include("/etc/hostname")
// RAYLAB-HONEST-CODE 05_triangle
#endif
