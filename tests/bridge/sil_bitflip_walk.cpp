// sil_bitflip_walk.cpp — one flipped bit per run, every bit of the fields a corrupted sensor
// frame could mislead with (issue 18): all 64 bits of seq, all 64 of utime, all 32 of every used
// count. Each run is the scenario flown in process (memq, the same plant, bridge and fsw_step as
// the LCM SIL) with the bit inverted in frame K's first transmission, after the plant sealed it.
//
// Pass, per run: the flip was refused (crc_rej + malformed == 1, nothing else refused), the plant
// re-sent the frame once (retx == 1, missed == 0), and the run flew exactly the commands of the
// clean run (same GNC_CMD digest, same count) — so every mission pass criterion the clean run
// meets is met, bit for bit. A flip can therefore cost one re-send and nothing else.
//
// usage: sil_bitflip_walk SCENARIO.yaml FRAME [--stride S] [--counts-stride S] [--fields seq,utime,counts]
//   --stride S walks every S-th bit of seq and utime, --counts-stride S of each count (1 = every
//   bit, the default; reduced forms in the suite use strides, the full walk is the command in the
//   bridge README).
// sil_bitflip_walk SCENARIO.yaml --random SEEDS [--ppm P]
//   instead: SEEDS runs with random flips in P ppm of the transmissions (default 10 000 = 1 %),
//   fault seeds 1..SEEDS; each flip refused and re-sent (crc_rej + malformed == retx == flips),
//   the commands identical to the clean run's.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "scenario/scenario.hpp"
#include "sil_run.hpp"

namespace {

// sensor_frame_v2_t's LCM encoding (big-endian): fingerprint 8, utime 8, seq 8, period_us 4,
// n_counts 2, counts 16 x 4, ... — byte offset of each field.
constexpr std::uint32_t kOffUtime = 8, kOffSeq = 16, kOffCounts = 30;

// Index (byte * 8 + bit, the injector's convention) of bit b (0 = LSB) of a big-endian field of
// `width` bytes at byte offset `off`.
std::uint32_t bit_index(std::uint32_t off, std::uint32_t width, std::uint32_t b)
{
    return (off + width - 1u - b / 8u) * 8u + (b % 8u);
}

struct Walk {
    int runs = 0, bad = 0;
};

bool check(const sil::InprocResult &r, const sil::InprocResult &clean, const std::string &what, Walk &w)
{
    ++w.runs;
    const auto &b = r.bridge;
    const bool refused = (b.crc_rej + b.malformed == 1) && (b.time_rej + b.jump_rej + b.range_rej == 0);
    const bool resent = (r.plant.retx == 1u) && (r.plant.missed == 0u);
    const bool same = (r.core.digest_cmd == clean.core.digest_cmd) && (r.core.cmd_n == clean.core.cmd_n) &&
                      !r.plant.diverged;
    if (!(refused && resent && same)) {
        ++w.bad;
        std::printf("FAIL %-14s crc_rej %d malformed %d time_rej %d jump_rej %d range_rej %d retx %llu missed %llu "
                    "cmd_n %llu/%llu digest %s%s\n",
                    what.c_str(), b.crc_rej, b.malformed, b.time_rej, b.jump_rej, b.range_rej,
                    static_cast<unsigned long long>(r.plant.retx), static_cast<unsigned long long>(r.plant.missed),
                    static_cast<unsigned long long>(r.core.cmd_n), static_cast<unsigned long long>(clean.core.cmd_n),
                    (r.core.digest_cmd == clean.core.digest_cmd) ? "same" : "DIFFERENT",
                    r.plant.diverged ? " DIVERGED" : "");
        return false;
    }
    return true;
}

int random_flips(int argc, char **argv)
{
    const long long seeds = std::strtoll(argv[3], nullptr, 10);
    long long ppm = 10000;
    if (argc == 6 && std::strcmp(argv[4], "--ppm") == 0) {
        ppm = std::strtoll(argv[5], nullptr, 10);
    } else if (argc != 4) {
        std::fprintf(stderr, "usage: %s SCENARIO.yaml --random SEEDS [--ppm P]\n", argv[0]);
        return 2;
    }
    if (seeds < 1 || ppm < 1 || ppm > 100000) {
        std::fprintf(stderr, "SEEDS must be >= 1 and P in [1, 100000]\n");
        return 2;
    }
    try {
        const sim::Scenario base = sim::load_scenario(argv[1]);
        sil::InprocOptions o;
        const sil::InprocResult clean = sil::run_inproc(base, o);
        int bad = 0;
        unsigned long long flips = 0;
        for (long long i = 1; i <= seeds; ++i) {
            sim::Scenario s = base;
            s.faults.seed = static_cast<std::uint64_t>(i);
            s.faults.bitflip_ppm = static_cast<std::uint32_t>(ppm);
            const sil::InprocResult r = sil::run_inproc(s, o);
            const auto fl = static_cast<std::int64_t>(r.plant.faults.bitflipped);
            flips += r.plant.faults.bitflipped;
            const auto &b = r.bridge;
            const bool ok = fl > 0 && b.crc_rej + b.malformed == fl && static_cast<std::int64_t>(r.plant.retx) == fl &&
                            r.plant.missed == 0u && b.time_rej + b.jump_rej + b.range_rej == 0 && !r.plant.diverged &&
                            r.core.digest_cmd == clean.core.digest_cmd && r.core.cmd_n == clean.core.cmd_n;
            if (!ok) {
                ++bad;
                std::printf("FAIL seed %lld: flips %lld crc_rej %d malformed %d retx %llu missed %llu digest %s\n", i,
                            static_cast<long long>(fl), b.crc_rej, b.malformed,
                            static_cast<unsigned long long>(r.plant.retx),
                            static_cast<unsigned long long>(r.plant.missed),
                            r.core.digest_cmd == clean.core.digest_cmd ? "same" : "DIFFERENT");
            }
        }
        std::printf("%s: %lld seeds at %lld ppm, %llu flips, %d runs failed; every passing run flew the clean "
                    "run's %llu commands (digest %016llx)\n",
                    argv[1], seeds, ppm, flips, bad, static_cast<unsigned long long>(clean.core.cmd_n),
                    static_cast<unsigned long long>(clean.core.digest_cmd));
        return bad == 0 ? 0 : 1;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "sil_bitflip_walk: %s\n", e.what());
        return 2;
    }
}

}  // namespace

