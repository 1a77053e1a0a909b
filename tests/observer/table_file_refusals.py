"""A scenario naming a bad table file never flies (CTest sil_table_file_refusals, label sil).

    python tests/observer/table_file_refusals.py --sil SIL --template SCENARIO.yaml --out DIR

Three images from the ground tools' independent writers (never the flight encoder): a payload
CRC that does not match (tools.observer image --set hdr.crc), an out-of-range field
(kappa_lo_q28 = 0, below its allowed [1, INT32_MAX]) and another mission's table (the impulse
default, id 0x0B04). For each, `sil run` on the template with `fsw: {table_file}` must exit
non-zero before the run starts (no summary written), with the flight loader's verdict in words:
the reason, the field and its allowed range, or the table ids.
"""
import argparse
import os
import subprocess
import sys

import yaml

CASES = [
    ("crc", ["tools.observer", "image", "--table", "obs_50hz_phys", "--set", "hdr.crc=1234"],
     ["refused by the DETUMBLE flight loader", "CRC"]),
    ("range", ["tools.observer", "image", "--table", "obs_50hz_phys", "--set", "kappa_lo_q28=0"],
     ["RANGE_LO: field 22 (kappa_lo_q28) below its allowed [1, 2147483647]"]),
    ("other_mission", ["tools.impulse", "image", "--table", "imp_default"],
     ["(table id 0x0B04)", "UPLOAD_ID", "the DETUMBLE table is 0x0B01"]),
]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sil", required=True)
    ap.add_argument("--template", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args(argv)
    os.makedirs(a.out, exist_ok=True)
    with open(a.template, encoding="utf-8") as fh:
        base = yaml.safe_load(fh)
    bad = 0
    for name, tool, want in CASES:
        img = os.path.join(a.out, name + ".bin")
        subprocess.run([sys.executable, "-m"] + tool + ["--revision", "3", "-o", img], check=True,
                       stdout=subprocess.DEVNULL)
        scn = dict(base, fsw={"table_file": name + ".bin"})
        path = os.path.join(a.out, name + ".yaml")
        with open(path, "w", encoding="utf-8") as fh:
            yaml.safe_dump(scn, fh, sort_keys=False)
        summary = os.path.join(a.out, name + ".summary.json")
        if os.path.exists(summary):
            os.remove(summary)
        r = subprocess.run([a.sil, "run", "--scenario", path, "--summary-json", summary], capture_output=True, text=True)
        msg = (r.stdout + r.stderr).strip().splitlines()
        last = msg[-1] if msg else ""
        ok = r.returncode != 0 and all(w in last for w in want) and not os.path.exists(summary)
        print("%-4s %-14s rc %d: %s" % ("ok" if ok else "FAIL", name, r.returncode, last))
        bad += 0 if ok else 1
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
