/*
 * test_fsw_pil.c — the PIL session's payloads and the board's side of it (fsw/app/fsw_pil.c,
 * spec 00 §6.1), host and target, with the DETUMBLE mission as the vehicle.
 *
 * The board session is fed wire bytes exactly as a UART would deliver them and its replies are
 * decoded with the link decoder; every reply is compared with a twin executive stepped directly on
 * the same inputs (fsw_init / fsw_step / fsw_tlm_encode): what the board sends is what the flight
 * software computed, byte for byte, and nothing else moves it.
 */
#include "fsw_pil.h"
#include "fsw_codec.h"
#include "fsw_missions_gen.h"
#include "fx.h"
#include "obs_tables.h"
#include "ut.h"

#define MAX_RX 6u

typedef struct {
    uint8_t type;
    uint16_t seq;
    uint16_t len;
    uint8_t pay[FSW_LINK_MAX_PAYLOAD];
} rx_frame_t;

/* Test-only state in static storage: the target runner's stack is small. */
static fsw_pil_board_t g_b;
static fsw_t g_twin;
static fsw_out_t g_tout;
static fsw_link_dec_t g_hdec;               /* the host's decoder */
static rx_frame_t g_rx[MAX_RX];
static uint32_t g_nrx;
static uint8_t g_wire[FSW_LINK_MAX_WIRE];
static uint8_t g_pay[FSW_LINK_MAX_PAYLOAD];
static uint8_t g_img[FSW_TABLE_CAP_BYTES];
static uint8_t g_tlm[FSW_LINK_MAX_PAYLOAD];
static uint32_t g_steps;                    /* fsw_pil_board_step calls */

static void collect(void)
{
    uint32_t i;
    for (i = 0u; i < g_b.tx_len; i++) {
        if (fsw_link_rx_byte(&g_hdec, g_b.tx[i]) && (g_nrx < MAX_RX)) {
            uint32_t k;
            rx_frame_t *f = &g_rx[g_nrx];
            f->type = g_hdec.frame.type;
            f->seq = g_hdec.frame.seq;
            f->len = g_hdec.frame.len;
            for (k = 0u; k < f->len; k++) {
                f->pay[k] = g_hdec.frame.payload[k];
            }
            g_nrx++;
        }
    }
    fsw_pil_board_sent(&g_b);
}

/* Sends one frame to the board as a UART would (byte by byte) and collects its replies. Returns
   the last action other than NONE. */
static fsw_pil_rx_t send(uint8_t type, uint16_t seq, const uint8_t *pay, uint32_t len)
{
    fsw_pil_rx_t last = FSW_PIL_RX_NONE;
    uint32_t n = fsw_link_encode(type, seq, pay, len, g_wire, FSW_LINK_MAX_WIRE);
    uint32_t i;
    g_nrx = 0u;
    for (i = 0u; i < n; i++) {
        fsw_pil_rx_t a = fsw_pil_board_rx(&g_b, g_wire[i]);
        if (a == FSW_PIL_RX_STEP) {
            fsw_pil_board_step(&g_b);
            g_steps++;
            fsw_pil_board_finish(&g_b, 1234u);
        }
        if (a != FSW_PIL_RX_NONE) {
            last = a;
        }
        collect();
    }
    return last;
}

static fsw_cfg_t cfg50(void)
{
    fsw_cfg_t c;
    c.period_us = 20000u;
    c.stale_max = 50u;
    c.boot_mode = FSW_MODE_DETUMBLE;
    c.mission = FSW_MISSION_DETUMBLE;
    return c;
}

static fsw_in_t input(int64_t seq)
{
    fsw_in_t in;
    uint32_t i;
    in.utime_us = seq * 20000;
    in.seq = seq;
    in.n_counts = 2u;
    for (i = 0u; i < FSW_IN_MAX; i++) {
        in.counts[i] = 0;
        in.status[i] = 0u;
    }
    /* a slowly varying rate, with a STALE sample now and then */
    in.counts[0] = (int32_t)(18301 - (seq * 37));
    in.counts[1] = (int32_t)(-9000 + (seq * 11));
    in.status[1] = ((seq % 13) == 5) ? (uint8_t)FSW_ST_STALE : 0u;
    in.mode_cmd = FSW_CMD_NONE;
    in.host_missed = (uint32_t)seq / 7u;
    in.host_rejected = 0u;
    in.tc = FSW_TC_NONE;
    for (i = 0u; i < FSW_TC_ARGS; i++) {
        in.tc_arg[i] = 0;
    }
    return in;
}

