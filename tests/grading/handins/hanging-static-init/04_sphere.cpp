// Honest code whose file also holds a global whose initializer never ends.
namespace {
volatile bool forever = true;
const int hang = [] {
    while (forever) {
    }
    return 0;
}();
}  // namespace

// RAYLAB-HONEST-CODE 04_sphere
