#include "imp_loop.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "impulse/imp_ref_solver.hpp"
#include "sensors/rng.hpp"

namespace imploop {

Vec6 example_x0()
{
    Vec6 x;
    x << 5000, -1, 4000, -1, 4000, -1;
    return x;
}

Vec6 random_x0(std::uint64_t seed, double pos, double vel)
{
    sim::Rng rng(seed, 0x494D5058u);   // "IMPX": test-case stream
    Vec6 x;
    for (int i = 0; i < 6; ++i) { x(i) = (2.0 * rng.uniform() - 1.0) * ((i % 2 == 0) ? pos : vel); }
    return x;
}

double quantile(std::vector<double> v, double q)
{
    if (v.empty()) { return 0.0; }
    std::sort(v.begin(), v.end());
    const auto n = static_cast<double>(v.size());
    const auto i = static_cast<size_t>(std::max(0.0, std::ceil(q * n) - 1.0));
    return v[std::min(i, v.size() - 1)];
}

namespace {

void put_u32(std::vector<std::uint8_t> &b, std::uint32_t v)
{
    for (int i = 0; i < 4; ++i) { b.push_back(static_cast<std::uint8_t>(v >> (8 * i))); }
}

}  // namespace

Out fly(const Cfg &c)
{
    Out o;
    const imp_params_t &p = c.p;
    const double h = p.period_us * 1e-6;
    sim::CwConfig pc = c.plant;
    pc.period_us = p.period_us;
    pc.w = p.omega_nradps * 1e-9;
    pc.a_nom = p.a_nom_umps2 * 1e-6;
    const std::int64_t ks = c.start_step;
    const std::uint32_t t0 = c.t0_override ? c.t0_override
                                           : static_cast<std::uint32_t>(std::max<std::int64_t>(ks, 0)) + p.plan_lead;
    const std::uint32_t tf = c.tf_override ? c.tf_override : t0 + static_cast<std::uint32_t>(std::lround(c.T / h));
    o.t0 = t0;
    o.tf = tf;
    const Vec6 xs = sim::CwPlant::phi(-static_cast<double>(t0) * h, pc.w) * c.x0;
    sim::CwPlant plant(pc, xs);

    {   // the open-loop plan's delta-v, from the double reference solver
        ref::ImpCase rc;
        rc.w = pc.w;
        rc.a_nom = pc.a_nom;
        rc.T = (tf - t0) * h;
        rc.x0 = c.x0;
        const ref::ImpPlan pl = ref::solve(rc);
        if (pl.outcome == IMP_SOL_VALID) { o.plan_dv = (pl.dv[0] + pl.dv[1]) * rc.V(); }
    }

    std::unique_ptr<imp_state_t> s;
    std::unique_ptr<ref::ImpFsw> rf;
    imp_out_t out{};
    if (c.use_ref) {
        rf = std::make_unique<ref::ImpFsw>(p);
    } else {
        s = std::make_unique<imp_state_t>();
        (void)imp_init(s.get(), &p, &out);
    }
    std::vector<std::uint8_t> bytes;
    bool prev_job = false;
    std::uint32_t prev_plans = 0, prev_failed = 0, prev_late = 0;
    for (std::uint32_t k = 0; k <= tf + 20; ++k) {
        imp_in_t in{};
        const sim::NavSample &nv = plant.nav();
        in.step = k;
        for (int r = 0; r < 3; ++r) {
            in.nav_pos_mm[r] = nv.pos_mm[static_cast<size_t>(r)];
            in.nav_vel_cnt[r] = nv.vel_cnt[static_cast<size_t>(r)];
        }
        in.nav_step = nv.step;
        in.nav_valid = nv.valid ? 1u : 0u;
        in.avail_mask = c.avail;
        if (static_cast<std::int64_t>(k) == ks) {
            in.cmd = IMP_CMD_START;
            in.cmd_t0_step = t0;
            in.cmd_tf_step = tf;
        }
        if (c.use_ref) {
            rf->step(in, out);
        } else {
            imp_step(s.get(), &p, &in, &out);
        }
        const std::uint32_t hl = out.health;
        const unsigned mode = (hl & IMP_H_MODE) >> IMP_H_MODE_SH;
        o.health_or |= hl;
        o.fx_or |= hl & FX_ST_MASK;
        if (hl & IMP_H_INTERLOCK) { ++o.interlock_steps; }
        auto first = [&](std::int64_t &kk, bool cond) {
            if (cond && kk < 0) { kk = k; }
        };
        first(o.k_stuck_off, (hl & IMP_H_STUCK_OFF) != 0u);
        first(o.k_stuck_on, (hl & IMP_H_STUCK_ON) != 0u);
        first(o.k_thrust_level, (hl & IMP_H_THRUST_LEVEL) != 0u);
        first(o.k_nav_stale, (hl & IMP_H_NAV_STALE) != 0u && k >= t0 && k < tf);
        first(o.k_expected_miss, (hl & IMP_H_EXPECTED_MISS) != 0u);
        first(o.k_abort, mode == IMP_MODE_ABORTED);
        if (out.on_mask != 0u) {
            first(o.k_first_on, true);
            o.k_last_on = k;
            if (o.k_abort >= 0) { o.on_after_abort = true; }
        }
        if (o.k_second_burn < 0 && (mode == IMP_MODE_ARMED || mode == IMP_MODE_FIRING)) {
            std::int64_t e2 = tf;
            for (int r = 0; r < 3; ++r) { e2 = std::min<std::int64_t>(e2, out.tlm.on2_step[r]); }
            o.k_second_burn = e2;
        }
        if (!c.use_ref) {
            const bool job = out.tlm.job_active != 0u;
            const bool finished = (prev_job || out.tlm.plans > prev_plans) && !job;
            if (finished && out.tlm.plans_failed == prev_failed && out.tlm.plans_late == prev_late &&
                mode != IMP_MODE_ABORTED && mode != IMP_MODE_DONE) {
                ++o.accepted;
                o.fres_max = std::max({o.fres_max, out.tlm.fres_lsb[0], out.tlm.fres_lsb[1]});
            }
            prev_job = job;
            prev_plans = out.tlm.plans;
            prev_failed = out.tlm.plans_failed;
            prev_late = out.tlm.plans_late;
        }
        if (c.keep_trace) {
            o.masks.push_back(out.on_mask);
            o.healths.push_back(hl);
        }
        bytes.clear();
        bytes.push_back(out.on_mask);
        for (int j = 0; j < 6; ++j) {
            put_u32(bytes, out.on_start_cnt[j]);
            put_u32(bytes, out.on_len_cnt[j]);
        }
        put_u32(bytes, hl);
        o.crc = fx_crc32(o.crc, bytes.data(), bytes.size());
        if (k < tf) {
            std::array<std::uint32_t, 6> st{}, len{};
            for (int j = 0; j < 6; ++j) {
                st[static_cast<size_t>(j)] = out.on_start_cnt[j];
                len[static_cast<size_t>(j)] = out.on_len_cnt[j];
            }
            plant.step(out.on_mask, st, len);
        }
    }
    o.xf = plant.x();
    o.mr = std::sqrt(o.xf(0) * o.xf(0) + o.xf(2) * o.xf(2) + o.xf(4) * o.xf(4));
    o.mv = std::sqrt(o.xf(1) * o.xf(1) + o.xf(3) * o.xf(3) + o.xf(5) * o.xf(5));
    o.dv_j = plant.dv_used();
    for (double d : o.dv_j) { o.dv += d; }
    o.mode = (out.health & IMP_H_MODE) >> IMP_H_MODE_SH;
    o.tlm = out.tlm;
    o.plans = out.tlm.plans;
    o.failed = out.tlm.plans_failed;
    o.late = out.tlm.plans_late;
    o.skipped = out.tlm.plans_skipped;
    o.nav_rej = out.tlm.nav_rej;
    o.cal_rej = out.tlm.cal_rej;
    o.cmd_rej = out.tlm.cmd_rej;
    o.st_sticky = out.tlm.st_sticky;
    o.stuck_j = out.tlm.stuck_j;
    for (size_t j = 0; j < 6; ++j) { o.alpha[j] = out.tlm.alpha_q30[j] / 1073741824.0; }
    o.violations = plant.violations();
    o.short_burns = plant.short_burns();
    return o;
}

}  // namespace imploop
