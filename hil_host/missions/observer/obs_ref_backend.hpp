// obs_ref_backend.hpp — "reference FSW" SIL backend of the DETUMBLE mission: the observer step
// in double precision (sim/observer/obs_ref, Eigen) in place of the fixed-point flight code, on
// the same table.
//
// It closes the same loop through the same bridge and LCM nodes, so a SIL run with it gives the
// double closed loop that spec 10 S0-8 compares the fixed-point SIL with. It covers the nominal
// path (both axes valid every step; the bridge's gate handles duplicates and stale frames) and
// starts like the flight code: initialise on the first complete sample, command on it.
// Telemetry is fsw_tlm_t filled from the double state (rounded to the flight formats), so every
// tool that reads a SIL log reads this one too. Analysis option: per-axis clipping of the
// command (never flight), which spec 10 S0-9 shows diverging where vector limiting settles.
#ifndef HIL_MISSIONS_OBS_REF_BACKEND_HPP
#define HIL_MISSIONS_OBS_REF_BACKEND_HPP

#include <cstdint>
#include <memory>

#include "backend.hpp"
#include "observer/obs_ref.hpp"

extern "C" {
#include "fsw_exec.h"
}

namespace host {

class RefObsBackend final : public bridge::Backend {
public:
    explicit RefObsBackend(const obs_params_t &table, bool per_axis_clip = false);
    bool reset() override;
    bool step(const bridge::Frame &f, bridge::StepOutput &out) override;
    void host_counters(const bridge::Counters &c) override;
    const char *name() const override { return per_axis_ ? "ref-obs-per-axis" : "ref-obs"; }

private:
    obs_params_t p_;
    ref::ObsTable t_;
    bool per_axis_;
    bool init_ = false;
    ref::ObsState st_;
    std::uint32_t step_ = 0, limited_run_ = 0;
    std::unique_ptr<fsw_tlm_t> tlm_;
    std::uint32_t missed_ = 0, rejected_ = 0;
};

}  // namespace host

#endif  // HIL_MISSIONS_OBS_REF_BACKEND_HPP
