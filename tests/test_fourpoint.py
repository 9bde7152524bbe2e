"""Four-point-contact (gothic-arch) ball bearings in the quasi-static model (bearing_core.models.quasistatic,
FourPointQuasiStaticModel) and the QJ1044 preset."""
import json
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from bearing_core.errors import BearingInputError
from bearing_core.bearing.geometry import from_dict, load_preset, preset_data
from bearing_core.contact.hertz_tables import HertzInterp
from bearing_core.models.quasistatic import (FourPointQuasiStaticModel, QuasiStaticModel, quasistatic_model,
                                      solve_quasistatic)

RPM = math.pi / 30.0
QJ = load_preset("QJ1044")


def _zero_clearance(g):
    """The gothic arch of g with zero internal clearance at its free contact angle:
    e_k = (f_k - 1/2) D sin(alpha0) (bearing_core.bearing.geometry module docstring)."""
    s = math.sin(g.alpha0)
    return g.with_overrides(inner_groove_offset=(g.fi - 0.5) * g.D * s, outer_groove_offset=(g.fo - 0.5) * g.D * s)


@pytest.mark.parametrize("omega, loads", [
    (0.0, (0.0, 0.0, 5000.0, 0.0, 0.0)),
    (10000 * RPM, (1000.0, 0.0, 3000.0, 0.0, 0.0)),
    (1000.0, (2000.0, 500.0, 3000.0, 20.0, -10.0)),
])
def test_zero_offset_reproduces_two_point(omega, loads):
    """The four-point model with zero groove offsets is the two-point model: same displacements, contact
    angles, loads and ring reaction to round-off (|du| < 1e-13 m, |dalpha| < 1e-12 rad, |dQ| < 1e-9 Q_max);
    the second arc of each ring never carries load."""
    g = load_preset("7218B")
    r2 = QuasiStaticModel(g).solve(omega, loads, stiffness=False)
    r4 = FourPointQuasiStaticModel(g).solve(omega, loads, stiffness=False)
    assert np.max(np.abs(r4.u - r2.u)) < 1e-13
    for f in ("alpha_i", "alpha_o", "beta", "omega_m"):
        assert np.max(np.abs(getattr(r4, f) - getattr(r2, f))) < 1e-12 * max(1.0, np.max(np.abs(getattr(r2, f))))
    qmax = max(r2.Q_i.max(), r2.Q_o.max())
    assert np.max(np.abs(r4.Q_i - r2.Q_i)) < 1e-9 * qmax and np.max(np.abs(r4.Q_o - r2.Q_o)) < 1e-9 * qmax
    np.testing.assert_allclose(r4.ring_reaction(), r2.ring_reaction(), rtol=0, atol=1e-8 * qmax)
    assert np.all(r4.Q_c[:, 0] + r4.Q_c[:, 1] == r4.Q_i) and np.all(np.minimum(r4.Q_c[:, 0], r4.Q_c[:, 1]) == 0)


def test_zero_clearance_radial_load_stribeck():
    """Radial load on a zero-clearance four-point bearing: both diagonal pairs carry the load equally and
    each follows the zero-clearance (epsilon = 1/2) distribution, Fr = 2 Z J_r(1/2) Q_max cos(alpha) with
    Sjovall's radial integral J_r(0.5) = 0.2288 (Harris & Kotzalas, Rolling Bearing Analysis 5th ed.,
    Vol. 1 Ch. 7, table of J_r(epsilon); Stribeck's 4.37 = 1/0.2288; recalled). Tolerance 0.5 % at light
    load (Q_max from the solver vs the integral with the solver's contact angle; Z = 23 discrete balls)."""
    g = _zero_clearance(QJ)
    assert abs(g.axial_play) < 1e-12 and abs(g.radial_play) < 1e-12
    assert math.isclose(g.contact_angle_zero_clearance, g.alpha0, rel_tol=1e-12)
    for Fr in (500.0, 2000.0):
        r = solve_quasistatic(g, 0.0, (Fr, 0.0, 0.0, 0.0, 0.0), stiffness=False)
        j = int(np.argmax(r.Q_c[:, 0]))
        assert j == 0 and np.all(r.contacts_per_ball[0] == 4)
        np.testing.assert_allclose(r.Q_c[0, 0], r.Q_c[0, 1], rtol=1e-9)      # mirror symmetry
        Qmax_integral = Fr / (2 * g.Z * 0.2288 * math.cos(r.alpha_c[0, 0]))
        assert r.Q_c[0, 0] == pytest.approx(Qmax_integral, rel=5e-3)
        assert abs(r.u[2]) < 1e-12                                          # stays axially centred


