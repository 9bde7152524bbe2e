"""Compilation flags of the hot kernels (bearing_core.numerics.jit) and the numerical shortcuts of the EHL traction.

* The fast build (fastmath without nnan / ninf, error_model='numpy') against the strict build
  (BEARING_PLAIN_MATH=1, run in a subprocess): traction kernels over a grid of contacts and the dynamics
  right-hand side with its outputs. Both builds run the same algorithm, so they may differ only by the
  rounding of re-associated sums and fused multiply-adds (relative 1e-12 typically); the bound 1e-9 of
  the largest value of each output leaves room for branch decisions (thermal-root regime, limiting-stress
  cap) taken on the other side of a rounding error, where the outputs are continuous.
* The thermal Eyring root (ehl_traction.thermal_eyring_root) against the root converged by bisection
  over the whole range of the Eyring argument and thermal coefficient, within its documented bounds.
"""
import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


# ---------------------------------------------------------------------------------------------------
# the same computations in both builds
def _ehl_grid():
    """ehl_ellipse_traction over p_max x u x slide-roll ratio x spin (ISO VG 68 mineral at 70 degC,
    steel on steel, composite roughness 0.1 um: full film and mixed lubrication both occur), the
    7218B inner-contact geometry."""
    from bearing_core.lubrication import ehl_traction as E
    from bearing_core.lubrication import lubricants as L
    from bearing_core.contact.contact_kernels import ellipse_quadrature, traction_params
    prm = L.rheology_traction_params(traction_params(u_min=1e-3), "iso-vg68-mineral", 343.15, 2.26e11,
                                     80e9 * 0.95, 1e-7)
    q = ellipse_quadrature(6, 2)
    D, Rdef, Rx, Ry = 0.0222, 0.0114, 0.0092, 0.0118
    out = []
    for pm in (0.5e9, 1.2e9, 2.5e9):
        for u in (0.05, 2.0, 25.0):
            for srr in (0.0, 1e-4, 3e-3, 0.05, 0.6):
                for spin in (0.0, 40.0, -300.0):
                    a, b = 1.6e-3 * pm / 1.2e9, 2.3e-4 * pm / 1.2e9
                    r = E.ehl_ellipse_traction(a, b, pm, D, Rdef, Rx, Ry, srr * u, 0.2 * srr * u, spin, 3.0, -2.0,
                                               u, prm, *q)
                    out.append(list(r))
    return out


def _simple_grid():
    """contact_kernels.ellipse_traction with the Coulomb and the illustrative curve laws."""
    from bearing_core.contact import contact_kernels as ck
    q = ck.ellipse_quadrature(6, 2)
    prm = ck.traction_params(mu0=0.1, v_reg=1e-3, A=-0.05, B=1.2, C=9.0, D=0.05)
    out = []
    for model in (ck.TRACTION_COULOMB, ck.TRACTION_CURVE):
        for vs in (0.0, 1e-4, 0.01, 0.3):
            for spin in (0.0, 50.0):
                out.append(list(ck.ellipse_traction(1.5e-3, 2.2e-4, 1.1e9, 0.0222, 0.0114, vs, -0.3 * vs, spin,
                                                    2.0, -1.0, 12.0, model, prm, *q)))
    return out


