"""CW model (spec 50 §2.2) and the switching-time Newton solver (§3) in double precision.

State order (x, xd, y, yd, z, zd); x along-track, y radial (towards the Earth), z cross-track.
Every function takes w (orbit rate) and works in SI; w = 1, a = 1 is the nondimensional system
of §4.1.
"""
import numpy as np

OMEGA = 1.131367e-3          # rad/s, 400 km (spec §2.3)
A_NOM = 0.04                 # m/s^2
T_EX = 1055.0                # s
X0_EX = np.array([5000.0, -1.0, 4000.0, -1.0, 4000.0, -1.0])

AXIS_STATE = (slice(0, 4), slice(0, 4), slice(4, 6))   # rows of F per axis
XY, Z = 0, 1


def phi_xy(t, w):
    tau = w * t
    s, c = np.sin(tau), np.cos(tau)
    return np.array([[1, (4 * s - 3 * tau) / w, 6 * (tau - s), 2 * (1 - c) / w],
                     [0, 4 * c - 3, 6 * w * (1 - c), 2 * s],
                     [0, -2 * (1 - c) / w, 4 - 3 * c, s / w],
                     [0, -2 * s, 3 * w * s, c]])


def phi_z(t, w):
    tau = w * t
    s, c = np.sin(tau), np.cos(tau)
    return np.array([[c, s / w], [-w * s, c]])


def phi(t, w):
    m = np.zeros((6, 6))
    m[:4, :4] = phi_xy(t, w)
    m[4:, 4:] = phi_z(t, w)
    return m


def psi(r, sig, w):
    """Thrust integral of axis r (0 x, 1 y, 2 z) per unit acceleration over sig seconds,
    on the axis's subsystem rows (4 for x/y, 2 for z)."""
    tau = w * sig
    s, c = np.sin(tau), np.cos(tau)
    if r == 0:
        return np.array([(4 * (1 - c) - 1.5 * tau ** 2) / w ** 2, (4 * s - 3 * tau) / w,
                         -2 * (tau - s) / w ** 2, -2 * (1 - c) / w])
    if r == 1:
        return np.array([2 * (tau - s) / w ** 2, 2 * (1 - c) / w, (1 - c) / w ** 2, s / w])
    return np.array([(1 - c) / w ** 2, s / w])


def phi_e(r, sig, w):
    """Phi(sig) e_r: response to a unit velocity change along axis r."""
    tau = w * sig
    s, c = np.sin(tau), np.cos(tau)
    if r == 0:
        return np.array([(4 * s - 3 * tau) / w, 4 * c - 3, -2 * (1 - c) / w, -2 * s])
    if r == 1:
        return np.array([2 * (1 - c) / w, 2 * s, s / w, c])
    return np.array([s / w, c])


def sub_axes(sub):
    return (0, 1) if sub == XY else (2,)


def sub_rows(sub):
    return slice(0, 4) if sub == XY else slice(4, 6)


def pol_signs(pattern, sub):
    """Pattern bits (bit = 1 negative): x-y bits 0..3 = s1x s2x s1y s2y; z bits 0..1 = s1z s2z."""
    n = 2 if sub == XY else 1
    return [((-1.0 if (pattern >> (2 * k)) & 1 else 1.0), (-1.0 if (pattern >> (2 * k + 1)) & 1 else 1.0))
            for k in range(n)]


def thr_index(r, sgn):
    return 2 * r + (1 if sgn < 0 else 0)


def residual(sub, t1, t2, pattern, x0, xt, T, w, alpha):
    rows = sub_rows(sub)
    f = phi(T, w)[rows, rows] @ x0[rows] - xt[rows]
    for k, r in enumerate(sub_axes(sub)):
        s1, s2 = pol_signs(pattern, sub)[k]
        a1 = alpha[thr_index(r, s1)]
        a2 = alpha[thr_index(r, s2)]
        f = f + s1 * a1 * (psi(r, T, w) - psi(r, T - t1[k], w)) + s2 * a2 * psi(r, T - t2[k], w)
    return f


def jacobian(sub, t1, t2, pattern, T, w, alpha):
    axes = sub_axes(sub)
    n = 2 * len(axes)
    j = np.zeros((n, n))
    for k, r in enumerate(axes):
        s1, s2 = pol_signs(pattern, sub)[k]
        j[:, 2 * k] = s1 * alpha[thr_index(r, s1)] * phi_e(r, T - t1[k], w)
        j[:, 2 * k + 1] = -s2 * alpha[thr_index(r, s2)] * phi_e(r, T - t2[k], w)
    return j


