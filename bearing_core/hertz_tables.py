"""Numpy-vectorised Hertz contact parameters of one bearing, interpolated in contact angle.

The exact Hertz solution (bearing_core.hertz.hertz_exact) is evaluated on a uniform contact-angle grid
for both raceways and interpolated linearly (seed 000 section 3.1: contact parameters by interpolation).
Used by the quasi-static model; the numba kernels use the array form of the same table.
"""
from __future__ import annotations

import numpy as np

from . import hertz
from .geometry import BearingGeometry


class HertzInterp:
    """Interpolated exact Hertz constants over alpha in [-pi/2, pi/2] for the inner and outer race."""

    def __init__(self, g: BearingGeometry, n: int = 721):
        self.alpha = np.linspace(-0.5 * np.pi, 0.5 * np.pi, n)
        E_red = hertz.reduced_modulus(g.ring_material.E, g.ring_material.nu, g.ball_material.E, g.ball_material.nu)
        self.E_red = E_red
        tabs = {}
        for inner, f in ((True, g.fi), (False, g.fo)):
            K = np.empty(n); ac = np.empty(n); bc = np.empty(n); Ee = np.empty(n)
            for j, a in enumerate(self.alpha):
                _, _, srho, Frho = hertz.contact_curvature(g.D, g.dm, f, abs(a), inner)
                hc = hertz.hertz_exact(srho, Frho, E_red)
                K[j], ac[j], bc[j], Ee[j] = hc.K_load, hc.a_coef, hc.b_coef, hc.ell_E
            tabs[inner] = (K, ac, bc, Ee)
        self._tabs = tabs

    def K(self, alpha, inner: bool):
        """Load-deflection constant [N/m^1.5] at contact angle(s) alpha [rad]."""
        return np.interp(alpha, self.alpha, self._tabs[inner][0])

    def ab_E(self, alpha, Q, inner: bool):
        """(a, b, p_max, E(k)) for loads Q [N] at contact angles alpha: semi-axes [m], pressure [Pa]."""
        _, ac, bc, Ee = self._tabs[inner]
        Q = np.maximum(np.asarray(Q, dtype=float), 0.0)
        q3 = np.cbrt(Q)
        a = np.interp(alpha, self.alpha, ac) * q3
        b = np.interp(alpha, self.alpha, bc) * q3
        ab = a * b
        p = np.where(ab > 0, 1.5 * Q / (np.pi * np.where(ab > 0, ab, 1.0)), 0.0)
        return a, b, p, np.interp(alpha, self.alpha, Ee)
