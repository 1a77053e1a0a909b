// imp_ref_backend.hpp — "reference FSW" SIL backend of the RENDEZVOUS mission: the impulse
// scheduler in double (sim/impulse ref::ImpFsw, same decision logic, same imp_in_t / imp_out_t)
// behind the same channel map and telecommands as the flight adapter (fsw/impulse/imp_mission.c),
// for spec 50 A4-4's comparison of SIL miss statistics. Nav is one 7-channel sample, valid only
// as a whole, with the adapter's own ranges (imp_mis_ranges); telemetry is the RENDEZVOUS layout
// with the reference's telemetry fields.
#ifndef HIL_MISSIONS_IMP_REF_BACKEND_HPP
#define HIL_MISSIONS_IMP_REF_BACKEND_HPP

#include <cstdint>
#include <memory>

#include "backend.hpp"
#include "impulse/imp_ref_fsw.hpp"

extern "C" {
#include "fsw_exec.h"
}

namespace host {

class RefImpBackend final : public bridge::Backend {
public:
    explicit RefImpBackend(const imp_params_t &table);
    bool reset() override;
    bool step(const bridge::Frame &f, bridge::StepOutput &out) override;
    void host_counters(const bridge::Counters &c) override;
    bool command(const bridge::FswCommand &c) override;
    const char *name() const override { return "ref-imp"; }

private:
    imp_params_t p_;
    std::unique_ptr<imp_mis_t> chan_;   // the flight adapter's block, only for its channel map
    std::unique_ptr<ref::ImpFsw> fsw_;
    std::unique_ptr<fsw_tlm_t> tlm_;
    std::uint32_t step_ = 0;
    std::uint32_t tc_ = 0;              // local id of this step's telecommand
    std::int32_t tc_arg_[FSW_TC_ARGS] = {};
    std::uint32_t missed_ = 0, rejected_ = 0;
};

}  // namespace host

#endif  // HIL_MISSIONS_IMP_REF_BACKEND_HPP
