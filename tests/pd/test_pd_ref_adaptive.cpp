// The reference backend flies ADAPTIVE (spec 40 §4.2, §4.4 A, G5): `--fsw ref` with the estimator's
// double design (sim/pd/pd_fest_ref, FestRef) and the §4.2 re-tune rule as fsw/pd/pd.c applies it,
// against the flight code (`--fsw fixed`) on the same scenario, through the in-process SIL harness of
// test_pd_sil.cpp: sim/pd/scenarios/pd_adaptive.yaml (boot table pd_adaptive: pitch and roll ADAPTIVE
// from boot, ch_mask 6; pitch displaced 0.017 rad; cold start at k2_cold) at its 0.03 Hz and at 0.01
// and 0.10 Hz, and at 0.03 Hz under 5 % frame loss (the gap path). And yaw: refused ADAPTIVE by the
// reference exactly where the flight refuses it.
//
// Bounds, derived (the measured figures are printed):
// - t* (pitch): the spec's G5 bound max(1 s, 2 %), as A3-4 in test_pd_sil.cpp. The two loops see the
//   same noise sequence; at equal gains their torques differ by <= 1 actuator count on rare samples
//   (A3-4: max |x_fx - x_ref| <= 2e-6 rad), so t* can move only where the band's last crossing is
//   marginal, and only if the re-tunes fall on the same periods — which the f_hat and k2 bounds below
//   check.
// - f_hat at 300 s and 1 200 s: golden G3 (test_pd_fest_golden_host) measures the port within
//   0.002 % of the double design on one input stream (fsw/pd/README.md "The estimator in fixed
//   point"). In closed loop the streams differ: the flight feeds its q28 torque, the reference its
//   double one (<= 2^-29 N m apart), and both round to the same 2^-20 N m actuator count except where
//   the two straddle a half count, so the attitudes differ by <= 2e-6 rad (A3-4's bound, asserted below;
//   measured <= 1e-8 rad here, 5e-8 rad under frame loss: < 1/40 of the noise sigma_y = 2e-6 rad the
//   estimator is built to ignore). Such a perturbation moves the raw estimate by far less than the port's own rounding over
//   the RLS memory, so the difference stays G3's: bound 5 x 0.002 % = 0.01 % (measured <= 0.0016 %).
//   The one way past it is the published f_hat's hysteresis (in TRACK it moves only by >= 0.5 %): two
//   raw estimates a hair apart can straddle a step and publish values one step apart (G3's own bound
//   allows that, 0.6 %). Here the runs are deterministic (one seed) and no straddle occurs; one that did
//   would also put the re-tunes on different periods, which is the divergence this test exists to
//   flag, so the tight bound is kept and a failure should be read with that in mind.
// - k2 final: k2 = sched(f_hat) at the last accepted re-tune, so the two k2 differ by at most the
//   schedule's change over the f_hat bound around the reference's f_hat(1200): max over
//   f in f_ref (1 +- 0.01 %) of |sched(f) - sched(f_ref)| (the schedule's slope x the f_hat bound,
//   evaluated on the table's own nodes), plus the schedule's own resolution: its fraction phi is
//   rounded to 2^-16 of a node step (<= max node step / 2^16 apart for f a hair apart) and the
//   flight's k2 to one uq22 LSB.
// - FAULT: none in either (fest_resets == 0, PD_H_FEST_FAULT never set).
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "pd/pd_fest_ref.hpp"
#include "pd/pd_metrics.hpp"
#include "pd/pd_ref.hpp"
#include "pd/pd_section.hpp"
#include "scenario/scenario.hpp"
#include "sil_run.hpp"
#include "pd_sil_harness.hpp"
extern "C" {
#include "fsw_ids.h"
#include "pd.h"
#include "pd_ids.h"
#include "pd_mission.h"
}
// last: cmocka.h defines macros (fail, ...) that clash with the standard library headers
#include "sim_test.hpp"

