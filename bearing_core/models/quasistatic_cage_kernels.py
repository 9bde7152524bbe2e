"""numba kernels of the quasi-static cage model (bearing_core.models.quasistatic_cage, whose module docstring
states the equations and the method).

Unknowns:   xl (Z, 7) per ball: r, z [m] (centre), Omega_r, Omega_t, Omega_z [rad/s] (absolute angular
            velocity, local frame), q [N] (pocket-force coordinate, pocket_place), theta_dot [rad/s]
            (orbital speed); xg (8): inner ring dx, dy, dz [m], tx, ty [rad]; cage speed wc [rad/s];
            cage-centre coordinates gx, gy [N] (cage_centre)
Pocket:     pocket_tangential_force, pocket_place   the dynamics' pocket kernels and the ball's place in its
                                pocket for a given tangential pocket force (false position)
State:      cage_state          the unknowns written into a dynamics state (dynamics_kernels layout): cage
                                turning about its standing centre, balls in their pockets, ring at its pose
Residual:   cage_residual       one call of the dynamics' right-hand side (dynamics_kernels.rhs) at that
                                state: per ball the generalised forces of its unknowns and its kinematic
                                residual, the ring's 5 loads, the cage's torque and forces, each ball's
                                share of them; orbit_coupling adds the terms that tie ball j to ball j - 1
                                along the orbit (the motion periodic in the cage frame)
Jacobian:   cage_jacobian       forward differences, one call per ball unknown (all balls at once: the
                                rhs couples no two balls) with orbit_coupling's derivatives in closed
                                form, one call per global unknown; cage_dense
                                assembles the dense matrix; dense_solve its LU solve
Scaled unknowns v = (xl / xs_l, xg / xs_g) flattened (ball-major); residuals are forces [N] (moments over
D/2 or dm/2).
"""
from __future__ import annotations

import math

import numpy as np

from . import dynamics_kernels as K
from ..contact.contact_kernels import ball_pocket_contact_rel
from .quasistatic_tribo_kernels import _lu6
from ..lubrication.pocket_film import ball_pocket_lubricated_rel
from ..numerics.jit import hot

NL = 7      # per-ball unknowns: r, z, Omega_r, Omega_t, Omega_z, q, theta_dot
NG = 8      # global unknowns: dx, dy, dz, tx, ty, wc, gx, gy
G_WC, G_GX, G_GY = 5, 6, 7
# force scale of the coordinates q and g inside a dry clearance [N]: |q| <= Q_GAP moves the ball linearly
# across its pocket clearance (g the cage across its land clearance), beyond it the penalty contact carries
# |q| - Q_GAP
Q_GAP = 1.0


@hot
def pocket_tangential_force(dth, thb, wc, rbc, P, D, Wr, Wz):
    """Tangential force [N] of the pocket on the ball (along the orbit; < 0 pushes it back) at the offset dth
    [rad] from the pocket centre about the cage centre (arm rbc [m]), the ball's azimuth rate about the cage
    centre thb and the cage speed wc [rad/s], its angular velocity components Wr, Wz [rad/s]: the
    dynamics' pocket kernels (dry: contact_kernels.ball_pocket_contact_rel; oil: pocket_film.
    ball_pocket_lubricated_rel, films on both walls with their squeeze terms), at rest radially and axially."""
    if P[K.P_LUBE] > 0.5:
        r = ball_pocket_lubricated_rel(dth, thb, wc, rbc, P[K.P_CPOCKET], P[K.P_KPOCKET], P[K.P_CPOCKETD],
                                       P[K.P_MUBL], P[K.P_MUEHL], 0.01, P[K.P_ETA_PK], P[K.P_ALPHA_PK],
                                       P[K.P_EPK], P[K.P_SIGPK], D, 0.0, 0.0, Wr, Wz, 0.0, 0.0)
        return r[1]
    r = ball_pocket_contact_rel(dth, thb, wc, rbc, P[K.P_CPOCKET], P[K.P_KPOCKET], P[K.P_CPOCKETD],
                                P[K.P_MUPOCKET], 0.01, D, 0.0, 0.0, Wr, Wz, 0.0, 0.0)
    return r[1]


