"""Interface of the executive (spec 00 §3.3): the single source of its mode and health-bit names,
the table loader's reason codes, the input status bits and the telemetry header every mission's
layout starts with. Not flight code: `python -m tools.iface c` turns it into fsw_ids.h and
fsw_tlm_head.c (committed; CTest golden_iface_regen checks them). Mission modes are not here:
each mission's mode number is its line in missions.json.
"""
from tools.iface.schema import Bit, Field, enum

# Modes of the executive itself; the mission modes come from missions.json.
MODES = enum("mode", "FSW_MODE_", [
    ("BOOT", 0, "until the first step"),
    ("STANDBY", 1, "no module runs, actuators safe"),
    ("SAFE", 3, "entered on a persistent fault or by command; left only by command")],
    "executive modes (fsw_tlm_t.mode)")

HEALTH = [
    Bit("STALE", 0x00000100, "a consumed channel is invalid this step"),
    Bit("STALE_PERSIST", 0x00000200, "a channel invalid for >= stale_max steps"),
    Bit("SAT_PERSIST", 0x00000400, "plant SAT bit on a channel for >= stale_max steps"),
    Bit("SCRUB", 0x00000800, "active table failed its CRC scrub"),
    Bit("SAFE", 0x00001000, "mode is SAFE"),
    Bit("MODE_REJ", 0x00002000, "a mode command was refused this step"),
    Bit("TBL_REJ", 0x00004000, "a table upload was refused since the last step"),
    Bit("TBL_NEW", 0x00008000, "a new table became active at this step"),
    Bit("MODULE", 0x00010000, "the module reports a fault bit (its health word in telemetry)"),
    Bit("NO_TABLE", 0x00020000, "no valid module table (boot table refused)"),
    Bit("TC_REJ", 0x00040000, "a telecommand was refused this step (unknown, other mission, wrong mode)"),
    Bit("TBL_PENDING", 0x00080000, "a validated table waits for the mission's commit rule"),
    Bit("MODULE_SAFE", 0x00100000, "the module reported a fault it judged persistent (its safe_bits): SAFE"),
]

# Per-channel status bits of fsw_in_t.status (the bridge maps the plant's sensor_frame_v2_t bits).
STATUS = [Bit("STALE", 0x1, "the plant marks the sample stale"),
          Bit("SAT", 0x2, "the plant's sensor model clipped the count at full scale")]

# Reason codes of a table refusal (bits 0..7 of the reason word; bits 8..15 the detail).
TBL_REASONS = enum("tbl_reason", "FSW_TBL_R_", [
    ("NONE", 0, "no rejection since init"),
    ("CHUNK_LEN", 1, "chunk n == 0 or n > FSW_TABLE_CHUNK_MAX, null data"),
    ("BUSY", 2, "chunk while a validated candidate awaits commit"),
    ("OVERSIZE", 3, "total_len < header or > FSW_TABLE_CAP_BYTES"),
    ("UPLOAD_ID", 4, "chunk table_id is not this table's"),
    ("TOTAL_CHANGED", 5, "total_len differs from the upload's first chunk"),
    ("REV_CHANGED", 6, "revision differs from the upload's first chunk"),
    ("OFFSET", 7, "offset + n beyond total_len (or capacity)"),
    ("OVERLAP", 8, "bytes already received differ from the new chunk"),
    ("MISSING", 9, "end of upload with bytes missing"),
    ("DECODE", 10, "header length field != image bytes - header"),
    ("CRC", 11, "payload CRC-32 mismatch"),
    ("ID", 12, "header table_id != descriptor"),
    ("VERSION", 13, "header layout_version != descriptor"),
    ("LENGTH", 14, "payload length != descriptor"),
    ("RANGE_LO", 15, "field (detail = index) below its min"),
    ("RANGE_HI", 16, "field (detail = index) above its max"),
    ("INVARIANT", 17, "relation (detail = index) violated"),
    ("NO_UPLOAD", 18, "end of upload when none is in progress"),
    ("SCRUB", 19, "active image CRC mismatch found by the scrub"),
    ("MODULE", 20, "module check vetoed the candidate (detail: 1 + index of its lowest why bit, 0xFF undecodable)")],
    "table refusal reasons (fsw_table.h)")

# The telemetry header of every mission's layout, relative to `const fsw_tlm_t *t`. Then come the
# mission's actuator counts, its health word (<prefix>_health) and its block (<prefix>_iface.py).
HEAD = ([Field("utime_us", "i64", "t->utime_us", unit="us", note="echoed sample time"),
         Field("seq", "i64", "t->seq", note="echoed frame index")] +
        [Field(n, "u32", "t->" + n, unit=u, note=note) for n, u, note in [
            ("step", "", "executive step counter"),
            ("mode", "", "FSW_MODE_* or the mission's mode"),
            ("health", "", "bits 0-7 fx status of the module, 8-19 FSW_H_*"),
            ("health_sticky", "", "OR of health since init"),
            ("n_chan_rej", "count", "channel samples refused (range or STALE bit)"),
            ("n_stale_steps", "count", "steps with an invalid consumed channel"),
            ("n_in_bad", "count", "frames carrying fewer channels than the mission consumes"),
            ("n_tbl_acc", "count", "table candidates committed"),
            ("n_tbl_rej", "count", "table uploads refused (loader or module veto)"),
            ("tbl_reason", "", "reason word of the latest table refusal"),
            ("tbl_revision", "", "active table revision"),
            ("n_scrub_err", "count", "scrub CRC mismatches"),
            ("n_safe", "count", "SAFE entries"),
            ("n_mode_rej", "count", "refused mode commands"),
            ("host_missed", "count", "missed commands reported by the host"),
            ("host_rejected", "count", "frames rejected by the host"),
            ("n_tc", "count", "telecommands taken by the module"),
            ("n_tc_rej", "count", "telecommands refused")]])

LAYOUT_REV = 0   # revision of the header; bits 8..15 of every telemetry layout version
