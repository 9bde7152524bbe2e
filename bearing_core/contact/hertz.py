"""Hertz point contact of a ball on a raceway (SI units: m, N, Pa, rad).

Sources
-------
[HK]  T. A. Harris, M. N. Kotzalas, *Rolling Bearing Analysis*, 5th ed., Vol. 1 "Essential Concepts
      of Bearing Technology", CRC Press 2007: Ch. 2 (ball-raceway curvatures, curvature sum
      sum_rho and curvature difference F(rho)) and Ch. 6 (Hertz contact stress and deformation,
      dimensionless a*, b*, delta*).
[HD]  B. J. Hamrock, D. Dowson, *Ball Bearing Lubrication - The Elastohydrodynamics of Elliptical
      Contacts*, Wiley 1981, Ch. 3 (also NASA TM-81691 "Ball Bearing Mechanics", 1981): effective radii
      Rx, Ry (Eqs. 3.x), reduced modulus E' = 2/((1-nu_a^2)/E_a + (1-nu_b^2)/E_b), exact Hertz
      ellipticity k, semi-axes and mutual approach.
[BH77] W. E. Brewe, B. J. Hamrock, "Simplified solution for elliptical-contact deformation between
      two elastic solids", J. Lubr. Technol. (ASME) 99 (1977) 485-487: curve fits
      k = 1.0339 (Ry/Rx)^0.6360, E = 1.0003 + 0.5968 Rx/Ry, K = 1.5277 + 0.6023 ln(Ry/Rx).
[HB83] B. J. Hamrock, W. E. Brewe, "Simplified solution for stresses and deformations",
      J. Lubr. Technol. 105 (1983) 171-177; B. J. Hamrock, *Fundamentals of Fluid Film Lubrication*,
      McGraw-Hill 1994 (simplified elliptical-contact solutions): k = alpha_r^(2/pi), E = 1 + (pi/2 - 1)/alpha_r,
      K = pi/2 + (pi/2 - 1) ln(alpha_r), alpha_r = Ry/Rx.
[J]   K. L. Johnson, *Contact Mechanics*, CUP 1985, Eqs. 4.22-4.23 (sphere contact) and Sec. 4.2.
[TG]  S. P. Timoshenko, J. N. Goodier, *Theory of Elasticity*, 3rd ed., McGraw-Hill 1970, Sec. 140.
[seed] Lubricants 2025, 13(5), 218, Sec. 3.1: contact parameters interpolated over contact angle.

Conventions
-----------
x = rolling direction, y = across the groove (transverse).  Rx <= Ry for every ball-raceway contact
of a real bearing, so the semi-major axis a lies along y and the ellipticity k = a/b >= 1.
Elliptic integrals: K(e), E(e) complete integrals of the first/second kind with eccentricity
e^2 = 1 - 1/k^2.  scipy.special.ellipk/ellipe take the *parameter* m = e^2 (not the modulus e);
near k -> infinity the complementary parameter p = 1 - m = 1/k^2 is passed to scipy.special.ellipkm1
to keep full precision.

Exact Hertz relations used (with R = 1/sum_rho, E' = reduced modulus) [HD, Ch. 3]:
    F_rho = ((k^2 + 1) E - 2 K) / ((k^2 - 1) E)                       (solved for k)
    a     = (6 k^2 E Q R / (pi E'))^(1/3)        semi-major axis (across the groove)
    b     = (6 E Q R / (pi k E'))^(1/3)          semi-minor axis (rolling direction)
    delta = K (9/(2 E R) (Q/(pi k E'))^2)^(1/3)  mutual approach of the two bodies
    p_max = 3 Q / (2 pi a b)
Equivalent Harris form [HK Ch. 6]: a = a* (3Q/(E' sum_rho))^(1/3), b = b* (..)^(1/3),
delta = delta* (3Q/(E' sum_rho))^(2/3) sum_rho/2 with a* = (2k^2E/pi)^(1/3), b* = (2E/(pi k))^(1/3),
delta* = (2K/pi) (pi/(2k^2E))^(1/3)  (checked against the form above in tests/test_hertz.py).

Fast forms and their measured accuracy
--------------------------------------
Measured against the exact solution over ball-raceway contacts of real bearings (conformity
f = 0.51..0.58, D/dm = 0.1..0.3, contact angle 0..90 deg in 1 deg steps, inner and outer race, i.e.
alpha_r = Ry/Rx = 5.6..73), maximum relative error (script: tests/test_hertz.py::test_fast_forms_error_map):

=================  =======  =======  =======  =======  =======  ================================
form               a        b        delta    p_max    K_load   meets 0.5 %?
=================  =======  =======  =======  =======  =======  ================================
APPROX_BH77        3.2 %    1.5 %    2.9 %    1.6 %    4.5 %    no  (worst at alpha_r = 73)
APPROX_HB83        2.7 %    1.2 %    3.1 %    1.6 %    4.8 %    no
APPROX_NEWTON      3.3e-5   1.7e-5   2.1e-5   1.6e-5   3.1e-5   yes (default)
=================  =======  =======  =======  =======  =======  ================================

* ``APPROX_BH77``  Brewe & Hamrock 1977 fits [BH77] (kept for reference / comparison with papers).
* ``APPROX_HB83``  Hamrock & Brewe 1983 fits [HB83] (exact at alpha_r = 1, worse at alpha_r 2..10).
* ``APPROX_NEWTON`` BH77 start + ONE Newton step in ln k on the exact relation
  alpha_r = (k^2 E - K)/(K - E), with K and E from the arithmetic-geometric mean (5-6 iterations);
  closed form, no iteration to convergence, runs in numba kernels.  Max error 3.3e-5 relative in
  the bearing range and < 1e-3 for any 1 <= alpha_r <= 1e4.  Use it in kernels when no table exists.
The tabulated exact solution (build_hertz_table + hertz_lookup, n = 181, linear in alpha) is the
fastest form; its interpolation error is given in build_hertz_table.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numba import njit
from scipy import optimize, special

from ..errors import BearingInputError, check_range

__all__ = [
    "contact_curvature", "reduced_modulus", "HertzConstants", "hertz_exact", "hertz_approx",
    "HertzTable", "build_hertz_table", "hertz_lookup", "hertz_lookup_alpha", "hertz_approx_nb",
    "hertz_approx_constants_nb", "ellipke_agm", "APPROX_BH77", "APPROX_HB83", "APPROX_NEWTON",
    "APPROX_MAX_ERROR", "TABLE_ROWS",
]

HALF_PI = 0.5 * math.pi

# Fast-form selectors (ints so that numba kernels can take them).
APPROX_BH77 = 0     # Brewe & Hamrock 1977 curve fits [BH77]
APPROX_HB83 = 1     # Hamrock & Brewe 1983 / Hamrock 1994 fits [HB83]
APPROX_NEWTON = 2   # BH77 start + one Newton step on the exact relation (default)
_APPROX_NAMES = {"bh77": APPROX_BH77, "brewe_hamrock_1977": APPROX_BH77,
                 "hb83": APPROX_HB83, "hamrock_brewe_1983": APPROX_HB83,
                 "newton": APPROX_NEWTON}

# Measured max relative error over the bearing range of the module docstring (max over a, b, delta,
# p_max, K_load; re-measured by tests/test_hertz.py::test_fast_forms_error_map).
APPROX_MAX_ERROR = {APPROX_BH77: 0.045, APPROX_HB83: 0.048, APPROX_NEWTON: 3.3e-5}


# --------------------------------------------------------------------------------------------------
# geometry
# --------------------------------------------------------------------------------------------------
@njit(cache=True)
def _contact_curvature_nb(D, dm, f, alpha, inner):
    """(Rx, Ry, sum_rho, F_rho) of a ball-raceway contact; no input checks (see contact_curvature).

    [HD Ch. 2-3]: gamma = D cos(alpha)/dm; inner: Rx = D(1-gamma)/2, outer: Rx = D(1+gamma)/2;
    Ry = f D/(2f-1).  sum_rho = 1/Rx + 1/Ry equals Harris' 4/D - 1/(fD) +- 2 gamma/(D(1 -+ gamma))
    [HK Ch. 2]; F_rho = (1/Rx - 1/Ry)/sum_rho is Harris' curvature difference F(rho).
    """
    gamma = D * math.cos(alpha) / dm
    if inner:
        Rx = 0.5 * D * (1.0 - gamma)
    else:
        Rx = 0.5 * D * (1.0 + gamma)
    Ry = f * D / (2.0 * f - 1.0)
    cx = 1.0 / Rx
    cy = 1.0 / Ry
    sum_rho = cx + cy
    F_rho = (cx - cy) / sum_rho
    return Rx, Ry, sum_rho, F_rho


def _check_geometry(D, dm, f, alpha):
    check_range("D", D, 0.0, None, lo_incl=False, unit="m")
    check_range("dm", dm, 0.0, None, lo_incl=False, unit="m")
    if not dm > D:
        raise BearingInputError("dm", dm, f"dm > D = {D!r} m", "pitch diameter must exceed ball diameter")
    check_range("f", f, 0.5, None, lo_incl=False)
    check_range("alpha", alpha, 0.0, HALF_PI, unit="rad")


def contact_curvature(D, dm, f, alpha, inner):
    """Effective radii and curvature sum/difference of a ball-raceway contact.

    D ball diameter [m], dm pitch diameter [m], f = r/D groove conformity (> 0.5), alpha contact
    angle [rad] in [0, pi/2], inner=True for the inner raceway.  Returns (Rx, Ry, sum_rho, F_rho):
    Rx [m] effective radius in the rolling direction, Ry [m] across the groove, sum_rho = 1/Rx + 1/Ry
    [1/m], F_rho = (1/Rx - 1/Ry)/sum_rho [-] (Harris curvature difference).  [HK Ch. 2], [HD Ch. 2].
    """
    _check_geometry(D, dm, f, alpha)
    Rx, Ry, s, F = _contact_curvature_nb(float(D), float(dm), float(f), float(alpha), bool(inner))
    return float(Rx), float(Ry), float(s), float(F)


@njit(cache=True)
def _reduced_modulus_nb(E1, nu1, E2, nu2):
    return 2.0 / ((1.0 - nu1 * nu1) / E1 + (1.0 - nu2 * nu2) / E2)


def reduced_modulus(E1, nu1, E2, nu2):
    """E' = 2 / ((1-nu1^2)/E1 + (1-nu2^2)/E2) [Pa] (Hamrock & Dowson convention [HD]; E' = 2 E*)."""
    check_range("E1", E1, 0.0, None, lo_incl=False, unit="Pa")
    check_range("nu1", nu1, -1.0, 0.5, lo_incl=False, hi_incl=False)
    check_range("E2", E2, 0.0, None, lo_incl=False, unit="Pa")
    check_range("nu2", nu2, -1.0, 0.5, lo_incl=False, hi_incl=False)
    return float(_reduced_modulus_nb(float(E1), float(nu1), float(E2), float(nu2)))


# --------------------------------------------------------------------------------------------------
# elliptic integrals and the k(F_rho) relation
# --------------------------------------------------------------------------------------------------
@njit(cache=True)
def ellipke_agm(k):
    """(K, E) complete elliptic integrals for ellipticity k >= 1 (e^2 = 1 - 1/k^2), numba.

    Arithmetic-geometric mean (Abramowitz & Stegun 17.6): a0 = 1, b0 = sqrt(1 - e^2) = 1/k,
    c0^2 = e^2; K = pi/(2 a_N), E = K (1 - sum_n 2^(n-1) c_n^2).  Converges quadratically
    (<= 6 iterations to machine precision for k <= 1e4).
    """
    m = (k - 1.0) * (k + 1.0) / (k * k)   # e^2 without cancellation
    a = 1.0
    b = 1.0 / k
    s = 0.5 * m
    pw = 0.5
    for _ in range(40):
        c = 0.5 * (a - b)
        an = 0.5 * (a + b)
        b = math.sqrt(a * b)
        a = an
        pw *= 2.0
        s += pw * c * c
        if abs(c) < 1e-16 * a:
            break
    K = HALF_PI / a
    return K, K * (1.0 - s)


@njit(cache=True)
def _F_of_k_nb(k, K, E):
    """Curvature difference belonging to ellipticity k (exact Hertz relation [HD Eq. 3.x]).

    Written with m = e^2 = (k^2-1)/k^2 as F = ((2-m) E - 2 (1-m) K)/(m E); for m < 1e-4 the
    series F = 3m/8 + 3m^2/16 avoids the cancellation of the two O(1) terms.
    """
    m = (k - 1.0) * (k + 1.0) / (k * k)
    if m < 1e-4:
        return 0.375 * m + 0.1875 * m * m
    return ((2.0 - m) * E - 2.0 * (1.0 - m) * K) / (m * E)


@njit(cache=True)
def _newton_k_step_nb(k, alpha_r):
    """One Newton step in t = ln k on G(t) = ln(alpha_r(k)) - ln(alpha_r_target).

    The exact Hertz relation written as alpha_r = Ry/Rx = (k^2 E - K)/(K - E) [HD Ch. 3] (equivalent to
    F_rho(k) with F_rho = (alpha_r - 1)/(alpha_r + 1)); ln alpha_r is nearly linear in ln k, so one
    step from the BH77 fit lands very close to the root.  Derivatives (m = e^2 = 1 - p, p = 1/k^2,
    A&S 17.3.11-12): dK/dm = (E - p K)/(2 m p), dE/dm = (E - K)/(2 m), dm/dt = 2/k^2.
    Returns (k_new, K(k_new), E(k_new)).
    """
    m = (k - 1.0) * (k + 1.0) / (k * k)
    if m < 1e-4:
        # near-circular contact: F ~ 3m/8 + 3m^2/16 -> m = 8F/3 (1 - 4F/3), k = 1/sqrt(1-m)
        Ft = (alpha_r - 1.0) / (alpha_r + 1.0)
        mt = 8.0 * Ft / 3.0 * (1.0 - 4.0 * Ft / 3.0)
        kn = 1.0 / math.sqrt(1.0 - mt)
        K2, E2 = ellipke_agm(kn)
        return kn, K2, E2
    K, E = ellipke_agm(k)
    p = 1.0 - m
    k2 = k * k
    dK = (E - p * K) / (2.0 * m * p)
    dE = (E - K) / (2.0 * m)
    u = k2 * E - K                     # numerator of alpha_r
    v = K - E                          # denominator of alpha_r
    du = E / (p * p) + k2 * dE - dK    # d/dm (k^2 = 1/p)
    dv = dK - dE
    G = math.log(u / v) - math.log(alpha_r)
    dG = (du / u - dv / v) * 2.0 / k2  # d/dt
    kn = k * math.exp(-G / dG)
    if kn < 1.0:
        kn = 1.0
    K2, E2 = ellipke_agm(kn)
    return kn, K2, E2


@njit(cache=True)
def hertz_approx_constants_nb(Rx, Ry, E_red, method):
    """Fast Hertz constants (k, ell_E, ell_K, a_coef, b_coef, K_load) for Ry >= Rx > 0, numba.

    method: APPROX_BH77 (0) Brewe & Hamrock 1977, APPROX_HB83 (1) Hamrock & Brewe 1983,
    APPROX_NEWTON (2, recommended: max 3.3e-5 relative error over the bearing range) BH77 start +
    one Newton step with AGM elliptic integrals.  a = a_coef Q^(1/3), b = b_coef Q^(1/3),
    Q = K_load delta^1.5.  No input checks (see hertz_approx for the checked Python form).
    """
    ar = Ry / Rx
    if method == 1:
        k = ar ** (2.0 / math.pi)
        E = 1.0 + (HALF_PI - 1.0) / ar
        K = HALF_PI + (HALF_PI - 1.0) * math.log(ar)
    else:
        k = 1.0339 * ar ** 0.6360
        E = 1.0003 + 0.5968 / ar
        K = 1.5277 + 0.6023 * math.log(ar)
        if method == 2:
            if k < 1.0:
                k = 1.0
            k, K, E = _newton_k_step_nb(k, ar)
    R = Rx * Ry / (Rx + Ry)
    return _constants_from_kEK_nb(k, E, K, R, E_red)


@njit(cache=True)
def _constants_from_kEK_nb(k, E, K, R, E_red):
    """(k, E, K, a_coef, b_coef, K_load) from ellipticity, elliptic integrals, R = 1/sum_rho, E'."""
    a_coef = (6.0 * k * k * E * R / (math.pi * E_red)) ** (1.0 / 3.0)
    b_coef = (6.0 * E * R / (math.pi * k * E_red)) ** (1.0 / 3.0)
    # delta = d_coef Q^(2/3),  d_coef = K (9/(2 E R))^(1/3) (pi k E')^(-2/3)
    d_coef = K * (4.5 / (E * R)) ** (1.0 / 3.0) * (math.pi * k * E_red) ** (-2.0 / 3.0)
    K_load = d_coef ** -1.5
    return k, E, K, a_coef, b_coef, K_load


