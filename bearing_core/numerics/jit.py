"""Compilation flags of the hot numba kernels (contact, traction, dynamics right-hand side), chosen here
and nowhere else.

Default (fast) build:
  * error_model='numpy': a division by zero gives inf / NaN instead of raising; this removes the
    zero-division branch numba's default ('python') puts on every division and lets LLVM vectorise;
  * fastmath flags FASTMATH = {'nsz', 'arcp', 'contract', 'reassoc'}: no signed zeros, reciprocal
    multiplication, fused multiply-add, re-association of sums. The no-NaN / no-Inf flags are NOT set:
    the integrators and the checks of bearing_core detect non-finite values, which 'nnan' / 'ninf' would
    let LLVM fold away.

Plain build: the environment variable BEARING_PLAIN_MATH=1 (read once, at import) compiles the same
kernels with strict IEEE arithmetic and error_model='python'. Its numba cache lives in its own
sub-directory ('plain_math' under NUMBA_CACHE_DIR, or under bearing_core/__pycache__), because numba's
cache key does not include the compilation flags. tests/test_jit_flags.py holds the fast build against
the plain one within stated tolerances.
"""
from __future__ import annotations

import os

from numba import njit
from numba.core import config as _nb_config

PLAIN_MATH = os.environ.get("BEARING_PLAIN_MATH", "").strip().lower() not in ("", "0", "false", "no")

FASTMATH = frozenset() if PLAIN_MATH else frozenset({"nsz", "arcp", "contract", "reassoc"})
ERROR_MODEL = "python" if PLAIN_MATH else "numpy"
# contraction (fused multiply-add) only: for polynomial kernels whose error bound re-association would break
CONTRACT = frozenset() if PLAIN_MATH else frozenset({"contract"})

if PLAIN_MATH:
    _base = _nb_config.CACHE_DIR or os.path.join(os.path.dirname(os.path.abspath(__file__)), "__pycache__")
    if os.path.basename(os.path.normpath(_base)) != "plain_math":
        _nb_config.CACHE_DIR = os.path.join(_base, "plain_math")


def hot(fn=None, *, inline: str = "never", nogil: bool = False, nrt: bool | None = None,
        fastmath: frozenset | None = None):
    """numba.njit with the module's flags and cache=True; use as @hot, @hot(inline='always') or
    @hot(nogil=True) (integration loops that release the GIL for threaded batches). nrt=False: compiled
    without numba's reference-counting runtime, for a small kernel called very often that neither
    allocates nor returns arrays (its array arguments stay owned by the caller): no atomic reference
    count per call. numba passes the choice on to the callees it compiles for such a kernel unless they set
    their own: nrt=True sets it explicitly, for a kernel that allocates and is called from an nrt=False one
    (default None: taken over from the caller, reference counting when compiled on its own).
    fastmath=CONTRACT: contraction only instead of FASTMATH, for polynomial kernels with error-compensating
    steps (compiled on their own, inline='never': LLVM inlines them into the callers keeping these flags on
    their instructions)."""
    fm = FASTMATH if fastmath is None else fastmath
    kw = dict(cache=True, error_model=ERROR_MODEL, fastmath=set(fm) if fm else False,
              inline=inline, nogil=nogil)
    if nrt is not None:
        kw["_nrt"] = nrt
    if fn is None:
        return lambda f: njit(**kw)(f)
    return njit(**kw)(fn)


def build_info() -> dict:
    """The flags this process compiles the hot kernels with (for benchmarks and reports)."""
    return {"plain_math": PLAIN_MATH, "fastmath": sorted(FASTMATH), "error_model": ERROR_MODEL,
            "cache_dir": _nb_config.CACHE_DIR or "(numba default: __pycache__ next to the sources)"}
