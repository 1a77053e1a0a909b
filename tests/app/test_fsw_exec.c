/*
 * Executive (spec 00 §3.3): boot, modes and commands, input acceptance (stale/range/SAT),
 * SAFE rules, table upload (accept, corrupt, module veto) with nothing lost, scrub, telemetry
 * encoding, determinism and instance independence. RENDEZVOUS: the impulse table's boot path,
 * uploads committed at a step boundary only while the scheduler is idle or terminal (deferred
 * while it plans or fires, the firing bit-identical to a twin without the upload), corrupt and
 * vetoed uploads refused with nothing lost, scrub failure → SAFE. Host and target.
 */
#include "fsw_exec.h"
#include "obs_tables.h"
#include "imp_tables.h"
#include "imp_tbl_util.h"
#include "ut.h"

#define CNT_1DEG_S 18301   /* 1 deg/s in counts of 2^-20 rad/s */

/* Large objects live in static storage: the target runner has a small stack. Test-only state. */
static fsw_t g_a;
static fsw_t g_b;
static fsw_out_t g_oa;
static fsw_out_t g_ob;
static uint8_t g_img[FSW_TABLE_CAP_BYTES];

static fsw_cfg_t cfg50(void)
{
    fsw_cfg_t c;
    c.period_us = 20000u;
    c.stale_max = 50u;
    c.boot_mode = FSW_MODE_DETUMBLE;
    c.mission = FSW_MISSION_DETUMBLE;
    return c;
}

static fsw_in_t frame(int64_t seq, int32_t wy, int32_t wz)
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
    in.counts[0] = wy;
    in.counts[1] = wz;
    in.mode_cmd = FSW_CMD_NONE;
    in.host_missed = 0u;
    in.host_rejected = 0u;
    in.tc = FSW_TC_NONE;
    for (i = 0u; i < 8u; i++) {
        in.tc_arg[i] = 0;
    }
    return in;
}

/* Uploads img[0..n) in chunks of `chunk` bytes; returns the last rc. */
static fsw_rc_t upload(fsw_t *f, const uint8_t *img, uint32_t n, uint32_t revision, uint32_t chunk,
                       uint32_t *why)
{
    fsw_rc_t rc = FSW_OK;
    uint32_t off;
    for (off = 0u; off < n; off += chunk) {
        fsw_table_chunk_t c;
        c.table_id = (uint16_t)FSW_TBL_ID_OBS;
        c.revision = revision;
        c.total_len = n;
        c.offset = off;
        c.n = ((n - off) < chunk) ? (n - off) : chunk;
        c.data = &img[off];
        rc = fsw_table_upload(f, &c, why);
    }
    return rc;
}

UT_TEST(boot_tables_encode_load_and_enter_the_boot_mode)
{
    const obs_params_t *t[4] = {&OBS_TBL_50HZ_PHYS, &OBS_TBL_50HZ_PAPER, &OBS_TBL_5HZ_PAPER,
                                &OBS_TBL_PAPER_PRINTED};
    uint32_t i;
    for (i = 0u; i < 4u; i++) {
        fsw_cfg_t c = cfg50();
        fsw_in_t in = frame(1, 0, 0);
        c.period_us = t[i]->period_us;
        UT_CHECK_UEQ(fsw_obs_table_encode(t[i], 7u, g_img, sizeof(g_img)),
                     FSW_TABLE_HDR_BYTES + FSW_TBL_OBS_PAYLOAD);
        UT_CHECK_UEQ(fsw_init(&g_a, &c, t[i], 7u), FSW_OK);
        UT_CHECK_UEQ(g_a.tlm.n_tbl_rej, 0u);
        /* the decoded table is the C initialiser, field for field */
        UT_CHECK_UEQ(g_a.obs_p.period_us, t[i]->period_us);
        UT_CHECK_EQ(g_a.obs_p.phi0[7], t[i]->phi0[7]);
        UT_CHECK_EQ(g_a.obs_p.w[13], t[i]->w[13]);
        UT_CHECK_EQ(g_a.obs_p.ls[6], t[i]->ls[6]);
        UT_CHECK_EQ(g_a.obs_p.sigma, t[i]->sigma);
        UT_CHECK_UEQ(g_a.obs_p.revision, 7u);
        fsw_step(&g_a, &in, &g_oa);
        UT_CHECK_UEQ(g_oa.mode, FSW_MODE_DETUMBLE);
        UT_CHECK_UEQ(g_oa.tlm.tbl_revision, 7u);
    }
}

UT_TEST(bad_config_and_bad_boot_table_are_refused)
{
    fsw_cfg_t c = cfg50();
    obs_params_t p = OBS_TBL_50HZ_PHYS;
    fsw_in_t in = frame(1, 0, 0);
    c.stale_max = 0u;
    UT_UEQ(fsw_init(&g_a, &c, &OBS_TBL_50HZ_PHYS, 1u), FSW_ERR_ARG);
    c = cfg50();
    c.boot_mode = FSW_MODE_SAFE;
    UT_UEQ(fsw_init(&g_a, &c, &OBS_TBL_50HZ_PHYS, 1u), FSW_ERR_ARG);
    /* table period disagrees with the executive's */
    c = cfg50();
    c.period_us = 200000u;
    UT_TRUE(fsw_init(&g_a, &c, &OBS_TBL_50HZ_PHYS, 1u) != FSW_OK);
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_SAFE);
    UT_EQ(g_oa.act_cnt[0], 0);
    /* a range failure in the loader: kappa band inverted */
    c = cfg50();
    p.kappa_lo_q28 = p.kappa_hi_q28;
    UT_TRUE(fsw_init(&g_a, &c, &p, 1u) != FSW_OK);
    UT_UEQ(g_a.tlm.tbl_reason & 0xFFu, FSW_TBL_R_INVARIANT);
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_SAFE);
    UT_TRUE((g_oa.health & FSW_H_NO_TABLE) != 0u);
}

