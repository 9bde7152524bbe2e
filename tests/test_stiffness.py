"""The stiffness outputs stiffness[i,j] of every fidelity level (K = d(load)/d(pose) = -d(reaction)/d(pose); rows Fx,
Fy, Fz, Mx, My, columns dx, dy, dz, tx, ty) against central finite differences of what they differentiate, and the
FMU's fmi2GetDirectionalDerivative against them (docs/fidelity.md "Stiffness", docs/fmu.md "Directional
derivatives")."""
import math
import os
import sys
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))
from test_fmu import fmu  # noqa: E402,F401  (session fixture: the FMU built once, its kernel cache shared)

RPM = math.pi / 30
# the quasi-static level solves with the cage kernels, which compile for ~2 CPU minutes: as in
# tests/test_fidelity_quasistatic.py, those tests run with BEARING_TEST_QS_CAGE=1
needs_solves = pytest.mark.skipif(os.environ.get("BEARING_TEST_QS_CAGE") != "1",
                                  reason="solves with the quasi-static cage kernels: set BEARING_TEST_QS_CAGE=1 (they "
                                         "compile for ~2 CPU minutes)")
POSE = ("dx", "dy", "dz", "tx", "ty")
LOADS = ("Fx", "Fy", "Fz", "Mx", "My")
REACTIONS = tuple("reaction_" + n for n in LOADS)
IR = ("ir_x", "ir_y", "ir_z", "ir_tx", "ir_ty")


def _index():
    from bearing_core.session.output_map import OUTPUT_INDEX
    return OUTPUT_INDEX


def _K(values):
    from bearing_core.session.cosim_spec import STIFFNESS_NAMES
    ix = _index()
    return np.array([values[ix[n]] for n in STIFFNESS_NAMES]).reshape(5, 5)


def _rel(A, K):
    """Largest |A - K| of an entry on the entry's own scale sqrt(|K_ii K_jj|) (the units of entry ij)."""
    d = np.sqrt(np.abs(np.diag(K)))
    return float(np.max(np.abs(A - K) / np.outer(d, d)))


def test_spec_names_units():
    from bearing_core.session.cosim_spec import LIFE_NAMES, OUTPUT_NAMES, OUTPUT_SPEC, STIFFNESS_NAMES
    assert STIFFNESS_NAMES[0] == "stiffness[1,1]" and STIFFNESS_NAMES[-1] == "stiffness[5,5]"
    # appended at the end, followed only by the fatigue outputs appended after them
    assert OUTPUT_NAMES[-27:-2] == STIFFNESS_NAMES and OUTPUT_NAMES[-2:] == LIFE_NAMES
    units = {n: u for n, u, _ in OUTPUT_SPEC}
    assert units["stiffness[1,1]"] == "N/m" and units["stiffness[2,4]"] == "N/rad"
    assert units["stiffness[4,3]"] == "N.m/m" and units["stiffness[5,5]"] == "N.m/rad"
    from bearing_core.maps.build_map import STIFFNESS_NAMES as BUILT
    from bearing_core.session.fidelity import MAP_STIFFNESS
    assert BUILT == MAP_STIFFNESS             # what bearing build-map writes is what the map level reads


# ---- quasi-static level --------------------------------------------------------------------------------------------

def _qs_disp_session():
    from bearing_core.session.cosim import CoSimParameters, CoSimSession
    pose = {"dx": 1.22e-4, "dy": 1.6e-5, "dz": -9.4e-6, "tx": -3.0e-4, "ty": 2.29e-3}   # ~ Fx 1 kN, Fz 3 kN
    s = CoSimSession(CoSimParameters(bearing="7218B", fidelity="quasi-static", coupling="displacement",
                                     oil_fraction=0.01))
    inp = {"shaft_speed": 3000 * RPM, **pose}
    s.initialize(0.0, inp)
    return s, inp


@pytest.fixture(scope="module")
def qs_disp():
    return _qs_disp_session()


