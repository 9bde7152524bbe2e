"""Fatigue rating life from the load distribution: ISO/TS 16281 reference rating life L10r, ISO 281 modified
rating life L_nmr, Palmgren-Miner damage.

Units: SI at the interface (N, m, rad, s); the ISO formulas inside take N, mm, rpm and mm^2/s. Lives are in
10^6 revolutions of the rotating ring relative to the stationary one ([Mrev]) or hours at a speed ([h]).

Contact ratings (Lundberg-Palmgren point contact; Harris & Kotzalas, Rolling Bearing Analysis 5th ed., Vol. 2
Ch. 8; ISO/TS 16281:2008, same form), per raceway contact of operating angle alpha, N and mm:
    Q_c = k 98.1 (2 f / (2 f - 1))^0.41 (1 -+ g)^1.39 / (1 +- g)^(1/3) (D/dm)^0.3 D^1.8 Z^(-1/3)
    (D > 25.4 mm: 3.647 D^1.4 in place of D^1.8, ISO 281 6.1.1), g = D cos(alpha) / dm,
    upper signs inner raceway (f = fi), lower outer raceway (f = fo).
k ties the contact ratings to the bearing's rating C_r (ISO 281 from the geometry or the catalogue value of the
bearing file): with Lundberg-Palmgren's relation between raceway and bearing ratings at the nominal angle,
    C_ring = Q_c Z cos(alpha0) J_r / J_ring,   C = (C_i^(-10/3) + C_o^(-10/3))^(-0.3)      (i = 1)
(J_r = J_r(0.5), J_1 = J_1(0.5) for the rotating inner ring, J_2 = J_2(0.5) for the stationary outer ring: the
Sjovall-Lundberg-Palmgren load-distribution integrals, computed here by quadrature), k = C_r / C(k = 1).
k = 1 is Lundberg-Palmgren's theory without ISO's material factor b_m; for the ISO 281 C_r of the presets
k = 1.24-1.32 (b_m = 1.3 and the table's departure from the theory, bearing_core.bearing.ratings).

Reference rating life (ISO/TS 16281:2008 with per-ball contact ratings, Lundberg-Palmgren):
    rotating ring:    Q_e / Q_c = [ (1/Z) sum_j (Q_j / Q_cj)^3     ]^(1/3)       (cubic mean)
    stationary ring:  Q_e / Q_c = [ (1/Z) sum_j (Q_j / Q_cj)^(10/3) ]^(3/10)
    L_ring = (Q_c / Q_e)^3,   L10r = (L_i^(-e) + L_o^(-e))^(-1/e),  e = 10/9     [Mrev]
With the same Q_c for every ball this is (Q_c / Q_e)^3 with Q_e the ISO/TS 16281 equivalent rolling element
load. Four-point-contact bearings: the four raceway tracks (two arcs per ring) enter the sum as four rings.

Modified rating life (ISO 281:2007; ISO/TS 16281:2008):
    L_nmr = a_1 a_ISO L10r,   a_ISO = f(kappa, e_C C_u / P)  (ball bearing equations, a_iso())
    P = C_r L10r^(-1/3)  (dynamic equivalent reference load, ISO/TS 16281)
    kappa = nu / nu_1,  nu_1 the ISO 281 reference viscosity (reference_viscosity())
    C_u = C_0 / 22 (d_m <= 100 mm), C_0 / 22 (100 / d_m)^0.5 (d_m > 100 mm), ISO 281:2007 Annex B, ball
          bearings, with C_0 on ISO 76's basis (bearing_core.lubrication.friction_models.iso76_static_rating)
Palmgren-Miner damage over a run: D = sum dt / L_h (damage_increment_nb).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numba import njit

from ..errors import BearingInputError, check_range
from . import dynamics_kernels as K

E_BALL = 10.0 / 9.0            # Lundberg-Palmgren Weibull slope of ball bearings
P_BALL = 3.0                   # life exponent of ball bearings
REVS_PER_MREV = 1.0e6
ROTATING_RINGS = ("inner", "outer")
A_ISO_MAX = 50.0               # ISO 281:2007: a_ISO limited to 50
KAPPA_MIN, KAPPA_MAX = 0.1, 4.0  # ISO 281:2007: kappa < 0.1 not covered; kappa > 4 taken as 4
RELIABILITY_MIN, RELIABILITY_MAX = 90.0, 99.95   # ISO 281:2007 Table 12


def _load_distribution_integrals(eps: float = 0.5, n: int = 200001):
    """Sjovall integrals (Harris & Kotzalas Vol. 2 Ch. 8) at load-zone parameter eps: J_r, J_1 (cubic mean)
    and J_2 (10/3 mean) of Q(psi) = Q_max (1 - (1 - cos psi)/(2 eps))^1.5 (point contact)."""
    psi = np.linspace(-math.pi, math.pi, n)
    x = np.clip(1.0 - (1.0 - np.cos(psi)) / (2.0 * eps), 0.0, None)
    mean = lambda y: float(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(psi)) / (2.0 * math.pi))  # noqa: E731
    return mean(x ** 1.5 * np.cos(psi)), mean(x ** 4.5) ** (1.0 / 3.0), mean(x ** 5.0) ** 0.3


J_R, J_1, J_2 = _load_distribution_integrals()   # 0.2288, 0.5625, 0.5874


# ------------------------------------------------------------------------------------------------
# numba kernels (no input checks: the Python functions below do them)
@njit(cache=True)
def contact_rating_nb(D_mm, dm_mm, f, alpha, Z, inner, k):
    """Basic dynamic load rating Q_c [N] of one raceway contact at operating angle alpha [rad] (module
    docstring): D_mm, dm_mm [mm], conformity f [-], Z balls, inner True for the inner raceway, k tie factor."""
    g = D_mm * abs(math.cos(alpha)) / dm_mm
    if inner:
        geo = (1.0 - g) ** 1.39 / (1.0 + g) ** (1.0 / 3.0)
    else:
        geo = (1.0 + g) ** 1.39 / (1.0 - g) ** (1.0 / 3.0)
    dpow = D_mm ** 1.8 if D_mm <= 25.4 else 3.647 * D_mm ** 1.4
    return k * 98.1 * (2.0 * f / (2.0 * f - 1.0)) ** 0.41 * geo * (D_mm / dm_mm) ** 0.3 * dpow * Z ** (-1.0 / 3.0)


@njit(cache=True)
def ring_load_ratio_nb(Q, alpha, D_mm, dm_mm, f, inner, k, rotating):
    """Q_e / Q_c [-] of one raceway track (module docstring): Q [N], alpha [rad] per ball (Q <= 0: unloaded);
    rotating True: cubic mean, False: 10/3 mean."""
    Z = Q.size
    p = 3.0 if rotating else 10.0 / 3.0
    s = 0.0
    for j in range(Z):
        if Q[j] > 0.0:
            s += (Q[j] / contact_rating_nb(D_mm, dm_mm, f, alpha[j], Z, inner, k)) ** p
    return (s / Z) ** (1.0 / p)


@njit(cache=True)
def rating_life_mrev_nb(Q_i, Q_o, alpha_i, alpha_o, par):
    """Reference rating life L10r [10^6 rev] from the per-ball contact loads Q_i, Q_o [N] and operating
    contact angles alpha_i, alpha_o [rad] of a two-point bearing; par = life_parameters(geometry).
    inf when no ball is loaded."""
    rot_in = par[6] == 0.0
    ri = ring_load_ratio_nb(Q_i, alpha_i, par[0], par[1], par[2], True, par[5], rot_in)
    ro = ring_load_ratio_nb(Q_o, alpha_o, par[0], par[1], par[3], False, par[5], not rot_in)
    s = ri ** (3.0 * E_BALL) + ro ** (3.0 * E_BALL)       # L_ring^(-e) = (Q_e/Q_c)^(3e)
    if s <= 0.0:
        return math.inf
    return s ** (-1.0 / E_BALL)


@njit(cache=True)
def rating_life_hours_nb(Q_i, Q_o, alpha_i, alpha_o, par, speed_rpm):
    """Reference rating life L10r [h] at the relative ring speed speed_rpm [rpm] (sign ignored); inf at
    zero speed or without load. The fast entry point for a simulation state (kernels of the session)."""
    L = rating_life_mrev_nb(Q_i, Q_o, alpha_i, alpha_o, par)
    n = abs(speed_rpm)
    if n <= 0.0 or not L < math.inf:
        return math.inf
    return L * REVS_PER_MREV / (60.0 * n)


@njit(cache=True)
def rating_life_hours_details_nb(bd, par, speed_rpm):
    """L10r [h] straight from the dynamics' per-ball details bd (Z x dynamics_kernels.NBD: columns BD_QI, BD_AI,
    BD_QO, BD_AO and, for four-point bearings, the second arcs BD_QI2, BD_AI2, BD_QO2, BD_AO2, which are 0 for
    two-point bearings); par = life_parameters(geometry); speed_rpm the relative ring speed [rpm]. A four-point
    bearing's tracks are each ball's more and less loaded arc (the grouping bd holds). inf at zero speed or
    without load."""
    rot_in = par[6] == 0.0
    s = 0.0
    for cq, ca, inner in ((K.BD_QI, K.BD_AI, True), (K.BD_QO, K.BD_AO, False), (K.BD_QI2, K.BD_AI2, True),
                          (K.BD_QO2, K.BD_AO2, False)):
        f = par[2] if inner else par[3]
        r = ring_load_ratio_nb(bd[:, cq], bd[:, ca], par[0], par[1], f, inner, par[5], inner == rot_in)
        s += r ** (3.0 * E_BALL)
    n = abs(speed_rpm)
    if s <= 0.0 or n <= 0.0:
        return math.inf
    return s ** (-1.0 / E_BALL) * REVS_PER_MREV / (60.0 * n)


@njit(cache=True)
def damage_increment_nb(dt_s, life_h):
    """Palmgren-Miner damage increment dt / L [-] of dt_s [s] at a life life_h [h] (0 for an infinite life)."""
    if not life_h < math.inf:
        return 0.0
    return dt_s / (3600.0 * life_h)


# ------------------------------------------------------------------------------------------------
# ratings and factors
def _check_geometry(g):
    check_range("free_contact_angle_deg", math.degrees(g.alpha0), 0.0, 45.0, unit="deg")


def tie_factor(geometry) -> float:
    """k [-]: the factor on the Lundberg-Palmgren contact ratings that makes them combine (at the nominal
    angle, J_r/J_1 inner, J_r/J_2 outer) into the bearing's C_r (geometry.basic_dynamic_load_rating)."""
    g = geometry
    _check_geometry(g)
    D, dm = g.D * 1e3, g.dm * 1e3
    ca = math.cos(g.alpha0)
    Ci = contact_rating_nb(D, dm, g.fi, g.alpha0, g.Z, True, 1.0) * g.Z * ca * J_R / J_1
    Co = contact_rating_nb(D, dm, g.fo, g.alpha0, g.Z, False, 1.0) * g.Z * ca * J_R / J_2
    C_lp = (Ci ** (-10.0 / 3.0) + Co ** (-10.0 / 3.0)) ** -0.3
    return g.basic_dynamic_load_rating / C_lp


