// The HOLD plant (sim/pd/pd_plant, pd_coupled; spec 40 §2.1, §2.2, §2.6) against independent
// computations written out here: the §2.2 and §2.1 equations integrated by RK4 (the mass matrix
// taken from the equations as written, not from the plant's A), the momentum invariants, a double
// FAST law closed around the single and the coupled plant (§2.1 evidence, A3-7 bound), and the
// sensor / actuator / event hooks of the channel contract.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "pd/pd_model.hpp"
#include "pd/pd_plant.hpp"
#include "pd/pd_section.hpp"
#include "scenario/scenario.hpp"
#include "sensors/rng.hpp"
#include "sim_test.hpp"

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using sim::PdPlant;

constexpr double kTy = 0.25;
constexpr double kTwoPi = 6.283185307179586476925286766559;
constexpr double kLsbM = 1.0 / 1048576.0;   // 2^-20 N m

// ---- spec 40 §2.4, written out (not read from ref::pd::Channel) ----------------------------------
constexpr double kIx[3] = {48100.0, 7700.0, 52600.0};
constexpr double kH = 170.0, kIb = 0.36, kKbd = 2.4, kKbs = 0.12;
struct ModeP {
    int ch;
    double I, r, ratio;
};
const ModeP kModes[4] = {{0, 1630.0, 1.0, 1.00}, {0, 9941.0, 2.32, 1.74}, {1, 4285.0, 1.0, 1.04}, {2, 6130.0, 1.0, 1.13}};

struct Timer {
    std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
    double s() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); }
};

sim::Scenario scenario(const std::string &pd_body, double duration_s = 2000.0)
{
    return sim::parse_scenario("name: t\nmission: hold\nduration_s: " + std::to_string(duration_s) + "\npd: " + pd_body +
                                   "\n",
                               "t.yaml");
}

std::unique_ptr<PdPlant> plant_of(const sim::Scenario &s) { return std::make_unique<PdPlant>(s); }

std::int32_t cnt_of(double m_nm) { return static_cast<std::int32_t>(std::llround(m_nm / kLsbM)); }

sim::ActuatorCmd cmd_of(const std::array<std::int32_t, 3> &c, std::uint32_t seq)
{
    sim::ActuatorCmd a;
    a.seq = seq;
    a.n_ch = 3u;
    for (std::size_t i = 0; i < 3u; ++i) {
        a.cnt[i] = c[i];
    }
    return a;
}

// The arbitrary deterministic torque sequence, in counts (within +-1.2 N m: no clip).
std::array<std::int32_t, 3> torque_seq(long k)
{
    std::array<std::int32_t, 3> c{};
    for (int i = 0; i < 3; ++i) {
        const double kk = static_cast<double>(k), ii = static_cast<double>(i);
        const double m = 0.6 * std::sin(0.21 * kk + ii) + 0.4 * std::cos(0.037 * kk * (1.0 + ii)) +
                         ((k / 7 + i) % 3 == 0 ? 0.2 : -0.1);
        c[static_cast<std::size_t>(i)] = cnt_of(m);
    }
    return c;
}

// One lock-step period: frame, command, propagation.
sim::SensorFrame step(PdPlant &p, const std::array<std::int32_t, 3> &c)
{
    const sim::SensorFrame f = p.sense();
    p.apply(cmd_of(c, f.seq));
    EXPECT_TRUE(p.propagate() == sim::RunState::Running);
    return f;
}

// ---- RK4 on equations written as residuals R(q, q', q'', u) = 0 -----------------------------------
// The equations are linear in q'': the mass matrix is read off them column by column
// (R(0, 0, e_j, 0)), so nothing of the plant's own construction is reused.
using Residual = std::function<VectorXd(const VectorXd &, const VectorXd &, const VectorXd &, const VectorXd &)>;

struct Rk4 {
    Residual R;
    int nd = 0;
    Eigen::PartialPivLU<MatrixXd> lu;
    VectorXd q, qd;

