"""Operating maps for the 'map' fidelity level (``bearing build-map``): the bearing's steady outputs on a grid of
speed, Fx, Fz (optionally Fy, My and oil temperature), evaluated on Dask through the sweep machinery (sweep.run_sweep:
local cluster or a scheduler, cache and resume, progress), written as NetCDF3 with provenance.

Steady levels (``level``):
  'dynamic'      -- the dynamic model held at each point until steady (sweep.DynamicWindow: window means of the last
                    window; full 16-ball model, reduced='full' as in the co-simulation session). The cage speed's
                    time constant is the model's own relaxation from its Jones-Harris start (pure rolling) to the
                    steady cage speed: tau = integral (wc - wc_ss) dt / (wc(0) - wc_ss) over the run.
  'tribological' -- the quasi-static tribological model (quasistatic_tribo.py: free balls, centred cage) and the
                    dynamic model's outputs at its steady state (no integration); no cage time constant (0).

The map's variables are bearing_core.session.fidelity.MAP_OUTPUTS (what the session reads) plus the 5 x 5
quasi-static stiffness of the Jones-Harris model at the point (stiffness_<row><col>, rows and columns x, y, z,
tx, ty: [N/m, N/rad, N m/m, N m/rad]), the fatigue damage rate fatigue_damage_rate [1/s] = 1 / (3600 L10r_h) of
the ISO/TS 16281 reference rating life at the point's steady state (fatigue_damage_rate()) and skid_class (+1 skidding, 0 pure rolling, -1 over-skidding at the
session's 1 % tolerance).
"""
from __future__ import annotations

import datetime
import json
import math

import numpy as np

from ..errors import BearingInputError
from ..session.fidelity import MAP_AXES, MAP_FATIGUE_RATE, MAP_OUTPUTS, REQUIRED_AXES
from . import sweep as S

LEVELS = ("dynamic", "tribological")
STIFF_AXES = ("x", "y", "z", "tx", "ty")
STIFFNESS_NAMES = tuple(f"stiffness_{a}{b}" for a in STIFF_AXES for b in STIFF_AXES)
HEAT = {"heat_flux_race_inner": ("P_race_inner",), "heat_flux_race_outer": ("P_race_outer",),
        "heat_flux_pocket": ("P_pocket",), "heat_flux_land": ("P_land",), "heat_flux_drag": ("P_drag",),
        "heat_flux_damping": ("P_damping",), "heat_flux_churn_cage": ("P_churn_cage",),
        "heat_flux_churn_ring": ("P_churn_ring",), "heat_flux_race_slide": ("P_race_slide",),
        "heat_flux_race_spin": ("P_race_spin",), "heat_flux_race_diffslip": ("P_race_diffslip",)}
CHANNELS = {"reaction_Fx": "Fx", "reaction_Fy": "Fy", "reaction_Fz": "Fz", "reaction_Mx": "Mx", "reaction_My": "My",
            "friction_torque": "friction_torque", "friction_torque_outer": "friction_torque_outer",
            "ir_x": "ir_x", "ir_y": "ir_y", "ir_z": "ir_z", "ir_tx": "ir_tx", "ir_ty": "ir_ty",
            "max_contact_pressure": "p_max", "alpha_i_mean": "alpha_i_mean", "alpha_o_mean": "alpha_o_mean",
            "Q_i_max": "Q_i_max", "Q_o_max": "Q_o_max", "cage_speed": "cage_speed",
            "cage_speed_eq26": "pure_rolling_cage_speed",
            "cage_speed_pure_rolling_outer": "cage_speed_pure_rolling_outer",
            "cage_speed_pure_rolling_inner": "cage_speed_pure_rolling_inner", "drive_power": "P_drive"}


def _map_options(point, options):
    """DynamicsOptions of a map point: the sweep's, with the full 16-ball model (as the session)."""
    import dataclasses
    return dataclasses.replace(S.dynamics_options(point, options), reduced="full")


def _new_model(point, options):
    from ..models.dynamics import DynamicModel
    return DynamicModel(S.resolve_geometry(point), _map_options(point, options))


