"""Where a benchmark or Monte Carlo figure came from: the machine and the commit.

Shared by tools/bench/fx_insn.py and tools/impulse/mc.py so every report that carries
numbers names its machine and source revision the same way.
"""
import os
import platform
import re
import subprocess

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def machine_description():
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            m = re.search(r"model name\s*:\s*(.+)", f.read())
            if m:
                cpu = m.group(1).strip()
    except OSError:
        pass
    return {"host": platform.node(), "os": f"{platform.system()} {platform.release()}", "cpu": cpu,
            "cores": os.cpu_count(), "python": platform.python_version()}


def commit():
    """Short hash of HEAD, with -dirty when tracked files differ from it (numbers from a dirty
    tree are not reproducible from the hash alone)."""
    def git(*args):
        return subprocess.run(["git", "-C", ROOT, *args], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                              text=True, check=False)
    r = git("rev-parse", "--short=12", "HEAD")
    if r.returncode != 0:
        return "none (no commit yet)"
    dirty = git("status", "--porcelain", "--untracked-files=no").stdout.strip()
    return r.stdout.strip() + ("-dirty" if dirty else "")
