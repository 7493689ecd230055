// The compared intersection kernels and the ground truth (bench/kernels.h).
#include "kernels.h"

#include <cmath>

namespace raylab::bench {

namespace {

// ---------------------------------------------------------------------------------------
// Spheres

std::optional<Hit> sphere_hit(const Ray& r, const Sphere& s, float t) {
    Hit hit;
    hit.t = t;
    hit.position = r.o + t * r.w;
    hit.n = (hit.position - s.c) / s.r;
    return hit;
}

// Nearest of the roots t0 <= t1 inside [tmin, tmax]
template <class Real>
std::optional<Hit> nearest_root(const Ray& r, const Sphere& s, Real t0, Real t1) {
    if (t0 > t1) std::swap(t0, t1);
    Real t = t0;
    if (!(t >= r.tmin && t <= r.tmax)) {
        t = t1;
        if (!(t >= r.tmin && t <= r.tmax)) return std::nullopt;
    }
    return sphere_hit(r, s, static_cast<float>(t));
}

// The textbook quadratic: disc = b^2 - c, t = -b -+ sqrt(disc); cancels for small spheres
// far away (b^2 and c nearly equal) and for the root nearer to zero (-b + sqrt(disc)).
// UseA: solve a t^2 + 2 b t + c = 0 with a = w.w instead of assuming |w| = 1 (a float w
// normalised in float has |w|^2 = 1 +- 1e-7, and b^2 - c errs by D^2 |1 - a|)
template <class Real, bool UseA>
std::optional<Hit> sphere_naive(const Ray& r, const Sphere& s) {
    using V = glm::vec<3, Real>;
    const V f = V(r.o) - V(s.c), w = V(r.w);
    const Real a = UseA ? glm::dot(w, w) : Real(1);
    const Real b = glm::dot(f, w);
    const Real c = glm::dot(f, f) - Real(s.r) * Real(s.r);
    const Real disc = b * b - a * c;
    if (disc < 0) return std::nullopt;
    const Real root = std::sqrt(disc);
    return nearest_root<Real>(r, s, (-b - root) / a, (-b + root) / a);
}

// Ray Tracing Gems ch. 7: disc = r^2 - |f - b w|^2 and t = c / q for the second root
// (UseA: disc = a (r^2 - |f - (b / a) w|^2), roots q / a and c / q)
template <class Real, bool UseA>
std::optional<Hit> sphere_rtg(const Ray& r, const Sphere& s) {
    using V = glm::vec<3, Real>;
    const V f = V(r.o) - V(s.c), w = V(r.w);
    const Real a = UseA ? glm::dot(w, w) : Real(1);
    const Real b = glm::dot(f, w);
    const Real c = glm::dot(f, f) - Real(s.r) * Real(s.r);
    const V l = f - (b / a) * w;
    const Real disc = a * (Real(s.r) * Real(s.r) - glm::dot(l, l));
    if (disc < 0) return std::nullopt;
    const Real q = -b - std::copysign(std::sqrt(disc), b);
    return nearest_root<Real>(r, s, q / a, q != 0 ? c / q : Real(0));
}

std::optional<Hit> sphere_naive_float(const Ray& r, const Sphere& s) {
    return sphere_naive<float, false>(r, s);
}
std::optional<Hit> sphere_naive_double(const Ray& r, const Sphere& s) {
    return sphere_naive<double, false>(r, s);
}
std::optional<Hit> sphere_naive_double_a(const Ray& r, const Sphere& s) {
    return sphere_naive<double, true>(r, s);
}
std::optional<Hit> sphere_rtg_double(const Ray& r, const Sphere& s) {
    return sphere_rtg<double, false>(r, s);
}
std::optional<Hit> sphere_rtg_double_a(const Ray& r, const Sphere& s) {
    return sphere_rtg<double, true>(r, s);
}

// ---------------------------------------------------------------------------------------
// Triangles

std::optional<Hit> triangle_hit(const Ray& r, const Vec3& e1, const Vec3& e2, float t,
                                float beta, float gamma) {
    if (!(t >= r.tmin && t <= r.tmax)) return std::nullopt;
    Hit hit;
    hit.t = t;
    hit.position = r.o + t * r.w;
    hit.n = glm::normalize(glm::cross(e1, e2));
    hit.uv = Vec2(beta, gamma);
    return hit;
}

// Moeller and Trumbore (1997), without the det epsilon (a fixed epsilon is wrong for
// small or large triangles): det == 0 only for parallel rays and degenerate triangles
std::optional<Hit> triangle_moeller_trumbore(const Ray& r, const Vec3& v0, const Vec3& v1,
                                             const Vec3& v2) {
    const Vec3 e1 = v1 - v0, e2 = v2 - v0;
    const Vec3 p = glm::cross(r.w, e2);
    const float det = glm::dot(e1, p);
    if (det == 0.0f) return std::nullopt;
    const float inv_det = 1.0f / det;
    const Vec3 s = r.o - v0;
    const float beta = glm::dot(s, p) * inv_det;
    if (beta < 0.0f || beta > 1.0f) return std::nullopt;
    const Vec3 q = glm::cross(s, e1);
    const float gamma = glm::dot(r.w, q) * inv_det;
    if (gamma < 0.0f || beta + gamma > 1.0f) return std::nullopt;
    return triangle_hit(r, e1, e2, glm::dot(e2, q) * inv_det, beta, gamma);
}

// Cramer's rule on [v0 - v1, v0 - v2, w] (beta, gamma, t) = v0 - o, with the letters of
// Shirley, "Fundamentals of Computer Graphics", §4.4.2 (the DTU 02562 formulation)
std::optional<Hit> triangle_cramer(const Ray& r, const Vec3& v0, const Vec3& v1,
                                   const Vec3& v2) {
    const float a = v0.x - v1.x, b = v0.y - v1.y, c = v0.z - v1.z;
    const float d = v0.x - v2.x, e = v0.y - v2.y, f = v0.z - v2.z;
    const float g = r.w.x, h = r.w.y, i = r.w.z;
    const float j = v0.x - r.o.x, k = v0.y - r.o.y, l = v0.z - r.o.z;
    const float ei_hf = e * i - h * f, gf_di = g * f - d * i, dh_eg = d * h - e * g;
    const float M = a * ei_hf + b * gf_di + c * dh_eg;
    if (M == 0.0f) return std::nullopt;
    const float beta = (j * ei_hf + k * gf_di + l * dh_eg) / M;
    if (beta < 0.0f || beta > 1.0f) return std::nullopt;
    const float ak_jb = a * k - j * b, jc_al = j * c - a * l, bl_kc = b * l - k * c;
    const float gamma = (i * ak_jb + h * jc_al + g * bl_kc) / M;
    if (gamma < 0.0f || beta + gamma > 1.0f) return std::nullopt;
    const float t = -(f * ak_jb + e * jc_al + d * bl_kc) / M;
    return triangle_hit(r, v1 - v0, v2 - v0, t, beta, gamma);
}

// The reference's edge functions, in float: each edge's sign depends on that edge's two
// vertices only, so shared edges stay watertight; t is less accurate than in double
std::optional<Hit> triangle_edge_float(const Ray& r, const Vec3& v0, const Vec3& v1,
                                       const Vec3& v2) {
    const Vec3 a = v0 - r.o, b = v1 - r.o, c = v2 - r.o;
    const float e0 = glm::dot(glm::cross(b, c), r.w);
    const float e1 = glm::dot(glm::cross(c, a), r.w);
    const float e2 = glm::dot(glm::cross(a, b), r.w);
    if ((e0 < 0 || e1 < 0 || e2 < 0) && (e0 > 0 || e1 > 0 || e2 > 0)) return std::nullopt;
    const float det = e0 + e1 + e2;
    if (det == 0.0f) return std::nullopt;
    const Vec3 N = glm::cross(b - a, c - a);
    return triangle_hit(r, v1 - v0, v2 - v0, glm::dot(N, a) / det, e1 / det, e2 / det);
}

// ---------------------------------------------------------------------------------------
// Ground truth in long double

struct LVec3 {
    long double x, y, z;
    explicit LVec3(const Vec3& v) : x(v.x), y(v.y), z(v.z) {}
    LVec3(long double x_, long double y_, long double z_) : x(x_), y(y_), z(z_) {}
};
LVec3 operator-(const LVec3& a, const LVec3& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
LVec3 operator*(long double s, const LVec3& a) {
    return {s * a.x, s * a.y, s * a.z};
}
long double dot(const LVec3& a, const LVec3& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
LVec3 cross(const LVec3& a, const LVec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

std::optional<long double> in_range(const Ray& r, long double t) {
    if (t >= r.tmin && t <= r.tmax) return t;
    return std::nullopt;
}

}  // namespace

const std::vector<NamedSphereKernel>& sphere_kernels() {
    static const std::vector<NamedSphereKernel> kernels{
        {"naive float (b^2 - c)", &sphere_naive_float},
        {"naive double", &sphere_naive_double},
        {"naive double, a = w.w", &sphere_naive_double_a},
        {"reference (RTG ch. 7)", &reference::intersect_sphere},
        {"RTG ch. 7, double", &sphere_rtg_double},
        {"RTG ch. 7, double, a = w.w", &sphere_rtg_double_a},
    };
    return kernels;
}

const std::vector<NamedTriangleKernel>& triangle_kernels() {
    static const std::vector<NamedTriangleKernel> kernels{
        {"Moeller-Trumbore float", &triangle_moeller_trumbore},
        {"Cramer float", &triangle_cramer},
        {"edge functions float", &triangle_edge_float},
        {"reference (watertight, double)", &reference::intersect_triangle},
    };
    return kernels;
}

std::optional<long double> exact_sphere_t(const Ray& r, const Sphere& s) {
    // a t^2 + 2 b t + c = 0 with a = w.w; b^2 - a c = a (R^2 - |f - (b / a) w|^2)
    const LVec3 f = LVec3(r.o) - LVec3(s.c), w(r.w);
    const long double a = dot(w, w), b = dot(f, w);
    const long double R = s.r, c = dot(f, f) - R * R;
    const LVec3 l = f - (b / a) * w;
    const long double disc = a * (R * R - dot(l, l));
    if (disc < 0) return std::nullopt;
    const long double q = -b - std::copysign(std::sqrt(disc), b);
    long double t0 = q / a, t1 = q != 0 ? c / q : 0.0L;
    if (t0 > t1) std::swap(t0, t1);
    if (auto t = in_range(r, t0)) return t;
    return in_range(r, t1);
}

std::optional<long double> exact_triangle_t(const Ray& r, const Vec3& v0, const Vec3& v1,
                                            const Vec3& v2) {
    const LVec3 o(r.o), w(r.w);
    const LVec3 a = LVec3(v0) - o, b = LVec3(v1) - o, c = LVec3(v2) - o;
    const long double e0 = dot(cross(b, c), w), e1 = dot(cross(c, a), w),
                      e2 = dot(cross(a, b), w);
    if ((e0 < 0 || e1 < 0 || e2 < 0) && (e0 > 0 || e1 > 0 || e2 > 0)) return std::nullopt;
    const long double det = e0 + e1 + e2;
    if (det == 0) return std::nullopt;
    return in_range(r, dot(cross(b - a, c - a), a) / det);
}

}  // namespace raylab::bench