@njit(cache=True)
def _contact_from_coefs_nb(K_load, a_coef, b_coef, Q):
    """(K_load, a, b, delta, p_max) for load Q [N]; Q <= 0 (or NaN) -> zeros except K_load."""
    if not Q > 0.0:
        return K_load, 0.0, 0.0, 0.0, 0.0
    q3 = Q ** (1.0 / 3.0)
    a = a_coef * q3
    b = b_coef * q3
    delta = (Q / K_load) ** (2.0 / 3.0)
    p = 1.5 * Q / (math.pi * a * b)
    return K_load, a, b, delta, p


@njit(cache=True)
def hertz_approx_nb(Rx, Ry, E_red, Q, method):
    """(K_load, a, b, delta, p_max) of a contact with radii Rx <= Ry, modulus E', load Q; numba.

    See hertz_approx_constants_nb for ``method``; Q <= 0 gives a = b = delta = p_max = 0.
    """
    k, E, K, ac, bc, KL = hertz_approx_constants_nb(Rx, Ry, E_red, method)
    return _contact_from_coefs_nb(KL, ac, bc, Q)


# --------------------------------------------------------------------------------------------------
# exact solution (scipy) and the constants container
# --------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class HertzConstants:
    """Load-independent Hertz constants of one contact.

    k = a/b >= 1 ellipticity, ell_K / ell_E complete elliptic integrals at e^2 = 1 - 1/k^2,
    a = a_coef Q^(1/3) [m] (semi-major, across the groove), b = b_coef Q^(1/3) [m] (semi-minor,
    rolling direction), Q = K_load delta^1.5 (K_load [N/m^1.5], delta mutual approach [m]).
    """

    k: float
    ell_K: float
    ell_E: float
    a_coef: float
    b_coef: float
    K_load: float
    sum_rho: float = float("nan")
    F_rho: float = float("nan")
    E_red: float = float("nan")

    def _q(self, Q):
        q = np.asarray(Q, dtype=float)
        if np.any(np.isnan(q)):
            raise BearingInputError("Q", Q, "a real load [N] (Q <= 0 means no contact)", "NaN")
        return np.where(q > 0.0, q, 0.0)

    @staticmethod
    def _out(x):
        return float(x) if np.ndim(x) == 0 else x

    def a(self, Q):
        """Semi-major axis [m] for load Q [N] (array or scalar); 0 for Q <= 0."""
        return self._out(self.a_coef * np.cbrt(self._q(Q)))

    def b(self, Q):
        """Semi-minor axis [m] for load Q [N]; 0 for Q <= 0."""
        return self._out(self.b_coef * np.cbrt(self._q(Q)))

    def delta(self, Q):
        """Mutual approach [m] for load Q [N]: delta = (Q/K_load)^(2/3); 0 for Q <= 0."""
        return self._out((self._q(Q) / self.K_load) ** (2.0 / 3.0))

    def p_max(self, Q):
        """Maximum Hertz pressure 3Q/(2 pi a b) [Pa]; 0 for Q <= 0."""
        q = self._q(Q)
        ab = self.a_coef * self.b_coef * np.cbrt(q) ** 2
        return self._out(np.where(q > 0.0, 1.5 * q / (math.pi * np.where(q > 0.0, ab, 1.0)), 0.0))

    def contact(self, Q):
        """(a, b, delta, p_max) for load Q [N]."""
        return self.a(Q), self.b(Q), self.delta(Q), self.p_max(Q)


