// obs_golden_gen — build-time golden vectors of the observer from its double reference (spec 00
// §6.4, 10-observer §5). Run by a custom command of host builds only (golden_vectors() of
// tests/golden/CMakeLists.txt); writes a C header of const integer arrays into the build tree
// (never committed):
//
//   gv_obs_vectors.h   observer single-step sets of the three runs spec 10 S0-8 names: S0-5
//                      nominal and S0-5 gyro noise seed 0 (M-paper, OBS_TBL_50HZ_PAPER), S0-7
//                      nominal (M-phys, OBS_TBL_50HZ_PHYS); and the S0-9 authority case (S0-5
//                      nominal with the command vector-limited at 1.2 deg/s), whose vectors
//                      carry CMD_LIMITED / CMD_LIMIT_PERSIST, so the flag comparison sees set bits
//
//   obs_golden_gen --scenarios <sim/observer/scenarios> --out <dir>      (command line: CLI11; --help)
//
// The double reference (sim/observer/obs_ref) runs in closed loop with the exact plant
// (sim::SailPlant, as the reference FSW backend hil_host/bridge/ref_backend.cpp does: initialise
// from the first complete sample, then one reference step per sample, the plant holding the
// command counts). At each selected step n the reference state is quantised to the flight
// formats (x-hat q29, kappa q28, P_s q30 upper triangle, residual q29, previous command); one
// reference step from exactly that (dequantised) state on the step's gyro counts gives the
// outputs, so the fixed-point replay, loaded with the same integers, differs by arithmetic
// rounding only. The per-step bounds are computed here from that step's operands (gains,
// transition matrices, state), following the derivation in tests/observer/test_obs_golden_replay.c.
//
// Selection: every step of the first DENSE = 200 (0-4 s: the initialising sample, the collapse
// of P from P0, the largest gains and innovations), then every STRIDE-th step to the end of the
// scenario (S0-5: 30 = 0.6 s over 120 s; S0-7: 150 = 3 s over 600 s), which samples the K-hat
// transient, the peaks of mu and of the command (M-phys: 5.8 deg/s near 10-40 s), settling and
// the limit cycle. Single-step vectors are independent of each other, so a strided set covers
// the trajectory's whole operating range at a fraction of the image size.
//
// The emitter, the record CRC and the command line are tests/golden/gen/gv_emit.hpp's.
#include "gv_emit.hpp"
#include "observer/obs_ref.hpp"
#include "observer/sail_plant.hpp"
#include "scenario/scenario.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

extern "C" {
#include "gv_obs.h"
#include "obs_tables.h"
}

static_assert(sizeof(gv_obs_t) == 98u * 4u, "gv_obs_t: the emitter writes 98 words");

