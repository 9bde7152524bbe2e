"""Checks of the rheology-based EHL traction (bearing_core.lubrication.ehl_traction): analytic limits, published traction
levels and trends of named oils, mixed lubrication, rolling resistance. Each test names its source and
tolerance. Reference numbers marked 'recalled' come from memory of the cited papers (not re-checked against
them here); docs/tribology.md lists them."""
import math

import numpy as np
import pytest
from scipy import integrate

from bearing_core.contact import contact_kernels as ck
from bearing_core.lubrication import ehl_traction as E
from bearing_core.lubrication import lubricants as L
T40 = 313.15
R_DISC = 0.0127    # m, effective radius of a ball-on-disc / crowned twin-disc contact (Rx = Ry)
S = np.array([1e-4, 3e-4, 1e-3, 3e-3, 0.01, 0.02, 0.03, 0.05, 0.1])


def curve(oil, p, u, srr=S, T=T40, **kw):
    return E.disc_traction_curve(oil, T, p, u, srr, R_DISC, R_DISC, n=kw.pop("n", 24), **kw)


# ---- analytic limits -------------------------------------------------------------------------------
def _ellipse_integral(fun, a, b):
    return integrate.dblquad(lambda y, x: fun(x, y), -a, a, lambda x: -b * math.sqrt(1 - x * x / a ** 2),
                             lambda x: b * math.sqrt(1 - x * x / a ** 2), epsrel=1e-8)[0]


def _roelands(oil, T):
    o = L.get_oil(oil)
    eta0 = o.eta(T)
    return eta0, math.log(eta0) + 9.67, o.roelands(T)


@pytest.mark.parametrize("p0,u", [(1.2e9, 10.0), (2.0e9, 2.0)])
def test_small_slip_viscoelastic_limit(p0, u):
    """Small slip: each point is a linear Maxwell liquid entering at constant strain rate, stress
    tau_N (1 - exp(-tau_e / tau_N)) with tau_N = eta(p) s u / h (Roelands) and tau_e = G_e s s_in / h
    (Johnson & Tevaarwerk 1977, linear regime; exact for constant properties along the path). Independent
    scipy quadrature of that integral over the ellipse; tolerance 1 %. Where the viscosity is high
    everywhere that matters (2 GPa, 2 m/s) it is the purely elastic slope mu / s = 4 G_e b / (pi h p_max)
    (the distance from the inlet integrates to 8 a b^2 / 3) within 5 % (the rest is the outer annulus where
    the pressure, hence the viscosity, is low and the film stays Newtonian)."""
    s = 1e-7
    mu, info = curve("santotrac-50", p0, u, srr=s, n=48)
    eta0, lne, z = _roelands("santotrac-50", T40)
    a, b, Q, h, Ge = info["a"], info["b"], info["Q"], info["h_c"], info["G_e"]

    def tau(x, y):
        p = p0 * math.sqrt(max(0.0, 1 - x * x / a ** 2 - y * y / b ** 2))
        tn = eta0 * math.exp(lne * ((1 + p / 1.96e8) ** z - 1)) * s * u / h
        te = Ge * s * (b * math.sqrt(max(0.0, 1 - x * x / a ** 2)) + y) / h
        return tn * (-math.expm1(-te / tn))

    assert mu == pytest.approx(_ellipse_integral(tau, a, b) / Q, rel=0.01)
    if p0 > 1.5e9:
        assert mu / s == pytest.approx(4 * Ge * b / (math.pi * h * p0), rel=0.05)


def test_small_slip_newtonian_limit():
    """Without elasticity and at small slip the film is Newtonian: mu / s = (u / h) int eta(p) dA / Q with the
    Roelands viscosity (independent scipy quadrature of the same ellipse). Low pressure (0.3 GPa) and hot
    mineral oil keep eta gamma_dot << tau_0. Tolerance 1 %."""
    p0, u, s = 0.3e9, 5.0, 1e-9
    mu, info = curve("iso-vg32-mineral", p0, u, srr=s, T=373.15, elastic=False, thermal=False, n=48)
    eta0, lne, z = _roelands("iso-vg32-mineral", 373.15)
    a, b, Q, h = info["a"], info["b"], info["Q"], info["h_c"]

    def f(x, y):
        p = p0 * math.sqrt(max(0.0, 1 - x * x / a ** 2 - y * y / b ** 2))
        return eta0 * math.exp(lne * ((1 + p / 1.96e8) ** z - 1))

    I = _ellipse_integral(f, a, b)
    assert mu / s == pytest.approx(u / h * I / Q, rel=0.01)