def _fd_reactions(s, inp, t, h=(1e-9, 1e-9, 1e-9, 1e-8, 1e-8)):
    ix = _index()
    F = np.zeros((5, 5))
    for j, n in enumerate(POSE):
        r = []
        for sg in (1.0, -1.0):
            q = dict(inp)
            q[n] += sg * h[j]
            s.step(t, 1e-3, q)
            t += 1e-3
            r.append(np.array([s.values[ix[k]] for k in REACTIONS]))
        F[:, j] = -(r[0] - r[1]) / (2.0 * h[j])
    return F, t


@needs_solves
def test_quasistatic_stiffness_is_the_derivative_of_its_reactions(qs_disp):
    """Displacement coupling: central differences of the level's reactions in the ring pose give its stiffness
    outputs (<= 1e-4), at the first solution and after the pose moved far enough for a re-solve."""
    s, inp = qs_disp
    K0 = _K(s.values)
    assert np.all(np.diag(K0) > 0)                         # restoring: K = -d reaction / d pose
    assert 1e8 < K0[0, 0] < 5e8 and 1e8 < K0[2, 2] < 5e8     # N/m, a 7218B under 1 kN radial, 3 kN axial
    F, t = _fd_reactions(s, inp, 0.0)
    assert _rel(F, K0) <= 1e-4, (F, K0)
    # a pose 3 um further out: the level re-solves and its stiffness follows
    inp2 = dict(inp, dx=inp["dx"] + 3e-6)
    s.step(t, 1e-3, inp2)
    K1 = _K(s.values)
    assert abs(K1[0, 0] / K0[0, 0] - 1.0) > 1e-3            # a new solution's stiffness
    F1, _ = _fd_reactions(s, inp2, t + 1e-3)
    assert _rel(F1, K1) <= 1e-4, (F1, K1)


@needs_solves
def test_quasistatic_stiffness_is_the_tangent_of_its_solutions():
    """At a solution with fresh derivatives (the level's first): its stiffness against central differences of
    fresh solves of the whole bearing (balls and cage re-equilibrated, warm from the level's solution) at
    +-1e-7 m / +-1e-6 rad of the pose, within 5e-3 of an entry's scale (measured 1.5e-3; the solves' residual
    floor bounds it)."""
    from bearing_core.models.quasistatic_cage import OUTPUT_NAMES as QN
    s, _ = _qs_disp_session()
    lvl = s.steady.level
    res = lvl.tracker.res
    K = lvl.stiffness(res)
    p0 = res.inputs()
    i = QN.index("Fx")
    F = np.zeros((5, 5))
    for j, h in enumerate((1e-7, 1e-7, 1e-7, 1e-6, 1e-6)):
        out = []
        for sg in (1.0, -1.0):
            p = p0.copy()
            p[1 + j] += sg * h
            r = lvl.model.solve(p[0], displacement=p[1:6], T_oil=p[6], start=res, sensitivity=False)
            out.append(r.outputs[i:i + 5])
        F[:, j] = -(out[0] - out[1]) / (2.0 * h)
    assert _rel(F, K) <= 5e-3, (F, K)


@needs_solves
def test_quasistatic_load_coupling_stiffness_inverts_the_compliance():
    """Load coupling: the ring pose follows the loads; central differences of ir_x..ir_ty in Fx..My (the
    compliance) times the stiffness outputs is the identity (<= 1e-4)."""
    from bearing_core.session.cosim import CoSimParameters, CoSimSession
    s = CoSimSession(CoSimParameters(bearing="7218B", fidelity="quasi-static", oil_fraction=0.01))
    inp = {"shaft_speed": 3000 * RPM, "Fx": 1000.0, "Fz": 3000.0}
    s.initialize(0.0, inp)
    K = _K(s.values)
    ix = _index()
    C = np.zeros((5, 5))
    t = 0.0
    for j, (n, h) in enumerate(zip(LOADS, (0.01, 0.01, 0.01, 1e-3, 1e-3))):
        r = []
        for sg in (1.0, -1.0):
            q = dict(inp)
            q[n] = q.get(n, 0.0) + sg * h
            s.step(t, 1e-3, q)
            t += 1e-3
            r.append(np.array([s.values[ix[k]] for k in IR]))
        C[:, j] = (r[0] - r[1]) / (2.0 * h)
    assert np.max(np.abs(K @ C - np.eye(5))) <= 1e-4, K @ C


