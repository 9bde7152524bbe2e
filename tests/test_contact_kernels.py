"""Tests of bearing_core.contact.contact_kernels (per-contact building blocks of the transient dynamics)."""
import math

import numpy as np
import pytest
from scipy import special

from bearing_core.contact import contact_kernels as ck
from bearing_core.lubrication import pocket_film as pf
from bearing_core.contact import kinematics as kin
from bearing_core.bearing.geometry import load_preset
from bearing_core.models.quasistatic import QuasiStaticModel, solve_quasistatic

RPM = math.pi / 30.0
CASES = [("wan-105", 15000 * RPM, (0, 0, 889.84, 0, 0)),
         ("7218B", 10000 * RPM, (4000, 1000, 6000, 0, 0))]


@pytest.fixture(scope="module", params=CASES, ids=[c[0] for c in CASES])
def qs(request):
    name, omega, loads = request.param
    g = load_preset(name)
    res = solve_quasistatic(g, omega, loads, stiffness=False)
    model = QuasiStaticModel(g)          # same default table (n = 361) as the solver's
    Cr, Cz = model._centres(res.u)
    return g, res, model.hz.table, Cr, Cz


def _rel(x, ref):
    x, ref = np.asarray(x), np.asarray(ref)
    return np.max(np.abs(x - ref) / np.maximum(np.abs(ref), 1e-300))


# ---- 1. normal contact: one geometry with the quasi-static model (tolerance 1e-9 relative) --------
def test_ball_race_contact_matches_quasistatic(qs):
    g, res, tab, Cr, Cz = qs
    out = np.array([ck.ball_race_contact(res.X[j, 0], res.X[j, 1], Cr[j], Cz[j], (g.fo - 0.5) * g.D,
                                         (g.fi - 0.5) * g.D, tab.inner, tab.outer, tab.alpha0,
                                         tab.dalpha) for j in range(g.Z)])
    do, nor, noz, ao, Qo, a_o, b_o, p_o, di, nir, niz, ai, Qi, a_i, b_i, p_i = out.T
    assert np.all(Qo > 0) and np.all(Qi > 0)
    for x, ref in ((Qo, res.Q_o), (Qi, res.Q_i), (ao, res.alpha_o), (ai, res.alpha_i), (a_o, res.a_o),
                   (b_o, res.b_o), (a_i, res.a_i), (b_i, res.b_i), (p_o, res.p_o), (p_i, res.p_i),
                   (do, res.delta_o), (di, res.delta_i)):
        assert _rel(x, ref) < 1e-9
    np.testing.assert_allclose(nor, np.cos(ao), rtol=0, atol=1e-14)
    np.testing.assert_allclose(niz, -np.sin(ai), rtol=0, atol=1e-14)


def test_separated_contact_is_zero(qs):
    g, res, tab, Cr, Cz = qs
    # move the ball inwards along n_o by twice its deflection: the outer contact separates
    X = res.X[0] - 2 * res.delta_o[0] * res.X[0] / np.hypot(*res.X[0])
    out = ck.ball_race_contact(X[0], X[1], Cr[0], Cz[0], (g.fo - 0.5) * g.D, (g.fi - 0.5) * g.D,
                               tab.inner, tab.outer, tab.alpha0, tab.dalpha)
    assert out[0] < 0 and out[4:8] == (0.0, 0.0, 0.0, 0.0)


def test_normal_damping():
    """Hunt & Crossley 1975: F = Q (1 + chi delta_dot), chi = 3 (1 - e) / (2 v_in); never pulls."""
    chi = ck.hunt_crossley_chi(0.8, 0.5)
    assert chi == pytest.approx(0.6, rel=1e-15)
    assert ck.normal_contact_force(100.0, 1e-6, 0.1, ck.DAMP_HUNT_CROSSLEY, chi) == pytest.approx(106.0)
    assert ck.normal_contact_force(100.0, 1e-6, -1e3, ck.DAMP_HUNT_CROSSLEY, chi) == 0.0
    assert ck.normal_contact_force(0.0, 0.0, 5.0, ck.DAMP_HUNT_CROSSLEY, chi) == 0.0  # no jump at onset
    assert ck.normal_contact_force(100.0, 1e-6, 0.1, ck.DAMP_LINEAR, 50.0) == pytest.approx(105.0)
    assert ck.normal_contact_force(100.0, -1e-9, 0.1, ck.DAMP_LINEAR, 50.0) == 0.0
    assert ck.normal_contact_force(100.0, 1e-6, 0.1, ck.DAMP_NONE, 50.0) == 100.0


