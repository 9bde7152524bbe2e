"""Tests of bearing_core.models.wear (seed 003 modified Archard wear over the Hertz ellipse, raceway depth, duty cycle)."""
import json
import math

import numpy as np
import pytest
from scipy.special import ellipe

from bearing_core.models import wear
from bearing_core.errors import BearingInputError
from bearing_core.bearing.geometry import load_preset

RPM = math.pi / 30.0


def _states(n=1, Q=100.0, a=1e-3, b=2e-4, vs_t=0.0, vs_m=0.0, w_spin=0.0, w_roll_m=0.0, w_roll_t=0.0,
            R_def=0.0, race="outer", alpha=0.4, R_c=0.05, n_balls=10, ring_turns=False):
    one = np.ones(n)
    return wear.ContactStates(
        race=race, Q=Q * one, a=a * one, b=b * one, p_max=1.5 * Q / (math.pi * a * b) * one, alpha=alpha * one,
        psi=2 * np.pi * np.arange(n) / max(n, 1), Rx=6e-3 * one, Ry=0.2 * one, R_c=R_c * one, vs_t=vs_t * one,
        vs_m=vs_m * one, w_spin=w_spin * one, w_roll_m=w_roll_m * one, w_roll_t=w_roll_t * one,
        u_roll=10.0 * one, D=15e-3, R_def=R_def, r_groove=7.8e-3, E_prime=2.26e11, n_balls=n_balls,
        ring_turns=ring_turns)


K = 1e-17  # 1/Pa, a constant wear coefficient for the pure-integration checks


@pytest.mark.parametrize("pressure", ["uniform", "hertz"])
def test_archard_uniform_slip_reduces_to_V_equals_kFs(pressure):
    """Archard (J. Appl. Phys. 24 (1953) 981; seed 003 Eq. 20): with a uniform sliding speed v the ellipse
    integral iint k p v dA must equal k Q v, i.e. V = k F s over a sliding distance s = v t, exactly (1e-12),
    for a uniform pressure and for the Hertz pressure (both integrate to Q)."""
    st = _states(vs_t=0.3, vs_m=0.4)
    r = wear.wear_rates(st, wear.WearParams(k_const=K), n_major=8, n_minor=6, pressure=pressure)
    t = 3600.0   # V = k F s with s = |v| t, |v| = 0.5 m/s
    assert r.V_dot[0] * t == pytest.approx(K * 100.0 * (0.5 * t), rel=1e-12)
    assert r.F[0] == pytest.approx(100.0, rel=1e-12)


