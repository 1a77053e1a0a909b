/*
 * fsw_pil.h — the PIL/HIL session over the serial link (spec 00 §6.1): the payload of every packet
 * type, and the board's side of the protocol. One source for the host bridge and the board image.
 *
 * The framing (COBS, CRC-32, the byte-at-a-time decoder) is fsw_link.h. This file gives each
 * packet type its payload, little-endian, field by field through fsw_codec (layouts below and in
 * FSW_PIL_LAYOUT, whose CRC-32 is HELLO's layout hash), and runs the board: the board image's main
 * loop feeds every UART byte to fsw_pil_board_rx() and sends whatever it queues in b->tx.
 *
 * Session (host = the bridge's `pil` backend, board = this code on the target):
 *   board            sends HELLO at start (and again on a host HELLO, whose payload is empty, which
 *                    also starts a new session: not booted, staging and caches forgotten)
 *   host -> board    TABLE_CHUNK*  the boot image, staged in order (TABLE_ACK PARTIAL / ACCEPTED)
 *   host -> board    BOOT          the executive's configuration and the staged image's length
 *                                  and CRC: fsw_init; BOOT_ACK carries its verdict and the
 *                                  channel ranges (the bridge's sensor limits)
 *   host -> board    SENSOR k      fsw_in_t (mode command, telecommand and host counters ride in
 *                                  it: one packet per step, so a step's inputs arrive whole)
 *   board -> host    [LIMITS k]    the new channel ranges, when step k committed a table
 *                    CMD k, TLM k  the actuator counts and the encoded telemetry (+ instructions)
 *   host -> board    TABLE_CHUNK   an upload while flying: fsw_table_upload, TABLE_ACK
 *   host -> board    LINK_STATS    (empty) -> board replies LINK_STATS with its counters
 *   host -> board    PING          -> PONG with the same payload
 *   host -> board    MODE_CMD END  -> MODE_CMD echoed, then the board ends the session (QEMU: exit 0
 *                                  after the stack-canary check; a real board resets)
 *   host -> board    MODE_CMD RESET-> MODE_CMD echoed, then the board resets (fault injection: the
 *                                  host must detect the restarted board by its unsolicited HELLO)
 * The board applies the bridge's sequence rules (spec 00 §5.2) to SENSOR's fsw_in_t.seq (the link seq,
 * k mod 2^16, only ties replies to requests):
 * seq == last -> the cached replies of step last again, without stepping (a host retransmission
 * after a lost CMD/TLM); seq newer -> step; seq older -> dropped and counted (stale). A TABLE_CHUNK
 * with the seq of the last one answered gets the same TABLE_ACK again, not applied twice. Anything
 * the board cannot take is answered with ERROR (code, offending type, detail; the offending
 * frame's seq) and counted; the
 * executive and the session keep running on their last good state.
 *
 * No heap, no globals: fsw_pil_board_t is the caller's (the board image holds one statically;
 * the host test harness allocates one). Its size is dominated by fsw_t.
 */
#ifndef FSW_APP_PIL_H
#define FSW_APP_PIL_H

#include <stdint.h>
#include <stdbool.h>

#include "fsw_exec.h"
#include "fsw_link.h"

/* Packet types beyond spec 00 §6.1's list (fsw_link.h numbers 1..11). */
#define FSW_PIL_T_BOOT      FSW_LINK_T_BOOT
#define FSW_PIL_T_BOOT_ACK  FSW_LINK_T_BOOT_ACK
#define FSW_PIL_T_LIMITS    FSW_LINK_T_LIMITS

/* Board ids in HELLO. */
#define FSW_PIL_BOARD_HOST   0x0001u   /* the host harness (the board session compiled for the host) */
#define FSW_PIL_BOARD_AN385  0x0385u   /* QEMU mps2-an385, Cortex-M3 */
#define FSW_PIL_BOARD_AN386  0x0386u   /* QEMU mps2-an386, Cortex-M4 */

