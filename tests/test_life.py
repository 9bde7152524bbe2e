"""Fatigue rating life: ISO 281 C_r and factors, ISO/TS 16281-style L10r from the load distribution,
Palmgren-Miner damage, input errors, the `bearing life` command (bearing_core.models.life, docs/life.md)."""
import json
import math

import numpy as np
import pytest

from bearing_core.bearing.geometry import from_dict, load_bearing
from bearing_core.bearing.ratings import iso281_dynamic_load_rating, iso281_fc, lundberg_palmgren_fc
from bearing_core.errors import BearingInputError
from bearing_core.models import life as L
from bearing_core.models.quasistatic import QuasiStaticModel

# ISO 281:2007 Table 2 (ball bearings, single-row radial and angular contact), a few rows
ISO281_TABLE2 = {0.05: 46.7, 0.10: 55.5, 0.14: 58.8, 0.20: 59.9, 0.26: 58.2, 0.30: 56.0, 0.40: 48.4}


def _ball_set(Z, D_mm, dm_mm, alpha_deg=0.0, **kw):
    d = {"name": "test", "number_of_balls": Z, "ball_diameter_mm": D_mm, "pitch_diameter_mm": dm_mm,
         "free_contact_angle_deg": alpha_deg, "fi": 0.52, "fo": 0.53, "width_mm": 15.0,
         "inner_ring_mass_kg": 0.05, "outer_ring_mass_kg": 0.08, "inner_ring_inertia_kg_mm2": 5.0,
         "inner_ring_tilt_inertia_kg_mm2": 3.0, "cage": {"mass_kg": 0.005, "inertia_kg_mm2": 2.0}}
    d.update(kw)
    return from_dict(d)


def test_fc_table_and_lundberg_palmgren():
    """The f_c the rating uses is the standard's table at its rows; the Lundberg-Palmgren expression it derives
    from (conformities 0.52 / 0.53) is within 5 % of it."""
    for g, fc in ISO281_TABLE2.items():
        assert iso281_fc(g) == pytest.approx(fc, abs=1e-12)
        assert lundberg_palmgren_fc(g) == pytest.approx(fc, rel=0.05)
    with pytest.raises(BearingInputError, match="ISO 281 Table 2"):
        iso281_fc(0.45)


def test_cr_continuous_at_25_4_mm():
    """ISO 281 6.1.1: the D^1.4 form (3.647 D^1.4) continues the D^1.8 form at D_w = 25.4 mm."""
    lo = iso281_dynamic_load_rating(16, 25.4e-3 - 1e-9, 140e-3, math.radians(25))
    hi = iso281_dynamic_load_rating(16, 25.4e-3 + 1e-9, 140e-3, math.radians(25))
    assert hi == pytest.approx(lo, rel=1e-4)


def test_load_distribution_integrals():
    """Sjovall integrals at eps = 0.5 as tabulated by Harris & Kotzalas (Vol. 2 Ch. 8): 0.2288, 0.5625, 0.5875."""
    assert L.J_R == pytest.approx(0.2288, abs=2e-4)
    assert L.J_1 == pytest.approx(0.5625, abs=2e-4)
    assert L.J_2 == pytest.approx(0.5875, abs=3e-4)


def test_radial_zero_clearance_reproduces_cr():
    """A radial bearing without clearance under a radial load, inner ring held square: the load zone is the
    half ring (eps = 0.5) on which ISO 281 defines C_r, so L10r = (C_r / Fr)^3 up to the discrete ball set."""
    g = _ball_set(9, 7.94, 39.04)
    Fr = 1000.0
    res = QuasiStaticModel(g, fixed_tilt=True).solve(10.0, (Fr, 0, 0, 0, 0), stiffness=False)
    rl = L.rating_life(res, 100.0)
    assert rl.L10r_Mrev == pytest.approx((g.basic_dynamic_load_rating / Fr) ** 3, rel=0.03)
    assert rl.P_ref == pytest.approx(Fr, rel=0.01)


@pytest.fixture(scope="module")
def states():
    """Two quasi-static states of the 7218B (inner ring held square) with their lives."""
    g = load_bearing("7218B")
    out = []
    for rpm, loads in ((3000.0, (3000.0, 0, 5000.0, 0, 0)), (6000.0, (1000.0, 0, 12000.0, 0, 0))):
        res = QuasiStaticModel(g, fixed_tilt=True).solve(rpm * math.pi / 30, loads, stiffness=False)
        out.append((rpm, res))
    return g, out


