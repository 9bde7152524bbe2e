"""Co-simulation session of one bearing: the FMI-free core of the FMU (fmu_src/ only maps variables).

    s = CoSimSession(CoSimParameters(bearing="7218B", traction_model="lubricated"))
    s.initialize(t0=0.0, inputs={"shaft_speed": 104.7, "Fz": 3000.0})
    out = s.step(t=0.0, h=1e-3, inputs={...})       # advances exactly to t + h, inputs held
    out["cage_speed"]                                # outputs: a read-only mapping (s.values: the array)

Inputs are held constant over a step (shaft speed included: a speed step is applied at the start of
the step). Outputs are the instantaneous values at the end of the step, except the energy-carrying ones
(STEP_AVERAGED: heat fluxes, friction torques, drive power), which are averages over the communication step
(the time integral accumulated inside the integrator divided by the step), so that sum(heat_flux * h) is
the energy dissipated; their instantaneous values are the outputs 'instantaneous_<name>'. Every
problem is reported as a StepRejected (recoverable: the state is left as before the step) or
BearingInputError (configuration); numbers that are not finite never leave this module. SI units: rad/s, N, N m, m, rad, W, Pa.

CoSimParameters.fidelity chooses the model: 'dynamic' (default, the tribo-dynamic model above) or a steady level
of bearing_core.session.fidelity ('map': an operating map of bearing build-map, map_file), to which the session
then delegates; the same inputs, outputs, units and statuses (docs/fidelity.md).
"""
from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ..models.dynamics import DynamicModel, DynamicsOptions
from ..errors import BearingInputError, ConvergenceError, check_range
from ..bearing.geometry import load_preset
from ..models import dynamics_kernels as K
from ..models import life as LF
from .cosim_spec import INPUT_NAMES, INPUT_UNITS, OUTPUT_NAMES, OUTPUT_SPEC  # noqa: F401 (re-export)
from .cosim_spec import INT_OUTPUT_NAMES, INT_OUTPUT_SPEC  # noqa: F401 (re-export)
from .cosim_spec import LIFE_CAP_H, P_LIMIT, STEP_AVERAGED_NAMES, parse_inputs
from . import session_kernels as SK
from ..models.skid import SKID_MIN_SPEED, SKID_OVERSKIDDING, SKID_PURE_ROLLING, SKID_SKIDDING, SKID_TOL
from .output_map import (ALL_OUTPUT_NAMES, CSR_MIN_SPEED, HEAT_CHANNELS, OUTPUT_INDEX,  # noqa: F401 E402
                         OUT_CH, OUT_IDX, OUT_PTR, STEP_AVERAGED)
assert (SKID_SKIDDING, SKID_PURE_ROLLING, SKID_OVERSKIDDING) == (1, 0, -1)   # the codes assemble_outputs writes
_I_RUNAWAY = OUTPUT_INDEX["thermal_runaway"]
_I_PMAX = OUTPUT_INDEX["max_contact_pressure"]
_I_LIFE = OUTPUT_INDEX["life_L10r_h"]
_I_DAMAGE = OUTPUT_INDEX["fatigue_damage"]
_CH_SHAFT = K.OUT_INDEX["shaft_speed"]
_CH_OUTER = K.OUT_INDEX["outer_ring_speed"]
_INT_SLICE = slice(len(OUTPUT_NAMES), len(ALL_OUTPUT_NAMES))


class Outputs(Mapping):
    """Read-only name -> value view of an output array (Real outputs as float, Integer ones as int)."""

    __slots__ = ("_v",)

    def __init__(self, values: np.ndarray):
        self._v = values

    def __getitem__(self, name):
        i = OUTPUT_INDEX[name]
        return int(self._v[i]) if i >= _INT_SLICE.start else float(self._v[i])

    def __iter__(self):
        return iter(ALL_OUTPUT_NAMES)

    def __len__(self):
        return len(ALL_OUTPUT_NAMES)

    def __repr__(self):
        return f"Outputs({dict(self)!r})"


class StepRejected(RuntimeError):
    """The step could not be taken (bad input or solver failure); the session state is unchanged."""


