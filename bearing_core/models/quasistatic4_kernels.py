"""numba kernels of the four-point-contact (gothic-arch) quasi-static model (bearing_core.models.quasistatic,
FourPointQuasiStaticModel, whose docstring states the geometry, the contact and kinematics equations and
their sources: Jones 1960; Harris & Kotzalas, Rolling Bearing Analysis 5th ed., Vol. 2 Ch. 3; Amasorrain
et al. 2003; Leblanc & Nelias 2007).

One ball:        _ball4            the four arcs' deflections, validity (contact point on the arc's own
                                   side of the groove mid-plane) and Hertz loads, the load weights of each
                                   ring, the two-point kinematics at the weighted contact angles, the
                                   centrifugal force and the Coulomb-bounded gyroscopic friction shared by
                                   the weights, equilibrium residual.
All balls:       _solve_balls4     per-ball Newton; balls it leaves out of equilibrium are restarted from
                                   the minimum of their contact + centrifugal potential (_potential_minimum,
                                   Nelder-Mead) and solved again.
Ring:            ring_forces4      force and moment of the two inner arcs of every ball on the inner ring.
5-DOF solve:     solve             Newton on the ring equilibrium, Harris's hybrid criterion, stiffness.

The building blocks shared with the two-point model come from bearing_core.models.quasistatic_kernels: the
per-ball Newton step, the Coulomb bound, Harris's hybrid criterion, the scales, least-squares step
(Jacobi SVD), line-search acceptance and stiffness columns of the 5-DOF solve. Arguments as there; ``geo``
carries in addition the groove offsets (G_EO, G_EI), Cr / Cz are (Z, 2) (inner arcs 1, 2), and the ball
state S has NS4 rows: the two-point rows (S_* of quasistatic_kernels; Qi / Qo / d_i / d_o those of each
ring's dominant contact, ai / ao the weighted contact angles) followed by the per-contact rows S4_*.
"""
from __future__ import annotations

import math

import numpy as np

from . import quasistatic_kernels as qk
from ..contact.hertz import ROW_K_LOAD, hertz_lookup_alpha_inline
from ..numerics.jit import hot
from .quasistatic_kernels import (CTRL_HYBRID, CTRL_INNER, G_A, G_ALPHA0, G_D, G_DM, G_FI, G_FO, G_MASS, G_RI,
                                  G_RIG, K_REG, LINE_SEARCH_FAILED, NOT_CONVERGED, NS, OK, S_BETA, S_FC, S_QI,
                                  S_QO, S_RR, S_RZ)

G_EO, G_EI, N_GEO = qk.N_GEO, qk.N_GEO + 1, qk.N_GEO + 2
# per-contact rows after the two-point rows: loads, angles, deflections, friction forces, weights of
# inner arcs 1, 2 and outer arcs 1, 2; index of each ring's dominant arc (0 or 1)
(S4_QI1, S4_QI2, S4_QO1, S4_QO2, S4_AI1, S4_AI2, S4_AO1, S4_AO2, S4_DI1, S4_DI2, S4_DO1, S4_DO2, S4_FI1,
 S4_FI2, S4_FO1, S4_FO2, S4_WI1, S4_WI2, S4_WO1, S4_WO2, S4_KI, S4_KO, NS4) = range(NS, NS + 23)
PAIR_ROWS = {"Qi4": S4_QI1, "Qo4": S4_QO1, "ai4": S4_AI1, "ao4": S4_AO1, "di4": S4_DI1, "do4": S4_DO1,
             "Fi4": S4_FI1, "Fo4": S4_FO1, "wi": S4_WI1, "wo": S4_WO1}


@hot
def k_table(tab_i, tab_o):
    """(2, n) table of the Hertz load-deflection constant K(alpha) of the inner (row 0) and outer (row 1)
    race, from the HertzTable arrays: the only row the ball kernel looks up (hertz_lookup_alpha with row
    0 / 1), in one array (one reference count per call of the ball kernel instead of three arrays)."""
    n = tab_i.shape[1]
    Kt = np.empty((2, n))
    for k in range(n):
        Kt[0, k] = tab_i[ROW_K_LOAD, k]
        Kt[1, k] = tab_o[ROW_K_LOAD, k]
    return Kt


@hot(inline="always")
def _geo_tuple(geo):                   # N_GEO = 15 entries
    """The geometry array as a tuple (passed by value to the ball kernel: no reference counting)."""
    return (geo[0], geo[1], geo[2], geo[3], geo[4], geo[5], geo[6], geo[7], geo[8], geo[9], geo[10], geo[11],
            geo[12], geo[13], geo[14])


@hot(inline="always")
def _exp_neg(x):
    """exp(x) for x <= 0 (the deflection softmax of _weights): 1 at x = 0 and 0 below -746, where exp underflows to 0
    (without the call and libm's underflow error path)."""
    if x == 0.0:
        return 1.0
    return math.exp(x) if x > -746.0 else 0.0