# ---- 2. contact kinematics vs kinematics.py (pure rolling; 1e-9 relative) -------------------------
def _qs_rolling_state(g, res):
    """Contact kinematics of every ball in the QS pure-rolling state (ball centre on the pitch circle,
    as kinematics.py assumes)."""
    rb = 0.5 * g.dm
    wm, wR, be = res.omega_m, res.omega_R, res.beta
    out = []
    for j in range(g.Z):
        wr = -wR[j] * math.sin(be[j])
        wz = wR[j] * math.cos(be[j]) + wm[j]          # absolute = relative to cage + cage speed
        vt = wm[j] * rb
        ko = ck.contact_kinematics(rb, 0.0, vt, 0.0, wr, 0.0, wz, 0.0, 0.0, 0.0, 0.0,
                                   math.cos(res.alpha_o[j]), math.sin(res.alpha_o[j]), g.D)
        ki = ck.contact_kinematics(rb, 0.0, vt, 0.0, wr, 0.0, wz, res.omega, 0.0, 0.0, 0.0,
                                   -math.cos(res.alpha_i[j]), -math.sin(res.alpha_i[j]), g.D)
        out.append(ko + ki)
    return np.array(out).T


def test_pure_rolling_kinematics(qs):
    g, res, *_ = qs
    vso, vmo, so, rmo, rto, uo, vsi, vmi, si, rmi, rti, ui = _qs_rolling_state(g, res)
    uo_ref = res.omega_m * 0.5 * g.dm * (1 + g.D * np.cos(res.alpha_o) / g.dm)
    ui_ref = (res.omega - res.omega_m) * 0.5 * g.dm * (1 - g.D * np.cos(res.alpha_i) / g.dm)
    # rolling-direction sliding at both contact centres vanishes (relative to the rolling speed)
    assert np.max(np.abs(vso) / uo_ref) < 1e-9 and np.max(np.abs(vsi) / ui_ref) < 1e-9
    # no transverse sliding in this planar state
    assert np.max(np.abs(vmo) / uo_ref) < 1e-12 and np.max(np.abs(vmi) / ui_ref) < 1e-12
    # spin: 1e-9 relative to the rolling speed of the contact (spin_o ~ 0 under outer control)
    assert np.max(np.abs(so - res.spin_o) / res.roll_o) < 1e-9
    assert _rel(si, res.spin_i) < 1e-9
    assert _rel(np.abs(rmo), res.roll_o) < 1e-9 and _rel(np.abs(rmi), res.roll_i) < 1e-9
    # rolling (entrainment) speed: -omega_m (dm/2)(1 + D cos ao / dm) at the outer race, etc.
    assert _rel(-uo, uo_ref) < 1e-9 and _rel(ui, ui_ref) < 1e-9


def test_spin_matches_kinematics_module(qs):
    """Spin of contact_kinematics equals kinematics.contact_spin_roll evaluated independently."""
    g, res, *_ = qs
    si_ref, ri_ref, so_ref, ro_ref = kin.contact_spin_roll(res.omega, res.omega_m, res.omega_R, res.beta,
                                                           res.alpha_i, res.alpha_o)
    vso, vmo, so, rmo, rto, uo, vsi, vmi, si, rmi, rti, ui = _qs_rolling_state(g, res)
    assert np.max(np.abs(so - so_ref) / ro_ref) <= 1e-9
    assert np.max(np.abs(si - si_ref)) <= 1e-9 * np.max(np.abs(si_ref))


# ---- 3. traction over the ellipse -----------------------------------------------------------------
QUAD = ck.ellipse_quadrature(24, 24)


def _trac(a, b, Q, vs_t=0.0, vs_m=0.0, ws=0.0, wrm=0.0, wrt=0.0, u=10.0, model=0, params=None,
          D=0.02, R=0.0, quad=QUAD):
    p = 1.5 * Q / (math.pi * a * b)
    params = ck.traction_params(mu0=0.1, v_reg=1e-3) if params is None else params
    return np.array(ck.ellipse_traction(a, b, p, D, R, vs_t, vs_m, ws, wrm, wrt, u, model, params, *quad))