@hot
def pocket_place(q, thb, wc, rbc, P, D, Wr, Wz, guess):
    """Offset dth [rad] of the ball from its pocket centre (about the cage centre) at which the pocket's
    tangential force on the ball is -q [N] (q > 0: the ball leads its pocket and drives the cage): the
    root of pocket_tangential_force + q, decreasing in dth, bracketed by the penetrations that carry
    |q| + 1e3 N on the penalty stiffness alone, by false position with the Illinois modification (Dahlquist
    & Bjorck, Numerical Methods, Sec. 6.2) to 1e-9 N or 1e-14 rad. A dry pocket carries no force in its
    clearance: there |q| <= Q_GAP moves the ball linearly from the pocket centre to the wall, and beyond the
    pocket's force is -(|q| - Q_GAP) sign(q), so that the place is continuous in q.

    guess [rad] (NaN: none): a nearby root (the same ball's place at a neighbouring state, e.g. the base
    point of a finite difference); the bracket is then grown from it (steps 1e-6 of the clearance angle,
    eight-fold each time) instead of spanning the whole pocket, the same root to the same tolerance in a few
    evaluations."""
    cp = P[K.P_CPOCKET]
    kpk = P[K.P_KPOCKET]
    lim = (cp + (abs(q) + 1e3) / kpk) / rbc
    lo = -lim
    hi = lim
    if P[K.P_LUBE] < 0.5:
        if abs(q) <= Q_GAP:
            return q / Q_GAP * cp / rbc
        if q > 0.0:
            lo = cp / rbc
            q = q - Q_GAP
        else:
            hi = -cp / rbc
            q = q + Q_GAP
    if lo < guess < hi:
        f0 = pocket_tangential_force(guess, thb, wc, rbc, P, D, Wr, Wz) + q
        if abs(f0) <= 1e-9:
            return guess
        step = 1e-6 * cp / rbc
        if f0 > 0.0:                      # decreasing: the root lies above the guess
            lo, flo = guess, f0
            while True:
                x = min(guess + step, hi)
                fx = pocket_tangential_force(x, thb, wc, rbc, P, D, Wr, Wz) + q
                if fx <= 0.0 or x >= hi:
                    hi, fhi = x, fx
                    break
                lo, flo = x, fx
                step *= 8.0
        else:
            hi, fhi = guess, f0
            while True:
                x = max(guess - step, lo)
                fx = pocket_tangential_force(x, thb, wc, rbc, P, D, Wr, Wz) + q
                if fx >= 0.0 or x <= lo:
                    lo, flo = x, fx
                    break
                hi, fhi = x, fx
                step *= 8.0
    else:
        flo = pocket_tangential_force(lo, thb, wc, rbc, P, D, Wr, Wz) + q
        fhi = pocket_tangential_force(hi, thb, wc, rbc, P, D, Wr, Wz) + q
    side = 0
    x = 0.0
    for _ in range(100):
        x = (lo * fhi - hi * flo) / (fhi - flo) if fhi != flo else 0.5 * (lo + hi)
        if not (lo < x < hi):
            x = 0.5 * (lo + hi)
        f = pocket_tangential_force(x, thb, wc, rbc, P, D, Wr, Wz) + q
        if abs(f) <= 1e-9 or hi - lo <= 1e-14:
            break
        if f > 0.0:
            lo = x
            flo = f
            if side == -1:
                fhi *= 0.5
            side = -1
        else:
            hi = x
            fhi = f
            if side == 1:
                flo *= 0.5
            side = 1
    return x


@hot
def lu_factor(J, M, piv):
    """M, piv = the LU factors of J with partial pivoting (quasistatic_tribo_kernels._lu6), for lu_solve;
    False if J is exactly singular."""
    for i in range(J.shape[0]):
        for k in range(J.shape[1]):
            M[i, k] = J[i, k]
    return _lu6(M, piv) != 0.0


@hot
def lu_solve(M, piv, R, dv):
    """dv = J^-1 R from lu_factor's factors (dynamics_kernels._lu_solve)."""
    for i in range(R.size):
        dv[i] = R[i]
    K._lu_solve(M, piv, dv)