/* Payload sizes (bytes). */
#define FSW_PIL_HELLO_BYTES       16u
#define FSW_PIL_SENSOR_BYTES     148u
#define FSW_PIL_CMD_BYTES         88u
#define FSW_PIL_TLM_HEAD_BYTES     8u   /* insn, layout; the encoded telemetry follows */
#define FSW_PIL_TLM_MAX          (FSW_LINK_MAX_PAYLOAD - FSW_PIL_TLM_HEAD_BYTES)   /* 504 */
#define FSW_PIL_CHUNK_HEAD_BYTES  16u   /* + n data bytes */
#define FSW_PIL_ACK_BYTES         16u
#define FSW_PIL_BOOT_BYTES        24u
#define FSW_PIL_RANGES_HEAD_BYTES  4u   /* n, then n x (min, max) */
#define FSW_PIL_BOOT_ACK_HEAD_BYTES 12u /* rc, reason, limits generation, then the ranges */
#define FSW_PIL_STATS_BYTES       84u
#define FSW_PIL_PING_MAX          32u
#define FSW_PIL_ERROR_BYTES        8u

/* TABLE_ACK result (the bridge's table_ack_t RESULT_* values). */
#define FSW_PIL_ACK_ACCEPTED 0u   /* complete and validated: active at the first step its commit rule allows */
#define FSW_PIL_ACK_PARTIAL  1u
#define FSW_PIL_ACK_REJECTED 2u

/* BOOT_ACK rc: fsw_init's fsw_rc_t (FSW_OK = 0), or one of these (negative: the boot was not tried). */
#define FSW_PIL_BOOT_BAD_IMAGE  (-100)   /* staged length or CRC differs from BOOT's */
#define FSW_PIL_BOOT_BAD_CFG    (-101)   /* BOOT's configuration fields out of range */

/* ERROR codes. */
#define FSW_PIL_E_LEN        1u   /* payload length wrong for its type (detail: the length) */
#define FSW_PIL_E_NOT_BOOTED 2u   /* SENSOR before a successful BOOT */
#define FSW_PIL_E_TYPE       3u   /* a type the board never receives (CMD, TLM, ...) */
#define FSW_PIL_E_STAGE      4u   /* a boot-image chunk out of order or beyond the buffer (staging restarts) */
#define FSW_PIL_E_TLM_SIZE   5u   /* the telemetry does not fit a TLM packet (detail: its length) */
#define FSW_PIL_E_FIELD      6u   /* a field out of range (detail: its payload offset) */

/* A SENSOR payload is fsw_in_t, always with FSW_IN_MAX channels. */
void fsw_pil_wr_sensor(fsw_wr_t *w, const fsw_in_t *in);
bool fsw_pil_rd_sensor(fsw_rd_t *r, fsw_in_t *in);   /* false: n_counts > FSW_IN_MAX or short */

/* CMD: seq (i64), mode, health, n_act, act_cnt[FSW_ACT_MAX], lim_gen. lim_gen counts the channel-range
   changes the board has reported (BOOT_ACK carries its value at boot): a CMD whose lim_gen moved
   without its LIMITS frame tells the host that frame was lost, and it asks for the step's replies
   again (the board re-sends LIMITS with them). */
typedef struct {
    int64_t  seq;
    uint32_t mode;
    uint32_t health;
    uint32_t n_act;
    int32_t  act_cnt[FSW_ACT_MAX];
    uint32_t lim_gen;
} fsw_pil_cmd_t;
void fsw_pil_wr_cmd(fsw_wr_t *w, const fsw_pil_cmd_t *c);
bool fsw_pil_rd_cmd(fsw_rd_t *r, fsw_pil_cmd_t *c);  /* false: n_act > FSW_ACT_MAX or short */

/* HELLO: version (u8), 0 (u8), board id (u16), layout hash, build id, missions (bit m = FSW_MISSION m configured). */
typedef struct {
    uint8_t  version;
    uint16_t board_id;
    uint32_t layout_hash;
    uint32_t build_id;
    uint32_t missions;
} fsw_pil_hello_t;
void fsw_pil_wr_hello(fsw_wr_t *w, const fsw_pil_hello_t *h);
bool fsw_pil_rd_hello(fsw_rd_t *r, fsw_pil_hello_t *h);

