"""Checks a campaign before any run, then flies it on Dask and streams the records to the store.

Check (nothing flies yet): the definition's own errors (spec.py); the base scenario with the
fixed overrides through `sil check` (the C++ scenario parser and the flight table loader); every
dispersion at its extremes (a uniform's ends, a normal's clip or mean +- 4 sigma, every choice and
grid value) through `sil check` — a table dispersion also against the flight loader's limits, by
field name; and a one-period probe run whose summary must hold every metric and criterion key
(the t_first_* keys exist only when their event happens and are exempt).

Run: a Dask client — a LocalCluster of one single-threaded process per core by default, or
`--scheduler tcp://host:8786` for an existing cluster — maps worker.run_one over the runs still
to do. Records are written to the store as they complete (at least every 2 s), so a kill loses
only the unwritten ones, which --resume runs again.
"""
import importlib
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

import yaml

from . import worker
from .spec import CampaignError
from .store import Store

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def default_sil():
    for preset in ("host-release", "host"):
        p = os.path.join(ROOT, "build", preset, "hil_host", "sil", "sil")
        if os.path.exists(p):
            return p
    return os.path.join(ROOT, "build", "host", "hil_host", "sil", "sil")


def _sil_check(sil, scn, where, label):
    path = os.path.join(where, "check.yaml")
    with open(path, "w", encoding="utf-8") as fh:
        yaml.safe_dump(scn, fh, sort_keys=False)
    r = subprocess.run([sil, "check", "--scenario", path], capture_output=True, text=True)
    if r.returncode != 0:
        msg = (r.stderr.strip().splitlines() or ["exit %d" % r.returncode])[-1]
        msg = msg.replace(path, "the scenario").replace("sil: ", "")
        raise CampaignError("%s: %s" % (label, msg))
    return json.loads(r.stdout)


def check(c, sil):
    """Everything that can be known before a run; sets c.mission, c.module, c.table_name."""
    if not os.path.exists(sil):
        raise CampaignError("no sil executable at %s (build the host or host-release preset, or give --sil)" % sil)
    from tools import iface
    tmp = tempfile.mkdtemp(prefix="campaign-check-")
    try:
        base = c.scenario({})
        f = base.get("fsw") or {}
        if f.get("table_file") and not os.path.isabs(f["table_file"]):
            f["table_file"] = os.path.join(os.path.dirname(c.base), f["table_file"])
        info = _sil_check(sil, base, tmp, "base scenario %s with `set`" % os.path.relpath(c.base))
        c.mission = info["mission"]
        c.module = iface.mission(c.mission).module
        c.table_name = info["table"]
        layout = None
        for x in c.dispersions:
            if x.table:
                if f.get("table_file"):
                    raise CampaignError("dispersion %s: the base scenario flies a table file; table dispersions start "
                                        "from a built-in table" % x.path)
                if layout is None:
                    layout = importlib.import_module("tools.%s.image" % c.module).LAYOUT
                field = x.path[len("table."):].split("[")[0]
                if field not in layout.fields:
                    raise CampaignError("dispersion %s: %s's table has no field '%s' (fields: %s)"
                                        % (x.path, c.mission, field, ", ".join(layout.fields)))
            for v in x.extremes():
                values = {x.path: v}
                try:
                    scn = c.scenario(values, "check")
                    sets = c.table_sets(values)
                except CampaignError as e:
                    raise CampaignError("dispersion %s: %s" % (x.path, e))
                if sets:
                    mod = importlib.import_module("tools.%s.image" % c.module)
                    p = dict(mod.params(c.table_name))
                    mod.LAYOUT.apply_sets(p, {}, sets)
                    bad = mod.LAYOUT.check_limits(p)
                    if bad:
                        raise CampaignError("dispersion %s at %r: %s" % (x.path, v, bad[0]))
                    with open(os.path.join(tmp, "table.bin"), "wb") as fh:
                        fh.write(mod.build(c.table_name, 2, sets))
                    scn["fsw"] = {"table_file": os.path.join(tmp, "table.bin")}
                _sil_check(sil, scn, tmp, "dispersion %s at %r" % (x.path, v))
        # The keys a run's summary holds: a one-period probe of the base scenario.
        probe = dict(base, duration_s=2.0 * info["period_us"] * 1e-6, commands=[])
        probe_path = os.path.join(tmp, "probe.yaml")
        with open(probe_path, "w", encoding="utf-8") as fh:
            yaml.safe_dump(probe, fh, sort_keys=False)
        sj = os.path.join(tmp, "probe.json")
        r = subprocess.run([sil, "run", "--scenario", probe_path, "--summary-json", sj], stdout=subprocess.DEVNULL,
                           stderr=subprocess.PIPE, text=True)
        if r.returncode != 0:
            raise CampaignError("probe run of the base scenario failed: %s" % r.stderr.strip())
        with open(sj, encoding="utf-8") as fh:
            keys = set(json.load(fh))
        for k in list(c.metrics) + [k for k, _, _, _ in c.criteria]:
            if k not in keys and not k.startswith("t_first_"):
                raise CampaignError("metric or criterion key '%s' is not in a %s run's summary (keys: %s)"
                                    % (k, c.mission, ", ".join(sorted(keys))))
        return info
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def run(c, out, sil, workers=None, scheduler=None, resume=False, stop_after=None, progress=True):
    """Flies the runs not yet in the store. stop_after: stop after that many completions (a kill
    the tests can reproduce). Returns the number of runs written."""
    from dask.distributed import Client, LocalCluster, as_completed
    from tqdm import tqdm

    store = Store(out)
    done = store.begin(c, resume)
    todo = [i for i in range(c.runs) if i not in done]
    print("campaign %s: %s, %d runs (%d done, %d to fly), seed %d, sil %s"
          % (c.name, c.mission, c.runs, len(done), len(todo), c.seed, sil), flush=True)
    if not todo:
        return 0
    if scheduler:
        client = Client(scheduler)
        cluster = None
    else:
        n = workers or os.cpu_count() or 1
        cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=":0",
                               silence_logs=40)
        client = Client(cluster)
    print("dask: %s, %d workers; dashboard %s" % (scheduler or "LocalCluster", len(client.scheduler_info()["workers"]),
                                                 client.dashboard_link), flush=True)
    written = 0
    failures = 0
    buf = []
    last = time.monotonic()
    try:
        futures = client.map(worker.run_one, [c] * len(todo), todo, [sil] * len(todo), pure=False)
        bar = tqdm(total=len(todo), unit="run", disable=not progress, file=sys.stderr)
        for fut in as_completed(futures):
            try:
                rec = fut.result()
            except Exception as e:   # a worker lost: recorded, not dropped
                i = todo[futures.index(fut)]
                rec = {"run": i, "status": "error", "passed": False, "reason": "worker: %s" % e, "wall_s": float("nan")}
            buf.append(rec)
            failures += 0 if rec["passed"] else 1
            bar.update(1)
            bar.set_postfix(failed=failures)
            if time.monotonic() - last > 2.0 or len(buf) >= 100:
                store.write(buf)
                written += len(buf)
                buf = []
                last = time.monotonic()
            if stop_after is not None and written + len(buf) >= stop_after:
                break
        store.write(buf)
        written += len(buf)
        bar.close()
        for f in futures:
            f.cancel()
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    print("campaign %s: %d runs written to %s (%d not passed)" % (c.name, written, store.dir, failures), flush=True)
    return written