# ---- map level ------------------------------------------------------------------------------------------------------

def _map_session(path, angle, fr=1600.0, fz=3500.0, rpm=2800.0):
    from bearing_core.session.cosim import CoSimParameters, CoSimSession
    s = CoSimSession(CoSimParameters(fidelity="map", map_file=str(path)))
    inp = {"shaft_speed": rpm * RPM, "Fx": fr * math.cos(angle), "Fy": fr * math.sin(angle), "Fz": fz}
    s.initialize(0.0, inp)
    return s, inp


def test_map_stiffness_turned_with_the_load_against_jones_harris_differences():
    """At a grid point of the shipped map (2800 rpm, radial 1600 N, Fz 3500 N) under a radial load turned by two
    ball pitches (the same ball set seen turned): the map level's turned stiffness against central differences of
    the Jones-Harris reactions at that load's equilibrium pose (the model the map's stiffness is of) <= 1e-3;
    the one-call step and the checked path give the same matrix."""
    from bearing_core.bearing.geometry import load_preset
    from bearing_core.models.quasistatic import QuasiStaticModel, quasistatic_model
    g = load_preset("7218B")
    angle = 2 * (2 * math.pi / g.Z)
    s, inp = _map_session(ROOT / "maps" / "7218B_oil.nc", angle)
    K_init = _K(s.values)                        # the checked path (initialize)
    s.step(0.0, 1e-3, inp)                       # the one-call step (map_step_stiffness)
    K = _K(s.values)
    assert np.array_equal(K, K_init)
    w = inp["shaft_speed"]
    u = np.asarray(QuasiStaticModel(g, "outer").solve(w, (inp["Fx"], inp["Fy"], inp["Fz"], 0.0, 0.0),
                                                       stiffness=False).u, dtype=float)
    m = quasistatic_model(g, "outer")
    F = np.zeros((5, 5))
    for j, h in enumerate((1e-7, 1e-7, 1e-7, 1e-6, 1e-6)):
        up, um = u.copy(), u.copy()
        up[j] += h
        um[j] -= h
        F[:, j] = -(np.asarray(m.residual(up, w)[0]) - np.asarray(m.residual(um, w)[0])) / (2.0 * h)
    assert _rel(F, K) <= 1e-3, (F, K)
    # the turn matters: the unturned matrix (the map's own, load along x) is far off
    s0, _ = _map_session(ROOT / "maps" / "7218B_oil.nc", 0.0)
    assert _rel(F, _K(s0.values)) > 0.1


def test_map_without_stiffness_variables(tmp_path):
    """An operating map written before build-map wrote the stiffness: the level runs, its stiffness outputs hold 0,
    and a warning names the map and what to do."""
    from scipy.io import netcdf_file
    src = netcdf_file(str(ROOT / "maps" / "7218B_oil.nc"), "r", mmap=False)
    path = tmp_path / "old.nc"
    dst = netcdf_file(str(path), "w")
    for k, v in src._attributes.items():
        setattr(dst, k, v)
    for d, n in src.dimensions.items():
        dst.createDimension(d, n)
    for k, v in src.variables.items():
        if k.startswith("stiffness_"):
            continue
        nv = dst.createVariable(k, v.data.dtype, v.dimensions)
        nv[...] = v.data
        for a, val in v._attributes.items():
            setattr(nv, a, val)
    dst.close()
    src.close()
    s, inp = _map_session(path, 0.3)
    assert np.all(_K(s.values) == 0.0)
    assert any("no stiffness variables" in w and "bearing build-map" in w for w in s.warnings), s.warnings
    s.step(0.0, 1e-3, inp)
    assert np.all(_K(s.values) == 0.0)


# ---- dynamic level ---------------------------------------------------------------------------------------------------

