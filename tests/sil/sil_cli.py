"""`sil run`'s command-line contract (hil_host/sil/README.md), one CTest per mistake class.

    python tests/sil/sil_cli.py --sil SIL --out DIR --case CASE

Cases (CTest sil_cli_<case>):
  upload_file      --upload of a directory, a missing file, an empty file, a 15-byte file
  upload_time      --upload IMG@abc, @-5, @nan, past the run's end, no @T at all
  upload_image     a revision suffix (IMG@T:REV: the revision is the header's), another mission's
                   image, a payload with a bad CRC: refused by the flight loader before the run
  options          --url, --fsw, outputs in a missing directory / a directory / twice the same
                   file, empty values, --upload with the reference, an unknown option
  upload_commits   a RENDEZVOUS image (revision 5) uploaded at 10 s commits when the scheduler is
                   DONE (its commit rule), the table counters show it; a DETUMBLE image at once
  bridge_counters  faulted memq runs: the summary's bridge counters (the bridge core's, end of
                   run) against the injector's counters, exactly
  determinism      a faulted memq run flown twice: verdict yes, equal digests, byte-equal logs;
                   --determinism-check compares two flights itself
  diverged         a detumbling run from 20 deg/s (far outside the design range) diverges: exit 3,
                   the reason in the summary and on stderr
  missed           every frame dropped on the rendezvous: 10 consecutive missed commands at
                   0.1 s are the 1 000 ms deadline exactly (exit 0), 11 are a loss of control (3)

Every refused case asserts: exit 2 (usage), the reason's words on stderr, nothing on stdout, no
summary and no log written (nothing was flown).
"""
import argparse
import filecmp
import os
import subprocess
import sys

import yaml

OBS = "sim/observer/scenarios/s0-5_noise_seed0_mpaper.yaml"
RDV = "sim/impulse/scenarios/rendezvous_example.yaml"

FAILS = []


def check(what, ok, detail=""):
    print("%-4s %s%s" % ("ok" if ok else "FAIL", what, (": " + detail) if detail else ""))
    if not ok:
        FAILS.append(what)


def summary_of(text):
    d = {}
    for line in text.splitlines():
        if " = " in line:
            k, v = line.split(" = ", 1)
            d[k] = v
    return d


class Ctx:
    def __init__(self, sil, out):
        self.sil, self.out = sil, out
        os.makedirs(out, exist_ok=True)

    def path(self, name):
        return os.path.join(self.out, name)

    def scenario(self, name, base, **changes):
        with open(base, encoding="utf-8") as fh:
            scn = yaml.safe_load(fh)
        scn.update(changes)
        p = self.path(name + ".yaml")
        with open(p, "w", encoding="utf-8") as fh:
            yaml.safe_dump(scn, fh, sort_keys=False)
        return p

    def image(self, name, module, table, revision, *sets):
        p = self.path(name)
        cmd = [sys.executable, "-m", "tools.%s" % module, "image", "--table", table, "--revision", str(revision),
               "-o", p]
        for s in sets:
            cmd += ["--set", s]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        return p

    def run(self, args, log=True):
        """sil run with a summary and a log next to it; (rc, stdout, stderr, summary dict)."""
        summ, lg = self.path("run.summary.txt"), self.path("run.lcmlog")
        for f in (summ, lg):
            if os.path.exists(f):
                os.remove(f)
        cmd = [self.sil, "run"] + args + ["--summary", summ] + (["--log", lg] if log else [])
        r = subprocess.run(cmd, capture_output=True, text=True)
        s = {}
        if os.path.exists(summ):
            with open(summ, encoding="utf-8") as fh:
                s = summary_of(fh.read())
        return r.returncode, r.stdout, r.stderr, s

    def refused(self, what, args, words):
        """The run is refused before it starts: exit 2, words on stderr, nothing flown."""
        summ, lg = self.path("run.summary.txt"), self.path("run.lcmlog")
        rc, out, err, _ = self.run(args)
        last = err.strip().splitlines()[-1] if err.strip() else ""
        flown = out != "" or os.path.exists(summ) or os.path.exists(lg)
        missing = [w for w in words if w not in err]
        check(what, rc == 2 and not missing and not flown and "Traceback" not in err and "terminate" not in err,
              "rc %d%s%s | %s" % (rc, ", FLOWN" if flown else "", (", missing %r" % missing) if missing else "", last))


