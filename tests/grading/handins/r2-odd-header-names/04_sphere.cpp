// Headers beside the module with names a shell or a tool could misread (a leading dash,
// glob characters, a command substitution, a semicolon, a backslash, the module's own
// name with .h) and files named like the grader's reports: staged as plain names, the
// honest code compiles with them and the reports stay the grader's
#include "-o.h"
#include "*.h"
#include "$(touch pwned).h"
#include "a;b c.h"
#include "04_sphere.cpp.h"
#include "back\slash.h"
// RAYLAB-HONEST-CODE 04_sphere