def test_dynamic_tangent_stiffness():
    """The dynamic level's stiffness at a communication point (forward differences of the contact forces, balls
    held) against central differences of the same right-hand side (<= 2e-3 of an entry's scale), and stiffer
    than the Jones-Harris stiffness with its balls re-equilibrated (contacts in series)."""
    from bearing_core.session.cosim import CoSimParameters, CoSimSession
    s = CoSimSession(CoSimParameters(bearing="7218B"))
    inp = {"shaft_speed": 3000 * RPM, "Fx": 1000.0, "Fz": 3000.0}
    s.initialize(0.0, inp)
    s.step(0.0, 1e-3, inp)
    K = _K(s.values)
    Kc = s._tangent(s.model).copy()            # central differences (no base point)
    assert _rel(K, Kc) <= 2e-3, (K, Kc)
    from bearing_core.models.quasistatic import QuasiStaticModel
    jh = np.asarray(QuasiStaticModel(s.model.g, "outer").solve(3000 * RPM, (1000, 0, 3000, 0, 0)).stiffness)
    assert K[0, 0] > 1.5 * jh[0, 0] and K[2, 2] > 1.5 * jh[2, 2]
    # displacement coupling at the pose the loads gave: the pose is an input, perturbed there
    ix = _index()
    pose = {k: float(s.values[ix[n]]) for k, n in zip(POSE, IR)}
    d = CoSimSession(CoSimParameters(bearing="7218B", coupling="displacement"))
    d.initialize(0.0, {"shaft_speed": 3000 * RPM, **pose})
    d.step(0.0, 1e-3, {"shaft_speed": 3000 * RPM, **pose})
    Kd = _K(d.values)
    assert _rel(Kd, d._tangent(d.model).copy()) <= 2e-3
    assert np.all(np.abs(np.diag(Kd)[:3] / np.diag(K)[:3] - 1.0) < 0.1), (np.diag(Kd), np.diag(K))


# ---- the FMU: fmi2GetDirectionalDerivative ----------------------------------------------------------------------------

@pytest.fixture
def fmu_path(fmu, monkeypatch):
    monkeypatch.setenv("BEARING_FMU_CACHE", fmu["cache"])     # the model processes' kernel cache of the FMU tests
    return fmu["path"]


def _open(path, params, inputs):
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave
    md = read_model_description(path)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    f = FMU2Slave(guid=md.guid, unzipDirectory=extract(path), modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName="stiffness")
    f.instantiate()
    f.setupExperiment(startTime=0.0)
    for k, v in params.items():
        f.setString([vr[k]], [v])
    f.enterInitializationMode()
    f.setReal([vr[k] for k in inputs], list(inputs.values()))
    f.exitInitializationMode()
    return f, vr


def _close(f):
    f.terminate()
    f.freeInstance()


def test_fmu_model_structure(fmu_path):
    from fmpy import read_model_description
    from fmpy.validation import validate_fmu
    assert validate_fmu(fmu_path) == []
    md = read_model_description(fmu_path)
    assert md.coSimulation.providesDirectionalDerivative
    deps = {u.variable.name: sorted(d.name for d in u.dependencies) for u in md.outputs}
    assert deps["reaction_Fx"] == sorted(LOADS + POSE) and deps["ir_ty"] == sorted(LOADS + POSE)
    assert deps["cage_speed"] == [] and deps["stiffness[1,1]"] == []