    Rk4(Residual r, int n) : R(std::move(r)), nd(n), q(VectorXd::Zero(n)), qd(VectorXd::Zero(n))
    {
        MatrixXd M(nd, nd);
        const VectorXd z = VectorXd::Zero(nd), u0 = VectorXd::Zero(3);
        for (int j = 0; j < nd; ++j) {
            M.col(j) = R(z, z, VectorXd::Unit(nd, j), u0) - R(z, z, z, u0);
        }
        lu.compute(M);
    }
    VectorXd acc(const VectorXd &qq, const VectorXd &vv, const VectorXd &u) const
    {
        return lu.solve(-R(qq, vv, VectorXd::Zero(nd), u));
    }
    // One sample Ty with u held, n_sub RK4 steps.
    void sample(const VectorXd &u, int n_sub)
    {
        const double h = kTy / n_sub;
        for (int s = 0; s < n_sub; ++s) {
            const VectorXd k1q = qd, k1v = acc(q, qd, u);
            const VectorXd k2q = qd + 0.5 * h * k1v, k2v = acc(q + 0.5 * h * k1q, qd + 0.5 * h * k1v, u);
            const VectorXd k3q = qd + 0.5 * h * k2v, k3v = acc(q + 0.5 * h * k2q, qd + 0.5 * h * k2v, u);
            const VectorXd k4q = qd + h * k3v, k4v = acc(q + h * k3q, qd + h * k3v, u);
            q += h / 6.0 * (k1q + 2.0 * k2q + 2.0 * k3q + k4q);
            qd += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        }
    }
};

// §2.2, channel c alone: dof [x, beta, q_1..q_n]; u(c) is its gimbal torque.
Residual single_eq(int c, double f_hz)
{
    std::vector<ModeP> ms;
    for (const ModeP &m : kModes) {
        if (m.ch == c) {
            ms.push_back(m);
        }
    }
    return [c, f_hz, ms](const VectorXd &q, const VectorXd &v, const VectorXd &a, const VectorXd &u) {
        const Eigen::Index n = static_cast<Eigen::Index>(ms.size());
        VectorXd r(2 + n);
        // Ix x'' + sum I_i q_i'' - H beta' = 0
        r(0) = kIx[c] * a(0) - kH * v(1);
        // Ib beta'' + kbd beta' + kbs beta + H x' = M
        r(1) = kIb * a(1) + kKbd * v(1) + kKbs * q(1) + kH * v(0) - u(c);
        for (Eigen::Index i = 0; i < n; ++i) {
            const ModeP &m = ms[static_cast<std::size_t>(i)];
            const double om = m.ratio * kTwoPi * f_hz;
            r(0) += m.I * a(2 + i);
            // r_i x'' + q_i'' + Omega_i^2 q_i = 0
            r(2 + i) = m.r * a(0) + a(2 + i) + om * om * q(2 + i);
        }
        return r;
    };
}

// §2.1, dof [x_y, x_r, x_p, beta_y, beta_r, beta_p, q_y1, q_y2, q_r, q_p]; sg the coupling sign.
Residual coupled_eq(double f_hz, double sg)
{
    return [f_hz, sg](const VectorXd &q, const VectorXd &v, const VectorXd &a, const VectorXd &u) {
        const double ca = std::cos(kTwoPi / 8.0);
        VectorXd r(10);
        for (int k = 0; k < 3; ++k) {
            double sb = 0.0, sx = 0.0;   // sum_{j != k} beta_j'', x_j''
            for (int j = 0; j < 3; ++j) {
                if (j != k) {
                    sb += a(3 + j);
                    sx += a(j);
                }
            }
            // body k: I_k x_k'' - H beta_k' + a Ib [sg sum beta_j'' + a (2 x_k'' + sum x_j'')] + sum I q'' = 0
            r(k) = kIx[k] * a(k) - kH * v(3 + k) + ca * kIb * (sg * sb + ca * (2.0 * a(k) + sx));
            // gimbal k: Ib beta_k'' + kbd beta_k' + kbs beta_k + sg a Ib sum x_j'' + H x_k' = M_k
            r(3 + k) = kIb * a(3 + k) + kKbd * v(3 + k) + kKbs * q(3 + k) + sg * ca * kIb * sx + kH * v(k) - u(k);
        }
        for (int i = 0; i < 4; ++i) {
            const ModeP &m = kModes[i];
            const double om = m.ratio * kTwoPi * f_hz;
            r(m.ch) += m.I * a(6 + i);
            r(6 + i) = m.r * a(m.ch) + a(6 + i) + om * om * q(6 + i);
        }
        return r;
    };
}

VectorXd u_of(const std::array<std::int32_t, 3> &c)
{
    VectorXd u(3);
    for (int i = 0; i < 3; ++i) {
        u(i) = static_cast<double>(c[static_cast<std::size_t>(i)]) * kLsbM;
    }
    return u;
}

