/*
 * The RESPIN mission through the executive (spec 00 §3.3, spec 30 §8): boot from the table image
 * into the mission mode, the channel map (gyro x/y/z, wheel x/y/z in; wheel torques out), g0
 * averaged with zero torque, then the far law's command in counts derived by hand; refused samples
 * counted with zero torque and never SAFE; telecommands only in the mission's namespace; a table
 * upload refused naming its field with nothing lost, a good one committed with the law's state
 * kept; the telemetry's size and layout. Host and target.
 */
#include "fsw_exec.h"
#include "rsp_tables.h"
#include "ut.h"

#define TC_RESET FSW_TC_ID(FSW_MISSION_RESPIN, RSP_CMD_RESET_COUNTERS)

/* omega_z = 1 878 000 * 2^-22 = 0.44775 rad/s: G = J_z omega_z = 299.99 N m s along +z, g = e_z
   (spec 30 §7 A2's start), far above g_guard. */
#define W_Z_CNT 1878000
/* The far law at g = e_z: M_i = -M* Sgn(g_i) with Sgn 0 = +1, so M = -0.15 N m on every axis;
   H = 0 keeps the momentum clamp [-49.8, 49.8] N m inactive. Wheel torque = -M = +0.15 N m =
   0.15 * 2^17 = 19 660.8 counts; from M* = round(0.15 * 2^24) = 2 516 582 (2^-24 N m),
   2 516 582 / 2^7 = 19 660.80 -> 19 661. */
#define FAR_CMD_CNT 19661

/* Large objects live in static storage: the target runner has a small stack. Test-only state. */
static fsw_t g_a;
static fsw_out_t g_oa;
static uint8_t g_img[FSW_TABLE_CAP_BYTES];

static fsw_cfg_t cfg(void)
{
    fsw_cfg_t c;
    c.period_us = RSP_TBL_DEFAULT.period_us;
    c.stale_max = 5u;
    c.boot_mode = FSW_MODE_RESPIN;
    c.mission = FSW_MISSION_RESPIN;
    return c;
}

static fsw_in_t frame(int64_t k, int32_t w_z)
{
    fsw_in_t in;
    uint32_t i;
    in.utime_us = k * (int64_t)RSP_TBL_DEFAULT.period_us;
    in.seq = k;
    in.n_counts = RSP_N_SENS;
    for (i = 0u; i < FSW_IN_MAX; i++) {
        in.counts[i] = 0;
        in.status[i] = 0u;
    }
    /* the gyro's white noise: a word that never repeats (the module calls n_stale equal words stale) */
    in.counts[0] = (int32_t)(k & 7);
    in.counts[2] = w_z;
    in.mode_cmd = FSW_CMD_NONE;
    in.host_missed = 0u;
    in.host_rejected = 0u;
    in.tc = FSW_TC_NONE;
    for (i = 0u; i < FSW_TC_ARGS; i++) {
        in.tc_arg[i] = 0;
    }
    return in;
}

static fsw_rc_t boot(const rsp_params_t *p, uint32_t rev)
{
    fsw_cfg_t c = cfg();
    uint32_t n = rsp_table_encode(p, rev, g_img, (uint32_t)sizeof(g_img));
    return fsw_init(&g_a, &c, g_img, n);
}

static fsw_rc_t upload(const uint8_t *img, uint32_t n, uint32_t rev, uint32_t *why)
{
    fsw_table_chunk_t c;
    c.table_id = (uint16_t)RSP_TBL_ID;
    c.revision = rev;
    c.total_len = n;
    c.offset = 0u;
    c.n = n;
    c.data = img;
    return fsw_table_upload(&g_a, &c, why);
}

/* Steps k0 .. k0 + n - 1 with good frames. */
static void run(int64_t k0, uint32_t n)
{
    uint32_t i;
    for (i = 0u; i < n; i++) {
        fsw_in_t in = frame(k0 + (int64_t)i, W_Z_CNT);
        fsw_step(&g_a, &in, &g_oa);
    }
}

