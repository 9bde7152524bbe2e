"""The 'map' fidelity level: operating maps (bearing build-map on Dask), their interpolation and lag in the
co-simulation session, range errors, the FMU at fidelity 'map' through fmpy, and the map against the dynamic
model off its grid (docs/fidelity.md)."""
import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest

from bearing_core.errors import BearingInputError
from bearing_core.session.cosim import CoSimParameters, CoSimSession, StepRejected
from bearing_core.session.fidelity import MAP_FATIGUE_RATE, MAP_OUTPUTS, MAP_STIFFNESS, SPEED_SCALED, GROSS_SKID_SLIP

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))
RPM = math.pi / 30.0
AXES = {"speed_rpm": [1000.0, 2000.0, 4000.0], "fx_N": [0.0, 1000.0, 2000.0], "fz_N": [1000.0, 3000.0]}
PARAMS = {"bearing": "7218B", "traction_model": "lubricated", "lubrication": "auto", "friction_coefficient": 0.1,
          "cage_friction_coefficient": 0.1, "lubricant": "generic-mineral-oil", "oil": "", "oil_fraction": 0.0,
          "churning": False, "oil_temperature": 313.15}
TAU = 0.01


def field(name, n, fx, fz):
    """A multilinear field per output (speed-scaled outputs: per rpm, times n), which the map's interpolation
    reproduces exactly; distinct coefficients per output."""
    k = MAP_OUTPUTS.index(name) + 1
    if name == "cage_time_constant":
        return TAU + 0 * n
    if name == "steady":
        return 1.0 + 0 * n
    if name == "cage_speed_cv":
        return 1e-4 + 0 * n
    if name == "cage_speed":      # slip 1 - cage / pure: gross skidding at light axial load (fz 1000 N)
        return n * RPM * np.where(fz < 2000.0, 0.25, 0.43) + 0 * fx
    if name in ("cage_speed_pure_rolling_outer", "cage_speed_eq26"):
        return n * RPM * (0.44 + 1e-6 * fx + 2e-7 * fz)
    base = 0.1 * k + 1e-4 * k * fx / 1000.0 * (1.0 + fz / 5000.0) + 3e-5 * k * fz / 1000.0
    if name in SPEED_SCALED:
        return n * base
    return base * (1.0 + n / 5000.0)


def rate_field(n, fx, fz):
    """The fatigue damage rate [1/s] of the synthetic map: proportional to the speed n [rpm] at a load (as bearing
    build-map writes it), multilinear per unit speed, so that the interpolation reproduces it exactly."""
    return n * 1e-12 * (1.0 + fx / 1000.0 + 0.5 * fz / 1000.0)


def synthetic_map(path, fz_linear=False, fatigue_rate=True):
    import xarray as xr
    n, fx, fz = np.meshgrid(*[np.array(v) for v in AXES.values()], indexing="ij")
    data = {nm: (list(AXES), np.asarray(field(nm, n, fx, fz), dtype=float) * np.ones(n.shape)) for nm in MAP_OUTPUTS}
    if fatigue_rate:
        data[MAP_FATIGUE_RATE] = (list(AXES), rate_field(n, fx, fz))
    for k, nm in enumerate(MAP_STIFFNESS):   # the stiffness variables (map_kernels.map_stiffness): distinct fields
        i, j = divmod(k, 5)
        scale = 1e8 if i == j else 1e7 * (1 + k % 3)
        data[nm] = (list(AXES), scale * (1.0 + (k + 1) * 1e-4 * fx / 1000.0 + 2e-5 * (k + 2) * fz / 1000.0 + n / 2e4))
    ds = xr.Dataset(data, coords={k: np.array(v) for k, v in AXES.items()})
    ds.attrs.update(bearing="7218B", level="synthetic", parameters=json.dumps(PARAMS), grid=json.dumps(AXES))
    ds.to_netcdf(str(path), engine="scipy")
    return str(path)


