#!/usr/bin/env python3
"""mkcorpus_fsw_step.py - seed corpus for tests/fuzz/fuzz_fsw_step (spec 00 §8 "Fuzzing").

Writes inputs in the harness's format (tests/fuzz/fuzz_fsw_step.c, tests/fuzz/README.md):
u8 cfg, u8 stale_max - 1, then records of op, u8 repeat - 1 and the op's operands. The seeds
start the fuzzer at the deep states: a long nominal DETUMBLE run per table, dropouts, stale
and saturated channels, duplicated / reordered / gapped frames, junk counts, mode commands; a
RENDEZVOUS START per table followed by hundreds of steps (planning and the first burns),
then nav dropouts, ABORT, CLEAR and a second START. Standard library only; deterministic.

Usage: mkcorpus_fsw_step.py OUT_DIR      (the build tree; nothing generated is committed)
"""
import argparse
import os
import struct
import sys

sys.dont_write_bytecode = True

SEQ_NEXT, SEQ_DUP, SEQ_BACK, SEQ_JUMP = 0, 1, 2, 3
DELTA, RAW, STATUS, MODE, TC, NCOUNTS = 4, 8, 16, 32, 64, 128
TC_START, TC_ABORT, TC_CLEAR = 2, 3, 4
MODE_STANDBY, MODE_DETUMBLE, MODE_SAFE, MODE_RDV = 1, 2, 3, 4


def cfg(rdv, table, standby=False, stale_max=5):
    return bytes([(1 if rdv else 0) | (table << 1) | (8 if standby else 0), stale_max - 1])


def run(steps):
    """Plain steps, 256 per record."""
    out = b""
    while steps > 0:
        n = min(steps, 256)
        out += bytes([SEQ_NEXT, n - 1])
        steps -= n
    return out


def rec(op, reps=1, operands=b""):
    return bytes([op, reps - 1]) + operands


def i16s(*v):
    return b"".join(struct.pack("<H", (x + 32768) & 0xFFFF) for x in v)


def i32s(*v):
    return b"".join(struct.pack("<i", x) for x in v)


def start(lead, dur, target=(0, 0, 0, 0, 0, 0)):
    return rec(TC, 1, bytes([TC_START, lead, dur]) + i16s(*target))


# The harness sends a START with t_f - t0 = 100 + 16 dur steps; the scheduler takes it only for
# tau_f = w (t_f - t0) h in [0.2, 2.0] rad (w = 1.131e-3 rad/s): dur 5..104 on the 1 s table,
# dur 105..255 on the 0.1 s tables (at most 418 s). From the paper's state (5, 4, 4 km) 418 s is
# infeasible at a_nom = 0.04 m/s^2, so the 0.1 s seeds first put the nav state at 300, 200, 200 m
# (at rest), where the plan succeeds and the burns start.
DUR = {0: 150, 1: 100, 2: 150}


def near(table):
    """A raw nav record with a state the 0.1 s tables can reach; nothing on the 1 s table."""
    return b"" if table == 1 else rec(RAW, 1, i32s(300000, 200000, 200000, 0, 0, 0, 0))


def rdv(table, steps=5):
    """RENDEZVOUS boot on a table, steps of the boot nav state (near() on 0.1 s), then START."""
    return cfg(True, table) + near(table) + run(steps - 1 if near(table) else steps) + start(60, DUR[table])


