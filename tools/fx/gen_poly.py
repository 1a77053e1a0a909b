#!/usr/bin/env python3
"""gen_poly.py - minimax coefficients of the fixed-point trigonometry (spec 00 §1.6).

Writes fsw/fx/fx_trig_coef.h: the integer coefficient tables of fsw/fx/fx_trig.c and the
extended-precision constants of the BAM <-> radian conversions.

  sin(pi/4 t)  = t * (S0 - u (S1 - u (S2 - u (S3 - u S4))))            odd degree 9
  cos(pi/4 t)  = 1 - u (C1 - u (C2 - u (C3 - u C4)))                   even degree 8, C0 = 1
  atan(v)/2pi  = v * (A0 - w (A1 - w (A2 - w (A3 - w (A4 - w A5)))))   odd degree 11, in turns

with t in [0, 1] the octant fraction (t = 1 is pi/4), u = t^2, v in [0, tan(pi/8)], w = v^2.
The signs of the coefficients alternate, so the tables hold magnitudes and fx_trig.c runs the
nested form above on unsigned integers: every Horner stage is positive, every product is an
exact uint32 x uint32 -> uint64 product and every rounding acts on a non-negative value.

Method
  1. Remez exchange (float64 on a dense grid, exact rational solves of the reference systems)
     for the minimax polynomial of each function on its interval; cos has C0 = 1 pinned.
  2. Sequential quantisation: the coefficients are rounded to integers one at a time, from the
     lowest degree, and the remaining ones are re-fitted (Remez with the rounded ones fixed)
     after each step, so later coefficients absorb the rounding of earlier ones.
  3. Integer polish: a deterministic coordinate search of +-1..+-3 LSB steps on every
     coefficient that minimises the worst error of the bit-exact integer model (the Python
     mirror of fx_trig.c) before its final rounding, on a fixed evaluation grid.
Output is deterministic: running it twice gives a byte-identical header. Transcendental
values come from Python's math module (glibc libm), linear systems are solved in exact
rationals, and numpy is used only for IEEE float64 / uint64 element-wise arithmetic; the
integer search compares errors quantised to 1e-6 LSB, so last-bit noise cannot steer it.

Usage (needs numpy: the project's .venv):
  .venv/bin/python tools/fx/gen_poly.py              # write fsw/fx/fx_trig_coef.h
  .venv/bin/python tools/fx/gen_poly.py --out PATH   # write elsewhere
  .venv/bin/python tools/fx/gen_poly.py --check      # regenerate in memory, compare with --out
"""

import argparse
import math
import sys
from fractions import Fraction
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
DEFAULT_OUT = ROOT / "fsw" / "fx" / "fx_trig_coef.h"
GEN_CMD = ".venv/bin/python tools/fx/gen_poly.py"

# pi to 100 decimals: source of the exact extended-precision constants.
PI = Fraction("3.14159265358979323846264338327950288419716939937510"
              "58209749445923078164062862089986280348253421170679")

# ------------------------------------------------------------------------- formats
# Fixed by fx_trig.c (changing one of these means changing the C code as well).
X_Q = 29       # octant fraction t = x / 2^29, x in [0, 2^29]
U_Q = 31       # u = t^2 in uq31 (u <= 1 needs 2^31, which fits a uint32)
OUT_Q = 30     # sin/cos results in q30
V_Q = 32       # atan argument v in uq32
W_Q = 34       # w = v^2 in uq34 (w <= 0.1716 -> < 2^32)
BAM_BITS = 32  # atan result in turns * 2^32
COEF_MAX = 2**31 - 1   # tables are int32_t
TAN_PI_8 = math.tan(math.pi / 8.0)


# ------------------------------------------------------------------------- Remez
def solve_exact(rows, rhs):
    """Gaussian elimination in exact rationals (float inputs are converted exactly)."""
    n = len(rows)
    a = [[Fraction(v) for v in r] + [Fraction(b)] for r, b in zip(rows, rhs)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(a[r][c]))
        a[c], a[p] = a[p], a[c]
        for r in range(n):
            if r != c and a[r][c] != 0:
                f = a[r][c] / a[c][c]
                a[r] = [x - f * y for x, y in zip(a[r], a[c])]
    return [a[r][n] / a[r][r] for r in range(n)]