@pytest.fixture(scope="module")
def smap(tmp_path_factory):
    return synthetic_map(tmp_path_factory.mktemp("maps") / "synthetic.nc")


def session(path, **kw):
    return CoSimSession(CoSimParameters(fidelity="map", map_file=path, **kw))


def inputs(rpm, fx, fz, **kw):
    return dict({"shaft_speed": rpm * RPM, "Fx": fx, "Fz": fz}, **kw)


def expected(name, rpm, fx, fz):
    return float(field(name, np.array(rpm), np.array(fx), np.array(fz)))


def test_interpolation_reproduces_multilinear_fields_off_the_grid(smap):
    """Off-grid points: every output the map holds comes back exactly (multilinear interpolation, speed-scaled
    outputs per unit speed); derived ratios follow; outputs the level does not give hold 0; nothing is NaN."""
    s = session(smap)
    rng = np.random.default_rng(7)
    for _ in range(5):
        rpm, fx, fz = rng.uniform(1000, 4000), rng.uniform(0, 2000), rng.uniform(1000, 3000)
        s.initialize(0.0, inputs(rpm, fx, fz))
        o = s.outputs
        for nm in ("friction_torque", "heat_flux_total", "heat_flux_pocket", "reaction_Fz", "alpha_o_mean",
                   "film_parameter_min", "cage_speed_pure_rolling_outer", "ir_z", "max_contact_pressure"):
            assert o[nm] == pytest.approx(expected(nm, rpm, fx, fz), rel=1e-12), nm
        assert o["instantaneous_friction_torque"] == o["friction_torque"]
        assert o["cage_shaft_ratio"] == pytest.approx(o["cage_speed"] / (rpm * RPM), rel=1e-12)
        slip = 1.0 - o["cage_speed"] / o["cage_speed_pure_rolling_outer"]
        assert o["cage_slip_ratio"] == pytest.approx(slip, rel=1e-12)
        assert o["skid_state"] == (1 if slip > 0.01 else (-1 if slip < -0.01 else 0))
        assert o["ball0_omega_r"] == 0.0 and o["ir_ax"] == 0.0 and o["temperature_oil"] == 313.15
        assert np.all(np.isfinite(s.values))


def test_radial_load_direction_turns_the_vector_outputs(smap):
    """A map over Fx (no Fy axis) reads a load (Fx, Fy) at its radial magnitude; the x-y outputs turn with it."""
    a, b = session(smap), session(smap)
    a.initialize(0.0, inputs(2500, 1200.0, 2000.0))
    b.initialize(0.0, inputs(2500, 0.0, 2000.0, Fy=1200.0))
    oa, ob = a.outputs, b.outputs
    assert ob["reaction_Fy"] == pytest.approx(oa["reaction_Fx"], rel=1e-12)
    assert ob["reaction_Fx"] == pytest.approx(-oa["reaction_Fy"], rel=1e-12, abs=1e-12)
    assert ob["ir_y"] == pytest.approx(oa["ir_x"], rel=1e-12)
    assert ob["friction_torque"] == oa["friction_torque"] and ob["cage_speed"] == oa["cage_speed"]


