"""Kinematic reference of the cage speed and the skid classification.

Definition (used by the dynamics outputs ``cage_speed_pure_rolling_outer`` / ``_inner``, the co-simulation
session, the CLI and the FMU):

* For every ball loaded at both races, the pure-rolling cage (orbital) speed at ITS OWN instantaneous
  contact angles alpha_i, alpha_o, with the spin axis of raceway control (Jones; Harris & Kotzalas,
  Rolling Bearing Analysis 5th ed., Vol. 2, Ch. 3, ball and cage speeds):
      tan(beta) = sin(ao) / (cos(ao) + D/dm)   outer-raceway control,
      tan(beta) = sin(ai) / (cos(ai) - D/dm)   inner-raceway control,
      w_c = w (1 - g_i) / [(1 - g_i) + (1 + g_o) cos(ai - beta) / cos(ao - beta)],  g = D cos(alpha) / dm,
  (pure rolling at both contact centres, inner ring at w, outer ring fixed). The bearing's reference is
  the mean over the loaded balls: outer- and inner-control values. With equal angles both equal the
  classical w (1 - g) / 2.
* Skid classification against the outer-raceway-control reference w_o (the control that holds at speed,
  where the ball's gyroscopic moment is carried at the outer race -- Jones; Harris & Kotzalas Vol. 2 Ch. 3):
      cage_slip_ratio s = 1 - w_cage / w_o,
      skid_state = +1 skidding (s > tol), -1 over-skidding (s < -tol), 0 pure rolling (|s| <= tol),
  tol = SKID_TOL = 0.01 (1 %, the order of the microslip (creep) of a rolling EHL contact: slide-to-roll
  ratios below ~1e-2 are the linear creep region of the traction curves, not gross sliding). The inner-
  control value is reported as the other bound (it is the lower bound of pure rolling at speed).
* Seed 000's Eq. 26 (spin neglected, both rolling radii D/2, mean contact angles of the loaded balls)
  remains available as ``pure_rolling_cage_speed`` / ``cage_shaft_ratio_theory``: it is neither control
  bound at speed (at 10,000 rpm on 7218B, Fx 1 kN / Fz 3 kN it lies 20 % below the outer-control value).
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import check_range

SKID_TOL = 0.01
SKID_SKIDDING, SKID_PURE_ROLLING, SKID_OVERSKIDDING = 1, 0, -1
SKID_LABELS = {1: "skidding", 0: "pure rolling", -1: "over-skidding"}


def pure_rolling_cage_speeds(omega, alpha_i, alpha_o, D, dm, loaded=None,
                             omega_outer: float = 0.0) -> tuple[float, float]:
    """Mean pure-rolling cage speed [rad/s] over the loaded balls: (outer-raceway control, inner-raceway
    control) (module docstring). omega [rad/s] shaft speed, omega_outer [rad/s] outer-ring speed (both
    signed; the kinematics depend on omega - omega_outer, seen from the outer ring: w_c = omega_outer +
    f (omega - omega_outer)); alpha_i, alpha_o [rad] per-ball contact angles
    (arrays); D, dm [m]; loaded: boolean mask of balls loaded at both races (default: all)."""
    ai = np.atleast_1d(np.asarray(alpha_i, dtype=float))
    ao = np.atleast_1d(np.asarray(alpha_o, dtype=float))
    check_range("D / dm", D / dm, 0.0, 0.5, lo_incl=False)
    if loaded is not None:
        ai, ao = ai[np.asarray(loaded, bool)], ao[np.asarray(loaded, bool)]
    if ai.size == 0:
        raise ValueError("no loaded ball: the pure-rolling reference is undefined")
    g = D / dm
    gi, go = g * np.cos(ai), g * np.cos(ao)
    out = []
    for beta in (np.arctan2(np.sin(ao), np.cos(ao) + g), np.arctan2(np.sin(ai), np.cos(ai) - g)):
        wc = omega_outer + (omega - omega_outer) * (1 - gi) / ((1 - gi) + (1 + go) * np.cos(ai - beta) / np.cos(ao - beta))
        out.append(float(np.mean(wc)))
    return out[0], out[1]


SKID_MIN_SPEED = 0.1
"""rad/s: below this |w_outer - omega_outer| (a bearing at rest or passing through zero speed) the slip ratio
is 0/0: reported as 0, state pure rolling."""


def classify_skid(cage_speed: float, w_outer: float, tol: float = SKID_TOL,
                  omega_outer: float = 0.0) -> tuple[int, float]:
    """(skid_state, cage_slip_ratio) of a cage turning at cage_speed against the outer-raceway-control
    reference w_outer [rad/s] (module docstring): +1 skidding, 0 pure rolling, -1 over-skidding. The slip
    ratio is measured in the frame of the outer ring (speed omega_outer [rad/s], default fixed), which makes
    it the same for either sense of rotation: s = (w_outer - cage_speed) / (w_outer - omega_outer) = 1 -
    cage_speed / w_outer for a fixed outer ring (0, state 0, when |w_outer - omega_outer| < SKID_MIN_SPEED)."""
    check_range("tol", tol, 0.0, 1.0)
    d = w_outer - omega_outer
    if not (abs(d) >= SKID_MIN_SPEED and math.isfinite(cage_speed)):
        return SKID_PURE_ROLLING, 0.0
    s = (w_outer - cage_speed) / d
    if s > tol:
        return SKID_SKIDDING, s
    if s < -tol:
        return SKID_OVERSKIDDING, s
    return SKID_PURE_ROLLING, s
