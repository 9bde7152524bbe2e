"""Tangent stiffness of the transient model's current contact state (the 'dynamic' fidelity level's stiffness
outputs, bearing_core.session.cosim).

K[i, j] = -d(reaction_i)/d(pose_j) [N/m, N/rad, N m/m, N m/rad]: rows Fx, Fy, Fz, Mx, My of the force and moment of
the bearing on the shaft (dynamics_kernels.rhs output channels Fx..My: the balls' contact forces on the inner ring,
normal Hertz force with its damping and the race tractions), columns the inner-ring pose dx, dy, dz [m], tx, ty [rad]
(the state y[0:5] with load coupling, the held inputs U_DX..U_TY with displacement coupling). Every other state is
held: ball positions, ball and cage speeds, the cage, the ring's rates. It is the stiffness a master sees over a
time much shorter than the balls' own motion in the contact (the balls' radial and axial contact modes, 1e4-1e5
rad/s): the contact springs in series with nothing. It is not the quasi-static stiffness with the balls
re-equilibrated (Jones-Harris, bearing_core.models.quasistatic: softer, since the balls move to share the load), and
it carries no damping (d reaction / d ring rates) and no dependence on the speeds.

Forward differences of the right-hand side's ring forces from the communication point's own output channels (steps
1e-8 m, 1e-7 rad, as the Jones-Harris stiffness of quasistatic_kernels.stiffness_steps; the truncation error is
about h / (4 delta) of an entry, 2.5e-4 at a 1e-5 m contact deflection): five right-hand-side calls in one kernel
call, made only at communication points (the integration's hot loop is untouched); central differences (ten calls)
on request.
"""
from __future__ import annotations

import numpy as np

from ..numerics.jit import hot
from . import dynamics_kernels as K

_EMPTY = np.zeros(0)
STEPS = (1e-8, 1e-8, 1e-8, 1e-7, 1e-7)
"""Central-difference steps of the pose: dx, dy, dz [m], tx, ty [rad]."""


@hot
def ring_tangent_stiffness(t, y, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, steps, diag0, yy, uu, dy, diag,
                           bd, Kout):
    """Kout (5 x 5) = -d(Fx, Fy, Fz, Mx, My of the bearing on the shaft)/d(dx, dy, dz, tx, ty) at (t, y) with
    every state but the ring pose held: differences with the steps (5) [m, rad] of dynamics_kernels.rhs's output
    channels, forward from diag0 (the output channels at (t, y) itself, DynamicModel.evaluate_point) or, if
    diag0 is empty, central. yy, uu, dy, diag, bd: work arrays (sizes of y, U, y, NOUT, nb x NBD). The pose is
    y[0:5] (load coupling, P_COUPLING 0) or U[U_DX:U_TY + 1] (displacement coupling). Returns True if every
    entry is finite."""
    disp = P[K.P_COUPLING] > 0.5
    i0 = K.O_FX
    central = diag0.shape[0] == 0
    ok = True
    for j in range(5):
        h = steps[j]
        for s in range(2 if central else 1):
            sg = 1.0 if s == 0 else -1.0
            for k in range(y.shape[0]):
                yy[k] = y[k]
            for k in range(U.shape[0]):
                uu[k] = U[k]
            if disp:
                uu[K.U_DX + j] += sg * h
            else:
                yy[j] += sg * h
            K.rhs(t, yy, dy, P, uu, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd, False)
            for i in range(5):
                if not central:
                    Kout[i, j] = -(diag[i0 + i] - diag0[i0 + i]) / h
                elif s == 0:
                    Kout[i, j] = diag[i0 + i]
                else:
                    Kout[i, j] = -(Kout[i, j] - diag[i0 + i]) / (2.0 * h)
    for i in range(5):
        for j in range(5):
            if not np.isfinite(Kout[i, j]):
                ok = False
    return ok


class TangentStiffness:
    """ring_tangent_stiffness for a DynamicModel, with its work arrays allocated once."""

    def __init__(self):
        self.K = np.zeros((5, 5))
        self._steps = np.array(STEPS)
        self._work = None

    def __call__(self, m, diag0=None) -> np.ndarray:
        """The tangent stiffness (5 x 5, module docstring) of the DynamicModel m at its current state: forward
        differences from diag0, its output channels there (m.evaluate_point()[0]; five right-hand-side calls), or
        central differences without it (ten); raises FloatingPointError if an entry is not finite."""
        w = self._work
        nb = int(m.P[K.P_NB])
        if w is None or w[0].shape != m.y.shape or w[4].shape[0] != nb:
            w = self._work = (np.empty_like(m.y), np.empty_like(m.U), np.empty_like(m.y), np.zeros(K.NOUT),
                              np.zeros((nb, K.NBD)))
        if not ring_tangent_stiffness(m.t, m.y, m.P, m.U, m._tab_i, m._tab_o, m._ta0, m._tda, m._tp, *m._quad,
                                      self._steps, _EMPTY if diag0 is None else diag0, *w, self.K):
            raise FloatingPointError("the tangent stiffness of the contact state is not finite")
        return self.K