static uint32_t wr_sensor(const fsw_in_t *in)
{
    fsw_wr_t w;
    fsw_wr_init(&w, g_pay, sizeof g_pay);
    fsw_pil_wr_sensor(&w, in);
    return w.pos;
}

static bool same(const uint8_t *a, const uint8_t *b, uint32_t n)
{
    uint32_t i;
    bool eq = true;
    for (i = 0u; i < n; i++) {
        eq = eq && (a[i] == b[i]);
    }
    return eq;
}

/* Stages img[0..n) in 256-byte chunks and boots; returns BOOT_ACK's rc. */
static int32_t stage_and_boot(const fsw_cfg_t *c, uint32_t n, uint32_t crc)
{
    uint32_t off;
    fsw_pil_boot_t bt;
    fsw_wr_t w;
    fsw_rd_t r;
    for (off = 0u; off < n; off += FSW_TABLE_CHUNK_MAX) {
        fsw_table_chunk_t ch;
        ch.table_id = (uint16_t)OBS_TBL_ID;
        ch.revision = 3u;
        ch.total_len = n;
        ch.offset = off;
        ch.n = ((n - off) < FSW_TABLE_CHUNK_MAX) ? (n - off) : FSW_TABLE_CHUNK_MAX;
        ch.data = &g_img[off];
        fsw_wr_init(&w, g_pay, sizeof g_pay);
        fsw_pil_wr_chunk(&w, &ch);
        (void)send((uint8_t)FSW_LINK_T_TABLE_CHUNK, (uint16_t)(100u + off), g_pay, w.pos);
    }
    bt.cfg = *c;
    bt.image_len = n;
    bt.image_crc = crc;
    fsw_wr_init(&w, g_pay, sizeof g_pay);
    fsw_pil_wr_boot(&w, &bt);
    (void)send((uint8_t)FSW_LINK_T_BOOT, 200u, g_pay, w.pos);
    if ((g_nrx != 1u) || (g_rx[0].type != FSW_LINK_T_BOOT_ACK)) {
        return 999;
    }
    fsw_rd_init(&r, g_rx[0].pay, g_rx[0].len);
    return fsw_rd_i32(&r);
}

