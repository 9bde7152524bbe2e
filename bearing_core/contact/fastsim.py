"""Dry / solid-lubricated rolling-contact traction by Kalker's simplified theory (FASTSIM).

SI units (m, s, rad, N, Pa, W). Numba kernels; the hot path (fastsim_traction_fast) allocates one work
array of 10 x 16 doubles per grid evaluation (the strip data, _strip_arrays).

Contents
--------
* kalker_coefficients(g, nu) -> (C11, C22, C23): creep coefficients of Kalker's linear theory.
* fastsim_traction(...): traction on the ball for one Hertz contact from the slip velocities of
  bearing_core.contact.contact_kernels.contact_kinematics (forces, spin moment, dissipated power).
* fastsim_map(...): the same, plus the adhesion / slip map and local tractions (for plots).
* fastsim_kalker(...): the solver in Kalker's own frame and creepages.
* fastsim_traction_fast(...): fastsim_traction with shortcuts (closed-form linear solution at small
  creepage, full-slip integral when every cell slips, the grid march vectorised across the strips);
  creepage_level, slip_level: the dimensionless levels that select them (docs/kalker.md).

Frames and signs (same as contact_kernels)
------------------------------------------
The contact ellipse of contact_kernels has semi-major axis a along m (across the groove) and
semi-minor axis b along t (rolling direction); n is the normal from the ball towards the race and
(t, m, n) is right handed (t x m = n). In a ball bearing the ROLLING direction is the MINOR axis:
Kalker's rolling-direction semi-axis is a' = b, the lateral one b' = a, and the ratio entering the
creep coefficients is a'/b' = b/a (~0.1-0.2 for ball-race contacts).
Inputs, as returned by contact_kinematics: vs_t, vs_m = sliding velocity of the ball material
minus the race material at the contact centre [m/s]; w_spin = (w_ball - w_race) . n [rad/s];
u_roll = rolling (entrainment) speed along t [m/s], signed: material passes through the contact in
the direction sign(u_roll) t, i.e. enters at the edge t = -sign(u_roll) b.
Creepages: xi = vs_t / |u_roll|, eta = vs_m / |u_roll|, phi = w_spin / |u_roll| [1/m].
Outputs: F_t, F_m = tangential force ON THE BALL [N] (the race gets -F), M_n = moment of the
tractions on the ball about the contact normal through the contact centre [N m] (positive about +n),
P_loss = -(F_t vs_t + F_m vs_m + M_n w_spin) [W], the power of the contact tractions on the rigid
relative motion, which in steady rolling equals the frictional dissipation (the elastic shear
energy is zero where a particle enters and where it leaves the patch).
Small-creepage (linear) limit (Kalker's linear theory, c = sqrt(a b)):
    F_t = -G c^2 C11 xi,   F_m = -G c^2 C22 eta + sign(u_roll) G c^3 C23 phi.
(The spin term flips with the rolling direction: in Kalker's frame the body rolls towards +x, i.e.
material moves towards -x; here x_K = -sign(u_roll) t, y_K = -sign(u_roll) m, z_K = n.)

Sources
-------
[K90]  J. J. Kalker, Three-dimensional elastic bodies in rolling contact, Kluwer 1990, Table E.3
       (creep coefficients C11, C22, C23 for g = a/b and b/a = 0.1 ... 1, nu = 0, 0.25, 0.5) and the
       asymptotic formulas for g -> 0. The numbers below were copied from the open-source CONTACT
       code of E.A.H. Vollebregt / Vtech CMCC (Apache-2.0), module m_hertz.f90, subroutine linrol
       ("table E.3 of Kalker", same data also in its usetab_table.f90). Note: an older copy
       (usetab_table.f90) has C23(a/b = 0.8, nu = 0.25) = 1.15; m_hertz.f90 has 1.25, which fits the
       row/column trend (1.14, 1.25, 1.36) -- 1.25 is used.
[K82]  J. J. Kalker, "A fast algorithm for the simplified theory of rolling contact", Vehicle System
       Dynamics 11 (1982) 1-13: flexibilities L1 = 8a'/(3 G C11), L2 = 8a'/(3 G C22),
       L3 = pi a'^2 / (4 G c C23) (the same as CONTACT's simpflex, pi a' sqrt(a'/b') / (4 G C23)),
       strip-wise integration from the leading edge, traction bound mu p with the PARABOLIC
       pressure p = 2Q/(pi a' b') (1 - x^2/a'^2 - y^2/b'^2) (Kalker's choice; the elliptic Hertz
       pressure is available as an option).
seed 000 (Lubricants 2025 13(5) 218) Sec. 2.2 (Eqs. 7-9): p = L^-1 u; p_{n+1} = p_n + s c dt / l
       (marching from the leading edge); T = sum p dA.
Combined elastic constants of two bodies (Kalker [K90], quasi-identical bodies; section number
       not re-checked): 2/G = 1/G1 + 1/G2, nu/G = (nu1/G1 + nu2/G2) / 2.
Known limitation (not corrected here): with three flexibilities and L1 != L2 (elliptic patch) the
saturated force at large OBLIQUE creepage is tilted away from the slip direction (P slightly below
mu Q |v|, e.g. 1.3 % for b/a = 0.15); u_roll == 0 uses exact full sliding instead. CONTACT blends
the three flexibilities into one at large creepage (m_hertz.f90 simpflex) -- not implemented.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..numerics.jit import hot

PRESSURE_PARABOLIC = 0   # Kalker's FASTSIM traction bound [K82]
PRESSURE_HERTZ = 1       # elliptic Hertz pressure 3Q/(2 pi a b) sqrt(1 - x^2/a^2 - y^2/b^2)

# --------------------------------------------------------------------------------------------------
# 1. creep coefficients, Kalker [K90] Table E.3 (via CONTACT m_hertz.f90 linrol)
# rows: g = 0.1, 0.2, ..., 1.0 ; columns: nu = 0, 0.25, 0.5
# case A: a'/b' = g <= 1 (rolling-direction semi-axis the smaller one: ball bearings)
_C11_A = [[2.51, 3.31, 4.85], [2.59, 3.37, 4.81], [2.68, 3.44, 4.80], [2.78, 3.53, 4.82],
          [2.88, 3.62, 4.83], [2.98, 3.72, 4.91], [3.09, 3.81, 4.97], [3.19, 3.91, 5.05],
          [3.29, 4.01, 5.12], [3.40, 4.12, 5.20]]
_C22_A = [[2.51, 2.52, 2.53], [2.59, 2.63, 2.66], [2.68, 2.75, 2.81], [2.78, 2.88, 2.98],
          [2.88, 3.01, 3.14], [2.98, 3.14, 3.31], [3.09, 3.28, 3.48], [3.19, 3.41, 3.65],
          [3.29, 3.54, 3.82], [3.40, 3.67, 3.98]]
_C23_A = [[0.334, 0.473, 0.731], [0.483, 0.603, 0.809], [0.607, 0.715, 0.889],
          [0.720, 0.823, 0.977], [0.827, 0.929, 1.07], [0.930, 1.03, 1.18], [1.03, 1.14, 1.29],
          [1.13, 1.25, 1.40], [1.23, 1.36, 1.51], [1.33, 1.47, 1.63]]
# case B: b'/a' = g <= 1 (rolling-direction semi-axis the larger one); rows g = 0.1 ... 1.0
_C11_B = [[10.7, 11.7, 12.9], [6.96, 7.78, 8.82], [5.57, 6.34, 7.34], [4.84, 5.57, 6.57],
          [4.37, 5.10, 6.11], [4.06, 4.78, 5.80], [3.82, 4.54, 5.58], [3.65, 4.36, 5.42],
          [3.51, 4.22, 5.30], [3.40, 4.12, 5.20]]
_C22_B = [[10.7, 12.8, 16.0], [6.96, 8.14, 9.79], [5.57, 6.40, 7.51], [4.84, 5.48, 6.31],
          [4.37, 4.90, 5.56], [4.06, 4.50, 5.04], [3.82, 4.21, 4.67], [3.65, 3.99, 4.39],
          [3.51, 3.81, 4.16], [3.40, 3.67, 3.98]]
_C23_B = [[12.2, 14.6, 18.0], [5.72, 6.63, 7.89], [3.79, 4.32, 5.01], [2.88, 3.24, 3.70],
          [2.35, 2.62, 2.96], [2.01, 2.23, 2.50], [1.76, 1.95, 2.18], [1.58, 1.75, 1.94],
          [1.44, 1.59, 1.77], [1.33, 1.47, 1.63]]


def _build_table():
    """(3 coefficients, 19 nodes, 3 nu) on the uniform coordinate z = 0.1 ... 1.9, where
    z = r for r = a'/b' <= 1 and z = 2 - 1/r for r > 1 (dz/dr = 1 on both sides of r = 1)."""
    T = np.zeros((3, 19, 3))
    for k, (A, B) in enumerate(((_C11_A, _C11_B), (_C22_A, _C22_B), (_C23_A, _C23_B))):
        A = np.asarray(A)
        B = np.asarray(B)
        T[k, :10] = A                    # z = 0.1 ... 1.0  (r = 0.1 ... 1)
        T[k, 10:] = B[8::-1]             # z = 1.1 ... 1.9  (b'/a' = 0.9 ... 0.1)
    return T


CREEP_TABLE = _build_table()
NU_NODES = np.array([0.0, 0.25, 0.5])


@hot
def _asymptotes(r, nu):
    """Kalker's asymptotic creep coefficients [K90] (as coded in CONTACT linrol): r = a'/b' -> 0
    (case A) or r -> infinity (case B)."""
    if r <= 1.0:
        g = r
        cx = math.pi ** 2 / 4.0 / (1.0 - nu)
        cy = math.pi ** 2 / 4.0
        cz = math.pi * math.sqrt(g) / 3.0 / (1.0 - nu) * (1.0 + nu * (math.log(16.0 / g) - 5.0))
    else:
        g = 1.0 / r
        al = math.log(16.0 / (g * g))
        cx = 2.0 * math.pi / (al - 2.0 * nu) / g * (1.0 + (3.0 - math.log(4.0)) / (al - 2.0 * nu))
        d = (1.0 - nu) * al + 2.0 * nu
        cy = 2.0 * math.pi / g * (1.0 + (1.0 - nu) * (3.0 - math.log(4.0)) / d) / d
        cz = 2.0 * math.pi / 3.0 / g ** 1.5 / ((1.0 - nu) * al - 2.0 + 4.0 * nu)
    return cx, cy, cz


@hot
def _table_at_nu_node(z, inu, k):
    """Catmull-Rom (C1, exact for quadratics) interpolation of coefficient k at nu node inu on the
    uniform z grid 0.1 ... 1.9 (z clipped to that range)."""
    n = 19
    s = (z - 0.1) / 0.1
    if s < 0.0:
        s = 0.0
    if s > n - 1:
        s = n - 1.0
    i = int(s)
    if i > n - 2:
        i = n - 2
    t = s - i
    p1 = CREEP_TABLE[k, i, inu]
    p2 = CREEP_TABLE[k, i + 1, inu]
    p0 = CREEP_TABLE[k, i - 1, inu] if i > 0 else 2.0 * p1 - p2
    p3 = CREEP_TABLE[k, i + 2, inu] if i + 2 < n else 2.0 * p2 - p1
    m1 = 0.5 * (p2 - p0)
    m2 = 0.5 * (p3 - p1)
    t2 = t * t
    t3 = t2 * t
    return ((2.0 * t3 - 3.0 * t2 + 1.0) * p1 + (t3 - 2.0 * t2 + t) * m1
            + (-2.0 * t3 + 3.0 * t2) * p2 + (t3 - t2) * m2)


@hot
def _table_at_nu_node_r(r, inu, k):
    """Coefficient k at nu node inu, table range 0.1 <= r <= 10 (r clipped to it)."""
    if r < 0.1:
        r = 0.1
    if r > 10.0:
        r = 10.0
    z = r if r <= 1.0 else 2.0 - 1.0 / r
    return _table_at_nu_node(z, inu, k)


@njit(cache=True)
def inverse_lagrange_nu(nu, nus, cs):
    """Interpolate a creep coefficient in Poisson's ratio as CONTACT (m_hertz.f90 linrol) does with
    Kalker's table: the Lagrange polynomial through the nodes (nus[i], 1/cs[i]) evaluated at nu, inverted.
    1/C is smooth in nu (compliance-like); C itself is not (C11 ~ 1/(1 - nu) in the slender limit).
    nus, cs: 1-D arrays of equal length (2 nodes: linear in 1/C; 3 nodes: quadratic)."""
    acc = 0.0
    n = nus.shape[0]
    for i in range(n):
        w = 1.0
        for j in range(n):
            if j != i:
                w *= (nu - nus[j]) / (nus[i] - nus[j])
        acc += w / cs[i]
    return 1.0 / acc


@hot
def _table_coefficient(r, nu, k):
    """Coefficient k from Kalker's table at r in [0.1, 10] (clipped): Catmull-Rom in z at each of the
    three nu nodes, then quadratic in 1/C over nu (CONTACT linrol)."""
    c0 = _table_at_nu_node_r(r, 0, k)
    c1 = _table_at_nu_node_r(r, 1, k)
    c2 = _table_at_nu_node_r(r, 2, k)
    # Lagrange weights on the nodes 0, 0.25, 0.5 (no allocation: called per contact evaluation)
    inv = ((nu - 0.25) * (nu - 0.5) * 8.0 / c0 - nu * (nu - 0.5) * 16.0 / c1
           + nu * (nu - 0.25) * 8.0 / c2)
    return 1.0 / inv


@hot(inline="always")
def _table_coefficients(r, nu):
    """(C11, C22, C23) from Kalker's table at r in [0.1, 10] (clipped): the arithmetic of
    _table_coefficient for the three coefficients at once (one row index, one set of Catmull-Rom and
    Lagrange weights; called per contact evaluation in the dynamics)."""
    rc = min(max(r, 0.1), 10.0)
    z = rc if rc <= 1.0 else 2.0 - 1.0 / rc
    n = 19
    sz = min(max((z - 0.1) / 0.1, 0.0), n - 1.0)
    i = min(int(sz), n - 2)
    t = sz - i
    t2 = t * t
    t3 = t2 * t
    h1 = 2.0 * t3 - 3.0 * t2 + 1.0       # Hermite basis on p1, m1, p2, m2
    h2 = t3 - 2.0 * t2 + t
    h3 = -2.0 * t3 + 3.0 * t2
    h4 = t3 - t2
    w0 = (nu - 0.25) * (nu - 0.5) * 8.0  # Lagrange weights on 1/C at nu = 0, 0.25, 0.5
    w1 = -nu * (nu - 0.5) * 16.0
    w2 = nu * (nu - 0.25) * 8.0
    out0 = 0.0
    out1 = 0.0
    out2 = 0.0
    for k in range(3):
        inv = 0.0
        for inu in range(3):
            p1 = CREEP_TABLE[k, i, inu]
            p2 = CREEP_TABLE[k, i + 1, inu]
            p0 = CREEP_TABLE[k, i - 1, inu] if i > 0 else 2.0 * p1 - p2
            p3 = CREEP_TABLE[k, i + 2, inu] if i + 2 < n else 2.0 * p2 - p1
            c = h1 * p1 + h2 * 0.5 * (p2 - p0) + h3 * p2 + h4 * 0.5 * (p3 - p1)
            w = w0 if inu == 0 else (w1 if inu == 1 else w2)
            inv += w / c
        if k == 0:
            out0 = 1.0 / inv
        elif k == 1:
            out1 = 1.0 / inv
        else:
            out2 = 1.0 / inv
    return out0, out1, out2


@hot
def kalker_coefficients(r, nu):
    """Kalker's creep coefficients (C11, C22, C23) [-] of the linear theory [K90 Table E.3].

    r = a'/b' [-]: semi-axis in the ROLLING direction over the lateral semi-axis (ball bearing,
    contact_kernels convention: r = b/a < 1); nu [-]: combined Poisson ratio, 0 <= nu <= 0.5
    (clipped).
    * 0.1 <= r <= 10 (the table): nodes reproduced exactly; Catmull-Rom (C1) in z = r (r <= 1),
      z = 2 - 1/r (r > 1) between the rows; over nu the Lagrange parabola through 1/C at
      nu = 0, 0.25, 0.5, as CONTACT's linrol (C is not linear in nu: linear interpolation puts C11
      0.84 % high at r = 1, nu = 0.3).
    * r < 0.1 or r > 10 (slender ellipses): Kalker's asymptotic expressions (_asymptotes, as in CONTACT
      linrol) times a correction 1 + k g (g = min(r, 1/r)) with k fixed by the table at g = 0.1, so the
      coefficient is continuous there and tends to Kalker's asymptote as g -> 0. (CONTACT switches to
      the bare asymptote at g = 0.101, a jump of up to 5 % in C23 that a time integrator would feel.)
    Linear theory: Fx = -G c^2 C11 xi, Fy = -G c^2 C22 eta - G c^3 C23 phi, c = sqrt(a' b')."""
    if nu < 0.0:
        nu = 0.0
    if nu > 0.5:
        nu = 0.5
    t0, t1, t2 = _table_coefficients(r, nu)
    if 0.1 <= r <= 10.0:
        return t0, t1, t2
    g = r if r < 0.1 else 1.0 / r
    r_end = 0.1 if r < 0.1 else 10.0
    ax, ay, az = _asymptotes(r, nu)
    ex, ey, ez = _asymptotes(r_end, nu)
    s = g / 0.1
    return (ax * (1.0 + (t0 / ex - 1.0) * s), ay * (1.0 + (t1 / ey - 1.0) * s),
            az * (1.0 + (t2 / ez - 1.0) * s))


@hot
def max_creep_damping(a, b, Q, u, G, nu):
    """Largest linear-theory longitudinal creep damping G c^2 C11 / |u_roll| [N s/m] over the contacts with
    Q > 0 and u_roll != 0: Kalker's F_t = -G c^2 C11 xi with xi = vs_t / |u_roll| [K90], c^2 = a b.
    Arrays a, b [m] (semi-axes, contact_kernels frame: b along the rolling direction), Q [N], u [m/s];
    G [Pa], nu [-] combined (combined_elastic). 0 if no contact qualifies."""
    k = 0.0
    for i in range(a.shape[0]):
        if Q[i] > 0.0 and a[i] > 0.0 and b[i] > 0.0 and u[i] != 0.0:
            k = max(k, G * a[i] * b[i] * kalker_coefficients(b[i] / a[i], nu)[0] / abs(u[i]))
    return k


def combined_elastic(E1, nu1, E2, nu2):
    """Combined shear modulus G [Pa] and Poisson ratio nu [-] of two bodies for the creep theory:
    G_i = E_i / (2 (1 + nu_i)), 2/G = 1/G1 + 1/G2, nu = G (nu1/G1 + nu2/G2) / 2 [K90]."""
    G1 = E1 / (2.0 * (1.0 + nu1))
    G2 = E2 / (2.0 * (1.0 + nu2))
    G = 2.0 / (1.0 / G1 + 1.0 / G2)
    nu = 0.5 * G * (nu1 / G1 + nu2 / G2)
    return G, nu


# --------------------------------------------------------------------------------------------------
# 2. FASTSIM [K82]
@hot
def _peak_pressure(Q, ap, bp, pressure):
    """Peak of the traction-bound pressure [Pa]: Hertz 3Q/(2 pi a b) or FASTSIM's parabolic 2Q/(pi a b)."""
    if pressure == PRESSURE_HERTZ:
        return 1.5 * Q / (math.pi * ap * bp)
    return 2.0 * Q / (math.pi * ap * bp)


