"""EHL traction of a lubricated ball-race contact from the lubricant's rheology, point by point over the
Hertz ellipse, with mixed-lubrication load sharing and the EHL rolling resistance. SI units throughout
(m, s, N, Pa, Pa s, K, W).

Formulation followed (one local, closed-form shear law per quadrature point; per-contact quantities once
per contact; names of the parameter slots in traction_params.P_*):

1. Local Hertz pressure p(x, y) = p_max sqrt(1 - x^2/a^2 - y^2/b^2) (the quadrature of
   traction_params.ellipse_quadrature carries the same ellipse).
2. Film: Hamrock-Dowson central film h_c (bearing_core.lubrication.film.hd_central_film_nb, [HD77]) at the contact's
   entrainment speed, inlet viscosity eta_0(T) and alpha(T); uniform over the contact (the EHL plateau).
   Shear rate gamma_dot = |v| / h_c, v the local sliding speed (contact_kernels.ellipse_traction's field).
3. Viscosity with pressure, Roelands [R66]: ln(eta/eta_0) = (ln eta_0 + 9.67) [(1 + p/p_0)^z - 1],
   p_0 = 1.96e8 Pa. z is the oil's own where published, else the Roelands index equivalent to the
   oil's Barus alpha at low pressure, z = alpha p_0 / (ln eta_0 + 9.67) (Hamrock NASA RP-1255 Ch. 4);
   which one is used is said per oil (bearing_core.lubrication.lubricants).
4. Non-Newtonian shear, Ree-Eyring sinh law [JT77, EJ86]: gamma_dot = (tau_0/eta) sinh(tau/tau_0), i.e.
   tau_v = tau_0 asinh(eta gamma_dot / tau_0), tau_0 the Eyring stress.
5. Shear heating [EJ86, JG80-style]: the viscosity in 4 is taken at the film's mid-plane temperature
   T = T_inlet + dT_flash + dT_film, with
     dT_film = tau |v| h / (8 k_oil)    (Couette shear heating, uniform in the film, conducted to both
                                         surfaces: the parabolic profile's peak rise),
     dT_flash = tau |v| sqrt(s_in / (pi u rho_s c_s k_s))   (surface temperature of a semi-infinite
                                         solid under the half of the heat flux it takes, after the
                                         exposure time s_in / u since the inlet edge, Jaeger / Carslaw &
                                         Jaeger moving-source result with the local flux),
   and eta(T) = eta(T_inlet) exp(-beta (T - T_inlet)), beta = -d ln eta / dT of the oil at T_inlet. The
   implicit equation tau = tau_0 asinh(X exp(-beta c tau)), dT = c tau, is solved to 1e-9 relative
   (thermal_eyring_root): in the Eyring-logarithmic regime (Evans & Johnson's thermal Eyring regime,
   tau ~ tau_0 ln(2X) / (1 + beta c tau_0)) as elsewhere, by a Householder and a Chebyshev step on
   ln sinh.
6. Elasticity, Maxwell [JT77]: a fluid element entering the Hertz zone at constant strain rate builds its
   stress as tau = tau_v (1 - exp(-tau_e / tau_v)) with tau_e = G_e gamma_dot s_in / u the elastic stress
   after the transit s_in / u (exact for a linear Maxwell liquid of constant properties; the Eyring
   tau_v in place of eta gamma_dot). G_e is the film's shear modulus G in series with the tangential
   compliance of the two solids: 1 / G_e = 1 / G + 8 b / (3 h C11 G_s), the modulus that makes the
   elastic film force G_e gamma (8 a b^2 / 3) s / h equal Kalker's linear creep force G_s C11 a b s in
   the small-slip limit (Kalker C11 of bearing_core.contact.fastsim.kalker_coefficients at the contact's b/a).
7. Limiting shear stress [BW79]: tau = min(tau, tau_L), tau_L = tau_L0 + gamma_L(T) p. gamma_L falls with
   temperature (measured for a naphthenic oil and a PAO/diester, Wikstrom & Hoglund, J. Tribol. 116 (1994)
   612-620); none of our sources gives a slope we could transfer, so, as for lubricants.traction_scale,
   the ASSUMPTION gamma_L(T) = gamma_L(T_ref) (1 - k_T (T - T_ref)), k_T = 0.003 1/K, T_ref = 40 degC, is
   used, at the inlet temperature (per contact) and with the film's heating dT = c tau_L (item 5) at each
   point: tau_L = tau_L,inlet / (1 + k_T' c tau_L,inlet), k_T' = k_T gamma_L(T_ref) / gamma_L(T_inlet)
   (closed form of the linear law).
8. Mixed lubrication [ZH91]: film parameter Lambda = h_c / sqrt(Rq1^2 + Rq2^2); the fluid carries the
   fraction f(Lambda) of the local pressure, the asperities the rest at the boundary friction
   coefficient mu_bl (regularised mu_bl tanh(|v| / v_bl)); f from Zhou & Hoeprich's fit
   f = 1.21 Lambda^0.64 / (1 + 0.37 Lambda^1.26) (recalled, check against the source), normalised by
   its maximum (1.0026 at Lambda = 2.258) and held at 1 beyond, so that it reaches full film smoothly.
9. EHL rolling resistance [HK07]: the hydrodynamic rolling force
     F_R = 2.86 E' Rx^2 k^0.348 G^0.022 U^0.66 W^0.47     (Harris & Kotzalas Vol. 2 Ch. 5, the fit of
   Houpert's / Hamrock's numerical results; recalled, check against the source), with the Hamrock-Dowson
   groups U, G, W and k = a/b. It is applied as the moment of the upstream shift of the pressure centre,
   M_R = F_R Rx about the contact's rolling axis m, opposing the relative rolling rotation (ball minus
   race) w_roll_m; the race gets the opposite moment. This conserves momentum and dissipates
   M_R |w_roll_m| = F_R u in pure rolling (u = Rx |w_roll_m|), the rolling-resistance power of F_R.

Sources
-------
[R66]  C. J. A. Roelands, Correlational aspects of the viscosity-temperature-pressure relationship of
       lubricating oils, PhD thesis, TU Delft, 1966.
[JT77] K. L. Johnson, J. L. Tevaarwerk, Shear behaviour of elastohydrodynamic oil films, Proc. R. Soc.
       Lond. A 356 (1977) 215-236.
[EJ86] C. R. Evans, K. L. Johnson, The rheological properties of elastohydrodynamic lubricants, Proc.
       IMechE 200(C5) (1986) 303-312.
[JG80] K. L. Johnson, J. A. Greenwood, Thermal analysis of an Eyring fluid in elastohydrodynamic
       traction, Wear 61 (1980) 353-374.
[BW79] S. Bair, W. O. Winer, A rheological model for elastohydrodynamic contacts based on primary
       laboratory data, J. Lubr. Technol. 101 (1979) 258-265.
[ZH91] R. S. Zhou, M. R. Hoeprich, Torque of tapered roller bearings, J. Tribol. 113 (1991) 590-597.
[HK07] T. A. Harris, M. N. Kotzalas, Rolling Bearing Analysis 5th ed., Vol. 2 (2007) Ch. 5.
[HD77] B. J. Hamrock, D. Dowson, J. Lubr. Technol. 99 (1977) 264-276.
"""
from __future__ import annotations