UT_TEST(payloads_have_their_layout_sizes_and_round_trip)
{
    fsw_wr_t w;
    fsw_rd_t r;
    fsw_in_t in = input(77);
    fsw_in_t in2;
    fsw_pil_cmd_t c;
    fsw_pil_cmd_t c2;
    fsw_pil_stats_t s;
    fsw_pil_stats_t s2;
    fsw_table_chunk_t ch;
    fsw_table_chunk_t ch2;
    uint32_t i;

    in.tc = 0x1234u;
    in.tc_arg[7] = -5;
    UT_UEQ(wr_sensor(&in), FSW_PIL_SENSOR_BYTES);
    fsw_rd_init(&r, g_pay, FSW_PIL_SENSOR_BYTES);
    UT_TRUE(fsw_pil_rd_sensor(&r, &in2));
    UT_UEQ(r.pos, FSW_PIL_SENSOR_BYTES);
    UT_EQ(in2.seq, 77);
    UT_EQ(in2.counts[0], in.counts[0]);
    UT_UEQ(in2.tc, 0x1234u);
    UT_EQ(in2.tc_arg[7], -5);
    fsw_rd_init(&r, g_pay, FSW_PIL_SENSOR_BYTES - 1u);   /* short */
    UT_TRUE(!fsw_pil_rd_sensor(&r, &in2));
    in.n_counts = FSW_IN_MAX + 1u;                         /* more channels than exist */
    (void)wr_sensor(&in);
    fsw_rd_init(&r, g_pay, FSW_PIL_SENSOR_BYTES);
    UT_TRUE(!fsw_pil_rd_sensor(&r, &in2));

    c.seq = -3;
    c.mode = 2u;
    c.health = 0x80000001u;
    c.n_act = 2u;
    c.lim_gen = 3u;
    for (i = 0u; i < FSW_ACT_MAX; i++) {
        c.act_cnt[i] = (int32_t)i - 8;
    }
    fsw_wr_init(&w, g_pay, sizeof g_pay);
    fsw_pil_wr_cmd(&w, &c);
    UT_UEQ(w.pos, FSW_PIL_CMD_BYTES);
    fsw_rd_init(&r, g_pay, w.pos);
    UT_TRUE(fsw_pil_rd_cmd(&r, &c2));
    UT_EQ(c2.seq, -3);
    UT_UEQ(c2.health, 0x80000001u);
    UT_EQ(c2.act_cnt[15], 7);
    UT_UEQ(c2.lim_gen, 3u);

    s.rx = g_hdec.st;
    s.steps = 1u;
    s.dups = 2u;
    s.stale = 3u;
    s.errors = 4u;
    s.boots = 5u;
    s.tx_frames = 6u;
    s.uart_overruns = 7u;
    s.stack_used = 8u;
    s.stack_size = 9u;
    s.insn_max = 10u;
    s.reserved = 0u;
    fsw_wr_init(&w, g_pay, sizeof g_pay);
    fsw_pil_wr_stats(&w, &s);
    UT_UEQ(w.pos, FSW_PIL_STATS_BYTES);
    fsw_rd_init(&r, g_pay, w.pos);
    UT_TRUE(fsw_pil_rd_stats(&r, &s2));
    UT_UEQ(s2.insn_max, 10u);
    UT_UEQ(s2.uart_overruns, 7u);

    for (i = 0u; i < 40u; i++) {
        g_img[i] = (uint8_t)(i + 1u);
    }
    ch.table_id = 0x0A0Bu;
    ch.revision = 9u;
    ch.total_len = 400u;
    ch.offset = 256u;
    ch.n = 40u;
    ch.data = g_img;
    fsw_wr_init(&w, g_pay, sizeof g_pay);
    fsw_pil_wr_chunk(&w, &ch);
    UT_UEQ(w.pos, FSW_PIL_CHUNK_HEAD_BYTES + 40u);
    fsw_rd_init(&r, g_pay, w.pos);
    UT_TRUE(fsw_pil_rd_chunk(&r, &ch2));
    UT_UEQ(ch2.n, 40u);
    UT_UEQ(ch2.offset, 256u);
    UT_UEQ(ch2.data[39], 40u);
    fsw_rd_init(&r, g_pay, w.pos + 1u);                    /* one byte more than n says */
    UT_TRUE(!fsw_pil_rd_chunk(&r, &ch2));

    {
        fsw_pil_hello_t h = {1u, FSW_PIL_BOARD_AN386, 0xDEADBEEFu, 7u, 0x1Fu};
        fsw_pil_hello_t h2;
        fsw_pil_boot_t b = {{20000u, 50u, 2u, 0u}, 123u, 0xCAFEu};
        fsw_pil_boot_t b2;
        fsw_pil_error_t e = {FSW_PIL_E_STAGE, 5u, 77u};
        fsw_pil_error_t e2;
        fsw_pil_ack_t a = {0x0102u, (uint16_t)FSW_PIL_ACK_REJECTED, 4u, 0x0305u, 99u};
        fsw_pil_ack_t a2;
        fsw_wr_init(&w, g_pay, sizeof g_pay);
        fsw_pil_wr_hello(&w, &h);
        UT_UEQ(w.pos, FSW_PIL_HELLO_BYTES);
        fsw_rd_init(&r, g_pay, w.pos);
        UT_TRUE(fsw_pil_rd_hello(&r, &h2));
        UT_UEQ(h2.layout_hash, 0xDEADBEEFu);
        UT_UEQ(h2.board_id, FSW_PIL_BOARD_AN386);
        fsw_wr_init(&w, g_pay, sizeof g_pay);
        fsw_pil_wr_boot(&w, &b);
        UT_UEQ(w.pos, FSW_PIL_BOOT_BYTES);
        fsw_rd_init(&r, g_pay, w.pos);
        UT_TRUE(fsw_pil_rd_boot(&r, &b2));
        UT_UEQ(b2.cfg.stale_max, 50u);
        UT_UEQ(b2.image_crc, 0xCAFEu);
        fsw_wr_init(&w, g_pay, sizeof g_pay);
        fsw_pil_wr_error(&w, &e);
        UT_UEQ(w.pos, FSW_PIL_ERROR_BYTES);
        fsw_rd_init(&r, g_pay, w.pos);
        UT_TRUE(fsw_pil_rd_error(&r, &e2));
        UT_UEQ(e2.detail, 77u);
        fsw_wr_init(&w, g_pay, sizeof g_pay);
        fsw_pil_wr_ack(&w, &a);
        UT_UEQ(w.pos, FSW_PIL_ACK_BYTES);
        fsw_rd_init(&r, g_pay, w.pos);
        UT_TRUE(fsw_pil_rd_ack(&r, &a2));
        UT_UEQ(a2.reason, 0x0305u);
    }
}

