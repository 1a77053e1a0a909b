"""Flight design (10-observer section 4.2): robust eigenstructure assignment on the exact ZOH model."""
import numpy as np
from scipy.signal import place_poles
from . import model as m
from . import paper as p

H_FLIGHT = 0.02
ZETA_S = 0.05
ORIENT_5HZ = (-1, -1)   # (D, W): Schur-branch orientation (det(V B) > 0 convention, paper.closure_step) reproducing the spec's 5 Hz D and word-length row


def conj_set(up):
    up = np.asarray(up, dtype=complex)
    return np.concatenate([up, np.conj(up)])


def s_targets(sigma, zeta_s=ZETA_S):
    """(controller poles, observer poles) in s, upper-half-plane members of conjugate pairs."""
    if sigma == -1:
        up6, _ = m.butter_pairs(6)
        up7, _ = m.butter_pairs(7)
        return list(up6), list(up7)
    e = lambda deg: np.exp(1j * np.deg2rad(deg))
    sail = lambda z: 1.01 * complex(-z, np.sqrt(1 - z * z))
    return [e(135), 3 * e(165), sail(zeta_s)], [3 * e(135), 3 * e(165), sail(0.1)]


def loop12(Phi, G, Ph, Gh, D, W6, C=m.C):
    """12-state loop: plant (Phi, G), predictor observer (Ph, Gh, W6), u = -D xhat."""
    return np.block([[Phi, -G @ D], [W6 @ C, Ph - Gh @ D - W6 @ C]])


def yt_design(sigma, h=H_FLIGHT, k2=m.K2_DESIGN, zeta_s=ZETA_S, J=m.J0):
    Phi, G = m.zoh(k2, sigma, h, J)
    sc, so = s_targets(sigma, zeta_s)
    zc = conj_set(np.exp(np.array(sc) * h))
    zo = conj_set(np.exp(np.array(so) * h))
    D = place_poles(Phi, G, zc, method="YT", maxiter=100, rtol=1e-10).gain_matrix
    W6 = place_poles(Phi.T, m.C.T, zo, method="YT", maxiter=100, rtol=1e-10).gain_matrix.T
    return dict(D=D, W6=W6, zc=zc, zo=zo, sigma=sigma, h=h)


def seq5hz_design(h=p.H_PAPER, k2=m.K2_DESIGN, sigma=-1, J=m.J0, orient=ORIENT_5HZ):
    """5 Hz table: sequential closure on the ZOH model with exp(s h) targets (section 4.2)."""
    Phi, G = m.zoh(k2, sigma, h, J)
    up6, _ = m.butter_pairs(6)
    up7, _ = m.butter_pairs(7)
    t6 = np.exp(np.array(up6) * h)
    t7 = np.exp(np.array(up7) * h)
    ev = np.linalg.eigvals(Phi)
    nut = ev[np.argmin(np.abs(ev - np.exp(1j * 50.99 * h)))]
    sail = ev[np.argmin(np.abs(ev - np.exp(1j * 0.99 * h)))]
    Ds, _ = p.seq_closure(Phi, G, [(nut, t6[0]), (sail, t6[1]), (1.0, t6[2])], orient[0])
    Wt, _ = p.seq_closure(Phi.T, m.C.T, [(nut, t7[0]), (sail, t7[1]), (1.0, t7[2])], orient[1])
    return dict(D=sum(Ds), W6=sum(Wt).T, zc=conj_set(t6), zo=conj_set(t7), sigma=sigma, h=h)


def rho_frozen(des, K, k2_true=m.K2_TRUE, Jf=1.0, exact_obs=False, quant=None):
    """rho of the 12-state loop; plant exact ZOH at k2_true, J*Jf; observer model at K (first-order Phi(kappa))."""
    sigma, h = des["sigma"], des["h"]
    Phi, G = m.zoh(k2_true, sigma, h, m.J0 * Jf)
    if exact_obs:
        Ph, Gh = m.zoh(K, sigma, h)
    else:
        Ph, Gh = m.FirstOrder(sigma, h).at(K)
    D, W6 = des["D"], des["W6"]
    return m.specrad(loop12(Phi, G, Ph, Gh, D, W6))


def window(f, lo, hi, K0=m.K2_TRUE, tol=1e-7):
    """Edges of {K : f(K) < 1} around K0 by bisection, searched within [lo, hi]; None if not reached."""
    def edge(a, b):   # f(a) < 1, search toward b
        if f(b) < 1:
            return None
        for _ in range(60):
            mid = 0.5 * (a + b)
            if f(mid) < 1:
                a = mid
            else:
                b = mid
            if abs(b - a) < tol:
                break
        return 0.5 * (a + b)
    return edge(K0, lo), edge(K0, hi)
