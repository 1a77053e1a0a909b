"""Per-function instruction attribution of one flight-code entry point on the emulated Cortex-M.

A benchmark, never a test (spec 00 §9). The SysTick figures of fx_insn.py / module_insn.py say how
many instructions a call costs; this says where they go. QEMU runs a bench image single-stepped with
its exec trace (`-singlestep -d exec,nochain`: one trace line per executed instruction, with the
symbol QEMU resolves from the ELF), streamed through a FIFO so no multi-GB log is written. A call
of FUNC starts at FUNC's entry address and ends when execution is back in the function that called
it (no recursion in fsw/, so the caller's code cannot run inside the call); every instruction in
between is counted against the function it belongs to (inlined code counts to its host).

    python -m tools.bench.insn_profile ELF FUNC [--machine mps2-an385] [--skip N] [--calls M]

  --skip N    ignore the first N calls (e.g. a filter's start-up steps)
  --calls M   attribute M calls after those, then stop QEMU (default 10)
  --min K     attribute only calls of at least K instructions (separates a function's paths, e.g.
              Newton iterations that solve from those that only evaluate the residual)
  --max K     and of at most K instructions

Prints the instructions per call (min / median / max; the same count as the SysTick method up to
the call instruction itself) and a table of instructions per call by function, largest first.
"""
import argparse
import collections
import os
import re
import statistics
import subprocess
import sys
import tempfile
import threading

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
QEMU_RUN = os.path.join(ROOT, "tools", "qemu-run.sh")
# "Trace 0: 0x7f71b4000100 [00800400/00000280/00000110/ff000201] board_reset_handler"
TRACE_RE = re.compile(r"^Trace [0-9]+: 0x[0-9a-f]+ \[[0-9a-f]+/([0-9a-f]+)/[0-9a-f]+/[0-9a-f]+\] ?(\S*)")


def entry_address(elf, func):
    out = subprocess.run(["arm-none-eabi-nm", elf], capture_output=True, text=True, check=True).stdout
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 3 and parts[2] == func and parts[1] in "tTwW":
            return int(parts[0], 16) & ~1   # Thumb bit
    return None


class Attributor:
    def __init__(self, entry, skip, calls, min_insns, max_insns):
        self.entry, self.skip, self.calls = entry, skip, calls
        self.min_insns, self.max_insns = min_insns, max_insns
        self.inside = False
        self.caller = None
        self.prev = None
        self.n_calls = 0
        self.cur = collections.Counter()
        self.per_call = []
        self.by_func = collections.Counter()

    def done(self):
        return len(self.per_call) >= self.calls

    def line(self, pc, name):
        if not self.inside:
            if pc == self.entry:
                self.inside, self.caller = True, self.prev
                self.n_calls += 1
                self.cur = collections.Counter({name: 1})
        elif name == self.caller:
            self.inside = False
            n = sum(self.cur.values())
            if self.n_calls > self.skip and self.min_insns <= n <= self.max_insns:
                self.per_call.append(n)
                self.by_func.update(self.cur)
        else:
            self.cur[name] += 1
        self.prev = name


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("elf")
    ap.add_argument("func")
    ap.add_argument("--machine", default="mps2-an385")
    ap.add_argument("--skip", type=int, default=0)
    ap.add_argument("--calls", type=int, default=10)
    ap.add_argument("--min", type=int, default=0, dest="min_insns")
    ap.add_argument("--max", type=int, default=2**62, dest="max_insns")
    a = ap.parse_args()
    entry = entry_address(a.elf, a.func)
    if entry is None:
        sys.exit(f"insn_profile: {a.func} not found in {a.elf}")
    att = Attributor(entry, a.skip, a.calls, a.min_insns, a.max_insns)
    with tempfile.TemporaryDirectory() as td:
        fifo = os.path.join(td, "trace")
        os.mkfifo(fifo)
        env = dict(os.environ, QEMU_TIMEOUT="3600",
                   QEMU_ARGS=f"-singlestep -d exec,nochain -D {fifo}")
        qemu = subprocess.Popen([QEMU_RUN, a.machine, a.elf], env=env, stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL, start_new_session=True)

        def reader():
            with open(fifo, encoding="utf-8", errors="replace") as f:
                for ln in f:
                    m = TRACE_RE.match(ln)
                    if m is None:
                        continue
                    att.line(int(m.group(1), 16), m.group(2))
                    if att.done():
                        break
        t = threading.Thread(target=reader)
        t.start()
        t.join()
        if qemu.poll() is None:
            os.killpg(qemu.pid, 9)   # enough calls seen: the rest of the bench is not needed
        qemu.wait()
    if not att.per_call:
        sys.exit(f"insn_profile: no complete call of {a.func} after skipping {a.skip}")
    n = len(att.per_call)
    sel = f" of {a.min_insns}..{a.max_insns} instructions" if (a.min_insns or a.max_insns < 2**62) else ""
    print(f"{a.func} on {a.machine}: {n} calls{sel} after {a.skip} skipped; instructions per call "
          f"min {min(att.per_call)} median {statistics.median(att.per_call)} max {max(att.per_call)}")
    print()
    print("| function | instructions per call | share |")
    print("|---|---:|---:|")
    tot = sum(att.by_func.values())
    for name, c in att.by_func.most_common():
        if c / tot < 0.002:
            break
        print(f"| `{name or '?'}` | {c / n:.0f} | {100.0 * c / tot:.1f} % |")


if __name__ == "__main__":
    main()
