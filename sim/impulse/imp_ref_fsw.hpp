// imp_ref_fsw — the reference FSW of the impulse scheduler (spec 50-impulse §6): "--fsw ref" in
// the rendezvous SIL (hil_host/bridge RefImpBackend) and the host closed loop (tests/impulse).
//
// The whole scheduler in double precision with the flight code's decision logic (imp.c,
// imp_tl.c, imp_nav.c, imp_sched.c): START checks, plan with warm -> rule -> search, best
// rounding onto the valve grid with the minimum-impulse and coast rules, timeline, re-plan
// epochs and FINAL, thrust-level calibration, nav outlier gate, stuck-valve monitor, expected
// miss, interlock. Same in/out structs as the flight module (imp_in_t -> imp_out_t), so a SIL
// run can swap it in ("reference FSW") to bound SIL metrics. Differences from the flight code,
// by design: the plan is computed in the step it starts (the flight job spreads it over steps,
// at most plan_iter_per_step work units each, and always finishes before t_a with a valid
// table), so PLANNING is never reported and no plan is late; telemetry fills the counters,
// mode, pattern, thrust factors, expected miss and monitor fields only.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "impulse/imp_ref_solver.hpp"

namespace ref {

class ImpFsw {
public:
    explicit ImpFsw(const imp_params_t &p);
    void init();
    void step(const imp_in_t &in, imp_out_t &out);
    unsigned mode() const { return mode_; }
    const std::array<double, 6> &alpha() const { return alpha_; }

    struct Nav {
        std::uint32_t step = 0;
        Vec6 x = Vec6::Zero();
        bool valid = false;
    };
    struct Tl {
        std::uint32_t ta = 0, ntot = 0;
        std::array<std::uint32_t, 3> n1{}, n2{};
        std::array<double, 3> t1{}, t2{};
        std::array<unsigned, 3> thr1{}, thr2{};
        unsigned pattern = 0;
        bool valid = false;
    };
    // Best rounding of a valid plan onto the grid (nondimensional problem p, n_total grid units).
    void round_plan(const ImpNd &p, const ImpPlan &pl, std::uint32_t n_total, std::array<std::uint32_t, 3> &n1,
                    std::array<std::uint32_t, 3> &n2, Vec6 &miss) const;

private:
    struct Seg {
        unsigned thr;
        std::uint64_t s, e;
    };
    struct Win {
        std::array<Vec6, 6> r;
        std::array<std::uint64_t, 6> on{};
        Vec6 xp = Vec6::Zero(), m = Vec6::Zero();
    };

    double tau_g(std::uint64_t n) const { return static_cast<double>(n) * dg_; }
    Vec6 convert(const std::int32_t *pos, const std::int32_t *vel) const;
    bool covers(std::uint32_t k) const { return static_cast<std::uint64_t>(k) * G_ >= lost_g_; }
    bool fresh(std::uint32_t k) const;
    static bool active(unsigned m);
    static bool terminal(unsigned m);
    void burn_response(Win &w, unsigned j, std::uint64_t bs, std::uint64_t be, std::uint64_t k1g, std::uint64_t k2g,
                       std::uint64_t teg) const;
    void log_response(Win &w, std::uint64_t k1g, std::uint64_t k2g, std::uint64_t teg) const;
    void tl_response(Win &w, const Tl &tl, std::uint64_t k1g, std::uint64_t k2g, std::uint64_t teg) const;
    Vec6 predict(const Win &w, const Vec6 &x1, std::uint64_t dgu) const;
    Win window(const Nav &a, const Nav &b) const;
    Vec6 propagate(const Nav &nv, std::uint32_t now, std::uint32_t ta, bool use_tl) const;
    bool gate_ok(const Nav &c) const;
    unsigned fd_evaluate(const Win &w, std::uint32_t span);
    unsigned fd_step();
    unsigned nav_intake(const imp_in_t &in);
    void log_add(unsigned j, std::uint64_t a, std::uint64_t b, std::uint64_t step_g);
    void log_prune();
    bool cal_done(unsigned j) const;
    void cal_reset();
    bool cal_epoch();
    bool final_at(std::uint32_t ta) const;
    bool plan(const ImpNd &nd, const ImpSolveOpt &o, std::uint32_t ta, Tl &tl);
    void start_replan(const imp_in_t &in, unsigned kind, std::uint32_t ta);
    unsigned start(const imp_in_t &in);
    unsigned command(const imp_in_t &in);
    void fd_react(const imp_in_t &in, unsigned ev);
    void epoch(const imp_in_t &in, bool regular);
    void progress(const imp_in_t &in);
    unsigned fire(std::uint32_t k, unsigned avail, imp_out_t &out);
    unsigned health(const imp_in_t &in, imp_out_t &out);

    imp_params_t p_;
    double w_, dg_, wv_;
    std::uint32_t G_, us_, nmin_;
    ImpGuards g_;
    // state
    unsigned mode_ = IMP_MODE_IDLE;
    std::uint32_t t0_ = 0, tf_ = 0, next_tp_ = 0;
    bool retry_ = false, marginal_ = false;
    std::uint32_t latched_ = 0;
    unsigned stuck_off_ = 0;
    unsigned stuck_j_ = 0xFF;
    Tl act_, pend_;
    Nav nav_;
    bool seen_ = false;
    std::uint32_t seen_step_ = 0;
    std::vector<Seg> log_;
    std::uint64_t lost_g_ = 0;
    Nav cal_ref_;
    std::array<double, 6> sum_w_{}, sum_wa_{}, alpha_{};
    std::array<unsigned, 6> n_acc_{};
    Nav fd_x0_;
    std::array<unsigned, 6> cnt_off_{}, cnt_on_{};
    std::array<std::uint64_t, 6> on_tot_{};
    std::array<double, 3> exp_dr_{}, exp_dv_{};
    Vec6 miss_ = Vec6::Zero();
    std::uint32_t plans_ = 0, failed_ = 0, skipped_ = 0, cmd_rej_ = 0, nav_rej_ = 0, cal_rej_ = 0, kept_ = 0;
    unsigned rej_reason_ = 0, pattern_ = 0;
    std::uint32_t health_sticky_ = 0;
};

}  // namespace ref
