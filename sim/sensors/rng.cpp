#include "sensors/rng.hpp"

#include <cmath>
#include <limits>

namespace sim {

std::uint64_t splitmix64(std::uint64_t *state) { return detrng::splitmix64(*state); }

namespace {
// Mix the stream id in through a second splitmix so that (seed, stream) pairs never collide
// for small integers.
std::uint64_t stream_state(std::uint64_t seed, std::uint64_t stream_id)
{
    std::uint64_t mix = stream_id;
    return seed ^ detrng::splitmix64(mix);
}
}  // namespace

Rng::Rng(std::uint64_t seed, std::uint64_t stream_id) : core_(stream_state(seed, stream_id)) {}

std::uint64_t Rng::next_u64() { return core_.next(); }

double Rng::uniform()
{
    // Top 53 bits scaled by 2^-53: exact, in [0, 1).
    return static_cast<double>(next_u64() >> 11) * 0x1.0p-53;
}

double Rng::gaussian()
{
    for (;;) {
        const double u = 2.0 * uniform() - 1.0;
        const double v = 2.0 * uniform() - 1.0;
        const double s = u * u + v * v;
        if (s > 0.0 && s < 1.0) {
            return u * std::sqrt(-2.0 * det_log(s) / s);
        }
    }
}

double det_log(double x)
{
    if (!(x > 0.0) || !std::isfinite(x)) {
        return std::numeric_limits<double>::quiet_NaN();
    }
    int e = 0;
    double m = std::frexp(x, &e);  // x = m * 2^e, m in [0.5, 1), exact
    if (m < 0.70710678118654752440) {
        m *= 2.0;  // exact
        e -= 1;
    }
    // m in [sqrt(1/2), sqrt(2)): ln m = 2 atanh(t), |t| <= 0.1716, t^2 <= 0.0295.
    const double t = (m - 1.0) / (m + 1.0);
    const double t2 = t * t;
    // Horner over 1/(2k+1), k = 0..12: the first omitted term is below 0.0295^13/27 ~ 5e-22.
    double sum = 1.0 / 25.0;
    for (int k = 11; k >= 0; --k) {
        sum = sum * t2 + 1.0 / static_cast<double>(2 * k + 1);
    }
    // ln 2 split so that e * ln2_hi is exact for |e| < 2^11.
    const double ln2_hi = 6.93147180369123816490e-01;
    const double ln2_lo = 1.90821492927058770002e-10;
    const double de = static_cast<double>(e);
    return de * ln2_hi + (2.0 * t * sum + de * ln2_lo);
}

}  // namespace sim
