/*
 * The HOLD mission through the executive (spec 00 §3.3, spec 40 §4.2, §8): boot from the table
 * image into the mission mode, the channel map (attitude counts[0..2] yaw / roll / pitch, gimbal
 * encoders counts[3..5], torques act[0..2]), ch_mask, the telecommands, the roll cap veto on an
 * upload, the step divider, a stale frame, the health word and the telemetry size; the table's
 * estimator blocks on the wire (offsets, round trip, reserved bytes, loader limits). Every expected
 * count is derived by hand in the comments. Host and target.
 *
 * Boot table gains (tools/pd/design.py; Ty = 0.25 s, 1/Ty = 4): yaw G_P = 2 20 = 40, G_D = 2 745 4
 * = 5960; roll G_P = 2 15 = 30, G_D = 2 135 4 = 1080; pitch G_P = 40, G_D = 2 475 4 = 3800 (N m/rad,
 * N m s/rad per sample). With y, dy in counts of 2^-26 rad, M = -4 (G_P y + G_D dy) q28 exactly
 * (test_pd.c), and the actuator count is rnd(M / 256) (2^-20 N m), half away from zero.
 */
#include "fsw_exec.h"
#include "pd_tables.h"
#include "ut.h"

#define TC(local) FSW_TC_ID(FSW_MISSION_HOLD, (local))
#define K_Q22(s)  ((uint32_t)(s) * 4194304u)
#define BETA_LIM  13176795            /* pi/4 2^24 = 13 176 794.6 -> 13 176 795 */
#define RW(code, detail) ((uint32_t)(code) | ((uint32_t)(detail) << FSW_TBL_DETAIL_SHIFT))

/* Large objects live in static storage: the target runner has a small stack. Test-only state. */
static fsw_t g_a;
static fsw_out_t g_oa;
static uint8_t g_img[FSW_TABLE_CAP_BYTES];
static uint8_t g_img2[FSW_TABLE_CAP_BYTES];
static pd_table_t g_t;
static pd_params_t g_chk;   /* pd_table_check's scratch */

/* round(v / 2^n) half away from zero, written out (spec 00 §1.3). */
static int32_t rnd_shr(int64_t v, uint32_t n)
{
    const uint64_t mag = (v < 0) ? ((uint64_t)0 - (uint64_t)v) : (uint64_t)v;
    const uint64_t q = (mag + ((uint64_t)1 << (n - 1u))) >> n;
    return (v < 0) ? -(int32_t)q : (int32_t)q;
}

/* The actuator count of M = -4 (gp y + gd dy) (integer gains, counts; no clamp reached here). */
static int32_t act_of(int64_t gp, int64_t gd, int64_t y, int64_t dy)
{
    return rnd_shr(-4 * ((gp * y) + (gd * dy)), 8u);
}

static fsw_cfg_t cfg(void)
{
    fsw_cfg_t c;
    c.period_us = PD_TBL_DEFAULT.c.period_us;
    c.stale_max = 5u;
    c.boot_mode = FSW_MODE_HOLD;
    c.mission = FSW_MISSION_HOLD;
    return c;
}

/* Frame k (seq k) with the three attitude counts; encoders 0. */
static fsw_in_t frame(int64_t k, int32_t y0, int32_t y1, int32_t y2)
{
    fsw_in_t in;
    uint32_t i;
    in.utime_us = k * (int64_t)PD_TBL_DEFAULT.c.period_us;
    in.seq = k;
    in.n_counts = PD_N_SENS;
    for (i = 0u; i < FSW_IN_MAX; i++) {
        in.counts[i] = 0;
        in.status[i] = 0u;
    }
    in.counts[0] = y0;
    in.counts[1] = y1;
    in.counts[2] = y2;
    in.mode_cmd = FSW_CMD_NONE;
    in.host_missed = 0u;
    in.host_rejected = 0u;
    in.tc = FSW_TC_NONE;
    for (i = 0u; i < FSW_TC_ARGS; i++) {
        in.tc_arg[i] = 0;
    }
    return in;
}

static void run(const fsw_in_t *in)
{
    fsw_step(&g_a, in, &g_oa);
}

static fsw_rc_t boot(const pd_table_t *t, uint32_t rev)
{
    fsw_cfg_t c = cfg();
    uint32_t n = pd_table_encode(t, rev, g_img, (uint32_t)sizeof(g_img));
    return fsw_init(&g_a, &c, g_img, n);
}

/* The n bytes of g_img (16 + 3068 = 3084 for a whole image: 13 chunks) in chunks of at most
   FSW_TABLE_CHUNK_MAX = 256 bytes; the rc and *why of the last chunk (where the candidate completes and
   is checked). */
static fsw_rc_t upload_img(uint32_t n, uint32_t rev, uint32_t *why)
{
    fsw_rc_t rc = FSW_OK;
    uint32_t off;
    for (off = 0u; off < n; off += FSW_TABLE_CHUNK_MAX) {
        fsw_table_chunk_t c;
        c.table_id = (uint16_t)PD_TBL_ID;
        c.revision = rev;
        c.total_len = n;
        c.offset = off;
        c.n = ((n - off) < FSW_TABLE_CHUNK_MAX) ? (n - off) : FSW_TABLE_CHUNK_MAX;
        c.data = &g_img[off];
        rc = fsw_table_upload(&g_a, &c, why);
    }
    return rc;
}

