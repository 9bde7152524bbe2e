"""Operating maps: sweeps of the bearing models over speed, loads, preload, oil, friction, clearances and
bearing, evaluated in parallel on Dask (a local cluster of processes by default, or any ``distributed``
scheduler), with a content-addressed cache of finished points, skid maps and the minimum-preload curve.

A *point* is a dict of sweep variables (VARIABLES; names carry their units). A sweep is a grid (the
Cartesian product of value lists, dims in the order given) or a list of points (a CSV file whose columns
are variable names), plus fixed base values, evaluated by one *model* (EVALUATORS): 'quasistatic'
(Jones-Harris, quasistatic.py), 'tribo' (quasi-static tribological model, quasistatic_tribo.py), 'dynamic'
(DynamicModel at held speed and load until steady, see DynamicWindow), 'profile' (DynamicModel through a
speed profile), or a plug-in 'module:function' ('fmu': bearing_cosim.fmu_sweep, the FMU through fmpy).

Skid criterion (seed 000 Sec. 4.2 after its ref. [5]; seed 001 Sec. 1): the cage speed ratio
    S = omega_cage / omega_cage,pr
with omega_cage,pr the pure-rolling cage speed of Harris & Kotzalas (Rolling Bearing Analysis 5th ed.,
Vol. 2 Ch. 3, outer raceway control: tan(beta) = sin(ao) / (cos(ao) + D/dm), omega_m from pure rolling at
both contact centres; kinematics.ball_speeds) evaluated at the model's own contact angles and averaged over
the loaded balls. The bearing *skids* when S < 1 - skid_threshold and *over-skids* when
S > 1 + overskid_threshold; the thresholds (default 0.05 each) are an engineering tolerance chosen by the
user, not a published constant. Minimum preload at a speed: the smallest axial preload (an axial force on
the inner ring added to Fz: constant-force, i.e. spring, preload) at which the bearing does not skid, found
by bisection between a preload that skids and one that does not (min_preload_curve).

Determinism: every point is solved from its own inputs only (no continuation from a neighbouring point, no
random numbers), so its result does not depend on which worker ran it or in which order; results are
ordered by point index. Cache: one JSON file per finished point, named by the SHA-256 of the point's
resolved content (including the content of a bearing file), the model, its options and the code version
(package version + hash of the bearing_core sources and presets). Failed points are not cached (they are
tried again on the next run).

dask, distributed, pandas, xarray and tqdm are imported inside the functions that need them, so that
``import bearing_core`` stays light.
"""
from __future__ import annotations

import csv
import hashlib
import itertools
import json
import math
import threading
import time
import uuid
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import BearingInputError

RPM = math.pi / 30.0  # rad/s per rpm


# ---- sweep variables ------------------------------------------------------------------------------
@dataclass(frozen=True)
class Variable:
    name: str
    kind: str            # 'float' | 'str'
    default: object
    lo: float | None = None
    hi: float | None = None
    doc: str = ""


VARIABLES = {v.name: v for v in (
    Variable("speed_rpm", "float", 0.0, 0.0, 190000.0, "inner-ring speed [rpm] (outer ring fixed)"),
    Variable("fx_N", "float", 0.0, -1e7, 1e7, "radial load on the inner ring, x [N]"),
    Variable("fy_N", "float", 0.0, -1e7, 1e7, "radial load on the inner ring, y [N]"),
    Variable("fz_N", "float", 0.0, -1e7, 1e7, "axial load on the inner ring [N]"),
    Variable("mx_Nm", "float", 0.0, -1e6, 1e6, "moment on the inner ring about x [N m]"),
    Variable("my_Nm", "float", 0.0, -1e6, 1e6, "moment on the inner ring about y [N m]"),
    Variable("preload_N", "float", 0.0, 0.0, 1e7, "axial (constant-force) preload, added to fz_N [N]"),
    Variable("oil", "str", "", doc="oil of the viscosity data (bearing_core.lubrication.lubricants; empty: the traction "
                                   "curve's oil)"),
    Variable("oil_temperature_C", "float", 40.0, -40.0, 200.0, "oil temperature [degC]"),
    Variable("oil_fraction", "float", 0.0, 0.0, 1.0, "oil volume fraction of the oil-air mixture (ball drag) [-]"),
    Variable("traction", "str", "lubricated", doc="ball-race traction: lubricated | coulomb | kalker"),
    Variable("mu", "float", 0.1, 0.0, 1.0, "ball-race friction coefficient (coulomb, kalker) [-]"),
    Variable("mu_cage", "float", 0.1, 0.0, 1.0, "ball-pocket and cage-land friction coefficient [-]"),
    Variable("pocket_clearance_mm", "float", float("nan"), 0.0, 10.0,
             "diametral ball-pocket clearance [mm] (default: the bearing's)"),
    Variable("land_clearance_mm", "float", float("nan"), 0.0, 10.0,
             "diametral cage-land clearance [mm] (default: the bearing's)"),
    Variable("bearing", "str", "7218B", doc="preset name ('bearing presets') or a bearing JSON file"),
)}
LOAD_VARIABLES = ("fx_N", "fy_N", "fz_N", "mx_Nm", "my_Nm", "preload_N")
OPTIONAL_DEFAULTS = ("pocket_clearance_mm", "land_clearance_mm")   # NaN default = the bearing's own value


# ---- code version and hashing -------------------------------------------------------------------
def code_version() -> str:
    """Package version + first 16 hex digits of the SHA-256 of bearing_core's sources and presets."""
    try:
        from importlib.metadata import version
        ver = version("bearing-tribodynamics")
    except Exception:  # not installed (source tree)
        ver = "0+source"
    core = Path(__file__).resolve().parent.parent
    h = hashlib.sha256()
    for f in sorted(list(core.rglob("*.py")) + list(core.rglob("presets/*.json"))):
        h.update(f.relative_to(core).as_posix().encode())
        h.update(f.read_bytes())
    return f"{ver}+{h.hexdigest()[:16]}"


def _canonical(v):
    if isinstance(v, float):
        return "nan" if math.isnan(v) else repr(v)
    if isinstance(v, dict):
        return {k: _canonical(v[k]) for k in sorted(v)}
    if isinstance(v, (list, tuple)):
        return [_canonical(x) for x in v]
    return v


def point_key(point: dict, model: str, options: dict, version: str) -> str:
    """SHA-256 (hex) of the point's content, the model, its options and the code version. A bearing given
    as a file is hashed by content, so editing the file invalidates its points."""
    p = dict(point)
    b = str(p.get("bearing", ""))
    if b.endswith(".json") and Path(b).is_file():
        p["bearing"] = "file:" + hashlib.sha256(Path(b).read_bytes()).hexdigest()
    for k in ("profile", "fmu"):
        f = options.get(k)
        if isinstance(f, str) and Path(f).is_file():
            options = dict(options, **{k: "file:" + hashlib.sha256(Path(f).read_bytes()).hexdigest()})
    blob = json.dumps({"point": _canonical(p), "model": model, "options": _canonical(options),
                       "version": version}, sort_keys=True)
    return hashlib.sha256(blob.encode()).hexdigest()


