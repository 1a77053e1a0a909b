// xoshiro256.hpp — the project's one deterministic integer generator (host side): splitmix64
// and xoshiro256** 1.0 (Blackman & Vigna). Header-only and integer-only, so a seed gives the
// same stream on every platform and standard library. Front-ends: sim::Rng (sensor noise, with
// independent streams and doubles) and fault::Xoshiro256ss (fault injection decisions).
#ifndef SIM_SENSORS_XOSHIRO256_HPP
#define SIM_SENSORS_XOSHIRO256_HPP

#include <cstdint>

namespace detrng {

// One splitmix64 step on x (advances x).
inline std::uint64_t splitmix64(std::uint64_t &x)
{
    std::uint64_t z = (x += UINT64_C(0x9E3779B97F4A7C15));
    z = (z ^ (z >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94D049BB133111EB);
    return z ^ (z >> 31);
}

class Xoshiro256ss {
public:
    // The four state words are successive splitmix64 outputs from splitmix_state.
    explicit Xoshiro256ss(std::uint64_t splitmix_state = 0u)
    {
        std::uint64_t st = splitmix_state;
        for (std::uint64_t &w : s_) {
            w = splitmix64(st);
        }
    }
    std::uint64_t next()
    {
        const std::uint64_t r = rotl(s_[1] * 5u, 7) * 9u;
        const std::uint64_t t = s_[1] << 17;
        s_[2] ^= s_[0];
        s_[3] ^= s_[1];
        s_[1] ^= s_[2];
        s_[0] ^= s_[3];
        s_[2] ^= t;
        s_[3] = rotl(s_[3], 45);
        return r;
    }

private:
    static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
    std::uint64_t s_[4] = {};
};

}  // namespace detrng

#endif  // SIM_SENSORS_XOSHIRO256_HPP