UT_TEST(mode_commands_follow_the_transition_rules)
{
    fsw_cfg_t c = cfg50();
    fsw_in_t in;
    int64_t k = 1;
    UT_UEQ(fsw_init(&g_a, &c, &OBS_TBL_50HZ_PHYS, 1u), FSW_OK);
    in = frame(k++, CNT_1DEG_S, CNT_1DEG_S);
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_DETUMBLE);
    in = frame(k++, CNT_1DEG_S, CNT_1DEG_S);
    fsw_step(&g_a, &in, &g_oa);
    UT_TRUE(g_oa.act_cnt[0] != 0);                 /* detumbling: a real command */
    in = frame(k++, CNT_1DEG_S, CNT_1DEG_S);
    in.mode_cmd = FSW_MODE_STANDBY;
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_STANDBY);
    UT_EQ(g_oa.act_cnt[0], 0);                     /* safe value outside DETUMBLE */
    UT_EQ(g_oa.act_cnt[1], 0);
    in = frame(k++, CNT_1DEG_S, CNT_1DEG_S);
    in.mode_cmd = FSW_MODE_BOOT;                   /* not commandable */
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_STANDBY);
    UT_TRUE((g_oa.health & FSW_H_MODE_REJ) != 0u);
    UT_UEQ(g_oa.tlm.n_mode_rej, 1u);
    in = frame(k++, CNT_1DEG_S, CNT_1DEG_S);
    in.mode_cmd = 99u;                             /* unknown */
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.tlm.n_mode_rej, 2u);
    in = frame(k++, CNT_1DEG_S, CNT_1DEG_S);
    in.mode_cmd = FSW_MODE_SAFE;
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_SAFE);
    UT_UEQ(g_oa.tlm.n_safe, 1u);
    in = frame(k++, CNT_1DEG_S, CNT_1DEG_S);
    in.mode_cmd = FSW_MODE_DETUMBLE;               /* SAFE leaves only to STANDBY */
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_SAFE);
    UT_UEQ(g_oa.tlm.n_mode_rej, 3u);
    in = frame(k++, CNT_1DEG_S, CNT_1DEG_S);
    in.mode_cmd = FSW_MODE_STANDBY;
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_STANDBY);
    in = frame(k++, CNT_1DEG_S, CNT_1DEG_S);
    in.mode_cmd = FSW_MODE_DETUMBLE;
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_DETUMBLE);
    in = frame(k++, CNT_1DEG_S, CNT_1DEG_S);
    fsw_step(&g_a, &in, &g_oa);
    UT_TRUE(g_oa.act_cnt[0] != 0);                 /* commanding again after re-entry */
}

UT_TEST(invalid_channels_hold_the_last_good_value_and_are_counted)
{
    fsw_cfg_t c = cfg50();
    fsw_in_t in;
    int64_t k;
    uint32_t skip0;
    UT_UEQ(fsw_init(&g_a, &c, &OBS_TBL_50HZ_PHYS, 1u), FSW_OK);
    for (k = 1; k <= 5; k++) {
        in = frame(k, CNT_1DEG_S, -CNT_1DEG_S);
        fsw_step(&g_a, &in, &g_oa);
    }
    skip0 = g_oa.tlm.obs.n_skip;
    /* out of range on y: count >= gyro_max_cnt */
    in = frame(6, OBS_TBL_50HZ_PHYS.gyro_max_cnt, -CNT_1DEG_S);
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.tlm.n_chan_rej, 1u);
    UT_UEQ(g_oa.tlm.n_stale_steps, 1u);
    UT_TRUE((g_oa.health & FSW_H_STALE) != 0u);
    UT_EQ(g_a.last_good[0], CNT_1DEG_S);           /* held, never clamped */
    UT_UEQ(g_oa.tlm.obs.n_skip, skip0 + 1u);       /* the module skipped that axis */
    /* plant STALE bit on z */
    in = frame(7, CNT_1DEG_S, -CNT_1DEG_S);
    in.status[1] = FSW_ST_STALE;
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.tlm.n_chan_rej, 2u);
    UT_UEQ(g_oa.tlm.obs.n_skip, skip0 + 2u);
    /* short frame: both channels invalid */
    in = frame(8, CNT_1DEG_S, -CNT_1DEG_S);
    in.n_counts = 1u;
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.tlm.n_in_bad, 1u);
    UT_UEQ(g_oa.tlm.n_chan_rej, 3u);
    /* recovery: a clean frame clears the step flag */
    in = frame(9, CNT_1DEG_S, -CNT_1DEG_S);
    fsw_step(&g_a, &in, &g_oa);
    UT_TRUE((g_oa.health & FSW_H_STALE) == 0u);
    UT_UEQ(g_oa.mode, FSW_MODE_DETUMBLE);
    UT_TRUE((g_oa.tlm.health_sticky & FSW_H_STALE) != 0u);
}

UT_TEST(persistent_stale_and_sat_go_to_safe_with_zero_command)
{
    fsw_cfg_t c = cfg50();
    fsw_in_t in;
    int64_t k;
    UT_UEQ(fsw_init(&g_a, &c, &OBS_TBL_50HZ_PHYS, 1u), FSW_OK);
    for (k = 1; k < 50; k++) {
        in = frame(k, CNT_1DEG_S, CNT_1DEG_S);
        in.status[0] = FSW_ST_STALE;
        fsw_step(&g_a, &in, &g_oa);
        UT_CHECK_UEQ(g_oa.mode, FSW_MODE_DETUMBLE);   /* 49 stale steps: not yet */
    }
    in = frame(50, CNT_1DEG_S, CNT_1DEG_S);
    in.status[0] = FSW_ST_STALE;
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_SAFE);
    UT_TRUE((g_oa.health & FSW_H_STALE_PERSIST) != 0u);
    UT_EQ(g_oa.act_cnt[0], 0);
    UT_EQ(g_oa.act_cnt[1], 0);
    /* stays SAFE once the input is good again (left only by command) */
    in = frame(51, CNT_1DEG_S, CNT_1DEG_S);
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_SAFE);

    UT_UEQ(fsw_init(&g_a, &c, &OBS_TBL_50HZ_PHYS, 1u), FSW_OK);
    for (k = 1; k <= 50; k++) {
        in = frame(k, CNT_1DEG_S, CNT_1DEG_S);
        in.status[1] = FSW_ST_SAT;
        fsw_step(&g_a, &in, &g_oa);
    }
    UT_UEQ(g_oa.mode, FSW_MODE_SAFE);
    UT_TRUE((g_oa.health & FSW_H_SAT_PERSIST) != 0u);
}

/* fx status bits are never silent, and they are not a SAFE trigger (fsw/app/README.md
   "Executive": spec 10 S0-9 at 1.0 deg/s needs the loop to keep commanding while the estimate,
   out of its design range, saturates from 11.9 s until the plant diverges at 26.8 s). A gyro
   stuck at 1 deg/s on the 5 Hz table (found by fuzz_fsw_step) saturates the regressor column of
   F from the second step on: every such step carries the fx bits and FSW_H_MODULE, the
   commands stay inside the table's limit, and the executive stays in DETUMBLE. */
