/*
 * The RENDEZVOUS mission through the executive (spec 50 §5, spec 00 §3.3): boot, the nav channel
 * map (one sample, valid only whole, never a SAFE trigger), telecommands only in the mission mode
 * and only in its namespace, the impulse table's boot path, uploads committed at a step boundary
 * only while the scheduler is idle or terminal (deferred while it plans or fires, the firing
 * bit-identical to a twin without the upload), corrupt and vetoed uploads refused with nothing
 * lost, scrub failure -> SAFE. Host and target.
 */
#include "fsw_exec.h"
#include "imp_tables.h"
#include "imp_tbl_util.h"
#include "ut.h"

#define TC_START FSW_TC_ID(FSW_MISSION_RENDEZVOUS, IMP_CMD_START)
#define TC_ABORT FSW_TC_ID(FSW_MISSION_RENDEZVOUS, IMP_CMD_ABORT)
#define TC_CLEAR FSW_TC_ID(FSW_MISSION_RENDEZVOUS, IMP_CMD_CLEAR_FAULTS)

/* A mode command for a mode that is not this mission's: DETUMBLE's when the build holds that
   mission too (a mode the executive flies, the sharpest case), else the next number, which no
   configured mission flies (FSW_MISSIONS=RENDEZVOUS builds this test as well). */
#if defined(FSW_MODE_DETUMBLE)
#define OTHER_MODE FSW_MODE_DETUMBLE
#else
#define OTHER_MODE (FSW_MODE_RENDEZVOUS + 1u)
#endif

/* Large objects live in static storage: the target runner has a small stack. Test-only state. */
static fsw_t g_a;
static fsw_t g_b;
static fsw_out_t g_oa;
static fsw_out_t g_ob;
static uint8_t g_img[FSW_TABLE_CAP_BYTES];
static uint8_t g_boot[FSW_TABLE_CAP_BYTES];

/* Boots f from the impulse table p (revision rev) through its image, as a board would. */
static fsw_rc_t boot_imp(fsw_t *f, const fsw_cfg_t *c, const imp_params_t *p, uint32_t rev)
{
    uint32_t n = imp_table_encode(p, rev, g_boot, (uint32_t)sizeof(g_boot));
    return fsw_init(f, c, g_boot, n);
}

static fsw_in_t frame(int64_t seq)
{
    fsw_in_t in;
    uint32_t i;
    in.utime_us = seq * 100000;
    in.seq = seq;
    in.n_counts = 0u;
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
    return in;
}

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
    fsw_in_t in = frame(k);
    uint32_t i;
    in.utime_us = k * 100000;
    in.n_counts = IMP_N_SENS;
    for (i = 0u; i < 3u; i++) {
        in.counts[i] = (i == 0u) ? 5000000 : 4000000;   /* mm */
        in.counts[3u + i] = -100000;                    /* 10 um/s */
    }
    in.counts[6] = (int32_t)k;
    return in;
}

UT_TEST(rendezvous_boot_channel_map_and_telemetry)
{
    uint8_t buf[IMP_TLM_TOTAL_BYTES];
    fsw_cfg_t c = cfg_rdv();
    fsw_in_t in = nav_frame(0);
    uint32_t i;
    UT_UEQ(boot_imp(&g_a, &c, &IMP_TBL_DEFAULT, 3u), FSW_OK);
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_RENDEZVOUS);
    UT_UEQ(g_oa.n_act, IMP_N_ACT);
    for (i = 0u; i < FSW_ACT_MAX; i++) {
        UT_CHECK_EQ(g_oa.act_cnt[i], 0);              /* IDLE: every thruster off */
    }
    UT_UEQ(g_oa.health & 0xFFu, 0u);
    UT_UEQ(g_oa.tlm.mission, FSW_MISSION_RENDEZVOUS);
    UT_UEQ(g_oa.tlm.m.rendezvous.mode, IMP_MODE_IDLE);
    UT_UEQ(g_oa.tlm.tbl_revision, 3u);
    UT_UEQ(fsw_tlm_layout(&g_oa.tlm), IMP_TLM_LAYOUT);
    UT_UEQ(fsw_tlm_encode(&g_oa.tlm, buf, IMP_TLM_TOTAL_BYTES), IMP_TLM_TOTAL_BYTES);
    UT_UEQ(fsw_tlm_encode(&g_oa.tlm, buf, IMP_TLM_TOTAL_BYTES - 1u), 0u);
    UT_UEQ(buf[16], 1u);                               /* step 1, after utime and seq */
    /* an image of another table (the observer's id) is refused by the loader, named */
    {
        uint32_t n = imp_table_encode(&IMP_TBL_DEFAULT, 1u, g_boot, (uint32_t)sizeof(g_boot));
        g_boot[0] = 0x01u;                             /* table_id, little-endian: 0x0B01 */
        g_boot[1] = 0x0Bu;
        UT_UEQ(fsw_init(&g_b, &c, g_boot, n), FSW_ERR_HEADER);
        UT_UEQ(g_b.tlm.tbl_reason & 0xFFu, FSW_TBL_R_ID);
        fsw_step(&g_b, &in, &g_ob);
        UT_UEQ(g_ob.mode, FSW_MODE_SAFE);
    }
    /* a configuration naming a mission this build does not contain */
    c.mission = 0xEEu;
    UT_UEQ(boot_imp(&g_b, &c, &IMP_TBL_DEFAULT, 1u), FSW_ERR_ARG);
}

