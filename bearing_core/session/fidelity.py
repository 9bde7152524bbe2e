"""Fidelity levels of the co-simulation session (CoSimParameters.fidelity) other than the full dynamics.

A *steady level* gives the bearing's steady outputs at the held inputs (speed, loads, oil temperature) and the
time constant with which the cage speed follows them; SteadySession turns it into a session with the inputs,
outputs, units and statuses of the dynamic one (bearing_core.session.cosim.CoSimSession delegates to it). A level
is a class constructed from the CoSimParameters (raising BearingInputError for parameters it cannot take) with:

    names                    the names of its steady values: session output names (a missing one holds 0),
                             'cage_speed_eq26' (seed 000 Eq. 26 cage speed [rad/s]) and 'cage_time_constant' [s]
    i_tau                    the index of 'cage_time_constant' in names
    inertia                  the rotating inertia of balls and cage referred to the cage speed [kg m^2]
                             (2 KE / cage speed^2; read after steady_into): the acceleration torque
                             (0: none)
    rotate                   True: the level is read at the radial load hypot(Fx, Fy) along x and the x-y outputs
                             (ROTATED) are turned by the load's direction (an axisymmetric bearing)
    query(u) -> (x, cos, sin)      its query point of the inputs u (dict of INPUT_NAMES, SI), and the radial
                             load's direction; raises BearingInputError naming an input outside its range
    steady_into(x, ss, rate) -> flags    the steady values at x into ss (one per name), the shaft speed changing
                             at rate [rad/s^2] over the step (a level may use it for the cage's lag); flags:
                             FLAG_* bits of where the level is weak (a warning is logged on entry)
    point_text(x), describe()      words for messages

and optionally a one-call step: step_kernel (map_kernels.map_step's signature), its level arguments step_args
and the query point x_fast it fills; SteadySession takes it while the inputs pass and the checked path above
(query, steady_into) otherwise, which names the reason of a refusal.

Levels (FIDELITY_LEVELS, in the order of the FMU's Enumeration after 'dynamic'): 'map', an operating map of the
dynamic model's steady windows built by ``bearing build-map`` and read here (MapLevel); 'quasi-static', the
steady state of the whole bearing with its cage solved at the inputs and followed along them
(QuasiStaticLevel). A steady level is added with one entry in FIDELITY_LEVELS; its class is constructed as
Level(params, geometry, options, check_loads), callables giving the session's BearingGeometry and
DynamicsOptions and running its load checks (a seating axial load, the static capacity).

What a steady level gives (docs/fidelity.md): every step-averaged output is the steady value at the step's
held inputs (its 'instantaneous_' twin the same); the cage speed follows its steady value through a first-order
lag with the level's time constant (the map's: the dynamic model's own relaxation of the cage speed at that
operating point), and the derived ratios and the skid state follow the lagged cage speed; the friction torque
and drive power add the power that changes the kinetic energy of balls and cage as the shaft speed changes
from step to step (map_kernels.steady_level_outputs: a run-up costs the drive more than the steady losses, a
coast-down less; the heat is the losses alone); the per-ball
instantaneous outputs (ball0_*) and the ring acceleration ir_ax hold 0. Temperatures: the isothermal oil
temperature (the thermal network is not run at these levels). SI units: rad/s, N, N m, m, rad, W, Pa, K.
"""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from ..errors import BearingInputError
from .cosim_spec import INPUT_NAMES, INT_OUTPUT_NAMES, LIFE_CAP_H, OUTPUT_NAMES, P_LIMIT, parse_inputs
# map_kernels (numba) is imported where a level is built, so that the names here (FIDELITIES) load without numba
# (the FMU's slave class reads them when it is constructed)

ALL_NAMES = OUTPUT_NAMES + INT_OUTPUT_NAMES
RPM = math.pi / 30.0    # rad/s per rpm

# ---- the operating map's contract (written by bearing_core.maps.build_map) -------------------------------
MAP_AXES = {"speed_rpm": "shaft_speed", "fx_N": "Fx", "fz_N": "Fz", "fy_N": "Fy", "my_Nm": "My",
            "oil_temperature_C": "oil_temperature"}
"""Grid axes a map may have (map name: the session input or parameter it is read at); speed_rpm, fx_N and fz_N
are required; axes in the file's order."""
REQUIRED_AXES = ("speed_rpm", "fx_N", "fz_N")
MAP_FATIGUE_RATE = "fatigue_damage_rate"
"""The map's optional fatigue variable [1/s]: 1 / (3600 L10r_h) of the grid point's steady state (ISO/TS 16281
reference rating life, bearing_core.models.life; 0 where the life is infinite), the Palmgren-Miner damage per second
of running there. At fixed loads it is proportional to the shaft speed (L10r_h = L10r [10^6 rev] 10^6 / (60 n)),
so it is interpolated per unit speed (SPEED_SCALED). A map without it runs with the fatigue outputs 0."""
SPEED_SCALED = ("cage_speed", "cage_speed_eq26", "cage_speed_pure_rolling_outer", "cage_speed_pure_rolling_inner",
                "drive_power", "heat_flux_total", "heat_flux_race_inner", "heat_flux_race_outer", "heat_flux_pocket",
                "heat_flux_land", "heat_flux_drag", "heat_flux_damping", "heat_flux_churn_cage",
                "heat_flux_churn_ring", "heat_flux_race_slide", "heat_flux_race_spin", "heat_flux_race_diffslip",
                MAP_FATIGUE_RATE)
"""Map outputs interpolated per unit speed (value / speed_rpm): speeds, powers and the fatigue damage rate, nearly
proportional to the shaft speed at a load (power = torque x speed; damage rate = revolutions per second / L10r),
so that the interpolation error comes only from the slowly
varying ratio."""
MAP_OUTPUTS = ("reaction_Fx", "reaction_Fy", "reaction_Fz", "reaction_Mx", "reaction_My", "friction_torque",
               "friction_torque_outer", "ir_x", "ir_y", "ir_z", "ir_tx", "ir_ty", "max_contact_pressure",
               "alpha_i_mean", "alpha_o_mean", "Q_i_max", "Q_o_max", "film_min_inner", "film_min_outer",
               "film_parameter_min") + SPEED_SCALED[:-1] + ("cage_time_constant", "cage_speed_cv", "steady")
