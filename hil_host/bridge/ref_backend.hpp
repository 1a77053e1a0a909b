// ref_backend.hpp — "reference FSW" SIL backend: the observer step in double precision
// (sim/reference/obs_ref, Eigen) in place of the fixed-point flight code, on the same table.
//
// It closes the same loop through the same bridge and LCM nodes, so a SIL run with it gives the
// double closed loop that spec 10 S0-8 compares the fixed-point SIL with. It covers the nominal
// path (both axes valid every step; the bridge's gate handles duplicates and stale frames) and
// starts like the flight code: initialise on the first complete sample, command on it.
// Telemetry is fsw_tlm_t filled from the double state (rounded to the flight formats), so every
// tool that reads a SIL log reads this one too. Analysis option: per-axis clipping of the
// command (never flight), which spec 10 S0-9 shows diverging where vector limiting settles.
#ifndef HIL_BRIDGE_REF_BACKEND_HPP
#define HIL_BRIDGE_REF_BACKEND_HPP

#include <cstdint>
#include <memory>

#include "backend.hpp"
#include "imp_ref_fsw.hpp"
#include "obs_ref.hpp"

extern "C" {
#include "fsw_exec.h"
}

namespace bridge {

class RefObsBackend final : public Backend {
public:
    explicit RefObsBackend(const obs_params_t &table, bool per_axis_clip = false);
    bool reset() override;
    bool step(const Frame &f, StepOutput &out) override;
    void host_counters(const Counters &c) override;
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

// The rendezvous "reference FSW": the impulse scheduler in double (sim/impulse ref::ImpFsw,
// same decision logic, same imp_in_t / imp_out_t) behind the same channel maps and telecommands
// as the executive's RENDEZVOUS mission (fsw_exec.h), for spec 50 A4-4's comparison of SIL miss
// statistics. Nav is taken as one 7-channel sample, valid only as a whole, exactly as the
// executive does; telemetry is the RENDEZVOUS layout with the reference's telemetry fields.
class RefImpBackend final : public Backend {
public:
    explicit RefImpBackend(const imp_params_t &table);
    bool reset() override;
    bool step(const Frame &f, StepOutput &out) override;
    void host_counters(const Counters &c) override;
    bool command(const FswCommand &c) override;
    const char *name() const override { return "ref-imp"; }

private:
    imp_params_t p_;
    std::unique_ptr<ref::ImpFsw> fsw_;
    std::unique_ptr<fsw_tlm_t> tlm_;
    std::uint32_t step_ = 0;
    std::int32_t tc_ = 0;
    std::int32_t tc_arg_[8] = {};
    std::uint32_t missed_ = 0, rejected_ = 0;
};

}  // namespace bridge

#endif  // HIL_BRIDGE_REF_BACKEND_HPP
