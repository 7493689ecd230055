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

// Double-double numbers (Dekker 1971; Shewchuk 1997): hi + lo, |lo| at most half an ulp
// of hi, about 106 bits. Only for hits far nearer the origin than their triangle
struct DD {
    double hi, lo;
};

DD two_sum(double a, double b) {
    const double s = a + b, bb = s - a;
    return {s, (a - (s - bb)) + (b - bb)};
}

// a b exactly (Dekker's split into 26-bit halves: no FMA, -ffp-contract=off keeps it so)
DD two_product(double a, double b) {
    const auto split = [](double v, double& h, double& l) {
        const double c = 134217729.0 * v;  // 2^27 + 1
        h = c - (c - v);
        l = v - h;
    };
    double ah, al, bh, bl;
    split(a, ah, al);
    split(b, bh, bl);
    const double p = a * b;
    return {p, ((ah * bh - p) + ah * bl + al * bh) + al * bl};
}

DD add(const DD& a, const DD& b) {
    const DD s = two_sum(a.hi, b.hi);
    return two_sum(s.hi, s.lo + (a.lo + b.lo));
}

// (a - b) . n, with a - b exact per component and n in double-double
double dot_of_difference(const DVec3& a, const DVec3& b, const DD n[3]) {
    DD acc{0.0, 0.0};
    for (int c = 0; c < 3; ++c) {
        const DD d = two_sum(a[c], -b[c]);
        DD term = two_product(d.hi, n[c].hi);
        term.lo += d.hi * n[c].lo + d.lo * n[c].hi;
        acc = add(acc, term);
    }
    return acc.hi + acc.lo;
}

// ray_onto_plane for the plane through `near` with normal e1 x e2, when the hit x is far
// nearer the origin than every vertex: in double, the plane's offset near x is known only
// to about 2^-52 |near| (a triangle 2^35 away seen at |x| = 0.8 put the point 45 delta
// off, below its surface). The normal (the products of the float edges, exact in
// double-double) and the two signed distances from the plane are computed in
// double-double, the rest in double
Vec3 ray_onto_far_plane(const Vec3& x, const Ray& r, const DVec3& e1, const DVec3& e2,
                        const DVec3& near) {
    DD n[3];
    for (int c = 0; c < 3; ++c) {
        const int a = (c + 1) % 3, b = (c + 2) % 3;
        const DD m = two_product(e1[b], e2[a]);
        n[c] = add(two_product(e1[a], e2[b]), DD{-m.hi, -m.lo});
    }
    const DVec3 nd(n[0].hi + n[0].lo, n[1].hi + n[1].lo, n[2].hi + n[2].lo);
    const DVec3 o(r.o), w(r.w);
    const double wn = glm::dot(w, nd), nn = glm::dot(nd, nd);
    if (wn == 0.0 || !(nn > 0.0) || !std::isfinite(nn)) return x;
    const DVec3 p = o + (dot_of_difference(near, o, n) / wn) * w;
    const DVec3 q = p - (dot_of_difference(p, near, n) / nn) * nd;
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) return x;
    return to_float(q);
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
    // edges whose product is smallest (a sliver with one vertex 2^18 away, its normal
    // from the two long edges off by 1.3e-10, put the point 2e4 delta off). The plane's
    // offset is taken at the vertex nearest x, where a tilt of the normal moves the plane
    // least
    const Vec3* const v[3] = {&v0, &v1, &v2};
    const DVec3 p[3] = {DVec3(v0), DVec3(v1), DVec3(v2)};
    // edge[j] runs from vertex j + 1 to j + 2, opposite vertex j
    const DVec3 edge[3] = {p[2] - p[1], p[0] - p[2], p[1] - p[0]};
    const double l[3] = {glm::dot(edge[0], edge[0]), glm::dot(edge[1], edge[1]),
                         glm::dot(edge[2], edge[2])};
    // Vertex i is opposite the longest edge; its edges to i + 1 and i + 2 keep the
    // orientation of (v1 - v0) x (v2 - v0)
    const int i = l[0] >= l[2] && l[0] >= l[1] ? 0 : (l[1] >= l[2] ? 1 : 2);
    const DVec3 e1 = edge[(i + 2) % 3], e2 = -edge[(i + 1) % 3];
    const DVec3 n = glm::cross(e1, e2);
    const double nn = glm::dot(n, n);
    if (!(nn > 0.0) || !std::isfinite(nn)) return x;
    const DVec3 X(x);
    double d[3];
    for (int j = 0; j < 3; ++j)
        d[j] = glm::dot(p[j] - X, p[j] - X);
    const int k = d[0] <= d[1] ? (d[0] <= d[2] ? 0 : 2) : (d[1] <= d[2] ? 1 : 2);
    // In double the plane near x is off by about 2^-52 |near|: beyond 2^10 |x| that nears
    // 2^-40 of x, and the offset is computed in double-double
    if (max_abs(*v[k]) > 0x1p10f * max_abs(x))
        return ray_onto_far_plane(x, r, e1, e2, p[k]);
    return ray_onto_plane(x, r, n, glm::dot(p[k], n));
}

float module_error_bound(const Ray& r, float t, const Vec3& x) {
    return 8.0f * std::numeric_limits<float>::epsilon() *
           (max_abs(r.o) + std::abs(t) * max_abs(r.w) + max_abs(x));
}

Vec3 accept_refined(const Vec3& x, const Vec3& refined, const Vec3& n, const Ray& r,
                    float t) {
    if (!is_finite(refined) || !is_finite(n)) return x;
    const double bound = module_error_bound(r, t, x);
    const DVec3 X(x), d = DVec3(refined) - X, w(r.w);
    const double ww = glm::dot(w, w);
    // NaN in any of them keeps x (the comparisons are false)
    const double across_surface = std::abs(glm::dot(d, DVec3(n)));
    const double across_ray =
        ww > 0.0 ? glm::length(glm::cross(X - DVec3(r.o), w)) / std::sqrt(ww) : 0.0;
    const bool agree =
        across_surface <= bound && across_ray <= bound &&
        max_abs(refined - x) <= 0x1p-8f * (max_abs(r.o) + std::abs(t) + max_abs(x));
    return agree ? refined : x;
}

Vec3 unit_normal(const SceneTriangle& t) {
    const DVec3 N = glm::cross(DVec3(t.v1) - DVec3(t.v0), DVec3(t.v2) - DVec3(t.v0));
    const double len = glm::length(N);
    return len > 0.0 ? Vec3(N * (1.0 / len)) : Vec3(0.0f);
}

}  // namespace raylab