UT_TEST(rendezvous_bad_nav_is_counted_and_never_safe)
{
    fsw_cfg_t c = cfg_rdv();
    int64_t k;
    UT_UEQ(boot_imp(&g_a, &c, &IMP_TBL_DEFAULT, 1u), FSW_OK);
    for (k = 0; k < 40; k++) {
        fsw_in_t in = nav_frame(k);
        if ((k % 4) == 1) {
            in.status[2] = FSW_ST_STALE;               /* plant: no valid sample */
        } else if ((k % 4) == 2) {
            in.counts[3] = IMP_NAV_VEL_MAX_CNT + 1;    /* beyond the accepted range */
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
    UT_UEQ(boot_imp(&g_a, &c, &IMP_TBL_DEFAULT, 1u), FSW_OK);
    fsw_step(&g_a, &in, &g_oa);
    in = nav_frame(1);
    in.tc = TC_START;                          /* START in STANDBY: refused */
    in.tc_arg[0] = 200;
    in.tc_arg[1] = 200 + 10550;
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.tlm.n_tc_rej, 1u);
    UT_TRUE((g_oa.health & FSW_H_TC_REJ) != 0u);
    UT_UEQ(g_oa.tlm.m.rendezvous.mode, IMP_MODE_IDLE);
    in = nav_frame(2);
    in.mode_cmd = OTHER_MODE;                          /* not this mission's mode */
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_STANDBY);
    UT_UEQ(g_oa.tlm.n_mode_rej, 1u);
    in = nav_frame(3);
    in.mode_cmd = FSW_MODE_RENDEZVOUS;
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_RENDEZVOUS);
    in = nav_frame(4);
    in.tc = TC_START;                          /* now taken by the scheduler */
    in.tc_arg[0] = 200;
    in.tc_arg[1] = 200 + 10550;
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.tlm.n_tc, 1u);
    UT_TRUE(g_oa.tlm.m.rendezvous.mode != IMP_MODE_IDLE);       /* planning (or already armed) */
    UT_UEQ(g_oa.tlm.m.rendezvous.cmd_rej, 0u);
}

/* ------------------------------------------------------------------ RENDEZVOUS: the impulse table */

static imp_params_t g_ip;
static fsw_tlm_t g_tla;
static fsw_tlm_t g_tlb;
static uint8_t g_ea[IMP_TLM_TOTAL_BYTES];
static uint8_t g_eb[IMP_TLM_TOTAL_BYTES];
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
        c.table_id = (uint16_t)IMP_TBL_ID;
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
    uint32_t n = imp_table_encode(p, rev, g_img, sizeof(g_img));
    UT_CHECK_UEQ(n, FSW_TABLE_HDR_BYTES + IMP_TBL_PAYLOAD);
    return upload_imp(f, g_img, n, 40u, why);
}