@njit(cache=True)
def _fastsim_core(ap, bp, Q, mu, G, C11, C22, C23, xi, eta, phi, n_x, n_y, pressure,
                  store, sX, sY, sTx, sTy, sSlip):
    """FASTSIM in Kalker's frame: x rolling direction (material moves towards -x, enters at the
    leading edge x = +a'(y)), y lateral, z normal; ap = a' (x semi-axis), bp = b'. Creepages xi, eta
    [-], phi [1/m]: rigid slip per unit rolling distance w = (xi - phi y, eta + phi x).
    Traction on the body whose slip is w: stick increment dp = -w / L ds over the travelled
    distance ds, bounded by mu p_z. Returns (Fx, Fy, Mz) [N, N, N m]. If store, the cell centres,
    tractions and slip flags are written to the (n_y, n_x) arrays sX, sY, sTx, sTy, sSlip."""
    Fx = 0.0
    Fy = 0.0
    Mz = 0.0
    if not (Q > 0.0 and ap > 0.0 and bp > 0.0):
        if store:
            for j in range(n_y):
                for i in range(n_x):
                    sX[j, i] = 0.0
                    sY[j, i] = 0.0
                    sTx[j, i] = 0.0
                    sTy[j, i] = 0.0
                    sSlip[j, i] = False
        return Fx, Fy, Mz
    c = math.sqrt(ap * bp)
    iL1 = 3.0 * G * C11 / (8.0 * ap)
    iL2 = 3.0 * G * C22 / (8.0 * ap)
    iL3 = 4.0 * G * c * C23 / (math.pi * ap * ap)
    p0 = _peak_pressure(Q, ap, bp, pressure)
    mup0 = mu * p0
    dy = 2.0 * bp / n_y
    ia2 = 1.0 / (ap * ap)
    for j in range(n_y):
        y = -bp + (j + 0.5) * dy
        ey = 1.0 - (y / bp) ** 2
        aj = ap * math.sqrt(ey)
        dx = 2.0 * aj / n_x
        dA = dx * dy
        gx = xi * iL1 - phi * y * iL3          # constant along the strip
        px = 0.0
        py = 0.0
        for i in range(n_x):
            xc = aj - (i + 0.5) * dx
            if i == 0:
                ds = 0.5 * dx
                xm = aj - 0.25 * dx
            else:
                ds = dx
                xm = xc + 0.5 * dx
            px -= gx * ds
            py -= (eta * iL2 + phi * xm * iL3) * ds
            e = ey - xc * xc * ia2
            if e < 0.0:
                e = 0.0
            if pressure == PRESSURE_HERTZ:
                gb = mup0 * math.sqrt(e)
            else:
                gb = mup0 * e
            pm = math.sqrt(px * px + py * py)
            slip = pm > gb
            if slip:
                if pm > 0.0:
                    f = gb / pm
                    px *= f
                    py *= f
            fx = px * dA
            fy = py * dA
            Fx += fx
            Fy += fy
            Mz += xc * fy - y * fx
            if store:
                sX[j, i] = xc
                sY[j, i] = y
                sTx[j, i] = px
                sTy[j, i] = py
                sSlip[j, i] = slip
    return Fx, Fy, Mz