def test_quadrature_integrates_pressure():
    """Hertz pressure integrates to Q (tolerance 0.1 %; exact by construction)."""
    for n in (4, 12, 24):
        xi, wxi, zeta, wz = ck.ellipse_quadrature(n, n)
        integral = 1.0 * 0.3e-3 * 2.1e-3 * np.sum(np.outer((1 - xi ** 2) * wxi, wz))  # p_max = 1
        assert integral == pytest.approx(2 * math.pi / 3 * 0.3e-3 * 2.1e-3, rel=1e-12)


@pytest.mark.parametrize("ang", [0.0, 0.7, 2.0])
def test_coulomb_translation_slip(ang):
    """Pure translation slip, Coulomb, v >> v_reg: F = -mu0 Q v_hat (tolerance 0.5 %; exact here)."""
    Q, v = 1500.0, 2.0
    F = _trac(2.0e-3, 0.25e-3, Q, vs_t=v * math.cos(ang), vs_m=v * math.sin(ang), R=0.0105)
    mu0 = 0.1
    assert math.hypot(F[0], F[1]) == pytest.approx(mu0 * Q, rel=1e-9)
    assert F[0] == pytest.approx(-mu0 * Q * math.cos(ang), abs=1e-9 * Q)
    assert F[1] == pytest.approx(-mu0 * Q * math.sin(ang), abs=1e-9 * Q)
    assert F[5] == pytest.approx(mu0 * Q * v, rel=1e-9)


def test_spin_moment_circular_johnson():
    """Circular Hertz contact in full spin sliding: M = 3 pi mu Q a / 16 (Johnson 1985; Harris &
    Kotzalas M_s = 3 mu Q a E(e) / 8 with E = pi/2). Tolerance 0.5 %."""
    a, Q, mu = 0.5e-3, 1000.0, 0.1
    F = _trac(a, a, Q, ws=1e4)   # v = w r >> v_reg except within r < 1e-7 m
    M_ref = 3 * math.pi * mu * Q * a / 16
    assert -F[2] == pytest.approx(M_ref, rel=5e-3)
    assert abs(F[0]) < 1e-9 * Q and abs(F[1]) < 1e-9 * Q


@pytest.mark.parametrize("k", [2.0, 8.0])
def test_spin_moment_elliptical(k):
    """Elliptical contact, full spin sliding: M = (3/8) mu Q a E(e), e^2 = 1 - b^2/a^2 (Harris &
    Kotzalas Vol. 2 Ch. 4; closed form of the polar integral of p r). Tolerance 0.5 %."""
    a, Q, mu = 2.0e-3, 1000.0, 0.1
    b = a / k
    F = _trac(a, b, Q, ws=1e4)
    M_ref = 3.0 / 8.0 * mu * Q * a * special.ellipe(1 - 1 / k ** 2)
    assert -F[2] == pytest.approx(M_ref, rel=5e-3)


def test_traction_power_identity_and_sign():
    """Random states, both models, curvature on: P_loss >= 0 and equals minus the power of the
    returned force/moments on the relative motion (1e-10 relative)."""
    rng = np.random.default_rng(1)
    lub = ck.traction_params(A=-0.03, B=2.0, C=25.0, D=0.03, u_min=1e-3)
    Dd, f = 0.02, 0.52
    R = 2 * f * Dd / (2 * f + 1)
    for _ in range(200):
        a = rng.uniform(0.3e-3, 3e-3)
        b = a / rng.uniform(1.0, 10.0)
        st = rng.normal(size=5) * np.array([1.0, 0.3, 500.0, 2000.0, 200.0])
        u = rng.normal() * 10
        for model, par in ((0, None), (1, lub)):
            F = _trac(a, b, 800.0, *st, u=u, model=model, params=par, D=Dd, R=R)
            Ft, Fm, Mn, Mm, Mt, P = F
            assert P >= 0
            P2 = -(Ft * st[0] + Fm * st[1] + Mn * st[2] + st[3] * (Mm - Dd / 2 * Ft)
                   + st[4] * (Mt + Dd / 2 * Fm))
            assert P2 == pytest.approx(P, rel=1e-10, abs=1e-12)


