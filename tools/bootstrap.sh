#!/usr/bin/env bash
# Idempotent, non-interactive dependency installer (spec 00 §7).
# Installs only what is missing; prints what it installed. Every entry point calls it.
#   tools/bootstrap.sh            Debian packages + Python venv (.venv, git-ignored)
#   BOOTSTRAP_SKIP_VENV=1 ...     packages only
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export DEBIAN_FRONTEND=noninteractive

PKGS=(cmake ninja-build pkg-config gcc g++ python3 python3-venv
      libcmocka-dev libeigen3-dev liblcm-dev liblcm-bin libglib2.0-dev
      gcc-arm-none-eabi libnewlib-arm-none-eabi binutils-arm-none-eabi qemu-system-arm
      cppcheck clang-tidy clang-14 libclang-rt-14-dev libyaml-cpp-dev libcli11-dev)

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
    need=()
    for m in numpy scipy matplotlib lcm; do
        "$VENV/bin/python" -c "import $m" 2>/dev/null || need+=("$m")
    done
    if ((${#need[@]})); then
        "$VENV/bin/python" -m pip install -q --disable-pip-version-check "${need[@]}"
        echo "bootstrap: pip installed ${need[*]}"
    else
        echo "bootstrap: Python venv complete"
    fi
fi