@hot(inline="always")
def _weights(v1, v2, Q1, Q2, d1, d2, D):
    """Shares (w1, w2) of the two arcs of one ring: Q_k plus 1e-9 N times a softmax of the deflections
    over 1e-6 D (which decides for unloaded balls and keeps w continuous), 0 on invalid arcs, normalised.
    A ring with one loaded contact gets w = 1 there: the two-point model exactly."""
    dm_ = -np.inf
    if v1:
        dm_ = d1
    if v2:
        dm_ = max(dm_, d2)
    w1 = max(Q1, 0.0) + 1e-9 * _exp_neg(min(0.0, d1 - dm_) / (1e-6 * D)) if v1 else 0.0
    w2 = max(Q2, 0.0) + 1e-9 * _exp_neg(min(0.0, d2 - dm_) / (1e-6 * D)) if v2 else 0.0
    ws = w1 + w2
    return w1 / ws, w2 / ws


@hot(inline="always")
def _arc(vr, vz, rc, f, D, off, side, sg, Kt, race, dal, full):
    """One arc: ball centre minus arc centre (vr, vz) [m], arc radius rc [m]. Returns (n_r, n_z, delta,
    alpha, valid, Q): unit normal from the arc centre, deflection, contact angle (atan2 of sg n; on an
    invalid arc computed only if full, else 0: it then enters nothing), whether the contact point lies
    on the arc's own side of the groove mid-plane (side +1: f D sin(alpha) >= e, -1: < -e) and the load
    (K delta^1.5, K_REG delta when separated, 0 when invalid)."""
    L = math.sqrt(vr * vr + vz * vz)
    nr = vr / L
    nz = vz / L
    d = L - rc
    sn = sg * f * D * nz
    valid = sn >= off if side > 0 else sn < -off
    a = 0.0
    if valid or full:
        # atan2(sg n_z, sg n_r); as atan of the ratio where sg n_r > 0 (a contact angle within +-90 deg:
        # the same angle to round-off, at half the cost of libm's atan2)
        a = math.atan(nz / nr) if sg * nr > 0.0 else math.atan2(sg * nz, sg * nr)
    Q = 0.0
    if valid:
        Q = hertz_lookup_alpha_inline(Kt, 0.0, dal, a, race) * d * math.sqrt(d) if d > 0.0 else K_REG * d
    return nr, nz, d, a, valid, Q


@hot(inline="always")
def _mean_dir(w1, w2, a1, a2, c1, s1, c2, s2):
    """cos and sin of the weighted contact angle w1 a1 + w2 a2; from the normals (c_k, s_k) = (cos a_k,
    sin a_k) where one weight is 0 (one valid arc: the angle itself)."""
    if w2 == 0.0:
        return c1, s1
    if w1 == 0.0:
        return c2, s2
    a = w1 * a1 + w2 * a2
    return math.cos(a), math.sin(a)


