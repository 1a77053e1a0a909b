/*
 * fsw_pil_board.c — the board's side of the PIL session (fsw_pil.h, spec 00 §6.1): boot from a
 * host-sent configuration and staged image, the bridge's sequence rules with the duplicate cache,
 * uploads, diagnostics. The payload codecs are fsw_pil.c.
 */
#include "fsw_pil.h"
#include "fsw_codec.h"
#include "fsw_missions_gen.h"
#include "fx.h"

/* Appends one frame to the transmit queue (and to the duplicate cache when cache is true). */
static void board_queue(fsw_pil_board_t *b, uint8_t type, uint16_t seq, uint32_t len, bool cache)
{
    uint32_t n = 0u;
    if ((b->tx_len + FSW_LINK_MAX_WIRE) <= FSW_PIL_TX_CAP) {
        n = fsw_link_encode(type, seq, b->pay, len, &b->tx[b->tx_len], FSW_PIL_TX_CAP - b->tx_len);
    }
    if (n > 0u) {
        if (cache && ((b->cache_len + n) <= FSW_PIL_TX_CAP)) {
            uint32_t i;
            for (i = 0u; i < n; i++) {
                b->cache[b->cache_len + i] = b->tx[b->tx_len + i];
            }
            b->cache_len += n;
        }
        b->tx_len += n;
        fx_cnt_inc(&b->st.tx_frames);
    }
}

static void board_error(fsw_pil_board_t *b, uint16_t code, uint8_t type, uint32_t detail)
{
    fsw_wr_t w;
    fsw_pil_error_t e;
    e.code = code;
    e.type = type;
    e.detail = detail;
    fsw_wr_init(&w, b->pay, FSW_LINK_MAX_PAYLOAD);
    fsw_pil_wr_error(&w, &e);
    fx_cnt_inc(&b->st.errors);
    /* the offending frame's seq (for a step's TLM, the SENSOR's), so the host can tie it to its request */
    board_queue(b, (uint8_t)FSW_LINK_T_ERROR, b->dec.frame.seq, w.pos, false);
}

static void board_hello(fsw_pil_board_t *b)
{
    fsw_wr_t w;
    fsw_pil_hello_t h;
    h.version = (uint8_t)FSW_LINK_VERSION;
    h.board_id = b->board_id;
    h.layout_hash = fsw_pil_layout_hash();
    h.build_id = b->build_id;
    h.missions = fsw_pil_missions();
    fsw_wr_init(&w, b->pay, FSW_LINK_MAX_PAYLOAD);
    fsw_pil_wr_hello(&w, &h);
    b->tx_seq++;
    board_queue(b, (uint8_t)FSW_LINK_T_HELLO, b->tx_seq, w.pos, false);
}

/* The ranges of the executive's channels, as fsw_sensor_ranges gives them. */
static void board_wr_ranges(const fsw_pil_board_t *b, fsw_wr_t *w)
{
    fsw_range_t r[FSW_IN_MAX];
    uint32_t n = 0u;
    fsw_sensor_ranges(&b->fsw, r, &n);
    fsw_pil_wr_ranges(w, r, n);
}

void fsw_pil_board_init(fsw_pil_board_t *b, uint16_t board_id, uint32_t build_id)
{
    fsw_link_dec_init(&b->dec);
    b->st.rx = b->dec.st;
    b->st.steps = 0u;
    b->st.dups = 0u;
    b->st.stale = 0u;
    b->st.errors = 0u;
    b->st.boots = 0u;
    b->st.tx_frames = 0u;
    b->st.uart_overruns = 0u;
    b->st.stack_used = 0u;
    b->st.stack_size = 0u;
    b->st.insn_max = 0u;
    b->st.reserved = 0u;
    b->stage_got = 0u;
    b->tx_len = 0u;
    b->cache_len = 0u;
    b->tbl_acc_seen = 0u;
    b->lim_gen = 0u;
    b->build_id = build_id;
    b->board_id = board_id;
    b->last_seq = 0u;
    b->last_in_seq = 0;
    b->tx_seq = 0u;
    b->booted = false;
    b->have_last = false;
    b->ack_len = 0u;
    b->ack_seq = 0u;
    b->have_ack = false;
    board_hello(b);
}

