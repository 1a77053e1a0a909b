/*
 * fsw_pil.c — the PIL session's packet payloads and layout hash (fsw_pil.h, spec 00 §6.1); the board's
 * side of the session is fsw_pil_board.c.
 */
#include "fsw_pil.h"
#include "fsw_codec.h"
#include "fsw_missions_gen.h"
#include "fx.h"

/*
 * The canonical description of every layout on the link: HELLO's layout hash is its CRC-32. Any
 * change to a payload below must change this text; test_fsw_pil checks each writer's size against
 * the FSW_PIL_*_BYTES the text repeats.
 */
uint32_t fsw_pil_layout_hash(void)
{
    static const char pil_layout[] =
        "link v1: u8 version, u8 type, u16 seq, u16 len, payload[len], u32 crc32; cobs, 0x00 delimiter\n"
        "HELLO 1 (16): u8 version, u8 0, u16 board, u32 layout_hash, u32 build_id, u32 missions\n"
        "SENSOR 2 (148): i64 utime_us, i64 seq, u32 n_counts, i32 counts[16], u8 status[16], u32 mode_cmd, "
        "u32 host_missed, u32 host_rejected, u32 tc, i32 tc_arg[8]\n"
        "CMD 3 (88): i64 seq, u32 mode, u32 health, u32 n_act, i32 act_cnt[16], u32 lim_gen\n"
        "TLM 4 (8+n): u32 insn, u32 layout, u8 tlm[n<=504]\n"
        "TABLE_CHUNK 5 (16+n): u16 table_id, u16 n, u32 revision, u32 total_len, u32 offset, u8 data[n<=256]\n"
        "TABLE_ACK 6 (16): u16 table_id, u16 result, u32 revision, u32 reason, u32 bytes_received\n"
        "PING 8 / PONG 9 (<=32): u8 echo[]\n"
        "LINK_STATS 10 (0 request, 84): u32 rx[10], u32 steps, u32 dups, u32 stale, u32 errors, u32 boots, "
        "u32 tx_frames, u32 uart_overruns, u32 stack_used, u32 stack_size, u32 insn_max, u32 0\n"
        "MODE_CMD 7 (4): u32 op (1 end, 2 reset)\n"
        "ERROR 11 (8): u16 code, u16 type, u32 detail\n"
        "BOOT 12 (24): u32 mission, u32 period_us, u16 stale_max, u16 0, u32 boot_mode, u32 image_len, u32 image_crc\n"
        "BOOT_ACK 13 (12+4+8n): i32 rc, u32 reason, u32 lim_gen, u32 n, n x (i32 min, i32 max)\n"
        "LIMITS 14 (4+8n): u32 n, n x (i32 min, i32 max)\n";
    return fx_crc32(0u, (const uint8_t *)pil_layout, sizeof(pil_layout) - 1u);
}

uint32_t fsw_pil_missions(void)
{
    uint32_t m = 0u;
    uint32_t i;
    for (i = 0u; i < FSW_N_MISSIONS; i++) {
        if (fsw_mis_desc(i) != NULL) {
            m |= (1u << i);
        }
    }
    return m;
}

/* ------------------------------------------------------------------ payloads */

void fsw_pil_wr_sensor(fsw_wr_t *w, const fsw_in_t *in)
{
    uint32_t i;
    fsw_wr_i64(w, in->utime_us);
    fsw_wr_i64(w, in->seq);
    fsw_wr_u32(w, in->n_counts);
    fsw_wr_i32n(w, in->counts, FSW_IN_MAX);
    for (i = 0u; i < FSW_IN_MAX; i++) {
        fsw_wr_u8(w, in->status[i]);
    }
    fsw_wr_u32(w, in->mode_cmd);
    fsw_wr_u32(w, in->host_missed);
    fsw_wr_u32(w, in->host_rejected);
    fsw_wr_u32(w, in->tc);
    fsw_wr_i32n(w, in->tc_arg, FSW_TC_ARGS);
}

bool fsw_pil_rd_sensor(fsw_rd_t *r, fsw_in_t *in)
{
    uint32_t i;
    in->utime_us = fsw_rd_i64(r);
    in->seq = fsw_rd_i64(r);
    in->n_counts = fsw_rd_u32(r);
    fsw_rd_i32n(r, in->counts, FSW_IN_MAX);
    for (i = 0u; i < FSW_IN_MAX; i++) {
        in->status[i] = fsw_rd_u8(r);
    }
    in->mode_cmd = fsw_rd_u32(r);
    in->host_missed = fsw_rd_u32(r);
    in->host_rejected = fsw_rd_u32(r);
    in->tc = fsw_rd_u32(r);
    fsw_rd_i32n(r, in->tc_arg, FSW_TC_ARGS);
    return (!r->err) && (in->n_counts <= FSW_IN_MAX);
}