@hot(nrt=False)                # called per ball evaluation: no reference counting of Kt
def _ball4(Xr, Xz, cr1, cz1, cr2, cz2, omega, oc_in, control, geo, Kt, dal, full):
    """State of one ball with centre (Xr, Xz) [m] relative to the centre of outer arc 1, inner arc
    centres (cr1, cz1), (cr2, cz2) [m]. Returns two tuples: the two-point state in the order of the rows
    S_* (Rr, Rz, Qi, Qo, d_i, d_o, ai, ao, bx, wm, wR, Fc, Mg, lam_i, oc, Fi, Fo) and the per-contact
    values in the order of the rows S4_*, and by: the attitude angle is beta = atan2(by, bx) (ball_states4;
    the Newton iterations do not need it). full: also the angles of invalid arcs (recorded states)."""
    D = geo[G_D]
    eo = geo[G_EO]
    ei = geo[G_EI]
    fo = geo[G_FO]
    fi = geo[G_FI]
    # outer arcs 1, 2: centres (0, 0), (0, 2 e_o); inner arcs: (cr_k, cz_k); normal n_i from the inner
    # centre, contact angle of an inner arc atan2(-n_iz, -n_ir)
    nor1, noz1, do1, ao1, vo1, Qo1 = _arc(Xr, Xz, (fo - 0.5) * D, fo, D, eo, 1, 1.0, Kt, 1, dal, full)
    nor2, noz2, do2, ao2, vo2, Qo2 = _arc(Xr, Xz - 2.0 * eo, (fo - 0.5) * D, fo, D, eo, -1, 1.0, Kt, 1, dal,
                                          full)
    nir1, niz1, di1, ai1, vi1, Qi1 = _arc(Xr - cr1, Xz - cz1, (fi - 0.5) * D, fi, D, ei, 1, -1.0, Kt, 0, dal,
                                          full)
    nir2, niz2, di2, ai2, vi2, Qi2 = _arc(Xr - cr2, Xz - cz2, (fi - 0.5) * D, fi, D, ei, -1, -1.0, Kt, 0, dal,
                                          full)
    wi1, wi2 = _weights(vi1, vi2, Qi1, Qi2, di1, di2, D)
    wo1, wo2 = _weights(vo1, vo2, Qo1, Qo2, do1, do2, D)
    ai = wi1 * ai1 + wi2 * ai2
    ao = wo1 * ao1 + wo2 * ao2
    di_e = -np.inf
    if vi1:
        di_e = di1
    if vi2:
        di_e = max(di_e, di2)
    if control == CTRL_INNER:
        oc = False
    elif control == CTRL_HYBRID:
        oc = oc_in or di_e <= 0.0        # balls without inner contact roll on the outer race only
    else:
        oc = oc_in
    # kinematics.kinematics at the weighted angles (raceway control, pure rolling), cos / sin of the
    # angles from the normals where one arc of a ring carries all the weight
    cai, sai = _mean_dir(wi1, wi2, ai1, ai2, -nir1, -niz1, -nir2, -niz2)
    cao, sao = _mean_dir(wo1, wo2, ao1, ao2, nor1, noz1, nor2, noz2)
    bx, by, wm, wR, Fc, Mg, lam_i, Fi, Fo = qk.ball_kinematics(cai, sai, cao, sao, oc, control, omega, geo,
                                                               max(Qi1, 0.0) + max(Qi2, 0.0),
                                                               max(Qo1, 0.0) + max(Qo2, 0.0))
    Fi1, Fi2, Fo1, Fo2 = wi1 * Fi, wi2 * Fi, wo1 * Fo, wo2 * Fo
    Rr = (-Qi1 * nir1 + Fi1 * niz1) + (-Qi2 * nir2 + Fi2 * niz2) \
        + ((-Qo1 * nor1 + Fo1 * noz1) + (-Qo2 * nor2 + Fo2 * noz2)) + Fc
    Rz = (-Qi1 * niz1 - Fi1 * nir1) + (-Qi2 * niz2 - Fi2 * nir2) \
        + ((-Qo1 * noz1 - Fo1 * nor1) + (-Qo2 * noz2 - Fo2 * nor2))
    ki = 1 if wi2 > wi1 else 0             # dominant arc (numpy.argmax: the first on a tie)
    ko = 1 if wo2 > wo1 else 0
    two = (Rr, Rz, Qi2 if ki else Qi1, Qo2 if ko else Qo1, di2 if ki else di1, do2 if ko else do1, ai, ao,
           bx, wm, wR, Fc, Mg, lam_i, 1.0 if oc else 0.0, Fi, Fo)
    four = (Qi1, Qi2, Qo1, Qo2, ai1, ai2, ao1, ao2, di1, di2, do1, do2, Fi1, Fi2, Fo1, Fo2, wi1, wi2, wo1, wo2,
            float(ki), float(ko))
    return two, four, by


@hot(inline="always")
def _ball_rq(xr, xz, j, Cr, Cz, omega, ocj, control, geo, Kt, dal):
    """(Rr, Rz, Qi, Qo) of ball j placed at (xr, xz) [m]."""
    r = _ball4(xr, xz, Cr[j, 0], Cz[j, 0], Cr[j, 1], Cz[j, 1], omega, ocj, control, geo, Kt, dal,
               False)[0]
    return r[0], r[1], r[2], r[3]


@hot
def ball_states4(X, Cr, Cz, omega, oc, control, geo, Kt, dal, S):
    """All balls' states into S (NS4, Z). X (Z, 2) [m]; Cr, Cz (Z, 2) [m]; oc (Z,) bool."""
    gt = _geo_tuple(geo)
    for j in range(X.shape[0]):
        two, four, by = _ball4(X[j, 0], X[j, 1], Cr[j, 0], Cz[j, 0], Cr[j, 1], Cz[j, 1], omega, oc[j], control,
                               gt, Kt, dal, True)
        for k in range(NS):
            S[k, j] = two[k]
        S[S_BETA, j] = math.atan2(by, two[S_BETA])      # attitude angle from (bx, by)
        for k in range(NS4 - NS):
            S[NS + k, j] = four[k]


@hot(inline="always")
def _centres4(u, cpsi, spsi, geo, Cr, Cz):
    """Centres of inner arcs 1, 2 per ball into Cr, Cz (Z, 2) [m] (FourPointQuasiStaticModel docstring)."""
    A = geo[G_A]
    ei = geo[G_EI]
    cr0 = A * math.cos(geo[G_ALPHA0])
    cz0 = A * math.sin(geo[G_ALPHA0])
    for j in range(cpsi.shape[0]):
        tilt = u[3] * spsi[j] - u[4] * cpsi[j]
        dr = u[0] * cpsi[j] + u[1] * spsi[j]
        da = u[2] + geo[G_RI] * tilt
        Cr[j, 0] = cr0 + dr - ei * tilt
        Cr[j, 1] = cr0 + dr + ei * tilt
        Cz[j, 0] = cz0 + da
        Cz[j, 1] = cz0 + da - 2.0 * ei


@hot
def centres4(u, cpsi, spsi, geo):
    """(Cr, Cz), each (Z, 2) [m]: inner arc centres of every ball for ring displacement u."""
    Z = cpsi.shape[0]
    Cr = np.empty((Z, 2))
    Cz = np.empty((Z, 2))
    _centres4(u, cpsi, spsi, geo, Cr, Cz)
    return Cr, Cz


