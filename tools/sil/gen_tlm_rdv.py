"""Generator of the RENDEZVOUS telemetry layout (fsw_tlm_t, layout FSW_TLM_RDV_LAYOUT_VERSION).

One list below is the single source of the wire layout. It writes
    fsw/app/fsw_tlm_rdv.c              the flight encoder (C99, field by field, little-endian)
    fsw/app/fsw_tlm_formats_rdv.json   the tools' scaling file (tools/sil/tlm.py)
    hil_host/sil/tlm_rdv_fields.hpp    the decoder table of the SIL metrics

    python -m tools.sil gen-tlm-rdv [--check]      (from the repo root)

--check regenerates in memory and fails when a committed file differs (CTest
golden_tlm_rdv_regen), so the three can never drift apart.
"""
import json
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
OUT_C = os.path.join(ROOT, "fsw", "app", "fsw_tlm_rdv.c")
OUT_JSON = os.path.join(ROOT, "fsw", "app", "fsw_tlm_formats_rdv.json")
OUT_HPP = os.path.join(ROOT, "hil_host", "sil", "tlm_rdv_fields.hpp")
LAYOUT_VERSION = 0x00020001
AX = "xyz"
THR = ["px", "mx", "py", "my", "pz", "mz"]   # thruster j = +x, -x, +y, -y, +z, -z
FAIL = ["none", "iter", "diverge", "singular", "cond", "fx", "order"]   # IMP_FAIL_*


def F(name, typ, c, q=None, unit=None, note=None):
    d = {"name": name, "type": typ, "c": c}
    if q is not None:
        d["q"] = q
    if unit:
        d["unit"] = unit
    if note:
        d["note"] = note
    return d


def fields():
    f = [F("utime_us", "i64", "t->utime_us", unit="us", note="echoed sample time"),
         F("seq", "i64", "t->seq", note="echoed frame index (the impulse time base)")]
    for n, note in [("step", "executive step counter"), ("mode", "0 BOOT 1 STANDBY 2 DETUMBLE 3 SAFE 4 RENDEZVOUS"),
                    ("health", "FSW_H_* | fx status"), ("health_sticky", None), ("n_chan_rej", "nav samples refused"),
                    ("n_stale_steps", None), ("n_in_bad", None), ("n_tbl_acc", None), ("n_tbl_rej", None),
                    ("tbl_reason", None), ("tbl_revision", None), ("n_scrub_err", None), ("n_safe", None),
                    ("n_mode_rej", None), ("host_missed", None), ("host_rejected", None), ("n_tc", "telecommands taken"),
                    ("n_tc_rej", "telecommands refused")]:
        f.append(F(n, "u32", "t->" + n, note=note))
    for j in range(6):
        f.append(F("act_start_" + THR[j], "i32", "t->act_cnt[%du]" % j, unit="us", note="on-window start in the step"))
    for j in range(6):
        f.append(F("act_len_" + THR[j], "i32", "t->act_cnt[%du]" % (6 + j), unit="us", note="on-window length"))
    f.append(F("act_mask", "i32", "t->act_cnt[12u]", note="bit j: thruster j on"))
    f.append(F("imp_health", "u32", "t->imp_health", note="IMP_H_* | fx status of this step"))
    i = "t->imp."
    for n in ["plans", "plans_failed", "plans_late", "plans_skipped", "cmd_rej", "nav_rej", "cal_rej", "plans_kept"]:
        f.append(F("imp_" + n, "u32", i + n))
    for k in range(7):
        f.append(F("imp_fail_" + FAIL[k], "u32", i + "fail_cnt[%du]" % k, note="attempt failures by cause"))
    for n, note in [("mode", "IMP_MODE_*"), ("rej_reason", "IMP_REJ_* of the last refused command"),
                    ("how_xy", "0 none 1 warm 2 rule 3 search"), ("how_z", None), ("pattern", "polarity bits"),
                    ("iters_xy", None), ("iters_z", None), ("last_fail_xy", None), ("last_fail_z", None),
                    ("stuck_j", "0xFF: none"), ("stuck_off_mask", None), ("job_active", None)]:
        f.append(F("imp_" + n, "u8", i + n, note=note))
    f.append(F("imp_plan_units", "u16", i + "plan_units"))
    f.append(F("imp_plan_steps", "u16", i + "plan_steps"))
    f.append(F("imp_fres_xy", "i32", i + "fres_lsb[0u]", unit="LSB q28"))
    f.append(F("imp_fres_z", "i32", i + "fres_lsb[1u]", unit="LSB q28"))
    for n in ["t1", "t2"]:
        for r in range(3):
            f.append(F("imp_%s_%s" % (n, AX[r]), "i32", i + "%s_q29[%du]" % (n, r), q=29, unit="rad (w t)"))
    for n in ["on1_step", "on2_step", "on1_us", "on2_us"]:
        for r in range(3):
            f.append(F("imp_%s_%s" % (n, AX[r]), "u32", i + "%s[%du]" % (n, r)))
    for k, s in enumerate(["x", "xd", "y", "yd", "z", "zd"]):
        f.append(F("imp_miss_" + s, "i32", i + "miss_q28[%du]" % k, q=28, note="predicted terminal error, nondimensional"))
    f.append(F("imp_round_xy", "u8", i + "round_choice[0u]"))
    f.append(F("imp_round_z", "u8", i + "round_choice[1u]"))
    for n in ["rho", "dv1", "dv2"]:
        for r in range(3):
            f.append(F("imp_%s_%s" % (n, AX[r]), "i32", i + "%s_q28[%du]" % (n, r), q=28))
    for n in ["dv_cmd", "dv_used"]:
        for j in range(6):
            f.append(F("imp_%s_%s" % (n, THR[j]), "i32", i + "%s_q28[%du]" % (n, j), q=28, unit="a_nom/w"))
    for j in range(6):
        f.append(F("imp_alpha_" + THR[j], "i32", i + "alpha_q30[%du]" % j, q=30))
    for j in range(6):
        f.append(F("imp_cal_windows_" + THR[j], "u16", i + "cal_windows[%du]" % j))
    for n in ["nu", "exp_dr", "exp_dv"]:
        for r in range(3):
            f.append(F("imp_%s_%s" % (n, AX[r]), "i32", i + "%s_q28[%du]" % (n, r), q=28))
    for n in ["nav_age", "st_step", "st_sticky", "health_sticky", "revision"]:
        f.append(F("imp_" + n, "u32", i + n))
    return f


