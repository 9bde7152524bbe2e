"""Numpy-vectorised Hertz contact parameters of one bearing, interpolated in contact angle.

A thin vectorised front end to bearing_core.contact.hertz.build_hertz_table (exact Hertz solution on a uniform
contact-angle grid, seed 000 section 3.1); the constants depend on cos(alpha) only, so |alpha| is used.
Used by the quasi-static model; numba kernels call hertz.hertz_lookup on the same arrays.

The exact table costs about 13 ms (722 elliptic-integral root solves at n = 361; measured on 7218B) and every model
construction and every quasi-static start builds one, so the tables of the last few bearings are memoised
by their defining numbers (D, dm, fi, fo, E', n); each HertzInterp gets its own copy of the arrays, so no
two models share mutable data.
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np

from . import hertz
from ..bearing.geometry import BearingGeometry


@lru_cache(maxsize=32)
def _exact_table(D: float, dm: float, fi: float, fo: float, E_red: float, n: int) -> hertz.HertzTable:
    return hertz.build_hertz_table(D, dm, fi, fo, E_red, n=n)


def hertz_table(D, dm, fi, fo, E_red, n=361) -> hertz.HertzTable:
    """hertz.build_hertz_table(D, dm, fi, fo, E_red, n), memoised; the arrays are fresh copies."""
    t = _exact_table(float(D), float(dm), float(fi), float(fo), float(E_red), n)
    return t._replace(alpha=t.alpha.copy(), inner=t.inner.copy(), outer=t.outer.copy())


class HertzInterp:
    """Interpolated exact Hertz constants for the inner and outer race of bearing ``g``."""

    def __init__(self, g: BearingGeometry, n: int = 361):
        self.E_red = hertz.reduced_modulus(g.ring_material.E, g.ring_material.nu,
                                           g.ball_material.E, g.ball_material.nu)
        self.table = hertz_table(g.D, g.dm, g.fi, g.fo, self.E_red, n=n)
        self.alpha = self.table.alpha
        self._tabs = {True: self.table.inner, False: self.table.outer}

    def _row(self, alpha, inner, row):
        return np.interp(np.abs(alpha), self.alpha, self._tabs[inner][row])

    def K(self, alpha, inner: bool):
        """Load-deflection constant [N/m^1.5] at contact angle(s) alpha [rad]."""
        return self._row(alpha, inner, hertz.ROW_K_LOAD)

    def ab_E(self, alpha, Q, inner: bool):
        """(a, b, p_max, E(k)) for loads Q [N] at contact angles alpha: semi-axes [m], pressure [Pa]."""
        Q = np.maximum(np.asarray(Q, dtype=float), 0.0)
        q3 = np.cbrt(Q)
        a = self._row(alpha, inner, hertz.ROW_A_COEF) * q3
        b = self._row(alpha, inner, hertz.ROW_B_COEF) * q3
        ab = a * b
        p = np.where(ab > 0, 1.5 * Q / (np.pi * np.where(ab > 0, ab, 1.0)), 0.0)
        return a, b, p, self._row(alpha, inner, hertz.ROW_ELL_E)
