"""CTest pil_rly_uploads_match_sil: table uploads through a board (the link's TABLE_CHUNK / TABLE_ACK,
the board's staging and LIMITS) fly exactly as in SIL. The RELAY run of sil_batch_table_file_matches_memq
(600 s, booted from a table file rly_fixed_031 rev 2, rly_default rev 3 uploaded at 30 s and committed at
a window end) is flown with the board session in-process (`--pil-loopback`) and `--compare-sil`: the
command and telemetry streams equal SIL's, both images accepted, revision 3 active at the end; and again
with 5 % of the link's frames lost and 5 % bit-flipped each way, where the re-sent chunks are answered
from the board's ack cache (an upload's last chunk applied twice would be refused BUSY and counted):
the streams still equal SIL's. Up to 20 re-sends: a step's exchange (SENSOR, CMD, TLM) survives these
faults with p = 0.9^3 = 0.73, so with 8 re-sends (the fault rows' setting, over 1 500 steps) one of
these 600 000 steps is expected to fail all nine (measured: 1, counted as pil_missed_steps, and the
plant then holds a command SIL did not, so the streams differ); with 20, 0.27^21 ~ 1e-12 a step.

    python tests/relay/pil_uploads_check.py SIL OUT_DIR [--clean-only]
    (--clean-only: the sanitizer build, about 4 x slower, flies the clean run only)
"""
import json
import os
import shutil
import subprocess
import sys

import yaml

from tools.relay import image

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def fly(sil, scn, out, name, extra):
    sj = os.path.join(out, name + ".json")
    p = subprocess.run([sil, "run", "--scenario", scn, "--summary-json", sj, "--pil-loopback", "--compare-sil",
                        "--pil-dir", out] + extra, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    assert p.returncode == 0, (name, p.returncode, p.stderr[-600:])
    with open(sj, encoding="utf-8") as fh:
        return json.load(fh)


def main():
    sil, out = sys.argv[1], sys.argv[2]
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    boot, up = os.path.join(out, "boot.bin"), os.path.join(out, "up.bin")
    with open(boot, "wb") as fh:
        fh.write(image.build("rly_fixed_031", 2))
    with open(up, "wb") as fh:
        fh.write(image.build("rly_default", 3))
    with open(os.path.join(ROOT, "sim/relay/scenarios/relay_short.yaml"), encoding="utf-8") as fh:
        s = yaml.safe_load(fh)
    s["name"] = "relay_pil_uploads"
    s["fsw"] = {"table_file": boot}
    s["duration_s"] = 600
    scn = os.path.join(out, "scenario.yaml")
    with open(scn, "w", encoding="utf-8") as fh:
        yaml.safe_dump(s, fh)
    upl = ["--upload", up + "@30"]
    clean = fly(sil, scn, out, "clean", upl)
    runs = [("clean", clean)]
    if "--clean-only" not in sys.argv[3:]:
        faulty = fly(sil, scn, out, "faulty", upl + ["--pil-faults", "drop=0.05,flip=0.05,seed=5", "--pil-retx", "20",
                                                   "--pil-timeout-ms", "50"])
        runs.append(("faulty", faulty))
    for name, r in runs:
        print("%-6s same streams %s, uploads accepted %s rejected %s, revision %s, retx %s, board dups %s" % (
            name, r["pil_vs_sil_same_streams"], r["table_uploads_accepted"], r["table_uploads_rejected"],
            r["table_revision_active"], r["pil_retx"], r.get("pil_board_dups")))
        assert int(r["pil_vs_sil_same_streams"]) == 1, name
        assert int(r["table_uploads_accepted"]) == 2 and int(r["table_uploads_rejected"]) == 0, name
        assert int(r["table_revision_active"]) == 3, name
        assert int(r["pil_missed_steps"]) == 0 and int(r["pil_link_down"]) == 0, name
    if len(runs) > 1:
        assert int(faulty["pil_retx"]) > 0 and int(faulty["pil_fault_dropped"]) > 0, "the faults did not act"
    print("uploads through the board = SIL (%s)" % ", ".join(n for n, _ in runs))


if __name__ == "__main__":
    main()