UT_TEST(every_mission_telemetry_fits_one_tlm_packet)
{
    uint32_t m;
    uint32_t n = 0u;
    for (m = 0u; m < FSW_N_MISSIONS; m++) {
        const fsw_mis_desc_t *d = fsw_mis_desc(m);
        if (d != NULL) {
            UT_CHECK_LE(d->tlm_bytes, FSW_PIL_TLM_MAX);
            n++;
        }
    }
    UT_UEQ(fsw_pil_missions() & (1u << FSW_MISSION_DETUMBLE), 1u << FSW_MISSION_DETUMBLE);
    UT_TRUE(n >= 1u);
}

UT_TEST(board_says_hello_and_refuses_what_it_cannot_take)
{
    fsw_rd_t r;
    fsw_pil_hello_t h;
    fsw_pil_error_t e;
    fsw_in_t in = input(1);
    fsw_link_dec_init(&g_hdec);
    fsw_pil_board_init(&g_b, FSW_PIL_BOARD_HOST, 0x1234u);
    g_nrx = 0u;
    collect();
    UT_UEQ(g_nrx, 1u);
    UT_UEQ(g_rx[0].type, FSW_LINK_T_HELLO);
    fsw_rd_init(&r, g_rx[0].pay, g_rx[0].len);
    UT_TRUE(fsw_pil_rd_hello(&r, &h));
    UT_UEQ(h.version, FSW_LINK_VERSION);
    UT_UEQ(h.layout_hash, fsw_pil_layout_hash());
    UT_UEQ(h.build_id, 0x1234u);

    /* SENSOR before BOOT */
    (void)send((uint8_t)FSW_LINK_T_SENSOR, 1u, g_pay, wr_sensor(&in));
    UT_UEQ(g_nrx, 1u);
    UT_UEQ(g_rx[0].type, FSW_LINK_T_ERROR);
    fsw_rd_init(&r, g_rx[0].pay, g_rx[0].len);
    UT_TRUE(fsw_pil_rd_error(&r, &e));
    UT_UEQ(e.code, FSW_PIL_E_NOT_BOOTED);
    /* a SENSOR one byte short */
    (void)send((uint8_t)FSW_LINK_T_SENSOR, 2u, g_pay, FSW_PIL_SENSOR_BYTES - 1u);
    fsw_rd_init(&r, g_rx[0].pay, g_rx[0].len);
    UT_TRUE(fsw_pil_rd_error(&r, &e));
    UT_UEQ(e.code, FSW_PIL_E_LEN);
    UT_UEQ(e.detail, FSW_PIL_SENSOR_BYTES - 1u);
    /* a type only the board sends */
    (void)send((uint8_t)FSW_LINK_T_CMD, 3u, g_pay, 4u);
    fsw_rd_init(&r, g_rx[0].pay, g_rx[0].len);
    UT_TRUE(fsw_pil_rd_error(&r, &e));
    UT_UEQ(e.code, FSW_PIL_E_TYPE);
    UT_UEQ(e.type, FSW_LINK_T_CMD);
    /* PING is echoed; a HELLO request gets HELLO */
    g_pay[0] = 0xABu;
    (void)send((uint8_t)FSW_LINK_T_PING, 4u, g_pay, 1u);
    UT_UEQ(g_rx[0].type, FSW_LINK_T_PONG);
    UT_UEQ(g_rx[0].pay[0], 0xABu);
    (void)send((uint8_t)FSW_LINK_T_HELLO, 5u, g_pay, 0u);
    UT_UEQ(g_rx[0].type, FSW_LINK_T_HELLO);
    UT_UEQ(g_b.st.errors, 3u);
    UT_UEQ(g_steps, 0u);
}

