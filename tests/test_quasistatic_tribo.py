"""Quasi-static tribological model (bearing_core.models.quasistatic_tribo): the steady state of the dynamics'
own contact interface. Checked against a long run of the dynamics, conservation laws, the Jones-Harris
low-speed limit and Harris's raceway-control bounds of the spin axis."""
import json
import math

import numpy as np
import pytest

import bearing_core.models.dynamics_kernels as K

from bearing_core.cli import main as cli_main
from bearing_core.models.dynamics import DynamicModel, DynamicsOptions, records_to_dict
from bearing_core.errors import BearingInputError
from bearing_core.bearing.geometry import load_preset
from bearing_core.models.quasistatic_tribo import TriboQuasiStaticModel, solve_tribo_quasistatic

RPM = math.pi / 30
G = load_preset("7218B")


def _opt(traction, mu=0.1, **kw):
    return DynamicsOptions(traction=traction, mu=mu, mu_pocket=mu, mu_land=mu, integrator="auto", **kw)


@pytest.mark.parametrize("traction, speed_rpm", [("kalker", 3000), ("kalker", 10000), ("coulomb", 3000),
                                                 ("lubricated", 10000)])
def test_steady_state_equals_long_dynamic_run(traction, speed_rpm):
    """Same contact interface, so the quasi-static solution must be the state the dynamics settles to. The
    dynamics starts from Jones-Harris and runs 0.3 s (reduced axisymmetric model, Fz = 3000 N). Tolerances:
    contact angles 0.005 deg, loads 0.01 %, ball angular velocity 0.05 % of its magnitude, orbital
    speed 0.02 %, friction torque 0.2 % (the dynamics still carries a small ripple). The dynamics runs at
    rtol 1e-6, atol_pos 1e-10 m: at the default 1e-4 / 1e-8 m the integration error kicks Kalker's stiff
    creep forces into friction-torque spikes of up to 20 % after an integrator switch (measured at
    3000 rpm; they vanish at the tighter tolerance, which here costs no more rhs calls)."""
    opt = _opt(traction, reduced="axisymmetric")
    q = solve_tribo_quasistatic(G, speed_rpm * RPM, (0, 0, 3000, 0, 0), opt)
    m = DynamicModel(G, _opt(traction, reduced="axisymmetric", rtol=1e-6, atol_pos=1e-10))
    m.initialize(speed_rpm * RPM, (0, 0, 3000, 0, 0))
    # the quasi-static model has no cage (free balls, centred cage): compare with the same physics, the
    # cage's oil films (pocket shear, flooded-land drag) off in the dynamics too
    m.P[K.P_LUBE] = 0.0
    m.P[K.P_ETA_LAND] = 0.0
    d = records_to_dict(m.advance(0.3, record_dt=1e-3))
    bd = m.ball_details()
    assert abs(math.degrees(q.alpha_i[0] - bd["alpha_i"][0])) < 0.005
    assert abs(math.degrees(q.alpha_o[0] - bd["alpha_o"][0])) < 0.005
    assert abs(q.Q_i[0] / bd["Q_i"][0] - 1) < 1e-4
    assert abs(q.Q_o[0] / bd["Q_o"][0] - 1) < 1e-4
    W = bd["omega"][0]
    assert np.linalg.norm(q.omega_ball[0] - W) < 5e-4 * np.linalg.norm(W)
    assert abs(q.orbit_speed[0] / bd["orbit_speed"][0] - 1) < 2e-4
    assert abs(q.friction_torque / d["friction_torque"][-50:].mean() - 1) < 2e-3
    # pure axial load: every ball alike
    assert np.ptp(q.Q_i) < 1e-6 * q.Q_i.mean()