def steady_outputs(m, mean, point, cage_sd=0.0, steady=True, tau=0.0) -> dict:
    """The map's variables from the window means ``mean`` (dynamics_kernels.OUT_NAMES channels) of the model m at
    its current state (films and stiffness at the point's speed and loads)."""
    from ..models import dynamics_kernels as K
    from ..models.quasistatic import QuasiStaticModel
    from ..models.skid import SKID_TOL
    I = K.OUT_INDEX
    out = {k: float(mean[I[c]]) for k, c in CHANNELS.items()}
    for k, chans in HEAT.items():
        out[k] = float(sum(mean[I[c]] for c in chans))
    out["heat_flux_total"] = float(sum(out[k] for k in ("heat_flux_race_inner", "heat_flux_race_outer",
                                                          "heat_flux_pocket", "heat_flux_land", "heat_flux_drag",
                                                          "heat_flux_damping", "heat_flux_churn_cage",
                                                          "heat_flux_churn_ring")))
    f = m.film()
    for k, key in (("film_min_inner", "h_min_i"), ("film_min_outer", "h_min_o")):
        h = np.asarray(f[key])
        out[k] = float(h[h > 0].min()) if np.any(h > 0) else 0.0
    out["film_parameter_min"] = float(f["Lambda_min"])
    out["cage_time_constant"] = float(tau)
    out["cage_speed_cv"] = float(cage_sd / abs(out["cage_speed"])) if out["cage_speed"] != 0 else 0.0
    out["steady"] = 1.0 if steady else 0.0
    pure = out["cage_speed_pure_rolling_outer"]
    slip = 1.0 - out["cage_speed"] / pure if pure > 0 else 0.0
    out["skid_class"] = 1.0 if slip > SKID_TOL else (-1.0 if slip < -SKID_TOL else 0.0)
    out["cage_speed_ratio"] = out["cage_speed"] / pure if pure > 0 else float("nan")
    try:
        r = QuasiStaticModel(m.g, "outer").solve(point["speed_rpm"] * S.RPM, S.point_loads(point), stiffness=True)
        k5 = np.asarray(r.stiffness, dtype=float).reshape(5, 5)
    except Exception:        # no Jones-Harris equilibrium: the stiffness is left out (NaN), the rest stands
        k5 = np.full((5, 5), np.nan)
    for i, a in enumerate(STIFF_AXES):
        for j, b in enumerate(STIFF_AXES):
            out[f"stiffness_{a}{b}"] = float(k5[i, j])
    out[MAP_FATIGUE_RATE] = fatigue_damage_rate(m, point["speed_rpm"])
    missing = [k for k in MAP_OUTPUTS if k not in out]
    assert not missing, missing
    return out


def fatigue_damage_rate(m, speed_rpm: float) -> float:
    """The map's fatigue variable [1/s] (fidelity.MAP_FATIGUE_RATE): 1 / (3600 L10r_h) with L10r_h [h] the
    ISO/TS 16281 reference rating life of the model m's per-ball contact loads and operating contact angles at its
    current state (the end of the steady window; models.life.rating_life_hours_details_nb, inner ring rotating at
    speed_rpm [rpm], the same function as the session's output life_L10r_h). 0 where the life is infinite (no
    loaded ball); NaN where the state cannot be evaluated (as the stiffness: the rest of the point stands)."""
    from ..models import life as LF
    try:
        _, bd = m.evaluate_point()
        L = LF.rating_life_hours_details_nb(bd, LF.life_parameters(m.g, "inner"), float(speed_rpm))
    except Exception:
        return float("nan")
    return 1.0 / (3600.0 * L) if L < math.inf else 0.0