UT_TEST(fx_status_is_reported_and_commands_stay_limited)
{
    fsw_cfg_t c = cfg50();
    fsw_in_t in;
    int64_t k;
    uint32_t n_fx = 0u;
    int32_t lim = (OBS_TBL_5HZ_PAPER.bdot_max_q29 >> OBS_TBL_5HZ_PAPER.act_cnt_shift) + 1;
    c.period_us = 200000u;
    c.stale_max = 5u;
    UT_UEQ(fsw_init(&g_a, &c, &OBS_TBL_5HZ_PAPER, 1u), FSW_OK);
    for (k = 1; k <= 100; k++) {
        in = frame(k, CNT_1DEG_S, CNT_1DEG_S);
        fsw_step(&g_a, &in, &g_oa);
        UT_CHECK_UEQ(g_oa.mode, FSW_MODE_DETUMBLE);
        UT_CHECK((g_oa.act_cnt[0] <= lim) && (g_oa.act_cnt[0] >= -lim));
        UT_CHECK((g_oa.act_cnt[1] <= lim) && (g_oa.act_cnt[1] >= -lim));
        if ((g_oa.health & 0xFFu) != 0u) {
            UT_CHECK((g_oa.health & FSW_H_MODULE) != 0u);
            UT_CHECK((g_oa.tlm.health_sticky & 0xFFu) != 0u);
            n_fx++;
        } else {
            UT_CHECK(k == 1);   /* the initialising step only */
        }
    }
    UT_UEQ(n_fx, 99u);
    UT_UEQ(g_oa.tlm.n_safe, 0u);
}

/* Runs a and b on the same inputs; b gets `img` uploaded between steps 20 and 21. */
static void run_pair_with_upload(const uint8_t *img, uint32_t n, uint32_t rev, fsw_rc_t *rc,
                                 uint32_t *why)
{
    fsw_cfg_t c = cfg50();
    int64_t k;
    (void)fsw_init(&g_a, &c, &OBS_TBL_50HZ_PHYS, 1u);
    (void)fsw_init(&g_b, &c, &OBS_TBL_50HZ_PHYS, 1u);
    for (k = 1; k <= 40; k++) {
        fsw_in_t in = frame(k, CNT_1DEG_S + (int32_t)(k * 37), -CNT_1DEG_S);
        if (k == 21) {
            *rc = upload(&g_b, img, n, rev, 100u, why);
        }
        fsw_step(&g_a, &in, &g_oa);
        fsw_step(&g_b, &in, &g_ob);
    }
}

UT_TEST(table_upload_accepted_at_the_step_boundary)
{
    obs_params_t p = OBS_TBL_50HZ_PHYS;
    uint32_t n;
    uint32_t why = 0u;
    fsw_rc_t rc = FSW_ERR_ARG;
    p.bdot_max_q29 = p.bdot_max_q29 / 2;     /* a real change: a lower command limit */
    n = fsw_obs_table_encode(&p, 2u, g_img, sizeof(g_img));
    run_pair_with_upload(g_img, n, 2u, &rc, &why);
    UT_UEQ(rc, FSW_OK);
    UT_UEQ(why, 0u);
    UT_UEQ(g_ob.tlm.tbl_revision, 2u);
    UT_UEQ(g_ob.tlm.n_tbl_acc, 1u);
    UT_UEQ(g_ob.tlm.n_tbl_rej, 0u);
    UT_UEQ(g_ob.tlm.obs.revision, 2u);
    UT_EQ(g_b.obs_p.bdot_max_q29, p.bdot_max_q29);
    UT_TRUE((g_ob.tlm.health_sticky & FSW_H_TBL_NEW) != 0u);
    UT_UEQ(g_oa.tlm.tbl_revision, 1u);
}

UT_TEST(corrupt_or_vetoed_tables_are_refused_and_nothing_is_lost)
{
    obs_params_t p = OBS_TBL_50HZ_PHYS;
    uint32_t n;
    uint32_t why = 0u;
    fsw_rc_t rc = FSW_OK;
    /* 1. CRC: one payload bit flipped after encoding */
    n = fsw_obs_table_encode(&OBS_TBL_50HZ_PHYS, 3u, g_img, sizeof(g_img));
    g_img[FSW_TABLE_HDR_BYTES + 200u] ^= 0x10u;
    run_pair_with_upload(g_img, n, 3u, &rc, &why);
    UT_UEQ(rc, FSW_ERR_CRC);
    UT_UEQ(why & 0xFFu, FSW_TBL_R_CRC);
    UT_UEQ(g_ob.tlm.n_tbl_rej, 1u);
    UT_UEQ(g_ob.tlm.tbl_reason & 0xFFu, FSW_TBL_R_CRC);
    UT_UEQ(g_ob.tlm.tbl_revision, 1u);
    UT_TRUE((g_ob.tlm.health_sticky & FSW_H_TBL_REJ) != 0u);
    /* nothing lost: the refused upload changed no command and no estimate */
    UT_EQ(g_ob.act_cnt[0], g_oa.act_cnt[0]);
    UT_EQ(g_ob.act_cnt[1], g_oa.act_cnt[1]);
    UT_EQ(g_ob.tlm.obs.kappa_q28, g_oa.tlm.obs.kappa_q28);
    UT_EQ(g_ob.tlm.obs.x_q29[0], g_oa.tlm.obs.x_q29[0]);
    /* 2. module veto: valid CRC and ranges, but a period the executive does not run */
    p.period_us = 10000u;
    n = fsw_obs_table_encode(&p, 4u, g_img, sizeof(g_img));
    run_pair_with_upload(g_img, n, 4u, &rc, &why);
    UT_UEQ(why & 0xFFu, FSW_TBL_R_MODULE);
    UT_UEQ(g_ob.tlm.tbl_revision, 1u);
    UT_EQ(g_ob.act_cnt[0], g_oa.act_cnt[0]);
    /* 3. loader range: n_lost = 0 */
    p = OBS_TBL_50HZ_PHYS;
    p.n_lost = 0u;
    n = fsw_obs_table_encode(&p, 5u, g_img, sizeof(g_img));
    run_pair_with_upload(g_img, n, 5u, &rc, &why);
    UT_UEQ(why & 0xFFu, FSW_TBL_R_RANGE_LO);
    UT_UEQ((why >> FSW_TBL_DETAIL_SHIFT) & 0xFFu, 16u);   /* field index of n_lost */
    UT_UEQ(g_ob.tlm.n_tbl_rej, 1u);
    UT_EQ(g_ob.tlm.obs.kappa_q28, g_oa.tlm.obs.kappa_q28);
}

UT_TEST(scrub_failure_goes_to_safe)
{
    fsw_cfg_t c = cfg50();
    fsw_in_t in = frame(1, 0, 0);
    UT_UEQ(fsw_init(&g_a, &c, &OBS_TBL_50HZ_PHYS, 1u), FSW_OK);
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_DETUMBLE);
    g_a.obs_tbl.img[g_a.obs_tbl.active][FSW_TABLE_HDR_BYTES + 10u] ^= 1u;   /* memory upset */
    in = frame(2, 0, 0);
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_SAFE);
    UT_TRUE((g_oa.health & FSW_H_SCRUB) != 0u);
    UT_UEQ(g_oa.tlm.n_scrub_err, 1u);
}