def test_lubricated_curve_shape():
    """mu(s) = (A + B s) exp(-C s) + D (seed 002), s = v / max(|u|, u_min); uniform slip over the
    ellipse gives F = mu(s) Q (1e-9)."""
    A, B, C, D = -0.03, 2.0, 25.0, 0.03
    par = ck.traction_params(A=A, B=B, C=C, D=D, u_min=1e-3)
    for s in (1e-4, 1e-3, 0.01, 0.04, 0.2, 1.0):
        ref = (A + B * s) * math.exp(-C * s) + D
        assert ck.traction_coefficient(s * 5.0, -5.0, 1, par) == pytest.approx(ref, rel=1e-12)
    # small s: linear with slope B - A C
    s = 1e-6
    assert ck.traction_coefficient(s * 5, 5.0, 1, par) / s == pytest.approx(B - A * C, rel=1e-4)
    # u_roll -> 0 guard
    assert ck.traction_coefficient(1e-3, 0.0, 1, par) == pytest.approx((A + B) * math.exp(-C) + D)
    Q, s = 1200.0, 0.03
    F = _trac(1.5e-3, 0.2e-3, Q, vs_t=-s * 8.0, u=8.0, model=1, params=par)
    mu = (A + B * s) * math.exp(-C * s) + D
    assert F[0] == pytest.approx(mu * Q, rel=1e-9) and abs(F[1]) < 1e-12 * Q


def test_curvature_term_rolling_slip():
    """Pure rolling at the contact centre with conformal curvature (seed 004): sliding along t at
    x is w_roll (rho(x) - D/2); the net force opposes the ball's centre-point rolling offset and the
    moment about m equals sum(rho F_t)."""
    Dd, f, a, b, Q = 0.02, 0.52, 2e-3, 0.25e-3, 1000.0
    R = 2 * f * Dd / (2 * f + 1)
    F = _trac(a, b, Q, wrm=100.0, R=R, D=Dd)
    # rho(x) - D/2 <= 0 everywhere in the contact (rho(+-a) = sqrt(D^2/4 - a^2) < D/2), so
    # v_t <= 0 and the traction is along +t
    assert F[0] > 0 and abs(F[1]) < 1e-12
    F0 = _trac(a, b, Q, wrm=100.0, R=0.0, D=Dd)
    assert np.all(F0 == 0.0)


# ---- 4. ball-pocket contact -----------------------------------------------------------------------
def _pocket(dth, ddth=0.0, C=0.0, rp=0.05, cp=0.1e-3, K=1e7, mu=0.1, **kw):
    args = dict(vr=0.0, vz=0.0, wr=0.0, wz=0.0, vcr=0.0, vcz=0.0)
    args.update(kw)
    return np.array(ck.ball_pocket_contact(1.0 + dth, 1.0, 100.0 + ddth, 100.0, rp, cp, K, C, mu, 1e-3,
                                           0.01, args["vr"], args["vz"], args["wr"], args["wz"],
                                           args["vcr"], args["vcz"]))


def test_pocket_clearance_and_direction():
    rp, cp, K = 0.05, 0.1e-3, 1e7
    th_cl = cp / rp
    for d in (0.0, 0.5 * th_cl, -0.999 * th_cl):
        assert np.all(_pocket(d, ddth=10.0, C=100.0) == 0.0)      # inside the clearance: no force
    out = _pocket(1.5 * th_cl)
    assert out[0] == pytest.approx(K * 0.5 * cp, rel=1e-9) and out[1] == -out[0]
    out = _pocket(-1.5 * th_cl)
    assert out[1] == pytest.approx(K * 0.5 * cp, rel=1e-9)       # pushed forward (+t)
    # only pushing: a separating velocity with strong damping never gives a pulling force
    assert np.all(_pocket(1.01 * th_cl, ddth=-1.0, C=1e6) == 0.0)
    # continuity at the clearance edge (elastic part): F -> 0 linearly
    f1 = _pocket(th_cl * (1 + 1e-9))[0]
    assert 0 < f1 < K * 1e-9 * cp * 1.01
    # wrap across +-pi
    assert _pocket(2 * math.pi + 1.5 * th_cl)[0] == pytest.approx(K * 0.5 * cp, rel=1e-6)


