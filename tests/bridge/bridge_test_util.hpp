// bridge_test_util.hpp — shared helpers for the bridge tests: CMocka includes, a recording fake
// backend, and a deterministic integer gyro-count pattern.
#ifndef TESTS_BRIDGE_TEST_UTIL_HPP
#define TESTS_BRIDGE_TEST_UTIL_HPP

#include <csetjmp>
#include <cstdarg>
#include <cstddef>
#include <cstdint>
#include <vector>

extern "C" {
#include <cmocka.h>   // no extern "C" of its own
}

#include "backend.hpp"
#include "bridge_types.hpp"

namespace bt {

// Recording backend: command counts[0] = seq * 10, counts[1] = counts[0] of the frame seen.
class FakeBackend final : public bridge::Backend {
public:
    bool reset() override { seen.clear(); return true; }
    bool step(const bridge::Frame &f, bridge::StepOutput &out) override
    {
        if (fail_next) {
            fail_next = false;
            return false;
        }
        seen.push_back(f);
        out = bridge::StepOutput{};
        out.n_counts = 2;
        out.counts[0] = static_cast<std::int32_t>(f.seq * 10);
        out.counts[1] = f.counts[0];
        out.fsw_health = 0x80000001u;
        out.tlm_layout_version = 7;
        out.tlm_len = 3;
        out.tlm[0] = 1; out.tlm[1] = 2; out.tlm[2] = 3;
        return true;
    }
    const char *name() const override { return "fake"; }
    bool limits_changed(bridge::SensorLimits &lim) override
    {
        if (!new_limits) {
            return false;
        }
        lim = *new_limits;
        new_limits = nullptr;
        return true;
    }
    std::vector<bridge::Frame> seen;
    bool fail_next = false;
    const bridge::SensorLimits *new_limits = nullptr;   // reported after the next step
};

// Frame k with 2 channels: small, smooth gyro-like counts (triangle waves of +-20 and +-12
// counts, 2^-20 rad/s each), so the open-loop observer stays in its nominal envelope.
inline std::int32_t triangle(std::int64_t k, std::int64_t half_period, std::int64_t amp)
{
    const std::int64_t p = k % (2 * half_period);
    const std::int64_t v = (p < half_period) ? p : (2 * half_period - p);
    return static_cast<std::int32_t>((v * 2 * amp) / half_period - amp);
}

inline bridge::Frame make_frame(std::int64_t k, std::int32_t period_us)
{
    bridge::Frame f{};
    f.seq = k;
    f.utime = k * period_us;
    f.period_us = period_us;
    f.n_counts = 2;
    f.counts[0] = triangle(k, 100, 20);
    f.counts[1] = triangle(k + 37, 70, 12);
    return f;
}

}  // namespace bt

#endif  // TESTS_BRIDGE_TEST_UTIL_HPP
