"""Oil supply of the bearing and the effective oil content of its cavity.

The ball drag, the cage / ring churning (bearing_core.lubrication.churning) and the dynamics' drag all act in an oil-air
mixture of oil volume fraction X (linear mixing of density and viscosity). X is set here from how the oil
is supplied, the input users know: ``OilSupply(method, flow_rate, T_in, oil_level, bath_model)``.

Methods and their cavity oil fraction X [-] (``cavity_oil_fraction``):

* ``jet`` (circulating oil, jets into the bearing) and ``oil-air`` (mist / oil-air, a small oil flow
  carried by air): the empirical correlation of Parker for jet-lubricated high-speed ball bearings
  (R. J. Parker, 'Comparison of predicted and experimental thermal performance of angular-contact ball
  bearings', NASA TP-2275, 1984; used for the fluid drag of the balls in SHABERTH and quoted in Harris &
  Kotzalas, Rolling Bearing Analysis 5th ed. (2007), Vol. 2, Ch. 3 'fluid drag'):

      X_cav = 1e5 W^0.37 / (n d_m^1.7)      [percent of the free volume]      (Parker)
      W oil flow [cm^3/min], n shaft speed [rpm], d_m pitch diameter [mm].

  Neither the report nor the book could be read here. Searched (stored copies of public web pages,
  documentation, code and issue threads): 'Parker 1984 NASA TP-2275 comparison of predicted and
  experimental thermal performance', 'percent oil in bearing cavity X_cav = 10^5 W^0.37 / (n dm^1.7)',
  'SHABERTH fluid drag percent oil in cavity oil-air mixture', 'SHABERTH operation manual input percent
  of lubricant', 'Xcav oil percentage bearing cavity effective density', 'effective lubricant volume
  fraction bearing cavity empirical formula 0.37 1.7', exact-string look-ups 'dm**1.7', 'dm^1.7', 'Xcav'.
  Found: the SHABERTH operation manual (AFAPL-TR-76-90) and TN D-7870 only as title pages; no text of
  the correlation. The form, exponents and coefficient are therefore quoted from memory, and so is its
  unit: PERCENT of the free cavity volume (X = X_cav / 100 as a fraction).
  Why percent and not a fraction -- from the energy balance of the NASA runs, not from their measured heat:
  the 35-mm bore bearing ran 'successfully ... up to 2.5 million DN' with 303-1894 cm^3/min of ester oil
  entering at 394 K (TP-1732 summary). Read as a fraction, X_cav at 72,000 rpm and 303 cm^3/min (d_m
  53.5 mm) is 0.013, and the ball drag alone (bearing_core.lubrication.churning.ball_drag_power, cd 0.5,
  12 balls of 11.9 mm on 53.5 mm, oil 900 kg/m^3) is 2.3 kW; the oil flow carries m_dot c_p = 9 W/K,
  so the oil would leave 250 K above its inlet, at ~640 K, far past the 473 K limit of the ester (and
  the rings could not stay near the inlet temperature): the runs could not have been 'successful'. Read
  as percent, the drag is 0.23 kW and the oil rise 25 K -- consistent. (At 758 cm^3/min the fraction
  reading still puts the oil at ~530 K; only at the largest flow, 1894, would it stay just below the
  limit, 469 K.) tests/test_oil_bath_skf.py repeats this with the library. This uses only the published
  operating conditions and the statement of successful running, not the measured heat the validation
  cases compare with.
  Validity: the NASA jet-lubricated angular-contact ball bearing tests of that period, e.g. the
  35-mm bore bearing at 48,000-72,000 rpm (2.5 million DN) with 303-1894 cm^3/min (Schuller, Pinel &
  Signer, NASA TP-1732, 1980, summary) and the 120-mm bore bearing to 25,000 rpm (3 million DN; Bamberger,
  Zaretsky & Signer, NASA TN D-7870, 1975, abstract); taken here as n d_m 0.5e6-4.0e6 mm rpm (d_m about
  1.2-1.4 times the bore for these bearings) and 300-20,000 cm^3/min (the upper end recalled, not read).
  Outside this range the value is flagged ``extrapolated`` (always for oil-air: flows of cm^3 per hour).
  The trend is physical: more flow -> more oil in the cavity (sublinear, W^0.37), higher speed and a
  larger bearing -> the oil is flung out faster (1/n, d_m^-1.7).
* ``bath``: oil bath with a static oil level H [m] above the lowest point of the outer raceway (groove
  bottom; SKF's H). Two estimates (``cavity_oil_fraction(..., bath_model=...)``):
  - ``skf`` (default): SKF's (2004) oil-bath drag term, M_drag = V_M(H/d_m) K_ball d_m^5 n^2
    (friction_models.skf_drag_torque, V_M from SKF's diagram, figure-digitised by a third party), taken
    as the drag of the balls in the cavity mixture: X is the oil fraction whose ball drag power (Harris &
    Kotzalas' ball drag as in churning.ball_drag_power, cd 0.5, orbit speed w (1 - gamma)/2 with the outer
    ring fixed) equals M_drag w. Both grow as n^2, so X does not depend on the speed. The oil density is
    taken as RHO_OIL_NOMINAL = 870 kg/m^3 (the oils of the library lie within +-5 %). Bore and outside
    diameter for K_ball: the preset's, else estimated from the raceways
    (friction_models.bearing_envelope_mm). Levels above 1.2 d_m are taken at 1.2 d_m (SKF) and flagged.
  - ``geometric``: the orbit-averaged submerged share of the cavity's annular cross-section between the
    raceway diameters (a first-principles geometric estimate, not a correlation):
      X = [S(r_o, y) - S(r_i, y)] / [pi (r_o^2 - r_i^2)],   y = H - r_o,
    S(r, y) the area of the disc of radius r below the horizontal line y (circle-segment formula),
    r_o, r_i the outer and inner raceway radii. The validation case skf-oil-bath-drag-7218B compares the
    drag this gives (balls, cage and inner-ring churning) with SKF's drag term.
  Flow rate optional (circulating bath); 0 = standing bath.
* ``grease``: no free oil in the cavity: after running-in the grease is channelled out of the path of the
  balls and cage and the bearing runs on the base oil bleeding into the contacts (P. M. Lugt, 'A review on
  grease lubrication in rolling bearings', Tribology Transactions 52 (2009) 470). X = 0 (air); no oil flow.

``oil_fraction`` given explicitly (CLI ``--oil-fraction``, FMU ``oil_fraction`` > 0) overrides all of this.

Work of the supply oil (``supply_oil_work``): the oil that goes through the bearing enters without swirl
and leaves the rotating parts with their tangential speed, so the rotating parts give it angular momentum.
By the angular-momentum balance of a steady through-flow (Euler's turbomachine equation, L. Euler 1754;
S. L. Dixon, C. A. Hall, Fluid Mechanics and Thermodynamics of Turbomachinery, 7th ed. (2014), Ch. 1,
'Euler work equation': torque = m_dot (r2 c_u2 - r1 c_u1), power = torque x the body's angular speed),
with the jet aimed at the inner ring (between the inner ring and the cage, ASSUMED: the arrangement of the
NASA jet-lubricated tests as we recall it, not read) the oil first takes the inner ring's speed at its
land radius r_i, then leaves the rotating set at the cage's outer surface r_c with the cage's speed:

    P_oil = m_dot [w^2 r_i^2 + w_c (w_c r_c^2 - w r_i^2)]        [W]

the inner ring's work w (m_dot w r_i^2), and the cage's, w_c times the change of the oil's angular
momentum across it (negative: faster oil drives the cage, which then needs less drive from the balls).
The power is drawn from the shaft (through the ring, and through the balls for the cage); half of the
exit kinetic energy m_dot (w_c r_c)^2 / 2 leaves with the oil and is dissipated downstream in the same
oil, the rest in the bearing, so all of it heats the oil. Upper and lower bounds of the same balance:
oil that leaves with the inner ring's speed (m_dot w^2 r_i^2) or is accelerated by the cage alone (m_dot
w_c^2 r_c^2). In the dynamics it would add to the drive torque of the inner ring, whose speed is
prescribed, and give the cage a small torque; it is taken as a heat source of the thermal network
(thermal.SOURCES 'Q_oil_work'), not as a load, so the dynamics' records (friction torque, P_drive) do not
include it; DynamicModel.thermal_equilibrium adds it to its drive power and friction torque. Bath and
grease: 0 (no through-flow to accelerate; a circulating bath's flow enters the bath, not the rotating
set). The mass of the carrier air of oil-air lubrication is not counted.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import BearingInputError, check_range

METHODS = ("jet", "oil-air", "bath", "grease")
BATH_MODELS = ("skf", "geometric")
RHO_OIL_NOMINAL = 870.0      # kg/m^3, oil density of the SKF-equivalent bath fraction (module docstring)
CD_BALL = 0.5                # ball drag coefficient, as the dynamics' default (DynamicsOptions.cd)

# Parker's correlation (module docstring): coefficient, flow and size exponents; units cm^3/min, rpm, mm
PARKER_COEF = 1.0e5
PARKER_W_EXP = 0.37
PARKER_DM_EXP = 1.7
# stated validity of the correlation (as recalled, module docstring)
PARKER_NDM_RANGE = (0.5e6, 4.0e6)        # n d_m [mm rpm]
PARKER_W_RANGE = (300.0, 20000.0)        # [cm^3/min]


@dataclass(frozen=True)
class OilSupply:
    """How the oil reaches the bearing (SI).

    method: 'jet' | 'oil-air' | 'bath' | 'grease'; flow_rate [m^3/s] of oil through the bearing (jet and
    oil-air need > 0; bath optional; grease 0); T_in [K] oil supply temperature; oil_level [m] (bath only):
    static level above the lowest point of the outer raceway; bath_model: 'skf' | 'geometric', the bath's
    oil-content estimate (module docstring)."""

    method: str = "jet"
    flow_rate: float = 0.0
    T_in: float = 313.15
    oil_level: float | None = None
    bath_model: str = "skf"

    def validate(self):
        if self.method not in METHODS:
            raise BearingInputError("lubrication method", self.method, "one of " + ", ".join(METHODS))
        if self.bath_model not in BATH_MODELS:
            raise BearingInputError("bath_model", self.bath_model, " | ".join(BATH_MODELS))
        check_range("oil flow_rate", self.flow_rate, 0.0, 0.1, unit="m^3/s")
        check_range("oil inlet temperature T_in", self.T_in, 233.15, 473.15, unit="K")
        if self.method in ("jet", "oil-air") and self.flow_rate <= 0.0:
            raise BearingInputError("oil flow_rate", self.flow_rate, f"> 0 m^3/s for lubrication method "
                                    f"'{self.method}' (the oil content of the cavity follows from the flow)")
        if self.method == "grease" and self.flow_rate != 0.0:
            raise BearingInputError("oil flow_rate", self.flow_rate, "0 for lubrication method 'grease'")
        if self.method == "bath":
            if self.oil_level is None:
                raise BearingInputError("oil_level", None, "a level >= 0 m for lubrication method 'bath'")
            check_range("oil_level", self.oil_level, 0.0, 10.0, unit="m")
        elif self.oil_level is not None:
            raise BearingInputError("oil_level", self.oil_level,
                                    f"none for lubrication method '{self.method}' (bath only)")
        return self


@dataclass(frozen=True)
class CavityOil:
    """Oil content of the cavity: fraction X [-] of the free volume, the method and formula it came from,
    extrapolated = outside the stated validity of the correlation, note = why."""

    fraction: float
    method: str
    formula: str
    extrapolated: bool = False
    note: str = ""

    def as_dict(self) -> dict:
        return {"oil_fraction": self.fraction, "method": self.method, "formula": self.formula,
                "extrapolated": self.extrapolated, "note": self.note}


def parker_fraction(flow_rate: float, n_rpm: float, dm: float) -> tuple[float, bool, str]:
    """Parker's cavity oil fraction X [-] (module docstring) for flow_rate [m^3/s], shaft speed n_rpm
    [rpm], pitch diameter dm [m]; returns (X, extrapolated, note). X is capped at 1 (flooded)."""
    check_range("oil flow_rate", flow_rate, 0.0, 0.1, lo_incl=False, unit="m^3/s")
    check_range("shaft speed", n_rpm, 0.0, 1e6, lo_incl=False, unit="rpm")
    check_range("pitch diameter dm", dm, 0.0, 10.0, lo_incl=False, unit="m")
    W = flow_rate * 6.0e7                 # m^3/s -> cm^3/min
    dm_mm = dm * 1e3
    X = min(PARKER_COEF * W ** PARKER_W_EXP / (n_rpm * dm_mm ** PARKER_DM_EXP) / 100.0, 1.0)
    ndm = n_rpm * dm_mm
    notes = []
    if not PARKER_NDM_RANGE[0] <= ndm <= PARKER_NDM_RANGE[1]:
        notes.append(f"n dm = {ndm:.3g} mm rpm outside {PARKER_NDM_RANGE[0]:.2g}-{PARKER_NDM_RANGE[1]:.2g}")
    if not PARKER_W_RANGE[0] <= W <= PARKER_W_RANGE[1]:
        notes.append(f"flow {W:.3g} cm^3/min outside {PARKER_W_RANGE[0]:g}-{PARKER_W_RANGE[1]:g}")
    return X, bool(notes), "; ".join(notes)


def _disc_area_below(r: float, y: float) -> float:
    """Area of the disc of radius r centred at 0 below the horizontal line at height y."""
    if y <= -r:
        return 0.0
    if y >= r:
        return math.pi * r * r
    return r * r * math.acos(-y / r) + y * math.sqrt(r * r - y * y)


def bath_fraction(oil_level: float, r_inner: float, r_outer: float) -> float:
    """Orbit-averaged oil fraction [-] of the annulus r_inner < r < r_outer [m] in a bath whose level is
    oil_level [m] above the annulus' lowest point (module docstring)."""
    check_range("oil_level", oil_level, 0.0, 10.0, unit="m")
    if not 0.0 < r_inner < r_outer:
        raise BearingInputError("raceway radii", (r_inner, r_outer), "0 < r_inner < r_outer")
    y = oil_level - r_outer
    return (_disc_area_below(r_outer, y) - _disc_area_below(r_inner, y)) / (math.pi * (r_outer ** 2 - r_inner ** 2))


