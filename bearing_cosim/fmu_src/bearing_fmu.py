"""FMI 2.0 co-simulation slave of the angular-contact ball bearing (a pythonfmu Fmi2Slave). It only
translates between FMI variables and bearing_core.session.cosim.CoSimSession; all physics lives in bearing_core.

In the built FMU this file, bearing_core and pythonfmu lie in resources/code/ and run in the model process of
each instance (native/model_process.py), driven by the FMU's own native FMI layer (native/bearing_fmi2.c).
"""
from __future__ import annotations

import math
from xml.etree.ElementTree import Element, SubElement

from pythonfmu import Boolean, Fmi2Causality, Fmi2Slave, Fmi2Variability, Integer, Real, String
from pythonfmu.enums import Fmi2Initial, Fmi2Status
from pythonfmu.default_experiment import DefaultExperiment

from bearing_core.session.cosim_spec import INPUT_NAMES, INPUT_UNITS, INT_OUTPUT_SPEC, OUTPUT_SPEC  # light, no numba

# Start values of the inputs: a loaded bearing at a moderate speed, so that the default experiment
# initialises and runs in every master (7218B: 3000 rpm, Fx 1 kN radial, Fz 3 kN axial; the axial load
# seats the single angular-contact bearing, without it there is no equilibrium).
INPUT_START = {"shaft_speed": 3000.0 * math.pi / 30.0, "Fx": 1000.0, "Fz": 3000.0}

# FMI 2.0 unit definitions: exponents of kg, m, s, rad
_UNITS = {
    "m": dict(m=1), "m/s": dict(m=1, s=-1), "m/s2": dict(m=1, s=-2), "rad": dict(rad=1),
    "rad/s": dict(rad=1, s=-1), "N": dict(kg=1, m=1, s=-2), "N.m": dict(kg=1, m=2, s=-2),
    "W": dict(kg=1, m=2, s=-3), "Pa": dict(kg=1, m=-1, s=-2), "N/m": dict(kg=1, s=-2), "Pa.s": dict(kg=1, m=-1, s=-1),
    "K": dict(K=1), "m3/s": dict(m=3, s=-1),
    "N/rad": dict(kg=1, m=1, s=-2, rad=-1), "N.m/m": dict(kg=1, m=1, s=-2), "N.m/rad": dict(kg=1, m=2, s=-2, rad=-1),
    "1": dict(), "h": dict(s=1, factor=3600),
}
# Modelica unit syntax (FMI 2.0 section 2.2.2) for unit strings written otherwise in the tables
_MODELICA_UNIT = {"m^3/s": "m3/s", "m^3": "m3", "m/s^2": "m/s2"}
# display units (FMI 2.0 DisplayUnit: display = factor * value + offset)
_DISPLAY_UNITS = {"rad/s": (("rpm", 30.0 / math.pi, 0.0),), "K": (("degC", 1.0, -273.15),),
                  "rad": (("deg", 180.0 / math.pi, 0.0),), "m": (("mm", 1e3, 0.0), ("um", 1e6, 0.0)),
                  "Pa": (("MPa", 1e-6, 0.0),)}
_DISPLAY_DEFAULT = {"rad/s": "rpm", "K": "degC", "rad": "deg"}
# FMI quantity of each unit
_QUANTITY = {"m": "Length", "m/s": "Velocity", "m/s2": "Acceleration", "rad": "Angle", "rad/s": "AngularVelocity",
             "N": "Force", "N.m": "Torque", "W": "Power", "Pa": "Pressure", "N/m": "TranslationalSpringConstant",
             "N.m/rad": "RotationalSpringConstant",
             "Pa.s": "DynamicViscosity", "K": "ThermodynamicTemperature", "m3/s": "VolumeFlowRate"}
# typical magnitudes (FMI nominal) of the quantities in this bearing model, for masters' error control
_NOMINAL = {"m": 1e-5, "m/s": 1e-3, "m/s2": 10.0, "rad": 1e-3, "rad/s": 100.0, "N": 1e3, "N.m": 1.0, "W": 100.0,
            "Pa": 1e9, "K": 300.0}