# ---- sweep specification ------------------------------------------------------------------------
def parse_values(name: str, spec: str) -> list:
    """Values of a grid dimension from text: 'start:stop:num' (num evenly spaced values, both ends
    included) or a comma list 'a,b,c' (numbers, or names for text variables)."""
    var = _variable(name)
    spec = str(spec).strip()
    if var.kind == "str":
        vals = [s.strip() for s in spec.split(",") if s.strip()]
    elif ":" in spec:
        parts = spec.split(":")
        if len(parts) != 3:
            raise BearingInputError(f"grid {name}", spec, "start:stop:num or a comma list a,b,c")
        try:
            a, b, n = float(parts[0]), float(parts[1]), int(parts[2])
        except ValueError:
            raise BearingInputError(f"grid {name}", spec, "start:stop:num with numbers and an integer num")
        if n < 1:
            raise BearingInputError(f"grid {name}", spec, "num >= 1 (an empty range has no points)")
        vals = np.linspace(a, b, n).tolist()
    else:
        try:
            vals = [float(s) for s in spec.split(",") if s.strip()]
        except ValueError:
            raise BearingInputError(f"grid {name}", spec, "numbers a,b,c or start:stop:num")
    if not vals:
        raise BearingInputError(f"grid {name}", spec, "at least one value (an empty range has no points)")
    return vals


def parse_assignment(text: str) -> tuple[str, str]:
    if "=" not in text:
        raise BearingInputError("sweep variable", text, "NAME=VALUE(S), NAME one of " + ", ".join(VARIABLES))
    k, v = text.split("=", 1)
    return k.strip(), v.strip()


def read_points_csv(path) -> list[dict]:
    """A list of points from a CSV file: one column per sweep variable (header = variable names)."""
    p = Path(path)
    if not p.is_file():
        raise BearingInputError("points file", str(path), "an existing CSV file")
    with p.open(newline="") as fh:
        rows = list(csv.DictReader(fh))
    if not rows:
        raise BearingInputError("points file", str(path), "a header and at least one row (no points given)")
    out = []
    for i, r in enumerate(rows):
        pt = {}
        for k, v in r.items():
            if k is None or v is None:
                raise BearingInputError("points file", f"{path} row {i + 2}", "the same number of columns as the header")
            k = k.strip()
            var = _variable(k)
            if var.kind == "str":
                pt[k] = v.strip()
            else:
                try:
                    pt[k] = float(v)
                except ValueError:
                    raise BearingInputError(k, v, "a number", f"{path} row {i + 2}")
        out.append(pt)
    return out


def _variable(name: str) -> Variable:
    if name not in VARIABLES:
        raise BearingInputError("sweep variable", name, "one of " + ", ".join(VARIABLES))
    return VARIABLES[name]


@dataclass
class SweepSpec:
    """A sweep: model name, model options, fixed base values, and either grid (dict variable -> list of
    values, Cartesian product in this order) or points (list of dicts). Call validate() before running."""

    model: str = "quasistatic"
    base: dict = field(default_factory=dict)
    grid: dict = field(default_factory=dict)
    points_list: list | None = None
    options: dict = field(default_factory=dict)

    @property
    def is_grid(self) -> bool:
        return self.points_list is None

    def points(self) -> list[dict]:
        """Fully resolved points (every variable set), in index order."""
        base = {k: v.default for k, v in VARIABLES.items()}
        base.update(self.base)
        if self.is_grid:
            names = list(self.grid)
            combos = itertools.product(*[self.grid[n] for n in names]) if names else [()]
            return [dict(base, **dict(zip(names, c))) for c in combos]
        return [dict(base, **p) for p in self.points_list]

    def varied(self) -> list[str]:
        if self.is_grid:
            return list(self.grid)
        keys = []
        for p in self.points_list:
            keys += [k for k in p if k not in keys]
        return keys

    def validate(self) -> list[dict]:
        """Check everything before any work starts; returns the points. Raises BearingInputError naming the
        variable, the value and the allowed range."""
        ev = get_evaluator(self.model)
        for k in list(self.base) + list(self.grid):
            _variable(k)
        if self.is_grid:
            for k, vals in self.grid.items():
                if len(vals) == 0:
                    raise BearingInputError(f"grid {k}", vals, "at least one value (an empty range has no points)")
        elif len(self.points_list) == 0:
            raise BearingInputError("points", [], "at least one point")
        else:
            for p in self.points_list:
                for k in p:
                    _variable(k)
        pts = self.points()
        n_max = int(self.options.get("max_points", 1_000_000))
        if len(pts) > n_max:
            raise BearingInputError("number of points", len(pts), f"<= {n_max}")
        unused = [k for k in self.varied() if k not in ev.uses]
        if unused:
            raise BearingInputError("sweep variable", unused[0],
                                    f"one that the model '{self.model}' uses: " + ", ".join(ev.uses),
                                    "it would not change the result")
        checked = set()
        for i, p in enumerate(pts):
            for k, v in p.items():
                var = VARIABLES[k]
                key = (k, v if not (isinstance(v, float) and math.isnan(v)) else "nan")
                if key in checked:
                    continue
                checked.add(key)
                _check_value(var, v, i, self.model, ev)
        ev.validate_options(self.options)
        return pts


def _check_value(var: Variable, v, i: int, model: str, ev):
    where = f"point {i}"
    if var.kind == "str":
        if not isinstance(v, str):
            raise BearingInputError(var.name, v, "a name", where)
        if var.name == "bearing":
            _load_bearing(v)      # unknown preset or bad file: error now
        elif var.name == "traction":
            from ..models.dynamics import TRACTION_MODELS
            if v not in TRACTION_MODELS:
                raise BearingInputError("traction", v, " | ".join(TRACTION_MODELS), where)
        elif var.name == "oil" and v:
            from ..lubrication.lubricants import get_oil
            get_oil(v)
        return
    try:
        x = float(v)
    except (TypeError, ValueError):
        raise BearingInputError(var.name, v, "a number", where)
    if math.isnan(x) and var.name in OPTIONAL_DEFAULTS:
        return
    if not math.isfinite(x):
        raise BearingInputError(var.name, v, f"a finite number in [{var.lo}, {var.hi}]", where)
    lo = var.lo
    if var.name == "speed_rpm":
        lo = ev.min_speed_rpm
    if (lo is not None and x < lo) or (var.hi is not None and x > var.hi):
        extra = f" for model '{model}'" if var.name == "speed_rpm" else ""
        raise BearingInputError(var.name, v, f"{lo} <= value <= {var.hi}{extra}", where)


# ---- resolving a point into model inputs ------------------------------------------------------
def _load_bearing(name: str):
    from ..bearing.geometry import from_dict, load_preset
    s = str(name)
    if s.lower().endswith(".json"):
        p = Path(s)
        if not p.is_file():
            raise BearingInputError("bearing", s, "a preset name or an existing bearing JSON file")
        try:
            d = json.loads(p.read_text())
        except json.JSONDecodeError as e:
            raise BearingInputError("bearing", s, "a valid JSON bearing definition", str(e))
        return from_dict(d)
    return load_preset(s)


def resolve_geometry(point: dict):
    """BearingGeometry of the point (preset or file, with clearance overrides)."""
    from dataclasses import replace
    g = _load_bearing(point.get("bearing", VARIABLES["bearing"].default))
    cage = g.cage
    pc, lc = point.get("pocket_clearance_mm", float("nan")), point.get("land_clearance_mm", float("nan"))
    if not math.isnan(pc):
        cage = replace(cage, pocket_clearance=pc * 1e-3)
    if not math.isnan(lc):
        cage = replace(cage, land_clearance=lc * 1e-3)
    return g.with_overrides(cage=cage) if cage is not g.cage else g