static fsw_rc_t upload(const pd_table_t *t, uint32_t rev, uint32_t *why)
{
    const uint32_t n = pd_table_encode(t, rev, g_img, (uint32_t)sizeof(g_img));
    UT_CHECK_UEQ(n, FSW_TABLE_HDR_BYTES + PD_TBL_PAYLOAD);
    return upload_img(n, rev, why);
}

/* Little-endian u32 at byte off of the payload in g_img. */
static uint32_t pl_u32(uint32_t off)
{
    const uint8_t *b = &g_img[FSW_TABLE_HDR_BYTES + off];
    return (uint32_t)b[0] | ((uint32_t)b[1] << 8) | ((uint32_t)b[2] << 16) | ((uint32_t)b[3] << 24);
}

static const pd_ch_tlm_t *ch(uint32_t k)
{
    return &g_oa.tlm.m.hold.ch[k];
}

/* Yaw y = 640: M = -160 640 = -102 400 -> -400 counts; roll y = 64: -120 64 = -7680 -> -30;
   pitch y = -1280: +204 800 -> +800. The boot table's k2_nom equals k2_cold on every channel
   (FALLBACK_GAIN), and it is the boot table (TABLE_DEFAULT). Telemetry: header 88 + 3 actuator
   counts 12 + health 4 + block (18 words x 3 channels + revision) 220 = 324 bytes. */
UT_TEST(boots_into_hold_and_commands_each_channel)
{
    uint8_t buf[PD_TLM_TOTAL_BYTES];
    fsw_in_t in = frame(1, 640, 64, -1280);
    UT_UEQ(boot(&PD_TBL_DEFAULT, 3u), FSW_OK);
    run(&in);
    UT_UEQ(g_oa.mode, FSW_MODE_HOLD);
    UT_UEQ(g_oa.n_act, 3u);
    UT_EQ(g_oa.act_cnt[0], -400);
    UT_EQ(g_oa.act_cnt[1], -30);
    UT_EQ(g_oa.act_cnt[2], 800);
    UT_EQ(g_oa.tlm.act_cnt[2], 800);
    UT_UEQ(g_oa.health, 0u);
    UT_UEQ(g_oa.tlm.mod_health, PD_H_TABLE_DEFAULT | PD_H_FALLBACK_GAIN);
    UT_EQ(ch(2)->m_q28, 204800);
    UT_EQ(ch(0)->y_q30, 10240);               /* 16 640 */
    UT_UEQ(ch(1)->k2_q22, K_Q22(135));
    UT_UEQ(g_oa.tlm.mission, FSW_MISSION_HOLD);
    UT_UEQ(g_oa.tlm.tbl_revision, 3u);
    UT_UEQ(g_oa.tlm.m.hold.revision, 3u);
    UT_UEQ(fsw_tlm_layout(&g_oa.tlm), PD_TLM_LAYOUT);
    UT_UEQ(PD_TLM_TOTAL_BYTES, 324u);
    UT_UEQ(fsw_tlm_encode(&g_oa.tlm, buf, PD_TLM_TOTAL_BYTES), 324u);
    UT_UEQ(fsw_tlm_encode(&g_oa.tlm, buf, PD_TLM_TOTAL_BYTES - 1u), 0u);
}

/* Booted in STANDBY the torques are the safe 0; the mode command enters HOLD and the first sample
   carries no derivative (pitch y = 6400 -> -160 6400 / 256 = -4000). */
UT_TEST(hold_is_entered_from_standby_without_a_kick)
{
    fsw_cfg_t c = cfg();
    uint32_t n;
    fsw_in_t in = frame(1, 0, 0, 3200);
    c.boot_mode = FSW_MODE_STANDBY;
    n = pd_table_encode(&PD_TBL_DEFAULT, 1u, g_img, (uint32_t)sizeof(g_img));
    UT_UEQ(fsw_init(&g_a, &c, g_img, n), FSW_OK);
    run(&in);
    UT_UEQ(g_oa.mode, FSW_MODE_STANDBY);
    UT_EQ(g_oa.act_cnt[2], 0);
    in = frame(2, 0, 0, 6400);
    in.mode_cmd = FSW_MODE_HOLD;
    run(&in);
    UT_UEQ(g_oa.mode, FSW_MODE_HOLD);
    UT_EQ(g_oa.act_cnt[2], -4000);
    UT_EQ(ch(2)->dy_q30, 0);
}

/* Channel k's torque depends only on attitude k and encoder k + 3.
   Frame 1 y = (6400, 1280, 2560): (-4000, -600, -1600).
   Frame 2 only y0 -> 6464 (dy 64): yaw -4 (40 6464 + 5960 64) / 256 = -2 560 000 / 256 = -10 000;
   roll and pitch see dy = 0 and keep -600, -1600.
   Frame 3 y0 steady (-160 6464 / 256 = -4040) and pitch encoder -beta_lim: pitch's torque (< 0)
   drives beta further out, zeroed; the others unchanged. Frame 4 the same on yaw's encoder. Frame 5
   roll encoder +beta_lim with roll's torque < 0 (inward): it passes. */