def test_kernel_equals_python_path(states):
    g, sts = states
    par = L.life_parameters(g)
    for rpm, res in sts:
        Lh = L.rating_life_hours_nb(res.Q_i, res.Q_o, res.alpha_i, res.alpha_o, par, rpm)
        rl = L.rating_life(res, rpm)
        assert Lh == pytest.approx(rl.L10r_h, rel=1e-12)
        assert rl.L10r_h == pytest.approx(rl.L10r_Mrev * 1e6 / (60 * rpm), rel=1e-12)
        assert rl.L10r_Mrev < min(rl.L_inner_Mrev, rl.L_outer_Mrev)


def test_details_kernel_equals_arrays(states):
    """rating_life_hours_details_nb on a per-ball details array (the dynamics' layout) equals the array form."""
    from bearing_core.models import dynamics_kernels as K
    g, sts = states
    par = L.life_parameters(g)
    for rpm, res in sts:
        bd = np.zeros((g.Z, K.NBD))
        bd[:, K.BD_QI], bd[:, K.BD_AI], bd[:, K.BD_QO], bd[:, K.BD_AO] = res.Q_i, res.alpha_i, res.Q_o, res.alpha_o
        ref = L.rating_life_hours_nb(res.Q_i, res.Q_o, res.alpha_i, res.alpha_o, par, rpm)
        assert L.rating_life_hours_details_nb(bd, par, rpm) == pytest.approx(ref, rel=1e-12)
    assert L.rating_life_hours_details_nb(np.zeros((g.Z, K.NBD)), par, 1000.0) == math.inf


def test_damage_at_held_state_is_time_over_life(states):
    g, sts = states
    par = L.life_parameters(g)
    rpm, res = sts[0]
    Lh = L.rating_life_hours_nb(res.Q_i, res.Q_o, res.alpha_i, res.alpha_o, par, rpm)
    d = L.FatigueDamage()
    assert d.value == 0.0
    dt, n = 1e-3, 5000
    for _ in range(n):
        d.advance(dt, Lh)
    assert d.value == pytest.approx(n * dt / 3600.0 / Lh, rel=1e-9)
    assert L.damage_increment_nb(1.0, math.inf) == 0.0


def test_damage_two_level_duty_cycle_is_sum_of_parts(states):
    """Palmgren-Miner: the damage of a two-level cycle is the sum of the levels' damages, in either order, and
    the cycle's equivalent life lies between the two levels' lives."""
    g, sts = states
    par = L.life_parameters(g)
    lives = [L.rating_life_hours_nb(r.Q_i, r.Q_o, r.alpha_i, r.alpha_o, par, rpm) for rpm, r in sts]
    times = (7200.0, 1800.0)          # s at each level
    parts = []
    for Lh, t in zip(lives, times):
        d = L.FatigueDamage()
        for _ in range(100):
            d.advance(t / 100, Lh)
        parts.append(d.value)
    for order in ((0, 1), (1, 0)):
        d = L.FatigueDamage()
        for k in order:
            for _ in range(100):
                d.advance(times[k] / 100, lives[k])
        assert d.value == pytest.approx(sum(parts), rel=1e-12)
    L_eq = sum(times) / 3600.0 / sum(parts)
    assert min(lives) < L_eq < max(lives)


def test_catalogue_rating_overrides_iso():
    """dynamic_load_rating_N replaces the ISO C_r; at the same state the life scales as (C / C_ISO)^3."""
    g = load_bearing("wan-105")
    g2 = g.with_overrides(dynamic_load_rating=1.1 * g.iso281_dynamic_load_rating)
    assert g2.basic_dynamic_load_rating == pytest.approx(1.1 * g.iso281_dynamic_load_rating)
    res = QuasiStaticModel(g, fixed_tilt=True).solve(300.0, (2000.0, 0, 4000.0, 0, 0), stiffness=False)
    a = L.rating_life(res, 3000.0)
    res.geometry = g2
    b = L.rating_life(res, 3000.0)
    assert b.L10r_Mrev / a.L10r_Mrev == pytest.approx(1.1 ** 3, rel=1e-9)
    with pytest.raises(BearingInputError, match="dynamic_load_rating_N"):
        load_bearing({**_defn("wan-105"), "dynamic_load_rating_N": -5.0})


def _defn(name):
    from bearing_core.bearing.geometry import bearing_definition
    return bearing_definition(name)


def test_a_iso_and_a1():
    """a_ISO: 0.1 without the fatigue-limit term, continuous at kappa = 0.4 and 1, rising with kappa, at most 50;
    a_1 = 1 at 90 % reliability."""
    assert L.a_iso(1.0, 0.0) == pytest.approx(0.1)
    for kb in (0.4, 1.0):
        assert L.a_iso(kb * (1 - 1e-9), 0.5) == pytest.approx(L.a_iso(kb, 0.5), rel=1e-3)
    vals = [L.a_iso(k, 0.1) for k in (0.1, 0.2, 0.4, 0.7, 1.0, 2.0, 4.0)]
    assert all(b > a for a, b in zip(vals, vals[1:]))
    assert L.a_iso(8.0, 0.1) == L.a_iso(4.0, 0.1)          # kappa > 4 taken as 4
    assert L.a_iso(4.0, 5.0) == 50.0
    assert L.a1_reliability(90.0) == pytest.approx(1.0)
    with pytest.raises(BearingInputError, match="kappa"):
        L.a_iso(0.05, 0.5)
    # ISO 281 nu_1: the two speed ranges meet at 1000 r/min within the standard's rounding (2 %)
    assert L.reference_viscosity(0.1, 999.999) == pytest.approx(L.reference_viscosity(0.1, 1000.0), rel=0.03)