def point_loads(point: dict) -> np.ndarray:
    """(Fx, Fy, Fz + preload, Mx, My) [N, N m]."""
    return np.array([point["fx_N"], point["fy_N"], point["fz_N"] + point["preload_N"], point["mx_Nm"],
                     point["my_Nm"]], dtype=float)


def dynamics_options(point: dict, options: dict):
    from ..models.dynamics import DynamicsOptions
    kw = dict(traction=point["traction"], mu=point["mu"], mu_pocket=point["mu_cage"], mu_land=point["mu_cage"],
              oil=point["oil"], oil_temperature=point["oil_temperature_C"] + 273.15,
              oil_fraction=point["oil_fraction"])
    for k in ("integrator", "rtol", "record_dt", "churning", "lubricant", "kalker_grid"):
        if k in options:
            kw[k] = options[k]
    return DynamicsOptions(**kw)


# ---- pure-rolling cage speed and the skid criterion ----------------------------------------------
def pure_rolling_cage_speed(omega, alpha_i, alpha_o, D, dm, loaded=None) -> float:
    """Pure-rolling cage speed [rad/s] with outer raceway control at each loaded ball's contact angles [rad]
    for inner-ring speed omega [rad/s], outer ring fixed: the reference of the dynamics' skid outputs
    (skid.pure_rolling_cage_speeds, Harris & Kotzalas 5th ed. Vol. 2 Ch. 3); all balls if none is loaded."""
    from ..models.skid import pure_rolling_cage_speeds
    m = None if loaded is None or not np.any(loaded) else loaded
    return pure_rolling_cage_speeds(omega, alpha_i, alpha_o, D, dm, loaded=m)[0]


SKID_STATES = ("skidding", "pure rolling", "over-skidding")


def skid_state(ratio: float, skid_threshold: float = 0.05, overskid_threshold: float = 0.05) -> str:
    """'skidding' if ratio < 1 - skid_threshold, 'over-skidding' if ratio > 1 + overskid_threshold, else
    'pure rolling'; '' for an undefined ratio (zero speed)."""
    if ratio is None or not math.isfinite(ratio):
        return ""
    if ratio < 1.0 - skid_threshold:
        return "skidding"
    if ratio > 1.0 + overskid_threshold:
        return "over-skidding"
    return "pure rolling"


def _ratio(cage, pure):
    return cage / pure if pure > 0 else float("nan")


# ---- evaluators -----------------------------------------------------------------------------------
_COMMON = ("bearing", "fx_N", "fy_N", "fz_N", "mx_Nm", "my_Nm", "preload_N")
_TRIBO = ("oil", "oil_temperature_C", "oil_fraction", "traction", "mu")
_CAGE = ("mu_cage", "pocket_clearance_mm", "land_clearance_mm")


class Evaluator:
    """A model that maps one resolved point to a dict of outputs (names with units)."""

    name = ""
    uses: tuple = ()
    min_speed_rpm = 0.0
    option_names: tuple = ()
    threaded_batch = False      # True: run_batch advances its points on several threads (dynamics.advance_many)

    def validate_options(self, options: dict):
        pass

    def __call__(self, point: dict, options: dict) -> dict:
        raise NotImplementedError

    def run_batch(self, points: list, options: dict, threads: int = 1, on_done=None) -> list:
        """Evaluate several points in this process; per point its outputs or the exception it raised (one
        failing point never stops the others). Default: one point after the other; the dynamic evaluators
        advance their points together (dynamics.advance_many, ``threads`` threads). on_done(k), if given, is
        called when point k is finished (progress)."""
        out = []
        for k, p in enumerate(points):
            try:
                out.append(self(p, options))
            except Exception as e:      # recorded for this point
                out.append(e)
            if on_done is not None:
                on_done(k)
        return out


class QuasiStaticEvaluator(Evaluator):
    """Jones-Harris quasi-static model (quasistatic.py), raceway control options['control']. Its cage speed
    is the pure-rolling value by construction (ratio 1 up to the spin-free formula's difference)."""

    name = "quasistatic"
    uses = ("speed_rpm",) + _COMMON
    option_names = ("control",)

    def validate_options(self, options):
        c = options.get("control", "outer")
        if c not in ("outer", "inner", "hybrid"):
            raise BearingInputError("control", c, "outer | inner | hybrid")

    def __call__(self, point, options):
        from ..models.quasistatic import QuasiStaticModel
        g = resolve_geometry(point)
        n = point["speed_rpm"]
        r = QuasiStaticModel(g, options.get("control", "outer")).solve(n * RPM, point_loads(point), stiffness=False)
        j = int(np.argmax(r.Q_i))
        loaded = (r.Q_i > 0) & (r.Q_o > 0)
        pr = pure_rolling_cage_speed(n * RPM, r.alpha_i, r.alpha_o, g.D, g.dm, loaded)
        return {"cage_speed_rpm": r.cage_speed / RPM, "pure_rolling_cage_speed_rpm": pr / RPM,
                "cage_speed_ratio": _ratio(r.cage_speed, pr),
                "cage_shaft_ratio": r.cage_speed / (n * RPM) if n > 0 else float("nan"),
                "alpha_i_deg": float(np.degrees(r.alpha_i[j])), "alpha_o_deg": float(np.degrees(r.alpha_o[j])),
                "Q_i_N": float(r.Q_i[j]), "Q_o_N": float(r.Q_o[j]),
                "omega_R_rpm": float(r.omega_R[j] / RPM), "spin_roll_i": float(r.spin_roll_i[j]),
                "spin_roll_o": float(r.spin_roll_o[j]), "p_max_i_Pa": float(r.p_i[j]),
                "dz_m": float(r.u[2]), "dx_m": float(r.u[0]), "residual_rel": float(r.residual)}


class TriboEvaluator(Evaluator):
    """Quasi-static tribological model (quasistatic_tribo.py) with the point's traction, friction and
    oil-air mixture (ball drag). Needs rolling: speed >= 10 rpm."""

    name = "tribo"
    uses = ("speed_rpm",) + _COMMON + _TRIBO
    min_speed_rpm = 10.0

    def __call__(self, point, options):
        from ..models.quasistatic_tribo import TriboQuasiStaticModel
        g = resolve_geometry(point)
        w = point["speed_rpm"] * RPM
        r = TriboQuasiStaticModel(g, dynamics_options(point, options)).solve(w, point_loads(point))
        loaded = (r.Q_i > 0) & (r.Q_o > 0)
        pr = pure_rolling_cage_speed(w, r.alpha_i, r.alpha_o, g.D, g.dm, loaded)
        j = int(np.argmax(r.Q_i))
        return {"cage_speed_rpm": r.cage_speed / RPM, "pure_rolling_cage_speed_rpm": pr / RPM,
                "cage_speed_ratio": _ratio(r.cage_speed, pr),
                "friction_torque_Nm": r.friction_torque, "heat_W": r.losses["P_drive"],
                "P_race_inner_W": r.losses["P_race_inner"], "P_race_outer_W": r.losses["P_race_outer"],
                "P_drag_W": r.losses["P_drag"],
                "alpha_i_deg": float(np.degrees(r.alpha_i[j])), "alpha_o_deg": float(np.degrees(r.alpha_o[j])),
                "Q_i_N": float(r.Q_i[j]), "Q_o_N": float(r.Q_o[j]),
                "slide_roll_i_max": float(np.max(np.abs(r.slide_roll_i))),
                "slide_roll_o_max": float(np.max(np.abs(r.slide_roll_o))), "residual_N": float(r.residual)}