def _F_of_k_scipy(k):
    """Exact F_rho(k) with scipy (parameter convention m = e^2; ellipkm1 takes p = 1 - m = 1/k^2)."""
    p = 1.0 / (k * k)
    m = (k - 1.0) * (k + 1.0) / (k * k)
    if m < 1e-4:
        return 0.375 * m + 0.1875 * m * m
    K = special.ellipkm1(p)
    E = special.ellipe(m)
    return ((2.0 - m) * E - 2.0 * p * K) / (m * E)


def _k_exact(F_rho):
    """Ellipticity k >= 1 solving F_rho = ((k^2+1)E - 2K)/((k^2-1)E) (brentq in ln k)."""
    if F_rho < 1e-10:
        # k -> 1 limit: F = 3m/8 + 3m^2/16 + O(m^3)  ->  m = 8F/3 (1 - 4F/3)
        m = 8.0 * F_rho / 3.0 * (1.0 - 4.0 * F_rho / 3.0)
        return 1.0 / math.sqrt(1.0 - m)
    hi = 2.0
    while _F_of_k_scipy(hi) < F_rho:
        hi *= 2.0
        if hi > 1e12:
            raise BearingInputError("F_rho", F_rho, "0 <= F_rho < 1", "ellipticity beyond 1e12")
    lo = 1.0
    g = lambda t: _F_of_k_scipy(math.exp(t)) - F_rho  # noqa: E731
    t = optimize.brentq(g, math.log(lo), math.log(hi), xtol=1e-15, rtol=1e-15, maxiter=200)
    return math.exp(t)


