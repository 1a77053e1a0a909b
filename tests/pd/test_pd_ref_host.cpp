// The fixed-point HOLD law against its double reference (sim/pd/pd_ref), over
// the whole accepted rate range of every boot table (golden values from the reference only).
//
// Tolerance, derived: the reference reads the same table dequantised, K = gain_q16 / 2^12 N m s
// and omega = rate * 2^-20 rad/s exactly; K omega / 2^-16 = gain_q16 * rate / 2^16 is then one
// double product of two exact values (relative error <= 2^-53, below 1e-9 LSB over the range
// here). The flight code rounds the exact value once, half away from zero:
// |u_fixed - u_ref / LSB| <= 1/2 LSB (+ 1e-9 for the double's rounding). Both clamp at u_max_cnt; the limit flag may differ only where the
// reference lies within 1/2 LSB above the limit (rounding brings the flight value onto it).
#include <cmath>
#include <cstdio>

#include "pd/pd_section.hpp"
#include "pd/pd_ref.hpp"
extern "C" {
#include "pd_tables.h"
}
#include "sim_test.hpp"

SIM_TEST(fixed_law_matches_the_reference)
{
    const pd_params_t &p = PD_TBL_DEFAULT;
    const ref::PdTable t = ref::dequantise(p);
    static pd_state_t s;
    pd_init(&s, &p);
    double worst = 0.0;
    unsigned n = 0u, flag_dont_care = 0u;
    const std::int64_t lim = p.rate_max_cnt - 1;
    for (std::int64_t r = -lim; r <= lim; r += 37) {   // ~28 000 rates, both signs, every residue mod 32
        pd_in_t in{static_cast<std::int32_t>(r), true};
        pd_out_t o{};
        pd_step(&s, &p, &in, &o);
        const ref::PdOut ro = ref::pd_law(t, static_cast<double>(r) * sim::kPdRateLsbRadps);
        const double u_ref = ro.tau_nm / sim::kPdTorqueLsbNm;
        const double d = std::fabs(static_cast<double>(o.u_cnt) - u_ref);
        worst = std::fmax(worst, d);
        EXPECT_LE(d, 0.5 + 1e-9);
        const bool lim_fx = (o.health & PD_H_CMD_LIMITED) != 0u;
        if (lim_fx != ro.limited) {
            const double exact = std::fabs(t.k_nms * static_cast<double>(r) * sim::kPdRateLsbRadps) /
                                 sim::kPdTorqueLsbNm;
            EXPECT_LE(exact - static_cast<double>(p.u_max_cnt), 0.5);
            ++flag_dont_care;
        }
        ++n;
    }
    std::printf("%u rates: worst |u_fixed - u_ref| = %.4f LSB (bound 0.5), %u limit flags in the 1/2-LSB window\n", n,
                worst, flag_dont_care);
    EXPECT_TRUE(n > 20000u);
}

int main()
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(fixed_law_matches_the_reference)};
    return cmocka_run_group_tests_name("pd_ref", tests, nullptr, nullptr);
}