@njit(cache=True)
def _full_slip_core(ap, bp, Q, mu, vx, vy, w, n_x, n_y, pressure, store, sX, sY, sTx, sTy, sSlip):
    """Rolling speed zero: every cell slides, traction -mu p v/|v| with the rigid sliding velocity
    v = (vx - w y, vy + w x) (Kalker frame). Same grid and outputs as _fastsim_core."""
    Fx = 0.0
    Fy = 0.0
    Mz = 0.0
    p0 = _peak_pressure(Q, ap, bp, pressure)
    dy = 2.0 * bp / n_y
    ia2 = 1.0 / (ap * ap)
    for j in range(n_y):
        y = -bp + (j + 0.5) * dy
        ey = 1.0 - (y / bp) ** 2
        aj = ap * math.sqrt(ey)
        dx = 2.0 * aj / n_x
        for i in range(n_x):
            xc = aj - (i + 0.5) * dx
            e = ey - xc * xc * ia2
            if e < 0.0:
                e = 0.0
            gb = mu * p0 * (math.sqrt(e) if pressure == PRESSURE_HERTZ else e)
            ux = vx - w * y
            uy = vy + w * xc
            v = math.sqrt(ux * ux + uy * uy)
            px = 0.0
            py = 0.0
            if v > 0.0:
                px = -gb * ux / v
                py = -gb * uy / v
            Fx += px * dx * dy
            Fy += py * dx * dy
            Mz += (xc * py - y * px) * dx * dy
            if store:
                sX[j, i] = xc
                sY[j, i] = y
                sTx[j, i] = px
                sTy[j, i] = py
                sSlip[j, i] = v > 0.0
    return Fx, Fy, Mz