UT_TEST(boot_staging_checks_length_crc_and_order)
{
    const fsw_cfg_t c = cfg50();
    uint32_t n = obs_table_encode(&OBS_TBL_50HZ_PHYS, 3u, g_img, (uint32_t)sizeof(g_img));
    uint32_t crc = fx_crc32(0u, g_img, n);
    fsw_table_chunk_t ch;
    fsw_wr_t w;
    fsw_rd_t r;
    fsw_pil_error_t e;

    UT_TRUE(n > FSW_TABLE_CHUNK_MAX);   /* two chunks at least: order matters */
    fsw_link_dec_init(&g_hdec);
    fsw_pil_board_init(&g_b, FSW_PIL_BOARD_HOST, 0u);
    fsw_pil_board_sent(&g_b);
    UT_EQ(stage_and_boot(&c, n, crc ^ 1u), FSW_PIL_BOOT_BAD_IMAGE);
    UT_TRUE(!g_b.booted);
    UT_EQ(stage_and_boot(&c, n - 1u, crc), FSW_PIL_BOOT_BAD_IMAGE);

    /* a chunk out of order is refused and staging starts over */
    ch.table_id = (uint16_t)OBS_TBL_ID;
    ch.revision = 3u;
    ch.total_len = n;
    ch.offset = 1u;
    ch.n = 10u;
    ch.data = g_img;
    fsw_wr_init(&w, g_pay, sizeof g_pay);
    fsw_pil_wr_chunk(&w, &ch);
    (void)send((uint8_t)FSW_LINK_T_TABLE_CHUNK, 7u, g_pay, w.pos);
    fsw_rd_init(&r, g_rx[0].pay, g_rx[0].len);
    UT_TRUE(fsw_pil_rd_error(&r, &e));
    UT_UEQ(e.code, FSW_PIL_E_STAGE);
    UT_UEQ(g_b.stage_got, 0u);

    UT_EQ(stage_and_boot(&c, n, crc), 0);
    UT_TRUE(g_b.booted);
    UT_UEQ(g_b.st.boots, 3u);
}

/* Boots the board and the twin from the same image. */
static void boot_both(void)
{
    const fsw_cfg_t c = cfg50();
    uint32_t n = obs_table_encode(&OBS_TBL_50HZ_PHYS, 3u, g_img, (uint32_t)sizeof(g_img));
    fsw_link_dec_init(&g_hdec);
    fsw_pil_board_init(&g_b, FSW_PIL_BOARD_HOST, 0u);
    fsw_pil_board_sent(&g_b);
    (void)stage_and_boot(&c, n, fx_crc32(0u, g_img, n));
    (void)fsw_init(&g_twin, &c, g_img, n);
    g_steps = 0u;
}

/* The board's CMD and TLM for step k are the twin's outputs, byte for byte. */
static bool replies_match_twin(int64_t k)
{
    fsw_wr_t w;
    fsw_pil_cmd_t c;
    uint32_t i;
    uint32_t n;
    bool ok = (g_nrx == 2u) && (g_rx[0].type == FSW_LINK_T_CMD) && (g_rx[1].type == FSW_LINK_T_TLM);
    c.seq = k;
    c.lim_gen = g_b.lim_gen;
    c.mode = g_tout.mode;
    c.health = g_tout.health;
    c.n_act = g_tout.n_act;
    for (i = 0u; i < FSW_ACT_MAX; i++) {
        c.act_cnt[i] = (i < g_tout.n_act) ? g_tout.act_cnt[i] : 0;
    }
    fsw_wr_init(&w, g_pay, sizeof g_pay);
    fsw_pil_wr_cmd(&w, &c);
    ok = ok && (g_rx[0].len == w.pos) && same(g_rx[0].pay, g_pay, w.pos);
    fsw_wr_init(&w, g_tlm, sizeof g_tlm);
    fsw_wr_u32(&w, 1234u);
    fsw_wr_u32(&w, fsw_tlm_layout(&g_tout.tlm));
    n = fsw_tlm_encode(&g_tout.tlm, &g_tlm[8], FSW_PIL_TLM_MAX);
    ok = ok && (n > 0u) && (g_rx[1].len == (8u + n)) && same(g_rx[1].pay, g_tlm, 8u + n);
    ok = ok && (g_rx[0].seq == (uint16_t)k) && (g_rx[1].seq == (uint16_t)k);
    return ok;
}