import math

import numpy as np
from .film import hd_central_film_ln, hd_central_film_nb, hd_groups_nb
from ..numerics import mathx as mx
from ..numerics.jit import hot

ROELANDS_P0 = 1.96e8       # Pa [R66]
ROELANDS_LN_ETA_INF = 9.67  # -ln(6.31e-5 Pa s) [R66]
LN2 = mx.LN2
_ZH_LAM_PEAK = (0.64 / (0.37 * 1.26 - 0.37 * 0.64)) ** (1.0 / 1.26)   # argmax of the Zhou-Hoeprich fit, 2.258
_ZH_PEAK = 1.21 * _ZH_LAM_PEAK ** 0.64 / (1.0 + 0.37 * _ZH_LAM_PEAK ** 1.26)

# the traction parameter array's layout: contact.traction_params (R_* rheology slots)
from ..contact.traction_params import (R_LUBMODEL, R_ETA0, R_LNE, R_Z, R_ALPHA, R_BETA, R_TAU0,  # noqa: F401
                                       R_TAUL0, R_GAML, R_GFILM, R_KOIL, R_EPRIME, R_GSC11, R_RCK, R_RQ,
                                       R_MUBL, R_VBL, R_RR, R_THERMAL, R_KGAM, N_PARAMS)
# rows of ehl_scratch (one column per quadrature point): the nodes and weights (xi, w_xi, zeta, w_zeta of
# traction_params.ellipse_quadrature), then ehl_ellipse_traction_into's work rows: sliding velocity (t, m),
# position (x, y, rho), pressure, shear-force weight, distance from the inlet edge, shear force per unit
# sliding speed; then the per-contact values of the shear law, one column per point, for the pair kernel
# (ehl_pair_traction_into): ln(eta_0 / (tau_0 h)), G_e / (h u), the film and flash heating factors, the
# fluid's load fraction and the asperities' friction coefficient
_XI, _WXI, _ZETA, _WZETA, _VT, _VM, _XS, _YS, _RH, _PP, _WQ, _SI, _DF = range(13)
_LX, _GH, _CF, _CL, _FF, _MB = range(13, 19)
_NROWS = 19


@hot(inline="always")
def roelands_ln_factor(p, lne, z):
    """ln(eta(p) / eta_0) [-] of the Roelands equation [R66] at gauge pressure p >= 0 [Pa]; lne =
    ln(eta_0 [Pa s]) + 9.67, z the pressure-viscosity index."""
    if p <= 0.0:
        return 0.0
    return lne * mx.expm1(z * mx.log1p(p / ROELANDS_P0))


@hot
def fluid_fraction(lam):
    """Fraction of the load carried by the fluid film [-] at film parameter lam [-]: the Zhou-Hoeprich
    fit [ZH91] 1.21 lam^0.64 / (1 + 0.37 lam^1.26) normalised by its maximum, 1 for lam >= 2.258."""
    if lam >= _ZH_LAM_PEAK:
        return 1.0
    if lam <= 0.0:
        return 0.0
    return 1.21 * lam ** 0.64 / (1.0 + 0.37 * lam ** 1.26) / _ZH_PEAK


@hot
def hydrodynamic_rolling_force(u, eta0, alpha_pv, Rx, k, E_prime, Q):
    """EHL rolling force F_R [N] [HK07]: 2.86 E' Rx^2 k^0.348 G^0.022 U^0.66 W^0.47 (Hamrock-Dowson
    groups of film.hd_groups_nb). u [m/s] entrainment speed, eta0 [Pa s], alpha_pv [1/Pa], Rx [m], k = a/b
    [-], E_prime [Pa], Q [N]. 0 without load or motion."""
    if not (Q > 0.0 and u != 0.0 and eta0 > 0.0):
        return 0.0
    U, G, W = hd_groups_nb(u, eta0, alpha_pv, Rx, E_prime, Q)
    return _rolling_force_ln(E_prime, Rx, k, math.log(U), math.log(G), math.log(W))