// Truth dof of the plant in the §2.1 order (x, beta, q), from truth().
VectorXd truth_dof(const PdPlant &p)
{
    const std::vector<double> t = p.truth();
    VectorXd d(10);
    for (int i = 0; i < 10; ++i) {
        d(i) = t[static_cast<std::size_t>(i)];
    }
    return d;
}

}  // namespace

// 1. Single plant: ref::pd::discretise propagation (<= 1e-12 rad) and an RK4 of §2.2 (<= 1e-9 rad).
SIM_TEST(single_matches_zoh_and_rk4)
{
    const Timer tm;
    const double f = 0.03;
    const sim::Scenario s = scenario("{plant: single, f_hz: 0.03, x0_rad: [0.004, -0.009, 0.017], sensor: {noise_rad: 0}}");
    auto p = plant_of(s);
    const std::array<double, 3> x0{{0.004, -0.009, 0.017}};
    const ref::pd::Channel chs[3] = {ref::pd::Channel::yaw(), ref::pd::Channel::roll(), ref::pd::Channel::pitch()};
    std::vector<ref::pd::Discrete> d;
    std::vector<VectorXd> sz;
    std::vector<Rk4> rk;
    for (int c = 0; c < 3; ++c) {
        d.push_back(ref::pd::discretise(chs[c], f));
        VectorXd z = VectorXd::Zero(d.back().Ad.rows());
        z(0) = x0[static_cast<std::size_t>(c)];
        sz.push_back(z);
        Rk4 r(single_eq(c, f), static_cast<int>(chs[c].modes.size()) + 2);
        r.q(0) = x0[static_cast<std::size_t>(c)];
        rk.push_back(std::move(r));
    }
    const int qoff[3] = {6, 8, 9};
    double e_zoh = 0.0, e_rk = 0.0;
    for (long k = 0; k < 400; ++k) {
        const std::array<std::int32_t, 3> c = torque_seq(k);
        step(*p, c);
        const VectorXd u = u_of(c);
        const VectorXd t = truth_dof(*p);
        for (int ch = 0; ch < 3; ++ch) {
            sz[static_cast<std::size_t>(ch)] = d[static_cast<std::size_t>(ch)].Ad * sz[static_cast<std::size_t>(ch)] +
                                               d[static_cast<std::size_t>(ch)].Bd * u(ch);
            Rk4 &r = rk[static_cast<std::size_t>(ch)];
            r.sample(u, 64);
            const VectorXd &z = sz[static_cast<std::size_t>(ch)];
            // [x, beta, q..] of the channel against the truth's x_ch, beta_ch, q of the channel
            std::vector<std::pair<int, int>> map{{0, ch}, {1, 3 + ch}};
            for (int i = 0; i < r.nd - 2; ++i) {
                map.emplace_back(2 + i, qoff[ch] + i);
            }
            for (const auto &m : map) {
                e_zoh = std::max(e_zoh, std::fabs(z(m.first) - t(m.second)));
                e_rk = std::max(e_rk, std::fabs(r.q(m.first) - t(m.second)));
            }
        }
    }
    std::printf("  single, 400 samples: max |plant - discretise| = %.3e rad, max |plant - RK4(Ty/64)| = %.3e rad "
                "(%.2f s)\n",
                e_zoh, e_rk, tm.s());
    EXPECT_LE(e_zoh, 1e-12);
    EXPECT_LE(e_rk, 1e-9);
}

// 2. Coupled plant against an RK4 of the §2.1 equations, both coupling signs.
SIM_TEST(coupled_matches_rk4)
{
    const Timer tm;
    for (int sg : {1, -1}) {
        const double f = 0.05;
        const sim::Scenario s = scenario("{plant: coupled, coupling_sign: " + std::to_string(sg) +
                                         ", f_hz: 0.05, x0_rad: [0.004, -0.009, 0.017], sensor: {noise_rad: 0}}");
        auto p = plant_of(s);
        Rk4 r(coupled_eq(f, sg), 10);
        r.q(0) = 0.004;
        r.q(1) = -0.009;
        r.q(2) = 0.017;
        double e = 0.0, cross = 0.0;
        for (long k = 0; k < 400; ++k) {
            const std::array<std::int32_t, 3> c = torque_seq(k);
            step(*p, c);
            r.sample(u_of(c), 64);
            e = std::max(e, (r.q - truth_dof(*p)).cwiseAbs().maxCoeff());
        }
        // The cross terms act: a yaw torque alone moves roll and pitch (sign-dependent).
        const sim::Scenario s0 = scenario("{plant: coupled, coupling_sign: " + std::to_string(sg) +
                                          ", x0_rad: [0, 0, 0], sensor: {noise_rad: 0}}");
        auto p0 = plant_of(s0);
        for (long k = 0; k < 40; ++k) {
            step(*p0, {{cnt_of(0.5), 0, 0}});
            cross = std::max(cross, std::fabs(p0->truth()[1]));
        }
        std::printf("  coupled sign %+d, 400 samples: max |plant - RK4(Ty/64)| = %.3e rad; roll from a yaw torque "
                    "%.3e rad\n",
                    sg, e, cross);
        EXPECT_LE(e, 1e-9);
        EXPECT_TRUE(cross > 1e-9);
    }
    std::printf("  (%.2f s)\n", tm.s());
}

