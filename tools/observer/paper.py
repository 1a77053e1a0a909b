"""Paper mode (10-observer section 3): Euler model, Tustin targets, sequential closure of modes."""
import numpy as np
from scipy.linalg import schur
from . import model as m

H_PAPER = 0.2
DEG = np.pi / 180

# ---- printed values (x_p coordinates), transcribed from the paper --------------------------------
D1_P = np.array([[0.9822, 0.0066, 0.0009, -0.0010, 0.0101, -0.0000],
                 [-0.0066, 0.9822, -0.0101, 0.0000, 0.0009, -0.0010]])
D2_P = np.array([[0.0094, 0.0119, -0.0103, 0.0102, 0.0091, -0.0090],
                 [-0.0119, 0.0094, -0.0091, 0.0090, -0.0103, 0.0102]])
D3_P = np.array([[0.0093, 0.0328, -0.0882, 0.0767, -0.0553, 0.0694],
                 [-0.0258, 0.0102, 0.0375, -0.0498, -0.0758, 0.0676]])
D_P = np.array([[1.0008, 0.0514, -0.0976, 0.0859, -0.0360, 0.0604],
                [-0.0444, 1.0017, 0.0182, -0.0408, -0.0852, 0.0768]])
W1_P = np.array([[0.0612, -10.0131], [10.0131, 0.0612], [-0.2042, -0.0012], [-0.2170, 2.0815],
                 [0.0012, -0.2042], [-2.0815, -0.2170], [0.0, 0.0]])
W2_P = np.array([[0.1275, -0.0600], [0.0600, 0.1275], [0.0655, -0.0532], [0.0289, -0.0541],
                 [0.0532, 0.0655], [0.0541, 0.0289], [0.0, 0.0]])
W3_P = np.array([[0.1693, -0.0711], [0.0748, 0.1671], [0.3907, 0.0674], [0.3632, 0.0681],
                 [-0.0633, 0.3826], [-0.0645, 0.3555], [0.0, 0.0]])
W4_P = np.array([[0.1803, 0.0164], [0.0164, 0.0015], [0.8930, 0.0810], [0.9387, 0.0852],
                 [0.2448, 0.0222], [0.2472, 0.0224], [-1.6061, -0.1458]])
W_P = np.array([[0.5383, -10.1279], [10.1643, 0.3573], [1.1450, 0.0940], [1.1138, 2.1808],
                [0.2359, 0.2661], [-1.8448, 0.1899], [-1.6061, -0.1458]])
ROOTS6_P = np.array([0.93241 + 0.18195j, 0.85981 + 0.12282j, 0.82282 + 0.04302j])
ROOTS7_P = np.array([0.9388 + 0.1849j, 0.8725 + 0.1378j, 0.8318 + 0.0729j])
ROOT7_REAL_P = 0.8182
OPEN_P = np.array([1.0 + 10.198j, 1.0 + 0.1979j, 1.0, 1.0])


def T6(h=H_PAPER):
    T = np.eye(6)
    T[3, 2], T[3, 3] = 1.0, h
    T[5, 4], T[5, 5] = 1.0, h
    return T


def T7(h=H_PAPER):
    T = np.eye(7)
    T[:6, :6] = T6(h)
    return T


def printed_D(h=H_PAPER):
    """Printed sum D converted to x coordinates: D = D_p T."""
    return D_P @ T6(h)


def printed_W(h=H_PAPER):
    return np.linalg.solve(T7(h), W_P)


def targets(h=H_PAPER):
    up6, _ = m.butter_pairs(6)
    up7, r7 = m.butter_pairs(7)
    return (np.array([m.tustin(p, h) for p in up6]), np.array([m.tustin(p, h) for p in up7]),
            float(m.tustin(r7[0], h)))