def life_parameters(geometry, rotating: str = "inner") -> np.ndarray:
    """Parameter array of the life kernels: (D [mm], dm [mm], fi, fo, Z, k, rotating ring 0 inner / 1 outer,
    C_r [N])."""
    if rotating not in ROTATING_RINGS:
        raise BearingInputError("rotating", rotating, " | ".join(ROTATING_RINGS))
    g = geometry
    return np.array([g.D * 1e3, g.dm * 1e3, g.fi, g.fo, float(g.Z), tie_factor(g),
                     0.0 if rotating == "inner" else 1.0, g.basic_dynamic_load_rating])


def contact_ratings(geometry, alpha_i, alpha_o):
    """(Q_ci, Q_co) [N] per ball at the operating contact angles alpha_i, alpha_o [rad]."""
    par = life_parameters(geometry)
    ai, ao = np.atleast_1d(np.asarray(alpha_i, float)), np.atleast_1d(np.asarray(alpha_o, float))
    Qci = np.array([contact_rating_nb(par[0], par[1], par[2], a, geometry.Z, True, par[5]) for a in ai])
    Qco = np.array([contact_rating_nb(par[0], par[1], par[3], a, geometry.Z, False, par[5]) for a in ao])
    return Qci, Qco


def a1_reliability(reliability_pct: float) -> float:
    """Life modification factor for reliability a_1 [-] at reliability R [%], 90 <= R <= 99.95: the three-parameter
    Weibull relation behind ISO 281:2007 Table 12 (slope 1.5, minimum life 0.05 L10),
    a_1 = 0.95 (ln(100/R) / ln(100/90))^(2/3) + 0.05 (bearing_validation case iso281-a1-reliability)."""
    R = check_range("reliability", reliability_pct, RELIABILITY_MIN, RELIABILITY_MAX, unit="%")
    return 0.95 * (math.log(100.0 / R) / math.log(100.0 / 90.0)) ** (2.0 / 3.0) + 0.05


