// fsw_backend.hpp — in-process SIL backend around the executive (fsw/app/fsw_exec.h).
//
// The flight software in the loop is fsw_step() with its boot observer table; the bridge's
// frame becomes fsw_in_t (status STALE/SAT -> FSW_ST_*), command counts come from fsw_out_t,
// telemetry is fsw_tlm_encode() (layout FSW_TLM_LAYOUT_VERSION, fsw/app/fsw_tlm_formats.json).
// Table chunks go to fsw_table_upload() between steps, exactly as a board would take them.
#ifndef HIL_BRIDGE_FSW_BACKEND_HPP
#define HIL_BRIDGE_FSW_BACKEND_HPP

#include <cstdint>
#include <memory>
#include <string>

#include "backend.hpp"
#include "frame_validator.hpp"

extern "C" {
#include "fsw_exec.h"
}

namespace bridge {

// A boot observer table by name (obs_50hz_phys, obs_50hz_paper, obs_5hz_paper,
// obs_paper_printed), with the operator overrides of a scenario applied. Throws
// std::invalid_argument for an unknown name or an override that does not fit its Q format.
obs_params_t boot_obs_table(const std::string &name, double k_hat0_per_s2 = 0.0,
                            double bdot_max_degps = 0.0);
// A boot impulse table by name (imp_default: 0.1 s tick; imp_1s; imp_sub1ms: 1 ms valve grid).
imp_params_t boot_imp_table(const std::string &name);

class InProcessFswBackend final : public Backend {
public:
    // DETUMBLE mission: the observer with its boot table.
    InProcessFswBackend(const obs_params_t &boot, std::uint32_t revision = 1u,
                        std::uint16_t stale_max = 250u);
    // RENDEZVOUS mission: the impulse scheduler with its boot table, booting into RENDEZVOUS.
    explicit InProcessFswBackend(const imp_params_t &boot_imp, std::uint32_t revision = 1u);
    bool reset() override;
    bool step(const Frame &f, StepOutput &out) override;
    void host_counters(const Counters &c) override;
    bool table_chunk(const TableChunk &c, TableAck &ack) override;
    bool command(const FswCommand &c) override;
    const char *name() const override { return "sil-fsw"; }

    const fsw_out_t &last_out() const { return out_; }
    // Sensor limits for the bridge's validator: the observer table's gyro range, or the nav
    // ranges the executive accepts (fsw_exec.h FSW_NAV_*).
    SensorLimits sensor_limits() const;
    const fsw_t &fsw() const { return *f_; }

private:
    obs_params_t boot_{};
    imp_params_t boot_imp_{};
    std::uint32_t revision_;
    fsw_cfg_t cfg_{};
    std::unique_ptr<fsw_t> f_;          // ~12 KiB: on the heap of the host process
    fsw_out_t out_{};
    std::uint32_t missed_ = 0, rejected_ = 0;
    std::uint32_t mode_cmd_ = FSW_CMD_NONE;   // for the next step only
    std::uint32_t tc_ = FSW_TC_NONE;          // module telecommand for the next step only
    std::int32_t tc_arg_[8] = {};
    bool ok_ = false;
};

}  // namespace bridge

#endif  // HIL_BRIDGE_FSW_BACKEND_HPP