class _MapRun(S._WindowRun):
    """A point of MapDynamicWindow: the window loop of sweep.DynamicWindow, keeping every channel's window mean,
    the cage speed's spread over the window and its history from the start (time constant)."""

    def __init__(self, m, options):
        super().__init__(m, options)
        self.hist = []
        self.mean = None
        self.cage_sd = 0.0

    def take(self, rec):
        from ..models import dynamics_kernels as K
        self.hist.append(rec[:, [K.OUT_INDEX["t"], K.OUT_INDEX["cage_speed"]]].copy())
        self.mean = rec.mean(axis=0)
        self.cage_sd = float(rec[:, K.OUT_INDEX["cage_speed"]].std())
        super().take(rec)

    def time_constant(self) -> float:
        """Time constant [s] of the cage speed's first-order lag at this point: the decay rate of the cage
        speed's deviation from its steady value after the Jones-Harris start, where the deviation is smallest
        and still measurable, tau = (t_b - t_a) / ln(d_a / d_b): t_a and t_b are the first times the deviation
        falls to d_a = 4 d_b and to d_b = max(1/20 of its start, 3 standard deviations of the cage speed over
        the last window). A first-order lag is the linearisation about the steady state, so its constant is
        the decay of small deviations, not the area of the whole relaxation, which the skid's nonlinear start
        dominates. 0 where the start deviates by less than 0.2 % or by less than d_a (no lag measurable above
        the cage speed's own fluctuation). Where the deviation does not fall that far within the run, the
        relaxation time of the whole run (the integral of the deviation over its start)."""
        h = np.concatenate(self.hist)
        t, wc = h[:, 0], h[:, 1]
        wss = self.s["cage"]
        w0 = self.w0
        d0 = abs(w0 - wss)
        if not d0 > 2e-3 * abs(wss):
            return 0.0
        db = max(0.05 * d0, 3.0 * self.cage_sd)
        da = 4.0 * db
        if da >= d0:
            return 0.0
        tt = np.concatenate([[self.t0], t])
        dev = np.abs(np.concatenate([[w0], wc]) - wss)

        def first_below(level, start=0):
            k = np.nonzero(dev[start:] <= level)[0]
            if not k.size or start + k[0] == 0:
                return None, None
            i = start + k[0]            # interpolated between the samples around the crossing
            f = (dev[i - 1] - level) / (dev[i - 1] - dev[i]) if dev[i - 1] > dev[i] else 1.0
            return tt[i - 1] + f * (tt[i] - tt[i - 1]), i
        ta, ia = first_below(da)
        tb, _ = first_below(db, ia) if ia is not None else (None, None)
        if ta is not None and tb is not None and tb > ta:
            return float((tb - ta) / math.log(da / db))
        sdev = np.concatenate([[w0 - wss], wc - wss])
        tau = float(np.sum(0.5 * (sdev[1:] + sdev[:-1]) * np.diff(tt)) / (w0 - wss))
        return tau if tau > 0 else 0.0

    def outputs(self) -> dict:
        out = super().outputs()
        out.update(steady_outputs(self.m, self.mean, self.point, self.cage_sd, self.steady, self.time_constant()))
        return out


class MapDynamicWindow(S.DynamicWindow):
    """sweep.DynamicWindow giving the map's variables (steady_outputs) of the full 16-ball model."""

    name = "map-dynamic"

    def _start(self, point, options, models=None):
        from ..models import dynamics_kernels as K
        m = _new_model(point, options)
        m.initialize(point["speed_rpm"] * S.RPM, S.point_loads(point), start=options.get("start", "jones-harris"))
        r = _MapRun(m, options)
        r.t0 = m.t
        r.point = point
        r.w0 = float(m.evaluate_point()[0][K.OUT_INDEX["cage_speed"]])
        return r


class MapTribological(S.Evaluator):
    """The quasi-static tribological model (quasistatic_tribo.py) at each point, and the dynamic model's outputs
    at its steady state (DynamicModel started there, evaluated without integration)."""

    name = "map-tribological"
    uses = MapDynamicWindow.uses
    min_speed_rpm = 10.0

    def __call__(self, point, options):
        m = _new_model(point, options)
        m.initialize(point["speed_rpm"] * S.RPM, S.point_loads(point), start="tribological")
        diag = m.evaluate_point()[0].copy()
        return steady_outputs(m, diag, point, 0.0, True, 0.0)


def level_model(level: str) -> str:
    """The sweep model name ('module:attribute') of a steady level."""
    if level not in LEVELS:
        raise BearingInputError("level", level, " | ".join(LEVELS))
    return f"{__name__}:{ {'dynamic': 'MapDynamicWindow', 'tribological': 'MapTribological'}[level] }"


def map_grid(grid: dict) -> dict:
    """The grid in the map's axis order (bearing_core.session.fidelity.MAP_AXES), checked: the required axes
    present, values increasing, speeds > 0."""
    for k in grid:
        if k not in MAP_AXES:
            raise BearingInputError("grid variable", k, "one of " + ", ".join(MAP_AXES))
    for k in REQUIRED_AXES:
        if k not in grid:
            raise BearingInputError("grid", sorted(grid), "axes " + ", ".join(REQUIRED_AXES) + " (an operating map "
                                    "needs speed, radial and axial load)")
    out = {}
    for k in MAP_AXES:
        if k in grid:
            v = [float(x) for x in grid[k]]
            if any(b <= a for a, b in zip(v, v[1:])):
                raise BearingInputError(f"grid {k}", v, "strictly increasing values")
            out[k] = v
    if out["speed_rpm"][0] <= 0:
        raise BearingInputError("grid speed_rpm", out["speed_rpm"][0], "> 0 rpm")
    if out["fx_N"][0] < 0:
        raise BearingInputError("grid fx_N", out["fx_N"][0], ">= 0 N (the radial load's magnitude; its direction "
                                "is the session's)")
    return out