# Choice parameters: every String parameter listed here gets an Enumeration twin (ENUM_NAME, default
# <parameter>_choice) over these items, valued 1..n in this order (SimpleType <parameter>_choices), so that masters
# offer a drop-down and masters that cannot set Strings (fmpy's simulate_ssp) set the choice through fmi2SetInteger.
# The String stays for masters without FMI Enumerations (libcosim) and for free-form values (bearing: catalogue
# designations and bearing files). Precedence: set either; both start at the same item, whichever was changed from
# its start value is used; if both were changed they must name the same item, else the initialisation fails naming
# both. Applies to every parameter of the tables below listed here.
ENUMERATIONS = {
    "bearing": None,   # the bearing presets (bearing_preset_items), resolved when the slave is created
    "traction_model": ("lubricated", "coulomb", "kalker", "lubricated-curve"),
    "coupling": ("load", "displacement"),
    "outer_mounting": ("fixed", "elastic"),
    "integrator": ("auto", "adaptive", "implicit", "rk4"),
    "lubrication": ("auto", "oil", "solid", "dry"),
    "lubrication_method": ("jet", "oil-air", "bath", "grease"),
    "fidelity": None,  # the session's levels (fidelity_items), resolved when the slave is created
}
ENUM_NAME = {"bearing": "bearing_preset"}


def bearing_preset_items() -> tuple:
    """The presets the dynamics model takes: all of them (two-point and four-point-contact bearings)."""
    from bearing_core.bearing.geometry import list_presets
    return tuple(list_presets())


def fidelity_items() -> tuple:
    """The fidelity levels of the session (bearing_core.session.fidelity.FIDELITIES): 'dynamic' first."""
    from bearing_core.session.fidelity import FIDELITIES
    return tuple(FIDELITIES)


EMBEDDED_MAP = "operating_map.nc"
"""File name of the operating map the FMU embeds (bearing build-fmu --map FILE: resources/code/, beside this
module), used at fidelity 'map' when map_file is empty."""


def embedded_map(resources: str | None = None) -> str:
    """Path of the FMU's embedded operating map ('' if it has none): resources/code/operating_map.nc of the
    FMU's resources folder, else beside this module (the model process runs a copy of resources/code/
    without the data files)."""
    import os
    for d in ((os.path.join(resources, "code"),) if resources else ()) + (os.path.dirname(os.path.abspath(__file__)),):
        p = os.path.join(d, EMBEDDED_MAP)
        if os.path.isfile(p):
            return p
    return ""