def seeds():
    s = {}
    for t, name in enumerate(("phys", "paper", "5hz")):
        s[f"det_{name}_nominal"] = cfg(False, t) + run(990)
        s[f"det_{name}_standby_then_mode"] = (cfg(False, t, standby=True) + run(50)
                                              + rec(MODE, 1, bytes([MODE_DETUMBLE])) + run(600))
    s["det_dropouts"] = (cfg(False, 0) + run(200) + rec(STATUS, 3, bytes([1, 0])) + run(100)
                         + rec(STATUS, 20, bytes([1, 1])) + run(100) + rec(MODE, 1, bytes([MODE_DETUMBLE])) + run(200))
    s["det_saturated"] = cfg(False, 0) + run(100) + rec(STATUS, 30, bytes([2, 2])) + run(100)
    s["det_seq"] = (cfg(False, 0) + run(100) + rec(SEQ_DUP, 1) + run(10) + rec(SEQ_BACK, 1, bytes([3]))
                    + run(10) + rec(SEQ_JUMP, 1, struct.pack("<H", 5)) + run(10)
                    + rec(SEQ_JUMP, 1, struct.pack("<H", 2000)) + run(100))
    s["det_junk"] = (cfg(False, 0) + run(100) + rec(RAW, 1, i32s(2**31 - 1, -2**31)) + run(10)
                     + rec(RAW, 5, i32s(1 << 20, -(1 << 20))) + rec(RAW, 1, i32s(18301, 18301)) + run(200)
                     + rec(DELTA, 50, i16s(3000, -3000)) + run(100))
    s["det_short_frames"] = (cfg(False, 0) + run(100) + rec(NCOUNTS, 5, bytes([1])) + rec(NCOUNTS, 5, bytes([0]))
                             + rec(NCOUNTS, 5, bytes([17])) + rec(NCOUNTS, 100, bytes([2])))
    s["det_mode_junk"] = (cfg(False, 0) + run(50) + rec(MODE, 1, bytes([6])) + rec(MODE, 1, bytes([MODE_RDV]))
                          + rec(MODE, 1, bytes([MODE_SAFE])) + run(20) + rec(MODE, 1, bytes([MODE_DETUMBLE])) + run(100)
                          + rec(TC, 1, bytes([TC_START, 0, 0]) + i16s(0, 0, 0, 0, 0, 0)) + run(10))
    for t, name in enumerate(("0p1s", "1s", "sub1ms")):
        s[f"rdv_{name}_start"] = rdv(t) + run(900)
    s["rdv_1s_long"] = rdv(1) + run(980)
    s["rdv_nav_dropout"] = (rdv(0) + run(300)
                            + rec(STATUS, 200, bytes([1] * 7)) + run(300))
    s["rdv_abort_clear"] = (rdv(0) + run(200) + rec(TC, 1, bytes([TC_ABORT]))
                            + run(20) + rec(TC, 1, bytes([TC_CLEAR])) + run(20) + start(60, DUR[0], (100, -100, 50, 0, 0, 0))
                            + run(400))
    s["rdv_bad_starts"] = (cfg(True, 0) + run(5) + start(0, 0) + run(5) + start(60, 255, (32767, 32767, 32767, 0, 0, 0))
                           + run(100) + rec(TC, 1, bytes([5])) + run(5) + rec(MODE, 1, bytes([MODE_DETUMBLE])) + run(5))
    s["rdv_nav_junk"] = (rdv(0) + run(100)
                         + rec(RAW, 3, i32s(2**31 - 1, -2**31, 0, 25000001, -25000001, 0, 0)) + run(50)
                         + rec(DELTA, 20, i16s(30000, 0, 0, 0, 0, 0, 0)) + run(200))
    s["rdv_seq"] = (rdv(0) + run(100) + rec(SEQ_BACK, 1, bytes([50])) + run(20)
                    + rec(SEQ_JUMP, 1, struct.pack("<H", 300)) + run(200))
    return s


def main(argv=None):
    ap = argparse.ArgumentParser(description="Seed corpus for tests/fuzz/fuzz_fsw_step (deterministic).")
    ap.add_argument("out", metavar="OUT_DIR", help="corpus directory, created if missing "
                                                   "(the build tree: nothing generated is committed)")
    out = ap.parse_args(argv).out
    os.makedirs(out, exist_ok=True)
    for name, data in sorted(seeds().items()):
        with open(os.path.join(out, name), "wb") as f:
            f.write(data)
    print(f"mkcorpus_fsw_step: {len(seeds())} seeds in {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
