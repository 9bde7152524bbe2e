"""numba kernels of the quasi-static tribological model (bearing_core.models.quasistatic_tribo, whose module
docstring states the equations and the method).

Residual:   residual        the unknowns written into a dynamics state, one call of the dynamics' right-hand
                            side (dynamics_kernels.rhs), the generalised forces of each ball's 6 unknowns
                            and of the ring's 5, and each ball's share of the ring loads.
Jacobian:   jacobian        forward differences of the arrow structure (ball blocks: ball_jacobian) (balls do not touch each other):
                            column k of every ball block from ONE rhs call that perturbs unknown k of all
                            balls, one rhs call per ring unknown: 11 calls.
Linear:     arrow_solve     (diag(d) / dtau - J) dv = R on the scaled unknowns by block elimination
                            (a 6 x 6 LU per ball, the 6 x 6 Schur complement of the ring), with a dense
                            LU with partial pivoting as fallback when a ball block is (near) singular.
Solver:     ptc             pseudo-transient continuation (Kelley & Keyes, SIAM J. Numer. Anal. 35 (1998)
                            508) with switched evolution relaxation, as described in quasistatic_tribo;
                            the Jacobian is kept when a step is rejected (the point has not moved);
                            a near-Newton mode for the first stage.

Unknowns: xl (Z, 6) per ball (r, z, Omega_r, Omega_t, Omega_z, theta_dot), xg (6) ring (dx, dy, dz, tx, ty)
and an unused cage speed; scaled unknowns v = (xl / xs_l, xg / xs_g) flattened (ball-major). Residuals
are forces [N] (moments over D/2 or dm/2).
"""
from __future__ import annotations

import math

import numpy as np

from . import dynamics_kernels as K
from ..numerics.jit import hot

NLOC = 6    # per-ball unknowns: r, z, Omega_r, Omega_t, Omega_z, theta_dot
NGLOB = 6   # dx, dy, dz, tx, ty, (cage speed: not an unknown with free orbits; kept for the layout)

# ptc status
PTC_CONVERGED, PTC_BUDGET = 0, 1
# lazy Jacobian of ptc: rebuilt after this many accepted chord steps, or when dtau grew this much
LAZY_AGE = 20
LAZY_DTAU = 10.0
# near-Newton mode of ptc (newton=True): dtau beyond which the pseudo-time term is a small shift of the
# diagonal (no rebuild for its growth); accepted capped steps on one Jacobian before a residual growth
# forces a rebuild; chord steps that polish a converged point
DTAU_NEWTON = 1.0e3
NEWTON_CAPPED_AGE = 5
NEWTON_POLISH = 4
# near-Newton mode: rebuilds of the ball blocks alone (6 rhs calls instead of 11) between two rebuilds of
# the whole Jacobian (the ring's columns change little along the path: 57 -> 49 evaluations for 7218B,
# lubricated, 3000 rpm, Fx 1 kN, Fz 3 kN; median 49 -> 46 over bench_tribo_qs.py --speed)
NEWTON_RING_KEEP = 1


@hot
def load_state(y0, xl, xg, yy):
    """yy = y0 with the unknowns (xl, xg) written into the dynamics state layout."""
    for i in range(y0.size):
        yy[i] = y0[i]
    for k in range(5):
        yy[k] = xg[k]
    yy[11] = xg[5]
    for j in range(xl.shape[0]):
        b = K.NSTATE_FIXED + K.NSB * j
        yy[b + 1] = xl[j, 0]
        yy[b + 2] = xl[j, 1]
        yy[b + 3] = xl[j, 5]
        yy[b + 6] = xl[j, 2]
        yy[b + 7] = xl[j, 3]
        yy[b + 8] = xl[j, 4]