def reference_viscosity(dm: float, speed_rpm: float) -> float:
    """ISO 281:2007 reference kinematic viscosity nu_1 [mm^2/s] at pitch diameter dm [m] and speed
    [rpm] > 0: 45000 n^-0.83 D_pw^-0.5 for n < 1000 r/min, 4500 n^-0.5 D_pw^-0.5 for n >= 1000 r/min."""
    n = check_range("speed_rpm", speed_rpm, 0.0, None, lo_incl=False, unit="rpm")
    Dpw = dm * 1e3
    if n < 1000.0:
        return 45000.0 * n ** -0.83 * Dpw ** -0.5
    return 4500.0 * n ** -0.5 * Dpw ** -0.5


def a_iso(kappa: float, ec_cu_over_p: float) -> float:
    """Life modification factor a_ISO [-] of radial ball bearings, ISO 281:2007 equations for
    0.1 <= kappa < 0.4, 0.4 <= kappa < 1, 1 <= kappa <= 4 (kappa > 4 taken as 4; kappa < 0.1 is outside the
    standard: a BearingInputError), x = e_C C_u / P >= 0:
        a_ISO = 0.1 [1 - (2.5671 - c1 / kappa^c2)^0.83 x^(1/3)]^(-9.3),  limited to 50
        (c1, c2) = (2.2649, 0.054381), (1.9987, 0.19087), (1.9987, 0.071739)."""
    k = check_range("kappa", kappa, KAPPA_MIN, None, unit="(viscosity ratio; ISO 281 covers kappa >= 0.1)")
    x = check_range("e_C C_u / P", ec_cu_over_p, 0.0, None)
    k = min(k, KAPPA_MAX)
    if k < 0.4:
        c1, c2 = 2.2649, 0.054381
    elif k < 1.0:
        c1, c2 = 1.9987, 0.19087
    else:
        c1, c2 = 1.9987, 0.071739
    base = 2.5671 - c1 / k ** c2
    t = max(base, 0.0) ** 0.83 * x ** (1.0 / 3.0)
    if t >= 1.0:
        return A_ISO_MAX
    return min(0.1 * (1.0 - t) ** -9.3, A_ISO_MAX)


