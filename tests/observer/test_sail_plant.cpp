// Plant checks (spec 10 §2.4, §6 S0-1): exact ZOH against the RK4 option, gimbal angles and the
// momentum law, validity stop (DIVERGED), hardware clip events, held commands and determinism.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cstring>
#include <limits>
#include <vector>

#include "observer/sail_plant.hpp"
#include "sim_test.hpp"

using sim::Mat26;
using sim::Mat6;
using sim::Vec2;
using sim::Vec6;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// State-feedback gains of spec 10 §4.2 (designed on the ZOH model at k2_design = 0.0103214).
// Used here only as a convenient, known-good input sequence on the truth state.
Eigen::Matrix<double, 2, 6> gains(int sigma)
{
    Eigen::Matrix<double, 2, 6> d;
    if (sigma > 0) {
        d << 0.77216, 0.08077, 0.00130, -0.19169, -0.05186, 0.01776,  //
            -0.08077, 0.77216, 0.05186, -0.01776, 0.00130, -0.19169;
    } else {
        d << 1.02137, 0.01487, 0.01927, 0.01386, 0.00537, -0.03417,  //
            -0.01487, 1.02137, -0.00537, 0.03417, 0.01927, 0.01386;
    }
    return d;
}

sim::Scenario scenario(int sigma, double duration_s)
{
    sim::Scenario s = sim::sail_default_scenario();
    s.name = "test";
    s.mission_part<sim::SailScenario>().sigma = sigma;
    s.duration_s = duration_s;
    return s;
}

}  // namespace

// S0-1: ZOH against the ODE option over 20 s of closed loop, <= 1e-9 relative. The input
// sequence is u_k = -D x_k computed on the ZOH run and fed identically to the RK4 run, so the
// comparison sees the propagators only. Relative per component: max_k |dx_i| / max_k |x_i|.
SIM_TEST(test_zoh_vs_ode_20s)
{
    for (int sigma : {+1, -1}) {
        sim::Scenario s = scenario(sigma, 20.0);
        sim::SailPlant zoh(s);
        s.mission_part<sim::SailScenario>().propagator = sim::Propagator::Ode;
        sim::SailPlant ode(s);
        const auto d = gains(sigma);
        Vec6 peak = Vec6::Zero();
        Vec6 err = Vec6::Zero();
        sim::RunState st = sim::RunState::Running;
        while (st == sim::RunState::Running) {
            const Vec2 u = -d * zoh.x();
            st = zoh.advance_radps(u);
            (void)ode.advance_radps(u);
            peak = peak.cwiseMax(zoh.x().cwiseAbs());
            err = err.cwiseMax((zoh.x() - ode.x()).cwiseAbs());
        }
        EXPECT_TRUE(st == sim::RunState::Done);
        EXPECT_EQ_INT(zoh.seq(), 1000);
        const double rel = err.cwiseQuotient(peak).maxCoeff();
        std::printf("  %s: ZOH vs RK4 (%u substeps) over 20 s: worst relative %.2e\n", sim::sigma_name(sigma),
                    static_cast<unsigned>(ode.ode_substeps()), rel);
        EXPECT_LE(rel, 1e-9);
        EXPECT_TRUE(zoh.beta_rad() == ode.beta_rad());  // same exact update in both
    }
}