@pytest.mark.parametrize("b_over_a", [1.0, 0.2])
def test_pure_spin_against_full_slip_spin_moment(b_over_a):
    """Pure spin w about the contact normal with the Hertz pressure: iint p w r dA = M_s w / mu with the
    full-sliding spin moment M_s = 3 mu Q a E(e) / 8 (Harris & Kotzalas, Rolling Bearing Analysis 5th ed.,
    Vol. 2 Ch. 4; circular case 3 pi mu Q a / 16, Johnson, Contact Mechanics). E(e): complete elliptic
    integral of the 2nd kind, e^2 = 1 - (b/a)^2. The integrand has a kink at the centre, so the quadrature
    converges algebraically: the error must fall with the grid and be below 0.1% at 96 x 48."""
    a = 1e-3
    st = _states(a=a, b=b_over_a * a, w_spin=500.0)
    exact = 3.0 * 100.0 * a * ellipe(1.0 - b_over_a ** 2) / 8.0 * 500.0
    errs = []
    for n in (8, 24, 96):
        r = wear.wear_rates(st, wear.WearParams(k_const=K), n_major=n, n_minor=max(4, n // 2))
        errs.append(abs(r.P_pv[0] / exact - 1.0))
    assert errs[-1] < 1e-3
    assert errs[0] > errs[1] > errs[2]


def test_grid_convergence_on_a_real_contact():
    """Wan-105 inner contact (spin and Heathcote slip, seed 003 Fig. 5 load case at 10000 rpm): the wear rate
    converges with the grid; 64 x 32 within 0.05% of 192 x 96."""
    op = wear.operating_point_wear(load_preset("wan-105"), 10000 * RPM, (300, 300, 500, 3, 3))
    st = op["inner"].states
    ref = wear.wear_rates(st, n_major=192, n_minor=96).V_dot_total
    errs = [abs(wear.wear_rates(st, n_major=n, n_minor=n // 2).V_dot_total / ref - 1) for n in (8, 16, 64)]
    assert errs[2] < 5e-4
    assert errs[0] > errs[2]


def test_symmetry():
    """Mirror symmetry: reversing the spin mirrors the strip wear q(x) -> q(-x) and keeps the volume rate;
    zero spin (outer raceway control, outer contact) gives a symmetric q(x); equal balls under pure thrust
    give equal rates."""
    st = _states(w_spin=300.0, w_roll_m=-2000.0, R_def=7.7e-3, vs_t=0.01)
    st_m = _states(w_spin=-300.0, w_roll_m=-2000.0, R_def=7.7e-3, vs_t=0.01)
    p = wear.WearParams(k_const=K)
    r, rm = wear.wear_rates(st, p), wear.wear_rates(st_m, p)
    assert rm.V_dot[0] == pytest.approx(r.V_dot[0], rel=1e-12)
    np.testing.assert_allclose(rm.q[0], r.q[0][::-1], rtol=1e-10)
    assert np.max(np.abs(r.q[0] - r.q[0][::-1])) > 1e-3 * np.max(r.q[0])    # spin makes it asymmetric
    op = wear.operating_point_wear(load_preset("wan-105"), 12000 * RPM, (0, 0, 900, 0, 0))
    ro = op["outer"]
    assert np.max(np.abs(ro.states.w_spin)) < 1e-6 * 12000 * RPM
    np.testing.assert_allclose(ro.q[0], ro.q[0][::-1], rtol=1e-9, atol=1e-12 * np.max(ro.q[0]))
    for race in ("inner", "outer"):
        v = op[race].V_dot
        assert np.max(np.abs(v / v[0] - 1)) < 1e-6


def test_depth_profile_integrates_to_volume():
    """The raceway depth-rate profile integrated over the raceway surface (2 pi R_c x f D dtheta) gives back
    the wear volume rate (0.2%, interpolation of the strip profile); fixed ring: Z balls pass each point;
    turning ring: all contacts are spread round the ring."""
    th = np.radians(np.linspace(0.0, 50.0, 200001))
    for turns, n in ((False, 1), (True, 3)):
        st = _states(n=n, w_spin=300.0, w_roll_m=-2000.0, R_def=7.7e-3, ring_turns=turns, n_balls=10)
        r = wear.wear_rates(st, wear.WearParams(k_const=K))
        prof = r.depth_rate_profile(th)
        if turns:
            V = np.trapezoid(prof, th) * st.r_groove * 2 * math.pi * st.R_c[0]
        else:
            V = np.sum(np.trapezoid(prof, th, axis=1) * st.r_groove * 2 * math.pi * st.R_c / st.n_balls)
        assert V == pytest.approx(r.V_dot_total, rel=2e-3)


def test_wear_coefficient_seed003_eq22():
    """Seed 003 Eq. 22 with its data: k = 3.433e-8 Lambda^-1.032 / 8470 MPa; floored Lambda."""
    f = wear.wear_coefficient_nb
    assert f(1.0, 3.433e-8, -1.032, 8470e6, 0.05) == pytest.approx(3.433e-8 / 8.47e9, rel=1e-14)
    assert f(4.0, 3.433e-8, -1.032, 8470e6, 0.05) == pytest.approx(3.433e-8 * 4.0 ** -1.032 / 8.47e9, rel=1e-14)
    assert f(0.0, 3.433e-8, -1.032, 8470e6, 0.05) == f(0.05, 3.433e-8, -1.032, 8470e6, 0.05)


def test_entrainment_speed_equals_seed003_eqs_24_25():
    """Seed 003 Eqs. 24-25: u_i = (omega - omega_m)(dm - D cos a_i)/2, u_o = omega_m (dm + D cos a_o)/2. Our u_roll
    (contact_kinematics, the dynamics' definition) must agree within 0.5% on a quasi-static point (it uses
    the actual ball-centre radius instead of dm/2)."""
    g = load_preset("wan-105")
    w = 8000 * RPM
    op = wear.operating_point_wear(g, w, (300, 300, 500, 3, 3))
    q = op["qs"]
    ui = (w - q.omega_m) * (g.dm - g.D * np.cos(q.alpha_i)) / 2
    uo = q.omega_m * (g.dm + g.D * np.cos(q.alpha_o)) / 2
    np.testing.assert_allclose(np.abs(op["inner"].states.u_roll), ui, rtol=5e-3)
    np.testing.assert_allclose(np.abs(op["outer"].states.u_roll), uo, rtol=5e-3)


# ---- seed 003 trends -----------------------------------------------------------------------------
@pytest.fixture(scope="module")
def wan():
    return load_preset("wan-105")


def test_seed003_fig5_speed_trend(wan):
    """Seed 003 Fig. 5 (Fx = Fy = 300 N, Mx = My = 3 N m; preload not stated, Fz = 500 N assumed): k_i and k_o
    fall with speed and h_min rises with speed, for every loaded ball."""
    ks = {"inner": [], "outer": []}
    hs = {"inner": [], "outer": []}
    qs = {"inner": [], "outer": []}
    for n in (3000.0, 7000.0, 11000.0, 15000.0):
        op = wear.operating_point_wear(wan, n * RPM, (300, 300, 500, 3, 3))
        for race in ks:
            ks[race].append(op[race].k)
            hs[race].append(op[race].h_min)
            qs[race].append(op[race].states.Q)
    for race in ks:
        loaded = np.all(np.array(qs[race]) > 0, axis=0)   # at 15000 rpm three inner contacts unload
        assert loaded.sum() >= wan.Z - 3
        assert np.all(np.diff(np.array(ks[race])[:, loaded], axis=0) < 0), race
        assert np.all(np.diff(np.array(hs[race])[:, loaded], axis=0) > 0), race


def test_seed003_fig6_radial_force_trend(wan):
    """Seed 003 Fig. 6 (unilateral radial force): in the bearing zone k_i and k_o grow with Fx and are largest
    in the force direction; in the non-bearing zone k_o falls with Fx and k_i is W-shaped (two minima), more
    so as Fx grows. Ours at 10000 rpm, Fz = 500 N, Fx = 100/300/500 N (levels not stated in the seed); the
    force-direction maximum is asserted from 300 N (at 100 N the tilt-loaded opposite side still leads)."""
    runs = [wear.operating_point_wear(wan, 10000 * RPM, (F, 0, 500, 0, 0)) for F in (100.0, 300.0, 500.0)]
    psi = np.degrees(runs[0]["qs"].psi)
    j0 = int(np.argmin(np.abs(((psi - 0.0) + 180) % 360 - 180)))
    j180 = int(np.argmin(np.abs(((psi - 180.0) + 180) % 360 - 180)))
    for race in ("inner", "outer"):
        k = np.array([r[race].k for r in runs])
        assert np.all(np.diff(k[:, j0]) > 0), race
        for i in (1, 2):
            assert int(np.argmax(k[i])) == j0, race
    ko = np.array([r["outer"].k for r in runs])
    assert np.all(np.diff(ko[:, j180]) < 0)
    ki = np.array([r["inner"].k for r in runs])
    minima = [int(np.sum((x < np.roll(x, 1)) & (x < np.roll(x, -1)))) for x in ki]
    assert minima == [2, 2, 2]
    depth = [np.max(x) - np.min(x) for x in ki]
    assert depth[0] < depth[1] < depth[2]


def test_seed003_fig7_moment_two_bearing_zones(wan):
    """Seed 003 Fig. 7: under a moment M_y the inner raceway has two bearing zones, at the seed's azimuths 90 and
    270 deg (our psi = 90 - phi: 0 and 180 deg), and in the main one k_i grows with the moment."""
    runs = [wear.operating_point_wear(wan, 10000 * RPM, (0, 0, 500, 0, M)) for M in (1.0, 3.0, 5.0)]
    psi = np.degrees(runs[0]["qs"].psi)
    ki = np.array([r["inner"].k for r in runs])
    # local maxima of k_i (periodic; a flat top over two balls counts once) at the last level
    x = ki[-1]
    peaks = np.where((x >= np.roll(x, 1)) & (x > np.roll(x, -1)))[0]
    assert len(peaks) == 2
    dist = np.abs(((psi[peaks][:, None] - np.array([0.0, 180.0])[None, :]) + 180) % 360 - 180)
    assert np.all(dist.min(axis=1) < 360.0 / wan.Z)
    jmax = int(np.argmax(x))
    assert np.all(np.diff(ki[:, jmax]) > 0)


def test_seed003_fig12_sliding_over_the_ellipse(wan):
    """Seed 003 Fig. 12 (Fx = Fy = 300 N, preload 500 N, 10000 rpm): along the major axis the inner raceway's
    sliding is asymmetric, the outer raceway's symmetric (outer control: no spin). We check the strip wear
    q(x), which carries that sliding profile."""
    op = wear.operating_point_wear(wan, 10000 * RPM, (300, 300, 500, 0, 0))
    for j in range(wan.Z):
        qi, qo = op["inner"].q[j], op["outer"].q[j]
        assert np.max(np.abs(qo - qo[::-1])) < 1e-8 * np.max(qo)
        assert np.max(np.abs(qi - qi[::-1])) > 1e-2 * np.max(qi)


def test_seed003_fig13_centre_sliding_grows_with_speed(wan):
    """Seed 003 Fig. 13: the sliding speed at the contact-ellipse centre grows with the speed, and the inner
    raceway's exceeds the outer's (max over the balls)."""
    v = {"inner": [], "outer": []}
    for n in (4000.0, 8000.0, 12000.0):
        op = wear.operating_point_wear(wan, n * RPM, (300, 300, 500, 3, 3))
        for race in v:
            s = op[race].states
            v[race].append(np.max(np.hypot(s.vs_t, s.vs_m)))
    for race in v:
        assert np.all(np.diff(v[race]) > 0)
    assert all(a > b for a, b in zip(v["inner"], v["outer"]))


# ---- duty cycle and report --------------------------------------------------------------------------
def test_duty_cycle_accumulates(wan):
    L = (200.0, 0.0, 600.0, 0.0, 0.0)
    one = wear.wear_over_duty_cycle(wan, [(7200.0, 6000 * RPM, L)])
    two = wear.wear_over_duty_cycle(wan, [(3600.0, 6000 * RPM, L), (3600.0, 6000 * RPM, L), (1000.0, 0.0, L)])
    for race in ("inner", "outer"):
        assert two[f"{race}_wear_volume_m3"] == pytest.approx(one[f"{race}_wear_volume_m3"], rel=1e-10)
        assert two[f"{race}_max_wear_depth_m"] == pytest.approx(one[f"{race}_max_wear_depth_m"], rel=1e-10)
        assert two["segments"][2][f"{race}_wear_volume_rate_m3_per_s"] == 0.0   # no sliding at standstill
        seg = one["segments"][0]
        assert one[f"{race}_wear_volume_m3"] == pytest.approx(seg[f"{race}_wear_volume_rate_m3_per_s"] * 7200.0,
                                                              rel=1e-12)
        assert one[f"{race}_wear_volume_m3"] > 0
    assert two["total_time_s"] == 8200.0


def test_wear_report_json_and_units(wan):
    r = wear.wear_report("wan-105", 10000, fx=300, fz=500, hours=100, fy=300, mx=3, my=3)
    json.dumps(r)
    for race in ("inner", "outer"):
        assert r[f"{race}_wear_depth_m"] > 0
        assert r[f"{race}_wear_volume_m3"] == pytest.approx(r[f"{race}_wear_volume_rate_m3_per_s"] * 100 * 3600,
                                                            rel=1e-12)
        assert len(r[f"{race}_h_min_m"]) == wan.Z
    r2 = wear.wear_report("wan-105", 10000, fx=300, fz=500, hours=200, fy=300, mx=3, my=3)
    assert r2["inner_wear_depth_m"] == pytest.approx(2 * r["inner_wear_depth_m"], rel=1e-12)


@pytest.mark.parametrize("kw, name", [
    (dict(hours=-1.0), "hours"), (dict(speed_rpm=-5.0), "speed_rpm"), (dict(bearing="nope"), "bearing"),
    (dict(fx=float("nan")), "fx"),
])
def test_wear_report_bad_inputs(kw, name):
    args = dict(bearing="wan-105", speed_rpm=5000.0, fx=100.0, fz=500.0, hours=1.0)
    args.update(kw)
    with pytest.raises(BearingInputError) as e:
        wear.wear_report(**args)
    assert e.value.parameter == name


def test_params_validation():
    with pytest.raises(BearingInputError) as e:
        wear.WearParams(hardness=0.0).validate()
    assert e.value.parameter == "hardness"
    with pytest.raises(BearingInputError) as e:
        wear.WearParams(surface="flat").validate()
    assert e.value.parameter == "surface"
    with pytest.raises(BearingInputError) as e:
        _states(Q=-1.0)
    assert e.value.parameter == "Q"