def skf_bath_fraction(oil_level: float, geometry, cd: float = CD_BALL,
                      rho_oil: float = RHO_OIL_NOMINAL) -> tuple[float, bool, str]:
    """Oil fraction X [-] of the cavity mixture whose ball drag equals SKF's (2004) oil-bath drag term at the
    oil level oil_level [m] (module docstring, bath model 'skf'); returns (X, extrapolated, note). X is
    capped at 1 (flooded)."""
    from .churning import ball_drag_power
    from .friction_models import VM_H_CAP, bearing_envelope_mm, skf_drag_torque
    check_range("oil_level", oil_level, 0.0, 10.0, unit="m")
    check_range("cd", cd, 0.0, 5.0, lo_incl=False)
    check_range("rho_oil", rho_oil, 500.0, 2000.0, unit="kg/m^3")
    g = geometry
    d_mm, D_mm, how = bearing_envelope_mm(g)
    n = 1000.0                                    # any speed: both drags grow as n^2
    w = n * math.pi / 30.0
    M = skf_drag_torque(d_mm, D_mm, n, oil_level * 1e3)
    w_m = 0.5 * w * (1.0 - g.D * math.cos(g.alpha0) / g.dm)      # orbit speed, outer ring fixed
    P1 = ball_drag_power(1.0, cd, w_m, g.dm, g.D, int(g.Z))       # ball drag power per kg/m^3 of mixture
    rho_eq = M * w / P1
    X = (rho_eq - 1.2) / (rho_oil - 1.2)
    notes = []
    if oil_level * 1e3 > VM_H_CAP * 0.5 * (d_mm + D_mm):
        notes.append(f"level above {VM_H_CAP} dm taken at {VM_H_CAP} dm (SKF)")
    if X > 1.0:
        notes.append(f"SKF's drag needs X = {X:.3g} > 1: capped at 1 (flooded)")
    extrapolated = bool(notes)
    if how != "preset":
        notes.append(f"bore and outside diameter {how}")
    return min(max(X, 0.0), 1.0), extrapolated, "; ".join(notes)