def remez(func, exps, hi, fixed=(), npts=16384, iters=60):
    """Minimax fit of func(x) - sum(fixed c x^e) by sum c_k x^e_k on (0, hi], absolute error.

    Every basis function vanishes at 0 (e >= 1), so 0 is never a reference point.
    Returns ([c_k as float], E).
    """
    n = len(exps)

    def target(x):
        return func(x) - sum(float(c) * x ** e for c, e in fixed)

    # Dense grid, Chebyshev-spaced (denser near both ends), deterministic.
    k = np.arange(1, npts + 1, dtype=np.float64)
    grid = hi * 0.5 * (1.0 - np.cos(np.pi * k / npts))
    grid[-1] = hi
    tgrid = np.array([target(float(x)) for x in grid])

    ref = [hi * 0.5 * (1.0 - math.cos(math.pi * (i + 1) / (n + 1))) for i in range(n + 1)]
    coefs = [0.0] * n
    err_e = 0.0
    for _ in range(iters):
        rows = [[x ** e for e in exps] + [(-1.0) ** i] for i, x in enumerate(ref)]
        sol = solve_exact(rows, [target(x) for x in ref])
        coefs = [float(c) for c in sol[:n]]
        err_e = float(sol[n])

        def err(x):
            return target(x) - sum(c * x ** e for c, e in zip(coefs, exps))

        pg = np.zeros_like(grid)
        for c, e in zip(coefs, exps):
            pg = pg + c * grid ** e
        eg = tgrid - pg
        # One extremum per run of constant sign.
        ext = []
        start = 0
        for i in range(1, len(eg) + 1):
            if i == len(eg) or (eg[i] > 0) != (eg[start] > 0):
                j = start + int(np.argmax(np.abs(eg[start:i])))
                ext.append(j)
                start = i
        # Golden-section refinement of each extremum between its grid neighbours.
        pts = []
        for j in ext:
            a = float(grid[max(j - 1, 0)])
            b = float(grid[min(j + 1, len(grid) - 1)])
            sgn = 1.0 if eg[j] > 0 else -1.0
            g = (math.sqrt(5.0) - 1.0) / 2.0
            for _ in range(60):
                c1 = b - g * (b - a)
                c2 = a + g * (b - a)
                if sgn * err(c1) > sgn * err(c2):
                    b = c2
                else:
                    a = c1
            xm = 0.5 * (a + b)
            cand = [xm, float(grid[j])]
            xb = max(cand, key=lambda x: sgn * err(x))
            pts.append(xb)
        while len(pts) > n + 1:
            if abs(err(pts[0])) < abs(err(pts[-1])):
                pts.pop(0)
            else:
                pts.pop()
        if len(pts) < n + 1:
            break
        emax = max(abs(err(x)) for x in pts)
        ref = pts
        if emax - abs(err_e) <= 1e-6 * emax:
            break
    return coefs, abs(err_e)


def seq_quantise(func, exps, hi, qs, fixed0=()):
    """Round coefficients one at a time (lowest degree first), re-fitting the rest."""
    fixed = list(fixed0)
    out = []
    for i in range(len(exps)):
        coefs, _ = remez(func, exps[i:], hi, fixed=fixed)
        ci = round(abs(coefs[0]) * 2 ** qs[i])
        sign = 1 if coefs[0] >= 0 else -1
        out.append(ci)
        fixed.append((Fraction(sign * ci, 2 ** qs[i]), exps[i]))
    return out


def fmt_q(c):
    """Largest Q such that |c| * 2^Q fits the int32 tables (with 1/2 LSB of room)."""
    q = 0
    while abs(c) * 2 ** (q + 1) < COEF_MAX - 1:
        q += 1
    return q


# ------------------------------------------------------------------------- integer models
# Bit-exact mirrors of fx_trig.c. All arrays are numpy uint64; every value stays < 2^64.
def rnd_up(p, n):
    """round(p / 2^n), ties up: the half-away rounding of a non-negative value."""
    return (p + np.uint64(1 << (n - 1))) >> np.uint64(n)


def rnd_dn(p, n):
    """round(p / 2^n), ties down: used on subtrahends, so the difference rounds half away."""
    return (p + np.uint64((1 << (n - 1)) - 1)) >> np.uint64(n)


