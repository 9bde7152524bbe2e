"""Fits and ring growth in the dynamics, the co-simulation session and the FMU (DynamicsOptions.fits /
ring_growth; FMU parameters ring_growth, shaft_interference, housing_interference, shaft_bore, bore_diameter,
outside_diameter). The running geometry is bearing_core.bearing.ring_fits.operating_geometry(), whose equations are
checked against Timoshenko & Goodier and Harris & Kotzalas in tests/test_ring_fits.py; here it is checked that
the dynamics run on it (consistency between our own models, not a published reference)."""
import math
import sys
from pathlib import Path

import numpy as np
import pytest

from bearing_core.models import dynamics_kernels as K
from bearing_core.session.cosim import CoSimParameters, CoSimSession
from bearing_core.models.dynamics import DynamicModel, DynamicsOptions
from bearing_core.errors import BearingInputError
from bearing_core.bearing.geometry import load_preset
from bearing_core.contact.hertz_tables import HertzInterp
from bearing_core.models.quasistatic import solve_quasistatic
from bearing_core.bearing.ring_fits import OperatingTemperatures, RingFits, operating_geometry

W10K = 10000.0 * math.pi / 30.0
FIT20 = RingFits(shaft_interference=20e-6)
LOADS = (0.0, 0.0, 3000.0, 0.0, 0.0)


def _g():
    return load_preset("7218B", bore=0.090, outside_diameter=0.160)    # ISO 15 boundary dimensions 90 x 160 mm


def _geometry_params(m):
    return np.array([m.P[k] for k in (K.P_D, K.P_DM, K.P_FI, K.P_FO, K.P_A0)])


def _expected(g):
    return np.array([g.D, g.dm, g.fi, g.fo, g.alpha0])


def test_default_runs_the_nominal_geometry():
    """Without fits and ring growth (the default) the dynamics run the bearing as defined, bit for bit."""
    g = _g()
    m = DynamicModel(g, DynamicsOptions(traction="coulomb"))
    m.initialize(W10K, LOADS)
    assert m.g is g
    assert np.array_equal(_geometry_params(m), _expected(g))
    m.set_speed(2 * W10K)
    m.apply_temperatures(350.0, 360.0)
    assert m.g is g and np.array_equal(_geometry_params(m), _expected(g))


def test_20um_shaft_fit_at_10000rpm_dynamics_match_quasistatic():
    """7218B (90 x 160 mm), 20 um diametral shaft interference on a solid steel shaft, centrifugal growth at
    10,000 rpm, bearing at the 20 degC reference, Fz = 3 kN, Coulomb traction mu = 0.1. Consistency check between
    our own models (not a published reference): after 50 ms the dynamics' mean contact angles and axial ring
    position equal the quasi-static solution (outer raceway control) with the same fits within 0.05 deg / 0.1 deg
    (inner / outer) and 0.5 um, and the change caused by the fit and growth (about -1.3 deg on alpha_i) is the
    quasi-static one within 0.03 deg and 0.3 um. The running free contact angle is that of
    ring_fits.operating_geometry (1e-12 rad) and the Hertz tables are those of the running geometry."""
    g = _g()
    res = {}
    for name, fits in (("nominal", None), ("fit", FIT20)):
        m = DynamicModel(g, DynamicsOptions(traction="coulomb", fits=fits, ring_growth=fits is not None,
                                            oil_temperature=293.15))
        m.initialize(W10K, LOADS)
        m.advance(0.05)
        o = m.outputs()
        qs = solve_quasistatic(g, W10K, LOADS, fits=fits,
                               temperatures=OperatingTemperatures() if fits is not None else None)
        res[name] = (np.degrees([o["alpha_i_mean"], o["alpha_o_mean"]]), o["ir_z"],
                     np.degrees([qs.alpha_i[0], qs.alpha_o[0]]), qs.u[2])
        if fits is not None:
            g_op = operating_geometry(g, W10K, fits, OperatingTemperatures())
            assert abs(m.P[K.P_A0] - g_op.alpha0) < 1e-12
            assert np.allclose(_geometry_params(m), _expected(g_op), rtol=1e-13, atol=0)
            assert np.allclose(m._tab_i, HertzInterp(g_op).table.inner, rtol=1e-12)
            assert g.alpha0 - g_op.alpha0 > math.radians(0.8)          # the fit takes ~0.84 deg
    for name, (a_dyn, z_dyn, a_qs, z_qs) in res.items():
        assert abs(a_dyn[0] - a_qs[0]) < 0.05, (name, a_dyn, a_qs)
        assert abs(a_dyn[1] - a_qs[1]) < 0.1, (name, a_dyn, a_qs)
        assert abs(z_dyn - z_qs) < 0.5e-6, (name, z_dyn, z_qs)
    d_dyn = res["fit"][0] - res["nominal"][0]
    d_qs = res["fit"][2] - res["nominal"][2]
    assert d_qs[0] < -1.0
    assert np.all(np.abs(d_dyn - d_qs) < 0.03), (d_dyn, d_qs)
    assert abs((res["fit"][1] - res["nominal"][1]) - (res["fit"][3] - res["nominal"][3])) < 0.3e-6