@hot(inline="always")
def _rolling_force_ln(E_prime, Rx, k, lnU, lnG, lnW):
    """hydrodynamic_rolling_force from the logarithms of the Hamrock-Dowson groups [N]."""
    return 2.86 * E_prime * Rx * Rx * math.exp(0.348 * math.log(k) + 0.022 * lnG + 0.66 * lnU + 0.47 * lnW)


@hot(inline="always")
def _asinh_exp(lX):
    """asinh(exp(lX)) for any lX: ln 2 + lX above lX = 20 (the next term, exp(-2 lX) / 4, is below 1e-18)."""
    sm = mx.asinh_pos(mx.exp(lX if lX < 20.0 else 20.0))
    return sm if lX <= 20.0 else lX + LN2


@hot(inline="always")
def thermal_eyring_root(lX, K):
    """Root s >= 0 of the thermal Eyring equation s = asinh(X exp(-K s)) (item 5 in units of tau_0:
    s = tau / tau_0, K = beta c tau_0 >= 0), given lX = ln X. Branch-free, so that it vectorises.

    Written as g(s) = ln sinh s + K s - ln X = s (1 + K) + ln(1 - e^{-2s}) - ln 2 - ln X = 0
    (increasing and concave in s). The seed is Newton's step from the isothermal root s_i = asinh X
    (where g = K s_i), s_i / (1 + K tanh s_i), tanh s_i = X / sqrt(1 + X^2), with s_i from series in X,
    ln X and 1 / X^2 (relative error <= 1e-4; no log on the path from ln X); it lies below the root, by
    up to 53 % at K = 31.6, where g bends like a logarithm. One Householder step of order 3 (quartic
    convergence) in the variable ln s, in which g is nearly linear there, takes it to within 2.4e-3; one
    Chebyshev step (cubic) on g in s finishes. All derivatives of g follow from w = 1 - e^{-2s}:
    g' = 1 + K + 2 (1 - w) / w, g'' = -4 (1 - w) / w^2, g''' = 8 (1 - w)(2 - w) / w^3, so each step
    costs one exp and one log. The seed and the Householder step use the coarse exp / log of
    bearing_core.numerics.mathx (<= 6e-7) and a Pade form of the step's factor e^{-d} (<= 1.4e-6); the Chebyshev
    step, in full precision, cubes the iterate's error, so that the root moves by < 5e-12 relative
    (measured 1.3e-12) against the same steps in full precision. Measured relative error against the converged
    root (tests/test_jit_flags.py, ln X in [-28, 50]): <= 2e-14 for K <= 3, <= 2e-12 for K <= 10,
    <= 1e-9 for K <= 31.6. The seed is held above 3.3e-308 (exp(-708)); the root stays positive."""
    return _thermal_eyring_root(lX, lX, K)


@hot(inline="always")
def _thermal_eyring_root(lXc, lX, K):
    """thermal_eyring_root with its seed and Householder step taken from lXc, an approximation of lX, so
    that the root can start from a coarse ln X while the full-precision one is being computed. An
    absolute error of lXc up to 3e-5 leaves the error bounds unchanged (tests/test_jit_flags.py); 1e-4
    raises the one for K <= 3 to 1e-13."""
    # seed: Newton's step on g from the isothermal root s_i = asinh X (where g = K s_i):
    # s_i / (1 + K tanh s_i), tanh s_i = X / sqrt(1 + X^2); below the root (g is concave). s_i to 1e-4
    # (the steps below remove it) without a log on the path from ln X: Taylor series in X below
    # X = e^-0.75 and in 1 / X^2 above X = e^0.75 (asinh X = ln 2X + 1 / (4 X^2) - ...), between them a
    # polynomial in ln X (Chebyshev fit of degree 6 over |ln X| <= 0.75, relative error 9e-6)
    x = mx.exp_lo(lXc if lXc < 20.0 else 20.0)
    x2 = x * x
    r = math.sqrt(1.0 + x2)
    u = 1.0 / (x2 if x2 > 1.0 else 1.0)                 # 1 / X^2 where used (X > 2.1)
    s_lo = x * (1.0 + x2 * (-1.0 / 6.0 + x2 * (3.0 / 40.0 - x2 * (5.0 / 112.0))))
    s_hi = (lXc + LN2) + u * (0.25 - u * (3.0 / 32.0 - u * (15.0 / 288.0)))
    l2 = lXc * lXc
    s_mid = ((0.8813739608608067 + lXc * 0.7070891455748324) +
             l2 * ((0.1767523031968521 - lXc * 0.02917219344930663) +
                   l2 * ((-0.018167773628819685 + lXc * 0.005054404389377888) + l2 * 0.0029017703331124614)))
    si = s_lo if lXc < -0.75 else (s_mid if lXc <= 0.75 else s_hi)
    s = si * r / (r + K * x)
    s = 3.3e-308 if s < 3.3e-308 else s                 # exp(-708), where mathx.exp stops
    # coarse Householder step of order 3 in ln s, where G(ln s) = g(s) is nearly linear for s << 1 / K:
    # G1 = s g', G2 = G1 + s^2 g'', G3 = G1 + 3 s^2 g'' + s^3 g''' from g' = 1 + K + 2 t / w,
    # g'' = -4 t / w^2, g''' = 8 t (1 + t) / w^3 (w = 1 - e^{-2s}, t = 1 - w; q = s / w keeps them scaled)
    w = -mx.expm1_lo(-2.0 * s)
    t = 1.0 - w
    g = s * (1.0 + K) + mx.log_lo(w) - LN2 - lXc
    q = s / w
    tq = t * q
    G1 = s * (1.0 + K) + 2.0 * tq
    G2 = G1 - 4.0 * tq * q
    G3 = G1 - 12.0 * tq * q + 8.0 * (1.0 + t) * tq * q * q
    d = 3.0 * g * (2.0 * G1 * G1 - g * G2) / (6.0 * G1 * G1 * G1 - 6.0 * g * G1 * G2 + g * g * G3)
    # s e^{-d}: d lies in [-0.75, 0] for K <= 31.6; Pade (3, 3) form of e^{-d}, relative error
    # d^7 / 100800 (1.4e-6 at d = -0.75), with d clamped to [-3, 3] where the form stays positive
    d = min(max(d, -3.0), 3.0)
    d2 = d * d
    pe = 1.0 + 0.1 * d2
    qo = d * (0.5 + d2 * (1.0 / 120.0))
    s = s * (pe - qo) / (pe + qo)
    # Chebyshev's step (cubic) on g in full precision: (g / g') (1 + g g'' / (2 g'^2))
    # = (g w / N) (1 - 2 g t / N^2), N = w g' = 2 + (K - 1) w; 1 / N is computed while the log is
    w = -mx.expm1(-2.0 * s)
    t = 1.0 - w
    rN = 1.0 / (2.0 + (K - 1.0) * w)
    g = s * (1.0 + K) + mx.log(w) - LN2 - lX
    ds = g * w * rN * (1.0 - 2.0 * g * t * rN * rN)
    s = 0.1 * s if ds >= 0.9 * s else s - ds
    return s