@dataclass
class CoSimParameters:
    """Fixed parameters of a session (validated by CoSimSession)."""

    bearing: str = "7218B"
    traction_model: str = "lubricated"     # lubricated | coulomb | kalker
    friction_coefficient: float = 0.1
    cage_friction_coefficient: float = 0.1
    lubricant: str = "generic-mineral-oil"
    coupling: str = "load"                 # load | displacement
    outer_mounting: str = "fixed"          # fixed | elastic
    housing_stiffness: float = 1e8
    fixed_tilt: bool = False
    integrator_tolerance: float = 1e-4
    integrator: str = "auto"               # auto | adaptive | implicit | rk4 (auto: the stiff EHL traction)
    # geometry overrides of the preset (0 keeps the preset value)
    free_contact_angle: float = 0.0        # rad
    pocket_clearance: float = 0.0          # m, diametral
    land_clearance: float = 0.0            # m, diametral
    ball_diameter: float = 0.0             # m (D)
    pitch_diameter: float = 0.0            # m (dm)
    number_of_balls: int = 0               # Z
    inner_groove_conformity: float = 0.0   # fi = inner groove radius / D
    outer_groove_conformity: float = 0.0   # fo = outer groove radius / D
    # oil, churning and the thermal network
    oil: str = ""                          # lubricants.OILS name ("" = the traction curve's oil)
    oil_fraction: float = 0.0              # oil volume fraction of the oil-air mixture (drag, churning)
    churning: bool = False                 # seed 001 Eqs. 12-17 churning torques on cage and inner ring
    oil_temperature: float = 313.15        # K, oil temperature when thermal is off
    thermal: bool = False                  # thermal network (seed 001 Eqs. 21-29), stepped every step
    ambient_temperature: float = 308.15    # K, ambient air and initial temperature of the network
    oil_inlet_temperature: float = 0.0     # K, oil supply temperature (0 = ambient)
    oil_flow_rate: float = 0.0             # m^3/s of circulating oil through the bearing
    # oil supply (bearing_core.lubrication.oil_supply): jet | oil-air | bath | grease; with oil_fraction 0 the cavity oil
    # content follows from it when oil_flow_rate > 0 or the method is bath / grease
    lubrication_method: str = "jet"
    oil_level: float = 0.0                 # m, bath: static level above the lowest point of the outer raceway
    thermal_time_scale: float = 1.0        # thermal seconds per simulated second (> 1 fast-forwards heating)
    # lubrication regime of races and cage: auto (from traction_model) | oil | solid | dry (DynamicsOptions)
    lubrication: str = "auto"
    # fits and ring growth (bearing_core.bearing.ring_fits; DynamicsOptions.fits / ring_growth)
    ring_growth: bool = False              # centrifugal (inner ring) and thermal growth of rings and balls
    shaft_interference: float = 0.0        # m, diametral, inner ring on the shaft (> 0 tight)
    housing_interference: float = 0.0      # m, diametral, outer ring in the housing (> 0 tight)
    shaft_bore: float = 0.0                # m, bore of a hollow shaft (0: solid)
    bore_diameter: float = 0.0             # m, bearing bore d (0: from the bearing definition)
    outside_diameter: float = 0.0          # m, bearing outside diameter (0: from the bearing definition)
    # fidelity level (bearing_core.session.fidelity, docs/fidelity.md): dynamic (the full model) | map (an operating
    # map of steady outputs, map_file from bearing build-map)
    fidelity: str = "dynamic"
    map_file: str = ""