/* The nav frame of step k, with the START telecommand of the paper's example at k == 4. */
static fsw_in_t rdv_frame(int64_t k)
{
    fsw_in_t in = nav_frame(k);
    if (k == 4) {
        in.tc = TC_START;
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
    (void)fsw_tlm_encode(&g_tla, g_ea, IMP_TLM_TOTAL_BYTES);
    (void)fsw_tlm_encode(&g_tlb, g_eb, IMP_TLM_TOTAL_BYTES);
    for (i = 0u; i < IMP_TLM_TOTAL_BYTES; i++) {
        d += (g_ea[i] != g_eb[i]) ? 1u : 0u;
    }
    for (i = 0u; i < IMP_N_ACT; i++) {
        d += (g_oa.act_cnt[i] != g_ob.act_cnt[i]) ? 1u : 0u;
    }
    return d;
}

static void isnap_take(const fsw_t *f)
{
    uint32_t i;
    for (i = 0u; i < FSW_TABLE_CAP_BYTES; i++) {
        g_isnap[i] = f->tbl.img[f->tbl.active][i];
    }
}

static uint32_t isnap_diff(const fsw_t *f)
{
    uint32_t i;
    uint32_t d = 0u;
    for (i = 0u; i < FSW_TABLE_CAP_BYTES; i++) {
        d += (f->tbl.img[f->tbl.active][i] != g_isnap[i]) ? 1u : 0u;
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
        fired += (g_ob.act_cnt[IMP_ACT_MASK] != 0) ? 1u : 0u;
    }
    return fired;
}

static void boot_rdv_pair(void)
{
    fsw_cfg_t c = cfg_rdv();
    UT_CHECK_UEQ(boot_imp(&g_a, &c, &IMP_TBL_DEFAULT, 1u), FSW_OK);
    UT_CHECK_UEQ(boot_imp(&g_b, &c, &IMP_TBL_DEFAULT, 1u), FSW_OK);
}

UT_TEST(rendezvous_boot_table_goes_through_the_loader)
{
    fsw_cfg_t c = cfg_rdv();
    const imp_params_t *t[2] = {&IMP_TBL_DEFAULT, &IMP_TBL_SUB1MS};
    uint32_t i;
    for (i = 0u; i < 2u; i++) {
        fsw_in_t in = nav_frame(0);
        UT_CHECK_UEQ(boot_imp(&g_a, &c, t[i], 6u), FSW_OK);
        g_ip = *t[i];
        g_ip.revision = 6u;
        UT_CHECK_UEQ(imp_params_diff(&g_a.m.rendezvous.p, &g_ip, 1), 0u);   /* decoded from the active image */
        UT_CHECK_UEQ(fsw_table_revision(&g_a.tbl), 6u);
        UT_CHECK(fsw_mission_table(&g_a) == &g_a.tbl);
        fsw_step(&g_a, &in, &g_oa);
        UT_CHECK_UEQ(g_oa.mode, FSW_MODE_RENDEZVOUS);
        UT_CHECK_UEQ(g_oa.tlm.tbl_revision, 6u);
        UT_CHECK_UEQ(g_oa.tlm.m.rendezvous.revision, 6u);
        UT_CHECK_UEQ(g_oa.tlm.n_tbl_rej, 0u);
    }
    UT_TRUE(fsw_mission_table(NULL) == NULL);
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
    UT_UEQ(g_b.tbl.state, FSW_TBL_S_READY);
    UT_UEQ(g_b.m.rendezvous.p.miss_flag_q28, IMP_TBL_DEFAULT.miss_flag_q28);   /* not before the boundary */
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
    UT_UEQ(g_ob.tlm.m.rendezvous.revision, 2u);                  /* the scheduler runs with it */
    UT_UEQ(g_ob.tlm.m.rendezvous.mode, IMP_MODE_IDLE);
    UT_UEQ(g_ob.mode, FSW_MODE_RENDEZVOUS);
    g_ip.revision = 2u;
    UT_UEQ(imp_params_diff(&g_b.m.rendezvous.p, &g_ip, 1), 0u);
    UT_UEQ(g_oa.tlm.tbl_revision, 1u);                  /* the other instance is untouched */
    UT_UEQ(g_oa.tlm.n_tbl_acc, 0u);
    /* and a START after the commit plans with it */
    {
        fsw_in_t in = nav_frame(11);
        in.tc = TC_START;
        in.tc_arg[0] = 11 + 60;
        in.tc_arg[1] = 11 + 60 + 10550;
        step_pair(&in);
        UT_UEQ(g_ob.tlm.m.rendezvous.cmd_rej, 0u);
        UT_TRUE(g_ob.tlm.m.rendezvous.mode != IMP_MODE_IDLE);
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
    UT_UEQ(g_ob.tlm.m.rendezvous.mode, IMP_MODE_PLANNING);      /* START taken at step 4 */
    /* a validated candidate while the plan job runs: it waits (through ARMED and FIRING) */
    g_ip = IMP_TBL_DEFAULT;
    g_ip.miss_flag_q28 = 3 * g_ip.miss_flag_q28;
    UT_UEQ(upload_params(&g_b, &g_ip, 2u, &why), FSW_OK);
    UT_UEQ(g_b.tbl.state, FSW_TBL_S_READY);
    fired = 0u;
    for (k = 5; k <= 120; k++) {
        fsw_in_t in = rdv_frame(k);
        step_pair(&in);
        fired += (g_ob.act_cnt[IMP_ACT_MASK] != 0) ? 1u : 0u;
        UT_CHECK((g_ob.health & FSW_H_TBL_PENDING) != 0u);
        UT_CHECK_UEQ(g_ob.tlm.tbl_revision, 1u);
        UT_CHECK_UEQ(g_ob.tlm.n_tbl_acc, 0u);
        UT_CHECK_UEQ(tlm_diff_but_tables(), 0u);       /* the plan and the firing are untouched */
    }
    UT_UEQ(g_ob.tlm.m.rendezvous.mode, IMP_MODE_FIRING);
    UT_LE(10, fired);                                   /* thrusters really fired meanwhile */
    UT_UEQ(imp_params_diff(&g_b.m.rendezvous.p, &IMP_TBL_DEFAULT, 1), 0u);
    /* a further chunk is BUSY: a state complaint, not a refusal */
    rej = g_ob.tlm.n_tbl_rej;
    UT_UEQ(upload_params(&g_b, &g_ip, 3u, &why), FSW_ERR_STATE);
    UT_UEQ(why & 0xFFu, FSW_TBL_R_BUSY);
    UT_UEQ(g_b.tlm.n_tbl_rej, rej);
    UT_UEQ(g_b.tbl.state, FSW_TBL_S_READY);
    /* ABORT: the scheduler is terminal after this step, the table is committed at the next */
    {
        fsw_in_t in = rdv_frame(121);
        in.tc = TC_ABORT;
        step_pair(&in);
        UT_UEQ(g_ob.tlm.m.rendezvous.mode, IMP_MODE_ABORTED);
        UT_EQ(g_ob.act_cnt[IMP_ACT_MASK], 0);
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
    UT_UEQ(g_ob.tlm.m.rendezvous.revision, 2u);
    UT_UEQ(g_ob.tlm.m.rendezvous.mode, IMP_MODE_IDLE);           /* re-initialised with the new table */
    UT_UEQ(g_oa.tlm.m.rendezvous.mode, IMP_MODE_ABORTED);
    UT_EQ(g_b.m.rendezvous.p.miss_flag_q28, g_ip.miss_flag_q28);
}

UT_TEST(rendezvous_upload_in_standby_commits_at_once)
{
    fsw_cfg_t c = cfg_rdv();
    uint32_t why = 99u;
    fsw_in_t in = nav_frame(0);
    c.boot_mode = FSW_MODE_STANDBY;
    UT_UEQ(boot_imp(&g_a, &c, &IMP_TBL_DEFAULT, 1u), FSW_OK);
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(upload_params(&g_a, &IMP_TBL_SUB1MS, 4u, &why), FSW_OK);
    in = nav_frame(1);
    in.mode_cmd = FSW_MODE_RENDEZVOUS;                  /* committed first, then the entry */
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_RENDEZVOUS);
    UT_UEQ(g_oa.tlm.tbl_revision, 4u);
    UT_UEQ(g_oa.tlm.m.rendezvous.revision, 4u);
    UT_UEQ(g_a.m.rendezvous.p.subtick_us, 1000u);
}

UT_TEST(rendezvous_corrupt_or_vetoed_tables_are_refused_and_nothing_is_lost)
{
    uint32_t why = 0u;
    uint32_t n;
    uint32_t act;
    uint32_t len;
    boot_rdv_pair();
    (void)run_rdv_pair(0, 64);
    UT_UEQ(g_ob.tlm.m.rendezvous.mode, IMP_MODE_FIRING);
    isnap_take(&g_b);
    act = g_b.tbl.active;
    len = g_b.tbl.active_len;
    /* 1. CRC: one payload bit flipped after encoding */
    n = imp_table_encode(&IMP_TBL_DEFAULT, 3u, g_img, sizeof(g_img));
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
    UT_UEQ(g_b.tbl.active, act);
    UT_UEQ(g_b.tbl.active_len, len);
    UT_UEQ(g_b.tbl.state, FSW_TBL_S_IDLE);
    g_ip = IMP_TBL_DEFAULT;
    g_ip.revision = 1u;
    UT_UEQ(imp_params_diff(&g_b.m.rendezvous.p, &g_ip, 1), 0u);
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
            fired += (g_ob.act_cnt[IMP_ACT_MASK] != 0) ? 1u : 0u;
            UT_CHECK_UEQ(tlm_diff_but_tables(), 0u);
        }
        UT_LE(10, fired);
    }
    UT_UEQ(g_ob.tlm.m.rendezvous.mode, IMP_MODE_FIRING);
    UT_TRUE((g_ob.health & FSW_H_TBL_REJ) == 0u);
}

