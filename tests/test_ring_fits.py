"""Ring growth and fits (bearing_core.bearing.ring_fits) and their use in the quasi-static model."""
import math

import numpy as np
import pytest
from scipy.integrate import solve_bvp

from bearing_core.errors import BearingInputError
from bearing_core.bearing.geometry import load_preset
from bearing_core.bearing.materials import get_material
from bearing_core.models.quasistatic import solve_quasistatic
from bearing_core.bearing.ring_fits import (OperatingTemperatures, RingFits, lame_u, operating_geometry, ring_growth,
                                    rotating_annulus_u)

RPM = math.pi / 30.0
STEEL = get_material("steel")
# 7218B with its ISO 15 boundary dimensions d = 90 mm, D = 160 mm (dimension series 02, bore code 18)
G218 = load_preset("7218B", bore=0.090, outside_diameter=0.160)


def _bvp_annulus(a, b, omega, p_a, p_b, mat):
    """Independent numerical solution of the plane-stress axisymmetric Navier equation
    d/dr (1/r d(r u)/dr) = -(1 - nu^2) rho omega^2 r / E with sigma_r(a) = -p_a, sigma_r(b) = -p_b."""
    E, nu, rho = mat.E, mat.nu, mat.density
    c = E / (1 - nu ** 2)

    def f(r, y):  # y = (u / b, sigma_r / E)
        u, sr = y[0] * b, y[1] * E
        dudr = sr / c - nu * u / r          # from sigma_r = c (du/dr + nu u/r)
        st = c * (u / r + nu * dudr)
        return np.vstack([dudr / b, ((st - sr) / r - rho * omega ** 2 * r) / E])

    def bc(ya, yb):
        return np.array([ya[1] + p_a / E, yb[1] + p_b / E])

    r = np.linspace(a, b, 200)
    sol = solve_bvp(f, bc, r, np.zeros((2, r.size)), tol=1e-9, max_nodes=100000)
    assert sol.success
    return lambda x: sol.sol(x) * np.array([b, E])


def test_rotating_ring_closed_form_vs_numerical():
    """Rotating free annulus (Timoshenko & Goodier, Theory of Elasticity, Sec. 32) and Lame pressure
    solutions against an independent numerical solution of the plane-stress Navier equation
    (scipy solve_bvp), rel. 1e-6, for the 7218B inner ring (90 mm bore, equivalent 111 mm cylinder) at
    10,000 rpm and 50 MPa bore pressure."""
    a, b, w = 0.045, 0.0555, 10000 * RPM
    s = _bvp_annulus(a, b, w, 0.0, 0.0, STEEL)
    for r in (a, 0.5 * 102.79e-3, b):
        assert rotating_annulus_u(r, a, b, w, STEEL) == pytest.approx(s(r)[0], rel=1e-6)
    s = _bvp_annulus(a, b, 0.0, 50e6, 0.0, STEEL)
    for r in (a, b):
        assert lame_u(r, a, b, 50e6, 0.0, STEEL) == pytest.approx(s(r)[0], rel=1e-6)
    s = _bvp_annulus(a, b, 0.0, 0.0, 30e6, STEEL)
    assert lame_u(b, a, b, 0.0, 30e6, STEEL) == pytest.approx(s(b)[0], rel=1e-6)


def test_7218B_inner_ring_growth_at_10000_rpm():
    """The free 7218B inner ring grows about 5 um in radius at 10,000 rpm (the figure quoted for this
    bearing in the project's requirements; closed form rho w^2 b ((3+nu) a^2 + (1-nu) b^2) / (4E) =
    4.55 um for a ring ending at the raceway, 5.2 um at the raceway of the 111 mm equivalent ring);
    both within 4-6 um."""
    w = 10000 * RPM
    g1 = ring_growth(G218, w, RingFits())
    g2 = ring_growth(G218, w, RingFits(inner_ring_diameter=G218.inner_raceway_diameter))
    b = 0.5 * G218.inner_raceway_diameter
    closed = STEEL.density * w ** 2 * b * ((3 + STEEL.nu) * 0.045 ** 2 + (1 - STEEL.nu) * b ** 2) / (4 * STEEL.E)
    assert g2.inner_centrifugal == pytest.approx(closed, rel=1e-12)
    assert 4e-6 < g2.inner_centrifugal < g1.inner_centrifugal < 6e-6
    assert g1.shaft_fit_lost and g1.outer_radius == 0.0


