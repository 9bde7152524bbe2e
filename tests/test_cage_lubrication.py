"""Oil-lubricated cage (lubrication.pocket_film.ball_pocket_lubricated, the flooded guiding land) and the
lubrication regime (DynamicsOptions.lubrication)."""
import math

import numpy as np
import pytest

from bearing_core.models import dynamics_kernels as K
from bearing_core.lubrication.pocket_film import ball_pocket_lubricated
from bearing_core.models.dynamics import DynamicModel, DynamicsOptions, records_to_dict
from bearing_core.errors import BearingInputError
from bearing_core.bearing.geometry import load_preset

RPM = math.pi / 30
D, R = 0.02, 0.01
ETA, ALPHA, EP, SIG = 0.02, 2e-8, 1.5e10, 0.4e-6
KCB, CCB = 2e7, 50.0


def _pocket(dth_rp, c_p=1e-3, wz=0.0, wr=0.0, vrel=0.0, vr=0.0, vz=0.0, eta=ETA, sig=SIG, mu_bl=0.15,
            mu_ehl=0.05):
    r_p = 0.06
    return ball_pocket_lubricated(dth_rp / r_p, 0.0, vrel / r_p, 0.0, r_p, c_p, KCB, CCB, mu_bl, mu_ehl, 0.01,
                                  eta, ALPHA, EP, sig, D, vr, vz, wr, wz, 0.0, 0.0)


def _bht(ar):
    phi = 1.0 / (1.0 + 2.0 / (3.0 * ar))
    return 128.0 * ar * phi ** 2 * (0.131 * math.atan(ar / 2.0) + 1.683) ** 2


def test_bht_sphere_plane_value():
    """Brewe, Hamrock & Taylor's isoviscous-rigid fit at a_r = 1 (sphere on a plane) is 140.1, the
    constant 11.84^2 of the sphere-plane film load (Hamrock & Dowson, Ball Bearing Lubrication, 1981)."""
    assert _bht(1.0) == pytest.approx(140.1, rel=1e-3)
    assert math.sqrt(_bht(1.0)) == pytest.approx(11.84, rel=1e-3)


@pytest.mark.parametrize("along", ["axis", "around"])
def test_film_force_is_the_isoviscous_rigid_conformal_pocket_load(along):
    """Brewe, Hamrock & Taylor (J. Lubr. Technol. 101 (1979) 231), isoviscous-rigid minimum film,
    H = (h/R_x)(W/U)^2 = 128 a_r phi^2 [0.131 atan(a_r/2) + 1.683]^2, phi = 1/(1 + 2/(3 a_r)),
    U = eta u / (E' R_x), W = F / (E' R_x^2), u = (ball surface speed)/2. The pocket is a cylinder of radius
    R + c_p bored along r: entrainment along its axis (ball spinning about z) has R_x = R, R_y = R (R + c_p)
    / c_p; around it (spin about r) the radii swap. The net wall force of a ball 10 um from one wall (the
    other 1.99 mm away) equals the difference of the two walls' loads from that formula within 0.1 %."""
    w = 2000.0
    c_p, h = 1e-3, 10e-6
    Rc = R * (R + c_p) / c_p
    Rx, Ry = (R, Rc) if along == "axis" else (Rc, R)
    out = _pocket(c_p - h, c_p=c_p, wz=w if along == "axis" else 0.0, wr=w if along == "around" else 0.0)
    u = 0.5 * R * w

    def load(gap):
        return ETA * u * Rx * math.sqrt(_bht(Ry / Rx) * Rx / gap)

    assert -out[1] == pytest.approx(load(h) - load(2 * c_p - h), rel=1e-3)


def test_conformal_pocket_carries_more_than_a_flat_wall():
    """The conformal pocket wall carries more film load than a flat wall (c_p -> infinity) at the same gap
    and entrainment along the pocket axis: the ratio is sqrt(H_IR(a_r) / H_IR(1)) (Brewe-Hamrock-Taylor)."""
    w, h = 2000.0, 10e-6
    near = _pocket(1e-3 - h, c_p=1e-3, wz=w)[1]
    far = _pocket(1.0 - h, c_p=1.0, wz=w)[1]
    ar = (R + 1e-3) / 1e-3
    # the far wall of the small pocket (1.99 mm) also pushes; compare the near-wall loads
    Fnear = ETA * 0.5 * R * w * R * math.sqrt(_bht(ar) * R / h)
    assert -near == pytest.approx(Fnear - ETA * 0.5 * R * w * R * math.sqrt(_bht(ar) * R / (2e-3 - h)), rel=1e-3)
    assert -near > 5 * -far


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