UT_TEST(telemetry_encodes_to_its_fixed_size)
{
    uint8_t buf[FSW_TLM_BYTES];
    fsw_cfg_t c = cfg50();
    fsw_in_t in = frame(0x0102030405LL, 5, 6);
    UT_UEQ(fsw_init(&g_a, &c, &OBS_TBL_50HZ_PHYS, 1u), FSW_OK);
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(fsw_tlm_encode(&g_oa.tlm, buf, FSW_TLM_BYTES), FSW_TLM_BYTES);
    UT_UEQ(fsw_tlm_encode(&g_oa.tlm, buf, FSW_TLM_BYTES - 1u), 0u);
    /* seq is the second little-endian i64 */
    UT_UEQ(buf[8], 0x05u);
    UT_UEQ(buf[12], 0x01u);
    UT_UEQ(buf[16], 1u);                           /* step 1 */
}

UT_TEST(deterministic_and_instances_independent)
{
    fsw_cfg_t c = cfg50();
    uint8_t ba[FSW_TLM_BYTES];
    uint8_t bb[FSW_TLM_BYTES];
    int64_t k;
    uint32_t i;
    uint32_t diff = 0u;
    UT_UEQ(fsw_init(&g_a, &c, &OBS_TBL_50HZ_PHYS, 1u), FSW_OK);
    UT_UEQ(fsw_init(&g_b, &c, &OBS_TBL_50HZ_PHYS, 1u), FSW_OK);
    for (k = 1; k <= 200; k++) {
        fsw_in_t in = frame(k, CNT_1DEG_S - (int32_t)(k * 53), CNT_1DEG_S + (int32_t)(k * 11));
        fsw_in_t other = frame(k, -3 * CNT_1DEG_S, 2 * CNT_1DEG_S);
        fsw_step(&g_a, &in, &g_oa);
        fsw_step(&g_b, &other, &g_ob);   /* interleaved, different data */
    }
    (void)fsw_tlm_encode(&g_oa.tlm, ba, FSW_TLM_BYTES);
    UT_UEQ(fsw_init(&g_b, &c, &OBS_TBL_50HZ_PHYS, 1u), FSW_OK);
    for (k = 1; k <= 200; k++) {
        fsw_in_t in = frame(k, CNT_1DEG_S - (int32_t)(k * 53), CNT_1DEG_S + (int32_t)(k * 11));
        fsw_step(&g_b, &in, &g_ob);
    }
    (void)fsw_tlm_encode(&g_ob.tlm, bb, FSW_TLM_BYTES);
    for (i = 0u; i < FSW_TLM_BYTES; i++) {
        diff += (ba[i] != bb[i]) ? 1u : 0u;
    }
    UT_UEQ(diff, 0u);
}

/* ------------------------------------------------------------------ RENDEZVOUS mission */

static fsw_cfg_t cfg_rdv(void)
{
    fsw_cfg_t c;
    c.period_us = 100000u;
    c.stale_max = 5u;
    c.boot_mode = FSW_MODE_RENDEZVOUS;
    c.mission = FSW_MISSION_RENDEZVOUS;
    return c;
}

/* A nav frame of the paper's example state (5 km, -1 m/s, 4 km, -1 m/s, 4 km, -1 m/s), sample
   taken at step k. */
static fsw_in_t nav_frame(int64_t k)
{
    fsw_in_t in = frame(k, 0, 0);
    uint32_t i;
    in.utime_us = k * 100000;
    in.n_counts = FSW_RDV_N_SENS;
    for (i = 0u; i < 3u; i++) {
        in.counts[i] = (i == 0u) ? 5000000 : 4000000;   /* mm */
        in.counts[3u + i] = -100000;                    /* 10 um/s */
    }
    in.counts[6] = (int32_t)k;
    return in;
}

UT_TEST(rendezvous_boot_channel_map_and_telemetry)
{
    uint8_t buf[FSW_TLM_RDV_BYTES];
    fsw_cfg_t c = cfg_rdv();
    fsw_in_t in = nav_frame(0);
    uint32_t i;
    UT_UEQ(fsw_init_rdv(&g_a, &c, &IMP_TBL_DEFAULT, 3u), FSW_OK);
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_RENDEZVOUS);
    UT_UEQ(g_oa.n_act, FSW_RDV_N_ACT);
    for (i = 0u; i < FSW_ACT_MAX; i++) {
        UT_CHECK_EQ(g_oa.act_cnt[i], 0);              /* IDLE: every thruster off */
    }
    UT_UEQ(g_oa.health & 0xFFu, 0u);
    UT_UEQ(g_oa.tlm.mission, FSW_MISSION_RENDEZVOUS);
    UT_UEQ(g_oa.tlm.imp.mode, IMP_MODE_IDLE);
    UT_UEQ(g_oa.tlm.tbl_revision, 3u);
    UT_UEQ(fsw_tlm_layout(&g_oa.tlm), FSW_TLM_RDV_LAYOUT_VERSION);
    UT_UEQ(fsw_tlm_encode(&g_oa.tlm, buf, FSW_TLM_RDV_BYTES), FSW_TLM_RDV_BYTES);
    UT_UEQ(fsw_tlm_encode(&g_oa.tlm, buf, FSW_TLM_RDV_BYTES - 1u), 0u);
    UT_UEQ(buf[16], 1u);                               /* step 1, after utime and seq */
    /* the wrong mission's init is refused */
    UT_UEQ(fsw_init(&g_b, &c, &OBS_TBL_50HZ_PHYS, 1u), FSW_ERR_ARG);
    {
        fsw_cfg_t d = cfg50();
        UT_UEQ(fsw_init_rdv(&g_b, &d, &IMP_TBL_DEFAULT, 1u), FSW_ERR_ARG);
    }
}

UT_TEST(rendezvous_bad_nav_is_counted_and_never_safe)
{
    fsw_cfg_t c = cfg_rdv();
    int64_t k;
    UT_UEQ(fsw_init_rdv(&g_a, &c, &IMP_TBL_DEFAULT, 1u), FSW_OK);
    for (k = 0; k < 40; k++) {
        fsw_in_t in = nav_frame(k);
        if ((k % 4) == 1) {
            in.status[2] = FSW_ST_STALE;               /* plant: no valid sample */
        } else if ((k % 4) == 2) {
            in.counts[3] = FSW_NAV_VEL_MAX_CNT + 1;    /* beyond the accepted range */
        } else if ((k % 4) == 3) {
            in.n_counts = 6u;                          /* frame too short */
        } else {
            /* valid */
        }
        fsw_step(&g_a, &in, &g_oa);
        UT_CHECK_UEQ(g_oa.mode, FSW_MODE_RENDEZVOUS);  /* far beyond stale_max = 5, still flying */
    }
    UT_UEQ(g_oa.tlm.n_chan_rej, 30u);
    UT_UEQ(g_oa.tlm.n_in_bad, 10u);
    UT_UEQ(g_oa.tlm.n_safe, 0u);
    UT_TRUE((g_oa.tlm.health_sticky & FSW_H_STALE) != 0u);
}

