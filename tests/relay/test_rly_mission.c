/*
 * The RELAY mission through the executive (spec 00 §3.3, spec 20 §8): boot from the table image
 * into the mission mode, the channel map (angle counts in, a level code out), a STALE or SAT sample
 * handled by the module (never the executive's SAFE), telecommands only in the mission's namespace,
 * a table upload refused naming its field with nothing lost, the commit at a window boundary, the
 * app counter wrap (F3), and the telemetry's size and layout. Host and target.
 */
#include "fsw_exec.h"
#include "rly_tables.h"
#include "ut.h"

#define TC_RESET FSW_TC_ID(FSW_MISSION_RELAY, RLY_CMD_RESET_COUNTERS)

/* Large objects live in static storage: the target runner has a small stack. Test-only state. */
static fsw_t g_a;
static fsw_out_t g_oa;
static uint8_t g_img[FSW_TABLE_CAP_BYTES];

static fsw_cfg_t cfg(void)
{
    fsw_cfg_t c;
    c.period_us = RLY_TBL_DEFAULT.period_us;
    c.stale_max = 5u;
    c.boot_mode = FSW_MODE_RELAY;
    c.mission = FSW_MISSION_RELAY;
    return c;
}

static fsw_in_t frame(int64_t k, int32_t x)
{
    fsw_in_t in;
    uint32_t i;
    in.utime_us = k * (int64_t)RLY_TBL_DEFAULT.period_us;
    in.seq = k;
    in.n_counts = RLY_N_SENS;
    for (i = 0u; i < FSW_IN_MAX; i++) {
        in.counts[i] = 0;
        in.status[i] = 0u;
    }
    in.counts[0] = x;
    in.mode_cmd = FSW_CMD_NONE;
    in.host_missed = 0u;
    in.host_rejected = 0u;
    in.tc = FSW_TC_NONE;
    for (i = 0u; i < FSW_TC_ARGS; i++) {
        in.tc_arg[i] = 0;
    }
    return in;
}

static fsw_rc_t boot(const rly_params_t *p, uint32_t rev)
{
    fsw_cfg_t c = cfg();
    uint32_t n = rly_table_encode(p, rev, g_img, (uint32_t)sizeof(g_img));
    return fsw_init(&g_a, &c, g_img, n);
}

static fsw_rc_t upload(const uint8_t *img, uint32_t n, uint32_t rev, uint32_t *why)
{
    fsw_table_chunk_t c;
    c.table_id = (uint16_t)RLY_TBL_ID;
    c.revision = rev;
    c.total_len = n;
    c.offset = 0u;
    c.n = n;
    c.data = img;
    return fsw_table_upload(&g_a, &c, why);
}

UT_TEST(boots_into_the_mission_and_commands)
{
    uint8_t buf[RLY_TLM_TOTAL_BYTES];
    fsw_in_t in = frame(1, 0);
    UT_UEQ(boot(&RLY_TBL_DEFAULT, 3u), FSW_OK);
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_RELAY);
    UT_UEQ(g_oa.n_act, RLY_N_ACT);
    UT_EQ(g_oa.act_cnt[0], RLY_LVL_WEAK_POS);          /* W_POS, inside the deadband */
    UT_UEQ(g_oa.health, 0u);
    in = frame(2, 8389);                                /* x = eps: R_MAIN, FULL_NEG */
    fsw_step(&g_a, &in, &g_oa);
    UT_EQ(g_oa.act_cnt[0], RLY_LVL_FULL_NEG);
    UT_UEQ(g_oa.tlm.m.relay.st, RLY_ST_R_MAIN);
    UT_UEQ(g_oa.tlm.mission, FSW_MISSION_RELAY);
    UT_UEQ(g_oa.tlm.tbl_revision, 3u);
    UT_UEQ(g_oa.tlm.m.relay.revision, 3u);
    UT_UEQ(fsw_tlm_layout(&g_oa.tlm), RLY_TLM_LAYOUT);
    UT_UEQ(fsw_tlm_encode(&g_oa.tlm, buf, RLY_TLM_TOTAL_BYTES), RLY_TLM_TOTAL_BYTES);
    UT_UEQ(fsw_tlm_encode(&g_oa.tlm, buf, RLY_TLM_TOTAL_BYTES - 1u), 0u);
}

/* A STALE sample and a sample with the plant's SAT bit: invalid for the module (F1, counted),
   the pulse goes on; 100 in a row COAST (OFF) with SENSOR_LOST as a module fault; the executive
   never goes to SAFE (stale_max = 5 here). */
