// An existence oracle: __has_include of a path outside the hand-in. Without namespaces,
// Landlock refuses the open of an existing file (the compiler stops, its message hidden)
// but a missing one is just false: the report then tells the two apart. The grader must
// treat both alike (here: the #error below, as inside bubblewrap where neither exists)
#include "raylab/contract.h"
#if __has_include("@SECRET@.absent")
#else
#error probe-04-false
#endif