@hot
def dense_solve(J, R, dv):
    """dv = J^-1 R by LU with partial pivoting (quasistatic_tribo_kernels._lu6, dynamics_kernels._lu_solve);
    False if J is exactly singular."""
    n = R.size
    M = J.copy()
    piv = np.empty(n, dtype=np.int64)
    if _lu6(M, piv) == 0.0:
        return False
    for i in range(n):
        dv[i] = R[i]
    K._lu_solve(M, piv, dv)
    return True


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
def cage_state(y0, xl, xg, P, U, yy, dguess, dplace):
    """yy = y0 with the unknowns written into the dynamics state: ring pose (rates 0), cage angle 0, speed wc,
    centre from (gx, gy) (at rest); ball j at the azimuth whose offset from pocket j (the right-hand side's
    dth, measured about the cage centre) makes the pocket's tangential force -q_j (pocket_place), at (r, z),
    orbiting about the bearing axis at theta_dot_j, no radial or axial velocity, angular velocity
    (Omega_r, Omega_t, Omega_z). dplace (Z, 2) receives each ball's pocket offsets of the two fixed-point
    passes; dguess (Z, 2) holds those of a neighbouring state to start pocket_place from (NaN: none; the
    second pass starts from the first)."""
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
    D = P[K.P_D]
    for j in range(Z):
        b = K.NSTATE_FIXED + K.NSB * j
        rb = xl[j, 0]
        thd = xl[j, 6]
        psi = 2.0 * math.pi * j / Z
        th = psi
        # the rhs measures the offset about the cage centre, dth = th - psi + atan2(xc s - yc c, rb - xc c -
        # yc s), with the azimuth rate about it thb = thd rb (bx c + by s) / |b|^2; both change with th by
        # terms of order e / rb: two fixed-point passes
        d = math.nan
        for ps in range(2):
            c = math.cos(th)
            s = math.sin(th)
            bx = rb * c - xc
            by = rb * s - yc
            rbc = math.sqrt(bx * bx + by * by)
            thb = thd * rb * (bx * c + by * s) / (rbc * rbc)
            g = dguess[j, ps]
            d = pocket_place(xl[j, 5], thb, wc, rbc, P, D, xl[j, 2], xl[j, 4], g if math.isfinite(g) else d)
            dplace[j, ps] = d
            th = psi + d - math.atan2(xc * s - yc * c, rb - xc * c - yc * s)
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
def kin_scale(P, U):
    """Scale [N s] of the kinematic residuals: m_b (dm/2) |omega| Z / (2 pi), the orbital inertia force of a
    speed difference of 1 rad/s over one ball spacing."""
    return P[K.P_MB] * 0.5 * P[K.P_DM] * max(abs(U[K.U_W1]), 1.0) * P[K.P_Z] / (2.0 * math.pi)


@hot
def pocket_offsets(yy, Z, dth):
    """dth[j]: offset [rad] of ball j from its pocket centre about the cage centre at the state yy (the
    right-hand side's dth; cage angle 0)."""
    xc = yy[12]
    yc = yy[13]
    for j in range(Z):
        b = K.NSTATE_FIXED + K.NSB * j
        th = yy[b]
        rb = yy[b + 1]
        c = math.cos(th)
        s = math.sin(th)
        dth[j] = th - 2.0 * math.pi * j / Z + math.atan2(xc * s - yc * c, rb - xc * c - yc * s)