void fsw_pil_wr_cmd(fsw_wr_t *w, const fsw_pil_cmd_t *c)
{
    fsw_wr_i64(w, c->seq);
    fsw_wr_u32(w, c->mode);
    fsw_wr_u32(w, c->health);
    fsw_wr_u32(w, c->n_act);
    fsw_wr_i32n(w, c->act_cnt, FSW_ACT_MAX);
    fsw_wr_u32(w, c->lim_gen);
}

bool fsw_pil_rd_cmd(fsw_rd_t *r, fsw_pil_cmd_t *c)
{
    c->seq = fsw_rd_i64(r);
    c->mode = fsw_rd_u32(r);
    c->health = fsw_rd_u32(r);
    c->n_act = fsw_rd_u32(r);
    fsw_rd_i32n(r, c->act_cnt, FSW_ACT_MAX);
    c->lim_gen = fsw_rd_u32(r);
    return (!r->err) && (c->n_act <= FSW_ACT_MAX);
}

void fsw_pil_wr_hello(fsw_wr_t *w, const fsw_pil_hello_t *h)
{
    fsw_wr_u8(w, h->version);
    fsw_wr_u8(w, 0u);
    fsw_wr_u16(w, h->board_id);
    fsw_wr_u32(w, h->layout_hash);
    fsw_wr_u32(w, h->build_id);
    fsw_wr_u32(w, h->missions);
}

bool fsw_pil_rd_hello(fsw_rd_t *r, fsw_pil_hello_t *h)
{
    h->version = fsw_rd_u8(r);
    (void)fsw_rd_u8(r);
    h->board_id = fsw_rd_u16(r);
    h->layout_hash = fsw_rd_u32(r);
    h->build_id = fsw_rd_u32(r);
    h->missions = fsw_rd_u32(r);
    return !r->err;
}

void fsw_pil_wr_chunk(fsw_wr_t *w, const fsw_table_chunk_t *c)
{
    uint32_t i;
    uint32_t n = c->n;
    if (n > FSW_TABLE_CHUNK_MAX) {
        n = FSW_TABLE_CHUNK_MAX;
    }
    fsw_wr_u16(w, c->table_id);
    fsw_wr_u16(w, (uint16_t)n);
    fsw_wr_u32(w, c->revision);
    fsw_wr_u32(w, c->total_len);
    fsw_wr_u32(w, c->offset);
    for (i = 0u; i < n; i++) {
        fsw_wr_u8(w, c->data[i]);
    }
}

bool fsw_pil_rd_chunk(fsw_rd_t *r, fsw_table_chunk_t *c)
{
    bool ok;
    c->table_id = fsw_rd_u16(r);
    c->n = fsw_rd_u16(r);
    c->revision = fsw_rd_u32(r);
    c->total_len = fsw_rd_u32(r);
    c->offset = fsw_rd_u32(r);
    /* The data must be exactly the rest of the payload. */
    ok = (!r->err) && (c->n >= 1u) && (c->n <= FSW_TABLE_CHUNK_MAX) && ((r->len - r->pos) == c->n);
    c->data = ok ? &r->buf[r->pos] : NULL;
    return ok;
}

void fsw_pil_wr_ack(fsw_wr_t *w, const fsw_pil_ack_t *a)
{
    fsw_wr_u16(w, a->table_id);
    fsw_wr_u16(w, a->result);
    fsw_wr_u32(w, a->revision);
    fsw_wr_u32(w, a->reason);
    fsw_wr_u32(w, a->bytes_received);
}

bool fsw_pil_rd_ack(fsw_rd_t *r, fsw_pil_ack_t *a)
{
    a->table_id = fsw_rd_u16(r);
    a->result = fsw_rd_u16(r);
    a->revision = fsw_rd_u32(r);
    a->reason = fsw_rd_u32(r);
    a->bytes_received = fsw_rd_u32(r);
    return (!r->err) && (a->result <= FSW_PIL_ACK_REJECTED);
}

void fsw_pil_wr_boot(fsw_wr_t *w, const fsw_pil_boot_t *b)
{
    fsw_wr_u32(w, b->cfg.mission);
    fsw_wr_u32(w, b->cfg.period_us);
    fsw_wr_u16(w, b->cfg.stale_max);
    fsw_wr_u16(w, 0u);
    fsw_wr_u32(w, b->cfg.boot_mode);
    fsw_wr_u32(w, b->image_len);
    fsw_wr_u32(w, b->image_crc);
}

bool fsw_pil_rd_boot(fsw_rd_t *r, fsw_pil_boot_t *b)
{
    b->cfg.mission = fsw_rd_u32(r);
    b->cfg.period_us = fsw_rd_u32(r);
    b->cfg.stale_max = fsw_rd_u16(r);
    (void)fsw_rd_u16(r);
    b->cfg.boot_mode = fsw_rd_u32(r);
    b->image_len = fsw_rd_u32(r);
    b->image_crc = fsw_rd_u32(r);
    return !r->err;
}