UT_TEST(each_channel_uses_only_its_own_sensor_and_encoder)
{
    fsw_in_t in;
    UT_UEQ(boot(&PD_TBL_DEFAULT, 1u), FSW_OK);
    in = frame(1, 6400, 1280, 2560);
    run(&in);
    UT_EQ(g_oa.act_cnt[0], act_of(40, 5960, 6400, 0));
    UT_EQ(g_oa.act_cnt[0], -4000);
    UT_EQ(g_oa.act_cnt[1], -600);
    UT_EQ(g_oa.act_cnt[2], -1600);
    in = frame(2, 6464, 1280, 2560);
    run(&in);
    UT_EQ(g_oa.act_cnt[0], -10000);
    UT_EQ(g_oa.act_cnt[0], act_of(40, 5960, 6464, 64));
    UT_EQ(g_oa.act_cnt[1], -600);
    UT_EQ(g_oa.act_cnt[2], -1600);
    in = frame(3, 6464, 1280, 2560);
    in.counts[5] = -BETA_LIM;
    run(&in);
    UT_EQ(g_oa.act_cnt[0], -4040);
    UT_EQ(g_oa.act_cnt[1], -600);
    UT_EQ(g_oa.act_cnt[2], 0);
    UT_UEQ(ch(2)->health & PD_H_BETA_LIM, PD_H_BETA_LIM);
    UT_UEQ((ch(0)->health | ch(1)->health) & (PD_H_BETA_LIM | PD_H_BETA_WARN), 0u);
    UT_UEQ(ch(2)->beta_lim_cnt, 1u);
    in = frame(4, 6464, 1280, 2560);
    in.counts[3] = -BETA_LIM;
    run(&in);
    UT_EQ(g_oa.act_cnt[0], 0);
    UT_EQ(g_oa.act_cnt[1], -600);
    UT_EQ(g_oa.act_cnt[2], -1600);
    UT_UEQ(ch(0)->beta_lim_cnt, 1u);
    UT_UEQ(ch(2)->beta_lim_cnt, 1u);
    in = frame(5, 6464, 1280, 2560);
    in.counts[4] = BETA_LIM;
    run(&in);
    UT_EQ(g_oa.act_cnt[0], -4040);
    UT_EQ(g_oa.act_cnt[1], -600);
    UT_UEQ(ch(1)->beta_lim_cnt, 1u);
    UT_UEQ(ch(0)->beta_lim_cnt + ch(2)->beta_lim_cnt, 2u);
}

/* ch_mask 5 (yaw, pitch): roll commands 0 whatever its sensor says, and adds nothing to the health
   word (an out-of-range roll sample is not even looked at). Yaw, pitch y = 640: -400 each. */
UT_TEST(ch_mask_clearing_a_channel_commands_zero)
{
    fsw_in_t in;
    g_t = PD_TBL_DEFAULT;
    g_t.c.ch_mask = 5u;
    UT_UEQ(boot(&g_t, 1u), FSW_OK);
    in = frame(1, 640, 640, 640);
    run(&in);
    UT_EQ(g_oa.act_cnt[0], -400);
    UT_EQ(g_oa.act_cnt[1], 0);
    UT_EQ(g_oa.act_cnt[2], -400);
    in = frame(2, 640, 40000000, 640);        /* roll 0.6 rad: out of range, but masked */
    run(&in);
    UT_EQ(g_oa.act_cnt[1], 0);
    UT_UEQ(g_oa.tlm.mod_health, PD_H_TABLE_DEFAULT | PD_H_FALLBACK_GAIN);
    UT_UEQ(ch(1)->range_rej + ch(1)->miss_cnt, 0u);
    UT_EQ(ch(1)->m_q28, 0);
}

/* SET_F 30 000 (1e-6 Hz) = 0.03 Hz selects GROUND at node 4 (0.03 2^32 = 128 849 018.88 -> uq32
   128 849 019, 0.08 uq32 LSB above the node: phi = 0): yaw 220 s, roll 135 s (already its k2: no
   RETUNE), pitch 385 s exactly, with a RETUNE pulse on that sample only. With pitch G_D = 2 385 4
   = 3080, yaw 2 220 4 = 1760, roll 1080, a 64-count step on all three:
   yaw -4 (40 64 + 1760 64) / 256 = -1800, roll -4 (30 64 + 1080 64) / 256 = -1110,
   pitch -4 (40 64 + 3080 64) / 256 = -3120. SET_SOURCE 0 returns to FIXED (k2_nom), SET_SOURCE 1 to
   GROUND at the f last commanded. */
