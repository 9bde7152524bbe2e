"""Quasi-static ball bearing model, 5 degrees of freedom (Jones 1960; Harris & Kotzalas, Rolling
Bearing Analysis 5th ed., Vol. 2 Ch. 3 'High-speed operation'; seed 003 Eqs. 1-19).

Unknowns: inner-ring displacements u = (dx, dy, dz, tx, ty) [m, m, m, rad, rad] relative to the fixed
outer ring, and for each ball the position X = (Xr, Xz) of its centre relative to the outer groove
curvature centre [m]. Per ball j at azimuth psi_j = 2 pi j / Z (from +x towards +y):

  delta_r = dx cos psi + dy sin psi,   delta_a = dz + Ri (tx sin psi - ty cos psi)
  C = O_i - O_o = (A cos a0 + delta_r, A sin a0 + delta_a)          (seed 003 Eqs. 3, 5, 6)
  n_o = X/|X|,  delta_o = |X| - (fo - 1/2) D;  n_i = (X - C)/|X - C|,  delta_i = |X - C| - (fi - 1/2) D
  Q = K(alpha) delta^1.5  (Hertz, exact load-deflection constant interpolated in contact angle)
  ball:  -Q_i n_i - Q_o n_o + F_i e_i + F_o e_o + Fc r = 0,   e_k = (n_kz, -n_kr)          (Eq. 17)
  Fc = m dm omega_m^2 / 2,   Mg = J omega_m omega_R sin(beta)  (Eqs. 9-10)
  F_i = lambda_i Mg / D, F_o = lambda_o Mg / D: outer control lambda_o = 2, lambda_i = 0; inner control
        lambda_i = lambda_o = 1 (Harris & Kotzalas; seed 003 Eq. 12), each bounded by mu_gyro Q (a
        lightly loaded ball pivots instead: gyroscopic slip)
  ring:  F_ext + sum_j (Q_i n_i - F_i e_i) = 0 (forces), moments about the ring centre with the force
         applied at the inner groove-centre locus of radius Ri plus the friction force's moment
         arm fi D about it (Eqs. 18-19).

Separated contacts carry a tiny linear tension spring (k_reg = 1e-3 N/m) so that an unloaded ball keeps
a defined position; its force is < 1e-8 N for any real clearance and enters both balances consistently.
Hybrid control follows Harris's criterion: the outer race controls a ball when
Q_o a_o E(k_o) cos(alpha_i - alpha_o) > Q_i a_i E(k_i) (Harris & Kotzalas Vol. 2 Ch. 3).

The ball states, ball Newton solves, ring forces, 5-DOF Newton solve and stiffness matrix run as numba
kernels: bearing_core.models.quasistatic_kernels for the two-point model, bearing_core.models.quasistatic4_kernels
(the same algorithm with the four-point ball) for FourPointQuasiStaticModel.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..contact import kinematics as kin
from . import quasistatic4_kernels as q4k
from . import quasistatic_kernels as qsk
from ..errors import BearingInputError, ConvergenceError, check_range
from ..bearing.geometry import BearingGeometry
from ..contact.hertz_tables import HertzInterp
from ..bearing.ring_fits import operating_geometry

K_REG = qsk.K_REG  # N/m, tension spring of separated contacts (see module docstring)
_CTRL_CODE = {"outer": qsk.CTRL_OUTER, "inner": qsk.CTRL_INNER, "hybrid": qsk.CTRL_HYBRID}
LOAD_NAMES = ("Fx", "Fy", "Fz", "Mx", "My")
DOF_NAMES = ("dx", "dy", "dz", "tx", "ty")


@dataclass
class QuasiStaticResult:
    """Quasi-static solution. Arrays are per ball (length Z). SI units: m, rad, N, rad/s, Pa."""

    geometry: BearingGeometry
    omega: float                 # inner-ring speed [rad/s]
    loads: np.ndarray            # (Fx, Fy, Fz, Mx, My) [N, N m]
    control: str
    u: np.ndarray                # (dx, dy, dz, tx, ty) [m, rad]
    psi: np.ndarray              # ball azimuths [rad]
    alpha_i: np.ndarray
    alpha_o: np.ndarray
    Q_i: np.ndarray
    Q_o: np.ndarray
    delta_i: np.ndarray          # contact deflections [m] (<= 0: separated)
    delta_o: np.ndarray
    a_i: np.ndarray              # Hertz semi-major axes [m]
    b_i: np.ndarray
    a_o: np.ndarray
    b_o: np.ndarray
    p_i: np.ndarray              # maximum Hertz pressure [Pa]
    p_o: np.ndarray
    omega_m: np.ndarray          # orbital speed [rad/s]
    omega_R: np.ndarray          # ball spin speed relative to the cage frame [rad/s]
    beta: np.ndarray             # attitude angle [rad]
    spin_i: np.ndarray           # spin speeds relative to each race [rad/s]
    spin_o: np.ndarray
    roll_i: np.ndarray
    roll_o: np.ndarray
    Fc: np.ndarray               # centrifugal force [N]
    Mg: np.ndarray               # gyroscopic moment [N m]
    F_i: np.ndarray              # friction forces resisting Mg at the inner / outer contact [N]
    F_o: np.ndarray
    outer_control: np.ndarray    # bool, which race controls (hybrid), else all equal
    residual: float              # relative force residual of the ring equilibrium
    iterations: int
    stiffness: np.ndarray | None = None  # 5x5 [N/m, N/rad, N m/m, N m/rad]
    X: np.ndarray | None = field(default=None, repr=False)

    omega_outer: float = 0.0     # outer-ring speed [rad/s] (omega_m is then absolute, omega_R relative to the cage)

    @property
    def spin_roll_i(self):
        return self.spin_i / np.where(self.roll_i != 0, self.roll_i, np.inf)

    @property
    def spin_roll_o(self):
        return self.spin_o / np.where(self.roll_o != 0, self.roll_o, np.inf)

    @property
    def cage_speed(self) -> float:
        """Pure-rolling cage speed [rad/s]: mean orbital speed of the loaded balls (all balls if
        none is loaded)."""
        loaded = (self.Q_i > 0) & (self.Q_o > 0)
        return float(np.mean(self.omega_m[loaded])) if loaded.any() else float(np.mean(self.omega_m))

    def ring_reaction(self) -> np.ndarray:
        """(Fx, Fy, Fz, Mx, My) that the balls exert on the inner ring [N, N m]."""
        return _ring_forces(self.geometry, self.psi, self.alpha_i, self.Q_i, self.F_i)


def _ring_forces(g, psi, alpha_i, Q_i_eff, Fi):
    """Force and moment of the balls on the inner ring; Q_i_eff includes the regularisation, Fi is the
    inner-contact gyroscopic friction force [N] (qsk.ring_forces)."""
    F = np.empty(5)
    qsk.ring_forces(np.cos(psi), np.sin(psi), np.ascontiguousarray(alpha_i, dtype=float),
                    np.ascontiguousarray(Q_i_eff, dtype=float), np.ascontiguousarray(Fi, dtype=float),
                    float(g.Ri), float(g.ri), F)
    return F


def _state_dict(S):
    """Ball-state dict of a (qsk.NS, Z) kernel state array (outer_ctrl as bool)."""
    st = {k: S[i].copy() for i, k in enumerate(qsk.STATE_NAMES)}
    st["outer_ctrl"] = st["outer_ctrl"] != 0.0
    return st


class QuasiStaticModel:
    """Jones-Harris 5-DOF quasi-static model of one bearing (outer ring fixed, inner ring turning)."""

    FOUR_POINT = False      # FourPointQuasiStaticModel handles gothic-arch grooves
    _KERNELS = qsk          # kernel module of the model: residual, solve, stiffness, N_GEO
    _NS = qsk.NS            # rows of its ball-state array

    def __init__(self, geometry: BearingGeometry, control: str = "outer", n_table: int = 361,
                 mu_gyro: float = 0.1, fixed_tilt: bool = False):
        """mu_gyro: Coulomb limit of the friction that resists the gyroscopic moment [-]; fixed_tilt: the
        inner ring cannot tilt (a rigid shaft held by other bearings): tx = ty = 0 and Mx, My are
        reactions, not loads."""
        if not self.FOUR_POINT:
            geometry.require_two_point("two-point quasi-static model (QuasiStaticModel)")
        self.mu_gyro = check_range("mu_gyro", mu_gyro, 0.0, 1.0)
        self.fixed_tilt = bool(fixed_tilt)
        if control not in kin.CONTROL_MODES:
            raise BearingInputError("control", control, " | ".join(kin.CONTROL_MODES))
        self.g = geometry
        self.control = control
        self.hz = HertzInterp(geometry, n_table)
        Z = geometry.Z
        self.psi = 2.0 * np.pi * np.arange(Z) / Z
        self._omega = 0.0
        # outer-ring speed [rad/s] about +z: the problem is solved in the frame turning with the outer ring
        # (omega is then the inner ring's speed relative to it); the centrifugal force and the gyroscopic
        # moment take the absolute orbital speed omega_m + omega_outer (the spin relative to the cage is
        # frame-invariant). Harris & Kotzalas Vol. 2 Ch. 3 with both rings rotating.
        self.omega_outer = 0.0

    @property
    def psi(self) -> np.ndarray:
        """Ball azimuths [rad] (default 2 pi j / Z; may be set, e.g. to the balls of a dynamic state)."""
        return self._psi

    @psi.setter
    def psi(self, value):
        psi = np.array(value, dtype=float).reshape(-1)
        if psi.size != self.g.Z or not np.all(np.isfinite(psi)):
            raise BearingInputError("psi", np.asarray(value).tolist(), f"{self.g.Z} finite ball azimuths [rad]")
        self._psi = psi
        self._cpsi, self._spsi = np.cos(psi), np.sin(psi)

    # ---- per-ball geometry and forces (numba kernels: bearing_core.models.quasistatic_kernels) ---------
    def _kargs(self):
        """Geometry / parameter array, cos / sin of the azimuths, control code and Hertz tables of the
        kernels (built per call: omega_outer may be set after construction)."""
        g = self.g
        geo = np.empty(self._KERNELS.N_GEO)
        geo[qsk.G_D], geo[qsk.G_DM], geo[qsk.G_FO], geo[qsk.G_FI] = g.D, g.dm, g.fo, g.fi
        geo[qsk.G_A], geo[qsk.G_ALPHA0], geo[qsk.G_RI], geo[qsk.G_RIG] = g.A, g.alpha0, g.Ri, g.ri
        geo[qsk.G_MASS], geo[qsk.G_INERTIA] = g.ball_mass, g.ball_inertia
        geo[qsk.G_MU], geo[qsk.G_WOUT] = self.mu_gyro, self.omega_outer
        if self.FOUR_POINT:
            geo[q4k.G_EO], geo[q4k.G_EI] = g.outer_groove_offset, g.inner_groove_offset
        return geo, self._cpsi, self._spsi, _CTRL_CODE[self.control], self.hz.table.inner, self.hz.table.outer, \
            self.hz.table.dalpha

    def _centres(self, u):
        geo, c, s, *_ = self._kargs()
        return qsk.centres(np.asarray(u, dtype=float), c, s, geo)

    def _ball_state(self, X, Cr, Cz, omega, outer_ctrl):
        """Per-ball state dict (keys qsk.STATE_NAMES) at ball centres X (Z, 2) [m]."""
        geo, _, _, ctrl, ti, to, dal = self._kargs()
        S = np.empty((qsk.NS, self.g.Z))
        qsk.ball_states(np.ascontiguousarray(X, dtype=float), np.asarray(Cr, dtype=float),
                        np.asarray(Cz, dtype=float), float(omega), np.asarray(outer_ctrl, dtype=bool), ctrl,
                        geo, ti, to, dal, S)
        return _state_dict(S)

    def _x_start(self, u):
        """Initial ball positions: on the line of centres, with equal deflections; at speed a ball whose
        equal deflection is below the outer deflection of the pure-rolling centrifugal force starts on the
        outer race with that deflection (quasistatic_kernels._x_start)."""
        geo, c, s, _, _, to, dal = self._kargs()
        return qsk.x_start(np.asarray(u, dtype=float), float(self._omega), c, s, geo, to, dal)

    def residual(self, u, omega, X0=None, outer_ctrl=None):
        """Force of the balls on the inner ring at displacement u (balls re-equilibrated from X0):
        (F (5,) [N, N m], X (Z, 2) [m], state dict, converged)."""
        self._omega = omega
        u = np.asarray(u, dtype=float)
        if X0 is None:
            X0 = self._x_start(u)
        if outer_ctrl is None:
            outer_ctrl = np.ones(self.g.Z, dtype=bool)
        geo, c, s, ctrl, ti, to, dal = self._kargs()
        F, X, S, ok = self._KERNELS.residual(u, float(omega), np.ascontiguousarray(X0, dtype=float),
                                             np.asarray(outer_ctrl, dtype=bool), ctrl, geo, c, s, ti, to, dal)
        return F, X, self._states(S), bool(ok)

    def _states(self, S):
        """Ball-state dict of a kernel state array S (NS, Z)."""
        return _state_dict(S)

    def _ring_force(self, st):
        """(Fx, Fy, Fz, Mx, My) of the balls on the inner ring from a ball state [N, N m]."""
        return _ring_forces(self.g, self.psi, st["ai"], st["Qi"], st["Fi"])

    # ---- the 5-DOF solve ---------------------------------------------------------------------
    def solve(self, omega: float, loads, u0=None, tol: float = 1e-10, maxit: int = 100,
              stiffness: bool = True) -> QuasiStaticResult:
        """Solve for the inner-ring displacements under loads (Fx, Fy, Fz, Mx, My) [N, N m] at inner-ring
        speed omega [rad/s], from u0 [m, rad] (None: a rigid-ring estimate). If the direct solve from u0
        fails, the one from the rigid-ring estimate follows, then continuation in speed from the static
        solution. Raises ConvergenceError if no equilibrium is found."""
        omega = check_range("omega", omega, 0.0, 2.0e4, unit="rad/s")
        loads = np.asarray(loads, dtype=float).reshape(-1)
        if loads.size != 5:
            raise BearingInputError("loads", loads.tolist(), "5 values (Fx, Fy, Fz, Mx, My)")
        for nm, v in zip(LOAD_NAMES, loads):
            check_range(nm, v, -1e7, 1e7, unit="N or N m")
        with np.errstate(all="ignore"):
            try:
                return self._solve(omega, loads, u0, tol, min(maxit, 30), stiffness)
            except ConvergenceError as e:
                first = e
            # the plain Newton iteration (fixed step limits, a new Jacobian every iteration), then
            # continuation: static solution first, then speed in steps
            try:
                return self._solve(omega, loads, u0, tol, min(maxit, 30), stiffness, fast=False)
            except ConvergenceError:
                pass
            if u0 is not None:
                # a given start (e.g. a neighbouring solution) that does not lead here: the rigid-ring start.
                # Measured: 7218B at 20,000 rpm, (Fx, Fy, Fz) = (3200, 960, 960) N fails the line search
                # from any neighbouring solution, even from its own solution's u: the balls restart on
                # the outer race (quasistatic_kernels._x_start), while the equilibrium found from the
                # rigid-ring start has unloaded balls at inner contact angles of 74-95 deg.
                for fast in (True, False):
                    try:
                        return self._solve(omega, loads, None, tol, min(maxit, 30), stiffness, fast=fast)
                    except ConvergenceError:
                        pass
            try:
                res = self._solve(0.0, loads, None, tol, maxit, False, fast=False)
                u = res.u
                for w in np.linspace(0.0, omega, 9)[1:]:
                    res = self._solve(float(w), loads, u, tol, maxit, False, fast=False)
                    u = res.u
                return self._solve(omega, loads, u, tol, maxit, stiffness, fast=False)
            except ConvergenceError as e:
                raise ConvergenceError(
                    f"no quasi-static equilibrium found for omega = {omega:.6g} rad/s, loads = "
                    f"{loads.tolist()}, control = {self.control!r} (direct solve: {first}; speed "
                    f"continuation: {e})") from None

    def _u_guess(self, loads):
        """Static rigid-ring estimate: a uniform axial/radial approach that carries the load."""
        g = self.g
        Ki = float(self.hz.K(np.array([g.alpha0]), inner=True)[0])
        Ko = float(self.hz.K(np.array([g.alpha0]), inner=False)[0])
        Kn = 1.0 / (Ki ** (-2 / 3) + Ko ** (-2 / 3)) ** 1.5  # series Hertz constant
        Fa, Fr = abs(loads[2]), math.hypot(loads[0], loads[1])
        sa, ca = math.sin(g.alpha0), math.cos(g.alpha0)
        u = np.zeros(5)
        Qa = (Fa + 0.5 * Fr * sa / max(ca, 0.2) + 1e-3) / (g.Z * max(sa, 0.1))
        dn = (Qa / Kn) ** (2 / 3)
        clear = g.A * (1 - math.cos(g.alpha0))
        u[2] = math.copysign(1.0, loads[2] if loads[2] != 0 else 1.0) * (dn / max(sa, 0.1))
        if Fr > 0:
            Qr = 5.0 * Fr / (g.Z * max(ca, 0.2))
            dr = (Qr / Kn) ** (2 / 3) / max(ca, 0.2)
            u[0] = dr * loads[0] / Fr
            u[1] = dr * loads[1] / Fr
        return u

    def _solve(self, omega, loads, u0, tol, maxit, stiffness, fast=True):
        """One Newton solve of the 5-DOF ring equilibrium (kernel solve; algorithm and fast in the
        docstring of quasistatic_kernels.solve)."""
        g = self.g
        u = self._u_guess(loads) if u0 is None else np.array(u0, dtype=float)
        self._omega = omega
        geo, c, s, ctrl, ti, to, dal = self._kargs()
        X = np.empty((g.Z, 2))
        S = np.empty((self._NS, g.Z))
        Kmat = np.empty((5, 5))
        info = np.zeros(2)
        status, it = self._KERNELS.solve(float(omega), np.ascontiguousarray(loads, dtype=float), u, self.fixed_tilt, ctrl,
                               float(tol), int(maxit), bool(stiffness), geo, c, s, ti, to, dal, X, S, Kmat, info,
                               bool(fast))
        if status == qsk.LINE_SEARCH_FAILED:
            raise ConvergenceError(f"quasi-static line search failed at omega={omega:.4g} rad/s, "
                                   f"loads={loads.tolist()}, |residual|={info[0]:.3e}")
        if status != qsk.OK:
            raise ConvergenceError(f"quasi-static model did not converge in {maxit} iterations at "
                                   f"omega={omega:.4g} rad/s, loads={loads.tolist()}, "
                                   f"max scaled residual={info[1]:.3e}")
        st = self._states(S)
        res = self._result(omega, loads, u, X, st, st["outer_ctrl"], it)
        if stiffness:
            res.stiffness = Kmat
        return res

    def _result(self, omega, loads, u, X, st, outer_ctrl, it):
        g = self.g
        Qi = np.maximum(st["Qi"], 0.0)
        Qo = np.maximum(st["Qo"], 0.0)
        a_i, b_i, p_i, _ = self.hz.ab_E(st["ai"], Qi, inner=True)
        a_o, b_o, p_o, _ = self.hz.ab_E(st["ao"], Qo, inner=False)
        si, ri_, so, ro_ = kin.contact_spin_roll(omega, st["wm"], st["wR"], st["beta"], st["ai"], st["ao"])
        Fb = self._ring_force(st)
        act = slice(0, 3) if self.fixed_tilt else slice(0, 5)
        resid = float(np.linalg.norm((loads + Fb)[act]) / max(np.linalg.norm(loads[act]), 1e-12))
        return QuasiStaticResult(
            geometry=g, omega=omega, loads=loads.copy(), control=self.control, u=u.copy(), psi=self.psi.copy(),
            alpha_i=st["ai"], alpha_o=st["ao"], Q_i=Qi, Q_o=Qo, delta_i=st["d_i"], delta_o=st["d_o"],
            a_i=a_i, b_i=b_i, a_o=a_o, b_o=b_o, p_i=p_i, p_o=p_o, omega_m=st["wm"], omega_R=st["wR"],
            beta=st["beta"], spin_i=si, spin_o=so, roll_i=ri_, roll_o=ro_, Fc=st["Fc"], Mg=st["Mg"],
            F_i=st["Fi"], F_o=st["Fo"],
            outer_control=np.asarray(outer_ctrl, dtype=bool).copy(), residual=resid, iterations=it, X=X.copy())

    def stiffness_matrix(self, res: QuasiStaticResult) -> np.ndarray:
        """5x5 bearing stiffness K_kl = d(load_k)/d(u_l) at the solution, by central differences
        of the ring force with every ball re-equilibrated (steps 1e-8 m, 1e-7 rad)
        [N/m, N/rad, N m/m, N m/rad]."""
        self._omega = res.omega
        geo, c, s, ctrl, ti, to, dal = self._kargs()
        return self._KERNELS.stiffness(np.asarray(res.u, dtype=float), float(res.omega),
                                       np.ascontiguousarray(res.X), np.asarray(res.outer_control, dtype=bool),
                                       ctrl, geo, c, s, ti, to, dal)


# =============================================================================================
# Four-point-contact (gothic-arch) bearings
# =============================================================================================
CONTACT_NAMES = ("inner 1", "inner 2", "outer 1", "outer 2")


@dataclass
class FourPointResult(QuasiStaticResult):
    """Quasi-static solution of a four-point-contact bearing. The two-point fields (alpha_i, Q_i, a_i, ...,
    alpha_o, Q_o, ...) hold each ring's dominant (most loaded) contact; alpha_i/alpha_o used in the ball
    kinematics are the weighted angles of FourPointQuasiStaticModel; the per-contact arrays have shape (Z, 4) in CONTACT_NAMES order: 'inner 1' / 'outer 1' are
    the arcs of the diagonal pair that carries +Fz on the inner ring (contact angles > 0), 'inner 2' /
    'outer 2' their mirror images (contact angles < 0). Separated contacts have Q = 0, delta <= 0."""

    Q_c: np.ndarray | None = None        # contact loads [N]
    alpha_c: np.ndarray | None = None    # contact angles [rad]
    delta_c: np.ndarray | None = None    # deflections [m]
    a_c: np.ndarray | None = None        # Hertz semi-axes [m]
    b_c: np.ndarray | None = None
    p_c: np.ndarray | None = None        # maximum Hertz pressure [Pa]
    F_c: np.ndarray | None = None        # friction force resisting the gyroscopic moment [N]
    weight_c: np.ndarray | None = None   # share of each contact in its ring's kinematics (see the model)

    @property
    def contacts_per_ball(self) -> np.ndarray:
        """Number of loaded contacts of each ball (0..4)."""
        return np.sum(self.Q_c > 0, axis=1)

    def ring_reaction(self) -> np.ndarray:
        """(Fx, Fy, Fz, Mx, My) that the balls exert on the inner ring [N, N m]."""
        return _ring_forces4(self.geometry, self.psi, self.alpha_c[:, :2], self.Q_c[:, :2], self.F_c[:, :2])


def _ring_forces4(g, psi, alpha_i, Q_i, Fi):
    """Force and moment of the balls on the inner ring of a gothic-arch bearing. alpha_i, Q_i, Fi: (Z, 2)
    contact angles, loads (incl. regularisation) and gyroscopic friction forces of inner arcs 1 and 2 [rad,
    N]. Each contact force acts through its arc centre, at radius Ri and height +-e_i from the inner ring
    mid-plane (the tilt reference); a friction force has the extra arm fi D about that centre (as in
    _ring_forces, which this equals for e_i = 0)."""
    nir, niz = -np.cos(alpha_i), -np.sin(alpha_i)
    zc = np.array([g.inner_groove_offset, -g.inner_groove_offset])
    fr = Q_i * nir - Fi * niz
    fz = Q_i * niz + Fi * nir
    Fr = fr.sum(axis=1)
    Fz_ = fz.sum(axis=1)
    m = g.Ri * Fz_ - (fr * zc).sum(axis=1) + g.ri * Fi.sum(axis=1)
    c, s = np.cos(psi), np.sin(psi)
    return np.array([np.sum(Fr * c), np.sum(Fr * s), np.sum(Fz_), np.sum(m * s), -np.sum(m * c)])


class FourPointQuasiStaticModel(QuasiStaticModel):
    """Jones-Harris quasi-static model of a four-point-contact (gothic-arch) ball bearing; reduces to
    QuasiStaticModel for zero groove offsets.

    Geometry (bearing_core.bearing.geometry module docstring): relative to the curvature centre O_o1 of outer
    arc 1 the other centres are O_o2 = (0, 2 e_o), O_i1 = C = (A cos a0 + dr_1, A sin a0 + da) and
    O_i2 = (A cos a0 + dr_2, A sin a0 - 2 e_i + da), with da as in the two-point model and
    dr_k = dr - z_k (tx sin psi - ty cos psi), z_k = +-e_i the height of the inner centre above the inner
    ring mid-plane. Each arc k gives a Hertz contact, delta_k = |X - O_k| - (f - 1/2) D,
    Q_k = K(alpha_k) delta_k^1.5, only where its contact point lies on the arc's own side of the groove
    mid-plane (f D sin(alpha) >= e for arcs 1, < -e for arcs 2: a groove of two arcs meeting at the
    mid-plane; at e = 0 exactly one arc of each ring counts, the single-arc groove). The ball equilibrium
    sums all contacts (Amasorrain et al. 2003, Eqs. for the four contact loads; Leblanc & Nelias 2007).

    Speed effects as in the two-point model: centrifugal force on every ball; the ball kinematics (raceway
    control, attitude angle, gyroscopic moment) are those of the two-point model with, for each ring, the
    load-weighted mean contact angle sum_k w_k alpha_k, w_k = Q_k / sum Q (quasistatic4_kernels._weights),
    and the friction force resisting the gyroscopic moment is shared between that ring's contacts by the
    same weights. The solve is quasistatic4_kernels.solve: the two-point algorithm with a restart of the
    balls its per-ball Newton leaves out of equilibrium from the minimum of their potential. With
    one loaded contact per ring this is the two-point model exactly. With three or four loaded contacts a
    ball cannot roll without sliding on all of them; that sliding (Leblanc & Nelias 2007) and its friction
    are not resolved here (a stated simplification), only the contact loads and angles."""

    FOUR_POINT = True
    _KERNELS = q4k
    _NS = q4k.NS4

    def _centres(self, u):
        """Centres of inner arcs 1, 2 of every ball, (Cr, Cz) each (Z, 2) [m]."""
        geo, c, s, *_ = self._kargs()
        return q4k.centres4(np.asarray(u, dtype=float), c, s, geo)

    def _ball_state(self, X, Cr, Cz, omega, outer_ctrl):
        """Per-ball state dict at ball centres X (Z, 2) [m], inner arc centres Cr, Cz (Z, 2) [m]: the keys
        of the two-point model (Qi, Qo, d_i, d_o of each ring's dominant contact, ai, ao the weighted
        contact angles) and the per-contact arrays (Z, 2) Qi4, Qo4, ai4, ao4, di4, do4, Fi4, Fo4, wi, wo,
        dominant arcs ki, ko."""
        geo, _, _, ctrl, ti, to, dal = self._kargs()
        S = np.empty((q4k.NS4, self.g.Z))
        q4k.ball_states4(np.ascontiguousarray(X, dtype=float), np.ascontiguousarray(Cr, dtype=float),
                         np.ascontiguousarray(Cz, dtype=float), float(omega), np.asarray(outer_ctrl, dtype=bool),
                         ctrl, geo, q4k.k_table(ti, to), dal, S)
        return self._states(S)

    def _states(self, S):
        st = _state_dict(S[:qsk.NS])
        for k, row in q4k.PAIR_ROWS.items():
            st[k] = S[row:row + 2].T.copy()
        st["ki"] = S[q4k.S4_KI].astype(np.int64)
        st["ko"] = S[q4k.S4_KO].astype(np.int64)
        return st

    def _x_start(self, u):
        """Initial ball positions X (Z, 2) [m] (quasistatic4_kernels._x_start4)."""
        geo, c, s, ctrl, ti, to, dal = self._kargs()
        return q4k.x_start4(np.asarray(u, dtype=float), float(self._omega), ctrl, c, s, geo, ti, to, dal)

    def _ring_force(self, st):
        return _ring_forces4(self.g, self.psi, st["ai4"], st["Qi4"], st["Fi4"])

    def _u_guess(self, loads):
        u = super()._u_guess(loads)
        g = self.g
        if g.is_four_point:
            s = 0.5 * g.axial_play          # from 'pair 1 just touching' (u = 0) to the centred ring
            Fr = math.hypot(loads[0], loads[1])
            if Fr >= abs(loads[2]) * math.tan(g.alpha0):
                # radial load dominant: ring near axially centred, radial play taken up (both pairs)
                u[2] = -s
                if Fr > 0:
                    u[0] += 0.5 * max(g.radial_play, 0.0) * loads[0] / Fr
                    u[1] += 0.5 * max(g.radial_play, 0.0) * loads[1] / Fr
            else:
                u[2] = -s + math.copysign(abs(s) + abs(u[2]), loads[2])
        return u

    def _result(self, omega, loads, u, X, st, outer_ctrl, it):
        res = super()._result(omega, loads, u, X, st, outer_ctrl, it)
        rows = np.arange(self.g.Z)
        res.alpha_i, res.alpha_o = st["ai4"][rows, st["ki"]], st["ao4"][rows, st["ko"]]
        res.a_i, res.b_i, res.p_i, _ = self.hz.ab_E(res.alpha_i, res.Q_i, inner=True)
        res.a_o, res.b_o, res.p_o, _ = self.hz.ab_E(res.alpha_o, res.Q_o, inner=False)
        Qi, Qo = np.maximum(st["Qi4"], 0.0), np.maximum(st["Qo4"], 0.0)
        a_i, b_i, p_i, _ = self.hz.ab_E(st["ai4"], Qi, inner=True)
        a_o, b_o, p_o, _ = self.hz.ab_E(st["ao4"], Qo, inner=False)
        kw = {f: getattr(res, f) for f in res.__dataclass_fields__}
        return FourPointResult(
            **kw, Q_c=np.concatenate([Qi, Qo], axis=1), alpha_c=np.concatenate([st["ai4"], st["ao4"]], axis=1),
            delta_c=np.concatenate([st["di4"], st["do4"]], axis=1), a_c=np.concatenate([a_i, a_o], axis=1),
            b_c=np.concatenate([b_i, b_o], axis=1), p_c=np.concatenate([p_i, p_o], axis=1),
            F_c=np.concatenate([st["Fi4"], st["Fo4"]], axis=1), weight_c=np.concatenate([st["wi"], st["wo"]], axis=1))



def quasistatic_model(geometry: BearingGeometry, control: str = "outer", **kw) -> QuasiStaticModel:
    """The quasi-static model for this bearing: FourPointQuasiStaticModel for a gothic-arch
    (four-point-contact) bearing, QuasiStaticModel otherwise; keywords as QuasiStaticModel."""
    cls = FourPointQuasiStaticModel if geometry.is_four_point else QuasiStaticModel
    return cls(geometry, control, **kw)


MIRROR_LOADS = np.array([1.0, -1.0, 1.0, -1.0, 1.0])
"""(Fx, Fy, Fz, Mx, My) and (dx, dy, dz, tx, ty) reflected in the x-z plane (a plane through the bearing axis)."""
_SPEED_FIELDS = ("omega_m", "omega_R", "spin_i", "spin_o", "roll_i", "roll_o")


def mirror_result(res: QuasiStaticResult) -> QuasiStaticResult:
    """The solution reflected in the x-z plane: the same bearing turning the other way under the reflected loads.

    A reflection maps the ball at azimuth psi to -psi (index j -> (Z - j) mod Z on the default pitch
    psi_j = 2 pi j / Z), reverses every angular speed about the bearing axis and every ball speed (orbit, spin,
    roll: angular velocities are axial vectors, their components in the plane change sign), changes the sign of
    Fy, Mx and of dy, tx (S K S for the stiffness, S = diag(1, -1, 1, -1, 1)), and leaves contact angles, loads,
    deflections, pressures, attitude angles, centrifugal forces and gyroscopic moments (about the tangential
    axis, normal to the plane) as they are."""
    from dataclasses import fields, replace as dc_replace
    Z = res.psi.size
    idx = (-np.arange(Z)) % Z
    if not np.allclose(res.psi, 2.0 * np.pi * np.arange(Z) / Z, rtol=0.0, atol=1e-12):
        raise BearingInputError("psi", "custom ball azimuths", "the default pitch 2 pi j / Z for a mirrored solution")
    upd = {}
    for f in fields(res):
        v = getattr(res, f.name)
        if f.name in ("psi", "loads", "u", "stiffness", "geometry") or not isinstance(v, np.ndarray):
            continue
        if v.ndim >= 1 and v.shape[0] == Z:
            v = v[idx].copy()
            if f.name in _SPEED_FIELDS:
                v = -v
            upd[f.name] = v
    S = MIRROR_LOADS
    upd["omega"] = -res.omega
    upd["omega_outer"] = -res.omega_outer
    upd["loads"] = res.loads * S
    upd["u"] = res.u * S
    if res.stiffness is not None:
        upd["stiffness"] = res.stiffness * np.outer(S, S)
    return dc_replace(res, **upd)


def solve_quasistatic(geometry: BearingGeometry, omega: float, loads, control: str = "outer",
                      stiffness: bool = True, mu_gyro: float = 0.1, fits=None,
                      temperatures=None, omega_outer: float = 0.0) -> QuasiStaticResult:
    """Convenience wrapper: quasistatic_model(geometry, control).solve(omega, loads).

    omega: inner-ring speed [rad/s], signed about +z, in [-2e4, 2e4]; omega_outer [rad/s]: outer-ring speed,
    signed, same range; loads: (Fx, Fy, Fz, Mx, My) [N, N m] applied to the inner ring; control: 'outer' |
    'inner' | 'hybrid'. As the dynamics' start (docs/reversal_and_outputs.md), the problem is solved in the frame
    turning with the outer ring at the relative speed |omega - omega_outer|; a negative difference is solved
    with the loads reflected in the x-z plane and the result reflected back (mirror_result). With a turning
    outer ring the centrifugal force and gyroscopic moment take the absolute orbital speed, and omega_m is
    reported absolute (the solved relative one plus omega_outer). fits (bearing_core.bearing.ring_fits.RingFits)
    and/or temperatures (ring_fits.OperatingTemperatures): solve the operating geometry
    ring_fits.operating_geometry(geometry, |omega|, fits, temperatures) (centrifugal, thermal and fit growth
    of the rings; result.geometry is that geometry)."""
    omega = check_range("omega", omega, -2.0e4, 2.0e4, unit="rad/s")
    omega_outer = check_range("omega_outer", omega_outer, -2.0e4, 2.0e4, unit="rad/s")
    if fits is not None or temperatures is not None:
        geometry = operating_geometry(geometry, abs(omega), fits, temperatures)
    w_rel = omega - omega_outer
    mirror = w_rel < 0.0
    loads = np.asarray(loads, dtype=float).reshape(-1)
    model = quasistatic_model(geometry, control, mu_gyro=mu_gyro)
    model.omega_outer = -omega_outer if mirror else omega_outer
    res = model.solve(abs(w_rel), loads * MIRROR_LOADS if (mirror and loads.size == 5) else loads,
                      stiffness=stiffness)
    if omega_outer != 0.0:
        from dataclasses import replace as dc_replace
        res = dc_replace(res, omega=abs(w_rel) + model.omega_outer, omega_outer=model.omega_outer,
                         omega_m=res.omega_m + model.omega_outer)
    return mirror_result(res) if mirror else res