_ENUM_DESC = {
    "traction_model": ("traction over the contact ellipse with the lubricant's traction curve",
                       "Coulomb friction (friction_coefficient)", "Kalker's FASTSIM (dry rolling contact)"),
    "coupling": ("loads Fx..My are inputs", "the inner-ring pose dx..wy is an input"),
    "outer_mounting": ("outer ring fixed", "outer ring on a radial housing spring (housing_stiffness)"),
    "integrator": ("per 5 ms (or communication step) the cheaper of an adaptive RK4 and implicit", "Dormand-Prince 5(4)", "Rosenbrock-W",
                   "fixed-step RK4 (1e-5 s)"),
    "fidelity": ("the full tribo-dynamic model", "operating map of steady outputs (map_file or the embedded map) with "
                 "a first-order lag of the cage speed", "steady state of the whole bearing with its cage, solved at "
                 "the inputs and followed along them, with a first-order lag of the cage speed"),
}
# Geometry of the bearing as parameters (0: keep the value of the bearing definition); applied by
# bearing_core.session.cosim over the loaded bearing. name, type, unit, description, (min, max)
_GEOMETRY_PARAMS = (
    ("ball_diameter", float, "m", "ball diameter D (0: from the bearing definition)", (0.0, 0.2)),
    ("pitch_diameter", float, "m", "pitch diameter dm (0: from the bearing definition)", (0.0, 2.0)),
    ("number_of_balls", int, None, "number of balls Z (0: from the bearing definition)", (0, 200)),
    ("inner_groove_conformity", float, "1", "inner groove radius / D, fi (0: from the bearing definition)", (0.0, 1.0)),
    ("outer_groove_conformity", float, "1", "outer groove radius / D, fo (0: from the bearing definition)", (0.0, 1.0)),
)
_INPUT_DESC = {
    "shaft_speed": "inner-ring (shaft) speed, held over a step", "Fx": "load on the inner ring, x",
    "Fy": "load on the inner ring, y", "Fz": "load on the inner ring, z (axial)", "Mx": "moment on the inner ring about x",
    "My": "moment on the inner ring about y", "dx": "displacement-driven: inner-ring x", "dy": "displacement-driven: inner-ring y",
    "dz": "displacement-driven: inner-ring z", "tx": "displacement-driven: tilt about x", "ty": "displacement-driven: tilt about y",
    "vx": "displacement-driven: dx/dt", "vy": "displacement-driven: dy/dt", "vz": "displacement-driven: dz/dt",
    "wx": "displacement-driven: d(tx)/dt", "wy": "displacement-driven: d(ty)/dt",
    "outer_ring_speed": "outer-ring speed about the bearing axis, signed, held over a step",
}
_PARAMS = (
    # name, type, start, unit, description, (min, max)
    ("bearing", str, "7218B", None, "bearing preset name (bearing presets: 7218B, 7008-ma2023, 7008-rivera2021, wan-105, QJ1044)", None),
    ("traction_model", str, "lubricated", None, "ball-race traction: lubricated | coulomb | kalker (FASTSIM)", None),
    ("friction_coefficient", float, 0.1, "1", "Coulomb friction coefficient of the ball-race contacts", (0.0, 1.0)),
    ("cage_friction_coefficient", float, 0.1, "1", "ball-pocket and cage-land friction coefficient", (0.0, 1.0)),
    ("lubricant", str, "generic-mineral-oil", None, "lubricant of the traction curve", None),
    ("coupling", str, "load", None, "load (loads are inputs) | displacement (ring pose is an input)", None),
    ("outer_mounting", str, "fixed", None, "outer ring: fixed | elastic (housing spring)", None),
    ("housing_stiffness", float, 1e8, "N/m", "radial housing stiffness for outer_mounting = elastic", (1e4, 1e12)),
    ("fixed_tilt", bool, False, None, "inner ring cannot tilt (shaft held by other bearings)", None),
    ("integrator", str, "auto", None, "auto (per 5 ms or communication step, the cheaper of an adaptive RK4(3) and implicit) | adaptive (Dormand-Prince 5(4)) | implicit (Rosenbrock-W) | rk4 (fixed 1e-5 s)", None),
    ("integrator_tolerance", float, 1e-4, "1", "relative tolerance of the adaptive integrator", (1e-10, 1e-2)),
    ("free_contact_angle", float, 0.0, "rad", "override of the preset's free contact angle (0: preset)", (0.0, 1.0472)),
    ("pocket_clearance", float, 0.0, "m", "override of the diametral ball-pocket clearance (0: preset)", (0.0, 0.01)),
    ("land_clearance", float, 0.0, "m", "override of the diametral cage-land clearance (0: preset)", (0.0, 0.01)),
    ("oil", str, "", None, "oil of the viscosity data (bearing_core.lubrication.lubricants; empty: the traction curve's oil)", None),
    ("oil_fraction", float, 0.0, "1", "oil volume fraction of the oil-air mixture (ball drag, churning)", (0.0, 1.0)),
    ("churning", bool, False, None, "oil churning torques on cage and inner ring (seed 001 Eqs. 12-17)", None),
    ("oil_temperature", float, 313.15, "K", "oil temperature when thermal is off", (233.15, 473.15)),
    ("thermal", bool, False, None, "thermal network (seed 001 Eqs. 21-29) fed by the losses of every step", None),
    ("ambient_temperature", float, 308.15, "K", "ambient air temperature and initial temperature", (233.15, 473.15)),
    ("oil_inlet_temperature", float, 0.0, "K", "oil supply temperature (0: ambient)", (0.0, 473.15)),
    ("oil_flow_rate", float, 0.0, "m^3/s", "circulating oil flow through the bearing", (0.0, 0.1)),
    ("lubrication_method", str, "jet", None, "oil supply: jet | oil-air | bath | grease; with oil_fraction 0 the "
     "cavity oil content follows from it (jet / oil-air: Parker's correlation of flow, speed and pitch diameter; "
     "bath: oil_level; grease: none) when oil_flow_rate > 0 or the method is bath / grease", None),
    ("oil_level", float, 0.0, "m", "bath: static oil level above the lowest point of the outer raceway", (0.0, 10.0)),
    ("thermal_time_scale", float, 1.0, "1", "thermal seconds per simulated second (> 1 fast-forwards heating)", (1e-3, 1e6)),
    ("lubrication", str, "auto", None, "lubrication regime of races and cage: oil (lubricated traction, oil-lubricated "
     "pocket and land) | solid (Kalker/Coulomb traction with friction_coefficient, dry cage) | dry (Coulomb "
     "everywhere) | auto (oil for traction_model lubricated, else solid)", None),
    # fits and ring growth (bearing_core.bearing.ring_fits): the running contact geometry
    ("ring_growth", bool, False, None, "rings and balls grow with speed (centrifugal growth of the inner ring) and "
     "temperature (thermal network, or oil_temperature with thermal off); the contact geometry follows every step", None),
    ("shaft_interference", float, 0.0, "m", "diametral interference of the inner ring on the steel shaft, > 0 tight "
     "(0: none; needs the bore and outside diameter)", (-1e-3, 1e-3)),
    ("housing_interference", float, 0.0, "m", "diametral interference of the outer ring in the thick steel housing, "
     "> 0 tight (0: none)", (-1e-3, 1e-3)),
    ("shaft_bore", float, 0.0, "m", "bore of a hollow shaft for the shaft fit (0: solid shaft)", (0.0, 2.0)),
    ("bore_diameter", float, 0.0, "m", "bearing bore d for fits and ring growth (0: from the bearing definition)",
     (0.0, 2.0)),
    ("outside_diameter", float, 0.0, "m", "bearing outside diameter for fits and ring growth (0: from the bearing "
     "definition)", (0.0, 3.0)),
    # fidelity level (docs/fidelity.md)
    ("fidelity", str, "dynamic", None, "model fidelity: dynamic (the full tribo-dynamic model) | map (operating map "
     "of steady outputs from bearing build-map, interpolated, with a first-order lag of the cage speed; real-time "
     "capable) | quasi-static (the steady state of the whole bearing with its cage, solved at the inputs, any "
     "bearing file, load or displacement coupling, shaft speed >= 10 rad/s); same inputs and outputs, per-ball "
     "outputs ball0_* and ir_ax hold 0 at the steady levels", None),
    ("map_file", str, "", None, "operating map (NetCDF from bearing build-map) for fidelity map; empty: the map "
     "embedded in the FMU (bearing build-fmu --map FILE)", None),
)