def fatigue_load_limit(C0: float, dm: float) -> float:
    """Fatigue load limit C_u [N] of a ball bearing, ISO 281:2007 Annex B (estimate): C_0 / 22 for
    D_pw <= 100 mm, C_0 / 22 (100 / D_pw)^0.5 above; C0 [N], dm [m]."""
    Dpw = dm * 1e3
    return C0 / 22.0 if Dpw <= 100.0 else C0 / 22.0 * (100.0 / Dpw) ** 0.5


# ------------------------------------------------------------------------------------------------
# results
@dataclass
class RatingLife:
    """Reference rating life of one state. L10r_Mrev [10^6 rev], L10r_h [h] (at speed_rpm), L_inner_Mrev,
    L_outer_Mrev the raceway lives [10^6 rev], Q_ei, Q_eo [N] equivalent rolling element loads (ISO/TS 16281:
    cubic mean on the rotating ring, 10/3 mean on the stationary one), Q_ci, Q_co [N] per-ball contact ratings
    at the operating angles, P_ref [N] = C_r L10r^(-1/3), C_r [N], k the tie factor."""

    L10r_Mrev: float
    L10r_h: float
    L_inner_Mrev: float
    L_outer_Mrev: float
    Q_ei: float
    Q_eo: float
    Q_ci: np.ndarray
    Q_co: np.ndarray
    P_ref: float
    C_r: float
    k: float
    speed_rpm: float