def test_cage_speed_follows_a_first_order_lag(smap):
    """A speed step: the cage speed moves towards its new steady value by exp(-h / tau) per step (inputs held);
    the torque is the new steady value plus, in the step of the speed change, the work that brings balls and
    cage to the new speed, I c^2 (w1^2 - w0^2) / 2 (c the steady cage/shaft ratio, I the geometric rotating
    inertia, contact.kinematics.rotating_inertia), over the step and the shaft speed: summed, the kinetic
    energy gained; held, the steady torque; a coast-down gives the energy back; state get/set restores the
    lag."""
    from bearing_core import load_bearing
    from bearing_core.contact.kinematics import rotating_inertia
    g = load_bearing("7218B")
    inertia = float(rotating_inertia(g.Z, g.ball_mass, g.ball_inertia, g.cage.inertia, g.alpha0, g.D, g.dm))
    s = session(smap)
    s.initialize(0.0, inputs(2000, 500.0, 2500.0))
    w0 = s.outputs["cage_speed"]
    assert s.outputs["friction_torque"] == pytest.approx(expected("friction_torque", 2000, 500.0, 2500.0), rel=1e-12)
    st = s.get_state()
    h = 2e-3
    s.step(0.0, h, inputs(3000, 500.0, 2500.0))
    ref = session(smap)
    ref.initialize(0.0, inputs(3000, 500.0, 2500.0))
    wss = ref.outputs["cage_speed"]     # the steady value there
    assert s.outputs["cage_speed"] == pytest.approx(wss + (w0 - wss) * math.exp(-h / TAU), rel=1e-12)
    t_ss = expected("friction_torque", 3000, 500.0, 2500.0)
    assert ref.outputs["friction_torque"] == pytest.approx(t_ss, rel=1e-12)
    work = (s.outputs["friction_torque"] - t_ss) * 3000 * RPM * h
    # the synthetic map's cage/shaft ratio is the same at both speeds: the work is the kinetic energy gained
    assert work == pytest.approx(0.5 * inertia * (wss ** 2 - w0 ** 2), rel=1e-9)
    assert s.outputs["instantaneous_friction_torque"] == s.outputs["friction_torque"]
    assert s.outputs["drive_power"] - expected("drive_power", 3000, 500.0, 2500.0) == pytest.approx(work / h, rel=1e-9)
    for k in range(1, 200):
        s.step(k * h, h, inputs(3000, 500.0, 2500.0))
    assert s.outputs["cage_speed"] == pytest.approx(wss, rel=1e-6)
    assert s.outputs["friction_torque"] == pytest.approx(t_ss, rel=1e-12)
    s.set_state(st)
    assert s.t == 0.0 and s.outputs["cage_speed"] == w0
    # a coast-down from 2000 rpm: the kinetic energy of balls and cage drives the bearing, the drive torque drops
    s.step(0.0, h, inputs(1000, 500.0, 2500.0))
    w2 = session_steady_cage(smap, 1000)
    back = (s.outputs["friction_torque"] - expected("friction_torque", 1000, 500.0, 2500.0)) * 1000 * RPM * h
    assert back == pytest.approx(0.5 * inertia * (w2 ** 2 - w0 ** 2), rel=1e-9) and back < 0.0


def session_steady_cage(path, rpm):
    r = session(path)
    r.initialize(0.0, inputs(rpm, 500.0, 2500.0))
    return r.outputs["cage_speed"]


def test_map_lag_constant_is_the_decay_of_small_deviations():
    """The map's cage lag constant (build_map._MapRun.time_constant) from a relaxation history: a pure exponential
    gives its own constant; a relaxation whose large start is faster or slower than its small-deviation decay
    gives the decay's constant, not the area of the whole relaxation; a deviation within the cage speed's own
    fluctuation gives 0; a start within 0.2 % of the steady value gives 0."""
    from bearing_core.maps.build_map import _MapRun

    def run(dev_fn, d0, sd=0.0, wss=400.0, dt=1e-5, t_end=0.2):
        r = object.__new__(_MapRun)
        t = np.arange(1, int(round(t_end / dt)) + 1) * dt
        r.hist = [np.column_stack([t, wss + dev_fn(t)])]
        r.s, r.w0, r.t0, r.cage_sd = {"cage": wss}, wss + d0, 0.0, sd
        return r.time_constant()

    tau = 4e-3
    assert run(lambda t: 20.0 * np.exp(-t / tau), 20.0) == pytest.approx(tau, rel=1e-3)
    assert run(lambda t: -20.0 * np.exp(-t / tau), -20.0) == pytest.approx(tau, rel=1e-3)
    # a fast drop of 3/4 within 0.2 ms, then the 4 ms decay: the decay's constant (the area would give ~1.0 ms)
    two = lambda t: 15.0 * np.exp(-t / 5e-5) + 5.0 * np.exp(-t / tau)
    assert run(two, 20.0) == pytest.approx(tau, rel=1e-3)
    # a slow start (a plateau of 10 ms), then the decay: the decay's constant (the area would give ~14 ms)
    slow = lambda t: np.where(t < 0.01, 20.0, 20.0 * np.exp(-(t - 0.01) / tau))
    assert run(slow, 20.0) == pytest.approx(tau, rel=1e-3)
    assert run(lambda t: 3.0 * np.exp(-t / tau), 3.0, sd=1.0) == 0.0       # within 3 standard deviations
    assert run(lambda t: 10.0 * np.exp(-t / tau), 10.0, sd=1.0) == 0.0     # not 4 x 3 standard deviations
    assert run(lambda t: 20.0 * np.exp(-t / tau), 20.0, sd=1.0) == pytest.approx(tau, rel=1e-3)
    assert run(lambda t: 0.5 * np.exp(-t / tau), 0.5) == 0.0               # start within 0.2 % of 400