int main(int argc, char **argv)
{
    if (argc >= 4 && std::strcmp(argv[2], "--random") == 0) {
        return random_flips(argc, argv);
    }
    if (argc < 3) {
        std::fprintf(stderr, "usage: %s SCENARIO.yaml FRAME [--counts-stride S] [--fields seq,utime,counts]\n", argv[0]);
        return 2;
    }
    const std::string path = argv[1];
    const long long frame = std::strtoll(argv[2], nullptr, 10);
    std::uint32_t stride = 1u, word_stride = 1u;
    std::string fields = "seq,utime,counts";
    for (int i = 3; i + 1 < argc; i += 2) {
        if (std::strcmp(argv[i], "--stride") == 0) {
            word_stride = static_cast<std::uint32_t>(std::strtoul(argv[i + 1], nullptr, 10));
        } else if (std::strcmp(argv[i], "--counts-stride") == 0) {
            stride = static_cast<std::uint32_t>(std::strtoul(argv[i + 1], nullptr, 10));
        } else if (std::strcmp(argv[i], "--fields") == 0) {
            fields = argv[i + 1];
        } else {
            std::fprintf(stderr, "unknown option %s\n", argv[i]);
            return 2;
        }
    }
    if (frame < 0 || stride == 0u || word_stride == 0u) {
        std::fprintf(stderr, "FRAME must be >= 0 and the stride >= 1\n");
        return 2;
    }
    try {
        sim::Scenario base = sim::load_scenario(path);
        sil::InprocOptions o;
        const sil::InprocResult clean = sil::run_inproc(base, o);
        if (clean.plant.diverged || clean.plant.retx != 0u || clean.bridge.crc_rej != 0) {
            std::printf("FAIL the clean run is not clean (%s)\n", clean.plant.reason.c_str());
            return 1;
        }
        if (static_cast<std::uint64_t>(frame) >= clean.plant.steps) {
            std::fprintf(stderr, "FRAME %lld is past the run's %llu frames\n", frame,
                         static_cast<unsigned long long>(clean.plant.steps));
            return 2;
        }
        // The used counts: the channels the scenario's sensor frames carry.
        const std::uint32_t n_counts = static_cast<std::uint32_t>(sil::run_limits(base).n_channels);
        Walk w;
        auto fly = [&](std::uint32_t bit, const std::string &what) {
            sim::Scenario s = base;
            s.faults.flip_frame = frame;
            s.faults.flip_bit = bit;
            (void)check(sil::run_inproc(s, o), clean, what, w);
        };
        if (fields.find("seq") != std::string::npos) {
            for (std::uint32_t b = 0; b < 64u; b += word_stride) { fly(bit_index(kOffSeq, 8u, b), "seq:" + std::to_string(b)); }
        }
        if (fields.find("utime") != std::string::npos) {
            for (std::uint32_t b = 0; b < 64u; b += word_stride) { fly(bit_index(kOffUtime, 8u, b), "utime:" + std::to_string(b)); }
        }
        if (fields.find("counts") != std::string::npos) {
            for (std::uint32_t c = 0; c < n_counts; ++c) {
                for (std::uint32_t b = 0; b < 32u; b += stride) {
                    fly(bit_index(kOffCounts + 4u * c, 4u, b), "counts[" + std::to_string(c) + "]:" + std::to_string(b));
                }
            }
        }
        std::printf("%s: frame %lld, %u counts, %d runs, %d failed; clean run %llu commands, digest %016llx\n",
                    path.c_str(), frame, n_counts, w.runs, w.bad, static_cast<unsigned long long>(clean.core.cmd_n),
                    static_cast<unsigned long long>(clean.core.digest_cmd));
        return (w.bad == 0 && w.runs > 0) ? 0 : 1;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "sil_bitflip_walk: %s\n", e.what());
        return 2;
    }
}