def cavity_oil_fraction(supply: OilSupply, geometry, n_rpm: float, bath_model: str | None = None) -> CavityOil:
    """Effective oil fraction of the bearing cavity for the supply at shaft speed n_rpm [rpm] (module
    docstring). geometry: BearingGeometry (pitch and raceway diameters); bath_model: 'skf' | 'geometric'
    (bath only, module docstring; None: the supply's bath_model)."""
    supply.validate()
    if bath_model is None:
        bath_model = supply.bath_model
    if bath_model not in BATH_MODELS:
        raise BearingInputError("bath_model", bath_model, " | ".join(BATH_MODELS))
    m = supply.method
    if m in ("jet", "oil-air"):
        X, ext, note = parker_fraction(supply.flow_rate, n_rpm, geometry.dm)
        if m == "oil-air":
            ext, note = True, "oil-air: Parker's jet correlation extrapolated to a mist flow" + (
                "; " + note if note else "")
        return CavityOil(X, m, "Parker (NASA TP-2275): X[%] = 1e5 W^0.37 / (n dm^1.7)", ext, note)
    if m == "bath":
        if bath_model == "skf":
            X, ext, note = skf_bath_fraction(supply.oil_level, geometry)
            return CavityOil(X, m, "SKF (2004) oil-bath drag M_drag = V_M(H/dm) K_ball dm^5 n^2 as ball drag "
                                   "(V_M figure-digitised)", ext, note)
        X = bath_fraction(supply.oil_level, 0.5 * geometry.inner_raceway_diameter,
                          0.5 * geometry.outer_raceway_diameter)
        return CavityOil(X, m, "submerged share of the cavity annulus below the oil level (geometric)")
    return CavityOil(0.0, m, "channelled grease: no free oil in the cavity (Lugt 2009)")