UT_TEST(set_f_and_set_source_select_the_gain_source)
{
    fsw_in_t in;
    UT_UEQ(boot(&PD_TBL_DEFAULT, 1u), FSW_OK);
    in = frame(1, 0, 0, 0);
    run(&in);
    UT_UEQ(ch(2)->k2_q22, K_Q22(475));
    in = frame(2, 0, 0, 0);
    in.tc = TC(PD_CMD_SET_F);
    in.tc_arg[0] = 30000;
    run(&in);
    UT_UEQ(g_oa.tlm.n_tc, 1u);
    UT_UEQ(ch(0)->k2_q22, K_Q22(220));
    UT_UEQ(ch(1)->k2_q22, K_Q22(135));
    UT_UEQ(ch(2)->k2_q22, K_Q22(385));
    UT_UEQ(ch(2)->health, PD_H_RETUNE | (PD_SRC_GROUND << PD_H_SRC_SH));
    UT_UEQ(ch(0)->health, PD_H_RETUNE | (PD_SRC_GROUND << PD_H_SRC_SH));
    UT_UEQ(ch(1)->health, PD_H_FALLBACK_GAIN | (PD_SRC_GROUND << PD_H_SRC_SH));
    in = frame(3, 64, 64, 64);
    run(&in);
    UT_UEQ(ch(2)->health & PD_H_RETUNE, 0u);
    UT_EQ(g_oa.act_cnt[0], -1800);
    UT_EQ(g_oa.act_cnt[1], -1110);
    UT_EQ(g_oa.act_cnt[2], -3120);
    /* out-of-range arguments are ignored: SET_SOURCE 3 (no such source), SET_F 0.5 Hz */
    in = frame(4, 64, 64, 64);
    in.tc = TC(PD_CMD_SET_SOURCE);
    in.tc_arg[0] = (int32_t)PD_SRC_ADAPTIVE + 1;
    run(&in);
    in = frame(5, 64, 64, 64);
    in.tc = TC(PD_CMD_SET_F);
    in.tc_arg[0] = 500000;
    run(&in);
    UT_UEQ(ch(2)->k2_q22, K_Q22(385));
    UT_UEQ(ch(2)->health, PD_SRC_GROUND << PD_H_SRC_SH);
    in = frame(6, 64, 64, 64);
    in.tc = TC(PD_CMD_SET_SOURCE);
    in.tc_arg[0] = (int32_t)PD_SRC_FIXED;
    run(&in);
    UT_UEQ(ch(2)->k2_q22, K_Q22(475));
    UT_UEQ(ch(2)->health, PD_H_RETUNE | PD_H_FALLBACK_GAIN);
    in = frame(7, 64, 64, 64);
    in.tc = TC(PD_CMD_SET_SOURCE);
    in.tc_arg[0] = (int32_t)PD_SRC_GROUND;
    run(&in);
    UT_UEQ(ch(2)->k2_q22, K_Q22(385));
    UT_UEQ(g_oa.tlm.n_tc, 5u);
    UT_UEQ(g_oa.tlm.n_tc_rej, 0u);
}

/* SET_K2 (2^-8 s) selects FIXED at yaw 100.5 s = 25 728, roll 160 s = 40 960 (above roll's k2_max:
   clamped to 150 s), pitch 200.25 s = 51 264: uq22 100.5 2^22 = 421 527 552, 150 2^22 = 629 145 600,
   200.25 2^22 = 839 909 376. First GROUND at 0.05 Hz (node 8: pitch 235 s), so every channel
   re-tunes. Then pitch G_D = 2 200.25 4 = 1602: a 64-count step gives -4 (40 64 + 1602 64) / 256
   = -1642. */
UT_TEST(set_k2_selects_fixed_gains_clamped_to_k2_max)
{
    fsw_in_t in;
    UT_UEQ(boot(&PD_TBL_DEFAULT, 1u), FSW_OK);
    in = frame(1, 0, 0, 0);
    in.tc = TC(PD_CMD_SET_F);
    in.tc_arg[0] = 50000;
    run(&in);
    UT_UEQ(ch(2)->k2_q22, K_Q22(235));
    in = frame(2, 0, 0, 0);
    in.tc = TC(PD_CMD_SET_K2);
    in.tc_arg[0] = 25728;
    in.tc_arg[1] = 40960;
    in.tc_arg[2] = 51264;
    run(&in);
    UT_UEQ(ch(0)->k2_q22, 421527552u);
    UT_UEQ(ch(1)->k2_q22, 629145600u);
    UT_UEQ(ch(2)->k2_q22, 839909376u);
    UT_UEQ(ch(0)->health, PD_H_RETUNE);
    UT_UEQ(ch(1)->health, PD_H_RETUNE);
    UT_UEQ(ch(2)->health, PD_H_RETUNE);
    in = frame(3, 0, 0, 64);
    run(&in);
    UT_EQ(g_oa.act_cnt[2], -1642);
    UT_UEQ(ch(2)->health, 0u);
}

/* RESET_COUNTERS clears every channel's counters and sticky health (the reset acts before this
   step's sample, so the sticky word is this step's word). */
UT_TEST(reset_counters_clears_the_channels)
{
    fsw_in_t in;
    UT_UEQ(boot(&PD_TBL_DEFAULT, 1u), FSW_OK);
    in = frame(1, 0, 0, 0);
    run(&in);
    in = frame(2, 0, 0, 0);
    in.status[0] = FSW_ST_STALE;
    in.counts[2] = 33554433;                  /* pitch > 0.5 rad */
    run(&in);
    UT_UEQ(ch(0)->miss_cnt, 1u);
    UT_UEQ(ch(2)->range_rej, 1u);
    UT_UEQ(ch(0)->health_sticky & PD_H_STALE, PD_H_STALE);
    in = frame(3, 0, 0, 0);
    in.tc = TC(PD_CMD_RESET_COUNTERS);
    run(&in);
    UT_UEQ(g_oa.tlm.n_tc, 1u);
    UT_UEQ(ch(0)->miss_cnt, 0u);
    UT_UEQ(ch(2)->range_rej, 0u);
    UT_UEQ(ch(0)->health_sticky, ch(0)->health);
    UT_UEQ(ch(2)->health_sticky, ch(2)->health);
    UT_UEQ(ch(2)->health_sticky & (PD_H_STALE | PD_H_REJECT), 0u);
}

/* Roll k2_max 151 s is inside every loader range but above the sampled-mode cap (spec 40 §3.4):
   the module check vetoes it with PD_WHY_CAP (bit 6: detail 7), nothing changes. Exactly 150 s is
   accepted and commits at the next boundary (no longer the boot table). */