def map_parameters(point: dict, options: dict) -> dict:
    """The CoSimParameters (bearing_core.session.fidelity.MAP_PARAMETERS) a map of these points is for."""
    o = _map_options(point, options)
    return {"bearing": str(point["bearing"]), "traction_model": o.traction, "lubrication": "auto",
            "friction_coefficient": o.mu, "cage_friction_coefficient": o.mu_pocket, "lubricant": o.lubricant,
            "oil": o.oil, "oil_fraction": o.oil_fraction, "churning": bool(o.churning),
            "oil_temperature": o.oil_temperature}


def build_map(grid: dict, base: dict | None = None, level: str = "dynamic", options: dict | None = None,
              command: str = "", **run):
    """Evaluate the grid (dict axis -> values; bearing_core.session.fidelity.MAP_AXES) with the steady level at
    the fixed values base (sweep variables: bearing, traction, mu, mu_cage, oil, ...) on Dask (run: the keyword
    arguments of sweep.run_sweep: cache_dir, scheduler, workers, progress, batch_size ...). Returns
    (xarray Dataset of the map, sweep DataFrame)."""
    import xarray as xr
    grid = map_grid(grid)
    base = dict(base or {})
    for k in grid:
        if k in base:
            raise BearingInputError(k, base[k], "set either as a grid axis or as a fixed value, not both")
    opts = {"window_s": 0.04, "max_time_s": 1.0, "steady_tol": 2e-3, "torque_tol": 0.02, "integrator": "auto"}
    opts.update(options or {})
    if level != "dynamic":
        opts = {k: v for k, v in opts.items() if k in ("integrator", "rtol", "churning", "lubricant")}
    spec = S.SweepSpec(model=level_model(level), base=base, grid=grid, options=opts)
    pts = spec.validate()
    df = S.run_sweep(spec, **run)
    dims = list(grid)
    shape = tuple(len(grid[d]) for d in dims)
    data = {}
    for name in MAP_OUTPUTS + STIFFNESS_NAMES + (MAP_FATIGUE_RATE, "skid_class"):
        col = df[name].to_numpy(dtype=float) if name in df.columns else np.full(len(df), np.nan)
        col = np.where(df["status"].to_numpy() == "ok", col, np.nan)
        data[name] = (dims, col.reshape(shape))
    coords = {d: np.asarray(grid[d], dtype=float) for d in dims}
    ds = xr.Dataset(data, coords=coords)
    g = S.resolve_geometry(pts[0])
    params = map_parameters(pts[0], opts)
    nfail = int((df["status"] != "ok").sum())
    ds.attrs.update(
        title="bearing operating map (fidelity 'map')", bearing=g.name, bearing_source=str(pts[0]["bearing"]),
        oil=params["oil"] or params["lubricant"], traction=params["traction_model"], level=level,
        code_version=S.code_version(), grid=json.dumps(grid), base=json.dumps(base, default=str),
        options=json.dumps(opts, default=str), parameters=json.dumps(params),
        created=datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        points=len(df), failed_points=nfail, unsteady_points=int(np.sum(df.get("steady", 1) == 0)),
        command=command, units="SI (rad/s, N, N m, m, rad, W, Pa, s); axes: speed_rpm [rpm], fx_N fy_N fz_N [N], "
                               "my_Nm [N m], oil_temperature_C [degC]")
    for name in MAP_OUTPUTS:
        ds[name].attrs["description"] = "steady value (window mean of the last window)"
    ds[MAP_FATIGUE_RATE].attrs.update(units="1/s", description="Palmgren-Miner damage rate 1 / (3600 L10r_h), "
                                      "ISO/TS 16281 reference rating life at the end of the steady window")
    return ds, df


def write_map(ds, path) -> None:
    """NetCDF3 (scipy engine: no netCDF4/HDF5 library needed)."""
    ds.to_netcdf(str(path), engine="scipy")


def map_summary(ds) -> str:
    """One line: the grid, the failed and unsteady points."""
    g = json.loads(ds.attrs["grid"])
    dims = ", ".join(f"{k} {v[0]:g}-{v[-1]:g} ({len(v)})" for k, v in g.items())
    return (f"{ds.attrs['bearing']} {ds.attrs['traction']} level {ds.attrs['level']}: {dims}; "
            f"{ds.attrs['points']} points, {ds.attrs['failed_points']} failed, {ds.attrs['unsteady_points']} not steady")

