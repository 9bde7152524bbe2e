"""Per-contact numba kernels for the transient (Gupta-style) ball bearing dynamics: ball-race normal
contact, contact-point kinematics, traction integrated over the Hertz contact ellipse, ball-pocket
contact. SI units throughout (m, s, rad, N, Pa, W).

Conventions (same as bearing_core.contact.kinematics / bearing_core.models.quasistatic)
-----------------------------------------------------------------------
* Bearing axis z; inner ring turns at omega > 0 about +z. For a ball at azimuth psi the local
  orthonormal right-handed frame is (r, t, z): r radially out, t = z x r the orbital direction.
* Ball-race geometry through the groove curvature centres (quasistatic.py, seed 003 Eqs. 3-6):
  X = (Xr, Xz) ball centre minus the outer groove centre O_o, C = O_i - O_o,
  delta_o = |X| - (fo - 1/2) D, n_o = X/|X| = (cos ao, sin ao);
  delta_i = |X - C| - (fi - 1/2) D, n_i = (X - C)/|X - C| = (-cos ai, -sin ai).
  n is the unit vector from the ball centre towards the contact (in (r, z)).
  Q = K(alpha) delta^1.5 for delta > 0, else 0 (Hertz, exact constant from hertz.build_hertz_table
  interpolated in contact angle by hertz.hertz_lookup; identical to quasistatic.HertzInterp).
* Contact plane axes: n (normal, ball -> race), t (rolling direction, orbital) and the major-axis
  direction m = (-n_z, 0, n_r) in (r, t, z) components. (m, n, t) is right handed: m x n = t,
  n x t = m, t x m = n. The contact ellipse has semi-major axis a along m (across the groove) and
  semi-minor axis b along t. Contact-plane coordinates: x along m, y along t.
* "Sliding" = velocity of the ball material minus the race material at the same point (ball
  relative to race). Traction forces returned are forces ON THE BALL (the race gets the opposite).
* Contact centre = O_ball + (D/2) n (undeformed ball surface point, Jones / Harris convention; the
  pure-rolling relations of kinematics.py hold there).

Sources
-------
[J60]  A. B. Jones, "A general theory for elastically constrained ball and radial roller bearings
       under arbitrary load and speed conditions", J. Basic Eng. 82 (1960) 309-320.
[HK]   T. A. Harris, M. N. Kotzalas, Rolling Bearing Analysis 5th ed. (2007), Vol. 2 Ch. 3 (ball
       speeds, spin) and Ch. 4 (friction; full-sliding spin moment M_s = 3 mu Q a E(e)/8).
[G84]  P. K. Gupta, Advanced Dynamics of Rolling Elements, Springer 1984 (contact-based ball / cage
       dynamics, penalty pocket contact).
[HC75] K. H. Hunt, F. R. E. Crossley, "Coefficient of restitution interpreted as damping in
       vibroimpact", J. Appl. Mech. 42 (1975) 440-445.
[Jo85] K. L. Johnson, Contact Mechanics, CUP 1985 (torsion of a Hertz circular contact in full slip,
       M = 3 pi mu Q a / 16, the a = b case of M_s above; section number not re-checked).
seed 002 (Ma et al. 2023) Sec. 2.1-2.2: traction by integrating p(x, y) mu(s(x, y)) over the ellipse,
       p = p_max sqrt(1 - x^2/a^2 - y^2/b^2), mu(s) = (A + B s) exp(-C s) + D, s = v/u (kept as the
       illustrative curve model TRACTION_CURVE; the lubricated model is the rheology-based EHL traction
       of bearing_core.lubrication.ehl_traction, which integrates over the same ellipse and sliding field).
seed 004 Eqs. 1-5: rolling-direction slip on the deformed contact surface, rolling radius
       rho(x) = sqrt(R^2 - x^2) - sqrt(R^2 - a^2) + sqrt((D/2)^2 - a^2), R = 2 f D / (2 f + 1).
seed 000 Eq. 6: ball-pocket penalty force K_cb r_p dtheta + C_cb r_p dtheta_dot beyond the clearance
       angle. Here the penetration (|dtheta| - theta_cl) r_p is used instead of r_p |dtheta| so that
       the force is continuous at the clearance edge (Gupta's form).
"""
from __future__ import annotations