// 3. Momentum invariant per channel (M^d = 0, arbitrary gimbal torques): the integral of each
// body equation, written out.
SIM_TEST(momentum_invariant)
{
    const double ca = std::cos(kTwoPi / 8.0);
    for (int variant = 0; variant < 3; ++variant) {   // single, coupled +1, coupled -1
        const double sg = (variant == 2) ? -1.0 : 1.0;
        const std::string kind = (variant == 0) ? "{plant: single" : "{plant: coupled, coupling_sign: " +
                                                                         std::to_string(static_cast<int>(sg));
        auto p = plant_of(scenario(kind + ", f_hz: 0.02, x0_rad: [0.01, 0.02, -0.017], sensor: {noise_rad: 0}}"));
        const Eigen::Index nd = 10;
        auto L = [&](int k) {
            const VectorXd &s = p->state();
            double l = kIx[k] * s(nd + k) - kH * s(3 + k);   // Ix x' - H beta
            for (int i = 0; i < 4; ++i) {
                if (kModes[i].ch == k) {
                    l += kModes[i].I * s(nd + 6 + i);        // + sum I_i q_i'
                }
            }
            if (variant > 0) {   // + a Ib [sg sum beta_j' + a (2 x_k' + sum x_j')]
                double sb = 0.0, sx = 0.0;
                for (int j = 0; j < 3; ++j) {
                    if (j != k) {
                        sb += s(nd + 3 + j);
                        sx += s(nd + j);
                    }
                }
                l += ca * kIb * (sg * sb + ca * (2.0 * s(nd + k) + sx));
            }
            return l;
        };
        std::array<double, 3> l0{}, dev{}, scale{};
        for (int k = 0; k < 3; ++k) {
            l0[static_cast<std::size_t>(k)] = L(k);
        }
        for (long n = 0; n < 2000; ++n) {
            step(*p, torque_seq(n));
            for (int k = 0; k < 3; ++k) {
                const std::size_t i = static_cast<std::size_t>(k);
                dev[i] = std::max(dev[i], std::fabs(L(k) - l0[i]));
                scale[i] = std::max(scale[i], kH * std::fabs(p->state()(3 + k)));   // |H beta|, the largest term
            }
        }
        for (std::size_t k = 0; k < 3u; ++k) {
            std::printf("  %s ch %zu: max |L - L0| / max |H beta| = %.3e\n", variant == 0 ? "single " : (variant == 1 ? "coupled+" : "coupled-"),
                        k, dev[k] / scale[k]);
            EXPECT_TRUE(scale[k] > 1.0);
            EXPECT_LE(dev[k], 1e-10 * scale[k]);
        }
    }
}

