#!/usr/bin/env bash
# Idempotent, non-interactive dependency installer (spec 00 §7).
# Installs only what is missing; prints what it installed. Every entry point calls it.
#   tools/bootstrap.sh            Debian packages + Python venv (.venv, git-ignored) with the
#                                 project's `tools` package installed editable (pyproject.toml)
#   BOOTSTRAP_SKIP_VENV=1 ...     packages only
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export DEBIAN_FRONTEND=noninteractive

PKGS=(cmake ninja-build pkg-config gcc g++ python3 python3-venv
      libcmocka-dev libeigen3-dev liblcm-dev liblcm-bin libglib2.0-dev
      gcc-arm-none-eabi libnewlib-arm-none-eabi binutils-arm-none-eabi qemu-system-arm
      cppcheck clang-tidy clang-14 libclang-rt-14-dev libyaml-cpp-dev nlohmann-json3-dev libcli11-dev zlib1g-dev)

missing=()
for p in "${PKGS[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q '^install ok installed$'; then
        missing+=("$p")
    fi
done

if ((${#missing[@]})); then
    SUDO=""
    if [ "$(id -u)" -ne 0 ]; then
        command -v sudo >/dev/null || { echo "bootstrap: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
        SUDO="sudo"
    fi
    echo "bootstrap: installing ${missing[*]}"
    $SUDO apt-get update -qq
    $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
    echo "bootstrap: installed ${missing[*]}"
else
    echo "bootstrap: Debian packages present"
fi

if [ "${BOOTSTRAP_SKIP_VENV:-0}" != 1 ]; then
    VENV="$ROOT/.venv"
    if [ ! -x "$VENV/bin/python" ]; then
        python3 -m venv "$VENV"
        echo "bootstrap: created $VENV"
    fi
    # What the venv lacks: each distribution in pyproject.toml's [project] dependencies (by name;
    # the list is unpinned), and this tree's `tools` package installed editable from $ROOT.
    # `pip install -e` then installs the project and whichever dependencies are missing; nothing
    # runs when the check finds nothing.
    need=$("$VENV/bin/python" -I - "$ROOT" <<'PY'   # -I: not the cwd's *.egg-info
import importlib.metadata as md
import json
import pathlib
import re
import sys
import tomllib

root = pathlib.Path(sys.argv[1])
project = tomllib.loads((root / "pyproject.toml").read_text(encoding="utf-8"))["project"]
need = []
for req in project.get("dependencies", []):
    name = re.match(r"[A-Za-z0-9._-]+", req).group(0)
    try:
        md.distribution(name)
    except md.PackageNotFoundError:
        need.append(name)
try:
    url = json.loads(md.distribution(project["name"]).read_text("direct_url.json") or "{}")
except md.PackageNotFoundError:
    url = {}
if url.get("url") != root.as_uri() or not url.get("dir_info", {}).get("editable"):
    need.append(f"{project['name']} (editable, {root})")
print(" ".join(need))
PY
)
    if [ -n "$need" ]; then
        "$VENV/bin/python" -m pip install -q --disable-pip-version-check -e "$ROOT"
        echo "bootstrap: pip installed $need"
    else
        echo "bootstrap: Python venv complete"
    fi
fi