@njit(cache=True)
def fastsim_kalker(ap, bp, Q, mu, G, nu, xi, eta, phi, n_x, n_y, pressure):
    """FASTSIM [K82] in Kalker's frame and creepages (see _fastsim_core): ap, bp [m] semi-axes in
    the rolling / lateral direction, Q [N], mu [-], G [Pa], nu [-] (combined, combined_elastic),
    xi, eta [-], phi [1/m]; n_x cells per strip, n_y strips; pressure PRESSURE_PARABOLIC (Kalker)
    or PRESSURE_HERTZ. Returns (Fx, Fy, Mz) on the body, Kalker's sign convention
    (linear limit Fx = -G c^2 C11 xi, Fy = -G c^2 (C22 eta + c C23 phi))."""
    C11, C22, C23 = kalker_coefficients(ap / bp, nu)
    e2 = np.empty((0, 0))
    b2 = np.empty((0, 0), dtype=np.bool_)
    return _fastsim_core(ap, bp, Q, mu, G, C11, C22, C23, xi, eta, phi, n_x, n_y, pressure,
                         False, e2, e2, e2, e2, b2)


@njit(cache=True)
def _contact_frame(a, b, Q, mu, G, nu, vs_t, vs_m, w_spin, u_roll, n_x, n_y, pressure,
                   store, sX, sY, sTx, sTy, sSlip):
    Ft = 0.0
    Fm = 0.0
    Mn = 0.0
    if not (Q > 0.0 and a > 0.0 and b > 0.0):
        return Ft, Fm, Mn, 0.0
    ap = b                   # rolling direction t: minor axis
    bp = a                   # lateral direction m: major axis
    if u_roll != 0.0:
        sg = -1.0 if u_roll > 0.0 else 1.0        # x_K = sg t, y_K = sg m
        C11, C22, C23 = kalker_coefficients(ap / bp, nu)
        iu = 1.0 / abs(u_roll)
        Fx, Fy, Mz = _fastsim_core(ap, bp, Q, mu, G, C11, C22, C23, sg * vs_t * iu,
                                   sg * vs_m * iu, w_spin * iu, n_x, n_y, pressure,
                                   store, sX, sY, sTx, sTy, sSlip)
    else:
        sg = -1.0
        Fx, Fy, Mz = _full_slip_core(ap, bp, Q, mu, sg * vs_t, sg * vs_m, w_spin, n_x, n_y,
                                     pressure, store, sX, sY, sTx, sTy, sSlip)
    Ft = sg * Fx
    Fm = sg * Fy
    Mn = Mz
    if store:                # map back to (t, m) coordinates and components
        for j in range(n_y):
            for i in range(n_x):
                sX[j, i] *= sg
                sY[j, i] *= sg
                sTx[j, i] *= sg
                sTy[j, i] *= sg
    P = -(Ft * vs_t + Fm * vs_m + Mn * w_spin)
    return Ft, Fm, Mn, P


