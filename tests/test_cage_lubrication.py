"""Oil-lubricated cage (contact_kernels.ball_pocket_lubricated, the flooded guiding land) and the
lubrication regime (DynamicsOptions.lubrication)."""
import math

import numpy as np
import pytest

from bearing_core import dynamics_kernels as K
from bearing_core.contact_kernels import ball_pocket_lubricated
from bearing_core.dynamics import DynamicModel, DynamicsOptions, records_to_dict
from bearing_core.errors import BearingInputError
from bearing_core.geometry import load_preset

RPM = math.pi / 30
D, R = 0.02, 0.01
ETA, ALPHA, EP, SIG = 0.02, 2e-8, 1.5e10, 0.4e-6
KCB, CCB = 2e7, 50.0


def _pocket(dth_rp, c_p=1e-3, wz=0.0, wr=0.0, vrel=0.0, vr=0.0, vz=0.0, eta=ETA, sig=SIG, mu_bl=0.15,
            mu_ehl=0.05):
    r_p = 0.06
    return ball_pocket_lubricated(dth_rp / r_p, 0.0, vrel / r_p, 0.0, r_p, c_p, KCB, CCB, mu_bl, mu_ehl, 0.01,
                                  eta, ALPHA, EP, sig, D, vr, vz, wr, wz, 0.0, 0.0)


def test_film_force_is_the_isoviscous_rigid_sphere_plane_load():
    """Brewe, Hamrock & Taylor (J. Lubr. Technol. 101 (1979) 231), isoviscous-rigid minimum film,
    H = (h/R)(W/U)^2 = 128 a_r phi^2 [0.131 atan(a_r/2) + 1.683]^2, phi = 1/(1 + 2/(3 a_r)), a_r = 1 for a
    sphere on a plane, U = eta u / (E' R), W = F / (E' R^2), u = mean surface speed = (ball surface speed)/2.
    The net wall force of a ball 10 um from one wall (the other 1.99 mm away) equals the difference of the
    two walls' loads from that formula within 0.1 %."""
    ar = 1.0
    phi = 1.0 / (1.0 + 2.0 / (3.0 * ar))
    H = 128.0 * ar * phi ** 2 * (0.131 * math.atan(ar / 2.0) + 1.683) ** 2
    w = 2000.0                                   # ball spin about z: surface speed R w on both walls
    c_p, h = 1e-3, 10e-6
    out = _pocket(c_p - h, c_p=c_p, wz=w)
    u = 0.5 * R * w

    def load(gap):
        return ETA * u * R * math.sqrt(H * R / gap)

    assert -out[1] == pytest.approx(load(h) - load(2 * c_p - h), rel=1e-3)


def test_film_shear_is_the_goldman_cox_brenner_torque():
    """Goldman, Cox & Brenner (Chem. Eng. Sci. 22 (1967) 637): a sphere rotating at Omega next to a wall at
    gap h feels the torque 8 pi eta R^3 Omega [(2/5) ln(R/h) + 0.3817]; the pocket's two walls add (within
    0.2 %; the kernel rounds 8 x 0.3817 to 3.05)."""
    w = 2000.0
    c_p, h = 1e-3, 20e-6
    out = _pocket(c_p - h, c_p=c_p, wz=w)
    T = sum(8 * math.pi * ETA * R ** 3 * w * (0.4 * math.log(R / g) + 0.3817) for g in (h, 2 * c_p - h))
    assert abs(out[5]) == pytest.approx(T, rel=2e-3)
    assert out[5] < 0                            # opposes the spin


@pytest.mark.parametrize("sig, mu_ref", [(5e-6, 0.15), (1e-9, 0.05)])
def test_contact_friction_blends_boundary_and_full_film(sig, mu_ref):
    """In contact (ball pressed 5 um into a wall at 10 m/s of surface sliding) the friction coefficient is
    the boundary value mu_bl for Lambda <= 1 (rough: sigma 5 um) and the full-film value mu_ehl for
    Lambda >= 3 (smooth); the viscous shear is removed with eta -> 1e-7 Pa s in the film terms (the EHL
    film of the contact uses the same eta, so the smooth case needs sigma -> 1 nm)."""
    c_p = 1e-3
    out = _pocket(c_p + 5e-6, c_p=c_p, wz=1000.0, eta=1e-7 if sig > 1e-6 else 0.02, sig=sig)
    Fn, Fr = out[0], out[2]
    if sig > 1e-6:
        assert abs(Fr) / Fn == pytest.approx(mu_ref, rel=2e-3)
    else:
        fv = math.pi * 0.02 * R * 10.0 * (3.2 * math.log(R / 1e-9) + 3.05)
        fv2 = math.pi * 0.02 * R * 10.0 * (3.2 * math.log(R / (2 * c_p + 5e-6)) + 3.05)
        Fc = KCB * 5e-6
        # the far wall's shear acts on the opposite side of the ball: its surface slides the other way
        assert abs(Fr) == pytest.approx(fv + mu_ref * Fc - fv2, rel=5e-3)