def hertz_exact(sum_rho, F_rho, E_red):
    """Exact Hertz constants for curvature sum [1/m], curvature difference [-] and E' [Pa].

    k from the exact relation F_rho = ((k^2+1) E(e) - 2 K(e))/((k^2-1) E(e)), e^2 = 1 - 1/k^2 [HD Ch. 3],
    [HK Ch. 6], solved by brentq with scipy.special elliptic integrals; F_rho -> 0 gives k -> 1 (sphere).
    Returns HertzConstants (a = a_coef Q^(1/3), b = b_coef Q^(1/3), Q = K_load delta^1.5).
    """
    check_range("sum_rho", sum_rho, 0.0, None, lo_incl=False, unit="1/m")
    check_range("F_rho", F_rho, 0.0, 1.0, hi_incl=False)
    check_range("E_red", E_red, 0.0, None, lo_incl=False, unit="Pa")
    F_rho = float(F_rho)
    k = _k_exact(F_rho)
    m = (k - 1.0) * (k + 1.0) / (k * k)
    K = float(special.ellipkm1(1.0 / (k * k)))
    E = float(special.ellipe(m))
    R = 1.0 / float(sum_rho)
    k, E, K, ac, bc, KL = _constants_from_kEK_nb(k, E, K, R, float(E_red))
    return HertzConstants(k=float(k), ell_K=float(K), ell_E=float(E), a_coef=float(ac), b_coef=float(bc),
                          K_load=float(KL), sum_rho=float(sum_rho), F_rho=F_rho, E_red=float(E_red))


