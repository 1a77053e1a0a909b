/*
 * lcm_types.h — one table of the gnc LCM types for the C tests: generic fill / encode / decode
 * entry points (thin wrappers, so no function-pointer casts), pinned encoded sizes and pinned
 * fingerprints. The fingerprint is the first 8 bytes of every encoded message; it changes when a
 * field is renamed, reordered or retyped, and recorded logs then stop decoding. A failing pin
 * means a layout change: make a new ..._v2_t type instead (hil_host/lcmtypes/README.md).
 */
#ifndef TESTS_LCM_TYPES_H
#define TESTS_LCM_TYPES_H

#include "lcm_pattern.h"

typedef struct {
    const char *name;         /* type name, also the channel used by the log tests */
    size_t size;              /* sizeof the C struct */
    int encoded_len;          /* pinned encoded size */
    uint64_t fingerprint;     /* pinned fingerprint (first 8 bytes, big-endian) */
    void (*fill)(void *m);
    int (*enc)(void *buf, int off, int maxlen, const void *m);
    int (*dec)(const void *buf, int off, int maxlen, void *m);
    int (*size_of)(const void *m);
} lcm_type_ops_t;

#define LCM_TYPE_OPS_(T, PAT) \
    static inline void fill_##T(void *m) { PAT((gnc_##T *)m); } \
    static inline int enc_##T(void *b, int o, int l, const void *m) \
    { return gnc_##T##_encode(b, o, l, (const gnc_##T *)m); } \
    static inline int dec_##T(const void *b, int o, int l, void *m) \
    { return gnc_##T##_decode(b, o, l, (gnc_##T *)m); } \
    static inline int size_##T(const void *m) { return gnc_##T##_encoded_size((const gnc_##T *)m); }

LCM_TYPE_OPS_(sensor_frame_t, pat_sensor)
LCM_TYPE_OPS_(actuator_cmd_t, pat_act)
LCM_TYPE_OPS_(fsw_tlm_frame_t, pat_tlm)
LCM_TYPE_OPS_(sim_truth_t, pat_truth)
LCM_TYPE_OPS_(table_upload_t, pat_upload)
LCM_TYPE_OPS_(table_ack_t, pat_ack)
LCM_TYPE_OPS_(sil_ctl_t, pat_ctl)
LCM_TYPE_OPS_(fsw_cmd_t, pat_cmd)
LCM_TYPE_OPS_(sensor_frame_v2_t, pat_sensor2)
LCM_TYPE_OPS_(actuator_cmd_v2_t, pat_act2)
LCM_TYPE_OPS_(table_upload_v2_t, pat_upload2)
LCM_TYPE_OPS_(fsw_cmd_v2_t, pat_cmd2)

#define LCM_TYPE_ROW_(T, LEN, FP) \
    { #T, sizeof(gnc_##T), (LEN), UINT64_C(FP), fill_##T, enc_##T, dec_##T, size_##T }

static const lcm_type_ops_t lcm_types[] = {
    LCM_TYPE_ROW_(sensor_frame_t,  PAT_SIZE_SENSOR, 0x2007310CAFDB75DB),
    LCM_TYPE_ROW_(actuator_cmd_t,  PAT_SIZE_ACT,    0x91B1605F333ADD28),
    LCM_TYPE_ROW_(fsw_tlm_frame_t, PAT_SIZE_TLM,    0xDD346439E2C1E12C),
    LCM_TYPE_ROW_(sim_truth_t,     PAT_SIZE_TRUTH,  0x6DFE66BB58A529BD),
    LCM_TYPE_ROW_(table_upload_t,  PAT_SIZE_UPLOAD, 0x761968F3BDEBD216),
    LCM_TYPE_ROW_(table_ack_t,     PAT_SIZE_ACK,    0x7E7B615B9FBCBA38),
    LCM_TYPE_ROW_(sil_ctl_t,       PAT_SIZE_CTL,    0x937B516171D38092),
    LCM_TYPE_ROW_(fsw_cmd_t,       PAT_SIZE_CMD,    0x20B66D8B1E07C406),
    LCM_TYPE_ROW_(sensor_frame_v2_t, PAT_SIZE_SENSOR2, 0xE4917BD4F34CE046),
    LCM_TYPE_ROW_(actuator_cmd_v2_t, PAT_SIZE_ACT2,    0xD97AC35854DEC6A4),
    LCM_TYPE_ROW_(table_upload_v2_t, PAT_SIZE_UPLOAD2, 0x59352703DF03CECF),
    LCM_TYPE_ROW_(fsw_cmd_v2_t,      PAT_SIZE_CMD2,    0xC5754E1E1F923ED4),
};
#define LCM_N_TYPES (sizeof lcm_types / sizeof lcm_types[0])

/* Largest C struct (fsw_tlm_frame_t), for static scratch objects. */
typedef union {
    gnc_sensor_frame_t a; gnc_actuator_cmd_t b; gnc_fsw_tlm_frame_t c; gnc_sim_truth_t d;
    gnc_table_upload_t e; gnc_table_ack_t f; gnc_sil_ctl_t g; gnc_fsw_cmd_t h;
    gnc_sensor_frame_v2_t i; gnc_actuator_cmd_v2_t j; gnc_table_upload_v2_t k; gnc_fsw_cmd_v2_t l;
} lcm_any_t;

static inline uint64_t lcm_be64(const uint8_t *p)
{
    uint64_t v = 0;
    int i;
    for (i = 0; i < 8; ++i) { v = (v << 8) | p[i]; }
    return v;
}

#endif /* TESTS_LCM_TYPES_H */