UT_TEST(lost_samples_are_the_modules_business)
{
    fsw_in_t in;
    int64_t k;
    UT_UEQ(boot(&RLY_TBL_DEFAULT, 1u), FSW_OK);
    in = frame(1, 8389);
    fsw_step(&g_a, &in, &g_oa);
    in = frame(2, 8000);
    in.status[0] = FSW_ST_SAT;
    fsw_step(&g_a, &in, &g_oa);
    UT_EQ(g_oa.act_cnt[0], RLY_LVL_FULL_NEG);
    UT_UEQ(g_oa.tlm.m.relay.n_x_invalid, 1u);
    for (k = 3; k < 102; k++) {
        in = frame(k, 8000);
        in.status[0] = FSW_ST_STALE;
        fsw_step(&g_a, &in, &g_oa);
    }
    UT_EQ(g_oa.act_cnt[0], RLY_LVL_OFF);
    UT_UEQ(g_oa.tlm.m.relay.st, RLY_ST_COAST);
    UT_TRUE((g_oa.tlm.mod_health & RLY_H_SENSOR_LOST) != 0u);
    UT_TRUE((g_oa.health & FSW_H_MODULE) != 0u);
    UT_UEQ(g_oa.mode, FSW_MODE_RELAY);
    UT_UEQ(g_oa.tlm.n_safe, 0u);
    in = frame(102, 0);
    fsw_step(&g_a, &in, &g_oa);
    UT_EQ(g_oa.act_cnt[0], RLY_LVL_WEAK_POS);
}

UT_TEST(telecommands_in_the_mission_namespace_only)
{
    fsw_in_t in;
    UT_UEQ(boot(&RLY_TBL_DEFAULT, 1u), FSW_OK);
    in = frame(1, 0);
    in.status[0] = FSW_ST_STALE;
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.tlm.m.relay.n_x_invalid, 1u);
    in = frame(2, 0);
    in.tc = FSW_TC_ID(FSW_MISSION_RELAY + 1u, RLY_CMD_RESET_COUNTERS);   /* another namespace */
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.tlm.n_tc_rej, 1u);
    UT_UEQ(g_oa.tlm.m.relay.n_x_invalid, 1u);
    in = frame(3, 0);
    in.tc = TC_RESET;
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.tlm.n_tc, 1u);
    UT_UEQ(g_oa.tlm.m.relay.n_x_invalid, 0u);
    UT_UEQ(g_oa.tlm.m.relay.health_sticky, 0u);
}

/* An upload with gamma below 2 sensor LSB is refused by the loader naming field 3 (gamma_q24);
   one with gamma >= eps by the relation (gamma + 1 <= eps); the active table and the law go on.
   A good one (k_t0 changed) waits for the window boundary and commits there, keeping the law's
   state and k_t (the in-flight rule of rly_mission.c). One that moves the deadband edge (eps)
   waits further: through every window boundary the law passes in a pulse or brake, committing at
   the first boundary it passes in W. */
