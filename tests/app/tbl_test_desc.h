/*
 * Test table 0x7E57, layout 3: the descriptor the table tests load against. It stands in for a
 * generated limits table (spec 00 §3.2); tools/table/mktable.py describes the same layout
 * independently (TEST_LAYOUT) for the oracle test.
 *
 *  idx off type  name        [min, max]            boot value
 *   0   0  u8    mode        [0, 3]                2
 *   1   1  u8    enable      [0, 1]                1
 *   2   2  u16   period_ms   [1, 1000]             200
 *   3   4  u32   stale_max   [1, 1000]             16
 *   4   8  i32   gain_q16    [-262144, 262144]     -100
 *   5  12  i32   quant_q16   [0, 1000]             64
 *   6  16  i32   hyst_q16    [0, 100000]           1000
 *   7  20  u32   max_count   [10, 4000000000]      1234
 * relations: 0: quant + 2 <= hyst (hysteresis exceeds quantisation by 2 LSB)
 *            1: stale_max + 1 <= max_count
 */
#ifndef TESTS_APP_TBL_TEST_DESC_H
#define TESTS_APP_TBL_TEST_DESC_H

#include "app/fsw_table.h"

#define TT_ID        0x7E57u
#define TT_VERSION   3u
#define TT_PAYLOAD   24u
#define TT_TOTAL     (FSW_TABLE_HDR_BYTES + TT_PAYLOAD)

typedef struct {
    uint8_t mode;
    uint8_t enable;
    uint16_t period_ms;
    uint32_t stale_max;
    int32_t gain_q16;
    int32_t quant_q16;
    int32_t hyst_q16;
    uint32_t max_count;
} tt_params_t;

extern const fsw_table_desc_t tt_desc;

void tt_defaults(tt_params_t *p);
/* Encodes p field by field with the codec; returns the image length (0 if cap too small). */
uint32_t tt_build(uint8_t *img, uint32_t cap, const tt_params_t *p, uint16_t id,
                  uint16_t version, uint32_t revision);
/* Recomputes the header CRC over the length the header claims (clamped to the image). */
void tt_fix_crc(uint8_t *img, uint32_t total);

#endif
