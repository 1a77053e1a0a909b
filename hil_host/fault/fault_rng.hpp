// fault_rng.hpp — the fault layer's front-end on the project's deterministic generator
// (sim/sensors/xoshiro256.hpp): integer-only decisions, no std::random distributions.
#ifndef HIL_FAULT_RNG_HPP
#define HIL_FAULT_RNG_HPP

#include <cstdint>

#include "sensors/xoshiro256.hpp"

namespace fault {

using detrng::splitmix64;

// The fault layer's front-end on the project's generator: seed words straight from splitmix64
// of the seed, plus integer-only decisions.
class Xoshiro256ss {
public:
    explicit Xoshiro256ss(std::uint64_t seed) : core_(seed) {}
    std::uint64_t next() { return core_.next(); }
    // Uniform in [0, n) for n >= 1 (Lemire's multiply-shift with rejection; unbiased).
    std::uint32_t below(std::uint32_t n)
    {
        if (n <= 1u) {
            (void)next();   // keep the draw count independent of n
            return 0u;
        }
        const std::uint32_t thresh = static_cast<std::uint32_t>(-n) % n;
        for (;;) {
            const std::uint64_t m = (next() >> 32) * n;
            if (static_cast<std::uint32_t>(m) >= thresh) {
                return static_cast<std::uint32_t>(m >> 32);
            }
        }
    }
    // true with probability ppm / 1e6 (one draw every call).
    bool chance_ppm(std::uint32_t ppm) { return below(1000000u) < ppm; }

private:
    detrng::Xoshiro256ss core_;
};

}  // namespace fault

#endif  // HIL_FAULT_RNG_HPP
