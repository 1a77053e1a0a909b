// pd_sil_harness.hpp — the in-process SIL harness the HOLD closed-loop tests share (test_pd_sil.cpp,
// test_pd_ref_adaptive.cpp): fly a scenario with the flight code ("fixed") or a reference backend
// ("ref"), read its PdMetrics, edit its HOLD part, queue a telecommand at t = 0.
#ifndef TESTS_PD_SIL_HARNESS_HPP
#define TESTS_PD_SIL_HARNESS_HPP

#include <cstdint>
#include <string>

#include "pd/pd_metrics.hpp"
#include "pd/pd_section.hpp"
#include "scenario/scenario.hpp"
#include "sil_run.hpp"
extern "C" {
#include "fsw_ids.h"
}

namespace pd_sil {

inline sil::InprocResult fly(const sim::Scenario &s, const std::string &fsw)
{
    sil::InprocOptions o;
    o.fsw = fsw;
    return sil::run_inproc(s, o);
}

inline const host::PdMetrics &mm(const sil::InprocResult &r) { return r.metrics<host::PdMetrics>(); }
inline sim::PdSetup &body(sim::Scenario &s) { return s.mission_part<sim::PdScenario>().body; }

// A HOLD telecommand (its local id, args in flight units) before the first frame.
inline void command(sim::Scenario &s, std::uint32_t local, std::int32_t a0, std::int32_t a1 = 0, std::int32_t a2 = 0)
{
    sim::ScnCommand c;
    c.t_s = 0.0;
    c.name = "test";
    c.cmd = static_cast<std::int32_t>(FSW_TC_ID(FSW_MISSION_HOLD, local));
    c.args[0] = a0;
    c.args[1] = a1;
    c.args[2] = a2;
    s.commands.push_back(c);
}

}  // namespace pd_sil

#endif