@njit(cache=True)
def fastsim_traction(a, b, Q, mu, G, nu, vs_t, vs_m, w_spin, u_roll, n_x=20, n_y=20,
                     pressure=PRESSURE_PARABOLIC):
    """Traction on the ball at one ball-race contact by FASTSIM [K82] (seed 000 Sec. 2.2).

    a, b [m]: semi-axes along m (major, lateral) and t (minor, rolling direction), as in
    contact_kernels; Q [N] normal force; mu [-] friction coefficient (traction bound mu p);
    G [Pa], nu [-]: combined shear modulus and Poisson ratio (combined_elastic);
    vs_t, vs_m [m/s], w_spin [rad/s], u_roll [m/s]: from contact_kernels.contact_kinematics;
    n_x cells along each strip (rolling direction), n_y strips across; pressure:
    PRESSURE_PARABOLIC (Kalker's FASTSIM, default) or PRESSURE_HERTZ.
    Returns (F_t, F_m [N], M_n [N m], P_loss [W]) -- see the module docstring for the frame and
    signs. u_roll == 0: full sliding, -mu p v/|v| everywhere (the limit of infinite creepage).
    Cost ~ n_x n_y: about 4.5 us per call for the default 20 x 20 grid when called from numba code
    (from Python, omitting the defaulted arguments adds ~25 us of dispatch overhead: pass all)."""
    e2 = np.empty((0, 0))
    b2 = np.empty((0, 0), dtype=np.bool_)
    return _contact_frame(a, b, Q, mu, G, nu, vs_t, vs_m, w_spin, u_roll, n_x, n_y, pressure,
                          False, e2, e2, e2, e2, b2)