def _rhs_outputs():
    """dy/dt and the output channels of the lubricated 7218B (16 balls, Fx 1000 N, Fz 3000 N) at its
    initial (quasi-static) state at 10,000 rpm, perturbed by a small ball motion so that sliding,
    spin and pocket contact are all present."""
    from bearing_core.models import dynamics_kernels as K
    from bearing_core.models.dynamics import DynamicModel, DynamicsOptions
    from bearing_core.bearing.geometry import load_preset
    m = DynamicModel(load_preset("7218B"), DynamicsOptions(traction="lubricated", reduced="full"))
    m.initialize(10000.0 * math.pi / 30.0, (1000.0, 0.0, 3000.0, 0.0, 0.0))
    y = m.y.copy()
    nb = int(m.P[K.P_NB])
    rng = np.random.default_rng(7)
    for j in range(nb):
        o = K.NSTATE_FIXED + K.NSB * j
        y[o] += 0.02 * rng.standard_normal()            # azimuth: some balls in their pocket's contact
        y[o + 3] *= 1.0 + 0.01 * rng.standard_normal()  # orbital speed
        y[o + 6:o + 9] *= 1.0 + 0.01 * rng.standard_normal(3)   # ball angular velocity: sliding and spin
    diag = np.zeros(K.NOUT)
    bd = np.zeros((nb, K.NBD))
    dy = K.evaluate(m.t, y, m.P, m.U, m._tab_i, m._tab_o, m._ta0, m._tda, m._tp, *m._quad, diag, bd)
    return {"dy": dy.tolist(), "diag": diag.tolist(), "bd": bd.tolist(), "nfixed": K.NSTATE_FIXED, "nsb": K.NSB}


def _emit(what):
    from bearing_core.numerics.jit import build_info
    if what == "kernels":
        return {"build": build_info(), "ehl": _ehl_grid(), "simple": _simple_grid()}
    return {"build": build_info(), "rhs": _rhs_outputs()}


def _fast_and_plain(what):
    """(fast, plain) results; the plain build is computed in a subprocess with BEARING_PLAIN_MATH=1."""
    env = dict(os.environ, BEARING_PLAIN_MATH="1")
    env["PYTHONPATH"] = ROOT + os.pathsep + env.get("PYTHONPATH", "")
    r = subprocess.run([sys.executable, os.path.abspath(__file__), what], env=env, capture_output=True,
                       text=True, timeout=900)
    assert r.returncode == 0, r.stderr[-3000:]
    plain = json.loads(r.stdout.strip().splitlines()[-1])
    return _emit(what), plain


@pytest.fixture(scope="module")
def builds():
    return _fast_and_plain("kernels")


def _close_columns(f, p, rel):
    """|f - p| <= rel * max|p| per column (each output of the kernel)."""
    f, p = np.asarray(f, float), np.asarray(p, float)
    assert f.shape == p.shape and np.all(np.isfinite(f))
    scale = np.max(np.abs(p), axis=0)
    err = np.max(np.abs(f - p), axis=0)
    assert np.all(err <= rel * scale + 1e-300), (err / np.where(scale > 0, scale, 1.0))


def test_builds_differ_in_their_flags(builds):
    fast, plain = builds
    assert plain["build"]["plain_math"] and plain["build"]["error_model"] == "python"
    assert not plain["build"]["fastmath"]
    assert not fast["build"]["plain_math"] and fast["build"]["error_model"] == "numpy"
    assert {"nnan", "ninf", "fast"}.isdisjoint(fast["build"]["fastmath"])   # NaN / Inf stay detectable
    assert plain["build"]["cache_dir"] != fast["build"]["cache_dir"]


def test_traction_kernels_fast_vs_plain(builds):
    fast, plain = builds
    _close_columns(fast["ehl"], plain["ehl"], 1e-9)
    _close_columns(fast["simple"], plain["simple"], 1e-9)


@pytest.mark.slow
def test_rhs_fast_vs_plain():
    """Ball derivatives per state slot (angle, radius, axial, their rates, the three angular velocities),
    the ring / cage block, the output channels and per-ball details: within 1e-9 of each slot's largest
    value. (Slow only by the strict build's first compilation of the right-hand side.)"""
    fast, plain = _fast_and_plain("rhs")
    f, p = np.array(fast["rhs"]["dy"]), np.array(plain["rhs"]["dy"])
    nf, nsb = fast["rhs"]["nfixed"], fast["rhs"]["nsb"]
    _close_columns(f[nf:].reshape(-1, nsb), p[nf:].reshape(-1, nsb), 1e-9)
    _close_columns(f[:nf, None], p[:nf, None], 1e-9)
    # output channels one by one (each its own scale)
    fd, pd = np.array(fast["rhs"]["diag"]), np.array(plain["rhs"]["diag"])
    assert np.all(np.abs(fd - pd) <= 1e-9 * np.abs(pd) + 1e-12)
    _close_columns(fast["rhs"]["bd"], plain["rhs"]["bd"], 1e-9)