@hot
def _x_start4(Cr, Cz, omega, control, geo, Kt, dal, X):
    """Initial ball positions (FourPointQuasiStaticModel._x_start): per ball the candidate with the
    smaller force residual among (a) the line of centres of the more compressed diagonal pair with equal
    deflections (the mean of both pairs when both are compressed; at speed a ball in the clearance on the
    outer arc, pressed by the pure-rolling centrifugal force) and, at speed, (b) the seat in the outer
    arch: on the outer groove mid-plane, pressed into both outer arcs by the centrifugal force."""
    D = geo[G_D]
    eo = geo[G_EO]
    ro = (geo[G_FO] - 0.5) * D
    ri = (geo[G_FI] - 0.5) * D
    Fc = 0.0
    K0 = 1.0
    if omega > 0.0:
        Fc = qk.rolling_fc(omega, geo)
        K0 = hertz_lookup_alpha_inline(Kt, 0.0, dal, geo[G_ALPHA0], 1)
    lo = ro + (Fc / K0) ** (2.0 / 3.0)
    seat = omega > 0.0 and eo > 0.0
    gt = _geo_tuple(geo)
    xs = 0.0
    if seat:
        sa = eo / ro                                     # sin of the arch contact angle of a seated ball
        ls = ro + (Fc / (2.0 * K0 * math.sqrt(max(1.0 - sa * sa, 1e-6)))) ** (2.0 / 3.0)
        xs = math.sqrt(max(ls * ls - eo * eo, 0.0))
    for j in range(Cr.shape[0]):
        d = np.empty(2)
        xr = np.empty(2)
        xz = np.empty(2)
        for k in range(2):
            oz = 2.0 * eo * k
            vr = Cr[j, k]
            vz = Cz[j, k] - oz
            L = math.hypot(vr, vz)
            d[k] = 0.5 * (L - (ro + ri))
            t = (ro + d[k]) / max(L, 1e-300)
            xr[k] = vr * t
            xz[k] = oz + vz * t
        if d[0] > 0.0 and d[1] > 0.0:
            X[j, 0] = 0.5 * (xr[0] + xr[1])
            X[j, 1] = 0.5 * (xz[0] + xz[1])
        else:
            k = 1 if d[1] > d[0] else 0
            X[j, 0] = xr[k]
            X[j, 1] = xz[k]
            if omega > 0.0 and d[k] < 0.0:
                oz = 2.0 * eo * k
                ta = math.atan2(Cz[j, k] - oz, Cr[j, k])
                X[j, 0] = lo * math.cos(ta)
                X[j, 1] = oz + lo * math.sin(ta)
        if seat:
            r1 = _ball_rq(X[j, 0], X[j, 1], j, Cr, Cz, omega, True, control, gt, Kt, dal)
            r2 = _ball_rq(xs, eo, j, Cr, Cz, omega, True, control, gt, Kt, dal)
            if math.hypot(r2[0], r2[1]) < math.hypot(r1[0], r1[1]):
                X[j, 0] = xs
                X[j, 1] = eo


@hot
def x_start4(u, omega, control, cpsi, spsi, geo, tab_i, tab_o, dal):
    """Initial ball positions X (Z, 2) [m] for ring displacement u (see _x_start4)."""
    Z = cpsi.shape[0]
    Cr = np.empty((Z, 2))
    Cz = np.empty((Z, 2))
    _centres4(u, cpsi, spsi, geo, Cr, Cz)
    X = np.empty((Z, 2))
    _x_start4(Cr, Cz, omega, control, geo, k_table(tab_i, tab_o), dal, X)
    return X