@hot(inline="always")
def _point_stress(v, pf, s_in, lxh, lne, z, h, u, tau0, tauL0, gamL, G_e, cfilm, cflash, beta, thermal, kgam):
    """Fluid shear stress [Pa] at one point of the contact (items 3-7), branch-free in the point's values.

    v [m/s] sliding speed; pf [Pa] pressure carried by the fluid; s_in [m] distance from the inlet edge;
    lxh = ln(eta_0 / (tau_0 h)); cfilm = h / (8 k_oil); cflash = 1 / sqrt(pi u rho c k) (0: no flash
    heating); the rest as fluid_shear_stress. 0 for v = 0."""
    return _point_stress_g(v, pf, s_in, lxh, lne, z, G_e / (h * u), G_e > 0.0, tau0, tauL0, gamL, cfilm, cflash,
                           beta, thermal, kgam)


@hot(inline="always")
def _point_stress_g(v, pf, s_in, lxh, lne, z, ghu, elastic, tau0, tauL0, gamL, cfilm, cflash, beta, thermal,
                    kgam):
    """_point_stress with the film's elasticity as ghu = G_e / (h u) [1/m] (per contact) and elastic =
    G_e > 0."""
    vv = 1e-300 if v < 1e-300 else v
    # ln(eta(p) v / (tau_0 h)); Roelands with log(1 + p/p0) in place of log1p: what matters is the absolute
    # error of ln(eta/eta_0), here <= z lne 1.1e-16, not the relative one near p = 0
    lX = lxh + lne * mx.expm1(z * mx.log(1.0 + pf * (1.0 / ROELANDS_P0))) + mx.log(vv)
    # the same with the coarse exp / log, absolute error ~ 8e-7 (ln(eta / eta_0) + lne) + 1e-7 |ln v|
    # (<= 3e-5 up to ln(eta / eta_0) = 25): the thermal root starts from it, in parallel with the
    # full-precision lX that it needs in its last step only
    lXc = lxh + lne * mx.expm1_lo(z * mx.log_lo(1.0 + pf * (1.0 / ROELANDS_P0))) + mx.log_lo(vv)
    tl = tauL0 + gamL * pf
    if thermal:
        c = vv * (cfilm + math.sqrt(s_in) * cflash)       # temperature rise per unit stress [K/Pa]
        tl = tl / (1.0 + kgam * c * tl)
        tau = tau0 * _thermal_eyring_root(lXc, lX, beta * c * tau0)
    else:
        tau = tau0 * _asinh_exp(lX)                        # Ree-Eyring
    if elastic:
        ts = 1e-300 if tau < 1e-300 else tau
        tau = -ts * mx.expm1(-ghu * vv * s_in / ts)         # Maxwell: elastic stress after the transit
    tau = tl if tau > tl else tau
    return tau if v > 0.0 else 0.0 * tau


