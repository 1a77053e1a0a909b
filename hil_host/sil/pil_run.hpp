// pil_run.hpp — a run's flight software on a board (spec 00 §6): `sil run --pil ELF` (QEMU),
// `--pil-serial DEV` (a real board, HIL) or `--pil-loopback` (the board session compiled for the
// host, in this process: the protocol without an emulator). The batch driver flies the plant and
// the bridge exactly as for SIL; only the backend differs, so SIL and PIL streams compare byte for
// byte.
#ifndef HIL_SIL_PIL_RUN_HPP
#define HIL_SIL_PIL_RUN_HPP

#include <cstdint>
#include <memory>
#include <string>

#include "mission_host.hpp"
#include "pil_backend.hpp"
#include "qemu_board.hpp"
#include "scenario/scenario.hpp"

namespace sil {

struct PilRunOptions {
    std::string elf;                   // QEMU: the board image (fsw_pil.elf)
    std::string machine = "mps2-an385";
    std::string serial;                // HIL: a serial device instead of QEMU
    int baud = 921600;
    bool loopback = false;             // the board session in this process
    std::string dir;                   // QEMU's socket and logs (default: the current directory)
    int timeout_ms = 2000;             // link: per transmission
    int retx = 3;
    int down_after = 5;
    int qemu_timeout_s = 3600;         // the whole QEMU run (qemu-run.sh's timeout)
    std::string insn_csv;              // per-step instruction counts to this file (empty: none)
    // Faults on the link's byte stream (spec 00 §8; hil_host/pil FaultyPort), both directions,
    // per frame, in parts per million; seeded and deterministic.
    std::uint32_t drop_ppm = 0, flip_ppm = 0, trunc_ppm = 0;
    std::uint64_t fault_seed = 1;
    std::int64_t reset_at = -1;        // MODE_CMD RESET before this step (a board reset mid-run)
    std::int64_t silent_at = -1;       // from this step on the board's replies are swallowed (a silent board)
    bool expect_hash_set = false;      // test hook: expect this layout hash instead of the host's own
    std::uint32_t expect_hash = 0;
    bool active() const { return loopback || !elf.empty() || !serial.empty(); }
    std::string describe() const;
};

// One board for one run: opens the port (starting QEMU when asked), boots the board from the
// scenario's configuration and boot image (or none when the scenario names a table file, which then
// arrives by upload, as in SIL). Throws std::runtime_error naming the cause when the board does not
// come up or refuses the boot.
class PilRun {
public:
    PilRun(const sim::Scenario &scn, const PilRunOptions &opt);
    ~PilRun();
    pil::PilBackend &backend() { return *be_; }
    // The batch driver calls this before step k's frame: the scheduled board faults.
    void before_step(std::uint64_t k);
    // End of run: the board's LINK_STATS, MODE_CMD END, QEMU's exit code; the pil_* summary keys.
    // Returns the board's exit code (0 when there is no QEMU); non-zero also when the link went down.
    int finish(host::Summary &s);

private:
    PilRunOptions opt_;
    std::unique_ptr<pil::QemuBoard> qemu_;
    pil::FaultyPort *faults_ = nullptr;   // owned by be_'s port chain, when faults are asked for
    double period_s_ = 0.0;
    std::unique_ptr<pil::PilBackend> be_;
};

}  // namespace sil

#endif  // HIL_SIL_PIL_RUN_HPP