SIZE = {"u8": 1, "u16": 2, "u32": 4, "i32": 4, "i64": 8}
WR = {"u8": "fsw_wr_u8", "u16": "fsw_wr_u16", "u32": "fsw_wr_u32", "i32": "fsw_wr_i32", "i64": "fsw_wr_i64"}


def render():
    fl = fields()
    nbytes = sum(SIZE[x["type"]] for x in fl)
    if nbytes > 512:
        raise SystemExit("gen_tlm_rdv: %d bytes do not fit fsw_tlm_frame_t.tlm[512]" % nbytes)
    c = ["/*",
         " * fsw_tlm_rdv.c — fsw_tlm_t of the RENDEZVOUS mission on the wire (layout 0x%08X, %d bytes)." % (LAYOUT_VERSION, nbytes),
         " * GENERATED by `python -m tools.sil gen-tlm-rdv` from tools/sil/gen_tlm_rdv.py; do not edit.",
         " * The same list writes fsw_tlm_formats_rdv.json (tools) and hil_host/sil/tlm_rdv_fields.hpp (SIL",
         " * metrics); CTest golden_tlm_rdv_regen keeps the three identical.",
         " */",
         '#include "fsw_exec.h"',
         '#include "fsw_codec.h"',
         "",
         "uint32_t fsw_tlm_rdv_encode(const fsw_tlm_t *t, uint8_t *buf, uint32_t cap)",
         "{",
         "    uint32_t n = 0u;",
         "    if ((t != NULL) && (buf != NULL) && (cap >= FSW_TLM_RDV_BYTES)) {",
         "        fsw_wr_t w;",
         "        fsw_wr_init(&w, buf, cap);"]
    for x in fl:
        c.append("        %s(&w, %s);" % (WR[x["type"]], x["c"]))
    c += ["        if ((!w.err) && (w.pos == FSW_TLM_RDV_BYTES)) {",
          "            n = w.pos;",
          "        }",
          "    }",
          "    return n;",
          "}",
          ""]
    js = {"layout_version": LAYOUT_VERSION, "byte_order": "little", "bytes": nbytes,
          "doc": "fsw_tlm_t wire layout of the RENDEZVOUS mission (fsw/app/fsw_tlm_rdv.c, generated by "
                 "tools/sil/gen_tlm_rdv.py). Real value = raw / 2^q; nondimensional units per spec 50 §4.1.",
          "fields": [{k: v for k, v in x.items() if k != "c"} for x in fl]}
    code = {"u8": "b", "u16": "h", "u32": "u", "i32": "i", "i64": "q"}
    h = ["// tlm_rdv_fields.hpp — decoder table of the RENDEZVOUS telemetry (layout 0x%08X, %d bytes)." % (LAYOUT_VERSION, nbytes),
         "// GENERATED by `python -m tools.sil gen-tlm-rdv` (tools/sil/gen_tlm_rdv.py); do not edit.",
         "#ifndef HIL_SIL_TLM_RDV_FIELDS_HPP",
         "#define HIL_SIL_TLM_RDV_FIELDS_HPP",
         "",
         "namespace sil {",
         "",
         "// name, wire type: 'b' u8, 'h' u16, 'u' u32, 'i' i32, 'q' i64",
         "struct TlmField { const char *name; char t; };",
         "constexpr unsigned kTlmRdvBytes = %du;" % nbytes,
         "constexpr TlmField kTlmRdv[] = {"]
    for x in fl:
        h.append('    {"%s", \'%s\'},' % (x["name"], code[x["type"]]))
    h += ["};", "", "}  // namespace sil", "", "#endif", ""]
    return {OUT_C: "\n".join(c), OUT_JSON: json.dumps(js, indent=1) + "\n", OUT_HPP: "\n".join(h)}, nbytes


def main(check=False):
    files, nbytes = render()
    bad = []
    for path, text in files.items():
        old = open(path).read() if os.path.exists(path) else None
        if check:
            if old != text:
                bad.append(os.path.relpath(path, ROOT))
        elif old != text:
            with open(path, "w") as fh:
                fh.write(text)
            print("wrote", os.path.relpath(path, ROOT))
    if bad:
        print("gen-tlm-rdv: %s differ from the generator; run `python -m tools.sil gen-tlm-rdv`" % ", ".join(bad))
        return 1
    if check:
        print("gen-tlm-rdv: %d-byte layout, all three files regenerate byte-identically" % nbytes)
    return 0


if __name__ == "__main__":
    sys.exit(main("--check" in sys.argv))