def horner_model(mags, qs, z, zq):
    """Nested alternating Horner: returns (stage_1 value, its Q) with
    stage_k = M_k - z * stage_{k+1}, stage values held in the coefficient formats."""
    acc = np.full_like(z, np.uint64(mags[-1]))
    for k in range(len(mags) - 2, 0, -1):
        sh = zq + qs[k + 1] - qs[k]
        acc = np.uint64(mags[k]) - rnd_dn(z * acc, sh)
    return acc


def u_of_x(x):
    return rnd_up(x * x, 2 * X_Q - U_Q)


def sin_model(mags, qs, x, final=True):
    """S = x * P(u) in q30; P = S0 - u * stage1 held in uq(q0+1)."""
    u = u_of_x(x)
    st1 = horner_model(mags, qs, u, U_Q)
    qp = qs[0] + 1
    sh = U_Q + qs[1] - qp
    p = (np.uint64(mags[0]) << np.uint64(1)) - rnd_dn(u * st1, sh)
    nsh = X_Q + qp - OUT_Q
    if final:
        return rnd_up(x * p, nsh)
    return (x * p).astype(np.float64) / 2.0 ** nsh


def cos_model(mags, qs, x, final=True):
    """C = 2^30 - u * stage1, rounded once (mags[0] is the pinned 1.0)."""
    u = u_of_x(x)
    st1 = horner_model(mags, qs, u, U_Q)
    sh = U_Q + qs[1] - OUT_Q
    if final:
        return np.uint64(1 << OUT_Q) - rnd_dn(u * st1, sh)
    return float(1 << OUT_Q) - (u * st1).astype(np.float64) / 2.0 ** sh


def atan_model(mags, qs, v, final=True):
    """A = v * P(w) in turns * 2^32; P = A0 - w * stage1 held in uq(q0+1)."""
    w = rnd_up(v * v, 2 * V_Q - W_Q)
    st1 = horner_model(mags, qs, w, W_Q)
    qp = qs[0] + 1
    sh = W_Q + qs[1] - qp
    p = (np.uint64(mags[0]) << np.uint64(1)) - rnd_dn(w * st1, sh)
    nsh = V_Q + qp - BAM_BITS
    if final:
        return rnd_up(v * p, nsh)
    return (v * p).astype(np.float64) / 2.0 ** nsh


# ------------------------------------------------------------------------- evaluation grids
def splitmix(seed, n, mod):
    out = []
    s = seed
    m64 = (1 << 64) - 1
    for _ in range(n):
        s = (s + 0x9E3779B97F4A7C15) & m64
        z = s
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & m64
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & m64
        z ^= z >> 31
        out.append(z % mod)
    return out


def grid_x():
    top = 1 << X_Q
    pts = set(range(0, top + 1, 1 << 11))
    pts.update(range(0, 4097))
    pts.update(range(top - 4096, top + 1))
    pts.update(splitmix(1, 1 << 16, top + 1))
    return np.array(sorted(pts), dtype=np.uint64)


def grid_v(vmax):
    pts = set(range(0, vmax + 1, 1 << 14))
    pts.update(range(0, 4097))
    pts.update(range(vmax - 4096, vmax + 1))
    pts.update(splitmix(2, 1 << 16, vmax + 1))
    return np.array(sorted(pts), dtype=np.uint64)


def truth(fn, xs, scale_in, scale_out):
    return np.array([fn(float(x) * scale_in) * scale_out for x in xs.tolist()])


def polish(model, mags, qs, xs, ref, frozen=(0,), steps=(1, -1, 2, -2, 3, -3), rounds=12,
           extra=None):
    """Coordinate search on the integer coefficients: minimise the worst pre-rounding error."""
    def score(m):
        e = np.abs(model(m, qs, xs, final=False) - ref)
        bad = 0 if extra is None else extra(m)
        # Quantised objective: robust tie-breaking, deterministic.
        return (bad, round(float(e.max()) * 1e6), round(float(np.sqrt(np.mean(e * e))) * 1e6))

    best = list(mags)
    bscore = score(best)
    for _ in range(rounds):
        moved = False
        for k in range(len(best)):
            if k in frozen:
                continue
            for d in steps:
                cand = list(best)
                cand[k] += d
                s = score(cand)
                if s < bscore:
                    best, bscore, moved = cand, s, True
        if not moved:
            break
    return best, bscore


