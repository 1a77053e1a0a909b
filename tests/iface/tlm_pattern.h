/*
 * tlm_pattern.h — the value pattern of the telemetry layout test (tests/iface): field i of a
 * layout holds splitmix64(i + 1) cut to its wire type, so neighbouring fields never hold the same
 * bytes and a field read at a wrong offset or with a wrong type shows. tlm_layout_check.py
 * computes the same values in Python. Host test code only.
 */
#ifndef TLM_PATTERN_H
#define TLM_PATTERN_H

#include <stdint.h>
#include <string.h>

#include "fsw_exec.h"

static inline uint64_t tlm_pat_u64(uint32_t i)
{
    uint64_t z = ((uint64_t)i + 1u) * UINT64_C(0x9E3779B97F4A7C15);
    z = (z ^ (z >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94D049BB133111EB);
    return z ^ (z >> 31);
}
static inline uint8_t tlm_pat_u8(uint32_t i) { return (uint8_t)(tlm_pat_u64(i) & 0xFFu); }
static inline uint16_t tlm_pat_u16(uint32_t i) { return (uint16_t)(tlm_pat_u64(i) & 0xFFFFu); }
static inline uint32_t tlm_pat_u32(uint32_t i) { return (uint32_t)(tlm_pat_u64(i) & 0xFFFFFFFFu); }
/* two's complement reinterpretation without an implementation-defined conversion */
static inline int32_t tlm_pat_i32(uint32_t i)
{
    uint32_t u = tlm_pat_u32(i);
    int32_t v;
    memcpy(&v, &u, sizeof v);
    return v;
}
static inline int64_t tlm_pat_i64(uint32_t i)
{
    uint64_t u = tlm_pat_u64(i);
    int64_t v;
    memcpy(&v, &u, sizeof v);
    return v;
}

#ifdef __cplusplus
extern "C" {
#endif
/* Generated (tools/iface/gen_build.py tlm_pattern): field i of the mission's layout = pattern(i). */
void tlm_pattern_fill(fsw_tlm_t *t, uint32_t mission);
#ifdef __cplusplus
}
#endif

#endif