def _mean(Q, p):
    Q = np.maximum(np.asarray(Q, float), 0.0)
    return float(np.mean(Q ** p) ** (1.0 / p))


def _tracks(res):
    """(Q, alpha, inner) of each raceway track of a quasi-static result: two for a two-point bearing, four for
    a four-point one (FourPointResult.Q_c, alpha_c in CONTACT_NAMES order)."""
    if getattr(res, "Q_c", None) is not None:
        Qc, ac = np.asarray(res.Q_c, float), np.asarray(res.alpha_c, float)
        return [(Qc[:, m].copy(), ac[:, m].copy(), m < 2) for m in range(4)]
    return [(np.asarray(res.Q_i, float), np.asarray(res.alpha_i, float), True),
            (np.asarray(res.Q_o, float), np.asarray(res.alpha_o, float), False)]


def rating_life(res, speed_rpm: float | None = None, rotating: str = "inner") -> RatingLife:
    """Reference rating life (module docstring) of a quasi-static result (or any object with geometry, Q_i, Q_o,
    alpha_i, alpha_o per ball [N, rad]; four-point results use all four contacts). speed_rpm: relative ring
    speed for the life in hours (None: from res.omega - res.omega_outer). rotating: 'inner' | 'outer', the ring
    that turns relative to the load (cubic mean)."""
    g = res.geometry
    par = life_parameters(g, rotating)
    if speed_rpm is None:
        speed_rpm = (float(res.omega) - float(getattr(res, "omega_outer", 0.0))) * 30.0 / math.pi
    speed_rpm = check_range("speed_rpm", speed_rpm, -2e5, 2e5, unit="rpm")
    D, dm, k = par[0], par[1], par[5]
    s = 0.0
    ring_s = [0.0, 0.0]
    for Q, al, inner in _tracks(res):
        rot = inner == (rotating == "inner")
        r = ring_load_ratio_nb(np.ascontiguousarray(Q), np.ascontiguousarray(al), D, dm, g.fi if inner else g.fo,
                               inner, k, rot)
        ring_s[0 if inner else 1] += r ** (3.0 * E_BALL)
        s += r ** (3.0 * E_BALL)
    if s <= 0.0:
        raise BearingInputError("loads", np.asarray(res.loads).tolist() if hasattr(res, "loads") else None,
                                "a load that loads at least one ball (no loaded contact: no fatigue life)")
    L = s ** (-1.0 / E_BALL)
    Li, Lo = ((x ** (-1.0 / E_BALL) if x > 0 else math.inf) for x in ring_s)
    n = abs(speed_rpm)
    Lh = L * REVS_PER_MREV / (60.0 * n) if n > 0 else math.inf
    Qci, Qco = contact_ratings(g, res.alpha_i, res.alpha_o)
    pi_, po_ = (3.0, 10.0 / 3.0) if rotating == "inner" else (10.0 / 3.0, 3.0)
    Cr = float(par[7])
    return RatingLife(L10r_Mrev=L, L10r_h=Lh, L_inner_Mrev=Li, L_outer_Mrev=Lo, Q_ei=_mean(res.Q_i, pi_),
                      Q_eo=_mean(res.Q_o, po_), Q_ci=Qci, Q_co=Qco, P_ref=Cr * L ** (-1.0 / P_BALL), C_r=Cr, k=k,
                      speed_rpm=speed_rpm)


