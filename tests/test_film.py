"""Tests of bearing_core.lubrication.film (Hamrock-Dowson film thickness, film parameter, inlet-heating factor)."""
import math

import numpy as np
import pytest

from bearing_core.lubrication import film
from bearing_core.errors import BearingInputError


def test_published_worked_example_stachowiak_batchelor():
    """Stachowiak & Batchelor, Engineering Tribology (EHL chapter, problem with printed answers; seen as a
    tutorbin.com question): a steel ball, d = 30 mm, rolls without sliding from rest down a steel plate at
    45 deg covered by oil, eta0 = 50 cP, alpha = 2.2e-8 m^2/N, E = 2.1e11 Pa, nu = 0.3, rho = 7800 kg/m^3.
    Printed answers: h_min = 0.059 um after 1 cm and 0.281 um after 1 m.
    The book's conventions for the inputs (not Hamrock-Dowson's): reduced radius R' = 1/(1/Rx + 1/Ry) = d/4
    in place of Rx, U with (U_A + U_B)/2 = v/2, E' = E/(1 - nu^2), k = 1.0339 (Ry/Rx)^0.636 = 1.0339.
    The ball speed after s metres of rolling is v = sqrt(10/7 g s sin 45) (solid sphere, no slip).
    Tolerance 1.5% (answers printed to 2-3 digits)."""
    d, eta0, alpha, E, nu, rho, g = 0.03, 0.05, 2.2e-8, 2.1e11, 0.3, 7800.0, 9.81
    W = rho * math.pi * d ** 3 / 6.0 * g * math.cos(math.pi / 4)
    Ep = E / (1.0 - nu ** 2)
    for s, published in ((0.01, 0.059e-6), (1.0, 0.281e-6)):
        v = math.sqrt(10.0 / 7.0 * g * s * math.sin(math.pi / 4))
        r = film.film_thickness(v / 2.0, eta0, alpha, d / 4.0, d / 4.0, Ep, W)
        assert r.k == pytest.approx(1.0339, rel=1e-12)
        assert r.h_min == pytest.approx(published, rel=0.015)
        # the numba kernel the dynamics calls gives the same number
        assert film.hd_minimum_film_nb(v / 2.0, eta0, alpha, d / 4.0, d / 4.0, Ep, W, 0.0) == pytest.approx(
            r.h_min, rel=1e-14)


@pytest.mark.parametrize("which, exps", [("central", (0.67, 0.53, -0.067)), ("minimum", (0.68, 0.49, -0.073))])
def test_exponents_hamrock_dowson_1977(which, exps):
    """Hamrock & Dowson 1977 Part III: H_c ~ U^0.67 G^0.53 W^-0.067, H_min ~ U^0.68 G^0.49 W^-0.073 at fixed k.
    Doubling u, eta0, alpha and Q in turn must scale h by 2^exponent (tolerance 1e-12)."""
    fn = film.hd_central_film_nb if which == "central" else film.hd_minimum_film_nb
    base = dict(u=12.0, eta0=0.04, alpha_pv=2.2e-8, Rx=6.5e-3, Ry=0.2, E_prime=2.26e11, Q=300.0, k=8.0)
    h0 = fn(**base)
    for key, e in (("u", exps[0]), ("eta0", exps[0]), ("alpha_pv", exps[1]), ("Q", exps[2])):
        h1 = fn(**{**base, key: 2.0 * base[key]})
        assert h1 / h0 == pytest.approx(2.0 ** e, rel=1e-12), key


def test_ellipticity_terms():
    """HD77 ellipticity terms: h_min ~ (1 - exp(-0.68 k)), h_c ~ (1 - 0.61 exp(-0.73 k)); k from Rx, Ry by the
    BH77 fit 1.0339 (Ry/Rx)^0.636 (seed 003 Eq. 23) or HD77's 1.03 (Ry/Rx)^0.64."""
    args = (10.0, 0.04, 2.2e-8, 5e-3, 5e-3 * 20.0, 2.26e11, 200.0)
    k = 1.0339 * 20.0 ** 0.636
    assert film.ellipticity_nb(5e-3, 0.1, film.ELLIPTICITY_BH77) == pytest.approx(k, rel=1e-14)
    assert film.ellipticity_nb(5e-3, 0.1, film.ELLIPTICITY_HD77) == pytest.approx(1.03 * 20.0 ** 0.64, rel=1e-14)
    hm_auto = film.hd_minimum_film_nb(*args, 0.0)
    hm_k2 = film.hd_minimum_film_nb(*args, 2.0)
    assert hm_auto / hm_k2 == pytest.approx((1 - math.exp(-0.68 * k)) / (1 - math.exp(-0.68 * 2.0)), rel=1e-12)
    hc_auto = film.hd_central_film_nb(*args, 0.0)
    hc_k2 = film.hd_central_film_nb(*args, 2.0)
    assert hc_auto / hc_k2 == pytest.approx((1 - 0.61 * math.exp(-0.73 * k)) / (1 - 0.61 * math.exp(-1.46)),
                                            rel=1e-12)