@njit(cache=True)
def fastsim_map_into(a, b, Q, mu, G, nu, vs_t, vs_m, w_spin, u_roll, n_x, n_y, pressure,
                     T, M, Tt, Tm, slip):
    """fastsim_traction that also fills preallocated (n_y, n_x) arrays: cell centres T (along t),
    M (along m) [m], local traction on the ball Tt, Tm [Pa], slip (True = sliding, False =
    adhesion). Rows j = lateral strips, columns i = cells from the leading edge. Returns the same
    tuple as fastsim_traction."""
    return _contact_frame(a, b, Q, mu, G, nu, vs_t, vs_m, w_spin, u_roll, n_x, n_y, pressure,
                          True, T, M, Tt, Tm, slip)


def fastsim_map(a, b, Q, mu, G, nu, vs_t, vs_m, w_spin, u_roll, n_x=40, n_y=40,
                pressure=PRESSURE_PARABOLIC):
    """Adhesion / slip map for plotting (allocates). Returns a dict with T, M (cell centres along t
    and m [m]), Tt, Tm (traction on the ball [Pa]), slip (bool), all (n_y, n_x), and F_t, F_m,
    M_n, P_loss as in fastsim_traction."""
    T = np.zeros((n_y, n_x))
    M = np.zeros((n_y, n_x))
    Tt = np.zeros((n_y, n_x))
    Tm = np.zeros((n_y, n_x))
    slip = np.zeros((n_y, n_x), dtype=np.bool_)
    Ft, Fm, Mn, P = fastsim_map_into(float(a), float(b), float(Q), float(mu), float(G), float(nu),
                                     float(vs_t), float(vs_m), float(w_spin), float(u_roll),
                                     int(n_x), int(n_y), int(pressure), T, M, Tt, Tm, slip)
    return dict(T=T, M=M, Tt=Tt, Tm=Tm, slip=slip, F_t=Ft, F_m=Fm, M_n=Mn, P_loss=P)


# --------------------------------------------------------------------------------------------------
# 3. Shortcuts around the grid (fastsim_traction_fast). Same frame, signs and outputs as
#    fastsim_traction; see docs/kalker.md for the measured accuracy and cost.
SHORTCUT_LIN = 0.03      # default creepage level f below which the closed-form linear solution is used
SHORTCUT_SLIP = 3.0      # default creepage level f above which the full-slip integral is used


@hot
def creepage_level(ap, bp, Q, mu, G, C11, C22, C23, xi, eta, phi):
    """Dimensionless creepage f = sqrt(xi*^2 + eta*^2 + phi*^2) (Kalker frame), each creepage scaled by the
    value at which its linear force alone reaches 3 mu Q (the Vermeulen-Johnson / simplified-theory
    saturation of pure creepage, parabolic bound: xi* = G c^2 C11 |xi| / (3 mu Q) = 1):
    xi* = G c^2 C11 xi / (3 mu Q), eta* = G c^2 C22 eta / (3 mu Q), and for spin the longitudinal
    creepage that gives the same stick traction rate at the strip ends y = +-b' (phi b' L1 / L3):
    phi* = G c^3 C23 phi max(1, 32 b' / (3 pi a')) / (3 mu Q) -- 22x the plain G c^3 C23 phi / (3 mu Q)
    for a ball-race ellipse b/a = 0.15, where spin saturates the strip ends long before the centre.
    (Like CONTACT's f_crp in m_hertz.f90 simpflex, but each term dimensionless.)"""
    s = G * ap * bp / (3.0 * mu * Q)
    c = math.sqrt(ap * bp)
    x = s * C11 * xi
    y = s * C22 * eta
    z = s * c * C23 * phi * max(1.0, 32.0 * bp / (3.0 * math.pi * ap))
    return math.sqrt(x * x + y * y + z * z)


@hot
def slip_level(ap, bp, Q, mu, G, C11, C22, C23, xi, eta, phi):
    """Lower bound over the patch of the FASTSIM increment |g| = |(xi/L1 - phi y/L3, eta/L2 + phi x/L3)|,
    scaled by the rate 2 mu p0 / a' (parabolic p0 = 2Q/(pi a' b')) at which a strip saturates from its
    leading edge: h = |g|_min pi a'^2 b' / (4 mu Q). With spin, |g| = |phi| / L3 times the distance from the
    spin pole (x0, y0) = (-eta L3/(phi L2), xi L3/(phi L1)); the distance to the bounding box of the
    ellipse is used (a lower bound), so h = 0 when the pole may lie in the patch (cells near the pole
    stick however large the spin)."""
    c = math.sqrt(ap * bp)
    iL1 = 3.0 * G * C11 / (8.0 * ap)
    iL2 = 3.0 * G * C22 / (8.0 * ap)
    iL3 = 4.0 * G * c * C23 / (math.pi * ap * ap)
    if phi == 0.0:
        gmin = math.sqrt((xi * iL1) ** 2 + (eta * iL2) ** 2)
    else:
        x0 = -eta * iL2 / (phi * iL3)
        y0 = xi * iL1 / (phi * iL3)
        dxo = max(abs(x0) - ap, 0.0)
        dyo = max(abs(y0) - bp, 0.0)
        gmin = abs(phi) * iL3 * math.sqrt(dxo * dxo + dyo * dyo)
    return gmin * math.pi * ap * ap * bp / (4.0 * mu * Q)


@hot
def _linear_closed_form(ap, bp, G, C11, C22, C23, xi, eta, phi):
    """FASTSIM's stick solution integrated exactly over the ellipse (no traction bound): the limit of the
    grid result at small creepage (Kalker frame). Stick traction at distance s = a(y) - x from the
    leading edge: p_x = -(xi/L1 - phi y/L3) s, p_y = -(eta/L2) s - (phi/(2 L3)) (a(y)^2 - x^2). Gives
    Fx = -G c^2 C11 xi, Fy = -G c^2 C22 eta - G c^3 C23 phi (Kalker's linear theory, by the choice of
    L1, L2, L3 [K82]) and Mz = (3 pi/32) G C22 a'^2 b' eta - 32/(15 pi) G c C23 b'^3 phi."""
    c = math.sqrt(ap * bp)
    Fx = -G * c * c * C11 * xi
    Fy = -G * c * c * (C22 * eta + c * C23 * phi)
    Mz = 3.0 * math.pi / 32.0 * G * C22 * ap * ap * bp * eta - 32.0 / (15.0 * math.pi) * G * c * C23 * bp ** 3 * phi
    return Fx, Fy, Mz