// S0-1 / §2.4 self-test: from w0 = (1, 1) deg/s, bring the platform to rest with u = -D x; the
// momentum then sits in beta: beta_final = -+(J + J_C) w0 / H = (-1.0196, +1.0196) deg, within
// 1e-4 deg. Along the way h_y + H beta_z and h_z - H beta_y stay constant (hdot = -+H bdot).
SIM_TEST(test_final_gimbal_angles)
{
    for (int sigma : {+1, -1}) {
        sim::SailPlant p(scenario(sigma, 600.0));
        const auto d = gains(sigma);
        const Mat6 acl = p.zoh().phi - p.zoh().gamma * d;
        const double rho = Eigen::EigenSolver<Mat6>(acl, false).eigenvalues().cwiseAbs().maxCoeff();
        const Mat26 m = sim::sail_momentum_rows(p.params(), sigma);
        const double hr = p.params().h_rotor_nms();
        const Vec2 h0 = m * p.x();
        double cons = 0.0;
        double peak_beta = 0.0;
        sim::RunState st = sim::RunState::Running;
        while (st == sim::RunState::Running) {
            st = p.advance_radps(-d * p.x());
            const Vec2 hk = m * p.x();
            cons = std::max(cons, std::fabs(hk(0) + hr * p.beta_rad()(1) - h0(0)) / h0.norm());
            cons = std::max(cons, std::fabs(hk(1) - hr * p.beta_rad()(0) - h0(1)) / h0.norm());
            peak_beta = std::max(peak_beta, p.beta_rad().cwiseAbs().maxCoeff());
        }
        EXPECT_TRUE(st == sim::RunState::Done);
        const double jt = p.params().j_true_kgm2() + p.params().jc_kgm2;
        const double expect_deg = jt * 1.0 / hr;  // w0 = 1 deg/s per axis
        const double by = p.beta_rad()(0) / kDeg;
        const double bz = p.beta_rad()(1) / kDeg;
        std::printf("  %s: rho(Phi - Gamma D) = %.6f; beta_final = (%.6f, %.6f) deg, expected (-+%.6f); "
                    "|w| = %.1e deg/s, |mu| = %.1e deg at 600 s; peak |beta| %.3f deg; "
                    "momentum law max rel %.1e\n",
                    sim::sigma_name(sigma), rho, by, bz, expect_deg, p.x().head<2>().norm() / kDeg,
                    std::max(std::fabs(p.x()(sim::kMuY)), std::fabs(p.x()(sim::kMuZ))) / kDeg, peak_beta / kDeg,
                    cons);
        EXPECT_LE(rho, 1.0);
        EXPECT_NEAR(by, -expect_deg, 1e-4);
        EXPECT_NEAR(bz, +expect_deg, 1e-4);
        EXPECT_NEAR(by, -1.0196, 1e-4);  // the printed value
        EXPECT_NEAR(bz, +1.0196, 1e-4);
        EXPECT_LE(cons, 1e-9);
    }
}

// §2.4 validity: a run ends DIVERGED when |w| > 30 deg/s; the state then no longer advances.
// A constant 0.3 rad/s gimbal rate drives w_z at g * 0.3 = 15 rad/s^2 through the rotor
// coupling, so |w| passes 30 deg/s within a few steps.
SIM_TEST(test_divergence_rate)
{
    sim::SailPlant p(scenario(+1, 60.0));
    sim::GimbalActuators act(p.sail().gimbal);
    sim::ActuatorCmd cmd;
    cmd.n_ch = 2u;
    std::uint8_t st0 = 0u;
    cmd.cnt[0] = act.counts(0.3, &st0);
    cmd.cnt[1] = 0;
    EXPECT_EQ_INT(st0, 0);
    sim::RunState st = sim::RunState::Running;
    while (st == sim::RunState::Running) {
        (void)p.sense();
        p.apply(cmd);
        st = p.propagate();
    }
    std::printf("  %s\n", p.diverged_reason().c_str());
    EXPECT_TRUE(st == sim::RunState::Diverged);
    EXPECT_TRUE(p.seq() < 500u);
    EXPECT_TRUE(p.diverged_reason().find("|w_") != std::string::npos);
    const std::uint32_t k = p.seq();
    EXPECT_TRUE(p.propagate() == sim::RunState::Diverged);
    EXPECT_EQ_INT(p.seq(), k);
}