def test_out_of_range_inputs_are_refused_naming_input_and_range(smap):
    s = session(smap)
    with pytest.raises(BearingInputError, match=r"shaft_speed.*1000-4000 rpm.*never extrapolates"):
        s.initialize(0.0, inputs(5000, 500.0, 2500.0))
    s.initialize(0.0, inputs(2000, 500.0, 2500.0))
    before = s.values.copy()
    with pytest.raises(StepRejected, match=r"radial load hypot\(Fx, Fy\) = 2500.*0 N <= value <= 2000 N"):
        s.step(0.0, 1e-3, inputs(2000, 1500.0, 2500.0, Fy=2000.0))
    with pytest.raises(StepRejected, match=r"Fz = 500.*1000 N <= value <= 3000 N"):
        s.step(0.0, 1e-3, inputs(2000, 500.0, 500.0))
    with pytest.raises(StepRejected, match=r"Mx = 5.*0 N.m at fidelity 'map'"):
        s.step(0.0, 1e-3, inputs(2000, 500.0, 2500.0, Mx=5.0))
    with pytest.raises(StepRejected, match="outer_ring_speed"):
        s.step(0.0, 1e-3, inputs(2000, 500.0, 2500.0, outer_ring_speed=10.0))
    assert np.array_equal(s.values, before) and s.t == 0.0      # a refused step leaves the state as it was
    s.step(0.0, 1e-3, inputs(2000, 500.0, 2500.0))


def test_one_call_step_equals_the_checked_path(smap):
    """The map level's one-call step kernel (query, interpolation, outputs and lag: map_kernels.map_step) gives
    the outputs, cage lag, warnings and refusals of the checked path (MapLevel.query, steady_into and
    steady_level_outputs from Python) bit for bit, over random inputs in and around the map's range, radial
    loads in any direction included."""
    rng = np.random.default_rng(7)
    fast, checked = session(smap), session(smap)
    checked.steady._fast = None
    assert fast.steady._fast is not None
    for s in (fast, checked):
        s.initialize(0.0, inputs(2000, 500.0, 2500.0))
    t, refused = 0.0, 0
    for k in range(300):
        rpm, fz, fr, ang = rng.uniform(900, 4100), rng.uniform(900, 3100), rng.uniform(0, 2100), rng.uniform(0, 6.3)
        u = inputs(rpm, fr * math.cos(ang), fz, Fy=fr * math.sin(ang))
        if k % 50 == 7:
            u["Mx"] = 1.0
        if k % 50 == 11:
            u["Fz"] = float("nan")
        res = []
        for s in (fast, checked):
            try:
                s.step(t, 1e-3, u)
                res.append(None)
            except StepRejected as e:
                res.append(str(e))
        assert res[0] == res[1]
        refused += res[0] is not None
        assert np.array_equal(fast.values, checked.values) and fast.steady.wc == checked.steady.wc
        if res[0] is None:
            t += 1e-3
    assert fast.warnings == checked.warnings and len(fast.warnings) > 0
    assert 10 < refused < 200
    from bearing_core.session.output_map import OUTPUT_INDEX
    assert fast.values[OUTPUT_INDEX["stiffness[1,1]"]] > 0.0     # the turned stiffness outputs were compared too


