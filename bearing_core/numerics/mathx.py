"""Branch-free exp, expm1, log, log1p, asinh and tanh for the hot numba kernels: polynomial forms that LLVM
inlines and vectorises (SIMD over the quadrature points of the EHL traction), where a call into the C
library (~3 ns, one value at a time) cannot be vectorised. NaN propagates through all of them.

Ranges and error bounds (relative to the exact value; measured by tests/test_mathx.py):

    exp(x)      x clamped to [-708, 708] (exp(-708) = 3.3e-308 is returned below, not 0)   <= 5e-15
    expm1(x)    same clamp                                                               <= 5e-15
    log(x)      x in [2.3e-308, 1.8e308] (smaller x taken as 2.3e-308)                     <= 5e-16
    log1p(y)    y > -1, 1 + y <= 1.8e308                                                  <= 1e-15
    asinh_pos(x) x in [0, 1e150]                                                          <= 1e-15
    tanh_pos(x)  x >= 0                                                                   <= 5e-15

Coarse variants, for the early iterates of Newton solves whose last step uses the functions above (the
last step squares the iterate's error, so that their error does not reach the root):

    exp_lo(x)    as exp                                                                    <= 2e-7
    expm1_lo(x)  as expm1                                                                  <= 6e-7
    log_lo(x)    as log                                                                    <= 1e-7

Methods (standard, as in fdlibm / Cody & Waite, "Software Manual for the Elementary Functions", 1980):
exp and expm1: x = k ln2 + r, |r| <= ln2 / 2 (ln2 split into a high and a low part), t = e^r - 1 by its
Taylor series to r^13 (truncation r^14 / 14! < 5e-18), 2^k built from the exponent bits; exp = 2^k t + 2^k,
expm1 = 2^k t + (2^k - 1) (exact for k = 0, so no cancellation near 0); log: x = 2^e m with m in
[sqrt(1/2), sqrt(2)), log m = 2 atanh(s), s = (m - 1) / (m + 1), |s| <= 0.1716, series to s^19 (truncation < 1e-16); log1p(y) =
log(u) + (y - (u - 1)) / u with u = 1 + y rounded (the correction restores the bits lost in 1 + y);
asinh(x) = log1p(x + x^2 / (1 + sqrt(1 + x^2))); tanh(x) = -expm1(-2x) / (2 + expm1(-2x)). The coarse
variants use the same reductions with the series cut at r^6 (truncation r^7 / 7! < 1.2e-7, relative
to e^r - 1 r^6 / 7! < 3.5e-7) and at s^7 (2 s^9 / 9 < 3e-8).
The series are evaluated by Estrin's scheme (sums of pairs c_k + c_{k+1} r with powers r^2, r^4, r^8 in
place of Horner's rule): the same accuracy, but a dependency chain of about 5 instead of 13 fused
multiply-adds for exp, which sets the cost where only 16 points (two SIMD vectors) are in flight.
"""
from __future__ import annotations

import math

import numpy as np
from llvmlite import ir
from numba import types
from numba.extending import intrinsic

from numba import njit

from .jit import ERROR_MODEL, PLAIN_MATH

# own flags: fused multiply-add only, never re-association (it would undo the Cody-Waite reduction and the
# log1p correction). Not inlined by numba (which would compile them with the caller's flags): LLVM inlines
# and vectorises them keeping these flags on their instructions.
_mx = njit(cache=True, error_model=ERROR_MODEL, fastmath=False if PLAIN_MATH else {"contract"})

LN2 = 0.6931471805599453
_LN2_HI = 6.93147180369123816490e-01     # ln 2 rounded to 32 significant bits (fdlibm): k _LN2_HI is exact
_LN2_LO = 1.90821492927058770002e-10     # ln 2 - _LN2_HI
_INV_LN2 = 1.44269504088896338700e+00
_SQRT2 = 1.4142135623730951
_HALF_LN2 = 0.34657359027997264
_TINY = 2.2250738585072014e-308          # smallest normal double


@intrinsic
def _f64_bits(typingctx, x):
    """The IEEE-754 bits of a float64 as an int64."""
    if not isinstance(x, types.Float):
        return None

    def codegen(context, builder, signature, args):
        return builder.bitcast(args[0], ir.IntType(64))
    return types.int64(types.float64), codegen


@intrinsic
def _bits_f64(typingctx, n):
    """The float64 whose IEEE-754 bits are the int64 n."""
    if not isinstance(n, types.Integer):
        return None

    def codegen(context, builder, signature, args):
        return builder.bitcast(args[0], ir.DoubleType())
    return types.float64(types.int64), codegen


