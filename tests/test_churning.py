"""Checks of bearing_core.lubrication.churning (seed 001 Eqs. 10, 12-17) against physics nobody here wrote."""
import math

import numpy as np
import pytest

from bearing_core.lubrication import churning as ch
from bearing_core.errors import BearingInputError
from bearing_core.bearing.geometry import load_preset, from_dict

RHO, ETA = 870.0, 0.03


def test_laminar_limit_is_petroff():
    # concentric laminar Couette flow (Petroff): T = 2 pi eta w R^3 B / c_r, exact; tolerance 1e-12
    R, B, c, w = 0.07, 0.02, 0.3e-3, 50.0
    Re, Ta = ch.churning_numbers(RHO, ETA, R, w, c)
    assert ch.churning_regime(Re, Ta) == ch.REGIME_LAMINAR
    T = ch.cylinder_churning_torque(RHO, ETA, w, B, 2 * R, c)
    assert -T == pytest.approx(2 * math.pi * ETA * w * R ** 3 * B / c, rel=1e-12)
    # and seed 001 Eq. 15 with Eq. 12 literally, Re on the diametral clearance
    mu_v = ch.viscous_friction_coefficient(Re, Ta)
    assert mu_v == pytest.approx(16.0 / Re, rel=1e-15)
    assert ch.cylinder_churning_power(RHO, ETA, w, B, 2 * R, c) == pytest.approx(
        math.pi * RHO * mu_v * w ** 3 * B * (2 * R) ** 4 / 64.0, rel=1e-12)


def test_taylor_number_definition():
    # Taylor (1923): Ta = (w R c_r / nu) sqrt(c_r / R), onset of vortices at ~41.3 (seed uses 41)
    R, c, w = 0.05, 1e-3, 30.0
    Re, Ta = ch.churning_numbers(RHO, ETA, R, w, c)
    assert Ta == pytest.approx(w * R * c / (ETA / RHO) * math.sqrt(c / R), rel=1e-12)
    assert Re == pytest.approx(2 * w * R * c / (ETA / RHO), rel=1e-12)


def test_regime_boundaries_and_jumps():
    # seed 001 Eqs. 12-14 as published: factor 1 below Ta = 41, 1.3 (Ta/41)^0.539474 above (Re < 2500),
    # 3.0 (Re/2500)^0.85596 above Re = 2500. The correlation is discontinuous: jump 1.3 at Ta = 41 and to
    # 3.0 at Re = 2500 (tolerance 1e-6 relative on the factors one ulp-ish either side)
    e = 1e-9
    assert ch.churning_factor(100.0, 41.0 * (1 - e)) == 1.0
    assert ch.churning_factor(100.0, 41.0 * (1 + e)) == pytest.approx(1.3, rel=1e-6)
    Ta = 100.0
    below = ch.churning_factor(2500.0 * (1 - e), Ta)
    above = ch.churning_factor(2500.0 * (1 + e), Ta)
    assert below == pytest.approx(1.3 * (Ta / 41.0) ** 0.539474, rel=1e-6)
    assert above == pytest.approx(3.0, rel=1e-6)
    # within each regime the factor is continuous and increasing
    for Re, Tas in ((1000.0, np.linspace(42, 600, 50)),):
        f = [ch.churning_factor(Re, t) for t in Tas]
        assert all(b > a for a, b in zip(f, f[1:]))
    f = [ch.churning_factor(r, 1e3) for r in np.linspace(2501, 1e5, 50)]
    assert all(b > a for a, b in zip(f, f[1:]))


def test_speed_exponents():
    # power ~ w^2 laminar (Petroff), ~ w^(2 + 0.85596) turbulent Couette (Eq. 14), ~ w^(2 + 0.539474)
    # in the vortex regime (mu_v ~ Ta^0.539474 / Re, Ta ~ Re ~ w) -- log-slope within 1e-6
    def slope(w, B=0.02, D=0.2, c=1e-3, rho=RHO, eta=ETA):
        p1 = ch.cylinder_churning_power(rho, eta, w, B, D, c)
        p2 = ch.cylinder_churning_power(rho, eta, w * 1.001, B, D, c)
        return math.log(p2 / p1) / math.log(1.001)

    assert slope(0.5) == pytest.approx(2.0, abs=1e-9)                       # laminar
    Re, Ta = ch.churning_numbers(RHO, ETA, 0.1, 200.0, 1e-3)
    assert ch.churning_regime(Re, Ta) == ch.REGIME_VORTEX
    assert slope(200.0) == pytest.approx(2.539474, abs=1e-6)
    Re, Ta = ch.churning_numbers(RHO, ETA, 0.1, 2000.0, 1e-3)
    assert ch.churning_regime(Re, Ta) == ch.REGIME_TURBULENT
    assert slope(2000.0) == pytest.approx(2.85596, abs=1e-6)


def test_torque_power_consistency_and_sign():
    for w in (-300.0, -1.0, 0.0, 2.0, 700.0):
        T = ch.cylinder_churning_torque(RHO, ETA, w, 0.02, 0.15, 0.5e-3)
        P = ch.cylinder_churning_power(RHO, ETA, w, 0.02, 0.15, 0.5e-3)
        assert P == pytest.approx(-T * w, rel=1e-15) and P >= 0.0
        assert T * w <= 0.0                                   # opposes the motion
        F = ch.ball_drag_force(RHO, 0.5, w, 0.125, 0.022)
        assert F * w <= 0.0