def test_pocket_energy_identity():
    """The dissipation the kernel reports (film + friction + damping) plus the rate of the penalty's
    elastic energy equals minus the power of the pocket forces on the relative motion, for arbitrary
    states (exact to rounding)."""
    rng = np.random.default_rng(1)
    r_p, c_p = 0.06, 2e-4
    for _ in range(20):
        dth = rng.uniform(-1.05, 1.05) * c_p / r_p
        thb_d, thc_d = rng.uniform(-1, 1) * 0.05 + 500.0, 500.0
        vr, vz, wr, wz, vcr = rng.normal(size=5) * np.array([0.01, 0.01, 300, 300, 0.01])
        Fn, Ft, Fr, Fz, Mr, Mz, Tw, Pl, Pd, Ue = ball_pocket_lubricated(
            dth, 0.0, thb_d, thc_d, r_p, c_p, KCB, CCB, 0.15, 0.05, 0.01, ETA, ALPHA, EP, SIG, D, vr, vz, wr,
            wz + thc_d, vcr, 0.0)
        vrel = (thb_d - thc_d) * r_p
        pen = abs(dth) * r_p - c_p
        dUe = KCB * pen * math.copysign(1.0, dth) * vrel if pen > 0 else 0.0
        power = Ft * vrel + Fr * (vr - vcr) + Fz * vz + Mz * wz + Mr * wr
        assert Pl + Pd + dUe == pytest.approx(-power, rel=1e-9, abs=1e-9)


def test_regime_mapping_keeps_the_solid_lubricated_seed000_setup():
    """lubrication='auto' with Kalker or Coulomb traction is the solid regime: the parameter vector is
    identical to lubrication='solid' (dry Coulomb cage, no oil at the cage), so seed 000's Kalker runs are
    unchanged; 'solid' with the oil traction runs Kalker, 'dry' runs Coulomb; 'oil' needs an oil traction."""
    g = load_preset("7218B")
    for trac in ("kalker", "coulomb"):
        a = DynamicModel(g, DynamicsOptions(traction=trac, mu=0.001))
        b = DynamicModel(g, DynamicsOptions(traction=trac, mu=0.001, lubrication="solid"))
        assert a.opt.regime == "solid"
        np.testing.assert_array_equal(a._params(False), b._params(False))
        assert a._params(False)[K.P_LUBE] == 0.0
    assert DynamicsOptions(lubrication="solid").race_traction == "kalker"
    assert DynamicsOptions(lubrication="dry").race_traction == "coulomb"
    assert DynamicsOptions().regime == "oil"
    with pytest.raises(BearingInputError, match="traction"):
        DynamicsOptions(traction="kalker", lubrication="oil").validate()
    with pytest.raises(BearingInputError, match="lubrication"):
        DynamicsOptions(lubrication="grease").validate()
    with pytest.raises(BearingInputError, match="lubrication"):
        DynamicsOptions(lubrication="dry", churning=True).validate()


def test_oil_regime_floods_the_land_with_the_oil_viscosity():
    """Oil regime: the guiding land carries the oil's viscosity at the oil temperature (VG 32 at 50 degC)
    without land_viscosity being set; a centred cage then loses the Petroff power 2 pi eta R^3 B w_c^2 / c
    (Petroff 1883; seed 001 Eq. 5 at zero eccentricity) to the land -- within 5 % over a pure-axial run
    (the cage stays within 5 % of the clearance of the centre). Solid regime: no land film."""
    from bearing_core.lubricants import get_oil
    g = load_preset("7218B")
    m = DynamicModel(g, DynamicsOptions(oil_temperature=323.15, integrator="auto"))
    m.initialize(3000 * RPM, (0.0, 0.0, 3000.0, 0.0, 0.0))
    eta = get_oil("iso-vg32-mineral").eta(323.15)
    assert m.P[K.P_ETA_LAND] == pytest.approx(eta, rel=1e-12) and m.P[K.P_ETA_PK] == pytest.approx(eta)
    d = records_to_dict(m.advance(0.04, record_dt=1e-3))
    late = slice(len(d["t"]) // 2, None)
    wc = d["cage_speed"][late]
    c = 0.5 * g.cage.land_clearance
    Rl = m.P[K.P_RLAND]
    ref = 2 * math.pi * eta * Rl ** 3 * g.cage.land_width * wc ** 2 / c
    assert np.all(np.hypot(d["cage_x"], d["cage_y"])[late] < 0.05 * c)
    assert d["P_land"][late].mean() == pytest.approx(ref.mean(), rel=0.05)
    s = DynamicModel(g, DynamicsOptions(traction="kalker"))
    s.initialize(3000 * RPM, (0.0, 0.0, 3000.0, 0.0, 0.0))
    assert s.P[K.P_ETA_LAND] == 0.0 and s.P[K.P_LUBE] == 0.0


def test_power_balance_oil_regime_combined_load():
    """Conservation with the oil-lubricated cage (films, squeeze, EHL/boundary friction, flooded land):
    drive power + external-load power = dissipated power + d(kinetic + elastic energy)/dt over 0.02 s
    windows within 1 % (7218B, 4000 rpm, Fx 1 kN, Fz 3 kN, RK4 at 1e-5 s, quasi-static start)."""
    g = load_preset("7218B")
    m = DynamicModel(g, DynamicsOptions(oil_temperature=323.15, integrator="rk4", reduced="full"))
    m.initialize(4000 * RPM, (1000.0, 0.0, 3000.0, 0.0, 0.0))
    d = records_to_dict(m.advance(0.06, record_dt=2e-4))
    t = d["t"]
    E = d["KE"] + d["U_elastic"]
    diss = sum(d[k] for k in ("P_race_inner", "P_race_outer", "P_pocket", "P_land", "P_drag", "P_damping",
                              "P_churn_cage", "P_churn_ring"))
    src = d["P_drive"] + d["P_ext"]
    assert d["P_pocket"].mean() > 0 and d["P_land"].mean() > 0
    for a, b in ((0.02, 0.04), (0.04, 0.0598)):
        s = (t >= a) & (t <= b)
        W_in = np.trapezoid(src[s], t[s])
        W_out = np.trapezoid(diss[s], t[s]) + (E[s][-1] - E[s][0])
        assert abs(W_out / W_in - 1) < 0.01, (a, W_in, W_out)
