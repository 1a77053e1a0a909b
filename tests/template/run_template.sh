#!/usr/bin/env bash
# CTest template_module: the module template cannot rot. In a scratch copy of the source tree,
# `tools/new_module.py` creates a module in every layer; the copy must then differ from the tree
# only by that module's own folders and one registry line, configure a build of that mission
# alone, build its targets and pass its tests (unit, golden, SIL, report agreement).
#   run_template.sh SRC_DIR WORK_DIR PYTHON [JOBS]
set -euo pipefail
src=$1; work=$2; py=$3; jobs=${4:-2}
name=damper; prefix=dmp; mission=DAMPER
tree=$work/tree
rm -rf "$work"; mkdir -p "$tree"
# The working tree as git sees it (tracked and new files, not build outputs or the venv).
(cd "$src" && git ls-files -z --cached --others --exclude-standard) |
    (cd "$src" && xargs -0 cp --parents -t "$tree" 2>/dev/null || true)
cd "$tree"
git init -q . && git add -A && git -c user.name=t -c user.email=t@t commit -qm base
export PYTHONPATH=$tree PYTHONDONTWRITEBYTECODE=1   # the copy's tools, not the source tree's
"$py" tools/new_module.py "$name" --prefix "$prefix" --mission "$mission" > "$work/new_module.log"
# Adding a module touches its own folders and the registry line only.
bad=$(git status --porcelain --untracked-files=all |
      grep -v -E "^ M missions.json$|^\?\? (fsw|sim|tools|tests)/$name/|^\?\? hil_host/missions/$name/" || true)
if [[ -n $bad ]]; then echo "template_module: files outside the module's folders changed:"; echo "$bad"; exit 1; fi
git diff --numstat missions.json | awk '{ if ($1 != 2 || $2 != 1) { print "missions.json: +" $1 " -" $2 " lines, expected the entry and a comma"; exit 1 } }'
git add -A && git diff --cached --stat | tail -1
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Debug -DFSW_MISSIONS="$mission" -DFSW_PYTHON="$py" > "$work/configure.log"
targets="test_$prefix test_${prefix}_mission test_${prefix}_ref_host test_${name}_scenario ${prefix}_tbl_image test_${prefix}_sil sil"
# shellcheck disable=SC2086
cmake --build build -j "$jobs" --target $targets > "$work/build.log" || { tail -40 "$work/build.log"; exit 1; }
ctest --test-dir build -R "$prefix|$name" -j "$jobs" --output-on-failure