def case_upload_file(c):
    d = c.path("a_dir")
    os.makedirs(d, exist_ok=True)
    empty, short = c.path("empty.bin"), c.path("short.bin")
    open(empty, "wb").close()
    with open(short, "wb") as fh:
        fh.write(b"\x01\x0b" + bytes(13))
    c.refused("directory", ["--scenario", OBS, "--upload", d + "@1"], ["'%s': not a regular file" % d])
    c.refused("missing file", ["--scenario", OBS, "--upload", c.path("nope.bin") + "@1"],
              ["cannot be read (No such file or directory)"])
    c.refused("empty file", ["--scenario", OBS, "--upload", empty + "@1"],
              ["0 bytes, shorter than the 16-byte table header"])
    c.refused("15-byte file", ["--scenario", OBS, "--upload", short + "@1"],
              ["15 bytes, shorter than the 16-byte table header"])


def case_upload_time(c):
    img = c.image("obs_rev5.bin", "observer", "obs_50hz_paper", 5)
    for t, words in (("abc", ["time 'abc' is not a non-negative number of seconds"]),
                     ("-5", ["time '-5' is not a non-negative number of seconds"]),
                     ("nan", ["time 'nan' is not a non-negative number of seconds"]),
                     ("", ["expected IMAGE@T_S"]),
                     ("120", ["time 120 s is not inside the run (duration 120"]),   # S0-5 is 120 s long
                     ("1e9", ["time 1e9 s is not inside the run"])):
        c.refused("upload time '%s'" % t, ["--scenario", OBS, "--upload", img + ("@" + t if t else "")], words)
    c.refused("no @ at all", ["--scenario", OBS, "--upload", img], ["expected IMAGE@T_S"])


def case_upload_image(c):
    img = c.image("obs_rev5.bin", "observer", "obs_50hz_paper", 5)
    c.refused("revision suffix", ["--scenario", OBS, "--upload", img + "@5:3"],
              ["no revision suffix: table id and revision come from the image header"])
    c.refused("revision suffix, non-numeric", ["--scenario", OBS, "--upload", img + "@5:x"],
              ["no revision suffix"])
    imp = c.image("imp_rev5.bin", "impulse", "imp_default", 5)
    c.refused("another mission's image", ["--scenario", OBS, "--upload", imp + "@1"],
              ["(table id 0x0B04) refused by the DETUMBLE flight loader", "UPLOAD_ID"])
    crc = c.image("obs_badcrc.bin", "observer", "obs_50hz_paper", 5, "hdr.crc=1234")
    c.refused("bad CRC", ["--scenario", OBS, "--upload", crc + "@1"], ["refused by the DETUMBLE flight loader", "CRC"])


def case_options(c):
    img = c.image("obs_rev5.bin", "observer", "obs_50hz_paper", 5)
    d = c.path("a_dir")
    os.makedirs(d, exist_ok=True)
    c.refused("--url bogus", ["--scenario", OBS, "--url", "bogus://x"], ["--url bogus://x: sil run flies over memq://"])
    c.refused("--url empty", ["--scenario", OBS, "--url", ""], ["--url", "must not be empty"])
    c.refused("--fsw unknown", ["--scenario", OBS, "--fsw", "float"],
              ["--fsw float: not a flight software of the DETUMBLE mission (fixed, ref, ref-per-axis)"])
    c.refused("--fsw ref with --upload", ["--scenario", OBS, "--fsw", "ref", "--upload", img + "@1"],
              ["--upload needs --fsw fixed"])
    c.refused("--summary-json in a missing directory", ["--scenario", OBS, "--summary-json", c.path("no/dir/s.json")],
              ["does not exist"])
    c.refused("--summary-json is a directory", ["--scenario", OBS, "--summary-json", d], ["is a directory"])
    c.refused("--summary-json and --summary the same file",
              ["--scenario", OBS, "--summary-json", c.path("run.summary.txt")],
              ["--summary and --summary-json name the same file"])
    c.refused("--scenario a directory", ["--scenario", d], ["--scenario"])
    c.refused("--scenario missing", ["--scenario", c.path("none.yaml")], ["--scenario"])
    c.refused("unknown option", ["--scenario", OBS, "--revision", "3"], ["--revision"])
    c.refused("--progress with a value", ["--scenario", OBS, "--progress=7"], ["progress was given a disallowed flag override"])