/* TABLE_CHUNK: table_id (u16), n (u16), revision, total_len, offset, data[n]. */
void fsw_pil_wr_chunk(fsw_wr_t *w, const fsw_table_chunk_t *c);
/* data points into the reader's buffer. false: n = 0, n > FSW_TABLE_CHUNK_MAX, or short. */
bool fsw_pil_rd_chunk(fsw_rd_t *r, fsw_table_chunk_t *c);

/* TABLE_ACK: table_id (u16), result (u16), revision, reason, bytes_received. */
typedef struct {
    uint16_t table_id;
    uint16_t result;          /* FSW_PIL_ACK_* */
    uint32_t revision;
    uint32_t reason;          /* loader reason word (low 16 bits meaningful), 0 unless REJECTED */
    uint32_t bytes_received;
} fsw_pil_ack_t;
void fsw_pil_wr_ack(fsw_wr_t *w, const fsw_pil_ack_t *a);
bool fsw_pil_rd_ack(fsw_rd_t *r, fsw_pil_ack_t *a);

/* BOOT: mission, period_us, stale_max (u16), 0 (u16), boot_mode, image_len, image_crc (fx_crc32 of the
   staged image; 0 with image_len 0 = boot without a table). */
typedef struct {
    fsw_cfg_t cfg;
    uint32_t  image_len;
    uint32_t  image_crc;
} fsw_pil_boot_t;
void fsw_pil_wr_boot(fsw_wr_t *w, const fsw_pil_boot_t *b);
bool fsw_pil_rd_boot(fsw_rd_t *r, fsw_pil_boot_t *b);

/* Channel ranges (LIMITS, and the tail of BOOT_ACK): n (u32 <= FSW_IN_MAX), n x (min i32, max i32). */
void fsw_pil_wr_ranges(fsw_wr_t *w, const fsw_range_t *rng, uint32_t n);
bool fsw_pil_rd_ranges(fsw_rd_t *r, fsw_range_t *rng, uint32_t *n);

/* The table-upload verdict both backends give (the bridge's TableAck): one chunk into the executive. */
void fsw_pil_table_chunk(fsw_t *f, const fsw_table_chunk_t *c, fsw_pil_ack_t *ack);

/* LINK_STATS: the decoder's counters, then the board's. */
typedef struct {
    fsw_link_stats_t rx;
    uint32_t steps;          /* SENSOR packets stepped */
    uint32_t dups;           /* SENSOR seq == last: cached replies re-sent */
    uint32_t stale;          /* SENSOR seq older than last: dropped */
    uint32_t errors;         /* ERROR packets sent */
    uint32_t boots;          /* BOOTs tried */
    uint32_t tx_frames;      /* frames queued for sending */
    uint32_t uart_overruns;  /* the board driver's RX overruns (0 on the host harness) */
    uint32_t stack_used;     /* the board's painted stack high-water mark, bytes (0: unknown) */
    uint32_t stack_size;     /* its stack region, bytes */
    uint32_t insn_max;       /* most SysTick-bracket instructions of one fsw_step so far */
    uint32_t reserved;
} fsw_pil_stats_t;
void fsw_pil_wr_stats(fsw_wr_t *w, const fsw_pil_stats_t *s);
bool fsw_pil_rd_stats(fsw_rd_t *r, fsw_pil_stats_t *s);

/* ERROR: code (u16), the offending packet's type (u16), detail (u32). */
typedef struct {
    uint16_t code;
    uint16_t type;
    uint32_t detail;
} fsw_pil_error_t;
void fsw_pil_wr_error(fsw_wr_t *w, const fsw_pil_error_t *e);
bool fsw_pil_rd_error(fsw_rd_t *r, fsw_pil_error_t *e);

/* The layout hash: CRC-32 of FSW_PIL_LAYOUT (the canonical description of every payload above and
   the link header), so two builds that would read each other's bytes differently refuse to talk. */
uint32_t fsw_pil_layout_hash(void);
/* Bit m set for every mission configured in this build. */
uint32_t fsw_pil_missions(void);