def test_seed003_modulus_as_printed_factor():
    """Seed 003 Eq. 23 uses E = 1.12e5 MPa (about E'/2) in U, G and W. With E'/2 instead of E' the HD77 minimum
    film grows by 2^(0.68 - 0.49 - 0.073) exactly (the Rx factor is unchanged)."""
    Ep = 2.24e11
    a = film.hd_minimum_film_nb(20.0, 0.04, 2.2e-8, 6.6e-3, 0.196, Ep, 400.0, 0.0)
    b = film.hd_minimum_film_nb(20.0, 0.04, 2.2e-8, 6.6e-3, 0.196, Ep / 2.0, 400.0, 0.0)
    assert b / a == pytest.approx(2.0 ** (0.68 - 0.49 - 0.073), rel=1e-12)


def test_film_parameter_seed003_roughness():
    """Seed 003 Sec. 3.1.1: Lambda = h_min / sqrt(sigma_r^2 + sigma_s^2) with 0.18 um on both surfaces."""
    s = math.hypot(film.SEED003_SIGMA_RACE, film.SEED003_SIGMA_BALL)
    assert s == pytest.approx(0.18e-6 * math.sqrt(2.0), rel=1e-14)
    assert film.film_parameter(1e-6, 0.18e-6, 0.18e-6) == pytest.approx(1e-6 / s, rel=1e-14)
    r = film.film_thickness(15.0, 0.04, 2.2e-8, 6.5e-3, 0.2, 2.26e11, 300.0, sigma=(0.18e-6, 0.18e-6))
    assert r.Lambda == pytest.approx(r.h_min / s, rel=1e-14)


def test_special_cases_and_arrays():
    assert film.hd_minimum_film_nb(0.0, 0.04, 2.2e-8, 6.5e-3, 0.2, 2.26e11, 300.0, 0.0) == 0.0
    assert math.isnan(film.hd_central_film_nb(10.0, 0.04, 2.2e-8, 6.5e-3, 0.2, 2.26e11, 0.0, 0.0))
    # sign of the entrainment speed does not matter; arrays broadcast
    r = film.film_thickness(np.array([-10.0, 10.0]), 0.04, 2.2e-8, 6.5e-3, 0.2, 2.26e11, np.array([300.0, 300.0]))
    assert r.h_min[0] == pytest.approx(r.h_min[1], rel=1e-15)
    assert r.h_c[0] > r.h_min[0]


def test_thermal_factor_properties():
    """Gupta et al. 1992 inlet-heating factor (coefficients as quoted in the bearing-dynamics literature, not
    checked against the 1992 paper): 1 at standstill, falls with speed and with slide-to-roll ratio, in (0, 1]."""
    f = film.thermal_reduction_nb
    assert f(0.0, 0.04, 0.03, 0.14, 1.5e9, 2.26e11, 0.0) == 1.0
    phis = [f(u, 0.04, 0.03, 0.14, 1.5e9, 2.26e11, 0.0) for u in (1.0, 5.0, 20.0, 50.0)]
    assert all(0.0 < p <= 1.0 for p in phis)
    assert all(b < a for a, b in zip(phis, phis[1:]))
    assert f(20.0, 0.04, 0.03, 0.14, 1.5e9, 2.26e11, 0.1) < f(20.0, 0.04, 0.03, 0.14, 1.5e9, 2.26e11, 0.0)
    iso = film.film_thickness(20.0, 0.04, 2.2e-8, 6.5e-3, 0.2, 2.26e11, 300.0)
    th = film.film_thickness(20.0, 0.04, 2.2e-8, 6.5e-3, 0.2, 2.26e11, 300.0, thermal=film.ThermalOptions())
    assert th.h_min == pytest.approx(iso.h_min * th.phi_T, rel=1e-14)
    assert th.phi_T < 1.0


@pytest.mark.parametrize("kw, name", [
    (dict(eta0=-1.0), "eta0"), (dict(Q=-5.0), "Q"), (dict(Rx=0.0), "Rx"), (dict(E_prime=0.0), "E_prime"),
    (dict(ellipticity="x"), "ellipticity"), (dict(u=float("nan")), "u"),
])
def test_bad_inputs_name_parameter(kw, name):
    args = dict(u=10.0, eta0=0.04, alpha_pv=2.2e-8, Rx=6.5e-3, Ry=0.2, E_prime=2.26e11, Q=300.0)
    extra = {k: v for k, v in kw.items() if k not in args}
    args.update({k: v for k, v in kw.items() if k in args})
    with pytest.raises(BearingInputError) as e:
        film.film_thickness(**args, **extra)
    assert e.value.parameter == name
    assert "allowed" in str(e.value)
