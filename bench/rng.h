// bench/rng.h: a small seeded generator (SplitMix64, Steele et al. 2014), so that every
// ray set is reproduced exactly from the seed the bench prints.
#pragma once

#include <cmath>
#include <cstdint>

#include "raylab/math.h"

namespace raylab::bench {

class Rng {
  public:
    /// A generator for one ray set: the master seed mixed with the set's own number.
    Rng(std::uint64_t seed, std::uint64_t stream)
        : state_(seed ^ (stream * 0xD1B54A32D192ED03ull)) {
        next();
    }

    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    /// Uniform in [0, 1), 53 random bits.
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    /// Uniform in [lo, hi).
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    /// Uniform on the unit sphere (Archimedes: z uniform, azimuth uniform).
    DVec3 unit_vector() {
        const double z = uniform(-1.0, 1.0), phi = uniform(0.0, 6.283185307179586);
        const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
        return DVec3(s * std::cos(phi), s * std::sin(phi), z);
    }
    /// Uniform in the cube [-h, h]^3.
    DVec3 in_cube(double h) {
        return DVec3(uniform(-h, h), uniform(-h, h), uniform(-h, h));
    }

  private:
    std::uint64_t state_;
};

/// A unit vector perpendicular to unit vector a (any one, chosen by rng).
inline DVec3 random_perpendicular(Rng& rng, const DVec3& a) {
    for (;;) {
        const DVec3 p = glm::cross(a, rng.unit_vector());
        const double len = glm::length(p);
        if (len > 1e-3) return p / len;
    }
}

}  // namespace raylab::bench