"""Variables a map holds (besides its axes): the session outputs of the steady state at each grid point (window
means of the dynamic model), 'cage_speed_eq26' the seed 000 Eq. 26 cage speed [rad/s], 'cage_time_constant' [s]
the relaxation time of the cage speed, 'cage_speed_cv' the cage speed's standard deviation over the last window
relative to its mean, 'steady' 1 if the steadiness criterion was met, else 0. The stiffness variables
(MAP_STIFFNESS) give the stiffness outputs (map_kernels.map_step_stiffness, MapLevel.stiffness_into; a map without them still
runs, its stiffness outputs 0, with a warning); skid_class is for the user and not read here."""
MAP_STIFFNESS = tuple(f"stiffness_{a}{b}" for a in ("x", "y", "z", "tx", "ty") for b in ("x", "y", "z", "tx", "ty"))
"""The map's stiffness variables (bearing_core.maps.build_map: the Jones-Harris 5 x 5 stiffness at the grid point's
speed and loads, K = d(load)/d(pose), rows x, y, z, tx, ty of the load, columns of the pose), row-major in the
order of the outputs stiffness[1,1] .. stiffness[5,5]."""
ROTATED = (("reaction_Fx", "reaction_Fy"), ("reaction_Mx", "reaction_My"), ("ir_x", "ir_y"), ("ir_tx", "ir_ty"))
"""x-y vectors turned with the radial load (maps without fy_N and my_Nm axes: a load (Fx, Fy) is read at the radial
load hypot(Fx, Fy) along x and these outputs are turned by its direction; the bearing is axisymmetric)."""
# validity flags of a grid point (MapLevel.flags): where the map does not hold (docs/fidelity.md)
FLAG_GROSS_SKID = 1
FLAG_CAGE_UNSTEADY = 2
GROSS_SKID_SLIP = 0.3
"""Cage slip ratio 1 - cage speed / pure-rolling cage speed (outer-raceway control) above which a grid point is
marked gross skidding: there the cage speed changes fastest with load and speed and the steady window is
least representative (an engineering threshold, not a published constant)."""
CAGE_CV_UNSTEADY = 0.01
"""Relative standard deviation of the cage speed over the last window above which the cage is counted as not
steady (cage whirl, instability): the window mean then stands for a motion, not a state."""
MAP_PARAMETERS = ("bearing", "traction_model", "lubrication", "friction_coefficient", "cage_friction_coefficient",
                  "lubricant", "oil", "oil_fraction", "churning", "oil_temperature")
"""CoSimParameters a map was built for (its attribute 'parameters'); a session at fidelity 'map' must have the
same values (oil_temperature: unless the map has an oil_temperature_C axis)."""
FIXED_PARAMETERS = {"coupling": "load", "outer_mounting": "fixed", "fixed_tilt": False, "thermal": False,
                    "ring_growth": False, "shaft_interference": 0.0, "housing_interference": 0.0,
                    "free_contact_angle": 0.0, "pocket_clearance": 0.0, "land_clearance": 0.0, "ball_diameter": 0.0,
                    "pitch_diameter": 0.0, "number_of_balls": 0, "inner_groove_conformity": 0.0,
                    "outer_groove_conformity": 0.0, "oil_flow_rate": 0.0, "lubrication_method": "jet",
                    "oil_level": 0.0}
"""Parameters whose value a map level requires: the map is of a load-driven bearing, outer ring fixed, inner
ring free to tilt, isothermal, with the bearing definition's geometry."""


def fixed_parameter_reason(name: str) -> str:
    """Why the map level requires the value FIXED_PARAMETERS[name] (the detail of its refusal; the C map FMU's
    table carries the same words, bearing_cosim.map_table)."""
    if name == "coupling":
        return ("displacement coupling: the map gives the steady state of a load-driven bearing, not the forces of a "
                "prescribed ring pose; use fidelity 'dynamic'")
    if name in ("oil_flow_rate", "lubrication_method", "oil_level"):
        return ("the map's cavity oil content is its oil_fraction parameter, not an oil supply's (whose oil content "
                "follows the speed); use fidelity 'dynamic' for an oil supply")
    return ("the map is of an isothermal bearing with its definition's geometry, outer ring fixed and inner ring "
            "free to tilt")


def read_map(path) -> dict:
    """An operating map from a NetCDF file (scipy.io.netcdf_file: NetCDF3, no xarray): {'axes': [(name,
    values)], 'vars': {name: array (grid shape)}, 'attrs': {name: str}}."""
    from scipy.io import netcdf_file
    p = Path(path)
    if not p.is_file():
        raise BearingInputError("map_file", str(path), "an existing operating-map file (bearing build-map)")
    try:
        f = netcdf_file(str(p), "r", mmap=False)
    except Exception as e:
        raise BearingInputError("map_file", str(path), "a NetCDF3 operating map (bearing build-map)",
                                f"{type(e).__name__}: {e}")
    try:
        attrs = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in f._attributes.items()}
        vars_ = {k: np.array(v.data, dtype=float) for k, v in f.variables.items() if v.data.dtype.kind in "fiu"}
        dims = {k: v.dimensions for k, v in f.variables.items()}
    finally:
        f.close()
    shape_dims = dims.get("cage_speed")
    if shape_dims is None:
        raise BearingInputError("map_file", str(path), "an operating map (bearing build-map)", "no cage_speed variable")
    axes = [(d, vars_[d]) for d in shape_dims]
    return {"axes": axes, "vars": {k: v for k, v in vars_.items() if dims[k] == shape_dims}, "attrs": attrs,
            "path": str(p)}