class CoSimSession:
    """One bearing in a co-simulation (several sessions are independent: no shared state)."""

    def __init__(self, params: CoSimParameters):
        self.p = params
        self.model: DynamicModel | None = None
        self.t = 0.0
        # outputs at the last communication point, in the order of ALL_OUTPUT_NAMES (updated in place: the
        # FMU reads its output variables from this array)
        self.values = np.zeros(len(ALL_OUTPUT_NAMES))
        # a steady fidelity level (bearing_core.session.fidelity) runs the session instead of the dynamic model
        self.steady = None
        self.warnings = []     # messages for the FMU log (steady levels: entry into a region where they are weak)
        from .fidelity import FIDELITIES, FIDELITY_LEVELS
        if params.fidelity not in FIDELITIES:
            raise BearingInputError("fidelity", params.fidelity, " | ".join(FIDELITIES))
        if params.fidelity != "dynamic":
            from .fidelity import ALL_NAMES as FIDELITY_NAMES, SteadySession
            assert ALL_OUTPUT_NAMES == FIDELITY_NAMES
            level = FIDELITY_LEVELS[params.fidelity](params, self._geometry, self._options, self._check_loads)
            self.steady = SteadySession(params, level, self.values, Outputs,
                                        StepRejected, CSR_MIN_SPEED)
            self.warnings = self.steady.warnings
        self.thermal_runaway = False
        # work arrays of one communication point (allocated once: no per-step allocations)
        self._new = np.zeros(len(ALL_OUTPUT_NAMES))
        self._x = np.zeros(2 * K.NOUT + len(SK.EXTRA_NAMES))
        self._ext = np.zeros(SK.N_EXT)
        self._ext_isothermal = False   # ext holds the (constant) temperatures of a model without the network
        from ..models.tangent_stiffness import TangentStiffness
        self._tangent = TangentStiffness()
        self._films = None
        self._saved = None          # rollback buffers of the step in progress (_save)
        self._in_key = None         # (inputs as given, model geometry) of the last validated inputs
        self._in_u = None           # ... and their validated values
        self._applied = None        # the validated inputs the model holds (None: apply at the next step)
        self._life_par = None       # (geometry, models.life.life_parameters of it) for the fatigue outputs

    @property
    def outputs(self) -> Outputs:
        """Snapshot of the outputs at the last communication point (name -> value)."""
        return Outputs(self.values.copy())

    def _geometry(self):
        """The preset with the non-zero geometry overrides applied (validated by BearingGeometry)."""
        import dataclasses
        p = self.p
        g = load_preset(p.bearing)
        for name, v in (("free_contact_angle", p.free_contact_angle), ("pocket_clearance", p.pocket_clearance),
                        ("land_clearance", p.land_clearance)):
            check_range(name, v, 0.0, None)
        if p.free_contact_angle > 0.0:
            g = g.with_overrides(alpha0=float(p.free_contact_angle))
        cage = g.cage
        if p.pocket_clearance > 0.0:
            cage = dataclasses.replace(cage, pocket_clearance=float(p.pocket_clearance))
        if p.land_clearance > 0.0:
            cage = dataclasses.replace(cage, land_clearance=float(p.land_clearance))
        if cage is not g.cage:
            g = g.with_overrides(cage=cage)
        # main geometry values (0 keeps the bearing definition); ranges of Harris & Kotzalas, Rolling Bearing
        # Analysis 5th ed., Vol. 1 Ch. 2 (conformity r/D > 0.5 for a ball to fit its groove; 0.515-0.54 usual)
        over = {}
        for name, field_, lo, hi, unit in (("ball_diameter", "D", 1e-4, 0.2, "m"), ("pitch_diameter", "dm", 1e-3, 2.0, "m"),
                                           ("inner_groove_conformity", "fi", 0.5, 1.0, ""),
                                           ("outer_groove_conformity", "fo", 0.5, 1.0, "")):
            v = getattr(p, name)
            if v != 0.0:
                check_range(name, v, lo, hi, lo_incl=False, unit=unit)
                over[field_] = float(v)
        if p.number_of_balls != 0:
            if p.number_of_balls != int(p.number_of_balls) or not 3 <= p.number_of_balls <= 200:
                raise BearingInputError("number_of_balls", p.number_of_balls, "an integer 3 <= Z <= 200 (0: from the "
                                        "bearing definition)")
            over["Z"] = int(p.number_of_balls)
        if over:
            D, dm, Z = over.get("D", g.D), over.get("dm", g.dm), over.get("Z", g.Z)
            set_ = ", ".join(n for n, f in (("ball_diameter", "D"), ("pitch_diameter", "dm"), ("number_of_balls", "Z"),
                                            ("inner_groove_conformity", "fi"), ("outer_groove_conformity", "fo"))
                             if f in over)
            if not D < 0.5 * dm:
                raise BearingInputError("ball_diameter" if "D" in over else "pitch_diameter", D if "D" in over else dm,
                                        f"ball_diameter < pitch_diameter / 2 (here D = {D:.6g} m, dm = {dm:.6g} m)")
            # balls must not overlap on the pitch circle: Z D < pi dm, i.e. Z <= pi / asin(D / dm)
            zmax = int(math.pi / math.asin(D / dm))
            if Z > zmax:
                raise BearingInputError("number_of_balls", Z, f"Z <= {zmax} (balls of D = {D:.6g} m touch on the "
                                        f"pitch circle dm = {dm:.6g} m)")
            try:
                g = g.with_overrides(**over)
            except BearingInputError as e:
                raise BearingInputError(set_, [getattr(p, n.strip()) for n in set_.split(",")],
                                        "a consistent bearing geometry", str(e)) from None
        return g

    def _options(self) -> DynamicsOptions:
        p = self.p
        # check under the names the user set (FMU parameters), before DynamicsOptions checks its own
        check_range("friction_coefficient", p.friction_coefficient, 0.0, 1.0)
        check_range("cage_friction_coefficient", p.cage_friction_coefficient, 0.0, 1.0)
        check_range("integrator_tolerance", p.integrator_tolerance, 1e-10, 1e-2)
        check_range("housing_stiffness", p.housing_stiffness, 1e4, 1e12, unit="N/m")
        if p.traction_model not in ("lubricated", "coulomb", "kalker"):
            raise BearingInputError("traction_model", p.traction_model, "lubricated | coulomb | kalker")
        check_range("oil_fraction", p.oil_fraction, 0.0, 1.0)
        check_range("ambient_temperature", p.ambient_temperature, 233.15, 473.15, unit="K")
        T_in = p.oil_inlet_temperature or p.ambient_temperature
        check_range("oil_inlet_temperature", T_in, 233.15, 473.15, unit="K")
        check_range("oil_flow_rate", p.oil_flow_rate, 0.0, 0.1, unit="m3/s")
        from ..lubrication.oil_supply import METHODS, OilSupply
        if p.lubrication_method not in METHODS:
            raise BearingInputError("lubrication_method", p.lubrication_method, " | ".join(METHODS))
        check_range("oil_level", p.oil_level, 0.0, 10.0, unit="m")
        supply = None
        if p.oil_fraction == 0.0 and (p.oil_flow_rate > 0.0 or p.lubrication_method in ("bath", "grease")):
            supply = OilSupply(p.lubrication_method, p.oil_flow_rate, T_in,
                               p.oil_level if p.lubrication_method == "bath" else None).validate()
        td = None
        if p.thermal:
            from ..heat.thermal import ThermalData
            td = ThermalData(T_amb=p.ambient_temperature, T_in=T_in, flow_rate=p.oil_flow_rate)
        fits = self._fits()
        return DynamicsOptions(
            fits=fits, ring_growth=bool(p.ring_growth),
            traction=p.traction_model, lubricant=p.lubricant, mu=p.friction_coefficient,
            mu_pocket=p.cage_friction_coefficient, mu_land=p.cage_friction_coefficient, coupling=p.coupling,
            outer_mount=p.outer_mounting, housing_stiffness=p.housing_stiffness, fixed_tilt=bool(p.fixed_tilt),
            rtol=p.integrator_tolerance, integrator=p.integrator, reduced="full",
            oil=p.oil, oil_fraction=p.oil_fraction, churning=bool(p.churning),
            oil_temperature=p.oil_temperature if not p.thermal else T_in, thermal=bool(p.thermal),
            thermal_data=td, thermal_time_scale=p.thermal_time_scale, lubrication=p.lubrication,
            oil_supply=supply)

    def _fits(self):
        """ring_fits.RingFits of the fit parameters (solid or hollow steel shaft, thick steel housing), or
        None without interference and ring growth (the nominal geometry)."""
        p = self.p
        for name in ("shaft_interference", "housing_interference"):
            check_range(name, getattr(p, name), -1e-3, 1e-3, unit="m")
        for name, hi in (("shaft_bore", 2.0), ("bore_diameter", 2.0), ("outside_diameter", 3.0)):
            check_range(name, getattr(p, name), 0.0, hi, unit="m")
        if not (p.ring_growth or p.shaft_interference != 0.0 or p.housing_interference != 0.0):
            return None
        from ..bearing.ring_fits import RingFits
        g = load_preset(self.p.bearing)
        for name, v, gv, key in (("bore_diameter", p.bore_diameter, g.bore, "bore_diameter_mm"),
                                 ("outside_diameter", p.outside_diameter, g.outside_diameter, "outside_diameter_mm")):
            if v <= 0.0 and not gv > 0.0:
                raise BearingInputError(name, v, "> 0 m", f"fits and ring growth need the bearing's boundary "
                                        f"dimensions; {self.p.bearing} has no {key}: set {name}")
        return RingFits(shaft_interference=float(p.shaft_interference),
                        housing_interference=float(p.housing_interference), shaft_bore=float(p.shaft_bore),
                        bore=float(p.bore_diameter) if p.bore_diameter > 0.0 else None,
                        outside_diameter=float(p.outside_diameter) if p.outside_diameter > 0.0 else None)

    @staticmethod
    def _inputs(inputs: dict) -> dict:
        u = parse_inputs(inputs)
        check_range("shaft_speed", u["shaft_speed"], -2.0e4, 2.0e4, unit="rad/s")
        check_range("outer_ring_speed", u["outer_ring_speed"], -2.0e4, 2.0e4, unit="rad/s")
        for k in ("Fx", "Fy", "Fz"):
            check_range(k, u[k], -1e7, 1e7, unit="N")
        return u

    def _check_seated(self, u: dict, g=None):
        """Load-driven coupling: the axial load must seat the single angular-contact bearing (Fz > 0). Every
        ball pushes the inner ring along its contact line, whose axial component has the same sign for all
        balls (Q_j sin(alpha_j) >= 0), so sum Q_j sin(alpha_j) = Fz has no solution with Fz <= 0 other than
        all Q_j = 0, which carries no radial load or moment either: no equilibrium exists. Refused at once
        instead of after a failed quasi-static solve or with the ring driven out of its raceway.
        A four-point-contact (gothic-arch) bearing carries axial load both ways and radial load alone: it
        needs some load, any direction (Fx, Fy, Fz not all 0)."""
        if g is not None and g.is_four_point:
            if self.p.coupling == "load" and u["Fx"] == 0.0 and u["Fy"] == 0.0 and u["Fz"] == 0.0:
                raise BearingInputError("Fx, Fy, Fz", [0.0, 0.0, 0.0], "a non-zero load on the inner ring",
                                        "an unloaded four-point-contact bearing has no defined inner-ring position")
            return
        if self.p.coupling == "load" and not u["Fz"] > 0.0:
            what = "no axial load" if u["Fz"] == 0.0 else "a reversed axial load"
            raise BearingInputError("Fz", u["Fz"], "Fz > 0 N (the axial load that seats the bearing)",
                                    f"{what} on a single angular-contact bearing: its balls can only push the inner "
                                    "ring axially in one direction, so there is no equilibrium")

    def _check_loads(self, u: dict, g):
        """_check_seated and _check_capacity: the load checks every fidelity level applies before it solves."""
        self._check_seated(u, g)
        self._check_capacity(u, g)

    def _check_capacity(self, u: dict, g):
        """Load-driven coupling: refuse at once loads whose equilibrium surely exceeds the P_LIMIT contact
        stress. The inner-contact forces balance the applied force, so by the triangle inequality
        sum_j Q_j >= |F| and max_j Q_j >= |F| / Z; the Hertz pressure of that load is taken on the flattest
        inner contact over all contact angles (a lower bound of the pressure the model would reach)."""
        if self.p.coupling != "load":
            return
        q = math.sqrt(u["Fx"] ** 2 + u["Fy"] ** 2 + u["Fz"] ** 2) / g.Z
        memo = getattr(self, "_capacity_memo", None)
        if memo is not None and memo[0] == (id(g), q):     # inputs held from the last step: same answer
            p = memo[1]
        else:
            from ..contact.hertz import contact_curvature, hertz_approx, reduced_modulus
            E = reduced_modulus(g.ring_material.E, g.ring_material.nu, g.ball_material.E, g.ball_material.nu)
            p = min(hertz_approx(*contact_curvature(g.D, g.dm, g.fi, a, True)[:2], E).p_max(q)
                    for a in np.linspace(0.0, 0.5 * math.pi, 7))
            self._capacity_memo = ((id(g), q), p)
        if p > P_LIMIT:
            raise BearingInputError("loads", [u["Fx"], u["Fy"], u["Fz"]], "loads the bearing can carry",
                                    f"maximum contact pressure at least {p / 1e9:.2f} GPa (largest ball load >= "
                                    f"|F| / Z = {q:.4g} N) exceeds the {P_LIMIT / 1e9:.1f} GPa static limit of ball "
                                    "bearings (ISO 76)")

    def initialize(self, t0: float, inputs: dict):
        """Build the model and start it from the quasi-static state at the given inputs (a steady level: its
        steady state at the inputs)."""
        if self.steady is not None:
            self.steady.initialize(t0, inputs)
            self.t = self.steady.t
            return
        u = self._inputs(inputs)
        g = self._geometry()
        self._check_seated(u, g)
        self._check_capacity(u, g)
        self.model = DynamicModel(g, self._options())
        loads = (u["Fx"], u["Fy"], u["Fz"], u["Mx"], u["My"])
        disp = None
        if self.p.coupling == "displacement":
            disp = [u[k] for k in ("dx", "dy", "dz", "tx", "ty", "vx", "vy", "vz", "wx", "wy")]
        try:
            self.model.initialize(u["shaft_speed"], loads, displacement=disp, t0=float(t0),
                                  omega_outer=u["outer_ring_speed"])
        except ConvergenceError as e:
            raise BearingInputError("inputs", dict(u), "a load case with a quasi-static equilibrium", str(e))
        self.t = float(t0)
        self._in_key = self._in_u = self._applied = None
        self._ext_isothermal = False
        m = self.model
        SK.same_point(m.t, m.y, m.U, m.P, m.t, m.y, m.U, m.P)    # load the compiled kernel here, not in the first step
        self._update_outputs()
        self._check_limits()

    def _validated(self, inputs: dict) -> dict:
        """The inputs checked (_inputs, _check_seated, _check_capacity); checked again only when they or the
        running geometry changed since the last call (a NaN never compares equal: always checked)."""
        g = self.model.g
        key = self._in_key
        try:
            same = key is not None and key[1] is g and key[0] == inputs
        except (TypeError, ValueError):   # values that do not compare (arrays ...): check them
            same = False
        if same:
            return self._in_u
        try:
            u = self._inputs(inputs)
            self._check_seated(u, g)
            self._check_capacity(u, g)
        except BearingInputError as e:
            raise StepRejected(str(e))
        self._in_key, self._in_u = (dict(inputs), g), u
        return u

    def _save(self):
        """Copy the state a failed step returns to into preallocated buffers."""
        m = self.model
        sv = self._saved
        if sv is None or sv["y"].shape != m.y.shape:
            sv = self._saved = {"y": np.empty_like(m.y), "U": np.empty_like(m.U), "stats": np.empty_like(m.stats),
                                "quad": np.empty_like(m.quad), "out": np.empty_like(self.values)}
        np.copyto(sv["y"], m.y)
        np.copyto(sv["U"], m.U)
        np.copyto(sv["stats"], m.stats)
        np.copyto(sv["quad"], m.quad)
        np.copyto(sv["out"], self.values)
        sv["t"] = m.t
        sv["thermal"] = m.thermal_state()     # None without the thermal network
        return sv

    def step(self, t: float, h: float, inputs: dict) -> Outputs:
        """Advance from t to t + h with the inputs held; returns the outputs at t + h."""
        if self.steady is not None:
            out = self.steady.step(t, h, inputs)
            self.t = self.steady.t
            return out
        m = self.model
        if m is None:
            raise StepRejected("step before initialize")
        if not (math.isfinite(h) and h > 0.0):
            raise StepRejected(f"communication step h = {h!r} is invalid; allowed: h > 0")
        if abs(t - self.t) > 1e-9 * max(1.0, abs(t)):
            raise StepRejected(f"step starts at t = {t!r} but the bearing is at t = {self.t!r}")
        u = self._validated(inputs)
        sv = self._save()
        try:
            if self._applied is not u:
                m.set_inputs(loads=(u["Fx"], u["Fy"], u["Fz"], u["Mx"], u["My"]),
                             displacement=None if self.p.coupling != "displacement" else
                             [u[k] for k in ("dx", "dy", "dz", "tx", "ty", "vx", "vy", "vz", "wx", "wy")])
                # input held over the step: the speed takes its new value at the start of the step
                m.set_speed(u["shaft_speed"], u["outer_ring_speed"])
                self._applied = u
            # (held inputs: the model still holds them; advance continues the held speed from its last end)
            m.advance(t + h, record_dt=max(h, 1e-6))
            if m.thermal_runaway:
                # a temperature past the oil's limit: flagged and the step discarded (never reported as OK)
                from ..heat.thermal import ThermalRunaway
                self.thermal_runaway = True
                th = m.thermal
                raise StepRejected(str(ThermalRunaway(th.temperatures(), th.T_max, th.oil.name,
                                                      f"at t = {t + h:.6g} s")))
            self.t = m.t
            self._update_outputs(sv["quad"], m.t - t)
            self._check_limits()
        except (BearingInputError, FloatingPointError, StepRejected) as e:
            np.copyto(m.y, sv["y"])
            np.copyto(m.U, sv["U"])
            np.copyto(m.stats, sv["stats"])
            np.copyto(m.quad, sv["quad"])
            m.t = sv["t"]
            self._applied = None
            m.invalidate_jacobian()      # the failed step's W is not carried into the next attempt
            m.set_thermal_state(sv["thermal"])
            self.t = m.t
            # the outputs of the restored point: those before the step (instantaneous values and the
            # averages of the last accepted step), with the runaway flag of now
            np.copyto(self.values, sv["out"])
            self.values[_I_RUNAWAY] = 1.0 if self.thermal_runaway else 0.0
            raise StepRejected(str(e))
        return Outputs(self.values.copy())

    def _update_outputs(self, q0=None, h=0.0):
        """Outputs at the current instant into self.values (one numba call, session_kernels.films_and_outputs).
        Step averages: from the time integrals (model.quad) at the end of the step of length h [s] and q0 at
        its start; q0 None at initialisation, where the instantaneous values stand for them. Raises
        StepRejected, values unchanged, if any output is not finite."""
        m = self.model
        diag, bd = m.evaluate_point()      # from the integration's end point (or one rhs call)
        if self._films is None or self._films.shape[1] != bd.shape[0]:
            self._films = np.zeros((4, bd.shape[0]))
        ext = self._ext
        if m.thermal is not None or not self._ext_isothermal:     # (isothermal: constant, filled once)
            T = m.temperatures()
            ext[0], ext[1], ext[2], ext[3] = T["ball"], T["outer"], T["inner"], T["oil"]
            ext[4], ext[5] = T["heat_to_ambient"], T["heat_to_oil_flow"]
            self._ext_isothermal = m.thermal is None
        ext[6] = 1.0 if self.thermal_runaway else 0.0
        ext[7] = m.oil_fraction_used()
        # the tangent stiffness of the contact state at this instant, balls held (models.tangent_stiffness: five
        # right-hand-side calls, at communication points only)
        try:
            ext[SK.EXT_STIFFNESS:] = self._tangent(m, diag).ravel()
        except FloatingPointError as e:
            raise StepRejected(str(e))
        if self.p.fixed_tilt and self.p.coupling == "load":
            # the ring held square: the tilts are no degrees of freedom, their rows and columns 0 (as at the
            # quasi-static level), so that the compliance over the free coordinates is the translational one
            kt = ext[SK.EXT_STIFFNESS:].reshape(5, 5)
            kt[3:, :] = 0.0
            kt[:, 3:] = 0.0
        if q0 is None:
            q1 = q0 = diag
            h = 0.0
        else:
            q1 = m.quad
        # films and outputs in one kernel call (output_map.point_outputs, inlined: the Python here runs on caches
        # the integration has evicted)
        g = m.g
        ok = SK.films_and_outputs(bd, g.D, g.dm, g.fi, g.fo, *m.film_parameters(), self._films, diag, q1, q0, h,
                                  ext, OUT_CH, CSR_MIN_SPEED, SKID_TOL, SKID_MIN_SPEED, OUT_PTR, OUT_IDX,
                                  self._x, self._new)
        if not ok:
            bad = [n for n, v in zip(ALL_OUTPUT_NAMES, self._new) if not math.isfinite(v)]
            raise StepRejected(f"non-finite outputs {bad} (solver failure)")
        self._life_outputs(bd, diag, h)
        np.copyto(self.values, self._new)

    def _life_outputs(self, bd, diag, h):
        """life_L10r_h and fatigue_damage into self._new at the end of a step of h [s] (0: initialisation, the
        damage starts at 0): the ISO/TS 16281 reference rating life of the per-ball contact loads and operating
        angles bd at this instant (models.life.rating_life_hours_details_nb, inner ring rotating, at the relative
        ring speed), and the damage of the step with the life at its end, D += h / L10r_h
        (models.life.damage_increment_nb). An infinite life (no loaded ball, standstill) is reported as
        LIFE_CAP_H and adds no damage. Once per communication point, never inside the integration."""
        g = self.model.g
        lp = self._life_par
        if lp is None or lp[0] is not g:
            lp = self._life_par = (g, LF.life_parameters(g, "inner"))
        rpm = (diag[_CH_SHAFT] - diag[_CH_OUTER]) * (30.0 / math.pi)
        L = LF.rating_life_hours_details_nb(bd, lp[1], rpm)
        self._new[_I_LIFE] = L if L < LIFE_CAP_H else LIFE_CAP_H
        self._new[_I_DAMAGE] = (self.values[_I_DAMAGE] + LF.damage_increment_nb(h, L)) if h > 0.0 else 0.0

    def _check_limits(self):
        p = float(self.values[_I_PMAX])
        if p > P_LIMIT:
            raise StepRejected(f"maximum contact pressure {p / 1e9:.2f} GPa exceeds the {P_LIMIT / 1e9:.1f} GPa "
                               "static limit of ball bearings (ISO 76): the loads are beyond what the bearing carries")

    # ---- state for rollback (FMI get/set FMU state) --------------------------------------------
    def get_state(self):
        if self.steady is not None:
            return ("steady", self.steady.get_state())
        m = self.model
        return None if m is None else (m.y.copy(), m.t, m.U.copy(), m.stats.copy(), self.values.copy(),
                                       m.thermal_state(), m.quad.copy(), m.integrator_state())

    def set_state(self, state):
        if state is None:
            return
        if self.steady is not None:
            self.steady.set_state(state[1])
            self.t = self.steady.t
            return
        y, t, U, stats, outs, th, quad, ws = state
        self.model.set_thermal_state(th)
        self.model.quad[:] = quad
        self.model.y[:] = y
        self.model.t = t
        self.model.U[:] = U
        self.model.stats[:] = stats
        self.model.update_operating_geometry()     # running geometry of the restored speed and temperatures
        self.model.set_integrator_state(ws)
        self.t = t
        self._applied = None           # the restored U holds the inputs of the restored point
        self.values[:] = outs
        self.thermal_runaway = bool(self.values[_I_RUNAWAY])
