// pd_ref_backend.hpp — "reference FSW" SIL backend of the HOLD mission: the law in
// double precision (sim/pd/pd_ref) in place of the fixed-point flight code, on the
// same table and through the same bridge and LCM nodes, so `sil run --fsw ref` gives the closed
// loop the fixed-point run is compared with. It uses the flight code's channel ranges (the
// adapter's pd_mis_ranges) rather than retyping them. Telemetry is fsw_tlm_t filled from
// the double state (rounded to the flight counts), so every tool that reads a SIL log reads it.
#ifndef HIL_MISSIONS_PD_REF_BACKEND_HPP
#define HIL_MISSIONS_PD_REF_BACKEND_HPP

#include <cstdint>
#include <memory>

#include "backend.hpp"
#include "pd/pd_section.hpp"
#include "pd/pd_ref.hpp"

extern "C" {
#include "fsw_exec.h"
#include "pd_mission.h"
}

namespace host {

class RefPdBackend final : public bridge::Backend {
public:
    explicit RefPdBackend(const pd_params_t &table);
    bool reset() override;
    bool step(const bridge::Frame &f, bridge::StepOutput &out) override;
    void host_counters(const bridge::Counters &c) override;
    const char *name() const override { return "ref-pd"; }

private:
    pd_params_t p_;
    ref::PdTable t_;
    fsw_range_t rng_{};
    std::uint32_t step_ = 0, limited_run_ = 0;
    std::unique_ptr<fsw_tlm_t> tlm_;
    std::uint32_t missed_ = 0, rejected_ = 0;
};

}  // namespace host

#endif