UT_TEST(rendezvous_telecommands_only_in_the_mission_mode)
{
    fsw_cfg_t c = cfg_rdv();
    fsw_in_t in = nav_frame(0);
    c.boot_mode = FSW_MODE_STANDBY;
    UT_UEQ(fsw_init_rdv(&g_a, &c, &IMP_TBL_DEFAULT, 1u), FSW_OK);
    fsw_step(&g_a, &in, &g_oa);
    in = nav_frame(1);
    in.tc = FSW_TC_IMP_START;                          /* START in STANDBY: refused */
    in.tc_arg[0] = 200;
    in.tc_arg[1] = 200 + 10550;
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.tlm.n_tc_rej, 1u);
    UT_TRUE((g_oa.health & FSW_H_TC_REJ) != 0u);
    UT_UEQ(g_oa.tlm.imp.mode, IMP_MODE_IDLE);
    in = nav_frame(2);
    in.mode_cmd = FSW_MODE_DETUMBLE;                   /* not this mission's mode */
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_STANDBY);
    UT_UEQ(g_oa.tlm.n_mode_rej, 1u);
    in = nav_frame(3);
    in.mode_cmd = FSW_MODE_RENDEZVOUS;
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_RENDEZVOUS);
    in = nav_frame(4);
    in.tc = FSW_TC_IMP_START;                          /* now taken by the scheduler */
    in.tc_arg[0] = 200;
    in.tc_arg[1] = 200 + 10550;
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.tlm.n_tc, 1u);
    UT_TRUE(g_oa.tlm.imp.mode != IMP_MODE_IDLE);       /* planning (or already armed) */
    UT_UEQ(g_oa.tlm.imp.cmd_rej, 0u);
}

/* ------------------------------------------------------------------ RENDEZVOUS: the impulse table */

static imp_params_t g_ip;
static fsw_tlm_t g_tla;
static fsw_tlm_t g_tlb;
static uint8_t g_ea[FSW_TLM_RDV_BYTES];
static uint8_t g_eb[FSW_TLM_RDV_BYTES];
static uint8_t g_isnap[FSW_TABLE_CAP_BYTES];

#define RW(code, detail) ((code) | ((uint32_t)(detail) << FSW_TBL_DETAIL_SHIFT))
#define TBL_BITS (FSW_H_TBL_REJ | FSW_H_TBL_NEW | FSW_H_TBL_PENDING)
#define RDV_T0   60
#define RDV_TF   (60 + 10550)

/* Uploads an impulse image in chunks of `chunk` bytes; returns the last rc. */
static fsw_rc_t upload_imp(fsw_t *f, const uint8_t *img, uint32_t n, uint32_t chunk, uint32_t *why)
{
    fsw_rc_t rc = FSW_OK;
    uint32_t off;
    for (off = 0u; off < n; off += chunk) {
        fsw_table_chunk_t c;
        c.table_id = (uint16_t)FSW_TBL_ID_IMP;
        c.revision = 77u;
        c.total_len = n;
        c.offset = off;
        c.n = ((n - off) < chunk) ? (n - off) : chunk;
        c.data = &img[off];
        rc = fsw_table_upload(f, &c, why);
    }
    return rc;
}

/* Encodes p with revision rev into g_img and uploads it into f. */
static fsw_rc_t upload_params(fsw_t *f, const imp_params_t *p, uint32_t rev, uint32_t *why)
{
    uint32_t n = fsw_imp_table_encode(p, rev, g_img, sizeof(g_img));
    UT_CHECK_UEQ(n, FSW_TABLE_HDR_BYTES + FSW_TBL_IMP_PAYLOAD);
    return upload_imp(f, g_img, n, 40u, why);
}

/* The nav frame of step k, with the START telecommand of the paper's example at k == 4. */
static fsw_in_t rdv_frame(int64_t k)
{
    fsw_in_t in = nav_frame(k);
    if (k == 4) {
        in.tc = FSW_TC_IMP_START;
        in.tc_arg[0] = RDV_T0;
        in.tc_arg[1] = RDV_TF;
    }
    return in;
}

/* One step of both instances on the same frame. */
static void step_pair(const fsw_in_t *in)
{
    fsw_step(&g_a, in, &g_oa);
    fsw_step(&g_b, in, &g_ob);
}

/* Bytes of the encoded telemetry of a and b that differ, once the table counters, reason,
   revision and table health bits of b are set to a's: "nothing else changed". */
static uint32_t tlm_diff_but_tables(void)
{
    uint32_t i;
    uint32_t d = 0u;
    g_tla = g_oa.tlm;
    g_tlb = g_ob.tlm;
    g_tlb.n_tbl_acc = g_tla.n_tbl_acc;
    g_tlb.n_tbl_rej = g_tla.n_tbl_rej;
    g_tlb.tbl_reason = g_tla.tbl_reason;
    g_tlb.tbl_revision = g_tla.tbl_revision;
    g_tlb.health = (g_tlb.health & ~TBL_BITS) | (g_tla.health & TBL_BITS);
    g_tlb.health_sticky = (g_tlb.health_sticky & ~TBL_BITS) | (g_tla.health_sticky & TBL_BITS);
    (void)fsw_tlm_encode(&g_tla, g_ea, FSW_TLM_RDV_BYTES);
    (void)fsw_tlm_encode(&g_tlb, g_eb, FSW_TLM_RDV_BYTES);
    for (i = 0u; i < FSW_TLM_RDV_BYTES; i++) {
        d += (g_ea[i] != g_eb[i]) ? 1u : 0u;
    }
    for (i = 0u; i < FSW_RDV_N_ACT; i++) {
        d += (g_oa.act_cnt[i] != g_ob.act_cnt[i]) ? 1u : 0u;
    }
    return d;
}

static void isnap_take(const fsw_t *f)
{
    uint32_t i;
    for (i = 0u; i < FSW_TABLE_CAP_BYTES; i++) {
        g_isnap[i] = f->imp_tbl.img[f->imp_tbl.active][i];
    }
}

static uint32_t isnap_diff(const fsw_t *f)
{
    uint32_t i;
    uint32_t d = 0u;
    for (i = 0u; i < FSW_TABLE_CAP_BYTES; i++) {
        d += (f->imp_tbl.img[f->imp_tbl.active][i] != g_isnap[i]) ? 1u : 0u;
    }
    return d;
}

/* a and b booted alike, run to step k_end inclusive (START at 4); returns the steps at which
   b fired a thruster. */
static uint32_t run_rdv_pair(int64_t k0, int64_t k_end)
{
    int64_t k;
    uint32_t fired = 0u;
    for (k = k0; k <= k_end; k++) {
        fsw_in_t in = rdv_frame(k);
        step_pair(&in);
        fired += (g_ob.act_cnt[FSW_RDV_ACT_MASK] != 0) ? 1u : 0u;
    }
    return fired;
}

static void boot_rdv_pair(void)
{
    fsw_cfg_t c = cfg_rdv();
    UT_CHECK_UEQ(fsw_init_rdv(&g_a, &c, &IMP_TBL_DEFAULT, 1u), FSW_OK);
    UT_CHECK_UEQ(fsw_init_rdv(&g_b, &c, &IMP_TBL_DEFAULT, 1u), FSW_OK);
}

