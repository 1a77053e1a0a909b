"""One campaign run: the base scenario with run i's inputs, flown by `sil run` (the in-process
lock-step driver: plant, bridge and fsw_step on LCM's in-process memq provider, no sockets; with
`driver: batch`, `sil run --batch`: the same streams without LCM), its
summary.json read back. Runs on a Dask worker: everything it needs travels in the Campaign object
and the sil path, so a worker on another machine needs only the project built at the same path
and its venv (README "Campaigns")."""
import importlib
import json
import os
import shutil
import subprocess
import tempfile
import time

import yaml

STATUS = ("ok", "fail", "error", "timeout")


def _image(c, sets):
    mod = importlib.import_module("tools.%s.image" % c.module)
    return mod.build(c.table_name, 2, sets)


def materialise(c, i, where, name_suffix=None):
    """Writes run i's scenario (and its table image, when the table is dispersed) into `where`;
    returns (scenario path, inputs)."""
    values = c.inputs(i)
    scn = c.scenario(values, name_suffix if name_suffix is not None else "run%d" % i)
    # Paths the base names relative to itself stay valid from another folder.
    f = scn.get("fsw") or {}
    if f.get("table_file") and not os.path.isabs(f["table_file"]):
        f["table_file"] = os.path.join(os.path.dirname(c.base), f["table_file"])
    sets = c.table_sets(values)
    if sets:
        with open(os.path.join(where, "table.bin"), "wb") as fh:
            fh.write(_image(c, sets))
        scn["fsw"] = {"table_file": "table.bin"}
    path = os.path.join(where, "scenario.yaml")
    with open(path, "w", encoding="utf-8") as fh:
        yaml.safe_dump(scn, fh, sort_keys=False)
    return path, values


def run_one(c, i, sil):
    """The record of run i: run, status, passed, reason, wall_s, in.<path>..., m.<metric>..."""
    t0 = time.monotonic()
    rec = {"run": i, "status": "error", "passed": False, "reason": ""}
    tmp = tempfile.mkdtemp(prefix="campaign-%s-%d-" % (c.name, i))
    try:
        path, values = materialise(c, i, tmp)
        for p, v in values.items():
            rec["in." + p] = v
        sj = os.path.join(tmp, "summary.json")
        try:
            drv = ["--batch"] if c.driver == "batch" else []
            r = subprocess.run([sil, "run", "--scenario", path, "--summary-json", sj] + drv, stdout=subprocess.DEVNULL,
                               stderr=subprocess.PIPE, text=True, timeout=c.timeout_s)
        except subprocess.TimeoutExpired:
            rec.update(status="timeout", reason="no result within %g s" % c.timeout_s)
            return rec
        # Exit 3: flown, but control was lost (plant diverged, or too many consecutive missed
        # commands; hil_host/sil/README.md): a failed run with its summary, not an error.
        lost = r.returncode == 3 and os.path.exists(sj)
        if (r.returncode != 0 and not lost) or not os.path.exists(sj):
            last = (r.stderr.strip().splitlines() or ["exit %d" % r.returncode])[-1]
            rec.update(status="error", reason=last[:300])
            return rec
        with open(sj, encoding="utf-8") as fh:
            s = json.load(fh)
        for k in c.metrics:
            v = s.get(k)
            rec["m." + k] = float(v) if isinstance(v, (int, float)) else float("nan")
        for k, _, _, _ in c.criteria:
            v = s.get(k)
            rec.setdefault("m." + k, float(v) if isinstance(v, (int, float)) else float("nan"))
        ok, why = c.passed({k[2:]: v for k, v in rec.items() if k.startswith("m.")})
        if lost:
            ok, why = False, "loss of control: %s" % s.get("loss_of_control_reason", "?")
        rec.update(status="ok" if ok else "fail", passed=ok, reason=why)
        return rec
    except Exception as e:   # any problem becomes this run's record, never a lost run
        rec.update(status="error", reason=("%s: %s" % (type(e).__name__, e))[:300])
        return rec
    finally:
        rec["wall_s"] = time.monotonic() - t0
        shutil.rmtree(tmp, ignore_errors=True)
