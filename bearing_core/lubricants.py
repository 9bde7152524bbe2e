"""Lubricant data for traction: the rheological traction curve of seed 002,
mu(s) = (A + B s) exp(-C s) + D, s = slide-to-roll ratio.

The seeds give the form but no coefficients; both curves below are chosen, not fitted to a measurement.
They keep mu(0) = A + D = 0 (no traction without slip) and stay inside the 0.03-0.08 range of EHL
traction coefficients of mineral oils (Harris & Kotzalas, Rolling Bearing Analysis 5th ed., Vol. 2 Ch. 4).

* ``generic-mineral-oil`` (default): B = 0, a limiting-shear-stress curve mu = D (1 - exp(-C s)), initial
  slope C D = 6, 90 % of the limit 0.06 at s = 2.3 %. Monotonic.
* ``generic-mineral-oil-thermal``: B > 0 gives a maximum of 0.065 at s = 2.3 % and a falling branch to
  0.04 (thermal softening). The falling branch is a negative damping: in our runs of a 7218B at
  10000 rpm under pure thrust it drives a self-excited whirl of the inner ring when the ring has no other
  damping (as an undamped rotor model would give it). Use it with a damped rotor.

Replace them with coefficients fitted to your oil's traction measurements.
"""
from __future__ import annotations

from dataclasses import dataclass

from .errors import BearingInputError


@dataclass(frozen=True)
class TractionCurve:
    name: str
    A: float
    B: float
    C: float
    D: float
    density: float      # kg/m^3, for drag in the oil-air mixture
    source: str

    def mu(self, s):
        import numpy as np
        s = np.abs(s)
        return (self.A + self.B * s) * np.exp(-self.C * s) + self.D


LUBRICANTS = {
    "generic-mineral-oil": TractionCurve("generic-mineral-oil", -0.06, 0.0, 100.0, 0.06, 870.0,
                                         "illustrative, see module docstring"),
    "generic-mineral-oil-thermal": TractionCurve("generic-mineral-oil-thermal", -0.04, 6.0, 60.0, 0.04, 870.0,
                                                 "illustrative, see module docstring"),
}


def get_lubricant(name: str) -> TractionCurve:
    if name not in LUBRICANTS:
        raise BearingInputError("lubricant", name, "one of " + ", ".join(sorted(LUBRICANTS)))
    return LUBRICANTS[name]
