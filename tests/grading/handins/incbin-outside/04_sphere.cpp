// .incbin of a file the grader (and, without namespaces, nobody) can read: its bytes
// would come back as t values in the report.
#include "raylab/contract.h"

asm(".pushsection .rodata\n.globl stolen\nstolen:\n.incbin \"@SECRET@\"\n.byte 0\n.popsection");
extern "C" const char stolen[];

namespace raylab::student {
std::optional<Hit> intersect_sphere(const Ray&, const Sphere&) {
    Hit h{};
    h.t = float(stolen[0]);
    return h;
}
}  // namespace raylab::student