// Tilt beyond 30 deg, and NaN/Inf anywhere in the state, end the run; counts stay defined.
SIM_TEST(test_divergence_tilt_and_nonfinite)
{
    sim::SailPlant p(scenario(-1, 10.0));
    Vec6 x = Vec6::Zero();
    x(sim::kMuZ) = 30.5 * kDeg;
    p.set_state(x, Vec2::Zero());
    EXPECT_TRUE(p.check() == sim::RunState::Diverged);
    EXPECT_TRUE(p.diverged_reason().find("|mu_z|") != std::string::npos);
    x(sim::kMuZ) = 29.5 * kDeg;
    p.set_state(x, Vec2::Zero());
    EXPECT_TRUE(p.check() == sim::RunState::Running);

    x = Vec6::Zero();
    x(sim::kWy) = std::numeric_limits<double>::quiet_NaN();
    x(sim::kWz) = std::numeric_limits<double>::infinity();
    p.set_state(x, Vec2::Zero());
    EXPECT_TRUE(p.check() == sim::RunState::Diverged);
    EXPECT_TRUE(p.diverged_reason().find("non-finite") != std::string::npos);
    // The sensor path must not convert NaN/Inf: counts 0, SAT | NONFINITE.
    const sim::SensorFrame f = p.sense();
    EXPECT_EQ_INT(f.cnt[0], 0);
    EXPECT_EQ_INT(f.cnt[1], 0);
    EXPECT_EQ_INT(f.status[0], sim::kStatusSat | sim::kStatusNonFinite);
    EXPECT_EQ_INT(f.status[1], sim::kStatusSat | sim::kStatusNonFinite);
    p.set_state(Vec6::Zero(), Vec2(std::numeric_limits<double>::quiet_NaN(), 0.0));
    EXPECT_TRUE(p.check() == sim::RunState::Diverged);
}

// §2.4 actuators: hardware clip at 0.35 rad/s per axis, logged as a truth event; exactly at the
// limit is not a clip; counts map to rad/s exactly (LSB 2^-20).
SIM_TEST(test_actuator_clip_event)
{
    sim::SailPlant p(scenario(+1, 10.0));
    sim::ActuatorCmd cmd;
    cmd.n_ch = 2u;
    cmd.cnt[0] = 400000;    // 0.3815 rad/s > 0.35
    cmd.cnt[1] = -1000;     // -9.5e-4 rad/s
    cmd.seq = 0u;
    (void)p.sense();
    p.apply(cmd);
    EXPECT_TRUE(p.propagate() == sim::RunState::Running);
    EXPECT_EQ_INT(p.events().size(), 1);
    if (!p.events().empty()) {
        const sim::TruthEvent &e = p.events()[0];
        EXPECT_TRUE(e.kind == "ACT_CLIP");
        EXPECT_EQ_INT(e.channel, 0);
        EXPECT_EQ_INT(e.seq, 0);
        EXPECT_EQ_INT(e.utime_us, 0);
        EXPECT_NEAR(e.requested, 400000.0 / 1048576.0, 0.0);
        EXPECT_NEAR(e.applied, 0.35, 0.0);
    }
    EXPECT_NEAR(p.bdot_applied_radps()(0), 0.35, 0.0);
    EXPECT_NEAR(p.bdot_applied_radps()(1), -1000.0 / 1048576.0, 0.0);
    // Negative side, and a command exactly representable at the limit is not clipped.
    sim::GimbalActuators act(p.sail().gimbal);
    std::vector<sim::TruthEvent> ev;
    const auto u = act.apply({-367002, 367001}, 5u, 100000, &ev);  // 367001.6 counts = 0.35 rad/s
    EXPECT_EQ_INT(ev.size(), 1);
    EXPECT_NEAR(u[0], -0.35, 0.0);
    EXPECT_NEAR(u[1], 367001.0 / 1048576.0, 0.0);
    // SI -> counts checks happen before the cast.
    std::uint8_t st = 0u;
    EXPECT_EQ_INT(act.counts(std::numeric_limits<double>::quiet_NaN(), &st), 0);
    EXPECT_EQ_INT(st, sim::kStatusSat | sim::kStatusNonFinite);
    EXPECT_EQ_INT(act.counts(1e300, &st), INT32_MAX);
    EXPECT_EQ_INT(st, sim::kStatusSat);
    EXPECT_EQ_INT(act.counts(-0.35, &st), -367002);
    EXPECT_EQ_INT(st, 0);
}

