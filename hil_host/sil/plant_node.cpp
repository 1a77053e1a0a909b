#include "plant_node.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "channels.hpp"
#include "lcm_codec.hpp"
#include "gnc/actuator_cmd_v2_t.hpp"
#include "gnc/fsw_cmd_v2_t.hpp"
#include "gnc/sensor_frame_v2_t.hpp"
#include "gnc/sil_ctl_t.hpp"
#include "gnc/sim_truth_t.hpp"
#include "sensors/counts.hpp"

// The plant status bits STALE and SAT are the wire bits; NonFinite is published as STALE.
static_assert(sim::kStatusStale == gnc::sensor_frame_v2_t::STATUS_STALE, "plant STALE bit != wire");
static_assert(sim::kStatusSat == gnc::sensor_frame_v2_t::STATUS_SAT, "plant SAT bit != wire");

namespace sil {

namespace {

fault::FaultConfig fault_config(const sim::FaultSetup &f)
{
    fault::FaultConfig c;
    c.seed = f.seed;
    c.drop_ppm = f.drop_ppm;
    c.dup_ppm = f.dup_ppm;
    c.reorder_ppm = f.reorder_ppm;
    c.reorder_window = f.reorder_window;
    c.bitflip_ppm = f.bitflip_ppm;
    c.truncate_ppm = f.truncate_ppm;
    if (f.flip_frame >= 0) {
        c.flip_id = static_cast<std::uint64_t>(f.flip_frame);
        c.flip_bit = f.flip_bit;
    }
    return c;
}

bool in_window(const std::array<double, 2> &w, double t)
{
    return w[0] >= 0.0 && t >= w[0] && t < w[1];
}

using Clock = std::chrono::steady_clock;

int ms_left(Clock::time_point until)
{
    const auto d = std::chrono::duration_cast<std::chrono::milliseconds>(until - Clock::now()).count();
    return (d <= 0) ? 0 : static_cast<int>(d);
}

}  // namespace

PlantNode::PlantNode(lcm_t *lcm, const sim::Scenario &scn, bool sync)
    : lcm_(lcm), scn_(scn), sync_(sync), plant_(sim::make_plant(scn)), inj_(fault_config(scn.faults)), buf_(4096)
{
    if (lcm_ == nullptr) {
        throw std::invalid_argument("PlantNode: null lcm_t");
    }
    // A node never subscribes to a channel it publishes (udpm loops its own messages back).
    sub_cmd_ = lcm_subscribe(lcm_, kChCmd, &PlantNode::on_cmd_cb, this);
    sub_ctl_ = lcm_subscribe(lcm_, kChCtl, &PlantNode::on_ctl_cb, this);
}

PlantNode::~PlantNode()
{
    if (sub_cmd_ != nullptr) { lcm_unsubscribe(lcm_, sub_cmd_); }
    if (sub_ctl_ != nullptr) { lcm_unsubscribe(lcm_, sub_ctl_); }
}

void PlantNode::on_cmd_cb(const lcm_recv_buf_t *rb, const char *, void *user)
{
    static_cast<PlantNode *>(user)->on_cmd(static_cast<const std::uint8_t *>(rb->data), rb->data_size);
}

void PlantNode::on_ctl_cb(const lcm_recv_buf_t *rb, const char *, void *user)
{
    auto *self = static_cast<PlantNode *>(user);
    gnc::sil_ctl_t m;
    if (m.decode(rb->data, 0, static_cast<int>(rb->data_size)) < 0) {
        return;
    }
    if (m.node_id == gnc::sil_ctl_t::NODE_BRIDGE && m.command == gnc::sil_ctl_t::CMD_READY) {
        self->bridge_ready_ = true;
    }
}

void PlantNode::on_cmd(const std::uint8_t *buf, std::size_t len)
{
    gnc::actuator_cmd_v2_t m;
    const bridge::Wire w = bridge::decode(buf, len, m);
    if (w == bridge::Wire::BadCrc) {
        ++sum_.crc_cmds;   // refused before any field is used; the frame's re-send asks again
        return;
    }
    if (w != bridge::Wire::Ok || m.n_counts < 0 || m.n_counts > 16) {
        ++sum_.bad_cmds;
        return;
    }
    if (m.seq < 0 || static_cast<std::uint64_t>(m.seq) < k_) {
        ++sum_.late_cmds;
        return;
    }
    if (static_cast<std::uint64_t>(m.seq) != k_) {
        ++sum_.bad_cmds;   // a command for a frame not yet sent cannot be genuine
        return;
    }
    if (got_) {
        ++sum_.dup_cmds;
        return;
    }
    got_ = true;
    cmd_ = sim::ActuatorCmd{};
    cmd_.seq = static_cast<std::uint32_t>(m.seq & 0xFFFFFFFF);
    cmd_.n_ch = static_cast<std::uint32_t>(m.n_counts < static_cast<std::int16_t>(sim::kMaxChannels)
                                               ? m.n_counts : static_cast<std::int16_t>(sim::kMaxChannels));
    for (std::size_t i = 0; i < cmd_.n_ch; ++i) {
        cmd_.cnt[i] = m.counts[i];
    }
}

void PlantNode::inject_sensor_faults(sim::SensorFrame &f, double t_s)
{
    const std::size_t cn = scn_.faults.nan_channel, cs = scn_.faults.spike_channel;
    if (in_window(scn_.faults.nan_s, t_s) && cn < f.n_ch) {
        // A NaN truth on the channel goes through the one SI -> count conversion, as a diverging
        // model would (count 0, NonFinite and SAT: the bridge receives it marked STALE).
        std::uint8_t st = 0u;
        f.cnt[cn] = sim::counts_from_si(std::numeric_limits<double>::quiet_NaN(), 1.0, 1, &st);
        f.status[cn] = st;
        ++sum_.nan_frames;
    }
    if (in_window(scn_.faults.spike_s, t_s) && cs < f.n_ch) {
        f.cnt[cs] = std::numeric_limits<std::int32_t>::max();   // beyond any sensor table limit
        ++sum_.spike_frames;
    }
}

int encode_frame(const sim::Scenario &scn, const sim::SensorFrame &f, std::int32_t plant_flags,
                 std::vector<std::uint8_t> &buf)
{
    gnc::sensor_frame_v2_t m{};
    m.utime = f.utime_us;
    m.seq = static_cast<std::int64_t>(f.seq);
    m.period_us = static_cast<std::int32_t>(f.period_us);
    m.n_counts = static_cast<std::int16_t>(f.n_ch);
    for (std::size_t i = 0; i < 16u; ++i) {
        m.counts[i] = (i < f.n_ch) ? f.cnt[i] : 0;
        std::int8_t st = 0;
        if (i < f.n_ch) {
            if ((f.status[i] & (sim::kStatusNonFinite | sim::kStatusStale)) != 0u) {
                st = static_cast<std::int8_t>(st | gnc::sensor_frame_v2_t::STATUS_STALE);
            }
            if ((f.status[i] & sim::kStatusSat) != 0u) { st = static_cast<std::int8_t>(st | gnc::sensor_frame_v2_t::STATUS_SAT); }
        }
        m.status[i] = st;
    }
    m.scenario_flags = scn.faults.any() ? 1 : 0;
    m.plant_flags = plant_flags;
    return bridge::encode(m, buf.data(), buf.size());   // sealed with its crc32
}

int encode_truth(const sim::Plant &plant, std::uint64_t k, std::vector<std::uint8_t> &buf)
{
    gnc::sim_truth_t m{};
    m.utime = plant.utime_us();
    m.seq = static_cast<std::int64_t>(k);
    std::array<double, 16> st{};
    std::array<double, 8> ex{};
    plant.truth_message(st, ex);
    for (std::size_t i = 0; i < 16u; ++i) { m.state[i] = st[i]; }
    for (std::size_t i = 0; i < 8u; ++i) { m.extra[i] = ex[i]; }
    m.events = static_cast<std::int32_t>(plant.events().size() > 0x7FFFFFFF ? 0x7FFFFFFF : plant.events().size());
    return m.encode(buf.data(), 0, static_cast<int>(buf.size()));
}

void PlantNode::publish_frame(const sim::SensorFrame &f, std::int32_t plant_flags, bool through_faults)
{
    const int n = encode_frame(scn_, f, plant_flags, buf_);
    if (n < 0) {
        throw std::runtime_error("sensor_frame_v2_t encode failed");
    }
    fault::Packet p;
    p.id = f.seq;
    p.bytes.assign(buf_.begin(), buf_.begin() + n);
    std::vector<fault::Packet> out;
    if (through_faults) {
        inj_.push(std::move(p), out);
    } else {
        out.push_back(std::move(p));
    }
    for (const auto &q : out) {
        lcm_publish(lcm_, kChSensor, q.bytes.data(), static_cast<unsigned>(q.bytes.size()));
    }
}

void PlantNode::publish_truth(std::uint64_t k)
{
    const int n = encode_truth(*plant_, k, buf_);
    if (n > 0) {
        lcm_publish(lcm_, kChTruth, buf_.data(), static_cast<unsigned>(n));
    }
}

void PlantNode::publish_ctl(std::int32_t command, std::int32_t status)
{
    gnc::sil_ctl_t m{};
    m.utime = plant_->utime_us();
    m.command = command;
    for (std::size_t i = 0; i < 32u; ++i) {
        m.scenario[i] = (i < scn_.name.size()) ? static_cast<std::uint8_t>(scn_.name[i]) : 0u;
    }
    m.seed = static_cast<std::int64_t>(sim::mission_section(scn_.mission).noise_seed(scn_));
    m.node_id = gnc::sil_ctl_t::NODE_PLANT;
    m.status = status;
    const int n = m.encode(buf_.data(), 0, static_cast<int>(buf_.size()));
    if (n > 0) {
        lcm_publish(lcm_, kChCtl, buf_.data(), static_cast<unsigned>(n));
    }
}

void PlantNode::publish_commands(std::uint64_t k, double t_s)
{
    while (next_cmd_ < scn_.commands.size() && scn_.commands[next_cmd_].t_s <= t_s + 1e-9) {
        const sim::ScnCommand &c = scn_.commands[next_cmd_++];
        gnc::fsw_cmd_v2_t m{};
        m.utime = plant_->utime_us();
        m.apply_seq = static_cast<std::int64_t>(k);
        m.cmd = c.cmd;
        for (std::size_t i = 0; i < 8u; ++i) { m.args[i] = c.args[i]; }
        const int n = bridge::encode(m, buf_.data(), buf_.size());   // sealed with its crc32
        if (n > 0) {
            lcm_publish(lcm_, kChFswCmd, buf_.data(), static_cast<unsigned>(n));
        }
    }
}

bool PlantNode::wait_for_bridge(int timeout_ms)
{
    const auto until = Clock::now() + std::chrono::milliseconds(timeout_ms);
    while (!bridge_ready_ && ms_left(until) > 0) {
        (void)lcm_handle_timeout(lcm_, ms_left(until));
    }
    return bridge_ready_;
}

bool PlantNode::wait_command(std::uint64_t k, const sim::SensorFrame &f)
{
    std::uint32_t retx = 0u;
    if (sync_) {
        for (;;) {
            while (!got_ && lcm_handle_timeout(lcm_, 0) > 0) {
            }
            if (got_ || retx >= scn_.lockstep.retx_max) {
                break;
            }
            ++retx;
            ++sum_.retx;
            publish_frame(f, gnc::sensor_frame_v2_t::PLANT_RETX, true);
        }
        // Deliver anything the bridge still queued (its telemetry) before the next frame.
        while (lcm_handle_timeout(lcm_, 0) > 0) {
        }
        return got_;
    }
    const auto t0 = Clock::now();
    const auto deadline = t0 + std::chrono::milliseconds(scn_.lockstep.deadline_ms);
    auto next_retx = t0 + std::chrono::milliseconds(scn_.lockstep.retx_ms);
    (void)k;
    while (!got_) {
        const int left = ms_left(deadline);
        if (left == 0) {
            break;
        }
        const int to_retx = ms_left(next_retx);
        if (to_retx == 0) {
            if (retx < scn_.lockstep.retx_max) {
                ++retx;
                ++sum_.retx;
                publish_frame(f, gnc::sensor_frame_v2_t::PLANT_RETX, true);
            }
            next_retx = Clock::now() + std::chrono::milliseconds(scn_.lockstep.retx_ms);
            continue;
        }
        (void)lcm_handle_timeout(lcm_, (to_retx < left) ? to_retx : left);
    }
    return got_;
}

PlantSummary PlantNode::run()
{
    plant_->reset(scn_);
    sum_ = PlantSummary{};
    next_cmd_ = 0;
    sum_.sync = sync_;
    std::uint64_t missed_run = 0;
    const std::uint64_t n = scn_.n_steps();
    publish_ctl(gnc::sil_ctl_t::CMD_START, 0);
    for (k_ = 0; k_ < n; ++k_) {
        const double t_s = static_cast<double>(plant_->utime_us()) * 1e-6;
        if (before_frame_) {
            before_frame_(k_, plant_->utime_us());
        }
        publish_commands(k_, t_s);
        sim::SensorFrame f = plant_->sense();
        inject_sensor_faults(f, t_s);
        publish_truth(k_);
        got_ = false;
        publish_frame(f, 0, true);
        if (wait_command(k_, f)) {
            plant_->apply(cmd_);
            missed_run = 0;
        } else {
            ++sum_.missed;   // the last command stays applied (spec 00 §5.2 step 4)
            ++missed_run;
            sum_.missed_run_max = (missed_run > sum_.missed_run_max) ? missed_run : sum_.missed_run_max;
            publish_ctl(gnc::sil_ctl_t::CMD_HEARTBEAT,
                        static_cast<std::int32_t>(sum_.missed > 0x7FFFFFFFu ? 0x7FFFFFFFu : sum_.missed));
        }
        const sim::RunState st = plant_->propagate();
        ++sum_.steps;
        if (progress_) {
            progress_(k_ + 1, n);
        }
        if (st == sim::RunState::Diverged) {
            sum_.diverged = true;
            sum_.reason = "DIVERGED: " + plant_->diverged_reason();
            ++k_;
            break;
        }
    }
    std::vector<fault::Packet> rest;
    inj_.flush(rest);   // a frame still held by the reorder fault arrives late, after the run
    for (const auto &q : rest) {
        lcm_publish(lcm_, kChSensor, q.bytes.data(), static_cast<unsigned>(q.bytes.size()));
    }
    if (sync_) {
        while (lcm_handle_timeout(lcm_, 0) > 0) {
        }
    }
    sum_.faults = inj_.counters();
    sum_.t_end_s = static_cast<double>(plant_->utime_us()) * 1e-6;
    publish_ctl(gnc::sil_ctl_t::CMD_STOP, sum_.diverged ? 1 : 0);
    if (sync_) {
        while (lcm_handle_timeout(lcm_, 0) > 0) {
        }
    }
    return sum_;
}

}  // namespace sil
