"""Elastohydrodynamic film thickness of a ball-raceway contact (Hamrock-Dowson) and the film parameter.

SI units throughout: m, s, N, Pa, Pa s, 1/Pa, K, W/(m K).

Formulas
--------
[HD77] B. J. Hamrock, D. Dowson, "Isothermal elastohydrodynamic lubrication of point contacts, Part III -
       fully flooded results", J. Lubr. Technol. (ASME) 99 (1977) 264-276; also B. J. Hamrock, D. Dowson,
       *Ball Bearing Lubrication*, Wiley 1981, Ch. 8:
           central  H_c   = h_c   / Rx = 2.69 U^0.67 G^0.53 W^-0.067 (1 - 0.61 exp(-0.73 k))
           minimum  H_min = h_min / Rx = 3.63 U^0.68 G^0.49 W^-0.073 (1 - exp(-0.68 k))
       with U = eta0 u / (E' Rx), G = alpha E', W = Q / (E' Rx^2), u the mean entrainment speed
       (u_a + u_b)/2 [m/s], Rx the effective radius in the rolling (entrainment) direction, Ry across it,
       E' = 2 / ((1 - nu_a^2)/E_a + (1 - nu_b^2)/E_b) and k the ellipticity a/b (a across the rolling
       direction).
[BH77] W. E. Brewe, B. J. Hamrock, J. Lubr. Technol. 99 (1977) 485-487: k = 1.0339 (Ry/Rx)^0.6360
       (HD77 itself used 1.03 (Ry/Rx)^0.64). Seed 003 (Liu et al., Preprints 2026) Eq. 23 writes the
       minimum-film formula above with kappa = 1.0339 (Ry/Rx)^0.636, which is the default here.
[Seed 003] Eq. 23, and Sec. 3.1.1: Lambda = h_min / sqrt(sigma_r^2 + sigma_s^2) (film parameter). The
       seed's oil and surface data are module constants below (SEED003_*).
[G92]  P. K. Gupta, H. S. Cheng, D. Zhu, N. H. Forster, J. B. Schrand, "Viscoelastic effects in
       MIL-L-7808-type lubricant, Part I: analytical formulation", Tribol. Trans. 35 (1992) 269-274:
       inlet shear heating reduces the isothermal film by
           phi_T = (1 - 13.2 (p_h / E') L^0.42) / (1 + 0.213 (1 + 2.23 s^0.83) L^0.64),
           L = eta0 beta_T u^2 / K_f   (thermal loading parameter),
       s = slide-to-roll ratio, beta_T the temperature-viscosity coefficient [1/K], K_f the oil thermal
       conductivity [W/(m K)], p_h the maximum Hertz pressure. We took the coefficients from the form in
       which this fit is usually quoted in later bearing-dynamics papers; they were not checked against the
       1992 paper itself. Optional, off by default.

Notes
-----
* The seed's Eq. 23 names E "the effective elastic modulus" and gives E = 1.12e5 MPa, which is about
  E* = E'/2 for steel (E' = 2.26e11 Pa for 206 GPa / 0.3). With E'/2 in place of E', U and W double and G
  halves: h_min grows by 2^(0.68 - 0.49 - 0.073) = 1.084 (+8.4 %). The functions here take E' as an
  argument; pass SEED003_E_FILM to reproduce the seed as printed (studies/wear_study.py reports both).
* Exponent checks: h_c ~ U^0.67 G^0.53 W^-0.067 and h_min ~ U^0.68 G^0.49 W^-0.073 at fixed k
  (tests/test_film.py). In dimensional terms h ~ u^0.68 eta0^0.68 alpha^0.49 Q^-0.073.
* The numba kernels (``*_nb``) do no input checks; the Python wrapper ``film_thickness`` does.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from ..errors import BearingInputError, check_range

# ---- seed 003 (Liu et al., Preprints 2026, Sec. 3.1.1) data ------------------------------------------
SEED003_ETA0 = 0.04            # Pa s, "eta0 takes 0.04 Pa s"
SEED003_XI = 2.2e-8            # 1/Pa (m^2/N), pressure-viscosity coefficient "xi takes 2.2e-8 m^2/N"
SEED003_E_FILM = 1.12e11       # Pa, "E takes 1.12e5 MPa" (the seed's modulus in U, G, W; see Notes)
SEED003_SIGMA_RACE = 0.18e-6   # m, raceway roughness "sigma_r ... take 0.18 um"
SEED003_SIGMA_BALL = 0.18e-6   # m, ball roughness ("sigma_b take 0.18 um")

ELLIPTICITY_BH77 = 0   # k = 1.0339 (Ry/Rx)^0.636 [BH77], seed 003 Eq. 23 (default)
ELLIPTICITY_HD77 = 1   # k = 1.03 (Ry/Rx)^0.64 [HD77]


# --------------------------------------------------------------------------------------------------
# numba kernels
@njit(cache=True)
def ellipticity_nb(Rx, Ry, form):
    """Ellipticity k = a/b [-] from the effective radii Rx, Ry [m]: form ELLIPTICITY_BH77 (default,
    1.0339 (Ry/Rx)^0.636) or ELLIPTICITY_HD77 (1.03 (Ry/Rx)^0.64)."""
    if form == ELLIPTICITY_HD77:
        return 1.03 * (Ry / Rx) ** 0.64
    return 1.0339 * (Ry / Rx) ** 0.636


@njit(cache=True)
def hd_groups_nb(u, eta0, alpha_pv, Rx, E_prime, Q):
    """Hamrock-Dowson dimensionless groups (U, G, W) [HD77]: U = eta0 |u| / (E' Rx), G = alpha E',
    W = Q / (E' Rx^2). u [m/s] entrainment speed, eta0 [Pa s], alpha_pv [1/Pa], Rx [m], E_prime [Pa],
    Q [N]."""
    U = eta0 * abs(u) / (E_prime * Rx)
    G = alpha_pv * E_prime
    W = Q / (E_prime * Rx * Rx)
    return U, G, W


@njit(cache=True)
def hd_central_film_nb(u, eta0, alpha_pv, Rx, Ry, E_prime, Q, k):
    """Central film thickness h_c [m], Hamrock-Dowson [HD77]:
    h_c = Rx 2.69 U^0.67 G^0.53 W^-0.067 (1 - 0.61 exp(-0.73 k)).

    Arguments (SI): u entrainment speed [m/s] (sign ignored), eta0 [Pa s], alpha_pv [1/Pa], Rx, Ry [m],
    E_prime [Pa], Q [N], k ellipticity [-] (k <= 0: computed from Rx, Ry with the BH77 fit).
    Returns 0 for u = 0 and NaN for Q <= 0 (no contact: the formula does not apply)."""
    if not Q > 0.0:
        return math.nan
    if k <= 0.0:
        k = ellipticity_nb(Rx, Ry, ELLIPTICITY_BH77)
    U, G, W = hd_groups_nb(u, eta0, alpha_pv, Rx, E_prime, Q)
    if U == 0.0:
        return 0.0
    return hd_central_film_ln(Rx, math.log(U), math.log(G), math.log(W), k)


@njit(cache=True)
def hd_central_film_ln(Rx, lnU, lnG, lnW, k):
    """hd_central_film_nb from the natural logarithms of the Hamrock-Dowson groups U, G, W [HD77] (for
    kernels that need the groups' powers more than once): Rx 2.69 exp(0.67 lnU + 0.53 lnG - 0.067 lnW)
    (1 - 0.61 exp(-0.73 k)) [m]; Rx [m], k [-]."""
    return Rx * 2.69 * math.exp(0.67 * lnU + 0.53 * lnG - 0.067 * lnW) * (1.0 - 0.61 * math.exp(-0.73 * k))


@njit(cache=True)
def hd_minimum_film_nb(u, eta0, alpha_pv, Rx, Ry, E_prime, Q, k):
    """Minimum film thickness h_min [m], Hamrock-Dowson [HD77], seed 003 Eq. 23:
    h_min = Rx 3.63 U^0.68 G^0.49 W^-0.073 (1 - exp(-0.68 k)).
    Same arguments and special cases as hd_central_film_nb."""
    if not Q > 0.0:
        return math.nan
    if k <= 0.0:
        k = ellipticity_nb(Rx, Ry, ELLIPTICITY_BH77)
    U, G, W = hd_groups_nb(u, eta0, alpha_pv, Rx, E_prime, Q)
    if U == 0.0:
        return 0.0
    return Rx * 3.63 * U ** 0.68 * G ** 0.49 * W ** -0.073 * (1.0 - math.exp(-0.68 * k))


@njit(cache=True)
def film_parameter_nb(h_min, sigma_1, sigma_2):
    """Film parameter Lambda = h_min / sqrt(sigma_1^2 + sigma_2^2) [-] (seed 003 Sec. 3.1.1); sigma_1,
    sigma_2 [m] rms roughness of the two surfaces. Infinite for perfectly smooth surfaces."""
    s = math.sqrt(sigma_1 * sigma_1 + sigma_2 * sigma_2)
    if s > 0.0:
        return h_min / s
    return math.inf


@njit(cache=True)
def thermal_reduction_nb(u, eta0, beta_T, K_f, p_h, E_prime, srr):
    """Inlet shear heating reduction factor phi_T in (0, 1] [G92]:
    phi_T = (1 - 13.2 (p_h/E') L^0.42) / (1 + 0.213 (1 + 2.23 |srr|^0.83) L^0.64), L = eta0 beta_T u^2 / K_f.
    u [m/s] entrainment speed, eta0 [Pa s], beta_T [1/K] temperature-viscosity coefficient, K_f [W/(m K)]
    oil thermal conductivity, p_h [Pa] maximum Hertz pressure, E_prime [Pa], srr [-] slide-to-roll ratio.
    Clipped to [0.05, 1] (the fit's numerator turns negative far outside its range)."""
    L = eta0 * beta_T * u * u / K_f
    if L <= 0.0:
        return 1.0
    phi = (1.0 - 13.2 * (p_h / E_prime) * L ** 0.42) / (1.0 + 0.213 * (1.0 + 2.23 * abs(srr) ** 0.83) * L ** 0.64)
    if phi > 1.0:
        return 1.0
    if phi < 0.05:
        return 0.05
    return phi


@njit(cache=True)
def film_thickness_nb(u, eta0, alpha_pv, Rx, Ry, E_prime, Q, k, phi_T):
    """(h_c, h_min) [m] of one contact, Hamrock-Dowson times a thermal factor phi_T [-] (1: isothermal).
    Arguments as hd_central_film_nb; the per-contact entry point for the dynamics."""
    hc = hd_central_film_nb(u, eta0, alpha_pv, Rx, Ry, E_prime, Q, k)
    hm = hd_minimum_film_nb(u, eta0, alpha_pv, Rx, Ry, E_prime, Q, k)
    return phi_T * hc, phi_T * hm


# --------------------------------------------------------------------------------------------------
# Python wrapper
@dataclass(frozen=True)
class FilmResult:
    """Film of one contact (or arrays of contacts): h_c, h_min [m]; U, G, W, k [-] (Hamrock-Dowson groups);
    phi_T [-] thermal factor applied (1 = isothermal); Lambda [-] film parameter (NaN if no roughness
    was given)."""

    h_c: np.ndarray
    h_min: np.ndarray
    U: np.ndarray
    G: np.ndarray
    W: np.ndarray
    k: np.ndarray
    phi_T: np.ndarray
    Lambda: np.ndarray


@dataclass(frozen=True)
class ThermalOptions:
    """Inputs of the inlet-heating factor [G92]: beta_T [1/K] temperature-viscosity coefficient,
    K_f [W/(m K)] oil thermal conductivity, srr [-] slide-to-roll ratio, p_h [Pa] maximum Hertz pressure
    (None: computed from Q, Rx, Ry, E' with the Hertz point-contact formulas of Hamrock & Dowson)."""

    beta_T: float = 0.03
    K_f: float = 0.14
    srr: float = 0.0
    p_h: float | None = None


def _check_array(name, v, lo, lo_incl, unit):
    a = np.asarray(v, dtype=float)
    for x in np.atleast_1d(a).ravel():
        check_range(name, x, lo, None, lo_incl=lo_incl, unit=unit)
    return a


def _hertz_pmax(Q, Rx, Ry, E_prime, k):
    """Maximum Hertz pressure [Pa] from the Hamrock-Brewe simplified solution (HB83, as in hertz.py):
    E(k) ~ 1 + (pi/2 - 1) Rx/Ry, a = (6 k^2 E Q R / (pi E'))^(1/3), b = a/k, p = 3Q/(2 pi a b)."""
    R = 1.0 / (1.0 / Rx + 1.0 / Ry)
    Ek = 1.0 + (0.5 * math.pi - 1.0) * Rx / Ry
    a = (6.0 * k * k * Ek * Q * R / (math.pi * E_prime)) ** (1.0 / 3.0)
    b = a / k
    return 1.5 * Q / (math.pi * a * b)


def film_thickness(u, eta0, alpha_pv, Rx, Ry, E_prime, Q, k=None, sigma=None,
                   ellipticity: str = "bh77", thermal: ThermalOptions | None = None) -> FilmResult:
    """Hamrock-Dowson central and minimum film thickness [HD77] of ball-raceway contacts (scalars or arrays
    that broadcast).

    u [m/s] entrainment speed (mean of the two surface speeds relative to the contact), eta0 [Pa s]
    inlet viscosity, alpha_pv [1/Pa] pressure-viscosity coefficient, Rx, Ry [m] effective radii (rolling
    direction, across), E_prime [Pa] E' = 2/((1-nu1^2)/E1 + (1-nu2^2)/E2), Q [N] contact load; k [-] the
    ellipticity (None: the ``ellipticity`` fit, 'bh77' = seed 003's 1.0339 (Ry/Rx)^0.636 or 'hd77' =
    1.03 (Ry/Rx)^0.64); sigma = (sigma_1, sigma_2) [m] rms roughness for Lambda; thermal: ThermalOptions
    to apply Gupta's inlet-heating factor [G92] (default None = isothermal).
    Raises BearingInputError (parameter, value, allowed range) on bad input."""
    u = np.asarray(u, dtype=float)
    if not np.all(np.isfinite(u)):
        raise BearingInputError("u", u.tolist(), "finite entrainment speed [m/s]")
    eta0 = check_range("eta0", eta0, 0.0, None, lo_incl=False, unit="Pa s")
    alpha_pv = check_range("alpha_pv", alpha_pv, 0.0, 1e-6, unit="1/Pa")
    Rx = _check_array("Rx", Rx, 0.0, False, "m")
    Ry = _check_array("Ry", Ry, 0.0, False, "m")
    E_prime = check_range("E_prime", E_prime, 0.0, None, lo_incl=False, unit="Pa")
    Q = _check_array("Q", Q, 0.0, False, "N")
    form = {"bh77": ELLIPTICITY_BH77, "hd77": ELLIPTICITY_HD77}.get(str(ellipticity).lower())
    if form is None:
        raise BearingInputError("ellipticity", ellipticity, "'bh77' | 'hd77'")
    if thermal is not None:
        check_range("thermal.beta_T", thermal.beta_T, 0.0, None, unit="1/K")
        check_range("thermal.K_f", thermal.K_f, 0.0, None, lo_incl=False, unit="W/(m K)")
        check_range("thermal.srr", thermal.srr, -10.0, 10.0)
        if thermal.p_h is not None:
            check_range("thermal.p_h", thermal.p_h, 0.0, None, lo_incl=False, unit="Pa")
    u, Rx, Ry, Q = np.broadcast_arrays(u, Rx, Ry, Q)
    if k is None:
        kk = np.vectorize(lambda rx, ry: ellipticity_nb(rx, ry, form))(Rx, Ry) if Rx.ndim else \
            np.asarray(ellipticity_nb(float(Rx), float(Ry), form))
    else:
        kk = np.broadcast_to(_check_array("k", k, 0.0, False, ""), u.shape).astype(float)
    kk = np.asarray(kk, dtype=float)
    U = eta0 * np.abs(u) / (E_prime * Rx)
    G = alpha_pv * E_prime * np.ones_like(U)
    W = Q / (E_prime * Rx * Rx)
    hc = np.empty(u.shape)
    hm = np.empty(u.shape)
    phi = np.ones(u.shape)
    for idx in np.ndindex(u.shape):
        hc[idx] = hd_central_film_nb(float(u[idx]), eta0, alpha_pv, float(Rx[idx]), float(Ry[idx]), E_prime,
                                     float(Q[idx]), float(kk[idx]))
        hm[idx] = hd_minimum_film_nb(float(u[idx]), eta0, alpha_pv, float(Rx[idx]), float(Ry[idx]), E_prime,
                                     float(Q[idx]), float(kk[idx]))
        if thermal is not None:
            ph = thermal.p_h if thermal.p_h is not None else _hertz_pmax(float(Q[idx]), float(Rx[idx]),
                                                                        float(Ry[idx]), E_prime, float(kk[idx]))
            phi[idx] = thermal_reduction_nb(float(u[idx]), eta0, thermal.beta_T, thermal.K_f, ph, E_prime,
                                            thermal.srr)
    hc *= phi
    hm *= phi
    if sigma is None:
        lam = np.full(u.shape, np.nan)
    else:
        s1, s2 = (float(s) for s in sigma)
        check_range("sigma_1", s1, 0.0, None, unit="m")
        check_range("sigma_2", s2, 0.0, None, unit="m")
        lam = hm / math.hypot(s1, s2) if (s1 > 0 or s2 > 0) else np.full(u.shape, np.inf)
    sq = (lambda x: float(x)) if u.ndim == 0 else (lambda x: x)
    return FilmResult(h_c=sq(hc), h_min=sq(hm), U=sq(U), G=sq(G), W=sq(W), k=sq(kk), phi_T=sq(phi),
                      Lambda=sq(lam))


def film_parameter(h_min, sigma_1, sigma_2):
    """Lambda = h_min / sqrt(sigma_1^2 + sigma_2^2) [-] (seed 003 Sec. 3.1.1); h_min, sigma [m]."""
    check_range("sigma_1", sigma_1, 0.0, None, unit="m")
    check_range("sigma_2", sigma_2, 0.0, None, unit="m")
    s = math.hypot(float(sigma_1), float(sigma_2))
    if s == 0.0:
        raise BearingInputError("sigma", (sigma_1, sigma_2), "at least one roughness > 0 m")
    return np.asarray(h_min, dtype=float) / s
