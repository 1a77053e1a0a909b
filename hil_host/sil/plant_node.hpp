// plant_node.hpp — the plant side of the lock-step protocol (spec 00 §5.2) over LCM.
//
// The simulator owns the clock: publish frame k (and truth k), wait for command k, apply it
// (or hold the last one: a missed command), propagate, repeat. Faults of the scenario are
// applied on the way out (hil_host/fault: drop, duplicate, reorder, bit flip, truncate; plus
// a NaN truth and an out-of-range count window on one channel).
//
// Two waiting disciplines:
//   sync  (memq, one thread): the plant drains the lcm_t queue; everything the bridge will ever
//         answer has then arrived, so "no command" is final at once. A frame is re-published
//         up to lockstep.retx_max times, then the command is missed. Fully deterministic.
//   async (udpm, separate processes): wall-clock retx_ms / deadline_ms of the scenario.
// Missed commands are announced on GNC_CTL (HEARTBEAT from NODE_PLANT, status = missed count)
// before the next frame, so the bridge reports them in telemetry. The scenario's telecommands
// (its `commands:` list, the test conductor) go out on GNC_FSW_CMD before the first frame at or
// after their time, with apply_seq = that frame's seq. The plant is the scenario's mission's
// (sim::make_plant, from the mission registry).
#ifndef HIL_SIL_PLANT_NODE_HPP
#define HIL_SIL_PLANT_NODE_HPP

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <lcm/lcm.h>

#include "fault_injector.hpp"
#include <memory>

#include "plant/plant.hpp"
#include "scenario/scenario.hpp"

namespace sil {

struct PlantSummary {
    std::uint64_t steps = 0;          // periods propagated
    std::uint64_t missed = 0;         // commands not received for their frame
    std::uint64_t missed_run_max = 0; // longest run of consecutive missed commands (the loss-of-control rule)
    std::uint64_t retx = 0;           // frames re-published
    std::uint64_t late_cmds = 0;      // commands for an earlier frame (dropped)
    std::uint64_t dup_cmds = 0;       // second command for the current frame (ignored)
    std::uint64_t bad_cmds = 0;       // undecodable commands
    std::uint64_t crc_cmds = 0;       // commands refused on their crc32
    std::uint64_t nan_frames = 0;     // frames built from a NaN truth (fault window)
    std::uint64_t spike_frames = 0;   // frames with an out-of-range count (fault window)
    fault::FaultCounters faults{};
    bool diverged = false;
    double t_end_s = 0.0;
    std::string reason;               // why the run ended early (DIVERGED, no bridge)
    bool sync = false;                // memq lock-step (no clock in the loop)
    // memq: every missed or re-sent frame is a function of the scenario and its fault seed, so
    // faults do not make a run non-deterministic (the streams are compared by --determinism-check
    // and the CTests). udpm: a re-sent or missed frame is a wall-clock decision.
    bool deterministic() const { return sync || (missed == 0 && retx == 0); }
};

// The sensor frame of step k as the plant publishes it (sealed with its crc32; plant_flags:
// PLANT_RETX on a re-send) and the truth message; the batch driver (batch.hpp) sends the same bytes.
int encode_frame(const sim::Scenario &scn, const sim::SensorFrame &f, std::int32_t plant_flags,
                 std::vector<std::uint8_t> &buf);
int encode_truth(const sim::Plant &plant, std::uint64_t k, std::vector<std::uint8_t> &buf);

class PlantNode {
public:
    // Hooks the runner may use between steps (e.g. a table upload at a given time).
    using StepHook = std::function<void(std::uint64_t k, std::int64_t utime_us)>;

    PlantNode(lcm_t *lcm, const sim::Scenario &scn, bool sync);
    ~PlantNode();
    PlantNode(const PlantNode &) = delete;
    PlantNode &operator=(const PlantNode &) = delete;

    void set_progress(std::function<void(std::uint64_t k, std::uint64_t n)> cb) { progress_ = std::move(cb); }
    void set_before_frame(StepHook h) { before_frame_ = std::move(h); }
    // async only: wait up to timeout_ms for the bridge's READY. false: none came.
    bool wait_for_bridge(int timeout_ms);
    PlantSummary run();
    std::int64_t utime_us() const { return plant_->utime_us(); }

private:
    static void on_cmd_cb(const lcm_recv_buf_t *rb, const char *ch, void *user);
    static void on_ctl_cb(const lcm_recv_buf_t *rb, const char *ch, void *user);
    void on_cmd(const std::uint8_t *buf, std::size_t len);
    void publish_frame(const sim::SensorFrame &f, std::int32_t plant_flags, bool through_faults);
    void publish_truth(std::uint64_t k);
    void publish_ctl(std::int32_t command, std::int32_t status);
    bool wait_command(std::uint64_t k, const sim::SensorFrame &f);
    void inject_sensor_faults(sim::SensorFrame &f, double t_s);
    void publish_commands(std::uint64_t k, double t_s);
    std::size_t next_cmd_ = 0;      // scenario commands published so far

    lcm_t *lcm_;
    sim::Scenario scn_;
    bool sync_;
    std::unique_ptr<sim::Plant> plant_;
    fault::FaultInjector inj_;
    lcm_subscription_t *sub_cmd_ = nullptr;
    lcm_subscription_t *sub_ctl_ = nullptr;
    std::uint64_t k_ = 0;
    bool got_ = false;
    bool bridge_ready_ = false;
    sim::ActuatorCmd cmd_{};
    PlantSummary sum_{};
    std::vector<std::uint8_t> buf_;
    std::function<void(std::uint64_t, std::uint64_t)> progress_;
    StepHook before_frame_;
};

}  // namespace sil

#endif  // HIL_SIL_PLANT_NODE_HPP