def _window_summary(rec) -> dict:
    from ..models import dynamics_kernels as K
    I = K.OUT_INDEX
    m = rec.mean(axis=0)
    return {"cage": m[I["cage_speed"]], "pure": m[I["cage_speed_pure_rolling_outer"]],
            "torque": m[I["friction_torque"]], "heat": m[I["P_drive"]], "alpha_i": m[I["alpha_i_mean"]],
            "alpha_o": m[I["alpha_o_mean"]], "Q_i_max": m[I["Q_i_max"]], "p_max": m[I["p_max"]],
            "P_pocket": m[I["P_pocket"]], "P_land": m[I["P_land"]],
            "P_race": m[I["P_race_inner"]] + m[I["P_race_outer"]]}


class DynamicWindow(Evaluator):
    """DynamicModel (dynamics.py) at held speed and loads, advanced in windows of options['window_s']
    (default 0.02 s) from options['start'] ('jones-harris' | 'tribological'). Steadiness criterion: between
    two consecutive windows the window mean of the cage speed changes by less than options['steady_tol']
    (default 0.002) and that of the friction torque by less than options['torque_tol'] (default 0.05; the
    torque carries pocket and contact fluctuations of a few per cent from window to window), relative to the
    latest window mean (torque: plus 1e-6 N m). Outputs are the means over the last window; 'steady' says
    whether the criterion was met before options['max_time_s'] (default 1 s) simulated; 'settle_time_s' is
    the simulated time at that moment."""

    name = "dynamic"
    uses = ("speed_rpm",) + _COMMON + _TRIBO + _CAGE
    min_speed_rpm = 10.0
    option_names = ("window_s", "max_time_s", "steady_tol", "torque_tol", "start", "integrator", "rtol")

    @property
    def threaded_batch(self) -> bool:
        """True unless a subclass evaluates its points another way (its own __call__, e.g. the FMU)."""
        return type(self).__call__ is DynamicWindow.__call__

    def validate_options(self, o):
        from ..errors import check_range
        check_range("window_s", o.get("window_s", 0.02), 1e-3, 10.0, unit="s")
        check_range("max_time_s", o.get("max_time_s", 1.0), 1e-3, 100.0, unit="s")
        check_range("steady_tol", o.get("steady_tol", 2e-3), 1e-8, 0.5)
        check_range("torque_tol", o.get("torque_tol", 0.05), 1e-8, 1.0)
        if o.get("start", "jones-harris") not in ("jones-harris", "tribological"):
            raise BearingInputError("start", o.get("start"), "jones-harris | tribological")

    def _start(self, point, options, models=None):
        """The point's initialised model and its window settings (models: see _new_model)."""
        m = _new_model(point, options, models)
        m.initialize(point["speed_rpm"] * RPM, point_loads(point), start=options.get("start", "jones-harris"))
        return _WindowRun(m, options)

    def __call__(self, point, options):
        r = self._start(point, options)
        while not r.done:
            r.take(r.m.advance(r.next_t(), record_dt=r.rdt))
        return r.outputs()

    def run_batch(self, points, options, threads=1, on_done=None):
        """All points' windows advanced together: each round advances every unfinished model by one window
        with dynamics.advance_many (``threads`` threads; bit-identical to advancing one model at a time),
        so every point sees exactly the calls of __call__. A point whose start or integration raises is
        reported as that exception; the others go on. on_done(k): point k finished (progress)."""
        if not self.threaded_batch:
            return super().run_batch(points, options, threads, on_done)
        from ..models.dynamics import advance_many
        runs, models = [], {}
        for p in points:
            try:
                runs.append(self._start(p, options, models))
            except Exception as e:
                runs.append(e)
        pending = set(range(len(runs)))

        def report():
            for k in sorted(pending):
                r = runs[k]
                if isinstance(r, Exception) or r.error is not None or r.done:
                    pending.discard(k)
                    if on_done is not None:
                        on_done(k)
        report()
        active = [r for r in runs if isinstance(r, _WindowRun) and not r.done]
        while active:
            recs = advance_many([r.m for r in active], [r.next_t() for r in active], record_dt=active[0].rdt,
                                workers=threads, return_exceptions=True)
            for r, rec in zip(active, recs):
                if isinstance(rec, Exception):
                    r.error = rec
                else:
                    try:
                        r.take(rec)
                    except Exception as e:
                        r.error = e
            active = [r for r in active if r.error is None and not r.done]
            report()
        out = []
        for r in runs:
            if isinstance(r, Exception) or r.error is not None:
                out.append(r if isinstance(r, Exception) else r.error)
                continue
            try:
                out.append(r.outputs())
            except Exception as e:
                out.append(e)
        return out


_START_VARIABLES = ("speed_rpm",) + LOAD_VARIABLES     # enter DynamicModel.initialize only, not the model


def _new_model(point, options, models=None):
    """A new (not initialised) DynamicModel of the point. models: a dict shared by the points of a batch:
    the first point of each combination of the variables other than speed and loads (bearing, clearances,
    oil, traction, friction; the sweep options are the batch's) constructs the model, the others get a copy
    of it (copy.deepcopy of the un-initialised model: the same object as a new construction, without
    rebuilding its Hertz tables; the batch test holds the results equal bit for bit)."""
    import copy
    from ..models.dynamics import DynamicModel
    if models is None:
        return DynamicModel(resolve_geometry(point), dynamics_options(point, options))
    key = json.dumps(_canonical({k: v for k, v in point.items() if k not in _START_VARIABLES}), sort_keys=True)
    if key not in models:
        models[key] = DynamicModel(resolve_geometry(point), dynamics_options(point, options))
    return copy.deepcopy(models[key])


class _WindowRun:
    """One point of DynamicWindow: its model, the window loop's state and the steadiness test."""

    def __init__(self, m, options):
        self.m = m
        self.win = float(options.get("window_s", 0.02))
        self.t_max = float(options.get("max_time_s", 1.0))
        self.tol = float(options.get("steady_tol", 2e-3))
        self.ttol = float(options.get("torque_tol", 0.05))
        self.rdt = min(self.win / 20.0, 1e-3)
        self.prev = self.s = None
        self.steady = False
        self.error = None

    @property
    def done(self) -> bool:
        return self.steady or not self.m.t < self.t_max - 1e-12

    def next_t(self) -> float:
        return min(self.m.t + self.win, self.t_max)

    def take(self, rec):
        """Summarise the window just advanced; steady when the window means moved less than the tolerances."""
        s = self.s = _window_summary(rec)
        if self.prev is not None:
            dc = abs(s["cage"] - self.prev["cage"]) <= self.tol * abs(s["cage"])
            dt = abs(s["torque"] - self.prev["torque"]) <= self.ttol * abs(s["torque"]) + 1e-6
            if dc and dt:
                self.steady = True
                return
        self.prev = s

    def outputs(self) -> dict:
        s = self.s
        return {"cage_speed_rpm": s["cage"] / RPM, "pure_rolling_cage_speed_rpm": s["pure"] / RPM,
                "cage_speed_ratio": _ratio(s["cage"], s["pure"]), "friction_torque_Nm": s["torque"],
                "heat_W": s["heat"], "P_race_W": s["P_race"], "P_pocket_W": s["P_pocket"], "P_land_W": s["P_land"],
                "alpha_i_deg": math.degrees(s["alpha_i"]), "alpha_o_deg": math.degrees(s["alpha_o"]),
                "Q_i_N": s["Q_i_max"], "p_max_Pa": s["p_max"], "steady": self.steady, "settle_time_s": self.m.t}


