/*
 * fuzz_link_decoder — the serial link's byte-at-a-time decoder (fsw/app/fsw_link.c) on arbitrary
 * byte streams (spec 00 §8: "byte stream → decoder → packet parser").
 *
 * Properties, checked on every input (a violation traps):
 *  - no crash, no out-of-bounds access (ASan/UBSan in the libFuzzer build);
 *  - an accepted frame re-encodes (fsw_link_encode) to exactly the bytes it arrived as;
 *  - a byte that is not a delimiter never completes a frame;
 *  - counters: bytes == input size, and frames + every error kind == the non-empty runs;
 *  - an accepted frame's type and length are in range.
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "fsw_link.h"

static fsw_link_dec_t s_dec;
static uint8_t s_run[FSW_LINK_MAX_COBS];
static uint8_t s_wire[FSW_LINK_MAX_WIRE];

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    size_t i;
    uint32_t rn = 0u;
    uint32_t runs = 0u;
    const fsw_link_stats_t *st = &s_dec.st;
    fsw_link_dec_init(&s_dec);
    for (i = 0u; i < size; i++) {
        uint8_t b = data[i];
        bool ok = fsw_link_rx_byte(&s_dec, b);
        if (b != 0u) {
            if (ok) {
                __builtin_trap();
            }
            if (rn < FSW_LINK_MAX_COBS) {
                s_run[rn] = b;
            }
            rn++;
        } else {
            if (rn > 0u) {
                runs++;
            }
            if (ok) {
                uint32_t m;
                if ((s_dec.frame.len > FSW_LINK_MAX_PAYLOAD) || (s_dec.frame.type == 0u) ||
                    (s_dec.frame.type > FSW_LINK_T_MAX) || (rn > FSW_LINK_MAX_COBS)) {
                    __builtin_trap();
                }
                m = fsw_link_encode(s_dec.frame.type, s_dec.frame.seq, s_dec.frame.payload, s_dec.frame.len,
                                    s_wire, FSW_LINK_MAX_WIRE);
                if ((m != (rn + 1u)) || (memcmp(s_wire, s_run, rn) != 0) || (s_wire[rn] != 0u)) {
                    __builtin_trap();
                }
            }
            rn = 0u;
        }
    }
    if ((st->bytes != (uint32_t)size) ||
        ((st->frames + st->err_oversize + st->err_cobs + st->err_short + st->err_len + st->err_crc +
          st->err_version + st->err_type) != runs)) {
        __builtin_trap();
    }
    return 0;
}
