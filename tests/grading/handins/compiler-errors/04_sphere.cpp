// An honest mistake: debug prints of GLM vectors without an operator<<, each of which
// makes the compiler list every candidate (well over 64 KiB of messages).
#include <iostream>

#include "raylab/contract.h"

namespace raylab::student {
std::optional<Hit> intersect_sphere(const Ray& r, const Sphere& sphere) {
    std::cout << r.o << r.w << sphere.c << std::endl;
    std::cout << r.o + r.w << sphere.c - r.o << std::endl;
    std::cout << glm::cross(r.o, r.w) << glm::normalize(r.w) << std::endl;
    std::cerr << r.o << r.w << sphere.c << r.o << r.w << sphere.c << std::endl;
    return std::nullopt;
}
}  // namespace raylab::student
