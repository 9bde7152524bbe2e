"""Oil churning and ball drag losses of an oil-flooded ball bearing (seed 001, Gao et al., Friction 2022,
section 2.2.2, Eqs. 10, 12-17), as powers [W] and as the equivalent drag torques / forces on the bodies
(power / speed), so that the dynamics can apply them and stay energy consistent (torque x relative speed =
dissipated power, exactly).

Rotating-cylinder churning (cage, Eq. 15; inner ring, Eq. 17)
-------------------------------------------------------------
    Q = pi rho mu_v w^3 B D^4 / 64                                      (seed 001 Eqs. 15, 17)
with the viscous friction coefficient mu_v from the Reynolds and Taylor numbers (Eqs. 12-14, after Harris,
SLE Trans. 9(3) 229, 1966, and Rumbarger et al., ASME J. Lubr. Technol. 95(4) 401, 1973):
    laminar            mu_l = 16 / Re                                    (Eq. 12)
    Taylor vortices    mu_v = 1.3 mu_l (Ta / 41)^0.539474                (Eq. 13)
    turbulent Couette  mu_v = 3.0 mu_l (Re / 2500)^0.85596               (Eq. 14)

Definitions we had to fix (the seed writes Re = R w c / eta and Ta = Re sqrt(c / R) without saying which
clearance c, and with the dynamic viscosity eta where a Reynolds number needs rho / eta):

* Re = rho |w| R c / eta with c = 2 c_r, the DIAMETRAL clearance (c_r = radial gap). This is the only
  reading under which the laminar branch (Eqs. 12 + 15) is the exact concentric Couette (Petroff) loss,
  Q_lam = pi eta w^2 B D^3 / (4 c_r), and it is the clearance of the seed's own Eq. 5 (Petroff with c_g
  diametral). Checked in tests/test_churning.py against the Petroff torque 2 pi eta w R^3 B / c_r.
* Ta = rho |w| R c_r / eta * sqrt(c_r / R), Taylor's number on the RADIAL gap, for which the onset of
  Taylor vortices is Ta = 41.3 (G. I. Taylor, Phil. Trans. R. Soc. A 223, 289, 1923; narrow gap) --
  the seed's threshold 41. With the diametral c in Ta the vortex onset would fall at a Taylor number of
  41 / 2^1.5 = 14.5, contradicting Taylor; we do not do that.
* Regime order where the seed's conditions overlap ('laminar: Re < 2500 or Ta < 41'; 'vortex: Ta > 41';
  'turbulent: Re > 2500'): Re > 2500 -> turbulent Couette; else Ta > 41 -> vortex; else laminar.
* The published correlation is DISCONTINUOUS at the regime boundaries: mu_v jumps by the factor 1.3 at
  Ta = 41 (Re < 2500) and, at Re = 2500, from 1.3 (Ta/41)^0.539474 (or 1) to 3.0. We keep it as
  published (the tests check the jump factors); an integrator sees a step in the drag torque when a
  speed ramp crosses a boundary.
* The speed is the relative angular speed of the body and the wall across the gap. Seed 001 uses the
  absolute cage speed w_c (outer-guided cage, outer ring fixed) and the absolute inner-ring speed w_i;
  ``churning_losses`` does the same by default.

Ball drag (Eq. 16)
------------------
Seed 001 Eq. 16, Q_ch.b = c_d pi rho mu_v w_b^3 D_m^3 D_b N_b / (256 g), is not dimensionally a power
(kg/s with rho a mass density; one length short even with rho a weight density). The 'g' is the
English-unit weight density of Harris's ball drag force, F_v = c_v pi rho D^2 (d_m w_m)^1.95 / (32 g)
(Harris & Kotzalas, Rolling Bearing Analysis 5th ed., Vol. 2, Ch. 3, rho as weight density, the exponent
1.95 an empirical fit). We use its dimensionally consistent SI form with the mass density:
    F_d = c_d pi rho D^2 (d_m w_m)^2 / 32 = 1/2 c_d rho (pi D^2 / 4) u^2,  u = w_m d_m / 2   (seed 001 Eq. 10)
    Q_ch.b = Z F_d u = Z c_d pi rho D^2 d_m^3 w_m^3 / 64
which is exactly the drag the dynamics applies (dynamics_kernels: 0.5 rho_eff cd (pi D^2/4) v|v|), so
Q_ch.b and the dynamics' 'P_drag' are the same loss: use one of them. mu_v does not enter (Harris's drag
has no viscous friction coefficient; a mu_v ~ 16/Re factor would make the drag vanish at high speed).

Effective fluid: ``oil_fraction`` X in (0, 1] mixes oil and air linearly in density and viscosity
(rho = 1.2 + X (rho_oil - 1.2), as the dynamics does for ball drag; X = 1: flooded, as seed 001).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

from numba import njit

from ..errors import BearingInputError, check_range

REGIME_LAMINAR = 0
REGIME_VORTEX = 1
REGIME_TURBULENT = 2
REGIME_NAMES = ("laminar", "taylor-vortex", "turbulent-couette")
TA_CRIT = 41.0          # seed 001 Eq. 13 (Taylor 1923: 41.3)
RE_CRIT = 2500.0        # seed 001 Eq. 14
EXP_VORTEX = 0.539474   # seed 001 Eq. 13
EXP_TURB = 0.85596      # seed 001 Eq. 14


# =============================================================================================
# numba kernels (floats only; SI)
# =============================================================================================
@njit(cache=True)
def churning_numbers(rho, eta, R, w_rel, c_r):
    """(Re, Ta) of a cylinder of radius R [m] turning at w_rel [rad/s] relative to a wall across a radial
    gap c_r [m] in a fluid (rho [kg/m^3], eta [Pa s]). Re on the diametral clearance 2 c_r, Ta on the
    radial gap (see module docstring)."""
    Re_r = rho * abs(w_rel) * R * c_r / eta
    return 2.0 * Re_r, Re_r * math.sqrt(c_r / R)


@njit(cache=True)
def churning_regime(Re, Ta):
    """0 laminar, 1 Taylor vortex, 2 turbulent Couette (seed 001 Eqs. 12-14, order in module docstring)."""
    if Re > RE_CRIT:
        return REGIME_TURBULENT
    if Ta > TA_CRIT:
        return REGIME_VORTEX
    return REGIME_LAMINAR


@njit(cache=True)
def churning_factor(Re, Ta):
    """mu_v / mu_l: 1 (laminar, Eq. 12), 1.3 (Ta/41)^0.539474 (Eq. 13), 3.0 (Re/2500)^0.85596 (Eq. 14)."""
    reg = churning_regime(Re, Ta)
    if reg == REGIME_TURBULENT:
        return 3.0 * (Re / RE_CRIT) ** EXP_TURB
    if reg == REGIME_VORTEX:
        return 1.3 * (Ta / TA_CRIT) ** EXP_VORTEX
    return 1.0


@njit(cache=True)
def viscous_friction_coefficient(Re, Ta):
    """mu_v of seed 001 Eqs. 12-14 (mu_l = 16 / Re). Re > 0."""
    return 16.0 / Re * churning_factor(Re, Ta)


@njit(cache=True)
def cylinder_churning_torque(rho, eta, w_rel, B, D, c_r):
    """Churning drag torque [N m] on a cylinder (diameter D, wetted width B [m]) turning at w_rel [rad/s]
    relative to the wall across the radial gap c_r [m]; opposes w_rel. |T| w_rel = Q of seed 001
    Eqs. 15/17 = pi rho mu_v w^3 B D^4 / 64, written as the Petroff torque times mu_v / mu_l so that it is
    finite and zero at w_rel = 0."""
    if w_rel == 0.0:
        return 0.0
    Re, Ta = churning_numbers(rho, eta, 0.5 * D, w_rel, c_r)
    t_lam = math.pi * eta * abs(w_rel) * B * D ** 3 / (4.0 * c_r)
    return -math.copysign(t_lam * churning_factor(Re, Ta), w_rel)


@njit(cache=True)
def cylinder_churning_power(rho, eta, w_rel, B, D, c_r):
    """Churning loss [W] (>= 0) of seed 001 Eqs. 15/17; = -torque * w_rel."""
    return -cylinder_churning_torque(rho, eta, w_rel, B, D, c_r) * w_rel


@njit(cache=True)
def ball_drag_force(rho, cd, w_m, dm, D):
    """Drag force [N] on one ball orbiting at w_m [rad/s] on the pitch diameter dm [m] (seed 001 Eq. 10,
    Harris & Kotzalas Vol. 2 Ch. 3 in SI): -1/2 cd rho (pi D^2/4) u |u|, u = w_m dm / 2; opposes the
    orbital motion. Its moment about the bearing axis is force * dm / 2."""
    u = 0.5 * w_m * dm
    return -0.5 * cd * rho * (0.25 * math.pi * D * D) * u * abs(u)


@njit(cache=True)
def ball_drag_power(rho, cd, w_m, dm, D, Z):
    """Ball churning / drag loss [W] of Z balls: Z cd pi rho D^2 dm^3 |w_m|^3 / 64 (our SI reading of
    seed 001 Eq. 16, see module docstring)."""
    return -Z * ball_drag_force(rho, cd, w_m, dm, D) * 0.5 * w_m * dm


# =============================================================================================
# geometry of the churned surfaces
# =============================================================================================
@dataclass(frozen=True)
class ChurningGeometry:
    """Surfaces of seed 001 Eqs. 15-17 [m]. D_c, B_c, c_c: cage guided-surface diameter, cage width,
    radial gap at that surface (the guiding land gap for a ring-guided cage); D_Li, B_ir, c_s: inner-ring
    shoulder diameter, churned inner-ring width B_arc + 2 B_Li, radial gap between the inner-ring shoulder
    and the surrounding cage bore; dm, D, Z: pitch diameter, ball diameter, number of balls."""

    D_c: float
    B_c: float
    c_c: float
    D_Li: float
    B_ir: float
    c_s: float
    dm: float
    D: float
    Z: int

    def __post_init__(self):
        for nm in ("D_c", "B_c", "c_c", "D_Li", "B_ir", "c_s", "dm", "D"):
            check_range(nm, getattr(self, nm), 0.0, 10.0, lo_incl=False, unit="m")
        if not isinstance(self.Z, int) or self.Z < 1:
            raise BearingInputError("Z", self.Z, "integer >= 1")
        if self.c_c >= 0.5 * self.D_c:
            raise BearingInputError("c_c", self.c_c, f"< D_c / 2 = {0.5 * self.D_c} m")
        if self.c_s >= 0.5 * self.D_Li:
            raise BearingInputError("c_s", self.c_s, f"< D_Li / 2 = {0.5 * self.D_Li} m")

    @classmethod
    def from_bearing(cls, g, **overrides) -> "ChurningGeometry":
        """Defaults from a BearingGeometry (estimates, not from a source; override what you know):
        guided surface at dm/2 +- 0.35 D as in the dynamics' land model (dynamics.py P_RLAND), c_c =
        land_clearance / 2; inner-ring shoulder D_Li = dm - 0.7 D; cage width B_c = 0.8 x bearing
        width; B_ir = bearing width (= B_arc + 2 B_Li); c_s = land gap for an inner-ring-guided cage, else
        the gap to a cage bore at dm - 0.35 D, i.e. 0.175 D."""
        guide = g.cage.guidance
        D_Li = g.dm - 0.7 * g.D
        if guide == "inner":
            D_c = g.dm - 0.7 * g.D
            c_s = 0.5 * g.cage.land_clearance
        else:
            D_c = g.dm + 0.7 * g.D
            c_s = 0.175 * g.D
        d = dict(D_c=D_c, B_c=0.8 * g.width, c_c=max(0.5 * g.cage.land_clearance, 1e-6), D_Li=D_Li,
                 B_ir=g.width, c_s=c_s, dm=g.dm, D=g.D, Z=int(g.Z))
        for k in overrides:
            if k not in d:
                raise BearingInputError(k, overrides[k], "one of " + ", ".join(d))
        d.update(overrides)
        return cls(**d)


def churning_losses(geom, oil, T, omega_i, omega_c, omega_m=None, cd=0.5, oil_fraction=1.0,
                    cage_wall_speed=0.0, ir_wall_speed=0.0) -> dict:
    """Seed 001 churning losses and equivalent drag loads for one bearing.

    geom: ChurningGeometry or BearingGeometry (then ChurningGeometry.from_bearing); oil: name in
    lubricants.OILS (or a traction-curve name); T: oil temperature [K]; omega_i, omega_c: inner-ring and
    cage speeds [rad/s]; omega_m: ball orbital speed [rad/s] (default omega_c); cd: ball drag coefficient;
    oil_fraction: X of the churned medium (scales rho and eta). cage_wall_speed / ir_wall_speed: speed of
    the wall across each gap (default 0: the seed's absolute speeds).

    Returns Q_ch_c, Q_ch_b, Q_ch_s [W]; torque_cage, torque_ir [N m] (on the body, opposing its motion
    relative to the wall); force_ball [N] per ball (orbital direction); Re_*, Ta_*, regime_* for cage
    ('c') and inner ring ('s'); rho, eta used.
    """
    from .lubricants import get_oil

    if not isinstance(geom, ChurningGeometry):
        geom = ChurningGeometry.from_bearing(geom)
    o = get_oil(oil)
    check_range("oil_fraction", oil_fraction, 0.0, 1.0, lo_incl=False)
    check_range("cd", cd, 0.0, 5.0)
    for nm, v in (("omega_i", omega_i), ("omega_c", omega_c), ("cage_wall_speed", cage_wall_speed),
                  ("ir_wall_speed", ir_wall_speed)):
        check_range(nm, v, -1e5, 1e5, unit="rad/s")
    if omega_m is None:
        omega_m = omega_c
    check_range("omega_m", omega_m, -1e5, 1e5, unit="rad/s")
    # oil-air mixture as in the dynamics (dynamics.py: rho_eff = 1.2 + X (rho_oil - 1.2)); air viscosity
    # 1.8e-5 Pa s
    rho = 1.2 + oil_fraction * (o.density(T) - 1.2)
    eta = 1.8e-5 + oil_fraction * (o.eta(T) - 1.8e-5)
    wc = omega_c - cage_wall_speed
    ws = omega_i - ir_wall_speed
    Tc = cylinder_churning_torque(rho, eta, wc, geom.B_c, geom.D_c, geom.c_c)
    Ts = cylinder_churning_torque(rho, eta, ws, geom.B_ir, geom.D_Li, geom.c_s)
    Re_c, Ta_c = churning_numbers(rho, eta, 0.5 * geom.D_c, wc, geom.c_c)
    Re_s, Ta_s = churning_numbers(rho, eta, 0.5 * geom.D_Li, ws, geom.c_s)
    return dict(
        Q_ch_c=-Tc * wc, Q_ch_s=-Ts * ws,
        Q_ch_b=ball_drag_power(rho, cd, omega_m, geom.dm, geom.D, geom.Z),
        torque_cage=Tc, torque_ir=Ts, force_ball=ball_drag_force(rho, cd, omega_m, geom.dm, geom.D),
        Re_c=Re_c, Ta_c=Ta_c, regime_c=REGIME_NAMES[churning_regime(Re_c, Ta_c)],
        Re_s=Re_s, Ta_s=Ta_s, regime_s=REGIME_NAMES[churning_regime(Re_s, Ta_s)],
        rho=rho, eta=eta,
    )