// 4. Closed loop, double FAST law, all channels from x0 = 0.017: coupled vs single (A3-7).
SIM_TEST(coupled_vs_single_closed_loop)
{
    const Timer tm;
    struct Case {
        double f;
        double k2[3];
    };
    const Case cases[2] = {{0.01, {795.0, 135.0, 475.0}}, {0.10, {50.0, 135.0, 75.0}}};
    const double k0 = 2.0, k1[3] = {20.0, 15.0, 20.0};
    const long n = std::lround(2000.0 / kTy);
    auto fly = [&](const std::string &kind, const Case &cs) {
        char fb[32];
        std::snprintf(fb, sizeof fb, "%.3f", cs.f);
        auto p = plant_of(scenario(kind + ", f_hz: " + fb + ", x0_rad: [0.017, 0.017, 0.017], sensor: {noise_rad: 0}}"));
        std::vector<std::array<double, 3>> xs;
        std::array<double, 3> yp{};
        for (long k = 0; k <= n; ++k) {
            std::array<double, 3> y{};
            std::array<std::int32_t, 3> c{};
            for (std::size_t i = 0; i < 3u; ++i) {
                y[i] = p->truth()[i];
                if (k == 0) {
                    yp[i] = y[i];   // y_{-1} = y_0
                }
                const double m = -(k0 * k1[i] * y[i] + k0 * cs.k2[i] * (y[i] - yp[i]) / kTy);
                c[i] = cnt_of(m);
                yp[i] = y[i];
            }
            xs.push_back(y);
            if (k < n) {
                step(*p, c);
            }
        }
        return xs;
    };
    for (const Case &cs : cases) {
        const std::vector<std::array<double, 3>> xs = fly("{plant: single", cs);
        for (int sg : {1, -1}) {
            const std::vector<std::array<double, 3>> xc = fly("{plant: coupled, coupling_sign: " + std::to_string(sg), cs);
            std::array<double, 3> d{};
            for (std::size_t k = 0; k < xs.size(); ++k) {
                for (std::size_t i = 0; i < 3u; ++i) {
                    d[i] = std::max(d[i], std::fabs(xc[k][i] - xs[k][i]));
                }
            }
            std::printf("  f %.2f Hz, sign %+d: max |x_coupled - x_single| yaw %.3e, roll %.3e, pitch %.3e rad\n", cs.f,
                        sg, d[0], d[1], d[2]);
            for (std::size_t i = 0; i < 3u; ++i) {
                EXPECT_LE(d[i], 2e-5);
            }
        }
    }
    std::printf("  (%.2f s)\n", tm.s());
}

// 5a. Attitude and encoder counts, saturation, bias, the per-channel noise streams.
SIM_TEST(sensor_counts)
{
    {
        auto p = plant_of(scenario("{x0_rad: [0.1, -0.2, 0.017], sensor: {noise_rad: 0, bias_rad: [0.001, -0.002, 0]}}"));
        const sim::SensorFrame f = p->sense();
        EXPECT_EQ_INT(f.n_ch, 6);
        EXPECT_EQ_INT(f.cnt[0], std::llround(0.101 * 67108864.0));
        EXPECT_EQ_INT(f.cnt[1], std::llround(-0.202 * 67108864.0));
        EXPECT_EQ_INT(f.cnt[2], std::llround(0.017 * 67108864.0));
        for (std::size_t i = 0; i < 6u; ++i) {
            EXPECT_EQ_INT(f.status[i], 0);
        }
        // Encoders: beta in 2^-24 rad, no noise.
        for (long k = 0; k < 40; ++k) {
            step(*p, torque_seq(k));
        }
        const sim::SensorFrame g = p->sense();
        for (std::size_t i = 0; i < 3u; ++i) {
            const double beta = p->truth()[3 + i];
            EXPECT_TRUE(std::fabs(beta) > 1e-4);
            EXPECT_EQ_INT(g.cnt[3 + i], std::llround(beta * 16777216.0));
            EXPECT_EQ_INT(g.status[3 + i], 0);
        }
    }
    {   // +-0.5 rad: the count saturates at 2^25 with SAT
        auto p = plant_of(scenario("{x0_rad: [0.6, -0.7, 0.4999], sensor: {noise_rad: 0}}"));
        const sim::SensorFrame f = p->sense();
        EXPECT_EQ_INT(f.cnt[0], 33554432);
        EXPECT_EQ_INT(f.status[0], sim::kStatusSat);
        EXPECT_EQ_INT(f.cnt[1], -33554432);
        EXPECT_EQ_INT(f.status[1], sim::kStatusSat);
        EXPECT_EQ_INT(f.status[2], 0);
    }
    {   // the noise: stream k of the seed, one draw per sample, independent of every sigma
        const char *const variants[2] = {"[2.0e-6, 5.0e-5, 0]", "[2.0e-6, 0, 1.0e-5]"};
        std::vector<std::vector<std::int32_t>> yaw(2);
        for (int v = 0; v < 2; ++v) {
            auto p = plant_of(scenario(std::string("{x0_rad: [0.01, 0.02, 0.03], sensor: {seed: 7, noise_rad: ") +
                                       variants[v] + ", bias_rad: [1.0e-4, 0, 0]}}"));
            const std::array<double, 3> sig = v == 0 ? std::array<double, 3>{{2e-6, 5e-5, 0.0}}
                                                     : std::array<double, 3>{{2e-6, 0.0, 1e-5}};
            std::array<sim::Rng, 3> g{{sim::Rng(7u, 0u), sim::Rng(7u, 1u), sim::Rng(7u, 2u)}};
            long bad = 0;
            for (long k = 0; k < 200; ++k) {
                const std::vector<double> t = p->truth();
                const sim::SensorFrame f = step(*p, torque_seq(k));
                for (std::size_t i = 0; i < 3u; ++i) {
                    const double m = t[i] + (i == 0 ? 1e-4 : 0.0) + sig[i] * g[i].gaussian();
                    bad += (f.cnt[i] != std::llround(m * 67108864.0)) ? 1 : 0;
                }
                yaw[static_cast<std::size_t>(v)].push_back(f.cnt[0]);
            }
            EXPECT_EQ_INT(bad, 0);
        }
        EXPECT_TRUE(yaw[0] == yaw[1]);   // roll's and pitch's sigma do not move yaw's noise
    }
}