def test_large_slip_bounded_by_limiting_shear_stress():
    """The shear never exceeds the Bair-Winer limiting shear stress tau_L = tau_L0 + gamma_L p, so
    mu <= gamma_L (tau_L0 = 0); isothermal, the plateau approaches gamma_L (within 3 % at s = 1) because
    the Eyring stress at the Roelands viscosity exceeds tau_L over almost the whole ellipse."""
    g = L.get_oil("santotrac-50").gamma_L
    s = np.array([0.05, 0.2, 0.5, 1.0])
    mu_iso, _ = curve("santotrac-50", 1.2e9, 10.0, srr=s, thermal=False)
    mu_th, _ = curve("santotrac-50", 1.2e9, 10.0, srr=s, thermal=True)
    assert np.all(mu_iso <= g * (1 + 1e-12)) and np.all(mu_th <= g * (1 + 1e-12))
    assert mu_iso[-1] == pytest.approx(g, rel=0.03)
    assert np.all(mu_th <= mu_iso + 1e-12)          # shear heating only lowers the traction


# ---- measured traction levels of named oils ----------------------------------------------------------
@pytest.mark.parametrize("oil,p0,u,mu_meas,src", [
    # Santotrac 50: disc-machine maximum traction coefficient ~0.09-0.1 at 1-2 GPa, 40 degC (Johnson &
    # Tevaarwerk, Proc. R. Soc. A 356 (1977); Loewenthal & Rohn, NASA TP-2154 (1983)); recalled
    ("santotrac-50", 1.2e9, 10.0, 0.095, "JT77 / NASA TP-2154, recalled"),
    # mineral oil (HVI 650 class): maximum ~0.06 at ~1 GPa, 40 degC (Johnson & Tevaarwerk 1977; Evans &
    # Johnson, Proc. IMechE 200C (1986)); recalled
    ("iso-vg68-mineral", 1.0e9, 5.0, 0.06, "JT77 / EJ86 mineral oil, recalled"),
])
def test_peak_traction_named_oils(oil, p0, u, mu_meas, src):
    """Peak (maximum over slide-roll ratio) traction coefficient against the measured level. Tolerance
    25 %: the model parameters are literature values for the oil class (tau_0, gamma_L, G; recalled),
    not fitted to these curves, and gamma_L alone differs by 10-20 % between sources (Bair & Winer 1979,
    Hoglund & Jacobson 1986)."""
    mu, _ = curve(oil, p0, u, srr=np.linspace(0.002, 0.1, 50))
    assert mu.max() == pytest.approx(mu_meas, rel=0.25), src
    # the traction-fluid / mineral-oil ranking of every disc-machine study
    if oil == "santotrac-50":
        mu_min, _ = curve("iso-vg68-mineral", p0, u, srr=np.linspace(0.002, 0.1, 50))
        assert mu.max() > 1.3 * mu_min.max()


# ---- trends ----------------------------------------------------------------------------------------
def test_trends_pressure_speed_temperature():
    """Loewenthal & Rohn, NASA TP-2154 (1983), Santotrac 50 and TDF-88 over a wide range: traction rises
    with contact pressure up to about 2 GPa and falls with surface speed; the apparent stiffness of the
    contact (initial slope) falls with speed. Traction falls with temperature (viscosity; Johnson &
    Tevaarwerk 1977). Checked as strict monotonicity of the peak over 0.6 / 1.0 / 1.5 GPa, 5 / 20 / 50 m/s,
    40 / 80 / 120 degC, and of the slope at s = 1e-4 over speed. Known departures (docs/tribology.md): the
    model's peak levels off at about 1.5 GPa (shear heating of the higher limiting stress), not 2 GPa, and
    with a pressure-independent film modulus G its initial slope does not rise with pressure."""
    s = np.concatenate(([1e-4], np.linspace(0.002, 0.1, 30)))
    peak = lambda **kw: curve("santotrac-50", srr=s, **kw)[0]
    byp = [peak(p=p, u=10.0) for p in (0.6e9, 1.0e9, 1.5e9)]
    byu = [peak(p=1.2e9, u=u) for u in (5.0, 20.0, 50.0)]
    byT = [peak(p=1.2e9, u=10.0, T=T) for T in (313.15, 353.15, 393.15)]
    assert byp[0][1:].max() < byp[1][1:].max() < byp[2][1:].max()
    assert byu[0][1:].max() > byu[1][1:].max() > byu[2][1:].max()
    assert byu[0][0] > byu[1][0] > byu[2][0]
    assert byT[0][1:].max() > byT[1][1:].max() > byT[2][1:].max()