class MapLevel:
    """The 'map' level: an operating map (bearing build-map) interpolated multilinearly (map_kernels), never
    extrapolated: an input outside the map's grid is refused naming the input and the range."""

    name = "map"
    #: the warning's words for each validity flag
    FLAG_TEXT = {FLAG_GROSS_SKID: f"gross skidding (cage slip ratio > {GROSS_SKID_SLIP:g} at a neighbouring grid point)",
                 FLAG_CAGE_UNSTEADY: "an unsteady cage (cage instability or whirl at a neighbouring grid point)"}

    def __init__(self, params, geometry=None, options=None, check_loads=None):
        path = params.map_file
        if not path:
            raise BearingInputError("map_file", path, "an operating-map file (bearing build-map) for fidelity "
                                    "'map' (the FMU uses the map it embeds when map_file is empty)")
        m = read_map(path)
        self.path = m["path"]
        self.attrs = m["attrs"]
        names = [a for a, _ in m["axes"]]
        for a in names:
            if a not in MAP_AXES:
                raise BearingInputError("map_file", path, "a map over " + ", ".join(MAP_AXES), f"unknown axis {a}")
        for a in REQUIRED_AXES:
            if a not in names:
                raise BearingInputError("map_file", path, "a map with the axes " + ", ".join(REQUIRED_AXES),
                                        f"no {a} axis")
        missing = [v for v in MAP_OUTPUTS if v not in m["vars"]]
        if missing:
            raise BearingInputError("map_file", path, "an operating map with " + ", ".join(MAP_OUTPUTS),
                                    f"missing {', '.join(missing)}")
        self.axis_names = tuple(names)
        self.axes = [np.asarray(v, dtype=float) for _, v in m["axes"]]
        for a, v in zip(names, self.axes):
            if v.size > 1 and not np.all(np.diff(v) > 0):
                raise BearingInputError("map_file", path, "increasing axis values", f"axis {a}: {v.tolist()}")
        self._check_parameters(params)
        # the optional fatigue variable (MAP_FATIGUE_RATE) is read after the required ones; without it the fatigue
        # outputs hold 0 (SteadySession._life_into) and fatigue_missing says so
        has_rate = MAP_FATIGUE_RATE in m["vars"]
        self.names = MAP_OUTPUTS + ((MAP_FATIGUE_RATE,) if has_rate else ())
        self.fatigue_missing = "" if has_rate else (
            f"the operating map {m['path']} has no {MAP_FATIGUE_RATE} variable: the outputs life_L10r_h and "
            "fatigue_damage hold 0 (life unknown); rebuild the map with bearing build-map, which writes it")
        shape = tuple(v.size for v in self.axes)
        npts = int(np.prod(shape))
        vals = np.empty((npts, len(self.names)))
        for k, nm in enumerate(self.names):
            v = np.asarray(m["vars"][nm], dtype=float).reshape(shape)
            if nm in SPEED_SCALED:    # per unit speed [per rpm]
                v = v / self.axes[0].reshape((-1,) + (1,) * (len(shape) - 1))
            vals[:, k] = v.ravel()
        self.values = np.ascontiguousarray(vals)
        self.speed_scaled = np.array([1 if nm in SPEED_SCALED else 0 for nm in self.names], dtype=np.int64)
        # validity flags of the grid points
        cage = m["vars"]["cage_speed"].ravel()
        pure = m["vars"]["cage_speed_pure_rolling_outer"].ravel()
        with np.errstate(divide="ignore", invalid="ignore"):
            slip = np.where(pure > 0, 1.0 - cage / pure, 0.0)
        unsteady = (m["vars"]["steady"].ravel() < 0.5) | (m["vars"]["cage_speed_cv"].ravel() > CAGE_CV_UNSTEADY)
        self.flags = (np.where(slip > GROSS_SKID_SLIP, FLAG_GROSS_SKID, 0)
                      | np.where(unsteady, FLAG_CAGE_UNSTEADY, 0)).astype(np.int64)
        self.axes_flat = np.concatenate(self.axes)
        self.ptr = np.cumsum([0] + [v.size for v in self.axes]).astype(np.int64)
        st = np.ones(len(shape), dtype=np.int64)
        for d in range(len(shape) - 2, -1, -1):
            st[d] = st[d + 1] * shape[d + 1]
        self.strides = st
        self._idx = np.zeros(len(shape), dtype=np.int64)
        self._w = np.zeros(len(shape))
        self._x = np.zeros(len(shape))
        self.rotate = "fy_N" not in names and "my_Nm" not in names
        self.i_tau = MAP_OUTPUTS.index("cage_time_constant")
        # fixed coordinates (the oil temperature parameter) and the input read at each axis
        self._src = []
        for a in names:
            if a == "oil_temperature_C":
                self._src.append(("param", params.oil_temperature - 273.15))
            else:
                self._src.append(("input", MAP_AXES[a]))
        # per axis, as Python numbers (the per-step query): source kind (0 parameter, 1 speed, 2 radial load Fx,
        # 3 input), source, lo, hi, tolerance of the range test (round-off of unit conversions)
        self._q = []
        for a, (kind, src), v in zip(names, self._src, self.axes):
            lo, hi = float(v[0]), float(v[-1])
            k = 0 if kind == "param" else (1 if a == "speed_rpm" else (2 if a == "fx_N" else 3))
            self._q.append((k, src, lo, hi, 1e-9 * max(1.0, abs(lo), abs(hi))))
        T = params.oil_temperature
        if "oil_temperature_C" in names:
            d = names.index("oil_temperature_C")
            lo, hi = self.axes[d][0] + 273.15, self.axes[d][-1] + 273.15
            if not lo - 1e-9 <= T <= hi + 1e-9:
                raise BearingInputError("oil_temperature", T, f"{lo:.6g} K <= value <= {hi:.6g} K (the map's range, "
                                        f"{self.path}; fidelity 'map' never extrapolates)")
        # the rotating inertia of balls and cage [kg m^2] (the acceleration torque): geometric, pure rolling with
        # outer raceway control (within 1.5 % of 2 KE / wc^2 of the quasi-static level's solutions on the 7218B)
        self.inertia = 0.0
        if geometry is not None:
            from ..contact.kinematics import rotating_inertia
            g = geometry()
            self.inertia = float(rotating_inertia(g.Z, g.ball_mass, g.ball_inertia, g.cage.inertia, g.alpha0, g.D,
                                                  g.dm))
        from . import map_kernels as MK
        self._interp = MK.interp_multilinear
        self._interp(self.axes_flat, self.ptr, self.strides, self.values, self.speed_scaled, self.flags,
                     np.array([v[0] for v in self.axes]), self._idx, self._w, np.zeros(len(self.names)))
        # the same query as arrays, for the one-call step (map_kernels.map_step)
        ix = {n: i for i, n in enumerate(INPUT_NAMES)}
        zero_in = [ix[name] for name, axis in (("Fy", "fy_N"), ("Mx", None), ("My", "my_Nm"))
                   if not ((axis is not None and axis in self.axis_names) or (name == "Fy" and self.rotate))]
        self.step_kernel = MK.map_step
        self.x_fast = np.zeros(len(shape))
        self.step_args = (ix["shaft_speed"], ix["Fx"], ix["Fy"], ix["outer_ring_speed"],
                          np.array(zero_in, dtype=np.int64), self.rotate, RPM,
                          np.array([q[0] for q in self._q], dtype=np.int64),
                          np.array([ix[q[1]] if q[0] == 3 else -1 for q in self._q], dtype=np.int64),
                          np.array([float(q[1]) if q[0] == 0 else 0.0 for q in self._q]),
                          np.array([q[2] for q in self._q]), np.array([q[3] for q in self._q]),
                          np.array([q[4] for q in self._q]),
                          self.axes_flat, self.ptr, self.strides, self.values, self.speed_scaled, self.flags,
                          self.x_fast, np.zeros(len(shape), dtype=np.int64), np.zeros(len(shape)))
        self._init_stiffness(m, shape, ix)

    def _init_stiffness(self, m, shape, ix):
        """The stiffness outputs' arrays (map_kernels.map_stiffness): the map's MAP_STIFFNESS variables as
        (n_points x 25); a map without them (built before bearing build-map wrote them) leaves the outputs 0 and
        says so in stiffness_missing (SteadySession logs it as a warning)."""
        from . import map_kernels as MK
        from .cosim_spec import STIFFNESS_NAMES
        from .output_map import OUTPUT_INDEX
        missing = [v for v in MAP_STIFFNESS if v not in m["vars"]]
        self.stiffness_missing = ""
        self.stiffness_into = None
        if missing:
            self.stiffness_missing = (
                f"the operating map {self.path} has no stiffness variables ({', '.join(missing[:3])}, ...): the "
                "outputs stiffness[i,j] hold 0 and fmi2GetDirectionalDerivative is refused; rebuild the map with "
                "bearing build-map, which writes them")
            return
        npts = int(np.prod(shape))
        kv = np.empty((npts, 25))
        for k, nm in enumerate(MAP_STIFFNESS):
            kv[:, k] = np.asarray(m["vars"][nm], dtype=float).reshape(shape).ravel()
        self.kvalues = np.ascontiguousarray(kv)
        i_k = OUTPUT_INDEX[STIFFNESS_NAMES[0]]
        assert all(OUTPUT_INDEX[n] == i_k + k for k, n in enumerate(STIFFNESS_NAMES))
        kbuf = np.zeros(25)
        # the one-call step: map_step and then the stiffness on the cell its interpolation left
        # (map_kernels.map_step_stiffness), its arguments after map_step's level arguments
        self.step_kernel = MK.map_step_stiffness
        self.step_args = self.step_args + (self.kvalues, kbuf, i_k)
        kern = MK.map_stiffness

        def stiffness_into(cs, sn, out):
            """After steady_into (whose interpolation left its cell in self._idx, self._w), the radial load's
            direction (cs, sn): the stiffness into out; False if an entry is not finite."""
            return kern(self.strides, self.kvalues, self._idx, self._w, cs, sn, kbuf, i_k, out)

        self.stiffness_into = stiffness_into

    def _check_parameters(self, p):
        try:
            built = json.loads(self.attrs.get("parameters", "{}"))
        except json.JSONDecodeError:
            built = {}
        for k in MAP_PARAMETERS:
            if k not in built:
                raise BearingInputError("map_file", self.path, "a map with its build parameters",
                                        f"attribute 'parameters' has no {k}")
            if k == "oil_temperature" and "oil_temperature_C" in self.axis_names:
                continue
            v, b = getattr(p, k), built[k]
            if isinstance(b, (int, float)) and not isinstance(b, bool):
                same = isinstance(v, (int, float)) and abs(float(v) - float(b)) <= 1e-9 * max(1.0, abs(float(b)))
            else:
                same = str(v).lower() == str(b).lower() or (k == "lubrication" and v == "auto" and
                                                            b == built.get("lubrication_auto", b))
            if not same:
                raise BearingInputError(k, v, f"{b!r}, the value the operating map {self.path} was built for",
                                        "fidelity 'map' reads the map only for the parameters it was built with")
        for k, want in FIXED_PARAMETERS.items():
            v = getattr(p, k)
            if v != want:
                raise BearingInputError(k, v, f"{want!r} at fidelity 'map'", fixed_parameter_reason(k))

    def ranges(self) -> list:
        """(input, lo, hi, unit) of each axis read from an input, in input units."""
        out = []
        for a, (kind, src), v in zip(self.axis_names, self._src, self.axes):
            if kind != "input":
                continue
            f = RPM if a == "speed_rpm" else 1.0
            out.append((src, v[0] * f, v[-1] * f, {"speed_rpm": "rad/s", "my_Nm": "N.m"}.get(a, "N")))
        return out

    def query(self, u: dict):
        """(x, cos, sin): the map coordinates of the inputs u and the radial-load direction. Raises
        BearingInputError naming the input outside the map's range, or an input the map does not vary."""
        if u["outer_ring_speed"] != 0.0:
            raise BearingInputError("outer_ring_speed", u["outer_ring_speed"], "0 rad/s at fidelity 'map' (the map "
                                    "is of the bearing with the outer ring fixed)")
        cs, sn = 1.0, 0.0
        fx = u["Fx"]
        if self.rotate:
            fr = math.sqrt(u["Fx"] * u["Fx"] + u["Fy"] * u["Fy"])   # as map_kernels.map_step (bit for bit)
            if fr > 0.0:
                cs, sn = u["Fx"] / fr, u["Fy"] / fr
            fx = fr
        for name, axis, unit in (("Fy", "fy_N", "N"), ("Mx", None, "N.m"), ("My", "my_Nm", "N.m")):
            if (axis is not None and axis in self.axis_names) or (name == "Fy" and self.rotate):
                continue
            if u[name] != 0.0:
                raise BearingInputError(name, u[name], f"0 {unit} at fidelity 'map' (the map {self.path} has no "
                                        f"{axis or name} axis)")
        x = self._x
        for d, (kind, src, lo, hi, tol) in enumerate(self._q):
            if kind == 0:
                v = src
            elif kind == 1:
                v = u["shaft_speed"] / RPM
            elif kind == 2:
                v = fx
            else:
                v = u[src]
            if not lo - tol <= v <= hi + tol:
                raise self.range_error(d, v)
            x[d] = lo if v < lo else (hi if v > hi else v)
        return x, cs, sn

    def range_error(self, d, xd) -> BearingInputError:
        a = self.axis_names[d]
        lo, hi = self.axes[d][0], self.axes[d][-1]
        kind, src = self._src[d]
        if a == "speed_rpm":
            return BearingInputError("shaft_speed", xd * RPM, f"{lo * RPM:.6g} rad/s <= value <= {hi * RPM:.6g} rad/s "
                                     f"({lo:.6g}-{hi:.6g} rpm), the range of the operating map {self.path}",
                                     "fidelity 'map' never extrapolates")
        if a == "fx_N" and self.rotate:
            return BearingInputError("radial load hypot(Fx, Fy)", xd, f"{lo:.6g} N <= value <= {hi:.6g} N, the range "
                                     f"of the operating map {self.path}", "fidelity 'map' never extrapolates")
        unit = {"my_Nm": "N.m", "oil_temperature_C": "degC"}.get(a, "N")
        name = src if kind == "input" else "oil_temperature"
        return BearingInputError(name, xd, f"{lo:.6g} {unit} <= value <= {hi:.6g} {unit}, the range of the "
                                 f"operating map {self.path}", "fidelity 'map' never extrapolates")

    def steady_into(self, x, ss, rate: float = 0.0) -> int:
        """Steady values at the map coordinates x into ss (one per name of self.names); returns the validity
        flags of the interpolation cell. Raises BearingInputError if x lies outside the grid."""
        d, fl = self._interp(self.axes_flat, self.ptr, self.strides, self.values, self.speed_scaled, self.flags, x,
                             self._idx, self._w, ss)
        if d >= 0:
            raise self.range_error(d, x[d])
        return fl

    def point_text(self, x) -> str:
        """The map coordinates x in words, e.g. 'speed_rpm 9500, fx_N 1000, fz_N 3000'."""
        return ", ".join(f"{a} {float(v):.5g}" for a, v in zip(self.axis_names, x))

    def describe(self) -> str:
        return f"operating map {self.path} ({self.attrs.get('level', '?')} level, {self.attrs.get('bearing', '?')})"