def _mixed_mu(sig, eta, vs, Fc, c_p, mu_bl=0.15, mu_ehl=0.05):
    """Reference of the contact friction coefficient, written out from the formulas named in
    contact_kernels (Hamrock-Dowson films, Zhou-Hoeprich fluid fraction, Barus-Newtonian film shear)."""
    from bearing_core.lubrication.ehl_traction import fluid_fraction
    Rs, Rt = R, R * (R + c_p) / c_p            # entrainment along the pocket axis (spin about z)
    k = 1.0339 * (Rt / Rs) ** 0.636
    U, W, G = eta * 0.5 * vs / (EP * Rs), Fc / (EP * Rs ** 2), ALPHA * EP
    h = Rs * max(3.63 * U ** 0.68 * G ** 0.49 * W ** -0.073 * (1 - math.exp(-0.68 * k)),
                 8.70 * U ** 0.66 * W ** -0.21 * (1 - 0.85 * math.exp(-0.31 * k)))
    f = fluid_fraction(h / sig)
    a = (3 * Fc * math.sqrt(Rs * Rt) / (2 * EP)) ** (1 / 3)
    pm = Fc / (math.pi * a * a)
    mu_f = min(mu_ehl, eta * math.exp(ALPHA * pm) * vs / (h * pm))
    return (1 - f) * mu_bl + f * mu_f, h, mu_f


@pytest.mark.parametrize("sig", [5e-6, 0.4e-6, 1e-9])
def test_contact_friction_mixes_boundary_and_film_shear(sig):
    """In contact (ball pressed 5 um into a wall at 10 m/s of surface sliding along the pocket axis) the
    friction coefficient is (1 - f) mu_bl + f mu_film, f the Zhou-Hoeprich fluid fraction of
    Lambda = h_min / sigma (Hamrock-Dowson soft-EHL film of the conformal pocket), mu_film the Newtonian
    shear of the film at the Barus viscosity of the mean Hertz pressure, limited by mu_ehl. Rough
    (sigma 5 um): close to mu_bl; smooth (1 nm): the film shear. The viscous shear outside the contact
    (Goldman-Cox-Brenner, checked above) is subtracted (rel. 0.5 %)."""
    c_p, eta, vs = 1e-3, 0.02, 10.0
    out = _pocket(c_p + 5e-6, c_p=c_p, wz=1000.0, eta=eta, sig=sig)
    Fn, Fr = out[0], out[2]
    Fc = KCB * 5e-6
    mu, h, mu_f = _mixed_mu(sig, eta, vs, Fc, c_p)
    hfl = max(sig, 1e-9)
    fv = math.pi * eta * R * vs * (3.2 * max(math.log(R / hfl), 0.0) + 3.05)
    fv2 = math.pi * eta * R * vs * (3.2 * math.log(R / (2 * c_p + 5e-6)) + 3.05)
    assert abs(Fr) == pytest.approx(fv + mu * Fc - fv2, rel=5e-3)
    if sig > 1e-6:
        assert mu > 0.1                          # Lambda << 1: mostly boundary
    if sig < 1e-8:
        assert mu == pytest.approx(mu_f) and mu_f < 0.05


def test_flooded_pocket_at_bearing_speed_is_not_boundary():
    """A phenolic pocket (E' 15 GPa) of a 22 mm ball, 0.2 mm clearance, loaded with 30 N at 15 m/s of ball
    surface sliding, ISO VG 32 at 40 degC (28 mPa s, 20 GPa^-1), 0.4 um composite roughness: the soft-EHL
    film of the conformal pocket is several roughnesses thick and the friction is the film's, below the SKF
    full-film coefficient (Gupta 1984 Ch. 5 and the brief of a hydrodynamic pocket: 0.01-0.05)."""
    Rb, c_p, eta, E_ph = 0.0111, 0.2e-3, 0.028, 1.54e10
    r_p = 0.0625
    pen = 30.0 / KCB
    out = ball_pocket_lubricated((c_p + pen) / r_p, 0.0, 0.0, 0.0, r_p, c_p, KCB, 0.0, 0.15, 0.05, 0.01,
                                 eta, ALPHA, E_ph, 0.4e-6, 2 * Rb, 0.0, 0.0, 0.0, 15.0 / Rb, 0.0, 0.0)
    Fn, Fr = out[0], out[2]
    fv = math.pi * eta * Rb * 15.0 * (3.2 * math.log(Rb / 0.4e-6) + 3.05)
    fv2 = math.pi * eta * Rb * 15.0 * (3.2 * math.log(Rb / (2 * c_p + pen)) + 3.05)   # far wall, opposite
    mu = (abs(Fr) - fv + fv2) / 30.0
    assert 0.005 < mu < 0.05


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
    from bearing_core.lubrication.lubricants import get_oil
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


@pytest.mark.parametrize("land_film,integrator", [("stationary", "rk4"), ("moving", "auto")])
def test_power_balance_oil_regime_combined_load(land_film, integrator):
    """Conservation with the oil-lubricated cage (films, squeeze, EHL/boundary friction, flooded land):
    drive power + external-load power = dissipated power + d(kinetic + elastic energy)/dt over 0.02 s
    windows within 1 % (7218B, 4000 rpm, Fx 1 kN, Fz 3 kN, quasi-static start; RK4 at 1e-5 s, and the
    production integrator with the moving centre's land film, whose squeeze damping is too stiff for that
    fixed step where the cage runs close to its land)."""
    g = load_preset("7218B")
    m = DynamicModel(g, DynamicsOptions(oil_temperature=323.15, integrator=integrator, reduced="full",
                                        land_film=land_film))
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
