"""Jones-Harris 5-DOF quasi-static model."""
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from bearing_core.errors import BearingInputError, ConvergenceError
from bearing_core.bearing.geometry import load_preset
from bearing_core.models.quasistatic import QuasiStaticModel, solve_quasistatic

RPM = math.pi / 30


def test_seed003_table2_wan105():
    """Seed 003 (Liu et al. 2026) Table 2, 'literature result' column (Wan Changsen 1987): wan-105 bearing,
    Fz = 889.84 N, 15000 rpm, outer raceway control. Tolerance: 1% on ball spin speed, orbital speed,
    both contact angles and both contact loads; 3% on the (inner) spin-to-roll ratio."""
    g = load_preset("wan-105")
    r = solve_quasistatic(g, 15000 * RPM, (0, 0, 889.84, 0, 0), control="outer")
    lit = dict(wR=57670, wm=7255, ai=37.7, ao=4.074, Qi=76.57, Qo=488.97, sr=0.689)
    got = dict(wR=abs(r.omega_R[0]) / RPM, wm=r.omega_m[0] / RPM, ai=math.degrees(r.alpha_i[0]),
               ao=math.degrees(r.alpha_o[0]), Qi=r.Q_i[0], Qo=r.Q_o[0], sr=r.spin_roll_i[0])
    for k in ("wR", "wm", "ai", "ao", "Qi", "Qo"):
        assert abs(got[k] / lit[k] - 1) < 0.01, (k, got[k], lit[k])
    assert abs(got["sr"] / lit["sr"] - 1) < 0.03
    # all balls identical under pure axial load
    assert np.ptp(r.Q_i) < 1e-6 * r.Q_i.mean()
    assert r.residual < 1e-6


def _analytic_static_axial(g, Fa, model):
    """Harris & Kotzalas (Vol. 1 Ch. 7, thrust load, zero speed): Fa = Z Kn A^1.5 sin(a) (cos a0/cos a - 1)^1.5
    with the series constant Kn = (Ki^-2/3 + Ko^-2/3)^-3/2 at the loaded angle a."""
    A, a0 = g.A, g.alpha0

    def f(a):
        Ki = model.hz.K(np.array([a]), True)[0]
        Ko = model.hz.K(np.array([a]), False)[0]
        Kn = (Ki ** (-2 / 3) + Ko ** (-2 / 3)) ** -1.5
        return g.Z * Kn * A ** 1.5 * math.sin(a) * (math.cos(a0) / math.cos(a) - 1) ** 1.5 - Fa
    a = brentq(f, a0 + 1e-9, math.radians(89))
    dz = A * math.cos(a0) * math.tan(a) - A * math.sin(a0)
    return a, dz


@pytest.mark.parametrize("name,Fa", [("7218B", 22250.0), ("7218B", 500.0), ("7008-ma2023", 300.0)])
def test_zero_speed_axial_matches_closed_form(name, Fa):
    """At zero speed under pure thrust the 5-DOF model must reduce to the closed-form thrust equation
    (Harris & Kotzalas Vol. 1 Ch. 7). Tolerance 1e-4 relative on contact angle and axial approach."""
    g = load_preset(name)
    m = QuasiStaticModel(g)
    r = m.solve(0.0, (0, 0, Fa, 0, 0))
    a, dz = _analytic_static_axial(g, Fa, m)
    assert abs(r.alpha_i[0] - a) < 1e-4 * a
    assert abs(r.alpha_o[0] - a) < 1e-4 * a
    assert abs(r.u[2] - dz) < 1e-4 * abs(dz)
    # axial stiffness: d Fa / d dz from the closed form by differences
    h = 1e-3 * Fa
    _, dz2 = _analytic_static_axial(g, Fa + h, m)
    _, dz1 = _analytic_static_axial(g, Fa - h, m)
    kz = 2 * h / (dz2 - dz1)
    assert abs(r.stiffness[2, 2] / kz - 1) < 2e-3


LOADS = {
    "axial": (0, 0, 2000, 0, 0),
    "radial": (3000, 0, 0, 0, 0),
    "moment": (0, 0, 1000, 0, 60.0),
    "combined": (1500, -800, 2500, 20, -15),
    "light": (0, 0, 1.0, 0, 0),
    "unloaded_balls": (6000, 0, 800, 0, 0),
}