@hot
def fluid_shear_stress(p, v, h, s_in, u, eta0, lne, z, beta, tau0, tauL0, gamL, G_e, k_oil, rck, thermal,
                       kgam=0.0):
    """Shear stress [Pa] of the EHL film at one point (module docstring items 3-7).

    p [Pa] pressure carried by the fluid; v [m/s] >= 0 sliding speed; h [m] film thickness; s_in [m]
    distance from the inlet edge along the rolling direction; u [m/s] > 0 entrainment speed; eta0 [Pa s]
    inlet viscosity; lne = ln eta0 + 9.67, z (Roelands); beta [1/K] temperature-viscosity coefficient;
    tau0 [Pa] Eyring stress; tauL0 [Pa], gamL [-] limiting shear stress tau_L0 + gamL p; G_e [Pa]
    effective shear modulus (film in series with the solids; <= 0: no elasticity); k_oil [W/(m K)];
    rck [J^2/(m^4 K^2 s)] = rho c k of the solids (flash temperature); thermal: shear heating on/off;
    kgam [1/K]: relative fall of tau_L with the film's temperature rise (item 7)."""
    if not (v > 0.0 and h > 0.0):
        return 0.0
    cflash = 1.0 / math.sqrt(math.pi * u * rck) if rck > 0.0 else 0.0
    return _point_stress(v, p, s_in, math.log(eta0 / (tau0 * h)), lne, z, h, u, tau0, tauL0, gamL, G_e,
                         h / (8.0 * k_oil), cflash, beta, thermal, kgam)


@hot(inline="always")
def ehl_scratch(xi, wxi, zeta, wzeta):
    """Point quadrature and work space of ehl_ellipse_traction_into and ehl_pair_traction_into [-], from the
    nodes and weights of traction_params.ellipse_quadrature: one column per point (xi[i], zeta[j] for i
    major, j minor), padded to a multiple of 16 columns with zero weight and zero pressure (zeta = 1)
    (LLVM runs its vectorised loop bodies only for trip counts of 16 and more), and the whole repeated
    once (columns npad ... 2 npad - 1), so that the pair kernel holds two contacts side by side; rows
    _XI, _WXI, _ZETA, _WZETA the nodes and weights, the others overwritten by each call. Build once per
    quadrature and thread, reuse for every contact."""
    nx = xi.shape[0]
    ny = zeta.shape[0]
    npt = nx * ny
    npad = (npt + 15) // 16 * 16
    buf = np.empty((_NROWS, 2 * npad))      # the work rows are written before they are read
    for h in range(2):
        o = h * npad
        for n in range(npt, npad):
            buf[_XI, o + n] = 0.0
            buf[_WXI, o + n] = 0.0
            buf[_ZETA, o + n] = 1.0
            buf[_WZETA, o + n] = 0.0
        for i in range(nx):
            for j in range(ny):
                buf[_XI, o + i * ny + j] = xi[i]
                buf[_WXI, o + i * ny + j] = wxi[i]
                buf[_ZETA, o + i * ny + j] = zeta[j]
                buf[_WZETA, o + i * ny + j] = wzeta[j]
    return buf


@hot
def ehl_ellipse_traction(a, b, p_max, D, R_def, Rx, Ry, vs_t, vs_m, w_spin, w_roll_m, w_roll_t, u_roll,
                         params, xi, wxi, zeta, wzeta):
    """ehl_ellipse_traction_into with the quadrature (xi, wxi, zeta, wzeta) of
    traction_params.ellipse_quadrature, as contact_kernels.ellipse_traction takes it (same outputs)."""
    return ehl_ellipse_traction_into(a, b, p_max, D, R_def, Rx, Ry, vs_t, vs_m, w_spin, w_roll_m, w_roll_t,
                                     u_roll, params, ehl_scratch(xi, wxi, zeta, wzeta))


@hot(inline="always")
def _law_params(params):
    """The oil's shear-law parameters as scalars (lubricants.rheology_traction_params): Roelands
    ln(eta_0) + 9.67 and z, beta [1/K], Eyring tau_0 [Pa], limiting shear tau_L0 [Pa] and gamma_L [-], the
    thermal switch, kgam [1/K] (relative fall of the limiting shear stress with the film heating), the
    boundary-friction sliding speed scale v_bl [m/s]."""
    return (params[R_LNE], params[R_Z], params[R_BETA], params[R_TAU0], params[R_TAUL0], params[R_GAML],
            params[R_THERMAL] > 0.5, params[R_KGAM], params[R_VBL])


@hot(inline="always")
def _ehl_contact(a, b, p_max, Rx, u_roll, params):
    """Per-contact values of the EHL traction (film, load sharing, elasticity, heating factors): (u, h, f,
    mubl, ghu, lxh, cfilm, cflash, sgn, fluid, lnU, lnG, lnW) for a loaded contact (p_max, a, b > 0)."""
    u = abs(u_roll)
    umin = params[6]
    if u < umin:
        u = umin
    eta0 = params[R_ETA0]
    alpha = params[R_ALPHA]
    Ep = params[R_EPRIME]
    Q = 2.0 / 3.0 * math.pi * a * b * p_max
    k = a / b
    # Hamrock-Dowson groups (film.hd_groups_nb) as logarithms, shared by the film and the rolling force
    lnU = math.log(eta0 * u / (Ep * Rx))
    lnG = math.log(alpha * Ep)
    lnW = math.log(Q / (Ep * Rx * Rx))
    h = hd_central_film_ln(Rx, lnU, lnG, lnW, k)
    rq = params[R_RQ]
    f = 1.0
    if rq > 0.0:
        f = fluid_fraction(h / rq)
    mubl = params[R_MUBL] * (1.0 - f)
    G = params[R_GFILM]
    gs = params[R_GSC11]
    Ge = 0.0
    if G > 0.0:
        Ge = 1.0 / (1.0 / G + 8.0 * b / (3.0 * h * gs)) if gs > 0.0 else G
    ghu = Ge / (h * u) if Ge > 0.0 else 0.0
    tau0 = params[R_TAU0]
    koil = params[R_KOIL]
    rck = params[R_RCK]
    sgn = 1.0 if u_roll >= 0.0 else -1.0
    fluid = h > 0.0
    lxh = math.log(eta0 / (tau0 * h)) if fluid else 0.0
    cfilm = h / (8.0 * koil)
    cflash = 1.0 / math.sqrt(math.pi * u * rck) if rck > 0.0 else 0.0
    return u, h, f, mubl, ghu, lxh, cfilm, cflash, sgn, fluid, lnU, lnG, lnW


