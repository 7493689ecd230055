// The reference's triangle test as the module computes it (solutions/05_triangle.cpp)
// and as the engine's kernel does (engine_kernels.h: triangle_t, with either way of
// choosing the ray's axes), compared bit for bit on adversarial inputs: integer
// coordinates (rays exactly through vertices and edges), axis-aligned and tied
// directions with signed zeros, thin triangles that nearly contain the ray (where pbrt's
// bound on t decides), origins on the plane, scales from 2^-140 to 2^120, unnormalised
// directions, degenerate triangles, infinities and NaN.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <optional>
#include <random>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "engine_kernels.h"
#include "raylab/contract.h"
#include "raylab/refine.h"  // unit_normal

using namespace raylab;

namespace {

std::string text(const Ray& r, const Vec3 v[3]) {
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "o (%a, %a, %a) w (%a, %a, %a) tmin %a tmax %a v0 (%a, %a, %a) "
                  "v1 (%a, %a, %a) v2 (%a, %a, %a)",
                  r.o.x, r.o.y, r.o.z, r.w.x, r.w.y, r.w.z, r.tmin, r.tmax, v[0].x,
                  v[0].y, v[0].z, v[1].x, v[1].y, v[1].z, v[2].x, v[2].y, v[2].z);
    return buf;
}

