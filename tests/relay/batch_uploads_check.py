"""CTest sil_batch_table_file_matches_memq: the batch driver takes table images by the same upload
path as the memq SIL. A RELAY run of 600 s (the adapter commits a new table at a window end, 500 s)
that boots from a table file (rly_fixed_031, revision 2)
and takes an upload of rly_default (revision 3) at 30 s is flown over memq and with --batch: the
command and telemetry streams are identical (digests), both images were accepted, revision 3 is
active at the end; a batch run without the upload has a different telemetry stream (the upload acted).

    python tests/relay/batch_uploads_check.py SIL OUT_DIR
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
    subprocess.run([sil, "run", "--scenario", scn, "--summary-json", sj] + extra, check=True,
                   stdout=subprocess.DEVNULL)
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
    s["name"] = "relay_batch_uploads"
    s["fsw"] = {"table_file": boot}
    s["duration_s"] = 600
    scn = os.path.join(out, "scenario.yaml")
    with open(scn, "w", encoding="utf-8") as fh:
        yaml.safe_dump(s, fh)
    upl = ["--upload", up + "@30"]
    m = fly(sil, scn, out, "memq", upl)
    b = fly(sil, scn, out, "batch", upl + ["--batch"])
    n = fly(sil, scn, out, "batch_no_upload", ["--batch"])
    keys = ("stream_digest_cmd", "stream_digest_tlm", "table_uploads_accepted", "table_uploads_rejected",
            "table_revision_active", "steps_tlm")
    for k in keys:
        print("%-24s memq %-18s batch %-18s no upload %s" % (k, m.get(k), b.get(k), n.get(k)))
    assert b["transport"] == "batch" and m["transport"] != "batch", (b["transport"], m["transport"])
    for k in keys:
        assert m[k] == b[k], k
    assert int(b["table_uploads_accepted"]) == 2 and int(b["table_uploads_rejected"]) == 0
    assert int(b["table_revision_active"]) == 3 and int(n["table_revision_active"]) == 2
    assert n["stream_digest_tlm"] != b["stream_digest_tlm"]
    print("batch = memq with a table file and an upload")


if __name__ == "__main__":
    main()
