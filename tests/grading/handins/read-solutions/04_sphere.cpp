// Reads the reference's source at run time and throws it, so that it lands in the
// student-facing report; also tries the bytes \xff and terminal escapes in the message.
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "raylab/contract.h"

namespace raylab::student {
std::optional<Hit> intersect_sphere(const Ray&, const Sphere&) {
    for (const char* path :
         {"@ROOT@/solutions/04_sphere.cpp", "../../solutions/04_sphere.cpp",
          "../solutions/04_sphere.cpp"}) {
        std::ifstream in(path);
        std::ostringstream s;
        s << in.rdbuf();
        if (!s.str().empty()) throw std::runtime_error(s.str());
    }
    throw std::runtime_error(
        "no solution found \xff\xfe bytes \x1b[31mred\x1b[0m \x07 end");
}
}  // namespace raylab::student