@_mx
def _exp_parts(x):
    """(2^k, e^r - 1) with x = k ln2 + r, |r| <= ln2 / 2, x clamped to [-708, 708] (module docstring)."""
    xc = min(max(x, -708.0), 708.0)
    kf = math.floor(xc * _INV_LN2 + 0.5)
    r = (xc - kf * _LN2_HI) - kf * _LN2_LO
    if x != x:
        r = x
    r2 = r * r
    r4 = r2 * r2
    hi = (((1.0 / 40320.0 + r * (1.0 / 362880.0)) + r2 * (1.0 / 3628800.0 + r * (1.0 / 39916800.0))) +
          r4 * (1.0 / 479001600.0 + r * (1.0 / 6227020800.0)))
    lo = (1.0 / 24.0 + r * (1.0 / 120.0)) + r2 * (1.0 / 720.0 + r * (1.0 / 5040.0))
    t = r + r2 * ((0.5 + r * (1.0 / 6.0)) + r2 * (lo + r4 * hi))
    return _bits_f64((np.int64(kf) + 1023) << 52), t


@_mx
def _exp_reduce(x):
    """(2^k, r) with x = k ln2 + r, |r| <= ln2 / 2, x clamped to [-708, 708]; r = NaN for x = NaN."""
    xc = min(max(x, -708.0), 708.0)
    kf = math.floor(xc * _INV_LN2 + 0.5)
    r = (xc - kf * _LN2_HI) - kf * _LN2_LO
    if x != x:
        r = x
    return _bits_f64((np.int64(kf) + 1023) << 52), r


@_mx
def _exp_parts_lo(x):
    """_exp_parts with the series cut at r^6 (coarse variants)."""
    s, r = _exp_reduce(x)
    r2 = r * r
    return s, r + r2 * ((0.5 + r * (1.0 / 6.0)) + r2 * ((1.0 / 24.0 + r * (1.0 / 120.0)) + r2 * (1.0 / 720.0)))


@_mx
def exp_lo(x):
    """e^x to 2e-7 relative, x clamped to [-708, 708] (module docstring: coarse variants)."""
    s, t = _exp_parts_lo(x)
    return s * t + s


@_mx
def expm1_lo(x):
    """e^x - 1 to 6e-7 relative (module docstring: coarse variants)."""
    s, t = _exp_parts_lo(x)
    return s * t + (s - 1.0)


@_mx
def exp(x):
    """e^x, x clamped to [-708, 708] (module docstring)."""
    s, t = _exp_parts(x)
    return s * t + s


@_mx
def expm1(x):
    """e^x - 1, accurate near 0 (module docstring)."""
    s, t = _exp_parts(x)
    return s * t + (s - 1.0)


@_mx
def _log1p_reduced(f):
    """log(1 + f) for f in [sqrt(1/2) - 1, sqrt(2) - 1]: 2 atanh(s), s = f / (2 + f)."""
    s = f / (2.0 + f)
    z = s * s
    z2 = z * z
    z4 = z2 * z2
    hi = (1.0 / 11.0 + z * (1.0 / 13.0)) + z2 * (1.0 / 15.0 + z * (1.0 / 17.0)) + z4 * (1.0 / 19.0)
    R = z * (((1.0 / 3.0 + z * (1.0 / 5.0)) + z2 * (1.0 / 7.0 + z * (1.0 / 9.0))) + z4 * hi)
    return 2.0 * s + 2.0 * s * R


@_mx
def _log_reduce(x):
    """(e, m) with x = 2^e m, m in [sqrt(1/2), sqrt(2)), x taken as >= 2.3e-308; m = NaN for x = NaN."""
    xc = max(x, _TINY)
    bits = _f64_bits(xc)
    e = (bits >> 52) - 1023
    m = _bits_f64((bits & 0x000FFFFFFFFFFFFF) | 0x3FF0000000000000)     # x = 2^e m, m in [1, 2)
    big = m > _SQRT2
    m = 0.5 * m if big else m
    ef = float(e + 1) if big else float(e)
    if x != x:
        m = x
    return ef, m


@_mx
def log(x):
    """Natural logarithm of x in [2.3e-308, 1.8e308] (module docstring)."""
    ef, m = _log_reduce(x)
    return ef * _LN2_HI + (_log1p_reduced(m - 1.0) + ef * _LN2_LO)


@_mx
def log_lo(x):
    """Natural logarithm to 1e-7 relative, x as for log (module docstring: coarse variants)."""
    ef, m = _log_reduce(x)
    f = m - 1.0
    s = f / (2.0 + f)
    z = s * s
    return ef * _LN2_HI + ((2.0 * s + 2.0 * s * (z * ((1.0 / 3.0 + z * (1.0 / 5.0)) + (z * z) * (1.0 / 7.0)))) +
                           ef * _LN2_LO)


@_mx
def log1p(y):
    """log(1 + y), accurate near 0 (module docstring)."""
    u = 1.0 + y
    return log(u) + (y - (u - 1.0)) / u


@_mx
def asinh_pos(x):
    """asinh(x) for x in [0, 1e150] (module docstring)."""
    return log1p(x + x * x / (1.0 + math.sqrt(1.0 + x * x)))


@_mx
def tanh_pos(x):
    """tanh(x) for x >= 0 (module docstring)."""
    e = expm1(-2.0 * x)
    return -e / (2.0 + e)