@hot(inline="always")
def _ehl_field(sc, o, npad, a, b, p_max, D, R_def, vs_t, vs_m, w_spin, w_roll_m, w_roll_t, sgn):
    """Pass 1 of the EHL traction over columns o ... o + npad - 1 of sc: sliding field over the ellipse
    (same as contact_kernels.ellipse_traction), position, pressure, shear-force weight, distance from the
    inlet edge."""
    hh = 0.5 * D
    curv = R_def > a and hh > a
    c0 = 0.0
    if curv:
        c0 = math.sqrt(hh * hh - a * a) - math.sqrt(R_def * R_def - a * a)
    pab = p_max * a * b
    for n in range(o, o + npad):
        xn = sc[_XI, n]
        zn = sc[_ZETA, n]
        x = a * xn
        w2 = 1.0 - xn * xn
        w = math.sqrt(w2)
        rho = math.sqrt(R_def * R_def - x * x) + c0 if curv else hh
        d = rho - hh
        y = b * w * zn
        p = p_max * w * math.sqrt(1.0 - zn * zn)                 # local Hertz pressure
        sc[_VT, n] = vs_t - w_spin * x + w_roll_m * d
        sc[_VM, n] = vs_m - w_roll_t * d + w_spin * y
        sc[_XS, n] = x
        sc[_YS, n] = y
        sc[_RH, n] = rho
        sc[_PP, n] = p
        # quadrature weight of the pressure-weighted integral: pab w^2 wxi wzeta = p dA, so the shear force
        # tau dA = tau * (pab w^2 wxi wzeta / p)
        sc[_WQ, n] = pab * w2 * sc[_WXI, n] * sc[_WZETA, n] / p if p > 0.0 else 0.0
        sc[_SI, n] = b * w + sgn * y                               # distance from the inlet edge


@hot(inline="always")
def _ehl_sums(sc, o, npad):
    """Pass 3 of the EHL traction over columns o ... o + npad - 1 of sc: forces, moments and power."""
    Ft = 0.0
    Fm = 0.0
    Mn = 0.0
    Mm = 0.0
    Mt = 0.0
    P = 0.0
    for n in range(o, o + npad):
        r = sc[_DF, n]
        vt = sc[_VT, n]
        vm = sc[_VM, n]
        rho = sc[_RH, n]
        ft = -r * vt
        fm = -r * vm
        Ft += ft
        Fm += fm
        Mn += sc[_YS, n] * fm - sc[_XS, n] * ft
        Mm += rho * ft
        Mt -= rho * fm
        P += r * (vt * vt + vm * vm)
    return Ft, Fm, Mn, Mm, Mt, P


@hot(inline="always")
def _ehl_rolling(a, b, Rx, w_roll_m, f, lnU, lnG, lnW, params):
    """EHL rolling resistance: moment F_R Rx opposing the relative rolling rotation about m [N m] and its
    power [W] (module docstring item 9); (0, 0) when switched off."""
    if params[R_RR] > 0.5 and params[R_ETA0] > 0.0:
        FR = _rolling_force_ln(params[R_EPRIME], Rx, a / b, lnU, lnG, lnW) * f
        if FR > 0.0:
            MR = FR * Rx * math.tanh(w_roll_m * Rx / params[6])
            return MR, MR * w_roll_m
    return 0.0, 0.0


@hot(nrt=False)     # called per contact from the right-hand side: no reference counts of its arrays
def ehl_ellipse_traction_into(a, b, p_max, D, R_def, Rx, Ry, vs_t, vs_m, w_spin, w_roll_m, w_roll_t, u_roll,
                              params, sc):
    """Rheology-based EHL traction on the ball, integrated over the Hertz ellipse (module docstring).

    Same contact geometry, kinematics, quadrature and outputs as contact_kernels.ellipse_traction
    (a along m, b along t; forces on the ball along t and m, moments about the ball centre along n, m, t,
    dissipated power), plus Rx, Ry [m] the effective radii of the contact in and across the rolling
    direction (for the film thickness and the rolling force). params: traction_params.traction_params
    with the oil's rheology (lubricants.rheology_traction_params). The EHL rolling-resistance moment is
    included in M_m and in the power. sc: the quadrature as ehl_scratch (its work rows are overwritten:
    one per thread).

    Three passes over the quadrature points, each vectorised by LLVM over the points (branch-free in the
    point's values, indexed in 2-D: row views would cost a reference count each): their sliding field,
    pressure and weights; the shear law (_point_stress); the sums of forces and moments."""
    if sc.shape[0] != _NROWS:
        raise ValueError("ehl_ellipse_traction_into: sc is not an ehl_scratch array")
    if not (p_max > 0.0 and a > 0.0 and b > 0.0):
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    u, h, f, mubl, ghu, lxh, cfilm, cflash, sgn, fluid, lnU, lnG, lnW = _ehl_contact(a, b, p_max, Rx, u_roll,
                                                                                     params)
    lne, z, beta, tau0, tauL0, gamL, thermal, kgam, vbl = _law_params(params)
    elastic = ghu > 0.0
    npad = sc.shape[1] // 2
    # ---- pass 1: sliding field over the ellipse
    _ehl_field(sc, 0, npad, a, b, p_max, D, R_def, vs_t, vs_m, w_spin, w_roll_m, w_roll_t, sgn)
    # ---- pass 2: shear stress at every point (vectorised)
    for n in range(npad):
        vt = sc[_VT, n]
        vm = sc[_VM, n]
        p = sc[_PP, n]
        v = math.sqrt(vt * vt + vm * vm)
        tau = 0.0
        if fluid:
            tau = _point_stress_g(v, f * p, sc[_SI, n], lxh, lne, z, ghu, elastic, tau0, tauL0, gamL, cfilm,
                                  cflash, beta, thermal, kgam)
        if mubl > 0.0:
            tau += mubl * p * mx.tanh_pos(v / vbl)            # asperities' share, boundary friction
        sc[_DF, n] = tau * sc[_WQ, n] / v if v > 0.0 else 0.0    # shear force per unit sliding speed
    # ---- pass 3: forces, moments and power; the EHL rolling resistance (opposing the rolling about m)
    Ft, Fm, Mn, Mm, Mt, P = _ehl_sums(sc, 0, npad)
    MR, PR = _ehl_rolling(a, b, Rx, w_roll_m, f, lnU, lnG, lnW, params)
    return Ft, Fm, Mn, Mm - MR, Mt, P + PR


