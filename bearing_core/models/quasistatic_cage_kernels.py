"""numba kernels of the quasi-static cage model (bearing_core.models.quasistatic_cage, whose module docstring
states the equations and the method).

Unknowns:   xl (Z, 6) per ball: r, z [m] (centre), Omega_r, Omega_t, Omega_z [rad/s] (absolute angular
            velocity, local frame), q [N] (pocket-force coordinate: the ball's place in its pocket, pocket_offset)
            xg (8): inner ring dx, dy, dz [m], tx, ty [rad]; cage speed wc [rad/s]; cage-centre force
            coordinates gx, gy [N] (the cage centre's place in its land clearance, cage_centre)
State:      cage_state          the unknowns written into a dynamics state (dynamics_kernels layout) in which
                                every ball orbits with its pocket and nothing moves but the rotations
Residual:   cage_residual       one call of the dynamics' right-hand side (dynamics_kernels.rhs) at that
                                state; per ball the generalised forces of its 6 unknowns, the ring's 5
                                loads, the cage's torque and its two forces, each ball's share of them
Jacobian:   cage_jacobian       forward differences of the arrow structure: column k of every ball block from
                                ONE rhs call that perturbs unknown k of all balls, one call per global
                                unknown (14 calls)
Linear:     cage_arrow_solve    (diag(d) / dtau - J) dv = R by block elimination (a 6 x 6 LU per ball, the
                                8 x 8 Schur complement of ring and cage), dense LU as fallback
Solver:     cage_ptc            pseudo-transient continuation (Kelley & Keyes, SIAM J. Numer. Anal. 35
                                (1998) 508) with switched evolution relaxation and step caps, the Jacobian
                                kept while steps contract
Scaled unknowns v = (xl / xs_l, xg / xs_g) flattened (ball-major); residuals are forces [N] (moments over
D/2 or dm/2).
"""
from __future__ import annotations

import math

import numpy as np

from . import dynamics_kernels as K
from .quasistatic_tribo_kernels import _lu6
from ..numerics.jit import hot

NL = 6      # per-ball unknowns: r, z, Omega_r, Omega_t, Omega_z, q
NG = 8      # global unknowns: dx, dy, dz, tx, ty, wc, gx, gy
G_WC, G_GX, G_GY = 5, 6, 7
# force scale of the unknowns q and g inside the clearances [N]: a coordinate q of magnitude below Q_GAP
# moves the ball linearly across its pocket clearance (and the cage across its land clearance), beyond it
# the penalty contact carries |q| - Q_GAP
Q_GAP = 1.0
PTC_CONVERGED, PTC_BUDGET = 0, 1


@hot
def pocket_offset(q, cp, rp, kpk):
    """Angular offset [rad] of a ball from its pocket centre for the pocket-force coordinate q [N]: across
    the clearance cp [m] (half the diametral one) linearly for |q| <= Q_GAP, beyond it the penalty
    penetration (|q| - Q_GAP) / kpk (kpk [N/m] the pocket stiffness); rp [m] the arm about the cage
    centre. q > 0: the ball leads its pocket (it drives the cage)."""
    a = abs(q)
    if a <= Q_GAP:
        return q * cp / (Q_GAP * rp)
    s = 1.0 if q > 0.0 else -1.0
    return s * (cp + (a - Q_GAP) / kpk) / rp