def test_thermal_softening_at_large_slip():
    """Shear heating makes the traction curve fall past its maximum at high slide-roll ratio (the
    'thermal region' of Evans & Johnson 1986, measured on every disc machine at sliding speeds of m/s):
    at 20 m/s the traction at s = 0.5 is below the maximum by more than 10 %."""
    mu, _ = curve("iso-vg68-mineral", 1.0e9, 20.0, srr=np.array([0.01, 0.02, 0.05, 0.1, 0.5]))
    assert mu[-1] < 0.9 * mu.max()


# ---- mixed lubrication -----------------------------------------------------------------------------
def test_fluid_fraction_zhou_hoeprich():
    """Zhou & Hoeprich (J. Tribol. 113, 1991) fit 1.21 L^0.64 / (1 + 0.37 L^1.26) normalised to 1 at its
    maximum (L = (0.64 / (0.37 * 0.62))^(1/1.26) = 2.258, value 1.0026): 0 at L = 0, monotone, continuous at
    the maximum, 1 beyond (exact properties of the formula)."""
    lam = np.linspace(0.0, 5.0, 501)
    f = np.array([E.fluid_fraction(x) for x in lam])
    assert f[0] == 0.0 and np.all(np.diff(f) >= -1e-12) and f[-1] == 1.0
    lp = (0.64 / (0.37 * 0.62)) ** (1 / 1.26)
    fmax = 1.21 * lp ** 0.64 / (1 + 0.37 * lp ** 1.26)
    assert fmax == pytest.approx(1.0026, abs=1e-4)
    assert E.fluid_fraction(lp - 1e-9) == pytest.approx(1.0, abs=1e-9)
    assert E.fluid_fraction(1.0) == pytest.approx(1.21 / 1.37 / fmax, rel=1e-12)


def test_low_lambda_boundary_friction_dominates():
    """Lambda -> 0: the asperities carry the load and mu -> mu_bl (SKF's boundary coefficient 0.15) at
    any slide-roll ratio above the regularisation; Lambda >= 2.26: the roughness has no effect (exact)."""
    mu_s, info = curve("iso-vg32-mineral", 1.0e9, 0.01, srr=np.array([1.0, 1.5]), Rq=5e-6)   # thin film, rough
    assert info["Lambda"] < 0.01
    assert np.all(np.abs(mu_s - L.MU_BOUNDARY) < 0.02)
    s = np.array([0.01, 0.05])
    smooth, info0 = curve("iso-vg32-mineral", 1.0e9, 5.0, srr=s)
    fine, _ = curve("iso-vg32-mineral", 1.0e9, 5.0, srr=s, Rq=info0["h_c"] / 2.3)
    assert np.allclose(smooth, fine, rtol=1e-12)
    mid, info1 = curve("iso-vg32-mineral", 1.0e9, 5.0, srr=s, Rq=info0["h_c"] / 1.0)
    assert np.all(mid > smooth)


# ---- rolling resistance and the contact interface ----------------------------------------------------
def test_rolling_force_scaling_and_power():
    """F_R = 2.86 E' Rx^2 k^0.348 G^0.022 U^0.66 W^0.47 (Harris & Kotzalas Vol. 2 Ch. 5): exponents in u
    and Q exact; applied as the moment F_R Rx about the rolling axis, it dissipates F_R u in pure rolling
    (relative rolling rate u / Rx) (1e-6, the tanh regularisation being saturated)."""
    Ep, Rx, k = 2.26e11, 0.008, 8.0
    f1 = E.hydrodynamic_rolling_force(10.0, 0.03, 2e-8, Rx, k, Ep, 1000.0)
    assert E.hydrodynamic_rolling_force(20.0, 0.03, 2e-8, Rx, k, Ep, 1000.0) / f1 == pytest.approx(2 ** 0.66)
    assert E.hydrodynamic_rolling_force(10.0, 0.03, 2e-8, Rx, k, Ep, 3000.0) / f1 == pytest.approx(3 ** 0.47)
    prm = L.rheology_traction_params(ck.traction_params(u_min=0.5), "iso-vg32-mineral", T40, Ep, 80e9 * 3.4, 0.0)
    a, b, D, Ry = 2.0e-3, 0.25e-3, 0.02, 0.0104
    Q = 1000.0
    p = 1.5 * Q / (math.pi * a * b)
    u = 10.0
    out = E.ehl_ellipse_traction(a, b, p, D, 0.0, Rx, Ry, 0.0, 0.0, 0.0, u / Rx, 0.0, u, prm,
                                 *ck.ellipse_quadrature(6, 2))
    FR = E.hydrodynamic_rolling_force(u, prm[E.R_ETA0], prm[E.R_ALPHA], Rx, a / b, Ep, Q)
    assert out[5] == pytest.approx(FR * u, rel=1e-6)
    assert out[3] == pytest.approx(-FR * Rx, rel=1e-6)      # moment opposes the relative rolling