def case_upload_commits(c):
    imp = c.image("imp_rev5.bin", "impulse", "imp_default", 5)
    rc, _, err, s = c.run(["--scenario", RDV, "--upload", imp + "@10"], log=False)
    check("rendezvous upload flies", rc == 0 and s.get("plant_end") == "completed", "rc %d %s" % (rc, err.strip()))
    check("one upload accepted, none rejected",
          s.get("table_uploads_accepted") == "1" and s.get("table_uploads_rejected") == "0", str(s.get("table_uploads_accepted")))
    check("executive committed once", s.get("fsw_n_tbl_acc") == "1" and s.get("fsw_n_tbl_rej") == "0")
    check("active revision 1 -> 5", s.get("table_revision_boot") == "1" and s.get("table_revision_active") == "5"
          and s.get("fsw_tbl_revision") == "5", "%s -> %s" % (s.get("table_revision_boot"), s.get("table_revision_active")))
    # The impulse commit rule (fsw/impulse/imp_mission.c) holds the image while the scheduler
    # flies the mission: the commit is the first step after DONE (1060.0 s), one period later.
    check("commit at the scheduler's boundary", s.get("t_first_DONE") == "1060.0" and s.get("t_table_commit_s") == "1060.10",
          "DONE %s, commit %s" % (s.get("t_first_DONE"), s.get("t_table_commit_s")))
    obs = c.image("obs_rev5.bin", "observer", "obs_50hz_paper", 5)
    rc, _, err, s = c.run(["--scenario", OBS, "--upload", obs + "@10"], log=False)
    check("detumbling upload commits at the next step", rc == 0 and s.get("table_revision_active") == "5"
          and s.get("t_table_commit_s") == "10.00" and s.get("table_uploads_accepted") == "1",
          "rc %d commit %s rev %s" % (rc, s.get("t_table_commit_s"), s.get("table_revision_active")))


def ints(s, *keys):
    return [int(s[k]) for k in keys]


def case_bridge_counters(c):
    # Each delivered frame is classified by the bridge exactly once (stepped, duplicate, stale,
    # malformed, or refused on its crc32 / time rule / sequence window), so with the core's own final counters the sum equals the injector's deliveries;
    # the last telemetry frame cannot count a duplicate or stale frame that arrives after it.
    runs = {
        "dup": {"seed": 7, "dup_ppm": 20000},
        "truncate": {"seed": 11, "truncate_ppm": 20000},
        "mixed": {"seed": 11, "drop_ppm": 30000, "dup_ppm": 30000, "reorder_ppm": 30000, "reorder_window": 3,
                  "truncate_ppm": 10000, "bitflip_ppm": 10000},
        "bitflip": {"seed": 1058, "bitflip_ppm": 10000},
    }
    for name, faults in runs.items():
        scn = c.scenario("faults_" + name, OBS, faults=faults)
        rc, _, err, s = c.run(["--scenario", scn], log=False)
        check("%s: flown in control" % name, rc == 0, err.strip())
        if rc != 0:
            continue
        check("%s: counters are the bridge core's" % name, s.get("bridge_counters_from") == "bridge core, end of run")
        delivered, = ints(s, "fault_delivered")
        st, du, sl, ma = ints(s, "bridge_stepped", "bridge_dups", "bridge_stale", "bridge_malformed")
        cr, tr, jr = ints(s, "bridge_crc_rej", "bridge_time_rej", "bridge_jump_rej")
        check("%s: delivered %d == stepped + dups + stale + malformed + crc/time/jump refusals" % (name, delivered),
              delivered == st + du + sl + ma + cr + tr + jr, "%d + %d + %d + %d + %d + %d + %d" % (st, du, sl, ma, cr, tr, jr))
        check("%s: bridge missed == plant missed" % name, s["bridge_missed"] == s["plant_missed"])
        check("%s: rejected == malformed + range + nonfinite + table + crc + time + jump" % name,
              int(s["bridge_rejected"]) == ma + cr + tr + jr +
              sum(ints(s, "bridge_range_rej", "bridge_nonfinite_rej", "bridge_table_rej")))
        if name == "bitflip":
            # every flipped transmission refused (crc32, or the fingerprint) and re-sent, nothing else
            check("bitflip: crc_rej + malformed == injected flips == re-sent frames > 0",
                  int(s["fault_bitflipped"]) > 0 and cr + ma == int(s["fault_bitflipped"]) == int(s["plant_retx"]),
                  "%d + %d, %s, %s" % (cr, ma, s["fault_bitflipped"], s["plant_retx"]))
            check("bitflip: no time or window refusal, no range rejection", tr + jr + int(s["bridge_range_rej"]) == 0)
        if name == "dup":
            check("dup: bridge dups == injected duplicates > 0", int(s["fault_duplicated"]) > 0
                  and s["bridge_dups"] == s["fault_duplicated"] == s["plant_dup_cmds"],
                  "%s %s %s" % (s["bridge_dups"], s["fault_duplicated"], s["plant_dup_cmds"]))
            check("dup: every period stepped once", s["bridge_stepped"] == s["plant_steps"])
        if name == "truncate":
            check("truncate: bridge malformed == injected truncations == re-sent frames > 0",
                  int(s["fault_truncated"]) > 0 and s["bridge_malformed"] == s["fault_truncated"] == s["plant_retx"],
                  "%s %s %s" % (s["bridge_malformed"], s["fault_truncated"], s["plant_retx"]))