@hot
def _newton_balls4(Cr, Cz, omega, X, oc, control, geo, Kt, dal, tol, maxit, S, Rr, Rz):
    """Newton per ball on the ball equilibrium, X (Z, 2) updated in place: the iteration of
    quasistatic_kernels._solve_balls (2x2 forward-difference Jacobians, step 1e-10 D, step limit 1e-3 D,
    per-ball backtracking on |R|, at most 12 halvings down to 1e-3; converged when max |R| <
    tol (max(1, m dm omega^2 / 2) + max Q)), with the four-point ball. Leaves the final state in S;
    returns converged."""
    Z = X.shape[0]
    D = geo[G_D]
    scale = max(1.0, 0.5 * geo[G_MASS] * geo[G_DM] * omega ** 2)
    h = 1e-10 * D
    lim = 1e-3 * D
    gt = _geo_tuple(geo)
    Qi = np.empty(Z)
    Qo = np.empty(Z)
    known = np.zeros(Z, dtype=np.bool_)      # residual at X kept from the line search
    frozen = np.zeros(Z, dtype=np.bool_)     # at a fixed point of the iteration (X unchanged bit for bit)
    for it in range(maxit):
        rmax = 0.0
        qmax = 0.0
        finite = True
        for j in range(Z):
            if not known[j]:
                Rr[j], Rz[j], Qi[j], Qo[j] = _ball_rq(X[j, 0], X[j, 1], j, Cr, Cz, omega, oc[j], control, gt,
                                                      Kt, dal)
            if not (math.isfinite(Rr[j]) and math.isfinite(Rz[j]) and math.isfinite(Qi[j])
                    and math.isfinite(Qo[j])):
                finite = False
            rmax = max(rmax, abs(Rr[j]), abs(Rz[j]))
            qmax = max(qmax, Qi[j], Qo[j])
        if finite and rmax < tol * (scale + qmax):
            ball_states4(X, Cr, Cz, omega, oc, control, geo, Kt, dal, S)
            return True
        for j in range(Z):
            if frozen[j]:
                continue
            x0 = X[j, 0]
            x1 = X[j, 1]
            R0 = Rr[j]
            R1 = Rz[j]
            p0, p1, _, _ = _ball_rq(x0 + h, x1, j, Cr, Cz, omega, oc[j], control, gt, Kt, dal)
            q0, q1, _, _ = _ball_rq(x0, x1 + h, j, Cr, Cz, omega, oc[j], control, gt, Kt, dal)
            d0, d1 = qk.ball_newton_step((p0 - R0) / h, (q0 - R0) / h, (p1 - R1) / h, (q1 - R1) / h, R0, R1,
                                         D, lim)
            n0 = math.hypot(R0, R1)
            lam = 1.0
            xn0 = x0 + d0
            xn1 = x1 + d1
            known[j] = False
            for _ in range(12):
                t0, t1, t2, t3 = _ball_rq(xn0, xn1, j, Cr, Cz, omega, oc[j], control, gt, Kt, dal)
                if (math.hypot(t0, t1) <= n0 * (1.0 + 1e-9)) or not (lam > 1e-3):
                    known[j] = True
                    Rr[j], Rz[j], Qi[j], Qo[j] = t0, t1, t2, t3
                    break
                lam *= 0.5
                xn0 = x0 + lam * d0
                xn1 = x1 + lam * d1
            X[j, 0] = xn0
            X[j, 1] = xn1
            if xn0 == x0 and xn1 == x1:
                frozen[j] = True
    ball_states4(X, Cr, Cz, omega, oc, control, geo, Kt, dal, S)
    return False


@hot(inline="always")
def _potential(y0, y1, x0r, x0z, j, Cr, Cz, Fc, Ki, Ko, geo):
    """Contact + centrifugal potential [J] of ball j at x0 + y 1e-6 m: sum over the valid arcs of
    (2/5) K delta^2.5 (K at the free contact angle) minus Fc (Xr - x0r)."""
    D = geo[G_D]
    xr = x0r + y0 * 1e-6
    xz = x0z + y1 * 1e-6
    e = -Fc * (xr - x0r)
    for c in range(4):
        if c < 2:                      # outer arcs 1, 2: centres (0, 0), (0, 2 e_o)
            cr, cz, K, f, off, sg = 0.0, 2.0 * geo[G_EO] * c, Ko, geo[G_FO], geo[G_EO], 1.0
        else:                          # inner arcs 1, 2
            cr, cz, K, f, off, sg = Cr[j, c - 2], Cz[j, c - 2], Ki, geo[G_FI], geo[G_EI], -1.0
        vr = xr - cr
        vz = xz - cz
        L = math.hypot(vr, vz)
        sn = sg * vz / L               # sin of the contact angle
        valid = f * D * sn >= off if c % 2 == 0 else f * D * sn < -off
        d = L - (f - 0.5) * D
        if valid and d > 0.0:
            e += 0.4 * K * d ** 2.5
    return e


