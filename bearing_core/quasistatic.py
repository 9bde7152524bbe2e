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

The two-point model's ball states, ball Newton solves, ring forces, 5-DOF Newton solve and stiffness
matrix run as numba kernels (bearing_core.quasistatic_kernels); the four-point model runs the same
algorithm with numpy (FourPointQuasiStaticModel).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from . import kinematics as kin
from . import quasistatic_kernels as qsk
from .errors import BearingInputError, ConvergenceError, check_range
from .geometry import BearingGeometry
from .hertz_tables import HertzInterp
from .ring_fits import operating_geometry

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

    @property
    def spin_roll_i(self):
        return self.spin_i / np.where(self.roll_i > 0, self.roll_i, np.inf)

    @property
    def spin_roll_o(self):
        return self.spin_o / np.where(self.roll_o > 0, self.roll_o, np.inf)

    @property
    def cage_speed(self) -> float:
        """Pure-rolling cage speed [rad/s]: mean orbital speed of the loaded balls (all balls if
        none is loaded)."""
        loaded = (self.Q_i > 0) & (self.Q_o > 0)
        return float(np.mean(self.omega_m[loaded])) if loaded.any() else float(np.mean(self.omega_m))

    def ring_reaction(self) -> np.ndarray:
        """(Fx, Fy, Fz, Mx, My) that the balls exert on the inner ring [N, N m]."""
        return _ring_forces(self.geometry, self.psi, self.alpha_i, self.Q_i, self.F_i)


def _lambda_i(control, outer_control):
    """Share of the gyroscopic moment taken at the inner contact (lambda_i; lambda_o = 2 - lambda_i):
    0 where the outer race controls, 1 under inner control (Harris & Kotzalas)."""
    return np.where(outer_control, 0.0, 1.0)