def _method_id(method):
    if isinstance(method, str):
        key = method.strip().lower()
        if key not in _APPROX_NAMES:
            raise BearingInputError("method", method, "one of " + ", ".join(sorted(_APPROX_NAMES)))
        return _APPROX_NAMES[key]
    if method not in (APPROX_BH77, APPROX_HB83, APPROX_NEWTON):
        raise BearingInputError("method", method, "APPROX_BH77 (0), APPROX_HB83 (1), APPROX_NEWTON (2)")
    return int(method)


def hertz_approx(Rx, Ry, E_red, method=APPROX_NEWTON):
    """Fast Hertz constants from Rx <= Ry [m] and E' [Pa] (see module docstring for accuracy).

    method: APPROX_NEWTON / "newton" (default, meets 0.5 %: measured max error 3.3e-5 relative),
    APPROX_BH77 / "bh77" Brewe & Hamrock 1977 fits k = 1.0339 (Ry/Rx)^0.6360,
    E = 1.0003 + 0.5968 Rx/Ry, K = 1.5277 + 0.6023 ln(Ry/Rx) (measured max error 4.5 % on K_load,
    3.2 % on a, 2.9 % on delta: misses 0.5 %), APPROX_HB83 / "hb83" Hamrock & Brewe 1983
    k = (Ry/Rx)^(2/pi), E = 1 + (pi/2-1) Rx/Ry, K = pi/2 + (pi/2-1) ln(Ry/Rx) (measured max error
    4.8 % on K_load, 3.1 % on delta: misses 0.5 %).  Errors: bearing range of the module docstring.
    """
    check_range("Rx", Rx, 0.0, None, lo_incl=False, unit="m")
    check_range("Ry", Ry, 0.0, None, lo_incl=False, unit="m")
    check_range("E_red", E_red, 0.0, None, lo_incl=False, unit="Pa")
    if Ry < Rx:
        raise BearingInputError("Ry", Ry, f"Ry >= Rx = {Rx!r} m (semi-major axis across the groove)")
    mid = _method_id(method)
    k, E, K, ac, bc, KL = hertz_approx_constants_nb(float(Rx), float(Ry), float(E_red), mid)
    s = 1.0 / Rx + 1.0 / Ry
    return HertzConstants(k=float(k), ell_K=float(K), ell_E=float(E), a_coef=float(ac), b_coef=float(bc),
                          K_load=float(KL), sum_rho=s, F_rho=(1.0 / Rx - 1.0 / Ry) / s, E_red=float(E_red))


