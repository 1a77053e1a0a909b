/*
 * fx_crc.c — CRC-32 (zlib/IEEE 802.3, reflected, polynomial 0xEDB88320, init and final XOR
 * 0xFFFFFFFF; check value 0xCBF43926 for "123456789"), so Python's zlib.crc32 is an
 * independent oracle. A 16-entry nibble table keeps rodata at 64 bytes with two lookups per
 * byte; the loop is bounded by len.
 */
#include "fx.h"

uint32_t fx_crc32(uint32_t crc, const uint8_t *data, size_t len)
{
    /* Read-only table at block scope (MISRA 8.9): .rodata, no state. */
    static const uint32_t crc_nibble[16] = {
        0x00000000u, 0x1DB71064u, 0x3B6E20C8u, 0x26D930ACu, 0x76DC4190u, 0x6B6B51F4u,
        0x4DB26158u, 0x5005713Cu, 0xEDB88320u, 0xF00F9344u, 0xD6D6A3E8u, 0xCB61B38Cu,
        0x9B64C2B0u, 0x86D3D2D4u, 0xA00AE278u, 0xBDBDF21Cu,
    };
    uint32_t c = ~crc;
    size_t i;
    for (i = 0u; i < len; i++) {
        c ^= (uint32_t)data[i];
        c = (c >> 4) ^ crc_nibble[c & 0x0Fu];
        c = (c >> 4) ^ crc_nibble[c & 0x0Fu];
    }
    return ~c;
}