UT_TEST(roll_k2_max_above_the_cap_is_vetoed)
{
    fsw_in_t in;
    uint32_t why = 0u;
    UT_UEQ(boot(&PD_TBL_DEFAULT, 1u), FSW_OK);
    in = frame(1, 640, 640, 640);
    run(&in);
    g_t = PD_TBL_DEFAULT;
    g_t.ch[1].k2_max_q22 = K_Q22(151);
    UT_UEQ(pd_table_check(&g_t, &g_chk, &why), PD_WHY_CAP);
    UT_UEQ(why, PD_WHY_CAP);
    UT_UEQ(upload(&g_t, 2u, &why), FSW_ERR_INVARIANT);
    UT_UEQ(why, RW(FSW_TBL_R_MODULE, 7u));
    in = frame(2, 640, 640, 640);
    run(&in);
    UT_UEQ(g_oa.tlm.n_tbl_rej, 1u);
    UT_UEQ(g_oa.tlm.tbl_revision, 1u);
    UT_UEQ(g_oa.tlm.m.hold.revision, 1u);
    UT_EQ(g_oa.act_cnt[1], -300);              /* -120 640 / 256 */
    UT_UEQ(g_oa.tlm.mod_health & PD_H_TABLE_DEFAULT, PD_H_TABLE_DEFAULT);
    g_t.ch[1].k2_max_q22 = K_Q22(150);
    UT_UEQ(pd_table_check(&g_t, &g_chk, &why), 0u);
    UT_UEQ(upload(&g_t, 3u, &why), FSW_OK);
    in = frame(3, 640, 640, 640);
    run(&in);
    UT_UEQ(g_oa.tlm.n_tbl_acc, 1u);
    UT_UEQ(g_oa.tlm.tbl_revision, 3u);
    UT_UEQ(g_oa.health & FSW_H_TBL_NEW, FSW_H_TBL_NEW);
    UT_UEQ(g_oa.tlm.mod_health & PD_H_TABLE_DEFAULT, 0u);
    UT_EQ(g_oa.act_cnt[1], -300);              /* restarted: no derivative */
}

/* n_div = 2: Ty = 0.5 s, 1/Ty = 2 -> uq22 2^23 = 8 388 608. The law runs on executive steps 1, 3,
   5 after the mode entry; the actuator holds in between. Pitch y_f = 6400 + 64 f.
   f1: -160 6464 / 256 = -4040. f2: held. f3: dy = y_3 - y_1 = 128 over one sample, G_D = 2 475 / 0.5
   = 1900: -4 (40 6592 + 1900 128) / 256 = -2 027 520 / 256 = -7920. f4: held. f5: -4 (40 6720 +
   1900 128) / 256 = -8000. */
UT_TEST(n_div_2_runs_the_law_every_second_step)
{
    fsw_in_t in;
    uint32_t why = 0u;
    g_t = PD_TBL_DEFAULT;
    g_t.c.n_div = 2u;
    g_t.c.inv_ty_q22 = 8388608u;
    UT_UEQ(pd_table_check(&g_t, &g_chk, &why), 0u);
    UT_UEQ(boot(&g_t, 1u), FSW_OK);
    in = frame(1, 0, 0, 6464);
    run(&in);
    UT_EQ(g_oa.act_cnt[2], -4040);
    in = frame(2, 0, 0, 6528);
    run(&in);
    UT_EQ(g_oa.act_cnt[2], -4040);
    in = frame(3, 0, 0, 6592);
    run(&in);
    UT_EQ(g_oa.act_cnt[2], act_of(40, 1900, 6592, 128));
    UT_EQ(g_oa.act_cnt[2], -7920);
    UT_EQ(ch(2)->dy_q30, 2048);               /* 16 128 */
    in = frame(4, 0, 0, 6656);
    run(&in);
    UT_EQ(g_oa.act_cnt[2], -7920);
    in = frame(5, 0, 0, 6720);
    run(&in);
    UT_EQ(g_oa.act_cnt[2], -8000);
    UT_UEQ(ch(2)->miss_cnt, 0u);
}

/* A frame whose seq did not advance is a missing sample on every channel (miss_cnt, STALE): the
   torque is held one sample, then coasts; a fresh frame restarts the derivative. Pitch:
   f1 y 6400: -4000. f2 y 6464: -4 (40 6464 + 3800 64) / 256 = -2 007 040 / 256 = -7840.
   f3, f4 repeat seq 2: -7840 held, then 0 (COAST). Then seq 3 (advanced by one: nothing lost) with
   y 6656: -160 6656 / 256 = -4160. */
UT_TEST(a_repeated_seq_counts_as_missing)
{
    fsw_in_t in;
    UT_UEQ(boot(&PD_TBL_DEFAULT, 1u), FSW_OK);
    in = frame(1, 0, 0, 6400);
    run(&in);
    UT_EQ(g_oa.act_cnt[2], -4000);
    in = frame(2, 0, 0, 6464);
    run(&in);
    UT_EQ(g_oa.act_cnt[2], -7840);
    in = frame(2, 0, 0, 6528);
    run(&in);
    UT_EQ(g_oa.act_cnt[2], -7840);
    UT_UEQ(ch(0)->miss_cnt, 1u);
    UT_UEQ(ch(1)->miss_cnt, 1u);
    UT_UEQ(ch(2)->miss_cnt, 1u);
    UT_UEQ(ch(2)->health & PD_H_STALE, PD_H_STALE);
    in = frame(2, 0, 0, 6592);
    run(&in);
    UT_EQ(g_oa.act_cnt[2], 0);
    UT_UEQ(ch(2)->health & PD_H_COAST, PD_H_COAST);
    in = frame(3, 0, 0, 6656);
    run(&in);
    UT_EQ(g_oa.act_cnt[2], -4160);
    UT_UEQ(ch(2)->miss_cnt, 2u);
    UT_UEQ(g_oa.mode, FSW_MODE_HOLD);
    UT_UEQ(g_oa.tlm.n_chan_rej, 0u);
}