def test_power_identity_ehl():
    """Random contact states: the dissipated power equals minus the power of the returned forces and
    moments on the relative motion (the identity of contact_kernels.ellipse_traction), and is >= 0
    (1e-10 relative), with mixed lubrication, heating and rolling resistance on."""
    rng = np.random.default_rng(3)
    prm = L.rheology_traction_params(ck.traction_params(u_min=0.5), "iso-vg68-mineral", 330.0, 2.26e11,
                                     80e9 * 3.4, 0.3e-6)
    quad = ck.ellipse_quadrature(6, 3)
    Dd, f = 0.02, 0.52
    R = 2 * f * Dd / (2 * f + 1)
    for _ in range(100):
        a = rng.uniform(0.3e-3, 3e-3)
        b = a / rng.uniform(1.0, 10.0)
        Q = rng.uniform(10.0, 3000.0)
        p = 1.5 * Q / (math.pi * a * b)
        st = rng.normal(size=5) * np.array([1.0, 0.3, 500.0, 2000.0, 200.0])
        u = rng.normal() * 10
        F = E.ehl_ellipse_traction(a, b, p, Dd, R, 0.008, 0.0104, *st, u, prm, *quad)
        Ft, Fm, Mn, Mm, Mt, P = F
        assert P >= 0
        P2 = -(Ft * st[0] + Fm * st[1] + Mn * st[2] + st[3] * (Mm - Dd / 2 * Ft) + st[4] * (Mt + Dd / 2 * Fm))
        assert P2 == pytest.approx(P, rel=1e-10, abs=1e-12)


def test_rolling_resistance_in_quasistatic_tribological_model():
    """Quasi-static tribological model (7218B, 3000 rpm, Fz 3 kN, EHL traction): switching the rolling-
    resistance moment on raises the drive power by the rolling-resistance power sum(F_R u) over all ball-race
    contacts (F_R of Harris & Kotzalas Vol. 2 Ch. 5 at each contact's load, entrainment speed and radii);
    tolerance 2 % (the balls' slips re-balance slightly); power in = heat out in both cases (1e-6)."""
    from bearing_core.models.dynamics import DynamicsOptions
    from bearing_core.lubrication.film import ellipticity_nb
    from bearing_core.bearing.geometry import load_preset
    from bearing_core.models.quasistatic_tribo import solve_tribo_quasistatic
    g = load_preset("7218B")
    w = 3000 * math.pi / 30
    q = {}
    for rr in (True, False):
        o = DynamicsOptions(traction="lubricated", reduced="axisymmetric", integrator="auto", rolling_resistance=rr)
        q[rr] = solve_tribo_quasistatic(g, w, (0, 0, 3000, 0, 0), o, tol=1e-9)
        lo = q[rr].losses
        heat = sum(v for k, v in lo.items() if k in ("P_race_inner", "P_race_outer", "P_drag", "P_churn_cage",
                                                   "P_churn_ring"))
        assert heat == pytest.approx(lo["P_drive"], rel=1e-6)
    Ep = 2.0 / ((1 - g.ring_material.nu ** 2) / g.ring_material.E + (1 - g.ball_material.nu ** 2) / g.ball_material.E)
    oil = L.get_oil("iso-vg32-mineral")
    eta0, alpha = oil.eta(T40), oil.alpha(T40)
    PR = 0.0
    r = q[True]
    for race, sg, f in (("i", -1.0, g.fi), ("o", 1.0, g.fo)):
        for Q, al, u in zip(getattr(r, "Q_" + race), getattr(r, "alpha_" + race), getattr(r, "u_" + race)):
            Rx = 0.5 * g.D * (1 + sg * g.D * math.cos(al) / g.dm)
            Ry = f * g.D / (2 * f - 1)
            PR += E.hydrodynamic_rolling_force(abs(u), eta0, alpha, Rx, ellipticity_nb(Rx, Ry, 0), Ep, Q) * abs(u)
    dP = q[True].losses["P_drive"] - q[False].losses["P_drive"]
    assert dP == pytest.approx(PR, rel=0.02)


