"""Thermal network of the bearing assembly (seed 001, Gao et al., Friction 2022, section 2.3, Eqs. 21-29).

Nodes (index, name): 0 'ball' (all balls), 1 'outer' (outer ring + housing, T_h), 2 'inner' (inner ring +
shaft, T_s), 3 'oil' (oil in the bearing + cage, T_oil). Each node is isothermal (seed 001's assumption).

Energy equation of node k (seed 001 Eq. 21): C_k dT_k/dt = q_k - sum_j G_kj (T_k - T_j)
    - G_k,amb (T_k - T_amb) - G_k,flow (T_k - T_in),
C_k = sum c_p rho V over the parts of the node [J/K]; G = 1/R [W/K]. Time stepping: backward Euler exactly
as seed 001 Eqs. 22-25 (all conduction/convection terms at t_{n+1}); unconditionally stable, so it can run
on the slow thermal time scale with dt of seconds to minutes. Steady state: the same equations without
the storage term.

Resistances (seed 001 Eqs. 26-29), with the corrections we had to make:
* Ball-ring conduction through the Hertz contacts, contact_model 'moving-source' (default): each of the
  Z contacts per race is a heat source of the area of the contact ellipse moving over the surface of
  both bodies at the rolling speed U. Mean temperature rise of a body under a uniform circular source of
  radius a (Tian & Kennedy, ASME J. Tribol. 116 (1994) 167, Eq. for the average rise, uniform circular
  source, all Peclet numbers): theta = 1.64 q a / (k sqrt(pi (1.234 + Pe))), Pe = U a / (2 kappa),
  kappa = k / (rho c_p). Resistance contact -> bulk of body k: R_k = theta / (q pi a^2)
      R_k = 1.64 / (pi k a sqrt(pi (1.234 + Pe_k)))
  with a = sqrt(a_H b_H) (circle of the ellipse's area; our approximation). Pe -> 0 gives 0.265 / (k a):
  within 2 % of the stationary uniform-flux disc, 8 / (3 pi^2 k a) (Carslaw & Jaeger, Conduction of Heat
  in Solids, 2nd ed., 1959, Sec. 8.2), within 7 % of Holm's isothermal-disc constriction 1 / (4 k a)
  (Holm, Electric Contacts, 1967, Sec. 4); Pe >> 1 gives Jaeger's
  moving-source asymptote ~ 1 / sqrt(Pe) (Jaeger, Proc. R. Soc. N.S.W. 76 (1942) 203). Ball bulk <->
  ring bulk: Z contacts in parallel, each R_ball + R_ring in series. Frictional heat generated in a
  contact is split so that both surfaces reach the same mean temperature (Blok's partition, Blok, Proc.
  Gen. Disc. Lubrication, IMechE 1937; Harris & Kotzalas, Rolling Bearing Analysis 5th ed., Vol. 2,
  thermal chapter): fraction to the ball = R_ring / (R_ball + R_ring). Rolling kinematics of the outer-
  ring-stationary bearing without spin (Harris & Kotzalas Vol. 1, Ch. 8): gamma = D cos(alpha0) / d_m,
  U = w_shaft d_m (1 - gamma^2) / 4 at both contacts (the surface speed of balls and raceways relative
  to the contact). contact_model 'seed001' keeps seed 001's Eq. 26 (below) and the fixed contact_split.
  Seed 001 Eq. 26 (stationary conduction, contact_model 'seed001'): R = 2 L_a / (N K pi L_a L_b), L_a,
  L_b the contact semi-axes, K the steel conductivity. The seed prints N_b in the NUMERATOR, which would
  make the resistance grow with the number of (parallel) contacts; we divide by N_b (N_b parallel paths).
* Convection (Eq. 27): the seed prints R = L / (h A), which is not a thermal resistance (m K/W); we use
  R = 1 / (h A) (Newton's law of cooling; Incropera & DeWitt, Fundamentals of Heat and Mass Transfer).
* Oil-solid coefficients h_b_oil, h_h_oil, h_s_oil = None (default): forced convection of a surface
  moving through the cavity fluid, the flat-plate average (Incropera & DeWitt 6th ed. Eq. 7.30, laminar,
  Re_L < 5e5; Eq. 7.38 mixed laminar-turbulent above):
      h = 0.664 (k/L) Re_L^0.5 Pr^(1/3),   h = (k/L)(0.037 Re_L^0.8 - 871) Pr^(1/3),  Re_L = u L / nu
  (the form Harris & Kotzalas Vol. 2 use for the convection from bearing surfaces to the lubricant).
  Surfaces: balls u = U (ball surface speed), L = D; inner ring u = (w_shaft - w_cage) D_Li / 2, outer
  ring u = w_cage D_Lo / 2 (the cavity fluid carried round at the cage speed w_cage = w_shaft (1 -
  gamma) / 2), L = pi d_m / Z (the boundary layer restarts at every ball). Fluid: the oil at its inlet
  temperature when oil reaches the cavity (oil flow or a cavity oil fraction > 0: the surfaces are
  wetted), else air (Incropera Table A.4 at 350 K: k 0.030 W/(m K), nu 20.9e-6 m^2/s, Pr 0.70). Floor:
  50 W/(m^2 K), the lower end of seed 001's oil-solid range (still oil, no speed). An explicit number
  keeps seed 001's fixed coefficient. The coefficients and the moving-source resistances follow the
  shaft speed (set_speed, called by the dynamics at every thermal step).
* Heat transfer coefficients to air: solid-air and oil-air default 20 W/(m^2 K) (forced/natural convection of air, Incropera Table 1.1:
  gases 2-25 natural, 25-250 forced). All are ThermalData fields.
* Ring-to-housing and ring-to-shaft paths (fit_contact_resistance not None, default): the outer-ring node
  rejects to ambient through three resistances in series -- the contact of the housing fit,
  R''_c / (pi D_o B), the cylindrical housing wall, ln(D_h / D_o) / (2 pi k L_h) (Incropera & DeWitt 6th
  ed. Eq. 3.28), and the convection from the housing surfaces, 1 / (h_h_atm A_hatm); the inner-ring node
  through the shaft fit, R''_c / (pi D_s B), axial conduction along the solid shaft from the seat to its
  exposed surfaces over L_h / 2, (L_h / 2) / (k pi D_s^2 / 4) (Incropera Eq. 3.6, one-dimensional), and
  the convection 1 / (h_s_atm A_satm). R''_c = 6e-4 m^2 K/W, the lower end of Incropera Table 3.1 for
  stainless-steel interfaces at 0.1-10 MPa contact pressure (6-25e-4 in vacuum; air in the gaps of a fit
  lowers it), B the bearing width. The heat capacities of housing and shaft stay in the ring nodes (seed
  001's lumped nodes); fit_contact_resistance None gives back seed 001's convection-only Eq. 29.
* Oil flow (not in seed 001 Eqs. 22-25, standard for circulating / jet lubrication): the oil passing
  through removes m_dot c_p (T_oil - T_in) (the lubricant heat-removal balance of Harris & Kotzalas,
  Rolling Bearing Analysis 5th ed. Vol. 1 (friction heat removed by the circulating oil), and SKF's
  and ISO/TR 14179-2 thermal balances). m_dot = rho_oil(T_in) * flow_rate [kg/s].

Heat sources (keys of ``Q_sources``, W, seed 001 Eq. 20 plus the dynamics' ball drag) and their nodes. The
seed's Eqs. 22-25 put the race heat Q_br into the ball node AND Q_br.i / Q_br.o into the rings, and Q_bp
into the ball AND the oil node, i.e. those losses are counted twice (energy would not balance). We split
each between the two bodies of the contact (fraction ``contact_split`` / ``pocket_split`` to the ball;
contact_split None (default): Blok's partition of the moving-source resistances above, per race;
pocket_split default 1/2 -- the equal partition of frictional heat between two bodies; Harris &
Kotzalas Vol. 2 thermal chapter; Takabi & Khonsari, Tribol. Int. 60 (2013) 93 (seed 001 ref. [32])):
    Q_br_i  race inner contacts       ball (split_i), inner (1 - split_i)                 Eqs. 22, 24
    Q_br_o  race outer contacts       ball (split_o), outer (1 - split_o)                 Eqs. 22, 23
    Q_bp    ball-pocket friction      ball (pocket_split), oil+cage (1 - pocket_split)    Eqs. 22, 25
    Q_cg    cage-guide ring friction  the guiding ring's node (outer / inner), 'oil' for a ball-guided cage   Eq. 23
    Q_ch_c  cage churning             oil                                                 Eq. 25
    Q_ch_b  ball churning (drag)      ball                                                Eq. 22
    Q_ch_s  inner-ring churning       inner                                               Eq. 24
    drag    the dynamics' ball drag   ball (same physical loss as Q_ch_b: give one of them)
    Q_oil_work  work of the rotating parts on the supply oil (oil_supply.supply_oil_work)   oil

Oil properties (c_p, density) are taken at the oil inlet temperature and the network is linear (the
thermal properties do not follow the node temperatures); the viscosity at the node temperatures is the
dynamics' business (lubricants.eta(oil, T_oil)).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numba import njit

from ..errors import BearingInputError, check_range

NODES = ("ball", "outer", "inner", "oil")
N_NODES = 4
I_BALL, I_OUTER, I_INNER, I_OIL = range(4)
SOURCES = ("Q_br_i", "Q_br_o", "Q_bp", "Q_cg", "Q_ch_c", "Q_ch_b", "Q_ch_s", "drag", "Q_oil_work")

# thermal conductivity [W/(m K)] and specific heat [J/(kg K)] of the solid materials (names of
# bearing_core.bearing.materials). AISI 52100: 46.6 and 475 (ASM / MatWeb data sheet for AISI 52100); hot-pressed
# Si3N4: 30 and 700; brass: 120 and 380; cotton-phenolic: 0.3 and 1400; PA66: 0.25 and 1700 (handbook
# values, Incropera & DeWitt App. A and manufacturers' data; order-of-magnitude for the polymers).
MATERIAL_THERMAL = {
    "steel": (46.6, 475.0),
    "silicon_nitride": (30.0, 700.0),
    "brass": (120.0, 380.0),
    "phenolic": (0.3, 1400.0),
    "nylon": (0.25, 1700.0),
}


# Highest temperature [K] at which each oil may run (bulk / component temperature); beyond it the oil
# oxidises or cokes quickly and the bearing is in thermal runaway. Values recalled from memory, not
# re-checked against the sources:
#  * mineral oils (ISO VG 32 / 68, naphthenic, seed 003's oil): 120 degC -- the upper operating temperature
#    of mineral oils in rolling bearings (SKF Rolling bearings catalogue PUB BU/P1 17000 EN (2018),
#    'Lubrication', oil selection: mineral oils up to about 100-120 degC);
#  * MIL-PRF-23699 polyol ester: 200 degC -- the bulk oil temperature these turbine oils are qualified for
#    (MIL-PRF-23699 class; Zaretsky (ed.), STLE Tribology for Aerospace Applications (1997), oil chapter);
#  * synthetic paraffinic (PAO): 150 degC (same SKF catalogue chapter: synthetic hydrocarbons ~150 degC).
OIL_T_MAX = {
    "iso-vg32-mineral": (393.15, "mineral oil, SKF Rolling bearings catalogue (2018) 'Lubrication'"),
    "iso-vg68-mineral": (393.15, "mineral oil, SKF Rolling bearings catalogue (2018) 'Lubrication'"),
    "naphthenic-mineral": (393.15, "mineral oil, SKF Rolling bearings catalogue (2018) 'Lubrication'"),
    "seed003-oil": (393.15, "taken as a mineral oil (seed 003 gives no type)"),
    "mil-prf-23699-ester": (473.15, "MIL-PRF-23699 ester turbine oil bulk temperature limit"),
    "synthetic-paraffinic": (423.15, "synthetic hydrocarbon (PAO), SKF Rolling bearings catalogue (2018)"),
    "santotrac-50": (393.15, "traction fluid (cycloaliphatic hydrocarbon): no limit at hand, the mineral-oil "
                             "limit is assumed"),
}
OIL_T_MAX_DEFAULT = (393.15, "unknown oil: the mineral-oil limit")

CONTACT_MODELS = ("moving-source", "seed001")
# air at 350 K (Incropera & DeWitt Table A.4): conductivity [W/(m K)], kinematic viscosity [m^2/s], Prandtl
AIR_K, AIR_NU, AIR_PR = 0.030, 20.9e-6, 0.70
H_OIL_MIN = 50.0        # W/(m^2 K), lower end of seed 001's oil-solid range (still fluid)
RE_TRANSITION = 5.0e5   # flat-plate transition Reynolds number (Incropera & DeWitt Sec. 7.2)


def flat_plate_h(u: float, L: float, k: float, nu: float, Pr: float) -> float:
    """Average heat transfer coefficient [W/(m^2 K)] of a plate of length L [m] in a stream of speed u
    [m/s]: laminar 0.664 Re^0.5 Pr^(1/3) k/L (Incropera & DeWitt Eq. 7.30), mixed boundary layer
    (0.037 Re^0.8 - 871) Pr^(1/3) k/L above Re = 5e5 (Eq. 7.38)."""
    Re = abs(u) * L / nu
    if Re <= RE_TRANSITION:
        Nu = 0.664 * math.sqrt(Re) * Pr ** (1.0 / 3.0)
    else:
        Nu = (0.037 * Re ** 0.8 - 871.0) * Pr ** (1.0 / 3.0)
    return Nu * k / L


def moving_source_resistance(k: float, kappa: float, a: float, U: float) -> float:
    """Resistance [K/W] from a circular contact of radius a [m] moving at U [m/s] over a half-space of
    conductivity k [W/(m K)] and diffusivity kappa [m^2/s] to its bulk: mean rise / heat, Tian & Kennedy
    (1994) uniform circular source, R = 1.64 / (pi k a sqrt(pi (1.234 + Pe))), Pe = U a / (2 kappa)."""
    Pe = abs(U) * a / (2.0 * kappa)
    return 1.64 / (math.pi * k * a * math.sqrt(math.pi * (1.234 + Pe)))


class ThermalRunaway(RuntimeError):
    """A node of the thermal network passed the lubricant's temperature limit (the losses exceed what the
    bearing can reject): ``temperatures`` [K] by node, ``T_max`` [K] and ``oil``."""

    def __init__(self, temperatures: dict, T_max: float, oil: str, where: str = "", cause: str = ""):
        self.temperatures = dict(temperatures)
        self.T_max = T_max
        self.oil = oil
        self.cause = cause
        hot = max(self.temperatures, key=self.temperatures.get)
        self.node = hot
        super().__init__(
            f"thermal runaway{(' ' + where) if where else ''}: {hot} temperature "
            f"{self.temperatures[hot]:.0f} K ({self.temperatures[hot] - 273.15:.0f} degC) exceeds the "
            f"{T_max:.0f} K ({T_max - 273.15:.0f} degC) limit of oil '{oil}'; the losses are more than the "
            "bearing and its cooling can reject (more oil flow, a lower speed or load, or a lighter oil)"
            + (f"; cause: {cause}" if cause else ""))


def oil_temperature_limit(oil_name: str) -> float:
    """Highest permissible temperature [K] of the named oil (OIL_T_MAX)."""
    return OIL_T_MAX.get(oil_name, OIL_T_MAX_DEFAULT)[0]


def material_thermal(name: str) -> tuple[float, float]:
    if name not in MATERIAL_THERMAL:
        raise BearingInputError("material", name, "one of " + ", ".join(sorted(MATERIAL_THERMAL)))
    return MATERIAL_THERMAL[name]


# =============================================================================================
# kernels (numba, arrays of floats)
# =============================================================================================
@njit(cache=True)
def _solve_small(A, b):
    """Gaussian elimination with partial pivoting for a small dense system (n <= ~10)."""
    n = b.shape[0]
    M = A.copy()
    x = b.copy()
    for k in range(n):
        p = k
        for i in range(k + 1, n):
            if abs(M[i, k]) > abs(M[p, k]):
                p = i
        if p != k:
            for j in range(n):
                t = M[k, j]
                M[k, j] = M[p, j]
                M[p, j] = t
            t = x[k]
            x[k] = x[p]
            x[p] = t
        for i in range(k + 1, n):
            f = M[i, k] / M[k, k]
            for j in range(k, n):
                M[i, j] -= f * M[k, j]
            x[i] -= f * x[k]
    for k in range(n - 1, -1, -1):
        s = x[k]
        for j in range(k + 1, n):
            s -= M[k, j] * x[j]
        x[k] = s / M[k, k]
    return x


@njit(cache=True)
def thermal_be_step(C, L, g_out, T_out, q, T, dt):
    """One backward-Euler step (seed 001 Eqs. 22-25): solve (C/dt + L + diag(g_out)) T1 =
    C/dt T + q + g_out T_out. C [J/K] (n), L [W/K] (n x n conductance Laplacian between nodes), g_out [W/K]
    (n, total conductance of each node to its outside temperature), T_out [K] (n, the conductance-weighted
    outside temperature of each node), q [W] (n), T [K] (n), dt [s]. Returns T1."""
    n = T.shape[0]
    A = L.copy()
    b = q.copy()
    for k in range(n):
        A[k, k] += C[k] / dt + g_out[k]
        b[k] += C[k] / dt * T[k] + g_out[k] * T_out[k]
    return _solve_small(A, b)


@njit(cache=True)
def thermal_steady(L, g_out, T_out, q):
    """Steady state (L + diag(g_out)) T = q + g_out T_out."""
    n = q.shape[0]
    A = L.copy()
    b = q.copy()
    for k in range(n):
        A[k, k] += g_out[k]
        b[k] += g_out[k] * T_out[k]
    return _solve_small(A, b)


# =============================================================================================
# data
# =============================================================================================
@dataclass(frozen=True)
class ThermalData:
    """Items of the thermal network that are not in BearingGeometry (SI). None = derived from the bearing
    (see ``resolved``; estimates, not from a source).

    T_amb, T_in [K]: ambient and oil inlet temperature; flow_rate [m^3/s] of circulating oil (0 = no flow
    term, as seed 001 Eqs. 22-25); h_b_oil, h_h_oil, h_s_oil: oil-solid heat transfer coefficients
    [W/(m^2 K)] (seed 001: 50-1500); h_h_atm, h_s_atm, h_oil_atm: to ambient air [W/(m^2 K)]; D_h, L_h:
    housing outer diameter and length [m]; D_o: bearing outside diameter = housing bore [m]; D_s: shaft
    diameter = bearing bore [m]; L_shaft: shaft length exposed to ambient [m]; D_Li, D_Lo: inner / outer
    ring shoulder diameters [m]; oil_fill: fraction of the bearing's free volume filled with oil [0, 1];
    contact semi-axes a_i, b_i, a_o, b_o [m] of the Hertz contacts (from the dynamics / quasi-static model;
    None = Hertz at ball_load [N] at the free contact angle); contact_split, pocket_split: fraction of the
    contact / pocket heat to the ball (contact_split None: Blok's partition); shaft_speed [rad/s] for the
    speed-dependent convection and moving-source contact resistances (set_speed updates it);
    oil_fraction: cavity oil fraction (None: oil_fill) -- > 0 or a flow means wetted surfaces;
    contact_model: 'moving-source' | 'seed001' (module docstring); fit_contact_resistance [m^2 K/W]:
    R''_c of the shaft and housing fits in the ring-to-shaft / ring-to-housing paths (None: seed 001's
    convection-only paths to ambient; module docstring)."""

    T_amb: float = 308.15           # seed 001: T_atm = 35 degC
    T_in: float = 308.15
    flow_rate: float = 0.0
    h_b_oil: float | None = None    # None: flat-plate correlation (module docstring)
    h_h_oil: float | None = None
    h_s_oil: float | None = None
    h_h_atm: float = 20.0
    h_s_atm: float = 20.0
    h_oil_atm: float = 20.0
    D_h: float | None = None
    L_h: float | None = None
    D_o: float | None = None
    D_s: float | None = None
    L_shaft: float = 0.0
    D_Li: float | None = None
    D_Lo: float | None = None
    oil_fill: float = 1.0
    a_i: float | None = None
    b_i: float | None = None
    a_o: float | None = None
    b_o: float | None = None
    ball_load: float = 1000.0
    contact_split: float | None = None
    pocket_split: float = 0.5
    shaft_speed: float = 0.0
    oil_fraction: float | None = None
    contact_model: str = "moving-source"
    fit_contact_resistance: float | None = 6.0e-4

    def validate(self):
        check_range("T_amb", self.T_amb, 200.0, 500.0, unit="K")
        check_range("T_in", self.T_in, 233.15, 473.15, unit="K")
        check_range("flow_rate", self.flow_rate, 0.0, 0.1, unit="m^3/s")
        for nm in ("h_b_oil", "h_h_oil", "h_s_oil"):
            if getattr(self, nm) is not None:
                check_range(nm, getattr(self, nm), 0.0, 1e5, unit="W/(m^2 K)")
        for nm in ("h_h_atm", "h_s_atm", "h_oil_atm"):
            check_range(nm, getattr(self, nm), 0.0, 1e4, unit="W/(m^2 K)")
        for nm in ("D_h", "L_h", "D_o", "D_s", "D_Li", "D_Lo", "a_i", "b_i", "a_o", "b_o"):
            v = getattr(self, nm)
            if v is not None:
                check_range(nm, v, 0.0, 10.0, lo_incl=False, unit="m")
        check_range("L_shaft", self.L_shaft, 0.0, 10.0, unit="m")
        check_range("oil_fill", self.oil_fill, 0.0, 1.0)
        check_range("ball_load", self.ball_load, 0.0, 1e7, lo_incl=False, unit="N")
        if self.contact_split is not None:
            check_range("contact_split", self.contact_split, 0.0, 1.0)
        check_range("shaft_speed", self.shaft_speed, -1e5, 1e5, unit="rad/s")
        if self.oil_fraction is not None:
            check_range("oil_fraction", self.oil_fraction, 0.0, 1.0)
        if self.contact_model not in CONTACT_MODELS:
            raise BearingInputError("contact_model", self.contact_model, "one of " + ", ".join(CONTACT_MODELS))
        check_range("pocket_split", self.pocket_split, 0.0, 1.0)
        if self.fit_contact_resistance is not None:
            check_range("fit_contact_resistance", self.fit_contact_resistance, 0.0, 1.0, unit="m^2 K/W")

    def resolved(self, g) -> dict:
        """All dimensions [m] with the defaults derived from BearingGeometry g (estimates):
        D_o = outer raceway + 0.55 D, D_s = inner raceway - 0.55 D (7218B: 160.0 / 90.6 mm vs the ISO
        envelope 160 / 90), D_Lo = dm + 0.7 D, D_Li = dm - 0.7 D (the shoulders the dynamics' land model
        uses), D_h = 1.6 D_o, L_h = 2 x bearing width; contact semi-axes from Hertz at ball_load."""
        self.validate()
        do, di = g.outer_raceway_diameter, g.inner_raceway_diameter
        r = dict(
            D_o=self.D_o if self.D_o is not None else do + 0.55 * g.D,
            D_s=self.D_s if self.D_s is not None else di - 0.55 * g.D,
            D_Lo=self.D_Lo if self.D_Lo is not None else g.dm + 0.7 * g.D,
            D_Li=self.D_Li if self.D_Li is not None else g.dm - 0.7 * g.D,
        )
        r["D_h"] = self.D_h if self.D_h is not None else 1.6 * r["D_o"]
        r["L_h"] = self.L_h if self.L_h is not None else 2.0 * g.width
        if not r["D_s"] < r["D_Li"] < r["D_Lo"] < r["D_o"] < r["D_h"]:
            raise BearingInputError("D_s < D_Li < D_Lo < D_o < D_h", {k: r[k] for k in ("D_s", "D_Li", "D_Lo",
                                                                                         "D_o", "D_h")},
                                    "increasing diameters from shaft to housing")
        axes = (self.a_i, self.b_i, self.a_o, self.b_o)
        if any(v is None for v in axes):
            hz = _hertz_axes(g, self.ball_load)
            axes = tuple(h if v is None else v for v, h in zip(axes, hz))
        r["a_i"], r["b_i"], r["a_o"], r["b_o"] = axes
        return r


def _hertz_axes(g, Q):
    """Hertz semi-axes (a_i, b_i, a_o, b_o) [m] of a ball load Q [N] at the free contact angle."""
    from ..contact.hertz import contact_curvature, reduced_modulus, hertz_exact
    E = reduced_modulus(g.ring_material.E, g.ring_material.nu, g.ball_material.E, g.ball_material.nu)
    out = []
    for f, inner in ((g.fi, True), (g.fo, False)):
        cur = contact_curvature(g.D, g.dm, f, g.alpha0, inner)
        hc = hertz_exact(cur[2], cur[3], E)
        out += [hc.a_coef * Q ** (1.0 / 3.0), hc.b_coef * Q ** (1.0 / 3.0)]
    return tuple(out)


# =============================================================================================
# network
# =============================================================================================
class ThermalNetwork:
    """Four-node thermal network of seed 001 (see module docstring).

    ThermalNetwork(geometry, oil='iso-vg32-mineral', data=ThermalData(), T0=None)
      T0: initial node temperatures [K] (scalar or 4 values; default data.T_amb).
    Attributes: T (4,) [K]; C (4,) [J/K]; L (4x4) [W/K]; g_amb, g_flow (4,) [W/K]; dims (dict, m);
    conductances (dict name -> W/K); ledger: E_generated, E_ambient, E_flow [J], time [s].
    Methods: node_heat(Q) -> q (4,) [W]; step(Q, dt) -> T; steady_state(Q) -> T (state unchanged);
    heat_to_ambient(T=None), heat_to_oil_flow(T=None) [W]; stored_energy() [J];
    energy_residual() [J] = E_generated - E_ambient - E_flow - stored (0 to round-off).
    """

    def __init__(self, geometry, oil="iso-vg32-mineral", data: ThermalData | None = None, T0=None):
        from ..lubrication.lubricants import get_oil

        self.g = geometry
        self.data = data if data is not None else ThermalData()
        self.oil = get_oil(oil)
        d = self.data
        r = self.data.resolved(geometry)
        self.dims = r
        g = geometry
        Z = g.Z
        k_ball, cp_ball = material_thermal(g.ball_material.name)
        k_ring, cp_ring = material_thermal(g.ring_material.name)
        _, cp_cage = material_thermal(g.cage.material)
        rho_steel = g.ring_material.density
        K = 2.0 / (1.0 / k_ball + 1.0 / k_ring)          # series average of ball and ring conductivity
        # ---- heat capacities (seed 001 Eq. 21: C = c_p rho V) --------------------------------------
        C_ball = Z * g.ball_mass * cp_ball
        V_housing = 0.25 * math.pi * (r["D_h"] ** 2 - r["D_o"] ** 2) * r["L_h"]
        C_outer = (g.outer_ring_mass + rho_steel * V_housing) * cp_ring
        V_shaft = 0.25 * math.pi * r["D_s"] ** 2 * r["L_h"]
        C_inner = (g.inner_ring_mass + rho_steel * V_shaft) * cp_ring
        V_free = 0.25 * math.pi * (r["D_Lo"] ** 2 - r["D_Li"] ** 2) * g.width - Z * math.pi * g.D ** 3 / 6.0 \
            - g.cage.mass / material_density(g.cage.material)
        V_free = max(V_free, 0.0)
        rho_oil = self.oil.density(d.T_in)
        cp_oil = self.oil.specific_heat(d.T_in)
        C_oil = d.oil_fill * V_free * rho_oil * cp_oil + g.cage.mass * cp_cage
        self.C = np.array([C_ball, C_outer, C_inner, C_oil])
        self.V_oil = d.oil_fill * V_free
        # ---- conductances (seed 001 Eqs. 26-29, corrections in the module docstring) ----------------
        self._k_ball, self._k_ring, self._K = k_ball, k_ring, K
        self._kappa_ball = k_ball / (g.ball_material.density * cp_ball)
        self._kappa_ring = k_ring / (rho_steel * cp_ring)
        if self.data.oil_fraction is not None:
            wetted = d.flow_rate > 0.0 or self.data.oil_fraction > 0.0
        else:
            wetted = d.flow_rate > 0.0 or d.oil_fill > 0.0
        if wetted:      # oil properties at the inlet temperature (module docstring)
            self._fluid = (self.oil.conductivity(d.T_in), self.oil.nu(d.T_in),
                           self.oil.eta(d.T_in) * cp_oil / self.oil.conductivity(d.T_in))
        else:
            self._fluid = (AIR_K, AIR_NU, AIR_PR)
        A_boil = Z * math.pi * g.D ** 2                                          # Eq. 28
        A_hoil = math.pi * r["D_Lo"] * r["L_h"]
        A_soil = math.pi * r["D_Li"] * r["L_h"]
        A_hatm = 0.5 * math.pi * (r["D_h"] ** 2 - r["D_Lo"] ** 2) + math.pi * r["D_h"] * r["L_h"]   # Eq. 29
        A_satm = 0.5 * math.pi * abs(r["D_s"] ** 2 - r["D_Li"] ** 2) + math.pi * r["D_s"] * d.L_shaft
        A_oilatm = A_boil + A_hoil + A_soil
        self.areas = dict(A_boil=A_boil, A_hoil=A_hoil, A_soil=A_soil, A_hatm=A_hatm, A_satm=A_satm,
                          A_oilatm=A_oilatm)
        G_hatm, G_satm = d.h_h_atm * A_hatm, d.h_s_atm * A_satm
        if d.fit_contact_resistance is not None and G_hatm > 0.0:      # ring -> fit -> housing wall -> air
            R_fit_o = d.fit_contact_resistance / (math.pi * r["D_o"] * g.width)
            R_wall = math.log(r["D_h"] / r["D_o"]) / (2.0 * math.pi * k_ring * r["L_h"])
            G_hatm = 1.0 / (R_fit_o + R_wall + 1.0 / G_hatm)
        if d.fit_contact_resistance is not None and G_satm > 0.0:      # ring -> fit -> shaft -> air
            R_fit_i = d.fit_contact_resistance / (math.pi * r["D_s"] * g.width)
            R_shaft = 0.5 * r["L_h"] / (k_ring * 0.25 * math.pi * r["D_s"] ** 2)
            G_satm = 1.0 / (R_fit_i + R_shaft + 1.0 / G_satm)
        self.conductances = dict(G_hatm=G_hatm, G_satm=G_satm, G_oilatm=d.h_oil_atm * A_oilatm)
        self.shaft_speed = None
        self.set_speed(d.shaft_speed)
        self.g_amb = np.array([0.0, G_hatm, G_satm, d.h_oil_atm * A_oilatm])
        self.m_dot = rho_oil * d.flow_rate
        self.g_flow = np.array([0.0, 0.0, 0.0, self.m_dot * cp_oil])
        self.g_out = self.g_amb + self.g_flow
        with np.errstate(invalid="ignore", divide="ignore"):
            self.T_out = np.where(self.g_out > 0, (self.g_amb * d.T_amb + self.g_flow * d.T_in)
                                  / np.where(self.g_out > 0, self.g_out, 1.0), d.T_amb)
        if not np.any(self.g_out > 0):
            raise BearingInputError("h_h_atm, h_s_atm, h_oil_atm, flow_rate", 0.0,
                                    "at least one path to ambient or oil flow > 0 (else no steady state)")
        T0 = d.T_amb if T0 is None else T0
        T0 = np.broadcast_to(np.asarray(T0, dtype=float), (4,)).copy()
        for k in range(4):
            check_range(f"T0[{NODES[k]}]", T0[k], 200.0, 600.0, unit="K")
        self.T = T0
        self.T_init = T0.copy()
        self.E_generated = 0.0
        self.E_ambient = 0.0
        self.E_flow = 0.0
        self.time = 0.0

    # ---- speed-dependent internal conductances ------------------------------------------------------
    def set_speed(self, shaft_speed: float):
        """Internal conductances [W/K] and the contact heat partition at the shaft speed [rad/s] (module
        docstring: moving-source contact resistances, flat-plate convection); no-op at an unchanged speed."""
        w = abs(check_range("shaft_speed", shaft_speed, -1e5, 1e5, unit="rad/s"))
        if self.shaft_speed is not None and w == self.shaft_speed:
            return
        self.shaft_speed = w
        g, d, r, Z = self.g, self.data, self.dims, self.g.Z
        gam = g.D * math.cos(g.alpha0) / g.dm
        U = w * g.dm * (1.0 - gam * gam) / 4.0          # rolling speed of the contact surfaces
        w_cage = w * (1.0 - gam) / 2.0
        if d.contact_model == "seed001":
            G_bh = Z * self._K * math.pi * r["a_o"] * r["b_o"] / (2.0 * r["a_o"])      # 1 / R_bh, Eq. 26
            G_bs = Z * self._K * math.pi * r["a_i"] * r["b_i"] / (2.0 * r["a_i"])      # 1 / R_bs, Eq. 26
            split_i = split_o = 0.5
        else:
            G, split = [], []
            for a_h, b_h in ((r["a_o"], r["b_o"]), (r["a_i"], r["b_i"])):
                a = math.sqrt(a_h * b_h)
                R_b = moving_source_resistance(self._k_ball, self._kappa_ball, a, U)
                R_r = moving_source_resistance(self._k_ring, self._kappa_ring, a, U)
                G.append(Z / (R_b + R_r))
                split.append(R_r / (R_b + R_r))                 # Blok: equal mean surface temperatures
            (G_bh, G_bs), (split_o, split_i) = G, split
        if d.contact_split is not None:
            split_i = split_o = d.contact_split
        self.split_i, self.split_o = split_i, split_o
        k_f, nu_f, Pr_f = self._fluid
        L_pitch = math.pi * g.dm / Z
        h_auto = dict(h_b_oil=flat_plate_h(U, g.D, k_f, nu_f, Pr_f),
                      h_s_oil=flat_plate_h((w - w_cage) * r["D_Li"] / 2.0, L_pitch, k_f, nu_f, Pr_f),
                      h_h_oil=flat_plate_h(w_cage * r["D_Lo"] / 2.0, L_pitch, k_f, nu_f, Pr_f))
        h = {k: (getattr(d, k) if getattr(d, k) is not None else max(v, H_OIL_MIN)) for k, v in h_auto.items()}
        self.h = h
        G_boil = h["h_b_oil"] * self.areas["A_boil"]                      # 1/R = h A (Eq. 27 corrected)
        G_hoil = h["h_h_oil"] * self.areas["A_hoil"]
        G_soil = h["h_s_oil"] * self.areas["A_soil"]
        self.conductances.update(G_bh=G_bh, G_bs=G_bs, G_boil=G_boil, G_hoil=G_hoil, G_soil=G_soil)
        L = np.zeros((4, 4))
        for (i, j), Gij in (((I_BALL, I_OUTER), G_bh), ((I_BALL, I_INNER), G_bs), ((I_BALL, I_OIL), G_boil),
                            ((I_OUTER, I_OIL), G_hoil), ((I_INNER, I_OIL), G_soil)):
            L[i, i] += Gij
            L[j, j] += Gij
            L[i, j] -= Gij
            L[j, i] -= Gij
        self.L = L

    # ---- sources -------------------------------------------------------------------------------
    def node_heat(self, Q_sources: dict) -> np.ndarray:
        """Heat input per node [W] from the seed's source keys (mapping in the module docstring)."""
        d = self.data
        q = np.zeros(4)
        self._last_sources = dict(Q_sources)
        guide = self.g.cage.guidance
        cg_node = I_OUTER if guide == "outer" else (I_INNER if guide == "inner" else I_OIL)
        for key, v in Q_sources.items():
            if key not in SOURCES:
                raise BearingInputError("Q_sources key", key, "one of " + ", ".join(SOURCES))
            v = check_range(key, v, 0.0, 1e8, unit="W")
            if key == "Q_br_i":
                q[I_BALL] += self.split_i * v
                q[I_INNER] += (1.0 - self.split_i) * v
            elif key == "Q_br_o":
                q[I_BALL] += self.split_o * v
                q[I_OUTER] += (1.0 - self.split_o) * v
            elif key == "Q_bp":
                q[I_BALL] += d.pocket_split * v
                q[I_OIL] += (1.0 - d.pocket_split) * v
            elif key == "Q_cg":
                q[cg_node] += v
            elif key in ("Q_ch_c", "Q_oil_work"):
                q[I_OIL] += v
            elif key in ("Q_ch_b", "drag"):
                q[I_BALL] += v
            elif key == "Q_ch_s":
                q[I_INNER] += v
        return q

    # ---- integration ---------------------------------------------------------------------------
    def step(self, Q_sources: dict, dt: float) -> np.ndarray:
        """Advance by dt [s] with constant sources (backward Euler, seed 001 Eqs. 22-25); returns T [K]."""
        check_range("dt", dt, 0.0, 1e7, lo_incl=False, unit="s")
        q = self.node_heat(Q_sources)
        T1 = thermal_be_step(self.C, self.L, self.g_out, self.T_out, q, self.T, float(dt))
        # ledger, consistent with the implicit step: losses at T1
        self.E_generated += q.sum() * dt
        self.E_ambient += self.heat_to_ambient(T1) * dt
        self.E_flow += self.heat_to_oil_flow(T1) * dt
        self.T = T1
        self.time += dt
        return T1.copy()

    def steady_state(self, Q_sources: dict, set_state: bool = False) -> np.ndarray:
        """Steady node temperatures [K] for constant sources (state unchanged unless set_state)."""
        T = thermal_steady(self.L, self.g_out, self.T_out, self.node_heat(Q_sources))
        if set_state:
            self.T = T.copy()
        return T

    # ---- outputs -------------------------------------------------------------------------------
    def temperatures(self) -> dict:
        return {n: float(t) for n, t in zip(NODES, self.T)}

    def heat_to_ambient(self, T=None) -> float:
        """Heat rejected to the ambient air [W] at node temperatures T (default: current)."""
        T = self.T if T is None else np.asarray(T)
        return float(np.dot(self.g_amb, T - self.data.T_amb))

    def heat_to_oil_flow(self, T=None) -> float:
        """Heat carried away by the circulating oil, m_dot c_p (T_oil - T_in) [W]."""
        T = self.T if T is None else np.asarray(T)
        return float(np.dot(self.g_flow, T - self.data.T_in))

    def stored_energy(self) -> float:
        """sum C (T - T_init) [J]."""
        return float(np.dot(self.C, self.T - self.T_init))

    def energy_residual(self) -> float:
        """E_generated - E_ambient - E_flow - stored [J] (zero to round-off for the backward-Euler ledger)."""
        return self.E_generated - self.E_ambient - self.E_flow - self.stored_energy()

    @property
    def T_max(self) -> float:
        """Temperature limit [K] of the network's oil (OIL_T_MAX)."""
        return oil_temperature_limit(self.oil.name)

    def runaway(self, T=None) -> bool:
        """True when a node temperature (default: current) is past the oil's limit, or not finite."""
        T = self.T if T is None else np.asarray(T)
        return bool(not np.all(np.isfinite(T)) or np.max(T) > self.T_max)

    def runaway_cause(self) -> str:
        """The hottest node's heat input by source (of the last sources given) and its paths out [W/K]."""
        T = self.temperatures()
        hot = max(T, key=T.get)
        k = NODES.index(hot)
        src = getattr(self, "_last_sources", {})
        parts = {key: self.node_heat({key: v})[k] for key, v in src.items()}
        self._last_sources = src
        tot = sum(parts.values())
        top = sorted(((v, key) for key, v in parts.items() if v > 0.005 * tot), reverse=True)[:3]
        shares = ", ".join(f"{key} {100.0 * v / tot:.0f} %" for v, key in top) if tot > 0 else "none"
        paths = [f"{NODES[j]} {-self.L[k, j]:.3g}" for j in range(4) if j != k and self.L[k, j] < 0.0]
        if self.g_amb[k] > 0:
            paths.append(f"ambient {self.g_amb[k]:.3g}")
        if self.g_flow[k] > 0:
            paths.append(f"oil flow {self.g_flow[k]:.3g}")
        return (f"node '{hot}' takes {tot:.0f} W ({shares}); its conductances out [W/K]: "
                + ", ".join(paths) + f"; all nodes reject {self.heat_to_ambient() + self.heat_to_oil_flow():.0f} W"
                + f" (to ambient {self.heat_to_ambient():.0f} W, to the oil flow {self.heat_to_oil_flow():.0f} W)")

    def check_runaway(self, where: str = ""):
        """Raise ThermalRunaway (naming the node and the cause) if runaway()."""
        if self.runaway():
            raise ThermalRunaway(self.temperatures(), self.T_max, self.oil.name, where, self.runaway_cause())

    def time_constants(self) -> np.ndarray:
        """Thermal time constants [s] of the network: 1 / eigenvalues of C^-1 (L + diag(g_out))."""
        A = (self.L + np.diag(self.g_out)) / self.C[:, None]
        return np.sort(1.0 / np.real(np.linalg.eigvals(A)))[::-1]


def material_density(name: str) -> float:
    from ..bearing.materials import get_material
    return get_material(name).density