/* The module health word is the OR of the three channels' words, plus TABLE_DEFAULT while the boot
   table flies: yaw encoder 2^23 + 1 (> beta_warn) -> BETA_WARN on yaw; pitch y 2^25 + 1 (> 0.5 rad)
   -> REJECT | STALE on pitch; FALLBACK_GAIN from all three. No fx status bit, so no FSW_H_MODULE. */
UT_TEST(health_word_is_the_or_of_the_channels)
{
    fsw_in_t in;
    uint32_t why = 0u;
    UT_UEQ(boot(&PD_TBL_DEFAULT, 1u), FSW_OK);
    in = frame(1, 640, 640, 33554433);
    in.counts[3] = 8388609;
    run(&in);
    UT_UEQ(g_oa.tlm.mod_health,
           PD_H_TABLE_DEFAULT | PD_H_FALLBACK_GAIN | PD_H_BETA_WARN | PD_H_REJECT | PD_H_STALE);
    UT_UEQ(g_oa.tlm.mod_health, ch(0)->health | ch(1)->health | ch(2)->health | PD_H_TABLE_DEFAULT);
    UT_UEQ(ch(0)->health, PD_H_FALLBACK_GAIN | PD_H_BETA_WARN);
    UT_UEQ(ch(2)->health, PD_H_FALLBACK_GAIN | PD_H_REJECT | PD_H_STALE);
    UT_UEQ(g_oa.health & (FSW_H_MODULE | FX_ST_MASK), 0u);
    /* the same table uploaded is no longer the boot table */
    UT_UEQ(upload(&PD_TBL_DEFAULT, 2u, &why), FSW_OK);
    in = frame(2, 640, 640, 640);
    run(&in);
    UT_UEQ(g_oa.tlm.n_tbl_acc, 1u);
    UT_UEQ(g_oa.tlm.mod_health, PD_H_FALLBACK_GAIN);
}

/* A frame lost on the link (seq 3 never arrives) is a missing sample (spec 40 §8): the plant held the
   last torque over it, and the next sample differences across the single gap (fsw/pd/README.md,
   decision 9); a longer gap (more than PD_GAP_DIFF_MAX = 3 samples) restarts the derivative. Pitch:
   seq 1 y 6400: -4000; seq 2 y 6464: -7840; seq 4 y 6592, dy 128 counts (2048 q30):
   -(160 6592 + 15 200 128) / 256 = -(1 054 720 + 1 945 600) / 256 = -11 720. */
UT_TEST(a_lost_frame_is_missing_and_differenced_across)
{
    fsw_in_t in;
    UT_UEQ(boot(&PD_TBL_DEFAULT, 1u), FSW_OK);
    in = frame(1, 0, 0, 6400);
    run(&in);
    in = frame(2, 0, 0, 6464);
    run(&in);
    UT_EQ(g_oa.act_cnt[2], -7840);
    in = frame(4, 0, 0, 6592);
    run(&in);
    UT_UEQ(ch(2)->miss_cnt, 1u);
    UT_EQ(ch(2)->dy_q30, 2048);
    UT_EQ(g_oa.act_cnt[2], -11720);
    /* four lost frames: the derivative restarts */
    in = frame(9, 0, 0, 6912);
    run(&in);
    UT_UEQ(ch(2)->miss_cnt, 5u);
    UT_EQ(ch(2)->dy_q30, 0);
    UT_EQ(g_oa.act_cnt[2], -4320);            /* -160 6912 / 256 */
}

/* With n_div = 2 the samples are the frames 1, 3, 5, ... after the mode entry (by seq). Frame 3 lost:
   that sample is missing (the torque of frame 1 held over it), frame 4 is not a sample time (holds), and
   the sample of frame 5 differences across the one lost sample. Pitch y_f = 6400 + 64 f: f1 -4040;
   f4 holds -4040; f5 (Ty = 0.5 s: G_D = 1900, 7600 q28 per count): dy = 6720 - 6464 = 256 counts,
   -(160 6720 + 7600 256) / 256 = -(1 075 200 + 1 945 600) / 256 = -11 800. */
UT_TEST(n_div_2_a_lost_sample_frame_keeps_the_sample_phase)
{
    fsw_in_t in;
    g_t = PD_TBL_DEFAULT;
    g_t.c.n_div = 2u;
    g_t.c.inv_ty_q22 = 8388608u;
    UT_UEQ(boot(&g_t, 1u), FSW_OK);
    in = frame(1, 0, 0, 6464);
    run(&in);
    in = frame(2, 0, 0, 6528);
    run(&in);
    UT_EQ(g_oa.act_cnt[2], -4040);
    in = frame(4, 0, 0, 6656);
    run(&in);
    UT_EQ(g_oa.act_cnt[2], -4040);
    in = frame(5, 0, 0, 6720);
    run(&in);
    UT_EQ(g_oa.act_cnt[2], -11800);
    UT_UEQ(ch(2)->miss_cnt, 1u);
}