def case_determinism(c):
    scn = c.scenario("det", OBS, faults={"seed": 11, "drop_ppm": 30000, "dup_ppm": 30000, "reorder_ppm": 30000,
                                         "reorder_window": 3, "truncate_ppm": 10000})
    logs, sums = [], []
    for i in range(2):
        rc, _, err, s = c.run(["--scenario", scn])
        log = c.path("det%d.lcmlog" % i)
        os.replace(c.path("run.lcmlog"), log)
        logs.append(log)
        sums.append(s)
        check("flight %d: faulted (%s re-sent) and deterministic = yes" % (i, s.get("plant_retx")),
              rc == 0 and int(s.get("plant_retx", "0")) > 0 and s.get("deterministic") == "yes", err.strip())
    check("equal command/telemetry digests",
          sums[0]["stream_digest_cmd"] == sums[1]["stream_digest_cmd"] and
          sums[0]["stream_digest_tlm"] == sums[1]["stream_digest_tlm"], sums[0]["stream_digest_tlm"])
    check("byte-identical logs", filecmp.cmp(logs[0], logs[1], shallow=False))
    rc, _, err, s = c.run(["--scenario", scn, "--determinism-check"], log=False)
    check("--determinism-check: two flights compared, yes", rc == 0 and s.get("deterministic") == "yes" and
          s.get("deterministic_basis") == "two flights compared (stream digests)" and
          s.get("stream_digest_tlm") == sums[0]["stream_digest_tlm"], "%s / %s" % (s.get("deterministic"), err.strip()))
    # The digest can tell streams apart: another fault seed gives other streams.
    other = c.scenario("det_other", OBS, faults={"seed": 12, "drop_ppm": 30000, "dup_ppm": 30000,
                                                 "reorder_ppm": 30000, "reorder_window": 3, "truncate_ppm": 10000})
    _, _, _, s2 = c.run(["--scenario", other], log=False)
    check("another seed, another digest", s2.get("stream_digest_cmd") != sums[0]["stream_digest_cmd"])


def case_diverged(c):
    scn = c.scenario("w20", OBS, w0_degps=[20.0, 20.0])
    rc, out, err, s = c.run(["--scenario", scn], log=False)
    check("exit 3 (loss of control)", rc == 3, "rc %d" % rc)
    check("summary flown and written", s.get("plant_diverged") == "1" and out != "")
    reason = s.get("loss_of_control_reason", "")
    check("reason in the summary", s.get("loss_of_control") == "1" and reason.startswith("PLANT_DIVERGED: DIVERGED at t = ")
          and "deg > 30 deg" in reason, reason)
    check("reason on stderr", "sil: LOSS OF CONTROL: PLANT_DIVERGED: DIVERGED at t = " in err, err.strip())
    # The nominal start stays in control (the rule does not fire on everything).
    rc, _, err, s = c.run(["--scenario", OBS], log=False)
    check("S0-5 nominal: exit 0, loss_of_control 0", rc == 0 and s.get("loss_of_control") == "0"
          and s.get("loss_of_control_reason") == "none", err.strip())


def case_missed(c):
    for dur, want_rc in ((1.0, 0), (1.1, 3)):
        scn = c.scenario("drop_all_%g" % dur, RDV, duration_s=dur, faults={"seed": 3, "drop_ppm": 1000000})
        rc, _, err, s = c.run(["--scenario", scn], log=False)
        n = round(dur / 0.1)
        check("%d consecutive missed commands of 0.1 s (bound 10): exit %d" % (n, want_rc),
              rc == want_rc and s.get("plant_missed_run_max") == str(n) and s.get("plant_missed_run_bound") == "10"
              and s.get("plant_diverged") == "0", "rc %d, %s" % (rc, err.strip()))
        reason = s.get("loss_of_control_reason", "")
        if want_rc:
            check("reason names the missed commands and the deadline",
                  reason.startswith("MISSED_COMMANDS: 11 consecutive missed commands")
                  and "lockstep.deadline_ms = 1000 ms" in reason and "LOSS OF CONTROL: MISSED_COMMANDS" in err, reason)
        else:
            check("in control at the bound", s.get("loss_of_control") == "0" and reason == "none", reason)


CASES = {k[5:]: v for k, v in globals().items() if k.startswith("case_")}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sil", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--case", required=True, choices=sorted(CASES))
    a = ap.parse_args(argv)
    CASES[a.case](Ctx(os.path.abspath(a.sil), os.path.join(a.out, a.case)))
    print("%s: %s" % (a.case, "FAILED " + ", ".join(FAILS) if FAILS else "all ok"))
    return 1 if FAILS else 0


if __name__ == "__main__":
    sys.exit(main())