@hot
def _potential_minimum(x0r, x0z, j, Cr, Cz, Fc, geo, Kt, dal):
    """Ball centre [m] minimising the contact + centrifugal potential of ball j from x0 (in units of
    1e-6 m): the Nelder-Mead simplex method as scipy.optimize.minimize(method='Nelder-Mead') runs it
    (reflection 1, expansion 2, contractions and shrink 1/2; Nelder & Mead 1965; Gao & Han 2012 for the
    standard coefficients) with initial simplex (0, 0), (20, 0), (0, 20), xatol 1e-4, fatol 1e-14,
    2000 iterations."""
    Ki = hertz_lookup_alpha_inline(Kt, 0.0, dal, geo[G_ALPHA0], 0)
    Ko = hertz_lookup_alpha_inline(Kt, 0.0, dal, geo[G_ALPHA0], 1)
    sim = np.zeros((3, 2))
    sim[1, 0] = 20.0
    sim[2, 1] = 20.0
    fsim = np.empty(3)
    for k in range(3):
        fsim[k] = _potential(sim[k, 0], sim[k, 1], x0r, x0z, j, Cr, Cz, Fc, Ki, Ko, geo)
    _sort_simplex(sim, fsim)
    it = 1
    while it < 2000:
        dx = 0.0
        df = 0.0
        for k in range(1, 3):
            dx = max(dx, abs(sim[k, 0] - sim[0, 0]), abs(sim[k, 1] - sim[0, 1]))
            df = max(df, abs(fsim[0] - fsim[k]))
        if dx <= 1e-4 and df <= 1e-14:
            break
        xb0 = (sim[0, 0] + sim[1, 0]) / 2.0
        xb1 = (sim[0, 1] + sim[1, 1]) / 2.0
        xr0 = 2.0 * xb0 - sim[2, 0]
        xr1 = 2.0 * xb1 - sim[2, 1]
        fxr = _potential(xr0, xr1, x0r, x0z, j, Cr, Cz, Fc, Ki, Ko, geo)
        if fxr < fsim[0]:
            xe0 = 3.0 * xb0 - 2.0 * sim[2, 0]
            xe1 = 3.0 * xb1 - 2.0 * sim[2, 1]
            fxe = _potential(xe0, xe1, x0r, x0z, j, Cr, Cz, Fc, Ki, Ko, geo)
            if fxe < fxr:
                sim[2, 0], sim[2, 1], fsim[2] = xe0, xe1, fxe
            else:
                sim[2, 0], sim[2, 1], fsim[2] = xr0, xr1, fxr
        elif fxr < fsim[1]:
            sim[2, 0], sim[2, 1], fsim[2] = xr0, xr1, fxr
        else:
            shrink = False
            if fxr < fsim[2]:                               # outside contraction
                xc0 = 1.5 * xb0 - 0.5 * sim[2, 0]
                xc1 = 1.5 * xb1 - 0.5 * sim[2, 1]
                fxc = _potential(xc0, xc1, x0r, x0z, j, Cr, Cz, Fc, Ki, Ko, geo)
                if fxc <= fxr:
                    sim[2, 0], sim[2, 1], fsim[2] = xc0, xc1, fxc
                else:
                    shrink = True
            else:                                           # inside contraction
                xc0 = 0.5 * xb0 + 0.5 * sim[2, 0]
                xc1 = 0.5 * xb1 + 0.5 * sim[2, 1]
                fxc = _potential(xc0, xc1, x0r, x0z, j, Cr, Cz, Fc, Ki, Ko, geo)
                if fxc < fsim[2]:
                    sim[2, 0], sim[2, 1], fsim[2] = xc0, xc1, fxc
                else:
                    shrink = True
            if shrink:
                for k in range(1, 3):
                    sim[k, 0] = sim[0, 0] + 0.5 * (sim[k, 0] - sim[0, 0])
                    sim[k, 1] = sim[0, 1] + 0.5 * (sim[k, 1] - sim[0, 1])
                    fsim[k] = _potential(sim[k, 0], sim[k, 1], x0r, x0z, j, Cr, Cz, Fc, Ki, Ko, geo)
        it += 1
        _sort_simplex(sim, fsim)
    return x0r + sim[0, 0] * 1e-6, x0z + sim[0, 1] * 1e-6


@hot(inline="always")
def _sort_simplex(sim, fsim):
    """Stable sort of the three simplex vertices by function value (NaN last), as numpy.argsort."""
    for i in range(1, 3):
        k = i
        while k > 0 and (fsim[k] < fsim[k - 1] or (fsim[k - 1] != fsim[k - 1] and fsim[k] == fsim[k])):
            fsim[k], fsim[k - 1] = fsim[k - 1], fsim[k]
            for c in range(2):
                sim[k, c], sim[k - 1, c] = sim[k - 1, c], sim[k, c]
            k -= 1


@hot
def _solve_balls4(Cr, Cz, omega, X, oc, control, geo, Kt, dal, tol, maxit, S, Rr, Rz):
    """Ball equilibrium: the per-ball Newton iteration; balls it
    leaves out of equilibrium (a lightly loaded ball whose equilibrium contact angles are far from its
    start) are restarted from the minimum of their contact + centrifugal potential and the iteration is
    run again. Returns converged."""
    if _newton_balls4(Cr, Cz, omega, X, oc, control, geo, Kt, dal, tol, maxit, S, Rr, Rz):
        return True
    scale = max(1.0, 0.5 * geo[G_MASS] * geo[G_DM] * omega ** 2)
    qmax = 0.0
    for j in range(X.shape[0]):
        qmax = max(qmax, S[S_QI, j], S[S_QO, j])
    for j in range(X.shape[0]):
        if math.hypot(S[S_RR, j], S[S_RZ, j]) >= tol * (scale + qmax):
            X[j, 0], X[j, 1] = _potential_minimum(X[j, 0], X[j, 1], j, Cr, Cz, S[S_FC, j], geo, Kt, dal)
    return _newton_balls4(Cr, Cz, omega, X, oc, control, geo, Kt, dal, tol, maxit, S, Rr, Rz)


