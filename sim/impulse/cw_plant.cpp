#include "impulse/cw_plant.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace sim {

namespace {
// Noise and dropout streams of the nav sensor (independent: enabling dropouts does not shift
// the noise samples).
constexpr std::uint64_t kStreamNavNoise = 0x4E41564Eu;   // "NAVN"
constexpr std::uint64_t kStreamNavDrop = 0x4E415644u;    // "NAVD"

std::int32_t count(double v, double lsb)
{
    const double c = std::round(v / lsb);   // half away from zero
    const double lim = 2147483647.0;
    return static_cast<std::int32_t>(std::max(-lim, std::min(lim, c)));
}
}  // namespace

double NavConfig::sp() const
{
    switch (profile) {
    case NavProfile::Nominal: return 0.1;
    case NavProfile::Degraded: return 0.5;
    case NavProfile::Custom: return sigma_p;
    case NavProfile::Ideal: break;
    }
    return 0.0;
}

double NavConfig::sv() const
{
    switch (profile) {
    case NavProfile::Nominal: return 1e-3;
    case NavProfile::Degraded: return 5e-3;
    case NavProfile::Custom: return sigma_v;
    case NavProfile::Ideal: break;
    }
    return 0.0;
}

CwPlant::CwPlant(const CwConfig &cfg, const Vec6 &x0)
    : cfg_(cfg), x_(x0), rng_noise_(cfg.nav.seed, kStreamNavNoise), rng_drop_(cfg.nav.seed, kStreamNavDrop)
{
    const double h = cfg_.period_us * 1e-6;
    const double d = (cfg_.nav.f_nav > 0.0) ? std::round(1.0 / (cfg_.nav.f_nav * h)) : 1.0;
    nav_div_ = static_cast<std::uint32_t>(std::max(1.0, d));
    std::sort(cfg_.nav.outliers.begin(), cfg_.nav.outliers.end());
    sample_nav();
}

CwPlant::Mat6 CwPlant::phi(double t, double w)
{
    const double tau = w * t, s = std::sin(tau), c = std::cos(tau);
    Mat6 m = Mat6::Zero();
    m(0, 0) = 1;
    m(0, 1) = (4 * s - 3 * tau) / w;
    m(0, 2) = 6 * (tau - s);
    m(0, 3) = 2 * (1 - c) / w;
    m(1, 1) = 4 * c - 3;
    m(1, 2) = 6 * w * (1 - c);
    m(1, 3) = 2 * s;
    m(2, 1) = -2 * (1 - c) / w;
    m(2, 2) = 4 - 3 * c;
    m(2, 3) = s / w;
    m(3, 1) = -2 * s;
    m(3, 2) = 3 * w * s;
    m(3, 3) = c;
    m(4, 4) = c;
    m(4, 5) = s / w;
    m(5, 4) = -w * s;
    m(5, 5) = c;
    return m;
}

CwPlant::Vec6 CwPlant::psi(double t, double w, const Eigen::Vector3d &a)
{
    const double tau = w * t, s = std::sin(tau), c = std::cos(tau), w2 = w * w;
    Vec6 v;
    v(0) = a(0) * (4 * (1 - c) - 1.5 * tau * tau) / w2 + a(1) * 2 * (tau - s) / w2;
    v(1) = a(0) * (4 * s - 3 * tau) / w + a(1) * 2 * (1 - c) / w;
    v(2) = -a(0) * 2 * (tau - s) / w2 + a(1) * (1 - c) / w2;
    v(3) = -a(0) * 2 * (1 - c) / w + a(1) * s / w;
    v(4) = a(2) * (1 - c) / w2;
    v(5) = a(2) * s / w;
    return v;
}

void CwPlant::sample_nav()
{
    const NavConfig &nc = cfg_.nav;
    NavSample s;
    s.step = static_cast<std::uint32_t>(k_);
    bool valid = true;
    for (const auto &d : nc.dropouts) {
        if (t_s_ >= d.first && t_s_ < d.second) { valid = false; }
    }
    // Draw every random number whatever the outcome, so streams stay aligned across settings.
    if (rng_drop_.uniform() < nc.p_drop) { valid = false; }
    std::array<double, 6> n{};
    for (double &v : n) { v = rng_noise_.gaussian(); }
    double dp = 0.0, dv = 0.0;
    while (next_outlier_ < nc.outliers.size() && nc.outliers[next_outlier_].first <= t_s_ + 1e-9) {
        dp += nc.outliers[next_outlier_].second.first;
        dv += nc.outliers[next_outlier_].second.second;
        ++next_outlier_;
    }
    const double r = std::sqrt(x_(0) * x_(0) + x_(2) * x_(2) + x_(4) * x_(4));
    if (!(r <= nc.range_max)) { valid = false; }
    for (int a = 0; a < 3; ++a) {
        const auto au = static_cast<size_t>(a);
        const double p = x_(2 * a) + nc.sp() * n[2 * au] + nc.bias_p[au] + dp;
        const double v = x_(2 * a + 1) + nc.sv() * n[2 * au + 1] + nc.bias_v[au] + dv;
        s.pos_mm[au] = count(p, 1e-3);
        s.vel_cnt[au] = count(v, 1e-5);
    }
    s.valid = valid;
    nav_ = s;
}