namespace {

using gv::Emit;
using gv::header_top;
using gv::hex32;
using gv::ibound;
using gv::inf_norm;
using gv::qnt;
using gv::Q28;
using gv::Q29;
using gv::Q30;
using gv::set_crc;
using gv::write_file;

const gv::Origin kOrigin{"obs_golden_gen", "tests/observer/gen/obs_golden_gen.cpp", "sim/observer", "gv_obs.h"};

constexpr double kTie = 1e-6;   // relative distance to a decision threshold treated as a tie

struct ObsSetCfg {
    const char *name;        // C identifier suffix and digest name
    const char *file;        // scenario file in sim/observer/scenarios
    const char *table_name;
    const obs_params_t *tab;
    uint32_t dense, stride;
    double bdot_max_degps;   // command vector limit override (0: the table's), as the SIL boot table
};

struct ObsSetStats {
    uint32_t n = 0, dc = 0, dc_bits = 0, limited = 0, init = 0, flagged = 0, flags = 0;
    double bx0_min = 1e300, bx0_max = 0, bk_max = 0, bp0_min = 1e300, bp0_max = 0, bp1_max = 0, bx1_max = 0;
};

// obs_state_t loaded from quantised values (the integers both sides start from).
struct QState {
    std::array<int32_t, 6> x{};
    int32_t kappa = 0;
    std::array<int32_t, GV_P_UPPER> p{};
    std::array<int32_t, 2> qres{}, u_prev{};
};

ref::ObsState dequant(const QState &q)
{
    obs_state_t s{};
    for (size_t i = 0; i < 6; ++i) { s.x_q29[i] = q.x[i]; }
    s.kappa_q28 = q.kappa;
    size_t m = 0;
    for (size_t i = 0; i < 7; ++i) {
        for (size_t j = i; j < 7; ++j, ++m) {
            s.p_q30[i * 7 + j] = q.p[m];
            s.p_q30[j * 7 + i] = q.p[m];
        }
    }
    s.qres_q29[0] = q.qres[0];
    s.qres_q29[1] = q.qres[1];
    return ref::from_fixed(s);
}

QState quantise(const ref::ObsState &st, const std::array<int32_t, 2> &u_prev_cnt, unsigned act_shift)
{
    QState q;
    for (size_t i = 0; i < 6; ++i) { q.x[i] = qnt(st.x(static_cast<Eigen::Index>(i)), 29); }
    q.kappa = qnt(st.kappa, 28);
    size_t m = 0;
    for (Eigen::Index i = 0; i < 7; ++i) {
        for (Eigen::Index j = i; j < 7; ++j, ++m) { q.p[m] = qnt(st.p(i, j), 30); }
    }
    for (size_t i = 0; i < 2; ++i) {
        q.qres[i] = qnt(st.qres(static_cast<Eigen::Index>(i)), 29);
        q.u_prev[i] = static_cast<int32_t>(static_cast<int64_t>(u_prev_cnt[i]) * (int64_t{1} << act_shift));
    }
    return q;
}

// obs_ref does not expose the intermediates of its step, so the generator repeats the
// reference's measurement update (sequential scalar channels, exactly as obs_ref.cpp) from the
// step's state: the post-update z = [x; kappa] (before the kappa clamp), the covariance (before
// the diagonal clip) and the normalised innovations d^2 of the two channels.
struct RefUpdate {
    Eigen::Matrix<double, 7, 1> z;
    Eigen::Matrix<double, 7, 7> p;
    Eigen::Matrix<double, 7, 2> gain;
    std::array<double, 2> d2{}, e{}, sn{};
};

RefUpdate ref_update(const ref::ObsTable &rt, const ref::ObsState &rs, const std::array<int32_t, 2> &y)
{
    RefUpdate r;
    r.z << rs.x, rs.kappa;
    r.p = rs.p;
    for (int c = 0; c < 2; ++c) {
        const double e = y[static_cast<size_t>(c)] * rt.gyro_lsb - r.z(c);
        const double sn = r.p(c, c) + rt.r;
        const double es = e / rt.s(c);
        r.d2[static_cast<size_t>(c)] = es * es / sn;
        r.e[static_cast<size_t>(c)] = e;
        r.sn[static_cast<size_t>(c)] = sn;
        const Eigen::Matrix<double, 7, 1> l = r.p.col(c) / sn;
        const Eigen::Matrix<double, 1, 7> row = r.p.row(c);
        r.gain.col(c) = l;
        for (int j = 0; j < 7; ++j) { r.z(j) += l(j) * e * rt.s(j) / rt.s(c); }
        r.p -= l * row;
    }
    return r;
}

// Flags of the step the flight code must raise, decided on the reference's values; the
// prediction's diagonal comes from the reference's own F_s. A decision whose reference value
// lies within the fixed-point error of its threshold is a don't-care bit; the windows come from
// the step's bounds (v.bx, v.bk, v.bp, computed first): kappa clamp bk LSB_k; covariance clip
// bp LSB_P; command limit max_i sum_k |D_ik| dx_k + 1 LSB_x (dx_k <= 1 + amp_k after the
// update); d^2 = e_s^2 / S: d^2 (2 r + r^2 + dS/S) with r = de/|e| (de <= 1 LSB_x, dS <= bp LSB_P)
// plus 4 LSB of q16 for its own division; never below a relative 1e-6 of the threshold.
void expected_flags(const obs_params_t &tab, const ref::ObsTable &rt, const RefUpdate &ru, const ref::ObsStepOut &ro,
                    uint32_t limited_run, const gv_obs_t &v, uint32_t &health, uint32_t &dc)
{
    health = 0u;
    dc = 0u;
    auto decide = [&](double val, double thr, double win, bool above, uint32_t bit) {
        if (std::fabs(val - thr) <= std::max(win, kTie * std::fabs(thr))) {
            dc |= bit;
        } else if (above ? (val > thr) : (val < thr)) {
            health |= bit;
        }
    };
    const double lsb_x = 1.0 / Q29, lsb_p = v.bp[0] / Q30;
    const double d2max = tab.d2_max_q16 / 65536.0;
    for (size_t c = 0; c < 2; ++c) {
        const double re = lsb_x / std::max(std::fabs(ru.e[c]), lsb_x);   // relative innovation error
        const double rel = 2.0 * re + re * re + lsb_p / ru.sn[c];
        decide(ru.d2[c], d2max, ru.d2[c] * rel + 4.0 / 65536.0, true, OBS_H_INNOV_HIGH);
    }
    decide(ru.z(6), rt.kappa_lo, v.bk / Q28, false, OBS_H_K_CLAMP_LO);
    decide(ru.z(6), rt.kappa_hi, v.bk / Q28, true, OBS_H_K_CLAMP_HI);
    Eigen::Matrix<double, 7, 7> p = ru.p;
    for (int i = 0; i < 7; ++i) {
        decide(p(i, i), rt.p_floor, lsb_p, false, OBS_H_COV_CLIP);
        decide(p(i, i), rt.p_ceil, lsb_p, true, OBS_H_COV_CLIP);
        p(i, i) = std::min(std::max(p(i, i), rt.p_floor), rt.p_ceil);
    }
    double du = 0.0;
    for (int i = 0; i < 2; ++i) {
        double row = 1.0;
        for (int k = 0; k < 6; ++k) {
            row += std::fabs(rt.d(i, k)) * (1.0 + std::ldexp(std::fabs(ro.gain(k, 1)), tab.ls[k] - tab.ls[1]));
        }
        du = std::max(du, row * lsb_x);
    }
    const Eigen::Vector2d u = -rt.d * ru.z.head<6>();
    decide(u.cwiseAbs().maxCoeff(), rt.bdot_max, du, true, OBS_H_CMD_LIMITED);
    if (ro.limited != ((health & OBS_H_CMD_LIMITED) != 0u) && (dc & OBS_H_CMD_LIMITED) == 0u) {
        throw std::runtime_error("command limit decision differs from obs_ref");
    }
    if (ro.limited && limited_run + 1u >= tab.n_sat) { health |= OBS_H_CMD_LIMIT_PERSIST; }
    const Eigen::Matrix<double, 7, 7> pp = ro.fs * p * ro.fs.transpose() + rt.q;
    for (int i = 0; i < 7; ++i) {
        decide(pp(i, i), rt.p_floor, lsb_p, false, OBS_H_COV_CLIP);
        decide(pp(i, i), rt.p_ceil, lsb_p, true, OBS_H_COV_CLIP);
    }
}

// Per-step bounds (LSB), the derivation of tests/observer/test_obs_golden_replay.c evaluated on
// this step's reference operands. Index d = 0, 1: the two implementations' commands are equal,
// or one count apart (more fails the vector).
void step_bounds(const obs_params_t &tab, const ref::ObsTable &rt, const ref::ObsState &rs, const RefUpdate &ru,
                 const ref::ObsStepOut &ro, gv_obs_t &v)
{
    const double act_lsb_x = std::ldexp(1.0, tab.act_cnt_shift);   // one command count in LSB_x
    std::array<double, 7> amp{};
    for (int j = 0; j < 7; ++j) {
        amp[static_cast<size_t>(j)] = std::ldexp(std::fabs(ro.gain(j, 1)), tab.ls[j] - tab.ls[1]);
    }
    // kappa (LSB_k): channel 0's correction rounds once (0.5); channel 1's innovation carries
    // <= 1 LSB_x, amplified by amp_6 = |L_61| 2^(ls_6 - ls_1) and read in LSB_k (x 0.5), and
    // its correction rounds once (0.5); +1 margin (clamp and rounding ties); +0.5 for the
    // stored (rounded) reference value.
    const double bk = 0.5 + 0.5 + 0.5 * amp[6] + 1.0 + 0.5;
    v.bk = ibound(bk);
    // x-hat (LSB_x): after the update dx_k <= 1 + amp_k. The prediction x+ = Phi(kappa) x + Gamma u
    // carries sum_k |Phi_jk| dx_k (row sums of this step's Phi(kappa)), rounds once (0.5), and
    // adds: the rounding of each Phi(kappa) / Gamma(kappa) entry (0.5 LSB of q_phi0 / q_gam0)
    // times |x_k| / |u_k|; the kappa difference (<= bk LSB_k) through Phi_k x + Gamma_k u; for
    // d = 1, one command count through Gamma(kappa): sum_u |Gamma_ju| act_lsb; +1 margin; +0.5
    // for the stored reference value.
    const Eigen::Matrix<double, 6, 6> phi = rt.phi0 + (std::min(std::max(ru.z(6), rt.kappa_lo), rt.kappa_hi) -
                                                       rt.kappa0) * rt.phik;
    Eigen::Vector2d u;
    u << v.cmd_cnt[0] * rt.act_lsb, v.cmd_cnt[1] * rt.act_lsb;
    const double lsb_phi = std::ldexp(1.0, -static_cast<int>(tab.q_phi0));
    const double lsb_gam = std::ldexp(1.0, -static_cast<int>(tab.q_gam0));
    for (int j = 0; j < 6; ++j) {
        double carried = 0.0, entries = 0.0, kap = 0.0, cnt = 0.0;
        for (int k = 0; k < 6; ++k) {
            carried += std::fabs(phi(j, k)) * (1.0 + amp[static_cast<size_t>(k)]);
            entries += 0.5 * lsb_phi * std::fabs(ru.z(k)) * Q29;
            kap += std::fabs(rt.phik(j, k) * ru.z(k));
        }
        for (int k = 0; k < 2; ++k) {
            entries += 0.5 * lsb_gam * std::fabs(u(k)) * Q29;
            kap += std::fabs(rt.gamk(j, k) * u(k));
            cnt += std::fabs(ro.gam(j, k)) * act_lsb_x;
        }
        const double base = carried + 0.5 + entries + bk / Q28 * kap * Q29 + 1.0 + 0.5;
        v.bx[0][j] = ibound(base);
        v.bx[1][j] = ibound(base + cnt);
    }
    // P_s (LSB_P), as tests/observer/test_obs_golden_host.cpp: the update dP_upd <= (1 + 2.88)
    // (1 + ||L_1||inf) + 1; the prediction ||F_s||inf^2 dP_upd + 2 * 2 * 1.44 ||F_s||inf +
    // 0.5 ||F_s||inf + 1.5; the regressor column from the post-update x difference:
    // 2 max_i |df_s,i| ||P_s row 6||_1 ||F_s||inf. Added here: the kappa difference in the Phi
    // block of F_s, 2 (bk 2^-28) ||Phi_k,s||inf ||P_s||inf ||F_s||inf; for d = 1, one command
    // count in the regressor, df_u,i = sum_u |Gamma_k,iu| act_lsb (same scaling as df); +0.5 for
    // the stored reference value.
    const double fs_n = inf_norm(ro.fs);
    const double l1_n = ro.gain.col(1).cwiseAbs().maxCoeff();
    const double p6_norm1 = rs.p.row(6).cwiseAbs().sum();
    const double p_n = inf_norm(rs.p);
    double df_max = 0.0, dfu_max = 0.0, phik_s = 0.0;
    for (int i = 0; i < 6; ++i) {
        double df = 0.0, dfu = 0.0, row = 0.0;
        for (int j = 0; j < 6; ++j) {
            df += std::fabs(rt.phik(i, j)) * (1.0 + amp[static_cast<size_t>(j)]);
            row += std::ldexp(std::fabs(rt.phik(i, j)), tab.ls[j] - tab.ls[i]);
        }
        for (int k = 0; k < 2; ++k) { dfu += std::fabs(rt.gamk(i, k)) * act_lsb_x; }
        df_max = std::max(df_max, std::ldexp(df, 1 + tab.ls[6] - tab.ls[i]));   // LSB_x -> LSB_P: x2
        dfu_max = std::max(dfu_max, std::ldexp(dfu, 1 + tab.ls[6] - tab.ls[i]));
        phik_s = std::max(phik_s, row);
    }
    const double dp_upd = (1.0 + 2.88) * (1.0 + l1_n) + 1.0;
    const double bp = fs_n * fs_n * dp_upd + 4.0 * 1.44 * fs_n + 0.5 * fs_n + 1.5 + 2.0 * df_max * p6_norm1 * fs_n +
                      2.0 * bk / Q28 * phik_s * p_n * fs_n * Q30 + 0.5;
    v.bp[0] = ibound(bp);
    v.bp[1] = ibound(bp + 2.0 * dfu_max * p6_norm1 * fs_n);
}

// The set's table: the boot table with the override of hil_host/bridge boot_obs_table().
obs_params_t set_table(const ObsSetCfg &cfg)
{
    obs_params_t p = *cfg.tab;
    if (cfg.bdot_max_degps > 0.0) { p.bdot_max_q29 = qnt(cfg.bdot_max_degps * 3.14159265358979323846 / 180.0, 29); }
    return p;
}

std::vector<gv_obs_t> obs_set(const std::string &scn_dir, const ObsSetCfg &cfg, ObsSetStats &stats)
{
    const sim::Scenario scn = sim::load_scenario(scn_dir + "/" + cfg.file);
    const obs_params_t tab = set_table(cfg);
    const ref::ObsTable rt = ref::dequantise(tab);
    if (scn.period_us != tab.period_us) { throw std::runtime_error("scenario period != table period"); }
    sim::SailPlant plant(scn);
    const uint64_t n = scn.n_steps();
    std::vector<gv_obs_t> out;
    bool init = false;
    ref::ObsState st;
    uint32_t limited_run = 0u;
    std::array<int32_t, 2> prev_cnt{{0, 0}};
    for (uint64_t k = 0; k < n; ++k) {
        const sim::SensorFrame f = plant.sense();
        const std::array<int32_t, 2> y{{f.cnt[0], f.cnt[1]}};
        const bool valid = f.status[0] == 0u && f.status[1] == 0u;
        std::array<int32_t, 2> cmd{{0, 0}};
        if (!valid) { throw std::runtime_error("invalid gyro sample in a nominal scenario"); }
        const bool first = !init;
        if (first) {
            st = ref::initial_state(tab, y);
            init = true;
        }
        const bool pick = k < cfg.dense || ((k - cfg.dense) % cfg.stride) == 0u;
        if (pick) {
            gv_obs_t v{};
            v.seq = f.seq;
            v.gyro_cnt[0] = y[0];
            v.gyro_cnt[1] = y[1];
            v.init = first ? 0u : 1u;
            QState q;
            ref::ObsState rs;
            if (first) {
                // The flight state after obs_init: x = 0, kappa = kappa_init, P = 0; the step
                // initialises from the sample (x = (y, 0), P = P0), exactly the reference's
                // initial_state, which is representable.
                q.kappa = tab.kappa_init_q28;
                rs = st;
            } else {
                q = quantise(st, prev_cnt, tab.act_cnt_shift);
                rs = dequant(q);
            }
            for (size_t i = 0; i < 6; ++i) { v.x_q29[i] = q.x[i]; }
            v.kappa_q28 = q.kappa;
            for (size_t i = 0; i < GV_P_UPPER; ++i) { v.p_q30[i] = q.p[i]; }
            for (size_t i = 0; i < 2; ++i) {
                v.qres_q29[i] = q.qres[i];
                v.u_prev_q29[i] = q.u_prev[i];
            }
            v.limited_run = limited_run;
            ref::ObsState post = rs;
            const ref::ObsStepOut ro = ref::obs_step_ref(rt, post, y);
            v.cmd_cnt[0] = ro.cmd_cnt[0];
            v.cmd_cnt[1] = ro.cmd_cnt[1];
            for (size_t i = 0; i < 6; ++i) { v.x1_q29[i] = qnt(post.x(static_cast<Eigen::Index>(i)), 29); }
            v.kappa1_q28 = qnt(post.kappa, 28);
            size_t m = 0;
            for (Eigen::Index i = 0; i < 7; ++i) {
                for (Eigen::Index j = i; j < 7; ++j, ++m) { v.p1_q30[m] = qnt(post.p(i, j), 30); }
            }
            const RefUpdate ru = ref_update(rt, rs, y);
            if ((ru.gain - ro.gain).cwiseAbs().maxCoeff() > 1e-12 * (1.0 + ro.gain.cwiseAbs().maxCoeff())) {
                throw std::runtime_error("repeated update disagrees with obs_ref's gains");
            }
            step_bounds(tab, rt, rs, ru, ro, v);
            expected_flags(tab, rt, ru, ro, limited_run, v, v.health, v.health_dc);
            out.push_back(v);
            ++stats.n;
            stats.dc += v.health_dc != 0u ? 1u : 0u;
            stats.dc_bits |= v.health_dc;
            stats.flagged += v.health != 0u ? 1u : 0u;
            stats.flags |= v.health;
            stats.limited += ro.limited ? 1u : 0u;
            stats.init += first ? 1u : 0u;
            stats.bx0_min = std::min(stats.bx0_min, static_cast<double>(*std::min_element(v.bx[0], v.bx[0] + 6)));
            stats.bx0_max = std::max(stats.bx0_max, static_cast<double>(*std::max_element(v.bx[0], v.bx[0] + 6)));
            stats.bx1_max = std::max(stats.bx1_max, static_cast<double>(*std::max_element(v.bx[1], v.bx[1] + 6)));
            stats.bk_max = std::max(stats.bk_max, static_cast<double>(v.bk));
            stats.bp0_min = std::min(stats.bp0_min, static_cast<double>(v.bp[0]));
            stats.bp0_max = std::max(stats.bp0_max, static_cast<double>(v.bp[0]));
            stats.bp1_max = std::max(stats.bp1_max, static_cast<double>(v.bp[1]));
        }
        // The closed loop continues on the reference's own double state.
        const ref::ObsStepOut o = ref::obs_step_ref(rt, st, y);
        cmd = o.cmd_cnt;
        limited_run = o.limited ? limited_run + 1u : 0u;
        prev_cnt = cmd;
        sim::ActuatorCmd ac;
        ac.seq = f.seq;
        ac.n_ch = 2u;
        ac.cnt[0] = cmd[0];
        ac.cnt[1] = cmd[1];
        plant.apply(ac);
        if (plant.propagate() != sim::RunState::Running && k + 1u < n) {
            throw std::runtime_error(std::string("plant run ended early in ") + cfg.file);
        }
    }
    return out;
}

void emit_obs_record(Emit &e, const gv_obs_t &v)
{
    e.nl();
    e.open();
    e.u(v.seq);
    e.in(v.gyro_cnt, 2);
    e.u(v.init);
    e.in(v.x_q29, 6);
    e.i(v.kappa_q28);
    e.in(v.p_q30, GV_P_UPPER);
    e.in(v.qres_q29, 2);
    e.in(v.u_prev_q29, 2);
    e.u(v.limited_run);
    e.in(v.cmd_cnt, 2);
    e.in(v.x1_q29, 6);
    e.i(v.kappa1_q28);
    e.in(v.p1_q30, GV_P_UPPER);
    e.u(v.health);
    e.u(v.health_dc);
    e.open();
    e.in(v.bx[0], 6);
    e.in(v.bx[1], 6);
    e.close();
    e.i(v.bk);
    e.in(v.bp, 2);
    e.close();
}

void gen_obs(const std::string &scn_dir, const std::string &out_dir)
{
    const std::array<ObsSetCfg, 4> sets{{
        {"PAPER", "s0-5_nominal_mpaper.yaml", "obs_50hz_paper", &OBS_TBL_50HZ_PAPER, 200u, 30u, 0.0},
        {"NOISE", "s0-5_noise_seed0_mpaper.yaml", "obs_50hz_paper", &OBS_TBL_50HZ_PAPER, 200u, 30u, 0.0},
        {"PHYS", "s0-7_nominal_mphys.yaml", "obs_50hz_phys", &OBS_TBL_50HZ_PHYS, 200u, 150u, 0.0},
        {"LIMIT", "s0-5_nominal_mpaper.yaml", "obs_50hz_paper, bdot_max 1.2 deg/s", &OBS_TBL_50HZ_PAPER, 200u, 30u, 1.2},
    }};
    std::string text = header_top(kOrigin, "GV_OBS_VECTORS_H", "gv_obs_vectors.h - observer single-step golden vectors "
                                                      "(spec 10-observer §5): S0-5 nominal and noise seed 0, S0-7 nominal.");
    for (const ObsSetCfg &cfg : sets) {
        ObsSetStats s;
        const std::vector<gv_obs_t> v = obs_set(scn_dir, cfg, s);
        std::ostringstream h;
        h << "/* " << cfg.file << ", table " << cfg.table_name << ": " << s.n << " single-step vectors (steps 0-"
          << (cfg.dense - 1u) << ", then every " << cfg.stride << "th); " << s.init << " initialising, " << s.limited
          << " limited, " << s.flagged << " with flags (OR " << hex32(s.flags) << "), " << s.dc
          << " with a don't-care flag (OR " << hex32(s.dc_bits) << ").\n"
          << "   Bounds (LSB): x-hat " << s.bx0_min << "-" << s.bx0_max << " (one count apart: <= " << s.bx1_max
          << "), kappa <= " << s.bk_max << ", P_s " << s.bp0_min << "-" << s.bp0_max << " (<= " << s.bp1_max
          << "). */\n";
        h << "#define GV_OBS_" << cfg.name << "_N " << v.size() << "u\n";
        const obs_params_t tab = set_table(cfg);
        h << "#define GV_OBS_" << cfg.name << "_BDOT_MAX_Q29 " << tab.bdot_max_q29 << "   /* command limit of the set */\n";
        h << "#define GV_OBS_" << cfg.name << "_TABLE_FP " << hex32(gv_obs_table_fp(&tab)) << "   /* "
          << cfg.table_name << " */\n";
        h << "#define GV_OBS_" << cfg.name << "_CRC " << hex32(set_crc(v)) << "   /* the records, as words */\n";
        h << "static const gv_obs_t GV_OBS_" << cfg.name << "[" << v.size() << "] = {";
        Emit e;
        for (const gv_obs_t &r : v) { emit_obs_record(e, r); }
        h << e.str() << "\n};\n\n";
        text += h.str();
        std::printf("obs_golden_gen: observer %s (%s): %u vectors, %zu bytes; bounds x %g-%g (%g), kappa %g, P %g-%g (%g); "
                    "flagged %u (0x%08x); don't-care %u (0x%08x)\n",
                    cfg.name, cfg.file, s.n, v.size() * sizeof(gv_obs_t), s.bx0_min, s.bx0_max, s.bx1_max, s.bk_max,
                    s.bp0_min, s.bp0_max, s.bp1_max, s.flagged, s.flags, s.dc, s.dc_bits);
    }
    text += "#endif\n";
    write_file(out_dir + "/gv_obs_vectors.h", text);
}

}  // namespace

int main(int argc, char **argv)
{
    std::string scn_dir;
    return gv::run(
        argc, argv, "obs_golden_gen",
        "obs_golden_gen: build-time golden vectors of the observer (gv_obs_vectors.h) from its double reference.",
        [&scn_dir](CLI::App &app) {
            app.add_option("--scenarios", scn_dir, "scenario directory (sim/observer/scenarios)")
                ->required()
                ->check(CLI::ExistingDirectory);
        },
        [&scn_dir](const std::string &out_dir) { gen_obs(scn_dir, out_dir); });
}