void fsw_pil_wr_ranges(fsw_wr_t *w, const fsw_range_t *rng, uint32_t n)
{
    uint32_t i;
    uint32_t m = n;
    if (m > FSW_IN_MAX) {
        m = FSW_IN_MAX;
    }
    fsw_wr_u32(w, m);
    for (i = 0u; i < m; i++) {
        fsw_wr_i32(w, rng[i].min);
        fsw_wr_i32(w, rng[i].max);
    }
}

bool fsw_pil_rd_ranges(fsw_rd_t *r, fsw_range_t *rng, uint32_t *n)
{
    uint32_t m = fsw_rd_u32(r);
    bool ok = (!r->err) && (m <= FSW_IN_MAX);
    *n = 0u;
    if (ok) {
        uint32_t i;
        for (i = 0u; i < m; i++) {
            rng[i].min = fsw_rd_i32(r);
            rng[i].max = fsw_rd_i32(r);
        }
        ok = !r->err;
        *n = ok ? m : 0u;
    }
    return ok;
}

void fsw_pil_wr_stats(fsw_wr_t *w, const fsw_pil_stats_t *s)
{
    fsw_wr_u32(w, s->rx.bytes);
    fsw_wr_u32(w, s->rx.empty);
    fsw_wr_u32(w, s->rx.frames);
    fsw_wr_u32(w, s->rx.err_oversize);
    fsw_wr_u32(w, s->rx.err_cobs);
    fsw_wr_u32(w, s->rx.err_short);
    fsw_wr_u32(w, s->rx.err_len);
    fsw_wr_u32(w, s->rx.err_crc);
    fsw_wr_u32(w, s->rx.err_version);
    fsw_wr_u32(w, s->rx.err_type);
    fsw_wr_u32(w, s->steps);
    fsw_wr_u32(w, s->dups);
    fsw_wr_u32(w, s->stale);
    fsw_wr_u32(w, s->errors);
    fsw_wr_u32(w, s->boots);
    fsw_wr_u32(w, s->tx_frames);
    fsw_wr_u32(w, s->uart_overruns);
    fsw_wr_u32(w, s->stack_used);
    fsw_wr_u32(w, s->stack_size);
    fsw_wr_u32(w, s->insn_max);
    fsw_wr_u32(w, s->reserved);
}

bool fsw_pil_rd_stats(fsw_rd_t *r, fsw_pil_stats_t *s)
{
    s->rx.bytes = fsw_rd_u32(r);
    s->rx.empty = fsw_rd_u32(r);
    s->rx.frames = fsw_rd_u32(r);
    s->rx.err_oversize = fsw_rd_u32(r);
    s->rx.err_cobs = fsw_rd_u32(r);
    s->rx.err_short = fsw_rd_u32(r);
    s->rx.err_len = fsw_rd_u32(r);
    s->rx.err_crc = fsw_rd_u32(r);
    s->rx.err_version = fsw_rd_u32(r);
    s->rx.err_type = fsw_rd_u32(r);
    s->steps = fsw_rd_u32(r);
    s->dups = fsw_rd_u32(r);
    s->stale = fsw_rd_u32(r);
    s->errors = fsw_rd_u32(r);
    s->boots = fsw_rd_u32(r);
    s->tx_frames = fsw_rd_u32(r);
    s->uart_overruns = fsw_rd_u32(r);
    s->stack_used = fsw_rd_u32(r);
    s->stack_size = fsw_rd_u32(r);
    s->insn_max = fsw_rd_u32(r);
    s->reserved = fsw_rd_u32(r);
    return !r->err;
}

void fsw_pil_wr_error(fsw_wr_t *w, const fsw_pil_error_t *e)
{
    fsw_wr_u16(w, e->code);
    fsw_wr_u16(w, e->type);
    fsw_wr_u32(w, e->detail);
}

bool fsw_pil_rd_error(fsw_rd_t *r, fsw_pil_error_t *e)
{
    e->code = fsw_rd_u16(r);
    e->type = fsw_rd_u16(r);
    e->detail = fsw_rd_u32(r);
    return !r->err;
}

void fsw_pil_table_chunk(fsw_t *f, const fsw_table_chunk_t *c, fsw_pil_ack_t *ack)
{
    uint32_t why = 0u;
    const uint32_t rej0 = f->tlm.n_tbl_rej;
    const fsw_rc_t rc = fsw_table_upload(f, c, &why);
    const fsw_table_t *t = fsw_mission_table(f);

    ack->table_id = c->table_id;
    ack->revision = c->revision;
    ack->reason = 0u;
    ack->bytes_received = t->cand_got;
    if ((f->tlm.n_tbl_rej != rej0) || (rc != FSW_OK)) {
        ack->result = (uint16_t)FSW_PIL_ACK_REJECTED;
        ack->reason = why & 0xFFFFu;
    } else if (t->state == FSW_TBL_S_READY) {
        ack->result = (uint16_t)FSW_PIL_ACK_ACCEPTED;   /* validated; commits at a step boundary */
        ack->bytes_received = c->total_len;
    } else {
        ack->result = (uint16_t)FSW_PIL_ACK_PARTIAL;
    }
}