void CwPlant::step(std::uint8_t on_mask, const std::array<std::uint32_t, 6> &start_us,
                   const std::array<std::uint32_t, 6> &len_us)
{
    const std::uint32_t h = cfg_.period_us;
    // Effective windows after the minimum on-time and faults, in us within the step.
    std::array<std::uint32_t, 6> on{}, off{}, cmd_on{}, cmd_off{};
    for (int j = 0; j < 6; ++j) {
        const auto ju = static_cast<size_t>(j);
        std::uint32_t a = 0, b = 0;
        if (((static_cast<unsigned>(on_mask) >> j) & 1u) != 0u) {
            a = std::min(start_us[ju], h);
            b = std::min(h, a + len_us[ju]);
        }
        const bool cont = open_[ju] && a == 0 && b > a;
        if (open_[ju] && !cont && open_us_[ju] < cfg_.t_min_us) { ++short_burns_; }   // ended short last step
        if (b > a && !cont && b < h && b - a < cfg_.t_min_us) {
            ++short_burns_;   // a whole burn inside this step, shorter than t_min
            b = cfg_.stretch ? std::min(h, a + cfg_.t_min_us) : a;
        }
        if (b > a) {
            open_us_[ju] = (cont ? open_us_[ju] : 0u) + (b - a);
            if (cont && b < h && open_us_[ju] < cfg_.t_min_us) { ++short_burns_; }
        }
        open_[ju] = b > a && b == h;
        cmd_on[ju] = a;
        cmd_off[ju] = b;
        if (j == cfg_.stuck_off_j && t_s_ >= cfg_.stuck_off_t) { b = a; }
        if (j == cfg_.stuck_on_j && t_s_ >= cfg_.stuck_on_t) { a = 0; b = h; }
        on[ju] = a;
        off[ju] = b;
    }
    // Violation: both thrusters of one axis commanded in one step (spec 50 §2.4, §5.2); a stuck
    // valve is not the flight code's doing and is not counted.
    for (int r = 0; r < 3; ++r) {
        const auto p = static_cast<size_t>(2 * r), m = p + 1;
        if (cmd_off[p] > cmd_on[p] && cmd_off[m] > cmd_on[m]) { ++violations_; }
    }
    std::vector<std::uint32_t> knots{0, h};
    for (int j = 0; j < 6; ++j) {
        knots.push_back(on[static_cast<size_t>(j)]);
        knots.push_back(off[static_cast<size_t>(j)]);
    }
    std::sort(knots.begin(), knots.end());
    knots.erase(std::unique(knots.begin(), knots.end()), knots.end());
    for (size_t i = 0; i + 1 < knots.size(); ++i) {
        const std::uint32_t ta = knots[i], tb = knots[i + 1];
        const double dt = (tb - ta) * 1e-6;
        Eigen::Vector3d acc = Eigen::Vector3d::Zero();
        for (int j = 0; j < 6; ++j) {
            const auto ju = static_cast<size_t>(j);
            if (on[ju] <= ta && tb <= off[ju] && off[ju] > on[ju]) {
                const double sgn = (j % 2 == 0) ? 1.0 : -1.0;
                acc(j / 2) += sgn * level(j);
                dv_used_[ju] += level(j) * dt;
            }
        }
        x_ = phi(dt, cfg_.w) * x_ + psi(dt, cfg_.w, acc);
    }
    ++k_;
    t_s_ = static_cast<double>(k_) * h * 1e-6;
    if (k_ % nav_div_ == 0u) { sample_nav(); }
}

void CwPlant::step_mask(std::uint8_t on_mask)
{
    std::array<std::uint32_t, 6> st{}, len{};
    len.fill(cfg_.period_us);
    step(on_mask, st, len);
}

void CwPlant::nav_counts(std::array<std::int32_t, 3> &pos_mm, std::array<std::int32_t, 3> &vel_cnt) const
{
    for (int r = 0; r < 3; ++r) {
        pos_mm[static_cast<size_t>(r)] = count(x_(2 * r), 1e-3);
        vel_cnt[static_cast<size_t>(r)] = count(x_(2 * r + 1), 1e-5);
    }
}

}  // namespace sim