@hot
def orbit_coupling(xl, xg, yy, P, U, Rl, lam):
    """Add lam times the terms that tie ball j to ball j - 1 along the orbit (lam = 1: the periodic motion;
    0: every ball held at the cage's azimuth rate, the start of a continuation in lam). The balls at the
    pocket azimuths psi_j = 2 pi j / Z are one ball seen a time dpsi / wc apart (the steady motion is
    periodic in the cage frame), so along its orbit a ball's orbital speed and its place in the pocket
    change at the rates wc (theta_dot_j - theta_dot_(j-1)) / dpsi and wc (dth_j - dth_(j-1)) / dpsi
    (first-order upwind differences in the direction of the orbit, wc > 0). The F_t equation gets the
    orbital inertia force m r wc (theta_dot_j - theta_dot_(j-1)) / dpsi, the kinematic equation reads
    thb_j - wc = wc (dth_j - dth_(j-1)) / dpsi (times kin_scale). The ball's angular velocity changes along
    the orbit too (its contact angles, loads and pocket force change with the azimuth): the three moment
    equations become J wc (Omega_j - Omega_(j-1)) / dpsi = (M_j + M_(j-1)) / 2, the trapezoidal rule
    along the orbit. Where the race traction saturates the steady moment equations hardly fix the ball's
    rolling speed, and its rotational inertia then sets how far the speed lags behind the load along the
    orbit: without these terms the race losses at 7218B, 3000 rpm, Fx 1 kN, Fz 3 kN were 176 W against the
    dynamics' 251 W, with them 250 W."""
    Z = xl.shape[0]
    dpsi = 2.0 * math.pi / Z
    wc = xg[G_WC]
    mb = P[K.P_MB]
    ks = kin_scale(P, U)
    Jb = P[K.P_JB]
    hD = 0.5 * P[K.P_D]
    dth = np.empty(Z)
    pocket_offsets(yy, Z, dth)
    for j in range(Z):
        i = j - 1 if j > 0 else Z - 1
        Rl[j, 5] -= lam * mb * xl[j, 0] * wc * (xl[j, 6] - xl[i, 6]) / dpsi
        Rl[j, 6] -= lam * ks * wc * (dth[j] - dth[i]) / dpsi
    # the ball's rotation along the orbit: J dOmega/dt = M (dynamics_kernels' ball equations in the frame
    # orbiting with it; Rl[:, 2:5] holds the moments over D/2 with their gyroscopic terms), dOmega/dt =
    # wc (Omega_j - Omega_(j-1)) / dpsi, the moments averaged over the interval (trapezoidal rule). The
    # trapezoidal rule conserves the rotational kinetic energy; upwind differences dissipate
    # J wc sum (Omega_j - Omega_(j-1))^2 / (2 dpsi): 2.5 % of the drive power at 7218B, 3000 rpm, Fx 1 kN,
    # Fz 3 kN, which broke the power balance of the steady state
    Mo = Rl[:, 2:5].copy()
    for j in range(Z):
        i = j - 1 if j > 0 else Z - 1
        for k in range(3):
            Rl[j, 2 + k] = ((1.0 - 0.5 * lam) * Mo[j, k] + 0.5 * lam * Mo[i, k]
                            - lam * Jb * wc * (xl[j, 2 + k] - xl[i, 2 + k]) / (dpsi * hD))


@hot
def cage_residual(t, y0, xl, xg, act, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy,
                  yy, dy, diag, bd, Rl, Rg, share, dguess, dplace):
    """Residuals [N] at (xl, xg): per ball Rl (Z, 6) (F_r + m r th_d^2, F_z, (M_r + J th_d Omega_t) / (D/2),
    (M_t - J th_d Omega_r) / (D/2), M_z / (D/2), F_t: the steady equations of dynamics_kernels' ball in
    the frame orbiting with it), global Rg (8) (ring loads F_ext + sum F_ball, moments over dm/2; cage
    torque over dm/2; cage forces), each ball's share of the global residuals share (Z, 8). yy receives
    the dynamics state; dy, diag and bd the right-hand side, outputs and ball details there. act (8,
    bool): active global unknowns (inactive ones have zero residual). dguess, dplace: cage_state."""
    cage_state(y0, xl, xg, P, U, yy, dguess, dplace)
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
        # azimuth rate of the ball about the cage centre (rhs's thb_d with rd = 0) minus the cage speed, in
        # force units (times KIN_SCALE)
        th = yy[b]
        c = math.cos(th)
        sn = math.sin(th)
        rb_ = yy[b + 1]
        bx = rb_ * c - yy[12]
        by = rb_ * sn - yy[13]
        thb = yy[b + 3] * rb_ * (bx * c + by * sn) / (bx * bx + by * by)
        Rl[j, 6] = kin_scale(P, U) * (thb - xg[G_WC])
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
def acceleration_loads(xl, xg, P, Rl, Rg, acc):
    """Subtract the d'Alembert loads of a uniform relative acceleration acc = dwc/dt / wc [1/s] of every
    rotation with the cage (the accelerating quasi-steady state: the balls' orbit and absolute rotation and
    the cage speed grow at the rate acc, the ball-race contact and pocket forces in equilibrium with the
    inertia forces; the class of models of Jain & Hunt and Han in seed 002's review, d'Alembert's principle):
    F_t - m r acc theta_dot, (M - J acc Omega) / (D/2) per component (the ball's rotation in its orbiting frame,
    Omega growing in proportion), cage torque (T - I_c acc wc) / (dm/2). acc = 0: the steady state."""
    if acc == 0.0:
        return
    mb = P[K.P_MB]
    Jb = P[K.P_JB]
    hD = 0.5 * P[K.P_D]
    for j in range(xl.shape[0]):
        Rl[j, 5] -= mb * xl[j, 0] * acc * xl[j, 6]
        for k in range(3):
            Rl[j, 2 + k] -= Jb * acc * xl[j, 2 + k] / hD
    Rg[5] -= P[K.P_IC] * acc * xg[G_WC] / (0.5 * P[K.P_DM])