# strips per SIMD block of _fastsim_strips and _full_slip_fastsim: the strip count is padded to a multiple of
# it (AVX-512: two vectors of 8 doubles; LLVM runs its vectorised loop body only for trip counts of 16 and
# more)
LANES = 16
# floor of the squared magnitudes under the square roots of the strip kernels [Pa^2]: a padded strip
# (zero bound, zero traction) gives 0 / sqrt(1e-300) = 0 instead of 0 / 0
_TINY2 = 1e-300


@hot(inline="always")
def _strip_arrays(ap, bp, mup0, xi, phi, iL1, iL3, n_x, n_y, hertz):
    """Structure-of-arrays strip data of the FASTSIM grid (n_y strips across y, padded to a multiple of
    LANES with empty strips beyond y = b': e_y clamped to 0 gives zero length, area and bound). Rows:
    0 y, 1 a'(y), 2 cell length dx, 3 x increment rate xi/L1 - phi y/L3 (constant along the strip),
    4 strip bound without the cell factor, 5-9 work rows (zeroed)."""
    npad = (n_y + LANES - 1) // LANES * LANES
    buf = np.empty((10, npad))
    dy = 2.0 * bp / n_y
    ibp = 1.0 / bp
    dxa = 2.0 * ap / n_x
    for j in range(npad):
        y = -bp + (j + 0.5) * dy
        yb = y * ibp
        ey = max(1.0 - yb * yb, 0.0)
        sey = math.sqrt(ey)
        buf[0, j] = y
        buf[1, j] = ap * sey
        buf[2, j] = dxa * sey
        buf[3, j] = xi * iL1 - phi * y * iL3
        buf[4, j] = mup0 * (sey if hertz else ey)
    buf[5:] = 0.0
    return buf


@hot(inline="always")
def _cell_shape(i, n_x, hertz):
    """Bound of cell i of any strip relative to the strip's bound: the cell centres lie at the same
    fractions of every strip, e_i / e_y = (4/n_x^2) (i + 1/2)(n_x - i - 1/2) (its square root for Hertz)."""
    q = 4.0 / (n_x * n_x) * (i + 0.5) * (n_x - i - 0.5)
    return math.sqrt(q) if hertz else q


@hot(inline="always")
def _strip_sums(buf, dy):
    """(Fx, Fy, Mz) from the per-strip sums of px, py, x py (rows 7-9 of _strip_arrays) times the cell areas."""
    Fx = 0.0
    Fy = 0.0
    Mz = 0.0
    for j in range(buf.shape[1]):
        dA = buf[2, j] * dy
        Fx += buf[7, j] * dA
        Fy += buf[8, j] * dA
        Mz += (buf[9, j] - buf[0, j] * buf[7, j]) * dA
    return Fx, Fy, Mz


@hot(inline="always")
def _strip_setup(ap, bp, Q, mu, G, C11, C22, C23, xi, phi, n_x, n_y, pressure):
    """Flexibility inverses 1/L1, 1/L2, 1/L3 (Kalker's simplified theory: L1 = 8a/(3 G C11),
    L2 = 8a/(3 G C22), L3 = pi a sqrt(a/b)/(4 G C23) with c = sqrt(ab)), the Hertz-pressure flag and the
    structure-of-arrays strip data (_strip_arrays) of the vectorised marches."""
    c = math.sqrt(ap * bp)
    iL1 = 3.0 * G * C11 / (8.0 * ap)
    iL2 = 3.0 * G * C22 / (8.0 * ap)
    iL3 = 4.0 * G * c * C23 / (math.pi * ap * ap)
    hertz = pressure == PRESSURE_HERTZ
    buf = _strip_arrays(ap, bp, mu * _peak_pressure(Q, ap, bp, pressure), xi, phi, iL1, iL3, n_x, n_y, hertz)
    return iL1, iL2, iL3, hertz, buf


@hot
def _full_slip_fastsim(ap, bp, Q, mu, G, C11, C22, C23, xi, eta, phi, n_x, n_y, pressure):
    """Large-creepage limit of FASTSIM: every cell carries the bound mu p along the direction of the
    FASTSIM increment -(xi/L1 - phi y/L3, eta/L2 + phi x/L3) (not exactly the rigid-slip direction when
    L1 != L2: the same tilt as the grid result, see the module docstring). Midpoint rule on the same
    strips as _fastsim_core, no march; SIMD across the strips as _fastsim_strips."""
    iL1, iL2, iL3, hertz, buf = _strip_setup(ap, bp, Q, mu, G, C11, C22, C23, xi, phi, n_x, n_y, pressure)
    npad = buf.shape[1]
    aj = buf[1]
    dx = buf[2]
    gx = buf[3]
    gbj = buf[4]
    sfx = buf[7]
    sfy = buf[8]
    sxfy = buf[9]
    gy0 = eta * iL2
    gy1 = phi * iL3
    for i in range(n_x):
        sh = _cell_shape(i, n_x, hertz)
        fc = i + 0.5
        for j in range(npad):
            xc = aj[j] - fc * dx[j]
            gxj = gx[j]
            gy = gy0 + gy1 * xc
            r = gbj[j] * sh / math.sqrt(max(gxj * gxj + gy * gy, _TINY2))
            fy = -r * gy
            sfx[j] -= r * gxj
            sfy[j] += fy
            sxfy[j] += xc * fy
    return _strip_sums(buf, 2.0 * bp / n_y)