# ------------------------------------------------------------------------- constants
def words96(val):
    """A Fraction in [0, 2^96) as round() to an integer, split into 3 uint32 words (hi first)."""
    k = round(val)
    assert 0 < k < (1 << 96)
    return [(k >> 64) & 0xFFFFFFFF, (k >> 32) & 0xFFFFFFFF, k & 0xFFFFFFFF], k


def dec(fr, digits=36):
    """Decimal string of a Fraction (truncated), for comments."""
    sign = "-" if fr < 0 else ""
    fr = abs(fr)
    ip = fr.numerator // fr.denominator
    frac = fr - ip
    s = str(ip) + "."
    for _ in range(digits):
        frac *= 10
        d = frac.numerator // frac.denominator
        s += str(d)
        frac -= d
    return sign + s


# ------------------------------------------------------------------------- main fit
def fit_all():
    notes = {}
    # --- sin: odd degree 9 in t on [0, 1].
    def fsin(t):
        return math.sin(math.pi / 4.0 * t)
    sexp = [1, 3, 5, 7, 9]
    scoef, serr = remez(fsin, sexp, 1.0)
    sq = [fmt_q(c) for c in scoef]
    smag = seq_quantise(fsin, sexp, 1.0, sq)
    # --- cos: even degree 8 with C0 = 1 pinned: fit cos - 1 by t^2..t^8.
    def fcos(t):
        return math.cos(math.pi / 4.0 * t) - 1.0
    cexp = [2, 4, 6, 8]
    ccoef, cerr = remez(fcos, cexp, 1.0)
    cq = [OUT_Q] + [fmt_q(c) for c in ccoef]
    cmag = [1 << OUT_Q] + seq_quantise(fcos, cexp, 1.0, cq[1:])
    # --- atan (turns): odd degree 11 on [0, vmax].
    tq = round(TAN_PI_8 * 2 ** V_Q)
    vmax = tq + 8                         # argument bound of fx_trig.c (+ rounding slack)
    vhi = vmax / 2.0 ** V_Q

    def fatan(v):
        return math.atan(v) / (2.0 * math.pi)
    aexp = [1, 3, 5, 7, 9, 11]
    acoef, aerr = remez(fatan, aexp, vhi)
    aq = [fmt_q(c) for c in acoef]
    amag = seq_quantise(fatan, aexp, vhi, aq)

    # Signs must alternate (+, -, +, ...) for the unsigned nested Horner of fx_trig.c.
    for name, co, first in (("sin", scoef, 1), ("cos", ccoef, -1), ("atan", acoef, 1)):
        for i, c in enumerate(co):
            want = first * (-1) ** i
            if (c > 0) != (want > 0):
                raise SystemExit(f"gen_poly: {name} coefficient {i} has the wrong sign")

    # --- integer polish against the bit-exact models.
    xs = grid_x()
    sref = truth(math.sin, xs, math.pi / 2.0 ** (X_Q + 2), 2.0 ** OUT_Q)
    cref = truth(math.cos, xs, math.pi / 2.0 ** (X_Q + 2), 2.0 ** OUT_Q)
    x45 = np.array([1 << X_Q], dtype=np.uint64)

    smag, ssc = polish(sin_model, smag, sq, xs, sref, frozen=())

    # Prefer sin(45 deg) == cos(45 deg) bit for bit, if the polish can reach it.
    def cos_extra(m):
        return 0 if int(cos_model(m, cq, x45)[0]) == int(sin_model(smag, sq, x45)[0]) else 1
    cmag, csc = polish(cos_model, cmag, cq, xs, cref, frozen=(0,), extra=cos_extra)
    c45 = int(cos_model(cmag, cq, x45)[0])
    s45 = int(sin_model(smag, sq, x45)[0])

    vs = grid_v(vmax)
    aref = truth(math.atan, vs, 2.0 ** -V_Q, 2.0 ** BAM_BITS / (2.0 * math.pi))
    amag, asc = polish(atan_model, amag, aq, vs, aref, frozen=())

    def final_err(model, mags, qs, xs_, ref):
        r = model(mags, qs, xs_, final=True).astype(np.float64)
        return float(np.max(np.abs(r - ref)))

    notes["sin"] = (serr * 2 ** OUT_Q, ssc[1] / 1e6, final_err(sin_model, smag, sq, xs, sref))
    notes["cos"] = (cerr * 2 ** OUT_Q, csc[1] / 1e6, final_err(cos_model, cmag, cq, xs, cref))
    notes["atan"] = (aerr * 2 ** BAM_BITS, asc[1] / 1e6, final_err(atan_model, amag, aq, vs, aref))
    notes["s45c45"] = (s45, c45)
    return (smag, sq, sexp), (cmag, cq, [0] + cexp), (amag, aq, aexp), vmax, tq, notes