@hot
def cage_centre(gx, gy, P, U):
    """Cage centre (xc, yc) [m] for the force coordinates (gx, gy) [N], along g. Dry land: eccentricity
    cl |g| / Q_GAP inside the land clearance cl [m] (half the diametral one), cl + (|g| - Q_GAP) / kl
    beyond it (kl [N/m] the land stiffness). Oil-flooded land (P_ETA_LAND > 0): eccentricity ratio
    eps = eps_max (1 - 1 / sqrt(1 + |g| / F0)), F0 = eta R |omega| B^3 / cl^2 the scale of the short journal
    bearing's film force (dynamics_kernels._cage_flooded_land; Ocvirk, Hamrock 'Fundamentals of Fluid Film
    Lubrication' Ch. 12), so that the film force, ~ F0 eps^2 / (1 - eps^2)^2, grows about linearly with |g|
    up to its value at eps_max."""
    cl = P[K.P_CLAND]
    gm = math.sqrt(gx * gx + gy * gy)
    if gm == 0.0:
        return 0.0, 0.0
    if P[K.P_ETA_LAND] > 0.0:
        w = abs(U[K.U_W1])
        F0 = P[K.P_ETA_LAND] * P[K.P_RLAND] * max(w, 1.0) * P[K.P_WLAND] ** 3 / (cl * cl)
        e = cl * P[K.P_EPSMAX] * (1.0 - 1.0 / math.sqrt(1.0 + gm / F0))
    elif gm <= Q_GAP:
        e = cl * gm / Q_GAP
    else:
        e = cl + (gm - Q_GAP) / P[K.P_KLAND]
    return gx * e / gm, gy * e / gm


@hot
def cage_state(y0, xl, xg, P, U, yy):
    """yy = y0 with the unknowns written into the dynamics state: ring pose (rates 0), cage angle 0, speed wc,
    centre from (gx, gy) (at rest); ball j at the azimuth whose offset from pocket j (the right-hand side's
    dth, measured about the cage centre) is pocket_offset(q_j), at (r, z), orbiting about the bearing axis
    at the speed that keeps it in its pocket (its azimuth about the cage centre turns at wc), no radial or
    axial velocity, angular velocity (Omega_r, Omega_t, Omega_z)."""
    for i in range(y0.size):
        yy[i] = y0[i]
    for k in range(5):
        yy[k] = xg[k]
        yy[5 + k] = 0.0
    wc = xg[G_WC]
    xc, yc = cage_centre(xg[G_GX], xg[G_GY], P, U)
    yy[10] = 0.0
    yy[11] = wc
    yy[12] = xc
    yy[13] = yc
    yy[14] = 0.0
    yy[15] = 0.0
    Z = xl.shape[0]
    cp = P[K.P_CPOCKET]
    kpk = P[K.P_KPOCKET]
    for j in range(Z):
        b = K.NSTATE_FIXED + K.NSB * j
        rb = xl[j, 0]
        d = pocket_offset(xl[j, 5], cp, rb, kpk)
        psi = 2.0 * math.pi * j / Z
        th = psi + d
        # the rhs measures the offset about the cage centre: th + atan2(xc s - yc c, rb - xc c - yc s) - psi
        # = d; fixed point (the correction is of order e / rb, its derivative in th too)
        for _ in range(3):
            c = math.cos(th)
            s = math.sin(th)
            th = psi + d - math.atan2(xc * s - yc * c, rb - xc * c - yc * s)
        c = math.cos(th)
        s = math.sin(th)
        bx = rb * c - xc
        by = rb * s - yc
        # azimuth rate about the cage centre = thd rb (bx c + by s) / |b|^2 (rhs's thb_d with rd = 0): = wc
        thd = wc * (bx * bx + by * by) / (rb * (bx * c + by * s))
        yy[b] = th
        yy[b + 1] = rb
        yy[b + 2] = xl[j, 1]
        yy[b + 3] = thd
        yy[b + 4] = 0.0
        yy[b + 5] = 0.0
        yy[b + 6] = xl[j, 2]
        yy[b + 7] = xl[j, 3]
        yy[b + 8] = xl[j, 4]