# ---------------------------------------------------------------------------------------------------
# the thermal Eyring root
def _root_bisect(lX, K):
    """Converged root of s = asinh(X exp(-K s)) (bisection on g(s) = ln sinh s + K s - ln X, 200 halvings)."""
    lo = np.zeros_like(lX)
    hi = np.maximum(np.arcsinh(np.exp(np.minimum(lX, 700.0))), lX + math.log(2.0) + 1.0)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        g = mid + np.log(-np.expm1(-2.0 * mid)) - math.log(2.0) + K * mid - lX
        lo = np.where(g < 0.0, mid, lo)
        hi = np.where(g >= 0.0, mid, hi)
    return 0.5 * (lo + hi)


def _thermal_roots():
    """ehl_traction.thermal_eyring_root mapped over arrays (lX, K) -> s, compiled once per process."""
    global _ROOTS
    if _ROOTS is None:
        from numba import njit
        from bearing_core.lubrication.ehl_traction import thermal_eyring_root

        @njit
        def roots(lX, K):
            out = np.empty(lX.size)
            for i in range(lX.size):
                out[i] = thermal_eyring_root(lX[i], K[i])
            return out
        _ROOTS = roots
    return _ROOTS


_ROOTS = None


def test_thermal_eyring_root_error_bounds():
    """Bounds stated in ehl_traction.thermal_eyring_root: relative error <= 2e-14 for K <= 3, <= 2e-12
    for K <= 10, <= 1e-9 for K <= 31.6, over ln X in [-28, 50] (Eyring argument 7e-13 ... 5e21, beyond
    both ends of the quadrature points of bearing contacts)."""
    roots = _thermal_roots()
    LX, KK = np.meshgrid(np.linspace(-28.0, 50.0, 521), np.concatenate(([0.0], 10 ** np.linspace(-7, 1.5, 240))))
    lX, K = LX.ravel(), KK.ravel()
    s = roots(lX, K)
    ref = _root_bisect(lX, K)
    rel = np.abs(s / ref - 1.0)
    for kmax, bound in ((3.0, 2e-14), (10.0, 2e-12), (31.7, 1e-9)):
        m = K <= kmax
        assert rel[m].max() <= bound, (kmax, rel[m].max(), lX[m][np.argmax(rel[m])], K[m][np.argmax(rel[m])])
    # K = 0 is the isothermal Ree-Eyring stress asinh(X)
    iso = K == 0.0
    assert np.allclose(s[iso], np.arcsinh(np.exp(lX[iso])), rtol=1e-12)
    # the seed and first step from a coarse ln X (off by up to 3e-5, as the traction kernel's) reach the
    # same bounds: the last step, on the exact ln X, removes the difference
    from bearing_core.lubrication.ehl_traction import _thermal_eyring_root
    from numba import njit

    @njit
    def roots_c(lXc, lX, K):
        out = np.empty(lX.size)
        for i in range(lX.size):
            out[i] = _thermal_eyring_root(lXc[i], lX[i], K[i])
        return out

    for dl in (3e-5, -3e-5):
        rel = np.abs(roots_c(lX + dl, lX, K) / ref - 1.0)
        for kmax, bound in ((3.0, 2e-14), (10.0, 2e-12), (31.7, 1e-9)):
            assert rel[K <= kmax].max() <= bound, (dl, kmax, rel[K <= kmax].max())