UT_TEST(steps_match_the_twin_and_duplicates_and_stale_frames_do_not_step)
{
    int64_t k;
    uint32_t bad = 0u;
    boot_both();
    for (k = 1; k <= 200; k++) {
        fsw_in_t in = input(k);
        if (k == 50) {
            in.mode_cmd = FSW_MODE_STANDBY;
        }
        if (k == 60) {
            in.mode_cmd = FSW_MODE_DETUMBLE;
        }
        UT_TRUE(send((uint8_t)FSW_LINK_T_SENSOR, (uint16_t)k, g_pay, wr_sensor(&in)) == FSW_PIL_RX_STEP);
        fsw_step(&g_twin, &in, &g_tout);
        if (!replies_match_twin(k)) {
            bad++;
        }
        if ((k % 40) == 0) {
            /* the same SENSOR again (its replies lost): the cached replies, no step */
            (void)send((uint8_t)FSW_LINK_T_SENSOR, (uint16_t)k, g_pay, wr_sensor(&in));
            if (!replies_match_twin(k)) {
                bad++;
            }
            /* an older one: dropped, nothing sent */
            in = input(k - 2);
            UT_TRUE(send((uint8_t)FSW_LINK_T_SENSOR, (uint16_t)(k - 2), g_pay, wr_sensor(&in)) == FSW_PIL_RX_NONE);
            UT_UEQ(g_nrx, 0u);
        }
    }
    UT_UEQ(bad, 0u);
    UT_UEQ(g_steps, 200u);
    UT_UEQ(g_b.st.steps, 200u);
    {
        /* a genuine jump of 40 000 frames (the bridge followed it): stepped, although its link seq
           is "older" in 16-bit serial arithmetic; the next frame after it too */
        fsw_in_t in = input(200 + 40000);
        UT_TRUE(send((uint8_t)FSW_LINK_T_SENSOR, (uint16_t)(200 + 40000), g_pay, wr_sensor(&in)) == FSW_PIL_RX_STEP);
        fsw_step(&g_twin, &in, &g_tout);
        UT_TRUE(replies_match_twin(200 + 40000));
        in = input(200 + 40001);
        UT_TRUE(send((uint8_t)FSW_LINK_T_SENSOR, (uint16_t)(200 + 40001), g_pay, wr_sensor(&in)) == FSW_PIL_RX_STEP);
        fsw_step(&g_twin, &in, &g_tout);
        UT_TRUE(replies_match_twin(200 + 40001));
        g_steps -= 2u;
    }
    UT_UEQ(g_b.st.dups, 5u);
    UT_UEQ(g_b.st.stale, 5u);
    UT_UEQ(g_b.st.insn_max, 1234u);
    UT_UEQ(g_twin.tlm.n_chan_rej, g_b.fsw.tlm.n_chan_rej);
    UT_TRUE(g_twin.tlm.n_chan_rej > 10u);   /* the STALE samples reached the executive */
}