class ProfileEvaluator(Evaluator):
    """DynamicModel through the speed profile options['profile'] ('seed000' or a CSV time_s, speed_rpm;
    dynamics.read_profile) at the point's loads. Outputs: means over the last 0.1 s ('final_'), and the
    smallest and largest cage speed ratio over the records after the first 0.05 s (the worst skid and
    over-skid of the profile)."""

    name = "profile"
    uses = _COMMON + _TRIBO + _CAGE
    option_names = ("profile", "start", "integrator", "rtol", "record_dt")

    @property
    def threaded_batch(self) -> bool:
        """True unless a subclass evaluates its points another way (its own __call__, e.g. the FMU)."""
        return type(self).__call__ is ProfileEvaluator.__call__

    def validate_options(self, o):
        from ..models.dynamics import read_profile
        t, n, loads = read_profile(o.get("profile", "seed000"))
        if loads:
            raise BearingInputError("profile", o.get("profile"), "time_s, speed_rpm only (loads are sweep variables)")

    def _start(self, point, options, models=None):
        """The point's model initialised at the profile's first speed, and the profile (t [s], speed [rpm])
        (models: see _new_model)."""
        from ..models.dynamics import read_profile
        t, n, _ = read_profile(options.get("profile", "seed000"))
        m = _new_model(point, options, models)
        m.initialize(n[0] * RPM, point_loads(point), t0=float(t[0]), start=options.get("start", "jones-harris"))
        return m, list(zip(t.tolist(), n.tolist()))

    def __call__(self, point, options):
        from ..models.dynamics import simulate_profile
        m, prof = self._start(point, options)
        return self._outputs(simulate_profile(m, prof, record_dt=options.get("record_dt", 1e-3)))

    def run_batch(self, points, options, threads=1, on_done=None):
        """All points driven through the profile together: segment by segment, every model advanced with
        dynamics.advance_many (``threads`` threads) with the calls of dynamics.simulate_profile (the same end
        time and end speed of each segment, the ring growth updated after it), so the records are those of
        __call__. A point whose start or integration raises is reported as that exception. (on_done is not
        called: the points finish together, with the batch.)"""
        if not self.threaded_batch:
            return super().run_batch(points, options, threads, on_done)
        from ..models.dynamics import advance_many
        from ..models import dynamics_kernels as K
        models, errors, recs, prof, built = [], [None] * len(points), [[] for _ in points], None, {}
        for i, p in enumerate(points):
            try:
                m, prof = self._start(p, options, built)
                models.append(m)
            except Exception as e:
                models.append(None)
                errors[i] = e
        rdt = options.get("record_dt", 1e-3)
        for (t0, n0), (t1, n1) in zip(prof or [], (prof or [])[1:]):
            idx = [i for i, m in enumerate(models) if m is not None and errors[i] is None and t1 > m.t + 1e-12]
            if not idx:
                continue
            w = (n0 + (n1 - n0) * (t1 - t0) / (t1 - t0)) * math.pi / 30.0     # as simulate_profile
            res = advance_many([models[i] for i in idx], t1, omega_end=w, record_dt=rdt, workers=threads,
                               return_exceptions=True)
            for i, r in zip(idx, res):
                if isinstance(r, Exception):
                    errors[i] = r
                    continue
                recs[i].append(r)
                try:
                    models[i].update_operating_geometry()
                except Exception as e:
                    errors[i] = e
        out = []
        for i in range(len(points)):
            if errors[i] is not None:
                out.append(errors[i])
                continue
            try:
                out.append(self._outputs(np.concatenate(recs[i]) if recs[i] else np.zeros((0, K.NOUT))))
            except Exception as e:
                out.append(e)
        return out

    @staticmethod
    def _outputs(rec) -> dict:
        from ..models.dynamics import records_to_dict
        d = records_to_dict(rec)
        tail = d["t"] >= d["t"][-1] - 0.1
        ok = (d["t"] >= d["t"][0] + 0.05) & (d["cage_speed_pure_rolling_outer"] > 0)
        r = d["cage_speed"][ok] / d["cage_speed_pure_rolling_outer"][ok]
        cage, pure = d["cage_speed"][tail].mean(), d["cage_speed_pure_rolling_outer"][tail].mean()
        return {"final_speed_rpm": float(d["shaft_speed"][-1] / RPM), "cage_speed_rpm": cage / RPM,
                "pure_rolling_cage_speed_rpm": pure / RPM, "cage_speed_ratio": _ratio(cage, pure),
                "cage_speed_ratio_min": float(r.min()) if r.size else float("nan"),
                "cage_speed_ratio_max": float(r.max()) if r.size else float("nan"),
                "friction_torque_Nm": float(d["friction_torque"][tail].mean()),
                "friction_torque_max_Nm": float(d["friction_torque"].max()),
                "heat_W": float(d["P_drive"][tail].mean())}


class PluginEvaluator(Evaluator):
    """An evaluator defined outside bearing_core: 'package.module:attribute' naming an Evaluator
    subclass or instance (e.g. bearing_cosim.fmu_sweep:FMUEvaluator)."""


EVALUATORS = {"quasistatic": QuasiStaticEvaluator, "tribo": TriboEvaluator, "dynamic": DynamicWindow,
              "profile": ProfileEvaluator}
# evaluators living outside bearing_core, imported by name on first use (and on each worker)
PLUGINS = {"fmu": "bearing_cosim.fmu_sweep:FMUEvaluator"}
MODEL_NAMES = tuple(EVALUATORS) + tuple(PLUGINS)


def get_evaluator(name: str) -> Evaluator:
    """The evaluator registered under name (EVALUATORS, PLUGINS) or given as 'module:attribute'."""
    import importlib
    if name in EVALUATORS:
        return EVALUATORS[name]()
    target = PLUGINS.get(name, name)
    if ":" not in target:
        raise BearingInputError("model", name, " | ".join(MODEL_NAMES) + " (or module:attribute)")
    mod, attr = target.split(":", 1)
    try:
        obj = getattr(importlib.import_module(mod), attr)
    except (ImportError, AttributeError) as e:
        raise BearingInputError("model", name, " | ".join(MODEL_NAMES), f"cannot import {target}: {e}")
    return obj() if isinstance(obj, type) else obj


# ---- one point on a worker ------------------------------------------------------------------------
def run_point(model: str, options: dict, point: dict, skid: tuple = (0.05, 0.05)) -> dict:
    """Evaluate one point; never raises for a model error: returns {'status': 'ok' | 'failed', 'error',
    outputs..., 'skid_state', 'eval_wall_s'}."""
    t0 = time.perf_counter()
    try:
        out = get_evaluator(model)(point, options)
        out["skid_state"] = skid_state(out.get("cage_speed_ratio", float("nan")), *skid)
        out.update(status="ok", error="")
    except Exception as e:  # recorded, never stops the sweep
        out = {"status": "failed", "error": f"{type(e).__name__}: {e}"}
    out["eval_wall_s"] = time.perf_counter() - t0
    return out


