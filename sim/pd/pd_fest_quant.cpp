// pd_fest_quant — see pd_fest_quant.hpp.
#include "pd/pd_fest_quant.hpp"

#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>

namespace ref::pd {

namespace {

std::uint32_t uq(double v, int q, const char *what)
{
    const double s = std::ldexp(v, q);
    if (!(s >= 0.0 && s <= 4294967295.0)) {
        throw std::invalid_argument(std::string("quantise_fest: ") + what + " out of range");
    }
    return static_cast<std::uint32_t>(std::llround(s));
}

std::int32_t sq(double v, int q, const char *what)
{
    const double s = std::ldexp(v, q);
    if (!(s >= -2147483648.0 && s <= 2147483647.0)) {
        throw std::invalid_argument(std::string("quantise_fest: ") + what + " out of range");
    }
    return static_cast<std::int32_t>(std::llround(s));
}

// A row of coefficients that multiply an input of LSB 2^-q_in into a result of LSB 2^-40:
// m = round(v 2^k), result = round(x m / 2^sh) with sh = k + q_in - 40; k is the largest that keeps
// every |m| < 2^30 (one bit under int32) and sh in [0, 62].
void row(const double *v, int n, int q_in, std::int32_t *m, std::uint8_t *sh, const char *what)
{
    double mx = 0.0;
    for (int i = 0; i < n; ++i) {
        mx = std::fmax(mx, std::fabs(v[i]));
    }
    if (!(mx > 0.0)) {
        for (int i = 0; i < n; ++i) {
            m[i] = 0;
        }
        *sh = 0;
        return;
    }
    int e = 0;
    (void)std::frexp(mx, &e);  // mx in [2^(e-1), 2^e)
    int k = 30 - e;            // mx 2^k < 2^30
    int s = k + q_in - 40;
    if (s > 62) {
        k -= s - 62;
        s = 62;
    }
    if (s < 0) {
        throw std::invalid_argument(std::string("quantise_fest: ") + what + ": coefficient too large");
    }
    for (int i = 0; i < n; ++i) {
        m[i] = sq(v[i], k, what);
    }
    *sh = static_cast<std::uint8_t>(s);
}

}  // namespace

pd_fest_params_t quantise_fest(const FestParams &p)
{
    if (std::fabs(p.Ty_s - 0.25) > 1e-12 || p.n_sections < 1 || p.n_sections > 2 ||
        (p.n_reg != 0 && p.n_reg != 2) || std::fabs(p.c_df_hz - 0.01) > 1e-12 ||
        std::fabs(p.c_dk2 - 100.0) > 1e-9 || std::fabs(p.c_f0_hz - 0.005) > 1e-12 || std::fabs(p.c_k20) > 1e-12) {
        throw std::invalid_argument("quantise_fest: parameters outside the flight port's fixed layout");
    }
    pd_fest_params_t q{};
    q.n_sec = static_cast<std::uint8_t>(p.n_sections);
    q.n_reg = static_cast<std::uint8_t>(p.n_reg);
    q.inv_m_q30 = uq(1.0 / p.m_ch, 30, "1/m_ch");
    q.alpha_hp_q30 = uq(p.alpha_hp, 30, "alpha_hp");
    q.f_hp_min_q32 = uq(p.f_hp_min_hz, 32, "f_hp_min");
    q.beta_kappa_q30 = uq(p.beta_kappa, 30, "beta_kappa");
    q.kappa_hi_q30 = uq(p.kappa_max_hi, 30, "kappa_hi");
    q.sigma_y_q40 = uq(p.sigma_y_rad, 40, "sigma_y");
    for (int i = 0; i < kFestNx; ++i) {
        row(p.Ad_r[i], kFestNx, 40, q.ad_m[i], &q.ad_sh[i], "Ad_r");
        row(&p.Bd_r[i], 1, 28, &q.bd_m[i], &q.bd_sh[i], "Bd_r");
        row(&p.L_r[i], 1, 40, &q.l_m[i], &q.l_sh[i], "L_r");
        for (int r = 0; r < kFestNr; ++r) {
            row(p.dA_r[r][i], kFestNx, 40, q.dad_m[r][i], &q.dad_sh[r][i], "dA_r");
            row(&p.dB_r[r][i], 1, 28, &q.dbd_m[r][i], &q.dbd_sh[r][i], "dB_r");
        }
    }
    for (int i = 0; i < 3; ++i) {
        q.aa_b_q29[i] = sq(p.aa_b[i], 29, "aa_b");
    }
    for (int i = 0; i < 2; ++i) {
        q.aa_a_q29[i] = sq(p.aa_a[i], 29, "aa_a");
    }
    for (int i = 0; i < kFestCF; ++i) {
        for (int j = 0; j < kFestCK; ++j) {
            q.cinv_q30[i][j] = uq(1.0 / p.c[i][j], 30, "1/c");
        }
    }
    return q;
}

std::string fest_params_json(const pd_fest_params_t &q)
{
    std::ostringstream o;
    auto arr = [&o](const char *name, const auto *v, int n, bool last = false) {
        o << "\"" << name << "\": [";
        for (int i = 0; i < n; ++i) {
            o << (i ? ", " : "") << static_cast<long long>(v[i]);
        }
        o << "]" << (last ? "" : ", ");
    };
    o << "{\"n_sec\": " << int(q.n_sec) << ", \"n_reg\": " << int(q.n_reg) << ", \"inv_m_q30\": " << q.inv_m_q30
      << ", \"alpha_hp_q30\": " << q.alpha_hp_q30 << ", \"f_hp_min_q32\": " << q.f_hp_min_q32
      << ", \"beta_kappa_q30\": " << q.beta_kappa_q30 << ", \"kappa_hi_q30\": " << q.kappa_hi_q30
      << ", \"sigma_y_q40\": " << q.sigma_y_q40 << ", ";
    arr("ad_m", &q.ad_m[0][0], 16);
    arr("ad_sh", q.ad_sh, 4);
    arr("bd_m", q.bd_m, 4);
    arr("bd_sh", q.bd_sh, 4);
    arr("l_m", q.l_m, 4);
    arr("l_sh", q.l_sh, 4);
    arr("dad_m", &q.dad_m[0][0][0], 32);
    arr("dad_sh", &q.dad_sh[0][0], 8);
    arr("dbd_m", &q.dbd_m[0][0], 8);
    arr("dbd_sh", &q.dbd_sh[0][0], 8);
    arr("aa_b_q29", q.aa_b_q29, 3);
    arr("aa_a_q29", q.aa_a_q29, 2);
    arr("cinv_q30", &q.cinv_q30[0][0], PD_FEST_CF * PD_FEST_CK, true);
    o << "}";
    return o.str();
}

}  // namespace ref::pd