@dataclass
class LifeReport:
    """Rating lives of one operating point (life_at). Lives in 10^6 rev (_Mrev) and hours (_h)."""

    bearing: str
    speed_rpm: float
    loads: tuple
    rating: RatingLife
    C_r: float
    C_r_source: str
    C_0: float
    C_u: float
    oil: str
    oil_temperature_c: float
    nu_mm2s: float
    nu1_mm2s: float
    kappa: float
    e_C: float
    reliability_pct: float
    a1: float
    a_iso: float
    L_nmr_Mrev: float
    L_nmr_h: float
    notes: list = field(default_factory=list)
    result: object = field(default=None, repr=False)

    def to_dict(self) -> dict:
        r = self.rating
        fin = lambda x: float(x) if math.isfinite(x) else None  # noqa: E731  (JSON: null for an infinite life)
        return {
            "bearing": self.bearing, "speed_rpm": self.speed_rpm,
            "loads": dict(zip(("Fx_N", "Fy_N", "Fz_N", "Mx_Nm", "My_Nm"), map(float, self.loads))),
            "C_r_N": self.C_r, "C_r_source": self.C_r_source, "C_0_N": self.C_0, "C_u_N": self.C_u,
            "tie_factor_k": r.k,
            "Q_ei_N": r.Q_ei, "Q_eo_N": r.Q_eo, "Q_ci_N": r.Q_ci.tolist(), "Q_co_N": r.Q_co.tolist(),
            "Q_i_N": np.asarray(self.result.Q_i).tolist() if self.result is not None else None,
            "Q_o_N": np.asarray(self.result.Q_o).tolist() if self.result is not None else None,
            "alpha_i_deg": np.degrees(self.result.alpha_i).tolist() if self.result is not None else None,
            "alpha_o_deg": np.degrees(self.result.alpha_o).tolist() if self.result is not None else None,
            "L_inner_Mrev": fin(r.L_inner_Mrev), "L_outer_Mrev": fin(r.L_outer_Mrev),
            "L10r_Mrev": fin(r.L10r_Mrev), "L10r_h": fin(r.L10r_h), "P_ref_N": r.P_ref,
            "oil": self.oil, "oil_temperature_c": self.oil_temperature_c, "nu_mm2s": self.nu_mm2s,
            "nu1_mm2s": self.nu1_mm2s, "kappa": self.kappa, "e_C": self.e_C,
            "reliability_pct": self.reliability_pct, "a1": self.a1, "a_iso": self.a_iso,
            "L_nmr_Mrev": fin(self.L_nmr_Mrev), "L_nmr_h": fin(self.L_nmr_h), "notes": list(self.notes),
        }


def modified_life(rating: RatingLife, C_u: float, kappa: float, e_C: float = 1.0,
                  reliability_pct: float = 90.0) -> tuple[float, float, float]:
    """(a_1, a_ISO, L_nmr [10^6 rev]) of ISO 281:2007 / ISO/TS 16281: L_nmr = a_1 a_ISO L10r, a_ISO at
    e_C C_u / P_ref. e_C: contamination factor 0..1 (ISO 281 Table 13)."""
    e_C = check_range("e_C (contamination factor)", e_C, 0.0, 1.0)
    a1 = a1_reliability(reliability_pct)
    ai = a_iso(kappa, e_C * C_u / rating.P_ref)
    return a1, ai, a1 * ai * rating.L10r_Mrev


