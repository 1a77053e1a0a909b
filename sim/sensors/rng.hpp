// Seeded, library-independent random numbers for sensor noise.
//
// std::normal_distribution and std::log are not specified bit for bit, so the same seed could
// give different noise under another standard library or libm. Here everything reduces to
// integer operations and IEEE-exact double operations (+, -, *, /, sqrt, frexp, ldexp), so a
// seed gives the same stream on every conforming platform (with FP contraction off).
#ifndef SIM_SENSORS_RNG_HPP
#define SIM_SENSORS_RNG_HPP

#include <cstdint>

#include "sensors/xoshiro256.hpp"

namespace sim {

// splitmix64 step: seeds xoshiro and derives independent stream seeds.
std::uint64_t splitmix64(std::uint64_t *state);

// xoshiro256** 1.0 (Blackman & Vigna) with a splitmix64-expanded seed. stream_id selects an
// independent stream for the same user seed (e.g. bias draw vs white noise), so enabling one
// source does not shift the other's samples.
class Rng {
public:
    explicit Rng(std::uint64_t seed = 0u, std::uint64_t stream_id = 0u);
    std::uint64_t next_u64();
    // Uniform on [0, 1) with 53 random bits.
    double uniform();
    // Standard normal, Marsaglia polar method with det_log() (one value per call; the partner
    // value is discarded so the stream does not depend on a hidden cache).
    double gaussian();

private:
    detrng::Xoshiro256ss core_;
};

// Natural log for x > 0 using only exact IEEE operations (frexp decomposition and an atanh
// series); within a few ulp of std::log and identical on every platform. Returns NaN for x <= 0.
double det_log(double x);

}  // namespace sim

#endif
