// Hit points moved back onto their primitive, in double (raylab/refine.h).
#include "raylab/refine.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace raylab {

namespace {

float max_abs(const Vec3& v) {
    return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

// Rounds a double point to float; each coordinate moves by at most half an ulp
Vec3 to_float(const DVec3& p) {
    return Vec3(static_cast<float>(p.x), static_cast<float>(p.y),
                static_cast<float>(p.z));
}

// The point of the plane p . n = k nearest to p (n need not be unit)
DVec3 onto_plane(const DVec3& p, const DVec3& n, double k) {
    return p - (glm::dot(p, n) - k) / glm::dot(n, n) * n;
}

// Where r meets the plane p . n = k, projected onto it again (the step along w rounds
// at about 2^-53 |o + t w|); x projected when r is parallel to the plane. Float inputs
// are exact in double, so the only errors are double roundings, about 2^-50 of the
// coordinates, far below the final rounding to float. One division, 1 / (w.n n.n),
// serves both steps: it starts before the dot products are done, so the second step
// does not wait for a division of its own (a fifth of the refinement's time)
Vec3 ray_onto_plane(const Vec3& x, const Ray& r, const DVec3& n, double k) {
    const DVec3 o(r.o), w(r.w);
    const double wn = glm::dot(w, n), nn = glm::dot(n, n);
    if (wn != 0.0) {
        // w.n n.n underflows for triangles and rays of subnormal size (|w.n n.n| can be
        // 2^-1040 where w.n and n.n are not): its reciprocal would overflow or lose bits,
        // so there the two steps divide separately
        const double wnn = wn * nn;
        DVec3 q;
        if (std::abs(wnn) >= std::numeric_limits<double>::min()) {
            const double inv = 1.0 / wnn;
            const DVec3 p = o + ((k - glm::dot(o, n)) * nn * inv) * w;
            q = p - ((glm::dot(p, n) - k) * wn * inv) * n;
        } else {
            q = onto_plane(o + (k - glm::dot(o, n)) / wn * w, n, k);
        }
        if (std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z))
            return to_float(q);
    }
    return to_float(onto_plane(DVec3(x), n, k));
}

}  // namespace

float hit_error_bound(const Vec3& x) {
    return std::numeric_limits<float>::epsilon() * max_abs(x);
}

Vec3 refine_on_plane(const Vec3& x, const Ray& r, const Plane& plane) {
    const DVec3 n(plane.n);
    if (!(glm::dot(n, n) > 0.0)) return x;
    return ray_onto_plane(x, r, n, -double(plane.d));
}

Vec3 refine_on_sphere(const Vec3& x, const Ray& r, float t, const Sphere& sphere) {
    const DVec3 c(sphere.c), o(r.o), w(r.w), f = o - c;
    const double rr = double(sphere.r) * double(sphere.r), ww = glm::dot(w, w);
    // ww t^2 + 2 b t + k = 0. In double the textbook discriminant is accurate enough:
    // its cancellation costs at most the 2^-53 of b^2 that float inputs can resolve
    const double b = glm::dot(f, w), k = glm::dot(f, f) - rr;
    const double disc = b * b - ww * k;
    DVec3 p(x);
    if (ww > 0.0 && disc >= 0.0) {
        const double s = std::sqrt(disc);
        const double t0 = (-b - s) / ww, t1 = (-b + s) / ww;
        const double td = std::abs(t0 - double(t)) <= std::abs(t1 - double(t)) ? t0 : t1;
        p = o + td * w;
    }
    const DVec3 fp = p - c;
    const double len = glm::length(fp);
    if (!(len > 0.0) || !std::isfinite(len)) return x;
    return to_float(c + (double(sphere.r) / len) * fp);
}

Vec3 refine_on_triangle(const Vec3& x, const Ray& r, const Vec3& v0, const Vec3& v1,
                        const Vec3& v2) {
    // Differences of floats are exact in double unless their exponents are more than 29
    // apart. A cross product of edges e, f errs by about 2^-53 |e| |f|, of the normal's
    // length |e| |f| sin(angle): taken at the vertex opposite the longest edge, the two
    // edges whose product is smallest (review: a sliver with one vertex 2^18 away, its
    // normal from the two long edges off by 1.3e-10, put the point 2e4 delta off). The
    // plane's offset is taken at the vertex nearest x, where a tilt of the normal moves
    // the plane least
    const DVec3 p[3] = {DVec3(v0), DVec3(v1), DVec3(v2)};
    const double l01 = glm::dot(p[1] - p[0], p[1] - p[0]);
    const double l12 = glm::dot(p[2] - p[1], p[2] - p[1]);
    const double l20 = glm::dot(p[0] - p[2], p[0] - p[2]);
    // Vertex i is opposite the longest edge; its edges to i + 1 and i + 2 keep the
    // orientation of (v1 - v0) x (v2 - v0)
    const int i = l12 >= l01 && l12 >= l20 ? 0 : (l20 >= l01 ? 1 : 2);
    const DVec3& apex = p[i];
    const DVec3 n = glm::cross(p[(i + 1) % 3] - apex, p[(i + 2) % 3] - apex);
    const double nn = glm::dot(n, n);
    if (!(nn > 0.0) || !std::isfinite(nn)) return x;
    const DVec3 X(x);
    const auto d2 = [&](const DVec3& v) { return glm::dot(v - X, v - X); };
    const DVec3& near = d2(p[0]) <= d2(p[1]) ? (d2(p[0]) <= d2(p[2]) ? p[0] : p[2])
                                             : (d2(p[1]) <= d2(p[2]) ? p[1] : p[2]);
    return ray_onto_plane(x, r, n, glm::dot(near, n));
}

Vec3 refine_sphere_normal(const Vec3& x, const Vec3& n, const Sphere& sphere) {
    const DVec3 f = DVec3(x) - DVec3(sphere.c);
    const double len = glm::length(f), n_len = glm::length(DVec3(n));
    if (!(len > 0.0) || !std::isfinite(len) || !(std::abs(n_len - 1.0) < 0x1p-4))
        return n;
    const DVec3 exact = f / len;
    const double cos = glm::dot(exact, DVec3(n)) / n_len;
    if (cos >= 0.5) return Vec3(exact);
    if (cos <= -0.5) return Vec3(-exact);
    return n;
}

Vec3 accept_refined(const Vec3& x, const Vec3& refined, const Ray& r, float t) {
    if (!is_finite(refined)) return x;
    const float scale = max_abs(r.o) + std::abs(t) + max_abs(x);
    return max_abs(refined - x) <= 0x1p-8f * scale ? refined : x;
}

}  // namespace raylab
