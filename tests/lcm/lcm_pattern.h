/*
 * lcm_pattern.h — deterministic test contents for every gnc LCM type, shared by the C and C++
 * round-trip tests and the cross-language writer. tests/lcm/lcm_xlang_check.py rebuilds the same
 * values in Python, so the generator and the field order here must match that script exactly:
 * fields in declaration order, array elements in index order, one splitmix64 draw each,
 * truncated to the field's width (two's complement). Doubles are exact binary fractions, plus
 * a few special values (-0, smallest subnormal, +inf, -1e308) compared bit for bit.
 */
#ifndef TESTS_LCM_PATTERN_H
#define TESTS_LCM_PATTERN_H

#include <stdint.h>
#include <string.h>

#include "gnc_actuator_cmd_t.h"
#include "gnc_fsw_cmd_t.h"
#include "gnc_fsw_tlm_frame_t.h"
#include "gnc_sensor_frame_t.h"
#include "gnc_sil_ctl_t.h"
#include "gnc_sim_truth_t.h"
#include "gnc_table_ack_t.h"
#include "gnc_table_upload_t.h"
#include "gnc_actuator_cmd_v2_t.h"
#include "gnc_fsw_cmd_v2_t.h"
#include "gnc_sensor_frame_v2_t.h"
#include "gnc_table_upload_v2_t.h"

/* Seeds, one per type (same in lcm_xlang_check.py). */
enum {
    PAT_SEED_SENSOR = 101, PAT_SEED_ACT = 102, PAT_SEED_TLM = 103, PAT_SEED_TRUTH = 104,
    PAT_SEED_UPLOAD = 105, PAT_SEED_ACK = 106, PAT_SEED_CTL = 107, PAT_SEED_CMD = 108,
    PAT_SEED_SENSOR2 = 109, PAT_SEED_ACT2 = 110, PAT_SEED_UPLOAD2 = 111, PAT_SEED_CMD2 = 112
};

