// The compiler itself is the target: an include that never ends grows cc1plus's buffer
// without bound (no memory limit on the sandboxed compile), for up to its 120 s timeout.
#include "/dev/zero"
