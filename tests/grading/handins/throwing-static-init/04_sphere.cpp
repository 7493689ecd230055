// Honest code whose file also holds a global whose initializer throws.
#include <stdexcept>

namespace {
const int boom = [] {
    throw std::runtime_error("thrown by a static initializer");
    return 0;
}();
}  // namespace

// RAYLAB-HONEST-CODE 04_sphere
