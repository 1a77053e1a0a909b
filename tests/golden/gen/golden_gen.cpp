// golden_gen — build-time golden vectors from the double references (spec 00 §6.4,
// 10-observer §5, 50-impulse §6). Run by a custom command of host builds only; writes C headers
// of const integer arrays into the build tree (never committed):
//
//   gv_obs_vectors.h   observer single-step sets of the three runs spec 10 S0-8 names: S0-5
//                      nominal and S0-5 gyro noise seed 0 (M-paper, OBS_TBL_50HZ_PAPER), S0-7
//                      nominal (M-phys, OBS_TBL_50HZ_PHYS); and the S0-9 authority case (S0-5
//                      nominal with the command vector-limited at 1.2 deg/s), whose vectors
//                      carry CMD_LIMITED / CMD_LIMIT_PERSIST, so the flag comparison sees set bits
//   gv_imp_vectors.h   impulse sets: G3 (the paper's example, iterates 0-5 and the plan) and a
//                      G4 subset (Monte Carlo draws of tools/impulse/imp_mc.cpp, seed 1)
//
//   golden_gen --scenarios <sim/scenarios> --out <dir>      (command line: CLI11; --help)
//
// Observer. The double reference (sim/reference/obs_ref) runs in closed loop with the exact plant
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
// Impulse. Problems are built as tests/impulse/test_imp_golden_host.cpp and imp_mc build them
// (state quantised to q28, tau_f to q29, alpha and units from IMP_TBL_DEFAULT; the reference
// solves the dequantised problem with the table's guards).
#include "fsw_cli.hpp"
#include "impulse/imp_ref_solver.hpp"
#include "observer/obs_ref.hpp"
#include "observer/sail_plant.hpp"
#include "scenario/scenario.hpp"
#include "sensors/rng.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

extern "C" {
#include "gv.h"
#include "gv_digest.h"
#include "imp_tables.h"
#include "obs_tables.h"
}

static_assert(sizeof(gv_obs_t) == 98u * 4u, "gv_obs_t: the emitter writes 98 words");
static_assert(sizeof(gv_imp_case_t) == 34u * 4u, "gv_imp_case_t: the emitter writes 34 words");
static_assert(sizeof(gv_imp_iter_t) == 12u * 4u, "gv_imp_iter_t: the emitter writes 12 words");