UT_TEST(rendezvous_refuses_a_chunk_for_another_table)
{
    uint32_t why = 0u;
    uint32_t n;
    fsw_cfg_t c = cfg_rdv();
    fsw_in_t in = nav_frame(0);
    UT_UEQ(boot_imp(&g_a, &c, &IMP_TBL_DEFAULT, 1u), FSW_OK);
    fsw_step(&g_a, &in, &g_oa);
    isnap_take(&g_a);
    /* 662 bytes under another table's id (the observer's 0x0B01), in chunks of 100 */
    n = 662u;
    {
        uint32_t off;
        fsw_rc_t rc = FSW_OK;
        for (off = 0u; off < n; off += 100u) {
            fsw_table_chunk_t ch;
            ch.table_id = 0x0B01u;
            ch.revision = 2u;
            ch.total_len = n;
            ch.offset = off;
            ch.n = ((n - off) < 100u) ? (n - off) : 100u;
            ch.data = &g_img[off];
            rc = fsw_table_upload(&g_a, &ch, &why);
        }
        UT_UEQ(rc, FSW_ERR_CHUNK);
    }
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
    UT_UEQ(g_ob.tlm.m.rendezvous.mode, IMP_MODE_FIRING);
    g_b.tbl.img[g_b.tbl.active][FSW_TABLE_HDR_BYTES + 10u] ^= 1u;   /* memory upset */
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
    UT_UEQ(boot_imp(&g_a, &c, &p, 1u), FSW_ERR_RANGE);
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
    UT_UEQ(g_oa.tlm.m.rendezvous.revision, 2u);
    /* the module check: a valid table of another period (PERIOD, detail 1) */
    UT_UEQ(boot_imp(&g_a, &c, &IMP_TBL_1S, 1u), FSW_ERR_INVARIANT);
    UT_UEQ(g_a.tlm.tbl_reason, RW(FSW_TBL_R_MODULE, 1u));
    in = nav_frame(0);
    fsw_step(&g_a, &in, &g_oa);
    UT_UEQ(g_oa.mode, FSW_MODE_SAFE);
    UT_TRUE((g_oa.health & FSW_H_NO_TABLE) != 0u);
    UT_UEQ(g_oa.tlm.tbl_reason, RW(FSW_TBL_R_MODULE, 1u));
    /* ... and plan_lead below the worst plan (LEAD, detail 8) */
    p = IMP_TBL_DEFAULT;
    p.plan_lead = 5u;
    UT_UEQ(boot_imp(&g_a, &c, &p, 1u), FSW_ERR_INVARIANT);
    UT_UEQ(g_a.tlm.tbl_reason, RW(FSW_TBL_R_MODULE, 8u));
    UT_UEQ(g_a.tlm.n_tbl_rej, 1u);
}

int main(void)
{
    UT_CASES(cases) = {
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
    return UT_RUN("imp_mission", cases);
}