def test_geometry_follows_speed_and_temperatures():
    """The running geometry follows every speed change (set_speed) and temperature update (apply_temperatures
    with ring temperatures, as the thermal network gives them) exactly as ring_fits.operating_geometry gives it;
    a hot inner ring takes clearance and lowers the free contact angle."""
    g = _g()
    m = DynamicModel(g, DynamicsOptions(traction="coulomb", fits=FIT20, ring_growth=True, oil_temperature=293.15))
    m.initialize(W10K, LOADS)
    m.set_speed(1.4 * W10K)
    g1 = operating_geometry(g, 1.4 * W10K, FIT20, OperatingTemperatures())
    assert np.allclose(_geometry_params(m), _expected(g1), rtol=1e-13, atol=0)
    m.apply_temperatures(330.0, 335.0, T_inner=345.0, T_outer=325.0)
    T = OperatingTemperatures(inner_ring=345.0 - 273.15, outer_ring=325.0 - 273.15, balls=335.0 - 273.15)
    g2 = operating_geometry(g, 1.4 * W10K, FIT20, T)
    assert np.allclose(_geometry_params(m), _expected(g2), rtol=1e-13, atol=0)
    assert g2.alpha0 < g1.alpha0 - math.radians(0.3)
    assert np.allclose(m._tab_o, HertzInterp(g2).table.outer, rtol=1e-12)


def test_thermal_network_drives_the_geometry():
    """With the thermal network on, each thermal update sets the geometry of its inner ring, outer ring and ball
    temperatures at the held speed."""
    g = _g()
    m = DynamicModel(g, DynamicsOptions(traction="coulomb", fits=FIT20, ring_growth=True, thermal=True))
    m.initialize(W10K, LOADS)
    th = m.thermal_state()
    Tn = th[0].copy()
    Tn[:] = (340.0, 320.0, 350.0, 330.0)      # ball, outer, inner, oil [K] (thermal.NODES)
    m.set_thermal_state((Tn, *th[1:]))
    T = OperatingTemperatures(inner_ring=350.0 - 273.15, outer_ring=320.0 - 273.15, balls=340.0 - 273.15)
    assert np.allclose(_geometry_params(m), _expected(operating_geometry(g, W10K, FIT20, T)), rtol=1e-13, atol=0)


def test_bad_fit_inputs_are_refused():
    """Ring growth without the boundary dimensions, a fit that takes all the clearance and a wrong fits type are
    refused at construction, naming the parameter."""
    g7 = load_preset("7218B")
    with pytest.raises(BearingInputError, match="bore"):
        DynamicModel(g7, DynamicsOptions(ring_growth=True))
    with pytest.raises(BearingInputError, match="operating diametral clearance"):
        DynamicModel(_g(), DynamicsOptions(fits=RingFits(shaft_interference=0.8e-3)))
    with pytest.raises(BearingInputError, match="fits"):
        DynamicsOptions(fits=20e-6).validate()


def test_cosim_parameters_fits_and_rollback():
    """Co-simulation session: the fit parameters reach the dynamics; a missing bore is refused naming
    bore_diameter; a step at a new speed regrows the inner ring and a rollback (set_state) restores the geometry
    of the restored speed."""
    base = dict(traction_model="coulomb", shaft_interference=20e-6, oil_temperature=293.15)
    with pytest.raises(BearingInputError, match="bore_diameter"):
        CoSimSession(CoSimParameters(**base)).initialize(0.0, {"shaft_speed": W10K, "Fz": 3000.0})
    s = CoSimSession(CoSimParameters(**base, ring_growth=True, bore_diameter=0.090, outside_diameter=0.160))
    s.initialize(0.0, {"shaft_speed": W10K, "Fz": 3000.0})
    g = _g()
    a0 = operating_geometry(g, W10K, FIT20, OperatingTemperatures()).alpha0
    assert abs(s.model.g.alpha0 - a0) < 1e-12
    st = s.get_state()
    s.step(0.0, 1e-3, {"shaft_speed": 1.4 * W10K, "Fz": 3000.0})
    assert abs(s.model.g.alpha0 - operating_geometry(g, 1.4 * W10K, FIT20, OperatingTemperatures()).alpha0) < 1e-12
    s.set_state(st)
    assert abs(s.model.g.alpha0 - a0) < 1e-12 and abs(s.model.P[K.P_A0] - a0) < 1e-12


@pytest.mark.slow
def test_fmu_fit_parameters(tmp_path, fmu):
    """The FMU declares the fit parameters with their units and takes them: a 20 um shaft fit with ring growth at
    10,000 rpm lowers the inner contact angle of the 7218B by the quasi-static model's amount (0.1 deg)."""
    from test_fmu import drive
    from test_fmu_metadata import _md, _var
    md = _md(fmu["path"])
    for name in ("shaft_interference", "housing_interference", "shaft_bore", "bore_diameter", "outside_diameter"):
        assert _var(md, name).find("Real").get("unit") == "m", name
    assert _var(md, "ring_growth").find("Boolean") is not None
    inp = {"shaft_speed": W10K, "Fx": 0.0, "Fz": 3000.0}      # (the FMU's start value of Fx is 1 kN)
    spec = {"start_inputs": inp, "steps": [[1e-3, inp]] * 2, "outputs": ["alpha_i_mean"]}
    dims = {"bore_diameter": 0.090, "outside_diameter": 0.160, "oil_temperature": 293.15,
            "traction_model": "coulomb"}
    a = {}
    for name, extra in (("nominal", {}), ("fit", {"shaft_interference": 20e-6, "ring_growth": True})):
        r = drive(fmu, dict(spec, params={**dims, **extra}), tmp_path, f"{name}.json")
        a[name] = math.degrees(r["rows"][-1]["values"][0])
    g = _g()
    q0 = solve_quasistatic(g, W10K, LOADS)
    q1 = solve_quasistatic(g, W10K, LOADS, fits=FIT20, temperatures=OperatingTemperatures())
    d_qs = math.degrees(q1.alpha_i[0] - q0.alpha_i[0])
    assert abs((a["fit"] - a["nominal"]) - d_qs) < 0.1, (a, d_qs)


sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_fmu import fmu  # noqa: E402,F401  (session fixture: the FMU built once)
