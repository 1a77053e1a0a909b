// fault_injector.hpp — seeded, deterministic fault layer (spec 00 §8) over a stream of packets.
//
// Packets go in by value, in order, through push(); the delivered stream comes out of push()
// and flush(). Per incoming packet, in this fixed order (every decision draws from the one RNG,
// in the same pattern whatever the outcome, so a seed fixes the whole stream):
//   1. drop       (drop_ppm)      the packet is gone                            dropped++
//   2. truncate   (truncate_ppm)  bytes cut to a random length in [0, size-1]   truncated++
//   3. bit flip   (bitflip_ppm)   one random bit of the bytes inverted          bitflipped++
//      targeted   (flip_id, flip_bit) the first packet with id == flip_id gets bit flip_bit
//                 (byte flip_bit / 8, bit flip_bit % 8) inverted, once: a test can walk every
//                 bit of a field, one run per bit; it draws nothing, so the random stream is
//                 the same with or without it                                   bitflipped++
//   4. duplicate  (dup_ppm)       a copy is delivered right after the packet    duplicated++
//   5. reorder    (reorder_ppm)   if no packet is held, the packet is held back and released
//                                 after d in [1, reorder_window] later packets have been
//                                 delivered (its duplicate, if any, travels with it)
// At most one packet is held at a time, so a held packet is always overtaken by a later one
// that was delivered in order: for a lock-step receiver it arrives stale. reordered counts
// packets actually overtaken (a packet still held at flush() with nothing delivered after it
// goes out in order and is not counted).
// Probabilities are integers in parts per million: no floating point in any decision.
// The trace records each packet's fate, so a test can derive exact expected receiver counters.
#ifndef HIL_FAULT_INJECTOR_HPP
#define HIL_FAULT_INJECTOR_HPP

#include <cstdint>
#include <vector>

#include "fault_rng.hpp"

namespace fault {

struct Packet {
    std::uint64_t id = 0;               // caller's identity (e.g. the frame's seq)
    std::vector<std::uint8_t> bytes;    // encoded message
};

struct FaultConfig {
    std::uint64_t seed = 1;
    std::uint32_t drop_ppm = 0;
    std::uint32_t dup_ppm = 0;
    std::uint32_t reorder_ppm = 0;
    std::uint32_t reorder_window = 1;   // >= 1; d drawn in [1, window]
    std::uint32_t bitflip_ppm = 0;
    std::uint32_t truncate_ppm = 0;
    std::uint64_t flip_id = kNoFlip;    // targeted one-shot flip: packet id ...
    std::uint32_t flip_bit = 0;         // ... and bit index in its bytes
    static constexpr std::uint64_t kNoFlip = ~UINT64_C(0);
};

struct FaultCounters {
    std::uint64_t in = 0;
    std::uint64_t delivered = 0;        // packets out, duplicates included
    std::uint64_t dropped = 0;
    std::uint64_t duplicated = 0;
    std::uint64_t reordered = 0;
    std::uint64_t bitflipped = 0;
    std::uint64_t truncated = 0;
};

enum FateBits : std::uint8_t {
    kFateDropped = 1u, kFateDuplicated = 2u, kFateReordered = 4u, kFateBitflip = 8u, kFateTruncated = 16u
};

struct Fate {
    std::uint64_t id = 0;
    std::uint8_t bits = 0;   // FateBits
};

class FaultInjector {
public:
    explicit FaultInjector(const FaultConfig &cfg) : cfg_(cfg), rng_(cfg.seed) {}

    void push(Packet p, std::vector<Packet> &out);
    void flush(std::vector<Packet> &out);

    const FaultCounters &counters() const { return c_; }
    const std::vector<Fate> &trace() const { return trace_; }

private:
    void deliver(const Packet &p, std::vector<Packet> &out);
    void release_held(std::vector<Packet> &out);

    FaultConfig cfg_;
    bool targeted_done_ = false;
    Xoshiro256ss rng_;
    FaultCounters c_{};
    std::vector<Fate> trace_;
    bool have_held_ = false;
    Packet held_{};
    bool held_dup_ = false;
    std::size_t held_trace_ = 0;
    std::uint32_t held_left_ = 0;       // deliveries still to pass it
    std::uint32_t held_passed_ = 0;     // deliveries that passed it so far
};

}  // namespace fault

#endif  // HIL_FAULT_INJECTOR_HPP