/* Queues a TABLE_ACK (from b->pay) and keeps its wire bytes for a re-sent chunk of the same seq. */
static void board_queue_ack(fsw_pil_board_t *b, uint16_t seq, uint32_t len)
{
    const uint32_t start = b->tx_len;
    board_queue(b, (uint8_t)FSW_LINK_T_TABLE_ACK, seq, len, false);
    if ((b->tx_len - start) <= FSW_PIL_ACK_WIRE) {
        uint32_t i;
        for (i = 0u; i < (b->tx_len - start); i++) {
            b->ack_wire[i] = b->tx[start + i];
        }
        b->ack_len = b->tx_len - start;
        b->ack_seq = seq;
        b->have_ack = true;
    }
}

/* TABLE_CHUNK: before BOOT it stages the boot image (in order, from offset 0); after, an upload.
   A chunk with the seq of the last one answered is a re-send (its ack was lost): the same ack
   again, the chunk not applied twice (an upload's last chunk applied twice would be refused BUSY). */
static void board_chunk(fsw_pil_board_t *b, fsw_rd_t *r, uint16_t seq)
{
    fsw_table_chunk_t c;
    fsw_pil_ack_t a;
    fsw_wr_t w;
    if (b->have_ack && (seq == b->ack_seq)) {
        uint32_t i;
        for (i = 0u; (i < b->ack_len) && ((b->tx_len + i) < FSW_PIL_TX_CAP); i++) {
            b->tx[b->tx_len + i] = b->ack_wire[i];
        }
        b->tx_len += i;
    } else if (!fsw_pil_rd_chunk(r, &c)) {
        board_error(b, (uint16_t)FSW_PIL_E_LEN, (uint8_t)FSW_LINK_T_TABLE_CHUNK, r->len);
    } else if (b->booted) {
        fsw_pil_table_chunk(&b->fsw, &c, &a);
        fsw_wr_init(&w, b->pay, FSW_LINK_MAX_PAYLOAD);
        fsw_pil_wr_ack(&w, &a);
        board_queue_ack(b, seq, w.pos);
    } else {
        /* Chunks stage in order. The host re-sends a chunk whose ack it lost; a chunk at offset 0
           restarts the staging, and anything else out of order is refused (the host starts over). */
        if (c.offset == 0u) {
            b->stage_got = 0u;
        } else if ((c.offset < b->stage_got) && ((b->stage_got - c.offset) == c.n)) {
            b->stage_got = c.offset;   /* the last chunk again (its ack was lost): take it again */
        } else {
            /* in order, or refused below */
        }
        if ((c.offset != b->stage_got) || (c.total_len > FSW_TABLE_CAP_BYTES) ||
            ((c.offset + c.n) > c.total_len)) {
            b->stage_got = 0u;
            board_error(b, (uint16_t)FSW_PIL_E_STAGE, (uint8_t)FSW_LINK_T_TABLE_CHUNK, c.offset);
        } else {
            uint32_t i;
            for (i = 0u; i < c.n; i++) {
                b->stage[c.offset + i] = c.data[i];
            }
            b->stage_got += c.n;
            a.table_id = c.table_id;
            a.revision = c.revision;
            a.reason = 0u;
            a.bytes_received = b->stage_got;
            a.result = (uint16_t)((b->stage_got == c.total_len) ? FSW_PIL_ACK_ACCEPTED : FSW_PIL_ACK_PARTIAL);
            fsw_wr_init(&w, b->pay, FSW_LINK_MAX_PAYLOAD);
            fsw_pil_wr_ack(&w, &a);
            board_queue_ack(b, seq, w.pos);
        }
    }
}

/* BOOT: fsw_init from the staged image. A BOOT is always answered; a second one re-boots. */
static void board_boot(fsw_pil_board_t *b, fsw_rd_t *r, uint16_t seq)
{
    fsw_pil_boot_t bt;
    fsw_wr_t w;
    if (!fsw_pil_rd_boot(r, &bt) || (r->pos != r->len)) {
        board_error(b, (uint16_t)FSW_PIL_E_LEN, (uint8_t)FSW_LINK_T_BOOT, r->len);
    } else {
        int32_t rc;
        uint32_t reason = 0u;
        fx_cnt_inc(&b->st.boots);
        if ((bt.image_len > FSW_TABLE_CAP_BYTES) || (bt.image_len != b->stage_got) ||
            ((bt.image_len > 0u) && (fx_crc32(0u, b->stage, bt.image_len) != bt.image_crc))) {
            rc = FSW_PIL_BOOT_BAD_IMAGE;
        } else if ((bt.cfg.mission >= FSW_N_MISSIONS) || (bt.cfg.period_us == 0u) || (bt.cfg.stale_max == 0u)) {
            rc = FSW_PIL_BOOT_BAD_CFG;
        } else {
            const fsw_rc_t frc = fsw_init(&b->fsw, &bt.cfg, (bt.image_len > 0u) ? b->stage : NULL, bt.image_len);
            rc = (int32_t)frc;
            reason = b->fsw.tlm.tbl_reason;
            b->booted = true;
            b->have_last = false;
            b->cache_len = 0u;
            b->tbl_acc_seen = b->fsw.tlm.n_tbl_acc;
            b->lim_gen = 0u;
        }
        fsw_wr_init(&w, b->pay, FSW_LINK_MAX_PAYLOAD);
        fsw_wr_i32(&w, rc);
        fsw_wr_u32(&w, reason);
        fsw_wr_u32(&w, b->lim_gen);
        if (b->booted && (rc >= 0)) {
            board_wr_ranges(b, &w);
        } else {
            fsw_wr_u32(&w, 0u);
        }
        board_queue(b, (uint8_t)FSW_LINK_T_BOOT_ACK, seq, w.pos, false);
    }
}