@hot(inline="always")
def _contact_rows(sc, n0, n1, lx, gh, cf, cl, f, mb):
    """One contact's values of the shear law (ln(eta_0 / (tau_0 h)), G_e / (h u), film and flash heating
    factors, fluid share, boundary friction) into columns n0 .. n1 - 1 of the pair kernel's scratch."""
    for n in range(n0, n1):
        sc[_LX, n] = lx
        sc[_GH, n] = gh
        sc[_CF, n] = cf
        sc[_CL, n] = cl
        sc[_FF, n] = f
        sc[_MB, n] = mb


@hot(nrt=False)     # called per ball from the right-hand side: no reference counts of its arrays
def ehl_pair_traction_into(a1, b1, p1, R1, Rx1, vt1, vm1, ws1, wm1, wt1, ur1,
                           a2, b2, p2, R2, Rx2, vt2, vm2, ws2, wm2, wt2, ur2, D, params, sc):
    """ehl_ellipse_traction_into for two contacts of one ball (the inner and the outer race contact: a,
    b, p_max, R_def, Rx, vs_t, vs_m, w_spin, w_roll_m, w_roll_t, u_roll of each, ball diameter D, one
    oil) at once: (Ft, Fm, Mn, Mm, Mt, P) of contact 1, then of contact 2. The same arithmetic per point;
    the shear law runs over the points of both contacts in one vectorised loop (twice the trip count
    hides more of its latency), the per-contact values of the law in rows of the scratch. An unloaded
    or dry (h = 0) contact falls back to the single-contact kernel."""
    if sc.shape[0] != _NROWS:
        raise ValueError("ehl_pair_traction_into: sc is not an ehl_scratch array")
    if not (p1 > 0.0 and a1 > 0.0 and b1 > 0.0 and p2 > 0.0 and a2 > 0.0 and b2 > 0.0):
        return (ehl_ellipse_traction_into(a1, b1, p1, D, R1, Rx1, 0.0, vt1, vm1, ws1, wm1, wt1, ur1, params, sc)
                + ehl_ellipse_traction_into(a2, b2, p2, D, R2, Rx2, 0.0, vt2, vm2, ws2, wm2, wt2, ur2, params, sc))
    (u1, h1, f1, mb1, gh1, lx1, cf1, cl1, sg1, fl1, lnU1, lnG1,
     lnW1) = _ehl_contact(a1, b1, p1, Rx1, ur1, params)
    (u2, h2, f2, mb2, gh2, lx2, cf2, cl2, sg2, fl2, lnU2, lnG2,
     lnW2) = _ehl_contact(a2, b2, p2, Rx2, ur2, params)
    if not (fl1 and fl2 and (gh1 > 0.0) == (gh2 > 0.0)):
        return (ehl_ellipse_traction_into(a1, b1, p1, D, R1, Rx1, 0.0, vt1, vm1, ws1, wm1, wt1, ur1, params, sc)
                + ehl_ellipse_traction_into(a2, b2, p2, D, R2, Rx2, 0.0, vt2, vm2, ws2, wm2, wt2, ur2, params, sc))
    lne, z, beta, tau0, tauL0, gamL, thermal, kgam, vbl = _law_params(params)
    elastic = gh1 > 0.0
    boundary = mb1 > 0.0 or mb2 > 0.0
    npad = sc.shape[1] // 2
    # ---- pass 1 per contact, with the contact's values of the shear law in every column
    _ehl_field(sc, 0, npad, a1, b1, p1, D, R1, vt1, vm1, ws1, wm1, wt1, sg1)
    _ehl_field(sc, npad, npad, a2, b2, p2, D, R2, vt2, vm2, ws2, wm2, wt2, sg2)
    _contact_rows(sc, 0, npad, lx1, gh1, cf1, cl1, f1, mb1)
    _contact_rows(sc, npad, 2 * npad, lx2, gh2, cf2, cl2, f2, mb2)
    # ---- pass 2: shear stress at the points of both contacts (one vectorised loop)
    for n in range(2 * npad):
        vt = sc[_VT, n]
        vm = sc[_VM, n]
        p = sc[_PP, n]
        v = math.sqrt(vt * vt + vm * vm)
        tau = _point_stress_g(v, sc[_FF, n] * p, sc[_SI, n], sc[_LX, n], lne, z, sc[_GH, n], elastic, tau0,
                              tauL0, gamL, sc[_CF, n], sc[_CL, n], beta, thermal, kgam)
        if boundary:
            tau += sc[_MB, n] * p * mx.tanh_pos(v / vbl)       # asperities' share, boundary friction
        sc[_DF, n] = tau * sc[_WQ, n] / v if v > 0.0 else 0.0
    # ---- pass 3 per contact
    Ft1, Fm1, Mn1, Mm1, Mt1, P1 = _ehl_sums(sc, 0, npad)
    Ft2, Fm2, Mn2, Mm2, Mt2, P2 = _ehl_sums(sc, npad, npad)
    MR1, PR1 = _ehl_rolling(a1, b1, Rx1, wm1, f1, lnU1, lnG1, lnW1, params)
    MR2, PR2 = _ehl_rolling(a2, b2, Rx2, wm2, f2, lnU2, lnG2, lnW2, params)
    return (Ft1, Fm1, Mn1, Mm1 - MR1, Mt1, P1 + PR1,
            Ft2, Fm2, Mn2, Mm2 - MR2, Mt2, P2 + PR2)


