// rly_long — the relay's long runs and statistics (spec 20 §2.3, §5, §7 S1, S4-S7), outside the suite;
// their results are in fsw/relay/README.md. Each closed loop is the exact plant (sim/relay rly_ref:
// closed form from the anchor with integer elapsed ticks) with either the fixed-point flight module
// (`--code flight`: rly_step on q24 samples, its own copy, windows and adaptation) or the double
// reference (`--code ref`: TickLaw + run_adaptive). The executive, bridge and LCM are left out — they
// carry the sample and the level code unchanged (sil run --batch proves the streams identical) and
// would cost most of the time.
//
//   rly_long exactness [--t 20000]                      S1: RK4 at 1e-4 s against drivers 1 and 2
//   rly_long stats --mode paper|improved|improved-up [--seeds 1-20] [--t 30000] [--code flight|ref] [--jobs 2] [--csv DIR]
//                                                       S5 / S7: per-seed freeze, k_t, late mean envelope
//   rly_long sweep [--from 0.28] [--to 0.40] [--step 0.001] [--t 20000] [--code ref|flight] [--jobs 2] [--csv DIR]
//                                                       S6 (continuous law) / S4, S6 spot checks (flight)
//   rly_long paper-errors                               §3.1 and §5.5 demonstrations
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "fsw_cli.hpp"
#include "relay/rly_ref.hpp"
#include "relay/rly_ref_params.hpp"

extern "C" {
#include "rly.h"
#include "rly_tables.h"
}