/* ------------------------------------------------------------------ the board's side */

/* Queued output: the replies to the last input, sent by the caller (fsw_pil_board_sent). */
#define FSW_PIL_TX_CAP (4u * FSW_LINK_MAX_WIRE)
#define FSW_PIL_ACK_WIRE 32u   /* a TABLE_ACK frame on the wire: 26-byte body, COBS, delimiter */

typedef enum {
    FSW_PIL_RX_NONE = 0,     /* nothing to do (byte absorbed) */
    FSW_PIL_RX_SEND = 1,     /* replies queued in b->tx[0 .. b->tx_len): send them */
    FSW_PIL_RX_STEP = 2,     /* a SENSOR to step: call fsw_pil_board_step, then _finish (then send) */
    FSW_PIL_RX_END = 3,      /* MODE_CMD END: send the queued ack, then end the session (exit/reset) */
    FSW_PIL_RX_RESET = 4     /* MODE_CMD RESET: send the queued ack, then reset the board */
} fsw_pil_rx_t;

/* MODE_CMD payload: u32 op. Flight modes never ride here (they are fsw_in_t.mode_cmd in SENSOR). */
#define FSW_PIL_MODE_END 1u   /* end of run: the board acks (MODE_CMD echoed) and ends the session */
#define FSW_PIL_MODE_RESET 2u /* fault injection: the board acks, then resets (a board reset mid-run, spec 00 §8) */

typedef struct {
    fsw_t            fsw;                          /* the executive and its mission */
    fsw_in_t         in;                           /* the step's input (decoded SENSOR) */
    int64_t          last_in_seq;                  /* fsw_in_t.seq of the last stepped SENSOR */
    fsw_out_t        out;
    fsw_link_dec_t   dec;
    fsw_pil_stats_t  st;
    uint8_t          stage[FSW_TABLE_CAP_BYTES];   /* the boot image, staged before BOOT */
    uint8_t          pay[FSW_LINK_MAX_PAYLOAD];    /* scratch payload */
    uint8_t          tx[FSW_PIL_TX_CAP];           /* queued frames */
    uint8_t          cache[FSW_PIL_TX_CAP];        /* step last's replies, re-sent on a duplicate */
    uint8_t          ack_wire[FSW_PIL_ACK_WIRE];   /* the last TABLE_ACK, re-sent on a re-sent chunk */
    uint32_t         stage_got;                    /* contiguous bytes staged */
    uint32_t         tx_len;
    uint32_t         cache_len;
    uint32_t         tbl_acc_seen;                 /* n_tbl_acc when ranges were last sent */
    uint32_t         lim_gen;                      /* LIMITS frames sent since boot (CMD.lim_gen) */
    uint32_t         ack_len;
    uint32_t         build_id;
    uint16_t         board_id;
    uint16_t         last_seq;                     /* link seq of the last stepped SENSOR */
    uint16_t         tx_seq;                       /* seq of board-initiated packets (HELLO) */
    uint16_t         ack_seq;                      /* seq of the chunk ack_wire answers */
    bool             booted;                       /* a BOOT has run fsw_init (whatever its verdict) */
    bool             have_last;
    bool             have_ack;
} fsw_pil_board_t;

/* Resets the session (not booted) and queues HELLO. */
void fsw_pil_board_init(fsw_pil_board_t *b, uint16_t board_id, uint32_t build_id);
/* One received byte. */
fsw_pil_rx_t fsw_pil_board_rx(fsw_pil_board_t *b, uint8_t byte);
/* fsw_step on the decoded SENSOR, nothing else (the board brackets this call with SysTick). */
void fsw_pil_board_step(fsw_pil_board_t *b);
/* Queues [LIMITS], CMD and TLM of the step just run (insn: its instruction count, 0 if unknown)
   and keeps them for a duplicate. */
void fsw_pil_board_finish(fsw_pil_board_t *b, uint32_t insn);
/* The caller has sent b->tx: empties the queue. */
void fsw_pil_board_sent(fsw_pil_board_t *b);

#endif /* FSW_APP_PIL_H */