# --------------------------------------------------------------------------------------------------
# Python entry point: traction curve of a disc-machine / ball-on-disc contact
def disc_traction_curve(oil, T, p_max, u, srr, Rx, Ry, E_prime=2.26e11, G_solid=80e9, nu_solid=0.3, Rq=0.0,
                        thermal=True, elastic=True, n=24, mu_bl=None):
    """Traction coefficient [-] of an EHL point contact in rolling with sliding, as measured on twin-disc
    and ball-on-disc machines (no spin; the rolling-resistance moment is not part of the measured shear).

    oil: bearing_core.lubrication.lubricants name; T [K] bulk (inlet) temperature; p_max [Pa] maximum Hertz pressure;
    u [m/s] entrainment (mean rolling) speed; srr [-] slide-to-roll ratio (u1 - u2) / u (scalar or array);
    Rx, Ry [m] effective radii in and across the rolling direction; E_prime [Pa]; G_solid [Pa] shear modulus
    and nu_solid [-] Poisson ratio of the (equal) solids; Rq [m] composite roughness; thermal / elastic:
    shear heating and Maxwell elasticity on/off; n: quadrature points per ellipse axis.
    Returns (mu array, dict of contact data: a, b, Q, h_c, Lambda)."""
    from ..contact.traction_params import ellipse_quadrature, traction_params
    from ..errors import check_range
    from ..contact.fastsim import kalker_coefficients
    from .film import ellipticity_nb
    from . import lubricants as L
    check_range("p_max", p_max, 1e7, 5e9, unit="Pa")
    check_range("u", u, 1e-3, 200.0, unit="m/s")
    # Hertz ellipse from p_max (Hamrock-Brewe: k from the radii, E(k) ~ 1 + (pi/2 - 1) Rx/Ry)
    k = 1.0 if Rx == Ry else (ellipticity_nb(Rx, Ry, 0) if Ry > Rx else 1.0 / ellipticity_nb(Ry, Rx, 0))
    Rr = 1.0 / (1.0 / Rx + 1.0 / Ry)
    Ek = 1.0 + (0.5 * math.pi - 1.0) * (min(Rx, Ry) / max(Rx, Ry))
    # p = 3Q/(2 pi a b), a = (6 k^2 E Q R / (pi E'))^(1/3), b = a / k  ->  Q from p_max
    c = (6.0 * k * k * Ek * Rr / (math.pi * E_prime)) ** (1.0 / 3.0)     # a = c Q^(1/3)
    Q = (p_max * 2.0 * math.pi * c * c / (3.0 * k)) ** 3                  # p = 3 Q k / (2 pi c^2 Q^(2/3))
    a = c * Q ** (1.0 / 3.0)
    b = a / k
    C11 = kalker_coefficients(b / a, nu_solid)[0]
    base = traction_params(u_min=1e-3)
    prm = L.rheology_traction_params(base, oil, T, E_prime, G_solid * C11 if elastic else 0.0, Rq,
                                     mu_bl=L.MU_BOUNDARY if mu_bl is None else mu_bl,
                                     rolling_resistance=False, thermal=thermal)
    if not elastic:
        prm[R_GFILM] = 0.0
    quad = ellipse_quadrature(n, n)
    s_arr = np.atleast_1d(np.asarray(srr, dtype=float))
    mu = np.empty(s_arr.size)
    for i, s in enumerate(s_arr):
        F = ehl_ellipse_traction(a, b, p_max, 2.0 * Rx, 0.0, Rx, Ry, s * u, 0.0, 0.0, 0.0, 0.0, u, prm, *quad)
        mu[i] = -F[0] / Q
    h = hd_central_film_nb(u, prm[R_ETA0], prm[R_ALPHA], Rx, Ry, E_prime, Q, a / b)
    info = {"a": a, "b": b, "Q": Q, "h_c": h, "Lambda": h / Rq if Rq > 0 else math.inf, "C11": C11,
            "G_e": (1.0 / (1.0 / prm[R_GFILM] + 8.0 * b / (3.0 * h * prm[R_GSC11]))
                    if (elastic and prm[R_GFILM] > 0) else 0.0)}
    return (mu if np.ndim(srr) else float(mu[0])), info