def test_ball_drag_is_textbook_drag():
    # F = 1/2 c_d rho A u^2, A = pi D^2 / 4, u = w_m dm / 2 (seed 001 Eq. 10); power Z F u
    rho, cd, wm, dm, D, Z = 860.0, 0.45, 400.0, 0.125, 0.0222, 16
    u = wm * dm / 2
    F = 0.5 * cd * rho * math.pi * D ** 2 / 4 * u ** 2
    assert -ch.ball_drag_force(rho, cd, wm, dm, D) == pytest.approx(F, rel=1e-13)
    assert ch.ball_drag_power(rho, cd, wm, dm, D, Z) == pytest.approx(Z * F * u, rel=1e-13)
    # Harris & Kotzalas Vol. 2 form in SI: c_d pi rho D^2 (dm w_m)^2 / 32
    assert F == pytest.approx(cd * math.pi * rho * D ** 2 * (dm * wm) ** 2 / 32.0, rel=1e-13)


def test_wrapper_and_errors():
    g = load_preset("7218B")
    r = ch.churning_losses(g, "iso-vg32-mineral", 323.15, 300.0, 130.0)
    cg = ch.ChurningGeometry.from_bearing(g)
    assert r["Q_ch_c"] == pytest.approx(-r["torque_cage"] * 130.0, rel=1e-14)
    assert r["Q_ch_s"] == pytest.approx(-r["torque_ir"] * 300.0, rel=1e-14)
    assert r["Q_ch_b"] == pytest.approx(-g.Z * r["force_ball"] * 130.0 * g.dm / 2, rel=1e-14)
    assert cg.c_c == pytest.approx(g.cage.land_clearance / 2)
    # hotter oil, less churning in laminar / vortex regimes
    r2 = ch.churning_losses(g, "iso-vg32-mineral", 363.15, 300.0, 130.0)
    assert r2["Q_ch_c"] < r["Q_ch_c"]
    with pytest.raises(BearingInputError) as e:
        ch.ChurningGeometry.from_bearing(g, c_c=-1.0)
    assert e.value.parameter == "c_c"
    with pytest.raises(BearingInputError) as e:
        ch.churning_losses(g, "iso-vg32-mineral", 323.15, 300.0, 130.0, oil_fraction=1.5)
    assert e.value.parameter == "oil_fraction"
    with pytest.raises(BearingInputError) as e:
        ch.ChurningGeometry.from_bearing(g, nonsense=1.0)
    assert e.value.parameter == "nonsense"


def _seed001_bearing(Db_mm, Z):
    """Seed 001's test bearing QJ1044 (four-point contact, 220 x 340 x 56 mm ISO envelope, 40 deg nominal
    contact angle, outer-ring-guided brass cage). Ball size and count are NOT in the paper: estimates."""
    return from_dict(dict(
        name="seed001-qj1044-estimate", ball_diameter_mm=Db_mm, number_of_balls=Z, pitch_diameter_mm=280.0,
        free_contact_angle_deg=40.0, fi=0.52, fo=0.52, width_mm=56.0, inner_ring_mass_kg=5.0,
        outer_ring_mass_kg=7.0, inner_ring_inertia_kg_mm2=1.5e5, inner_ring_tilt_inertia_kg_mm2=8e4,
        cage=dict(mass_kg=2.0, inertia_kg_mm2=4e4, guidance="outer", land_clearance_mm=1.0, material="brass")))


@pytest.mark.parametrize("Db,Z", [(31.75, 22), (34.925, 20)])
def test_seed001_churning_dominates_flooded_large_bearing(Db, Z):
    # Seed 001 section 4.3: for the oil-flooded 220 mm bearing at 1800 rpm, churning (cage + balls + inner
    # ring) is 60-80 % of the total loss. Library-only check: churning vs the race spin loss of the
    # quasi-static model (Coulomb spin moment 3/8 mu Q a E(e), mu = 0.06; Harris & Kotzalas Vol. 2), which
    # is the race loss of a ball that does not skid. Checked: churning >= 60 % over Fa = 3..36 kN.
    # NOT matched (recorded in docs/thermal.md): we get 93-99 % fully flooded, above the seed's 80 %; the
    # seed's pocket loss (~30 %) needs the dynamics.
    from scipy.special import ellipe
    from bearing_core.models.quasistatic import solve_quasistatic

    g = _seed001_bearing(Db, Z)
    w = 1800 * math.pi / 30
    for Fa in (3e3, 36e3):
        r = solve_quasistatic(g, w, (1000.0, 0.0, Fa, 0.0, 0.0), control="outer", stiffness=False)
        c = ch.churning_losses(g, "iso-vg68-mineral", 318.15, w, float(np.mean(r.omega_m)))
        churn = c["Q_ch_c"] + c["Q_ch_b"] + c["Q_ch_s"]
        spin = 0.0
        for Q, a, b, s in ((r.Q_i, r.a_i, r.b_i, r.spin_i), (r.Q_o, r.a_o, r.b_o, r.spin_o)):
            for q, aa, bb, ss in zip(Q, a, b, s):
                if q > 0:
                    spin += 3 / 8 * 0.06 * q * aa * ellipe(1 - (bb / aa) ** 2) * abs(ss)
        assert churn / (churn + spin) >= 0.60
        # seed 001: inner-ring churning 'mainly depends on the speed of the inner ring' -- load-free here
        assert c["regime_s"] == "turbulent-couette"