import math

import numpy as np
from .hertz import hertz_table_coefs

from ..numerics import mathx as MX
from ..numerics.mathx import _bits_f64, _f64_bits
from ..numerics.jit import CONTRACT, hot

# traction model selectors
from .traction_params import (TRACTION_COULOMB, TRACTION_CURVE, TRACTION_EHL, TRACTION_LUBRICATED,  # noqa: F401
                             P_MU0, P_VREG, P_A, P_B, P_C, P_D, P_UMIN, P_LUBMODEL, N_TRACTION_PARAMS,
                             traction_params, ellipse_quadrature)

# normal damping selectors
DAMP_NONE = 0
DAMP_HUNT_CROSSLEY = 1    # F = Q (1 + chi delta_dot), chi = 3 (1 - e) / (2 v_in)   [HC75]
DAMP_LINEAR = 2           # F = Q + c delta_dot


def hunt_crossley_chi(e, v_in):
    """Hunt-Crossley damping factor chi = 3 (1 - e) / (2 v_in) [s/m] for coefficient of restitution
    e [-] at impact speed v_in [m/s] [HC75]."""
    return 1.5 * (1.0 - e) / v_in


# --------------------------------------------------------------------------------------------------
# 0. arctangent and cube root inline (no C library call in the per-ball code)
# atan: fdlibm s_atan.c (Sun Microsystems, 1993), error < 1 ulp: |x| reduced to [0, 7/16] by
# atan(x) = atan(c) + atan((x - c) / (1 + c x)) with c = 0, 1/2, 1, 3/2 or infinity, then an odd polynomial of
# degree 23; atan(c) split into a high and a low part. Written branch-free (the reduction's constants chosen
# by comparisons, one division), so that LLVM inlines it into the callers.
(_AT0, _AT1, _AT2, _AT3, _AT4, _AT5, _AT6, _AT7, _AT8, _AT9, _AT10) = (
    3.33333333333329318027e-01, -1.99999999998764832476e-01, 1.42857142725034663711e-01,
    -1.11111104054623557880e-01, 9.09088713343650656196e-02, -7.69187620504482999495e-02,
    6.66107313738753120669e-02, -5.83357013379057348645e-02, 4.97687799461593236017e-02,
    -3.65315727442169155270e-02, 1.62858201153657823623e-02)


@hot(fastmath=CONTRACT)
def atan_ratio(ay, x):
    """atan(ay / x) [rad] for ay >= 0 and x > 0 (finite), with one division: the reduction's argument
    (ay / x - c) / (1 + c ay / x) is formed from ay and x directly, (ay - c x) / (x + c ay) (fdlibm s_atan.c
    otherwise; error within 2 ulp). NaN propagates."""
    # t = (A ay + B x) / (C x + E ay) and atan(c) = hi + lo for c = 0, 1/2, 1, 3/2, infinity
    A = 1.0; B = 0.0; C = 1.0; E = 0.0; hi = 0.0; lo = 0.0
    if ay >= 0.4375 * x:
        A = 2.0; B = -1.0; C = 2.0; E = 1.0
        hi = 4.63647609000806093515e-01; lo = 2.26987774529616870924e-17
    if ay >= 0.6875 * x:
        A = 1.0; B = -1.0; C = 1.0; E = 1.0
        hi = 7.85398163397448278999e-01; lo = 3.06161699786838301793e-17
    if ay >= 1.1875 * x:
        A = 1.0; B = -1.5; C = 1.0; E = 1.5
        hi = 9.82793723247329054082e-01; lo = 1.39033110312309984516e-17
    if not ay < 2.4375 * x:          # also NaN: NaN / NaN below stays NaN
        A = 0.0; B = -1.0; C = 0.0; E = 1.0
        hi = 1.57079632679489655800e+00; lo = 6.12323399573676603587e-17
    t = (A * ay + B * x) / (C * x + E * ay)
    z = t * t
    w = z * z
    s1 = z * (_AT0 + w * (_AT2 + w * (_AT4 + w * (_AT6 + w * (_AT8 + w * _AT10)))))
    s2 = w * (_AT1 + w * (_AT3 + w * (_AT5 + w * (_AT7 + w * _AT9))))
    return hi - ((t * (s1 + s2) - lo) - t)