def test_axial_load_closed_form_and_axial_play():
    """Pure axial load: one diagonal pair carries it, as a two-point bearing: Harris & Kotzalas Vol. 1
    Ch. 7 (axially loaded bearing, rigid rings): Fa = Z K_n(alpha) (A (cos a0/cos a - 1))^1.5 sin(alpha),
    axial approach A cos(a0) tan(alpha) - A sin(a0), K_n the series Hertz constant of the inner and outer
    contact (exact Hertz, bearing_core.contact.hertz) - solved here as one scalar equation, tolerance 1e-6. Reversing
    the load moves the ring through the axial play 2 (A sin a0 - e_i - e_o) of the geometry module:
    dz(+F) + dz(-F) = -P_a (mirror symmetry, 1e-10 m)."""
    g = QJ
    hz = HertzInterp(g)
    A, a0 = g.A, g.alpha0
    Fa = 20000.0

    def resid(a):
        Ki, Ko = hz.K(np.array([a]), True)[0], hz.K(np.array([a]), False)[0]
        Kn = (Ki ** (-2 / 3) + Ko ** (-2 / 3)) ** -1.5
        return g.Z * Kn * (A * (math.cos(a0) / math.cos(a) - 1)) ** 1.5 * math.sin(a) - Fa

    a = brentq(resid, a0 + 1e-9, a0 + 0.5, xtol=1e-14)
    dz = A * math.cos(a0) * math.tan(a) - A * math.sin(a0)
    rp = solve_quasistatic(g, 0.0, (0, 0, Fa, 0, 0), stiffness=False)
    rm = solve_quasistatic(g, 0.0, (0, 0, -Fa, 0, 0), stiffness=False)
    assert rp.u[2] == pytest.approx(dz, rel=1e-6)
    np.testing.assert_allclose(rp.alpha_c[:, 0], a, rtol=1e-6)
    np.testing.assert_allclose(rp.Q_c[:, 0], Fa / (g.Z * math.sin(a)), rtol=1e-6)
    assert np.all(rp.Q_c[:, [1, 3]] == 0) and np.all(rm.Q_c[:, [0, 2]] == 0)
    assert rp.u[2] + rm.u[2] == pytest.approx(-g.axial_play, abs=1e-10)
    np.testing.assert_allclose(rm.alpha_c[:, 1], -a, rtol=1e-6)


def test_centred_ball_touches_four_arcs_at_zero_clearance():
    """Geometry of the model against the geometry module: in the zero-clearance gothic arch
    (e_k = (f_k - 1/2) D sin(alpha_z)) with the inner ring centred (dz = -P_a/2 = 0) a ball at the point of
    the groove mid-plane on the line of arc centres touches all four arcs without deflection (|delta| <
    1e-15 m), at contact angles +-alpha_z = +-asin((e_i + e_o)/A) (to 1e-12 rad)."""
    g = _zero_clearance(QJ)
    m = FourPointQuasiStaticModel(g)
    Cr, Cz = m._centres(np.array([0.0, 0.0, -0.5 * g.axial_play, 0.0, 0.0]))
    eo = g.outer_groove_offset
    t = eo / Cz[0, 0]                      # the mid-plane z = e_o on the line O_o1 -> O_i1
    X = np.tile([Cr[0, 0] * t, eo], (g.Z, 1))
    st = m._ball_state(X, Cr, Cz, 0.0, np.ones(g.Z, dtype=bool))
    az = g.contact_angle_zero_clearance
    np.testing.assert_allclose(st["ai4"], np.tile([az, -az], (g.Z, 1)), atol=1e-12)
    np.testing.assert_allclose(st["ao4"], np.tile([az, -az], (g.Z, 1)), atol=1e-12)
    assert np.max(np.abs(st["di4"])) < 1e-15 and np.max(np.abs(st["do4"])) < 1e-15