/* SENSOR: the bridge's sequence rules on the frame's own 64-bit seq (fsw_in_t.seq), not on the 16-bit
   link seq: a genuine forward jump of 2^15 frames or more (the bridge follows one after its resync
   rule) would look old in 16-bit serial arithmetic, and every later frame would be dropped. */
static fsw_pil_rx_t board_sensor(fsw_pil_board_t *b, fsw_rd_t *r, uint16_t seq)
{
    fsw_pil_rx_t act = FSW_PIL_RX_SEND;
    if ((r->len != FSW_PIL_SENSOR_BYTES) || !fsw_pil_rd_sensor(r, &b->in)) {
        board_error(b, (uint16_t)FSW_PIL_E_LEN, (uint8_t)FSW_LINK_T_SENSOR, r->len);
    } else if (!b->booted) {
        board_error(b, (uint16_t)FSW_PIL_E_NOT_BOOTED, (uint8_t)FSW_LINK_T_SENSOR, 0u);
    } else if (b->have_last && (b->in.seq == b->last_in_seq)) {
        uint32_t i;
        fx_cnt_inc(&b->st.dups);
        for (i = 0u; (i < b->cache_len) && ((b->tx_len + i) < FSW_PIL_TX_CAP); i++) {
            b->tx[b->tx_len + i] = b->cache[i];
        }
        b->tx_len += i;
    } else if (b->have_last && (b->in.seq < b->last_in_seq)) {
        fx_cnt_inc(&b->st.stale);
        act = FSW_PIL_RX_NONE;
    } else {
        b->last_seq = seq;
        b->last_in_seq = b->in.seq;
        b->have_last = true;
        act = FSW_PIL_RX_STEP;
    }
    return act;
}

static fsw_pil_rx_t board_dispatch(fsw_pil_board_t *b)
{
    const fsw_link_frame_t *fr = &b->dec.frame;
    fsw_pil_rx_t act = FSW_PIL_RX_SEND;
    fsw_rd_t r;
    uint32_t i;
    fsw_rd_init(&r, fr->payload, fr->len);
    switch (fr->type) {
    case FSW_LINK_T_SENSOR:
        act = board_sensor(b, &r, fr->seq);
        break;
    case FSW_LINK_T_TABLE_CHUNK:
        board_chunk(b, &r, fr->seq);
        break;
    case FSW_LINK_T_BOOT:
        board_boot(b, &r, fr->seq);
        break;
    case FSW_LINK_T_HELLO:
        /* A host that says HELLO starts a new session (it may have restarted while the board
           flew): forget the boot, the staging and the caches, so its boot image cannot land in
           an upload of the old session. */
        b->booted = false;
        b->have_last = false;
        b->have_ack = false;
        b->stage_got = 0u;
        b->cache_len = 0u;
        board_hello(b);
        break;
    case FSW_LINK_T_PING:
        if (fr->len > FSW_PIL_PING_MAX) {
            board_error(b, (uint16_t)FSW_PIL_E_LEN, (uint8_t)FSW_LINK_T_PING, fr->len);
        } else {
            for (i = 0u; i < fr->len; i++) {
                b->pay[i] = fr->payload[i];
            }
            board_queue(b, (uint8_t)FSW_LINK_T_PONG, fr->seq, fr->len, false);
        }
        break;
    case FSW_LINK_T_LINK_STATS: {
        fsw_wr_t w;
        b->st.rx = b->dec.st;
        fsw_wr_init(&w, b->pay, FSW_LINK_MAX_PAYLOAD);
        fsw_pil_wr_stats(&w, &b->st);
        board_queue(b, (uint8_t)FSW_LINK_T_LINK_STATS, fr->seq, w.pos, false);
        break;
    }
    case FSW_LINK_T_MODE_CMD: {
        fsw_rd_t m;
        fsw_rd_init(&m, fr->payload, fr->len);
        const uint32_t op = fsw_rd_u32(&m);
        if ((fr->len == 4u) && ((op == FSW_PIL_MODE_END) || (op == FSW_PIL_MODE_RESET))) {
            for (i = 0u; i < fr->len; i++) {
                b->pay[i] = fr->payload[i];
            }
            board_queue(b, (uint8_t)FSW_LINK_T_MODE_CMD, fr->seq, fr->len, false);
            act = (op == FSW_PIL_MODE_END) ? FSW_PIL_RX_END : FSW_PIL_RX_RESET;
        } else {
            board_error(b, (uint16_t)FSW_PIL_E_FIELD, (uint8_t)FSW_LINK_T_MODE_CMD, fr->len);
        }
        break;
    }
    default:
        /* CMD, TLM, TABLE_ACK, PONG, ERROR, BOOT_ACK, LIMITS: the board never receives these */
        board_error(b, (uint16_t)FSW_PIL_E_TYPE, fr->type, 0u);
        break;
    }
    return act;
}

