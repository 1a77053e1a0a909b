"""The campaign's results: a folder of Parquet parts (pandas + pyarrow), written run by run as
they complete, each part atomically (a temporary name, then a rename), so a campaign killed at any
moment leaves whole parts only and `--resume` finds exactly the runs that are done.

    OUT/campaign.json         what is being run (name, runs, seed, a hash of the definition)
    OUT/results/part-*.parquet
"""
import glob
import hashlib
import json
import os

import pandas as pd


class Store(object):
    def __init__(self, out):
        self.out = os.path.abspath(out)
        self.dir = os.path.join(self.out, "results")

    def meta_path(self):
        return os.path.join(self.out, "campaign.json")

    def begin(self, c, resume):
        """Checks (resume) or writes the campaign's identity; returns the runs already done."""
        import numpy
        # numpy's Generator streams are stable within a release series, not promised across
        # them (NEP 19): the store names the numpy that drew its inputs, and a resume under
        # another refuses rather than mixing two draws.
        meta = {"name": c.name, "runs": c.runs, "seed": c.seed, "digest": digest(c), "campaign": c.path,
                "base": c.base, "mission": c.mission, "numpy": numpy.__version__}
        parts = glob.glob(os.path.join(self.dir, "part-*.parquet"))
        if os.path.exists(self.meta_path()):
            with open(self.meta_path(), encoding="utf-8") as fh:
                old = json.load(fh)
            if parts and not resume:
                raise SystemExit("campaign: %s already holds results of '%s'; --resume to continue it, or another --out"
                                 % (self.out, old.get("name")))
            if parts and old.get("numpy", meta["numpy"]) != meta["numpy"]:
                raise SystemExit("campaign: %s was drawn with numpy %s, this is %s: its inputs might differ; not resuming"
                                 % (self.out, old.get("numpy"), meta["numpy"]))
            if parts and old.get("digest") != meta["digest"]:
                raise SystemExit("campaign: %s holds results of another definition (%s, digest %s); not resuming"
                                 % (self.out, old.get("campaign"), old.get("digest")))
        os.makedirs(self.dir, exist_ok=True)
        with open(self.meta_path(), "w", encoding="utf-8") as fh:
            json.dump(meta, fh, indent=1)
        return set(self.load()["run"].tolist()) if parts else set()

    def write(self, records):
        if not records:
            return
        n = len(glob.glob(os.path.join(self.dir, "part-*.parquet")))
        while True:
            path = os.path.join(self.dir, "part-%06d.parquet" % n)
            if not os.path.exists(path):
                break
            n += 1
        tmp = path + ".tmp"
        pd.DataFrame.from_records(records).to_parquet(tmp, index=False)
        os.replace(tmp, path)

    def load(self):
        """Every run's record, one row per run, sorted by run."""
        parts = sorted(glob.glob(os.path.join(self.dir, "part-*.parquet")))
        if not parts:
            return pd.DataFrame({"run": []})
        df = pd.concat([pd.read_parquet(p) for p in parts], ignore_index=True)
        return df.drop_duplicates("run", keep="first").sort_values("run").reset_index(drop=True)


def digest(c):
    """The definition's identity: its own text and its base scenario's."""
    h = hashlib.sha256()
    for p in (c.path, c.base):
        with open(p, "rb") as fh:
            h.update(fh.read())
    return h.hexdigest()[:16]