class QuasiStaticLevel:
    """The 'quasi-static' level: the steady state of the whole bearing, cage included, solved on the dynamics'
    own forces (bearing_core.models.quasistatic_cage; docs/fidelity_quasistatic.md) at the held inputs, and
    followed along them by warm re-solves and first-order updates (QuasiStaticTracker: re-solve where the
    inputs leave a trust region set by the model's sensitivity and the measured error of its linear update).

    Each solution's outputs are evaluated through the dynamic session's own output path (output_map.
    point_outputs on the solution's right-hand-side channels and per-ball details): the same conventions,
    films and film parameter as at 'dynamic'. Between re-solves the outputs the solver differentiates (cage
    speed, torque, drive power, heat by source, reactions, ring pose, mean contact angles, largest loads and
    pressure) follow the linear update; the pure-rolling cage speeds scale with the shaft speed, the race
    losses' slide/spin split and the outer-ring torque with their totals; the films are those of the last
    solution. Load coupling: the loads are inputs; displacement coupling: the ring pose (dx..ty) is, and the
    outputs are the forces of that pose (the velocities vx..wy are not used: a steady level has no damping
    forces). Outer ring fixed, isothermal at oil_temperature. A point where no steady state is found raises
    ConvergenceError naming it (the FMU: fmi2Error with the message)."""

    name = "quasi-static"
    FLAG_TEXT = {FLAG_GROSS_SKID: f"gross skidding (cage slip ratio > {GROSS_SKID_SLIP:g})",
                 FLAG_CAGE_UNSTEADY: "cage instability (the cage centre's small motions about its steady position "
                                     "grow: the cage whirls in its clearance)"}
    rotate = False
    MIN_SPEED = 10.0     # rad/s: the solver's lower bound of the shaft speed (QuasiStaticCageModel.solve)
    #: outputs of the solver's linear update (session name, solver output name)
    PREDICTED = (("cage_speed", "cage_speed"), ("friction_torque", "friction_torque"), ("drive_power", "P_drive"),
                 ("heat_flux_total", "heat"), ("heat_flux_race_inner", "P_race_inner"),
                 ("heat_flux_race_outer", "P_race_outer"), ("heat_flux_pocket", "P_pocket"),
                 ("heat_flux_land", "P_land"), ("heat_flux_drag", "P_drag"), ("heat_flux_churn_cage", "P_churn_cage"),
                 ("heat_flux_churn_ring", "P_churn_ring"), ("reaction_Fx", "Fx"), ("reaction_Fy", "Fy"),
                 ("reaction_Fz", "Fz"), ("reaction_Mx", "Mx"), ("reaction_My", "My"), ("ir_x", "dx"),
                 ("ir_y", "dy"), ("ir_z", "dz"), ("ir_tx", "tx"), ("ir_ty", "ty"), ("alpha_i_mean", "alpha_i_mean"),
                 ("alpha_o_mean", "alpha_o_mean"), ("Q_i_max", "Q_i_max"), ("Q_o_max", "Q_o_max"),
                 ("max_contact_pressure", "p_max"))

    def __init__(self, params, geometry=None, options=None, check_loads=None):
        """params: CoSimParameters; geometry, options: callables giving the session's BearingGeometry and
        DynamicsOptions (CoSimSession._geometry, _options); check_loads(u, geometry): the session's load checks
        (a seating axial load, the static capacity), raising BearingInputError."""
        if params.thermal:
            raise BearingInputError("thermal", params.thermal, "False at fidelity 'quasi-static' (an isothermal "
                                    "steady model at oil_temperature)", "use fidelity 'dynamic' for the thermal network")
        if params.outer_mounting != "fixed":
            raise BearingInputError("outer_mounting", params.outer_mounting, "'fixed' at fidelity 'quasi-static'",
                                    "use fidelity 'dynamic' for an elastic outer-ring mounting")
        if params.oil_fraction == 0.0 and (params.oil_flow_rate > 0.0 or params.lubrication_method in ("bath", "grease")):
            raise BearingInputError("oil_flow_rate" if params.oil_flow_rate > 0.0 else "lubrication_method",
                                    params.oil_flow_rate if params.oil_flow_rate > 0.0 else params.lubrication_method,
                                    "an explicit oil_fraction (> 0) at fidelity 'quasi-static'",
                                    "the steady level takes the cavity oil content as the oil_fraction parameter; "
                                    "use fidelity 'dynamic' for an oil supply")
        if geometry is None or options is None:
            raise BearingInputError("fidelity", self.name, "a level built by CoSimSession (geometry and options)")
        from ..models.quasistatic_cage import OUTPUT_NAMES as QS_NAMES, QuasiStaticCageModel, QuasiStaticTracker
        from ..models import dynamics_kernels as K
        from .output_map import ALL_OUTPUT_NAMES
        from . import session_kernels as SK
        g = geometry()
        opt = options()
        self.geometry = g
        self.model = QuasiStaticCageModel(g, opt)      # refuses four-point and ball-guided bearings, naming them
        self.tracker = QuasiStaticTracker(self.model)
        self.disp = params.coupling == "displacement"
        # a solid- or dry-lubricated cage takes a pure axial load only: under a radial load or a moment its steady
        # equations have no root on the dynamics' branch (the dry cage's impacts carry the loss there; 0 of 32
        # random 7218B points converged), and the roots a solve can reach have the cage pressed on its land (7008,
        # 1000 rpm, Fx 358 N, Fz 716 N, dry: 0.21 N m against the dynamics' 0.0035; docs/fidelity_quasistatic.md)
        self._axial_only = opt.regime != "oil"
        self.T_oil = float(opt.oil_temperature)
        self.bearing = params.bearing
        self._check_loads = check_loads
        held = ("ir_ax",)
        self.names = tuple(n for n in ALL_OUTPUT_NAMES if not (n.startswith("instantaneous_") or
                                                                n.startswith("ball0_") or n in held)) \
            + ("cage_speed_eq26", "cage_time_constant")
        self.i_tau = len(self.names) - 1
        ix = {n: i for i, n in enumerate(self.names)}
        self._pred = np.array([[ix[a], QS_NAMES.index(b)] for a, b in self.PREDICTED], dtype=np.int64)
        self._speed_scaled = np.array([ix[n] for n in ("cage_speed_pure_rolling_outer", "cage_speed_pure_rolling_inner",
                                                       "cage_speed_eq26")], dtype=np.int64)
        self._race_split = np.array([ix[n] for n in ("heat_flux_race_slide", "heat_flux_race_spin",
                                                     "heat_flux_race_diffslip")], dtype=np.int64)
        self._i_race = (ix["heat_flux_race_inner"], ix["heat_flux_race_outer"])
        self._i_torque, self._i_torque_outer = ix["friction_torque"], ix["friction_torque_outer"]
        self._i_all = np.array([ALL_OUTPUT_NAMES.index(n) for n in self.names[:-2]], dtype=np.int64)
        self._i_cage, self._i_pure = ix["cage_speed"], ix["cage_speed_pure_rolling_outer"]
        self._i_pmax = ix["max_contact_pressure"]
        self._ext = np.zeros(SK.N_EXT)
        self._work = np.zeros(2 * K.NOUT + len(SK.EXTRA_NAMES))
        self._i_eq26 = K.OUT_INDEX["pure_rolling_cage_speed"]
        self._full = np.zeros(len(ALL_OUTPUT_NAMES))
        self._ss0 = np.zeros(len(self.names))     # the steady values at the last solution
        self._i_life = ix["life_L10r_h"]
        self._life_par = None                      # models.life.life_parameters of the geometry
        self._out0 = None                          # the solver's outputs there
        self._w0 = 0.0
        self.inertia = 0.0                         # 2 KE / wc^2 of the last solution [kg m^2]
        self._flags0 = 0
        self._last = None                          # (x, ss, flags) of the last query point
        # the one-call step (map_kernels.quasistatic_step) inside the trust region of the last solution: its
        # arrays, updated in place at each solution (_sync_kernel) and where the load checks pass (query)
        from . import map_kernels as MK
        n_out = len(QS_NAMES)
        ix_in = {n: i for i, n in enumerate(INPUT_NAMES)}
        ring_names = ("dx", "dy", "dz", "tx", "ty") if self.disp else ("Fx", "Fy", "Fz", "Mx", "My")
        self._k_ring_ok = np.full(5, np.nan)
        self._k_p0 = np.zeros(7)
        self._k_y0 = np.zeros(n_out)
        self._k_S = np.zeros((n_out, 7))
        self._k_tol = np.full(7, np.inf)
        self._k_sc = np.zeros(13)       # radius, imbalance, its allowed change, shaft speed, tau, p limit, slip, valid,
        #                                 flags of the solution (FLAG_CAGE_UNSTEADY), the shaft's rate at an
        #                                 accelerating solution (0: steady), the tracker's accel_min, accel_max,
        #                                 accel_rel
        self._unstable = 0               # FLAG_CAGE_UNSTEADY where the last solution's cage centre is unstable
        self.cage_growth = float("nan")  # its largest growth rate [1/s] (models.quasistatic_cage.cage_centre_stability)
        self.cage_whirl_frequency = float("nan")   # and its frequency [rad/s]
        self.x_fast = np.zeros(7)
        self.step_kernel = MK.quasistatic_step
        self.step_args = (ix_in["shaft_speed"], ix_in["outer_ring_speed"],
                          np.array([ix_in[n] for n in ring_names], dtype=np.int64), self._k_ring_ok,
                          0 if self.disp else 1, float(self.MIN_SPEED), 2.0e4, self.T_oil,
                          self._k_p0, self._k_y0, self._k_S, self._k_tol, self._k_sc,
                          QS_NAMES.index("P_drive"), QS_NAMES.index("heat"), self._pred, self._ss0,
                          self._speed_scaled, self._race_split, np.array(self._i_race, dtype=np.int64),
                          self._i_torque, self._i_torque_outer, self._i_pmax, self._i_cage, self._i_pure,
                          self.x_fast, np.zeros(n_out))

    def query(self, u: dict):
        """(x, 1, 0): x = (shaft speed, Fx, Fy, Fz, Mx, My or dx, dy, dz, tx, ty, oil temperature) [rad/s, N,
        N m or m, rad, K]. Raises BearingInputError for an input the level cannot take."""
        if u["outer_ring_speed"] != 0.0:
            raise BearingInputError("outer_ring_speed", u["outer_ring_speed"], "0 rad/s at fidelity 'quasi-static' "
                                    "(the steady model's outer ring is fixed)")
        w = u["shaft_speed"]
        if not self.MIN_SPEED <= w <= 2.0e4:
            raise BearingInputError("shaft_speed", w, f"{self.MIN_SPEED:g} rad/s <= value <= 20000 rad/s at fidelity "
                                    "'quasi-static' (a steady state needs a turning shaft; use fidelity 'dynamic' "
                                    "through standstill and reversal)")
        if self._check_loads is not None:
            self._check_loads(u, self.geometry)
        if self.disp:
            ring = [u[k] for k in ("dx", "dy", "dz", "tx", "ty")]
        else:
            ring = [u[k] for k in ("Fx", "Fy", "Fz", "Mx", "My")]
        if self._axial_only:
            for k in (("dx", "dy", "tx", "ty") if self.disp else ("Fx", "Fy", "Mx", "My")):
                if u[k] != 0.0:
                    raise BearingInputError(
                        k, u[k], "0 at fidelity 'quasi-static' with a solid- or dry-lubricated cage (a pure axial "
                        "load)", "its steady state is not found under radial load or moment, where the dry cage's "
                        "impacts carry the loss (docs/fidelity_quasistatic.md); use fidelity 'map' or 'dynamic'")
        self._k_ring_ok[:] = ring          # the load checks passed at these (the one-call step's condition)
        return np.array([w, *ring, self.T_oil]), 1.0, 0.0

    def restart(self):
        """The next point starts the inputs afresh (SteadySession.initialize): solved with its derivatives."""
        self.tracker.restart()
        self._last = None
        self._k_sc[7] = 0.0

    def steady_into(self, x, ss, rate: float = 0.0) -> int:
        """The steady values at x into ss (one per name); returns FLAG_GROSS_SKID where the cage skids grossly.
        Raises ConvergenceError naming the point where no steady state is found."""
        last = self._last
        tr = self.tracker
        if last is not None and np.array_equal(last[0], x) and (tr.res is None or tr.res.acceleration == 0.0):
            # (at an accelerating solution the same inputs end its ramp: the tracker solves the steady state)
            ss[:] = last[1]
            return last[2]
        y, solved = self.tracker.at(x, rate)
        res = self.tracker.res
        if solved:
            self._evaluate_solution(res)
            self._sync_kernel(res)
        ss[:] = self._ss0
        if not solved:
            o0 = self._out0
            for i, k in self._pred:
                ss[i] = self._ss0[i] + (y[k] - o0[k])
            f = x[0] / self._w0
            for i in self._speed_scaled:
                ss[i] = self._ss0[i] * f
            r0 = self._ss0[self._i_race[0]] + self._ss0[self._i_race[1]]
            if r0 > 0.0:
                fr = (ss[self._i_race[0]] + ss[self._i_race[1]]) / r0
                for i in self._race_split:
                    ss[i] = self._ss0[i] * fr
            if self._ss0[self._i_torque] != 0.0:
                ss[self._i_torque_outer] = self._ss0[self._i_torque_outer] * ss[self._i_torque] / self._ss0[self._i_torque]
        if ss[self._i_pmax] > P_LIMIT:
            raise BearingInputError("loads" if not self.disp else "ring pose", self.point_text(x),
                                    f"loads the bearing can carry: maximum contact pressure <= {P_LIMIT / 1e9:.1f} GPa "
                                    "(the static limit of ball bearings, ISO 76)",
                                    f"{ss[self._i_pmax] / 1e9:.2f} GPa in the steady state")
        tau = res.tau_cage
        ss[self.i_tau] = tau if math.isfinite(tau) and tau > 0.0 else 0.0
        pure = ss[self._i_pure]
        fl = FLAG_GROSS_SKID if pure > 0.0 and 1.0 - ss[self._i_cage] / pure > GROSS_SKID_SLIP else 0
        fl |= self._unstable
        self._last = (np.array(x, dtype=float), ss.copy(), fl)
        return fl

    def _evaluate_solution(self, res):
        """The session's outputs at a solution (the dynamic session's output path), kept as the base of the
        linear updates."""
        from .output_map import point_outputs
        from . import session_kernels as SK
        s = self.model.dynamic_setup(res.omega, res.T_oil)
        ext = self._ext
        ext[:] = 0.0
        ext[0:4] = res.T_oil
        ext[7] = s.oil_fraction_used()
        ext[SK.EXT_STIFFNESS:] = self.stiffness(res).ravel()
        films = np.zeros((4, res.bd.shape[0]))
        if not point_outputs(res.bd, self.geometry, s.film_parameters(), res.diag, ext, films, self._work, self._full):
            from ..errors import ConvergenceError
            raise ConvergenceError(f"quasi-static level: non-finite outputs at {self.point_text(res.inputs())}")
        self._ss0[:-2] = self._full[self._i_all]
        self._ss0[-2] = res.diag[self._i_eq26]
        # the fatigue life of the solution (models.life, per-ball loads and operating angles, inner ring rotating),
        # held between re-solves like the other outputs the solver does not differentiate (SteadySession._life_into)
        from ..models import life as LF
        from .cosim_spec import LIFE_CAP_H
        if self._life_par is None:
            self._life_par = LF.life_parameters(self.geometry, "inner")
        L = LF.rating_life_hours_details_nb(res.bd, self._life_par, res.omega * 30.0 / math.pi)
        self._ss0[self._i_life] = L if L < LIFE_CAP_H else LIFE_CAP_H
        self._out0 = res.outputs.copy()
        self._w0 = res.omega
        from ..models import dynamics_kernels as K
        wc = res.cage_speed
        ke = res.diag[K.OUT_INDEX["KE"]]
        self.inertia = 2.0 * ke / (wc * wc) if wc != 0.0 and math.isfinite(ke) else 0.0
        # cage instability: the cage centre's small motions about the solution grow (the level warns there).
        # Tested where the tracker computes the derivatives afresh (a cold solve, and a refresh at least every
        # refresh_every re-solves): it changes slowly with the operating point, and at every re-solve its 8
        # right-hand sides cost 0.008 s per simulated second on seed 000's ramp (AMD EPYC)
        if self.tracker._since_refresh == 0:
            self.cage_growth, self.cage_whirl_frequency = self.model.cage_centre_stability(res)
            self._unstable = FLAG_CAGE_UNSTEADY if self.cage_growth > 0.0 else 0

    def stiffness(self, res) -> np.ndarray:
        """The level's 5 x 5 stiffness K = d(load)/d(pose) = -d(reaction)/d(pose) at the solution res [N/m, N/rad,
        N m/m, N m/rad; rows Fx, Fy, Fz, Mx, My, columns dx, dy, dz, tx, ty]: the derivative of the level's own
        reactions, which between re-solves follow the linear update y0 + S (x - p0) on the solution's sensitivity S
        (models.quasistatic_cage.QuasiStaticCageModel._sensitivity: central secants over warm re-solves of the
        whole bearing, balls and cage re-equilibrated, at +-2e-7 m / +-2e-6 rad of the pose with displacement
        coupling, +-2 % of the load scale with load coupling; Broyden updates along the inputs' path between
        them, QuasiStaticTracker). Displacement coupling: K = -dS[Fx..My]/d(dx..ty). Load coupling: the pose
        follows the loads, C = dS[dx..ty]/d(Fx..My), and K = C^-1 over the pose's free coordinates (with
        fixed_tilt the tilts are held: their rows and columns are 0). Zero without a sensitivity."""
        from ..models.quasistatic_cage import OUTPUT_NAMES as QS_NAMES
        K = np.zeros((5, 5))
        S = getattr(res, "sensitivity", None)
        if S is None:
            return K
        if self.disp:
            i = QS_NAMES.index("Fx")
            K[:] = -S[i:i + 5, 1:6]
            return K
        i = QS_NAMES.index("dx")
        C = S[i:i + 5, 1:6]
        free = [k for k in range(5) if np.any(C[k] != 0.0) and np.any(C[:, k] != 0.0)]
        if free:
            try:
                K[np.ix_(free, free)] = np.linalg.inv(C[np.ix_(free, free)])
            except np.linalg.LinAlgError:
                from ..errors import ConvergenceError
                raise ConvergenceError(f"quasi-static level: singular compliance at {self.point_text(res.inputs())}")
        return K

    def _sync_kernel(self, res):
        """The one-call step's copy of the tracker's state at a new solution."""
        tr = self.tracker
        self._k_p0[:] = res.inputs()
        self._k_y0[:] = res.outputs
        self._k_S[:] = res.sensitivity
        self._k_tol[:] = tr._tol
        self._k_sc[:] = (tr.radius, tr._imb0, tr.balance_rel, self._w0, res.tau_cage, P_LIMIT, GROSS_SKID_SLIP, 1.0,
                         float(self._unstable), res.acceleration * res.omega, tr.accel_min, tr.accel_max, tr.accel_rel)

    def point_text(self, x) -> str:
        x = np.asarray(x, dtype=float)
        if self.disp:
            ring = f"pose dx {x[1]:.4g} m, dy {x[2]:.4g} m, dz {x[3]:.4g} m, tx {x[4]:.4g} rad, ty {x[5]:.4g} rad"
        else:
            ring = f"Fx {x[1]:.5g} N, Fy {x[2]:.5g} N, Fz {x[3]:.5g} N, Mx {x[4]:.4g} N.m, My {x[5]:.4g} N.m"
        return f"shaft speed {x[0] / RPM:.5g} rpm, {ring}, oil {x[6] - 273.15:.4g} degC"

    def describe(self) -> str:
        return f"quasi-static cage model ({self.bearing})"