def test_interference_fit_harris_relations():
    """Interference fits, equal materials, ring cylinder ending at the raceway: Harris & Kotzalas Vol. 1
    ('Fitting practice', recalled) inner raceway growth Delta d_i = I (d/d_i) (1 - (d_s/d)^2)/(1 - (d_s/d_i)^2)
    (solid shaft: I d/d_i) and outer raceway contraction Delta d_o = I_h (d_o/D)(1 - (D/D_h)^2)/(1 - (d_o/D_h)^2);
    rel. 1e-10."""
    g = G218
    d, Do, di, do = 0.090, 0.160, g.inner_raceway_diameter, g.outer_raceway_diameter
    I = 30e-6
    for ds in (0.0, 0.05):
        gr = ring_growth(g, 0.0, RingFits(shaft_interference=I, shaft_bore=ds, inner_ring_diameter=di))
        expect = I * (d / di) * (1 - (ds / d) ** 2) / (1 - (ds / di) ** 2)
        assert 2 * gr.inner_fit == pytest.approx(expect, rel=1e-10)
    Dh = 0.220
    gr = ring_growth(g, 0.0, RingFits(housing_interference=I, housing_outer_diameter=Dh, outer_ring_bore=do))
    expect = I * (do / Do) * (1 - (Do / Dh) ** 2) / (1 - (do / Dh) ** 2)
    assert -2 * gr.outer_fit == pytest.approx(expect, rel=1e-10)
    # thick housing (D_h -> inf): Delta d_o = I_h d_o / D
    gr = ring_growth(g, 0.0, RingFits(housing_interference=I, outer_ring_bore=do))
    assert -2 * gr.outer_fit == pytest.approx(I * do / Do, rel=1e-10)


def test_fit_pressure_ntn_catalogue():
    """Fit pressure against NTN, Ball and Roller Bearings (CAT. No. 2202/E), Sec. 17.4 'Fitting surface pressure',
    Table 17.4.1: steel shaft / inner ring, p = E Delta_d / (2 d) (1 - (d/D_i)^2) for a solid shaft and
    p = E Delta_d / (2 d) (1 - (d/D_i)^2) (1 - (d_0/d)^2) / (1 - (d_0/D_i)^2) for a hollow one (d_0 its bore,
    D_i the inner ring's average groove diameter, here its equivalent cylinder); rel. 1e-10. Units of the
    catalogue (N, mm) cancel: the relations are dimensionless in Delta_d / d."""
    g = G218
    d, Di = 0.090, 0.105
    I = 25e-6
    for d0 in (0.0, 0.040, 0.070):
        gr = ring_growth(g, 0.0, RingFits(shaft_interference=I, shaft_bore=d0, inner_ring_diameter=Di))
        expect = STEEL.E * I / (2 * d) * (1 - (d / Di) ** 2) * (1 - (d0 / d) ** 2) / (1 - (d0 / Di) ** 2)
        assert gr.shaft_pressure == pytest.approx(expect, rel=1e-10)


def test_thermal_clearance_reduction_iko_catalogue():
    """Clearance taken by a temperature difference: IKO needle roller bearing catalogue, Eq. (29),
    Delta_delta = alpha Delta_t E_o (alpha = 12.5e-6 /K for bearing steel, Delta_t the temperature difference
    between the outer ring and the inner ring with the rolling elements 'considered as one unit', E_o the outer
    ring bore (raceway) diameter; 15-20 K at high speeds). The model gives alpha Delta_t (d_o - Pd) exactly (balls
    and inner ring grow, d_i + 2 D = d_o - Pd); IKO's E_o differs from it by Pd / d_o (0.3 % for the 7218B):
    within 0.5 %, and bearing steel's coefficient is IKO's value."""
    assert STEEL.expansion == pytest.approx(12.5e-6, rel=1e-12)
    for dt in (15.0, 20.0):
        T = OperatingTemperatures(inner_ring=20 + dt, balls=20 + dt)
        gr = ring_growth(G218, 0.0, None, T)
        do = G218.outer_raceway_diameter
        assert -gr.clearance_change == pytest.approx(STEEL.expansion * dt * (do - G218.Pd), rel=1e-12)
        assert -gr.clearance_change == pytest.approx(12.5e-6 * dt * do, rel=5e-3)


