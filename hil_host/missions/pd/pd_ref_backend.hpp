// pd_ref_backend.hpp — "reference FSW" SIL backend of the HOLD mission: the three channels in double
// precision (sim/pd/pd_ref) in place of the fixed-point flight code, on the same table and through the
// same bridge and LCM nodes, so `sil run --fsw ref` gives the closed loop the fixed-point run is
// compared with (spec 40 G5). The adapter's rules are repeated here: the channel mask, the sample
// instants by seq (step divider, lost frames as gaps), a repeated seq counted as missing, the telecommands
// (SET_SOURCE 0..2: ADAPTIVE taken by the channels with a usable estimator, pitch and roll; yaw keeps its
// source). Telemetry is fsw_tlm_t filled from the double state (rounded to the flight formats), the
// estimator's fields (fest_f uq32, the fest word, P, att, FAULT count) included, so every tool that reads a
// SIL log (hil_host/missions/pd/pd_metrics) reads it as it reads the flight's.
#ifndef HIL_MISSIONS_PD_REF_BACKEND_HPP
#define HIL_MISSIONS_PD_REF_BACKEND_HPP

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "backend.hpp"
#include "pd/pd_ref.hpp"

extern "C" {
#include "fsw_exec.h"
#include "pd_mission.h"
}

namespace host {

class RefPdBackend final : public bridge::Backend {
public:
    explicit RefPdBackend(const pd_table_t &table);
    bool reset() override;
    bool command(const bridge::FswCommand &c) override;
    bool step(const bridge::Frame &f, bridge::StepOutput &out) override;
    void host_counters(const bridge::Counters &c) override;
    const char *name() const override { return "ref-pd"; }

private:
    pd_table_t t_;
    std::vector<ref::PdRefChannel> ch_;
    std::array<std::int32_t, PD_N_CH> act_{};
    std::uint32_t step_ = 0, health_ = 0;
    std::int64_t seq0_ = -1, last_seq_ = -1, last_idx_ = -1;
    std::uint32_t tc_ = 0;
    std::array<std::int32_t, FSW_TC_ARGS> tc_arg_{};
    std::unique_ptr<fsw_tlm_t> tlm_;
    std::uint32_t missed_ = 0, rejected_ = 0;
};

}  // namespace host

#endif
