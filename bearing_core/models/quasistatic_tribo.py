"""Quasi-static tribological model: steady ball motion with the traction of the dynamics' contact interface.

Seed 000 (Lubricants 2025 13(5) 218, Sec. 3.1, stage 1) starts its tribo-dynamic runs from a quasi-static
model in which the ball motion follows from the traction of rolling-contact theory (its ref. [19], Zhao,
Ma & Zi, Friction 11 (2023) 1987) instead of a raceway-control hypothesis (Jones-Harris, quasistatic.py).
This module is that model, built on the SAME contact interface as the dynamics: the right-hand side
``dynamics_kernels.rhs`` (Hertz contact through the groove curvature centres, contact kinematics and the
traction of ``DynamicsOptions.traction``: Kalker/FASTSIM, lubricated (rheology-based EHL traction with mixed
lubrication and the EHL rolling-resistance moment of each ball-race contact, bearing_core.lubrication.ehl_traction), the
illustrative curve or Coulomb, plus ball drag and churning) is evaluated at a state in which nothing
accelerates, and the accelerations are driven to zero. The rolling-resistance moment enters the ball moment
equations and, with the opposite sign, the ring's torque, as in the dynamics.

Steady state (Gupta, Advanced Dynamics of Rolling Elements 1984, Ch. 3 equations with all rates zero, in
the frame turning with each ball's azimuth psi_j = 2 pi j / Z):
  ball j, unknowns r_j, z_j (centre), Omega_j = (Omega_r, Omega_t, Omega_z) (absolute angular velocity, local
  frame) and its orbital speed th_d = theta_dot_j:
      F_r + m r th_d^2 = 0,   F_z = 0,   F_t = 0                                 (forces, centrifugal)
      M_r + J th_d Omega_t = 0,   M_t - J th_d Omega_r = 0,   M_z = 0             (moments, gyroscopic)
  inner ring (load-driven), unknowns (dx, dy, dz, tx, ty):  F_ext + sum_j F_ball->ring = 0 (5 equations;
  tx, ty held at 0 with fixed_tilt).
Each ball orbits freely at its own speed (as Jones-Harris, Harris & Kotzalas Vol. 2 Ch. 3: balls free in
their pocket clearance); the cage is centred, every ball sits at its pocket centre, so the rhs's pocket and
land contacts carry no load (in the oil regime their films are left out as well: the cage losses come from the
dynamics), and ``cage_speed`` is the mean orbital speed. A cage-held variant (common orbit,
pocket forces as unknowns) was tried and dropped: under combined load it converged in 13 of 36 cases.
The traction enters wholly: F_t, the lateral traction F_m (from spin, Kalker's C23) and the spin moment move
the contact angles, the attitude and yaw of the spin axis and the orbital speed away from Jones-Harris.

Solution: 6 Z + 5 unknowns, with a finite-difference Jacobian of the bearing's arrow structure (balls do not
touch each other: a 6 x 6 block per ball coupled to the ring; column k of every ball block comes from ONE
rhs call that perturbs unknown k of all balls, and the rhs reports each ball's share of the ring loads:
12 calls per Jacobian). Pseudo-transient continuation (implicit Euler steps of a dissipative pseudo-dynamics
that grow into Newton steps; Kelley & Keyes, SIAM J. Numer. Anal. 35 (1998) 508) on a Jacobian kept over
the steps while they make progress (each step then costs one rhs call), in up to four stages:
  1. near-Newton: a large first pseudo-time step (the pseudo-time term only a small shift of the diagonal),
     steps capped at 2 um / 0.3 omega, the Jacobian rebuilt when an uncapped step contracts the residual
     less than two-fold or a capped one lets it grow after 5 steps on one Jacobian (every other rebuild
     renews only the ball blocks, 6 rhs calls, and keeps the ring's columns); a point converged on a
     kept Jacobian is polished by up to 4 more chord steps while they contract. Budget 120 evaluations;
  2. the continuation from a small pseudo-time step (dtau 1), rebuilt also when dtau grew ten-fold, finished
     by one step on a new Jacobian (it gets through where the near-Newton steps stall: measured at
     Kalker mu 0.001 and in the lubricated cases at 10,000 rpm);
  3. the same with a new Jacobian at every step;
  4. a trust-region least-squares solve (scipy.optimize.least_squares 'trf').
A stage that ends at a spurious root (a ball that carried load at the start has lost both raceway contacts
or a ball has (nearly) stopped orbiting) counts as failed; the next one starts again from the start. Residuals,
Jacobian, the block-arrow linear solves and the continuation loop run in numba (quasistatic_tribo_kernels).
Start: the Jones-Harris solution (outer raceway control; the state DynamicModel.initialize starts from,
without its stiffness matrix), or a previous solution
(solve(start=...), e.g. the neighbouring case of a sweep; if it fails, the Jones-Harris start follows); if
that fails, continuation in speed from 100 rpm. The kernel parameters (DynamicModel's, for the bearing and
options) are memoised. Residuals are forces [N] (moments over D/2 or dm/2). Measured on 7218B
(bench/bench_tribo_qs.py, rheology-based EHL traction): 27 of 36 cases (Kalker 0.1 / 0.001, Coulomb,
lubricated; 1000 / 3000 / 10,000 rpm; pure thrust and two combined loads) converge to 1e-7 of the load;
the Coulomb and lubricated cases at 1000 and 3000 rpm in 34-117 rhs calls (stage 1), Kalker mu 0.001 at
1000 / 3000 rpm in 350-550 (stage 2); the rest raise ConvergenceError (Kalker 0.1 at 1000 rpm under
combined load and at 3000 rpm under Fx 3 kN / Fz 2 kN; at 10,000 rpm Kalker 0.001 and Coulomb under
combined load, Kalker 0.1 and lubricated under Fx 3 kN / Fz 2 kN, where the only roots found have balls
stopped in the unloaded zone).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from functools import lru_cache

import numpy as np

from . import dynamics_kernels as K
from . import quasistatic_tribo_kernels as TK
from ..errors import BearingInputError, ConvergenceError, check_range
from ..bearing.geometry import BearingGeometry
from .quasistatic import quasistatic_model
from .dynamics_setup import DynamicSetup, DynamicsOptions

NLOC = TK.NLOC      # per-ball unknowns: r, z, Omega_r, Omega_t, Omega_z, theta_dot
NGLOB = TK.NGLOB    # dx, dy, dz, tx, ty, (omega_c: not an unknown with free orbits; kept for the layout)
GLOBAL_NAMES = ("dx", "dy", "dz", "tx", "ty", "cage_speed")


@dataclass
class TriboQuasiStaticResult:
    """Steady state of the quasi-static tribological model. Per-ball arrays have length Z. SI units (m, rad,
    N, N m, rad/s, W). ``y`` is the matching state vector of dynamics_kernels (start of a dynamic run)."""

    geometry: BearingGeometry
    omega: float                  # inner-ring speed [rad/s]
    loads: np.ndarray             # (Fx, Fy, Fz, Mx, My) [N, N m]
    traction: str
    mu: float
    u: np.ndarray                 # inner-ring (dx, dy, dz, tx, ty) [m, rad]
    cage_speed: float             # mean orbital speed of the balls [rad/s]
    psi: np.ndarray               # ball azimuths [rad]
    alpha_i: np.ndarray
    alpha_o: np.ndarray
    Q_i: np.ndarray
    Q_o: np.ndarray
    a_i: np.ndarray
    b_i: np.ndarray
    a_o: np.ndarray
    b_o: np.ndarray
    omega_ball: np.ndarray        # (Z, 3) absolute angular velocity (Omega_r, Omega_t, Omega_z) [rad/s]
    attitude: np.ndarray          # attitude angle of the spin axis (cage frame) [rad]
    yaw: np.ndarray               # yaw angle of the spin axis [rad]
    Ft_i: np.ndarray              # traction on the ball along the rolling direction [N]
    Fm_i: np.ndarray              # traction across (along the major axis) [N]
    Ft_o: np.ndarray
    Fm_o: np.ndarray
    slip_i: np.ndarray            # contact-centre slip along the rolling direction [m/s]
    slip_o: np.ndarray
    u_i: np.ndarray               # entrainment speed [m/s]
    u_o: np.ndarray
    spin_i: np.ndarray            # spin about the contact normal relative to the race [rad/s]
    spin_o: np.ndarray
    orbit_speed: np.ndarray       # orbital speed of each ball [rad/s]
    friction_torque: float        # torque the shaft supplies [N m]
    reaction: np.ndarray          # (Fx, Fy, Fz, Mx, My) of the balls on the inner ring [N, N m]
    losses: dict                  # loss powers [W] by source and the drive power
    residual: float               # max |residual| [N] (forces; moments over D/2 or dm/2)
    iterations: int
    y: np.ndarray = field(repr=False, default=None)
    jones_harris: object = field(repr=False, default=None)   # the Jones-Harris start (None: warm start)

    @property
    def slide_roll_i(self):
        return self.slip_i / np.where(self.u_i > 0, self.u_i, np.inf)

    @property
    def slide_roll_o(self):
        return self.slip_o / np.where(self.u_o > 0, self.u_o, np.inf)

    @property
    def spin_roll_i(self):
        return self.spin_i * 0.5 * self.geometry.D / np.where(self.u_i > 0, self.u_i, np.inf)

    @property
    def spin_roll_o(self):
        return self.spin_o * 0.5 * self.geometry.D / np.where(self.u_o > 0, self.u_o, np.inf)


@lru_cache(maxsize=32)
def _checked_options(geometry: BearingGeometry, options):
    """options for the quasi-static solve (full model, no thermal network) after the dynamics' checks of
    the bearing and the options (DynamicSetup raises on bad ones); memoised (the result is immutable)."""
    opt = replace(options, reduced="full", thermal=False)
    DynamicSetup(geometry, opt)
    return opt


@lru_cache(maxsize=32)
def _kernel_setup(geometry: BearingGeometry, options, omega: float):
    """Parameters of the dynamics' right-hand side for the quasi-static solve, as DynamicModel.initialize
    sets them (running geometry at shaft speed omega [rad/s] with options.ring_growth, isothermal at the
    oil temperature), with the cage's oil films off (module docstring) and the ring's support damping
    left at 0 (the ring does not move in a steady state): (running geometry, P, tab_i, tab_o, ta0, tda,
    tp, quadrature). They depend on the bearing, the options and (with ring growth only) the speed, so they
    are memoised (~0.2 ms a build); callers take copies (_setup)."""
    dm = DynamicSetup(geometry, options)
    dm.update_operating_geometry(omega)
    dm.P = dm._params(False)
    dm.U[K.U_W0] = dm.U[K.U_W1] = omega
    dm.apply_temperatures(options.oil_temperature, options.oil_temperature)
    P = dm.P
    # Free balls, centred cage (module docstring): the cage takes no part, so its oil films (pocket shear,
    # flooded-land drag) are left out too; otherwise they would load the balls and drag a cage whose
    # torque balance is not an equation here, and power in would not equal heat out.
    P[K.P_LUBE] = 0.0
    P[K.P_ETA_LAND] = 0.0
    return dm.g, P, dm._tab_i, dm._tab_o, dm._ta0, dm._tda, dm._tp, dm._quad


class TriboQuasiStaticModel:
    """Quasi-static tribological model of one bearing with the traction of ``options`` (a DynamicsOptions:
    traction, mu, kalker_grid, lubricant, u_min, drag, churning, fixed_tilt are used; integrator settings
    are not). Load-driven inner ring only."""

    #: first stage of the solve: pseudo-transient continuation on a kept Jacobian (False: start with the
    #: per-step Jacobian, as the fallback does)
    lazy_jacobian = True
    #: near-Newton first attempt of the kept-Jacobian continuation: initial pseudo-time step (scaled) and
    #: residual evaluations (0: none)
    fast_dtau0 = 1.0e4
    fast_budget = 120
    #: tolerance of the Jones-Harris start (QuasiStaticModel.solve's scaled ring residual). Measured: 1e-6
    #: or 1e-8 save 1-3 of its ~10 iterations (~0.05 ms), but the start then moves by round-off, and that
    #: flips the outcome of cases that end in the fallback stages (at 1e-8, 2 of bench_tribo_qs.py --speed's
    #: 87 converging cases fail; at 1e-6, 7218B Coulomb at 10,000 rpm under Fz 3.2 kN fails)
    jones_harris_tol = 1e-10
    #: step cap of the ring tilts from a previous solution [10 urad]
    warm_tilt_cap = 10.0

    def __init__(self, geometry: BearingGeometry, options=None):
        opt = DynamicsOptions() if options is None else options
        if opt.coupling != "load":
            raise BearingInputError("coupling", opt.coupling, "load (the quasi-static model takes loads)")
        if opt.outer_mount != "fixed":
            raise BearingInputError("outer_mount", opt.outer_mount, "fixed (quasi-static model)")
        geometry.require_two_point("quasi-static tribological model")
        self.g = geometry
        try:
            self.opt = _checked_options(geometry, opt)
        except TypeError:                      # options with unhashable fields: no memo
            self.opt = _checked_options.__wrapped__(geometry, opt)

    def solve(self, omega: float, loads, tol: float = 1e-7, maxit: int = 3000,
              start: TriboQuasiStaticResult | None = None) -> TriboQuasiStaticResult:
        """Steady state at inner-ring speed omega [rad/s] (>= 1: the ball motion comes from rolling) under
        loads (Fx, Fy, Fz, Mx, My) [N, N m]. tol: convergence when max |residual| < tol times the load scale
        (largest of |F|, |M|/(dm/2) and 1 N); maxit: residual evaluations of one solve. start: a previous
        solution to start from (speeds scaled to omega; e.g. the neighbouring load case of a sweep: no
        Jones-Harris solve, the result's jones_harris is None), else the Jones-Harris solution; if the
        previous solution does not lead to a solution, the Jones-Harris start follows; if that does not
        converge, the solution is continued in speed from 100 rpm (or omega, if lower) in steps of x2 (a
        quarter of maxit each). Raises ConvergenceError if no step converges."""
        omega = check_range("omega", omega, 1.0, 2.0e4, unit="rad/s")
        check_range("tol", tol, 1e-12, 1e-2)
        if not isinstance(maxit, int) or not 1 <= maxit <= 100000:
            raise BearingInputError("maxit", maxit, "integer 1..100000")
        loads = np.asarray(loads, dtype=float).reshape(-1)
        if loads.size != 5 or not np.all(np.isfinite(loads)):
            raise BearingInputError("loads", loads.tolist(), "5 finite values (Fx, Fy, Fz, Mx, My)")
        if start is not None and not isinstance(start, TriboQuasiStaticResult):
            raise BearingInputError("start", type(start).__name__,
                                    "None or a TriboQuasiStaticResult of an earlier solve")
        try:
            return self._solve_one(omega, loads, tol, maxit, start, need_jh=False)
        except BearingInputError:
            raise
        except (ConvergenceError, np.linalg.LinAlgError, ValueError) as e:
            first = e
        if start is not None:                  # a previous solution that does not lead here: Jones-Harris
            try:
                return self._solve_one(omega, loads, tol, maxit, None)
            except BearingInputError:
                raise
            except (ConvergenceError, np.linalg.LinAlgError, ValueError):
                pass
        w_lo = min(omega, 100.0 * math.pi / 30.0)
        speeds = [w_lo]
        while speeds[-1] < omega:
            speeds.append(min(speeds[-1] * 2.0, omega))
        prev = None
        for w in speeds:
            try:
                prev = self._solve_one(w, loads, tol, max(maxit // 4, 50), prev, need_jh=(w == speeds[-1]))
            except BearingInputError:
                raise
            except (ConvergenceError, np.linalg.LinAlgError, ValueError) as e:
                raise ConvergenceError(f"{first}; continuation in speed failed at {w * 30 / math.pi:.0f} rpm: {e}") \
                    from None
        return prev

    def _setup(self, omega):
        """(running geometry, P, U-less kernel tables) for a solve at omega: copies of _kernel_setup's
        memoised arrays (every model gets its own)."""
        o = self.opt
        w = abs(float(omega)) if o.ring_growth else 0.0
        try:
            s = _kernel_setup(self.g, o, w)
        except TypeError:                      # options with unhashable fields: no memo
            s = _kernel_setup.__wrapped__(self.g, o, w)
        g, P, ti, to, ta0, tda, tp, quad = s
        return g, P.copy(), (ti.copy(), to.copy(), ta0, tda, tp.copy(), *(q.copy() for q in quad))

    def _jones_harris(self, g, omega, loads):
        """Jones-Harris solution (outer raceway control) of the running geometry g, as DynamicModel.initialize
        solves it (without the stiffness matrix: the ring does not move, its support damping does not act)."""
        if getattr(self, "_qsm_g", None) is not g:
            self._qsm = quasistatic_model(g, "outer", fixed_tilt=self.opt.fixed_tilt)
            self._qsm_g = g
        return self._qsm.solve(omega, loads, stiffness=False, tol=self.jones_harris_tol)

    def _solve_one(self, omega, loads, tol, maxit, start, need_jh=True):
        """One solve from start (None: the Jones-Harris solution); need_jh: solve Jones-Harris also when
        starting from a previous solution (for the result's jones_harris)."""
        g, P, tabs = self._setup(omega)
        Z = g.Z
        jh = self._jones_harris(g, omega, loads) if (start is None or need_jh) else None
        U = np.zeros(K.NU)
        U[K.U_W0] = U[K.U_W1] = omega
        U[K.U_FX:K.U_MY + 1] = loads
        t = 0.0
        # dynamics state of the start (DynamicModel.initialize's Jones-Harris state): ring at rest, centred
        # cage, balls at their pocket centres (free orbits)
        y = np.zeros(K.NSTATE_FIXED + K.NSB * Z)
        b = K.NSTATE_FIXED + K.NSB * np.arange(Z)
        psi = 2.0 * np.pi * np.arange(Z) / Z if jh is None else jh.psi.copy()
        y[b] = psi
        if start is None:
            Roo = 0.5 * g.dm - (g.fo - 0.5) * g.D * math.cos(g.alpha0)
            Zoo = -(g.fo - 0.5) * g.D * math.sin(g.alpha0)
            w_cage = jh.cage_speed
            y[0:5] = jh.u
            y[11] = w_cage
            y[b + 1] = Roo + jh.X[:, 0]
            y[b + 2] = Zoo + jh.X[:, 1]
            y[b + 3] = jh.omega_m
            for j in range(Z):                 # math.sin / cos: DynamicModel.initialize's state to the bit
                y[b[j] + 6] = -jh.omega_R[j] * math.sin(jh.beta[j])
                y[b[j] + 8] = jh.omega_R[j] * math.cos(jh.beta[j]) + jh.omega_m[j]
        hdm = 0.5 * g.dm
        act = np.ones(NGLOB, dtype=bool)
        if self.opt.fixed_tilt:
            act[3:5] = False
        act[5] = False                         # free orbits: no cage unknown
        scale = max(np.max(np.abs(loads[:3])), np.max(np.abs(loads[3:])) / hdm, 1.0)
        ftol = tol * scale
        iF, iM = K.OUT_INDEX["Fx"], K.OUT_INDEX["Mx"]

        xl = np.zeros((Z, NLOC))
        xg = np.zeros(NGLOB)
        if start is None:
            xl[:, 0] = y[b + 1]
            xl[:, 1] = y[b + 2]
            xl[:, 2:5] = y[np.stack([b + 6, b + 7, b + 8], axis=1)]
            xl[:, 5] = y[b + 3]
            xg[:5] = y[0:5]
            xg[5] = y[11]
            w_cage = abs(w_cage)
        else:                                  # previous solution, speeds scaled to this shaft speed
            ratio = omega / start.omega
            xl[:, 0] = start.y[b + 1]
            xl[:, 1] = start.y[b + 2]
            xl[:, 2:5] = start.omega_ball * ratio
            xl[:, 5] = start.orbit_speed * ratio
            xg[:5] = start.u
            xg[5] = start.cage_speed * ratio
            w_cage = abs(xg[5])

        # residuals, Jacobian, linear solves and the pseudo-transient loop: quasistatic_tribo_kernels
        # (numba), on the scaled unknowns (positions in um, speeds in omega, forces in N; the tilts in
        # 10 urad)
        xs_l = np.array([1e-6, 1e-6, omega, omega, omega, omega])
        xs_g = np.array([1e-6, 1e-6, 1e-6, 1e-5, 1e-5, omega])
        n = Z * NLOC + NGLOB
        wk = dict(xl=np.empty((Z, NLOC)), xg=np.empty(NGLOB), yy=np.empty(y.size), dy=np.empty(y.size),
                  diag=np.zeros(K.NOUT), bd=np.zeros((Z, K.NBD)), Rl=np.empty((Z, NLOC)), Rg=np.empty(NGLOB),
                  share=np.empty((Z, NGLOB)))

        last = [None]                          # the point whose outputs wk holds from a fresh evaluation

        def fun(v):
            last[0] = None
            R = np.empty(n)
            TK.scaled_residual(t, y, v, xs_l, xs_g, act, iF, iM, P, U, *tabs, wk["xl"], wk["xg"], wk["yy"],
                               wk["dy"], wk["diag"], wk["bd"], wk["Rl"], wk["Rg"], wk["share"], R)
            return R

        def jac(v):
            fun(v)
            A = np.empty((Z, NLOC, NLOC))
            B = np.empty((Z, NLOC, NGLOB))
            C = np.empty((Z, NGLOB, NLOC))
            Dg = np.empty((NGLOB, NGLOB))
            TK.jacobian(t, y, wk["xl"], wk["xg"], wk["Rl"], wk["Rg"], wk["share"], act, omega, iF, iM, P, U,
                        *tabs, wk["yy"], wk["dy"], wk["diag"], wk["bd"], A, B, C, Dg)
            J = np.empty((n, n))
            TK.assemble(A, B, C, Dg, xs_l, xs_g, J)
            return J

        def trf(v, budget):
            # trust-region least squares (scipy.optimize.least_squares, trust-region reflective); its SVDs of
            # the n x n Jacobian run on one BLAS thread (measured: 0.1 s per 102 x 102 SVD when OpenBLAS's
            # threads compete for 2 busy cores, against ~2 ms single-threaded)
            from scipy.optimize import least_squares
            from threadpoolctl import threadpool_limits
            with threadpool_limits(limits=1, user_api="blas"):
                sol = least_squares(fun, v, jac=jac, method="trf", xtol=1e-15, ftol=1e-15, gtol=1e-15,
                                    max_nfev=max(budget, 2))
            return sol.x, np.max(np.abs(fun(sol.x))), sol.nfev * 13

        v0 = np.concatenate([(xl / xs_l).ravel(), xg / xs_g])
        if not np.all(np.abs(fun(v0)) < 1e12):
            raise ConvergenceError("quasi-static tribological model: non-finite residual at the start")
        # stages of the solve (module docstring): near-Newton kept-Jacobian continuation (fast_budget
        # evaluations), the kept-Jacobian continuation from dtau 1 (a third of the budget), the per-step-Jacobian
        # continuation, then a trust-region least-squares solve from the start and from the better end point
        # (FASTSIM's slip/stick switching makes the residual only piecewise smooth; one of them usually gets
        # through). A stage that ends where a ball that carried load at the start has lost both raceway
        # contacts or a ball has (nearly) stopped orbiting (spurious roots: a ball without contact load and
        # without orbital speed has zero residuals) counts as failed.
        # step cap of the ring tilts [10 urad]: 3 urad from the Jones-Harris start (measured: larger caps
        # cost more evaluations there, 58 -> 73 for 7218B, 3000 rpm, Fx 1 kN, Fz 3 kN at 10 urad); from a
        # previous solution the tilt may have to move by ~0.5 mrad (a new radial load), which at 3 urad a
        # step took some hundred steps (median 347 evaluations over bench_tribo_qs.py --sweep's kind of
        # sweeps, 36 at 100 urad). The later stages keep 3 urad (the smaller steps get through where the
        # near-Newton stage fails: 7218B, Coulomb, 10,000 rpm load sweep).
        cap_tilt = 0.3 if start is None else self.warm_tilt_cap
        bd0 = wk["bd"]
        loaded0 = (bd0[:, K.BD_QI] > 0.0) | (bd0[:, K.BD_QO] > 0.0)

        def ptc(lazy, budget, dtau0=1.0):
            v = v0.copy()
            r, nf, _ = TK.ptc(t, y, v, xs_l, xs_g, act, float(omega), float(ftol), int(budget), lazy,
                              float(dtau0), dtau0 >= TK.DTAU_NEWTON,
                              float(cap_tilt if dtau0 >= TK.DTAU_NEWTON else 0.3), iF, iM, P, U, *tabs)
            return v, r, nf

        def evaluate(v):
            # residual with the outputs and ball details computed afresh (as dynamics_kernels.evaluate)
            wk["diag"][:] = 0.0
            wk["bd"][:] = 0.0
            fun(v)
            last[0] = v

        def spurious(v):
            evaluate(v)
            bd1 = wk["bd"]
            lost = loaded0 & (bd1[:, K.BD_QI] <= 0.0) & (bd1[:, K.BD_QO] <= 0.0)
            stopped = np.abs(wk["xl"][:, 5]) < 0.1 * w_cage
            return bool(np.any(lost | stopped))

        nfev = 0
        v1, r1 = v0, np.inf
        if self.lazy_jacobian:
            # near-Newton steps first (dtau0 >> 1), then the continuation from dtau 1
            for dtau0, budget in ((self.fast_dtau0, min(self.fast_budget, maxit // 3)), (1.0, max(maxit // 3, 1))):
                if budget < 1:
                    continue
                v1, r1, n1 = ptc(True, budget, dtau0)
                nfev += n1
                if r1 <= ftol and spurious(v1):
                    r1 = np.inf
                if r1 <= ftol:
                    break
        if not r1 <= ftol:
            v1, r1, n1 = ptc(False, maxit)
            nfev += n1
            if r1 <= ftol and spurious(v1):
                r1 = np.inf
        best_v, best_r = v1, r1
        if best_r > ftol:
            for vs in (v0, v1):
                v2, r2, n2 = trf(vs, maxit // 13)
                nfev += n2
                if r2 <= ftol and spurious(v2):
                    r2 = np.inf
                if r2 < best_r:
                    best_v, best_r = v2, r2
                if best_r <= ftol:
                    break

        class sol:   # noqa: N801
            x = best_v
        sol.nfev = nfev
        if last[0] is not sol.x:
            evaluate(sol.x)
        xl, xg, yy = wk["xl"].copy(), wk["xg"].copy(), wk["yy"].copy()
        res = max(np.max(np.abs(wk["Rl"])), np.max(np.abs(wk["Rg"])))
        if not res <= ftol:
            raise ConvergenceError(f"quasi-static tribological model at {omega * 30 / math.pi:.0f} rpm did not "
                                   f"converge in {sol.nfev} evaluations (residual {res:.3g} N, tolerance "
                                   f"{ftol:.3g} N)")
        xg[5] = float(np.mean(xl[:, 5]))
        return self._result(omega, loads, xl, xg, yy, res, sol.nfev, jh, psi, wk["diag"], wk["bd"])

    def _result(self, omega, loads, xl, xg, yy, res, it, jh, psi, diag, bd):
        """Result at the solution (xl, xg) with the dynamics state yy, its outputs diag and ball details bd
        (dynamics_kernels.evaluate at yy)."""
        g = self.g
        I = K.OUT_INDEX
        wc = xg[5]
        W = xl[:, 2:5]
        Wrel_z = W[:, 2] - xl[:, 5]
        # spin axis in the cage frame: attitude from the bearing axis (Harris's beta sign), yaw out of the plane
        attitude = -np.arctan2(-W[:, 0], np.abs(Wrel_z)) * np.sign(-Wrel_z + 1e-300)
        yaw = np.arctan2(W[:, 1], np.hypot(W[:, 0], Wrel_z))
        losses = {k: float(diag[I[k]]) for k in ("P_drive", "P_race_inner", "P_race_outer", "P_pocket", "P_land",
                                                   "P_drag", "P_churn_cage", "P_churn_ring", "P_race_slide",
                                                   "P_race_spin", "P_race_diffslip")}
        y = yy.copy()
        return TriboQuasiStaticResult(
            geometry=g, omega=float(omega), loads=loads.copy(), traction=self.opt.traction, mu=self.opt.mu,
            u=xg[:5].copy(), cage_speed=float(wc), psi=psi,
            alpha_i=bd[:, K.BD_AI].copy(), alpha_o=bd[:, K.BD_AO].copy(),
            Q_i=bd[:, K.BD_QI].copy(), Q_o=bd[:, K.BD_QO].copy(),
            a_i=bd[:, K.BD_AI_SEMI].copy(), b_i=bd[:, K.BD_BI].copy(),
            a_o=bd[:, K.BD_AO_SEMI].copy(), b_o=bd[:, K.BD_BO].copy(),
            omega_ball=W.copy(), attitude=attitude, yaw=yaw,
            Ft_i=bd[:, K.BD_FTI].copy(), Fm_i=bd[:, K.BD_FMI].copy(),
            Ft_o=bd[:, K.BD_FTO].copy(), Fm_o=bd[:, K.BD_FMO].copy(),
            slip_i=bd[:, K.BD_VSI].copy(), slip_o=bd[:, K.BD_VSO].copy(),
            u_i=bd[:, K.BD_UI].copy(), u_o=bd[:, K.BD_UO].copy(),
            spin_i=bd[:, K.BD_SPI].copy(), spin_o=bd[:, K.BD_SPO].copy(),
            orbit_speed=xl[:, 5].copy(),
            friction_torque=float(diag[I["friction_torque"]]),
            reaction=np.array([diag[I[k]] for k in ("Fx", "Fy", "Fz", "Mx", "My")]),
            losses=losses, residual=float(res), iterations=it, y=y, jones_harris=jh)


def solve_tribo_quasistatic(geometry: BearingGeometry, omega: float, loads, options=None,
                            tol: float = 1e-7, maxit: int = 3000) -> TriboQuasiStaticResult:
    """Convenience wrapper: TriboQuasiStaticModel(geometry, options).solve(omega, loads)."""
    return TriboQuasiStaticModel(geometry, options).solve(omega, loads, tol=tol, maxit=maxit)
