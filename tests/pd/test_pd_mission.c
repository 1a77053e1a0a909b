/*
 * The HOLD mission through the executive (spec 00 §3.3): boot from the table image into the
 * mission mode, the channel map (range from the table, refused samples counted, zero torque),
 * telecommands only in the mission's namespace, a table upload refused naming its field with
 * nothing lost, and the telemetry's size and layout. Host and target.
 */
#include "fsw_exec.h"
#include "pd_tables.h"
#include "ut.h"

#define TC_RESET FSW_TC_ID(FSW_MISSION_HOLD, PD_CMD_RESET_COUNTERS)

/* Large objects live in static storage: the target runner has a small stack. Test-only state. */
static fsw_t g_a;
static fsw_out_t g_oa;
static uint8_t g_img[FSW_TABLE_CAP_BYTES];

static fsw_cfg_t cfg(void)
{
    fsw_cfg_t c;
    c.period_us = PD_TBL_DEFAULT.period_us;
    c.stale_max = 5u;
    c.boot_mode = FSW_MODE_HOLD;
    c.mission = FSW_MISSION_HOLD;
    return c;
}

static fsw_in_t frame(int64_t k, int32_t rate)
{
    fsw_in_t in;
    uint32_t i;
    in.utime_us = k * (int64_t)PD_TBL_DEFAULT.period_us;
    in.seq = k;
    in.n_counts = PD_N_SENS;
    for (i = 0u; i < FSW_IN_MAX; i++) {
        in.counts[i] = 0;
        in.status[i] = 0u;
    }
    in.counts[0] = rate;
    in.mode_cmd = FSW_CMD_NONE;
    in.host_missed = 0u;
    in.host_rejected = 0u;
    in.tc = FSW_TC_NONE;
    for (i = 0u; i < FSW_TC_ARGS; i++) {
        in.tc_arg[i] = 0;
    }
    return in;
}

static fsw_rc_t boot(const pd_params_t *p, uint32_t rev)
{
    fsw_cfg_t c = cfg();
    uint32_t n = pd_table_encode(p, rev, g_img, (uint32_t)sizeof(g_img));
    return fsw_init(&g_a, &c, g_img, n);
}

static fsw_rc_t upload(const uint8_t *img, uint32_t n, uint32_t rev, uint32_t *why)
{
    fsw_table_chunk_t c;
    c.table_id = (uint16_t)PD_TBL_ID;
    c.revision = rev;
    c.total_len = n;
    c.offset = 0u;
    c.n = n;
    c.data = img;
    return fsw_table_upload(&g_a, &c, why);
}

UT_TEST(boots_into_the_mission_and_commands)
{
    uint8_t buf[PD_TLM_TOTAL_BYTES];
    fsw_in_t in = frame(1, 16384);
    UT_UEQ(boot(&PD_TBL_DEFAULT, 3u), FSW_OK);
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_HOLD);
    UT_UEQ(g_oa.n_act, PD_N_ACT);
    UT_EQ(g_oa.act_cnt[0], -512);                       /* test_pd.c's first case */
    UT_UEQ(g_oa.health, 0u);
    UT_UEQ(g_oa.tlm.mission, FSW_MISSION_HOLD);
    UT_UEQ(g_oa.tlm.tbl_revision, 3u);
    UT_UEQ(g_oa.tlm.m.hold.revision, 3u);
    UT_UEQ(fsw_tlm_layout(&g_oa.tlm), PD_TLM_LAYOUT);
    UT_UEQ(fsw_tlm_encode(&g_oa.tlm, buf, PD_TLM_TOTAL_BYTES), PD_TLM_TOTAL_BYTES);
    UT_UEQ(fsw_tlm_encode(&g_oa.tlm, buf, PD_TLM_TOTAL_BYTES - 1u), 0u);
}

/* The gyro's full scale (rate_max_cnt) and the plant's STALE bit: refused by the executive,
   counted, zero torque from the module (MEAS_SKIP); never SAFE within stale_max. */
