// Printing, comparisons and the random generator of the graders (grading.h).
#include "grading.h"

#include <cstdio>
#include <cstdlib>

namespace raylab::grading {

// The shortest of 6..9 significant digits that reads back as the same float
std::string format_float(float x) {
    char buf[32];
    for (int digits = 6; digits <= 9; ++digits) {
        std::snprintf(buf, sizeof buf, "%.*g", digits, static_cast<double>(x));
        if (std::strtof(buf, nullptr) == x || x != x) break;
    }
    return buf;
}

// ---- Printing -------------------------------------------------------------------------

std::string show(double x) {
    return format_float(static_cast<float>(x));
}
std::string show(const Vec2& v) {
    return "(" + format_float(v.x) + ", " + format_float(v.y) + ")";
}
std::string show(const Vec3& v) {
    return "(" + format_float(v.x) + ", " + format_float(v.y) + ", " + format_float(v.z) +
           ")";
}
std::string show(const Ray& r) {
    return "ray o = " + show(r.o) + ", w = " + show(r.w) + ", tmin = " + show(r.tmin) +
           ", tmax = " + show(r.tmax);
}
std::string show(const Plane& p) {
    return "plane n = " + show(p.n) + ", d = " + show(p.d);
}
std::string show(const Sphere& s) {
    return "sphere c = " + show(s.c) + ", r = " + show(s.r);
}
std::string show_triangle(const Vec3& v0, const Vec3& v1, const Vec3& v2) {
    return "triangle v0 = " + show(v0) + ", v1 = " + show(v1) + ", v2 = " + show(v2);
}
std::string show(const std::optional<Hit>& hit) {
    if (!hit) return "a miss (std::nullopt)";
    return "a hit at t = " + show(hit->t) + ", position " + show(hit->position) +
           ", n = " + show(hit->n) + ", uv = " + show(hit->uv);
}
std::string show(const CameraFrame& f) {
    return "x = " + show(f.x) + ", y = " + show(f.y) + ", n = " + show(f.n);
}
std::string show(const PinholeCamera& c) {
    return "camera eye = " + show(c.eye) + ", " + show(c.frame) + ", d = " + show(c.d);
}
std::string show(const PointLight& l) {
    return "light p = " + show(l.p) + ", I = " + show(l.I);
}
std::string show(const LightSample& s) {
    return "wi = " + show(s.wi) + ", r = " + show(s.r) + ", Li = " + show(s.Li);
}
std::string show(const Tile& t) {
    return "tile columns [" + std::to_string(t.x0) + ", " + std::to_string(t.x1) +
           "), rows [" + std::to_string(t.y0) + ", " + std::to_string(t.y1) + ")";
}

// ---- Comparisons ----------------------------------------------------------------------

bool close(double got, double want, double tolerance) {
    return std::abs(got - want) <= tolerance * std::max(1.0, std::abs(want));
}

bool close_abs(const Vec3& got, const Vec3& want, double tolerance) {
    for (int k = 0; k < 3; ++k) {
        if (!(std::abs(double(got[k]) - double(want[k])) <= tolerance)) return false;
    }
    return true;
}

double scale_of(std::initializer_list<Vec3> points, double t) {
    double s = std::max(1.0, std::abs(t));
    for (const Vec3& p : points)
        s = std::max(s, double(glm::length(p)));
    return s;
}

std::string diff_hit(const std::optional<Hit>& got, const std::optional<Hit>& want,
                     double scale, bool check_uv) {
    if (!want && !got) return "";
    if (got && !(std::isfinite(got->t) && std::isfinite(got->position.x) &&
                 std::isfinite(got->position.y) && std::isfinite(got->position.z)))
        return "expected " + show(want) +
               ", got a hit with a non-finite t or position: " + show(got);
    if (!want || !got) return "expected " + show(want) + ", got " + show(got);
    std::string why;
    const std::string within = " (tolerance " + show(tol::kDistance * scale) + ")";
    const auto add = [&](const std::string& what) {
        why += (why.empty() ? "" : "; ") + what;
    };
    if (!(std::abs(double(got->t) - want->t) <= tol::kDistance * scale))
        add("t: expected " + show(want->t) + ", got " + show(got->t) + within);
    if (!close_abs(got->position, want->position, tol::kDistance * scale))
        add("position: expected " + show(want->position) + ", got " +
            show(got->position) + within);
    if (!close_abs(got->n, want->n, tol::kNormal))
        add("n: expected " + show(want->n) + ", got " + show(got->n) + " (tolerance " +
            show(tol::kNormal) + ")");
    if (check_uv) {
        const Vec3 g(got->uv, 0.0f), w(want->uv, 0.0f);
        if (!close_abs(g, w, tol::kBarycentric))
            add("uv (beta, gamma): expected " + show(want->uv) + ", got " +
                show(got->uv) + " (tolerance " + show(tol::kBarycentric) + ")");
    }
    return why;
}

std::string diff_vec(const char* name, const Vec3& got, const Vec3& want,
                     double tolerance) {
    if (close_abs(got, want, tolerance)) return "";
    return std::string(name) + ": expected " + show(want) + ", got " + show(got) +
           " (tolerance " + show(tolerance) + ")";
}

std::string diff_radiance(const char* name, const Vec3& got, const Vec3& want) {
    for (int k = 0; k < 3; ++k) {
        const double g = got[k], w = want[k];
        if (!(std::abs(g - w) <= tol::kRadiance * std::abs(w) + 1e-7))
            return std::string(name) + ": expected " + show(want) + ", got " + show(got) +
                   " (relative tolerance " + show(tol::kRadiance) + " per channel)";
    }
    return "";
}

// ---- Companions ----------------------------------------------------------------------

bool needs_work(const std::string& companion, const std::string& why_not) {
    if (why_not.empty()) return true;
    FAIL_CHECK(
        "this case's answer can be given without doing the work (by a constant or a "
        "table of known answers), so it counts only together with "
        << companion << "; expected those right, but " << why_not);
    return false;
}

// ---- Rng ------------------------------------------------------------------------------

std::uint64_t Rng::next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

float Rng::uniform(float lo, float hi) {
    const float u = static_cast<float>(next() >> 40) * 0x1p-24f;  // [0, 1), 24 bits
    return lo + (hi - lo) * u;
}

int Rng::integer(int lo, int hi) {
    const std::uint64_t span = static_cast<std::uint64_t>(hi - lo) + 1;
    return lo + static_cast<int>(next() % span);
}

Vec3 Rng::in_box(float lo, float hi) {
    const float x = uniform(lo, hi), y = uniform(lo, hi), z = uniform(lo, hi);
    return Vec3(x, y, z);
}

Vec3 Rng::direction() {
    for (;;) {
        const Vec3 v = in_box(-1.0f, 1.0f);
        const float l2 = glm::dot(v, v);
        if (l2 > 1e-4f && l2 <= 1.0f) return v / std::sqrt(l2);
    }
}

Vec3 Rng::direction_near(const Vec3& axis, float min_cos, float max_cos) {
    for (;;) {
        const Vec3 v = direction();
        const float c = glm::dot(v, axis);
        if (c >= min_cos && c <= max_cos) return v;
    }
}

Ray random_ray_through(Rng& rng, const Vec3& p, const Vec3& w, float t) {
    Ray r{p - t * w, w, 0.0f, kInfinity};
    switch (rng.integer(0, 4)) {
        case 1:  // ends before p
            r.tmax = 0.9f * t;
            break;
        case 2:  // starts after p
            r.tmin = 1.1f * t;
            break;
        case 3:  // a window around p
            r.tmin = 0.5f * t;
            r.tmax = 1.5f * t;
            break;
        case 4:  // pointing away from p
            r.w = -w;
            break;
        default:
            break;
    }
    return r;
}

Hit make_hit(float t, const Vec3& position, const Vec3& n, const Vec2& uv) {
    Hit h;
    h.t = t;
    h.position = position;
    h.n = n;
    h.uv = uv;
    return h;
}

}  // namespace raylab::grading
