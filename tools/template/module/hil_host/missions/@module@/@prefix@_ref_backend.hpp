// @prefix@_ref_backend.hpp — "reference FSW" SIL backend of the @MISSION@ mission: the law in
// double precision (sim/@module@/@prefix@_ref) in place of the fixed-point flight code, on the
// same table and through the same bridge and LCM nodes, so `sil run --fsw ref` gives the closed
// loop the fixed-point run is compared with. It uses the flight code's channel ranges (the
// adapter's @prefix@_mis_ranges) rather than retyping them. Telemetry is fsw_tlm_t filled from
// the double state (rounded to the flight counts), so every tool that reads a SIL log reads it.
#ifndef HIL_MISSIONS_@PREFIX@_REF_BACKEND_HPP
#define HIL_MISSIONS_@PREFIX@_REF_BACKEND_HPP

#include <cstdint>
#include <memory>

#include "backend.hpp"
#include "@module@/@module@_section.hpp"
#include "@module@/@prefix@_ref.hpp"

extern "C" {
#include "fsw_exec.h"
#include "@prefix@_mission.h"
}

namespace host {

class Ref@Class@Backend final : public bridge::Backend {
public:
    explicit Ref@Class@Backend(const @prefix@_params_t &table);
    bool reset() override;
    bool step(const bridge::Frame &f, bridge::StepOutput &out) override;
    void host_counters(const bridge::Counters &c) override;
    const char *name() const override { return "ref-@prefix@"; }

private:
    @prefix@_params_t p_;
    ref::@Class@Table t_;
    fsw_range_t rng_{};
    std::uint32_t step_ = 0, limited_run_ = 0;
    std::unique_ptr<fsw_tlm_t> tlm_;
    std::uint32_t missed_ = 0, rejected_ = 0;
};

}  // namespace host

#endif
