/*
 * fx_rc.h — result codes of every flight entry point (spec 00 §3.1): the executive, the table
 * loader and the algorithm modules. They live in fsw/fx, the bottom layer, so a module header
 * needs nothing from fsw/app (fx.h includes this file).
 *
 * fsw_rc_t is a plain uint32_t rather than an enum: MISRA C:2012 gives enums their own
 * essential type, so every comparison or store into a telemetry word would need a cast. The
 * codes name the class of failure; the detailed reason of a table rejection (which check,
 * which field) is the separate reason word of fsw_table.h.
 */
#ifndef FSW_FX_RC_H
#define FSW_FX_RC_H

#include <stdint.h>

typedef uint32_t fsw_rc_t;

#define FSW_OK             0u  /* success */
#define FSW_ERR_ARG        1u  /* null pointer or argument outside its documented range */
#define FSW_ERR_STATE      2u  /* call not allowed in the current state (e.g. loader busy) */
#define FSW_ERR_CHUNK      3u  /* upload chunk inconsistent: offset, size, overlap, upload id */
#define FSW_ERR_INCOMPLETE 4u  /* upload ended with bytes missing */
#define FSW_ERR_DECODE     5u  /* image too short, or header length disagrees with the image */
#define FSW_ERR_CRC        6u  /* CRC-32 of the payload does not match */
#define FSW_ERR_HEADER     7u  /* table id, layout version or payload length not as expected */
#define FSW_ERR_RANGE      8u  /* a parameter lies outside its [min, max] */
#define FSW_ERR_INVARIANT  9u  /* a cross-field invariant does not hold */

#endif /* FSW_FX_RC_H */
