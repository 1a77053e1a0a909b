// The ADAPTIVE gain source in fixed point: the flight pd_step (pitch channel, FAST, cold start at
// k2_cold, the on-board estimator pd_fest and the §4.2 re-tune rule) closed around the exact discrete
// plant of fly_adaptive (sigma_y = 2e-6 rad, x0 = 0.017 rad, 1 200 s), next to the double design flown
// by fly_adaptive on the same plant and noise. The attitude reaches the flight code as counts of 2^-26
// rad and the torque leaves it in q28 N m, as over the link.
//   A3-5 (reduced, spec §7): f^ within R3 (5 % at 300 s, 10 % at 1 200 s) and t* against the §7
//        reference t*(k2 = 0) / t*(k2 = 150): <= 0.55 x best at <= 0.03 Hz, < best below 0.05 Hz,
//        <= 1.3 best + 10 s above (the bounds of golden_pd_fest_ref, the double design's test);
//   the flight t* agrees with the double design's within 10 % + 2 s (the loops differ by the
//        quantisation of y and M only, but a re-tune one period earlier or later moves t*);
//   a kick (A3-9's 0.017 rad at 600 s): the estimator FAULTs once, k2 goes to k2_cold for that
//        period, and the run still settles.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "pd/pd_fest_quant.hpp"
#include "pd/pd_fest_ref.hpp"
#include "sim_test.hpp"

extern "C" {
#include "pd.h"
#include "pd_mission.h"
#include "pd_tables.h"
}

namespace {

using namespace ref::pd;

const K2Schedule &pitch_schedule()
{
    static const K2Schedule s = load_k2_schedule(std::string(PD_SCHEDULE_DIR) + "/pitch_fast.json");
    return s;
}

const FestParams &pitch_fest()
{
    static const FestParams p = make_fest_params(Channel::pitch());
    return p;
}

pd_params_t adaptive_pitch()
{
    pd_params_t p{};
    pd_params_of(&PD_TBL_DEFAULT, 2u, &p);
    p.g.fest = quantise_fest(pitch_fest());
    p.c.src = static_cast<uint8_t>(PD_SRC_ADAPTIVE);
    return p;
}

struct Flight {
    double t_star = -1.0, f300 = 0.0, f1200 = 0.0;
    int conf300 = 0, retunes = 0, cold_after_fault = 0;
    uint32_t resets = 0u, sticky = 0u;
};

Flight fly_fixed(double f_hz, unsigned seed, double kick_s = -1.0)
{
    const Channel ch = Channel::pitch();
    const pd_params_t p = adaptive_pitch();
    uint32_t why = 0u;
    EXPECT_EQ_INT(pd_params_check(&p, &why), FSW_OK);
    EXPECT_EQ_INT(why, 0);
    pd_state_t s;
    pd_init(&s, &p);
    const Discrete d = discretise(ch, f_hz);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(d.Ad.rows()), xn(d.Ad.rows());
    x(0) = ch.x0;
    const long N = std::lround(1200.0 / ch.Ty);
    const long n_kick = kick_s > 0.0 ? std::lround(kick_s / ch.Ty) : -1;
    std::mt19937_64 rng(seed);  // the noise stream of fly_adaptive with the same seed
    std::normal_distribution<double> noise(0.0, 2e-6);
    std::vector<double> xs;
    xs.reserve(static_cast<std::size_t>(N + 1));
    Flight r;
    uint32_t k2_prev = s.k2_q22;
    for (long n = 0; n <= N; ++n) {
        if (n == n_kick) {
            x(0) += 0.017;
        }
        xs.push_back(x(0));
        if (n == N) {
            break;
        }
        pd_in_t in{};
        in.y_cnt = static_cast<int32_t>(std::lround(std::ldexp(x(0) + noise(rng), 26)));
        in.y_valid = true;
        in.beta_cnt = static_cast<int32_t>(std::lround(std::ldexp(x(1), 24)));
        in.beta_valid = true;
        pd_out_t out{};
        pd_step(&s, &p, &in, &out);
        r.sticky |= out.health;
        if (s.k2_q22 != k2_prev) {
            ++r.retunes;
            k2_prev = s.k2_q22;
        }
        if (s.fest.period_end && s.fest.state == PD_FEST_FAULT) {
            r.cold_after_fault += s.k2_adapt_q22 == p.g.k2_cold_q22 ? 1 : 0;
        }
        const double t = static_cast<double>(n + 1) * ch.Ty;
        if (s.fest.period_end && t <= 300.0 + 1e-9) {
            r.f300 = std::ldexp(static_cast<double>(s.fest.f_hat_q32), -32);
            r.conf300 = s.fest.confident ? 1 : 0;
        }
        if (s.fest.period_end) {
            r.f1200 = std::ldexp(static_cast<double>(s.fest.f_hat_q32), -32);
        }
        xn.noalias() = d.Ad * x + d.Bd * std::ldexp(static_cast<double>(out.m_q28), -28);
        x.swap(xn);
    }
    r.resets = s.fest.resets;
    if (n_kick > 0) {
        r.t_star = settle_time(std::vector<double>(xs.begin() + n_kick, xs.end()), ch.Ty, ch.dx);
    } else {
        r.t_star = settle_time(xs, ch.Ty, ch.dx);
    }
    return r;
}

}  // namespace