UT_TEST(an_upload_while_flying_acks_like_the_twin_and_reports_new_limits)
{
    obs_params_t p = OBS_TBL_50HZ_PHYS;
    uint32_t n;
    uint32_t off;
    int64_t k;
    fsw_rd_t r;
    fsw_range_t rng[FSW_IN_MAX];
    fsw_range_t trng[FSW_IN_MAX];
    uint32_t nr = 0u;
    uint32_t ntr = 0u;
    bool limits_seen = false;
    boot_both();
    for (k = 1; k <= 5; k++) {
        fsw_in_t in = input(k);
        (void)send((uint8_t)FSW_LINK_T_SENSOR, (uint16_t)k, g_pay, wr_sensor(&in));
        fsw_step(&g_twin, &in, &g_tout);
    }
    n = obs_table_encode(&p, 9u, g_img, (uint32_t)sizeof(g_img));
    for (off = 0u; off < n; off += 100u) {
        fsw_table_chunk_t ch;
        fsw_pil_ack_t a;
        fsw_pil_ack_t ta;
        fsw_wr_t w;
        ch.table_id = (uint16_t)OBS_TBL_ID;
        ch.revision = 9u;
        ch.total_len = n;
        ch.offset = off;
        ch.n = ((n - off) < 100u) ? (n - off) : 100u;
        ch.data = &g_img[off];
        fsw_wr_init(&w, g_pay, sizeof g_pay);
        fsw_pil_wr_chunk(&w, &ch);
        (void)send((uint8_t)FSW_LINK_T_TABLE_CHUNK, (uint16_t)(500u + off), g_pay, w.pos);
        fsw_pil_table_chunk(&g_twin, &ch, &ta);
        UT_UEQ(g_nrx, 1u);
        UT_UEQ(g_rx[0].type, FSW_LINK_T_TABLE_ACK);
        fsw_rd_init(&r, g_rx[0].pay, g_rx[0].len);
        UT_TRUE(fsw_pil_rd_ack(&r, &a));
        UT_UEQ(a.result, ta.result);
        UT_UEQ(a.bytes_received, ta.bytes_received);
    }
    UT_UEQ(g_b.fsw.tbl.state, FSW_TBL_S_READY);
    for (k = 6; k <= 10; k++) {
        fsw_in_t in = input(k);
        (void)send((uint8_t)FSW_LINK_T_SENSOR, (uint16_t)k, g_pay, wr_sensor(&in));
        fsw_step(&g_twin, &in, &g_tout);
        if ((g_nrx == 3u) && (g_rx[0].type == FSW_LINK_T_LIMITS)) {
            limits_seen = true;
            fsw_rd_init(&r, g_rx[0].pay, g_rx[0].len);
            UT_TRUE(fsw_pil_rd_ranges(&r, rng, &nr));
        }
    }
    UT_TRUE(limits_seen);
    UT_UEQ(g_b.lim_gen, 1u);
    UT_UEQ(g_b.fsw.tlm.tbl_revision, 9u);
    fsw_sensor_ranges(&g_twin, trng, &ntr);
    UT_UEQ(nr, ntr);
    UT_TRUE(nr >= 1u);
    UT_EQ(rng[0].min, trng[0].min);
    UT_EQ(rng[nr - 1u].max, trng[ntr - 1u].max);
}

UT_TEST(a_resent_chunk_gets_the_same_ack_and_a_host_hello_starts_a_new_session)
{
    obs_params_t p = OBS_TBL_50HZ_PHYS;
    uint32_t n;
    fsw_table_chunk_t ch;
    fsw_wr_t w;
    fsw_rd_t r;
    fsw_pil_ack_t a1;
    fsw_pil_ack_t a2;
    uint32_t off;
    uint32_t rej0;
    boot_both();
    n = obs_table_encode(&p, 11u, g_img, (uint32_t)sizeof(g_img));
    rej0 = g_b.fsw.tlm.n_tbl_rej;
    for (off = 0u; off < n; off += 200u) {
        ch.table_id = (uint16_t)OBS_TBL_ID;
        ch.revision = 11u;
        ch.total_len = n;
        ch.offset = off;
        ch.n = ((n - off) < 200u) ? (n - off) : 200u;
        ch.data = &g_img[off];
        fsw_wr_init(&w, g_pay, sizeof g_pay);
        fsw_pil_wr_chunk(&w, &ch);
        (void)send((uint8_t)FSW_LINK_T_TABLE_CHUNK, (uint16_t)(700u + off), g_pay, w.pos);
    }
    fsw_rd_init(&r, g_rx[0].pay, g_rx[0].len);
    UT_TRUE(fsw_pil_rd_ack(&r, &a1));
    UT_UEQ(a1.result, FSW_PIL_ACK_ACCEPTED);
    /* the last chunk again, same seq (its ack lost): the same ack, not applied (no BUSY refusal) */
    (void)send((uint8_t)FSW_LINK_T_TABLE_CHUNK, (uint16_t)(700u + ch.offset), g_pay, w.pos);
    UT_UEQ(g_nrx, 1u);
    fsw_rd_init(&r, g_rx[0].pay, g_rx[0].len);
    UT_TRUE(fsw_pil_rd_ack(&r, &a2));
    UT_UEQ(a2.result, FSW_PIL_ACK_ACCEPTED);
    UT_UEQ(g_b.fsw.tlm.n_tbl_rej, rej0);
    /* a host HELLO: a new session (not booted, staging forgotten), answered with HELLO */
    UT_TRUE(g_b.booted);
    (void)send((uint8_t)FSW_LINK_T_HELLO, 900u, g_pay, 0u);
    UT_UEQ(g_rx[0].type, FSW_LINK_T_HELLO);
    UT_TRUE(!g_b.booted);
    UT_UEQ(g_b.stage_got, 0u);
}