def closure_step(Ac, B, lam, target, tol=1e-3, orient=+1):
    """One step of section 3.2. Returns D_i (m x n) with V(Ac - B D_i) = Phi_t V.

    For a repeated eigenvalue the real Schur basis is not unique: a sign flip of one Schur vector
    transposes the target block relative to M and changes D_i (same eigenvalues). At the double
    eigenvalue 1 the block is semi-simple (T = I to 1e-15), so T[0,1] carries no sign and any
    orthonormal basis of the subspace is a Schur basis: rotations leave D_i unchanged, reflections
    flip it. The orientation is therefore fixed by det(V B) > 0 (the input directions), which
    does not depend on LAPACK (a T[0,1] >= 0 rule did, and flipped W3 between scipy versions);
    orient=-1 selects the transposed target block [[a, b], [-b, a]] in that branch."""
    ev = np.linalg.eigvals(Ac)
    schur_branch = False
    # re-identify lambda as the current eigenvalue nearest its nominal value (Im >= 0 for pairs)
    lam = ev[np.argmin(np.abs(ev - lam))]
    if abs(lam.imag) > tol and np.sum(np.abs(ev - lam) < tol) == 1:
        if lam.imag < 0:
            lam = np.conj(lam)
        wl, vl = np.linalg.eig(Ac.T)      # left eigenvectors of Ac
        w = vl[:, np.argmin(np.abs(wl - lam))]
        a, b = lam.real, lam.imag
        V = np.vstack([w.real, w.imag])
        M = np.array([[a, -b], [b, a]])
    else:
        ref = lam.real if abs(lam.imag) <= tol else lam

        def sel(x, y=None):
            z = x if y is None else complex(x, y)
            return abs(z - ref) < tol
        T, Z, r = schur(Ac.T, output="real", sort=sel)
        if r == 2 and np.linalg.det(Z[:, :2].T @ B) < 0:
            Z = Z.copy()
            T = T.copy()
            Z[:, 1] = -Z[:, 1]
            T[0, 1], T[1, 0] = -T[0, 1], -T[1, 0]
        V = Z[:, :r].T
        M = T[:r, :r].T
        schur_branch = True
    target = complex(target)
    if abs(target.imag) > 0:
        a, b = target.real, abs(target.imag)
        if schur_branch and orient < 0:
            b = -b
        Pt = np.array([[a, -b], [b, a]])
    else:
        Pt = np.array([[target.real]])
    if Pt.shape != M.shape:
        raise ValueError("block size mismatch: r=%d for target %s" % (M.shape[0], target))
    K = np.linalg.pinv(V @ B) @ (M - Pt)
    return K @ V


def seq_closure(A, B, pairs, orient=+1):
    """pairs: list of (nominal eigenvalue, target). Returns list of D_i and the final Ac."""
    Ac = A.copy()
    Ds = []
    for lam, tgt in pairs:
        Di = closure_step(Ac, B, lam, tgt, orient=orient)
        Ds.append(Di)
        Ac = Ac - B @ Di
    return Ds, Ac


def A_k(A, h, mu_hat, slip=False, J=m.J0, Kcol=None):
    """7x7 adjustable model [[A, h*A_k2*mu_e],[0,1]] (Kcol overrides the K column)."""
    Ak = np.eye(7)
    Ak[:6, :6] = A
    if Kcol is None:
        mue = np.array([0, 0, mu_hat[0], 0, mu_hat[1], 0])
        Kcol = h * m.A_k2(J) @ mue
        if slip:
            Kcol = Kcol.copy()
            Kcol[5] = -Kcol[5]
    Ak[:6, 6] = Kcol
    return Ak


MU_STAR = (0.1 * DEG, 0.1 * DEG)
C7 = np.hstack([m.C, np.zeros((2, 1))])


def paper_design(h=H_PAPER, k2=m.K2_PAPER, sigma=-1, mu_star=MU_STAR, slip=True, orient=+1):
    A, B = m.euler(k2, sigma, h)
    t6, t7, t7r = targets(h)
    ev = np.linalg.eigvals(A)
    nut = ev[np.argmax(ev.imag)]
    sail = ev[np.argmin(np.where(ev.imag > 1e-6, ev.imag, np.inf))]
    Ds, Acl = seq_closure(A, B, [(nut, t6[0]), (sail, t6[1]), (1.0, t6[2])], orient)
    Wt, Aol = seq_closure(A.T, m.C.T, [(nut, t7[0]), (sail, t7[1]), (1.0, t7[2])], orient)
    Ws = [np.vstack([Wi.T, np.zeros((1, 2))]) for Wi in Wt]
    W6sum = sum(Ws)
    Ak = A_k(A, h, mu_star, slip=slip)
    Ac7 = Ak - W6sum @ C7
    W4t = closure_step(Ac7.T, C7.T, 1.0, t7r)
    Ws.append(W4t.T)
    return dict(A=A, B=B, Ds=Ds, D=sum(Ds), Ws=Ws, W=sum(Ws), Acl=Acl, Ak=Ak, t6=t6, t7=t7, t7r=t7r)