def run_point_batch(model: str, options: dict, points: list, skid: tuple = (0.05, 0.05), threads: int = 1,
                    progress=None) -> list:
    """Evaluate a batch of points in one task (Evaluator.run_batch: the dynamic models advance them together
    on ``threads`` threads); never raises for a model error: per point the dict of run_point. eval_wall_s
    of each point is the batch's wall time divided by its number of points (the points share the time).
    progress: (topic, tag): on a Dask worker, each finished point is logged as the event (tag, k) on topic
    (the client's progress bar follows the points inside the batch)."""
    on_done = None
    if progress is not None:
        try:
            from distributed import get_worker
            worker, (topic, tag) = get_worker(), progress
            on_done = lambda k: worker.log_event(topic, (tag, k))  # noqa: E731
        except Exception:       # not on a worker: no events (the batch's result reports its points)
            on_done = None
    t0 = time.perf_counter()
    try:
        res = get_evaluator(model).run_batch(list(points), options, threads=max(1, int(threads)), on_done=on_done)
    except Exception as e:      # the evaluator itself failed: every point of the batch
        res = [e] * len(points)
    share = (time.perf_counter() - t0) / max(len(points), 1)
    out = []
    for r in res:
        if isinstance(r, Exception):
            r = {"status": "failed", "error": f"{type(r).__name__}: {r}"}
        else:
            r = dict(r)
            r["skid_state"] = skid_state(r.get("cage_speed_ratio", float("nan")), *skid)
            r.update(status="ok", error="")
        r["eval_wall_s"] = share
        out.append(r)
    return out


MAX_AUTO_BATCH = 32     # largest batch chosen automatically (progress and the cache advance per batch)
BATCHES_PER_SLOT = 4    # automatic batches per task slot of the cluster (load balance, progress)


def auto_batch_size(n_points: int, slots: int, threads: int = 1) -> int:
    """Points per task: about BATCHES_PER_SLOT tasks for each task slot of the cluster (so that the slots stay
    balanced when points differ in cost and the progress bar and cache advance often), at least ``threads``
    points (each thread of advance_many gets a model), at most MAX_AUTO_BATCH."""
    b = math.ceil(n_points / max(1, slots * BATCHES_PER_SLOT))
    return int(max(1, min(max(b, threads), MAX_AUTO_BATCH, max(n_points, 1))))


# ---- running on Dask ------------------------------------------------------------------------------
class _Cluster:
    """Context: a distributed Client on `scheduler` (address) or on a new LocalCluster of `workers`
    single-threaded processes (default: one per CPU divided by ``threads``, the threads each batch task
    runs its models on)."""

    def __init__(self, scheduler=None, workers=None, client=None, threads=1):
        self.scheduler, self.workers, self.client, self._own = scheduler, workers, client, False
        self.threads = max(1, int(threads or 1))

    def __enter__(self):
        if self.client is not None:
            return self.client
        from distributed import Client, LocalCluster
        if self.scheduler:
            self.client = Client(self.scheduler, timeout="30s")
        else:
            import os
            n = self.workers or max(1, (os.cpu_count() or 1) // self.threads)
            self.cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                                        dashboard_address=":0", host="127.0.0.1")
            self.client = Client(self.cluster)
        self._own = True
        return self.client

    def __exit__(self, *exc):
        if self._own:
            self.client.close()
            if getattr(self, "cluster", None) is not None:
                self.cluster.close()


def _progress(total, initial, enabled, desc):
    from tqdm import tqdm
    return tqdm(total=total, initial=initial, disable=not enabled, desc=desc, unit="pt", dynamic_ncols=True)


def _cached_results(keys, cache_dir):
    """Results read from cache_dir/<key>.json (marked cached=True; None where missing or unreadable) and
    the indices of the keys still to compute."""
    results = [None] * len(keys)
    todo = []
    for i, key in enumerate(keys):
        f = cache_dir / f"{key}.json" if cache_dir else None
        if f is not None and f.is_file():
            try:
                results[i] = dict(json.loads(f.read_text()), cached=True)
                continue
            except (json.JSONDecodeError, OSError):
                pass
        todo.append(i)
    return results, todo


def _store_result(cache_dir, key, r):
    """Write a successful point's result to cache_dir/<key>.json (atomically, through a temporary file)."""
    if r.get("status") == "ok" and cache_dir:
        tmp = cache_dir / f".{key}.tmp"
        tmp.write_text(json.dumps({k: v for k, v in r.items() if k != "cached"}))
        tmp.replace(cache_dir / f"{key}.json")


def _run_tasks(tasks, cache_dir, client, retries, progress, desc):
    """tasks: list of (key, callable, args). Cached results are read from cache_dir/<key>.json; the rest is
    submitted to the client. Returns (results in task order, number computed)."""
    from distributed import as_completed
    results, todo = _cached_results([t[0] for t in tasks], cache_dir)
    bar = _progress(len(tasks), len(tasks) - len(todo), progress, desc)
    failed = sum(1 for r in results if r is not None and r.get("status") == "failed")
    if todo:
        futs = {}
        for i in todo:
            key, fn, args = tasks[i]
            fut = client.submit(fn, *args, key=f"bearing-sweep-{key[:24]}-{i}", retries=retries, pure=False)
            futs[fut] = i
        for fut in as_completed(list(futs)):
            i = futs[fut]
            try:
                r = fut.result()
            except Exception as e:   # the task itself failed (e.g. its workers kept dying): recorded
                r = {"status": "failed", "error": f"{type(e).__name__}: {e}"}
            r = dict(r, cached=False)
            results[i] = r
            _store_result(cache_dir, tasks[i][0], r)
            failed += r.get("status") == "failed"
            bar.set_postfix(failed=failed, refresh=False)
            bar.update(1)
            fut.release()
    bar.close()
    return results, len(todo)


def _run_batches(keys, points, model, opts, skid, cache_dir, client, retries, progress, desc, batch_size,
                 threads):
    """Like _run_tasks for the points of a sweep, but batch_size points per task (at most; run_point_batch;
    None: auto_batch_size from the points left and the cluster's task slots). Cached points are read first and
    only the rest is batched; each arriving batch is written to the cache point by point. A batch task that
    fails as a whole (e.g. its workers kept dying) marks its points failed. Returns (results in point
    order, number computed)."""
    from distributed import as_completed
    results, todo = _cached_results(keys, cache_dir)
    bar = _progress(len(points), len(points) - len(todo), progress, desc)
    failed = 0
    lock, seen, closed = threading.Lock(), {}, set()       # per batch tag: points reported by events
    topic = f"bearing-sweep-progress-{uuid.uuid4().hex}" if progress else None

    def on_event(event):        # (time, (tag, k)) from run_point_batch, on the client's event-loop thread
        tag = event[1][0]
        with lock:
            if tag in closed or seen.get(tag, 0) >= sizes.get(tag, 0):
                return
            seen[tag] = seen.get(tag, 0) + 1
            bar.update(1)
    sizes = {}
    if todo and topic:
        try:
            client.subscribe_topic(topic, on_event)
        except Exception:       # a scheduler without events: the bar advances per batch
            topic = None
    if todo:
        if batch_size is None:
            slots = sum(client.nthreads().values()) or 1
            batch_size = auto_batch_size(len(todo), slots, threads)
        # strided: batch k holds points k, k + nb, ... so that neighbouring points of a grid, which usually
        # cost alike (the same speed region), spread over the batches and the batches cost alike
        nb = math.ceil(len(todo) / batch_size)
        groups = [todo[k::nb] for k in range(nb)]
        futs = {}
        for g in groups:
            sizes[g[0]] = len(g)
            fut = client.submit(run_point_batch, model, opts, [points[i] for i in g], skid, threads,
                                (topic, g[0]) if topic else None,
                                key=f"bearing-sweep-batch-{keys[g[0]][:24]}-{g[0]}-{len(g)}", retries=retries,
                                pure=False)
            futs[fut] = g
        try:
            for fut in as_completed(list(futs)):
                g = futs[fut]
                try:
                    rs = fut.result()
                except Exception as e:   # the task itself failed: recorded for each of its points
                    rs = [{"status": "failed", "error": f"{type(e).__name__}: {e}"}] * len(g)
                for i, r in zip(g, rs):
                    r = dict(r, cached=False)
                    results[i] = r
                    _store_result(cache_dir, keys[i], r)
                    failed += r.get("status") == "failed"
                with lock:
                    closed.add(g[0])
                    bar.set_postfix(failed=failed, refresh=False)
                    bar.update(len(g) - min(seen.get(g[0], 0), len(g)))
                fut.release()
        finally:
            if topic:
                try:
                    client.unsubscribe_topic(topic)
                except Exception:
                    pass
    bar.close()
    return results, len(todo)


