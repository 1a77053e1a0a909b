// fsw_backend.hpp — in-process SIL backend around the executive (fsw/app/fsw_exec.h), for any
// mission of the build.
//
// The flight software in the loop is fsw_step() booted from a table image, exactly as a board
// boots; the bridge's frame becomes fsw_in_t (status STALE/SAT -> FSW_ST_*), command counts come
// from fsw_out_t, telemetry is fsw_tlm_encode() (the mission's layout). Table chunks go to
// fsw_table_upload() between steps; telecommands (namespaced ids) and mode commands go to the
// next step, and the executive decides whether they are taken.
#ifndef HIL_BRIDGE_FSW_BACKEND_HPP
#define HIL_BRIDGE_FSW_BACKEND_HPP

#include <cstdint>
#include <memory>
#include <vector>

#include "backend.hpp"
#include "frame_validator.hpp"

extern "C" {
#include "fsw_exec.h"
}

namespace bridge {

// The step inputs a backend holds between steps: a mode command and a telecommand for the next
// step only, and the bridge's counters the flight software copies into its telemetry. Every
// backend that hands fsw_in_t to the executive (in this process, or over the PIL link) goes
// through the three functions below, so a frame means the same fsw_in_t whatever runs it.
struct FswPending {
    std::uint32_t mode_cmd = FSW_CMD_NONE;
    std::uint32_t tc = FSW_TC_NONE;
    std::int32_t tc_arg[FSW_TC_ARGS] = {};
    std::uint32_t missed = 0;
    std::uint32_t rejected = 0;
};

// Backend::command's rule: a mode command (non-negative target) or a namespaced telecommand is
// held for the next step (true); anything else is refused (false). A later one replaces it.
bool hold_command(FswPending &p, const FswCommand &c);
// Backend::host_counters: missed and the rejection total, clamped to uint32.
void set_host_counters(FswPending &p, const Counters &c);
// Frame k as the executive's input: counts, STALE/SAT bits as FSW_ST_*, n_counts clamped to
// [0, FSW_IN_MAX], and p's held commands, which this step consumes.
fsw_in_t make_fsw_in(const Frame &f, FswPending &p);

class InProcessFswBackend final : public Backend {
public:
    // cfg: the executive's configuration (mission, period, stale_max, boot mode); boot: the
    // mission's table image (its encoder or a ground tool's file), or empty to boot without a
    // table (fsw_init(f, cfg, NULL, 0): the table then arrives by upload).
    InProcessFswBackend(const fsw_cfg_t &cfg, std::vector<std::uint8_t> boot);
    bool reset() override;
    bool step(const Frame &f, StepOutput &out) override;
    void host_counters(const Counters &c) override;
    bool table_chunk(const TableChunk &c, TableAck &ack) override;
    bool command(const FswCommand &c) override;
    const char *name() const override { return "sil-fsw"; }

    // fsw_init's verdict on the boot image (FSW_OK, or the loader's / module check's code).
    fsw_rc_t boot_rc() const { return boot_rc_; }
    const fsw_out_t &last_out() const { return out_; }
    // The bridge validator's limits: the mission's channel ranges under the active table
    // (fsw_sensor_ranges, the adapter's own channel map) and the executive's period. Without a
    // table the ranges are open: the flight code refuses every channel itself until one commits.
    SensorLimits sensor_limits() const;
    bool limits_changed(SensorLimits &lim) override;
    const fsw_t &fsw() const { return *f_; }

private:
    fsw_cfg_t cfg_{};
    std::vector<std::uint8_t> boot_;
    std::unique_ptr<fsw_t> f_;          // tens of KiB: on the heap of the host process
    fsw_out_t out_{};
    FswPending pend_;                         // held commands and host counters
    fsw_rc_t boot_rc_ = FSW_ERR_ARG;
    std::uint32_t lim_tbl_acc_ = 0;           // n_tbl_acc when the limits were last reported
};

}  // namespace bridge

#endif  // HIL_BRIDGE_FSW_BACKEND_HPP