@hot
def cage_residual(t, y0, xl, xg, act, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy,
                  yy, dy, diag, bd, Rl, Rg, share):
    """Residuals [N] at (xl, xg): per ball Rl (Z, 6) (F_r + m r th_d^2, F_z, (M_r + J th_d Omega_t) / (D/2),
    (M_t - J th_d Omega_r) / (D/2), M_z / (D/2), F_t: the steady equations of dynamics_kernels' ball in
    the frame orbiting with it), global Rg (8) (ring loads F_ext + sum F_ball, moments over dm/2; cage
    torque over dm/2; cage forces), each ball's share of the global residuals share (Z, 8). yy receives
    the dynamics state; dy, diag and bd the right-hand side, outputs and ball details there. act (8,
    bool): active global unknowns (inactive ones have zero residual)."""
    cage_state(y0, xl, xg, P, U, yy)
    K.rhs(t, yy, dy, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd, True)
    mb = P[K.P_MB]
    Jb = P[K.P_JB]
    hD = 0.5 * P[K.P_D]
    hdm = 0.5 * P[K.P_DM]
    for j in range(xl.shape[0]):
        b = K.NSTATE_FIXED + K.NSB * j
        Rl[j, 0] = mb * dy[b + 4]
        Rl[j, 1] = mb * dy[b + 5]
        Rl[j, 2] = Jb * dy[b + 6] / hD
        Rl[j, 3] = Jb * dy[b + 7] / hD
        Rl[j, 4] = Jb * dy[b + 8] / hD
        Rl[j, 5] = mb * yy[b + 1] * dy[b + 3]          # F_t (orbital acceleration times m r)
        share[j, 0] = bd[j, K.BD_CFRX]
        share[j, 1] = bd[j, K.BD_CFRY]
        share[j, 2] = bd[j, K.BD_CFRZ]
        share[j, 3] = bd[j, K.BD_CMRX] / hdm
        share[j, 4] = bd[j, K.BD_CMRY] / hdm
        share[j, 5] = bd[j, K.BD_CTC] / hdm
        share[j, 6] = bd[j, K.BD_CFCX]
        share[j, 7] = bd[j, K.BD_CFCY]
    Rg[0] = U[K.U_FX] + diag[iF]
    Rg[1] = U[K.U_FY] + diag[iF + 1]
    Rg[2] = U[K.U_FZ] + diag[iF + 2]
    Rg[3] = (U[K.U_MX] + diag[iM]) / hdm
    Rg[4] = (U[K.U_MY] + diag[iM + 1]) / hdm
    Rg[5] = P[K.P_IC] * dy[11] / hdm                   # cage torque
    Rg[6] = P[K.P_MC] * dy[14]                         # cage forces
    Rg[7] = P[K.P_MC] * dy[15]
    for k in range(NG):
        if not act[k]:
            Rg[k] = 0.0
            for j in range(xl.shape[0]):
                share[j, k] = 0.0


@hot
def cage_scaled_residual(t, y0, v, xs_l, xs_g, act, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy,
                         xl, xg, yy, dy, diag, bd, Rl, Rg, share, R):
    """R = residual vector (balls then globals) at the scaled unknowns v (non-finite entries 1e12); (xl, xg)
    and (Rl, Rg, share) receive the physical unknowns and the residual blocks. Returns max |R|."""
    Z = xl.shape[0]
    for j in range(Z):
        for k in range(NL):
            xl[j, k] = v[j * NL + k] * xs_l[k]
    for k in range(NG):
        xg[k] = v[Z * NL + k] * xs_g[k]
    cage_residual(t, y0, xl, xg, act, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy,
                  yy, dy, diag, bd, Rl, Rg, share)
    r = 0.0
    for j in range(Z):
        for k in range(NL):
            q = Rl[j, k]
            R[j * NL + k] = q if math.isfinite(q) else 1e12
    for k in range(NG):
        q = Rg[k]
        R[Z * NL + k] = q if math.isfinite(q) else 1e12
    for i in range(R.size):
        r = max(r, abs(R[i]))
    return r


@hot
def _steps(xl, xg, omega, hl, hg):
    """Forward-difference steps: positions 1e-10 m, angular velocities 1e-7 of their size (at least 0.1
    omega), q and g 1e-4 N beyond the clearance (1e-6 N inside), cage speed 1e-7 of omega, tilts 1e-9 rad."""
    Z = xl.shape[0]
    for j in range(Z):
        hl[j, 0] = 1e-10
        hl[j, 1] = 1e-10
        for k in range(2, 5):
            hl[j, k] = 1e-7 * max(abs(xl[j, k]), 0.1 * omega) + 1e-9
        hl[j, 5] = 1e-4 if abs(xl[j, 5]) > Q_GAP else 1e-6
    hg[0] = 1e-10
    hg[1] = 1e-10
    hg[2] = 1e-10
    hg[3] = 1e-9
    hg[4] = 1e-9
    hg[5] = 1e-7 * max(abs(xg[G_WC]), 1e-3 * omega, 1e-3)
    gm = math.sqrt(xg[G_GX] ** 2 + xg[G_GY] ** 2)
    hg[6] = 1e-6 * max(gm, 1.0)
    hg[7] = hg[6]


