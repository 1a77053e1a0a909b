/*
 * fuzz_pil_board — the board's side of the PIL session (fsw/app/fsw_pil.c) on arbitrary byte
 * streams: decoder → packet parser → boot, staging, sequence rules, uploads, flight steps
 * (spec 00 §8: "byte stream → decoder → packet parser"; the session is what the parser feeds).
 *
 * Properties, checked on every input (a violation traps):
 *  - no crash, no out-of-bounds access, no UB (ASan/UBSan in the libFuzzer build);
 *  - the transmit queue never exceeds its capacity, and every frame the board queues decodes
 *    with the link decoder (the board never emits a malformed frame);
 *  - every STEP the session asks for is one flight step (st.steps counts them exactly);
 *  - the session is never wedged: after the input, a delimiter, a BOOT matching whatever is
 *    staged, and a SENSOR must give exactly CMD and TLM of that seq.
 * The session starts not booted, so inputs must reach BOOT themselves; the corpus
 * (tools/fuzz/mkcorpus_link.py, pil_* seeds) starts them with a valid BOOT and SENSOR.
 */
#include <stddef.h>
#include <stdint.h>

#include "fsw_codec.h"
#include "fsw_missions_gen.h"
#include "fsw_pil.h"
#include "fx.h"

static fsw_pil_board_t s_b;
static fsw_link_dec_t s_host;
static uint8_t s_wire[FSW_LINK_MAX_WIRE];
static uint8_t s_pay[FSW_LINK_MAX_PAYLOAD];
static uint32_t s_cmd;
static uint32_t s_tlm;
static uint32_t s_steps;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* Drains the board's queue through the host's decoder; every run must be a valid frame. */
static void drain(void)
{
    uint32_t i;
    uint32_t frames0 = s_host.st.frames;
    uint32_t runs = 0u;
    if (s_b.tx_len > FSW_PIL_TX_CAP) {
        __builtin_trap();
    }
    for (i = 0u; i < s_b.tx_len; i++) {
        if (fsw_link_rx_byte(&s_host, s_b.tx[i])) {
            if (s_host.frame.type == FSW_LINK_T_CMD) {
                s_cmd++;
            }
            if (s_host.frame.type == FSW_LINK_T_TLM) {
                s_tlm++;
            }
        }
        if (s_b.tx[i] == 0u) {
            runs++;
        }
    }
    if ((s_host.st.frames - frames0) != runs) {
        __builtin_trap();
    }
    fsw_pil_board_sent(&s_b);
}

static void feed(uint8_t byte)
{
    fsw_pil_rx_t a = fsw_pil_board_rx(&s_b, byte);
    if (a == FSW_PIL_RX_STEP) {
        fsw_pil_board_step(&s_b);
        fsw_pil_board_finish(&s_b, 0u);
        s_steps++;
    }
    drain();
}

static void send(uint8_t type, uint16_t seq, uint32_t len)
{
    uint32_t n = fsw_link_encode(type, seq, s_pay, len, s_wire, FSW_LINK_MAX_WIRE);
    uint32_t i;
    for (i = 0u; i < n; i++) {
        feed(s_wire[i]);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    size_t i;
    fsw_wr_t w;
    fsw_pil_boot_t bt;
    fsw_in_t in;
    uint16_t seq;

    fsw_link_dec_init(&s_host);
    fsw_pil_board_init(&s_b, FSW_PIL_BOARD_HOST, 0u);
    s_steps = 0u;
    drain();
    for (i = 0u; i < size; i++) {
        feed(data[i]);
    }
    if (s_b.st.steps != s_steps) {
        __builtin_trap();
    }

    /* Recovery: whatever the input did, a BOOT matching the staged bytes and a newer SENSOR fly. */
    feed(0u);
    bt.cfg.mission = FSW_MISSION_DETUMBLE;
    bt.cfg.period_us = 20000u;
    bt.cfg.stale_max = 50u;
    bt.cfg.boot_mode = FSW_MODE_DETUMBLE;
    bt.image_len = s_b.stage_got;
    bt.image_crc = fx_crc32(0u, s_b.stage, s_b.stage_got);
    fsw_wr_init(&w, s_pay, sizeof s_pay);
    fsw_pil_wr_boot(&w, &bt);
    send((uint8_t)FSW_LINK_T_BOOT, 1u, w.pos);
    if (!s_b.booted) {
        __builtin_trap();
    }
    in.utime_us = 20000;
    in.seq = 1;
    in.n_counts = 2u;
    for (i = 0u; i < FSW_IN_MAX; i++) {
        in.counts[i] = 0;
        in.status[i] = 0u;
    }
    in.mode_cmd = FSW_CMD_NONE;
    in.host_missed = 0u;
    in.host_rejected = 0u;
    in.tc = FSW_TC_NONE;
    for (i = 0u; i < FSW_TC_ARGS; i++) {
        in.tc_arg[i] = 0;
    }
    fsw_wr_init(&w, s_pay, sizeof s_pay);
    fsw_pil_wr_sensor(&w, &in);
    seq = 7u;
    s_cmd = 0u;
    s_tlm = 0u;
    send((uint8_t)FSW_LINK_T_SENSOR, seq, w.pos);
    if ((s_cmd != 1u) || (s_tlm != 1u) || (s_host.frame.seq != seq)) {
        __builtin_trap();
    }
    return 0;
}
