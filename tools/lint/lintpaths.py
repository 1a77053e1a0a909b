"""Path helpers shared by the lint scripts.

The lint scripts here (check_includes, scan_float, check_compile_flags, cppcheck_filter) and the
modules they share (clex, lintpaths) are a documented exception to importing through the `tools`
package of pyproject.toml: they are build-time proofs that must run with whatever python3 the
build has, without the project venv (CTest runs them with FSW_PYTHON, which is the system
interpreter when there is no .venv, e.g. after BOOTSTRAP_SKIP_VENV=1; run_cppcheck.sh pipes into
`python3`). So they use the standard library only, are run by path (`python3
tools/lint/scan_float.py ...`, never with -m), and import their siblings by module name: Python
puts a script's own directory first on sys.path, so they need no sys.path edit.
"""
import os


def repo_root():
    return os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def inside(path, root):
    path = os.path.realpath(path)
    root = os.path.realpath(root)
    return path == root or path.startswith(root + os.sep)