def test_parameters_the_map_was_not_built_for_are_refused(smap):
    with pytest.raises(BearingInputError, match=r"traction_model = 'kalker'.*'lubricated', the value the operating map"):
        session(smap, traction_model="kalker")
    with pytest.raises(BearingInputError, match=r"coupling = 'displacement'.*forces of a prescribed ring pose"):
        session(smap, coupling="displacement")
    with pytest.raises(BearingInputError, match="oil_temperature"):
        session(smap, oil_temperature=350.0)
    with pytest.raises(BearingInputError, match="fidelity = 'fast'"):
        CoSimSession(CoSimParameters(fidelity="fast"))
    with pytest.raises(BearingInputError, match="map_file"):
        CoSimSession(CoSimParameters(fidelity="map"))


def test_warning_when_entering_gross_skidding(smap):
    """The synthetic map skids grossly (slip > GROSS_SKID_SLIP) at Fz 1000 N: entering a cell next to it logs one
    warning, staying in it none, a new entry after leaving another."""
    assert 1.0 - 0.25 / 0.44 > GROSS_SKID_SLIP > 1.0 - 0.43 / 0.44
    s = session(smap)
    s.initialize(0.0, inputs(2000, 500.0, 3000.0))
    assert s.warnings == []
    s.step(0.0, 1e-3, inputs(2000, 500.0, 2000.0))
    s.step(1e-3, 1e-3, inputs(2000, 500.0, 1500.0))
    assert len(s.warnings) == 1 and "gross skidding" in s.warnings[0]
    s.step(2e-3, 1e-3, inputs(2000, 500.0, 3000.0))
    s.step(3e-3, 1e-3, inputs(2000, 500.0, 1200.0))
    assert len(s.warnings) == 2


def test_build_map_on_dask_tiny_grid_resumes_from_cache(tmp_path):
    """bearing build-map's library on a local Dask cluster (tribological level, 2 x 2 x 2 grid): provenance,
    every map variable finite, the session reads it; a second build takes every point from the cache."""
    from distributed import Client, LocalCluster
    from bearing_core.maps.build_map import build_map, write_map
    grid = {"speed_rpm": [2000.0, 3000.0], "fx_N": [0.0, 800.0], "fz_N": [2000.0, 3000.0]}
    # a worker in this process (the kernels loaded once); the same tasks as on worker processes
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=":0") as lc, \
            Client(lc) as cl:
        ds, df = build_map(grid, {"bearing": "7218B"}, "tribological", cache_dir=tmp_path / "cache", client=cl,
                           progress=False)
        assert df.attrs["computed"] == 8 and (df["status"] == "ok").all(), df["error"].tolist()
        _, df2 = build_map(grid, {"bearing": "7218B"}, "tribological", cache_dir=tmp_path / "cache", client=cl,
                           progress=False)
        assert df2.attrs["computed"] == 0
    path = tmp_path / "tiny.nc"
    write_map(ds, path)
    for k in ("bearing", "oil", "level", "code_version", "grid", "parameters"):
        assert ds.attrs[k] not in ("", None), k
    assert ds.attrs["level"] == "tribological" and json.loads(ds.attrs["grid"]) == grid
    for nm in MAP_OUTPUTS:
        assert np.all(np.isfinite(ds[nm].values)), nm
    s = session(str(path))
    s.initialize(0.0, inputs(2500, 400.0, 2500.0))
    o = s.outputs
    assert 0.3 < o["cage_shaft_ratio"] < 0.5 and o["friction_torque"] > 0 and np.all(np.isfinite(s.values))
    # the tribological level's outputs are those of its grid points at the corners
    s.initialize(0.0, inputs(3000, 800.0, 3000.0))
    assert s.outputs["friction_torque"] == pytest.approx(float(ds["friction_torque"].values[1, 1, 1]), rel=1e-12)
    # the fatigue damage rate of every grid point (1 / (3600 L10r_h), speed-proportional at a load) gives the life
    rate = ds["fatigue_damage_rate"].values
    assert np.all(np.isfinite(rate)) and np.all(rate > 0.0)
    assert s.outputs["life_L10r_h"] == pytest.approx(1.0 / (3600.0 * rate[1, 1, 1]), rel=1e-12)
    assert 1e2 < s.outputs["life_L10r_h"] < 1e9