@pytest.mark.parametrize("case", sorted(LOADS))
@pytest.mark.parametrize("speed_rpm", [0.0, 6000.0])
@pytest.mark.parametrize("control", ["outer", "inner", "hybrid"])
def test_equilibrium_residual_over_sweep(case, speed_rpm, control):
    """Ring equilibrium: the sum of ball forces on the inner ring equals the applied load within 1e-6
    relative, for pure axial, pure radial, moment, combined, light and partly
    unloaded cases, static and at speed, for every raceway control."""
    g = load_preset("7218B")
    loads = np.array(LOADS[case], dtype=float)
    r = solve_quasistatic(g, speed_rpm * RPM, loads, control=control, stiffness=False)
    reaction = r.ring_reaction()
    assert np.linalg.norm(reaction + loads) <= 1e-6 * np.linalg.norm(loads)
    assert np.all(np.isfinite(r.Q_i)) and np.all(r.Q_i >= 0) and np.all(r.Q_o >= 0)
    if case == "unloaded_balls":
        assert np.any(r.Q_i == 0), "a heavy radial load with light preload must unload some balls"
    if control == "outer" and speed_rpm > 0:
        assert np.allclose(r.spin_roll_o[r.Q_i > 0], 0, atol=1e-9)
    if control == "inner" and speed_rpm > 0:
        assert np.allclose(r.spin_roll_i[r.Q_i > 0], 0, atol=1e-9)


def test_speed_effects_centrifugal_and_gyroscopic():
    """Jones-Harris trends (Harris & Kotzalas Vol. 2 Ch. 3): with speed the outer contact angle falls,
    the inner one rises and the outer load grows by about the centrifugal force."""
    g = load_preset("7218B")
    r0 = solve_quasistatic(g, 0.0, (0, 0, 5000, 0, 0), stiffness=False)
    r1 = solve_quasistatic(g, 10000 * RPM, (0, 0, 5000, 0, 0), stiffness=False)
    assert r1.alpha_o[0] < r0.alpha_o[0] - math.radians(3)
    assert r1.alpha_i[0] > r0.alpha_i[0]
    # radial ball balance: Qo cos ao - Qi cos ai ~= Fc (friction terms are small)
    lhs = r1.Q_o[0] * math.cos(r1.alpha_o[0]) - r1.Q_i[0] * math.cos(r1.alpha_i[0])
    assert abs(lhs / r1.Fc[0] - 1) < 0.05


def test_stiffness_symmetric_at_zero_speed():
    """At zero speed the contact forces derive from a potential, so the stiffness matrix is symmetric
    (Lim & Singh 1990; de Mul et al. 1989). Tolerance 1e-3 of the largest entry in its block."""
    g = load_preset("7218B")
    r = solve_quasistatic(g, 0.0, (1000, 500, 3000, 10, -5))
    K = r.stiffness
    for i in range(5):
        for j in range(5):
            s = max(abs(K[i, i]), abs(K[j, j])) ** 0.5 * max(abs(K[i, i]), abs(K[j, j])) ** 0.5
            assert abs(K[i, j] - K[j, i]) <= 1e-3 * s
    assert np.all(np.linalg.eigvalsh(0.5 * (K + K.T)) > 0)


def test_hybrid_control_picks_outer_at_high_speed():
    """Harris's criterion chooses outer raceway control for a high-speed, lightly thrust-loaded
    bearing (large outer contact with small angle)."""
    g = load_preset("wan-105")
    r = solve_quasistatic(g, 15000 * RPM, (0, 0, 889.84, 0, 0), control="hybrid", stiffness=False)
    assert r.outer_control.all()


@pytest.mark.parametrize("kw,param", [
    (dict(omega=float("nan"), loads=(0, 0, 100, 0, 0)), "omega"),
    (dict(omega=-1.0, loads=(0, 0, 100, 0, 0)), "omega"),
    (dict(omega=10.0, loads=(0, 0, float("inf"), 0, 0)), "Fz"),
    (dict(omega=10.0, loads=(0, 0, 100)), "loads"),
])
def test_bad_input(kw, param):
    m = QuasiStaticModel(load_preset("7218B"))
    with pytest.raises(BearingInputError, match=param):
        m.solve(**kw)
    with pytest.raises(BearingInputError, match="control"):
        QuasiStaticModel(load_preset("7218B"), control="sideways")


def test_fixed_tilt_moments_are_reactions():
    """Rigid shaft option: with the tilts held at zero the forces still balance (1e-6) and the ring's
    moments become reactions; a radial load on a single ACBB then needs a restraining moment, which
    is what a free ring avoids by tilting."""
    g = load_preset("7218B")
    m = QuasiStaticModel(g, fixed_tilt=True)
    r = m.solve(3000 * RPM, (2000.0, 0.0, 3000.0, 0.0, 0.0))
    assert abs(r.u[3]) < 1e-15 and abs(r.u[4]) < 1e-15
    R = r.ring_reaction()
    assert np.linalg.norm(R[:3] + r.loads[:3]) < 1e-6 * np.linalg.norm(r.loads[:3])
    assert abs(R[4]) > 1.0     # a moment reaction appears
    free = QuasiStaticModel(g).solve(3000 * RPM, (2000.0, 0.0, 3000.0, 0.0, 0.0), stiffness=False)
    assert abs(free.u[4]) > 1e-4