def test_thermal_eyring_root_extremes():
    """Far outside the contacts' range (ln X in [-745, 700], K up to 1e6) the root stays finite and
    positive, within 1e-9 of the bisection root for K <= 31.6 and ln X >= -700 (where the exp of
    bearing_core.numerics.mathx stops at -708); NaN in ln X or K gives NaN."""
    roots = _thermal_roots()

    LX, KK = np.meshgrid(np.linspace(-745.0, 700.0, 290), np.concatenate(([0.0], 10 ** np.linspace(-12, 6, 55))))
    lX, K = LX.ravel(), KK.ravel()
    s = roots(lX, K)
    assert np.all(np.isfinite(s)) and s.min() > 0.0
    m = (K <= 31.7) & (lX >= -700.0)
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        lo = np.zeros(m.sum())
        hi = np.maximum(np.arcsinh(np.exp(np.minimum(lX[m], 700.0))), lX[m] + math.log(2.0) + 1.0)
        for _ in range(1100):
            mid = 0.5 * (lo + hi)
            g = mid + np.log(-np.expm1(-2.0 * mid)) - math.log(2.0) + K[m] * mid - lX[m]
            lo = np.where(g < 0.0, mid, lo)
            hi = np.where(g >= 0.0, mid, hi)
    assert np.max(np.abs(s[m] / (0.5 * (lo + hi)) - 1.0)) <= 1e-9
    assert np.all(np.isnan(roots(np.array([np.nan, 1.0]), np.array([1.0, np.nan]))))


def _root_full_precision(lX, K):
    """thermal_eyring_root's algorithm (seed, Householder step in ln s, Chebyshev step) with numpy's exp / log
    throughout, in place of the coarse polynomial exp / log of its seed and first step and the Pade form
    of that step's factor e^{-d} (the seed's series for asinh are part of the algorithm)."""
    ln2 = math.log(2.0)
    x = np.exp(np.minimum(lX, 20.0))
    x2 = x * x
    r = np.sqrt(1.0 + x2)
    u = 1.0 / np.maximum(x2, 1.0)
    s_lo = x * (1.0 + x2 * (-1.0 / 6.0 + x2 * (3.0 / 40.0 - x2 * (5.0 / 112.0))))
    s_hi = (lX + ln2) + u * (0.25 - u * (3.0 / 32.0 - u * (15.0 / 288.0)))
    s_mid = np.polynomial.polynomial.polyval(lX, [0.8813739608608067, 0.7070891455748324, 0.1767523031968521,
                                                  -0.02917219344930663, -0.018167773628819685,
                                                  0.005054404389377888, 0.0029017703331124614])
    si = np.where(lX < -0.75, s_lo, np.where(lX <= 0.75, s_mid, s_hi))
    s = np.maximum(si * r / (r + K * x), 3.3e-308)
    w = -np.expm1(-2.0 * s)
    t = 1.0 - w
    g = s * (1.0 + K) + np.log(w) - ln2 - lX
    q = s / w
    G1 = s * (1.0 + K) + 2.0 * t * q
    G2 = G1 - 4.0 * t * q * q
    G3 = G1 - 12.0 * t * q * q + 8.0 * (1.0 + t) * t * q ** 3
    d = 3.0 * g * (2.0 * G1 ** 2 - g * G2) / (6.0 * G1 ** 3 - 6.0 * g * G1 * G2 + g * g * G3)
    s = s * np.exp(-np.clip(d, -3.0, 3.0))
    w = -np.expm1(-2.0 * s)
    g = s * (1.0 + K) + np.log(w) - ln2 - lX
    N = 2.0 + (K - 1.0) * w
    ds = g * w / N * (1.0 - 2.0 * g * (1.0 - w) / N ** 2)
    return np.where(ds >= 0.9 * s, 0.1 * s, s - ds)


def test_thermal_eyring_root_coarse_steps():
    """The coarse exp / log of the root's seed and Householder step and the Pade form of that step's e^{-d}
    move the root by < 5e-12 relative against the same algorithm in full precision (its docstring), over
    ln X in [-28, 50] and K in [0, 31.6]: the last, full-precision Chebyshev step cubes their error."""
    roots = _thermal_roots()

    LX, KK = np.meshgrid(np.linspace(-28.0, 50.0, 1301), np.concatenate(([0.0], 10 ** np.linspace(-7, 1.5, 400))))
    lX, K = LX.ravel(), KK.ravel()
    assert np.max(np.abs(roots(lX, K) / _root_full_precision(lX, K) - 1.0)) < 5e-12


if __name__ == "__main__" and sys.argv[1:2] in (["kernels"], ["rhs"]):
    print(json.dumps(_emit(sys.argv[1])))