class BearingFMU(Fmi2Slave):
    author = "bearing-tribodynamics"
    description = ("Angular-contact ball bearing tribo-dynamic model (Gupta-style dynamics, Hertz contact, "
                   "traction over the contact ellipse, skidding, cage dynamics)")
    default_experiment = DefaultExperiment(start_time=0.0, stop_time=1.0, step_size=1e-3)
    log_categories = {
        "logError": "the reason of every fmi2Error (refused calls, failed initialisation, failed steps)",
        "logDiscard": "the reason of every rejected step (fmi2Discard)",
        "logWarning": "warnings",
        "logInfo": "information (only with logging on)",
    }

    def __init__(self, **kwargs):
        super().__init__(**kwargs)   # light: no numba import here (the builder instantiates this class)
        self._session = None
        self._units = {}
        self._ranges = {}
        self._enums = {}      # Enumeration name -> (String parameter, items); FMI values 1..n
        self._choice = {}     # String parameter -> item selected through its Enumeration
        self._start = {}
        for name, typ, start, unit, desc, rng in _PARAMS:
            setattr(self, name, start)
            self._start[name] = start
            cls = {str: String, float: Real, bool: Boolean}[typ]
            self.register_variable(cls(name, causality=Fmi2Causality.parameter, variability=Fmi2Variability.fixed,
                                       initial=Fmi2Initial.exact, description=desc))
            if unit:
                self._units[name] = _MODELICA_UNIT.get(unit, unit)
            if rng:
                self._ranges[name] = rng
        for name, typ, start, unit, desc, rng in _PARAMS:
            if name in ENUMERATIONS:
                items = ENUMERATIONS[name] if ENUMERATIONS[name] is not None else (
                    fidelity_items() if name == "fidelity" else bearing_preset_items())
                self._register_enum(name, items, desc)
        for name, typ, unit, desc, rng in _GEOMETRY_PARAMS:
            setattr(self, name, typ(0))
            cls = {float: Real, int: Integer}[typ]
            self.register_variable(cls(name, causality=Fmi2Causality.parameter, variability=Fmi2Variability.fixed,
                                       initial=Fmi2Initial.exact, description=desc))
            if unit:
                self._units[name] = unit
            self._ranges[name] = rng
        # the inputs live in one dict, handed to the session as it is at every step (no per-step rebuild; the
        # session compares it with its own copy of the last inputs)
        self._in = {name: float(INPUT_START.get(name, 0.0)) for name in INPUT_NAMES}
        for name, unit in zip(INPUT_NAMES, INPUT_UNITS):
            self.register_variable(Real(name, causality=Fmi2Causality.input, variability=Fmi2Variability.continuous,
                                        description=_INPUT_DESC[name], getter=lambda n=name: self._in[n],
                                        setter=lambda v, n=name: self._in.__setitem__(n, v)))
            self._units[name] = unit
        self._ranges["shaft_speed"] = self._ranges["outer_ring_speed"] = (-2.0e4, 2.0e4)
        # outputs: read from the session's output array (bearing_core.session.cosim.CoSimSession.values, in the order
        # of OUTPUT_SPEC then INT_OUTPUT_SPEC), which the session updates in place at every communication point
        self._out = [0.0] * (len(OUTPUT_SPEC) + len(INT_OUTPUT_SPEC))
        for i, (name, unit, desc) in enumerate(OUTPUT_SPEC):
            self.register_variable(Real(name, causality=Fmi2Causality.output, variability=Fmi2Variability.continuous,
                                        initial=Fmi2Initial.calculated, description=desc,
                                        getter=lambda i=i: float(self._out[i])))
            self._units[name] = _MODELICA_UNIT.get(unit, unit)
        for i, (name, unit, desc) in enumerate(INT_OUTPUT_SPEC, start=len(OUTPUT_SPEC)):
            self.register_variable(Integer(name, causality=Fmi2Causality.output,
                                           variability=Fmi2Variability.discrete, initial=Fmi2Initial.calculated,
                                           description=desc, getter=lambda i=i: int(self._out[i])))

    def _register_enum(self, param, items, desc):
        """The Enumeration twin of the String parameter ``param`` (fmi2Set/GetInteger: item value)."""
        items = tuple(items)
        ename = ENUM_NAME.get(param, f"{param}_choice")
        if self._start[param] not in items:
            raise ValueError(f"start value {self._start[param]!r} of {param} is not one of its items {items}")
        self._enums[ename] = (param, items)
        self._choice[param] = self._start[param]

        def setter(v):
            v = int(v)
            if not 1 <= v <= len(items):
                raise ValueError(f"{ename} = {v} is not an item value; allowed: "
                                 + ", ".join(f"{i + 1} ({it})" for i, it in enumerate(items)))
            self._choice[param] = items[v - 1]

        self.register_variable(Integer(ename, causality=Fmi2Causality.parameter, variability=Fmi2Variability.fixed,
                                       initial=Fmi2Initial.exact, getter=lambda: items.index(self._choice[param]) + 1,
                                       setter=setter,
                                       description=f"{desc} (Enumeration of the String parameter {param}: set either; "
                                                   "if both are changed they must agree)"))

    def _resolve_choices(self):
        """Each choice from its String or its Enumeration, whichever was changed (both: they must agree)."""
        from bearing_core.errors import BearingInputError
        for ename, (param, items) in self._enums.items():
            s, e, start = getattr(self, param), self._choice[param], self._start[param]
            if e != start:
                if s != start and str(s).lower() != e.lower():
                    raise BearingInputError(ename, e, f"the value of {param} ({s!r}) or {param}'s start value "
                                            f"({start!r})", f"{param} = {s!r} and {ename} = {e!r} both set a "
                                            "different choice; set only one")
                setattr(self, param, e)

    # ---- model description: units, ranges and InitialUnknowns (plain pythonfmu writes neither) ----
    def to_xml(self, model_options=dict()) -> Element:
        root = super().to_xml(model_options)
        children = list(root)
        pos = next(i for i, c in enumerate(children) if c.tag == "CoSimulation") + 1
        units = Element("UnitDefinitions")
        for u in sorted(set(self._units.values())):
            ue = SubElement(units, "Unit", name=u)
            SubElement(ue, "BaseUnit", {k: str(v) for k, v in _UNITS[u].items()})
            for du, factor, offset in _DISPLAY_UNITS.get(u, ()):
                SubElement(ue, "DisplayUnit", {"name": du, "factor": repr(factor), **({"offset": repr(offset)}
                                                                                    if offset else {})})
        root.insert(pos, units)
        types = Element("TypeDefinitions")
        for name, (param, items) in self._enums.items():
            st = SubElement(types, "SimpleType", name=f"{param}_choices")
            en = SubElement(st, "Enumeration")
            descs = _ENUM_DESC.get(param, ())
            for i, it in enumerate(items):
                SubElement(en, "Item", {"name": it, "value": str(i + 1),
                                        **({"description": descs[i]} if i < len(descs) else {})})
        if len(types):
            root.insert(pos + 1, types)
        for sv in root.find("ModelVariables"):
            name = sv.get("name")
            real = sv.find("Real")
            if real is not None:
                u = self._units.get(name)
                if u:
                    real.set("unit", u)
                    if u in _QUANTITY:
                        real.set("quantity", _QUANTITY[u])
                    if u in _DISPLAY_DEFAULT:
                        real.set("displayUnit", _DISPLAY_DEFAULT[u])
                    if u in _NOMINAL and sv.get("variability") == "continuous":
                        real.set("nominal", repr(_NOMINAL[u]))
                if name in self._ranges:
                    real.set("min", repr(float(self._ranges[name][0])))
                    real.set("max", repr(float(self._ranges[name][1])))
            integer = sv.find("Integer")
            if integer is not None and name in self._enums:
                integer.tag = "Enumeration"
                integer.set("declaredType", f"{self._enums[name][0]}_choices")
            elif integer is not None and name in self._ranges:
                integer.set("min", str(int(self._ranges[name][0])))
                integer.set("max", str(int(self._ranges[name][1])))
        ms = root.find("ModelStructure")
        outs = ms.find("Outputs")
        # fmi2GetDirectionalDerivative (native/bearing_fmi2.c, from the stiffness outputs; docs/fmu.md): the reactions
        # and the ring pose depend on the ring inputs, the pose dx..ty (coupling displacement: d reaction / d pose =
        # -stiffness) and the loads Fx..My (coupling load: d pose / d load = stiffness^-1), as FMI 2.0 requires of
        # the pairs a directional derivative covers; every other output is a function of the state at the
        # communication point (no dependency)
        root.find("CoSimulation").set("providesDirectionalDerivative", "true")
        index = {sv.get("name"): str(i + 1) for i, sv in enumerate(root.find("ModelVariables"))}
        ring_inputs = " ".join(index[n] for n in ("Fx", "Fy", "Fz", "Mx", "My", "dx", "dy", "dz", "tx", "ty"))
        ring_outputs = {index[n] for n in ("reaction_Fx", "reaction_Fy", "reaction_Fz", "reaction_Mx", "reaction_My",
                                           "ir_x", "ir_y", "ir_z", "ir_tx", "ir_ty")}
        if outs is not None:
            for u in outs:
                u.set("dependencies", ring_inputs if u.get("index") in ring_outputs else "")
            init = SubElement(ms, "InitialUnknowns")
            for u in outs:
                SubElement(init, "Unknown", index=u.get("index"))
        return root

    # ---- FMI calls -----------------------------------------------------------------------------
    def _inputs(self):
        return self._in

    def exit_initialization_mode(self):
        from bearing_core.session.cosim import CoSimParameters, CoSimSession
        self._resolve_choices()
        params = CoSimParameters(**{name: getattr(self, name) for name, *_ in _PARAMS + _GEOMETRY_PARAMS})
        if params.fidelity == "map" and not params.map_file:
            params.map_file = embedded_map(self.resources)
            if not params.map_file:
                from bearing_core.errors import BearingInputError
                raise BearingInputError("map_file", "", "an operating-map file (bearing build-map) for fidelity "
                                        "'map'", "this FMU embeds no map (bearing build-fmu --map FILE)")
        self._session = None
        session = CoSimSession(params)
        session.initialize(self._t0, self._inputs())   # raises with the reason (BearingInputError ...)
        self._session = session
        self._publish()
        self._log_warnings()

    def _log_warnings(self):
        """The session's warnings (a steady level entering a region where it is weak) into the FMU log."""
        w = self._session.warnings if self._session is not None else None
        while w:
            self.log(w.pop(0), Fmi2Status.warning)

    def setup_experiment(self, start_time, stop_time=None, tolerance=None):
        self._t0 = float(start_time)

    _t0 = 0.0

    def _publish(self):
        self._out = self._session.values

    def do_step(self, current_time, step_size):
        if self._session is None:
            self.log("do_step without a successful initialisation", Fmi2Status.error)
            return False
        try:
            self._session.step(current_time, step_size, self._inputs())
        except Exception as e:  # never let an exception reach the host (it would be fmi2Fatal)
            from bearing_core.session.cosim import StepRejected     # here, not per step
            if isinstance(e, StepRejected):
                self.log(f"step at t = {current_time:.9g} s rejected: {e}", Fmi2Status.discard)
                self._publish()          # flags such as thermal_runaway are visible after the discarded step
            else:
                self.log(f"step at t = {current_time:.9g} s failed: {type(e).__name__}: {e}", Fmi2Status.error)
            return False
        self._publish()
        if self._session.warnings:
            self._log_warnings()
        return True

    def terminate(self):
        self._session = None

    # ---- FMU state (rollback for iterative masters) ----------------------------------------------
    def _get_fmu_state(self):
        # the variables that can be set (parameters, inputs); the outputs come back with the session state
        state = {v.name: v.getter() for v in self.vars.values() if v.causality != Fmi2Causality.output}
        state["_session_state"] = None if self._session is None else self._session.get_state()
        return state

    def _set_fmu_state(self, state):
        st = dict(state)
        sess = st.pop("_session_state", None)
        super()._set_fmu_state(st)
        if self._session is not None and sess is not None:
            self._session.set_state(sess)
            self._publish()