# --------------------------------------------------------------------------------------------------
# tables over contact angle [seed Sec. 3.1]
# --------------------------------------------------------------------------------------------------
# Row layout of HertzTable.inner / HertzTable.outer (shape (N_ROWS, n), C-contiguous float64):
ROW_K_LOAD, ROW_A_COEF, ROW_B_COEF, ROW_K, ROW_ELL_E, ROW_ELL_K, ROW_RX, ROW_RY = range(8)
TABLE_ROWS = ("K_load", "a_coef", "b_coef", "k", "ell_E", "ell_K", "Rx", "Ry")
N_ROWS = len(TABLE_ROWS)


class HertzTable(NamedTuple):
    """Exact Hertz constants on a uniform contact-angle grid alpha_j = alpha0 + j*dalpha, j = 0..n-1.

    inner, outer: float64 arrays of shape (8, n), rows TABLE_ROWS = (K_load [N/m^1.5], a_coef,
    b_coef [m/N^(1/3)], k, ell_E, ell_K [-], Rx, Ry [m]).  Only floats and arrays, so the fields can
    be handed to numba kernels, e.g. hertz_lookup(tab.inner, tab.alpha0, tab.dalpha, alpha, Q).
    """

    alpha: np.ndarray
    inner: np.ndarray
    outer: np.ndarray
    alpha0: float
    dalpha: float
    E_red: float
    D: float
    dm: float
    fi: float
    fo: float