def supply_oil_work(supply: OilSupply, rho_oil: float, omega: float, omega_cage: float, r_ring: float,
                    r_cage: float) -> float:
    """Power [W] the rotating parts spend on the supply oil (module docstring 'Work of the supply oil'):
    m_dot [w^2 r_i^2 + w_c (w_c r_c^2 - w r_i^2)], m_dot = rho_oil [kg/m^3] x the supply's flow [m^3/s];
    omega, omega_cage [rad/s] inner-ring and cage speeds relative to the outer ring; r_ring [m] radius of
    the inner-ring land the jet hits; r_cage [m] outer radius of the cage. 0 for bath and grease. Never
    negative (a cage faster than the ring is not a physical steady state; clipped at 0)."""
    supply.validate()
    check_range("rho_oil", rho_oil, 500.0, 2000.0, unit="kg/m^3")
    check_range("omega", omega, -1e5, 1e5, unit="rad/s")
    check_range("omega_cage", omega_cage, -1e5, 1e5, unit="rad/s")
    check_range("r_ring", r_ring, 0.0, 5.0, lo_incl=False, unit="m")
    check_range("r_cage", r_cage, 0.0, 5.0, lo_incl=False, unit="m")
    if supply.method not in ("jet", "oil-air"):
        return 0.0
    m_dot = rho_oil * supply.flow_rate
    w, wc = abs(omega), abs(omega_cage)
    return max(m_dot * (w * w * r_ring * r_ring + wc * (wc * r_cage * r_cage - w * r_ring * r_ring)), 0.0)