@pytest.mark.parametrize("rpm, loads", [
    (1200, (8000.0, 0.0, 2000.0, 0.0, 300.0)),
    (1800, (1000.0, 0.0, 4000.0, 0.0, 0.0)),     # seed 001 test matrix: ~1 kN radial, light axial load
    (600, (1000.0, 0.0, 2000.0, 0.0, 0.0)),
])
def test_combined_load_equilibrium_and_four_contacts(rpm, loads):
    """Combined radial, axial (and moment) load on the QJ1044 at speed: the inner ring is in
    equilibrium (ring reaction + loads = 0 to 1e-8 of the load, all five components); the balls at the
    radial load carry three or four contacts, the others two."""
    loads = np.array(loads)
    r = solve_quasistatic(QJ, rpm * RPM, loads, stiffness=False)
    scale = np.array([1.0, 1.0, 1.0, 1 / (0.5 * QJ.dm), 1 / (0.5 * QJ.dm)])
    assert np.max(np.abs((r.ring_reaction() + loads) * scale)) < 1e-8 * np.linalg.norm(loads[:3])
    assert r.contacts_per_ball.max() >= 3 and r.contacts_per_ball.min() <= 2
    assert np.all(r.Q_c >= 0) and np.all(np.isfinite(r.p_c))


def test_qj1044_preset_and_seed001_cage_speed():
    """QJ1044 preset: four-point, split inner ring, 220 x 340 x 56 mm, estimated internal geometry.
    Seed 001 (Sec. 4.2, Fig. 11 discussion) states the theoretical cage speed ratio CSR_th = 0.452 at
    F_a = 32 kN, ~1 kN radial, 1,800 r/min; the estimated geometry gives the pure-rolling cage speed ratio
    within 1.5 % of it (a check of the estimated ball diameter and pitch diameter, not of the model)."""
    d = preset_data("QJ1044")
    assert d["estimated"] is True and "ESTIMATED" in d["notes"]
    g = QJ
    assert g.is_four_point and g.split_inner_ring
    assert (g.bore, g.outside_diameter, g.width) == pytest.approx((0.220, 0.340, 0.056))
    assert math.degrees(g.alpha0) == pytest.approx(40.0)
    assert g.axial_play == pytest.approx(0.19e-3, abs=1e-6)
    r = solve_quasistatic(g, 1800 * RPM, (1000.0, 0.0, 32000.0, 0.0, 0.0), stiffness=False)
    assert r.cage_speed / r.omega == pytest.approx(0.452, rel=0.015)


def test_two_point_paths_refuse_four_point():
    """Models that handle two-point contact only refuse a four-point bearing, naming the offset field."""
    with pytest.raises(BearingInputError, match="inner_groove_offset_mm"):
        QuasiStaticModel(QJ)
    with pytest.raises(BearingInputError, match="four-point"):
        QJ.require_two_point("dynamics model")
    assert isinstance(quasistatic_model(QJ), FourPointQuasiStaticModel)
    assert type(quasistatic_model(load_preset("7218B"))) is QuasiStaticModel


def test_bearing_file_fields():
    """Bearing files take the four-point fields; bad offsets are refused naming the field."""
    d = preset_data("QJ1044")
    g = from_dict(d)
    assert g.inner_groove_offset == pytest.approx(0.4008e-3)
    with pytest.raises(BearingInputError, match="inner_groove_offset"):
        from_dict(dict(d, inner_groove_offset_mm=-0.1))
    with pytest.raises(BearingInputError, match="outer_groove_offset"):
        from_dict(dict(d, outer_groove_offset_mm=5.0))
    with pytest.raises(BearingInputError, match="split_inner_ring"):
        from_dict(dict(d, split_inner_ring="yes"))
    with pytest.raises(BearingInputError, match="did you mean 'inner_groove_offset_mm'"):
        from_dict(dict(d, inner_groove_ofset_mm=0.4))


def test_cli_prints_four_contacts(capsys):
    """bearing quasistatic --bearing QJ1044 prints the four contacts of every ball (text and JSON)."""
    from bearing_core.cli import main

    assert main(["quasistatic", "--bearing", "QJ1044", "--speed-rpm", "0", "--fz", "5000", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    fp = d["four_point"]
    assert fp["contacts"] == ["inner 1", "inner 2", "outer 1", "outer 2"]
    assert np.array(fp["Q_N"]).shape == (23, 4)
    assert main(["quasistatic", "--bearing", "QJ1044", "--speed-rpm", "0", "--fz", "5000"]) == 0
    out = capsys.readouterr().out
    assert "Q_i2" in out and "axial play 0.1899 mm" in out