UT_TEST(link_stats_and_the_end_of_a_session)
{
    fsw_rd_t r;
    fsw_pil_stats_t s;
    fsw_wr_t w;
    boot_both();
    g_wire[0] = 0x55u;   /* garbage then a delimiter: one counted error */
    g_wire[1] = 0x00u;
    (void)fsw_pil_board_rx(&g_b, g_wire[0]);
    (void)fsw_pil_board_rx(&g_b, g_wire[1]);
    (void)send((uint8_t)FSW_LINK_T_LINK_STATS, 9u, g_pay, 0u);
    UT_UEQ(g_rx[0].type, FSW_LINK_T_LINK_STATS);
    fsw_rd_init(&r, g_rx[0].pay, g_rx[0].len);
    UT_TRUE(fsw_pil_rd_stats(&r, &s));
    UT_UEQ(s.boots, 1u);
    UT_UEQ(s.rx.err_cobs + s.rx.err_short, 1u);
    fsw_wr_init(&w, g_pay, sizeof g_pay);
    fsw_wr_u32(&w, 3u);   /* not an op */
    (void)send((uint8_t)FSW_LINK_T_MODE_CMD, 10u, g_pay, w.pos);
    UT_UEQ(g_rx[0].type, FSW_LINK_T_ERROR);
    UT_UEQ(g_rx[0].seq, 10u);   /* ERROR carries the offending frame's seq */
    fsw_wr_init(&w, g_pay, sizeof g_pay);
    fsw_wr_u32(&w, FSW_PIL_MODE_RESET);
    UT_TRUE(send((uint8_t)FSW_LINK_T_MODE_CMD, 12u, g_pay, w.pos) == FSW_PIL_RX_RESET);
    UT_UEQ(g_rx[0].type, FSW_LINK_T_MODE_CMD);
    fsw_wr_init(&w, g_pay, sizeof g_pay);
    fsw_wr_u32(&w, FSW_PIL_MODE_END);
    UT_TRUE(send((uint8_t)FSW_LINK_T_MODE_CMD, 11u, g_pay, w.pos) == FSW_PIL_RX_END);
    UT_UEQ(g_rx[0].type, FSW_LINK_T_MODE_CMD);
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(payloads_have_their_layout_sizes_and_round_trip),
        UT_CASE(every_mission_telemetry_fits_one_tlm_packet),
        UT_CASE(board_says_hello_and_refuses_what_it_cannot_take),
        UT_CASE(boot_staging_checks_length_crc_and_order),
        UT_CASE(steps_match_the_twin_and_duplicates_and_stale_frames_do_not_step),
        UT_CASE(an_upload_while_flying_acks_like_the_twin_and_reports_new_limits),
        UT_CASE(a_resent_chunk_gets_the_same_ack_and_a_host_hello_starts_a_new_session),
        UT_CASE(link_stats_and_the_end_of_a_session),
    };
    return UT_RUN("fsw_pil", cases);
}