@pytest.mark.parametrize("loads,speed,param,allowed", [
    ((0, 0, 0, 0, 0), 3000.0, "loads", "non-zero"),
    ((1000, 0, -3000, 0, 0), 3000.0, "Fz", "Fz > 0"),
    ((0, 0, 3000, 0, 0), -100.0, "speed_rpm", "< value <= 190000"),
    ((0, 0, 3000, 0, 0), 0.0, "speed_rpm", "< value <= 190000"),
])
def test_bad_inputs_named_not_nan(loads, speed, param, allowed):
    with pytest.raises(BearingInputError) as e:
        L.life_at(load_bearing("7218B"), speed, loads)
    assert e.value.parameter.startswith(param)
    assert allowed in str(e.value)


def test_bad_factors():
    g = load_bearing("7218B")
    with pytest.raises(BearingInputError, match="e_C"):
        L.life_at(g, 3000.0, (0, 0, 3000, 0, 0), e_C=1.5)
    with pytest.raises(BearingInputError, match="reliability"):
        L.life_at(g, 3000.0, (0, 0, 3000, 0, 0), reliability_pct=80.0)


def test_cli_json(capsys):
    from bearing_core.cli import main
    rc = main(["life", "--bearing", "7218B", "--speed-rpm", "3000", "--fx", "3000", "--fz", "5000", "--fixed-tilt",
               "--contamination", "0.5", "--reliability", "99", "--json"])
    assert rc == 0
    d = json.loads(capsys.readouterr().out)
    assert d["L10r_h"] == pytest.approx(d["L10r_Mrev"] * 1e6 / (60 * 3000), rel=1e-12)
    assert d["L_nmr_Mrev"] == pytest.approx(d["a1"] * d["a_iso"] * d["L10r_Mrev"], rel=1e-12)
    assert d["a1"] == pytest.approx(0.25, abs=0.005)       # ISO 281 Table 12 at 99 %
    assert d["kappa"] == pytest.approx(d["nu_mm2s"] / d["nu1_mm2s"])
    assert len(d["Q_i_N"]) == 16 and all(math.isfinite(x) for x in d["Q_ci_N"])
    rc = main(["life", "--bearing", "7218B", "--speed-rpm", "3000", "--fz", "-3000", "--json"])
    assert rc == 2
    err = capsys.readouterr().err
    assert "Fz = -3000.0" in err and "Fz > 0 N" in err and "nan" not in err.lower()


def test_duty_cycle_life_is_sum_of_levels(tmp_path, capsys):
    """duty_cycle_life: the damage of a two-level cycle is the sum of t_k / L_k of the levels solved alone, the
    equivalent life lies between theirs; `bearing life --duty` gives the same in --json form."""
    g = load_bearing("7218B")
    levels = [(3600.0, 1000.0, (1000.0, 0, 3000.0, 0, 0)), (600.0, 8000.0, (3000.0, 0, 6000.0, 0, 0))]
    dc = L.duty_cycle_life(g, levels, fixed_tilt=True)
    alone = [L.life_at(g, n, loads, fixed_tilt=True) for _, n, loads in levels]
    parts = [t / 3600.0 / r.rating.L10r_h for (t, _, _), r in zip(levels, alone)]
    assert dc.damage_L10r == pytest.approx(sum(parts), rel=1e-12)
    assert min(r.rating.L10r_h for r in alone) < dc.L10r_h < max(r.rating.L10r_h for r in alone)
    f = tmp_path / "duty.csv"
    f.write_text("duration_s,speed_rpm,Fx_N,Fz_N\n3600,1000,1000,3000\n600,8000,3000,6000\n")
    from bearing_core.cli import main
    assert main(["life", "--bearing", "7218B", "--duty", str(f), "--fixed-tilt", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["damage_L10r_per_cycle"] == pytest.approx(dc.damage_L10r, rel=1e-12)
    assert [lv["duration_s"] for lv in d["levels"]] == [3600.0, 600.0]
    with pytest.raises(BearingInputError, match="duration_s"):
        L.duty_cycle_life(g, [(0.0, 1000.0, (0, 0, 3000.0, 0, 0))])