namespace {

using pd_sil::body;
using pd_sil::command;
using pd_sil::fly;
using pd_sil::mm;

void common_checks(const sil::InprocResult &r)
{
    EXPECT_TRUE(!r.plant.diverged && r.plant.deterministic());
    EXPECT_EQ_INT(r.summary.number("fsw_n_safe"), 0);
    EXPECT_EQ_INT(r.summary.number("t_first_fx_status_s"), -1);
}

const char *const kCh[] = {"yaw", "roll", "pitch"};
constexpr std::size_t kPitch = 2;
constexpr double kFBound = 1e-4;    // f_hat, relative: 5 x G3's measured 0.002 % (above)

std::shared_ptr<const ref::pd::FestParams> design(std::size_t k)
{
    return std::make_shared<const ref::pd::FestParams>(ref::pd::make_fest_params(ref::pd::Channel::by_name(kCh[k])));
}

// One scenario flown by both backends, compared with the bounds above.
void compare(const sim::Scenario &s, const char *label)
{
    const pd_table_t tbl = sim::pd_boot_table(s.fsw.table);
    pd_params_t pp{};
    pd_params_of(&tbl, static_cast<std::uint32_t>(kPitch), &pp);
    const ref::PdChannelTable pt = ref::dequantise(pp);
    const double f = s.mission_part<sim::PdScenario>().body.f_hz;
    const sil::InprocResult fx = fly(s, "fixed");
    const sil::InprocResult rf = fly(s, "ref");
    common_checks(fx);
    EXPECT_TRUE(!rf.plant.diverged && rf.plant.deterministic());
    const host::PdMetrics &a = mm(fx), &b = mm(rf);
    const double ta = a.t_settle(kPitch), tb = b.t_settle(kPitch);
    const double fa3 = a.fest_f_at(kPitch, 300.0), fb3 = b.fest_f_at(kPitch, 300.0);
    const double fa12 = a.fest_f_at(kPitch, 1200.0), fb12 = b.fest_f_at(kPitch, 1200.0);
    const double ka = a.k2_final[kPitch], kb = b.k2_final[kPitch];
    // the k2 bound: the schedule's change over f_ref(1200) (1 +- kFBound), plus one phi step, one uq22 LSB
    double node_step = 0.0;
    for (std::size_t i = 0; i + 1 < PD_N_NODES; ++i) {
        node_step = std::fmax(node_step, std::fabs(pt.k2_node[i + 1] - pt.k2_node[i]));
    }
    const double k0 = ref::pd_sched_k2(pt, fb12);
    const double dk = std::fmax(std::fabs(ref::pd_sched_k2(pt, fb12 * (1.0 + kFBound)) - k0),
                                std::fabs(ref::pd_sched_k2(pt, fb12 * (1.0 - kFBound)) - k0)) +
                      node_step / 65536.0 + std::ldexp(1.0, -22);
    double max_dx = 0.0;
    for (std::size_t i = 0; i < a.x[kPitch].size() && i < b.x[kPitch].size(); ++i) {
        max_dx = std::fmax(max_dx, std::fabs(a.x[kPitch][i] - b.x[kPitch][i]));
    }
    std::printf("REF-ADAPTIVE pitch f %.2f Hz%s: t* fixed %.2f ref %.2f s; f^(300) fixed %.8f ref %.8f Hz (%+.5f %%); "
                "f^(1200) fixed %.8f ref %.8f Hz (%+.5f %%); k2 final fixed %.4f ref %.4f s (bound %.4f s, "
                "sched(f^ref) %.4f); k2 changes %u / %u; FAULTs %u / %u; miss %.0f / %.0f; max |x_fx - x_ref| %.3e rad; "
                "health OR 0x%08x / 0x%08x\n",
                f, label, ta, tb, fa3, fb3, 100.0 * (fa3 / fb3 - 1.0), fa12, fb12, 100.0 * (fa12 / fb12 - 1.0), ka, kb,
                dk, k0, a.k2_changes[kPitch], b.k2_changes[kPitch], a.fest_resets[kPitch], b.fest_resets[kPitch],
                fx.summary.number("fsw_pd_pitch_miss"), rf.summary.number("fsw_pd_pitch_miss"), max_dx,
                a.health_or[kPitch], b.health_or[kPitch]);
    // the trajectories: A3-4's bound (the same noise; at most one actuator count apart on rare samples)
    EXPECT_LE(max_dx, 2e-6);
    // both fly ADAPTIVE (the source in the health word) and re-tune
    EXPECT_EQ_INT((a.health_or[kPitch] & PD_H_SRC) >> PD_H_SRC_SH, PD_SRC_ADAPTIVE);
    EXPECT_EQ_INT((b.health_or[kPitch] & PD_H_SRC) >> PD_H_SRC_SH, PD_SRC_ADAPTIVE);
    EXPECT_TRUE(a.k2_changes[kPitch] > 0u && b.k2_changes[kPitch] > 0u);
    // t*
    EXPECT_TRUE(ta > 0.0 && tb > 0.0);
    EXPECT_NEAR(ta, tb, std::fmax(1.0, 0.02 * tb));
    // f_hat at 300 s and 1 200 s
    EXPECT_TRUE(fb3 > 0.0 && fb12 > 0.0);
    EXPECT_LE(std::fabs(fa3 / fb3 - 1.0), kFBound);
    EXPECT_LE(std::fabs(fa12 / fb12 - 1.0), kFBound);
    // k2 final
    EXPECT_LE(std::fabs(ka - kb), dk);
    // no FAULT in either
    EXPECT_EQ_INT(a.fest_resets[kPitch], 0);
    EXPECT_EQ_INT(b.fest_resets[kPitch], 0);
    EXPECT_EQ_INT(a.health_or[kPitch] & PD_H_FEST_FAULT, 0);
    EXPECT_EQ_INT(b.health_or[kPitch] & PD_H_FEST_FAULT, 0);
}

}  // namespace