fsw_pil_rx_t fsw_pil_board_rx(fsw_pil_board_t *b, uint8_t byte)
{
    fsw_pil_rx_t act = FSW_PIL_RX_NONE;
    if (fsw_link_rx_byte(&b->dec, byte)) {
        act = board_dispatch(b);
    }
    if ((act == FSW_PIL_RX_SEND) && (b->tx_len == 0u)) {
        act = FSW_PIL_RX_NONE;
    }
    return act;
}

void fsw_pil_board_step(fsw_pil_board_t *b)
{
    fsw_step(&b->fsw, &b->in, &b->out);
}

void fsw_pil_board_finish(fsw_pil_board_t *b, uint32_t insn)
{
    fsw_wr_t w;
    fsw_pil_cmd_t c;
    uint32_t i;
    uint32_t n;

    fx_cnt_inc(&b->st.steps);
    if (insn > b->st.insn_max) {
        b->st.insn_max = insn;
    }
    b->cache_len = 0u;
    if (b->fsw.tlm.n_tbl_acc != b->tbl_acc_seen) {
        b->tbl_acc_seen = b->fsw.tlm.n_tbl_acc;
        b->lim_gen++;
        fsw_wr_init(&w, b->pay, FSW_LINK_MAX_PAYLOAD);
        board_wr_ranges(b, &w);
        board_queue(b, (uint8_t)FSW_LINK_T_LIMITS, b->last_seq, w.pos, true);
    }
    c.seq = b->in.seq;
    c.mode = b->out.mode;
    c.health = b->out.health;
    c.n_act = (b->out.n_act > FSW_ACT_MAX) ? FSW_ACT_MAX : b->out.n_act;
    for (i = 0u; i < FSW_ACT_MAX; i++) {
        c.act_cnt[i] = (i < c.n_act) ? b->out.act_cnt[i] : 0;
    }
    c.lim_gen = b->lim_gen;
    fsw_wr_init(&w, b->pay, FSW_LINK_MAX_PAYLOAD);
    fsw_pil_wr_cmd(&w, &c);
    board_queue(b, (uint8_t)FSW_LINK_T_CMD, b->last_seq, w.pos, true);

    fsw_wr_init(&w, b->pay, FSW_LINK_MAX_PAYLOAD);
    fsw_wr_u32(&w, insn);
    fsw_wr_u32(&w, fsw_tlm_layout(&b->out.tlm));
    n = fsw_tlm_encode(&b->out.tlm, &b->pay[FSW_PIL_TLM_HEAD_BYTES], FSW_PIL_TLM_MAX);
    if (n == 0u) {
        board_error(b, (uint16_t)FSW_PIL_E_TLM_SIZE, (uint8_t)FSW_LINK_T_TLM, 0u);
    } else {
        board_queue(b, (uint8_t)FSW_LINK_T_TLM, b->last_seq, FSW_PIL_TLM_HEAD_BYTES + n, true);
    }
}

void fsw_pil_board_sent(fsw_pil_board_t *b)
{
    b->tx_len = 0u;
}