def build_hertz_table(D, dm, fi, fo, E_red, n=181):
    """HertzTable of the exact solution for alpha in [0, pi/2] (n points) for both raceways.

    D, dm [m], fi, fo inner/outer conformity, E_red = E' [Pa].  Build time ~10 ms for n = 181.
    Linear-interpolation error of hertz_lookup (K_load, a, b, delta, p_max vs exact, 1001 angles,
    the four test bearings of tests/test_hertz.py): max 1.1e-6 relative at n = 181, 1.7e-5 at n = 46.
    """
    check_range("fi", fi, 0.5, None, lo_incl=False)
    check_range("fo", fo, 0.5, None, lo_incl=False)
    _check_geometry(D, dm, fi, 0.0)
    check_range("E_red", E_red, 0.0, None, lo_incl=False, unit="Pa")
    if isinstance(n, bool) or int(n) != n or n < 2:
        raise BearingInputError("n", n, "integer >= 2")
    n = int(n)
    alpha = np.linspace(0.0, HALF_PI, n)
    tabs = []
    for inner, f in ((True, fi), (False, fo)):
        t = np.empty((N_ROWS, n))
        for j, al in enumerate(alpha):
            Rx, Ry, s, F = _contact_curvature_nb(float(D), float(dm), float(f), float(al), inner)
            hc = hertz_exact(s, F, E_red)
            t[:, j] = (hc.K_load, hc.a_coef, hc.b_coef, hc.k, hc.ell_E, hc.ell_K, Rx, Ry)
        tabs.append(np.ascontiguousarray(t))
    return HertzTable(alpha=alpha, inner=tabs[0], outer=tabs[1], alpha0=0.0, dalpha=HALF_PI / (n - 1),
                      E_red=float(E_red), D=float(D), dm=float(dm), fi=float(fi), fo=float(fo))


