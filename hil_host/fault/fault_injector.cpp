#include "fault_injector.hpp"

namespace fault {

namespace {

std::uint32_t size32(std::size_t n)
{
    return (n > 0xFFFFFFFFu) ? 0xFFFFFFFFu : static_cast<std::uint32_t>(n);
}

}  // namespace

void FaultInjector::deliver(const Packet &p, std::vector<Packet> &out)
{
    out.push_back(p);
    ++c_.delivered;
}

void FaultInjector::release_held(std::vector<Packet> &out)
{
    deliver(held_, out);
    if (held_dup_) {
        deliver(held_, out);
    }
    if (held_passed_ > 0u) {
        ++c_.reordered;
        trace_[held_trace_].bits = static_cast<std::uint8_t>(trace_[held_trace_].bits | kFateReordered);
    }
    have_held_ = false;
    held_ = Packet{};
}

void FaultInjector::push(Packet p, std::vector<Packet> &out)
{
    ++c_.in;
    Fate fate{};
    fate.id = p.id;
    // Fixed draw pattern per packet: drop, truncate (+len), flip (+bit), dup, reorder (+d).
    const bool drop = rng_.chance_ppm(cfg_.drop_ppm);
    const bool trunc = rng_.chance_ppm(cfg_.truncate_ppm);
    const std::uint32_t trunc_len = rng_.below(size32(p.bytes.size()));
    const bool flip = rng_.chance_ppm(cfg_.bitflip_ppm);
    const std::uint32_t flip_bit = rng_.below(size32(p.bytes.size() * 8u));
    const bool dup = rng_.chance_ppm(cfg_.dup_ppm);
    const bool reorder = rng_.chance_ppm(cfg_.reorder_ppm);
    const std::uint32_t win = (cfg_.reorder_window < 1u) ? 1u : cfg_.reorder_window;
    const std::uint32_t d = 1u + rng_.below(win);

    if (drop) {
        ++c_.dropped;
        fate.bits = kFateDropped;
        trace_.push_back(fate);
        return;
    }
    if (trunc && !p.bytes.empty()) {
        p.bytes.resize(trunc_len);
        ++c_.truncated;
        fate.bits = static_cast<std::uint8_t>(fate.bits | kFateTruncated);
    }
    if (flip && !p.bytes.empty() && ((flip_bit / 8u) < p.bytes.size())) {
        p.bytes[flip_bit / 8u] = static_cast<std::uint8_t>(p.bytes[flip_bit / 8u] ^ (1u << (flip_bit % 8u)));
        ++c_.bitflipped;
        fate.bits = static_cast<std::uint8_t>(fate.bits | kFateBitflip);
    }
    if (!targeted_done_ && (p.id == cfg_.flip_id) && ((cfg_.flip_bit / 8u) < p.bytes.size())) {
        targeted_done_ = true;
        p.bytes[cfg_.flip_bit / 8u] = static_cast<std::uint8_t>(p.bytes[cfg_.flip_bit / 8u] ^ (1u << (cfg_.flip_bit % 8u)));
        ++c_.bitflipped;
        fate.bits = static_cast<std::uint8_t>(fate.bits | kFateBitflip);
    }
    if (dup) {
        ++c_.duplicated;
        fate.bits = static_cast<std::uint8_t>(fate.bits | kFateDuplicated);
    }
    trace_.push_back(fate);

    if (reorder && !have_held_) {
        have_held_ = true;
        held_ = std::move(p);
        held_dup_ = dup;
        held_trace_ = trace_.size() - 1u;
        held_left_ = d;
        held_passed_ = 0u;
        return;
    }
    deliver(p, out);
    if (dup) {
        deliver(p, out);
    }
    if (have_held_) {
        ++held_passed_;
        if (--held_left_ == 0u) {
            release_held(out);
        }
    }
}

void FaultInjector::flush(std::vector<Packet> &out)
{
    if (have_held_) {
        release_held(out);
    }
}

}  // namespace fault