@hot
def residual(t, y0, xl, xg, act, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy,
             yy, dy, diag, bd, Rl, Rg, share):
    """Residuals [N] at (xl, xg): per ball Rl (Z, 6) (row k: generalised force of unknown k), ring Rg (6),
    each ball's share of the ring residuals share (Z, 6). yy receives the dynamics state; dy, diag and bd
    the right-hand side, outputs and ball details there. act (6, bool): active ring unknowns."""
    load_state(y0, xl, xg, yy)
    K.rhs(t, yy, dy, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd, True)
    mb = P[K.P_MB]
    Jb = P[K.P_JB]
    hD = 0.5 * P[K.P_D]
    hdm = 0.5 * P[K.P_DM]
    for j in range(xl.shape[0]):
        b = K.NSTATE_FIXED + K.NSB * j
        Rl[j, 0] = mb * dy[b + 4]                       # F_r + m r th_d^2
        Rl[j, 1] = mb * dy[b + 5]                       # F_z
        Rl[j, 2] = Jb * dy[b + 6] / hD                  # M_r + J th_d Omega_t
        Rl[j, 3] = Jb * dy[b + 7] / hD                  # M_t - J th_d Omega_r
        Rl[j, 4] = Jb * dy[b + 8] / hD                  # M_z
        Rl[j, 5] = mb * xl[j, 0] * dy[b + 3]            # F_t
        share[j, 0] = bd[j, K.BD_CFRX]
        share[j, 1] = bd[j, K.BD_CFRY]
        share[j, 2] = bd[j, K.BD_CFRZ]
        share[j, 3] = bd[j, K.BD_CMRX] / hdm
        share[j, 4] = bd[j, K.BD_CMRY] / hdm
        share[j, 5] = 0.0
    # ring: external load + balls (support damping is zero at rest)
    Rg[0] = U[K.U_FX] + diag[iF]
    Rg[1] = U[K.U_FY] + diag[iF + 1]
    Rg[2] = U[K.U_FZ] + diag[iF + 2]
    Rg[3] = (U[K.U_MX] + diag[iM]) / hdm
    Rg[4] = (U[K.U_MY] + diag[iM + 1]) / hdm
    Rg[5] = 0.0
    for k in range(NGLOB):
        if not act[k]:
            Rg[k] = 0.0


@hot
def jacobian(t, y0, xl, xg, Rl, Rg, share, act, omega, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp,
             qx, qwx, qy, qwy, yy, dy, diag, bd, A, B, C, Dg):
    """Arrow-structured Jacobian at (xl, xg) with residuals (Rl, Rg, share) there, by forward differences
    (11 rhs calls): ball blocks A, ball-global B, global-ball C (each Z x 6 x 6) and global-global Dg
    (6 x 6). Steps: positions 1e-10 m, speeds 1e-7 of their size (at least 0.1 omega for the ball's
    angular velocity), ring tilts 1e-9 rad."""
    Z = xl.shape[0]
    gp = xg.copy()
    Rl2 = np.empty((Z, NLOC))
    Rg2 = np.empty(NGLOB)
    sh2 = np.empty((Z, NGLOB))
    ball_jacobian(t, y0, xl, xg, Rl, share, act, omega, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp,
                  qx, qwx, qy, qwy, yy, dy, diag, bd, A, C)
    hg = np.array([1e-10, 1e-10, 1e-10, 1e-9, 1e-9, 1e-7 * max(abs(xg[5]), 1.0)])
    for k in range(NGLOB):
        if act[k]:
            gp[k] = xg[k] + hg[k]
            residual(t, y0, xl, gp, act, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy,
                     yy, dy, diag, bd, Rl2, Rg2, sh2)
            gp[k] = xg[k]
            for j in range(Z):
                for i in range(NLOC):
                    B[j, i, k] = (Rl2[j, i] - Rl[j, i]) / hg[k]
            for i in range(NGLOB):
                Dg[i, k] = (Rg2[i] - Rg[i]) / hg[k] if act[i] else 0.0
        else:
            for j in range(Z):
                for i in range(NLOC):
                    B[j, i, k] = 0.0
            for i in range(NGLOB):
                Dg[i, k] = 0.0
    for i in range(NGLOB):
        if not act[i]:
            Dg[i, i] = -1.0