// Clock and held command: t_k = k * period; without a new apply() the last command is held
// (spec 00 §5.2 step 4), and the ZOH step matches Phi x + Gamma u.
SIM_TEST(test_clock_and_held_command)
{
    sim::SailPlant p(scenario(+1, 1.0));
    sim::ActuatorCmd cmd;
    cmd.n_ch = 2u;
    cmd.cnt = {1048, -2096};
    p.apply(cmd);
    const Vec2 u(1048.0 / 1048576.0, -2096.0 / 1048576.0);
    Vec6 x = p.x();
    for (int k = 0; k < 3; ++k) {
        const sim::SensorFrame f = p.sense();
        EXPECT_EQ_INT(f.seq, k);
        EXPECT_EQ_INT(f.utime_us, 20000 * k);
        EXPECT_EQ_INT(f.period_us, 20000);
        (void)p.propagate();
        x = p.zoh().phi * x + p.zoh().gamma * u;
        EXPECT_TRUE(p.x() == x);
    }
    EXPECT_NEAR(p.beta_rad()(0), 3.0 * 0.02 * u(0), 1e-18);
    EXPECT_NEAR(p.beta_rad()(1), 3.0 * 0.02 * u(1), 1e-18);
    // Runs stop at duration: 1 s = 50 steps.
    sim::RunState st = sim::RunState::Running;
    while (st == sim::RunState::Running) {
        st = p.propagate();
    }
    EXPECT_TRUE(st == sim::RunState::Done);
    EXPECT_EQ_INT(p.seq(), 50);
}

// Same scenario and seed twice => bit-identical frames and truth (spec 00 §5.2); another seed
// changes the noise. A small integer feedback closes the loop so commands depend on the counts.
static void run_noisy(std::uint64_t seed, std::vector<std::int32_t> *cnts, std::vector<double> *truth)
{
    sim::Scenario s = scenario(-1, 20.0);
    s.mission_part<sim::SailScenario>().gyro.noise_radps = 1e-5;
    s.mission_part<sim::SailScenario>().gyro.bias_sigma_radps = 1e-6;
    s.mission_part<sim::SailScenario>().gyro.seed = seed;
    sim::SailPlant p(s);
    sim::RunState st = sim::RunState::Running;
    while (st == sim::RunState::Running) {
        const sim::SensorFrame f = p.sense();
        cnts->push_back(f.cnt[0]);
        cnts->push_back(f.cnt[1]);
        sim::ActuatorCmd cmd;
        cmd.seq = f.seq;
        cmd.n_ch = 2u;
        cmd.cnt[0] = -f.cnt[1] / 2;  // rotor follows the body, half gain
        cmd.cnt[1] = f.cnt[0] / 2;
        p.apply(cmd);
        st = p.propagate();
        const std::vector<double> t = p.truth();
        truth->insert(truth->end(), t.begin(), t.end());
    }
}

SIM_TEST(test_determinism)
{
    std::vector<std::int32_t> c1, c2, c3;
    std::vector<double> t1, t2, t3;
    run_noisy(42u, &c1, &t1);
    run_noisy(42u, &c2, &t2);
    run_noisy(43u, &c3, &t3);
    EXPECT_EQ_INT(c1.size(), 2000);
    EXPECT_TRUE(c1 == c2);
    EXPECT_TRUE(t1.size() == t2.size() && std::memcmp(t1.data(), t2.data(), t1.size() * sizeof(double)) == 0);
    EXPECT_TRUE(c1 != c3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_zoh_vs_ode_20s),
        cmocka_unit_test(test_final_gimbal_angles),
        cmocka_unit_test(test_divergence_rate),
        cmocka_unit_test(test_divergence_tilt_and_nonfinite),
        cmocka_unit_test(test_actuator_clip_event),
        cmocka_unit_test(test_clock_and_held_command),
        cmocka_unit_test(test_determinism),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