@hot
def cage_jacobian(t, y0, xl, xg, Rl, Rg, share, act, omega, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp,
                  qx, qwx, qy, qwy, yy, dy, diag, bd, A, B, C, Dg):
    """Arrow-structured Jacobian at (xl, xg) with residuals (Rl, Rg, share) there by forward differences
    (14 rhs calls; steps: _steps): ball blocks A (Z x 6 x 6), ball-global B (Z x 6 x 8), global-ball C
    (Z x 8 x 6), global-global Dg (8 x 8; -1 on the diagonal of inactive unknowns)."""
    Z = xl.shape[0]
    xp = xl.copy()
    gp = xg.copy()
    Rl2 = np.empty((Z, NL))
    Rg2 = np.empty(NG)
    sh2 = np.empty((Z, NG))
    hl = np.empty((Z, NL))
    hg = np.empty(NG)
    _steps(xl, xg, omega, hl, hg)
    for k in range(NL):
        for j in range(Z):
            xp[j, k] = xl[j, k] + hl[j, k]
        cage_residual(t, y0, xp, xg, act, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy,
                      yy, dy, diag, bd, Rl2, Rg2, sh2)
        for j in range(Z):
            xp[j, k] = xl[j, k]
            h = hl[j, k]
            for i in range(NL):
                A[j, i, k] = (Rl2[j, i] - Rl[j, i]) / h
            for i in range(NG):
                C[j, i, k] = (sh2[j, i] - share[j, i]) / h if act[i] else 0.0
    for k in range(NG):
        if act[k]:
            gp[k] = xg[k] + hg[k]
            cage_residual(t, y0, xl, gp, act, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy,
                          yy, dy, diag, bd, Rl2, Rg2, sh2)
            gp[k] = xg[k]
            for j in range(Z):
                for i in range(NL):
                    B[j, i, k] = (Rl2[j, i] - Rl[j, i]) / hg[k]
            for i in range(NG):
                Dg[i, k] = (Rg2[i] - Rg[i]) / hg[k] if act[i] else 0.0
        else:
            for j in range(Z):
                for i in range(NL):
                    B[j, i, k] = 0.0
            for i in range(NG):
                Dg[i, k] = 0.0
    # the ball columns' effect on the global rows is in C (each ball's share); the share does not hold the
    # global terms that depend on ball unknowns only through the cage / ring (none: land and churning
    # depend on the cage's own unknowns)
    for i in range(NG):
        if not act[i]:
            Dg[i, i] = -1.0


@hot
def cage_assemble(A, B, C, Dg, xs_l, xs_g, J):
    """Dense Jacobian J (n x n, n = 6 Z + 8) of the scaled unknowns from the arrow blocks."""
    Z = A.shape[0]
    ng = Z * NL
    for i in range(J.shape[0]):
        for k in range(J.shape[1]):
            J[i, k] = 0.0
    for j in range(Z):
        r0 = j * NL
        for i in range(NL):
            for k in range(NL):
                J[r0 + i, r0 + k] = A[j, i, k] * xs_l[k]
            for k in range(NG):
                J[r0 + i, ng + k] = B[j, i, k] * xs_g[k]
        for i in range(NG):
            for k in range(NL):
                J[ng + i, r0 + k] = C[j, i, k] * xs_l[k]
    for i in range(NG):
        for k in range(NG):
            J[ng + i, ng + k] = Dg[i, k] * xs_g[k]


@hot
def _dense_solve(A, B, C, Dg, xs_l, xs_g, d, dtau, R, dv):
    n = R.size
    M = np.empty((n, n))
    cage_assemble(A, B, C, Dg, xs_l, xs_g, M)
    for i in range(n):
        for k in range(n):
            M[i, k] = -M[i, k]
        if dtau > 0.0:
            M[i, i] += d[i] / dtau
    piv = np.empty(n, dtype=np.int64)
    if _lu6(M, piv) == 0.0:
        return False
    for i in range(n):
        dv[i] = R[i]
    K._lu_solve(M, piv, dv)
    return True