@hot
def ball_jacobian(t, y0, xl, xg, Rl, share, act, omega, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp,
                  qx, qwx, qy, qwy, yy, dy, diag, bd, A, C):
    """Ball blocks A and global-ball blocks C of the arrow Jacobian at (xl, xg) with residuals (Rl, share)
    there, by forward differences: column k of every ball's blocks from ONE rhs call that perturbs unknown
    k of all balls (6 calls). Steps: positions 1e-10 m, speeds 1e-7 of their size (at least 0.1 omega for
    the ball's angular velocity)."""
    Z = xl.shape[0]
    xp = xl.copy()
    Rl2 = np.empty((Z, NLOC))
    Rg2 = np.empty(NGLOB)
    sh2 = np.empty((Z, NGLOB))
    hl = np.empty((Z, NLOC))
    wmax = 0.0
    for j in range(Z):
        wmax = max(wmax, abs(xl[j, 5]))
    for j in range(Z):
        hl[j, 0] = 1e-10
        hl[j, 1] = 1e-10
        for k in range(2, 5):
            hl[j, k] = 1e-7 * max(abs(xl[j, k]), 0.1 * omega) + 1e-9
        hl[j, 5] = 1e-7 * max(wmax, 1.0)
    for k in range(NLOC):
        for j in range(Z):
            xp[j, k] = xl[j, k] + hl[j, k]
        residual(t, y0, xp, xg, act, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy,
                 yy, dy, diag, bd, Rl2, Rg2, sh2)
        for j in range(Z):
            xp[j, k] = xl[j, k]
            h = hl[j, k]
            for i in range(NLOC):
                A[j, i, k] = (Rl2[j, i] - Rl[j, i]) / h
            for i in range(NGLOB):
                C[j, i, k] = (sh2[j, i] - share[j, i]) / h if act[i] else 0.0


@hot(inline="always")
def _lu6(M, piv):
    """In-place LU with partial pivoting of a small square matrix (solved by dynamics_kernels._lu_solve); returns the smallest |pivot| relative to
    the largest entry (0 for an exactly singular matrix)."""
    n = M.shape[0]
    big = 0.0
    for i in range(n):
        for k in range(n):
            big = max(big, abs(M[i, k]))
    rmin = np.inf
    for c in range(n):
        p = c
        for i in range(c + 1, n):
            if abs(M[i, c]) > abs(M[p, c]):
                p = i
        piv[c] = p
        if p != c:
            for k in range(n):
                tmp = M[c, k]
                M[c, k] = M[p, k]
                M[p, k] = tmp
        d = M[c, c]
        rmin = min(rmin, abs(d) / big if big > 0.0 else 0.0)
        if d == 0.0:
            return 0.0
        for i in range(c + 1, n):
            if M[i, c] == 0.0:
                continue       # a zero below the pivot (the block-sparse Jacobians): nothing to eliminate
            f = M[i, c] / d
            M[i, c] = f
            for k in range(c + 1, n):
                M[i, k] -= f * M[c, k]
    return rmin


@hot
def assemble(A, B, C, Dg, xs_l, xs_g, J):
    """Dense Jacobian J (n x n, n = 6 Z + 6) of the scaled unknowns from the arrow blocks."""
    Z = A.shape[0]
    ng = Z * NLOC
    for i in range(J.shape[0]):
        for k in range(J.shape[1]):
            J[i, k] = 0.0
    for j in range(Z):
        r0 = j * NLOC
        for i in range(NLOC):
            for k in range(NLOC):
                J[r0 + i, r0 + k] = A[j, i, k] * xs_l[k]
            for k in range(NGLOB):
                J[r0 + i, ng + k] = B[j, i, k] * xs_g[k]
        for i in range(NGLOB):
            for k in range(NLOC):
                J[ng + i, r0 + k] = C[j, i, k] * xs_l[k]
    for i in range(NGLOB):
        for k in range(NGLOB):
            J[ng + i, ng + k] = Dg[i, k] * xs_g[k]


@hot
def jacobian_diagonal(A, Dg, xs_l, xs_g, d):
    """d = |diag J| of the scaled Jacobian, floored at 1e-9 of its largest entry (and of 1)."""
    Z = A.shape[0]
    ng = Z * NLOC
    dmax = 0.0
    for j in range(Z):
        for k in range(NLOC):
            d[j * NLOC + k] = abs(A[j, k, k] * xs_l[k])
            dmax = max(dmax, d[j * NLOC + k])
    for k in range(NGLOB):
        d[ng + k] = abs(Dg[k, k] * xs_g[k])
        dmax = max(dmax, d[ng + k])
    floor = 1e-9 * max(dmax, 1.0)
    for i in range(d.size):
        d[i] = max(d[i], floor)


@hot
def _dense_solve(A, B, C, Dg, xs_l, xs_g, d, dtau, R, dv):
    """Dense LU with partial pivoting of (diag(d) / dtau - J) dv = R; False if exactly singular."""
    n = R.size
    M = np.empty((n, n))
    assemble(A, B, C, Dg, xs_l, xs_g, M)
    for i in range(n):
        for k in range(n):
            M[i, k] = -M[i, k]
        M[i, i] += d[i] / dtau
    piv = np.empty(n, dtype=np.int64)
    if _lu6(M, piv) == 0.0:
        return False
    for i in range(n):
        dv[i] = R[i]
    K._lu_solve(M, piv, dv)
    return True