UT_TEST(rendezvous_boot_table_goes_through_the_loader)
{
    fsw_cfg_t c = cfg_rdv();
    const imp_params_t *t[2] = {&IMP_TBL_DEFAULT, &IMP_TBL_SUB1MS};
    uint32_t i;
    for (i = 0u; i < 2u; i++) {
        fsw_in_t in = nav_frame(0);
        UT_CHECK_UEQ(fsw_init_rdv(&g_a, &c, t[i], 6u), FSW_OK);
        g_ip = *t[i];
        g_ip.revision = 6u;
        UT_CHECK_UEQ(imp_params_diff(&g_a.imp_p, &g_ip, 1), 0u);   /* decoded from the active image */
        UT_CHECK_UEQ(fsw_table_revision(&g_a.imp_tbl), 6u);
        UT_CHECK(fsw_mission_table(&g_a) == &g_a.imp_tbl);
        fsw_step(&g_a, &in, &g_oa);
        UT_CHECK_UEQ(g_oa.mode, FSW_MODE_RENDEZVOUS);
        UT_CHECK_UEQ(g_oa.tlm.tbl_revision, 6u);
        UT_CHECK_UEQ(g_oa.tlm.imp.revision, 6u);
        UT_CHECK_UEQ(g_oa.tlm.n_tbl_rej, 0u);
    }
    {
        fsw_cfg_t d = cfg50();
        UT_UEQ(fsw_init(&g_b, &d, &OBS_TBL_50HZ_PHYS, 1u), FSW_OK);
        UT_TRUE(fsw_mission_table(&g_b) == &g_b.obs_tbl);
        UT_TRUE(fsw_mission_table(NULL) == NULL);
    }
}

UT_TEST(rendezvous_upload_accepted_at_the_step_boundary)
{
    uint32_t why = 99u;
    int64_t k;
    boot_rdv_pair();
    for (k = 0; k < 10; k++) {                          /* no START: the scheduler is IDLE */
        fsw_in_t in = nav_frame(k);
        step_pair(&in);
    }
    g_ip = IMP_TBL_DEFAULT;
    g_ip.miss_flag_q28 = 2 * g_ip.miss_flag_q28;        /* a real change: 20 m miss flag */
    g_ip.alpha_q30[1] = 1100000000;                     /* and a thrust factor */
    UT_UEQ(upload_params(&g_b, &g_ip, 2u, &why), FSW_OK);
    UT_UEQ(why, FSW_TBL_R_NONE);
    UT_UEQ(g_b.imp_tbl.state, FSW_TBL_S_READY);
    UT_UEQ(g_b.imp_p.miss_flag_q28, IMP_TBL_DEFAULT.miss_flag_q28);   /* not before the boundary */
    UT_UEQ(g_ob.tlm.tbl_revision, 1u);
    {
        fsw_in_t in = nav_frame(10);
        step_pair(&in);
    }
    UT_UEQ(g_ob.tlm.tbl_revision, 2u);
    UT_UEQ(g_ob.tlm.n_tbl_acc, 1u);
    UT_UEQ(g_ob.tlm.n_tbl_rej, 0u);
    UT_TRUE((g_ob.health & FSW_H_TBL_NEW) != 0u);
    UT_TRUE((g_ob.health & FSW_H_TBL_PENDING) == 0u);
    UT_UEQ(g_ob.tlm.imp.revision, 2u);                  /* the scheduler runs with it */
    UT_UEQ(g_ob.tlm.imp.mode, IMP_MODE_IDLE);
    UT_UEQ(g_ob.mode, FSW_MODE_RENDEZVOUS);
    g_ip.revision = 2u;
    UT_UEQ(imp_params_diff(&g_b.imp_p, &g_ip, 1), 0u);
    UT_UEQ(g_oa.tlm.tbl_revision, 1u);                  /* the other instance is untouched */
    UT_UEQ(g_oa.tlm.n_tbl_acc, 0u);
    /* and a START after the commit plans with it */
    {
        fsw_in_t in = nav_frame(11);
        in.tc = FSW_TC_IMP_START;
        in.tc_arg[0] = 11 + 60;
        in.tc_arg[1] = 11 + 60 + 10550;
        step_pair(&in);
        UT_UEQ(g_ob.tlm.imp.cmd_rej, 0u);
        UT_TRUE(g_ob.tlm.imp.mode != IMP_MODE_IDLE);
    }
}

UT_TEST(rendezvous_upload_waits_while_the_scheduler_plans_or_fires)
{
    uint32_t why = 99u;
    uint32_t fired;
    uint32_t rej;
    int64_t k;
    boot_rdv_pair();
    (void)run_rdv_pair(0, 4);
    UT_UEQ(g_ob.tlm.imp.mode, IMP_MODE_PLANNING);      /* START taken at step 4 */
    /* a validated candidate while the plan job runs: it waits (through ARMED and FIRING) */
    g_ip = IMP_TBL_DEFAULT;
    g_ip.miss_flag_q28 = 3 * g_ip.miss_flag_q28;
    UT_UEQ(upload_params(&g_b, &g_ip, 2u, &why), FSW_OK);
    UT_UEQ(g_b.imp_tbl.state, FSW_TBL_S_READY);
    fired = 0u;
    for (k = 5; k <= 120; k++) {
        fsw_in_t in = rdv_frame(k);
        step_pair(&in);
        fired += (g_ob.act_cnt[FSW_RDV_ACT_MASK] != 0) ? 1u : 0u;
        UT_CHECK((g_ob.health & FSW_H_TBL_PENDING) != 0u);
        UT_CHECK_UEQ(g_ob.tlm.tbl_revision, 1u);
        UT_CHECK_UEQ(g_ob.tlm.n_tbl_acc, 0u);
        UT_CHECK_UEQ(tlm_diff_but_tables(), 0u);       /* the plan and the firing are untouched */
    }
    UT_UEQ(g_ob.tlm.imp.mode, IMP_MODE_FIRING);
    UT_LE(10, fired);                                   /* thrusters really fired meanwhile */
    UT_UEQ(imp_params_diff(&g_b.imp_p, &IMP_TBL_DEFAULT, 1), 0u);
    /* a further chunk is BUSY: a state complaint, not a refusal */
    rej = g_ob.tlm.n_tbl_rej;
    UT_UEQ(upload_params(&g_b, &g_ip, 3u, &why), FSW_ERR_STATE);
    UT_UEQ(why & 0xFFu, FSW_TBL_R_BUSY);
    UT_UEQ(g_b.tlm.n_tbl_rej, rej);
    UT_UEQ(g_b.imp_tbl.state, FSW_TBL_S_READY);
    /* ABORT: the scheduler is terminal after this step, the table is committed at the next */
    {
        fsw_in_t in = rdv_frame(121);
        in.tc = FSW_TC_IMP_ABORT;
        step_pair(&in);
        UT_UEQ(g_ob.tlm.imp.mode, IMP_MODE_ABORTED);
        UT_EQ(g_ob.act_cnt[FSW_RDV_ACT_MASK], 0);
        UT_UEQ(g_ob.tlm.tbl_revision, 1u);
        UT_UEQ(tlm_diff_but_tables(), 0u);
    }
    {
        fsw_in_t in = rdv_frame(122);
        step_pair(&in);
    }
    UT_TRUE((g_ob.health & FSW_H_TBL_NEW) != 0u);
    UT_TRUE((g_ob.health & FSW_H_TBL_PENDING) == 0u);
    UT_UEQ(g_ob.tlm.tbl_revision, 2u);
    UT_UEQ(g_ob.tlm.n_tbl_acc, 1u);
    UT_UEQ(g_ob.tlm.imp.revision, 2u);
    UT_UEQ(g_ob.tlm.imp.mode, IMP_MODE_IDLE);           /* re-initialised with the new table */
    UT_UEQ(g_oa.tlm.imp.mode, IMP_MODE_ABORTED);
    UT_EQ(g_b.imp_p.miss_flag_q28, g_ip.miss_flag_q28);
}

