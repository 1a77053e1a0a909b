#!/usr/bin/env python3
"""check_stack.py - the painted stack high-water mark of every PIL run never exceeds the static
worst path of the board image (spec 00 §9 "worst-case stack"; issue 16 acceptance).

Usage: check_stack.py STATIC_JSON SUMMARY_JSON...
  STATIC_JSON   tools/stack_sum.py's report of the PIL image (CTest lint_stack_sum_pil), root
                board_reset_handler (the whole image: reset -> main -> session -> fsw_step)
  SUMMARY_JSON  `sil run --pil ... --summary-json` outputs (key pil_board_stack_used)
Exit 0 when every measured value is <= the static bound (and > 0: a run that measured nothing
proves nothing), 1 otherwise; prints one line per run.
"""
import json
import sys


def main(argv):
    if len(argv) < 3:
        print(__doc__)
        return 2
    with open(argv[1]) as fh:
        roots = {r["function"]: r for r in json.load(fh)["roots"]}
    bound = roots["board_reset_handler"]["worst"]
    ok = True
    for p in argv[2:]:
        with open(p) as fh:
            used = int(json.load(fh)["pil_board_stack_used"])
        good = 0 < used <= bound
        ok = ok and good
        print("%s: painted high-water %d B, static bound %d B (%s): %s" % (
            p, used, bound, " -> ".join(roots["board_reset_handler"]["path"][:4]) + " ...", "ok" if good else "FAIL"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