def test_fmu_directional_derivative_load_coupling(fmu_path):
    """Map level, load coupling: d ir / d load = stiffness^-1 (inverted in the FMI layer, the same numbers as the
    outputs' inverse), d reaction / d load = -identity, 0 for the pose inputs and outputs without a dependency; a
    known that is not an input is refused."""
    from bearing_core.session.cosim_spec import STIFFNESS_NAMES
    f, vr = _open(fmu_path, {"fidelity": "map", "map_file": str(ROOT / "maps" / "7218B_oil.nc")},
                  {"shaft_speed": 2800 * RPM, "Fx": 1000.0, "Fy": 600.0, "Fz": 3500.0})
    try:
        f.doStep(0.0, 1e-3)
        K = np.array(f.getReal([vr[n] for n in STIFFNESS_NAMES])).reshape(5, 5)
        assert 1e8 < K[0, 0] < 5e8
        J = np.array([f.getDirectionalDerivative([vr[k] for k in IR], [vr[n]], [1.0]) for n in LOADS]).T
        assert np.allclose(J, np.linalg.inv(K), rtol=1e-9, atol=0.0)
        assert np.max(np.abs(K @ J - np.eye(5))) < 1e-9
        dv = np.array([10.0, -20.0, 5.0, 0.1, -0.3])
        d = f.getDirectionalDerivative([vr[k] for k in IR] + [vr["cage_speed"]], [vr[k] for k in LOADS], dv.tolist())
        assert np.allclose(d[:5], J @ dv, rtol=1e-12, atol=1e-20) and d[5] == 0.0
        d = f.getDirectionalDerivative([vr[k] for k in REACTIONS], [vr["Fy"]], [1.0])
        assert d == [0.0, -1.0, 0.0, 0.0, 0.0]
        d = f.getDirectionalDerivative([vr[k] for k in REACTIONS], [vr["dx"]], [1.0])   # pose: not used here
        assert d == [0.0] * 5
        with pytest.raises(Exception):        # a known that is not an input
            f.getDirectionalDerivative([vr["reaction_Fx"]], [vr["cage_speed"]], [1.0])
    finally:
        _close(f)


@needs_solves
def test_fmu_directional_derivative_displacement_coupling(fmu_path):
    """Quasi-static level, displacement coupling: d reaction / d pose = -stiffness, d ir / d pose = identity."""
    from bearing_core.session.cosim_spec import STIFFNESS_NAMES
    pose = {"dx": 1.22e-4, "dy": 1.6e-5, "dz": -9.4e-6, "tx": -3.0e-4, "ty": 2.29e-3}
    f, vr = _open(fmu_path, {"fidelity": "quasi-static", "coupling": "displacement"},
                  {"shaft_speed": 3000 * RPM, **pose})
    try:
        f.doStep(0.0, 1e-3)
        K = np.array(f.getReal([vr[n] for n in STIFFNESS_NAMES])).reshape(5, 5)
        assert K[0, 0] > 1e8
        for j, n in enumerate(POSE):
            d = f.getDirectionalDerivative([vr[k] for k in REACTIONS], [vr[n]], [1.0])
            assert np.array_equal(np.array(d), -K[:, j])
            d = f.getDirectionalDerivative([vr[k] for k in IR], [vr[n]], [2.0])
            assert np.array_equal(np.array(d), 2.0 * np.eye(5)[:, j])
        dv = np.array([1e-6, -2e-6, 5e-7, 1e-5, -3e-5])
        d = f.getDirectionalDerivative([vr[k] for k in REACTIONS] + [vr["cage_speed"]], [vr[k] for k in POSE],
                                       dv.tolist())
        assert np.allclose(d[:5], -K @ dv, rtol=1e-12, atol=0.0) and d[5] == 0.0
    finally:
        _close(f)


@needs_solves
def test_rotor_master_jacobian_stable_where_explicit_diverges(fmu_path):
    """ssp_examples/rotor_bearings/jacobian_master.py, 10 ms at 1 ms steps: the explicit exchange leaves the bearings'
    range (diverges), the linear-implicit master on fmi2GetDirectionalDerivative stays within 1 um of the centre."""
    sys.path.insert(0, str(ROOT / "ssp_examples" / "rotor_bearings"))
    import jacobian_master as JM
    ex = JM.run(fmu_path, 1e-3, 0.01, "explicit")
    assert ex["diverged_at"] is not None and ex["diverged_at"] <= 0.005
    jac = JM.run(fmu_path, 1e-3, 0.01, "jacobian")
    assert jac["diverged_at"] is None and len(jac["t"]) >= 8
    assert np.all(np.abs(jac["q"][:, :2]) < 1e-6) and np.all(np.abs(jac["Fx_A"]) < 10.0)