namespace {

constexpr double Q26 = 67108864.0;
constexpr double Q28 = 268435456.0;
constexpr double Q29 = 536870912.0;
constexpr double Q30 = 1073741824.0;
constexpr double kTie = 1e-6;   // relative distance to a decision threshold treated as a tie

int32_t qnt(double v, int q)
{
    const double s = std::round(std::ldexp(v, q));
    if (!(s >= -2147483648.0 && s <= 2147483647.0)) {
        throw std::runtime_error("golden_gen: value outside int32 at q" + std::to_string(q));
    }
    return static_cast<int32_t>(s);
}

// An integer bound from a real one: the errors are integers, so err <= b iff err <= floor(b).
int32_t ibound(double b) { return static_cast<int32_t>(std::floor(b)); }

int32_t ceil_q8(double v) { return static_cast<int32_t>(std::ceil(v * 256.0)); }

// ------------------------------------------------------------------ C emitter

class Emit {
public:
    void i(int32_t v)
    {
        sep();
        if (v == INT32_MIN) {
            s_ << "(-2147483647 - 1)";
        } else {
            s_ << v;
        }
    }
    void u(uint32_t v)
    {
        sep();
        s_ << v << "u";
    }
    void in(const int32_t *v, size_t n)
    {
        open();
        for (size_t k = 0; k < n; ++k) { i(v[k]); }
        close();
    }
    void un(const uint32_t *v, size_t n)
    {
        open();
        for (size_t k = 0; k < n; ++k) { u(v[k]); }
        close();
    }
    void open()
    {
        sep();
        s_ << "{";
        first_ = true;
    }
    void close()
    {
        s_ << "}";
        first_ = false;
    }
    void nl() { s_ << "\n    "; }
    std::string str() const { return s_.str(); }

private:
    void sep()
    {
        if (!first_) { s_ << ", "; }
        first_ = false;
    }
    std::ostringstream s_;
    bool first_ = true;
};

void write_file(const std::string &path, const std::string &text)
{
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    if (!f) { throw std::runtime_error("golden_gen: cannot write " + path); }
    f << text;
    if (!f) { throw std::runtime_error("golden_gen: write failed: " + path); }
}

std::string hex32(uint32_t v)
{
    char b[16];
    std::snprintf(b, sizeof b, "0x%08xu", v);
    return b;
}

// ------------------------------------------------------------------ observer

struct ObsSetCfg {
    const char *name;        // C identifier suffix and digest name
    const char *file;        // scenario file in sim/scenarios
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

double inf_norm(const Eigen::MatrixXd &m) { return m.cwiseAbs().rowwise().sum().maxCoeff(); }

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
        throw std::runtime_error("golden_gen: command limit decision differs from obs_ref");
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
    if (scn.period_us != tab.period_us) { throw std::runtime_error("golden_gen: scenario period != table period"); }
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
        if (!valid) { throw std::runtime_error("golden_gen: invalid gyro sample in a nominal scenario"); }
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
                throw std::runtime_error("golden_gen: repeated update disagrees with obs_ref's gains");
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
            throw std::runtime_error(std::string("golden_gen: plant run ended early in ") + cfg.file);
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

// ------------------------------------------------------------------ impulse

struct Problem {
    gv_imp_case_t v{};
    ref::ImpCase c;   // the dequantised case the fixed-point code sees
};

// State in SI -> q28 problem (units and alpha from the table) and its dequantised case.
Problem make_problem(const imp_params_t &p, const ref::Vec6 &x0, double tauf)
{
    Problem f;
    f.c.w = p.omega_nradps * 1e-9;
    f.c.a_nom = p.a_nom_umps2 * 1e-6;
    f.v.tauf_q29 = qnt(tauf, 29);
    f.c.T = f.v.tauf_q29 / Q29 / f.c.w;
    for (int i = 0; i < 6; ++i) {
        const auto si = static_cast<size_t>(i);
        const double unit = (i % 2 == 0) ? f.c.L() : f.c.V();
        f.v.x0_q28[i] = qnt(x0(i) / unit, 28);
        f.v.xt_q28[i] = 0;
        f.c.x0(i) = f.v.x0_q28[i] / Q28 * unit;
        f.c.xt(i) = 0.0;
        f.v.alpha_q30[i] = p.alpha_q30[i];
        f.c.alpha[si] = p.alpha_q30[i] / Q30;
    }
    return f;
}

// The reference plan of a problem, into the record.
void solve_ref(const imp_params_t &p, Problem &f, uint32_t &n_valid)
{
    const ref::ImpGuards g = ref::guards_from_table(p);
    const ref::ImpPlan pl = ref::solve(f.c, g);
    gv_imp_case_t &v = f.v;
    v.outcome = pl.outcome;
    v.pattern = pl.pattern;
    for (size_t s = 0; s < 2; ++s) {
        v.how[s] = pl.how[s];
        v.iters[s] = static_cast<uint32_t>(pl.iters[s]);
        v.dv_q28[s] = qnt(pl.dv[s], 28);
    }
    for (size_t r = 0; r < 3; ++r) {
        v.t1_q29[r] = qnt(pl.t1[r], 29);
        v.t2_q29[r] = qnt(pl.t2[r], 29);
    }
    v.jinv_q8 = 0;
    if (pl.outcome == IMP_SOL_VALID) {
        ++n_valid;
        const ref::ImpNd nd = ref::nondim(f.c);
        const std::array<double, 2> a1{{pl.t1[0], pl.t1[1]}}, a2{{pl.t2[0], pl.t2[1]}};
        const std::array<double, 2> b1{{pl.t1[2], 0}}, b2{{pl.t2[2], 0}};
        const double nxy = inf_norm(ref::jacobian(nd, 0, pl.pattern & 0xFu, a1, a2).inverse());
        const double nz = inf_norm(ref::jacobian(nd, 1, (pl.pattern >> 4) & 3u, b1, b2).inverse());
        v.jinv_q8 = ceil_q8(std::max(nxy, nz));
    }
}

void emit_imp_case(Emit &e, const gv_imp_case_t &v)
{
    e.nl();
    e.open();
    e.i(v.tauf_q29);
    e.in(v.x0_q28, 6);
    e.in(v.xt_q28, 6);
    e.in(v.alpha_q30, 6);
    e.u(v.outcome);
    e.u(v.pattern);
    e.un(v.how, 2);
    e.un(v.iters, 2);
    e.in(v.t1_q29, 3);
    e.in(v.t2_q29, 3);
    e.in(v.dv_q28, 2);
    e.i(v.jinv_q8);
    e.close();
}

void emit_imp_iter(Emit &e, const gv_imp_iter_t &v)
{
    e.nl();
    e.open();
    e.u(v.sub);
    e.u(v.pat);
    e.u(v.k);
    e.in(v.t1_q29, 2);
    e.in(v.t2_q29, 2);
    e.in(v.f_q28, 4);
    e.i(v.jn_q8);
    e.close();
}

uint32_t words_crc(const void *rec, size_t bytes, uint32_t crc_in)
{
    gv_dg_t d;
    d.crc = crc_in;
    d.n = 0u;
    gv_dg_words(&d, rec, bytes);
    return d.crc;
}

template <typename T>
uint32_t set_crc(const std::vector<T> &v)
{
    uint32_t c = 0u;
    for (const T &r : v) { c = words_crc(&r, sizeof r, c); }
    return c;
}

std::string header_top(const char *guard, const char *what)
{
    std::ostringstream h;
    h << "/*\n * " << what << "\n"
      << " * GENERATED at build time by golden_gen (tests/golden/gen/golden_gen.cpp) from the double\n"
      << " * references in sim/reference: do not edit, never commit. Host builds regenerate it;\n"
      << " * Cortex-M builds import it from FSW_HOST_BUILD_DIR/golden/gen (tests/golden/README.md).\n"
      << " */\n#ifndef " << guard << "\n#define " << guard << "\n\n#include \"gv.h\"\n\n";
    return h.str();
}

void gen_obs(const std::string &scn_dir, const std::string &out_dir)
{
    const std::array<ObsSetCfg, 4> sets{{
        {"PAPER", "s0-5_nominal_mpaper.yaml", "obs_50hz_paper", &OBS_TBL_50HZ_PAPER, 200u, 30u, 0.0},
        {"NOISE", "s0-5_noise_seed0_mpaper.yaml", "obs_50hz_paper", &OBS_TBL_50HZ_PAPER, 200u, 30u, 0.0},
        {"PHYS", "s0-7_nominal_mphys.yaml", "obs_50hz_phys", &OBS_TBL_50HZ_PHYS, 200u, 150u, 0.0},
        {"LIMIT", "s0-5_nominal_mpaper.yaml", "obs_50hz_paper, bdot_max 1.2 deg/s", &OBS_TBL_50HZ_PAPER, 200u, 30u, 1.2},
    }};
    std::string text = header_top("GV_OBS_VECTORS_H", "gv_obs_vectors.h - observer single-step golden vectors "
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
        std::printf("golden_gen: observer %s (%s): %u vectors, %zu bytes; bounds x %g-%g (%g), kappa %g, P %g-%g (%g); "
                    "flagged %u (0x%08x); don't-care %u (0x%08x)\n",
                    cfg.name, cfg.file, s.n, v.size() * sizeof(gv_obs_t), s.bx0_min, s.bx0_max, s.bx1_max, s.bk_max,
                    s.bp0_min, s.bp0_max, s.bp1_max, s.flagged, s.flags, s.dc, s.dc_bits);
    }
    text += "#endif\n";
    write_file(out_dir + "/gv_obs_vectors.h", text);
}

void gen_imp(const std::string &out_dir)
{
    const imp_params_t &p = IMP_TBL_DEFAULT;
    const ref::ImpGuards g = ref::guards_from_table(p);
    const double w = p.omega_nradps * 1e-9;
    uint32_t n_valid = 0;
    // G3: the paper's example (spec 50 §3.4): X0 = (5 km, -1 m/s, 4 km, -1 m/s, 4 km, -1 m/s), T = 1055 s.
    ref::Vec6 ex;
    ex << 5000, -1, 4000, -1, 4000, -1;
    Problem g3 = make_problem(p, ex, w * 1055.0);
    solve_ref(p, g3, n_valid);
    std::vector<gv_imp_iter_t> its;
    {
        const ref::ImpNd nd = ref::nondim(g3.c);
        const std::array<std::pair<int, unsigned>, 2> subs{{{0, 0xCu}, {1, 0x1u}}};   // the rule's polarities
        for (const auto &sp : subs) {
            const ref::ImpAttempt a = ref::attempt(nd, g, sp.first, sp.second, {{0, 0}}, {{nd.tauf, nd.tauf}});
            for (size_t k = 0; k < a.hist.size() && k <= 5u; ++k) {
                const ref::ImpIter &h = a.hist[k];
                gv_imp_iter_t r{};
                r.sub = static_cast<uint32_t>(sp.first);
                r.pat = sp.second;
                r.k = static_cast<uint32_t>(k);
                for (size_t m = 0; m < 2; ++m) {
                    r.t1_q29[m] = qnt(h.t1[m], 29);
                    r.t2_q29[m] = qnt(h.t2[m], 29);
                }
                for (Eigen::Index m = 0; m < h.f.size(); ++m) { r.f_q28[m] = qnt(h.f(m), 28); }
                r.jn_q8 = ceil_q8(inf_norm(ref::jacobian(nd, sp.first, sp.second, h.t1, h.t2)));
                its.push_back(r);
            }
        }
    }
    // G4 subset: imp_mc's draws (sim::Rng(seed, box_id << 32 | i), X0 = (2u - 1) half-width), seed 1:
    // the first 64 of the nominal box (+-5 km / +-1 m/s, id 1) and 32 of the wide box (+-20 km /
    // +-5 m/s, id 2, where most plans are INFEASIBLE or NO_SOLUTION: outcome equality).
    struct Box {
        uint64_t id;
        double rp, rv;
        uint32_t n;
    };
    const std::array<Box, 2> boxes{{{1u, 5000.0, 1.0, 64u}, {2u, 20000.0, 5.0, 32u}}};
    std::vector<gv_imp_case_t> g4;
    std::array<uint32_t, 2> valid_box{{0, 0}};
    for (size_t b = 0; b < boxes.size(); ++b) {
        for (uint32_t i = 0; i < boxes[b].n; ++i) {
            sim::Rng rng(1u, (boxes[b].id << 32) | i);
            ref::Vec6 x0;
            for (int k = 0; k < 6; ++k) {
                const double u = rng.uniform();
                x0(k) = (2.0 * u - 1.0) * ((k % 2 == 0) ? boxes[b].rp : boxes[b].rv);
            }
            Problem pr = make_problem(p, x0, w * 1055.0);
            solve_ref(p, pr, valid_box[b]);
            g4.push_back(pr.v);
        }
    }
    // Tolerances in LSB of q29 at the table's orbit rate: spec 50 G3 (every iterate 1 ms, final
    // 0.25 ms) and G4 (0.25 ms); + 0.5 LSB for the rounded reference time (the error is an integer).
    const int32_t tol_1ms = ibound(1.0e-3 * w * Q29 + 0.5);
    const int32_t tol_025ms = ibound(0.25e-3 * w * Q29 + 0.5);
    std::string text = header_top("GV_IMP_VECTORS_H", "gv_imp_vectors.h - impulse solver golden vectors "
                                                      "(spec 50-impulse §6): G3 and a G4 subset.");
    std::ostringstream h;
    h << "#define GV_IMP_TABLE_FP " << hex32(gv_imp_table_fp(&p)) << "   /* IMP_TBL_DEFAULT */\n";
    h << "#define GV_IMP_TOL_1MS_Q29 " << tol_1ms << "     /* 1 ms = " << 1.0e-3 * w * Q29 << " LSB q29, + 0.5 */\n";
    h << "#define GV_IMP_TOL_025MS_Q29 " << tol_025ms << "   /* 0.25 ms = " << 0.25e-3 * w * Q29
      << " LSB q29, + 0.5 */\n\n";
    h << "/* G3: the paper's example, its reference plan (" << (g3.v.outcome == IMP_SOL_VALID ? "VALID" : "not valid")
      << ", pattern " << g3.v.pattern << ") and pure-Newton iterates from (0, tau_f). */\n";
    h << "static const gv_imp_case_t GV_IMP_G3_CASE = ";
    {
        Emit e;
        emit_imp_case(e, g3.v);
        h << e.str() << ";\n";
    }
    h << "#define GV_IMP_G3_N " << its.size() << "u\n";
    h << "#define GV_IMP_G3_CRC " << hex32(set_crc(its)) << "\n";
    h << "static const gv_imp_iter_t GV_IMP_G3[" << its.size() << "] = {";
    {
        Emit e;
        for (const gv_imp_iter_t &r : its) { emit_imp_iter(e, r); }
        h << e.str() << "\n};\n\n";
    }
    h << "/* G4 subset, imp_mc seed 1: nominal box 0-" << boxes[0].n - 1u << " (" << valid_box[0]
      << " valid), wide box 0-" << boxes[1].n - 1u << " (" << valid_box[1] << " valid). */\n";
    h << "#define GV_IMP_G4_N " << g4.size() << "u\n";
    h << "#define GV_IMP_G4_CRC " << hex32(set_crc(g4)) << "\n";
    h << "static const gv_imp_case_t GV_IMP_G4[" << g4.size() << "] = {";
    {
        Emit e;
        for (const gv_imp_case_t &r : g4) { emit_imp_case(e, r); }
        h << e.str() << "\n};\n\n";
    }
    text += h.str() + "#endif\n";
    write_file(out_dir + "/gv_imp_vectors.h", text);
    std::printf("golden_gen: impulse G3 %zu iterates + plan; G4 %zu cases (%u + %u valid)\n", its.size(), g4.size(),
                valid_box[0], valid_box[1]);
}

}  // namespace

int main(int argc, char **argv)
{
    std::string scn_dir, out_dir;
    CLI::App app{"golden_gen: build-time golden vectors (gv_obs_vectors.h, gv_imp_vectors.h) from the double "
                 "references.\nExit 0 written, 1 generation error, 2 bad usage.",
                 "golden_gen"};
    fsw_cli::last_value_wins(app);
    app.add_option("--scenarios", scn_dir, "scenario directory (sim/scenarios)")
        ->required()
        ->check(CLI::ExistingDirectory);
    app.add_option("--out", out_dir, "existing directory for the headers")->required()->check(CLI::ExistingDirectory);
    const int rc = fsw_cli::parse(app, argc, argv, 2);
    if (rc >= 0) {
        return rc;
    }
    try {
        gen_obs(scn_dir, out_dir);
        gen_imp(out_dir);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
    return 0;
}