UT_TEST(refused_samples_are_counted_and_safe)
{
    fsw_in_t in;
    UT_UEQ(boot(&PD_TBL_DEFAULT, 1u), FSW_OK);
    in = frame(1, PD_TBL_DEFAULT.rate_max_cnt);
    fsw_step(&g_a, &in, &g_oa);
    UT_EQ(g_oa.act_cnt[0], 0);
    UT_UEQ(g_oa.tlm.n_chan_rej, 1u);
    UT_TRUE((g_oa.tlm.mod_health & PD_H_MEAS_SKIP) != 0u);
    in = frame(2, 1000);
    in.status[0] = FSW_ST_STALE;
    fsw_step(&g_a, &in, &g_oa);
    UT_EQ(g_oa.act_cnt[0], 0);
    UT_UEQ(g_oa.tlm.n_chan_rej, 2u);
    UT_UEQ(g_oa.tlm.m.hold.n_skip, 2u);
    in = frame(3, PD_TBL_DEFAULT.rate_max_cnt - 1);
    fsw_step(&g_a, &in, &g_oa);
    UT_EQ(g_oa.act_cnt[0], -PD_TBL_DEFAULT.u_max_cnt);
    UT_UEQ(g_oa.mode, FSW_MODE_HOLD);
    UT_UEQ(g_oa.tlm.n_safe, 0u);
}

UT_TEST(telecommands_in_the_mission_namespace_only)
{
    fsw_in_t in;
    UT_UEQ(boot(&PD_TBL_DEFAULT, 1u), FSW_OK);
    in = frame(1, 1000);
    in.status[0] = FSW_ST_STALE;
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.tlm.m.hold.n_skip, 1u);
    in = frame(2, 1000);
    in.tc = FSW_TC_ID(FSW_MISSION_HOLD + 1u, PD_CMD_RESET_COUNTERS);   /* another namespace */
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.tlm.n_tc_rej, 1u);
    UT_UEQ(g_oa.tlm.m.hold.n_skip, 1u);
    in = frame(3, 1000);
    in.tc = TC_RESET;
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.tlm.n_tc, 1u);
    UT_UEQ(g_oa.tlm.m.hold.n_skip, 0u);
    UT_UEQ(g_oa.tlm.m.hold.health_sticky, 0u);
}

/* An upload with the gain above its limit: refused by the loader naming field 2 (gain_q16),
   the active table and the commands unchanged. */
UT_TEST(bad_upload_is_refused_naming_the_field)
{
    pd_params_t p = PD_TBL_DEFAULT;
    uint32_t why = 0u;
    uint32_t n;
    fsw_in_t in;
    UT_UEQ(boot(&PD_TBL_DEFAULT, 1u), FSW_OK);
    p.gain_q16 = PD_GAIN_MAX_Q16 + 1;
    n = pd_table_encode(&p, 2u, g_img, (uint32_t)sizeof(g_img));
    UT_UEQ(n, FSW_TABLE_HDR_BYTES + PD_TBL_PAYLOAD);
    UT_UEQ(upload(g_img, n, 2u, &why), FSW_ERR_RANGE);
    UT_UEQ(why & 0xFFu, FSW_TBL_R_RANGE_HI);
    UT_UEQ(why >> FSW_TBL_DETAIL_SHIFT, 2u);
    in = frame(1, 16384);
    fsw_step(&g_a, &in, &g_oa);
    UT_EQ(g_oa.act_cnt[0], -512);
    UT_UEQ(g_oa.tlm.n_tbl_rej, 1u);
    UT_UEQ(g_oa.tlm.tbl_revision, 1u);
    /* a good one commits at the next boundary */
    p = PD_TBL_DEFAULT;
    p.gain_q16 = 4096;
    n = pd_table_encode(&p, 3u, g_img, (uint32_t)sizeof(g_img));
    UT_UEQ(upload(g_img, n, 3u, &why), FSW_OK);
    in = frame(2, 16384);
    fsw_step(&g_a, &in, &g_oa);
    UT_EQ(g_oa.act_cnt[0], -1024);
    UT_UEQ(g_oa.tlm.tbl_revision, 3u);
    UT_UEQ(g_oa.tlm.n_tbl_acc, 1u);
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(boots_into_the_mission_and_commands),
        UT_CASE(refused_samples_are_counted_and_safe),
        UT_CASE(telecommands_in_the_mission_namespace_only),
        UT_CASE(bad_upload_is_refused_naming_the_field),
    };
    return UT_RUN("pd_mission", cases);
}