UT_TEST(rendezvous_upload_in_standby_commits_at_once)
{
    fsw_cfg_t c = cfg_rdv();
    uint32_t why = 99u;
    fsw_in_t in = nav_frame(0);
    c.boot_mode = FSW_MODE_STANDBY;
    UT_UEQ(fsw_init_rdv(&g_a, &c, &IMP_TBL_DEFAULT, 1u), FSW_OK);
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(upload_params(&g_a, &IMP_TBL_SUB1MS, 4u, &why), FSW_OK);
    in = nav_frame(1);
    in.mode_cmd = FSW_MODE_RENDEZVOUS;                  /* committed first, then the entry */
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_RENDEZVOUS);
    UT_UEQ(g_oa.tlm.tbl_revision, 4u);
    UT_UEQ(g_oa.tlm.imp.revision, 4u);
    UT_UEQ(g_a.imp_p.subtick_us, 1000u);
}

UT_TEST(rendezvous_corrupt_or_vetoed_tables_are_refused_and_nothing_is_lost)
{
    uint32_t why = 0u;
    uint32_t n;
    uint32_t act;
    uint32_t len;
    boot_rdv_pair();
    (void)run_rdv_pair(0, 64);
    UT_UEQ(g_ob.tlm.imp.mode, IMP_MODE_FIRING);
    isnap_take(&g_b);
    act = g_b.imp_tbl.active;
    len = g_b.imp_tbl.active_len;
    /* 1. CRC: one payload bit flipped after encoding */
    n = fsw_imp_table_encode(&IMP_TBL_DEFAULT, 3u, g_img, sizeof(g_img));
    g_img[FSW_TABLE_HDR_BYTES + 100u] ^= 0x04u;
    UT_UEQ(upload_imp(&g_b, g_img, n, 40u, &why), FSW_ERR_CRC);
    UT_UEQ(why, RW(FSW_TBL_R_CRC, 0u));
    /* 2. module veto: inside every range, but plan_lead below the worst plan (IMP_WHY_LEAD) */
    g_ip = IMP_TBL_DEFAULT;
    g_ip.plan_lead = 5u;
    {
        uint32_t mwhy = 0u;
        UT_TRUE(imp_params_check(&g_ip, &mwhy) != FSW_OK);
        UT_UEQ(mwhy, IMP_WHY_LEAD);
    }
    UT_UEQ(upload_params(&g_b, &g_ip, 4u, &why), FSW_ERR_INVARIANT);
    UT_UEQ(why, RW(FSW_TBL_R_MODULE, 8u));
    /* 3. module veto: scale constants inconsistent (k_tick_m no longer 1 / k_tau_m) */
    g_ip = IMP_TBL_DEFAULT;
    g_ip.k_tick_m = g_ip.k_tick_m / 2;
    UT_UEQ(upload_params(&g_b, &g_ip, 5u, &why), FSW_ERR_INVARIANT);
    UT_UEQ(why, RW(FSW_TBL_R_MODULE, 6u));
    /* 4. module veto: the 1 s table is valid, but not at this executive's period */
    UT_UEQ(upload_params(&g_b, &IMP_TBL_1S, 6u, &why), FSW_ERR_INVARIANT);
    UT_UEQ(why, RW(FSW_TBL_R_MODULE, 1u));
    /* 5. loader range: max_iter above IMP_ITER_CAP (field 7) */
    g_ip = IMP_TBL_DEFAULT;
    g_ip.max_iter = 17u;
    UT_UEQ(upload_params(&g_b, &g_ip, 7u, &why), FSW_ERR_RANGE);
    UT_UEQ(why, RW(FSW_TBL_R_RANGE_HI, 7u));
    /* the active image is bit-identical, nothing waits, the decoded table is the boot one */
    UT_UEQ(isnap_diff(&g_b), 0u);
    UT_UEQ(g_b.imp_tbl.active, act);
    UT_UEQ(g_b.imp_tbl.active_len, len);
    UT_UEQ(g_b.imp_tbl.state, FSW_TBL_S_IDLE);
    g_ip = IMP_TBL_DEFAULT;
    g_ip.revision = 1u;
    UT_UEQ(imp_params_diff(&g_b.imp_p, &g_ip, 1), 0u);
    /* and the mission flies on exactly as the twin that got no upload */
    {
        fsw_in_t in = rdv_frame(65);
        step_pair(&in);
    }
    UT_TRUE((g_ob.health & FSW_H_TBL_REJ) != 0u);
    UT_UEQ(g_ob.tlm.n_tbl_rej, 5u);
    UT_UEQ(g_ob.tlm.tbl_reason, RW(FSW_TBL_R_RANGE_HI, 7u));
    UT_UEQ(g_ob.tlm.tbl_revision, 1u);
    UT_UEQ(g_ob.tlm.n_tbl_acc, 0u);
    UT_UEQ(tlm_diff_but_tables(), 0u);
    {
        int64_t k;
        uint32_t fired = 0u;
        for (k = 66; k <= 100; k++) {
            fsw_in_t in = rdv_frame(k);
            step_pair(&in);
            fired += (g_ob.act_cnt[FSW_RDV_ACT_MASK] != 0) ? 1u : 0u;
            UT_CHECK_UEQ(tlm_diff_but_tables(), 0u);
        }
        UT_LE(10, fired);
    }
    UT_UEQ(g_ob.tlm.imp.mode, IMP_MODE_FIRING);
    UT_TRUE((g_ob.health & FSW_H_TBL_REJ) == 0u);
}