def test_fmu_at_fidelity_map_through_fmpy(smap, tmp_path):
    """The FMU built with an embedded map (bearing build-fmu --map) at fidelity 'map' (set by its Enumeration):
    the session's values, an out-of-range input refused with the reason in the log, the next step good, and the
    warning of a region where the map does not hold in the log."""
    from bearing_cosim.fmu_build import build
    from test_fmu import drive
    path = build(tmp_path / "dist", map_file=smap)
    cache = tmp_path / "fmu_cache"
    cache.mkdir()
    names = ["cage_speed", "friction_torque", "heat_flux_total", "reaction_Fx", "ball0_omega_r"]
    u = inputs(2500, 700.0, 2200.0)
    bad = inputs(6000, 700.0, 2200.0)
    spec = {"params": {"fidelity_choice": "map"}, "start_inputs": u, "steps": [[1e-3, u]] * 5 + [[1e-3, bad], [1e-3, u]],
            "outputs": names}
    res = drive({"path": str(path), "cache": str(cache)}, spec, tmp_path)
    assert res["init_error"] is None, res["log"][-2000:]
    s = session(smap)
    s.initialize(0.0, u)
    rows = res["rows"]
    assert [r["status"] for r in rows[:5]] == [0] * 5
    for k, nm in enumerate(names):
        assert rows[4]["values"][k] == pytest.approx(s.outputs[nm], rel=1e-12), nm
    assert rows[5]["status"] != 0 and "shaft_speed" in res["log"] and "never extrapolates" in res["log"]
    assert rows[6]["status"] == 0
    # the synthetic map skids grossly at Fz 1000 N, a corner of this operating point's cell: a logged warning
    assert "gross skidding" in res["log"]


SHIPPED = {"oil": ROOT / "maps" / "7218B_oil.nc"}


@pytest.mark.skipif(not SHIPPED["oil"].is_file(), reason="the shipped 7218B map is not in this checkout")
def test_shipped_map_against_the_dynamic_model_off_the_grid():
    """Two operating points between the shipped map's grid points (chosen before any comparison, away from the
    grid lines): the map's steady outputs against the dynamic model's window means there (the map's own
    evaluator and options). Cage speed 1 %, reactions 0.5 % of the load, mean contact angles 0.5 deg (the
    tolerances of docs/fidelity.md). Friction torque and heat 20 %: under combined load with a free inner ring
    the dynamic model's torque wanders slowly (0.25 s means between 1.18 and 1.71 N m over 3.4 s at 2908 rpm,
    Fx 1 kN, Fz 3 kN, docs/fidelity.md), so a 0.04 s window mean, the map's and the reference's, is one sample
    of it; 5 % is not a property the reference itself has."""
    import xarray as xr
    from bearing_core.maps import sweep as S
    from bearing_core.maps.build_map import MapDynamicWindow
    path = str(SHIPPED["oil"])
    with xr.open_dataset(path, engine="scipy") as ds:
        attrs = dict(ds.attrs)
    opts = json.loads(attrs["options"])
    base = {k: v.default for k, v in S.VARIABLES.items()}
    base.update(json.loads(attrs["base"]))
    s = session(path)
    ev = MapDynamicWindow()
    for rpm, fx, fz in ((3700.0, 1400.0, 3100.0), (8200.0, 2300.0, 6400.0)):
        r = ev(dict(base, speed_rpm=rpm, fx_N=fx, fz_N=fz), opts)
        s.initialize(0.0, inputs(rpm, fx, fz))
        o = s.outputs
        assert o["cage_speed"] == pytest.approx(r["cage_speed"], rel=0.01)
        assert o["friction_torque"] == pytest.approx(r["friction_torque"], rel=0.2)
        assert o["heat_flux_total"] == pytest.approx(r["heat_flux_total"], rel=0.2)
        assert math.hypot(o["reaction_Fx"] - r["reaction_Fx"], o["reaction_Fz"] - r["reaction_Fz"]) <= \
            0.005 * math.hypot(fx, fz)
        for a in ("alpha_i_mean", "alpha_o_mean"):
            assert abs(math.degrees(o[a] - r[a])) <= 0.5, a