@hot
def arrow_solve(A, B, C, Dg, xs_l, xs_g, d, dtau, R, dv):
    """Solve (diag(d) / dtau - J) dv = R, J the scaled arrow Jacobian (A, B, C, Dg; scales xs_l, xs_g), by
    eliminating each ball's 6 unknowns (LU with partial pivoting of its 6 x 6 block) and solving the
    ring's 6 x 6 Schur complement; falls back to the dense LU when a ball block or the Schur complement
    has a pivot below 1e-10 of its largest entry. Returns False if the matrix is exactly singular."""
    Z = A.shape[0]
    ng = Z * NLOC
    Mjj = np.empty((NLOC, NLOC))
    X = np.empty((Z, NLOC, NGLOB))       # M_jj^-1 M_jg
    x = np.empty((Z, NLOC))              # M_jj^-1 r_j
    S = np.empty((NGLOB, NGLOB))
    s = np.empty(NGLOB)
    col = np.empty(NLOC)
    piv = np.empty(NLOC, dtype=np.int64)
    pivs = np.empty(NGLOB, dtype=np.int64)
    for i in range(NGLOB):
        for k in range(NGLOB):
            S[i, k] = -Dg[i, k] * xs_g[k]
        S[i, i] += d[ng + i] / dtau
        s[i] = R[ng + i]
    for j in range(Z):
        r0 = j * NLOC
        for i in range(NLOC):
            for k in range(NLOC):
                Mjj[i, k] = -A[j, i, k] * xs_l[k]
            Mjj[i, i] += d[r0 + i] / dtau
        if not _lu6(Mjj, piv) > 1e-10:
            return _dense_solve(A, B, C, Dg, xs_l, xs_g, d, dtau, R, dv)
        for k in range(NGLOB):
            for i in range(NLOC):
                col[i] = -B[j, i, k] * xs_g[k]
            K._lu_solve(Mjj, piv, col)
            for i in range(NLOC):
                X[j, i, k] = col[i]
        for i in range(NLOC):
            col[i] = R[r0 + i]
        K._lu_solve(Mjj, piv, col)
        for i in range(NLOC):
            x[j, i] = col[i]
        # S -= M_gj X_j, s -= M_gj x_j with M_gj = -C_j xs_l
        for i in range(NGLOB):
            acc = 0.0
            for m in range(NLOC):
                acc += C[j, i, m] * xs_l[m] * x[j, m]
            s[i] += acc
            for k in range(NGLOB):
                acc = 0.0
                for m in range(NLOC):
                    acc += C[j, i, m] * xs_l[m] * X[j, m, k]
                S[i, k] += acc
    if not _lu6(S, pivs) > 1e-10:
        return _dense_solve(A, B, C, Dg, xs_l, xs_g, d, dtau, R, dv)
    K._lu_solve(S, pivs, s)
    for k in range(NGLOB):
        dv[ng + k] = s[k]
    for j in range(Z):
        r0 = j * NLOC
        for i in range(NLOC):
            acc = x[j, i]
            for k in range(NGLOB):
                acc -= X[j, i, k] * s[k]
            dv[r0 + i] = acc
    for i in range(dv.size):
        if not math.isfinite(dv[i]):
            return _dense_solve(A, B, C, Dg, xs_l, xs_g, d, dtau, R, dv)
    return True


@hot
def unpack(v, xs_l, xs_g, xl, xg):
    """Physical unknowns (xl, xg) from the scaled vector v."""
    Z = xl.shape[0]
    for j in range(Z):
        for k in range(NLOC):
            xl[j, k] = v[j * NLOC + k] * xs_l[k]
    for k in range(NGLOB):
        xg[k] = v[Z * NLOC + k] * xs_g[k]


@hot
def scaled_residual(t, y0, v, xs_l, xs_g, act, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy,
                    xl, xg, yy, dy, diag, bd, Rl, Rg, share, R):
    """R = residual vector (balls then ring) at the scaled unknowns v, non-finite entries replaced by 1e12;
    (xl, xg) and (Rl, Rg, share) receive the physical unknowns and the residual blocks. Returns max |R|."""
    unpack(v, xs_l, xs_g, xl, xg)
    residual(t, y0, xl, xg, act, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy,
             yy, dy, diag, bd, Rl, Rg, share)
    Z = xl.shape[0]
    r = 0.0
    for j in range(Z):
        for k in range(NLOC):
            q = Rl[j, k]
            R[j * NLOC + k] = q if math.isfinite(q) else 1e12
    for k in range(NGLOB):
        q = Rg[k]
        R[Z * NLOC + k] = q if math.isfinite(q) else 1e12
    for i in range(R.size):
        r = max(r, abs(R[i]))
    return r