SIM_TEST(ref_adaptive_pitch_matches_the_flight)
{
    for (double f : {0.01, 0.03, 0.10}) {
        sim::Scenario s = sim::load_scenario(SCENARIO_DIR "/pd_adaptive.yaml");
        body(s).f_hz = f;
        compare(s, "");
    }
}

// The gap path (pd_note_gap: swallowed samples fed to the estimator as invalid ones with the held
// torque, counted against n_bad_max in the re-tune rule): 5 % of the frames lost on the link with
// re-publication off (as A3-10 in test_pd_sil.cpp), same seed for both backends, same bounds.
SIM_TEST(ref_adaptive_pitch_matches_the_flight_under_frame_loss)
{
    sim::Scenario s = sim::load_scenario(SCENARIO_DIR "/pd_adaptive.yaml");
    s.faults.drop_ppm = 50000u;
    s.faults.seed = 7u;
    s.lockstep.retx_max = 0u;
    compare(s, ", 5 % frame loss");
}

// Who may fly ADAPTIVE, flight and reference alike: every channel of the committed tables (yaw's block
// has two sections), and no channel whose block fails pd_fest_check (here each block with n_sec = 3): a
// table with such a channel flying ADAPTIVE is vetoed (PD_WHY_MODE), the reference's channel refuses
// that boot source, and SET_SOURCE 2 is refused by both. In SIL SET_SOURCE 2 takes all three channels
// ADAPTIVE on both backends.
// channel k's parameters from tbl; bad: its estimator block corrupted (n_sec = 3)
static pd_params_t params_of(const pd_table_t &tbl, std::uint32_t k, bool bad)
{
    pd_params_t p{};
    pd_params_of(&tbl, k, &p);
    if (bad) {
        p.g.fest.n_sec = 3u;
    }
    return p;
}