def life_at(geometry, speed_rpm: float, loads, oil: str = "iso-vg32-mineral", oil_temperature_c: float = 40.0,
            e_C: float = 1.0, reliability_pct: float = 90.0, control: str = "outer",
            fixed_tilt: bool = False) -> LifeReport:
    """Rating lives at one operating point: Jones-Harris quasi-static load distribution (inner ring turning at
    speed_rpm > 0 [rpm], loads (Fx, Fy, Fz, Mx, My) [N, N m] on the inner ring, outer ring fixed), L10r from it,
    L_nmr with kappa of the oil at oil_temperature_c [degC] (bearing_core.lubrication.lubricants), contamination
    factor e_C [-] and reliability [%]. fixed_tilt: the inner ring held square (Mx, My are reactions).
    Raises BearingInputError naming the parameter, the value and the allowed range."""
    from ..lubrication.friction_models import iso76_static_rating
    from ..lubrication.lubricants import get_oil
    from .quasistatic import quasistatic_model

    g = geometry
    n = check_range("speed_rpm", speed_rpm, 0.0, 190000.0, lo_incl=False, unit="rpm")
    loads = np.asarray(loads, dtype=float).reshape(-1)
    if loads.size != 5:
        raise BearingInputError("loads", loads.tolist(), "5 values (Fx, Fy, Fz, Mx, My) [N, N m]")
    for nm, v in zip(("Fx", "Fy", "Fz", "Mx", "My"), loads):
        check_range(nm, v, -1e7, 1e7, unit="N or N m")
    if not np.any(loads[:3 if fixed_tilt else 5] != 0.0):
        raise BearingInputError("loads (Fx, Fy, Fz, Mx, My)", loads.tolist(),
                                "at least one non-zero load: an unloaded bearing has no fatigue life rating")
    if not g.is_four_point and g.alpha0 > 0.0 and loads[2] <= 0.0:
        raise BearingInputError("Fz", float(loads[2]), "Fz > 0 N",
                                "a single angular-contact bearing carries axial load on the inner ring in +z only; "
                                "a radial load or moment also needs Fz > 0 to be carried (its contact angle "
                                "induces an axial force)")
    e_C = check_range("e_C (contamination factor)", e_C, 0.0, 1.0)
    a1 = a1_reliability(reliability_pct)
    T = check_range("oil_temperature_c", oil_temperature_c, -40.0, 200.0, unit="degC")
    oil_obj = get_oil(oil)
    _check_geometry(g)
    model = quasistatic_model(g, control, fixed_tilt=fixed_tilt)
    res = model.solve(n * math.pi / 30.0, loads, stiffness=False)
    rl = rating_life(res, n)
    C0 = iso76_static_rating(g)
    Cu = fatigue_load_limit(C0, g.dm)
    nu = oil_obj.nu(T + 273.15) * 1e6
    nu1 = reference_viscosity(g.dm, n)
    kappa = nu / nu1
    notes = []
    if kappa < KAPPA_MIN:
        notes.append(f"kappa = {kappa:.3g} < 0.1 is outside ISO 281's a_ISO range: a_ISO evaluated at kappa = 0.1")
    if kappa > KAPPA_MAX:
        notes.append(f"kappa = {kappa:.3g} > 4: a_ISO evaluated at kappa = 4 (ISO 281:2007)")
    ai = a_iso(max(kappa, KAPPA_MIN), e_C * Cu / rl.P_ref)
    if ai >= A_ISO_MAX:
        notes.append("a_ISO at its limit of 50 (ISO 281:2007)")
    src = "catalogue (bearing file dynamic_load_rating_N)" if g.dynamic_load_rating > 0 else "ISO 281 from the geometry"
    Lnm = a1 * ai * rl.L10r_Mrev
    return LifeReport(bearing=g.name, speed_rpm=n, loads=tuple(map(float, loads)), rating=rl, C_r=rl.C_r,
                      C_r_source=src, C_0=C0, C_u=Cu, oil=oil, oil_temperature_c=T, nu_mm2s=nu, nu1_mm2s=nu1,
                      kappa=kappa, e_C=e_C, reliability_pct=float(reliability_pct), a1=a1, a_iso=ai,
                      L_nmr_Mrev=Lnm, L_nmr_h=Lnm * REVS_PER_MREV / (60.0 * n), notes=notes, result=res)