SIM_TEST(a35_pitch_fixed_point)
{
    struct Ref {
        double f, t0, t150;  // spec §7: t*(k2 = 0) / t*(k2 = 150)
    };
    const Ref refs[] = {{0.01, 1988.0, 1990.0}, {0.03, 340.0, 384.0}, {0.07, 130.0, 84.0}, {0.10, 95.0, 68.0}};
    for (const Ref &rf : refs) {
        const double best = std::min(rf.t0, rf.t150);
        AdaptiveConfig c;
        c.plant = Channel::pitch();
        c.f_hz = rf.f;
        c.seed = 0u;
        const AdaptiveRun dbl = fly_adaptive(c, pitch_fest(), pitch_schedule());
        const Flight fx = fly_fixed(rf.f, 0u);
        std::printf("  pitch %.2f Hz: fixed t* %.2f s (double %.2f, best constant %.0f), f^(300) %+.4f%s, "
                    "f^(1200) %+.4f, k2 changes %d, estimator resets %u, health sticky 0x%08x\n",
                    rf.f, fx.t_star, dbl.t_star_s, best, fx.f300 / rf.f - 1.0, fx.conf300 != 0 ? " c" : "",
                    fx.f1200 / rf.f - 1.0, fx.retunes, fx.resets, fx.sticky);
        EXPECT_LE(std::fabs(fx.f300 / rf.f - 1.0), 0.05);
        EXPECT_LE(std::fabs(fx.f1200 / rf.f - 1.0), 0.10);
        EXPECT_TRUE(fx.t_star >= 0.0);
        if (rf.f <= 0.03 + 1e-9) {
            EXPECT_LE(fx.t_star, 0.55 * best);
        }
        if (rf.f < 0.05) {
            EXPECT_TRUE(fx.t_star < best);
        } else {
            EXPECT_LE(fx.t_star, 1.3 * best + 10.0);
        }
        EXPECT_LE(std::fabs(fx.t_star - dbl.t_star_s), 0.1 * dbl.t_star_s + 2.0);
        EXPECT_TRUE(fx.retunes > 0);
        EXPECT_EQ_INT(fx.resets, 0);
        EXPECT_EQ_INT(fx.sticky & FX_ST_MASK, 0);
    }
}

SIM_TEST(kick_fault_cold_gain)
{
    const Flight fx = fly_fixed(0.03, 1u, 600.0);
    std::printf("  pitch 0.03 Hz, 0.017-rad kick at 600 s: resets %u, periods at k2_cold in FAULT %d, t* after the "
                "kick %.2f s, health sticky 0x%08x\n",
                fx.resets, fx.cold_after_fault, fx.t_star, fx.sticky);
    EXPECT_EQ_INT(fx.resets, 1);
    EXPECT_EQ_INT(fx.cold_after_fault, 1);
    EXPECT_TRUE((fx.sticky & PD_H_FEST_FAULT) != 0u);
    EXPECT_TRUE(fx.t_star >= 0.0);
}

// Who may fly ADAPTIVE: a block with a section count other than 1 or 2 is refused (yaw's two pass), a
// Ty other than 0.25 s is refused, and SET_SOURCE ADAPTIVE leaves such a channel on its source.
SIM_TEST(adaptive_refusals)
{
    pd_params_t p = adaptive_pitch();
    uint32_t why = 0u;
    EXPECT_EQ_INT(pd_params_check(&p, &why), FSW_OK);
    p.g.fest = quantise_fest(make_fest_params(Channel::yaw()));
    EXPECT_EQ_INT(pd_params_check(&p, &why), FSW_OK);
    p.g.fest.n_sec = 3u;
    EXPECT_EQ_INT(pd_params_check(&p, &why), FSW_ERR_RANGE);
    EXPECT_EQ_INT(why, PD_WHY_MODE);
    p = adaptive_pitch();
    p.c.period_us = 125000u;
    p.c.n_div = 2u;   // Ty still 0.25 s: accepted
    EXPECT_EQ_INT(pd_params_check(&p, &why), FSW_OK);
    p.c.n_div = 1u;   // Ty 0.125 s
    p.c.inv_ty_q22 = 8u << 22;
    (void)pd_params_check(&p, &why);
    EXPECT_TRUE((why & PD_WHY_MODE) != 0u);
    pd_params_t y{};
    pd_params_of(&PD_TBL_DEFAULT, 0u, &y);
    y.g.fest = quantise_fest(make_fest_params(Channel::yaw()));
    y.g.fest.n_sec = 3u;
    pd_state_t s;
    pd_init(&s, &y);
    EXPECT_TRUE(!pd_set_source(&s, &y, static_cast<uint8_t>(PD_SRC_ADAPTIVE)));
    EXPECT_EQ_INT(s.src, PD_SRC_FIXED);
    p = adaptive_pitch();
    p.c.src = static_cast<uint8_t>(PD_SRC_FIXED);
    pd_init(&s, &p);
    EXPECT_TRUE(pd_set_source(&s, &p, static_cast<uint8_t>(PD_SRC_ADAPTIVE)));
    EXPECT_EQ_INT(s.k2_adapt_q22, p.g.k2_cold_q22);
}

int main()
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(a35_pitch_fixed_point), cmocka_unit_test(kick_fault_cold_gain),
                                       cmocka_unit_test(adaptive_refusals)};
    return cmocka_run_group_tests_name("pd_adaptive_host", tests, nullptr, nullptr);
}