// 5b. Frozen and offset windows.
SIM_TEST(sensor_windows)
{
    auto base = plant_of(scenario("{x0_rad: [0.01, 0.02, 0.03]}"));
    auto p = plant_of(scenario("{x0_rad: [0.01, 0.02, 0.03], sensor: {frozen: [{t0_s: 2.0, t1_s: 4.0, channel: 1}], "
                               "offset: [{t0_s: 1.0, t1_s: 2.0, channel: 2, rad: 1.0}]}}"));
    std::vector<sim::SensorFrame> fb, fp;
    for (long k = 0; k < 24; ++k) {
        fb.push_back(step(*base, torque_seq(k)));
        fp.push_back(step(*p, torque_seq(k)));
    }
    for (std::size_t k = 0; k < 24u; ++k) {
        EXPECT_EQ_INT(fp[k].cnt[0], fb[k].cnt[0]);   // the other channels untouched
        const bool frozen = k >= 8u && k < 16u;      // samples at [2, 4) s
        EXPECT_EQ_INT(fp[k].cnt[1], frozen ? fb[7].cnt[1] : fb[k].cnt[1]);
        const bool off = k >= 4u && k < 8u;          // [1, 2) s: 1 rad beyond the range
        EXPECT_EQ_INT(fp[k].cnt[2], off ? 33554432 : fb[k].cnt[2]);
        EXPECT_EQ_INT(fp[k].status[2], off ? sim::kStatusSat : 0);
    }
    EXPECT_TRUE(fb[8].cnt[1] != fb[7].cnt[1]);   // the noise would have moved it
}

// 5c. A frequency step at the first boundary at or after t_s: Ad, Bd recomputed, state continuous.
SIM_TEST(frequency_step)
{
    auto p = plant_of(scenario("{f_hz: 0.02, f_steps: [{t_s: 200.1, f_hz: 0.08}], x0_rad: [0, 0, 0.017], "
                               "sensor: {noise_rad: 0}}"));
    const ref::pd::Channel ch = ref::pd::Channel::pitch();
    const ref::pd::Discrete d1 = ref::pd::discretise(ch, 0.02), d2 = ref::pd::discretise(ch, 0.08);
    VectorXd z = VectorXd::Zero(6);
    z(0) = 0.017;
    double e = 0.0;
    std::vector<double> q;
    const long kb = 801;   // 200.25 s
    for (long k = 0; k < 1600; ++k) {
        EXPECT_NEAR(p->truth()[PdPlant::kTruthFHz], k < kb ? 0.02 : 0.08, 0.0);
        const double m = (k < 10 || (k >= kb && k < kb + 10)) ? 0.5 : 0.0;   // a pulse excites the mode
        step(*p, {{0, 0, cnt_of(m)}});
        const ref::pd::Discrete &d = (k < kb) ? d1 : d2;
        z = d.Ad * z + d.Bd * (static_cast<double>(cnt_of(m)) * kLsbM);
        const std::vector<double> t = p->truth();
        e = std::max({e, std::fabs(t[2] - z(0)), std::fabs(t[5] - z(1)), std::fabs(t[9] - z(2))});
        q.push_back(t[9]);
    }
    EXPECT_LE(e, 1e-12);
    bool ev = false;
    for (const sim::TruthEvent &x : p->events()) {
        ev = ev || (x.kind == "F_STEP" && x.seq == kb && std::fabs(x.applied - 0.08) < 1e-15);
    }
    EXPECT_TRUE(ev);
    // The elastic oscillation's period before and after (zero crossings of q_pitch).
    auto period = [&](long a, long b) {
        std::vector<long> zc;
        for (long k = a + 1; k < b; ++k) {
            if ((q[static_cast<std::size_t>(k - 1)] < 0.0) != (q[static_cast<std::size_t>(k)] < 0.0)) {
                zc.push_back(k);
            }
        }
        return zc.size() < 3u ? -1.0 : 2.0 * kTy * static_cast<double>(zc.back() - zc.front()) / static_cast<double>(zc.size() - 1u);
    };
    const double t1 = period(40, kb), t2 = period(kb + 40, 1600);
    std::printf("  q_pitch period %.2f s at 0.02 Hz, %.2f s at 0.08 Hz (ratio %.3f)\n", t1, t2, t1 / t2);
    EXPECT_NEAR(t1 / t2, 4.0, 0.2);
}

