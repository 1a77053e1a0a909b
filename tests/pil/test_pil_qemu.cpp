// test_pil_qemu.cpp — the `pil` backend against the board image under QEMU (spec 00 §6.1, §6.2,
// §6.4): fsw_pil.elf on an emulated mps2 board, its UART0 on a unix socket, DETUMBLE booted over
// the link. Every step's output must be byte-identical to the in-process executive's, a table
// uploaded mid-run must be acked identically, TLM must carry instruction counts, and MODE_CMD
// END must make the guest exit 0.
//
//   test_pil_qemu <qemu-run.sh> <machine> <fsw_pil.elf> <work dir>
//
// Exit 77 (CTest: skipped) when the image does not exist (no Cortex-M build next to this one).
#include <algorithm>
#include <string>
#include <sys/stat.h>

#include "pil_test_util.hpp"
#include "qemu_board.hpp"

using namespace pt;

namespace {

pil::QemuOptions g_qemu;

void qemu_twin_identical(void **)
{
    pil::QemuBoard qb(g_qemu);
    pil::PilOptions opt{};
    opt.timeout_ms = 5000;   // the first reply waits for QEMU to start the guest
    Twin t(qb.port(), opt);
    assert_true(t.pil->reset());
    assert_int_equal(t.pil->boot_rc(), 0);
    expect_same_limits(t.ip.sensor_limits(), t.pil->sensor_limits());
    const std::uint16_t board = t.pil->hello().board_id;
    assert_true(board == FSW_PIL_BOARD_AN385 || board == FSW_PIL_BOARD_AN386);

    std::int64_t k = 0;
    for (; k < 120; ++k) {
        t.step(k);
    }
    const std::vector<std::uint8_t> img = det_image(OBS_TBL_50HZ_PAPER, 3u);
    for (std::size_t off = 0; off < img.size(); off += 200u) {
        TableChunk c{};
        c.table_id = static_cast<std::int32_t>(OBS_TBL_ID);
        c.revision = 3;
        c.total_len = static_cast<std::int32_t>(img.size());
        c.offset = static_cast<std::int32_t>(off);
        c.n = static_cast<std::int16_t>(std::min<std::size_t>(200u, img.size() - off));
        c.data = img.data() + off;
        TableAck a{}, b{};
        assert_true(t.ip.table_chunk(c, a));
        assert_true(t.pil->table_chunk(c, b));
        expect_same_ack(a, b);
    }
    for (; k < 300; ++k) {
        t.step(k);
    }
    const pil::PilCounters &c = t.pil->counters();
    assert_int_equal(c.missed_steps, 0);
    assert_int_equal(c.retx, 0);
    assert_int_equal(c.board_errors, 0);
    assert_int_equal(t.ip.fsw().tlm.n_tbl_acc, 1);

    // Instruction counts: deterministic under -icount, so every one is a real measurement.
    std::vector<std::uint32_t> insn = t.pil->insn();
    assert_int_equal(insn.size(), 300);
    std::sort(insn.begin(), insn.end());
    assert_true(insn.front() > 0u);
    const std::optional<fsw_pil_stats_t> s = t.pil->link_stats();
    assert_true(s.has_value());
    assert_int_equal(s->steps, 300);
    assert_int_equal(s->dups, 0);
    assert_int_equal(s->errors, 0);
    assert_int_equal(s->uart_overruns, 0);
    assert_int_equal(s->insn_max, insn.back());
    print_message("qemu board 0x%04x build 0x%08x: fsw_step instructions min %u median %u max %u; stack %u of %u bytes\n",
                  board, t.pil->hello().build_id, insn.front(), insn[insn.size() / 2], insn.back(), s->stack_used,
                  s->stack_size);

    assert_true(t.pil->end_session());
    assert_int_equal(qb.wait_exit(10000), 0);
}

}  // namespace

int main(int argc, char **argv)
{
    if (argc != 5) {
        std::fprintf(stderr, "usage: %s <qemu-run.sh> <machine> <fsw_pil.elf> <work dir>\n", argv[0]);
        return 2;
    }
    struct stat st{};
    if (::stat(argv[3], &st) != 0) {
        std::printf("no board image %s: skipped (build the Cortex-M preset's fsw_pil first)\n", argv[3]);
        return 77;
    }
    g_qemu.qemu_run = argv[1];
    g_qemu.machine = argv[2];
    g_qemu.elf = argv[3];
    g_qemu.dir = argv[4];
    g_qemu.timeout_s = 60;
    g_qemu.name = "test_pil_qemu";   // one run at a time: its logs replace the last run's
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(qemu_twin_identical),
    };
    return cmocka_run_group_tests_name("pil_qemu", tests, nullptr, nullptr);
}