@hot
def ring_forces4(cpsi, spsi, S, Ri, rig, ei, F):
    """Force and moment (Fx, Fy, Fz, Mx, My) of the balls on the inner ring into F [N, N m]: the loads
    (incl. regularisation) and gyroscopic friction forces of inner arcs 1, 2 (rows of S), each acting
    through its arc centre at radius Ri and height +-e_i from the ring mid-plane, friction moment arm rig
    about it (quasistatic._ring_forces4)."""
    for k in range(5):
        F[k] = 0.0
    for j in range(cpsi.shape[0]):
        fr = 0.0
        fz = 0.0
        mz = 0.0
        for a in range(2):
            Q = S[S4_QI1 + a, j]
            Fi = S[S4_FI1 + a, j]
            nir = -math.cos(S[S4_AI1 + a, j])
            niz = -math.sin(S[S4_AI1 + a, j])
            fra = Q * nir - Fi * niz
            fr += fra
            fz += Q * niz + Fi * nir
            mz += fra * (ei if a == 0 else -ei)
        m = Ri * fz - mz + rig * (S[S4_FI1, j] + S[S4_FI2, j])
        F[0] += fr * cpsi[j]
        F[1] += fr * spsi[j]
        F[2] += fz
        F[3] += m * spsi[j]
        F[4] += -m * cpsi[j]