/* pd_params_check refuses GROUND for a table whose schedule was made for another law (the literal
   table flies LITERAL with a FAST schedule; PD_WHY_MODE). Neither SET_F (which selects GROUND) nor
   SET_SOURCE GROUND may bring that schedule in by telecommand: pitch keeps k2_nom = 475 s (the FAST
   node at 0.03 Hz would be 385 s) and the source stays FIXED. */
UT_TEST(ground_is_refused_for_a_schedule_of_another_law)
{
    fsw_in_t in;
    g_t = PD_TBL_LITERAL;
    g_t.c.src = (uint8_t)PD_SRC_GROUND;
    UT_UEQ(pd_table_check(&g_t, &g_chk, NULL), PD_WHY_MODE);
    UT_UEQ(boot(&PD_TBL_LITERAL, 1u), FSW_OK);
    in = frame(1, 0, 0, 0);
    in.tc = TC(PD_CMD_SET_F);
    in.tc_arg[0] = 30000;
    run(&in);
    UT_CHECK_UEQ(ch(2)->k2_q22, K_Q22(475));
    UT_CHECK_UEQ(ch(2)->health & PD_H_SRC, PD_SRC_FIXED << PD_H_SRC_SH);
    in = frame(2, 0, 0, 0);
    in.tc = TC(PD_CMD_SET_SOURCE);
    in.tc_arg[0] = (int32_t)PD_SRC_GROUND;
    run(&in);
    UT_UEQ(ch(2)->k2_q22, K_Q22(475));
    UT_UEQ(ch(2)->health & PD_H_SRC, PD_SRC_FIXED << PD_H_SRC_SH);
}

/* Layout 3 (pd_table.c): 56 common bytes, then per channel 1004 (yaw at 56, roll at 1060, pitch at
   2064): gains and nodes 100, the estimator block 904 from +100. Yaw's block has n_sec = 2 and n_reg
   = 2, roll's 1 and 0, pitch's 1 and 2 (tools/pd/fest); in the pitch block inv_m at +104, ad_m[0][1]
   at +132, dad_sh[1][0] at +368, aa_a_q29[1] at +428, cinv_q30[12][10] at +432 + 4 (12 11 + 10) =
   +1000, the payload's last word (2064 + 1000 = 3064). Decoding and encoding again gives the image
   back byte for byte. */
UT_TEST(the_estimator_blocks_are_on_the_wire_at_their_offsets)
{
    const pd_fest_params_t *f = &PD_TBL_DEFAULT.ch[2].fest;
    uint32_t n = pd_table_encode(&PD_TBL_DEFAULT, 4u, g_img, (uint32_t)sizeof(g_img));
    uint32_t i;
    UT_UEQ(n, 3084u);
    UT_UEQ(PD_TBL_PAYLOAD, 3068u);
    UT_UEQ(g_img[FSW_TABLE_HDR_BYTES + 156u], 2u);     /* yaw n_sec, n_reg, reserved */
    UT_UEQ(g_img[FSW_TABLE_HDR_BYTES + 157u], 2u);
    UT_UEQ(g_img[FSW_TABLE_HDR_BYTES + 158u], 0u);
    UT_UEQ(g_img[FSW_TABLE_HDR_BYTES + 159u], 0u);
    UT_UEQ(pl_u32(1060u), PD_TBL_DEFAULT.ch[1].k0_q22);  /* roll's record */
    UT_UEQ(g_img[FSW_TABLE_HDR_BYTES + 1160u], 1u);
    UT_UEQ(g_img[FSW_TABLE_HDR_BYTES + 1161u], 0u);
    UT_UEQ(pl_u32(2064u), PD_TBL_DEFAULT.ch[2].k0_q22);  /* pitch's record */
    UT_UEQ(g_img[FSW_TABLE_HDR_BYTES + 2164u], 1u);
    UT_UEQ(g_img[FSW_TABLE_HDR_BYTES + 2165u], 2u);
    UT_UEQ(pl_u32(2168u), f->inv_m_q30);
    UT_UEQ(pl_u32(2196u), (uint32_t)f->ad_m[0][1]);
    UT_UEQ(g_img[FSW_TABLE_HDR_BYTES + 2432u], f->dad_sh[1][0]);
    UT_UEQ(pl_u32(2492u), (uint32_t)f->aa_a_q29[1]);
    UT_UEQ(pl_u32(3064u), f->cinv_q30[12][10]);
    UT_UEQ(pd_table_decode(&g_img[FSW_TABLE_HDR_BYTES], PD_TBL_PAYLOAD, 4u, &g_t), FSW_OK);
    UT_UEQ(g_t.ch[0].fest.n_sec, 2u);
    UT_EQ(g_t.ch[2].fest.ad_m[0][1], f->ad_m[0][1]);
    UT_UEQ(g_t.ch[2].fest.cinv_q30[12][10], f->cinv_q30[12][10]);
    UT_UEQ(pd_table_encode(&g_t, 4u, g_img2, (uint32_t)sizeof(g_img2)), n);
    for (i = 0u; i < n; i++) {
        if (g_img2[i] != g_img[i]) {
            UT_UEQ(i, n);   /* names the first byte that differs */
            break;
        }
    }
}

/* A reserved byte of an estimator block that is not 0 makes the payload undecodable (FSW_ERR_DECODE),
   even with a valid CRC: the module check vetoes the upload as undecodable (detail 0xFF) and the
   boot table stays. Pitch reserved0 at 2166, then yaw reserved1 at 159. */
