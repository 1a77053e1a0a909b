#!/usr/bin/env python3
"""Post-filter of run_cppcheck.sh: classify cppcheck output lines (spec 00 §4 "MISRA C:2012").

Reads cppcheck's output (template '{file}:{line}:{column}: {severity}: {id}: {message}') on
stdin and prints every finding. Exit status: 0 nothing left, 1 findings or skips.

Skips fail: noValidConfiguration, toomanyconfigs and missingInclude(System) mean a file or a
configuration was silently not analysed, so they count as failures even though cppcheck exits 0.

Two known defects of the cppcheck 2.10 misra addon are filtered (fsw/MISRA_DEVIATIONS.md):
 T1  its tokenizer drops the parentheses around the operands of `?:`, so
     `neg ? (1u << 1) : (1u << 0)` and `c ? (r + 1u) : r` are reported as 12.1. A 12.1 report
     on a `?` or `:` is dropped only if, in the source text, each operand the addon checks is a
     primary expression: a fully parenthesised group, or an identifier/constant (possibly with
     calls, subscripts or member access). Every other 12.1 report is kept.
 T2  it applies 10.7 to the operands of `<<`, `>>`, `<<=` and `>>=`, which perform no usual
     arithmetic conversions (C99 6.5.7), so `m >> (n - 1u)` with a 64-bit m is reported. A 10.7
     report is dropped only if the flagged operator sits in a parenthesised group that is, in
     the source text, a direct operand of a shift operator. Every other 10.7 report is kept.
"""
import re
import sys

sys.dont_write_bytecode = True      # no __pycache__ in the source tree
import clex  # noqa: E402  (sibling module: a script's directory is on sys.path; see lintpaths.py)

SKIP_IDS = ("noValidConfiguration", "toomanyconfigs", "missingInclude", "missingIncludeSystem")
_FINDING = re.compile(r"^(?P<file>.*?):(?P<line>\d+):(?P<col>\d+): (?P<sev>\w+): (?P<id>[\w.-]+): (?P<msg>.*)$")
_IDENT = re.compile(r"[A-Za-z_0-9.]")
_cache = {}


def source_lines(path):
    if path not in _cache:
        try:
            with open(path, encoding="utf-8", errors="replace") as fh:
                _cache[path] = clex.strip_comments(fh.read())
        except OSError:
            _cache[path] = None
    return _cache[path]


def match_forward(text, i):
    """i at '(' or '['; index just after the matching closer, or -1."""
    pairs = {"(": ")", "[": "]"}
    stack = []
    while i < len(text):
        c = text[i]
        if c in pairs:
            stack.append(pairs[c])
        elif c in ")]":
            if not stack or stack.pop() != c:
                return -1
            if not stack:
                return i + 1
        i += 1
    return -1


def match_backward(text, i):
    """i at ')'; index of the matching '(' or -1."""
    depth = 0
    while i >= 0:
        c = text[i]
        if c in ")]":
            depth += 1
        elif c in "([":
            depth -= 1
            if depth == 0:
                return i
        i -= 1
    return -1


def skip_ws(text, i, step):
    while 0 <= i < len(text) and text[i] in " \t\r\n\f\v":
        i += step
    return i


def primary_forward(text, i, terminators):
    """Is the operand starting at i a primary/postfix expression ending at a terminator?"""
    i = skip_ws(text, i, 1)
    if i >= len(text):
        return False
    if text[i] == "(":
        i = match_forward(text, i)
        if i < 0:
            return False
    elif _IDENT.match(text[i]):
        while i < len(text) and _IDENT.match(text[i]):
            i += 1
    else:
        return False
    while True:                                   # postfix: calls, subscripts, members
        i = skip_ws(text, i, 1)
        if i < len(text) and text[i] in "([":
            i = match_forward(text, i)
            if i < 0:
                return False
        elif text.startswith("->", i) or (i < len(text) and text[i] == "."):
            i += 2 if text.startswith("->", i) else 1
            i = skip_ws(text, i, 1)
            while i < len(text) and _IDENT.match(text[i]):
                i += 1
        else:
            break
    return i < len(text) and text[i] in terminators


def primary_backward(text, i):
    """Is the operand ending just before index i (exclusive) a primary expression that is the
    whole left operand of `?` (i.e. preceded by an assignment, `(`, `,`, `?`, `:`, `return`)?"""
    j = skip_ws(text, i - 1, -1)
    if j < 0:
        return False
    if text[j] == ")":
        j = match_backward(text, j)
        if j < 0:
            return False
        j -= 1
    elif _IDENT.match(text[j]):
        while j >= 0 and _IDENT.match(text[j]):
            j -= 1
    else:
        return False
    j = skip_ws(text, j, -1)
    if j < 0:
        return False
    c = text[j]
    if c in "(,?:{;":
        return True
    if text[max(0, j - 5):j + 1] == "return" and (j - 6 < 0 or not _IDENT.match(text[j - 6])):
        return True
    if c == "=":
        p = text[j - 1] if j >= 1 else ""
        if p in "=!":
            return False                                  # == !=
        if p in "<>":
            return j >= 2 and text[j - 2] == p            # <<= >>= (assignment), not <= >=
        return True                                        # = += -= *= /= %= &= |= ^=
    return False