@hot
def _residual4_tol(u, omega, X0, oc, control, geo, cpsi, spsi, Kt, dal, X, S, Cr, Cz, Rr, Rz, F, btol):
    """Ring force F of the balls at displacement u, balls re-equilibrated from X0 to the ball tolerance
    btol where the per-ball Newton iteration reaches it, else to quasistatic_kernels.BALL_TOL
    (_solve_balls4; retried from the geometric start with 200 iterations if that fails); X, S: final
    ball positions and states. Returns whether the balls are in equilibrium to BALL_TOL at least."""
    _centres4(u, cpsi, spsi, geo, Cr, Cz)
    qk._copy2(X0, X)
    n_it = max(60, Cr.shape[0] // 1000)          # 60 (typed int64, not a literal: one compilation)
    ok = False
    if btol < qk.BALL_TOL:
        ok = _newton_balls4(Cr, Cz, omega, X, oc, control, geo, Kt, dal, btol, n_it, S, Rr, Rz)
    if not ok:
        ok = _solve_balls4(Cr, Cz, omega, X, oc, control, geo, Kt, dal, qk.BALL_TOL, n_it, S, Rr, Rz)
    if not ok:
        _x_start4(Cr, Cz, omega, control, geo, Kt, dal, X)
        ok = _solve_balls4(Cr, Cz, omega, X, oc, control, geo, Kt, dal, qk.BALL_TOL, n_it + 140, S, Rr,
                           Rz)
    ring_forces4(cpsi, spsi, S, geo[G_RI], geo[G_RIG], geo[G_EI], F)
    return ok


@hot
def _residual4(u, omega, X0, oc, control, geo, cpsi, spsi, Kt, dal, X, S, Cr, Cz, Rr, Rz, F):
    """_residual4_tol at the ball tolerance quasistatic_kernels.BALL_TOL."""
    return _residual4_tol(u, omega, X0, oc, control, geo, cpsi, spsi, Kt, dal, X, S, Cr, Cz, Rr, Rz, F,
                          qk.BALL_TOL)


@hot(inline="always")
def _scratch4(Z):
    """Work arrays of the ball solves: inner arc centres Cr, Cz (Z, 2) and ball residuals Rr, Rz (Z,)."""
    return np.empty((Z, 2)), np.empty((Z, 2)), np.empty(Z), np.empty(Z)


@hot(inline="always")
def _balls4(Z):
    """Ball positions X (Z, 2) and states S (NS4, Z)."""
    return np.empty((Z, 2)), np.empty((NS4, Z))


@hot
def residual(u, omega, X0, oc, control, geo, cpsi, spsi, tab_i, tab_o, dal):
    """(F (5,), X (Z, 2), S (NS4, Z), ok): ring force of the balls at displacement u [N, N m] with the
    balls in equilibrium, started from X0."""
    Z = cpsi.shape[0]
    X, S = _balls4(Z)
    Cr, Cz, Rr, Rz = _scratch4(Z)
    F = np.empty(5)
    ok = _residual4(u, omega, X0, oc, control, geo, cpsi, spsi, k_table(tab_i, tab_o), dal, X, S, Cr, Cz, Rr,
                    Rz, F)
    return F, X, S, ok


@hot
def solve(omega, loads, u, fixed_tilt, control, tol, maxit, want_K, geo, cpsi, spsi, tab_i, tab_o, dal,
          X, S, Kmat, info, fast):
    """5-DOF inner-ring equilibrium of the four-point model: the algorithm and arguments of
    quasistatic_kernels.solve (Newton, forward-difference Jacobian, least-squares step, backtracking line
    search, the fast option, Harris's hybrid criterion in the first 15 iterations, stiffness by central
    differences) with
    the four-point ball equilibrium; S is (NS4, Z). Returns (status, iterations)."""
    Z = cpsi.shape[0]
    us = np.empty(5)
    smax_div = np.empty(5)
    fs = np.empty(5)
    qk.ring_scales(loads, geo, fixed_tilt, u, us, smax_div, fs)
    Kt = k_table(tab_i, tab_o)
    oc = np.ones(Z, dtype=np.bool_)
    new_oc = np.ones(Z, dtype=np.bool_)
    Cr, Cz, Rr, Rz = _scratch4(Z)
    F = np.empty(5)
    r = np.empty(5)
    rn = np.empty(5)
    rp = np.empty(5)
    Xn, Sn = _balls4(Z)
    Xp, Sp = _balls4(Z)
    up = np.empty(5)
    un = np.empty(5)
    J = np.empty((5, 5))
    step = np.empty(5)
    _centres4(u, cpsi, spsi, geo, Cr, Cz)
    X0 = np.empty((Z, 2))
    _x_start4(Cr, Cz, omega, control, geo, Kt, dal, X0)
    ok = _residual4(u, omega, X0, oc, control, geo, cpsi, spsi, Kt, dal, X, S, Cr, Cz, Rr, Rz, F)
    qk._scaled(loads, F, fs, u, us, fixed_tilt, r)
    it = 0
    converged = False
    grow = 1.0
    reuse = False
    for it in range(1, maxit + 1):
        if control == CTRL_HYBRID and it <= 15 and qk.hybrid_update(S, tab_i, tab_o, dal, new_oc, oc):
            reuse = False
            qk._copy2(X, X0)
            ok = _residual4(u, omega, X0, oc, control, geo, cpsi, spsi, Kt, dal, X, S, Cr, Cz, Rr, Rz,
                            F)
            qk._scaled(loads, F, fs, u, us, fixed_tilt, r)
        if ok and qk.ring_converged(r, tol):
            converged = True
            break
        btol = qk.ball_tolerance(r, fast)
        if not reuse:
            for k in range(5):
                qk.shifted(u, k, 1e-2 * us[k], up)
                _residual4_tol(up, omega, X, oc, control, geo, cpsi, spsi, Kt, dal, Xp, Sp, Cr, Cz, Rr, Rz, F,
                               btol)
                qk._scaled(loads, F, fs, up, us, fixed_tilt, rp)
                qk.jacobian_column(J, k, rp, r)
        has_step, clipped = qk.ring_step(J, r, smax_div, step, grow)
        if not has_step:
            break                   # no least-squares step
        lam = 1.0
        n0 = qk._norm5(r)
        accepted = False
        okn = False
        for _ in range(16):
            qk.trial_point(u, lam, step, us, un)
            okn = _residual4_tol(un, omega, X, oc, control, geo, cpsi, spsi, Kt, dal, Xn, Sn, Cr, Cz, Rr,
                                 Rz, F, btol)
            qk._scaled(loads, F, fs, un, us, fixed_tilt, rn)
            if okn and qk.sufficient_decrease(rn, n0, lam):
                accepted = True
                break
            if reuse:
                break               # no decrease along the kept Jacobian's step: a new Jacobian
            lam *= 0.5
        if not accepted:
            if reuse or grow > 1.0:
                # a kept Jacobian's step, or one from grown limits, that does not decrease |r|: again
                # with a new Jacobian and the initial limits
                reuse = False
                grow = 1.0
                continue
            info[0] = n0
            return LINE_SEARCH_FAILED, it
        reuse = qk.keep_jacobian(rn, n0, lam, fast)
        if reuse:
            qk.broyden_update(J, step, lam, rn, r)
        qk.accept(un, u, rn, r, Xn, X, Sn, S)
        ok = okn
        if not (control == CTRL_HYBRID and it < 15):
            grow = qk.step_growth(grow, clipped, lam, fast)     # fixed limits while the raceway control may change
    if not converged:
        info[1] = qk.max_abs_or_nan(r)
        return NOT_CONVERGED, it
    if want_K:
        qk._copy2(stiffness(u, omega, X, qk.outer_controls(S), control, geo, cpsi, spsi, tab_i, tab_o, dal),
                  Kmat)
    return OK, it


@hot
def stiffness(u, omega, X, oc, control, geo, cpsi, spsi, tab_i, tab_o, dal):
    """5x5 bearing stiffness K_kl = d(load_k)/d(u_l) [N/m, N/rad, N m/m, N m/rad] of the four-point model
    (as quasistatic_kernels.stiffness: central differences of the ring force, steps 1e-8 m, 1e-7 rad,
    every ball re-equilibrated from X)."""
    Z = cpsi.shape[0]
    h = qk.stiffness_steps()
    Kt = k_table(tab_i, tab_o)
    Kmat = np.empty((5, 5))
    up = np.empty(5)
    Fp = np.empty(5)
    Fm = np.empty(5)
    Xp, Sp = _balls4(Z)
    Cr, Cz, Rr, Rz = _scratch4(Z)
    for k in range(5):
        qk.shifted(u, k, h[k], up)
        _residual4(up, omega, X, oc, control, geo, cpsi, spsi, Kt, dal, Xp, Sp, Cr, Cz, Rr, Rz, Fp)
        qk.shifted(u, k, -h[k], up)
        _residual4(up, omega, X, oc, control, geo, cpsi, spsi, Kt, dal, Xp, Sp, Cr, Cz, Rr, Rz, Fm)
        qk.stiffness_column(Kmat, k, Fp, Fm, h[k])
    return Kmat
