#!/usr/bin/env bash
# The campaign runner's acceptance, at full size (tools/campaign/README.md; ~25 min on 2 cores):
# 1 000-run observer and rendezvous campaigns with their reports, each flown again with another
# worker count and compared; the rendezvous killed (kill -9, runner and cluster) after 70 s and
# resumed; the rendezvous on a separately started scheduler (port 8786) with two workers; and the
# throughput benchmark (a plain loop against the runner with 1 and 2 workers).
#   bash tools/campaign/acceptance.sh 2>&1 | tee acceptance.log
set -u
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
PY=.venv/bin/python
C="$PY -m tools.campaign"
T() { local s=$(date +%s.%N); "$@"; local e=$(date +%s.%N); echo "TIME $(echo "$e - $s" | bc) s: $*"; }
R=tools/impulse/campaigns/rdv_box.yaml
O=tools/observer/campaigns/detumble_dispersed.yaml
B=build/campaigns
rm -rf $B/detumble $B/detumble_w1 $B/rdv_box $B/rdv_box_w1 $B/rdv_killed $B/rdv_ext $B/rdv100_w1 $B/rdv100_w2
T $C run $O --out $B/detumble --workers 2 --no-progress | grep -E "passed |status  |runs written|TIME"
T $C run $R --out $B/rdv_box --workers 2 --no-progress | grep -E "passed |status  |runs written|TIME"
T $C run $O --out $B/detumble_w1 --workers 1 --no-progress --no-report | grep -E "runs written|TIME"
$C compare $B/detumble $B/detumble_w1
T $C run $R --out $B/rdv_box_w1 --workers 1 --no-progress --no-report | grep -E "runs written|TIME"
$C compare $B/rdv_box $B/rdv_box_w1
# kill -9 the whole campaign (runner and its LocalCluster) halfway, then resume
setsid $C run $R --out $B/rdv_killed --workers 2 --no-progress --no-report > /tmp/killed.log 2>&1 &
pid=$!
sleep 70
n=$($PY -c "import sys; sys.path.insert(0,'.'); from tools.campaign.store import Store; print(len(Store('$B/rdv_killed').load()))")
echo "before kill: $n runs recorded"
kill -9 -- -$pid; sleep 2
n=$($PY -c "import sys; sys.path.insert(0,'.'); from tools.campaign.store import Store; print(len(Store('$B/rdv_killed').load()))")
echo "after kill -9: $n runs recorded"
T $C run $R --out $B/rdv_killed --workers 2 --resume --no-progress --no-report | grep -E "campaign rdv-box:|TIME"
$PY - <<'PY'
import glob, pandas as pd
d = pd.concat([pd.read_parquet(p) for p in glob.glob("build/campaigns/rdv_killed/results/part-*.parquet")])
print("killed+resumed store: %d rows, %d unique runs, duplicates %d" % (len(d), d.run.nunique(), len(d) - d.run.nunique()))
PY
$C compare $B/rdv_box $B/rdv_killed
# a separately started scheduler and two workers
$PY - <<'PY'
import json, os, subprocess, time
from dask.distributed import Client
dask = ".venv/bin/dask"
sf = "/tmp/sched_acc.json"
if os.path.exists(sf): os.remove(sf)
ps = [subprocess.Popen([dask, "scheduler", "--port", "8786", "--dashboard-address", ":8787", "--scheduler-file", sf], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
while not os.path.exists(sf): time.sleep(0.1)
for _ in range(2):
    ps.append(subprocess.Popen([dask, "worker", "tcp://127.0.0.1:8786", "--nthreads", "1", "--dashboard-address", ":0"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
with Client("tcp://127.0.0.1:8786") as c:
    c.wait_for_workers(2, timeout=60)
t = time.time()
r = subprocess.run([".venv/bin/python", "-m", "tools.campaign", "run", "tools/impulse/campaigns/rdv_box.yaml", "--out", "build/campaigns/rdv_ext", "--scheduler", "tcp://127.0.0.1:8786", "--no-progress", "--no-report"], capture_output=True, text=True)
print(r.stdout.strip().splitlines()[-1], "TIME %.1f s" % (time.time() - t))
for p in ps[::-1]: p.terminate()
for p in ps: p.wait()
PY
$C compare $B/rdv_box $B/rdv_ext
# benchmarks: 100 runs, plain loop vs the runner with 1 and 2 workers
$PY - <<'PY'
import sys, time
sys.path.insert(0, ".")
from tools.campaign import runner, worker
from tools.campaign.spec import Campaign
c = Campaign("tools/impulse/campaigns/rdv_box.yaml"); c.runs = 100
sil = runner.default_sil(); runner.check(c, sil)
t = time.time()
for i in range(100): worker.run_one(c, i, sil)
dt = time.time() - t
print("BENCH plain loop, 100 runs: %.1f s = %.2f runs/s = %.0f ticks/s" % (dt, 100 / dt, 100 * 10610 / dt))
PY
for w in 1 2; do
  s=$(date +%s.%N)
  $C run $R --out $B/rdv100_w$w --runs 100 --workers $w --no-progress --no-report > /dev/null
  e=$(date +%s.%N)
  echo "BENCH runner $w worker(s), 100 runs: $(echo "$e - $s" | bc) s"
done
echo DONE