SIM_TEST(ref_adaptive_accepted_and_refused_where_the_flight_is)
{
    pd_table_t tbl = sim::pd_boot_table("pd_adaptive");
    for (int bad = 0; bad < 2; ++bad) {
        for (std::uint32_t k = 0; k < PD_N_CH; ++k) {
            pd_params_t p = params_of(tbl, k, bad != 0);
            std::uint32_t why = 0u;
            const bool fl_ok = pd_params_check(&p, &why) == FSW_OK;
            const ref::PdChannelTable t = ref::dequantise(p);
            bool ref_ok = true;
            try {
                ref::PdRefChannel c(t, design(k));
            } catch (const std::invalid_argument &) {
                ref_ok = false;
            }
            std::printf("boot ADAPTIVE %-5s%s: flight %s (why 0x%02x, pd_fest_check %u), reference %s\n", kCh[k],
                        bad != 0 ? " n_sec 3" : "", fl_ok ? "accepts" : "refuses", why, pd_fest_check(&p.g.fest),
                        ref_ok ? "accepts" : "refuses");
            EXPECT_TRUE(fl_ok == ref_ok);
            EXPECT_TRUE(fl_ok == (bad == 0));
            EXPECT_TRUE(t.fest_ok == (bad == 0));
        }
    }
    // the whole table with yaw flying: passes; with yaw's block corrupt, vetoed for PD_WHY_MODE
    std::uint32_t why = 0u;
    pd_params_t chk{};
    tbl.c.ch_mask = 7u;
    EXPECT_EQ_INT(pd_table_check(&tbl, &chk, &why), 0);
    tbl.ch[0].fest.n_sec = 3u;
    EXPECT_TRUE((pd_table_check(&tbl, &chk, &why) & PD_WHY_MODE) != 0u);

    // SET_SOURCE ADAPTIVE on a FIXED boot (pd_default): pd_set_source vs PdRefChannel::set_source,
    // the committed blocks and yaw's corrupt one
    const pd_table_t def = sim::pd_boot_table("pd_default");
    for (int bad = 0; bad < 2; ++bad) {
        for (std::uint32_t k = 0; k < PD_N_CH; ++k) {
            pd_params_t p = params_of(def, k, bad != 0);
            pd_state_t st{};
            pd_init(&st, &p);
            const bool fl = pd_set_source(&st, &p, static_cast<std::uint8_t>(PD_SRC_ADAPTIVE));
            ref::PdRefChannel c(ref::dequantise(p), design(k));
            const bool rf = c.set_source(PD_SRC_ADAPTIVE);
            std::printf("SET_SOURCE ADAPTIVE %-5s%s: flight %s (source %u), reference %s (source %d)\n", kCh[k],
                        bad != 0 ? " n_sec 3" : "", fl ? "takes it" : "refuses", st.src, rf ? "takes it" : "refuses",
                        c.source());
            EXPECT_TRUE(fl == rf);
            EXPECT_TRUE(fl == (bad == 0));
            EXPECT_EQ_INT(c.source(), st.src);
            // the cold start: k2_cold from the next sample in both (one missing sample stepped)
            pd_in_t in{};
            pd_out_t out{};
            pd_step(&st, &p, &in, &out);
            (void)c.step(ref::PdRefIn{});
            EXPECT_NEAR(std::ldexp(static_cast<double>(st.k2_q22), -22), c.k2(), 0.0);
            if (fl) { EXPECT_EQ_INT(st.k2_q22, p.g.k2_cold_q22); }
        }
    }

    // in SIL: pd_nominal (FIXED boot, all channels fly), SET_SOURCE 2 at t = 0, 60 s
    sim::Scenario s = sim::load_scenario(SCENARIO_DIR "/pd_nominal.yaml");
    s.duration_s = 60.0;
    command(s, PD_CMD_SET_SOURCE, static_cast<std::int32_t>(PD_SRC_ADAPTIVE));
    const sil::InprocResult fx = fly(s, "fixed");
    const sil::InprocResult rf = fly(s, "ref");
    for (std::size_t k = 0; k < PD_N_CH; ++k) {
        const std::uint32_t sa = (mm(fx).health_or[k] & PD_H_SRC) >> PD_H_SRC_SH;
        const std::uint32_t sb = (mm(rf).health_or[k] & PD_H_SRC) >> PD_H_SRC_SH;
        std::printf("SIL SET_SOURCE ADAPTIVE %-5s: source OR fixed %u ref %u, k2 final %.4f / %.4f s\n", kCh[k], sa, sb,
                    mm(fx).k2_final[k], mm(rf).k2_final[k]);
        // the health word's source field ORed over the run: ADAPTIVE (2) on every channel (the command
        // arrives before the first sample)
        EXPECT_EQ_INT(sa, PD_SRC_ADAPTIVE);
        EXPECT_EQ_INT(sb, sa);
        EXPECT_NEAR(mm(rf).k2_final[k], mm(fx).k2_final[k], 0.0);   // k2_cold at 60 s
    }
}

int main()
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(ref_adaptive_pitch_matches_the_flight),
                                       cmocka_unit_test(ref_adaptive_pitch_matches_the_flight_under_frame_loss),
                                       cmocka_unit_test(ref_adaptive_accepted_and_refused_where_the_flight_is)};
    return cmocka_run_group_tests_name("pd_ref_adaptive", tests, nullptr, nullptr);
}