def test_pocket_friction():
    """Coulomb friction mu F opposing the ball-surface sliding on the wall (regularised)."""
    th = 1.5 * 0.1e-3 / 0.05
    out = _pocket(th, wz=1000.0)       # wall at +t: surface point velocity -(D/2) wz along r
    Fn, Ft, Fr, Fz, Mr, Mz = out
    assert Fr == pytest.approx(0.1 * Fn, rel=1e-9) and Fz == 0.0
    # the friction moment opposes wz
    assert Mz < 0 and Mz == pytest.approx(-0.005 * Fr, rel=1e-12)
    out = _pocket(th, vz=-3.0, wz=100.0)   # ball wz = cage speed: pure axial sliding
    assert out[3] == pytest.approx(0.1 * out[0], rel=1e-9)


# ---- 5. inline arctangent and cube root ---------------------------------------------------------------
# Both are measured against the exact value, taken from the x87 extended-precision (64-bit mantissa) functions
# of numpy on long doubles: their own error is ~1/2048 of a double ulp. The C library's double functions are
# no reference: glibc's cbrt is up to 2.75 ulp off (1e-32, 7.9e-19), and numpy replaces it by its own SIMD
# code on AVX-512 machines only, so a comparison with np.cbrt passes or fails with the CPU.
def _ulp_error(got, x, ref_fn):
    """|got - exact| in units of the spacing of doubles at got (largest over the array)."""
    ref = ref_fn(np.asarray(x, dtype=np.longdouble))
    got = np.asarray(got, dtype=float)
    return float(np.max(np.abs(got.astype(np.longdouble) - ref) / np.spacing(np.abs(got)).astype(np.longdouble)))


ATAN_X = np.concatenate([np.geomspace(1e-12, 1e12, 4001), [0.4375, 0.6875, 1.1875, 2.4375],
                         np.nextafter([0.4375, 0.6875, 1.1875, 2.4375], 0.0)])
ATAN_X = np.concatenate([ATAN_X, -ATAN_X])
CBRT_X = np.concatenate([np.geomspace(1e-300, 1e300, 6001), 2.0 ** np.arange(-1000, 1001, 7), [1.0, 8.0, 27.0]])
# Published bounds of the algorithms, for exact IEEE evaluation (the strict build): fdlibm s_atan.c < 1 ulp,
# FreeBSD s_cbrt.c < 0.667 ulp. The fast build contracts a * b + c into fused multiply-adds (one rounding
# instead of two): in cbrt_pos the polynomial's rounding is removed by the final Newton step and the fused last
# step t + t r rounds once; in atan the fused polynomial and reduction steps move the result by less than the
# last step's rounding. Bound of the fast build: the published one plus one rounding of the result, 0.5 ulp.
ATAN_ULP_STRICT, CBRT_ULP_STRICT = 1.0, 0.667
FAST_EXTRA_ULP = 0.5


def test_inline_atan_against_exact():
    """contact_kernels.atan / atan2 (fdlibm s_atan.c) against the exact arctangent over 1e-12..1e12 of both
    signs and at the breakpoints of the argument reduction; atan2 for the contact normals of all quadrants
    (inline for x > 0, the C library otherwise); NaN propagates, +-inf gives +-pi/2."""
    got = np.array([ck.atan(v) for v in ATAN_X])
    assert _ulp_error(got, ATAN_X, np.arctan) <= ATAN_ULP_STRICT + FAST_EXTRA_ULP
    assert ck.atan(0.0) == 0.0
    assert math.isnan(ck.atan(math.nan))
    assert ck.atan(math.inf) == pytest.approx(0.5 * math.pi, rel=1e-16)
    ang = np.linspace(-math.pi, math.pi, 721)
    for r in (1e-6, 1.0, 3e3):
        yy, xx = r * np.sin(ang), r * np.cos(ang)
        got = np.array([ck.atan2(a, b) for a, b in zip(yy, xx)])
        ok = got != 0.0
        err = _ulp_error(got[ok], yy[ok], lambda y, x=xx[ok]: np.arctan2(y, np.asarray(x, dtype=np.longdouble)))
        assert err <= ATAN_ULP_STRICT + FAST_EXTRA_ULP