UT_TEST(boots_averages_g0_then_flies_the_far_law)
{
    uint8_t buf[RSP_TLM_TOTAL_BYTES];
    uint32_t i;
    UT_UEQ(boot(&RSP_TBL_DEFAULT, 3u), FSW_OK);
    run(1, RSP_TBL_DEFAULT.n_g0);
    UT_UEQ(g_oa.mode, FSW_MODE_RESPIN);
    UT_UEQ(g_oa.n_act, RSP_N_ACT);
    for (i = 0u; i < RSP_N_ACT; i++) {
        UT_EQ(g_oa.act_cnt[i], 0);                        /* g0 being averaged: zero torque */
    }
    UT_TRUE((g_oa.tlm.mod_health & RSP_H_G0_WAIT) != 0u);
    run(1 + (int64_t)RSP_TBL_DEFAULT.n_g0, 1u);
    UT_UEQ(g_oa.tlm.m.respin.phase, RSP_PH_RUN);
    UT_UEQ(g_oa.tlm.m.respin.region, RSP_RG_FAR);
    UT_EQ(g_oa.tlm.m.respin.a_f, 1);                      /* C_phi = 0: Sgn 0 = +1 */
    for (i = 0u; i < RSP_N_ACT; i++) {
        UT_EQ(g_oa.act_cnt[i], (i < 3u) ? FAR_CMD_CNT : 0);   /* wheels fly; the gimbal rates hold 0 */
    }
    UT_UEQ(g_oa.tlm.mission, FSW_MISSION_RESPIN);
    UT_UEQ(g_oa.tlm.tbl_revision, 3u);
    UT_UEQ(g_oa.tlm.m.respin.revision, 3u);
    UT_UEQ(g_oa.tlm.m.respin.mode, RSP_MODE_NEAREST);
    UT_UEQ(fsw_tlm_layout(&g_oa.tlm), RSP_TLM_LAYOUT);
    UT_UEQ(fsw_tlm_encode(&g_oa.tlm, buf, RSP_TLM_TOTAL_BYTES), RSP_TLM_TOTAL_BYTES);
    UT_UEQ(fsw_tlm_encode(&g_oa.tlm, buf, RSP_TLM_TOTAL_BYTES - 1u), 0u);
}

/* The gyro at full scale (gyro_max_cnt) and the plant's STALE bit: refused by the executive,
   counted, zero torque from the module (GYRO_BAD), for longer than stale_max: never SAFE, because
   the module judges its inputs itself (rsp_mission.c). */
UT_TEST(refused_samples_are_counted_with_zero_torque_and_never_safe)
{
    fsw_in_t in;
    uint32_t i;
    UT_UEQ(boot(&RSP_TBL_DEFAULT, 1u), FSW_OK);
    run(1, RSP_TBL_DEFAULT.n_g0 + 1u);
    UT_EQ(g_oa.act_cnt[0], FAR_CMD_CNT);
    for (i = 0u; i < 8u; i++) {
        in = frame(100 + (int64_t)i, RSP_TBL_DEFAULT.gyro_max_cnt);
        if ((i & 1u) != 0u) {
            in.counts[2] = W_Z_CNT;
            in.status[2] = FSW_ST_STALE;
        }
        fsw_step(&g_a, &in, &g_oa);
        UT_EQ(g_oa.act_cnt[0], 0);
        UT_EQ(g_oa.act_cnt[2], 0);
        UT_TRUE((g_oa.tlm.mod_health & RSP_H_GYRO_BAD) != 0u);
    }
    UT_UEQ(g_oa.tlm.n_chan_rej, 8u);
    UT_UEQ(g_oa.tlm.m.respin.n_gyro_bad, 8u);
    UT_UEQ(g_oa.mode, FSW_MODE_RESPIN);
    UT_UEQ(g_oa.tlm.n_safe, 0u);
    run(200, 1u);                                         /* good data: the far law again */
    UT_EQ(g_oa.act_cnt[2], FAR_CMD_CNT);
    UT_UEQ(g_oa.tlm.m.respin.region, RSP_RG_FAR);
}