namespace {

constexpr double kQ40 = 1099511627776.0;

double wall_s(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int level_of(std::uint8_t c)
{
    switch (c) {
    case RLY_LVL_WEAK_POS: return 1;
    case RLY_LVL_WEAK_NEG: return -1;
    case RLY_LVL_FULL_POS: return 2;
    case RLY_LVL_FULL_NEG: return -2;
    default: return 0;
    }
}

struct WinRow {            // one closed window: what the plots of a(t) and k_t(t) per run need
    std::uint32_t j = 0;
    double t_end_s = 0.0;
    double abar_rad = 0.0;
    double kt_in = 0.0, kt_next = 0.0;
    int phase = 0, event = 0;
};

struct SeedResult {
    std::uint32_t seed = 0;
    std::vector<WinRow> windows;
    bool frozen = false;            // frozen at the end
    double t_first_freeze_s = -1.0;
    double kt_final = 0.0;
    double kt_min = 1.0, kt_max = 0.0;
    double abar_late = 0.0;         // mean of the window means over [t_late, t_end]
    double wall = 0.0;
};

// The fixed-point module in closed loop with the exact plant (published state, q24 samples).
SeedResult fly_flight(rly_params_t p, double t_end_s, double t_late_s)
{
    static_assert(sizeof(rly_state_t) < 4096, "state on the stack");
    SeedResult r;
    r.seed = p.seed;
    rly_state_t s;
    rly_init(&s, &p);
    const ref::RelayModel model;
    ref::RelayState anchor, now;
    int lvl = 1;
    std::uint64_t ticks = 0;
    const double h = p.period_us * 1e-6;
    const auto n = static_cast<std::uint64_t>(std::llround(t_end_s / h));
    rly_in_t in{};
    in.valid = true;
    rly_out_t o{};
    std::uint32_t windows = 0;
    double sum_late = 0.0;
    std::uint32_t n_late = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (std::uint64_t k = 0; k < n; ++k) {
        in.x_q24 = ref::quantise_q24(now.x());
        rly_step(&s, &p, &in, &o);
        if (s.tlm.n_windows != windows) {
            windows = s.tlm.n_windows;
            const double t_end_win = static_cast<double>(k + 1) * h;
            const double kt = s.tlm.win.kt_in_q16 / 65536.0;
            r.windows.push_back({s.tlm.win.j, t_end_win, s.tlm.win.abar_q40 / kQ40, kt,
                                 s.tlm.win.kt_next_q16 / 65536.0, s.tlm.win.phase, s.tlm.win.event});
            r.kt_min = std::min(r.kt_min, kt);
            r.kt_max = std::max(r.kt_max, kt);
            if (r.t_first_freeze_s < 0.0 &&
                (s.tlm.win.event == RLY_EV_FREEZE_SETTLED || s.tlm.win.event == RLY_EV_FREEZE_CLIFF)) {
                r.t_first_freeze_s = t_end_win;
            }
            if (t_end_win - p.win_ticks * h >= t_late_s - 1e-9) {
                sum_late += s.tlm.win.abar_q40 / kQ40;
                ++n_late;
            }
        }
        const int l = level_of(o.cmd);
        if (l != lvl) {
            anchor = now;
            ticks = 0;
            lvl = l;
        }
        ++ticks;
        now = ref::propagate(model, anchor, lvl, static_cast<double>(ticks) * h);
    }
    r.frozen = s.ad.phase == RLY_PH_FROZEN;
    r.kt_final = s.kt_q16 / 65536.0;
    r.abar_late = n_late ? sum_late / n_late : 0.0;
    r.wall = wall_s(t0);
    return r;
}

SeedResult fly_ref(const rly_params_t &p, double t_end_s, double t_late_s)
{
    SeedResult r;
    r.seed = p.seed;
    ref::RelayLaw law;
    law.h_s = p.period_us * 1e-6;
    ref::RunOptions opt;
    opt.quantise = true;
    const auto t0 = std::chrono::steady_clock::now();
    const ref::AdaptiveRun a =
        ref::run_adaptive(ref::RelayModel{}, law, ref::adapt_params_of(p), ref::RelayState{}, t_end_s, p.win_ticks, opt);
    double sum = 0.0;
    std::uint32_t n = 0;
    for (std::size_t j = 0; j < a.windows.size(); ++j) {
        const ref::WindowRecord &w = a.windows[j];
        const double t_end_win = static_cast<double>(j + 1) * p.win_ticks * law.h_s;
        const double kt = w.adapt.kt_in_force_q16 / 65536.0;
        r.windows.push_back({static_cast<std::uint32_t>(j), t_end_win, w.abar_rad, kt, w.adapt.kt_next_q16 / 65536.0,
                             static_cast<int>(w.adapt.phase), static_cast<int>(w.adapt.event)});
        r.kt_min = std::min(r.kt_min, kt);
        r.kt_max = std::max(r.kt_max, kt);
        if (r.t_first_freeze_s < 0.0 && (w.adapt.event == ref::AdaptEvent::FREEZE_SETTLED ||
                                         w.adapt.event == ref::AdaptEvent::FREEZE_CLIFF)) {
            r.t_first_freeze_s = t_end_win;
        }
        if (t_end_win - p.win_ticks * law.h_s >= t_late_s - 1e-9) {
            sum += w.abar_rad;
            ++n;
        }
    }
    r.frozen = !a.windows.empty() && a.windows.back().adapt.phase == ref::AdaptPhase::FROZEN;
    r.kt_final = a.windows.empty() ? 0.0 : a.windows.back().adapt.kt_next_q16 / 65536.0;
    r.abar_late = n ? sum / n : 0.0;
    r.wall = wall_s(t0);
    return r;
}

template <class F>
void parallel(std::size_t n, unsigned jobs, F f)
{
    std::atomic<std::size_t> next{0};
    std::vector<std::thread> th;
    for (unsigned j = 0; j < std::max(1u, jobs); ++j) {
        th.emplace_back([&]() {
            for (std::size_t i = next++; i < n; i = next++) {
                f(i);
            }
        });
    }
    for (auto &t : th) {
        t.join();
    }
}

double quantile(std::vector<double> v, double q)
{
    std::sort(v.begin(), v.end());
    if (v.empty()) { return 0.0; }
    const double pos = q * static_cast<double>(v.size() - 1);
    const auto lo = static_cast<std::size_t>(std::floor(pos));
    const std::size_t hi = std::min(lo + 1, v.size() - 1);
    return v[lo] + (pos - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

// --csv DIR: DIR/<mode>_<code>_runs.csv (one row per seed) and DIR/<mode>_<code>_windows.csv (one row
// per window and seed), read by tools/relay/long_plots.py.
void write_stats_csv(const std::string &dir, const std::string &tag, const std::vector<SeedResult> &res)
{
    const std::string runs = dir + "/" + tag + "_runs.csv", wins = dir + "/" + tag + "_windows.csv";
    std::FILE *f = std::fopen(runs.c_str(), "w");
    std::FILE *g = std::fopen(wins.c_str(), "w");
    if (f == nullptr || g == nullptr) {
        std::fprintf(stderr, "rly_long: cannot write %s or %s\n", runs.c_str(), wins.c_str());
        if (f != nullptr) { std::fclose(f); }
        if (g != nullptr) { std::fclose(g); }
        return;
    }
    std::fprintf(f, "seed,frozen,t_first_freeze_s,kt_final,kt_min,kt_max,abar_late_rad\n");
    std::fprintf(g, "seed,j,t_end_s,abar_rad,kt_in,kt_next,phase,event\n");
    for (const SeedResult &r : res) {
        std::fprintf(f, "%u,%d,%.1f,%.6f,%.6f,%.6f,%.6e\n", r.seed, r.frozen ? 1 : 0, r.t_first_freeze_s, r.kt_final,
                     r.kt_min, r.kt_max, r.abar_late);
        for (const WinRow &w : r.windows) {
            std::fprintf(g, "%u,%u,%.1f,%.6e,%.6f,%.6f,%d,%d\n", r.seed, w.j, w.t_end_s, w.abar_rad, w.kt_in,
                         w.kt_next, w.phase, w.event);
        }
    }
    std::fclose(f);
    std::fclose(g);
    std::printf("wrote %s, %s\n", runs.c_str(), wins.c_str());
}

int cmd_stats(const std::string &mode, std::uint32_t s0, std::uint32_t s1, double t_end, const std::string &code,
              unsigned jobs, const std::string &csv)
{
    rly_params_t base = (mode == "paper") ? RLY_TBL_PAPER : RLY_TBL_DEFAULT;
    if (mode == "improved") {
        base.adapt_mode = RLY_ADAPT_IMPROVED;        // spec 20 §5.6 as printed
    } else if (mode == "improved-up") {
        base.adapt_mode = RLY_ADAPT_IMPROVED_UP;     // the cliff armed only after an upward step
    }
    std::vector<SeedResult> res(s1 - s0 + 1);
    const double t_late = t_end - 10000.0;
    parallel(res.size(), jobs, [&](std::size_t i) {
        rly_params_t p = base;
        p.seed = s0 + static_cast<std::uint32_t>(i);
        res[i] = (code == "flight") ? fly_flight(p, t_end, t_late) : fly_ref(p, t_end, t_late);
    });
    std::printf("%s, %s code, seeds %u-%u, %.0f s at 1 ms, abar_late over [%.0f, %.0f] s\n", mode.c_str(), code.c_str(),
                s0, s1, t_end, t_late, t_end);
    std::printf(" seed frozen first_freeze_s kt_final  kt_range          abar_late  wall_s\n");
    std::vector<double> ab, ktf;
    int frozen = 0, early = 0, out = 0;
    for (const SeedResult &r : res) {
        std::printf(" %4u %6s %14.0f %8.5f  [%.5f, %.5f] %10.4g %7.1f\n", r.seed, r.frozen ? "yes" : "no",
                    r.t_first_freeze_s, r.kt_final, r.kt_min, r.kt_max, r.abar_late, r.wall);
        ab.push_back(r.abar_late);
        if (r.frozen) {
            ++frozen;
            ktf.push_back(r.kt_final);
        }
        early += (r.t_first_freeze_s >= 0.0 && r.t_first_freeze_s < 10000.0 - 1e-6) ? 1 : 0;
        out += (r.kt_min < 0.28 - 1e-9 || r.kt_max > 0.40 + 1e-9) ? 1 : 0;
    }
    std::printf("summary: frozen %d/%zu, frozen before 10000 s %d, k_t outside [0.28, 0.40] %d; frozen k_t median %.4f"
                " (range %.4f-%.4f); abar_late median %.4g, p90 %.4g, max %.4g\n",
                frozen, res.size(), early, out, quantile(ktf, 0.5), ktf.empty() ? 0.0 : *std::min_element(ktf.begin(), ktf.end()),
                ktf.empty() ? 0.0 : *std::max_element(ktf.begin(), ktf.end()), quantile(ab, 0.5), quantile(ab, 0.9),
                *std::max_element(ab.begin(), ab.end()));
    if (!csv.empty()) {
        write_stats_csv(csv, mode + "_" + code, res);
    }
    return 0;
}

// abar over [2000, t_end] at fixed k_t: driver 1 (ref) or the flight module with adaptation OFF.
double abar_at(double kt, double t_end, const std::string &code)
{
    if (code == "ref") {
        ref::RunOptions opt;
        opt.abar_t0_s = 2000.0;
        opt.abar_t1_s = t_end;
        opt.mean_dt_s = 0.01;
        return ref::run_continuous(ref::RelayModel{}, ref::RelayLaw{}, ref::RelayState{}, t_end, opt, kt).abar_rad;
    }
    rly_params_t p = RLY_TBL_FIXED_031;
    p.kt0_q16 = static_cast<std::uint16_t>(std::lround(kt * 65536.0));
    p.win_ticks = 100000u;   // 100-s windows: the mean over [2000, t_end] from whole windows
    const SeedResult r = fly_flight(p, t_end, 2000.0);
    return r.abar_late;
}

int cmd_sweep(double from, double to, double step, double t_end, const std::string &code, unsigned jobs,
              const std::string &csv)
{
    std::vector<double> kts;
    for (double k = from; k <= to + 1e-9; k += step) {
        kts.push_back(std::round(k * 1e6) / 1e6);
    }
    std::vector<double> ab(kts.size());
    const auto t0 = std::chrono::steady_clock::now();
    parallel(kts.size(), jobs, [&](std::size_t i) { ab[i] = abar_at(kts[i], t_end, code); });
    std::printf("abar over [2000, %.0f] s, %s\n kt      abar\n", t_end, code == "ref" ? "continuous law (driver 1)" :
                "flight module at 1 ms (q24 samples)");
    for (std::size_t i = 0; i < kts.size(); ++i) {
        std::printf(" %.4f  %.4g\n", kts[i], ab[i]);
    }
    std::printf("wall %.1f s\n", wall_s(t0));
    if (!csv.empty()) {
        const std::string path = csv + "/sweep_" + code + ".csv";
        std::FILE *f = std::fopen(path.c_str(), "w");
        if (f == nullptr) {
            std::fprintf(stderr, "rly_long: cannot write %s\n", path.c_str());
            return 1;
        }
        std::fprintf(f, "kt,abar_rad\n");
        for (std::size_t i = 0; i < kts.size(); ++i) {
            std::fprintf(f, "%.4f,%.6e\n", kts[i], ab[i]);
        }
        std::fclose(f);
        std::printf("wrote %s\n", path.c_str());
    }
    return 0;
}

int cmd_exactness(double t_end)
{
    const ref::RelayModel m;
    const ref::RelayState s0;
    ref::RelayLaw law;
    law.h_s = 1e-4;
    ref::RunOptions opt;
    opt.abar_t1_s = t_end;
    auto t0 = std::chrono::steady_clock::now();
    const ref::RelayRun d1 = ref::run_continuous(m, law, s0, t_end, opt);
    const double w1 = wall_s(t0);
    t0 = std::chrono::steady_clock::now();
    const ref::RelayRun d2 = ref::run_tick_sampled(m, law, s0, t_end, opt);
    const double w2 = wall_s(t0);
    t0 = std::chrono::steady_clock::now();
    const ref::RelayRun rk = ref::run_rk4(m, law, s0, t_end, 1e-4, opt);
    const double wr = wall_s(t0);
    auto maxdt = [](const ref::RelayRun &a, const ref::RelayRun &b, std::size_t n) {
        double d = 0.0;
        for (std::size_t i = 0; i < n && i < a.switches.size() && i < b.switches.size(); ++i) {
            d = std::max(d, std::fabs(a.switches[i].t_s - b.switches[i].t_s));
        }
        return d;
    };
    std::printf("relay_exactness (spec 20 §2.3), published state, k_t = 20316 / 2^16, %.0f s\n", t_end);
    std::printf("  first 40 switch times, RK4 vs driver 2 (h = 1e-4 s): max |dt| %.3g s (pass <= 1e-6)\n", maxdt(rk, d2, 40));
    std::printf("  abar over [2000, %.0f] s: RK4 %.6g, driver 2 %.6g (%.3g %%, pass 0.5 %%), driver 1 %.6g (RK4 vs driver 1"
                " %.3g %%, pass 1 %%)\n", t_end, rk.abar_rad, d2.abar_rad, 100.0 * std::fabs(rk.abar_rad / d2.abar_rad - 1.0),
                d1.abar_rad, 100.0 * std::fabs(rk.abar_rad / d1.abar_rad - 1.0));
    std::printf("  first 10 / 40 switch times, RK4 vs driver 1: %.3g / %.3g ms (reported; spec 2.5 / 7.2)\n",
                1e3 * maxdt(rk, d1, 10), 1e3 * maxdt(rk, d1, 40));
    std::printf("  wall: driver 1 %.3f s, driver 2 %.3f s, RK4 %.2f s (RK4 / driver 1 = %.0f)\n", w1, w2, wr, wr / w1);
    std::printf("  conclusion: RK4's truncation error is invisible; switch times move because switching is quantised to\n"
                "  the step, and those timing errors feed back through tau1 -> tau2.\n");
    return 0;
}

int cmd_paper_errors()
{
    // §3.1: the printed brake condition x <= -eps - gamma. A right main pulse (FULL_NEG) then runs until x
    // reaches -eps - gamma, i.e. through the whole deadband: measured on the rigid axis from x = eps.
    ref::RelayModel rigid;
    rigid.n_modes = 0;
    rigid.omega_radps = {{0.0, 0.0, 0.0, 0.0}};
    rigid.k = {{0.0, 0.0, 0.0, 0.0}};
    ref::RelayState s;
    s.q_rad = {{0.0, 0.0, 0.0, 0.0}};
    s.xbar_rad = 5e-4;
    s.xbardot_radps = 3.762879e-5;
    for (int printed = 0; printed < 2; ++printed) {
        const double edge = printed ? (-5e-4 - 1e-4) : (5e-4 - 1e-4);
        // FULL_NEG from x = eps until x <= edge: closed form x(t) = x0 + v t - m_u t^2 / 2
        const double v = s.xbardot_radps, a = 4e-5, d = s.xbar_rad - edge;
        const double t = (v + std::sqrt(v * v + 2.0 * a * d)) / a;
        const double v_end = v - a * t;
        std::printf("§3.1 brake condition %s: main pulse %.3f s, rate at its end %.3g rad/s%s\n",
                    printed ? "as printed (x <= -eps - gamma)" : "corrected (x <= eps - gamma)", t, v_end,
                    printed ? " — the pulse crosses the whole deadband and leaves it on the other side at"
                              " full speed: the right-hand cycle never brakes inside the deadband" : "");
    }
    // §5.4/§5.5: PAPER with dk = 0.001 freezes at T_min wherever k_t is; with 0.002 it climbs first.
    for (std::uint16_t dk : {static_cast<std::uint16_t>(66u), static_cast<std::uint16_t>(131u)}) {
        rly_params_t p = RLY_TBL_PAPER;
        p.dk_q16 = dk;
        std::vector<SeedResult> r(8);
        parallel(r.size(), 2u, [&](std::size_t i) {
            rly_params_t q = p;
            q.seed = static_cast<std::uint32_t>(i + 1);
            r[i] = fly_ref(q, 30000.0, 20000.0);
        });
        std::printf("§5.4 PAPER, dk = %.4f, seeds 1-8 (reference): first freeze [s] / frozen k_t:", dk / 65536.0);
        for (const SeedResult &x : r) {
            std::printf(" %.0f/%.4f", x.t_first_freeze_s, x.kt_final);
        }
        std::printf("\n");
    }
    // §5.5 item 2: the cliff just above 0.3389 (continuous law).
    std::printf("§5.5 cliff (continuous law, abar over [2000, 20000] s):");
    const double ks[] = {0.339, 0.340, 0.341, 0.342, 0.343};
    std::vector<double> ab(5);
    parallel(5, 2u, [&](std::size_t i) { ab[i] = abar_at(ks[i], 20000.0, "ref"); });
    for (std::size_t i = 0; i < 5; ++i) {
        std::printf(" %.3f: %.3g", ks[i], ab[i]);
    }
    std::printf("\n");
    return 0;
}

}  // namespace

int main(int argc, char **argv)
{
    CLI::App app{"rly_long: the relay's long runs and statistics (spec 20 §2.3, §5, §7)"};
    app.require_subcommand(1);
    double t_end = 0.0, from = 0.28, to = 0.40, step = 0.001;
    std::string mode = "paper", code = "flight", sweep_code = "ref", seeds = "1-20", csv;
    unsigned jobs = 2;
    CLI::App *ex = app.add_subcommand("exactness", "S1: RK4 against drivers 1 and 2 (relay_exactness)");
    ex->add_option("--t", t_end, "run length [s] (default 20000)");
    CLI::App *st = app.add_subcommand("stats", "S5/S7: PAPER or IMPROVED over seeds");
    st->add_option("--mode", mode, "paper, improved (spec 20 §5.6) or improved-up (the shipped default)")
        ->check(CLI::IsMember({"paper", "improved", "improved-up"}));
    st->add_option("--seeds", seeds, "A-B (default 1-20)");
    st->add_option("--t", t_end, "run length [s] (default 30000)");
    st->add_option("--code", code)->check(CLI::IsMember({"flight", "ref"}));
    st->add_option("--jobs", jobs);
    st->add_option("--csv", csv, "directory for <mode>_<code>_runs.csv and _windows.csv (tools/relay/long_plots.py)")
        ->check(CLI::ExistingDirectory);
    CLI::App *sw = app.add_subcommand("sweep", "S6/S4: abar(k_t) at fixed k_t");
    sw->add_option("--from", from);
    sw->add_option("--to", to);
    sw->add_option("--step", step);
    sw->add_option("--t", t_end, "run length [s] (default 20000)");
    sw->add_option("--code", sweep_code)->check(CLI::IsMember({"flight", "ref"}));
    sw->add_option("--jobs", jobs);
    sw->add_option("--csv", csv, "directory for sweep_<code>.csv (tools/relay/long_plots.py)")
        ->check(CLI::ExistingDirectory);
    CLI::App *pe = app.add_subcommand("paper-errors", "§3.1 and §5.5 demonstrations");
    CLI11_PARSE(app, argc, argv);
    if (*ex) {
        return cmd_exactness(t_end > 0.0 ? t_end : 20000.0);
    }
    if (*st) {
        unsigned a = 0, b = 0;
        if (std::sscanf(seeds.c_str(), "%u-%u", &a, &b) != 2 || a == 0 || b < a) {
            std::fprintf(stderr, "rly_long: --seeds A-B with 1 <= A <= B\n");
            return 2;
        }
        return cmd_stats(mode, a, b, t_end > 0.0 ? t_end : 30000.0, code, jobs, csv);
    }
    if (*sw) {
        return cmd_sweep(from, to, step, t_end > 0.0 ? t_end : 20000.0, sweep_code, jobs, csv);
    }
    (void)pe;
    return cmd_paper_errors();
}
