// fault_rng.hpp — the fault layer's own RNG: splitmix64 seeding xoshiro256**. Integer-only,
// no std::random distributions, so a seed gives the same draws on every platform and library.
#ifndef HIL_FAULT_RNG_HPP
#define HIL_FAULT_RNG_HPP

#include <cstdint>

namespace fault {

inline std::uint64_t splitmix64(std::uint64_t &x)
{
    std::uint64_t z = (x += UINT64_C(0x9E3779B97F4A7C15));
    z = (z ^ (z >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94D049BB133111EB);
    return z ^ (z >> 31);
}

class Xoshiro256ss {
public:
    explicit Xoshiro256ss(std::uint64_t seed)
    {
        std::uint64_t x = seed;
        for (std::uint64_t &w : s_) {
            w = splitmix64(x);
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
    static std::uint64_t rotl(std::uint64_t x, int k)
    {
        return (x << k) | (x >> (64 - k));
    }
    std::uint64_t s_[4] = {};
};

}  // namespace fault

#endif  // HIL_FAULT_RNG_HPP