@hot
def cage_scaled_residual(t, y0, v, xs_l, xs_g, act, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy,
                         xl, xg, yy, dy, diag, bd, Rl, Rg, share, R, lam, dplace, acc):
    """R = residual vector (balls then globals) at the scaled unknowns v (non-finite entries 1e12); (xl, xg)
    and (Rl, Rg, share) receive the physical unknowns and the residual blocks. Returns max |R|.

    dplace (Z, 2): on entry the balls' pocket offsets of a nearby evaluation (NaN: none), the starts of
    pocket_place's root search (the same root to its tolerance, in fewer evaluations: an iteration's points are
    close); on return this evaluation's."""
    Z = xl.shape[0]
    for j in range(Z):
        for k in range(NL):
            xl[j, k] = v[j * NL + k] * xs_l[k]
    for k in range(NG):
        xg[k] = v[Z * NL + k] * xs_g[k]
    dg = dplace.copy()
    cage_residual(t, y0, xl, xg, act, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy,
                  yy, dy, diag, bd, Rl, Rg, share, dg, dplace)
    acceleration_loads(xl, xg, P, Rl, Rg, acc)
    orbit_coupling(xl, xg, yy, P, U, Rl, lam)
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
        hl[j, 5] = 1e-6 * max(abs(xl[j, 5]), 1.0)
        hl[j, 6] = 1e-7 * max(abs(omega), 1.0)
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
def _full_residual(t, y0, xl, xg, act, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, yy, dy, diag, bd,
                   Rl, Rg, share, lam, dguess, dplace, acc):
    cage_residual(t, y0, xl, xg, act, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy,
                  yy, dy, diag, bd, Rl, Rg, share, dguess, dplace)
    acceleration_loads(xl, xg, P, Rl, Rg, acc)
    orbit_coupling(xl, xg, yy, P, U, Rl, lam)