@hot
def atan(x):
    """Arctangent [rad] of x, error within 2 ulp (atan_ratio); NaN propagates, +-inf gives +-pi/2."""
    ax = abs(x)
    if ax > 1e300:               # +-inf (NaN passes on)
        ax = 1e300
    r = atan_ratio(ax, 1.0)
    return r if x >= 0.0 else -r


# cube root: FreeBSD s_cbrt.c (B. Evans, after fdlibm), error < 0.667 ulp: a first guess from the exponent
# bits, a polynomial to 23 bits, one Newton step to 53 bits
_CBRT_B1 = 715094163           # (1023 - 1023 / 3 - 0.03306235651) 2^20
(_CP0, _CP1, _CP2, _CP3, _CP4) = (1.87595182427177009643, -1.88497979543377169875, 1.621429720105354466140,
                                  -0.758397934778766047437, 0.145996192886612446982)


@hot(fastmath=CONTRACT)
def cbrt_pos(x):
    """Cube root of x > 0 [-] (FreeBSD s_cbrt.c, error < 0.667 ulp) for normal finite x; any other x (0,
    subnormal, inf, NaN, negative) through numpy's cbrt."""
    if not (x >= 2.2250738585072014e-308 and x <= 1.7976931348623157e308):
        return np.cbrt(x)
    hx = _f64_bits(x) >> 32
    t = _bits_f64((hx // 3 + _CBRT_B1) << 32)
    r = (t * t) * (t / x)
    t = t * ((_CP0 + r * (_CP1 + r * _CP2)) + ((r * r) * r) * (_CP3 + r * _CP4))
    t = _bits_f64((_f64_bits(t) + 0x80000000) & -0x40000000)     # round away from zero to 23 bits
    s = t * t                                                       # exact
    r = x / s
    r = (r - t) / (t + t + r)
    return t + t * r


@hot
def atan2(y, x):
    """atan2(y, x) [rad]: atan_ratio inline for finite x > 0 (within 2 ulp), the C library otherwise."""
    if x > 0.0 and x < 1e300 and abs(y) < 1e300:
        r = atan_ratio(abs(y), x)
        return r if y >= 0.0 else -r
    return math.atan2(y, x)


@hot
def wrap_angle(a):
    """Angle a [rad] wrapped to [-pi, pi) as (a + pi) % (2 pi) - pi."""
    return (a + math.pi) % (2.0 * math.pi) - math.pi


# --------------------------------------------------------------------------------------------------
# 1. ball-race normal contact
@hot(inline="always")
def _one_contact(dr, dz, rc, table, alpha0, dalpha, inner):
    L = math.sqrt(dr * dr + dz * dz)
    iL = 1.0 / L
    nr = dr * iL
    nz = dz * iL
    delta = L - rc
    # contact angle from (dr, dz) = L n directly: not waiting for the normalisation
    if inner:
        alpha = atan2(-dz, -dr)
    else:
        alpha = atan2(dz, dr)
    if delta > 0.0:
        # hertz table at |alpha|, and Q = K delta^1.5, Q^(1/3) = K^(1/3) delta^(1/2) without pow of delta
        K, ac, bc = hertz_table_coefs(table, alpha0, dalpha, alpha)
        sd = math.sqrt(delta)
        Q = K * delta * sd
        q3 = cbrt_pos(K) * sd
        a = ac * q3
        b = bc * q3
        p = 1.5 * Q / (math.pi * a * b)
    else:
        Q = 0.0
        a = 0.0
        b = 0.0
        p = 0.0
    return delta, nr, nz, alpha, Q, a, b, p


@hot(nrt=False)
def ball_race_contact(Xr, Xz, Cr, Cz, ro_c, ri_c, table_i, table_o, alpha0, dalpha):
    """Hertz normal contact of one ball with both races.

    Xr, Xz [m]: ball centre minus the outer groove curvature centre (local (r, z)); Cr, Cz [m]: inner
    minus outer groove centre; ro_c = (fo - 1/2) D, ri_c = (fi - 1/2) D [m]; table_i / table_o =
    HertzTable.inner / .outer, alpha0, dalpha = HertzTable.alpha0, .dalpha [rad].
    Returns (delta_o [m], nor, noz, alpha_o [rad], Q_o [N], a_o [m], b_o [m], p_o [Pa],
             delta_i, nir, niz, alpha_i, Q_i, a_i, b_i, p_i); n from the ball centre to the contact;
    Q = a = b = p = 0 where delta <= 0."""
    do, nor, noz, ao, Qo, a_o, b_o, p_o = _one_contact(Xr, Xz, ro_c, table_o, alpha0, dalpha, False)
    di, nir, niz, ai, Qi, a_i, b_i, p_i = _one_contact(Xr - Cr, Xz - Cz, ri_c, table_i, alpha0, dalpha,
                                                        True)
    return do, nor, noz, ao, Qo, a_o, b_o, p_o, di, nir, niz, ai, Qi, a_i, b_i, p_i


@hot(nrt=False)
def gothic_arch_contact(dr, dz, rc, fD, e, arc, table, alpha0, dalpha, inner):
    """Hertz normal contact of a ball with one arc of a gothic-arch (two-arc) groove.

    The groove is two circular arcs of radius f D whose curvature centres sit at +-e from the groove
    mid-plane, each arc on the side of the mid-plane opposite to its centre (Harris & Kotzalas Vol. 1,
    gothic-arch bearings; Amasorrain et al., Mech. Mach. Theory 38 (2003) 479; the same arcs as
    quasistatic.FourPointQuasiStaticModel). (dr, dz) [m]: ball centre minus this arc's curvature centre;
    rc = (f - 1/2) D, fD = f D [m]; e [m] the offset of the ring; arc = 1: the arc whose contact angle is
    positive (its contact point exists where f D sin(alpha) >= e), arc = 2: its mirror image (f D sin(alpha)
    < -e). At e = 0 both arcs are the single-arc groove and exactly one of them is valid.
    Returns (valid, delta [m], n_r, n_z, alpha [rad], Q [N], a [m], b [m], p [Pa]) as _one_contact; an arc
    whose contact point would lie beyond the mid-plane is not valid and carries nothing (no Hertz lookup)."""
    L = math.sqrt(dr * dr + dz * dz)
    nr = dr / L
    nz = dz / L
    sa = -nz if inner else nz                 # sin(alpha) (contact_kernels convention above)
    valid = fD * sa >= e if arc == 1 else fD * sa < -e
    if not valid:
        alpha = atan2(-nz, -nr) if inner else atan2(nz, nr)
        return False, L - rc, nr, nz, alpha, 0.0, 0.0, 0.0, 0.0
    delta, nr, nz, alpha, Q, a, b, p = _one_contact(dr, dz, rc, table, alpha0, dalpha, inner)
    return True, delta, nr, nz, alpha, Q, a, b, p


@hot
def normal_contact_force(Q_el, delta, delta_dot, model, c):
    """Normal force [N] with damping, from the elastic Hertz force Q_el [N], deflection delta [m] and
    its rate delta_dot [m/s] (> 0 approaching).

    model DAMP_NONE: Q_el. DAMP_HUNT_CROSSLEY: Q_el (1 + c delta_dot) with c = chi [s/m] from
    hunt_crossley_chi(e, v_in) [HC75]; the damping vanishes with the contact (no force jump at
    contact onset), default choice. DAMP_LINEAR: Q_el + c delta_dot, c [N s/m].
    Zero for delta <= 0; never negative (no adhesive pull on separation)."""
    if not delta > 0.0:
        return 0.0
    if model == DAMP_HUNT_CROSSLEY:
        F = Q_el * (1.0 + c * delta_dot)
    elif model == DAMP_LINEAR:
        F = Q_el + c * delta_dot
    else:
        F = Q_el
    return F if F > 0.0 else 0.0


# --------------------------------------------------------------------------------------------------
# 2. contact-point kinematics
@hot
def contact_kinematics(r_b, vr, vt, vz, wr, wt, wz, Omega_race, vrr, vrt, vrz, n_r, n_z, D):
    """Relative (ball minus race) motion at the contact centre O_ball + (D/2) n.

    r_b [m]: radius of the ball centre from the bearing axis; (vr, vt, vz) [m/s]: ball centre
    velocity (inertial, components in the local (r, t, z) frame at the ball azimuth); (wr, wt, wz)
    [rad/s]: ball absolute angular velocity (same components); Omega_race [rad/s]: race angular speed
    about +z (inner: shaft speed, outer: 0); (vrr, vrt, vrz) [m/s]: race centre velocity (local
    components; the race surface speed is taken as Omega_race times the contact-point radius from the
    bearing axis, i.e. race-centre offsets enter only through this velocity); (n_r, n_z): contact
    normal; D [m]: ball diameter.
    Returns (vs_t, vs_m, w_spin, w_roll_m, w_roll_t, u_roll):
      vs_t [m/s] sliding in the rolling direction t, vs_m [m/s] sliding along m = (-n_z, n_r);
      w_spin = (w_ball - w_race) . n [rad/s] (kinematics.contact_spin_roll's spin);
      w_roll_m = (w_ball - w_race) . m, w_roll_t = (w_ball - w_race) . t [rad/s];
      u_roll [m/s]: rolling (entrainment) speed along t, the mean of the ball and race surface
      speeds relative to the contact point, which moves with the ball's orbital angular speed
      vt / r_b (signed; < 0 for the usual rolling of the outer race)."""
    return contact_kinematics_orb(r_b, vr, vt, vz, vt / r_b, wr, wt, wz, Omega_race, vrr, vrt, vrz, n_r, n_z, D)


@hot
def contact_kinematics_orb(r_b, vr, vt, vz, w_orb, wr, wt, wz, Omega_race, vrr, vrt, vrz, n_r, n_z, D):
    """contact_kinematics with the ball's orbital angular speed w_orb = vt / r_b [rad/s] given (the right-hand
    side has it as a state: no division)."""
    h = 0.5 * D
    pr = h * n_r
    pz = h * n_z
    Rp = r_b + pr
    # ball material at the contact point: v + w x p
    vbr = vr + wt * pz
    vbt = vt + wz * pr - wr * pz
    vbz = vz - wt * pr
    # race material at the contact point
    vct = vrt + Omega_race * Rp
    dr = vbr - vrr
    dt = vbt - vct
    dz = vbz - vrz
    vs_t = dt
    vs_m = -n_z * dr + n_r * dz
    wzr = wz - Omega_race
    w_spin = wr * n_r + wzr * n_z
    w_roll_m = -n_z * wr + n_r * wzr
    w_roll_t = wt
    v_cp = w_orb * Rp
    u_roll = 0.5 * (vbt + vct) - v_cp
    return vs_t, vs_m, w_spin, w_roll_m, w_roll_t, u_roll


# --------------------------------------------------------------------------------------------------
# 3. traction over the contact ellipse
@hot(nrt=False)
def traction_coefficient(v, u_roll, model, params):
    """Traction coefficient [-] at sliding speed v >= 0 [m/s] and rolling speed u_roll [m/s].

    TRACTION_COULOMB: mu0 tanh(v / v_reg). TRACTION_CURVE (seed 002 Sec. 2.1, illustrative):
    (A + B s) exp(-C s) + D, s = v / max(|u_roll|, u_min). params from traction_params()."""
    if model == TRACTION_CURVE:
        u = abs(u_roll)
        um = params[P_UMIN]
        if u < um:
            u = um
        s = v / u
        return (params[P_A] + params[P_B] * s) * math.exp(-params[P_C] * s) + params[P_D]
    return params[P_MU0] * math.tanh(v / params[P_VREG])


@hot(nrt=False)
def ellipse_traction(a, b, p_max, D, R_def, vs_t, vs_m, w_spin, w_roll_m, w_roll_t, u_roll, model,
                     params, xi, wxi, zeta, wzeta):
    """Traction on the ball integrated over the Hertz ellipse (seed 002 Sec. 2.2; seed 004 Eqs. 1-5).

    a, b [m] semi-axes (a along m, b along t), p_max [Pa]; D [m] ball diameter; R_def [m] radius of
    the deformed contact surface across the groove, 2 f D / (2 f + 1) (pass 0 to ignore the
    curvature: flat contact at the ball radius D/2); the relative motion (vs_t, vs_m, w_spin,
    w_roll_m, w_roll_t, u_roll) from contact_kinematics; model / params: traction_coefficient;
    (xi, wxi, zeta, wzeta) from ellipse_quadrature.
    Local sliding at (x, y) on the deformed surface, rolling radius
    rho(x) = sqrt(R^2 - x^2) - sqrt(R^2 - a^2) + sqrt((D/2)^2 - a^2) (seed 004), d = rho - D/2:
        v_t = vs_t - w_spin x + w_roll_m d,    v_m = vs_m + w_spin y - w_roll_t d
    (rigid relative velocity field about the contact centre). Shear = -mu p v/|v|.
    Returns (F_t, F_m [N], M_n, M_m, M_t [N m], P_loss [W]): force on the ball along t and m; its
    moment about the ball centre along n (= spin moment about the contact normal), m and t;
    dissipated power sum(mu p |v| dA) >= 0 for mu >= 0. Identity (tested):
    P_loss = -[F_t vs_t + F_m vs_m + M_n w_spin + w_roll_m (M_m - D/2 F_t) + w_roll_t (M_t + D/2 F_m)].
    """
    Ft = 0.0
    Fm = 0.0
    Mn = 0.0
    Mm = 0.0
    Mt = 0.0
    P = 0.0
    if not (p_max > 0.0 and a > 0.0 and b > 0.0):
        return Ft, Fm, Mn, Mm, Mt, P
    h = 0.5 * D
    curv = R_def > a and h > a
    c0 = 0.0
    if curv:
        c0 = math.sqrt(h * h - a * a) - math.sqrt(R_def * R_def - a * a)
    pab = p_max * a * b
    for i in range(xi.shape[0]):
        x = a * xi[i]
        w2 = 1.0 - xi[i] * xi[i]
        w = math.sqrt(w2)
        if curv:
            rho = math.sqrt(R_def * R_def - x * x) + c0
        else:
            rho = h
        d = rho - h
        vt_x = vs_t - w_spin * x + w_roll_m * d
        vm_x = vs_m - w_roll_t * d
        wi = pab * w2 * wxi[i]
        for j in range(zeta.shape[0]):
            y = b * w * zeta[j]
            vm = vm_x + w_spin * y
            v = math.sqrt(vt_x * vt_x + vm * vm)
            if v > 0.0:
                mu = traction_coefficient(v, u_roll, model, params)
                dF = mu * wi * wzeta[j]
                ft = -dF * vt_x / v
                fm = -dF * vm / v
                Ft += ft
                Fm += fm
                Mn += y * fm - x * ft
                Mm += rho * ft
                Mt -= rho * fm
                P += dF * v
    return Ft, Fm, Mn, Mm, Mt, P


# --------------------------------------------------------------------------------------------------
# 4. ball-pocket contact
@hot
def ball_pocket_contact(theta_b, theta_c, dtheta_b, dtheta_c, r_p, c_p, K_cb, C_cb, mu_cb, v_reg,
                        D, vr, vz, wr, wz, vcr, vcz):
    """Penalty contact of a ball with its cage pocket along the orbital direction t (seed 000 Eq. 6
    with the penetration form; [G84]).

    theta_b, theta_c [rad]: ball and pocket-centre azimuths; dtheta_b, dtheta_c [rad/s] their rates;
    r_p [m] pitch radius; c_p [m] pocket clearance (half the diametral pocket clearance);
    K_cb [N/m], C_cb [N s/m]; mu_cb [-] friction, v_reg [m/s] its tanh regularisation; D [m];
    (vr, vz) [m/s] ball centre velocity, (wr, wz) [rad/s] ball angular velocity, (vcr, vcz)
    [m/s] cage centre velocity (local (r, t, z) components). The cage turns at dtheta_c about z.
    Penetration pen = |dtheta| r_p - c_p (dtheta wrapped to [-pi, pi]); contact when pen > 0:
    F_n = max(0, K_cb pen + C_cb pen_dot), pen_dot = sign(dtheta) (dtheta_b - dtheta_c) r_p (pushes
    only; the elastic part is continuous at pen = 0, the linear damper jumps by C_cb pen_dot at
    impact, as in seed 000).
    Friction opposes the sliding of the ball surface on the pocket wall at O_ball + sigma (D/2) t:
    f = -mu_cb F_n tanh(|v_s| / v_reg) v_s/|v_s|, v_s in (r, z).
    Returns (F_n [N], F_t, F_r, F_z [N] force on the ball, M_r, M_z [N m] its moment about the
    ball centre); the cage gets the opposite force."""
    return ball_pocket_contact_rel(wrap_angle(theta_b - theta_c), dtheta_b, dtheta_c, r_p, c_p, K_cb, C_cb,
                                   mu_cb, v_reg, D, vr, vz, wr, wz, vcr, vcz)


@hot
def ball_pocket_contact_rel(dth, dtheta_b, dtheta_c, r_p, c_p, K_cb, C_cb, mu_cb, v_reg, D, vr, vz, wr, wz, vcr,
                            vcz):
    """ball_pocket_contact from dth [rad], the ball azimuth minus the pocket-centre azimuth already wrapped
    to [-pi, pi) (the right-hand side forms it without an arctangent of the ball position)."""
    sig = 1.0 if dth >= 0.0 else -1.0
    pen = abs(dth) * r_p - c_p
    if not pen > 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    pen_dot = sig * (dtheta_b - dtheta_c) * r_p
    Fn = K_cb * pen + C_cb * pen_dot
    if not Fn > 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    h = 0.5 * D
    vsr = vr - vcr - sig * h * (wz - dtheta_c)
    vsz = vz - vcz + sig * h * wr
    vs = math.sqrt(vsr * vsr + vsz * vsz)
    Fr = 0.0
    Fz = 0.0
    if vs > 0.0:
        f = mu_cb * Fn * math.tanh(vs / v_reg) / vs
        Fr = -f * vsr
        Fz = -f * vsz
    Ft = -sig * Fn
    # moment of the friction force at arm sigma h t: t x r = -z, t x z = r
    Mr = sig * h * Fz
    Mz = -sig * h * Fr
    return Fn, Ft, Fr, Fz, Mr, Mz