@pytest.mark.parametrize("traction", ["kalker", "lubricated"])
def test_conservation_under_combined_load(traction):
    """Steady state: the reactions equal the applied loads and the drive power equals the heat generated in
    the contacts and by drag (power in = heat out, nothing accelerates). The solver drives forces and
    moments to zero, not power, so the power balance checks the traction kernels' loss against their
    forces and moments. Tolerance 1e-6 of the load / of the drive power."""
    loads = np.array([1000.0, 0.0, 3000.0, 0.0, 0.0])
    q = solve_tribo_quasistatic(G, 3000 * RPM, loads, _opt(traction, oil_fraction=0.05), tol=1e-10)
    assert np.all(np.abs(q.reaction[:3] + loads[:3]) < 1e-6 * 3000)
    assert np.all(np.abs(q.reaction[3:]) < 1e-6 * 3000 * G.dm)
    L = q.losses
    heat = L["P_race_inner"] + L["P_race_outer"] + L["P_drag"] + L["P_churn_cage"] + L["P_churn_ring"]
    assert L["P_drag"] > 0.0
    assert abs(L["P_drive"] - heat) < 1e-6 * L["P_drive"]
    assert abs(q.friction_torque * q.omega - L["P_drive"]) < 1e-9 * L["P_drive"]
    # the load zone: balls at the radial load carry more
    assert q.Q_i[0] > q.Q_i[G.Z // 2]


def test_low_speed_limit_and_spin_axis_between_control_limits():
    """Harris & Kotzalas Vol. 2 Ch. 3: at low speed the gyroscopic moment vanishes and the raceway-control
    hypothesis no longer matters for the orbital speed, so the tribological model's cage speed must
    approach Jones-Harris (tolerance 0.3 %, 7218B, 1000 rpm, Fz 3000 N). The spin axis is then set by the
    balance of the two spin moments and must lie between Harris's outer-control attitude
    tan b = sin a_o / (cos a_o + D/dm) and inner-control attitude tan b = sin a_i / (cos a_i - D/dm)."""
    for traction in ("kalker", "coulomb"):
        q = solve_tribo_quasistatic(G, 1000 * RPM, (0, 0, 3000, 0, 0), _opt(traction))
        jh = q.jones_harris
        assert abs(q.cage_speed / jh.cage_speed - 1) < 3e-3
        g_ = G.D / G.dm
        ai, ao = q.alpha_i[0], q.alpha_o[0]
        b_out = math.atan2(math.sin(ao), math.cos(ao) + g_)
        b_in = math.atan2(math.sin(ai), math.cos(ai) - g_)
        assert b_out + math.radians(1.0) < q.attitude[0] < b_in - math.radians(1.0), \
            (math.degrees(b_out), math.degrees(q.attitude[0]), math.degrees(b_in))


def test_tribological_start_removes_most_of_the_initial_transient():
    """Seed 000 Sec. 3.1: the quasi-static tribological solution as initial state makes the dynamics start
    near its steady state. Measured over the first 50 ms (Kalker, 3000 rpm, Fz 3000 N): the largest change
    of ball 0's axial angular velocity and inner contact angle must be at most a fifth of that after a
    Jones-Harris start (measured: about a tenth)."""
    dev = {}
    for start in ("jones-harris", "tribological"):
        m = DynamicModel(G, _opt("kalker", reduced="axisymmetric"))
        m.initialize(3000 * RPM, (0, 0, 3000, 0, 0), start=start)
        d = records_to_dict(m.advance(0.05, record_dt=1e-4))
        w, a = d["ball0_wz"], d["ball0_alpha_i"]
        dev[start] = (np.max(np.abs(w - w[0])) / abs(w[0]), np.max(np.abs(a - a[0])))
    assert dev["tribological"][0] < 0.2 * dev["jones-harris"][0]
    assert dev["tribological"][1] < 0.2 * dev["jones-harris"][1]


def test_input_errors():
    m = TriboQuasiStaticModel(G, _opt("kalker"))
    with pytest.raises(BearingInputError, match="omega"):
        m.solve(0.0, (0, 0, 3000, 0, 0))
    with pytest.raises(BearingInputError, match="loads"):
        m.solve(100.0, (0, 0, float("nan"), 0, 0))
    with pytest.raises(BearingInputError, match="Fz"):       # an input error, not a solver failure
        m.solve(100.0, (0, 0, 1e9, 0, 0))
    with pytest.raises(BearingInputError, match="maxit"):
        m.solve(100.0, (0, 0, 3000, 0, 0), maxit=0)
    with pytest.raises(BearingInputError, match="coupling"):
        TriboQuasiStaticModel(G, DynamicsOptions(coupling="displacement"))
    with pytest.raises(BearingInputError, match="start"):
        DynamicModel(G, _opt("kalker")).initialize(100.0, (0, 0, 3000, 0, 0), start="guess")
    for bad in ("previous", 1.0, np.zeros(10)):               # a start must be an earlier solve's result
        with pytest.raises(BearingInputError, match="start"):
            m.solve(100.0, (0, 0, 3000, 0, 0), start=bad)


def test_cli_quasistatic_traction_json(capsys):
    """`bearing quasistatic --traction kalker --json`: the tribological model's keys, the Jones-Harris start
    beside it, and the reaction equal to the load."""
    rc = cli_main(["quasistatic", "--bearing", "7218B", "--speed-rpm", "3000", "--fz", "3000",
                   "--traction", "kalker", "--mu", "0.1", "--json"])
    assert rc == 0
    d = json.loads(capsys.readouterr().out)
    assert d["model"] == "tribological" and d["traction"] == "kalker"
    assert len(d["alpha_i_deg"]) == G.Z and len(d["ball_omega_rpm"][0]) == 3
    assert abs(d["reaction"]["Fz_N"] + 3000) < 1e-3
    assert abs(d["cage_speed_rpm"] / d["jones_harris"]["cage_speed_rpm"] - 1) < 0.01
    assert cli_main(["quasistatic", "--bearing", "7218B", "--speed-rpm", "0", "--fz", "3000",
                     "--traction", "kalker"]) != 0


def test_start_from_the_previous_load_case():
    """A sweep's next case solved from the previous case's solution (solve(start=...): no Jones-Harris
    solve) reaches the steady state of the solve from the Jones-Harris start: both are equilibria of
    the same equations, so the inner ring's reaction equals the applied load to the solver tolerance
    (1e-7 of the load: Newton's third law at the ring), and the two agree to a few times that tolerance
    (cage speed 1e-6 relative, contact loads 1e-5 of the largest)."""
    opt = _opt("lubricated")
    m = TriboQuasiStaticModel(G, opt)
    w = 3000 * RPM
    loads = np.array((1000.0, 0.0, 3000.0, 0.0, 0.0))
    prev = m.solve(w, (800.0, 0.0, 3000.0, 0.0, 0.0))
    warm = m.solve(w, loads, start=prev)
    cold = m.solve(w, loads)
    assert warm.jones_harris is None and cold.jones_harris is not None
    for q in (warm, cold):
        assert np.max(np.abs(q.reaction + loads)) <= 1e-7 * 3000.0 * 1.001
    assert abs(warm.cage_speed / cold.cage_speed - 1) < 1e-6
    assert np.max(np.abs(warm.Q_i - cold.Q_i)) < 1e-5 * np.max(cold.Q_i)
    assert np.max(np.abs(warm.u - cold.u)) < 1e-5 * np.max(np.abs(cold.u))


def test_start_that_fails_falls_back_to_jones_harris():
    """A start that does not lead to a steady state (here: non-finite ball speeds) falls back to the
    Jones-Harris start and returns that solve's equilibrium (reaction equal to the load to 1e-7 of it):
    the same state as the solve without a start, to the bit (the same computation; the continuation in
    speed, the next fallback, would end elsewhere within the tolerance)."""
    from dataclasses import replace
    m = TriboQuasiStaticModel(G, _opt("coulomb"))
    w = 3000 * RPM
    loads = np.array((1000.0, 0.0, 3000.0, 0.0, 0.0))
    prev = m.solve(w, loads)
    bad = replace(prev, omega_ball=np.full_like(prev.omega_ball, np.nan))
    q = m.solve(w, loads, start=bad)
    assert q.jones_harris is not None
    assert np.max(np.abs(q.reaction + loads)) <= 1e-7 * 3000.0 * 1.001
    assert np.array_equal(q.y, prev.y) and q.iterations == prev.iterations


@pytest.mark.parametrize("options", [dict(traction="lubricated"), dict(traction="kalker", mu=0.1),
                                     dict(traction="coulomb", fits="fit20", ring_growth=True)])
def test_memoised_parameters_equal_the_dynamic_models(options):
    """The memoised kernel parameters of the quasi-static solve are those DynamicModel.initialize sets
    (the same bearing, options and speed; with ring growth the running geometry at that speed), except
    the entries the quasi-static model sets itself: the cage's oil films off and the ring's support
    damping (zero velocity at rest) left at 0. Exact equality: the same code computes them."""
    from bearing_core.models.quasistatic_tribo import _kernel_setup
    from bearing_core.bearing.ring_fits import RingFits
    g = G
    if options.get("fits") == "fit20":
        options = dict(options, fits=RingFits(shaft_interference=20e-6))
        g = load_preset("7218B", bore=0.090, outside_diameter=0.160)     # ISO 15 boundary dimensions
    m = TriboQuasiStaticModel(g, DynamicsOptions(**options))
    w = 6000 * RPM
    gq, P, tabs = m._setup(w)
    d = DynamicModel(g, m.opt)
    d.initialize(w, (1000.0, 0.0, 3000.0, 0.0, 0.0))
    Pd = d.P.copy()
    Pd[K.P_LUBE] = 0.0
    Pd[K.P_ETA_LAND] = 0.0
    Pd[K.P_CRX:K.P_CRTY + 1] = 0.0
    assert np.array_equal(P, Pd)
    assert (gq.D, gq.dm, gq.fi, gq.fo, gq.alpha0) == (d.g.D, d.g.dm, d.g.fi, d.g.fo, d.g.alpha0)
    for a, b in zip(tabs, (d._tab_i, d._tab_o, d._ta0, d._tda, d._tp, *d._quad)):
        assert np.array_equal(a, b)
    assert _kernel_setup.cache_info().currsize >= 1