bool same_bits(float a, float b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

bool same_hit(const std::optional<Hit>& a, const std::optional<Hit>& b) {
    if (a.has_value() != b.has_value()) return false;
    if (!a) return true;
    bool same = same_bits(a->t, b->t) && a->material == b->material &&
                same_bits(a->uv.x, b->uv.x) && same_bits(a->uv.y, b->uv.y);
    for (int k = 0; k < 3; ++k) {
        same = same && same_bits(a->position[k], b->position[k]) &&
               same_bits(a->n[k], b->n[k]) && same_bits(a->ns[k], b->ns[k]);
    }
    return same;
}

// The adversarial inputs, seeded
class Cases {
  public:
    explicit Cases(std::uint64_t seed) : g_(seed) {}
    double uniform(double a, double b) {
        return std::uniform_real_distribution<>(a, b)(g_);
    }
    int integer(int a, int b) { return std::uniform_int_distribution<>(a, b)(g_); }
    bool coin() { return integer(0, 1) == 1; }

    float special() {
        static const float s[] = {0.0f,   -0.0f,   1.0f,    -1.0f,          0.5f,
                                  2.0f,   1e-45f,  -1e-45f, 1e-38f,         1e38f,
                                  -1e38f, 3.4e38f, 1e-20f,  1e20f,          0.25f,
                                  0.75f,  3.0f,    -3.0f,   1.17549435e-38f};
        return s[integer(0, int(sizeof s / sizeof *s) - 1)];
    }
    float coord(int mode) {
        switch (mode) {
            case 0:
                return float(integer(-3, 3));  // exact vertices and edges
            case 1:
                return float(uniform(-1, 1));
            case 2:
                return special();
            case 3:
                return float(uniform(-1, 1) * std::pow(10.0, uniform(-40, 38)));
            case 4:
                return float(integer(-2, 2)) * 0.5f;
            default:
                return float(uniform(-1e-3, 1e-3)) + 1.0f;
        }
    }
    Vec3 vec(int mode) {
        const float x = coord(mode), y = coord(mode);
        return Vec3(x, y, coord(mode));
    }
    Vec3 direction(int mode) {
        switch (integer(0, 5)) {
            case 0: {  // along an axis, the other components +-0
                Vec3 w(0.0f);
                const int k = integer(0, 2);
                w[k] = coin() ? 1.0f : -1.0f;
                for (int j = 0; j < 3; ++j)
                    if (j != k) w[j] = coin() ? 0.0f : -0.0f;
                return w;
            }
            case 1: {  // ties between components, and zero
                const float x = float(integer(-1, 1)), y = float(integer(-1, 1));
                return Vec3(x, y, float(integer(-1, 1)));
            }
            case 2:
                return vec(mode);
            case 3: {
                const double x = uniform(-1, 1), y = uniform(-1, 1);
                return Vec3(glm::normalize(DVec3(x, y, uniform(-1, 1))));
            }
            case 4:
                return vec(3);
            default: {
                const float x = float(integer(-2, 2)), y = float(integer(-2, 2));
                Vec3 w(x, y, float(integer(-2, 2)));
                w[integer(0, 2)] = special();
                return w;
            }
        }
    }
    // One case: ray r and triangle v
    void next(Ray& r, Vec3 v[3]) {
        const int mode = integer(0, 5), kind = integer(0, 11);
        r = Ray{vec(mode), direction(mode), 0.0f, kInfinity};
        for (int k = 0; k < 3; ++k)
            v[k] = vec(mode);
        if (integer(0, 3) == 0) {
            r.tmin = float(uniform(0, 2));
            r.tmax = float(uniform(0, 10));
        }
        const auto aim = [&](const DVec3& p) {
            const DVec3 d = p - DVec3(r.o);
            if (glm::length(d) > 0) r.w = Vec3(glm::normalize(d));
        };
        const DVec3 a(v[0]), b(v[1]), c(v[2]);
        switch (kind) {
            case 0:  // a repeated vertex
                v[1] = v[0];
                break;
            case 1:  // collinear
                v[2] = v[0] + 2.0f * (v[1] - v[0]);
                break;
            case 2:  // at a vertex or an edge's midpoint
                aim(coin() ? a : 0.5 * (b + c));
                break;
            case 3: {  // a thin triangle nearly containing the ray: pbrt's bound decides
                r = Ray{Vec3(0.0f), Vec3(0.0f, 0.0f, coin() ? 1.0f : -1.0f), 0.0f,
                        kInfinity};
                const float e = float(std::pow(10.0, uniform(-40, -1)));
                const float z0 = float(uniform(-2, 3)), z1 = float(uniform(-2, 3));
                const float z2 = float(uniform(-2, 3));
                v[0] = Vec3(-1.0f, -e, z0);
                v[1] = Vec3(1.0f, -e, z1);
                v[2] = Vec3(float(uniform(-1, 1)), e * float(uniform(0.5, 3)), z2);
                if (coin()) std::swap(v[0], v[1]);
                const int turns = integer(0, 2);  // the axes rotated
                const auto rotate = [turns](Vec3& p) {
                    for (int j = 0; j < turns; ++j)
                        p = Vec3(p.z, p.x, p.y);
                };
                rotate(r.o), rotate(r.w);
                for (int k = 0; k < 3; ++k)
                    rotate(v[k]);
                if (coin()) {
                    const float s = float(std::pow(2.0, integer(-60, 60)));
                    for (int k = 0; k < 3; ++k)
                        v[k] *= s;
                }
                break;
            }
            case 4: {  // along an axis from an integer point
                const float x = float(integer(-2, 2)), y = float(integer(-2, 2));
                r.o = Vec3(x, y, float(integer(-2, 2)));
                Vec3 w(0.0f);
                const int k = integer(0, 2);
                w[k] = coin() ? 1.0f : -1.0f;
                w[(k + 1) % 3] = coin() ? 0.0f : -0.0f;
                r.w = w;
                break;
            }
            case 5:  // in the triangle's plane
                r.o = v[0];
                r.w = Vec3(glm::normalize(b - a));
                break;
            case 6:  // at the centroid
                aim((a + b + c) / 3.0);
                break;
            case 7: {  // from just off the plane (t near 0), towards it or away
                const double s = std::sqrt(uniform(0, 1)), t = uniform(0, 1);
                const DVec3 p = (1.0 - s) * a + s * (1.0 - t) * b + s * t * c;
                DVec3 n = glm::cross(b - a, c - a);
                if (!(glm::length(n) > 0)) break;
                n = glm::normalize(n);
                const double size = std::abs(p.x) + std::abs(p.y) + std::abs(p.z) + 1e-30;
                const double eps =
                    std::pow(10.0, -uniform(0, 12)) * (coin() ? 1 : -1) * size;
                r.o = Vec3(p + eps * n);
                DVec3 d = p - DVec3(r.o);
                const double jx = uniform(-1, 1), jy = uniform(-1, 1);
                d += 1e-3 * eps * DVec3(jx, jy, uniform(-1, 1));
                if (integer(0, 3) == 0) d = -d;
                if (glm::length(d) > 0) r.w = Vec3(glm::normalize(d));
                break;
            }
            case 8: {  // at the centroid, everything scaled, w too long or short
                aim((a + b + c) / 3.0);
                const float s = float(std::pow(2.0, integer(-140, 120)));
                for (int k = 0; k < 3; ++k)
                    v[k] *= s;
                r.o *= s;
                if (coin()) r.w *= float(std::pow(2.0, integer(-120, 120)));
                break;
            }
            case 9: {  // an infinity or a NaN somewhere
                float bad = coin() ? kInfinity : NAN;
                if (coin()) bad = -bad;
                Vec3* where[5] = {&r.o, &r.w, &v[0], &v[1], &v[2]};
                (*where[integer(0, 4)])[integer(0, 2)] = bad;
                break;
            }
            default:
                break;
        }
    }

  private:
    std::mt19937_64 g_;
};

// The module's Hit as the engine builds it from its kernel (engine_kernels.h:
// triangle_t, then finish_hit's t, position, normal and uv), with the ray's axes chosen
// by branches (the any-hit query's WoopRay) or without (the closest-hit query's)
std::optional<Hit> engine_hit(const Ray& r, const Vec3 v[3], bool unpredictable) {
    namespace kernels = reference::engine_kernels;
    const kernels::WoopRay q =
        unpredictable ? kernels::WoopRay(r, kernels::WoopRay::Unpredictable{})
                      : kernels::WoopRay(r);
    const SceneTriangle tri{v[0], v[1], v[2], 0};
    const Vec3 n = unit_normal(tri);
    kernels::TriangleExtra extra;
    const float t =
        kernels::triangle_t(r, q, v[0], v[1], v[2], n == Vec3(0.0f), r.tmax, extra);
    if (std::isnan(t)) return std::nullopt;
    Hit hit;
    hit.t = t;
    hit.position = r.o + t * r.w;
    hit.n = n;
    hit.uv = extra.uv;
    return hit;
}

}  // namespace

TEST_SUITE("kernels") {
    TEST_CASE(
        "the module's and the engine's triangle tests give the same hits bit for bit") {
        Cases cases(20261125);
        int hits = 0, differ = 0;
        for (int k = 0; k < 400000; ++k) {
            Ray r;
            Vec3 v[3];
            cases.next(r, v);
            const auto a = reference::intersect_triangle(r, v[0], v[1], v[2]);
            hits += a.has_value();
            for (const bool unpredictable : {false, true}) {
                const auto b = engine_hit(r, v, unpredictable);
                if (!same_hit(a, b) && ++differ <= 5) {
                    INFO("case " << k << ", unpredictable " << unpredictable << ": "
                                 << text(r, v));
                    CHECK(same_hit(a, b));
                }
            }
        }
        CHECK(differ == 0);
        CHECK(hits > 40000);  // the cases reach the hit path, not only the rejections
    }
}