@hot
def cage_arrow_solve(A, B, C, Dg, xs_l, xs_g, d, dtau, R, dv):
    """Solve (diag(d) / dtau - J) dv = R (dtau <= 0: -J dv = R, Newton), J the scaled arrow Jacobian, by
    eliminating each ball's 6 unknowns and solving the 8 x 8 Schur complement of ring and cage; dense LU
    when a pivot falls below 1e-12 of its block's largest entry. False if exactly singular."""
    Z = A.shape[0]
    ng = Z * NL
    Mjj = np.empty((NL, NL))
    X = np.empty((Z, NL, NG))
    x = np.empty((Z, NL))
    S = np.empty((NG, NG))
    s = np.empty(NG)
    col = np.empty(NL)
    piv = np.empty(NL, dtype=np.int64)
    pivs = np.empty(NG, dtype=np.int64)
    for i in range(NG):
        for k in range(NG):
            S[i, k] = -Dg[i, k] * xs_g[k]
        if dtau > 0.0:
            S[i, i] += d[ng + i] / dtau
        s[i] = R[ng + i]
    for j in range(Z):
        r0 = j * NL
        for i in range(NL):
            for k in range(NL):
                Mjj[i, k] = -A[j, i, k] * xs_l[k]
            if dtau > 0.0:
                Mjj[i, i] += d[r0 + i] / dtau
        if not _lu6(Mjj, piv) > 1e-12:
            return _dense_solve(A, B, C, Dg, xs_l, xs_g, d, dtau, R, dv)
        for k in range(NG):
            for i in range(NL):
                col[i] = -B[j, i, k] * xs_g[k]
            K._lu_solve(Mjj, piv, col)
            for i in range(NL):
                X[j, i, k] = col[i]
        for i in range(NL):
            col[i] = R[r0 + i]
        K._lu_solve(Mjj, piv, col)
        for i in range(NL):
            x[j, i] = col[i]
        for i in range(NG):
            acc = 0.0
            for m in range(NL):
                acc += C[j, i, m] * xs_l[m] * x[j, m]
            s[i] += acc
            for k in range(NG):
                acc = 0.0
                for m in range(NL):
                    acc += C[j, i, m] * xs_l[m] * X[j, m, k]
                S[i, k] += acc
    if not _lu6(S, pivs) > 1e-12:
        return _dense_solve(A, B, C, Dg, xs_l, xs_g, d, dtau, R, dv)
    K._lu_solve(S, pivs, s)
    for k in range(NG):
        dv[ng + k] = s[k]
    for j in range(Z):
        r0 = j * NL
        for i in range(NL):
            acc = x[j, i]
            for k in range(NG):
                acc -= X[j, i, k] * s[k]
            dv[r0 + i] = acc
    for i in range(dv.size):
        if not math.isfinite(dv[i]):
            return _dense_solve(A, B, C, Dg, xs_l, xs_g, d, dtau, R, dv)
    return True


@hot
def cage_diagonal(A, Dg, xs_l, xs_g, d):
    """d = |diag J| of the scaled Jacobian, floored at 1e-6 of its largest entry (and of 1)."""
    Z = A.shape[0]
    ng = Z * NL
    dmax = 0.0
    for j in range(Z):
        for k in range(NL):
            d[j * NL + k] = abs(A[j, k, k] * xs_l[k])
            dmax = max(dmax, d[j * NL + k])
    for k in range(NG):
        d[ng + k] = abs(Dg[k, k] * xs_g[k])
        dmax = max(dmax, d[ng + k])
    floor = 1e-6 * max(dmax, 1.0)
    for i in range(d.size):
        d[i] = max(d[i], floor)