def test_oil_temperature_axis_is_read_at_the_parameter(tmp_path):
    """A map over oil temperature is read at the session's oil_temperature (linear between its grid values);
    a temperature outside its range is refused naming the parameter and the range."""
    import xarray as xr
    ax = dict(AXES, oil_temperature_C=[30.0, 50.0])
    n, fx, fz, T = np.meshgrid(*[np.array(v) for v in ax.values()], indexing="ij")
    data = {nm: (list(ax), np.asarray(field(nm, n, fx, fz), dtype=float) * (1.0 + 0.01 * (T - 30.0)))
            for nm in MAP_OUTPUTS}
    ds = xr.Dataset(data, coords={k: np.array(v) for k, v in ax.items()})
    ds.attrs.update(parameters=json.dumps(PARAMS))
    path = str(tmp_path / "oil_T.nc")
    ds.to_netcdf(path, engine="scipy")
    s = session(path, oil_temperature=318.15)           # 45 degC
    s.initialize(0.0, inputs(2500, 700.0, 2200.0))
    assert s.outputs["friction_torque"] == pytest.approx(expected("friction_torque", 2500, 700.0, 2200.0) * 1.15,
                                                         rel=1e-12)
    assert s.outputs["temperature_oil"] == 318.15
    with pytest.raises(BearingInputError, match=r"oil_temperature = 340.*303.15 K <= value <= 323.15 K"):
        session(path, oil_temperature=340.0)


def test_embedded_map_shares_the_code_folder_but_not_the_guid(smap, tmp_path):
    """An FMU with an embedded map and one without: the same code hash (the model process's code copy and its
    compiled kernels are shared; the copy leaves the map out), different GUIDs; the map sits at
    resources/code/operating_map.nc, and the slave finds it in the FMU's resources folder."""
    import zipfile
    from bearing_cosim.fmu_build import build
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "bearing_cosim" / "fmu_src"))
    from bearing_fmu import embedded_map
    plain = build(tmp_path / "plain")
    with_map = build(tmp_path / "map", map_file=smap)
    cfg, guid = {}, {}
    for tag, path in (("plain", plain), ("map", with_map)):
        with zipfile.ZipFile(path) as z:
            cfg[tag] = json.loads(z.read("resources/model.json"))
            guid[tag] = cfg[tag]["guid"]
            if tag == "map":
                assert z.read("resources/code/operating_map.nc") == Path(smap).read_bytes()
                z.extractall(tmp_path / "unz")
    assert cfg["plain"]["code_hash"] == cfg["map"]["code_hash"]
    assert guid["plain"] != guid["map"]
    assert cfg["map"]["data_files"] == ["operating_map.nc"] and cfg["plain"]["data_files"] == []
    assert embedded_map(str(tmp_path / "unz" / "resources")) == str(tmp_path / "unz" / "resources" / "code" /
                                                                     "operating_map.nc")