def range_checks(smag, sq, cmag, cq, amag, aq, vmax):
    """Worst-case stage magnitudes, so fx_trig.c's uint64 arithmetic provably cannot wrap."""
    # Stages decrease monotonically in u (each subtracts a non-negative product), so the
    # largest value of every stage is its coefficient and the smallest is at the interval end.
    top = np.array([1 << X_Q], dtype=np.uint64)
    for mags, qs in ((smag, sq), (cmag, cq)):
        for k in range(1, len(mags)):
            assert 0 < mags[k] <= COEF_MAX
    u = int(u_of_x(top)[0])
    assert u <= 1 << 31
    st = int(horner_model(smag, sq, np.array([u], dtype=np.uint64), U_Q)[0])
    assert st > 0 and u * st < 2 ** 64
    st = int(horner_model(cmag, cq, np.array([u], dtype=np.uint64), U_Q)[0])
    assert st > 0 and u * st < 2 ** 64
    w = (vmax * vmax + (1 << (2 * V_Q - W_Q - 1))) >> (2 * V_Q - W_Q)
    assert w < 2 ** 32
    st = int(horner_model(amag, aq, np.array([w], dtype=np.uint64), W_Q)[0])
    assert st > 0
    assert 2 * amag[0] < 2 ** 32 and vmax * 2 * amag[0] < 2 ** 64