@hot
def ptc(t, y0, v, xs_l, xs_g, act, omega, ftol, budget, lazy, dtau0, newton, cap_tilt, iF, iM, P, U, tab_i, tab_o,
        ta0, tda, tp, qx, qwx, qy, qwy):
    """Pseudo-transient continuation from the scaled unknowns v (overwritten with the end point): implicit
    Euler steps (diag(|J_ii|) / dtau - J) dv = R of the pseudo-dynamics dx/dtau = diag(|J_ii|)^-1 R(x),
    dtau from dtau0 by switched evolution relaxation (dtau *= |R_old| / |R_new|, factor in [0.3, 10],
    dtau <= 1e15); a step is capped at 2 um per position, 0.3 omega per speed and cap_tilt [10 urad] per ring tilt and rejected (dtau / 10,
    Jacobian kept) if the residual grows more than 4-fold or is not finite. Stops when max |R| <= ftol or
    after budget residual evaluations (12 per Jacobian, 1 per trial step). Returns (max |R|, evaluations,
    status PTC_CONVERGED | PTC_BUDGET).

    lazy=False: a new Jacobian for every step. lazy=True: the Jacobian is kept over accepted steps
    (chord steps, 1 evaluation each) and rebuilt when the residual grew, after LAZY_AGE steps, when dtau
    grew LAZY_DTAU-fold since the rebuild (the step turns into Newton's) and before shrinking dtau after a
    rejected step; converged on a kept Jacobian, one step on a new one follows (accepted if it lowers the
    residual), so the end point has Newton's accuracy, not just the tolerance.

    newton=True (near-Newton mode, for dtau0 >= DTAU_NEWTON, lazy): no rebuild for dtau growth once the
    Jacobian was built at dtau >= DTAU_NEWTON; a residual growth on a capped step rebuilds only after
    NEWTON_CAPPED_AGE steps on the Jacobian; an uncapped step that contracts the residual less than two-fold
    rebuilds; converged on a kept Jacobian, up to NEWTON_POLISH more chord steps follow while the last one
    contracted at least two-fold (to 1e-3 of ftol; one that does not lower the residual is discarded)
    instead of the step on a new Jacobian; every other rebuild renews the ball blocks (A, C) only and keeps
    the ring's columns (B, Dg) (NEWTON_RING_KEEP), except for the step on a new Jacobian and polishing."""
    Z = (v.size - NGLOB) // NLOC
    n = v.size
    xl = np.empty((Z, NLOC))
    xg = np.empty(NGLOB)
    yy = np.empty(y0.size)
    dy = np.empty(y0.size)
    diag = np.zeros(K.NOUT)
    bd = np.zeros((Z, K.NBD))
    Rl = np.empty((Z, NLOC))
    Rg = np.empty(NGLOB)
    share = np.empty((Z, NGLOB))
    R = np.empty(n)
    R2 = np.empty(n)
    v2 = np.empty(n)
    dv = np.empty(n)
    d = np.empty(n)
    A = np.empty((Z, NLOC, NLOC))
    B = np.empty((Z, NLOC, NGLOB))
    C = np.empty((Z, NGLOB, NLOC))
    Dg = np.empty((NGLOB, NGLOB))
    cap = np.full(n, 0.3)          # step caps of the scaled unknowns: speeds 0.3 omega
    for j in range(Z):
        cap[j * NLOC] = 2.0        # ball centres 2 um
        cap[j * NLOC + 1] = 2.0
    for k in range(3):
        cap[Z * NLOC + k] = 2.0    # ring 2 um
    cap[Z * NLOC + 3] = cap_tilt   # ring tilts [10 urad]
    cap[Z * NLOC + 4] = cap_tilt
    r = scaled_residual(t, y0, v, xs_l, xs_g, act, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy,
                        xl, xg, yy, dy, diag, bd, Rl, Rg, share, R)
    nfev = 1
    dtau = dtau0
    fresh = False          # Jacobian up to date at v
    age = 0                # accepted steps on the current Jacobian
    dtau_ref = dtau
    polish = False
    npol = 0               # chord polishing steps taken (newton)
    ratio = 1.0            # residual ratio of the last accepted step
    ring_age = NEWTON_RING_KEEP   # rebuilds since the ring's Jacobian columns were computed (none yet)
    partial = False        # the current Jacobian has renewed ball blocks and kept ring columns
    no_partial = False     # such a Jacobian failed: whole ones from then on
    at_v = True            # (xl, xg), (Rl, Rg, share) hold v and its residual blocks
    while nfev < budget:
        if r <= ftol:
            if not (lazy and age > 0) or polish:
                break
            if newton:         # converged on a kept Jacobian: chord steps while they contract well
                if npol >= NEWTON_POLISH or ratio > 0.5 or r <= 1e-3 * ftol:
                    break
                npol += 1
            else:
                polish = True  # converged on a kept Jacobian: one step on a new one
                fresh = False
        if not fresh:
            if not at_v:       # the last residual call was a rejected trial: the blocks at v again
                scaled_residual(t, y0, v, xs_l, xs_g, act, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx,
                                qy, qwy, xl, xg, yy, dy, diag, bd, Rl, Rg, share, R)
                nfev += 1
                at_v = True
            if newton and ring_age < NEWTON_RING_KEEP and not (polish or no_partial) and npol == 0:
                # near-Newton rebuild: new ball blocks (6 rhs calls), the ring's columns kept
                ball_jacobian(t, y0, xl, xg, Rl, share, act, omega, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp,
                              qx, qwx, qy, qwy, yy, dy, diag, bd, A, C)
                nfev += 6
                ring_age += 1
                partial = True
            else:
                jacobian(t, y0, xl, xg, Rl, Rg, share, act, omega, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp,
                         qx, qwx, qy, qwy, yy, dy, diag, bd, A, B, C, Dg)
                nfev += 12
                ring_age = 0
                partial = False
            jacobian_diagonal(A, Dg, xs_l, xs_g, d)
            fresh = True
            age = 0
            dtau_ref = dtau
        if not arrow_solve(A, B, C, Dg, xs_l, xs_g, d, dtau, R, dv):
            if polish:
                break
            dtau *= 0.1
            nfev += 1       # counts as a trial (keeps the loop finite when the matrix stays singular)
            continue
        f = 1.0
        for i in range(n):
            f = max(f, abs(dv[i]) / cap[i])
        for i in range(n):
            v2[i] = v[i] + dv[i] / f
        r2 = scaled_residual(t, y0, v2, xs_l, xs_g, act, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp,
                             qx, qwx, qy, qwy, xl, xg, yy, dy, diag, bd, Rl, Rg, share, R2)
        nfev += 1
        at_v = False
        if polish:
            if r2 < r:
                for i in range(n):
                    v[i] = v2[i]
                r = r2
            break
        if npol > 0 and not r2 < r:
            break              # a polishing step that does not lower the residual is discarded
        if partial and age == 0 and not r2 < r:
            # the first step on ball blocks renewed with the ring's columns kept does not lower the residual:
            # discarded, the whole Jacobian renewed, now and at every later rebuild
            fresh = False
            no_partial = True
            continue
        if not math.isfinite(r2) or r2 > 4.0 * r:
            if lazy and age > 0:
                fresh = False          # a kept Jacobian: rebuild it before shrinking dtau
            else:
                dtau = max(dtau * 0.1, 1e-8)
            continue
        for i in range(n):
            v[i] = v2[i]
            R[i] = R2[i]
        at_v = True
        ratio = r2 / r if r > 0.0 else 0.0
        dtau = min(dtau * min(max(r / max(r2, 1e-300), 0.3), 10.0), 1e15)
        age += 1
        if newton:
            rebuild = ((r2 > r and not (f > 1.0 and age < NEWTON_CAPPED_AGE)) or (f == 1.0 and ratio > 0.5)
                       or age >= LAZY_AGE or (dtau > LAZY_DTAU * dtau_ref and dtau_ref < DTAU_NEWTON))
            if rebuild and not r2 <= ftol:
                fresh = False
        elif not lazy or r2 > r or age >= LAZY_AGE or dtau > LAZY_DTAU * dtau_ref:
            fresh = False
        r = r2
    return r, nfev, PTC_CONVERGED if r <= ftol else PTC_BUDGET