@njit(cache=True)
def hertz_lookup_alpha(table, alpha0, dalpha, alpha, row):
    """Row ``row`` of a (8, n) table linearly interpolated at contact angle alpha (numba).

    The Hertz constants depend on cos(alpha) only, so |alpha| is used; then clamped to the grid.
    """
    return hertz_lookup_alpha_inline(table, alpha0, dalpha, alpha, row)


@njit(cache=True, inline="always")
def hertz_lookup_alpha_inline(table, alpha0, dalpha, alpha, row):
    """hertz_lookup_alpha inlined into the caller (no call, no reference counting of the table: for
    kernels that look up per ball evaluation)."""
    n = table.shape[1]
    x = (abs(alpha) - alpha0) / dalpha
    if not x > 0.0:            # also catches NaN
        return table[row, 0]
    if x >= n - 1:
        return table[row, n - 1]
    j = int(x)
    w = x - j
    return (1.0 - w) * table[row, j] + w * table[row, j + 1]


@njit(cache=True, inline="always")
def hertz_table_coefs(table, alpha0, dalpha, alpha):
    """(K_load, a-coefficient, b-coefficient) at contact angle alpha [rad] from a (8, n) table: linear
    interpolation in |alpha| with one index computation, clamped to [alpha0, alpha0 + (n-1) dalpha]
    (NaN goes to the first node). a = a_coef Q^(1/3), b = b_coef Q^(1/3), Q = K_load delta^1.5."""
    n = table.shape[1]
    x = (abs(alpha) - alpha0) / dalpha
    if not x > 0.0:
        j = 0
        w = 0.0
    elif x >= n - 1:
        j = n - 2
        w = 1.0
    else:
        j = int(x)
        w = x - j
    KL = (1.0 - w) * table[ROW_K_LOAD, j] + w * table[ROW_K_LOAD, j + 1]
    ac = (1.0 - w) * table[ROW_A_COEF, j] + w * table[ROW_A_COEF, j + 1]
    bc = (1.0 - w) * table[ROW_B_COEF, j] + w * table[ROW_B_COEF, j + 1]
    return KL, ac, bc


@njit(cache=True)
def hertz_lookup(table, alpha0, dalpha, alpha, Q):
    """(K_load, a, b, delta, p_max) at contact angle alpha [rad] and load Q [N] from a (8, n) table.

    table = HertzTable.inner or .outer; alpha0, dalpha = HertzTable.alpha0, .dalpha.  Linear
    interpolation in |alpha|, clamped to [alpha0, alpha0 + (n-1) dalpha]; Q <= 0 gives
    a = b = delta = p_max = 0.  delta = (Q/K_load)^(2/3), p_max = 3Q/(2 pi a b).
    """
    KL, ac, bc = hertz_table_coefs(table, alpha0, dalpha, alpha)
    return _contact_from_coefs_nb(KL, ac, bc, Q)