def run_sweep(spec: SweepSpec, cache_dir=None, scheduler=None, workers=None, client=None, retries: int = 2,
              progress: bool = True, skid=(0.05, 0.05), batch_size: int | None = None,
              threads_per_worker: int = 1):
    """Validate, then evaluate every point of spec on Dask; returns a pandas DataFrame ordered by
    point_index: the point's variables that the model uses, status, error, the model outputs, skid_state, eval_wall_s and
    cached (True where the result came from the cache). Attribute df.attrs['computed']: points evaluated
    in this run.

    batch_size: points per Dask task (None: auto_batch_size; 1: one task per point, run_point). The
    dynamic and profile models advance the points of a batch together with dynamics.advance_many on
    threads_per_worker threads (the results are those of one point at a time, bit for bit); the new local
    cluster then gets CPUs / threads_per_worker worker processes unless ``workers`` is given. The other
    models evaluate a batch point after point (threads_per_worker is ignored: their Python/SciPy solvers hold
    the GIL), so for them batching only saves the per-task overhead."""
    import pandas as pd
    from ..errors import check_range
    for nm, v, hi in (("batch_size", batch_size, 100000), ("threads_per_worker", threads_per_worker, 512)):
        if v is not None and (check_range(nm, v, 1, hi) != int(v)):
            raise BearingInputError(nm, v, f"an integer in [1, {hi}]")
    batch_size = None if batch_size is None else int(batch_size)
    threads_per_worker = int(threads_per_worker)
    pts = spec.validate()
    version = code_version()
    cache = Path(cache_dir) if cache_dir else None
    if cache:
        cache.mkdir(parents=True, exist_ok=True)
    opts = dict(spec.options)
    skid = (float(skid[0]), float(skid[1]))
    keys = [point_key(p, spec.model, dict(opts, skid=list(skid)), version) for p in pts]
    if not get_evaluator(spec.model).threaded_batch:
        threads_per_worker = 1      # its batches run point after point: the workers are the parallelism
    with _Cluster(scheduler, workers, client, threads_per_worker) as cl:
        if batch_size == 1:
            tasks = [(k, run_point, (spec.model, opts, p, skid)) for k, p in zip(keys, pts)]
            res, computed = _run_tasks(tasks, cache, cl, retries, progress, f"sweep ({spec.model})")
        else:
            res, computed = _run_batches(keys, pts, spec.model, opts, skid, cache, cl, retries, progress,
                                         f"sweep ({spec.model})", batch_size, threads_per_worker)
    uses = set(get_evaluator(spec.model).uses)
    rows = []
    for i, (p, r) in enumerate(zip(pts, res)):   # the variables the model uses, then its outputs
        rows.append(dict({"point_index": i}, **{k: v for k, v in p.items() if k in uses}, **r))
    df = pd.DataFrame(rows)
    df.attrs["computed"] = computed
    return df


# ---- minimum preload by bisection -----------------------------------------------------------------
def bisect_min_preload(model: str, options: dict, point: dict, lo: float, hi: float, rtol: float = 0.02,
                       skid=(0.05, 0.05), max_iter: int = 40) -> dict:
    """Smallest preload [N] at which the point does not skid (cage speed ratio >= 1 - skid[0]), by
    bisection between lo (must skid) and hi (must not), geometric when lo > 0, until
    hi - lo <= rtol * hi. Returns min_preload_N (= the last non-skidding preload), preload_skidding_N
    (largest preload found skidding), the ratios there, evaluations, status and error. A failed evaluation
    ends the search with status 'failed'."""
    ev = get_evaluator(model)
    n_eval = 0

    def ratio(pl):
        nonlocal n_eval
        n_eval += 1
        return float(ev(dict(point, preload_N=pl), options)["cage_speed_ratio"])

    def skids(r):
        return r < 1.0 - skid[0]

    out = {"min_preload_N": float("nan"), "preload_skidding_N": float("nan"), "ratio_at_min_preload": float("nan"),
           "ratio_at_skidding_preload": float("nan"), "status": "ok", "error": ""}
    t0 = time.perf_counter()
    try:
        r_lo, r_hi = ratio(lo), ratio(hi)
        if not skids(r_lo):
            out.update(min_preload_N=lo, ratio_at_min_preload=r_lo, status="no skid at the lower bound")
        elif skids(r_hi):
            out.update(preload_skidding_N=hi, ratio_at_skidding_preload=r_hi, status="skids at the upper bound")
        else:
            for _ in range(max_iter):
                if hi - lo <= rtol * hi:
                    break
                mid = math.sqrt(lo * hi) if lo > 0 else 0.5 * (lo + hi)
                r = ratio(mid)
                if skids(r):
                    lo, r_lo = mid, r
                else:
                    hi, r_hi = mid, r
            out.update(min_preload_N=hi, preload_skidding_N=lo, ratio_at_min_preload=r_hi,
                       ratio_at_skidding_preload=r_lo)
    except Exception as e:
        out.update(status="failed", error=f"{type(e).__name__}: {e}")
    out.update(evaluations=n_eval, eval_wall_s=time.perf_counter() - t0)
    return out