@hot
def _fastsim_strips(ap, bp, Q, mu, G, C11, C22, C23, xi, eta, phi, n_x, n_y, pressure):
    """The grid march of _fastsim_core without the map output, vectorised ACROSS the strips: the strips
    are independent (each marches from its own leading edge), so cell i of every strip is one SIMD
    operation on structure-of-arrays strip data (_strip_arrays, padded to a multiple of LANES). The
    stick / slip choice is branch-free: the traction is scaled by gb / sqrt(max(|p|^2, gb^2)), exactly 1
    where the cell sticks (sqrt(gb^2) = gb in IEEE arithmetic). The bound of cell i is the strip's bound
    times a factor of i alone (_cell_shape): one square root per cell index, none per cell. Same grid and
    arithmetic as _fastsim_core, equal to rounding (tests/test_fastsim.py)."""
    iL1, iL2, iL3, hertz, buf = _strip_setup(ap, bp, Q, mu, G, C11, C22, C23, xi, phi, n_x, n_y, pressure)
    npad = buf.shape[1]
    aj = buf[1]
    dx = buf[2]
    gx = buf[3]
    gbj = buf[4]
    px = buf[5]        # traction of the current cell [Pa]
    py = buf[6]
    sfx = buf[7]       # sums over the strip's cells of px, py, x py [Pa, Pa, Pa m]
    sfy = buf[8]
    sxfy = buf[9]
    gy0 = eta * iL2
    gy1 = phi * iL3
    for i in range(n_x):
        sh = _cell_shape(i, n_x, hertz)
        # travelled distance fs dx from the previous slip point, slip rate taken at x = a' - fm dx (the
        # first cell: half a cell from the leading edge, rate midway), cell centre a' - fc dx
        fs = 0.5 if i == 0 else 1.0
        fm = 0.25 if i == 0 else float(i)
        fc = i + 0.5
        for j in range(npad):
            d = dx[j]
            a = aj[j]
            ds = fs * d
            pxj = px[j] - gx[j] * ds
            pyj = py[j] - (gy0 + gy1 * (a - fm * d)) * ds
            gb = gbj[j] * sh
            f = gb / math.sqrt(max(pxj * pxj + pyj * pyj, gb * gb, _TINY2))
            pxj *= f
            pyj *= f
            px[j] = pxj
            py[j] = pyj
            sfx[j] += pxj
            sfy[j] += pyj
            sxfy[j] += (a - fc * d) * pyj
    return _strip_sums(buf, 2.0 * bp / n_y)


@hot
def fastsim_traction_fast(a, b, Q, mu, G, nu, vs_t, vs_m, w_spin, u_roll, n_x=12, n_y=12,
                          pressure=PRESSURE_PARABOLIC, f_lin=SHORTCUT_LIN, f_slip=SHORTCUT_SLIP):
    """fastsim_traction (same arguments, frame, signs and outputs) with shortcuts around the grid:
    creepage level f (creepage_level) <= f_lin: the closed-form linear (stick) solution, no grid;
    f >= f_slip and slip_level >= f_slip (the increment exceeds f_slip times the saturation rate
    everywhere, spin pole outside the patch): the full-slip limit (bound times the FASTSIM increment
    direction, no march);
    otherwise the grid march of fastsim_traction, SIMD across the strips (_fastsim_strips).
    f_lin = 0 and f_slip = inf give the grid everywhere. u_roll == 0: exact full sliding as
    fastsim_traction. Accuracy and cost of each branch: docs/kalker.md, bench/bench_fastsim.py."""
    if not (Q > 0.0 and a > 0.0 and b > 0.0):
        return 0.0, 0.0, 0.0, 0.0
    ap = b
    bp = a
    if u_roll == 0.0:
        e2 = np.empty((0, 0))
        b2 = np.empty((0, 0), dtype=np.bool_)
        return _contact_frame(a, b, Q, mu, G, nu, vs_t, vs_m, w_spin, u_roll, n_x, n_y, pressure,
                              False, e2, e2, e2, e2, b2)
    sg = -1.0 if u_roll > 0.0 else 1.0
    C11, C22, C23 = kalker_coefficients(ap / bp, nu)
    iu = 1.0 / abs(u_roll)
    xi = sg * vs_t * iu
    eta = sg * vs_m * iu
    phi = w_spin * iu
    f = creepage_level(ap, bp, Q, mu, G, C11, C22, C23, xi, eta, phi)
    if f <= f_lin:
        Fx, Fy, Mz = _linear_closed_form(ap, bp, G, C11, C22, C23, xi, eta, phi)
    elif f >= f_slip and slip_level(ap, bp, Q, mu, G, C11, C22, C23, xi, eta, phi) >= f_slip:
        Fx, Fy, Mz = _full_slip_fastsim(ap, bp, Q, mu, G, C11, C22, C23, xi, eta, phi, n_x, n_y, pressure)
    else:
        Fx, Fy, Mz = _fastsim_strips(ap, bp, Q, mu, G, C11, C22, C23, xi, eta, phi, n_x, n_y, pressure)
    Ft = sg * Fx
    Fm = sg * Fy
    P = -(Ft * vs_t + Fm * vs_m + Mz * w_spin)
    return Ft, Fm, Mz, P


if __name__ == "__main__":          # timing of one contact evaluation at the default grid
    import time
    G, nu = combined_elastic(206e9, 0.3, 206e9, 0.3)
    args = (2.0e-3, 0.3e-3, 1000.0, 0.1, G, nu, 1e-3, 2e-4, 5.0, 10.0, 20, 20, PRESSURE_PARABOLIC)
    fastsim_traction(*args)
    n = 20000
    t0 = time.perf_counter()
    for _ in range(n):
        fastsim_traction(*args)
    print(f"fastsim_traction 20x20: {(time.perf_counter() - t0) / n * 1e6:.2f} us per call")
