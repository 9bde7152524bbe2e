"""Options and parameter assembly of the transient model: DynamicsOptions (checked on construction of a
model) and DynamicSetup, the bearing's running geometry, Hertz tables, traction parameters and the parameter
and input vectors of bearing_core.models.dynamics_kernels' right-hand side. The time integration is
DynamicModel's (bearing_core.models.dynamics); the quasi-static tribological model builds its
right-hand side from this module alone. SI units."""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ..contact import contact_kernels as CK
from . import dynamics_kernels as K
from ..errors import BearingInputError, check_range
from ..bearing.geometry import BearingGeometry
from ..contact.hertz_tables import HertzInterp
from ..lubrication.lubricants import get_lubricant
from ..numerics.compare import same_point

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
COUPLINGS = ("load", "displacement")
#: film of the flooded guiding land (DynamicsOptions.land_film): the film of a cage centre at rest (seed 001 Eq. 4)
#: or with the whirl and squeeze terms of a moving centre
LAND_FILMS = ("stationary", "moving")
START_MODELS = ("jones-harris", "tribological")


@dataclass(frozen=True)
class DynamicsOptions:
    """Model options (SI). traction: 'lubricated' (EHL traction from the oil's rheology over each contact
    ellipse with mixed lubrication by film parameter and the EHL rolling resistance, bearing_core.lubrication.ehl_traction;
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
    force and Petroff drag of seed 001 Eqs. 4-5 besides the contact penalty). land_film: 'stationary' (the film
    force of seed 001 Eq. 4, that of a cage centre at rest) or 'moving' (with the whirl and squeeze terms of the
    Reynolds equation for a moving centre: the film then opposes a cage whirl faster than half the sum of the
    surface speeds and damps the cage's radial motion; stiff where the cage runs close to its land, so the
    integration takes 2.4x the right-hand sides on seed 000's profile, docs/tribology.md).
    churning: oil churning torques of seed 001 Eqs. 12-17 (bearing_core.lubrication.churning) on the cage and the inner
    ring, in the oil-air mixture of oil_fraction (ball drag is the existing Eq. 10 term). oil_supply: a
    bearing_core.lubrication.oil_supply.OilSupply; with oil_fraction 0 the mixture's oil fraction is its cavity
    oil content at the current shaft speed (oil_supply.cavity_oil_fraction; an oil_fraction > 0 overrides
    it). oil: name in
    bearing_core.lubrication.lubricants (default: the traction curve's oil) for viscosity, density and pressure-
    viscosity; oil_temperature [K]: its temperature when thermal is off. thermal: a thermal network
    (bearing_core.heat.thermal, seed 001 Eqs. 21-29; thermal_data: ThermalData) stepped on the slow time scale
    after every advance() with the mean losses of the interval (times thermal_time_scale, > 1 to
    fast-forward the heating); its temperatures feed back into the oil viscosity and density (churning,
    drag, flooded land, film thickness) and the traction curve (lubricants.traction_curve_at at the ball
    temperature). roughness [m]: if > 0, the rms roughness of each surface (film parameter Lambda and mixed
    lubrication) in place of the geometry's ball_roughness / race_roughness (0, default).

    lubrication: the lubrication regime, setting consistent laws for races and cage:
      'oil'   -- lubricated race traction (traction must be one of OIL_TRACTIONS); oil-lubricated ball-pocket
                 contacts (films on both walls with EHL / boundary friction in contact,
                 pocket_film.ball_pocket_lubricated) and an oil-flooded guiding land (short journal
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

    Ring growth and fits (bearing_core.bearing.ring_fits): fits, a ring_fits.RingFits (None: free rings), the
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
    land_film: str = "stationary"

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
        if self.land_film not in LAND_FILMS:
            raise BearingInputError("land_film", self.land_film, " | ".join(LAND_FILMS))
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
        from ..lubrication.lubricants import TRACTION_OIL, get_oil
        get_oil(self.oil or TRACTION_OIL[self.lubricant])
        check_range("oil_temperature", self.oil_temperature, 233.15, 473.15, unit="K")
        check_range("thermal_time_scale", self.thermal_time_scale, 1e-3, 1e6)
        if self.roughness != 0.0:
            check_range("roughness", self.roughness, 1e-9, 1e-5, unit="m")
        check_range("mu_boundary", self.mu_boundary, 0.0, 1.0)
        if self.fits is not None:
            from ..bearing.ring_fits import RingFits
            if not isinstance(self.fits, RingFits):
                raise BearingInputError("fits", self.fits, "a bearing_core.bearing.ring_fits.RingFits or None")
        if not isinstance(self.ring_growth, (bool, np.bool_)):
            raise BearingInputError("ring_growth", self.ring_growth, "True | False")
        if self.oil_supply is not None:
            from ..lubrication.oil_supply import OilSupply
            if not isinstance(self.oil_supply, OilSupply):
                raise BearingInputError("oil_supply", self.oil_supply,
                                        "a bearing_core.lubrication.oil_supply.OilSupply or None")
            self.oil_supply.validate()
        if self.thermal_data is not None:
            from ..heat.thermal import ThermalData
            if not isinstance(self.thermal_data, ThermalData):
                raise BearingInputError("thermal_data", self.thermal_data, "a bearing_core.heat.thermal.ThermalData")
            self.thermal_data.validate()


class DynamicSetup:
    """One bearing's model definition for the dynamics' kernels: options, running geometry (fits, ring growth),
    Hertz tables, traction parameters, temperatures, parameter vector P and input vector U."""

    _rosw_ws = None     # implicit integrator's Jacobian workspace (dynamics_kernels.rosw_workspace), per instance
    _end_diag = _end_bd = _end_key = _key_buf = None   # outputs at the last integration's end, key (t, y, U, P, tp)
    _finite = True                                     # the state after the last integration call is finite

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
            from ..bearing.ring_fits import RingFits, _dimensions
            _dimensions(geometry, options.fits or RingFits())   # centrifugal growth needs bore / outside diameter
        if options.fits is not None or options.ring_growth:
            self.update_operating_geometry(0.0)    # bad fits / missing boundary dimensions fail here
        self.t = 0.0
        self.y = None
        self.stats = np.zeros(NSTATS)
        self.quad = np.zeros(K.NQUAD)     # time integrals of the output channels (integrals())
        self.qs = None

    # ---- operating geometry: fits and ring growth (bearing_core.bearing.ring_fits) ----------------------
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
        from ..bearing.ring_fits import OperatingTemperatures
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
        from ..bearing.ring_fits import operating_geometry
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
        from ..bearing.ring_fits import ring_growth
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
        from ..contact.hertz import reduced_modulus
        from ..bearing.materials import get_material
        cm = get_material(g.cage.material)
        P[K.P_EPK] = reduced_modulus(g.ball_material.E, g.ball_material.nu, cm.E, cm.nu)
        P[K.P_SIGPK] = math.hypot(o.roughness if o.roughness > 0 else g.ball_roughness, o.cage_roughness)
        # flooded land: the film force acts up to a minimum film of 3 composite roughnesses (the full-film
        # limit Lambda = 3) in the oil regime; 0.95 for a land flooded through land_viscosity in the solid regime
        P[K.P_EPSMAX] = (max(0.95, 1.0 - 3.0 * P[K.P_SIGPK] / (0.5 * g.cage.land_clearance))
                         if o.regime == "oil" else 0.95)
        from ..contact.fastsim import combined_elastic
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
        P[K.P_LANDFILM] = 1.0 if o.land_film == "moving" else 0.0
        P[K.P_WLAND] = g.cage.land_width
        from ..lubrication.churning import ChurningGeometry
        cg = ChurningGeometry.from_bearing(g)
        P[K.P_CH_ON] = 1.0 if o.churning else 0.0
        P[K.P_CH_BC], P[K.P_CH_DC], P[K.P_CH_CC] = cg.B_c, cg.D_c, cg.c_c
        P[K.P_CH_WALL] = 1.0 if g.cage.guidance == "inner" else 0.0
        P[K.P_CH_BIR], P[K.P_CH_DLI], P[K.P_CH_CS] = cg.B_ir, cg.D_Li, cg.c_s
        return P

    # ---- oil properties and temperatures ------------------------------------------------------
    @property
    def oil_name(self) -> str:
        from ..lubrication.lubricants import TRACTION_OIL
        return self.opt.oil or TRACTION_OIL[self.opt.lubricant]

    def cavity_oil(self):
        """oil_supply.CavityOil of options.oil_supply at the current relative shaft speed (None without a
        supply or with an explicit oil_fraction > 0)."""
        o = self.opt
        if o.oil_supply is None or o.oil_fraction > 0.0:
            return None
        from ..lubrication.oil_supply import cavity_oil_fraction
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
        from ..lubrication.lubricants import get_oil, traction_curve_at
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
        from ..contact.fastsim import combined_elastic, kalker_coefficients
        from ..lubrication.film import ellipticity_nb
        from ..lubrication.lubricants import rheology_traction_params
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
        """Hamrock-Dowson film thickness (bearing_core.lubrication.film, seed 003 Eq. 23) of every ball-race contact at
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
        return K.contact_films(bd, g.D, g.dm, g.fi, g.fo, *self.film_parameters(), h)

    def film_parameters(self) -> tuple:
        """(eta0 [Pa s], alpha [1/Pa] of the oil at its current temperature, reduced modulus E' [Pa], rms
        roughness of ball and race [m]): the arguments of dynamics_kernels.contact_films after the geometry,
        recomputed when the oil temperature or the options change."""
        T = getattr(self, "_T_oil", self.opt.oil_temperature)
        key = (id(self.opt), T)
        if getattr(self, "_film_key", None) != key:      # oil properties at T, recomputed when T changes
            from ..lubrication.lubricants import get_oil
            g = self.g
            oil = get_oil(self.oil_name)
            Ep = 2.0 / ((1 - g.ring_material.nu ** 2) / g.ring_material.E
                        + (1 - g.ball_material.nu ** 2) / g.ball_material.E)
            self._film_key = key
            self._film_par = (float(oil.eta(T)), float(oil.alpha(T)), Ep, *self.roughness_pair())
        return self._film_par

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