def min_preload_curve(spec: SweepSpec, speeds_rpm, lo: float = 1.0, hi: float = 5000.0, rtol: float = 0.02,
                      cache_dir=None, scheduler=None, workers=None, client=None, retries: int = 2,
                      progress: bool = True, skid=(0.05, 0.05)):
    """Minimum preload against speed: one bisection (bisect_min_preload) per speed, the speeds in parallel.
    spec supplies the model, options and base values (its grid/points are not used). Returns a DataFrame
    ordered by speed."""
    import pandas as pd
    from ..errors import check_range
    ev = get_evaluator(spec.model)
    speeds = [float(s) for s in speeds_rpm]
    if not speeds:
        raise BearingInputError("min-preload speeds", speeds, "at least one speed")
    for s in speeds:
        check_range("speed_rpm", s, max(ev.min_speed_rpm, 1e-9), 190000.0, unit="rpm")
    check_range("preload lower bound", lo, 0.0, 1e7, unit="N")
    check_range("preload upper bound", hi, lo, 1e7, lo_incl=False, unit="N")
    check_range("preload rtol", rtol, 1e-6, 0.5)
    if "preload_N" in spec.base and spec.base["preload_N"] != 0.0:
        raise BearingInputError("preload_N", spec.base["preload_N"], "not set: the bisection chooses the preload")
    base = SweepSpec(model=spec.model, base=dict(spec.base), grid={"speed_rpm": speeds}, options=spec.options)
    pts = base.validate()
    version = code_version()
    cache = Path(cache_dir) if cache_dir else None
    if cache:
        cache.mkdir(parents=True, exist_ok=True)
    skid = (float(skid[0]), float(skid[1]))
    tasks = []
    for p in pts:
        key = point_key(dict(p, task="min-preload", lo=lo, hi=hi, rtol=rtol), spec.model,
                        dict(spec.options, skid=list(skid)), version)
        tasks.append((key, bisect_min_preload, (spec.model, dict(spec.options), p, lo, hi, rtol, skid)))
    with _Cluster(scheduler, workers, client) as cl:
        res, computed = _run_tasks(tasks, cache, cl, retries, progress, "min preload")
    df = pd.DataFrame([dict({"speed_rpm": p["speed_rpm"]}, **r) for p, r in zip(pts, res)])
    df.attrs["computed"] = computed
    return df


# ---- results: tables, NetCDF and plots ------------------------------------------------------------
def to_dataset(df, spec: SweepSpec):
    """xarray Dataset of a grid sweep: one dimension per grid variable (in grid order), the numeric
    outputs as data variables (NaN where a point failed), status and error as text variables."""
    import pandas as pd
    import xarray as xr
    dims = list(spec.grid)
    shape = [len(spec.grid[d]) for d in dims]
    coords = {d: np.asarray(spec.grid[d]) for d in dims}
    data = {}
    skip = set(VARIABLES) | {"point_index", "cached"}
    for c in df.columns:
        if c in skip:
            continue
        col = df[c]
        if pd.api.types.is_bool_dtype(col.dtype) or c == "steady":
            vals = col.astype(float).to_numpy()
        elif pd.api.types.is_numeric_dtype(col.dtype):
            vals = col.to_numpy(dtype=float)
        else:
            vals = np.array(["" if x is None or (isinstance(x, float) and math.isnan(x)) else str(x)
                             for x in col], dtype=str)
        data[c] = (dims, vals.reshape(shape))
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(model=spec.model, options=json.dumps(spec.options, default=str),
                    base=json.dumps(spec.base, default=str), code_version=code_version())
    return ds


def write_results(df, spec: SweepSpec, out_dir, stem: str = "sweep") -> list[Path]:
    """<stem>.csv, <stem>.parquet and, for a grid, <stem>.nc (NetCDF, scipy backend). Returns the paths."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    paths = [out / f"{stem}.csv", out / f"{stem}.parquet"]
    df.to_csv(paths[0], index=False)
    df.to_parquet(paths[1], index=False)
    if spec.is_grid and spec.grid:
        p = out / f"{stem}.nc"
        to_dataset(df, spec).to_netcdf(p, engine="scipy")
        paths.append(p)
    return paths


def _map_axes(spec: SweepSpec):
    """(speed dim, load dim) of a grid for maps, or None."""
    if not spec.is_grid or "speed_rpm" not in spec.grid:
        return None
    loads = [d for d in spec.grid if d in LOAD_VARIABLES and len(spec.grid[d]) > 1]
    if len(spec.grid["speed_rpm"]) < 2 or not loads:
        return None
    return "speed_rpm", loads[0]


def plot_maps(df, spec: SweepSpec, out_dir, stem: str = "sweep", skid=(0.05, 0.05)) -> list[Path]:
    """Skid map (cage speed ratio over speed x load with the skidding / over-skidding boundaries),
    friction-torque and heat maps, for a grid with speed_rpm and a load variable (other grid dims at
    their first value). Returns the PNG paths written (none if the grid has no such pair)."""
    ax_ = _map_axes(spec)
    if ax_ is None:
        return []
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    ds = to_dataset(df, spec)
    xs, ys = ax_
    other = {d: 0 for d in spec.grid if d not in ax_}
    sub = ds.isel(other) if other else ds
    note = ", ".join(f"{d} = {spec.grid[d][0]}" for d in other)
    paths = []
    panels = [("cage_speed_ratio", "cage speed / pure-rolling cage speed [-]", "skid_map"),
              ("friction_torque_Nm", "friction torque [N m]", "torque_map"),
              ("heat_W", "heat (friction power) [W]", "heat_map")]
    for var, label, name in panels:
        if var not in sub:
            continue
        Z = sub[var].transpose(ys, xs).values.astype(float)
        if not np.isfinite(Z).any():
            continue
        X, Y = np.meshgrid(sub[xs].values, sub[ys].values)
        fig, a = plt.subplots(figsize=(7, 5), constrained_layout=True)
        if var == "cage_speed_ratio":
            lo, hi = 1.0 - skid[0], 1.0 + skid[1]
            span = max(np.nanmax(np.abs(Z - 1.0)), skid[0], skid[1])
            pc = a.pcolormesh(X, Y, Z, shading="auto", cmap="RdBu", vmin=1 - span, vmax=1 + span)
            if np.nanmin(Z) < lo < np.nanmax(Z):
                cs = a.contour(X, Y, Z, levels=[lo], colors="k", linewidths=2)
                a.clabel(cs, fmt={lo: f"skidding < {lo:g}"})
            if np.nanmin(Z) < hi < np.nanmax(Z):
                cs = a.contour(X, Y, Z, levels=[hi], colors="k", linestyles="--", linewidths=2)
                a.clabel(cs, fmt={hi: f"over-skidding > {hi:g}"})
        else:
            pc = a.pcolormesh(X, Y, Z, shading="auto", cmap="viridis")
        fail = sub["status"].transpose(ys, xs).values != "ok"
        if fail.any():
            a.plot(X[fail], Y[fail], "kx", ms=8, label="failed point")
            a.legend(loc="upper right")
        fig.colorbar(pc, ax=a, label=label)
        yv = np.asarray(sub[ys].values, float)
        if yv.min() > 0 and yv.max() / yv.min() >= 8.0:     # loads spanning a decade: log axis
            a.set_yscale("log")
        a.set_xlabel("inner-ring speed [rpm]")
        a.set_ylabel(ys.replace("_N", " [N]").replace("_Nm", " [N m]"))
        a.set_title(f"{spec.model}: {label}" + (f"\n{note}" if note else ""), fontsize=10)
        p = Path(out_dir) / f"{stem}_{name}.png"
        fig.savefig(p, dpi=110)
        plt.close(fig)
        paths.append(p)
    return paths


def plot_min_preload(df, path, title: str = "") -> Path:
    """Minimum preload against speed, with the bracketing skidding preload."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, a = plt.subplots(figsize=(7, 4.5), constrained_layout=True)
    ok = df["status"] == "ok"
    a.plot(df["speed_rpm"][ok], df["min_preload_N"][ok], "o-", label="minimum preload (no skidding)")
    a.plot(df["speed_rpm"][ok], df["preload_skidding_N"][ok], "v:", color="C3", label="largest preload found skidding")
    a.set_xlabel("inner-ring speed [rpm]")
    a.set_ylabel("axial preload [N]")
    a.set_title(title, fontsize=10)
    a.grid(alpha=0.3)
    a.legend()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return Path(path)