UT_TEST(rendezvous_refuses_a_chunk_for_another_table)
{
    uint32_t why = 0u;
    uint32_t n;
    fsw_cfg_t c = cfg_rdv();
    fsw_in_t in = nav_frame(0);
    UT_UEQ(fsw_init_rdv(&g_a, &c, &IMP_TBL_DEFAULT, 1u), FSW_OK);
    fsw_step(&g_a, &in, &g_oa);
    isnap_take(&g_a);
    n = fsw_obs_table_encode(&OBS_TBL_50HZ_PHYS, 2u, g_img, sizeof(g_img));
    UT_UEQ(upload(&g_a, g_img, n, 2u, 100u, &why), FSW_ERR_CHUNK);
    UT_UEQ(why, RW(FSW_TBL_R_UPLOAD_ID, 0u));
    in = nav_frame(1);
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.tlm.n_tbl_rej, 7u);                     /* every chunk of the 662 bytes (by 100) */
    UT_UEQ(g_oa.tlm.tbl_reason, RW(FSW_TBL_R_UPLOAD_ID, 0u));
    UT_UEQ(g_oa.tlm.tbl_revision, 1u);
    UT_UEQ(isnap_diff(&g_a), 0u);
    UT_UEQ(g_oa.mode, FSW_MODE_RENDEZVOUS);
}

UT_TEST(rendezvous_scrub_failure_goes_to_safe)
{
    uint32_t i;
    boot_rdv_pair();
    UT_LE(1, run_rdv_pair(0, 70));                      /* firing */
    UT_UEQ(g_ob.tlm.imp.mode, IMP_MODE_FIRING);
    g_b.imp_tbl.img[g_b.imp_tbl.active][FSW_TABLE_HDR_BYTES + 10u] ^= 1u;   /* memory upset */
    {
        fsw_in_t in = rdv_frame(71);
        step_pair(&in);
    }
    UT_UEQ(g_ob.mode, FSW_MODE_SAFE);
    UT_TRUE((g_ob.health & FSW_H_SCRUB) != 0u);
    UT_UEQ(g_ob.tlm.n_scrub_err, 1u);
    UT_UEQ(g_ob.tlm.n_safe, 1u);
    for (i = 0u; i < FSW_ACT_MAX; i++) {
        UT_CHECK_EQ(g_ob.act_cnt[i], 0);                /* every thruster off */
    }
    UT_UEQ(g_oa.mode, FSW_MODE_RENDEZVOUS);
    UT_UEQ(g_oa.tlm.n_scrub_err, 0u);
}

UT_TEST(rendezvous_bad_boot_table_goes_safe)
{
    fsw_cfg_t c = cfg_rdv();
    imp_params_t p = IMP_TBL_DEFAULT;
    fsw_in_t in = nav_frame(0);
    uint32_t why = 0u;
    /* the loader's range check: max_iter = 0 (field 7) */
    p.max_iter = 0u;
    UT_UEQ(fsw_init_rdv(&g_a, &c, &p, 1u), FSW_ERR_RANGE);
    UT_UEQ(g_a.tlm.tbl_reason, RW(FSW_TBL_R_RANGE_LO, 7u));
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_SAFE);
    UT_TRUE((g_oa.health & FSW_H_NO_TABLE) != 0u);
    UT_UEQ(g_oa.tlm.n_tbl_rej, 1u);
    UT_UEQ(g_oa.tlm.tbl_reason, RW(FSW_TBL_R_RANGE_LO, 7u));
    /* recovery: a good upload is committed at once (the scheduler does not run in SAFE) */
    UT_UEQ(upload_params(&g_a, &IMP_TBL_DEFAULT, 2u, &why), FSW_OK);
    in = nav_frame(1);
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_SAFE);                   /* SAFE is left only by command */
    UT_TRUE((g_oa.health & FSW_H_NO_TABLE) == 0u);
    UT_UEQ(g_oa.tlm.tbl_revision, 2u);
    in = nav_frame(2);
    in.mode_cmd = FSW_MODE_STANDBY;
    fsw_step(&g_a, &in, &g_oa);
    in = nav_frame(3);
    in.mode_cmd = FSW_MODE_RENDEZVOUS;
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_RENDEZVOUS);
    UT_UEQ(g_oa.tlm.imp.revision, 2u);
    /* the module check: a valid table of another period (PERIOD, detail 1) */
    UT_UEQ(fsw_init_rdv(&g_a, &c, &IMP_TBL_1S, 1u), FSW_ERR_INVARIANT);
    UT_UEQ(g_a.tlm.tbl_reason, RW(FSW_TBL_R_MODULE, 1u));
    in = nav_frame(0);
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_SAFE);
    UT_TRUE((g_oa.health & FSW_H_NO_TABLE) != 0u);
    UT_UEQ(g_oa.tlm.tbl_reason, RW(FSW_TBL_R_MODULE, 1u));
    /* ... and plan_lead below the worst plan (LEAD, detail 8) */
    p = IMP_TBL_DEFAULT;
    p.plan_lead = 5u;
    UT_UEQ(fsw_init_rdv(&g_a, &c, &p, 1u), FSW_ERR_INVARIANT);
    UT_UEQ(g_a.tlm.tbl_reason, RW(FSW_TBL_R_MODULE, 8u));
    UT_UEQ(g_a.tlm.n_tbl_rej, 1u);
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(boot_tables_encode_load_and_enter_the_boot_mode),
        UT_CASE(bad_config_and_bad_boot_table_are_refused),
        UT_CASE(mode_commands_follow_the_transition_rules),
        UT_CASE(invalid_channels_hold_the_last_good_value_and_are_counted),
        UT_CASE(persistent_stale_and_sat_go_to_safe_with_zero_command), UT_CASE(fx_status_is_reported_and_commands_stay_limited),
        UT_CASE(table_upload_accepted_at_the_step_boundary),
        UT_CASE(corrupt_or_vetoed_tables_are_refused_and_nothing_is_lost),
        UT_CASE(scrub_failure_goes_to_safe),
        UT_CASE(telemetry_encodes_to_its_fixed_size),
        UT_CASE(deterministic_and_instances_independent),
        UT_CASE(rendezvous_boot_channel_map_and_telemetry),
        UT_CASE(rendezvous_bad_nav_is_counted_and_never_safe),
        UT_CASE(rendezvous_telecommands_only_in_the_mission_mode),
        UT_CASE(rendezvous_boot_table_goes_through_the_loader),
        UT_CASE(rendezvous_upload_accepted_at_the_step_boundary),
        UT_CASE(rendezvous_upload_waits_while_the_scheduler_plans_or_fires),
        UT_CASE(rendezvous_upload_in_standby_commits_at_once),
        UT_CASE(rendezvous_corrupt_or_vetoed_tables_are_refused_and_nothing_is_lost),
        UT_CASE(rendezvous_refuses_a_chunk_for_another_table),
        UT_CASE(rendezvous_scrub_failure_goes_to_safe),
        UT_CASE(rendezvous_bad_boot_table_goes_safe),
    };
    return UT_RUN("fsw_exec", cases);
}
