"""Polynomial exp / expm1 / log / log1p / asinh / tanh of bearing_core.numerics.mathx against the extended-precision
(80-bit long double) functions of numpy over the documented ranges, within the bounds stated in the
module docstring; NaN propagates. Evaluated from a loop compiled with the hot-kernel flags
(bearing_core.numerics.jit), the way the traction kernels use them."""
import numpy as np
import pytest

from bearing_core.numerics import mathx as M
from bearing_core.numerics.jit import hot

RNG = np.random.default_rng(20261124)


def _eval(fn):
    @hot
    def ev(x, out):
        for i in range(x.size):
            out[i] = fn(x[i])
    return ev


def _max_rel(fn, ref, x):
    out = np.empty(x.size)
    _eval(fn)(x, out)
    r = ref(x.astype(np.longdouble))
    ok = r != 0
    return float(np.max(np.abs(out.astype(np.longdouble)[ok] - r[ok]) / np.abs(r[ok])))


def _logspace(lo, hi, n):
    return 10.0 ** RNG.uniform(lo, hi, n)


CASES = {
    "exp": (M.exp, np.exp, np.concatenate([RNG.uniform(-708, 708, 20000), RNG.uniform(-1, 1, 5000),
                                           RNG.uniform(-1e-6, 1e-6, 2000)]), 5e-15),
    "expm1": (M.expm1, np.expm1, np.concatenate([RNG.uniform(-700, 700, 10000), RNG.uniform(-0.4, 0.4, 10000),
                                                 _logspace(-300, 0, 3000), -_logspace(-300, 0, 3000)]), 5e-15),
    "log": (M.log, np.log, np.concatenate([_logspace(-307, 308, 20000), RNG.uniform(0.5, 2.0, 10000),
                                           1.0 + RNG.uniform(-1e-6, 1e-6, 3000)]), 5e-16),
    "log1p": (M.log1p, np.log1p, np.concatenate([_logspace(-300, 300, 10000), -_logspace(-300, -1e-4, 10000),
                                                 RNG.uniform(-0.3, 0.42, 5000)]), 1e-15),
    "asinh_pos": (M.asinh_pos, np.arcsinh, np.concatenate([_logspace(-300, 150, 20000), RNG.uniform(0, 3, 5000)]),
                  1e-15),
    "tanh_pos": (M.tanh_pos, np.tanh, np.concatenate([_logspace(-300, 3, 20000), RNG.uniform(0, 3, 5000)]), 5e-15),
    # coarse variants
    "exp_lo": (M.exp_lo, np.exp, np.concatenate([RNG.uniform(-708, 708, 20000), RNG.uniform(-1, 1, 5000),
                                                 RNG.uniform(-1e-6, 1e-6, 2000)]), 2e-7),
    "expm1_lo": (M.expm1_lo, np.expm1, np.concatenate([RNG.uniform(-700, 700, 10000), RNG.uniform(-0.4, 0.4, 10000),
                                                       _logspace(-300, 0, 3000), -_logspace(-300, 0, 3000)]), 6e-7),
    "log_lo": (M.log_lo, np.log, np.concatenate([_logspace(-307, 308, 20000), RNG.uniform(0.5, 2.0, 10000),
                                                 1.0 + RNG.uniform(-1e-6, 1e-6, 3000)]), 1e-7),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_error_bound(name):
    fn, ref, x, bound = CASES[name]
    assert _max_rel(fn, ref, x) <= bound


@pytest.mark.parametrize("name", sorted(CASES))
def test_nan_propagates(name):
    fn = CASES[name][0]
    out = np.empty(2)
    _eval(fn)(np.array([np.nan, 0.5]), out)
    assert np.isnan(out[0]) and np.isfinite(out[1])


def test_range_ends():
    out = np.empty(4)
    _eval(M.exp)(np.array([-800.0, 800.0, 0.0, 1.0]), out)
    assert out[0] == pytest.approx(np.exp(-708.0), rel=1e-14) and out[1] == pytest.approx(np.exp(708.0), rel=1e-14)
    assert out[2] == 1.0 and out[3] == pytest.approx(np.e, rel=1e-15)
    _eval(M.log)(np.array([0.0, 1e-320, 1.0, 2.0]), out)
    assert out[0] == out[1] == pytest.approx(np.log(2.2250738585072014e-308), rel=1e-15)
    assert out[2] == 0.0 and out[3] == pytest.approx(np.log(2.0), rel=1e-16)