def test_fit_loosening_speed():
    """A tight inner ring on a solid shaft of the same steel loses its fit at the speed where the
    differential centrifugal growth of ring bore and shaft equals I/2; from Timoshenko's rotating-disc
    solutions omega_L^2 = 2 E I / (rho a (3+nu) b^2) (ring a..b). The model's fit pressure is > 0 at
    0.999 omega_L and 0 at 1.001 omega_L."""
    I, a, b = 10e-6, 0.045, 0.0555
    wL = math.sqrt(2 * STEEL.E * I / (STEEL.density * a * (3 + STEEL.nu) * b ** 2))
    f = RingFits(shaft_interference=I)
    assert ring_growth(G218, 0.999 * wL, f).shaft_pressure > 0
    assert ring_growth(G218, 1.001 * wL, f).shaft_pressure == 0.0
    assert ring_growth(G218, 1.001 * wL, f).shaft_fit_lost


def test_uniform_temperature_is_a_similarity():
    """Everything (rings, balls, shaft, housing) of one steel at one temperature, free fits: the bearing
    scales by (1 + alpha dT): contact angle unchanged, clearance and pitch diameter scaled (1e-12)."""
    dT = 60.0
    T = OperatingTemperatures(inner_ring=20 + dT, outer_ring=20 + dT, balls=20 + dT)
    g2 = operating_geometry(G218, 0.0, RingFits(), T)
    s = 1 + STEEL.expansion * dT
    assert g2.alpha0 == pytest.approx(G218.alpha0, rel=1e-12)
    assert g2.Pd == pytest.approx(G218.Pd * s, rel=1e-9)
    assert g2.dm == pytest.approx(G218.dm * s, rel=1e-12) and g2.D == pytest.approx(G218.D * s, rel=1e-12)


def test_hot_inner_ring_reduces_clearance():
    """Inner ring 20 K warmer than outer ring and balls (free rings): the diametral clearance shrinks by
    2 alpha dT r_i (Harris & Kotzalas Vol. 1, thermal clearance change), 1e-12."""
    T = OperatingTemperatures(inner_ring=40.0)
    gr = ring_growth(G218, 0.0, None, T)
    assert gr.clearance_change == pytest.approx(-STEEL.expansion * 20.0 * G218.inner_raceway_diameter, rel=1e-12)


def test_quasistatic_with_fits():
    """solve_quasistatic(..., fits=...) solves the operating geometry: a 20 um shaft fit at 10,000 rpm
    reduces the 7218B clearance, hence its free contact angle, and under the same axial load the contact
    angle is smaller than without fits; an interference that removes the clearance is refused."""
    w = 10000 * RPM
    loads = (0.0, 0.0, 3000.0, 0.0, 0.0)
    fits = RingFits(shaft_interference=20e-6)
    g_op = operating_geometry(G218, w, fits)
    r0 = solve_quasistatic(G218, w, loads, stiffness=False)
    r1 = solve_quasistatic(G218, w, loads, stiffness=False, fits=fits)
    assert r1.geometry.alpha0 == g_op.alpha0 < G218.alpha0
    assert np.all(r1.alpha_i < r0.alpha_i)
    with pytest.raises(BearingInputError, match="operating diametral clearance"):
        operating_geometry(G218, w, RingFits(shaft_interference=0.8e-3))


def test_bad_input():
    """Missing boundary dimensions and out-of-range fits are refused naming the parameter."""
    g = load_preset("7218B")
    with pytest.raises(BearingInputError, match="bore"):
        ring_growth(g, 1000.0)
    with pytest.raises(BearingInputError, match="shaft_bore"):
        ring_growth(G218, 0.0, RingFits(shaft_bore=0.1))
    with pytest.raises(BearingInputError, match="housing_outer_diameter"):
        ring_growth(G218, 0.0, RingFits(housing_outer_diameter=0.15))
    with pytest.raises(BearingInputError, match="temperatures.balls"):
        ring_growth(G218, 0.0, None, OperatingTemperatures(balls=float("nan")))