def test_roughness_is_a_geometry_parameter():
    """Rq of balls and raceways live in the bearing geometry (defaults 0.03 / 0.08 um, typical precision
    finishes) and set the composite roughness of the EHL traction; DynamicsOptions.roughness > 0 overrides
    both; out-of-range values raise BearingInputError naming the field."""
    import dataclasses
    from bearing_core.models.dynamics import DynamicModel, DynamicsOptions
    from bearing_core.errors import BearingInputError
    from bearing_core.bearing.geometry import load_preset
    g = load_preset("7218B")
    assert (g.ball_roughness, g.race_roughness) == (0.03e-6, 0.08e-6)
    tp = DynamicModel(g, DynamicsOptions(traction="lubricated"))._ehl_params(T40)
    assert tp[E.R_RQ] == pytest.approx(math.hypot(0.03e-6, 0.08e-6))
    assert tp[E.R_LUBMODEL] == ck.TRACTION_EHL
    tp2 = DynamicModel(g, DynamicsOptions(traction="lubricated", roughness=0.2e-6))._ehl_params(T40)
    assert tp2[E.R_RQ] == pytest.approx(math.sqrt(2) * 0.2e-6)
    with pytest.raises(BearingInputError, match="race_roughness"):
        dataclasses.replace(g, race_roughness=-1e-7)
    with pytest.raises(BearingInputError, match="mu_boundary"):
        DynamicModel(g, DynamicsOptions(mu_boundary=1.5))


@pytest.mark.parametrize("rq,thermal,elastic,quad", [(0.3e-6, True, True, (4, 4)), (0.0, False, False, (6, 3)),
                                                     (0.05e-6, True, True, (6, 2))])
def test_pair_kernel_equals_two_single_contacts(rq, thermal, elastic, quad):
    """ehl_pair_traction_into (a ball's inner and outer contact in one kernel, the right-hand side's EHL
    path) against two ehl_ellipse_traction_into calls: the same arithmetic per point, only the shear law's
    loop runs over both contacts' points, so the results agree to 1e-14 of each output's largest value
    (an identity of the two code paths, no external reference). Random loaded contact states of both
    rolling directions, with mixed lubrication, shear heating and elasticity on or off, and pairs with one
    unloaded contact (the single-contact fallback); quadratures filling 16 and 32 columns."""
    rng = np.random.default_rng(7)
    prm = L.rheology_traction_params(ck.traction_params(u_min=0.5), "iso-vg68-mineral", 330.0, 2.26e11,
                                     80e9 * 3.4 if elastic else 0.0, rq, thermal=thermal)
    if not elastic:
        prm[E.R_GFILM] = 0.0
    sc = E.ehl_scratch(*ck.ellipse_quadrature(*quad))
    Dd = 0.02
    Rd = (2 * 0.52 * Dd / (2 * 0.52 + 1), 2 * 0.53 * Dd / (2 * 0.53 + 1))
    single, pair = [], []
    for it in range(60):
        args = []
        for c in range(2):
            a = rng.uniform(0.3e-3, 3e-3)
            b = a / rng.uniform(1.0, 10.0)
            Q = 0.0 if (it % 10 == 9 and c == it // 10 % 2) else rng.uniform(10.0, 3000.0)
            p = 1.5 * Q / (math.pi * a * b)
            st = rng.normal(size=5) * np.array([1.0, 0.3, 500.0, 2000.0, 200.0])
            u = rng.normal() * 10
            args.append((a, b, p, Rd[c], rng.uniform(0.007, 0.011), *st, u))
        r = E.ehl_pair_traction_into(*args[0], *args[1], Dd, prm, sc)
        for c in range(2):
            a, b, p, R, Rx = args[c][:5]
            single.append(E.ehl_ellipse_traction_into(a, b, p, Dd, R, Rx, 0.01, *args[c][5:], prm, sc))
            pair.append(r[6 * c:6 * c + 6])
    single, pair = np.array(single), np.array(pair)
    scale = np.max(np.abs(single), axis=0)
    assert np.all(scale > 0)
    assert np.all(np.abs(pair - single) <= 1e-14 * scale)