UT_TEST(uploads_refused_naming_the_field_and_committed_at_a_window_boundary)
{
    rly_params_t p = RLY_TBL_FIXED_031;
    uint32_t why = 0u;
    uint32_t n;
    int64_t k;
    fsw_in_t in;
    p.win_ticks = 10u;
    UT_UEQ(boot(&p, 1u), FSW_OK);
    p.gamma_q24 = 1;
    n = rly_table_encode(&p, 2u, g_img, (uint32_t)sizeof(g_img));
    UT_UEQ(n, FSW_TABLE_HDR_BYTES + RLY_TBL_PAYLOAD);
    UT_UEQ(upload(g_img, n, 2u, &why), FSW_ERR_RANGE);
    UT_UEQ(why & 0xFFu, FSW_TBL_R_RANGE_LO);
    UT_UEQ(why >> FSW_TBL_DETAIL_SHIFT, 3u);
    p = RLY_TBL_FIXED_031;
    p.win_ticks = 10u;
    p.gamma_q24 = p.eps_q24;
    n = rly_table_encode(&p, 2u, g_img, (uint32_t)sizeof(g_img));
    UT_TRUE(upload(g_img, n, 2u, &why) != FSW_OK);
    in = frame(1, 8389);
    fsw_step(&g_a, &in, &g_oa);
    UT_EQ(g_oa.act_cnt[0], RLY_LVL_FULL_NEG);
    UT_UEQ(g_oa.tlm.n_tbl_rej, 2u);
    UT_UEQ(g_oa.tlm.tbl_revision, 1u);
    /* a good one: pending until the step after the 10th (the window closes on tick 10) */
    p = RLY_TBL_FIXED_031;
    p.win_ticks = 10u;
    p.kt0_q16 = (uint16_t)(p.kt0_q16 + 1u);
    n = rly_table_encode(&p, 3u, g_img, (uint32_t)sizeof(g_img));
    UT_UEQ(upload(g_img, n, 3u, &why), FSW_OK);
    for (k = 2; k <= 10; k++) {
        in = frame(k, 8000);
        fsw_step(&g_a, &in, &g_oa);
        UT_UEQ(g_oa.tlm.tbl_revision, 1u);
        UT_TRUE((g_oa.health & FSW_H_TBL_PENDING) != 0u);
    }
    in = frame(11, 8000);
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.tlm.tbl_revision, 3u);
    UT_UEQ(g_oa.tlm.n_tbl_acc, 1u);
    UT_UEQ(g_oa.tlm.m.relay.st, RLY_ST_R_MAIN);         /* the pulse under way was kept */
    UT_UEQ(g_oa.tlm.m.relay.n, 10u);
    UT_UEQ(g_oa.tlm.m.relay.kt_q16, RLY_TBL_FIXED_031.kt0_q16);   /* k_t held, inside the new limits */
    /* geometry: eps moved. x held at 8000 (above the brake edge eps - gamma) keeps R_MAIN running to
       tick 2999; x = 0 from tick 3000 starts the brake, k_t tau1 ~ 926 ticks, then W+ holds (inside
       the deadband). About 390 10-tick window boundaries pass in the pulse and brake; the table
       waits through all of them and commits at the first boundary in W+. */
    p.eps_q24 = 9000;
    n = rly_table_encode(&p, 4u, g_img, (uint32_t)sizeof(g_img));
    UT_UEQ(upload(g_img, n, 4u, &why), FSW_OK);
    {
        uint32_t nw = g_oa.tlm.m.relay.n_windows;
        uint8_t st_at_boundary = RLY_ST_R_MAIN;
        uint32_t boundaries_not_w = 0u;
        for (k = 12; (k < 20000) && (g_oa.tlm.tbl_revision == 3u); k++) {
            in = frame(k, (k < 3000) ? 8000 : 0);
            fsw_step(&g_a, &in, &g_oa);
            if ((g_oa.tlm.tbl_revision == 3u) && (g_oa.tlm.m.relay.n_windows != nw)) {
                nw = g_oa.tlm.m.relay.n_windows;
                st_at_boundary = g_oa.tlm.m.relay.st;   /* the state the next step's commit test sees */
                if ((st_at_boundary != RLY_ST_W_POS) && (st_at_boundary != RLY_ST_W_NEG)) {
                    boundaries_not_w++;
                }
            }
        }
        /* ut_put_*: the target image has no libc printf */
        ut_puts("geometry table: committed at tick ");
        ut_put_i64((int64_t)k);
        ut_puts(" after ");
        ut_put_u64((uint64_t)boundaries_not_w);
        ut_puts(" boundaries outside W\n");
        UT_UEQ(g_oa.tlm.tbl_revision, 4u);
        UT_UEQ(g_oa.tlm.n_tbl_acc, 2u);
        UT_TRUE((st_at_boundary == RLY_ST_W_POS) || (st_at_boundary == RLY_ST_W_NEG));   /* committed from W */
        UT_TRUE(boundaries_not_w > 350u);   /* (3000 - 11 + 926) / 10 ~ 390 boundaries in pulse and brake */
        UT_TRUE((k > 3900) && (k < 4000));  /* committed within one window of the brake's end */
    }
}

/* F3: the module holds no absolute time; the app's counters started at 2^32 - 10^4 fly the same
   commands and module telemetry as a start at 0 over 12 000 ticks across the wrap. */
UT_TEST(f3_counter_wrap_changes_nothing)
{
    static int32_t cmd0[12000];
    static uint32_t a0[12000];
    fsw_in_t in;
    uint32_t k;
    int32_t x = 0;
    int32_t v = 3;
    UT_UEQ(boot(&RLY_TBL_DEFAULT, 1u), FSW_OK);
    for (k = 0u; k < 12000u; k++) {
        x = (x + v > 9000 || x + v < -9000) ? x : (x + v);
        v = (x >= 8389) ? -3 : ((x <= -8389) ? 3 : v);
        in = frame((int64_t)k + 1, x);
        fsw_step(&g_a, &in, &g_oa);
        cmd0[k] = g_oa.act_cnt[0];
        a0[k] = g_oa.tlm.m.relay.a_q40;
    }
    UT_UEQ(boot(&RLY_TBL_DEFAULT, 1u), FSW_OK);
    x = 0;
    v = 3;
    for (k = 0u; k < 12000u; k++) {
        x = (x + v > 9000 || x + v < -9000) ? x : (x + v);
        v = (x >= 8389) ? -3 : ((x <= -8389) ? 3 : v);
        in = frame((int64_t)4294957296 + (int64_t)k, x);   /* 2^32 - 10^4 + k */
        fsw_step(&g_a, &in, &g_oa);
        UT_EQ(g_oa.act_cnt[0], cmd0[k]);
        UT_UEQ(g_oa.tlm.m.relay.a_q40, a0[k]);
    }
    UT_UEQ(g_oa.tlm.n_in_bad, 0u);
}

int main(void)
{
    UT_CASES(cases) = {
        UT_CASE(boots_into_the_mission_and_commands),
        UT_CASE(lost_samples_are_the_modules_business),
        UT_CASE(telecommands_in_the_mission_namespace_only),
        UT_CASE(uploads_refused_naming_the_field_and_committed_at_a_window_boundary),
        UT_CASE(f3_counter_wrap_changes_nothing),
    };
    return UT_RUN("rly_mission", cases);
}