def test_start_from_a_neighbouring_solution_falls_back_to_the_rigid_ring_start():
    """A start u0 from the neighbouring load case of a sweep (7218B, 20,000 rpm, (3040, 912, 912) ->
    (3200, 960, 960) N) that fails the line search falls back to the rigid-ring start and returns the
    equilibrium: the sum of the ball forces on the inner ring equals the applied load within 1e-6
    relative (Newton's third law at the ring, as test_equilibrium_residual_over_sweep), the same
    displacement as the solve without u0 (to 1e-9 m)."""
    g = load_preset("7218B")
    m = QuasiStaticModel(g)
    w = 20000 * RPM
    loads = np.array((3200.0, 960.0, 960.0, 0.0, 0.0))
    u_prev = m.solve(w, 0.95 * loads, stiffness=False).u
    with pytest.raises(ConvergenceError):       # the direct solve from the neighbour alone fails
        m._solve(w, loads, u_prev, 1e-10, 30, False)
    r = m.solve(w, loads, u0=u_prev, stiffness=False)
    assert np.linalg.norm(r.ring_reaction() + loads) <= 1e-6 * np.linalg.norm(loads)
    cold = m.solve(w, loads, stiffness=False)
    assert np.max(np.abs(r.u - cold.u)) < 1e-9


# ---- signed speeds and a turning outer ring ----------------------------------------------------------------
def test_negative_speed_is_the_reversed_bearing():
    """Jones-Harris quasi-statics are even in the speed (centrifugal force ~ omega_m^2, gyroscopic moment ~
    omega_m omega_R), so the bearing turning the other way under the same loads has the same load distribution
    and displacement, with every ball and cage speed reversed. The negative speed is solved as the mirror image
    (x-z plane) of the positive one under the reflected loads (Fy, Mx reversed), so this checks the reflection
    of the loads, the displacement and the ball order as well."""
    g = load_preset("7218B")
    w = 8000 * RPM
    loads = (1000.0, 400.0, 3000.0, 25.0, -15.0)
    pos = solve_quasistatic(g, w, loads)
    neg = solve_quasistatic(g, -w, loads)
    assert neg.omega == -w
    np.testing.assert_allclose(neg.Q_i, pos.Q_i, rtol=1e-8, atol=1e-6)
    np.testing.assert_allclose(neg.alpha_o, pos.alpha_o, rtol=0, atol=1e-10)
    np.testing.assert_allclose(neg.u, pos.u, rtol=1e-8, atol=1e-12)
    np.testing.assert_allclose(neg.omega_m, -pos.omega_m, rtol=1e-8)
    np.testing.assert_allclose(neg.spin_roll_o, pos.spin_roll_o, rtol=1e-7, atol=1e-9)
    np.testing.assert_allclose(neg.stiffness, pos.stiffness, rtol=1e-6, atol=1e-6 * np.abs(pos.stiffness).max())
    assert neg.cage_speed == pytest.approx(-pos.cage_speed, rel=1e-9)
    # equilibrium: the balls' reaction on the inner ring balances the applied loads
    np.testing.assert_allclose(neg.ring_reaction(), -np.asarray(loads), rtol=1e-6, atol=1e-6)


def test_outer_ring_speed():
    """Both rings at the same speed: no relative motion, the cage turns with the rings (rigid rotation);
    an outer ring turning alone drives the cage the same way, faster than half its speed (the cage's
    pure-rolling share of the outer ring, (1 + D cos a / dm) / 2 > 1/2)."""
    g = load_preset("7218B")
    w = 3000 * RPM
    loads = (0.0, 0.0, 3000.0, 0.0, 0.0)
    both = solve_quasistatic(g, w, loads, omega_outer=w)
    assert both.cage_speed == pytest.approx(w, rel=1e-9)
    outer = solve_quasistatic(g, 0.0, loads, omega_outer=-w)
    assert outer.omega_outer == -w and outer.omega == 0.0
    assert -w < outer.cage_speed < -0.5 * w


def test_quasistatic_cli_signed_speeds(capsys):
    from bearing_core.cli import main
    assert main(["quasistatic", "--bearing", "7218B", "--speed-rpm", "-3000", "--fz", "3000", "--json"]) == 0
    import json
    d = json.loads(capsys.readouterr().out)
    assert d["speed_rpm"] == pytest.approx(-3000) and d["cage_speed_rpm"] < 0
    assert main(["quasistatic", "--bearing", "7218B", "--speed-rpm", "0", "--outer-speed-rpm", "2000",
                 "--fz", "3000", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["outer_speed_rpm"] == pytest.approx(2000) and 1000 < d["cage_speed_rpm"] < 2000
    assert main(["quasistatic", "--bearing", "7218B", "--speed-rpm", "-2e5", "--fz", "3000"]) == 2
    assert "--speed-rpm = -200000.0 is invalid; allowed: -190000 <= speed <= 190000 rpm" in capsys.readouterr().err
    assert main(["quasistatic", "--bearing", "7218B", "--speed-rpm", "-3000", "--fz", "3000",
                 "--traction", "kalker"]) == 2
    assert "--traction" in capsys.readouterr().err