@hot
def cage_ptc(t, y0, v, xs_l, xs_g, cap, act, omega, ftol, budget, dtau0, iF, iM, P, U, tab_i, tab_o, ta0, tda,
             tp, qx, qwx, qy, qwy, A, B, C, Dg, have_jac):
    """Pseudo-transient continuation from the scaled unknowns v (overwritten with the end point): implicit
    Euler steps (diag(|J_ii|) / dtau - J) dv = R of the pseudo-dynamics dx/dtau = diag(|J_ii|)^-1 R(x),
    dtau from dtau0 by switched evolution relaxation (dtau *= |R_old| / |R_new| within [0.3, 10]; beyond
    1e12 the steps are Newton's), each step scaled down to the caps cap (per scaled unknown). The Jacobian
    (A, B, C, Dg; given at v if have_jac) is kept over accepted steps that contract the residual at least
    two-fold and rebuilt otherwise; a step that raises the residual is rejected (on a fresh Jacobian dtau
    shrinks ten-fold). Stops when max |R| <= ftol or after budget residual evaluations (15 per Jacobian).
    Returns (max |R|, evaluations, Jacobian fresh at v: 1/0)."""
    Z = (v.size - NG) // NL
    n = v.size
    xl = np.empty((Z, NL))
    xg = np.empty(NG)
    yy = np.empty(y0.size)
    dy = np.empty(y0.size)
    diag = np.zeros(K.NOUT)
    bd = np.zeros((Z, K.NBD))
    Rl = np.empty((Z, NL))
    Rg = np.empty(NG)
    share = np.empty((Z, NG))
    R = np.empty(n)
    R2 = np.empty(n)
    v2 = np.empty(n)
    dv = np.empty(n)
    d = np.empty(n)
    r = cage_scaled_residual(t, y0, v, xs_l, xs_g, act, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy,
                             qwy, xl, xg, yy, dy, diag, bd, Rl, Rg, share, R)
    nfev = 1
    dtau = dtau0
    fresh = have_jac
    if fresh:
        cage_diagonal(A, Dg, xs_l, xs_g, d)
    age = 0
    at_v = True
    while nfev < budget and r > ftol:
        if not fresh:
            if not at_v:
                cage_scaled_residual(t, y0, v, xs_l, xs_g, act, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx,
                                     qy, qwy, xl, xg, yy, dy, diag, bd, Rl, Rg, share, R)
                nfev += 1
                at_v = True
            cage_jacobian(t, y0, xl, xg, Rl, Rg, share, act, omega, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp,
                          qx, qwx, qy, qwy, yy, dy, diag, bd, A, B, C, Dg)
            nfev += 14
            cage_diagonal(A, Dg, xs_l, xs_g, d)
            fresh = True
            age = 0
        if not cage_arrow_solve(A, B, C, Dg, xs_l, xs_g, d, dtau if dtau < 1e12 else 0.0, R, dv):
            dtau *= 0.1
            nfev += 1
            if dtau < 1e-10:
                break
            continue
        f = 1.0
        for i in range(n):
            f = max(f, abs(dv[i]) / cap[i])
        for i in range(n):
            v2[i] = v[i] + dv[i] / f
        r2 = cage_scaled_residual(t, y0, v2, xs_l, xs_g, act, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp,
                                  qx, qwx, qy, qwy, xl, xg, yy, dy, diag, bd, Rl, Rg, share, R2)
        nfev += 1
        at_v = False
        if not math.isfinite(r2) or r2 > r * (1.0 if f == 1.0 else 2.0):
            if age > 0:
                fresh = False           # a kept Jacobian: rebuild it first
            else:
                dtau = max(dtau * 0.1, 1e-10)
                if dtau <= 1e-10:
                    break
            continue
        for i in range(n):
            v[i] = v2[i]
            R[i] = R2[i]
        at_v = True
        ratio = r2 / r if r > 0.0 else 0.0
        dtau = min(dtau * min(max(r / max(r2, 1e-300), 0.3), 10.0), 1e15)
        r = r2
        age += 1
        if ratio > 0.5 or age >= 8:
            fresh = False
        else:
            fresh = fresh       # chord step: the Jacobian is kept
        if age > 0 and fresh:
            pass
    # a fresh Jacobian only if no accepted step since it was built
    return r, nfev, 1 if (fresh and age == 0) else 0