def newton(sub, pattern, x0, xt, T, w, alpha, t1=None, t2=None, max_iter=10, ftol=None, jac=None, gain=1.0,
           history=None):
    """Newton from (t1, t2) (default (0, T)). Returns (status, t1, t2, iters);
    status 'ok', 'iter', 'singular', 'diverge', 'invalid'."""
    n = len(sub_axes(sub))
    t1 = np.zeros(n) if t1 is None else np.array(t1, float)
    t2 = np.full(n, T) if t2 is None else np.array(t2, float)
    jac = jac or jacobian
    for it in range(max_iter + 1):
        f = residual(sub, t1, t2, pattern, x0, xt, T, w, alpha)
        if history is not None:
            history.append((t1.copy(), t2.copy(), f.copy()))
        if ftol is not None and np.max(np.abs(f)) <= ftol:
            ok = np.all(t1 >= -1e-9 * T) and np.all(t2 - t1 >= -1e-9 * T) and np.all(t2 <= T * (1 + 1e-9))
            return ('ok' if ok else 'invalid'), t1, t2, it
        if it == max_iter:
            break
        jm = jac(sub, t1, t2, pattern, T, w, alpha)
        if abs(np.linalg.det(jm)) < 1e-300:
            return 'singular', t1, t2, it
        d = np.linalg.solve(jm, f)
        t1 = t1 - gain * d[0::2]
        t2 = t2 - gain * d[1::2]
        if np.any(np.concatenate([t1, t2]) < -T) or np.any(np.concatenate([t1, t2]) > 2 * T):
            return 'diverge', t1, t2, it + 1
    return 'iter', t1, t2, max_iter


def impulsive(x0, xt, T, w, alpha=None):
    """Signed impulsive dv1, dv2 per axis (first Newton step from (0, T), all polarities +)."""
    alpha = np.ones(6) if alpha is None else alpha
    dv1, dv2 = np.zeros(3), np.zeros(3)
    for sub in (XY, Z):
        axes = sub_axes(sub)
        n = len(axes)
        t1, t2 = np.zeros(n), np.full(n, T)
        f = residual(sub, t1, t2, 0, x0, xt, T, w, alpha)
        d = np.linalg.solve(jacobian(sub, t1, t2, 0, T, w, alpha), f)
        for k, r in enumerate(axes):
            dv1[r] = alpha[2 * r] * (t1[k] - d[2 * k])
            dv2[r] = alpha[2 * r] * (T - (t2[k] - d[2 * k + 1]))
    return dv1, dv2


def rule_pattern(dv1, dv2, sub):
    p = 0
    for k, r in enumerate(sub_axes(sub)):
        p |= (1 if dv1[r] < 0 else 0) << (2 * k)
        p |= (1 if dv2[r] < 0 else 0) << (2 * k + 1)
    return p


def dv_of(sub, pattern, t1, t2, T, alpha, a_nom):
    tot = 0.0
    for k, r in enumerate(sub_axes(sub)):
        s1, s2 = pol_signs(pattern, sub)[k]
        tot += a_nom * (alpha[thr_index(r, s1)] * t1[k] + alpha[thr_index(r, s2)] * (T - t2[k]))
    return tot


def solve(x0, xt, T, w, a_nom=A_NOM, alpha=None, ftol_r=None, max_iter=10, tie_dv=1e-3):
    """Full §3.5 selection (rule, then search) per subsystem. Returns dict per subsystem."""
    alpha = np.ones(6) if alpha is None else alpha
    dv1, dv2 = impulsive(x0, xt, T, w, alpha * a_nom)
    L, V = a_nom / w ** 2, a_nom / w
    out = {}
    for sub in (XY, Z):
        nrow = 4 if sub == XY else 2
        ftol = np.array([ftol_r * (L if i % 2 == 0 else V) for i in range(nrow)]) if ftol_r else None
        ftol_s = None if ftol is None else np.min(ftol)
        rp = rule_pattern(dv1, dv2, sub)
        st, t1, t2, it = newton(sub, rp, x0, xt, T, w, alpha * a_nom, max_iter=max_iter, ftol=ftol_s)
        if st == 'ok':
            out[sub] = dict(how='rule', pattern=rp, t1=t1, t2=t2, iters=it,
                            dv=dv_of(sub, rp, t1, t2, T, alpha, a_nom))
            continue
        best = None
        for p in range(16 if sub == XY else 4):
            if p == rp:
                continue
            st, t1, t2, it = newton(sub, p, x0, xt, T, w, alpha * a_nom, max_iter=max_iter, ftol=ftol_s)
            if st != 'ok':
                continue
            dv = dv_of(sub, p, t1, t2, T, alpha, a_nom)
            if best is None or dv < best['dv'] - tie_dv:
                best = dict(how='search', pattern=p, t1=t1, t2=t2, iters=it, dv=dv)
        out[sub] = best or dict(how='none', pattern=None)
    return out