// 5d. Kick, latency, clip, a channel at rest, a missing channel, divergence, the truth layout.
SIM_TEST(kick_latency_clip_events)
{
    {   // kick: x += dx at the first boundary at or after t_s (5.1 s -> sample 21)
        auto a = plant_of(scenario("{x0_rad: [0.01, 0.02, 0.03]}"));
        auto b = plant_of(scenario("{x0_rad: [0.01, 0.02, 0.03], kicks: [{t_s: 5.1, dx_rad: [0.001, 0, -0.002]}]}"));
        for (long k = 0; k < 30; ++k) {
            const std::vector<double> ta = a->truth(), tb = b->truth();
            const double dx[3] = {0.001, 0.0, -0.002};
            for (std::size_t i = 0; i < 3u; ++i) {
                if (k < 21) {
                    EXPECT_NEAR(tb[i], ta[i], 0.0);
                } else if (k == 21) {
                    EXPECT_NEAR(tb[i], ta[i] + dx[i], 0.0);
                }
            }
            step(*a, torque_seq(k));
            step(*b, torque_seq(k));
        }
        int kicks = 0;
        for (const sim::TruthEvent &e : b->events()) {
            kicks += (e.kind == "KICK" && e.seq == 21u) ? 1 : 0;
        }
        EXPECT_EQ_INT(kicks, 2);
    }
    for (const char *kind : {"single", "coupled"}) {   // latency: exactly one sample
        auto a = plant_of(scenario(std::string("{plant: ") + kind + "}"));
        auto b = plant_of(scenario(std::string("{plant: ") + kind + ", latency_samples: 1}"));
        bool same = true;
        for (long k = 0; k < 200; ++k) {
            step(*a, k == 0 ? std::array<std::int32_t, 3>{{0, 0, 0}} : torque_seq(k - 1));
            step(*b, torque_seq(k));
            const std::vector<double> ta = a->truth(), tb = b->truth();   // all but extra[6] (the latency)
            same = same && std::equal(ta.begin(), ta.begin() + 16 + PdPlant::kExtraLatency, tb.begin());
        }
        EXPECT_TRUE(same);
    }
    {   // clip at M_max (2 N m): ACT_CLIP on entry; a command without its channel applies zero
        auto p = plant_of(scenario("{x0_rad: [0, 0, 0]}"));
        step(*p, {{0, cnt_of(3.0), cnt_of(-1.0)}});
        step(*p, {{0, cnt_of(3.0), 0}});
        step(*p, {{0, cnt_of(1.0), 0}});
        const sim::SensorFrame f = p->sense();
        EXPECT_NEAR(p->truth()[16 + 1], 1.0, 0.0);
        p->apply(cmd_of({{0, cnt_of(-2.5), 0}}, f.seq));
        p->propagate();
        EXPECT_NEAR(p->truth()[16 + 1], -2.0, 0.0);
        sim::ActuatorCmd one = cmd_of({{cnt_of(0.5), cnt_of(0.5), cnt_of(0.5)}}, f.seq + 1u);
        one.n_ch = 1u;
        (void)p->sense();
        p->apply(one);
        p->propagate();
        EXPECT_NEAR(p->truth()[16 + 0], 0.5, 0.0);
        EXPECT_NEAR(p->truth()[16 + 1], 0.0, 0.0);
        EXPECT_NEAR(p->truth()[16 + 2], 0.0, 0.0);
        std::vector<const sim::TruthEvent *> clips;
        for (const sim::TruthEvent &e : p->events()) {
            if (e.kind == "ACT_CLIP") {
                clips.push_back(&e);
            }
        }
        EXPECT_EQ_INT(clips.size(), 2);
        if (clips.size() == 2u) {
            EXPECT_EQ_INT(clips[0]->channel, 1);
            EXPECT_NEAR(clips[0]->requested, 3.0, 0.0);
            EXPECT_NEAR(clips[0]->applied, 2.0, 0.0);
            EXPECT_EQ_INT(clips[0]->seq, 0);
            EXPECT_NEAR(clips[1]->applied, -2.0, 0.0);
        }
    }
    {   // channels with x0 = 0 and no command stay exactly at rest (single plant)
        auto p = plant_of(scenario("{x0_rad: [0, 0, 0.017]}"));
        bool rest = true;
        for (long k = 0; k < 400; ++k) {
            step(*p, {{0, 0, torque_seq(k)[2]}});
            const VectorXd &s = p->state();
            for (int i : {0, 1, 3, 4, 6, 7, 8, 10, 11, 13, 14, 16, 17, 18}) {
                rest = rest && !(std::fabs(s(i)) > 0.0);   // exactly zero
            }
        }
        EXPECT_TRUE(rest);
        EXPECT_TRUE(std::fabs(p->truth()[2]) > 0.0);
    }
    {   // linear_validity: 0 exactly while some |beta| > 0.5 rad
        auto p = plant_of(scenario("{x0_rad: [0, 0, 0]}"));
        long invalid = 0, wrong = 0;
        for (long k = 0; k < 400; ++k) {
            step(*p, {{0, k < 200 ? cnt_of(2.0) : 0, 0}});
            const std::vector<double> t = p->truth();
            const bool ok = std::fabs(t[3]) <= 0.5 && std::fabs(t[4]) <= 0.5 && std::fabs(t[5]) <= 0.5;
            invalid += ok ? 0 : 1;
            wrong += (t[PdPlant::kTruthLinValid] > 0.5) != ok ? 1 : 0;
        }
        std::printf("  linear_validity 0 on %ld of 400 samples\n", invalid);
        EXPECT_TRUE(invalid > 0);
        EXPECT_EQ_INT(wrong, 0);
    }
    {   // divergence: |x| > 1 rad
        auto p = plant_of(scenario("{x0_rad: [0, 0.9, 0], kicks: [{t_s: 1.0, dx_rad: [0, 0.2, 0]}]}"));
        sim::RunState st = sim::RunState::Running;
        for (long k = 0; k < 10 && st == sim::RunState::Running; ++k) {
            (void)p->sense();
            st = p->propagate();
        }
        EXPECT_TRUE(st == sim::RunState::Diverged);
        EXPECT_TRUE(p->diverged_reason().find("|x|") != std::string::npos);
        EXPECT_TRUE(p->diverged_reason().find("roll") != std::string::npos);
        EXPECT_TRUE(p->propagate() == sim::RunState::Diverged);
    }
    {   // truth layout, seed, period
        const sim::Scenario s = scenario("{plant: coupled, coupling_sign: -1, latency_samples: 1, sensor: {seed: 42}}");
        auto p = plant_of(s);
        EXPECT_EQ_INT(s.period_us, 250000);
        EXPECT_EQ_INT(sim::mission_section("HOLD").noise_seed(s), 42);
        EXPECT_EQ_INT(p->truth().size(), PdPlant::kTruthSize);
        EXPECT_EQ_INT(p->truth_names().size(), PdPlant::kTruthSize);
        std::array<double, 16> st{};
        std::array<double, 8> ex{};
        p->truth_message(st, ex);
        EXPECT_NEAR(st[PdPlant::kTruthX + 2], 0.017, 0.0);
        EXPECT_NEAR(st[PdPlant::kTruthLinValid], 1.0, 0.0);
        EXPECT_NEAR(st[PdPlant::kTruthFHz], 0.03, 0.0);
        EXPECT_NEAR(st[PdPlant::kTruthPlant], -1.0, 0.0);
        EXPECT_NEAR(ex[PdPlant::kExtraLatency], 1.0, 0.0);
        EXPECT_TRUE(p->truth_names()[PdPlant::kTruthLinValid] == "linear_validity");
    }
}

int main()
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(single_matches_zoh_and_rk4), cmocka_unit_test(coupled_matches_rk4),
        cmocka_unit_test(momentum_invariant),         cmocka_unit_test(coupled_vs_single_closed_loop),
        cmocka_unit_test(sensor_counts),              cmocka_unit_test(sensor_windows),
        cmocka_unit_test(frequency_step),             cmocka_unit_test(kick_latency_clip_events),
    };
    return cmocka_run_group_tests_name("pd_plant", tests, nullptr, nullptr);
}