class FatigueDamage:
    """Palmgren-Miner damage accumulated over a run: D = sum dt / L_h(state). value is 0 at the start and is
    the whole state (get/set it to roll back)."""

    def __init__(self, value: float = 0.0):
        self.value = check_range("fatigue_damage", value, 0.0, None)

    def advance(self, dt_s: float, life_h: float) -> float:
        """Add the damage of dt_s [s] >= 0 at a life of life_h [h] > 0 (inf: none); returns the new sum."""
        check_range("dt_s", dt_s, 0.0, None, unit="s")
        if not (life_h > 0.0):
            raise BearingInputError("life_h", life_h, "value > 0 h (inf: no damage)")
        self.value += damage_increment_nb(float(dt_s), float(life_h))
        return self.value


@dataclass
class DutyCycleLife:
    """Rating lives of a duty cycle of held operating points (duty_cycle_life): levels (LifeReport each),
    durations_s [s], the Palmgren-Miner damage of one cycle with L10r and with L_nmr [-], and the equivalent
    lives L = cycle time / damage [h]."""

    levels: list
    durations_s: list
    damage_L10r: float
    damage_L_nmr: float
    L10r_h: float
    L_nmr_h: float

    def to_dict(self) -> dict:
        fin = lambda x: float(x) if math.isfinite(x) else None  # noqa: E731
        return {"cycle_s": float(sum(self.durations_s)), "damage_L10r_per_cycle": self.damage_L10r,
                "damage_L_nmr_per_cycle": self.damage_L_nmr, "L10r_h": fin(self.L10r_h),
                "L_nmr_h": fin(self.L_nmr_h),
                "levels": [dict(duration_s=float(t), **{k: v for k, v in rep.to_dict().items()
                                                          if k == "notes" or not isinstance(v, list)})
                           for t, rep in zip(self.durations_s, self.levels)]}   # (per-ball lists left out)


def duty_cycle_life(geometry, levels, **kw) -> DutyCycleLife:
    """Rating lives of a duty cycle: levels is a sequence of (duration_s [s] > 0, speed_rpm [rpm] > 0, loads
    (Fx, Fy, Fz, Mx, My) [N, N m]), each held (life_at with the keywords kw: oil, oil_temperature_c, e_C,
    reliability_pct, control, fixed_tilt). Palmgren-Miner: the damage of one cycle is sum t_k / L_k (lives in
    hours at each level's speed), the equivalent life the cycle time over that damage."""
    levels = list(levels)
    if not levels:
        raise BearingInputError("duty cycle", [], "at least one level (duration_s, speed_rpm, loads)")
    reps, ts = [], []
    for k, lev in enumerate(levels):
        try:
            t, n, loads = lev
        except (TypeError, ValueError):
            raise BearingInputError(f"duty cycle level {k}", lev, "(duration_s, speed_rpm, (Fx, Fy, Fz, Mx, My))")
        ts.append(check_range(f"duty cycle level {k}: duration_s", t, 0.0, None, lo_incl=False, unit="s"))
        reps.append(life_at(geometry, n, loads, **kw))
    d10 = sum(damage_increment_nb(t, r.rating.L10r_h) for t, r in zip(ts, reps))
    dnm = sum(damage_increment_nb(t, r.L_nmr_h) for t, r in zip(ts, reps))
    T_h = sum(ts) / 3600.0
    return DutyCycleLife(levels=reps, durations_s=ts, damage_L10r=d10, damage_L_nmr=dnm,
                         L10r_h=T_h / d10 if d10 > 0 else math.inf, L_nmr_h=T_h / dnm if dnm > 0 else math.inf)