static inline uint64_t pat_u64(uint64_t *s)
{
    uint64_t z = (*s += UINT64_C(0x9E3779B97F4A7C15));
    z = (z ^ (z >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94D049BB133111EB);
    return z ^ (z >> 31);
}
static inline int64_t pat_i64(uint64_t *s)
{
    uint64_t u = pat_u64(s);
    int64_t v;
    memcpy(&v, &u, sizeof v);   /* two's complement reinterpretation, no implementation-defined cast */
    return v;
}
static inline int32_t pat_i32(uint64_t *s)
{
    uint32_t u = (uint32_t)(pat_u64(s) & UINT32_C(0xFFFFFFFF));
    int32_t v;
    memcpy(&v, &u, sizeof v);
    return v;
}
static inline int16_t pat_i16(uint64_t *s)
{
    uint16_t u = (uint16_t)(pat_u64(s) & UINT32_C(0xFFFF));
    int16_t v;
    memcpy(&v, &u, sizeof v);
    return v;
}
static inline int8_t pat_i8(uint64_t *s)
{
    uint8_t u = (uint8_t)(pat_u64(s) & UINT32_C(0xFF));
    int8_t v;
    memcpy(&v, &u, sizeof v);
    return v;
}
static inline uint8_t pat_u8(uint64_t *s) { return (uint8_t)(pat_u64(s) & UINT32_C(0xFF)); }
/* Exact in double: a 32-bit integer over 1024. */
static inline double pat_f64(uint64_t *s) { return (double)pat_i32(s) / 1024.0; }

static inline void pat_sensor(gnc_sensor_frame_t *m)
{
    uint64_t s = PAT_SEED_SENSOR;
    int i;
    memset(m, 0, sizeof *m);
    m->utime = pat_i64(&s);
    m->seq = pat_i64(&s);
    m->period_us = pat_i32(&s);
    m->n_counts = pat_i16(&s);
    for (i = 0; i < 16; ++i) { m->counts[i] = pat_i32(&s); }
    for (i = 0; i < 16; ++i) { m->status[i] = pat_i8(&s); }
    m->scenario_flags = pat_i32(&s);
    m->plant_flags = pat_i32(&s);
}

static inline void pat_act(gnc_actuator_cmd_t *m)
{
    uint64_t s = PAT_SEED_ACT;
    int i;
    memset(m, 0, sizeof *m);
    m->utime = pat_i64(&s);
    m->seq = pat_i64(&s);
    m->n_counts = pat_i16(&s);
    for (i = 0; i < 16; ++i) { m->counts[i] = pat_i32(&s); }
    m->fsw_mode = pat_i32(&s);
    m->fsw_health = pat_i32(&s);
}

static inline void pat_tlm(gnc_fsw_tlm_frame_t *m)
{
    uint64_t s = PAT_SEED_TLM;
    int i;
    memset(m, 0, sizeof *m);
    m->utime = pat_i64(&s);
    m->seq = pat_i64(&s);
    m->tlm_layout_version = pat_i32(&s);
    m->tlm_len = pat_i16(&s);
    for (i = 0; i < 512; ++i) { m->tlm[i] = pat_u8(&s); }
    m->dups = pat_i32(&s);
    m->stale = pat_i32(&s);
    m->gaps = pat_i32(&s);
    m->rejected = pat_i32(&s);
    m->nonfinite_rej = pat_i32(&s);
    m->range_rej = pat_i32(&s);
    m->missed = pat_i32(&s);
    m->table_rej = pat_i32(&s);
}

static inline void pat_truth(gnc_sim_truth_t *m)
{
    uint64_t s = PAT_SEED_TRUTH;
    int i;
    uint64_t bits;
    memset(m, 0, sizeof *m);
    m->utime = pat_i64(&s);
    m->seq = pat_i64(&s);
    for (i = 0; i < 16; ++i) { m->state[i] = pat_f64(&s); }
    for (i = 0; i < 8; ++i) { m->extra[i] = pat_f64(&s); }
    /* Special values, set by bit pattern (no float literals that could round differently). */
    bits = UINT64_C(0x8000000000000000); memcpy(&m->extra[0], &bits, sizeof bits);  /* -0.0 */
    bits = UINT64_C(0x0000000000000001); memcpy(&m->extra[1], &bits, sizeof bits);  /* 2^-1074 */
    bits = UINT64_C(0x7FF0000000000000); memcpy(&m->extra[2], &bits, sizeof bits);  /* +inf */
    bits = UINT64_C(0xFFEBCCA8F4D0C3E2); memcpy(&m->extra[3], &bits, sizeof bits);  /* large negative finite (about -1.56e308) */
    m->events = pat_i32(&s);
}

static inline void pat_upload(gnc_table_upload_t *m)
{
    uint64_t s = PAT_SEED_UPLOAD;
    int i;
    memset(m, 0, sizeof *m);
    m->utime = pat_i64(&s);
    m->table_id = pat_i32(&s);
    m->revision = pat_i32(&s);
    m->total_len = pat_i32(&s);
    m->offset = pat_i32(&s);
    m->n = pat_i16(&s);
    for (i = 0; i < 256; ++i) { m->data[i] = pat_u8(&s); }
}

static inline void pat_ack(gnc_table_ack_t *m)
{
    uint64_t s = PAT_SEED_ACK;
    memset(m, 0, sizeof *m);
    m->utime = pat_i64(&s);
    m->table_id = pat_i32(&s);
    m->revision = pat_i32(&s);
    m->result = pat_i32(&s);
    m->reason = pat_i32(&s);
    m->bytes_received = pat_i32(&s);
}

static inline void pat_ctl(gnc_sil_ctl_t *m)
{
    uint64_t s = PAT_SEED_CTL;
    int i;
    memset(m, 0, sizeof *m);
    m->utime = pat_i64(&s);
    m->command = pat_i32(&s);
    for (i = 0; i < 32; ++i) { m->scenario[i] = pat_u8(&s); }
    m->seed = pat_i64(&s);
    m->node_id = pat_i32(&s);
    m->status = pat_i32(&s);
}

static inline void pat_cmd(gnc_fsw_cmd_t *m)
{
    uint64_t s = PAT_SEED_CMD;
    int i;
    memset(m, 0, sizeof *m);
    m->utime = pat_i64(&s);
    m->apply_seq = pat_i64(&s);
    m->cmd = pat_i32(&s);
    for (i = 0; i < 8; ++i) { m->args[i] = pat_i32(&s); }
}

/* Encoded sizes (8-byte fingerprint + big-endian fields). Pinned: a change means a layout change. */
/* The v2 types (issue 18): the v1 fields in order, then crc32 as one more draw. The pattern does
 * not seal the message: these tests check the bindings, the bridge tests check the seal. */
static inline void pat_sensor2(gnc_sensor_frame_v2_t *m)
{
    uint64_t s = PAT_SEED_SENSOR2;
    int i;
    memset(m, 0, sizeof *m);
    m->utime = pat_i64(&s);
    m->seq = pat_i64(&s);
    m->period_us = pat_i32(&s);
    m->n_counts = pat_i16(&s);
    for (i = 0; i < 16; ++i) { m->counts[i] = pat_i32(&s); }
    for (i = 0; i < 16; ++i) { m->status[i] = pat_i8(&s); }
    m->scenario_flags = pat_i32(&s);
    m->plant_flags = pat_i32(&s);
    m->crc32 = pat_i32(&s);
}

static inline void pat_act2(gnc_actuator_cmd_v2_t *m)
{
    uint64_t s = PAT_SEED_ACT2;
    int i;
    memset(m, 0, sizeof *m);
    m->utime = pat_i64(&s);
    m->seq = pat_i64(&s);
    m->n_counts = pat_i16(&s);
    for (i = 0; i < 16; ++i) { m->counts[i] = pat_i32(&s); }
    m->fsw_mode = pat_i32(&s);
    m->fsw_health = pat_i32(&s);
    m->crc32 = pat_i32(&s);
}

static inline void pat_upload2(gnc_table_upload_v2_t *m)
{
    uint64_t s = PAT_SEED_UPLOAD2;
    int i;
    memset(m, 0, sizeof *m);
    m->utime = pat_i64(&s);
    m->table_id = pat_i32(&s);
    m->revision = pat_i32(&s);
    m->total_len = pat_i32(&s);
    m->offset = pat_i32(&s);
    m->n = pat_i16(&s);
    for (i = 0; i < 256; ++i) { m->data[i] = pat_u8(&s); }
    m->crc32 = pat_i32(&s);
}

static inline void pat_cmd2(gnc_fsw_cmd_v2_t *m)
{
    uint64_t s = PAT_SEED_CMD2;
    int i;
    memset(m, 0, sizeof *m);
    m->utime = pat_i64(&s);
    m->apply_seq = pat_i64(&s);
    m->cmd = pat_i32(&s);
    for (i = 0; i < 8; ++i) { m->args[i] = pat_i32(&s); }
    m->crc32 = pat_i32(&s);
}

#define PAT_SIZE_SENSOR 118
#define PAT_SIZE_ACT     98
#define PAT_SIZE_TLM    574
#define PAT_SIZE_TRUTH  220
#define PAT_SIZE_UPLOAD 290
#define PAT_SIZE_ACK     36
#define PAT_SIZE_CTL     68
#define PAT_SIZE_CMD     60
#define PAT_SIZE_SENSOR2 122   /* the v2 types: + int32 crc32 */
#define PAT_SIZE_ACT2    102
#define PAT_SIZE_UPLOAD2 294
#define PAT_SIZE_CMD2     64
#define PAT_SIZE_MAX    574

#endif /* TESTS_LCM_PATTERN_H */