@hot
def cage_jacobian(t, y0, xl, xg, act, omega, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp,
                  qx, qwx, qy, qwy, yy, dy, diag, bd, A, B, C, Dg, E, lam, acc):
    """Jacobian at (xl, xg) by forward differences (steps: _steps), 7 + 8 + 1 rhs calls.

    Ball columns: with the globals held, the right-hand side couples no two balls (a ball's forces depend on
    its own unknowns, the ring pose and the cage's), so unknown k of ALL balls is perturbed in one call; that
    gives each ball's derivatives of its own residuals before orbit_coupling (Araw, Z x 7 x 7), of its share
    of the global residuals (C, Z x 8 x 7) and of its pocket offset dth. orbit_coupling is linear in those
    (and bilinear in r and theta_dot), so its derivatives follow in closed form: A (Z x 7 x 7), a ball's rows
    against its own unknowns, and E (Z x 7 x 7), against those of the ball before it along the orbit.
    Global columns: one call each (B, Z x 7 x 8; Dg, 8 x 8, -1 on the diagonal of inactive unknowns)."""
    Z = xl.shape[0]
    Rl0 = np.empty((Z, NL))
    Rg0 = np.empty(NG)
    share = np.empty((Z, NG))
    dbase = np.empty((Z, 2))            # the balls' places at the base point: the starts of the perturbed ones
    dpl = np.empty((Z, 2))
    cage_residual(t, y0, xl, xg, act, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy,
                  yy, dy, diag, bd, Rl0, Rg0, share, np.full((Z, 2), np.nan), dbase)
    acceleration_loads(xl, xg, P, Rl0, Rg0, acc)
    dth0 = np.empty(Z)
    pocket_offsets(yy, Z, dth0)
    Rl = Rl0.copy()                     # the full residual at the base point, for the global columns
    orbit_coupling(xl, xg, yy, P, U, Rl, lam)
    xp = xl.copy()
    gp = xg.copy()
    Rl2 = np.empty((Z, NL))
    Rg2 = np.empty(NG)
    sh2 = np.empty((Z, NG))
    dth2 = np.empty(Z)
    hl = np.empty((Z, NL))
    hg = np.empty(NG)
    _steps(xl, xg, omega, hl, hg)
    Araw = np.empty((Z, NL, NL))
    ddth = np.empty((Z, NL))
    for k in range(NL):
        for j in range(Z):
            xp[j, k] = xl[j, k] + hl[j, k]
        cage_residual(t, y0, xp, xg, act, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy,
                      yy, dy, diag, bd, Rl2, Rg2, sh2, dbase, dpl)
        acceleration_loads(xp, xg, P, Rl2, Rg2, acc)
        pocket_offsets(yy, Z, dth2)
        for j in range(Z):
            xp[j, k] = xl[j, k]
            h = hl[j, k]
            for i in range(NL):
                Araw[j, i, k] = (Rl2[j, i] - Rl0[j, i]) / h
            ddth[j, k] = (dth2[j] - dth0[j]) / h
            for i in range(NG):
                C[j, i, k] = (sh2[j, i] - share[j, i]) / h if act[i] else 0.0
    # orbit_coupling's derivatives: F_t row -c5 r_j (thd_j - thd_i), kinematic row -c6 (dth_j - dth_i),
    # moment rows (1 - lam/2) M_j + (lam/2) M_i - cm (Omega_j - Omega_i), i the ball before j
    dpsi = 2.0 * math.pi / Z
    wc = xg[G_WC]
    c5 = lam * P[K.P_MB] * wc / dpsi
    c6 = lam * kin_scale(P, U) * wc / dpsi
    cm = lam * P[K.P_JB] * wc / (dpsi * 0.5 * P[K.P_D])
    for j in range(Z):
        i = j - 1 if j > 0 else Z - 1
        n = j + 1 if j < Z - 1 else 0
        for m in range(NL):
            A[j, 0, m] = Araw[j, 0, m]
            A[j, 1, m] = Araw[j, 1, m]
            for q in range(3):
                A[j, 2 + q, m] = (1.0 - 0.5 * lam) * Araw[j, 2 + q, m]
            A[j, 5, m] = Araw[j, 5, m]
            A[j, 6, m] = Araw[j, 6, m] - c6 * ddth[j, m]
        A[j, 5, 0] -= c5 * (xl[j, 6] - xl[i, 6])
        A[j, 5, 6] -= c5 * xl[j, 0]
        for q in range(3):
            A[j, 2 + q, 2 + q] -= cm
        # ball n's rows against ball j's unknowns (j is the ball before n)
        for a in range(NL):
            for m in range(NL):
                E[n, a, m] = 0.0
        for m in range(NL):
            for q in range(3):
                E[n, 2 + q, m] = 0.5 * lam * Araw[j, 2 + q, m]
            E[n, 6, m] = c6 * ddth[j, m]
        E[n, 5, 6] = c5 * xl[n, 0]
        for q in range(3):
            E[n, 2 + q, 2 + q] += cm
    for k in range(NG):
        if act[k]:
            gp[k] = xg[k] + hg[k]
            _full_residual(t, y0, xl, gp, act, iF, iM, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, yy, dy,
                           diag, bd, Rl2, Rg2, sh2, lam, dbase, dpl, acc)
            gp[k] = xg[k]
            for j in range(Z):
                for i in range(NL):
                    B[j, i, k] = (Rl2[j, i] - Rl[j, i]) / hg[k]
            for i in range(NG):
                Dg[i, k] = (Rg2[i] - Rg0[i]) / hg[k] if act[i] else 0.0
        else:
            for j in range(Z):
                for i in range(NL):
                    B[j, i, k] = 0.0
            for i in range(NG):
                Dg[i, k] = 0.0
    for i in range(NG):
        if not act[i]:
            Dg[i, i] = -1.0


@hot
def cage_dense(A, B, C, Dg, E, xs_l, xs_g, J):
    """Dense Jacobian J (n x n, n = 7 Z + 8) of the scaled unknowns from the blocks."""
    Z = A.shape[0]
    ng = Z * NL
    for i in range(J.shape[0]):
        for k in range(J.shape[1]):
            J[i, k] = 0.0
    for j in range(Z):
        r0 = j * NL
        p0 = (j - 1 if j > 0 else Z - 1) * NL
        for i in range(NL):
            for k in range(NL):
                J[r0 + i, r0 + k] = A[j, i, k] * xs_l[k]
                J[r0 + i, p0 + k] += E[j, i, k] * xs_l[k]
            for k in range(NG):
                J[r0 + i, ng + k] = B[j, i, k] * xs_g[k]
        for i in range(NG):
            for k in range(NL):
                J[ng + i, r0 + k] = C[j, i, k] * xs_l[k]
    for i in range(NG):
        for k in range(NG):
            J[ng + i, ng + k] = Dg[i, k] * xs_g[k]