def offset(text, line, col):
    lines = text.split("\n")
    if line < 1 or line > len(lines) or col < 1 or col > len(lines[line - 1]):
        return -1
    return sum(len(l) + 1 for l in lines[:line - 1]) + col - 1


def question_for_colon(text, i):
    """Index of the `?` that owns the `:` at i (same nesting level), or -1."""
    depth, nested = 0, 0
    j = i - 1
    while j >= 0:
        c = text[j]
        if c in ")]":
            depth += 1
        elif c in "([":
            if depth == 0:
                return -1
            depth -= 1
        elif depth == 0 and c == ":":
            nested += 1
        elif depth == 0 and c == "?":
            if nested == 0:
                return j
            nested -= 1
        elif depth == 0 and c in ";{}":
            return -1
        j -= 1
    return -1


def ternary_false_positive(path, line, col):
    text = source_lines(path)
    if text is None:
        return False
    i = offset(text, line, col)
    if i < 0 or text[i] not in "?:":
        return False
    if text[i] == "?":
        return primary_backward(text, i)
    q = question_for_colon(text, i)
    if q < 0:
        return False
    return primary_forward(text, q + 1, ":") and primary_forward(text, i + 1, ";),}")


def shift_operand(path, line, col):
    """T2: is the operator at (line, col) inside a parenthesised group that is a direct operand
    of <<, >>, <<= or >>=?"""
    text = source_lines(path)
    if text is None:
        return False
    i = offset(text, line, col)
    if i < 0 or text[i] not in "+-*/%&|^":
        return False
    # innermost enclosing '(' of the operator
    depth, j = 0, i - 1
    while j >= 0:
        if text[j] == ")":
            depth += 1
        elif text[j] == "(":
            if depth == 0:
                break
            depth -= 1
        elif text[j] in ";{}":
            return False
        j -= 1
    if j < 0:
        return False
    close = match_forward(text, j)
    if close < 0 or close <= i:
        return False
    before = text[:j].rstrip()
    after = text[close:].lstrip()
    if before.endswith(("<<", ">>", "<<=", ">>=")):
        return True
    # (x + y) << n: the group is the left operand (and not a cast or a call's argument list)
    prev = before[-1:] if before else ""
    return after.startswith(("<<", ">>")) and not after.startswith(("<<=", ">>=")) and \
        (prev in "=(,?:" or before.endswith("return"))


def main():
    findings, skips, dropped = [], [], []
    for raw in sys.stdin:
        line = raw.rstrip("\n")
        m = _FINDING.match(line)
        if not m:
            continue          # code excerpts, progress lines
        fid = m.group("id")
        if fid in SKIP_IDS:
            skips.append(line)
            continue
        if fid == "misra-c2012-12.1" and ternary_false_positive(
                m.group("file"), int(m.group("line")), int(m.group("col"))):
            dropped.append("T1 " + line)
            continue
        if fid == "misra-c2012-10.7" and shift_operand(
                m.group("file"), int(m.group("line")), int(m.group("col"))):
            dropped.append("T2 " + line)
            continue
        if fid.startswith("misra-c2012-"):
            # Debian ships misra.py without rule texts: say which rule instead of the stock hint.
            line = "%s:%s:%s: %s: %s: MISRA C:2012 rule %s (see fsw/MISRA_DEVIATIONS.md for the deviations)" % (
                m.group("file"), m.group("line"), m.group("col"), m.group("sev"), fid,
                fid[len("misra-c2012-"):])
        findings.append(line)
    why = {"T1": "the misra addon loses the parentheses of ?: operands",
           "T2": "10.7 does not apply to shift operands (no usual arithmetic conversions)"}
    for d in dropped:
        tag, _, rest = d.partition(" ")
        print("note: dropped (deviation %s, %s): %s" % (tag, why[tag], rest))
    for f in findings:
        print(f)
    for s in skips:
        print(s)
    if skips:
        print("run_cppcheck: FAIL: cppcheck skipped code (%s); analysis is incomplete"
              % ", ".join(sorted({i for i in SKIP_IDS if any(i in s for s in skips)})))
    if findings:
        rules = sorted({_FINDING.match(f).group("id") for f in findings})
        print("run_cppcheck: FAIL: %d finding(s): %s" % (len(findings), " ".join(rules)))
    return 1 if (findings or skips) else 0


if __name__ == "__main__":
    sys.exit(main())
