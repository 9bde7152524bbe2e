"""Ring growth and fits: operating internal geometry of a bearing from speed, temperatures and the
interference fits on shaft and housing (SI units: m, rad/s, Pa, K; temperatures in degC at the edges).

The rings are thick cylinders (plane stress, axially free; Timoshenko & Goodier, Theory of Elasticity,
3rd ed., McGraw-Hill 1970, Sec. 28 'thick-walled cylinder' (Lame) and Sec. 32 'rotating disks of uniform
thickness'); this is the treatment of Harris & Kotzalas, Rolling Bearing Analysis, 5th ed., Vol. 1, Ch.
'Fitting practice' / 'Internal clearance'. For an annulus a <= r <= b of density rho, modulus E,
Poisson ratio nu, turning at omega, with pressure p_a on the bore and p_b on the outside:

  rotation:  sigma_r = (3+nu)/8 rho omega^2 (a^2 + b^2 - a^2 b^2/r^2 - r^2)
             sigma_t = (3+nu)/8 rho omega^2 (a^2 + b^2 + a^2 b^2/r^2 - (1+3nu)/(3+nu) r^2)
  pressure:  sigma_r = (p_a a^2 - p_b b^2)/(b^2 - a^2) - (p_a - p_b) a^2 b^2 / ((b^2 - a^2) r^2)
             sigma_t = (p_a a^2 - p_b b^2)/(b^2 - a^2) + (p_a - p_b) a^2 b^2 / ((b^2 - a^2) r^2)
  radial displacement u(r) = r (sigma_t - nu sigma_r) / E   (plus r alpha_T dT for a uniform temperature)

A free ring's outer surface grows u(b) = rho omega^2 b ((3+nu) a^2 + (1-nu) b^2) / (4 E) with speed.

Fits. The shaft (solid, or hollow with bore d_s) and the inner ring are joined at the bore radius a = d/2
with diametral interference I (> 0 tight). Compatibility u_ring(a) - u_shaft(a) = I_eff / 2 with the
rotation of both parts and the contact pressure p >= 0 gives

  p = max(0, I_eff/2 - (u_ring,rot(a) - u_shaft,rot(a))) / (c_ring + c_shaft)
  c_ring  = a/E_r ((b^2 + a^2)/(b^2 - a^2) + nu_r),   c_shaft = a/E_s ((a^2 + d_s^2/4)/(a^2 - d_s^2/4) - nu_s)
  I_eff   = I + d (alpha_s (T_shaft - T_ref) - alpha_r (T_i - T_ref))    (thermal change of the fit)

(p = 0: the fit has been lost to speed or temperature, the ring is free on the seat). The outer ring
(bore b_o, outside c = D_o/2) in a housing of outside diameter D_h (inf: a thick housing) is treated the
same way with the pressure on its outside. For equal materials and a ring cylinder ending at the raceway
this gives Harris & Kotzalas' fit relations (recalled, Vol. 1 'Fitting practice'):
  inner raceway growth  Delta d_i = I (d/d_i) (1 - (d_s/d)^2) / (1 - (d_s/d_i)^2)
  outer raceway shrink  Delta d_o = I_h (d_o/D_o) (1 - (D_o/D_h)^2) / (1 - (d_o/D_h)^2)

Ring cross-sections are not cylinders: each ring is an equivalent cylinder whose free diameter is, unless
given, the SKF estimate of the mean ring diameter d_e = d + 0.3 (D_o - d) for the inner ring (SKF rolling
bearings catalogue, 'Tolerances for seats on hollow shafts': d_e estimate with k = 0.3 for ball
bearings) and D_o - 0.3 (D_o - d) for the outer ring; displacements are taken at the raceway (groove
bottom) radius within that cylinder (at its edge when the raceway lies outside it).

Balls grow alpha_b (T_b - T_ref) D; groove radii and groove offsets grow with their ring's temperature.
The operating diametral clearance is Pd' = d_o' - d_i' - 2 D'; the new free contact angle follows from
cos(alpha0') = 1 - Pd' / (2 A') (Harris & Kotzalas Vol. 1 Eq. 2.9) and is what operating_geometry()
returns as a BearingGeometry, so that every model (quasi-static, dynamics) uses the same function.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import BearingInputError, check_range
from .geometry import BearingGeometry
from .materials import Material, get_material

T_REF_C = 20.0   # degC, temperature at which bearing, shaft and housing dimensions are given (ISO 1)


@dataclass(frozen=True)
class RingFits:
    """Mounting of the rings (SI, m).

    shaft_interference / housing_interference: diametral interference of the inner ring on the shaft /
    the outer ring in the housing [m] (> 0 tight, <= 0 clearance fit: no pressure);
    shaft_bore: bore of a hollow shaft [m] (0: solid); housing_outer_diameter [m] (inf: thick housing);
    shaft_material, housing_material: names of bearing_core.bearing.materials;
    inner_ring_diameter: free diameter of the inner ring's equivalent cylinder [m] (None: d + 0.3 (D_o - d));
    outer_ring_bore: bore of the outer ring's equivalent cylinder [m] (None: D_o - 0.3 (D_o - d));
    bore, outside_diameter: bearing boundary dimensions d, D_o [m] (None: from the geometry)."""

    shaft_interference: float = 0.0
    housing_interference: float = 0.0
    shaft_bore: float = 0.0
    housing_outer_diameter: float = math.inf
    shaft_material: str = "steel"
    housing_material: str = "steel"
    inner_ring_diameter: float | None = None
    outer_ring_bore: float | None = None
    bore: float | None = None
    outside_diameter: float | None = None


@dataclass(frozen=True)
class OperatingTemperatures:
    """Bulk temperatures [degC]: inner ring, outer ring, balls, shaft (None: as the inner ring),
    housing (None: as the outer ring), reference (dimensions given at this temperature)."""

    inner_ring: float = T_REF_C
    outer_ring: float = T_REF_C
    balls: float = T_REF_C
    shaft: float | None = None
    housing: float | None = None
    reference: float = T_REF_C


@dataclass(frozen=True)
class RingGrowth:
    """Radial growth of the raceways (at the groove bottom) and ball growth [m], by cause, and the fit
    pressures [Pa]. Positive = larger diameter."""

    inner_centrifugal: float        # free-ring centrifugal growth of the inner raceway radius
    inner_fit: float                # growth of the inner raceway radius from the shaft pressure
    inner_thermal: float            # free thermal growth of the inner raceway radius
    outer_fit: float                # (negative) growth of the outer raceway radius from the housing pressure
    outer_thermal: float
    ball_diameter: float            # thermal growth of the ball diameter
    shaft_pressure: float           # [Pa]
    housing_pressure: float         # [Pa]
    shaft_fit_lost: bool            # the shaft fit has no pressure left (speed / temperature / loose fit)

    @property
    def inner_radius(self) -> float:
        """Total radial growth of the inner raceway [m]."""
        return self.inner_centrifugal + self.inner_fit + self.inner_thermal

    @property
    def outer_radius(self) -> float:
        """Total radial growth of the outer raceway [m]."""
        return self.outer_fit + self.outer_thermal

    @property
    def clearance_change(self) -> float:
        """Change of the diametral clearance, Delta Pd = 2 u_o - 2 u_i - 2 Delta D [m]."""
        return 2.0 * self.outer_radius - 2.0 * self.inner_radius - 2.0 * self.ball_diameter


# ---- thick cylinders (Timoshenko & Goodier Secs. 28, 32), plane stress --------------------------------
def rotating_annulus_u(r, a, b, omega, mat: Material) -> float:
    """Radial displacement [m] at radius r of a free annulus a <= r <= b (a = 0: solid disc) turning at
    omega [rad/s] (Timoshenko & Goodier Sec. 32)."""
    k = mat.density * omega ** 2
    nu = mat.nu
    a2, b2, r2 = a * a, b * b, r * r
    ab = a2 * b2 / r2 if a > 0 else 0.0
    sr = (3 + nu) / 8 * k * (a2 + b2 - ab - r2)
    st = (3 + nu) / 8 * k * (a2 + b2 + ab - (1 + 3 * nu) / (3 + nu) * r2)
    return r * (st - nu * sr) / mat.E


def lame_u(r, a, b, p_a, p_b, mat: Material) -> float:
    """Radial displacement [m] at radius r of an annulus a <= r <= b (a = 0: solid) under pressure p_a on
    the bore and p_b on the outside [Pa] (Lame; Timoshenko & Goodier Sec. 28)."""
    a2, b2, r2 = a * a, b * b, r * r
    if a == 0.0:
        return r * (-p_b) * (1 - mat.nu) / mat.E
    A_ = (p_a * a2 - p_b * b2) / (b2 - a2)
    B_ = (p_a - p_b) * a2 * b2 / ((b2 - a2) * r2)
    sr, st = A_ - B_, A_ + B_
    return r * (st - mat.nu * sr) / mat.E


def _bore_compliance(a, b, mat):
    """u(a) per unit bore pressure of an annulus a..b [m/Pa]."""
    return lame_u(a, a, b, 1.0, 0.0, mat)


def _outside_compliance(b, a, mat):
    """-u(b) per unit outside pressure of an annulus a..b (a = 0: solid) [m/Pa]."""
    return -lame_u(b, a, b, 0.0, 1.0, mat)


def _dimensions(g: BearingGeometry, fits: RingFits):
    d = fits.bore if fits.bore is not None else g.bore
    Do = fits.outside_diameter if fits.outside_diameter is not None else g.outside_diameter
    if not d > 0:
        raise BearingInputError("bore", d, f"0 < bore < inner raceway diameter {g.inner_raceway_diameter:.6g} m",
                                "give bore_diameter_mm in the bearing definition or RingFits.bore")
    if not Do > 0:
        raise BearingInputError("outside_diameter", Do, f"> outer raceway diameter {g.outer_raceway_diameter:.6g} m",
                                "give outside_diameter_mm in the bearing definition or RingFits.outside_diameter")
    check_range("bore", d, 0.0, g.inner_raceway_diameter, lo_incl=False, hi_incl=False, unit="m")
    check_range("outside_diameter", Do, g.outer_raceway_diameter, None, lo_incl=False, unit="m")
    de = fits.inner_ring_diameter if fits.inner_ring_diameter is not None else d + 0.3 * (Do - d)
    Db = fits.outer_ring_bore if fits.outer_ring_bore is not None else Do - 0.3 * (Do - d)
    check_range("inner_ring_diameter", de, d, None, lo_incl=False, unit="m")
    check_range("outer_ring_bore", Db, 0.0, Do, lo_incl=False, hi_incl=False, unit="m")
    check_range("shaft_bore", fits.shaft_bore, 0.0, d, hi_incl=False, unit="m")
    if not (fits.housing_outer_diameter > Do):
        raise BearingInputError("housing_outer_diameter", fits.housing_outer_diameter, f"> outside diameter {Do:.6g} m")
    for nm in ("shaft_interference", "housing_interference"):
        check_range(nm, getattr(fits, nm), -0.01 * d, 0.01 * d, unit="m")
    return d, Do, de, Db


def ring_growth(g: BearingGeometry, omega: float = 0.0, fits: RingFits | None = None,
                temperatures: OperatingTemperatures | None = None) -> RingGrowth:
    """Raceway and ball growth of bearing g with the inner ring (and shaft) turning at omega [rad/s], at
    the given temperatures, mounted with the given fits (None: free rings, no centrifugal growth unless
    the bore is known). See the module docstring for the equations."""
    omega = check_range("omega", omega, 0.0, 2.0e4, unit="rad/s")
    T = temperatures or OperatingTemperatures()
    for nm in ("inner_ring", "outer_ring", "balls", "reference"):
        check_range(f"temperatures.{nm}", getattr(T, nm), -80.0, 400.0, unit="degC")
    Ts = T.inner_ring if T.shaft is None else check_range("temperatures.shaft", T.shaft, -80.0, 400.0, unit="degC")
    Th = T.outer_ring if T.housing is None else check_range("temperatures.housing", T.housing, -80.0, 400.0,
                                                              unit="degC")
    rm, bm = g.ring_material, g.ball_material
    dTi, dTo, dTb = T.inner_ring - T.reference, T.outer_ring - T.reference, T.balls - T.reference
    ri_race, ro_race = 0.5 * g.inner_raceway_diameter, 0.5 * g.outer_raceway_diameter
    u_th_i = rm.expansion * dTi * ri_race
    u_th_o = rm.expansion * dTo * ro_race
    dD = bm.expansion * dTb * g.D
    if fits is None and not (g.bore > 0 and g.outside_diameter > 0):
        if omega > 0:
            raise BearingInputError("bore", g.bore, "> 0 for centrifugal ring growth",
                                    "give bore_diameter_mm / outside_diameter_mm or RingFits(bore=..., outside_diameter=...)")
        return RingGrowth(0.0, 0.0, u_th_i, 0.0, u_th_o, dD, 0.0, 0.0, True)
    fits = fits or RingFits()
    d, Do, de, Db = _dimensions(g, fits)
    sm, hm = get_material(fits.shaft_material), get_material(fits.housing_material)
    a, b = 0.5 * d, 0.5 * de
    r_i = min(ri_race, b)
    # inner ring on the shaft, both turning at omega
    u_cf_race = rotating_annulus_u(r_i, a, b, omega, rm)
    c_s = 0.5 * fits.shaft_bore
    u_ring_rot_a = rotating_annulus_u(a, a, b, omega, rm)
    u_shaft_rot_a = rotating_annulus_u(a, c_s, a, omega, sm)
    I_eff = fits.shaft_interference + d * (sm.expansion * (Ts - T.reference) - rm.expansion * dTi)
    comp = _bore_compliance(a, b, rm) + _outside_compliance(a, c_s, sm)
    p_s = max(0.0, 0.5 * I_eff - (u_ring_rot_a - u_shaft_rot_a)) / comp
    u_fit_i = lame_u(r_i, a, b, p_s, 0.0, rm)
    # outer ring in the housing (not turning)
    bo, c = 0.5 * Db, 0.5 * Do
    r_o = max(ro_race, bo)
    h = 0.5 * fits.housing_outer_diameter
    I_h = fits.housing_interference + Do * (rm.expansion * dTo - hm.expansion * (Th - T.reference))
    if math.isinf(h):
        c_h = c * (1.0 + hm.nu) / hm.E          # bore of an infinite plate under pressure (Lame, b -> inf)
    else:
        c_h = _bore_compliance(c, h, hm)
    comp_o = _outside_compliance(c, bo, rm) + c_h
    p_h = max(0.0, 0.5 * I_h) / comp_o
    u_fit_o = lame_u(r_o, bo, c, 0.0, p_h, rm)
    return RingGrowth(u_cf_race, u_fit_i, u_th_i, u_fit_o, u_th_o, dD, p_s, p_h, p_s <= 0.0)


def operating_geometry(g: BearingGeometry, omega: float = 0.0, fits: RingFits | None = None,
                       temperatures: OperatingTemperatures | None = None) -> BearingGeometry:
    """The bearing as it runs: raceway diameters, ball diameter, groove radii and offsets changed by
    ring_growth(); pitch diameter and free contact angle re-derived (Harris & Kotzalas Vol. 1 Eqs. 2.1,
    2.8, 2.9). Raises BearingInputError when no diametral clearance is left (the two-point description
    with a free contact angle does not exist then)."""
    gr = ring_growth(g, omega, fits, temperatures)
    T = temperatures or OperatingTemperatures()
    rm = g.ring_material
    di = g.inner_raceway_diameter + 2.0 * gr.inner_radius
    do = g.outer_raceway_diameter + 2.0 * gr.outer_radius
    D = g.D + gr.ball_diameter
    s_i = 1.0 + rm.expansion * (T.inner_ring - T.reference)
    s_o = 1.0 + rm.expansion * (T.outer_ring - T.reference)
    fi, fo = g.fi * g.D * s_i / D, g.fo * g.D * s_o / D
    Pd = do - di - 2.0 * D
    A = (fi + fo - 1.0) * D
    if Pd < 0.0:
        raise BearingInputError("operating diametral clearance", Pd, ">= 0 m",
                                f"{g.name}: fits, speed and temperatures take up the clearance "
                                f"{g.Pd*1e6:.2f} um by {-gr.clearance_change*1e6:.2f} um")
    c = 1.0 - Pd / (2.0 * A)
    alpha0 = math.acos(max(-1.0, c))
    return g.with_overrides(D=D, dm=0.5 * (di + do), fi=fi, fo=fo, alpha0=alpha0,
                            inner_groove_offset=g.inner_groove_offset * s_i,
                            outer_groove_offset=g.outer_groove_offset * s_o,
                            bore=g.bore, outside_diameter=g.outside_diameter)