def test_pocket_kernels_from_wrapped_angle():
    """ball_pocket_contact_rel / ball_pocket_lubricated_rel, given the wrapped azimuth difference, return
    what ball_pocket_contact / ball_pocket_lubricated return for the two azimuths (the same code after the
    wrap), also a full turn away. Tolerance 1e-10 relative: the compilations may order the wrap's sums
    differently (re-association), ~1e-15 rad on the angle, amplified ~1e3x in the penetration r_p |dth| - c_p."""
    for th_b, th_c in ((1.0 + 3e-3, 1.0), (7.0 - 2.5e-3, 7.0 + 2.0 * math.pi), (-20.0, -20.0 + 1e-4)):
        kw = (100.0, 99.0, 0.05, 0.1e-3, 1e7, 50.0)
        tail = (0.01, 0.3, -0.2, 50.0, -30.0, 0.01, 0.0)
        a = ck.ball_pocket_contact(th_b, th_c, *kw, 0.1, 1e-3, *tail)
        b = ck.ball_pocket_contact_rel(ck.wrap_angle(th_b - th_c), *kw, 0.1, 1e-3, *tail)
        np.testing.assert_allclose(a, b, rtol=1e-10, atol=0.0)
        lub = (0.15, 0.05, 0.01, 0.02, 2e-8, 2.3e9, 4e-7)
        a = pf.ball_pocket_lubricated(th_b, th_c, *kw, *lub, *tail)
        b = pf.ball_pocket_lubricated_rel(ck.wrap_angle(th_b - th_c), *kw, *lub, *tail)
        np.testing.assert_allclose(a, b, rtol=1e-10, atol=0.0)


def test_inline_cbrt_against_exact():
    """contact_kernels.cbrt_pos (FreeBSD s_cbrt.c) against the exact cube root over 1e-300..1e300 and at powers
    of two; 0, inf and NaN through numpy."""
    got = np.array([ck.cbrt_pos(v) for v in CBRT_X])
    assert _ulp_error(got, CBRT_X, np.cbrt) <= CBRT_ULP_STRICT + FAST_EXTRA_ULP
    assert ck.cbrt_pos(0.0) == 0.0 and ck.cbrt_pos(math.inf) == math.inf and math.isnan(ck.cbrt_pos(math.nan))


_STRICT_SCRIPT = """
import json, numpy as np
from bearing_core.contact import contact_kernels as ck
from bearing_core.numerics import jit
assert jit.PLAIN_MATH
a = np.asarray(json.loads(input()))
c = np.asarray(json.loads(input()))
print(json.dumps([[ck.atan(v) for v in a], [ck.cbrt_pos(v) for v in c]]))
"""


def test_inline_atan_cbrt_strict_build_bounds_and_fast_build_against_it(tmp_path):
    """In the strict build (BEARING_PLAIN_MATH=1, a subprocess with its own cache) atan and cbrt_pos keep their
    published bounds; the fast build differs from the strict one by at most one rounding of the result."""
    import json
    import os
    import subprocess
    import sys
    env = dict(os.environ, BEARING_PLAIN_MATH="1", NUMBA_CACHE_DIR=str(tmp_path / "nb"))
    r = subprocess.run([sys.executable, "-c", _STRICT_SCRIPT], env=env, capture_output=True, text=True, timeout=600,
                       input=json.dumps(ATAN_X.tolist()) + "\n" + json.dumps(CBRT_X.tolist()) + "\n")
    assert r.returncode == 0, r.stderr[-3000:]
    atan_s, cbrt_s = (np.asarray(v) for v in json.loads(r.stdout))
    assert _ulp_error(atan_s, ATAN_X, np.arctan) <= ATAN_ULP_STRICT
    assert _ulp_error(cbrt_s, CBRT_X, np.cbrt) <= CBRT_ULP_STRICT
    atan_f = np.array([ck.atan(v) for v in ATAN_X])
    cbrt_f = np.array([ck.cbrt_pos(v) for v in CBRT_X])
    assert np.all(np.abs(atan_f - atan_s) <= np.spacing(np.abs(atan_s)))
    assert np.all(np.abs(cbrt_f - cbrt_s) <= np.spacing(cbrt_s))