UT_TEST(an_estimator_reserved_byte_not_zero_is_refused)
{
    fsw_in_t in;
    uint32_t why = 0u;
    uint32_t n;
    UT_UEQ(boot(&PD_TBL_DEFAULT, 1u), FSW_OK);
    in = frame(1, 0, 0, 0);
    run(&in);
    n = pd_table_encode(&PD_TBL_DEFAULT, 2u, g_img, (uint32_t)sizeof(g_img));
    UT_UEQ(n, FSW_TABLE_HDR_BYTES + PD_TBL_PAYLOAD);
    g_img[FSW_TABLE_HDR_BYTES + 2166u] = 1u;
    fsw_table_write_header(g_img, (uint16_t)PD_TBL_ID, (uint16_t)PD_TBL_LAYOUT, PD_TBL_PAYLOAD, 2u);
    UT_UEQ(pd_table_decode(&g_img[FSW_TABLE_HDR_BYTES], PD_TBL_PAYLOAD, 2u, &g_t), FSW_ERR_DECODE);
    UT_UEQ(upload_img(n, 2u, &why), FSW_ERR_INVARIANT);
    UT_UEQ(why, RW(FSW_TBL_R_MODULE, FSW_VETO_UNDECODED));
    in = frame(2, 0, 0, 0);
    run(&in);
    UT_UEQ(g_oa.tlm.n_tbl_rej, 1u);
    UT_UEQ(g_oa.tlm.tbl_revision, 1u);
    g_img[FSW_TABLE_HDR_BYTES + 2166u] = 0u;
    g_img[FSW_TABLE_HDR_BYTES + 159u] = 0x80u;
    fsw_table_write_header(g_img, (uint16_t)PD_TBL_ID, (uint16_t)PD_TBL_LAYOUT, PD_TBL_PAYLOAD, 3u);
    UT_UEQ(pd_table_decode(&g_img[FSW_TABLE_HDR_BYTES], PD_TBL_PAYLOAD, 3u, &g_t), FSW_ERR_DECODE);
    g_img[FSW_TABLE_HDR_BYTES + 159u] = 0u;
    UT_UEQ(pd_table_decode(&g_img[FSW_TABLE_HDR_BYTES], PD_TBL_PAYLOAD, 3u, &g_t), FSW_OK);
}

/* The loader's limits on the blocks (PD_LIMS): n_sec in [1, 2], n_reg in [0, 2]; descriptor indices
   20 common fields, then per channel 6 gains, n_sec, n_reg: yaw n_sec 26, roll n_sec 34, pitch n_reg
   43. Each is refused by the loader (RANGE_LO / RANGE_HI naming the field), before the module check. */
UT_TEST(estimator_n_sec_and_n_reg_are_range_checked_by_the_loader)
{
    fsw_in_t in;
    uint32_t why = 0u;
    UT_UEQ(boot(&PD_TBL_DEFAULT, 1u), FSW_OK);
    in = frame(1, 0, 0, 0);
    run(&in);
    g_t = PD_TBL_DEFAULT;
    g_t.ch[1].fest.n_sec = 0u;
    UT_UEQ(upload(&g_t, 2u, &why), FSW_ERR_RANGE);
    UT_UEQ(why, RW(FSW_TBL_R_RANGE_LO, 34u));
    g_t = PD_TBL_DEFAULT;
    g_t.ch[0].fest.n_sec = 3u;
    UT_UEQ(upload(&g_t, 3u, &why), FSW_ERR_RANGE);
    UT_UEQ(why, RW(FSW_TBL_R_RANGE_HI, 26u));
    g_t = PD_TBL_DEFAULT;
    g_t.ch[2].fest.n_reg = 3u;
    UT_UEQ(upload(&g_t, 4u, &why), FSW_ERR_RANGE);
    UT_UEQ(why, RW(FSW_TBL_R_RANGE_HI, 43u));
    in = frame(2, 0, 0, 0);
    run(&in);
    UT_UEQ(g_oa.tlm.n_tbl_rej, 3u);
    UT_UEQ(g_oa.tlm.tbl_revision, 1u);
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(boots_into_hold_and_commands_each_channel),
        UT_CASE(hold_is_entered_from_standby_without_a_kick),
        UT_CASE(each_channel_uses_only_its_own_sensor_and_encoder),
        UT_CASE(ch_mask_clearing_a_channel_commands_zero),
        UT_CASE(set_f_and_set_source_select_the_gain_source),
        UT_CASE(set_k2_selects_fixed_gains_clamped_to_k2_max),
        UT_CASE(reset_counters_clears_the_channels),
        UT_CASE(roll_k2_max_above_the_cap_is_vetoed),
        UT_CASE(n_div_2_runs_the_law_every_second_step),
        UT_CASE(a_repeated_seq_counts_as_missing),
        UT_CASE(health_word_is_the_or_of_the_channels),
        UT_CASE(a_lost_frame_is_missing_and_differenced_across),
        UT_CASE(n_div_2_a_lost_sample_frame_keeps_the_sample_phase),
        UT_CASE(ground_is_refused_for_a_schedule_of_another_law),
        UT_CASE(the_estimator_blocks_are_on_the_wire_at_their_offsets),
        UT_CASE(an_estimator_reserved_byte_not_zero_is_refused),
        UT_CASE(estimator_n_sec_and_n_reg_are_range_checked_by_the_loader),
    };
    return UT_RUN("pd_mission", cases);
}
