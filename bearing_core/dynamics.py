"""Transient tribo-dynamic bearing model: Python front end of bearing_core.dynamics_kernels.

    m = DynamicModel(load_preset("7218B"), DynamicsOptions(traction="lubricated"))
    m.initialize(omega=1000 * pi / 30, loads=(500, 0, 2000, 0, 0))   # quasi-static start
    rec = m.advance(0.1)                          # constant inputs
    rec = m.advance(0.2, omega_end=3000 * pi / 30)  # linear speed ramp over the interval

Every ``advance`` runs the whole time integration in compiled code; Python is entered once per call.
State layout, frames and signs: see the docstring of bearing_core.dynamics_kernels. SI units.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from . import contact_kernels as CK
from . import dynamics_kernels as K
from .errors import BearingInputError, ConvergenceError, check_range
from .geometry import BearingGeometry
from .hertz_tables import HertzInterp
from .lubricants import get_lubricant
from .quasistatic import quasistatic_model
from .session_kernels import same_point

TRACTION_MODELS = ("lubricated", "coulomb", "kalker", "lubricated-curve")
LUBRICATION_REGIMES = ("auto", "oil", "solid", "dry")
OIL_TRACTIONS = ("lubricated", "lubricated-curve")   # race traction laws of an oil-lubricated bearing
INTEGRATORS = ("rk4", "adaptive", "implicit", "auto", "adaptive-rk4")
METHOD_CODE = {"rk4": 0, "adaptive": 1, "implicit": 2, "adaptive-rk4": 3}
# stats: [0] accepted steps, [1] rejected, [2] rhs calls, [3] last step, [4] failure flag (kernels);
# integrator='auto' selector: current method, cost of the explicit and the implicit method [rhs
# equivalents / simulated s], intervals since the last probe, last step of each adaptive method (1, 2, 3)
ST_CUR, ST_C1, ST_C2, ST_AGE, ST_H1, ST_H2, ST_H3, NSTATS = 5, 6, 7, 8, 9, 10, 11, 12
ST_H = {1: ST_H1, 2: ST_H2, 3: ST_H3}
ROSW_LA_RHS = 1.0   # linear algebra of one Rosenbrock-W step attempt, in right-hand-side calls ('auto')
# The Rosenbrock-W method runs at 10x tighter absolute tolerances than the explicit ones on the balls'
# translational velocities. Its steps (5-7e-5 s at 1000 rpm) are set by atol alone, not by stability, and at
# the explicit methods' atol the window-mean friction torque came out 0.8 % low, which opened the energy
# balance by 1.1 % (7218B, 1000 rpm, Fx 1 kN, Fz 5 kN, free tilt; drive power against dissipation +
# d(KE)/dt over 0.05 s). Measured there, friction torque against the stability-limited adaptive RK4, and
# the implicit method's steps: -0.77 % at the explicit atol (742 steps in 0.05 s); 0.1x on every state
# -0.27 % (959); 0.1x on the ball velocities alone -0.30 % (862); on the ball angular velocities alone
# -0.45 % (840), on the rings and cage alone -0.49 % (861), on the ball positions alone -0.77 % (748);
# 0.01x on every state -0.07 % (1667).
IMPLICIT_ATOL_FACTOR = 0.1
AUTO_EXPLICIT = 3     # the explicit candidate of integrator='auto' (bench/bench_dynamics.py)
AUTO_PROBE = 25
AUTO_CHUNK = 5e-3   # [s] interval on which 'auto' chooses
COUPLINGS = ("load", "displacement")
START_MODELS = ("jones-harris", "tribological")


@dataclass(frozen=True)
class DynamicsOptions:
    """Model options (SI). traction: 'lubricated' (EHL traction from the oil's rheology over each contact
    ellipse with mixed lubrication by film parameter and the EHL rolling resistance, bearing_core.ehl_traction;
    the oil is ``oil`` or the one behind ``lubricant``; mu_boundary [-] the boundary friction coefficient of
    the asperity-borne load; rolling_resistance, ehl_thermal: the rolling-resistance moment and the shear
    heating of the film on/off), 'lubricated-curve' (the illustrative seed 002 curve of ``lubricant``),
    'coulomb' (mu, regularised as mu tanh(|v| / v_reg), v_reg [m/s]) or 'kalker' (FASTSIM with friction
    limit mu on a kalker_grid x kalker_grid grid, seed 000); u_min: floor of the entrainment speed [m/s];
    zeta: normal contact damping as a fraction of critical for the ball mass [-];
    integrator: 'rk4' (fixed dt, baseline), 'adaptive' (explicit Dormand-Prince 5(4), rtol),
    'adaptive-rk4' (explicit RK4 with an embedded order-3 FSAL error estimate, rtol: four right-hand
    sides per step against Dormand-Prince's six at the same stability-limited step), 'implicit'
    (Rosenbrock-W ROS34PW2 with the bearing's arrow-structured Jacobian, rtol; integrate_rosw) or 'auto'
    (per 5 ms chunk, whichever of 'adaptive-rk4' and 'implicit' costs less by their measured right-hand
    side counts: implicit wins where the traction is stiff, at low rolling speed and with Kalker creep
    forces);
    n_major x n_minor: quadrature points over each contact ellipse; reduced: 'auto' | 'full' |
    'axisymmetric' (one representative ball, pure axial load only); pocket/land: penalty stiffness
    [N/m], damping ratio, Coulomb friction; oil_fraction: oil volume fraction of the oil-air mixture for
    ball drag (seed 001 Eq. 10, drag coefficient cd); support_damping_ratio: viscous damping of the
    load-driven inner ring to ground (the shaft mounting), as a fraction of critical for each of its five
    modes on the quasi-static bearing stiffness. Without it the free ring is damped only by the contacts
    and a light ring whirls (self-excited by the traction); its force vanishes in steady state.
    fixed_tilt: the inner ring translates but cannot tilt (a stiff shaft held by other bearings); the
    moments are then reactions (outputs Mx, My), not loads. outer_mount: 'fixed' or 'elastic' (outer
    ring on a radial housing spring housing_stiffness [N/m] with damping ratio housing_damping_ratio on the
    outer-ring mass). land_viscosity [Pa s]: > 0 makes the guiding land oil-flooded (short journal bearing
    force and Petroff drag of seed 001 Eqs. 4-5 besides the contact penalty).
    churning: oil churning torques of seed 001 Eqs. 12-17 (bearing_core.churning) on the cage and the inner
    ring, in the oil-air mixture of oil_fraction (ball drag is the existing Eq. 10 term). oil_supply: a
    bearing_core.oil_supply.OilSupply; with oil_fraction 0 the mixture's oil fraction is its cavity oil
    content at the current shaft speed (oil_supply.cavity_oil_fraction; an oil_fraction > 0 overrides
    it). oil: name in
    bearing_core.lubricants (default: the traction curve's oil) for viscosity, density and pressure-
    viscosity; oil_temperature [K]: its temperature when thermal is off. thermal: a thermal network
    (bearing_core.thermal, seed 001 Eqs. 21-29; thermal_data: ThermalData) stepped on the slow time scale
    after every advance() with the mean losses of the interval (times thermal_time_scale, > 1 to
    fast-forward the heating); its temperatures feed back into the oil viscosity and density (churning,
    drag, flooded land, film thickness) and the traction curve (lubricants.traction_curve_at at the ball
    temperature). roughness [m]: if > 0, the rms roughness of each surface (film parameter Lambda and mixed
    lubrication) in place of the geometry's ball_roughness / race_roughness (0, default).

    lubrication: the lubrication regime, setting consistent laws for races and cage:
      'oil'   -- lubricated race traction (traction must be one of OIL_TRACTIONS); oil-lubricated ball-pocket
                 contacts (films on both walls with EHL / boundary friction in contact,
                 contact_kernels.ball_pocket_lubricated) and an oil-flooded guiding land (short journal
                 bearing + Petroff drag at the oil's viscosity, boundary friction mu_boundary in contact);
                 churning and ball drag allowed;
      'solid' -- solid-lubricated: Kalker or Coulomb race traction with mu (traction 'lubricated' is
                 replaced by 'kalker'), dry Coulomb pocket and land friction mu_pocket, mu_land;
      'dry'   -- Coulomb everywhere (traction 'lubricated' is replaced by 'coulomb'); no churning, no oil
                 in the land;
      'auto'  -- (default) from the traction law: 'lubricated' -> 'oil', 'kalker' / 'coulomb' -> 'solid'
                 (seed 000's solid-lubricated Kalker runs keep their dry Coulomb cage).
    mu_boundary (also the races' boundary coefficient) and mu_ehl_cage: boundary and full-film friction
    coefficients of the oil-lubricated cage contacts (defaults 0.15 and 0.05: mu_bl and mu_EHL (mineral oil)
    of the SKF friction model, SKF General Catalogue 6000 'Friction'); cage_roughness [m]: rms roughness of the pocket and land surfaces
    (0.4 um: an estimate for machined phenolic / brass cages, not from a source).

    Ring growth and fits (bearing_core.ring_fits): fits, a ring_fits.RingFits (None: free rings), the
    interference fits on shaft and housing; ring_growth: the rings grow with speed (centrifugal growth of
    the inner ring at the shaft speed) and temperature (thermal growth of rings and balls at the thermal
    network's temperatures, or at oil_temperature with thermal off). With either set, the geometry entries
    of the parameters (D, dm, fi, fo, alpha0, land radius) and the Hertz tables are those of
    ring_fits.operating_geometry(), updated at initialize(), set_speed() and every temperature update
    (apply_temperatures); without ring_growth the fits are taken at rest at the reference temperature
    (20 degC). Off by default: the bearing files carry no boundary dimensions (bore_diameter_mm,
    outside_diameter_mm) except QJ1044, and the reference results of the dynamics were computed on the
    nominal geometry (docs/fourpoint_and_fits.md)."""

    traction: str = "lubricated"
    lubricant: str = "generic-mineral-oil"
    mu_boundary: float = 0.15
    rolling_resistance: bool = True
    ehl_thermal: bool = True
    mu: float = 0.1
    v_reg: float = 0.02
    u_min: float = 0.5
    zeta: float = 0.05
    coupling: str = "load"
    integrator: str = "adaptive"
    dt: float = 1e-5
    rtol: float = 1e-4
    atol_pos: float = 1e-8
    n_major: int | None = None
    n_minor: int | None = None
    reduced: str = "auto"
    pocket_stiffness: float = 2e7
    pocket_damping_ratio: float = 0.2
    mu_pocket: float = 0.1
    land_stiffness: float = 2e7
    land_damping_ratio: float = 0.2
    mu_land: float = 0.1
    oil_fraction: float = 0.0
    cd: float = 0.5
    support_damping_ratio: float = 0.1
    fixed_tilt: bool = False
    outer_mount: str = "fixed"
    housing_stiffness: float = 1e8
    housing_damping_ratio: float = 0.05
    land_viscosity: float = 0.0
    kalker_grid: int = 12
    record_dt: float = 1e-3
    churning: bool = False
    oil: str = ""
    oil_temperature: float = 313.15
    thermal: bool = False
    thermal_data: object = None
    thermal_time_scale: float = 1.0
    roughness: float = 0.0
    lubrication: str = "auto"
    mu_ehl_cage: float = 0.05
    cage_roughness: float = 0.4e-6
    fits: object = None
    ring_growth: bool = False
    oil_supply: object = None

    @property
    def regime(self) -> str:
        """The resolved lubrication regime: 'oil', 'solid' or 'dry'."""
        if self.lubrication != "auto":
            return self.lubrication
        return "oil" if self.traction in OIL_TRACTIONS else "solid"

    @property
    def quadrature(self) -> tuple[int, int]:
        """(n_major, n_minor) points over each contact ellipse; unset ones follow the race traction law,
        chosen by accuracy against a 48 x 24 rule at equal cost (docs/speed.md, bench/bench_traction.py
        --quad-check): 4 x 4 for the EHL traction (friction torque within 0.2 %, race losses within 1 %
        at 1000 and 10,000 rpm; 6 x 2 is 4 % off at 1000 rpm, and both fill the 16-lane vector loop of
        ehl_traction), 6 x 2 for the curve and Coulomb laws (friction torque within 0.2 %)."""
        nm, nn = (4, 4) if self.race_traction == "lubricated" else (6, 2)
        return (self.n_major if self.n_major is not None else nm,
                self.n_minor if self.n_minor is not None else nn)

    @property
    def race_traction(self) -> str:
        """The race traction law the regime runs: traction, or kalker (solid) / coulomb (dry) in place of
        an oil traction law."""
        if self.regime == "solid" and self.traction in OIL_TRACTIONS:
            return "kalker"
        if self.regime == "dry" and self.traction in OIL_TRACTIONS:
            return "coulomb"
        return self.traction

    def validate(self):
        if self.lubrication not in LUBRICATION_REGIMES:
            raise BearingInputError("lubrication", self.lubrication, " | ".join(LUBRICATION_REGIMES))
        if self.lubrication == "oil" and self.traction not in OIL_TRACTIONS:
            raise BearingInputError("traction", self.traction, " | ".join(OIL_TRACTIONS)
                                    + " with lubrication='oil' (use lubrication='solid' or 'dry' for "
                                    "Kalker / Coulomb race traction)")
        if self.lubrication == "dry" and (self.churning or self.land_viscosity > 0 or self.oil_fraction > 0):
            raise BearingInputError("lubrication", self.lubrication,
                                    "oil | solid with churning, land_viscosity or oil_fraction (a dry bearing "
                                    "has no oil)")
        check_range("mu_boundary", self.mu_boundary, 0.0, 1.0)
        check_range("mu_ehl_cage", self.mu_ehl_cage, 0.0, 1.0)
        check_range("cage_roughness", self.cage_roughness, 1e-9, 1e-4, unit="m")
        if self.traction not in TRACTION_MODELS:
            raise BearingInputError("traction", self.traction, " | ".join(TRACTION_MODELS))
        if self.integrator not in INTEGRATORS:
            raise BearingInputError("integrator", self.integrator, " | ".join(INTEGRATORS))
        if self.coupling not in COUPLINGS:
            raise BearingInputError("coupling", self.coupling, " | ".join(COUPLINGS))
        if self.outer_mount not in ("fixed", "elastic"):
            raise BearingInputError("outer_mount", self.outer_mount, "fixed | elastic")
        check_range("housing_stiffness", self.housing_stiffness, 1e4, 1e12, unit="N/m")
        check_range("housing_damping_ratio", self.housing_damping_ratio, 0.0, 2.0)
        check_range("land_viscosity", self.land_viscosity, 0.0, 10.0, unit="Pa s")
        if self.reduced not in ("auto", "full", "axisymmetric"):
            raise BearingInputError("reduced", self.reduced, "auto | full | axisymmetric")
        get_lubricant(self.lubricant)
        check_range("mu", self.mu, 0.0, 1.0)
        check_range("v_reg", self.v_reg, 1e-5, 1.0, unit="m/s")
        check_range("u_min", self.u_min, 1e-3, 100.0, unit="m/s")
        check_range("zeta", self.zeta, 0.0, 2.0)
        check_range("dt", self.dt, 1e-8, 1e-3, unit="s")
        check_range("rtol", self.rtol, 1e-10, 1e-2)
        check_range("atol_pos", self.atol_pos, 1e-12, 1e-6, unit="m")
        if not isinstance(self.kalker_grid, int) or not 4 <= self.kalker_grid <= 80:
            raise BearingInputError("kalker_grid", self.kalker_grid, "integer 4..80")
        for nm in ("n_major", "n_minor"):
            v = getattr(self, nm)
            if v is not None and (not isinstance(v, int) or not 1 <= v <= 32):
                raise BearingInputError(nm, v, "integer 1..32")
        check_range("pocket_stiffness", self.pocket_stiffness, 1e3, 1e10, unit="N/m")
        check_range("land_stiffness", self.land_stiffness, 1e3, 1e10, unit="N/m")
        for nm in ("pocket_damping_ratio", "land_damping_ratio", "mu_pocket", "mu_land", "oil_fraction",
                   "support_damping_ratio"):
            check_range(nm, getattr(self, nm), 0.0, 1.0)
        check_range("cd", self.cd, 0.0, 5.0)
        check_range("record_dt", self.record_dt, 1e-6, 10.0, unit="s")
        from .lubricants import TRACTION_OIL, get_oil
        get_oil(self.oil or TRACTION_OIL[self.lubricant])
        check_range("oil_temperature", self.oil_temperature, 233.15, 473.15, unit="K")
        check_range("thermal_time_scale", self.thermal_time_scale, 1e-3, 1e6)
        if self.roughness != 0.0:
            check_range("roughness", self.roughness, 1e-9, 1e-5, unit="m")
        check_range("mu_boundary", self.mu_boundary, 0.0, 1.0)
        if self.fits is not None:
            from .ring_fits import RingFits
            if not isinstance(self.fits, RingFits):
                raise BearingInputError("fits", self.fits, "a bearing_core.ring_fits.RingFits or None")
        if not isinstance(self.ring_growth, (bool, np.bool_)):
            raise BearingInputError("ring_growth", self.ring_growth, "True | False")
        if self.oil_supply is not None:
            from .oil_supply import OilSupply
            if not isinstance(self.oil_supply, OilSupply):
                raise BearingInputError("oil_supply", self.oil_supply, "a bearing_core.oil_supply.OilSupply or None")
            self.oil_supply.validate()
        if self.thermal_data is not None:
            from .thermal import ThermalData
            if not isinstance(self.thermal_data, ThermalData):
                raise BearingInputError("thermal_data", self.thermal_data, "a bearing_core.thermal.ThermalData")
            self.thermal_data.validate()


class DynamicModel:
    """One bearing: outer ring fixed, inner ring at prescribed speed, balls (6 DOF each), cage
    (rotation and whirl), inner ring 5 DOF (load-driven) or prescribed (displacement-driven)."""

    _rosw_ws = None     # implicit integrator's Jacobian workspace (dynamics_kernels.rosw_workspace), per instance
    _end_diag = _end_bd = _end_key = None   # outputs at the last integration's end, key (t, y, U, P, tp)

    def __init__(self, geometry: BearingGeometry, options: DynamicsOptions = DynamicsOptions()):
        options.validate()
        if geometry.cage.guidance == "ball":
            # measured (docs/seed000_hypotheses.md): without a land the cage centre drifts onto a ball within
            # 0.1 s, because the pocket contact acts only along the orbital direction about the cage centre
            raise BearingInputError("cage.guidance", "ball", "outer | inner (a ball-guided cage is not supported "
                                    "by the dynamics yet: its pocket contact does not hold the cage radially)")
        self.g_nominal = geometry     # the bearing as defined (dimensions at 20 degC, unmounted)
        self.g = geometry             # the bearing as it runs (operating_geometry with fits / ring growth)
        self.opt = options
        self.P = None
        self.thermal = None
        self.U = np.zeros(K.NU)
        self._hz_key = None
        self._set_geometry(geometry)
        if options.ring_growth:
            from .ring_fits import RingFits, _dimensions
            _dimensions(geometry, options.fits or RingFits())   # centrifugal growth needs bore / outside diameter
        if options.fits is not None or options.ring_growth:
            self.update_operating_geometry(0.0)    # bad fits / missing boundary dimensions fail here
        self.t = 0.0
        self.y = None
        self.stats = np.zeros(NSTATS)
        self.quad = np.zeros(K.NQUAD)     # time integrals of the output channels (integrals())
        self.qs = None

    # ---- operating geometry: fits and ring growth (bearing_core.ring_fits) ----------------------
    HERTZ_REBUILD_REL = 1e-6   # relative change of D, dm, fi or fo that rebuilds the Hertz tables

    def _set_geometry(self, g: BearingGeometry):
        """Make g the running geometry: Hertz tables (rebuilt when D, dm, fi or fo moved by more than
        HERTZ_REBUILD_REL since the last build) and the geometry entries of the kernel parameters."""
        self.g = g
        key = np.array([g.D, g.dm, g.fi, g.fo])
        if self._hz_key is None or np.max(np.abs(key / self._hz_key - 1.0)) > self.HERTZ_REBUILD_REL:
            self.hz = HertzInterp(g)
            tab = self.hz.table
            self._tab_i = np.ascontiguousarray(tab.inner)
            self._tab_o = np.ascontiguousarray(tab.outer)
            self._ta0 = float(tab.alpha0)
            self._tda = float(tab.dalpha)
            self._hz_key = key
        P = self.P
        if P is not None:
            P[K.P_D], P[K.P_DM], P[K.P_FI], P[K.P_FO], P[K.P_A0] = g.D, g.dm, g.fi, g.fo, g.alpha0
            P[K.P_RLAND] = 0.5 * g.dm + (0.35 * g.D if P[K.P_GUIDE] == 0.0 else -0.35 * g.D)

    def ring_temperatures(self):
        """ring_fits.OperatingTemperatures [degC] the geometry follows with ring_growth: the thermal
        network's inner ring, outer ring and ball temperatures, else the bearing isothermal at the oil
        temperature (oil_temperature, or the last apply_temperatures)."""
        from .ring_fits import OperatingTemperatures
        if self.thermal is not None:
            T = self.thermal.temperatures()
            Ti, To, Tb = T["inner"], T["outer"], T["ball"]
        else:
            Ti = To = Tb = getattr(self, "_T_oil", self.opt.oil_temperature)
            Ti, To, Tb = getattr(self, "_T_parts", (Ti, To, Tb))
        return OperatingTemperatures(inner_ring=Ti - 273.15, outer_ring=To - 273.15, balls=Tb - 273.15)

    def update_operating_geometry(self, omega: float | None = None) -> BearingGeometry:
        """Running geometry from the nominal one (ring_fits.operating_geometry) with options.fits and, with
        options.ring_growth, the centrifugal growth at |omega| [rad/s] (None: the held shaft speed) and the
        thermal growth at ring_temperatures(); sets the parameters and returns it. No-op (nominal geometry)
        without fits and ring growth."""
        o = self.opt
        if o.fits is None and not o.ring_growth:
            return self.g
        from .ring_fits import operating_geometry
        if o.ring_growth:
            w = abs(float(self.U[K.U_W1] if omega is None else omega))
            g = operating_geometry(self.g_nominal, min(w, 2.0e4), o.fits, self.ring_temperatures())
        else:
            g = operating_geometry(self.g_nominal, 0.0, o.fits, None)
        self._set_geometry(g)
        return g

    def ring_growth_state(self):
        """ring_fits.RingGrowth (raceway and ball growth by cause, fit pressures) at the held shaft speed
        and the current temperatures, as update_operating_geometry() uses it; None without fits and ring
        growth."""
        from .ring_fits import ring_growth
        o = self.opt
        if o.fits is None and not o.ring_growth:
            return None
        if o.ring_growth:
            return ring_growth(self.g_nominal, min(abs(float(self.U[K.U_W1])), 2.0e4), o.fits,
                               self.ring_temperatures())
        return ring_growth(self.g_nominal, 0.0, o.fits, None)

    # ---- set-up -----------------------------------------------------------------------------
    def _params(self, axisym: bool) -> np.ndarray:
        g, o = self.g, self.opt
        P = np.zeros(K.NPAR)
        P[K.P_Z] = g.Z
        P[K.P_NB] = 1 if axisym else g.Z
        P[K.P_MULT] = g.Z if axisym else 1.0
        P[K.P_AXISYM] = 1.0 if axisym else 0.0
        P[K.P_D] = g.D
        P[K.P_DM] = g.dm
        P[K.P_FI] = g.fi
        P[K.P_FO] = g.fo
        P[K.P_A0] = g.alpha0
        P[K.P_EI] = g.inner_groove_offset      # gothic-arch grooves (0: two-point bearing)
        P[K.P_EO] = g.outer_groove_offset
        P[K.P_MB] = g.ball_mass
        P[K.P_JB] = g.ball_inertia
        P[K.P_MI] = g.inner_ring_mass
        P[K.P_IT] = g.inner_ring_tilt_inertia
        P[K.P_IP] = g.inner_ring_inertia
        P[K.P_MC] = g.cage.mass
        P[K.P_IC] = g.cage.inertia
        P[K.P_CPOCKET] = 0.5 * g.cage.pocket_clearance
        P[K.P_KPOCKET] = o.pocket_stiffness
        P[K.P_CPOCKETD] = 2.0 * o.pocket_damping_ratio * math.sqrt(o.pocket_stiffness * g.ball_mass)
        P[K.P_MUPOCKET] = o.mu_pocket
        P[K.P_CLAND] = 0.5 * g.cage.land_clearance
        P[K.P_KLAND] = o.land_stiffness
        P[K.P_CLANDD] = 2.0 * o.land_damping_ratio * math.sqrt(o.land_stiffness * g.cage.mass)
        P[K.P_MULAND] = o.mu_land
        # guiding land radius: outer land ~ dm/2 + D/2 * 0.7, inner land ~ dm/2 - D/2 * 0.7
        guide = {"outer": 0.0, "inner": 1.0, "ball": 2.0}[g.cage.guidance]
        P[K.P_GUIDE] = guide
        P[K.P_RLAND] = 0.5 * g.dm + (0.35 * g.D if guide == 0.0 else -0.35 * g.D)
        lub = get_lubricant(o.lubricant)
        P[K.P_TRACTION] = {"lubricated": 0.0, "lubricated-curve": 0.0, "coulomb": 1.0,
                            "kalker": 2.0}[o.race_traction]
        # cage lubrication (regime 'oil': lubricated pocket and land; viscosities set by apply_temperatures)
        P[K.P_LUBE] = 1.0 if o.regime == "oil" else 0.0
        P[K.P_MUBL] = o.mu_boundary
        P[K.P_MUEHL] = o.mu_ehl_cage
        from .hertz import reduced_modulus
        from .materials import get_material
        cm = get_material(g.cage.material)
        P[K.P_EPK] = reduced_modulus(g.ball_material.E, g.ball_material.nu, cm.E, cm.nu)
        P[K.P_SIGPK] = math.hypot(o.roughness if o.roughness > 0 else g.ball_roughness, o.cage_roughness)
        # flooded land: the film force acts up to a minimum film of 3 composite roughnesses (the full-film
        # limit Lambda = 3) in the oil regime; 0.95 for a land flooded through land_viscosity in the solid regime
        P[K.P_EPSMAX] = (max(0.95, 1.0 - 3.0 * P[K.P_SIGPK] / (0.5 * g.cage.land_clearance))
                         if o.regime == "oil" else 0.95)
        from .fastsim import combined_elastic
        P[K.P_GCOMB], P[K.P_NUCOMB] = combined_elastic(g.ring_material.E, g.ring_material.nu,
                                                       g.ball_material.E, g.ball_material.nu)
        P[K.P_FS_NX] = P[K.P_FS_NY] = o.kalker_grid
        P[K.P_ZETA] = o.zeta
        P[K.P_RHO_EFF] = 1.2 + o.oil_fraction * (lub.density - 1.2)
        P[K.P_CD] = o.cd
        self._tp = CK.traction_params(o.mu, o.v_reg, lub.A, lub.B, lub.C, lub.D, o.u_min)
        if o.race_traction == "lubricated":
            self._tp = self._ehl_params(o.oil_temperature)
        self._quad = CK.ellipse_quadrature(*o.quadrature)
        P[K.P_COUPLING] = 1.0 if o.coupling == "displacement" else 0.0
        P[K.P_FIXTILT] = 1.0 if o.fixed_tilt else 0.0
        P[K.P_MO] = g.outer_ring_mass
        P[K.P_OUTER_ELASTIC] = 1.0 if o.outer_mount == "elastic" else 0.0
        P[K.P_KH] = o.housing_stiffness if o.outer_mount == "elastic" else 0.0
        P[K.P_CH] = (2.0 * o.housing_damping_ratio * math.sqrt(o.housing_stiffness * g.outer_ring_mass)
                     if o.outer_mount == "elastic" else 0.0)
        P[K.P_ETA_LAND] = o.land_viscosity
        P[K.P_WLAND] = g.cage.land_width
        from .churning import ChurningGeometry
        cg = ChurningGeometry.from_bearing(g)
        P[K.P_CH_ON] = 1.0 if o.churning else 0.0
        P[K.P_CH_BC], P[K.P_CH_DC], P[K.P_CH_CC] = cg.B_c, cg.D_c, cg.c_c
        P[K.P_CH_WALL] = 1.0 if g.cage.guidance == "inner" else 0.0
        P[K.P_CH_BIR], P[K.P_CH_DLI], P[K.P_CH_CS] = cg.B_ir, cg.D_Li, cg.c_s
        return P

    # ---- oil properties and temperatures ------------------------------------------------------
    @property
    def oil_name(self) -> str:
        from .lubricants import TRACTION_OIL
        return self.opt.oil or TRACTION_OIL[self.opt.lubricant]

    def cavity_oil(self):
        """oil_supply.CavityOil of options.oil_supply at the current relative shaft speed (None without a
        supply or with an explicit oil_fraction > 0)."""
        o = self.opt
        if o.oil_supply is None or o.oil_fraction > 0.0:
            return None
        from .oil_supply import cavity_oil_fraction
        U = self.U
        w = abs(float(U[K.U_W1] - U[K.U_WO]))
        # at rest Parker's fraction diverges: 1 rpm caps it at 1 (flooded; no drag at rest anyway)
        return cavity_oil_fraction(o.oil_supply, self.g, max(w * 30.0 / math.pi, 1.0))

    def oil_fraction_used(self) -> float:
        """Oil fraction of the cavity mixture the churning and drag use: options.oil_fraction if > 0 or
        no supply, else the supply's cavity oil content at the current speed."""
        c = self.cavity_oil()
        return self.opt.oil_fraction if c is None else c.fraction

    def _set_mixture(self, rho, eta):
        """Oil-air mixture density and viscosity of drag and churning at oil_fraction_used()."""
        X = self.oil_fraction_used()
        self.P[K.P_RHO_EFF] = 1.2 + X * (rho - 1.2)
        self.P[K.P_CH_RHO] = 1.2 + X * (rho - 1.2)
        self.P[K.P_CH_ETA] = 1.8e-5 + X * (eta - 1.8e-5)     # air 1.8e-5 Pa s (churning.churning_losses)

    def apply_temperatures(self, T_oil: float, T_ball: float | None = None, T_inner: float | None = None,
                           T_outer: float | None = None):
        """Set the temperature-dependent parameters [K]: oil-air mixture density and viscosity for churning
        and drag at T_oil, the flooded land viscosity (if land_viscosity > 0, with thermal on), and the
        lubricated traction curve at T_ball (lubricants.traction_curve_at). With options.ring_growth the
        running geometry follows the inner ring, outer ring and ball temperatures T_inner, T_outer, T_ball
        (the thermal network's when it runs; missing ones: T_oil) at the held shaft speed
        (update_operating_geometry)."""
        from .lubricants import get_oil, traction_curve_at
        o = self.opt
        if o.ring_growth and self.thermal is None:
            Tb = T_oil if T_ball is None else T_ball
            self._T_parts = (T_oil if T_inner is None else T_inner, T_oil if T_outer is None else T_outer, Tb)
        if o.ring_growth or o.fits is not None:
            self.update_operating_geometry()
        oil = get_oil(self.oil_name)
        T_oil = min(max(float(T_oil), 233.15), 473.15)
        rho, eta = oil.density(T_oil), oil.eta(T_oil)
        self._set_mixture(rho, eta)
        if o.thermal and o.land_viscosity > 0:
            self.P[K.P_ETA_LAND] = eta
        if o.regime == "oil":
            # oil-lubricated cage: pocket films and the flooded guiding land at the oil temperature
            # (an explicit land_viscosity is kept when the thermal network is off)
            self.P[K.P_ETA_PK] = eta
            self.P[K.P_ALPHA_PK] = oil.alpha(T_oil)
            if o.land_viscosity <= 0 or o.thermal:
                self.P[K.P_ETA_LAND] = eta
        self._T_oil = T_oil
        if T_ball is not None and o.race_traction == "lubricated":
            self._tp = self._ehl_params(T_ball)      # the oil enters the contacts at the ball temperature
        elif T_ball is not None and o.race_traction == "lubricated-curve":
            T_ball = min(max(float(T_ball), 233.15), 473.15)
            c = traction_curve_at(o.lubricant, T_ball)
            self._tp = CK.traction_params(o.mu, o.v_reg, c.A, c.B, c.C, c.D, o.u_min)

    def roughness_pair(self) -> tuple[float, float]:
        """(ball, race) rms roughness [m]: options.roughness for both if > 0, else the geometry's."""
        r = self.opt.roughness
        return (r, r) if r > 0 else (self.g.ball_roughness, self.g.race_roughness)

    def _ehl_params(self, T: float):
        """Traction parameters of the rheology-based EHL model (ehl_traction) for the oil at inlet
        temperature T [K]: E' of the ball/ring pair; solids' tangential compliance G C11 with Kalker's C11 at
        the b/a of the inner contact at the free contact angle (Hamrock-Dowson ellipticity); composite
        roughness."""
        from .fastsim import combined_elastic, kalker_coefficients
        from .film import ellipticity_nb
        from .lubricants import rheology_traction_params
        g, o = self.g, self.opt
        rm, bm = g.ring_material, g.ball_material
        Ep = 2.0 / ((1 - rm.nu ** 2) / rm.E + (1 - bm.nu ** 2) / bm.E)
        Gc, nuc = combined_elastic(rm.E, rm.nu, bm.E, bm.nu)
        Rx = 0.5 * g.D * (1.0 - g.D * math.cos(g.alpha0) / g.dm)
        Ry = g.fi * g.D / (2.0 * g.fi - 1.0)
        C11 = kalker_coefficients(1.0 / ellipticity_nb(Rx, Ry, 0), nuc)[0]
        rb, rr = self.roughness_pair()
        base = CK.traction_params(o.mu, o.v_reg, 0.0, 0.0, 0.0, 0.0, o.u_min)
        return rheology_traction_params(base, self.oil_name, min(max(float(T), 233.15), 473.15), Ep, Gc * C11,
                                        math.hypot(rb, rr), mu_bl=o.mu_boundary,
                                        rolling_resistance=o.rolling_resistance, thermal=o.ehl_thermal)

    def film(self, bd: np.ndarray | None = None) -> dict:
        """Hamrock-Dowson film thickness (bearing_core.film, seed 003 Eq. 23) of every ball-race contact at
        the current instant with the oil at its current temperature: h_c_i, h_min_i, h_c_o, h_min_o [m]
        (arrays over balls; 0 where unloaded) and the smallest film parameter Lambda_min [-] (h_min over the
        composite roughness of roughness_pair()). bd: the per-ball details of evaluate_point() at this
        instant, if already computed (saves a right-hand-side call)."""
        if bd is None:
            bd = self.evaluate_point()[1]
        h = np.zeros((4, bd.shape[0]))
        lam = self.films_into(bd, h)
        return {"h_c_i": h[0], "h_min_i": h[1], "h_c_o": h[2], "h_min_o": h[3],
                "Lambda_min": float(lam) if math.isfinite(lam) else 0.0,
                "T_oil": getattr(self, "_T_oil", self.opt.oil_temperature)}

    def films_into(self, bd: np.ndarray, h: np.ndarray) -> float:
        """film() into a caller's array: h (4 x nb) = h_c_i, h_min_i, h_c_o, h_min_o [m] of the per-ball
        details bd; returns the smallest film parameter Lambda (inf if no contact is loaded)."""
        g = self.g
        T = getattr(self, "_T_oil", self.opt.oil_temperature)
        key = (id(self.opt), T)
        if getattr(self, "_film_key", None) != key:      # oil properties at T, recomputed when T changes
            from .lubricants import get_oil
            oil = get_oil(self.oil_name)
            Ep = 2.0 / ((1 - g.ring_material.nu ** 2) / g.ring_material.E
                        + (1 - g.ball_material.nu ** 2) / g.ball_material.E)
            self._film_key = key
            self._film_par = (float(oil.eta(T)), float(oil.alpha(T)), Ep, *self.roughness_pair())
        eta0, alpha, Ep, s1, s2 = self._film_par
        return K.contact_films(bd, g.D, g.dm, g.fi, g.fo, eta0, alpha, Ep, s1, s2, h)

    def evaluate_point(self) -> tuple[np.ndarray, np.ndarray]:
        """(output channels (NOUT), per-ball details (nb x NBD)) at the current instant: those the last
        integration computed at its end point if the state, time and inputs are still those, else one
        right-hand-side call (dynamics_kernels.evaluate). Read-only arrays."""
        k = self._end_key
        if k is not None and k[4] is self._tp and same_point(self.t, self.y, self.U, self.P, k[0], k[1], k[2], k[3]):
            return self._end_diag, self._end_bd
        diag = np.zeros(K.NOUT)
        bd = np.zeros((int(self.P[K.P_NB]), K.NBD))
        K.evaluate(self.t, self.y, self.P, self.U, self._tab_i, self._tab_o, self._ta0, self._tda, self._tp,
                   *self._quad, diag, bd)
        return diag, bd

    def initialize(self, omega: float, loads=(0.0, 0.0, 0.0, 0.0, 0.0), displacement=None, t0: float = 0.0,
                   start: str = "jones-harris", omega_outer: float = 0.0):
        """Start at (near) equilibrium from the quasi-static solution (outer raceway control) at shaft
        speed omega [rad/s] and loads (Fx, Fy, Fz, Mx, My) [N, N m]. Displacement-driven coupling takes
        ``displacement`` = (dx, dy, dz, tx, ty, vx, vy, vz, wx, wy) [m, rad, m/s, rad/s] instead; the
        quasi-static start then uses the load that this displacement needs (found by the QS solve of the
        loads returned by a static pass). start: 'jones-harris' (raceway control) or 'tribological' (the
        quasi-static tribological model with this model's traction, bearing_core.quasistatic_tribo; seed 000
        Sec. 3.1 stage 1; load-driven ring on a fixed outer ring only; its result is kept in self.tribo_qs).
        Both speeds are signed (about +z), in [-2e4, 2e4] rad/s; omega_outer [rad/s] turns the outer ring.
        Start with a rotating outer ring or a negative speed difference (docs/reversal_and_outputs.md): the
        quasi-static problem is solved in the frame turning with the outer ring at the relative speed
        |omega - omega_outer| (for a negative difference with the loads mirrored in the x-z plane and the
        state mirrored back, mirror_state), then omega_outer is added to the cage, orbital and ball z
        speeds. Jones-Harris start: centrifugal force and gyroscopic moment at the absolute orbital speed
        (QuasiStaticModel.omega_outer); the tribological start solves the relative problem with a fixed
        outer ring (its centrifugal force at the relative orbital speed; the dynamics relax it).
        self.qs / self.tribo_qs keep the solved (relative, possibly mirrored) problem."""
        if start not in START_MODELS:
            raise BearingInputError("start", start, " | ".join(START_MODELS))
        if start == "tribological" and (self.opt.coupling != "load" or self.opt.outer_mount != "fixed"):
            raise BearingInputError("start", start, "jones-harris with displacement coupling or an elastic outer ring")
        omega = check_range("omega", omega, -2.0e4, 2.0e4, unit="rad/s")
        omega_outer = check_range("omega_outer", omega_outer, -2.0e4, 2.0e4, unit="rad/s")
        loads = np.asarray(loads, dtype=float).reshape(-1)
        if loads.size != 5 or not np.all(np.isfinite(loads)):
            raise BearingInputError("loads", loads.tolist(), "5 finite values (Fx, Fy, Fz, Mx, My)")
        loads_in = loads.copy()
        self.thermal = None
        self._T_oil = self.opt.oil_temperature
        self.__dict__.pop("_T_parts", None)
        self.update_operating_geometry(omega)     # fits / ring growth at the shaft speed (isothermal start)
        w_rel = omega - omega_outer
        mirror = w_rel < 0.0
        if mirror:      # solve the mirrored start (x-z plane): Fy, Mx change sign
            loads = loads * MIRROR_LOADS
        omega = abs(w_rel)
        g, o = self.g, self.opt
        axisym = (o.reduced == "axisymmetric") or (
            o.reduced == "auto" and o.coupling == "load" and np.all(loads[[0, 1, 3, 4]] == 0.0))
        if o.reduced == "axisymmetric" and np.any(loads[[0, 1, 3, 4]] != 0.0):
            raise BearingInputError("reduced", "axisymmetric", "full or auto when Fx, Fy, Mx or My is non-zero")
        self.axisym = bool(axisym)
        self.P = self._params(self.axisym)
        qsm = quasistatic_model(g, "outer", fixed_tilt=o.fixed_tilt)   # four-point model for gothic arches
        qsm.omega_outer = -omega_outer if mirror else omega_outer     # in the (mirrored) solved problem
        if o.coupling == "displacement":
            if displacement is None:
                raise BearingInputError("displacement", None, "10 values for displacement-driven coupling")
            d = np.asarray(displacement, dtype=float).reshape(-1)
            if d.size != 10 or not np.all(np.isfinite(d)):
                raise BearingInputError("displacement", d.tolist(), "10 finite values")
            self.U[K.U_DX:K.U_WY + 1] = d
            if mirror:
                d = d * MIRROR_DISP
            Fb, X, st, ok = qsm.residual(d[:5], omega)
            loads = -Fb
            loads_in = loads * MIRROR_LOADS if mirror else loads
        qs = qsm.solve(omega, loads, stiffness=(o.coupling == "load"))
        self.qs = qs
        if o.coupling == "load":
            kd = np.clip(np.diag(qs.stiffness), 0.0, None)
            mass = np.array([g.inner_ring_mass] * 3 + [g.inner_ring_tilt_inertia] * 2)
            self.P[K.P_CRX:K.P_CRTY + 1] = 2.0 * o.support_damping_ratio * np.sqrt(kd * mass)
        nb = 1 if self.axisym else g.Z
        y = np.zeros(K.NSTATE_FIXED + K.NSB * nb)
        y[0:5] = qs.u if o.coupling == "load" else 0.0
        Roo = 0.5 * g.dm - (g.fo - 0.5) * g.D * math.cos(g.alpha0)
        Zoo = -(g.fo - 0.5) * g.D * math.sin(g.alpha0)
        y[11] = qs.cage_speed
        if o.outer_mount == "elastic" and not self.axisym:
            # the housing spring carries the radial load; the inner ring moves with the outer ring
            y[16:18] = loads[:2] / o.housing_stiffness
            if o.coupling == "load":
                y[0:2] += y[16:18]
        for j in range(nb):
            b = K.NSTATE_FIXED + K.NSB * j
            y[b] = qs.psi[j]
            y[b + 1] = Roo + qs.X[j, 0]
            y[b + 2] = Zoo + qs.X[j, 1]
            y[b + 3] = qs.omega_m[j]
            y[b + 6] = -qs.omega_R[j] * math.sin(qs.beta[j])
            y[b + 7] = 0.0
            y[b + 8] = qs.omega_R[j] * math.cos(qs.beta[j]) + qs.omega_m[j]
        self.tribo_qs = None
        if start == "tribological":
            from .quasistatic_tribo import TriboQuasiStaticModel
            tq = TriboQuasiStaticModel(g, o).solve(omega, loads)
            self.tribo_qs = tq
            y[0:5] = tq.u
            y[11] = tq.cage_speed
            for j in range(nb):       # reduced model: ball 0 stands for all (pure axial load: all equal)
                b, bt = K.NSTATE_FIXED + K.NSB * j, K.NSTATE_FIXED + K.NSB * j
                y[b + 1:b + 9] = tq.y[bt + 1:bt + 9]
        if mirror:
            y = mirror_state(y, nb)
        if omega_outer != 0.0:      # from the frame turning with the outer ring to the absolute frame
            y[11] += omega_outer
            for j in range(nb):
                b = K.NSTATE_FIXED + K.NSB * j
                y[b + 3] += omega_outer
                y[b + 8] += omega_outer
        self.y = y
        self.t = float(t0)
        self.U[K.U_W0] = self.U[K.U_W1] = omega_outer + (-omega if mirror else omega)
        self.U[K.U_WO] = omega_outer
        self.U[K.U_T0] = self.U[K.U_T1] = self.t
        self.U[K.U_FX:K.U_MY + 1] = loads_in
        self.stats[:] = 0.0
        self.quad[:] = 0.0
        self.invalidate_jacobian()
        self._atol = self._atol_scale(nb)
        self._atol_implicit = self._atol.copy()
        for j in range(nb):                      # ball translational velocities (see IMPLICIT_ATOL_FACTOR)
            b = K.NSTATE_FIXED + K.NSB * j
            self._atol_implicit[b + 4:b + 6] *= IMPLICIT_ATOL_FACTOR
        self.thermal = None
        self.apply_temperatures(self.opt.oil_temperature, self.opt.oil_temperature)
        if self.opt.thermal:
            from .thermal import ThermalData, ThermalNetwork
            td = self.opt.thermal_data or ThermalData(T_amb=self.opt.oil_temperature, T_in=self.opt.oil_temperature)
            td = replace(td, shaft_speed=omega,      # speed-dependent convection and contact resistances
                         oil_fraction=self.oil_fraction_used() if td.oil_fraction is None else td.oil_fraction)
            if td.a_i is None:   # contact ellipses of the most loaded ball (seed 001 Eq. 26)
                bd = self.ball_details()
                j = int(np.argmax(bd["Q_i"]))
                if bd["Q_i"][j] > 0.0 and bd["Q_o"][j] > 0.0:
                    td = replace(td, a_i=float(bd["a_i"][j]), b_i=float(bd["b_i"][j]), a_o=float(bd["a_o"][j]),
                                 b_o=float(bd["b_o"][j]), ball_load=float(bd["Q_i"][j]))
            self.thermal = ThermalNetwork(g, oil=self.oil_name, data=td, T0=None)
            self._apply_thermal()
        return self

    def _atol_scale(self, nb):
        """Absolute tolerances per state for the adaptive integrator (negative: absolute only, used for
        the unbounded angles): positions atol_pos [m] (contact deflections are um), velocities
        1e4 atol_pos [m/s], angular velocities 1e6-1e7 atol_pos [rad/s]."""
        a = np.empty(K.NSTATE_FIXED + K.NSB * nb)
        # measured: velocities at 1e5 atol_pos (the highest natural frequency times atol_pos) save a third of
        # the steps at 10,000 rpm but overstate the dissipated energy of a run-up from rest by 70 % (SSP
        # drivetrain, tests/test_ssp.py) and move Dormand-Prince's mean friction torque 6 % off RK4
        sp, sv, sw = self.opt.atol_pos, self.opt.atol_pos * 1e4, self.opt.atol_pos * 1e6
        a[0:3] = sp; a[3:5] = 10 * sp; a[5:8] = sv; a[8:10] = 10 * sv
        a[10] = -1e-5; a[11] = sw; a[12:14] = 10 * sp; a[14:16] = 10 * sv
        a[16:18] = sp; a[18:20] = sv
        for j in range(nb):
            b = K.NSTATE_FIXED + K.NSB * j
            a[b] = -1e-6
            a[b + 1:b + 3] = sp
            a[b + 3] = sw
            a[b + 4:b + 6] = sv
            a[b + 6:b + 9] = 10 * sw
        return a

    # ---- time integration ---------------------------------------------------------------------
    def set_inputs(self, loads=None, displacement=None):
        """Hold new loads (Fx, Fy, Fz, Mx, My) or displacement inputs (10 values) from now on."""
        if loads is not None:
            loads = np.asarray(loads, dtype=float).reshape(-1)
            if loads.size != 5 or not np.all(np.isfinite(loads)):
                raise BearingInputError("loads", loads.tolist(), "5 finite values (Fx, Fy, Fz, Mx, My)")
            if self.axisym and np.any(loads[[0, 1, 3, 4]] != 0.0):
                raise BearingInputError("loads", loads.tolist(),
                                        "pure axial load for the reduced (axisymmetric) model; "
                                        "initialise with reduced='full'")
            self.U[K.U_FX:K.U_MY + 1] = loads
        if displacement is not None:
            d = np.asarray(displacement, dtype=float).reshape(-1)
            if d.size != 10 or not np.all(np.isfinite(d)):
                raise BearingInputError("displacement", d.tolist(), "10 finite values")
            self.U[K.U_DX:K.U_WY + 1] = d

    def set_speed(self, omega: float, omega_outer: float | None = None):
        """Hold the shaft speed at omega [rad/s] from now on (a step change, no ramp), signed about +z; also
        the outer-ring speed omega_outer [rad/s] if given (else kept)."""
        omega = check_range("shaft_speed", omega, -2.0e4, 2.0e4, unit="rad/s")
        if omega_outer is not None:
            self.U[K.U_WO] = check_range("outer_ring_speed", omega_outer, -2.0e4, 2.0e4, unit="rad/s")
        self.U[K.U_W0] = self.U[K.U_W1] = omega
        self.U[K.U_T0] = self.U[K.U_T1] = self.t
        self.update_operating_geometry()          # centrifugal ring growth at the new speed
        if self.opt.oil_supply is not None:       # the supply's cavity oil content at the new speed
            from .lubricants import get_oil
            oil = get_oil(self.oil_name)
            self._set_mixture(oil.density(self._T_oil), oil.eta(self._T_oil))

    def advance(self, t_end: float, omega_end: float | None = None, record_dt: float | None = None):
        """Integrate from the current time to t_end [s]; the shaft speed ramps linearly from its current
        value to omega_end [rad/s] over the interval (held if None). Returns the records (n x NOUT
        array, columns dynamics_kernels.OUT_NAMES) taken every record_dt (default options.record_dt)."""
        if self.y is None:
            raise RuntimeError("call initialize() first")
        t_end = float(t_end)
        if not math.isfinite(t_end) or t_end <= self.t:
            raise BearingInputError("t_end", t_end, f"finite and > current time {self.t}")
        w0 = self.U[K.U_W1] if self.t >= self.U[K.U_T1] else self._shaft_speed(self.t)
        w1 = w0 if omega_end is None else check_range("omega_end", omega_end, -2.0e4, 2.0e4, unit="rad/s")
        self.U[K.U_W0], self.U[K.U_W1] = w0, w1
        self.U[K.U_T0], self.U[K.U_T1] = self.t, t_end
        rdt = self.opt.record_dt if record_dt is None else float(record_dt)
        # + 1 per auto chunk: float rounding can add one record at a chunk end
        nmax = int((t_end - self.t) / rdt) + 2 + int((t_end - self.t) / AUTO_CHUNK) + 1
        rec = np.zeros((nmax, K.NOUT))
        q0 = self.quad[:K.NOUT].copy()
        if self.opt.integrator == "auto" and t_end - self.t > 1.5 * AUTO_CHUNK:
            # split into chunks (whole multiples of the record interval) and choose per chunk
            L = rdt * max(1, round(AUTO_CHUNK / rdt))
            n = 0
            ta = self.t
            while ta < t_end - 1e-12:
                tb = min(ta + L, t_end)
                if t_end - tb < 0.5 * L:
                    tb = t_end
                n += self._integrate(ta, tb, rdt, rec[n:], nmax - n)
                if self.stats[4] != 0.0:
                    break
                ta = tb
        else:
            n = self._integrate(self.t, t_end, rdt, rec, nmax)
        if self.stats[4] != 0.0 or not np.all(np.isfinite(self.y)):
            raise FloatingPointError(
                f"integration failed at t in [{self.t:.6g}, {t_end:.6g}] s "
                f"({'non-finite state' if self.stats[4] == 1 else 'step size underflow'}); "
                "reduce dt / rtol or check the inputs")
        if self.thermal is not None and n > 0:
            # the network takes the mean powers over the interval: the time integrals accumulated in the
            # integrator (energy-consistent), not the mean of the sampled records
            mean = ((self.quad[:K.NOUT] - q0) / (t_end - self.t))[None, :]
            self._thermal_step(mean, (t_end - self.t) * self.opt.thermal_time_scale)
        self.t = t_end
        return rec[:n]

    # ---- thermal network on the slow time scale (seed 001 Eqs. 21-29) -------------------------------
    def heat_sources(self, rec) -> dict:
        """Mean loss powers [W] of records (n x NOUT) keyed by the thermal network's sources: race traction
        with half the contact damping each, pocket, land, churning of cage and inner ring, ball drag."""
        m = rec.mean(axis=0)
        I = K.OUT_INDEX
        dmp = 0.5 * m[I["P_damping"]]
        return {"Q_br_i": max(m[I["P_race_inner"]] + dmp, 0.0), "Q_br_o": max(m[I["P_race_outer"]] + dmp, 0.0),
                "Q_bp": max(m[I["P_pocket"]], 0.0), "Q_cg": max(m[I["P_land"]], 0.0),
                "Q_ch_c": max(m[I["P_churn_cage"]], 0.0), "Q_ch_s": max(m[I["P_churn_ring"]], 0.0),
                "Q_ch_b": 0.0, "drag": max(m[I["P_drag"]], 0.0)}

    def _thermal_step(self, rec, dt):
        self.thermal.set_speed(self.U[K.U_W1] - self.U[K.U_WO])
        self.thermal.step(self.heat_sources(rec), dt)
        self._apply_thermal()
        if self.thermal.runaway():
            self.thermal_runaway = True

    @property
    def thermal_runaway(self) -> bool:
        """True once a thermal-network temperature passed the oil's limit (thermal.OIL_T_MAX); stays set
        until the thermal state is restored to one below the limit (set_thermal_state)."""
        return getattr(self, "_runaway", False)

    @thermal_runaway.setter
    def thermal_runaway(self, v):
        self._runaway = bool(v)

    def skid(self) -> dict:
        """Kinematic reference and skid classification at the current instant (bearing_core.skid): pure-
        rolling cage speeds at the loaded balls' contact angles with outer / inner raceway control [rad/s],
        seed 000's Eq. 26 value (spin-free, mean angles) [rad/s], cage speed [rad/s], cage_slip_ratio and
        skid_state (+1 skidding, 0 pure rolling, -1 over-skidding) with its label."""
        from .skid import SKID_LABELS, classify_skid
        o = self.outputs()
        state, s = classify_skid(o["cage_speed"], o["cage_speed_pure_rolling_outer"], omega_outer=o["outer_ring_speed"])
        return {"cage_speed": o["cage_speed"], "cage_speed_pure_rolling_outer": o["cage_speed_pure_rolling_outer"],
                "cage_speed_pure_rolling_inner": o["cage_speed_pure_rolling_inner"],
                "cage_speed_seed000_eq26": o["pure_rolling_cage_speed"], "cage_slip_ratio": s,
                "skid_state": state, "skid_label": SKID_LABELS[state]}

    def _apply_thermal(self):
        T = self.thermal.temperatures()
        self.apply_temperatures(T["oil"], T["ball"], T["inner"], T["outer"])

    def thermal_equilibrium(self, window: float = 0.05, tol: float = 0.1, max_iter: int = 30) -> dict:
        """Two-time-scale thermal steady state at the current speed and loads: repeat (advance the dynamics
        by window [s] at fixed temperatures; mean losses of that window -> steady state of the thermal
        network -> new temperatures) until no node moves by more than tol [K]. Returns temperatures [K],
        losses by source, heat generated and rejected (ambient + oil flow) [W], the iterations and the
        balance (rejected / generated - 1) at the final temperatures."""
        if self.thermal is None:
            raise BearingInputError("thermal", False, "True (DynamicsOptions(thermal=True))")
        check_range("window", window, 1e-3, 10.0, unit="s")
        for it in range(1, max_iter + 1):
            rec = self.advance(self.t + window, record_dt=min(window / 20, 1e-3))
            Q = self.heat_sources(rec)
            T_old = self.thermal.T.copy()
            self.thermal.set_speed(self.U[K.U_W1] - self.U[K.U_WO])
            self.thermal.steady_state(Q, set_state=True)
            self._apply_thermal()
            if np.max(np.abs(self.thermal.T - T_old)) < tol:
                break
        else:
            # not converged: past the oil's limit it is a runaway (the fixed point keeps heating up)
            self.thermal.check_runaway(f"at {self.U[K.U_W1] * 30 / math.pi:.0f} rpm (thermal equilibrium not "
                                       f"reached in {max_iter} iterations, losses {sum(Q.values()):.0f} W)")
            raise ConvergenceError(f"thermal equilibrium not reached in {max_iter} iterations of {window} s")
        # a steady state past the oil's limit is a thermal runaway, not an equilibrium
        self.thermal.check_runaway(f"at {self.U[K.U_W1] * 30 / math.pi:.0f} rpm (thermal equilibrium after "
                                   f"{it} iterations, losses {sum(Q.values()):.0f} W)")
        # check: one more window at the final temperatures (no update); its losses must equal what the
        # network rejects at those temperatures
        th = self.thermal_state()
        rec = self.advance(self.t + window, record_dt=min(window / 20, 1e-3))
        self.set_thermal_state(th)
        Q = self.heat_sources(rec)
        gen = sum(Q.values())
        rej = self.thermal.heat_to_ambient() + self.thermal.heat_to_oil_flow()
        I = K.OUT_INDEX
        return {"temperatures_K": self.thermal.temperatures(), "losses_W": Q, "heat_generated_W": gen,
                "heat_rejected_W": rej, "balance": rej / gen - 1.0 if gen > 0 else 0.0, "iterations": it,
                "drive_power_W": float(rec[:, I["P_drive"]].mean()),
                "friction_torque_Nm": float(rec[:, I["friction_torque"]].mean()),
                "cage_speed_rad_s": float(rec[:, I["cage_speed"]].mean())}

    def thermal_state(self):
        """Copy of the thermal network state (None without one), for rollback."""
        if self.thermal is None:
            return None
        th = self.thermal
        return (th.T.copy(), th.E_generated, th.E_ambient, th.E_flow)

    def set_thermal_state(self, st):
        if st is None or self.thermal is None:
            self.update_operating_geometry()     # the geometry of the (restored) held speed
            return
        th = self.thermal
        th.T[:] = st[0]
        th.E_generated, th.E_ambient, th.E_flow = st[1], st[2], st[3]
        self._apply_thermal()
        self.thermal_runaway = th.runaway()

    def temperatures(self) -> dict:
        """Node temperatures [K] (ball, outer, inner, oil) and the heat flows to ambient and to the oil flow [W];
        the isothermal oil temperature when the thermal network is off."""
        if self.thermal is None:
            T = self.opt.oil_temperature
            return {"ball": T, "outer": T, "inner": T, "oil": T, "heat_to_ambient": 0.0, "heat_to_oil_flow": 0.0}
        d = dict(self.thermal.temperatures())
        d["heat_to_ambient"] = self.thermal.heat_to_ambient()
        d["heat_to_oil_flow"] = self.thermal.heat_to_oil_flow()
        return d

    def _integrate(self, t_start, t_end, rdt, rec, nmax):
        """One kernel call from t_start to t_end (state self.y); returns the number of records."""
        if self.opt.integrator == "auto":
            method = self._auto_choose()
        else:
            method = METHOD_CODE[self.opt.integrator]
        if method == 0:
            dt0 = self.opt.dt
        else:
            hk = self.stats[ST_H[method]]
            dt0 = hk if hk > 0 else (self.stats[3] if self.stats[3] > 0 else self.opt.dt)
            if hk <= 0 and method != 2:
                # an explicit method taking over from the implicit one starts at most at dt: the implicit
                # step (~5e-5 s at 1000 rpm) lies beyond the explicit stability limit (~3e-5 s), and the
                # first steps there passed the error test yet lost ~1 % of the energy balance
                dt0 = min(dt0, self.opt.dt)
        self.stats[4] = 0.0
        before = self.stats[:3].copy()
        nb = int(self.P[K.P_NB])
        if self._end_diag is None or self._end_bd.shape[0] != nb:
            self._end_diag, self._end_bd = np.zeros(K.NOUT), np.zeros((nb, K.NBD))
        self._end_key = None
        if method == 2:
            nb = int(self.P[K.P_NB])
            if self._rosw_ws is None or self._rosw_ws[3].shape[0] != nb:
                self._rosw_ws = K.rosw_workspace(nb)
            n = K.integrate_rosw(self.y, t_start, t_end, dt0, self.opt.rtol, self._atol_implicit, self.P, self.U,
                                 self._tab_i, self._tab_o, self._ta0, self._tda, self._tp, *self._quad,
                                 rdt, rec, nmax, self.stats, self.quad, self._end_diag, self._end_bd,
                                 *self._rosw_ws)
            if self.stats[4] != 0.0:
                self.invalidate_jacobian()
        else:
            n = K.integrate(self.y, t_start, t_end, dt0, method, self.opt.rtol, self._atol, self.P, self.U,
                            self._tab_i, self._tab_o, self._ta0, self._tda, self._tp, *self._quad,
                            rdt, rec, nmax, self.stats, self.quad, self._end_diag, self._end_bd)
        if self.stats[4] == 0.0:
            # outputs at the end point come with the integration (evaluate_point reuses them)
            self._end_key = (float(t_end), self.y.copy(), self.U.copy(), self.P.copy(), self._tp)
        if method > 0:
            self.stats[ST_H[method]] = self.stats[3]
            d = self.stats[:3] - before
            # cost in right-hand-side equivalents per simulated second (deterministic, unlike wall time):
            # the implicit step adds its linear algebra, 12-17 us per step attempt (7218B, 16 balls), about
            # one right-hand side under Kalker traction and half of one under EHL traction: counted as 1
            cost = (d[2] + (ROSW_LA_RHS * (d[0] + d[1]) if method == 2 else 0.0)) / (t_end - t_start)
            k = ST_C2 if method == 2 else ST_C1
            self.stats[k] = cost if self.stats[k] <= 0 else 0.5 * (self.stats[k] + cost)
        return n

    def integrator_state(self):
        """A copy of the integrator's memory beyond stats (the implicit method's W and its factors), for
        rollback with set_integrator_state: a step repeated from a restored state repeats the arithmetic."""
        return None if self._rosw_ws is None else tuple(a.copy() for a in self._rosw_ws)

    def set_integrator_state(self, ws):
        if ws is None:
            self.invalidate_jacobian()
        else:
            self._rosw_ws = tuple(a.copy() for a in ws)

    def invalidate_jacobian(self):
        """Make the implicit integrator rebuild its Jacobian at its next step (after the state was set
        from outside, e.g. an FMU rollback, so that a repeated step repeats the same arithmetic)."""
        if self._rosw_ws is not None:
            self._rosw_ws[-1][:] = (K.JAC_EVERY, -1.0)

    def _auto_choose(self) -> int:
        """integrator='auto': run the cheaper of the explicit Dormand-Prince (1) and the Rosenbrock-W (2)
        integrators, by their measured cost per simulated second (stats[ST_C1], stats[ST_C2]); the
        other one is probed every AUTO_PROBE intervals (times how much dearer it was, up to 8x), or sooner
        when the current one becomes much dearer than the other's last cost. The selector state lives in stats, so FMU rollback restores it."""
        st = self.stats
        ex = AUTO_EXPLICIT
        # Kalker creep forces are stiff at low rolling speed: start with the Rosenbrock-W, and until the
        # explicit method has been measured take its cost from its stability limit (_explicit_cost_kalker)
        # instead of probing it at the second interval (at 1000 rpm one 5 ms probe cost as much as 20 ms of
        # the implicit method; docs/kalker.md)
        kalker = self.opt.race_traction == "kalker"
        cur = int(st[ST_CUR]) if st[ST_CUR] > 0 else (2 if kalker else ex)
        other = 2 if cur != 2 else ex
        c_cur, c_oth = st[ST_C2 if cur == 2 else ST_C1], st[ST_C2 if other == 2 else ST_C1]
        if kalker and cur == 2 and c_oth <= 0 and c_cur > 0:
            c_oth = self._explicit_cost_kalker()
        st[ST_AGE] += 1
        # the probe interval grows with how much dearer the other method was (up to 8x): a probe of a
        # method 5x dearer every AUTO_PROBE chunks cost ~15 % (explicit at 1000 rpm, EHL traction)
        every = AUTO_PROBE * min(8.0, max(1.0, c_oth / c_cur)) if c_oth > 0 and c_cur > 0 else AUTO_PROBE
        probe = st[ST_AGE] >= every or (c_oth > 0 and c_cur > 1.5 * c_oth) or (c_oth <= 0 and st[ST_AGE] >= 2)
        if probe:
            st[ST_AGE] = 0
            st[ST_CUR] = other       # run the other one now; the next choice compares the two costs
            return other
        if c_oth > 0 and c_oth < c_cur:
            cur = other
        st[ST_CUR] = cur
        return cur

    def _explicit_cost_kalker(self) -> float:
        """Right-hand sides per simulated s the explicit adaptive RK4 would need under Kalker traction, from
        the stability limit of the stiffest creep relaxation (integrator='auto', before the explicit method
        has been measured). Kalker's linear theory gives the creep force -G c^2 C11 xi with xi = v_slip /
        |u_roll|, a damper k = G c^2 C11 / |u_roll| [N s/m] on the contact slip; a ball (mass m, inertia J)
        relaxes that slip at lambda = k (1/m + (D/2)^2 / J) [1/s]. RK4 is stable to h lambda <= 2.785 on the
        negative real axis (Hairer & Wanner II, Sec. IV.2; value recalled), 4 right-hand sides per step. The
        linear-theory slope is the largest creep slope (partial slip lowers it), so this overstates the cost:
        7218B, Fx 1000 N, Fz 3000 N, mu 0.1: estimate 3.5-3.7M at 1000 rpm and 0.39-0.40M at 10,000 rpm,
        measured 1.0-1.2M and 0.27-0.29M per simulated s. It only steers the choice until the explicit
        method's own cost has been measured (its first probe)."""
        from .fastsim import max_creep_damping
        _, bd = self.evaluate_point()
        G, nu = self.P[K.P_GCOMB], self.P[K.P_NUCOMB]
        k = max(max_creep_damping(bd[:, K.BD_AI_SEMI], bd[:, K.BD_BI], bd[:, K.BD_QI], bd[:, K.BD_UI], G, nu),
                max_creep_damping(bd[:, K.BD_AO_SEMI], bd[:, K.BD_BO], bd[:, K.BD_QO], bd[:, K.BD_UO], G, nu))
        D = self.P[K.P_D]
        return 4.0 * k * (1.0 / self.P[K.P_MB] + 0.25 * D * D / self.P[K.P_JB]) / 2.785

    def integrals(self) -> dict:
        """Time integrals [channel unit x s] of every output channel (dynamics_kernels.OUT_NAMES) since the
        last reset_integrals(), accumulated inside the integrator over its accepted steps (trapezoidal
        rule, dynamics_kernels.NQUAD): e.g. 'P_race_inner' is the energy [J] dissipated at the inner races,
        'friction_torque' the angular impulse [N m s]."""
        return dict(zip(K.OUT_NAMES, self.quad[:K.NOUT].tolist()))

    def reset_integrals(self):
        """Zero the time integrals (the next integration starts a new trapezoid at its first point)."""
        self.quad[:] = 0.0

    def _shaft_speed(self, t):
        w, _ = K._shaft(self.U, t)
        return w

    def outputs(self) -> dict:
        """Output channels at the current instant (names: dynamics_kernels.OUT_NAMES)."""
        return dict(zip(K.OUT_NAMES, self.evaluate_point()[0].tolist()))

    def ball_details(self) -> dict:
        """Per-ball contact angles [rad], loads [N], semi-axes [m], pressures [Pa], traction forces
        [N], centre slips [m/s], entrainment speeds [m/s], spins [rad/s] at the current instant. For a
        four-point-contact bearing the *_i / *_o values are each ring's first (more loaded) arc and
        Q_i2, alpha_i2, Q_o2, alpha_o2 the second arc (0 load when it does not touch)."""
        diag = np.zeros(K.NOUT)
        nb = int(self.P[K.P_NB])
        bd = np.zeros((nb, K.NBD))
        K.evaluate(self.t, self.y, self.P, self.U, self._tab_i, self._tab_o, self._ta0, self._tda, self._tp,
                   *self._quad, diag, bd)
        names = ("alpha_i", "alpha_o", "Q_i", "Q_o", "delta_i", "delta_o", "a_i", "b_i", "a_o", "b_o",
                 "p_i", "p_o", "Ft_i", "Fm_i", "Ft_o", "Fm_o", "slip_i", "slip_o", "u_i", "u_o",
                 "spin_i", "spin_o", "slip_m_i", "slip_m_o", "F_pocket")
        d = {n: bd[:, k].copy() for k, n in enumerate(names)}
        # four-point contact: the second (less loaded) arc of each ring; Q_i, alpha_i, ... hold the first
        for n, k in (("Q_i2", K.BD_QI2), ("alpha_i2", K.BD_AI2), ("Q_o2", K.BD_QO2), ("alpha_o2", K.BD_AO2)):
            d[n] = bd[:, k].copy()
        b = K.NSTATE_FIXED + K.NSB * np.arange(nb)
        d["theta"] = self.y[b].copy()
        d["orbit_speed"] = self.y[b + 3].copy()
        d["omega"] = self.y[np.stack([b + 6, b + 7, b + 8], axis=1)].copy()
        W = d["omega"]
        # attitude angle (from the bearing axis, Harris's beta sign) and yaw angle of the spin axis
        Wrel_z = W[:, 2] - d["orbit_speed"]
        d["attitude"] = np.arctan2(-W[:, 0], np.abs(Wrel_z)) * np.sign(-Wrel_z + 1e-300) * -1.0
        d["yaw"] = np.arctan2(W[:, 1], np.hypot(W[:, 0], Wrel_z))
        return d


MIRROR_LOADS = np.array([1.0, -1.0, 1.0, -1.0, 1.0])
"""Reflection in the x-z plane of (Fx, Fy, Fz, Mx, My): moments are axial vectors."""
MIRROR_DISP = np.array([1.0, -1.0, 1.0, -1.0, 1.0, 1.0, -1.0, 1.0, -1.0, 1.0])


def mirror_state(y: np.ndarray, nb: int) -> np.ndarray:
    """The state (dynamics_kernels layout) reflected in the x-z plane (y -> -y, a plane through the bearing
    axis): positions y, rates vy, tilts and tilt rates about x, angles and speeds about z change sign (axial
    vectors: a component in the plane flips, the normal one stays); ball j at theta goes to the ball at
    -theta, index (nb - j) % nb, with (Omega_r, Omega_t, Omega_z) -> (-Omega_r, Omega_t, -Omega_z)."""
    m = y.copy()
    for i in (1, 3, 6, 8, 10, 11, 13, 15, 17, 19):
        m[i] = -y[i]
    for j in range(nb):
        b = K.NSTATE_FIXED + K.NSB * j
        k = K.NSTATE_FIXED + K.NSB * ((nb - j) % nb)
        m[k:k + K.NSB] = y[b:b + K.NSB] * np.array([-1.0, 1.0, 1.0, -1.0, 1.0, 1.0, -1.0, 1.0, -1.0])
    return m


SEED000_PROFILE = ((0.0, 1000.0), (0.5, 1000.0), (1.4, 10000.0), (2.0, 10000.0))
"""Seed 000 acceleration case: (time [s], inner-ring speed [rpm]) breakpoints: 1000 rpm to 0.5 s, then
10,000 rpm/s up to 10,000 rpm at 1.4 s, held to 2 s (Lubricants 2025 13(5) 218, section 4)."""


PROFILE_LOAD_COLUMNS = ("Fx_N", "Fy_N", "Fz_N", "Mx_Nm", "My_Nm")


def read_profile(spec: str):
    """A speed profile: 'seed000' (SEED000_PROFILE) or a CSV file with columns time_s, speed_rpm (signed:
    negative turns the shaft backwards, |speed| <= 190,986 rpm = 2e4 rad/s) and optionally Fx_N, Fy_N,
    Fz_N, Mx_Nm, My_Nm and outer_speed_rpm (held per segment at the segment's start value in
    simulate_profile when given as a third tuple element). Returns (times [s], speeds [rpm], loads) with loads a dict
    of the load columns present (None if none). Bad files raise BearingInputError('profile', ...)."""
    import csv
    from pathlib import Path
    if spec == "seed000":
        t, n = zip(*SEED000_PROFILE)
        return np.array(t), np.array(n), None
    p = Path(spec)
    if not p.is_file():
        raise BearingInputError("profile", spec, "seed000 or an existing CSV file")
    with p.open() as fh:
        rows = list(csv.DictReader(fh))
    try:
        t = np.array([float(r["time_s"]) for r in rows])
        n = np.array([float(r["speed_rpm"]) for r in rows])
        loads = {c: np.array([float(r[c]) for r in rows]) for c in PROFILE_LOAD_COLUMNS if rows and c in rows[0]}
    except (KeyError, ValueError, TypeError):
        raise BearingInputError("profile", spec, "rows with numeric time_s, speed_rpm (and load columns if given)")
    vals = np.concatenate([t, n] + list(loads.values()))
    if len(t) < 2 or np.any(np.diff(t) <= 0) or not np.all(np.isfinite(vals)):
        raise BearingInputError("profile", spec, ">= 2 rows, strictly increasing finite time_s, finite values")
    if np.any(np.abs(n) > 2.0e4 * 30.0 / math.pi):
        raise BearingInputError("profile", spec, "|speed_rpm| <= 190986 rpm (2e4 rad/s)")
    if rows and "outer_speed_rpm" in rows[0]:
        try:
            no = np.array([float(r["outer_speed_rpm"]) for r in rows])
        except (ValueError, TypeError):
            raise BearingInputError("profile", spec, "numeric outer_speed_rpm")
        if not np.all(np.isfinite(no)) or np.any(np.abs(no) > 2.0e4 * 30.0 / math.pi):
            raise BearingInputError("profile", spec, "finite |outer_speed_rpm| <= 190986 rpm")
        loads = dict(loads, outer_speed_rpm=no)
    return t, n, (loads or None)


def simulate_profile(model: DynamicModel, profile, record_dt: float | None = None, progress=None) -> np.ndarray:
    """Drive an initialised model through a piecewise-linear speed profile ((t [s], speed [rpm]), ...)
    starting at the model's current time; returns the concatenated records. Python is entered once per
    profile segment (or per chunk of at most 0.05 s when ``progress`` is given, to report progress)."""
    prof = [(float(p[0]), float(p[1])) for p in profile]
    outer = [float(p[2]) if len(p) > 2 else None for p in profile]
    if any(not (math.isfinite(t) and math.isfinite(n)) for t, n in prof):
        raise BearingInputError("profile", profile, "finite (time s, speed rpm) pairs")
    if any(b[0] <= a[0] for a, b in zip(prof, prof[1:])):
        raise BearingInputError("profile", profile, "strictly increasing times")
    if any(abs(n) > 2.0e4 * 30.0 / math.pi for _, n in prof):
        raise BearingInputError("profile", profile, "speeds within +-190986 rpm (2e4 rad/s), signed")
    out = []
    t_end = prof[-1][0]
    for i, ((t0, n0), (t1, n1)) in enumerate(zip(prof, prof[1:])):
        if t1 <= model.t + 1e-12:
            continue
        if outer[i] is not None:       # outer-ring speed [rpm] held over the segment
            model.U[K.U_WO] = check_range("outer_speed_rpm", outer[i], -2.0e4 * 30.0 / math.pi,
                                          2.0e4 * 30.0 / math.pi, unit="rpm") * math.pi / 30.0
        chunks = [t1] if progress is None else list(np.arange(model.t + 0.05, t1, 0.05)) + [t1]
        for tc in chunks:
            if tc <= model.t + 1e-12:
                continue
            w = (n0 + (n1 - n0) * (tc - t0) / (t1 - t0)) * math.pi / 30.0
            out.append(model.advance(tc, omega_end=w, record_dt=record_dt))
            model.update_operating_geometry()     # ring growth at the speed reached (piecewise per chunk)
            if progress is not None:
                progress(model.t, t_end)
    return np.concatenate(out) if out else np.zeros((0, K.NOUT))


def advance_many(models, t_end, omega_end=None, record_dt: float | None = None, workers: int | None = None,
                 return_exceptions: bool = False) -> list:
    """Advance independent initialised models (e.g. the operating points of a sweep) to t_end [s] (a scalar
    or one per model) concurrently in one process: each model runs in a thread of a pool of ``workers``
    (default: one per CPU); the integration kernels release the GIL (numba nogil), so the threads run in
    parallel for all but the little Python around each kernel call. omega_end: None, a scalar or one per
    model [rad/s]. Returns the records of each model (as DynamicModel.advance), in order; the first error
    of any model is raised after all have finished, or with return_exceptions=True a model's exception
    takes its place in the list (the other models' results are kept)."""
    import os
    from concurrent.futures import ThreadPoolExecutor
    models = list(models)
    n = len(models)
    t_end = list(t_end) if np.ndim(t_end) else [t_end] * n
    omega_end = list(omega_end) if np.ndim(omega_end) else [omega_end] * n
    if len(t_end) != n or len(omega_end) != n:
        raise BearingInputError("t_end / omega_end", (len(t_end), len(omega_end)), f"scalars or {n} values")
    workers = max(1, min(n, workers or os.cpu_count() or 1))
    if workers == 1 and not return_exceptions:
        return [m.advance(t, omega_end=w, record_dt=record_dt) for m, t, w in zip(models, t_end, omega_end)]
    if workers == 1:
        out = []
        for m, t, w in zip(models, t_end, omega_end):
            try:
                out.append(m.advance(t, omega_end=w, record_dt=record_dt))
            except Exception as e:       # this model's error, in its place
                out.append(e)
        return out
    with ThreadPoolExecutor(max_workers=workers) as ex:
        futs = [ex.submit(m.advance, t, w, record_dt) for m, t, w in zip(models, t_end, omega_end)]
        if not return_exceptions:
            return [f.result() for f in futs]
        return [f.exception() or f.result() for f in futs]


def records_to_dict(rec: np.ndarray) -> dict:
    """Columns of an advance() record array by name."""
    return {n: rec[:, k] for k, n in enumerate(K.OUT_NAMES)}