_INPUT_SET = frozenset(INPUT_NAMES)
_ZEROS = (0.0,) * len(INPUT_NAMES)

FIDELITY_LEVELS = {"map": MapLevel, "quasi-static": QuasiStaticLevel}
"""Steady levels by name (CoSimParameters.fidelity); 'dynamic' is the full model (CoSimSession itself)."""
FIDELITIES = ("dynamic",) + tuple(FIDELITY_LEVELS)


class SteadySession:
    """A co-simulation session on a steady level: the API and output array of CoSimSession (which delegates to
    it). The state is the time, the lagged cage speed and the last step's shaft speed."""

    def __init__(self, params, level, values: np.ndarray, outputs_cls, step_rejected, csr_min_speed: float):
        """values: the session's output array (ALL_NAMES order); outputs_cls, step_rejected: the session's Outputs
        view and StepRejected error (bearing_core.session.cosim, which constructs this); csr_min_speed [rad/s]: below
        it the cage/shaft ratios are 0."""
        from ..models.skid import SKID_MIN_SPEED, SKID_TOL
        from . import map_kernels as MK
        self._outputs_kernel = MK.steady_level_outputs
        OUTPUT_INDEX = {n: i for i, n in enumerate(ALL_NAMES)}
        CSR_MIN_SPEED = csr_min_speed
        self._api = (outputs_cls, step_rejected)
        self.p = params
        self.level = level
        self.values = values           # the session's output array (updated in place)
        self.t = 0.0
        self.wc = 0.0
        self.w_prev = 0.0              # the shaft speed of the last step [rad/s] (the acceleration of balls and cage)
        self.warnings = []             # messages for the FMU log (entry into a region where the level is weak)
        self._flags = 0
        self._ss = np.zeros(len(level.names))
        self._new = np.zeros(len(ALL_NAMES))
        names = level.names
        src = np.full(len(ALL_NAMES), -1, dtype=np.int64)
        for i, n in enumerate(ALL_NAMES):
            base = n[len("instantaneous_"):] if n.startswith("instantaneous_") else n
            if base in names:
                src[i] = names.index(base)
        self._src = src
        self._rot = np.array([[OUTPUT_INDEX[a], OUTPUT_INDEX[b]] for a, b in ROTATED] if level.rotate else
                             np.zeros((0, 2)), dtype=np.int64).reshape(-1, 2)
        ib = [OUTPUT_INDEX[n] for n in ("cage_speed", "cage_shaft_ratio", "cage_shaft_ratio_theory", "skid_ratio",
                                        "cage_slip_ratio", "skid_state")]
        ib += [names.index("cage_speed_eq26"), OUTPUT_INDEX["cage_speed_pure_rolling_outer"]]
        ib += [OUTPUT_INDEX[n] for n in ("temperature_ball", "temperature_outer_ring", "temperature_inner_ring",
                                         "temperature_oil", "heat_to_ambient", "heat_to_oil_flow", "thermal_runaway")]
        ib += [OUTPUT_INDEX[n] for n in ("friction_torque", "instantaneous_friction_torque", "drive_power",
                                         "instantaneous_drive_power")]
        self._ib = np.array(ib, dtype=np.int64)
        T = float(params.oil_temperature)
        self._temps = np.array([T, T, T, T, 0.0, 0.0, 0.0])
        self._consts = (CSR_MIN_SPEED, SKID_TOL, SKID_MIN_SPEED)
        self._in_key = self._in_x = None
        # the cavity oil fraction: the oil_fraction parameter (steady levels take no oil supply)
        self._i_oil = OUTPUT_INDEX.get("oil_fraction_used", -1)
        self._oil = float(params.oil_fraction)
        # a level with a one-call step kernel (query, values, outputs: MapLevel.step_kernel) takes it while its
        # inputs pass; anything refused goes through the checked path, which names the reason
        self._fast = getattr(level, "step_kernel", None)
        # a level whose stiffness outputs are computed apart from its steady values (MapLevel: interpolated and
        # turned by map_kernels.map_stiffness after the step's outputs; its one-call step does the same)
        self._stiff_into = getattr(level, "stiffness_into", None)
        if getattr(level, "stiffness_missing", ""):
            self.warnings.append(level.stiffness_missing)
        self._i_speed = INPUT_NAMES.index("shaft_speed")
        self._res = np.zeros(2)
        # the fatigue outputs (_life_into): from the level's damage rate (MapLevel with MAP_FATIGUE_RATE), or its held
        # life (QuasiStaticLevel: life_L10r_h of its last solution), else they hold 0
        self._i_life, self._i_damage = OUTPUT_INDEX["life_L10r_h"], OUTPUT_INDEX["fatigue_damage"]
        self._i_rate = names.index(MAP_FATIGUE_RATE) if MAP_FATIGUE_RATE in names else -1
        self._map_fatigue = MK.map_fatigue
        self._i_life_ss = names.index("life_L10r_h") if "life_L10r_h" in names else -1
        if getattr(level, "fatigue_missing", ""):
            self.warnings.append(level.fatigue_missing)

    def _life_into(self, h: float):
        """life_L10r_h [h] and fatigue_damage [-] into self._new at the end of a step of h [s] (h = 0: the start,
        damage 0), the damage of the run so far in self.values. Inputs held over the step, so the life is that of
        the step's steady state.
        Map with MAP_FATIGUE_RATE (the interpolated damage rate r [1/s] in the steady values;
        map_kernels.map_fatigue):
            life_L10r_h = min(1 / (3600 r), LIFE_CAP_H) if r > 0 else LIFE_CAP_H
            fatigue_damage = fatigue_damage + r h        if r > 0 (else unchanged)
        Quasi-static level (its last solution's life L [h], capped at LIFE_CAP_H, held between re-solves):
            fatigue_damage = fatigue_damage + h / (3600 L)  if L < LIFE_CAP_H (else unchanged)
        A map without the rate: both hold 0 (life unknown)."""
        new = self._new
        d = self.values[self._i_damage] if h > 0.0 else 0.0
        if self._i_rate >= 0:
            self._map_fatigue(self._ss, self._i_rate, d, h, LIFE_CAP_H, self._i_life, self._i_damage, new)
            return
        if self._i_life_ss >= 0:
            L = self._ss[self._i_life_ss]
            new[self._i_life] = L
            if L < LIFE_CAP_H:
                d = d + h / (3600.0 * L)
        else:
            new[self._i_life] = 0.0
            d = 0.0
        new[self._i_damage] = d

    def _validated(self, inputs: dict):
        """(x, cos, sin, shaft speed) of the inputs; checked again only when they changed (a NaN never compares
        equal). Each input must be a known name and a finite number; the map's ranges bound the rest
        (level.query)."""
        key = self._in_key
        try:
            same = key is not None and key == inputs
        except (TypeError, ValueError):
            same = False
        if same:
            return self._in_x
        u = parse_inputs(inputs)
        x, cs, sn = self.level.query(u)
        self._in_key, self._in_x = dict(inputs), (x.copy(), cs, sn, u["shaft_speed"])
        return self._in_x

    def _step_fast(self, inputs: dict, h: float) -> bool:
        """The step in one kernel call (the level's step_kernel: query, interpolation, outputs and lag) with the
        inputs taken in INPUT_NAMES order; False (nothing changed) if the kernel refuses anything, and the
        checked path (_validated, _evaluate) then names the reason. Same arithmetic as that path."""
        try:
            u = np.fromiter(map(inputs.get, INPUT_NAMES, _ZEROS), np.float64, len(INPUT_NAMES))
        except (TypeError, ValueError):
            return False
        c0, c1, c2 = self._consts
        if self._fast(u, *self.level.step_args, self._ss, self.level.i_tau, self._src, self._rot, self.wc, h,
                      self._temps, self.level.inertia, self.w_prev, c0, c1, c2, self._ib, self._new,
                      self._res) != 0:
            return False
        self._note_flags(int(self._res[1]), self.level.x_fast, h)
        self.w_prev = float(u[self._i_speed])
        if self._i_oil >= 0:
            self._new[self._i_oil] = self._oil
        self._life_into(h)
        self.wc = float(self._res[0])
        np.copyto(self.values, self._new)
        return True

    def _evaluate(self, q, h):
        x, cs, sn, w = q
        rate = (w - self.w_prev) / h if h > 0.0 else 0.0
        fl = self.level.steady_into(x, self._ss, rate)
        tau = float(self._ss[self.level.i_tau])
        c0, c1, c2 = self._consts
        wc = self._outputs_kernel(self._ss, self._src, self._rot, cs, sn, self.wc, h, tau, w, self._temps,
                                  self.level.inertia, self.w_prev if h > 0.0 else w, c0, c1, c2, self._ib, self._new)
        if not math.isfinite(wc):
            bad = [n for n, v in zip(ALL_NAMES, self._new) if not math.isfinite(v)]
            raise BearingInputError("inputs", self.level.point_text(x),
                                    "an operating point where the map has values",
                                    f"{self.level.describe()} has no value for {bad[:4]} there (a failed grid point)")
        if self._stiff_into is not None and not self._stiff_into(cs, sn, self._new):
            raise BearingInputError("inputs", self.level.point_text(x), "an operating point where the map has values",
                                    f"{self.level.describe()} has no finite stiffness there (a failed grid point)")
        self._note_flags(fl, x, h)
        if self._i_oil >= 0:
            self._new[self._i_oil] = self._oil
        self._life_into(h)
        return wc

    def _note_flags(self, fl: int, x, h: float):
        """A warning when the operating point enters a cell with other validity flags (fl != 0)."""
        if fl and fl != self._flags:
            what = []
            texts = getattr(self.level, "FLAG_TEXT", MapLevel.FLAG_TEXT)
            for bit in (FLAG_GROSS_SKID, FLAG_CAGE_UNSTEADY):
                if fl & bit:
                    what.append(texts[bit])
            self.warnings.append(f"t = {self.t + h:.6g} s: the operating point ({self.level.point_text(x)}) entered "
                                 f"a region of {' and '.join(what)}, where fidelity '{self.level.name}' is least "
                                 "accurate (docs/fidelity.md); use fidelity 'dynamic' for this operation")
        self._flags = fl

    def initialize(self, t0: float, inputs: dict):
        restart = getattr(self.level, "restart", None)
        if restart is not None:      # a level that follows its inputs starts afresh
            restart()
        q = self._validated(inputs)
        self.wc = self._evaluate(q, 0.0)
        self.w_prev = q[3]
        np.copyto(self.values, self._new)
        self.t = float(t0)

    def step(self, t: float, h: float, inputs: dict):
        Outputs, StepRejected = self._api
        if not (math.isfinite(h) and h > 0.0):
            raise StepRejected(f"communication step h = {h!r} is invalid; allowed: h > 0")
        if abs(t - self.t) > 1e-9 * max(1.0, abs(t)):
            raise StepRejected(f"step starts at t = {t!r} but the bearing is at t = {self.t!r}")
        if self._fast is not None and _INPUT_SET.issuperset(inputs) and self._step_fast(inputs, h):
            self.t = t + h
            return Outputs(self.values.copy())
        try:
            q = self._validated(inputs)
            wc = self._evaluate(q, h)
        except BearingInputError as e:
            raise StepRejected(str(e))
        self.wc = wc
        self.w_prev = q[3]
        np.copyto(self.values, self._new)
        self.t = t + h
        return Outputs(self.values.copy())

    def get_state(self):
        return (self.t, self.wc, self.w_prev, self.values.copy(), self._flags)

    def set_state(self, state):
        if state is None:
            return
        self.t, self.wc, self.w_prev, v, self._flags = state
        self.values[:] = v