UT_TEST(telecommands_in_the_mission_namespace_only)
{
    fsw_in_t in;
    UT_UEQ(boot(&RSP_TBL_DEFAULT, 1u), FSW_OK);
    in = frame(1, 1000);
    in.status[2] = FSW_ST_STALE;
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.tlm.m.respin.n_gyro_bad, 1u);
    in = frame(2, 1000);
    in.tc = FSW_TC_ID(FSW_MISSION_RESPIN + 1u, RSP_CMD_RESET_COUNTERS);   /* another namespace */
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.tlm.n_tc_rej, 1u);
    UT_UEQ(g_oa.tlm.m.respin.n_gyro_bad, 1u);
    in = frame(3, 1000);
    in.tc = TC_RESET;
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.tlm.n_tc, 1u);
    UT_UEQ(g_oa.tlm.m.respin.n_gyro_bad, 0u);
    UT_UEQ(g_oa.tlm.m.respin.health_sticky & RSP_H_GYRO_BAD, 0u);
}

/* An upload with eps1 above 1 (Q1.30): refused by the loader naming field 7 (eps1_q30), the active
   table and the commands unchanged. A good one (mode PRINTED) commits at the next boundary and
   the law keeps g0, region and a_f. */
UT_TEST(bad_upload_is_refused_naming_the_field_good_one_keeps_the_state)
{
    rsp_params_t p = RSP_TBL_DEFAULT;
    uint32_t why = 0u;
    uint32_t n;
    int32_t g0;
    UT_UEQ(boot(&RSP_TBL_DEFAULT, 1u), FSW_OK);
    run(1, RSP_TBL_DEFAULT.n_g0 + 1u);
    g0 = g_oa.tlm.m.respin.g0_q20;
    UT_TRUE(g0 > 0);
    p.eps1_q30 = (int32_t)0x40000001;
    n = rsp_table_encode(&p, 2u, g_img, (uint32_t)sizeof(g_img));
    UT_UEQ(n, FSW_TABLE_HDR_BYTES + RSP_TBL_PAYLOAD);
    UT_UEQ(upload(g_img, n, 2u, &why), FSW_ERR_RANGE);
    UT_UEQ(why & 0xFFu, FSW_TBL_R_RANGE_HI);
    UT_UEQ(why >> FSW_TBL_DETAIL_SHIFT, 7u);
    run(100, 1u);
    UT_EQ(g_oa.act_cnt[1], FAR_CMD_CNT);
    UT_UEQ(g_oa.tlm.n_tbl_rej, 1u);
    UT_UEQ(g_oa.tlm.tbl_revision, 1u);
    p = RSP_TBL_PRINTED;
    n = rsp_table_encode(&p, 3u, g_img, (uint32_t)sizeof(g_img));
    UT_UEQ(upload(g_img, n, 3u, &why), FSW_OK);
    run(101, 1u);
    UT_UEQ(g_oa.tlm.tbl_revision, 3u);
    UT_UEQ(g_oa.tlm.n_tbl_acc, 1u);
    UT_UEQ(g_oa.tlm.m.respin.mode, RSP_MODE_PRINTED);
    UT_UEQ(g_oa.tlm.m.respin.phase, RSP_PH_RUN);
    UT_EQ(g_oa.tlm.m.respin.g0_q20, g0);
    UT_EQ(g_oa.act_cnt[1], FAR_CMD_CNT);
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(boots_averages_g0_then_flies_the_far_law),
        UT_CASE(refused_samples_are_counted_with_zero_torque_and_never_safe),
        UT_CASE(telecommands_in_the_mission_namespace_only),
        UT_CASE(bad_upload_is_refused_naming_the_field_good_one_keeps_the_state),
    };
    return UT_RUN("rsp_mission", cases);
}