def _coulomb_bound(F, Fmax):
    """Smooth |F| <= Fmax (F where Fmax = 0 is 0)."""
    x = np.abs(F) / np.where(Fmax > 0, Fmax, 1.0)
    return np.where(Fmax > 0, F / (1.0 + x ** 8) ** 0.125, 0.0)


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
        self._cpsi, self._spsi = np.cos(self.psi), np.sin(self.psi)
        self._omega = 0.0
        # outer-ring speed [rad/s] about +z: the problem is solved in the frame turning with the outer ring
        # (omega is then the inner ring's speed relative to it); the centrifugal force and the gyroscopic
        # moment take the absolute orbital speed omega_m + omega_outer (the spin relative to the cage is
        # frame-invariant). Harris & Kotzalas Vol. 2 Ch. 3 with both rings rotating.
        self.omega_outer = 0.0

    # ---- per-ball geometry and forces (numba kernels: bearing_core.quasistatic_kernels) ---------
    def _kargs(self):
        """Geometry / parameter array, cos / sin of the azimuths, control code and Hertz tables of the
        kernels (built per call: omega_outer may be set after construction)."""
        g = self.g
        geo = np.empty(qsk.N_GEO)
        geo[qsk.G_D], geo[qsk.G_DM], geo[qsk.G_FO], geo[qsk.G_FI] = g.D, g.dm, g.fo, g.fi
        geo[qsk.G_A], geo[qsk.G_ALPHA0], geo[qsk.G_RI], geo[qsk.G_RIG] = g.A, g.alpha0, g.Ri, g.ri
        geo[qsk.G_MASS], geo[qsk.G_INERTIA] = g.ball_mass, g.ball_inertia
        geo[qsk.G_MU], geo[qsk.G_WOUT] = self.mu_gyro, self.omega_outer
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
        """Initial ball positions: on the line of centres, with equal deflections; at speed a ball in the
        clearance starts on the outer race, pressed by the pure-rolling centrifugal force."""
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
        F, X, S, ok = qsk.residual(u, float(omega), np.ascontiguousarray(X0, dtype=float),
                                   np.asarray(outer_ctrl, dtype=bool), ctrl, geo, c, s, ti, to, dal)
        return F, X, _state_dict(S), bool(ok)

    def _ring_force(self, st):
        """(Fx, Fy, Fz, Mx, My) of the balls on the inner ring from a ball state [N, N m]."""
        return _ring_forces(self.g, self.psi, st["ai"], st["Qi"], st["Fi"])

    # ---- the 5-DOF solve ---------------------------------------------------------------------
    def solve(self, omega: float, loads, u0=None, tol: float = 1e-10, maxit: int = 100,
              stiffness: bool = True) -> QuasiStaticResult:
        """Solve for the inner-ring displacements under loads (Fx, Fy, Fz, Mx, My) [N, N m] at inner-ring
        speed omega [rad/s]. Uses continuation in speed from the static solution when a direct solve
        fails. Raises ConvergenceError if no equilibrium is found."""
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
            # continuation: static solution first, then speed in steps
            try:
                res = self._solve(0.0, loads, None, tol, maxit, False)
                u = res.u
                for w in np.linspace(0.0, omega, 9)[1:]:
                    res = self._solve(float(w), loads, u, tol, maxit, False)
                    u = res.u
                return self._solve(omega, loads, u, tol, maxit, stiffness)
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

    def _solve(self, omega, loads, u0, tol, maxit, stiffness):
        """One Newton solve of the 5-DOF ring equilibrium (qsk.solve; algorithm in its docstring)."""
        g = self.g
        u = self._u_guess(loads) if u0 is None else np.array(u0, dtype=float)
        self._omega = omega
        geo, c, s, ctrl, ti, to, dal = self._kargs()
        X = np.empty((g.Z, 2))
        S = np.empty((qsk.NS, g.Z))
        Kmat = np.empty((5, 5))
        info = np.zeros(2)
        status, it = qsk.solve(float(omega), np.ascontiguousarray(loads, dtype=float), u, self.fixed_tilt, ctrl,
                               float(tol), int(maxit), bool(stiffness), geo, c, s, ti, to, dal, X, S, Kmat, info)
        if status == qsk.LINE_SEARCH_FAILED:
            raise ConvergenceError(f"quasi-static line search failed at omega={omega:.4g} rad/s, "
                                   f"loads={loads.tolist()}, |residual|={info[0]:.3e}")
        if status != qsk.OK:
            raise ConvergenceError(f"quasi-static model did not converge in {maxit} iterations at "
                                   f"omega={omega:.4g} rad/s, loads={loads.tolist()}, "
                                   f"max scaled residual={info[1]:.3e}")
        st = _state_dict(S)
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
        return qsk.stiffness(np.asarray(res.u, dtype=float), float(res.omega), np.ascontiguousarray(res.X),
                             np.asarray(res.outer_control, dtype=bool), ctrl, geo, c, s, ti, to, dal)


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

    Geometry (bearing_core.geometry module docstring): relative to the curvature centre O_o1 of outer
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
    load-weighted mean contact angle sum_k w_k alpha_k, w_k = Q_k / sum Q (see _weights), and the friction
    force resisting the gyroscopic moment is shared between that ring's contacts by the same weights. With
    one loaded contact per ring this is the two-point model exactly. With three or four loaded contacts a
    ball cannot roll without sliding on all of them; that sliding (Leblanc & Nelias 2007) and its friction
    are not resolved here (a stated simplification), only the contact loads and angles."""

    FOUR_POINT = True

    def _centres(self, u):
        g = self.g
        c, s = np.cos(self.psi), np.sin(self.psi)
        tilt = u[3] * s - u[4] * c
        dr = u[0] * c + u[1] * s
        da = u[2] + g.Ri * tilt
        ei = g.inner_groove_offset
        Cr0 = g.A * math.cos(g.alpha0) + dr
        Cz1 = g.A * math.sin(g.alpha0) + da
        Cr = np.stack([Cr0 - ei * tilt, Cr0 + ei * tilt], axis=1)
        Cz = np.stack([Cz1, Cz1 - 2.0 * ei], axis=1)
        return Cr, Cz

    def _ball_state(self, X, Cr, Cz, omega, outer_ctrl, kin_frozen=None):
        g = self.g
        eo, ei = g.outer_groove_offset, g.inner_groove_offset
        Xr, Xz = X[:, 0:1], X[:, 1:2]
        # outer arcs 1, 2: centres (0, 0), (0, 2 e_o)
        vz = np.concatenate([Xz, Xz - 2.0 * eo], axis=1)
        vr = np.broadcast_to(Xr, vz.shape)
        lo = np.hypot(vr, vz)
        nor, noz = vr / lo, vz / lo
        d_o = lo - (g.fo - 0.5) * g.D
        ao = np.arctan2(noz, nor)
        so = g.fo * g.D * noz
        val_o = np.stack([so[:, 0] >= eo, so[:, 1] < -eo], axis=1)
        # inner arcs 1, 2
        dvr, dvz = Xr - Cr, Xz - Cz
        li = np.hypot(dvr, dvz)
        nir, niz = dvr / li, dvz / li
        d_i = li - (g.fi - 0.5) * g.D
        ai = np.arctan2(-niz, -nir)
        si = -g.fi * g.D * niz
        val_i = np.stack([si[:, 0] >= ei, si[:, 1] < -ei], axis=1)
        Ki = self.hz.K(ai, inner=True)
        Ko = self.hz.K(ao, inner=False)
        Qi = np.where(val_i, np.where(d_i > 0, Ki * np.abs(d_i) ** 1.5, K_REG * d_i), 0.0)
        Qo = np.where(val_o, np.where(d_o > 0, Ko * np.abs(d_o) ** 1.5, K_REG * d_o), 0.0)
        wi, wo = self._weights(Qi, d_i, val_i), self._weights(Qo, d_o, val_o)
        ai_e, ao_e = np.sum(wi * ai, axis=1), np.sum(wo * ao, axis=1)
        di_e = np.max(np.where(val_i, d_i, -np.inf), axis=1)
        if self.control == "inner":
            outer_ctrl = np.zeros(g.Z, dtype=bool)
        elif self.control == "hybrid":
            outer_ctrl = outer_ctrl | (di_e <= 0)
        if kin_frozen is None:
            beta, wm, wR = kin.kinematics(omega, ai_e, ao_e, g.D, g.dm, self.control, outer_ctrl)
        else:
            beta, wm, wR = kin_frozen
        wma = wm + self.omega_outer          # absolute orbital speed
        Fc = 0.5 * g.ball_mass * g.dm * wma ** 2
        Mg = g.ball_inertia * wma * wR * np.sin(beta) * -1.0
        lam_i = _lambda_i(self.control, outer_ctrl)
        lam_o = 2.0 - lam_i
        Qi_s = np.sum(np.maximum(Qi, 0.0), axis=1)
        Qo_s = np.sum(np.maximum(Qo, 0.0), axis=1)
        Fi = _coulomb_bound(lam_i * Mg / g.D, self.mu_gyro * Qi_s)
        Fo = _coulomb_bound(lam_o * Mg / g.D, self.mu_gyro * Qo_s)
        Fi4, Fo4 = wi * Fi[:, None], wo * Fo[:, None]
        Rr = np.sum(-Qi * nir + Fi4 * niz, axis=1) + np.sum(-Qo * nor + Fo4 * noz, axis=1) + Fc
        Rz = np.sum(-Qi * niz - Fi4 * nir, axis=1) + np.sum(-Qo * noz - Fo4 * nor, axis=1)
        rows = np.arange(g.Z)
        ki, ko = np.argmax(wi, axis=1), np.argmax(wo, axis=1)
        return dict(Rr=Rr, Rz=Rz, Qi=Qi[rows, ki], Qo=Qo[rows, ko], d_i=d_i[rows, ki], d_o=d_o[rows, ko],
                    ai=ai_e, ao=ao_e, beta=beta, wm=wm, wR=wR, Fc=Fc, Mg=Mg, lam_i=lam_i, outer_ctrl=outer_ctrl,
                    Fi=Fi, Fo=Fo, Qi4=Qi, Qo4=Qo, ai4=ai, ao4=ao, di4=d_i, do4=d_o, ki=ki, ko=ko, Fi4=Fi4,
                    Fo4=Fo4, wi=wi, wo=wo)

    # ---- Newton drivers of the four-point model (numpy; the two-point model runs them as numba kernels,
    # bearing_core.quasistatic_kernels, with the same algorithm) ---------------------------------
    def _newton_balls(self, u, omega, X0, outer_ctrl, tol=1e-10, maxit=60):
        """Newton per ball (vectorised, 2x2 finite-difference Jacobians) for the ball equilibrium
        (algorithm of quasistatic_kernels._solve_balls)."""
        g = self.g
        Cr, Cz = self._centres(u)
        X = X0.copy()
        scale = max(1.0, 0.5 * g.ball_mass * g.dm * omega ** 2)
        h = 1e-10 * g.D
        for it in range(maxit):
            st = self._ball_state(X, Cr, Cz, omega, outer_ctrl)
            R = np.stack([st["Rr"], st["Rz"]], axis=1)
            if np.max(np.abs(R)) < tol * (scale + max(st["Qi"].max(), st["Qo"].max(), 0.0)):
                return X, st, True
            J = np.empty((g.Z, 2, 2))
            for k in range(2):
                Xp = X.copy()
                Xp[:, k] += h
                sp = self._ball_state(Xp, Cr, Cz, omega, outer_ctrl)
                J[:, 0, k] = (sp["Rr"] - st["Rr"]) / h
                J[:, 1, k] = (sp["Rz"] - st["Rz"]) / h
            det = J[:, 0, 0] * J[:, 1, 1] - J[:, 0, 1] * J[:, 1, 0]
            det = np.where(np.abs(det) > 0, det, 1e-300)
            dX0 = -(J[:, 1, 1] * R[:, 0] - J[:, 0, 1] * R[:, 1]) / det
            dX1 = -(-J[:, 1, 0] * R[:, 0] + J[:, 0, 0] * R[:, 1]) / det
            dX = np.stack([dX0, dX1], axis=1)
            bad = ~np.all(np.isfinite(dX), axis=1)
            if bad.any():  # singular 2x2 (e.g. degenerate kinematics): small steepest-descent step
                dX[bad] = -1e-4 * g.D * np.sign(np.nan_to_num(R[bad]))
            # limit a step to 1e-3 D (~ contact deflections) and backtrack per ball on |R|
            lim = 1e-3 * g.D
            mag = np.max(np.abs(dX), axis=1, keepdims=True)
            dX = np.where(mag > lim, dX * lim / np.maximum(mag, 1e-300), dX)
            n0 = np.hypot(R[:, 0], R[:, 1])
            lam = np.ones(g.Z)
            Xn = X + dX
            for _ in range(12):
                sn = self._ball_state(Xn, Cr, Cz, omega, outer_ctrl)
                nn = np.hypot(sn["Rr"], sn["Rz"])
                worse = ~(nn <= n0 * (1.0 + 1e-9)) & (lam > 1e-3)
                if not worse.any():
                    break
                lam = np.where(worse, 0.5 * lam, lam)
                Xn = X + lam[:, None] * dX
            X = Xn
        st = self._ball_state(X, Cr, Cz, omega, outer_ctrl)
        return X, st, False

    def residual(self, u, omega, X0=None, outer_ctrl=None):
        """Force of the balls on the inner ring at displacement u (balls re-equilibrated from X0)."""
        self._omega = omega
        if X0 is None:
            X0 = self._x_start(u)
        if outer_ctrl is None:
            outer_ctrl = np.ones(self.g.Z, dtype=bool)
        X, st, ok = self._solve_balls(u, omega, X0, outer_ctrl)
        if not ok:
            # retry from the geometric start (the warm start may sit in a bad basin)
            X, st, ok = self._solve_balls(u, omega, self._x_start(u), outer_ctrl, maxit=200)
        return self._ring_force(st), X, st, ok

    def _solve(self, omega, loads, u0, tol, maxit, stiffness):
        """Newton solve of the ring equilibrium (algorithm of quasistatic_kernels.solve)."""
        g = self.g
        # scales: displacement ~ 1 um, tilt ~ 1e-5 rad; force scale from the load
        us = np.array([1e-6, 1e-6, 1e-6, 1e-5, 1e-5])
        Fscale = max(np.linalg.norm(loads[:3]), np.linalg.norm(loads[3:]) / (0.5 * g.dm), 1.0)
        fs = np.array([Fscale, Fscale, Fscale, Fscale * 0.5 * g.dm, Fscale * 0.5 * g.dm])
        u = self._u_guess(loads) if u0 is None else np.array(u0, dtype=float)
        if self.fixed_tilt:
            u[3:5] = 0.0
        self._omega = omega
        outer_ctrl = np.ones(g.Z, dtype=bool)
        X = self._x_start(u)

        def R_of(uu, Xw, oc):
            Fb, Xn, st, ok = self.residual(uu, omega, Xw, oc)
            r = (loads + Fb) / fs
            if self.fixed_tilt:
                r[3:5] = uu[3:5] / us[3:5]
            return r, Xn, st, ok

        r, X, st, ok = R_of(u, X, outer_ctrl)
        it = 0
        converged = False
        for it in range(1, maxit + 1):
            if self.control == "hybrid" and it <= 15:
                new_oc = self._hybrid_criterion(st)
                if np.any(new_oc != outer_ctrl):
                    outer_ctrl = new_oc
                    r, X, st, ok = R_of(u, X, outer_ctrl)
            if ok and np.max(np.abs(r)) < tol:
                converged = True
                break
            J = np.empty((5, 5))
            for k in range(5):
                up = u.copy()
                up[k] += 1e-2 * us[k]
                rp, _, _, _ = R_of(up, X, outer_ctrl)
                J[:, k] = (rp - r) / (1e-2)
            try:
                step = -np.linalg.lstsq(J, r, rcond=1e-12)[0]
            except np.linalg.LinAlgError:
                break
            # backtracking line search on |r|, step limited to 20 um / 1 mrad scaled units
            smax = np.max(np.abs(step) / np.array([20.0, 20.0, 20.0, 100.0, 100.0]))
            if smax > 1:
                step /= smax
            lam = 1.0
            n0 = np.linalg.norm(r)
            for _ in range(16):
                un = u + lam * step * us
                rn, Xn, stn, okn = R_of(un, X, outer_ctrl)
                if okn and np.linalg.norm(rn) < (1 - 1e-4 * lam) * n0:
                    break
                lam *= 0.5
            else:
                raise ConvergenceError(f"quasi-static line search failed at omega={omega:.4g} rad/s, "
                                       f"loads={loads.tolist()}, |residual|={n0:.3e}")
            u, r, X, st, ok = un, rn, Xn, stn, okn
        if not converged:
            raise ConvergenceError(f"quasi-static model did not converge in {maxit} iterations at "
                                   f"omega={omega:.4g} rad/s, loads={loads.tolist()}, "
                                   f"max scaled residual={np.max(np.abs(r)):.3e}")
        res = self._result(omega, loads, u, X, st, st["outer_ctrl"], it)
        if stiffness:
            res.stiffness = self.stiffness_matrix(res)
        return res

    def _hybrid_criterion(self, st):
        """Harris: outer control where Q_o a_o E(k_o) cos(ai - ao) > Q_i a_i E(k_i)."""
        ai, ao = st["ai"], st["ao"]
        Qi, Qo = np.maximum(st["Qi"], 0), np.maximum(st["Qo"], 0)
        a_i, _, _, Ei = self.hz.ab_E(ai, Qi, inner=True)
        a_o, _, _, Eo = self.hz.ab_E(ao, Qo, inner=False)
        return Qo * a_o * Eo * np.cos(ai - ao) > Qi * a_i * Ei

    def stiffness_matrix(self, res: QuasiStaticResult) -> np.ndarray:
        """5x5 bearing stiffness K_kl = d(load_k)/d(u_l) at the solution, by central differences
        of the ring force with every ball re-equilibrated [N/m, N/rad, N m/m, N m/rad]."""
        h = np.array([1e-8, 1e-8, 1e-8, 1e-7, 1e-7])
        Kmat = np.empty((5, 5))
        for k in range(5):
            up = res.u.copy()
            um = res.u.copy()
            up[k] += h[k]
            um[k] -= h[k]
            Fp, _, _, _ = self.residual(up, res.omega, res.X, res.outer_control)
            Fm, _, _, _ = self.residual(um, res.omega, res.X, res.outer_control)
            Kmat[:, k] = -(Fp - Fm) / (2 * h[k])
        return Kmat

    def _weights(self, Q, d, valid):
        """Share w_k of each arc of one ring in the ball kinematics and the gyroscopic friction: the
        contact loads Q_k (plus 1e-9 N times a softmax of the deflections over 1e-6 D, which decides for
        unloaded balls and keeps w continuous); 0 on invalid arcs. A ring with one loaded contact gets
        w = 1 there: the two-point model exactly."""
        g = self.g
        dm_ = np.max(np.where(valid, d, -np.inf), axis=1, keepdims=True)
        soft = np.where(valid, np.exp(np.minimum(0.0, d - dm_) / (1e-6 * g.D)), 0.0)
        w = np.where(valid, np.maximum(Q, 0.0), 0.0) + 1e-9 * soft
        return w / np.sum(w, axis=1, keepdims=True)

    def _ring_force(self, st):
        return _ring_forces4(self.g, self.psi, st["ai4"], st["Qi4"], st["Fi4"])

    def _solve_balls(self, u, omega, X0, outer_ctrl, tol=1e-10, maxit=60):
        """As QuasiStaticModel._solve_balls; balls that the Newton iteration leaves out of equilibrium
        (a lightly loaded ball whose equilibrium contact angles are far from its start) are restarted
        from the minimum of their contact + centrifugal potential."""
        X, st, ok = self._newton_balls(u, omega, X0, outer_ctrl, tol, maxit)
        if ok:
            return X, st, ok
        scale = max(1.0, 0.5 * self.g.ball_mass * self.g.dm * omega ** 2)
        bad = np.hypot(st["Rr"], st["Rz"]) >= tol * (scale + max(st["Qi"].max(), st["Qo"].max(), 0.0))
        Xe = X.copy()
        Cr, Cz = self._centres(u)
        for j in np.flatnonzero(bad):
            Xe[j] = self._potential_minimum(X[j], Cr[j], Cz[j], float(st["Fc"][j]))
        return self._newton_balls(u, omega, Xe, outer_ctrl, tol, maxit)

    def _potential_minimum(self, x0, Cr, Cz, Fc):
        """Ball centre [m] minimising sum_k (2/5) K_k delta_k^2.5 - Fc Xr over the valid arcs (Hertz
        contacts of one ball; K at the free contact angle), from x0 (scipy Nelder-Mead, 1e-4 um)."""
        from scipy.optimize import minimize

        g = self.g
        eo, ei = g.outer_groove_offset, g.inner_groove_offset
        Ki = float(self.hz.K(np.array([g.alpha0]), inner=True)[0])
        Ko = float(self.hz.K(np.array([g.alpha0]), inner=False)[0])
        cen = [(0.0, 0.0, Ko, g.fo, 1, eo), (0.0, 2 * eo, Ko, g.fo, 2, eo),
               (Cr[0], Cz[0], Ki, g.fi, -1, ei), (Cr[1], Cz[1], Ki, g.fi, -2, ei)]
        um = 1e-6

        def pot(y):
            xr, xz = x0[0] + y[0] * um, x0[1] + y[1] * um
            e = -Fc * (xr - x0[0])
            for cr, cz, K, f, kind, off in cen:
                vr, vz = xr - cr, xz - cz
                L = math.hypot(vr, vz)
                sn = vz / L if kind > 0 else -vz / L        # sin of the contact angle
                valid = f * g.D * sn >= off if abs(kind) == 1 else f * g.D * sn < -off
                d = L - (f - 0.5) * g.D
                if valid and d > 0:
                    e += 0.4 * K * d ** 2.5
            return e

        res = minimize(pot, np.zeros(2), method="Nelder-Mead",
                       options={"xatol": 1e-4, "fatol": 1e-14, "initial_simplex": [[0, 0], [20, 0], [0, 20]],
                                "maxiter": 2000})
        return x0 + res.x * um

    def _x_start(self, u):
        """Initial ball positions: per ball the candidate with the smaller force residual among (a) the
        line of centres of the more compressed diagonal pair with equal deflections (the mean of both
        pairs when both are compressed) and, at speed, (b) the seat in the outer arch: on the outer groove
        mid-plane, pressed into both outer arcs by the centrifugal force."""
        X = self._x_start_pairs(u)
        g = self.g
        if self._omega > 0 and g.outer_groove_offset > 0:
            wm = 0.5 * self._omega * (1.0 - g.D / g.dm)
            Fc = 0.5 * g.ball_mass * g.dm * wm ** 2
            eo, ro = g.outer_groove_offset, (g.fo - 0.5) * g.D
            K0 = float(self.hz.K(np.array([g.alpha0]), inner=False)[0])
            sa = eo / ro                                     # sin of the arch contact angle of a seated ball
            lo = ro + (Fc / (2.0 * K0 * math.sqrt(max(1.0 - sa * sa, 1e-6)))) ** (2.0 / 3.0)
            Xs = np.tile([math.sqrt(max(lo * lo - eo * eo, 0.0)), eo], (g.Z, 1))
            Cr, Cz = self._centres(u)
            oc = np.ones(g.Z, dtype=bool)
            s1 = self._ball_state(X, Cr, Cz, self._omega, oc)
            s2 = self._ball_state(Xs, Cr, Cz, self._omega, oc)
            better = np.hypot(s2["Rr"], s2["Rz"]) < np.hypot(s1["Rr"], s1["Rz"])
            X[better] = Xs[better]
        return X

    def _x_start_pairs(self, u):
        g = self.g
        Cr, Cz = self._centres(u)
        Oz = np.array([0.0, 2.0 * g.outer_groove_offset])
        vr, vz = Cr, Cz - Oz
        L = np.hypot(vr, vz)
        ro, ri = (g.fo - 0.5) * g.D, (g.fi - 0.5) * g.D
        d = 0.5 * (L - (ro + ri))
        t = (ro + d) / np.maximum(L, 1e-300)
        Xr, Xz = vr * t, Oz + vz * t
        both = np.all(d > 0, axis=1)
        k = np.argmax(d, axis=1)
        rows = np.arange(g.Z)
        X = np.stack([np.where(both, 0.5 * (Xr[:, 0] + Xr[:, 1]), Xr[rows, k]),
                      np.where(both, 0.5 * (Xz[:, 0] + Xz[:, 1]), Xz[rows, k])], axis=1)
        free = d[rows, k] < 0
        if self._omega > 0 and free.any():
            wm = 0.5 * self._omega * (1.0 - g.D / g.dm)
            Fc = 0.5 * g.ball_mass * g.dm * wm ** 2
            K0 = float(self.hz.K(np.array([g.alpha0]), inner=False)[0])
            kf = k[free]
            ao = np.arctan2(vz[free, kf], vr[free, kf])
            lo = ro + (Fc / K0) ** (2.0 / 3.0)
            X[free, 0] = lo * np.cos(ao)
            X[free, 1] = Oz[kf] + lo * np.sin(ao)
        return X

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


def solve_quasistatic(geometry: BearingGeometry, omega: float, loads, control: str = "outer",
                      stiffness: bool = True, mu_gyro: float = 0.1, fits=None,
                      temperatures=None) -> QuasiStaticResult:
    """Convenience wrapper: quasistatic_model(geometry, control).solve(omega, loads).

    omega: inner-ring speed [rad/s] (>= 0); loads: (Fx, Fy, Fz, Mx, My) [N, N m] applied to the inner
    ring; control: 'outer' | 'inner' | 'hybrid'. fits (bearing_core.ring_fits.RingFits) and/or
    temperatures (ring_fits.OperatingTemperatures): solve the operating geometry
    ring_fits.operating_geometry(geometry, omega, fits, temperatures) (centrifugal, thermal and fit growth
    of the rings; result.geometry is that geometry)."""
    if fits is not None or temperatures is not None:
        geometry = operating_geometry(geometry, omega, fits, temperatures)
    return quasistatic_model(geometry, control, mu_gyro=mu_gyro).solve(omega, loads, stiffness=stiffness)