def render(fit):
    (smag, sq, sexp), (cmag, cq, cexp), (amag, aq, aexp), vmax, tq, notes = fit
    range_checks(smag, sq, cmag, cq, amag, aq, vmax)
    L = []
    w = L.append
    w("/*")
    w(" * fx_trig_coef.h - GENERATED FILE, DO NOT EDIT.")
    w(f" * Generated by: {GEN_CMD}")
    w(f" * Check:        {GEN_CMD} --check")
    w(" *")
    w(" * Minimax (Remez) polynomials of fx_trig.c, quantised by sequential re-fitting and an")
    w(" * integer coordinate search on the bit-exact model. FX_TRIG_<F>_MAG initialises the")
    w(" * block-scope static const int32_t table of fx_trig.c (MISRA 8.9: each table is used by one")
    w(" * function). Tables hold MAGNITUDES; the signs alternate and fx_trig.c evaluates the nested")
    w(" * form on unsigned integers:")
    w(" *   sin(pi/4 t) = t (S0 - u (S1 - u (S2 - u (S3 - u S4))))           u = t^2, t in [0, 1]")
    w(" *   cos(pi/4 t) = 1 - u (C1 - u (C2 - u (C3 - u C4)))                C0 = 1 exactly")
    w(" *   atan(v)/2pi = v (A0 - w (A1 - w (A2 - w (A3 - w (A4 - w A5)))))  w = v^2,")
    w(" *                 v in [0, tan(pi/8)], result in turns (x 2^32 = BAM)")
    w(" * Coefficient k is held in Q FX_TRIG_<F>_Q<k>; each Horner stage stays in the format of")
    w(" * its coefficient, except the last one of sin and atan (S0 - u.., A0 - w..), held in one")
    w(" * more fraction bit as a uint32. Model figures on the generator's evaluation grid (the C")
    w(" * tests measure the real thing):")
    for name, unit in (("sin", "LSB q30"), ("cos", "LSB q30"), ("atan", "LSB BAM")):
        rm, pre, fin = notes[name]
        w(f" *   {name:4s}: real-coefficient minimax {rm:.4f}, integer model before the final")
        w(f" *         rounding {pre:.4f}, after it {fin:.4f} ({unit})")
    w(" */")
    w("#ifndef FSW_FX_TRIG_COEF_H")
    w("#define FSW_FX_TRIG_COEF_H")
    w("")
    w("#include <stdint.h>")
    w("")
    w("/* Fixed formats of the evaluation (fx_trig.c depends on them). */")
    w(f"#define FX_TRIG_X_Q   {X_Q}u  /* octant fraction t = x / 2^{X_Q}, x in [0, 2^{X_Q}] */")
    w(f"#define FX_TRIG_U_Q   {U_Q}u  /* u = t^2, uq{U_Q} */")
    w(f"#define FX_TRIG_OUT_Q {OUT_Q}u  /* sin, cos results */")
    w(f"#define FX_TRIG_V_Q   {V_Q}u  /* atan argument v, uq{V_Q} */")
    w(f"#define FX_TRIG_W_Q   {W_Q}u  /* w = v^2, uq{W_Q} */")
    w("")

    def table(tag, mags, qs, exps, real_note):
        w(f"/* {real_note} */")
        w(f"#define FX_TRIG_{tag}_N {len(mags)}u")
        for k, q in enumerate(qs):
            w(f"#define FX_TRIG_{tag}_Q{k} {q}u")
        w(f"#define FX_TRIG_{tag}_MAG {{ \\")
        for k, (m, q, e) in enumerate(zip(mags, qs, exps)):
            val = Fraction(m, 2 ** q) * (-1) ** k
            comma = "," if k + 1 < len(mags) else " "
            w(f"    INT32_C({m}){comma}  /* {tag[0]}{k} (x^{e}) = {float(val):+.17e}, q{q} */ \\")
        w("}")
        w("")

    table("SIN", smag, sq, sexp,
          "sin(pi/4 t): magnitudes of the odd degree-9 coefficients (signs + - + - +)")
    table("COS", cmag, cq, cexp,
          "cos(pi/4 t): magnitudes of the even degree-8 coefficients (signs + - + - +); C0 = 1")
    table("ATAN", amag, aq, aexp,
          "atan(v)/(2 pi): magnitudes of the odd degree-11 coefficients (signs + - + - + -)")

    w("/* Octant split of atan2: take v = min/max while min * 2^32 <= TAN_PI_8 * max. */")
    w(f"#define FX_TRIG_TAN_PI_8 UINT32_C({tq})  /* tan(pi/8) = {dec(Fraction(TAN_PI_8), 12)}, uq32 */")
    w(f"#define FX_TRIG_V_MAX    UINT32_C({vmax})  /* bound of v used by the fit, uq32 */")
    w("")
    w("/* Extended-precision conversion constants, round(c * 2^96) or round(c * 2^95), as three")
    w(" * 32-bit words, most significant first. */")
    k1w, k1 = words96(PI / 4 * 2 ** 96)
    k2w, k2 = words96(4 / PI * 2 ** 95)
    w(f"/* pi/4 = {dec(PI / 4)}, uq96 */")
    for i, x in enumerate(k1w):
        w(f"#define FX_TRIG_PI_4_W{2 - i}   UINT32_C(0x{x:08X})")
    w(f"/* 4/pi = {dec(4 / PI)}, uq95 */")
    for i, x in enumerate(k2w):
        w(f"#define FX_TRIG_4_PI_W{2 - i}   UINT32_C(0x{x:08X})")
    w("")
    w("#endif /* FSW_FX_TRIG_COEF_H */")
    return "\n".join(L) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", type=Path, default=DEFAULT_OUT)
    ap.add_argument("--check", action="store_true",
                    help="regenerate and compare with --out; exit 1 on any difference")
    args = ap.parse_args()
    fit = fit_all()
    text = render(fit)
    notes = fit[5]
    for name in ("sin", "cos", "atan"):
        rm, pre, fin = notes[name]
        print(f"gen_poly: {name:4s} minimax {rm:.4f}  model pre-round {pre:.4f}  final {fin:.4f} LSB",
              file=sys.stderr)
    print(f"gen_poly: sin(45) = {notes['s45c45'][0]}, cos(45) = {notes['s45c45'][1]}", file=sys.stderr)
    if args.check:
        old = args.out.read_text() if args.out.exists() else ""
        if old != text:
            print(f"gen_poly: {args.out} differs from the generator output", file=sys.stderr)
            return 1
        print(f"gen_poly: {args.out} is up to date", file=sys.stderr)
        return 0
    args.out.write_text(text)
    print(f"gen_poly: wrote {args.out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
