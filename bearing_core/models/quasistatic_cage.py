"""Quasi-static cage model: the steady state of the whole bearing, cage included, on the dynamics' own forces.

The dynamics' right-hand side (dynamics_kernels.rhs: Hertz contact, the traction law of the options --
rheology-based EHL traction or Kalker/FASTSIM --, the ball-pocket contact -- lubricated films on both walls
(lubrication.pocket_film) or dry Coulomb --, the guiding land -- oil-flooded short journal bearing with
Petroff drag, or dry penalty contact with Coulomb friction --, ball drag and churning) is evaluated at a
candidate steady state and its accelerations are driven to zero. In the candidate state the cage turns at wc
about its centre (xc, yc), which stands still; ball j sits in pocket j (cage angle 0, pocket azimuth
2 pi j / Z) where the pocket pushes it with the tangential force -q_j, orbits at theta_dot_j; the inner ring
stands at its pose and turns at omega. Steady equations (Gupta, Advanced Dynamics of Rolling Elements 1984,
Ch. 3 and 5, the equations of dynamics_kernels' ball in the frame orbiting with it, radial and axial rates zero):

  ball j (unknowns r, z, Omega_r, Omega_t, Omega_z, q, theta_dot):
      F_r + m r th_d^2 = 0,  F_z = 0,
      J wc (Omega_j - Omega_j-1) / dpsi = (M_j + M_j-1) / 2   per component, M = (M_r + J th_d Omega_t,
                                                      M_t - J th_d Omega_r, M_z)  (rotational inertia along
                                                      the orbit, trapezoidal rule)
      F_t = m r wc (th_d,j - th_d,j-1) / dpsi        (race tractions + drag + pocket force)
      thb_j - wc = wc (dth_j - dth_j-1) / dpsi        (azimuth rate about the cage centre; place in pocket)
  inner ring (unknowns dx, dy, dz, tx, ty; load coupling):  F_ext + sum_j F_ball->ring = 0
  cage (unknowns wc and the centre coordinates gx, gy):
      sum_j (pocket force moments + pocket film shear) + land torque + churning = 0   (torque about z)
      sum_j pocket forces + land force = 0                                           (forces in x, y)

The rates along the orbit tie ball j to ball j - 1 (quasistatic_cage_kernels.
orbit_coupling): the balls at the pocket azimuths are one ball seen dpsi / wc apart in a motion periodic in
the cage frame (dpsi = 2 pi / Z), so along its orbit a ball speeds up or slows down and crosses its pocket
clearance; summed over the balls, the mean orbital speed about the cage centre is the cage speed. The
pocket-force coordinate q and the cage-centre coordinates (quasistatic_cage_kernels.pocket_place,
cage_centre) make the problem regular: the ball's place in its pocket follows from the force through the
dynamics' own pocket kernel (a dry pocket: linear across its clearance for |q| <= 1 N).

Solution: 7 Z + 8 unknowns, a finite-difference Jacobian (23 right-hand-side calls), damped Newton steps with
caps and Levenberg-Marquardt steps where no fraction of the Newton step lowers the residual. Cold start: the
pure axial load from the free-ball tribological solution (quasistatic_tribo; else Jones-Harris), with the
balls held at the cage's azimuth rate in the oil regime (orbit coupling 0), continuation in the other loads,
then in the orbit coupling to 1 (and, with displacement coupling, in the ring pose); with an oil-lubricated
cage, where that fails under a combined load, the same path from twice and four times the axial load (a light
axial load alone skids grossly at high speed and has no steady state); where the path fails at a speed, the
same path at half and at a quarter of it and continuation in the shaft speed up to it (the way a run-up
reaches the point; oil-lubricated cage). A previous solution is a warm start. A
point that does not converge raises ConvergenceError naming speed, loads or pose, and oil temperature. Tolerances: aim at tol, accept tol_accept (the contact laws' kinks leave a residual floor).

Sensitivity: central secants of the outputs over warm re-solves at the inputs +- a step on the scale of the
re-solve tolerance (or, sensitivity_method 'implicit', dx/dp = -J^-1 dR/dp on the solution's Jacobian with
chord steps, secants where that fails its checks). Time constant of the cage speed's first-order lag:
tau = I / (-dT/dwc), I = 2 KE / wc^2 the rotating parts' inertia referred to the cage speed (cage, balls' orbit
and absolute rotation), T the net torque on cage and balls about the axis with every other
equation in equilibrium (ball spin, contact and pocket forces follow the cage much faster):
-dT/dwc = -(dm/2) / (J^-1)[wc, cage torque row]. Accelerating state (accelerating): every rotation with the cage
growing at the relative rate acc = (dwc/dt) / wc, the forces balancing the d'Alembert loads (quasistatic_cage_kernels.
acceleration_loads); its lag behind the steady state gives the secant time constant of a ramp
(secant_time_constant), which QuasiStaticTracker uses while the shaft accelerates; inside a ramp the tracker
re-solves the accelerating state alone (accelerating_at), whose cage speed carries the lag. Method, accuracy
against the dynamic model and its limits: docs/fidelity_quasistatic.md.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from . import dynamics_kernels as K
from . import quasistatic_cage_kernels as CK
from .dynamics_setup import DynamicSetup, DynamicsOptions
from .quasistatic import quasistatic_model
from .quasistatic_tribo import TriboQuasiStaticModel
from ..bearing.geometry import BearingGeometry
from ..errors import BearingInputError, ConvergenceError, check_range

NL, NG = CK.NL, CK.NG
INPUT_NAMES = ("omega", "Fx", "Fy", "Fz", "Mx", "My", "T_oil")
DISP_INPUT_NAMES = ("omega", "dx", "dy", "dz", "tx", "ty", "T_oil")
# scalar outputs of a solution (and of its sensitivity)
OUTPUT_NAMES = ("cage_speed", "friction_torque", "P_drive", "heat", "P_race_inner", "P_race_outer", "P_pocket",
                "P_land", "P_drag", "P_churn_cage", "P_churn_ring", "Fx", "Fy", "Fz", "Mx", "My",
                "dx", "dy", "dz", "tx", "ty", "alpha_i_mean", "alpha_o_mean", "Q_i_max", "Q_o_max", "p_max",
                "cage_x", "cage_y")
_DIAG = ("cage_speed", "friction_torque", "P_drive", None, "P_race_inner", "P_race_outer", "P_pocket", "P_land",
         "P_drag", "P_churn_cage", "P_churn_ring", "Fx", "Fy", "Fz", "Mx", "My",
         "ir_x", "ir_y", "ir_z", "ir_tx", "ir_ty", "alpha_i_mean", "alpha_o_mean", "Q_i_max", "Q_o_max", "p_max",
         "cage_x", "cage_y")
_HEAT = ("P_race_inner", "P_race_outer", "P_pocket", "P_land", "P_drag", "P_churn_cage", "P_churn_ring", "P_damping")


def output_vector(diag: np.ndarray) -> np.ndarray:
    """The scalar outputs (OUTPUT_NAMES) from the dynamics' output channels diag; 'heat' is the sum of the
    loss channels [W] (races, pocket, land, drag, churning)."""
    I = K.OUT_INDEX
    out = np.empty(len(OUTPUT_NAMES))
    for k, n in enumerate(_DIAG):
        out[k] = sum(diag[I[h]] for h in _HEAT) if n is None else diag[I[n]]
    return out


@dataclass
class QuasiStaticCageResult:
    """Steady state of the quasi-static cage model (SI: m, rad, N, N m, rad/s, W). Per-ball arrays have
    length Z; ``y`` is the matching dynamics state (a start for DynamicModel)."""

    geometry: BearingGeometry
    omega: float                   # inner-ring speed [rad/s]
    loads: np.ndarray              # (Fx, Fy, Fz, Mx, My) applied [N, N m] (displacement: -reaction)
    displacement: np.ndarray       # inner-ring pose (dx, dy, dz, tx, ty) [m, rad]
    T_oil: float                   # oil temperature [K]
    coupling: str
    cage_speed: float              # [rad/s]
    cage_centre: np.ndarray        # (xc, yc) [m]
    friction_torque: float         # torque the shaft supplies [N m]
    heat: dict                     # loss powers by source [W] and their sum 'total'
    P_drive: float                 # drive power [W]
    reaction: np.ndarray           # (Fx, Fy, Fz, Mx, My) of the balls on the inner ring [N, N m]
    alpha_i: np.ndarray            # contact angles [rad]
    alpha_o: np.ndarray
    Q_i: np.ndarray                # contact loads [N]
    Q_o: np.ndarray
    p_i: np.ndarray                # largest Hertz pressures [Pa]
    p_o: np.ndarray
    pocket_force: np.ndarray       # ball-pocket normal force [N]
    pocket_q: np.ndarray           # pocket-force coordinate q [N] (> 0: the ball leads its pocket)
    orbit_speed: np.ndarray        # orbital speed of each ball [rad/s]
    omega_ball: np.ndarray         # (Z, 3) angular velocity (Omega_r, Omega_t, Omega_z) [rad/s]
    film: dict                     # Hamrock-Dowson films (DynamicSetup.film) and the smallest film parameter
    outputs: np.ndarray            # the scalar outputs, in the order of OUTPUT_NAMES
    residual: float                # max |residual| [N]
    iterations: int                # right-hand-side evaluations of the solve
    tau_cage: float                # time constant of the cage speed's first-order lag [s]
    acceleration: float = 0.0      # relative acceleration dwc/dt / wc of every rotation [1/s] (0: steady;
    #                                QuasiStaticCageModel.accelerating)
    sensitivity: np.ndarray = field(repr=False, default=None)   # d outputs / d inputs (len OUTPUT_NAMES x 7)
    input_names: tuple = INPUT_NAMES
    secant_inputs: tuple = ()      # inputs whose derivatives are secants over warm re-solves (contact-law kinks)
    x: tuple = field(repr=False, default=None)   # (xl, xg) unknowns (warm start)
    y: np.ndarray = field(repr=False, default=None)
    diag: np.ndarray = field(repr=False, default=None)
    bd: np.ndarray = field(repr=False, default=None)     # per-ball details (dynamics_kernels BD_*) at the solution
    jacobian: np.ndarray = field(repr=False, default=None)   # last Jacobian of the solve (scaled; warm starts)

    def output(self, name: str) -> float:
        return float(self.outputs[OUTPUT_NAMES.index(name)])

    def inputs(self) -> np.ndarray:
        """The input vector (INPUT_NAMES, or DISP_INPUT_NAMES with displacement coupling) of this solution."""
        ring = self.loads if self.coupling == "load" else self.displacement
        return np.concatenate([[self.omega], ring, [self.T_oil]])

    def predict(self, omega: float, ring, T_oil: float | None = None) -> np.ndarray:
        """First-order update of the outputs (OUTPUT_NAMES) at new inputs: omega [rad/s], ring = loads (Fx,
        Fy, Fz, Mx, My) [N, N m] or the ring pose (displacement coupling), T_oil [K] (None: this one)."""
        p = np.concatenate([[omega], np.asarray(ring, dtype=float).reshape(5),
                            [self.T_oil if T_oil is None else T_oil]])
        return self.outputs + self.sensitivity @ (p - self.inputs())

    def input_tolerance(self, rel: float = 2e-3, keys=("cage_speed", "friction_torque", "heat")) -> np.ndarray:
        """Per input, the change that moves any of the outputs ``keys`` by rel of its value on the linear
        update (inf where they do not depend on it): re-solve when an input has moved beyond a fraction of
        this since the last solve; within it, predict()."""
        tol = np.full(len(INPUT_NAMES), np.inf)
        for k in keys:
            i = OUTPUT_NAMES.index(k)
            scale = rel * max(abs(self.outputs[i]), 1e-9)
            s = np.abs(self.sensitivity[i])
            with np.errstate(divide="ignore"):
                tol = np.minimum(tol, np.where(s > 0, scale / s, np.inf))
        return tol


class QuasiStaticCageModel:
    """Quasi-static cage model of one bearing with the options of the dynamics (a DynamicsOptions:
    traction, lubrication regime, cage and land parameters, drag, churning, coupling, fixed_tilt; integrator
    settings are not used). Outer ring fixed."""

    #: residual tolerance relative to the load scale (largest of |F|, |M| / (dm/2), 100 N): the solve aims at
    #: tol and accepts a point at tol_accept where the contact laws' kinks leave a residual floor above tol
    #: (measured: 7218B, 3000 rpm, Fx 1 kN, Fz 3 kN: cage speed 0.35 % and torque 3.4 % apart between a point
    #: at 1e-3 and one at 5e-5)
    tol = 2e-5
    tol_accept = 1e-3
    #: energy balance of an accepted point: |drive power - losses| <= power_balance_tol x the larger of the two
    #: + power_balance_abs [W]: a guard against gross failures, not an accuracy criterion. Accepted points
    #: balance to 0.05-0.7 % at 1500-2900 rpm and to 2-5 % at 570-1060 rpm, where the residual floor is a larger
    #: share of the losses (7218B, oil, Fx 1 kN, Fz 3 kN); warm solves stalled on the floor were seen at 27-37 %
    power_balance_tol = 0.1
    power_balance_abs = 0.05
    #: the energy balance an accelerating state (accelerating) is held to: drive power = losses + 2 KE acc
    #: within this share. Its solves stall on the contact laws' residual floor more often than the steady
    #: ones where the race traction saturates (7218B, Fx 1 kN, Fz 3 kN, 8400 rpm, acc 0.6-1 1/s: 0.2-0.5 N,
    #: 8-10 % off the balance), and only its lag is used (the cage's time constant)
    accelerating_balance_tol = 0.25
    #: residual evaluations of one accelerating solve (a warm one takes 20-60 on seed 000's ramp)
    accelerating_budget = 200
    #: an accelerating solve keeps its Jacobian over steps that at least halve the max-norm residual (steady
    #: solves: contract it four-fold). Measured on seed 000's ramp, where the tracker solves accelerating states
    #: warm from the last (7218B, oil, Fx 1 kN, Fz 3 kN, 1 ms steps): 47 instead of 62 Jacobians and 182
    #: instead of 219 residual evaluations in its 34 solves; the cage speed within 0.5 % of the four-fold rule's
    #: except at 3 steps near 7400 rpm, where the accelerating states have several roots (2.6 % there, the
    #: dynamic cage speed between the two and 0.7 % from this one's)
    accelerating_chord = 0.5
    _balance_guard = True
    #: the oil-lubricated pocket's contact dashpot (DynamicsOptions.pocket_damping_ratio) in the steady
    #: equations. Off: a linear (Kelvin-Voigt) dashpot switches on at first contact with a force step
    #: C |d gap / dt|, and in the steady periodic motion a ball meets its pocket wall at the rate the orbit
    #: coupling gives it, so the pocket force jumps there (22 N at the 7218B's ball 0, 3300 rpm, Fx 1 kN, Fz
    #: 3 kN): the equations have no root where a pocket's force falls inside the step, and the solve stalls on
    #: it (the residual floor). What it costs and gains is measured in docs/fidelity_quasistatic.md. The
    #: dynamics keep their dashpot; so does a dry pocket here (without it the dry cage converges at 21 of 32
    #: random points, but with torque 30-69 % below the dynamics' at most of them: its impacts' dissipation is
    #: much of the dry loss)
    pocket_dashpot = False
    #: residual evaluations of one solve attempt
    budget = 1500
    #: derivatives of the outputs: 'secant' (central secants over warm re-solves at the inputs +- a step on the
    #: scale of the re-solve tolerance, _secant_step; 14 warm solves) or 'implicit' (implicit function theorem on
    #: the solution's Jacobian, secants only where the linearisation fails its checks; measured: 7218B, 6452 rpm,
    #: Fx 1.9 kN, Fz 5 kN, the implicit dT/dFx was 0.127 N m/N against a secant -1.9e-4: a near-null direction of
    #: the finite-difference Jacobian (the balls' places in their pockets) that barely moves the residual moves
    #: the torque)
    sensitivity_method = "secant"
    #: chord steps on the solution's Jacobian after the first-order change of the unknowns in the directional
    #: differences of the sensitivity (the residual at the solution, R, stays the reference)
    sensitivity_chord_steps = 2
    #: weight of the orbit coupling (quasistatic_cage_kernels.orbit_coupling): 1 the periodic motion, 0
    #: every ball held at the cage's azimuth rate
    lam = 1.0
    acc = 0.0           # relative acceleration dwc/dt / wc of the solved state [1/s] (0: steady)
    #: orbit coupling along the load path (None: 0 with an oil-lubricated cage, whose pocket films give every
    #: ball a pocket force; 1 with a dry one, whose balls float in their clearance until the load grows)
    path_lam0 = None
    #: largest relative change of the cage speed in one continuation step
    path_jump = 0.05
    #: tolerance factor of the intermediate continuation steps (the end point is solved to tol)
    path_tol_factor = 3.0
    _tol_factor = 1.0
    #: residual evaluations of one continuation step
    sub_budget = 500
    #: axial loads of the cold path's start, as multiples of the operating point's (tried in turn where a start
    #: or its path fails; oil-lubricated cage): _cold
    axial_start_factors = (1.0, 2.0, 4.0)
    #: start speeds of the speed path, as fractions of the operating point's, tried in turn where the cold
    #: path fails (_speed_path)
    speed_path_factors = (0.5, 0.25)
    #: step caps of the damped Newton solve: positions [um], tilts [10 urad]
    cap_position = 10.0
    cap_tilt = 10.0

    def __init__(self, geometry: BearingGeometry, options: DynamicsOptions | None = None):
        opt = DynamicsOptions() if options is None else options
        if opt.outer_mount != "fixed":
            raise BearingInputError("outer_mount", opt.outer_mount, "fixed (quasi-static cage model)")
        geometry.require_two_point("quasi-static cage model")
        if geometry.cage.guidance == "ball":
            raise BearingInputError("cage.guidance", "ball", "outer | inner (land-guided cage)")
        self.g = geometry
        self.opt = replace(opt, reduced="full", thermal=False)
        self.opt.validate()
        self._setups = {}
        self._lu_last: _LU | None = None
        self._dplace = np.full((geometry.Z, 2), np.nan)   # pocket offsets of the last evaluation (_evaluate)

    def forget(self):
        """Drop what the last solves leave for the next one (the pocket offsets that start the root searches,
        the kept LU factors): the next solve then starts from its own start only."""
        self._dplace[:] = np.nan
        self._lu_last = None

    # ---- parameters -------------------------------------------------------------------------------
    def _setup(self, omega: float, T_oil: float):
        """DynamicSetup at oil temperature T_oil [K] (and shaft speed omega with ring growth), memoised per
        (T_oil, speed if ring growth)."""
        key = (round(T_oil, 9), round(omega, 6) if self.opt.ring_growth else 0.0)
        s = self._setups.get(key)
        if s is None:
            if len(self._setups) > 8:
                self._setups.clear()
            s = DynamicSetup(self.g, replace(self.opt, oil_temperature=T_oil))
            s.U[K.U_W0] = s.U[K.U_W1] = omega
            s.update_operating_geometry(omega)
            s.P = s._params(False)
            s.apply_temperatures(T_oil, T_oil)
            self._setups[key] = s
        return s

    def dynamic_setup(self, omega: float, T_oil: float) -> DynamicSetup:
        """The dynamics' setup (parameters, tables, films) the solve at shaft speed omega [rad/s] and oil
        temperature T_oil [K] uses."""
        return self._setup(omega, T_oil)

    def _kernel_args(self, s):
        return (s._tab_i, s._tab_o, s._ta0, s._tda, s._tp, *s._quad)

    # ---- solve ------------------------------------------------------------------------------------------
    def solve(self, omega: float, loads=None, displacement=None, T_oil: float | None = None,
              start: QuasiStaticCageResult | None = None, sensitivity: bool = True,
              cold: bool = True) -> QuasiStaticCageResult:
        """Steady state at inner-ring speed omega [rad/s] (>= 10) under loads (Fx, Fy, Fz, Mx, My) [N, N m]
        (load coupling) or at the ring pose displacement (dx, dy, dz, tx, ty) [m, rad] (displacement
        coupling), oil temperature T_oil [K] (None: options.oil_temperature). start: a previous solution to
        start from (warm start). sensitivity: also the derivatives and the cage time constant. cold: False,
        only the warm start is tried. Raises ConvergenceError naming the operating point if no start converges."""
        omega = check_range("omega", omega, 10.0, 2.0e4, unit="rad/s")
        T_oil = self.opt.oil_temperature if T_oil is None else check_range("T_oil", T_oil, 233.15, 473.15, unit="K")
        disp = self.opt.coupling == "displacement"
        if disp:
            if displacement is None:
                raise BearingInputError("displacement", None,
                                        "5 values (dx, dy, dz, tx, ty) with displacement coupling")
            ring = np.asarray(displacement, dtype=float).reshape(-1)
            name = "displacement"
        else:
            if loads is None:
                raise BearingInputError("loads", None, "5 values (Fx, Fy, Fz, Mx, My) with load coupling")
            ring = np.asarray(loads, dtype=float).reshape(-1)
            name = "loads"
        if ring.size != 5 or not np.all(np.isfinite(ring)):
            raise BearingInputError(name, ring.tolist(), "5 finite values")
        if start is not None and not isinstance(start, QuasiStaticCageResult):
            raise BearingInputError("start", type(start).__name__, "None or a QuasiStaticCageResult")
        errors = []
        if start is not None:
            res = self._solve_from(omega, ring, T_oil, self._start("warm", start, omega, ring, T_oil), sensitivity,
                                   J0=start.jacobian)
            if isinstance(res, QuasiStaticCageResult):
                return res
            errors.append(f"warm start: {res}")
        if not cold and start is not None:
            raise ConvergenceError(
                f"quasi-static cage model: no steady state found from the warm start at {omega * 30 / math.pi:.0f} "
                f"rpm, {name} {np.array2string(ring, precision=6)}, oil temperature {T_oil - 273.15:.1f} degC "
                f"({'; '.join(errors)})")
        budget = self.budget
        lam0 = self.path_lam0 if self.path_lam0 is not None else (0.0 if self.opt.regime == "oil" else 1.0)
        try:
            res = self._cold(omega, ring, T_oil, errors, lam0)
        except (ConvergenceError, np.linalg.LinAlgError, ValueError) as e:
            errors.append(str(e))
            res = None
        finally:
            self.budget = budget
            self.lam = 1.0
        if res is None and self.opt.regime == "oil":
            # (a dry cage's paths end on roots with the cage pressed on its land: _cold)
            res = self._speed_path(omega, ring, T_oil, errors, lam0)
        if res is not None:
            if sensitivity:
                s_, P, U, act, tabs, xs_l, xs_g = self._problem(omega, ring, T_oil)
                v = np.concatenate([(res.x[0] / xs_l).ravel(), res.x[1] / xs_g])
                self._sensitivity(res, v, s_, P, U, act, tabs, xs_l, xs_g)
            return res
        raise ConvergenceError(
            f"quasi-static cage model: no steady state found at {omega * 30 / math.pi:.0f} rpm, {name} "
            f"{np.array2string(ring, precision=6)}, oil temperature {T_oil - 273.15:.1f} degC ({'; '.join(errors)})")

    def update_sensitivity(self, res: QuasiStaticCageResult, columns=None) -> QuasiStaticCageResult:
        """Compute res.sensitivity and res.tau_cage (as solve(..., sensitivity=True)) for a solution solved
        without them; columns: indices of the inputs (res.input_names) whose derivatives are computed (None:
        all); the others are kept from res.sensitivity (zero if it has none). Returns res."""
        if not isinstance(res, QuasiStaticCageResult):
            raise BearingInputError("res", type(res).__name__, "a QuasiStaticCageResult")
        p0 = res.inputs()
        s_, P, U, act, tabs, xs_l, xs_g = self._problem(p0[0], p0[1:6], p0[6])
        v = np.concatenate([(res.x[0] / xs_l).ravel(), res.x[1] / xs_g])
        self._sensitivity(res, v, s_, P, U, act, tabs, xs_l, xs_g, columns)
        return res

    def accelerating(self, res: QuasiStaticCageResult, acc: float, start: QuasiStaticCageResult | None = None,
                     max_halvings: int = 3):
        """The accelerating quasi-steady state at res's inputs: the balls' orbit and rotation and the cage speed
        growing at the relative rate acc = dwc/dt / wc [1/s] (a shaft speed ramp of rate acc x omega), with the
        contact, traction and pocket forces in equilibrium with the inertia forces (d'Alembert;
        quasistatic_cage_kernels.acceleration_loads). Where the traction's slope falls at larger slip, the cage
        lags its steady speed by more than the linearisation tau x acc x wc predicts. Warm from start (an
        accelerating state nearby) if given, else continued in acc from the steady state res in halves (at most
        max_halvings failures). Returns the result (its cage speed the lagging one), or None where none is
        found on res's branch (a cage/shaft speed ratio more than path_jump from res's)."""
        acc = float(acc)
        if acc == 0.0 or not math.isfinite(acc):
            return None
        p = res.inputs()
        ratio0 = res.cage_speed / res.omega
        if start is not None and start.acceleration * acc > 0.0:
            out = self._accelerating_attempt(p, acc, start, ratio0)
            if out is not None:
                return out
        cur, a_cur, path, failed = res, 0.0, [acc], 0
        while path:
            a = path[-1]
            out = self._accelerating_attempt(p, a, cur, ratio0)
            if out is not None:
                cur, a_cur = out, a
                path.pop()
            else:
                failed += 1
                if failed > max_halvings:
                    return None
                path.append(0.5 * (a_cur + a))
        return cur

    def accelerating_at(self, p, acc: float, start: QuasiStaticCageResult):
        """The accelerating quasi-steady state (accelerating) at the inputs p = (omega, 5 loads or pose values,
        T_oil) [rad/s, N, N m or m, rad, K] and relative rate acc [1/s], warm from the accelerating state start
        at nearby inputs: one warm solve, without continuation. None where it fails or ends more than path_jump
        from start's cage/shaft speed ratio (another branch)."""
        acc = float(acc)
        if acc == 0.0 or not math.isfinite(acc) or start.acceleration * acc <= 0.0:
            return None
        return self._accelerating_attempt(np.asarray(p, dtype=float), acc, start, start.cage_speed / start.omega)

    def _accelerating_attempt(self, p, acc, st, ratio0):
        """One warm solve of the accelerating state at inputs p and relative rate acc from the state st (its
        Jacobian reused); None where it fails or its cage/shaft speed ratio is more than path_jump from
        ratio0."""
        omega, ring, T_oil = float(p[0]), p[1:6], float(p[6])
        self.acc = acc
        tol_b, budget = self.power_balance_tol, self.budget
        self.power_balance_tol = self.accelerating_balance_tol
        self.budget = self.accelerating_budget
        try:
            out = self._solve_from(omega, ring, T_oil, self._start("warm", st, omega, ring, T_oil), False,
                                   J0=st.jacobian)
        finally:
            self.acc = 0.0
            self.power_balance_tol, self.budget = tol_b, budget
        if isinstance(out, QuasiStaticCageResult) and \
                abs(out.cage_speed / out.omega / ratio0 - 1.0) <= self.path_jump:
            return out
        return None

    def secant_time_constant(self, res: QuasiStaticCageResult, acc_state: QuasiStaticCageResult) -> float:
        """Time constant [s] of the cage speed's first-order lag that reproduces the lag of the accelerating
        state acc_state (accelerating) behind the steady state res in a ramp: tau = (c_steady - c_acc) /
        (acc c_acc) over the cage/shaft speed ratios c (at one shaft speed: (wc_steady - wc_acc) / (acc
        wc_acc)), the secant of the cage's relaxation over the lag itself (a first-order lag in a ramp of rate a
        trails by tau a). NaN where the lag does not have the sign of the acceleration."""
        a = acc_state.acceleration
        ca = acc_state.cage_speed / acc_state.omega
        if a == 0.0 or ca == 0.0:
            return float("nan")
        tau = (res.cage_speed / res.omega - ca) / (a * ca)
        return float(tau) if tau > 0.0 and math.isfinite(tau) else float("nan")

    def _cold(self, omega, ring, T_oil, errors, lam0):
        """Solve without a previous solution (module docstring): the pure axial load at orbit coupling lam0 (0:
        every ball held at the cage's azimuth rate) from the free-ball tribological start (else Jones-Harris),
        continuation in the other loads to the operating point, then in the orbit coupling to 1; where that
        fails under a combined load with an oil-lubricated cage, the same from a heavier axial load
        (axial_start_factors). With displacement coupling the path runs under the loads the ring pose needs
        (Jones-Harris), and the last step holds the pose. Returns the result or None (reasons appended to errors)."""
        disp = self.opt.coupling == "displacement"
        loads = self._loads_of_pose(ring, omega) if disp else ring
        model = self if not disp else QuasiStaticCageModel(self.g, replace(self.opt, coupling="load"))
        budget = self.budget
        for k, factor in enumerate(self.axial_start_factors):
            # a light axial load alone skids grossly at high speed (the 7218B's dynamic cage at 0.1-0.2 of the
            # shaft speed, unsteady, at 10,000 rpm under Fz <= 1.7 kN), where the steady equations have no root;
            # a radial load on top puts the loaded balls back to rolling. Such points start under a heavier
            # axial load and follow the straight load path down to their own
            if k > 0 and factor * loads[2] <= self.axial_start_factors[k - 1] * loads[2]:
                continue
            ring0 = np.array([0.0, 0.0, factor * loads[2], 0.0, 0.0])
            self.budget = budget
            out = self._cold_path(omega, ring, loads, ring0, model, T_oil, errors, lam0, disp)
            if out is not None:
                return out
            if np.all(loads[[0, 1, 3, 4]] == 0.0) or self.opt.regime != "oil":
                # a pure axial load: its own start was the path. A dry cage: from a heavier start the path ends
                # on roots with the cage pressed on its land and the balls on their pockets (7008, Kalker mu
                # 0.1, 1000 rpm, Fx 358 N, Fz 716 N: 63.5 W of pocket and land loss, where the dynamic cage and
                # balls float and the loss is 1.8 W)
                return None
        return None

    def _cold_path(self, omega, ring, loads, ring0, model, T_oil, errors, lam0, disp):
        """_cold's path from the axial load ring0 (the start) to the operating point; the result or None."""
        model.lam = lam0
        res = None
        for kind in ("tribological", "jones-harris"):
            try:
                x0 = model._start(kind, None, omega, ring0, T_oil)
            except (ConvergenceError, np.linalg.LinAlgError, ValueError) as e:
                errors.append(f"{kind} start: {e}")
                continue
            model._tol_factor = self.path_tol_factor
            model.budget = self.budget
            res = model._solve_from(omega, ring0, T_oil, x0, False)
            model._tol_factor = 1.0
            model.budget = self.sub_budget
            if isinstance(res, QuasiStaticCageResult):
                break
            errors.append(f"{kind} start under the axial load {ring0[2]:.5g} N alone: {res}")
            res = None
        if res is None:
            return None
        if np.any(loads != ring0):
            res = model._continuation(res, lambda a: (ring0 + a * (loads - ring0), lam0), omega, T_oil, errors,
                                      "loads")
        if res is None:
            return None
        res_loads = res
        for tight in (False, True):
            # the orbit coupling's path, solved loosely (path_tol_factor); where its end does not then converge
            # to the full tolerance, once more at the full tolerance: a loose point on a path that bends can
            # leave the end point outside Newton's reach (7218B, 10,019 rpm, Fx 1.2 kN, Fz 4.6 kN)
            res = res_loads
            model.lam = lam0
            if lam0 < 1.0:
                res = model._continuation(res, lambda a: (loads, lam0 + a * (1.0 - lam0)), omega, T_oil, errors,
                                          "orbit coupling", tol_factor=1.0 if tight else None)
            if res is None:
                return None
            if disp:
                break
            # the end point to the full tolerance
            out = self._solve_from(omega, ring, T_oil, self._start("warm", res, omega, ring, T_oil), False)
            if isinstance(out, QuasiStaticCageResult):
                return out
            errors.append(f"end point{' (orbit coupling path at the full tolerance)' if tight else ''}: {out}")
            if lam0 >= 1.0:
                return None
        if not disp:
            return None
        # the ring pose: from the load path's end to the prescribed one
        self.lam = 1.0
        self.budget = self.sub_budget
        pose0 = np.array(res.displacement)
        res = replace(res, coupling="displacement")
        res = self._continuation(res, lambda a: (pose0 + a * (ring - pose0), 1.0), omega, T_oil, errors, "ring pose")
        if res is None:
            return None
        out = self._solve_from(omega, ring, T_oil, self._start("warm", res, omega, ring, T_oil), False)
        if isinstance(out, QuasiStaticCageResult):
            return out
        errors.append(f"end point: {out}")
        return None

    def _continuation(self, res, path, omega, T_oil, errors, what, tol_factor=None, speed=None):
        """Follow path(a) -> (ring input, orbit coupling) from a = 0 (res) to 1 in adaptive steps (a quarter
        first, x1.5 after a success, halved after a failure, at least 1/512), each point solved to tol_factor
        times the tolerance (None: path_tol_factor); speed(a): the shaft speed along the path [rad/s] (None:
        omega throughout). Returns the end result or None."""
        a, da = 0.0, 0.25
        lam_res = self.lam          # the orbit coupling of res
        self._tol_factor = self.path_tol_factor if tol_factor is None else tol_factor
        self._balance_guard = False            # the path's intermediate points are solved loosely
        try:
            while a < 1.0:
                a2 = min(a + da, 1.0)
                ring, lam = path(a2)
                self.lam = lam
                w = omega if speed is None else speed(a2)
                out = self._solve_from(w, ring, T_oil, self._start("warm", res, w, ring, T_oil), False)
                # a step that moves the cage/shaft speed ratio by more than path_jump has left the branch it
                # follows (the steady problem has several roots: 7218B, 10,000 rpm, Fx 1 kN, Fz 3 kN has one
                # at 4374 rpm and a skidding one at 2664 rpm): a smaller step
                jump = isinstance(out, QuasiStaticCageResult) and \
                    abs((out.cage_speed / out.omega) / (res.cage_speed / res.omega) - 1.0) > self.path_jump
                if isinstance(out, QuasiStaticCageResult) and not jump:
                    res, a, da, lam_res = out, a2, da * 1.5, lam
                    continue
                if jump:
                    out = (f"cage speed jumped from {res.cage_speed * 30 / math.pi:.0f} to "
                           f"{out.cage_speed * 30 / math.pi:.0f} rpm")
                da *= 0.5
                if da < 1.0 / 512.0:
                    errors.append(f"continuation in the {what} stopped at {a:.4f} of the way: {out}")
                    return None
            return res
        finally:
            self.lam = lam_res
            self._tol_factor = 1.0
            self._balance_guard = True

    def _speed_path(self, omega, ring, T_oil, errors, lam0):
        """Where the cold path fails at omega: the same cold path at a lower speed (speed_path_factors x
        omega, at least 10 rad/s), then continuation in the shaft speed up to omega with the loads (or the
        ring pose) held, and the end point to the full tolerance. At high speed the centrifugal and gyroscopic
        loads and the race traction near saturation make the load path's Newton steps stall on the contact
        laws' residual floor, where the same point is reached along the speed as a run-up reaches it (7218B,
        oil: 12,000 rpm under Fz 8 kN alone, from 6000 rpm). Returns the result or None (reasons appended to
        errors)."""
        budget = self.budget
        for f in self.speed_path_factors:
            omega0 = f * omega
            if omega0 < 10.0:
                continue
            sub = []
            try:
                self.budget = budget
                res = self._cold(omega0, ring, T_oil, sub, lam0)
                if res is None:
                    errors.append(f"from {omega0 * 30 / math.pi:.0f} rpm: no steady state there either")
                    continue
                self.lam = 1.0
                self.budget = self.sub_budget
                res = self._continuation(res, lambda a: (ring, 1.0), omega, T_oil, errors, "shaft speed from "
                                         f"{omega0 * 30 / math.pi:.0f} rpm",
                                         speed=lambda a: omega0 + a * (omega - omega0))
                if res is None:
                    continue
                self.budget = budget
                out = self._solve_from(omega, ring, T_oil, self._start("warm", res, omega, ring, T_oil), False)
                if not isinstance(out, QuasiStaticCageResult):
                    errors.append(f"end point of the speed path from {omega0 * 30 / math.pi:.0f} rpm: {out}")
                    continue
                # the branch a run-up follows can end past the load at which the dynamic cage still rolls:
                # such a root has no restoring cage torque, and the dynamic cage started there decelerates
                # towards gross skidding (7218B, 11,986 rpm, Fx 432 N, Fz 2332 N: the root at 599 rad/s, the
                # dynamic cage from 567 to 495 rad/s over 0.1-0.3 s, the oil map's nearest point skidding at
                # 182 rad/s). Roots reached only along the speed are kept where the cage speed is restored
                tau = self._restoring_time_constant(out)
                if math.isfinite(tau) and tau > 0.0:
                    return out
                errors.append(f"end point of the speed path from {omega0 * 30 / math.pi:.0f} rpm at a cage speed of "
                              f"{out.cage_speed * 30 / math.pi:.0f} rpm has no restoring cage torque (dT/dwc >= 0: "
                              "the cage drifts from it towards gross skidding)")
            except (ConvergenceError, np.linalg.LinAlgError, ValueError) as e:
                errors.append(f"from {omega0 * 30 / math.pi:.0f} rpm: {e}")
            finally:
                self.budget = budget
                self.lam = 1.0
        return None

    def _restoring_time_constant(self, res):
        """The cage lag's linear time constant at the solution res [s] (_tau_cage on its Jacobian): inf where
        the cage torque has no restoring slope dT/dwc < 0."""
        p0 = res.inputs()
        _, P, U, act, tabs, xs_l, xs_g = self._problem(p0[0], p0[1:6], p0[6])
        v = np.concatenate([(res.x[0] / xs_l).ravel(), res.x[1] / xs_g])
        J = self._jacobian(v, float(res.omega), P, U, act, tabs, xs_l, xs_g)
        z = np.empty(v.size)
        if not self._lu(J).solve(self._e_wc(v.size), z):
            return float("nan")
        return self._tau_cage(res, z, xs_g)

    def _start(self, kind, st, omega, ring, T_oil):
        """Unknowns (xl, xg) to start from: a previous solution (speeds scaled to omega), the free-ball
        tribological solution or the Jones-Harris one (cage at the mean orbital speed, centred, balls at their
        pocket centres)."""
        g = self.g
        Z = g.Z
        xl = np.zeros((Z, NL))
        xg = np.zeros(NG)
        if kind == "warm":
            ratio = omega / st.omega
            xl[:] = st.x[0]
            xg[:] = st.x[1]
            xl[:, 2:5] *= ratio
            xl[:, 6] *= ratio
            xg[CK.G_WC] *= ratio
            if self.opt.coupling == "displacement":
                xg[:5] = ring
            return xl, xg
        loads = ring if self.opt.coupling == "load" else self._loads_of_pose(ring, omega)
        if kind == "tribological":
            o = replace(self.opt, coupling="load", oil_temperature=T_oil)
            tq = TriboQuasiStaticModel(g, o).solve(omega, loads)
            b = K.NSTATE_FIXED + K.NSB * np.arange(Z)
            xl[:, 0] = tq.y[b + 1]
            xl[:, 1] = tq.y[b + 2]
            xl[:, 2:5] = tq.omega_ball
            xg[:5] = tq.u
            xg[CK.G_WC] = tq.cage_speed
            xl[:, 6] = tq.orbit_speed
        else:
            qsm = quasistatic_model(g, "outer", fixed_tilt=self.opt.fixed_tilt)
            jh = qsm.solve(omega, loads, stiffness=False)
            Roo = 0.5 * g.dm - (g.fo - 0.5) * g.D * math.cos(g.alpha0)
            Zoo = -(g.fo - 0.5) * g.D * math.sin(g.alpha0)
            xl[:, 0] = Roo + jh.X[:, 0]
            xl[:, 1] = Zoo + jh.X[:, 1]
            xl[:, 2] = -jh.omega_R * np.sin(jh.beta)
            xl[:, 4] = jh.omega_R * np.cos(jh.beta) + jh.omega_m
            xg[:5] = jh.u
            xg[CK.G_WC] = jh.cage_speed
            xl[:, 6] = jh.omega_m
        if self.opt.coupling == "displacement":
            xg[:5] = ring
        return xl, xg

    def _pose_scale(self, d, omega):
        """Load scale [N] of a ring pose: the largest force (or moment over dm/2) that holds it (Jones-Harris),
        memoised for the last pose."""
        key = (tuple(np.round(np.asarray(d, dtype=float), 12)), round(float(omega), 6))
        if getattr(self, "_pose_key", None) != key:
            F = self._loads_of_pose(d, omega)
            self._pose_key = key
            self._pose_val = max(np.max(np.abs(F[:3])), np.max(np.abs(F[3:])) / (0.5 * self.g.dm), 100.0)
        return self._pose_val

    def _loads_of_pose(self, d, omega):
        """Loads (Fx, Fy, Fz, Mx, My) that hold the inner ring at pose d by the Jones-Harris model (the start
        of a displacement-coupled solve, as DynamicModel.initialize)."""
        qsm = quasistatic_model(self.g, "outer", fixed_tilt=self.opt.fixed_tilt)
        Fb, X, st, ok = qsm.residual(np.asarray(d, dtype=float), omega)
        return -np.asarray(Fb, dtype=float)

    def _problem(self, omega, ring, T_oil):
        """Kernel arguments of one operating point: (setup, P, U, act, tables, scales)."""
        s = self._setup(omega, T_oil)
        P = s.P.copy()
        disp = self.opt.coupling == "displacement"
        P[K.P_COUPLING] = 1.0 if disp else 0.0
        P[K.P_CRX:K.P_CRTY + 1] = 0.0
        if not self.pocket_dashpot and P[K.P_LUBE] > 0.5:
            P[K.P_CPOCKETD] = 0.0
        U = np.zeros(K.NU)
        U[K.U_W0] = U[K.U_W1] = omega
        if disp:
            U[K.U_DX:K.U_TY + 1] = ring
        else:
            U[K.U_FX:K.U_MY + 1] = ring
        act = np.ones(NG, dtype=bool)
        if disp:
            act[:5] = False
        elif self.opt.fixed_tilt:
            act[3:5] = False
        xs_l = np.array([1e-6, 1e-6, omega, omega, omega, 10.0, omega])
        xs_g = np.array([1e-6, 1e-6, 1e-6, 1e-5, 1e-5, omega, 10.0, 10.0])
        return s, P, U, act, self._kernel_args(s), xs_l, xs_g

    def _solve_from(self, omega, ring, T_oil, x0, sensitivity, J0=None):
        """Damped Newton from x0 (_ptc; J0: a Jacobian to start the chord steps with, e.g. the previous
        solution's); the result, or the reason it failed (a string)."""
        s, P, U, act, tabs, xs_l, xs_g = self._problem(omega, ring, T_oil)
        g = self.g
        Z = g.Z
        xl0, xg0 = x0
        v = np.concatenate([(xl0 / xs_l).ravel(), xg0 / xs_g])
        hdm = 0.5 * g.dm
        if self.opt.coupling == "load":
            scale = max(np.max(np.abs(ring[:3])), np.max(np.abs(ring[3:])) / hdm, 1.0)
        else:                    # the loads the pose needs (Jones-Harris), as the load scale
            scale = self._pose_scale(ring, omega)
        ftol = self.tol * self._tol_factor * max(scale, 100.0)
        if P[K.P_LUBE] < 0.5:
            # dry pocket and land: no force in the clearance, so no slope there. A ball inside its clearance
            # with an unbalanced tangential force is first put against the wall that takes it, then a cage
            # inside its land clearance against the land that takes the pockets' net force
            out = self._evaluate(v, P, U, act, tabs, xs_l, xs_g)
            q = v[5:Z * NL:NL] * xs_l[5]
            Ft = out[7][:, 5]
            gap = (np.abs(q) <= CK.Q_GAP) & (np.abs(Ft) > ftol)
            q[gap] = Ft[gap] + np.sign(Ft[gap]) * CK.Q_GAP
            v[5:Z * NL:NL] = q / xs_l[5]
            gv = v[Z * NL + 6:] * xs_g[6:]
            if np.hypot(*gv) <= CK.Q_GAP and P[K.P_ETA_LAND] <= 0.0:
                out = self._evaluate(v, P, U, act, tabs, xs_l, xs_g)
                Fc = out[8][6:8]
                if np.hypot(*Fc) > ftol:
                    v[Z * NL + 6:] = (Fc + Fc / np.hypot(*Fc) * CK.Q_GAP) / xs_g[6:]
        cap = np.full(v.size, 0.2)                  # speeds: 0.2 omega a step
        for j in range(Z):
            cap[j * NL] = cap[j * NL + 1] = self.cap_position
            cap[j * NL + 5] = 20.0                  # q: 200 N
        cap[Z * NL:Z * NL + 3] = self.cap_position
        cap[Z * NL + 3:Z * NL + 5] = self.cap_tilt
        cap[Z * NL + 6:] = 20.0                     # g: 200 N
        r, nfev, J = self._ptc(v, cap, float(omega), ftol, P, U, act, tabs, xs_l, xs_g, J0)
        facc = ftol * self.tol_accept / self.tol
        if not r <= facc:
            return f"residual {r:.3g} N after {nfev} evaluations (tolerance {facc:.3g} N)"
        res = self._result(omega, ring, T_oil, v, nfev, s, P, U, act, tabs, xs_l, xs_g, False)
        # a steady state conserves energy: the shaft's drive power is the sum of the losses (the outer ring is
        # fixed and does no work). A point accepted on the residual floor whose moment equations are still off
        # breaks this balance although its forces balance
        # (an accelerating state: plus the rate of change of the kinetic energy of balls and cage, 2 KE acc, KE
        # growing with the square of the speeds)
        pd, hb = res.P_drive, res.heat["total"]
        if self.acc != 0.0:
            res.acceleration = float(self.acc)
            hb += 2.0 * float(res.diag[K.OUT_INDEX["KE"]]) * self.acc
        if self._balance_guard and not abs(pd - hb) <= self.power_balance_tol * max(abs(pd), abs(hb)) + \
                self.power_balance_abs:
            return (f"residual {r:.3g} N after {nfev} evaluations, but the drive power {pd:.5g} W does not match "
                    f"the losses {hb:.5g} W (energy balance of a steady state)")
        if sensitivity:
            self._sensitivity(res, v, s, P, U, act, tabs, xs_l, xs_g)
        if res.jacobian is None:
            res.jacobian = J
        return res

    def _jacobian(self, v, omega, P, U, act, tabs, xs_l, xs_g):
        """Dense Jacobian of the scaled residual at v (quasistatic_cage_kernels.cage_jacobian: 16 rhs calls, counted as 17 in the budget)."""
        Z = self.g.Z
        n = v.size
        xl = (v[:Z * NL].reshape(Z, NL) * xs_l).copy()
        xg = v[Z * NL:] * xs_g
        y0 = np.zeros(K.NSTATE_FIXED + K.NSB * Z)
        yy, dy = np.empty(y0.size), np.empty(y0.size)
        diag, bd = np.zeros(K.NOUT), np.zeros((Z, K.NBD))
        A = np.empty((Z, NL, NL))
        B = np.empty((Z, NL, NG))
        C = np.empty((Z, NG, NL))
        Dg = np.empty((NG, NG))
        E = np.empty((Z, NL, NL))
        iF, iM = K.OUT_INDEX["Fx"], K.OUT_INDEX["Mx"]
        CK.cage_jacobian(0.0, y0, xl, xg, act, omega, iF, iM, P, U, *tabs, yy, dy, diag, bd, A, B, C, Dg, E, self.lam, self.acc)
        J = np.empty((n, n))
        CK.cage_dense(A, B, C, Dg, E, xs_l, xs_g, J)
        return J

    def _ptc(self, v, cap, omega, ftol, P, U, act, tabs, xs_l, xs_g, J0=None):
        """Damped Newton on the scaled unknowns v (overwritten): the Newton step scaled down to the caps, then
        halved until the residual's 2-norm falls (Armijo-free backtracking, down to 1/64); when no fraction
        of it lowers the residual, Levenberg-Marquardt steps (J^T J + mu diag(J^T J)) dv = -J^T R with mu
        growing ten-fold until one does. The Jacobian is kept over steps that contract the max-norm
        residual at least four-fold (chord steps; accelerating solves: two-fold, accelerating_chord); J0, if
        given, is the first one (rebuilt as soon as a step on it fails). Stops at max |R| <= ftol, after the
        budget, or when six steps on fresh Jacobians in a row lowered the max-norm residual by less than 5 % each (the floor that the kinks of the contact laws
        leave). Returns (max |R|, rhs evaluations, the last Jacobian or None)."""
        budget = self.budget
        R = self._evaluate(v, P, U, act, tabs, xs_l, xs_g)[-1]
        r = float(np.max(np.abs(R)))
        r2n = float(R @ R)
        nfev = 1
        J = J0
        J_last = J0
        stall = 0
        lu = None
        while nfev < budget and not r <= ftol and stall < 6:
            fresh = J is None
            if fresh:
                J = self._jacobian(v, omega, P, U, act, tabs, xs_l, xs_g)
                J_last = J
                nfev += 17
            if lu is None or lu.J is not J:
                lu = self._lu(J)
            dv = np.empty(v.size)
            if not lu.solve(-R, dv):
                dv[:] = np.nan
            accepted = False
            if np.all(np.isfinite(dv)):
                f = max(1.0, float(np.max(np.abs(dv) / cap)))
                a = 1.0 / f
                while a >= 1.0 / 64.0 / f and nfev < budget:
                    v2 = v + a * dv
                    R2 = self._evaluate(v2, P, U, act, tabs, xs_l, xs_g)[-1]
                    nfev += 1
                    if np.all(np.isfinite(R2)) and float(R2 @ R2) < r2n:
                        accepted = True
                        break
                    a *= 0.5
            if not accepted and not fresh:
                J = None                      # a kept Jacobian: rebuild it and try again
                continue
            if not accepted:
                JTJ = J.T @ J
                g = J.T @ R
                dd = np.maximum(np.diag(JTJ), 1e-12 * max(np.max(np.diag(JTJ)), 1.0))
                mu = 1e-3
                while mu < 1e12 and nfev < budget:
                    if not CK.dense_solve(JTJ + mu * np.diag(dd), -g, dv):
                        mu *= 10.0
                        continue
                    f = max(1.0, float(np.max(np.abs(dv) / cap)))
                    v2 = v + dv / f
                    R2 = self._evaluate(v2, P, U, act, tabs, xs_l, xs_g)[-1]
                    nfev += 1
                    if np.all(np.isfinite(R2)) and float(R2 @ R2) < r2n:
                        accepted = True
                        break
                    mu *= 10.0
                if not accepted:
                    break
            r_new = float(np.max(np.abs(R2)))
            contract = r_new / r if r > 0 else 0.0
            stall = stall + 1 if (fresh and contract > 0.95) else 0
            v[:], R, r, r2n = v2, R2, r_new, float(R2 @ R2)
            if contract > (self.accelerating_chord if self.acc != 0.0 else 0.25):
                J = None
        return r, nfev, J_last

    def _lu(self, J):
        """The LU factors of J, memoised for the last Jacobian (a warm start's J0 is its solution's)."""
        lu = self._lu_last
        if lu is None or lu.J is not J:
            lu = _LU(J)
            self._lu_last = lu
        return lu

    # ---- result ---------------------------------------------------------------------------------------
    def _evaluate(self, v, P, U, act, tabs, xs_l, xs_g):
        Z = self.g.Z
        xl = np.empty((Z, NL))
        xg = np.empty(NG)
        y0 = np.zeros(K.NSTATE_FIXED + K.NSB * Z)
        yy = np.empty(y0.size)
        dy = np.empty(y0.size)
        diag = np.zeros(K.NOUT)
        bd = np.zeros((Z, K.NBD))
        Rl = np.empty((Z, NL))
        Rg = np.empty(NG)
        share = np.empty((Z, NG))
        R = np.empty(v.size)
        iF, iM = K.OUT_INDEX["Fx"], K.OUT_INDEX["Mx"]
        # the last evaluation's pocket offsets start this one's root searches (cage_scaled_residual)
        if self._dplace.shape[0] != Z:
            self._dplace = np.full((Z, 2), np.nan)
        r = CK.cage_scaled_residual(0.0, y0, v, xs_l, xs_g, act, iF, iM, P, U, *tabs, xl, xg, yy, dy, diag, bd, Rl,
                                    Rg, share, R, self.lam, self._dplace, self.acc)
        return r, xl, xg, yy, dy, diag, bd, Rl, Rg, share, R

    def _result(self, omega, ring, T_oil, v, nfev, s, P, U, act, tabs, xs_l, xs_g, sensitivity):
        g = self.g
        Z = g.Z
        r, xl, xg, yy, dy, diag, bd, Rl, Rg, share, R = self._evaluate(v, P, U, act, tabs, xs_l, xs_g)
        I = K.OUT_INDEX
        heat = {k: float(diag[I[k]]) for k in _HEAT}
        heat["total"] = float(sum(heat.values()))
        b = K.NSTATE_FIXED + K.NSB * np.arange(Z)
        h = np.zeros((4, Z))
        lam = s.films_into(bd, h)
        film = {"h_c_i": h[0], "h_min_i": h[1], "h_c_o": h[2], "h_min_o": h[3],
                "Lambda_min": float(lam) if math.isfinite(lam) else 0.0}
        disp = self.opt.coupling == "displacement"
        pose = np.array(ring if disp else xg[:5], dtype=float)
        reaction = np.array([diag[I[k]] for k in ("Fx", "Fy", "Fz", "Mx", "My")])
        res = QuasiStaticCageResult(
            geometry=g, omega=float(omega), loads=(-reaction if disp else np.array(ring, dtype=float)),
            displacement=pose, T_oil=float(T_oil), coupling=self.opt.coupling,
            cage_speed=float(xg[CK.G_WC]), cage_centre=np.array([yy[12], yy[13]]),
            friction_torque=float(diag[I["friction_torque"]]), heat=heat, P_drive=float(diag[I["P_drive"]]),
            reaction=reaction, alpha_i=bd[:, K.BD_AI].copy(), alpha_o=bd[:, K.BD_AO].copy(),
            Q_i=bd[:, K.BD_QI].copy(), Q_o=bd[:, K.BD_QO].copy(), p_i=bd[:, K.BD_PI].copy(),
            p_o=bd[:, K.BD_PO].copy(), pocket_force=bd[:, K.BD_FPOCKET].copy(), pocket_q=xl[:, 5].copy(),
            orbit_speed=yy[b + 3].copy(), omega_ball=xl[:, 2:5].copy(), film=film,
            outputs=output_vector(diag), residual=float(r), iterations=int(nfev), tau_cage=float("nan"),
            input_names=DISP_INPUT_NAMES if disp else INPUT_NAMES,
            x=(xl.copy(), xg.copy()), y=yy.copy(), diag=diag.copy(), bd=bd.copy())
        if sensitivity:
            self._sensitivity(res, v, s, P, U, act, tabs, xs_l, xs_g)
        return res

    def cage_centre_stability(self, res: QuasiStaticCageResult) -> tuple[float, float]:
        """Linear stability of the cage centre at the steady state res: the eigenvalues of its small motions
        (position and velocity, 4 x 4; Lund's rotordynamic stability of a journal on its film, here the land
        film and the pocket forces) with the balls, the rings and the cage's rotation held, from central
        differences of the dynamics' right-hand side at the solution's state (8 calls). Returns (largest
        growth rate [1/s], its frequency [rad/s]). A growth rate > 0: the centre's small motions grow and the
        cage whirls in its clearance (cage instability), which a steady state does not represent."""
        if not isinstance(res, QuasiStaticCageResult):
            raise BearingInputError("res", type(res).__name__, "a QuasiStaticCageResult")
        p0 = res.inputs()
        _, P, U, act, tabs, xs_l, xs_g = self._problem(p0[0], p0[1:6], p0[6])
        v = np.concatenate([(res.x[0] / xs_l).ravel(), res.x[1] / xs_g])
        y = self._evaluate(v, P, U, act, tabs, xs_l, xs_g)[3].copy()
        A = np.zeros((4, 4))
        A[0, 2] = A[1, 3] = 1.0
        fp, fm = np.empty(y.size), np.empty(y.size)
        diag, bd = np.zeros(K.NOUT), np.zeros((self.g.Z, K.NBD))
        # cage centre x, y [m] and its velocity [m/s] (dynamics_kernels state layout: y[12:16])
        for c, (i, h) in enumerate(((12, 1e-8), (13, 1e-8), (14, 1e-5), (15, 1e-5))):
            yp = y.copy()
            yp[i] += h
            K.rhs(0.0, yp, fp, P, U, *tabs, diag, bd, False)
            yp[i] = y[i] - h
            K.rhs(0.0, yp, fm, P, U, *tabs, diag, bd, False)
            A[2:, c] = (fp[14:16] - fm[14:16]) / (2.0 * h)
        if not np.all(np.isfinite(A)):
            return float("nan"), float("nan")
        ev = np.linalg.eigvals(A)
        k = int(np.argmax(ev.real))
        return float(ev[k].real), float(abs(ev[k].imag))

    def _sensitivity(self, res, v, s, P, U, act, tabs, xs_l, xs_g, columns=None):
        """res.sensitivity (d outputs / d inputs) and res.tau_cage (module docstring) at the solution v."""
        g = self.g
        Z = g.Z
        n = v.size
        r, xl, xg, yy, dy, diag, bd, Rl, Rg, share, R = self._evaluate(v, P, U, act, tabs, xs_l, xs_g)
        J = self._jacobian(v, float(res.omega), P, U, act, tabs, xs_l, xs_g)
        res.jacobian = J
        lu = self._lu(J)
        def solve(rhs):            # J dv = rhs; the least-squares solution of smallest norm if J is singular
            dv = np.empty(n)       # (a dry cage whose balls all float: their common place in the pockets)
            if lu.solve(rhs, dv):
                return dv
            from threadpoolctl import threadpool_limits
            with threadpool_limits(limits=1, user_api="blas"):
                return np.linalg.lstsq(J, rhs, rcond=1e-12)[0]

        res.tau_cage = self._tau_cage(res, solve(self._e_wc(n)), xs_g)
        # derivatives of the outputs: dx/dp = -J^-1 dR/dp, then one directional difference per input
        p0 = res.inputs()
        Sens = np.zeros((len(OUTPUT_NAMES), 7)) if res.sensitivity is None else res.sensitivity.copy()
        # a point accepted above the target tolerance sits on a kink of the contact laws: secants there
        ring0 = p0[1:6]
        scale0 = (max(np.max(np.abs(ring0[:3])), np.max(np.abs(ring0[3:])) / (0.5 * g.dm), 100.0)
                  if self.opt.coupling == "load" else self._pose_scale(ring0, p0[0]))
        smooth = res.residual <= self.tol * scale0
        for k in (range(7) if columns is None else columns):
            # central differences over steps that span the kinks of the contact laws (shaft speed 1e-4 of it,
            # forces 0.1 N, moments 0.01 N m, oil 0.1 K; ring pose 10 nm, 0.1 urad)
            hp = [1e-4 * max(abs(p0[0]), 1.0), 0.1, 0.1, 0.1, 1e-2, 1e-2, 0.1][k]
            if self.opt.coupling == "displacement" and 1 <= k <= 5:
                hp = 1e-8 if k <= 3 else 1e-7
            outs = []
            linear = True
            for sg in (1.0, -1.0):
                p = p0.copy()
                p[k] += sg * hp
                s2, P2, U2, act2, tabs2, xs_l2, xs_g2 = self._problem(p[0], p[1:6], p[6])
                R2 = np.empty(n)
                self._residual_at(v, P2, U2, act2, tabs2, xs_l, xs_g, R2)
                v1 = v + solve(-(R2 - R))  # first-order change of the scaled unknowns, then chord steps on J
                R1 = np.empty(n)           # while they bring the residual closer to the solution's
                R0 = R2.copy()
                self._residual_at(v1, P2, U2, act2, tabs2, xs_l, xs_g, R1)
                for _ in range(self.sensitivity_chord_steps):
                    v2 = v1 + solve(-(R1 - R))
                    self._residual_at(v2, P2, U2, act2, tabs2, xs_l, xs_g, R2)
                    if not np.max(np.abs(R2 - R)) < np.max(np.abs(R1 - R)):
                        break
                    v1, R1 = v2, R2.copy()
                # the linearisation holds if the steps took away most of the residual change
                linear = linear and np.max(np.abs(R1 - R)) <= 0.01 * np.max(np.abs(R0 - R))
                outs.append(output_vector(self._evaluate(v1, P2, U2, act2, tabs2, xs_l, xs_g)[5]))
            if self.sensitivity_method == "secant" or not (linear and smooth):
                # the secant over warm re-solves at p +- dp
                # (shaft speed 1 %, forces 2 % of the load scale, moments 2 % of it times dm/2, oil 1 K),
                # the scale on which the linear update is used
                dp = self._secant_step(k, p0)
                sec = {}
                for f in (1.0, 0.25):          # a quarter of the step where the warm solve does not converge
                    for sg in (1.0, -1.0):
                        p = p0.copy()
                        p[k] += sg * f * dp
                        ring = p[1:6]
                        out = self._solve_from(p[0], ring, p[6], self._start("warm", res, p[0], ring, p[6]), False,
                                               J0=J)
                        if isinstance(out, QuasiStaticCageResult):
                            sec[sg] = out.outputs
                    if sec:
                        dp *= f
                        break
                if not sec:         # neither side converged: keep the linearisation
                    Sens[:, k] = (outs[0] - outs[1]) / (2.0 * hp)
                    continue
                outs = [sec.get(1.0, res.outputs), sec.get(-1.0, res.outputs)]
                hp = dp * 0.5 * len(sec)
                res.secant_inputs = res.secant_inputs + (res.input_names[k],)
            Sens[:, k] = (outs[0] - outs[1]) / (2.0 * hp)
        res.sensitivity = Sens

    def _e_wc(self, n):
        e = np.zeros(n)
        e[self.g.Z * NL + CK.G_WC] = 1.0
        return e

    def _tau_cage(self, res, z, xs_g):
        """Time constant [s] of the cage speed's first-order lag (module docstring) from z = J^-1 e_wc, the
        response of the unknowns to the cage torque row: (J^-1)[wc, cage torque row] = 1 / (dR_c/dwc with
        the other equations in equilibrium), so dT/dwc = (dm/2) / (z_wc xs_wc) [N m s]. The inertia is that of
        the solution's rotating parts referred to the cage speed, 2 KE / wc^2 (the cage, the balls' orbital
        translation and their absolute rotation, which the rolling balls carry along with the cage: Harris &
        Kotzalas Vol. 2 Ch. 3; the same inertia the steady levels charge the drive with for a speed change)."""
        g = self.g
        slope = 1.0 / (z[g.Z * NL + CK.G_WC] * xs_g[CK.G_WC]) * (0.5 * g.dm)
        wc = res.cage_speed
        ke = float(res.diag[K.OUT_INDEX["KE"]]) if res.diag is not None else float("nan")
        inertia = 2.0 * ke / (wc * wc) if wc != 0.0 and math.isfinite(ke) and ke > 0.0 else \
            g.cage.inertia + g.Z * g.ball_mass * (0.5 * g.dm) ** 2
        return float(inertia / -slope) if slope < 0.0 else float("inf")

    def _secant_step(self, k, p0):
        """Input step of the secant sensitivity of input k (see _sensitivity)."""
        if k == 0:
            return 1e-2 * abs(p0[0])
        if k == 6:
            return 1.0
        if self.opt.coupling == "displacement":
            return 2e-7 if k <= 3 else 2e-6
        scale = max(np.max(np.abs(p0[1:4])), np.max(np.abs(p0[4:6])) / (0.5 * self.g.dm), 100.0)
        return 2e-2 * scale * (1.0 if k <= 3 else 0.5 * self.g.dm)

    def _residual_at(self, v, P, U, act, tabs, xs_l, xs_g, R):
        out = self._evaluate(v, P, U, act, tabs, xs_l, xs_g)
        R[:] = out[-1]


class _LU:
    """LU factors of one Jacobian (quasistatic_cage_kernels.lu_factor), for the chord steps and the
    sensitivity's solves on it."""

    def __init__(self, J: np.ndarray):
        self.J = J
        self.M = np.empty_like(J)
        self.piv = np.empty(J.shape[0], dtype=np.int64)
        self.ok = bool(CK.lu_factor(J, self.M, self.piv))

    def solve(self, R, dv) -> bool:
        """dv = J^-1 R; False if J is singular."""
        if not self.ok:
            return False
        CK.lu_solve(self.M, self.piv, np.ascontiguousarray(R, dtype=float), dv)
        return True


def solve_quasistatic_cage(geometry: BearingGeometry, omega: float, loads, options=None, **kw) -> QuasiStaticCageResult:
    """Convenience wrapper: QuasiStaticCageModel(geometry, options).solve(omega, loads, **kw)."""
    return QuasiStaticCageModel(geometry, options).solve(omega, loads, **kw)


class QuasiStaticTracker:
    """The steady state along moving inputs (a co-simulation's communication points): a warm re-solve where the
    inputs have left the trust region of the last solution, the first-order update (predict) inside it.

    Trust region: max_k |p_k - p0_k| / t_k <= radius, with t_k the input change that moves the cage speed, the
    friction torque or the heat by rel of its value, or a reaction force by rel of the load scale, on the linear
    update (the model's own sensitivity). At each re-solve the update's error e = max over those outputs of
    |predicted - solved| / (that scale) is measured; a first-order update errs by O(dp^2), so the radius that would have met e = 1 is
    d / sqrt(e), d the normalised step taken; the new radius is 0.8 of it, at most twice the old and within
    [radius_min, radius_max] (the step-size control of an error-per-step integrator; Hairer, Norsett & Wanner,
    Solving ODEs I, Sec. II.4).

    Derivatives between re-solves: Broyden's rank-one secant update along the step between two solutions,
    S += (dy - S dp) (W dp)^T / (dp^T W dp), W = diag(1 / t^2) (Dennis & Schnabel, Numerical Methods for
    Unconstrained Optimization and Nonlinear Equations, 1983, Sec. 8.1): the outputs' change along the path the
    inputs actually take is reproduced exactly and the other columns keep their secants. The full secants of the
    moved inputs and the cage time constant (QuasiStaticCageModel._sensitivity) are recomputed where the update
    erred by more than refresh_error, and every refresh_every re-solves.

    A re-solve is warm-started from the last solution; where that fails, it continues along the straight input
    path in halves, and only then falls back to the model's cold solve (the load path from the free-ball start).

    Ramps: while the shaft's relative rate s = (d omega/dt) / omega stays within [accel_min, accel_max] with one
    sign, a re-solve solves the accelerating state alone, warm from the last one (_ramp_step; half the work of a
    steady re-solve plus its accelerating state). Its cage speed is the lagging one (tau_cage 0); its torque and
    drive power are stated without the kinetic energy's change, which the steady levels add from the inputs
    (steady_equivalent). Where the ramp ends or reverses, the steady state is solved warm from the accelerating
    one, with fresh derivatives, and the cage speed relaxes to it with the secant time constant (_end_ramp)."""

    #: relative accuracy aimed at by the linear update between re-solves (the cage-speed contract's 1 %). Measured
    #: on seed 000's ramp (7218B, oil, Fx 1 kN, Fz 3 kN, 1 ms steps): 35 re-solves and 0.46 s per simulated
    #: second at 1e-2; 299 and 6.3 s at 5e-3, where the solutions' own scatter on the residual floor (their
    #: torque to a few per cent) keeps the measured error of the update high and the trust region small
    rel = 1e-2
    #: the re-solves along the inputs aim at tol_factor x the model's tol (1e-4 of the load scale; still
    #: accepted at tol_accept). Measured (7218B, oil, Fx 1 kN, Fz 3 kN, 3000 -> 4000 rpm in 0.2 s, 1 ms steps):
    #: aiming at tol, warm solves stalled on the contact laws' residual floor at 1.4-2 N and their torque drifted
    #: 25 % below the converged one (0.98 against 1.30 N m at 3395 rpm) before a re-solve snapped back; at 5 x
    #: tol the torque followed the cold solves (1.217 against 1.218 N m at 3200 rpm) without jumps, at 3.3x less
    #: wall time
    tol_factor = 5.0
    #: the linear update also re-solves where it breaks the energy balance of a steady state (drive power =
    #: losses) by more than this share beyond the last solution's own imbalance: torque and heat are updated
    #: apart, and an update that drifts in one of them between re-solves shows here at every step (seen on a
    #: drive cycle's run-up: torque x speed 30 % below the heat, then held for 12 s at constant inputs)
    balance_rel = 2e-2
    radius_min = 0.5
    radius_max = 64.0
    refresh_error = 10.0
    refresh_every = 8
    #: relative shaft acceleration [1/s] from which a solution's cage lag is the secant over the accelerating
    #: state's (_lag); below it the lag is a small fraction of the cage speed (the linear time constants are
    #: 0.1-20 ms, so < 0.1 % at 0.05 1/s) and the linear time constant is used
    accel_min = 0.05
    #: and up to which (a faster change is a step of the input, whose accelerating state the traction cannot
    #: hold: the linear time constant is used)
    accel_max = 50.0
    #: inside a ramp (the relative rate within [accel_min, accel_max], one sign), a re-solve solves the
    #: accelerating state alone, warm from the last one (_ramp_step): its cage speed carries the lag itself. It
    #: is re-solved, inside the trust region too, where the shaft's rate [rad/s^2] has moved by more than this
    #: share of the rate it was solved at: the lag is tau s wc (about 2 % of the cage speed on seed 000's ramp
    #: near 8000-10,000 rpm), so 20 % of the rate moves the cage speed by about 0.4 %
    accel_rel = 0.2
    max_bisect = 6
    #: a warm re-solve whose cage/shaft speed ratio moves by more than this from its start has left the branch
    #: it follows (the steady problem has several roots; docs/fidelity_quasistatic.md): the step is halved, as
    #: a failed one (QuasiStaticCageModel.path_jump for the cold solve's continuation)
    path_jump = 0.05
    KEYS = ("cage_speed", "friction_torque", "heat")
    #: also held to rel, of the load scale (the largest reaction force, at least 100 N): the reactions, which a
    #: rotor model takes from the bearing (displacement coupling) and a load-driven bearing balances
    FORCE_KEYS = ("Fx", "Fy", "Fz")

    def __init__(self, model: QuasiStaticCageModel, rel: float | None = None):
        self.model = model
        if rel is not None:
            self.rel = check_range("rel", rel, 1e-5, 0.2)
        self.res: QuasiStaticCageResult | None = None
        self.radius = self.radius_min
        self.resolves = 0
        self.refreshes = 0
        self.last_error = float("nan")
        self._tol = None
        self._since_refresh = 0
        self._keys = np.array([OUTPUT_NAMES.index(k) for k in self.KEYS + self.FORCE_KEYS])
        self._i_power, self._i_heat = OUTPUT_NAMES.index("P_drive"), OUTPUT_NAMES.index("heat")
        self._imb0 = 0.0
        self._nforce = len(self.FORCE_KEYS)
        self._fresh = True
        self._tau_lin = float("nan")     # the cage lag's linear time constant (last fresh derivatives) [s]
        self._acc_res = None             # the last accelerating state (_lag)
        self.secant_lags = 0             # solutions whose lag is the accelerating state's secant
        self.ramp_solves = 0             # re-solves of the accelerating state alone (_ramp_step)
        self.ramp_ends = 0               # steady solves where a ramp ended (_end_ramp)
        self._ramp_moved = np.zeros(7, dtype=bool)   # the inputs that moved over the ramp's re-solves

    def restart(self):
        """The next point is solved cold, with its full derivatives: a new start of the inputs rather than a
        step along them. Its solution does not depend on the points solved before (the steady equations have
        several roots at high speed, and a warm start from an unrelated point can end on another branch than
        the cold path: 7218B, 10,789 rpm, Fx 1.27 kN, Fz 4.92 kN gave a cage speed of 534.0 rad/s and 2.81 N m
        warm from 11,582 rpm, Fx 0.45 kN, Fz 4.12 kN against 529.5 rad/s and 3.13 N m cold)."""
        self._fresh = True
        self.res = None
        self.model.forget()

    def _solve_args(self, p):
        ring = p[1:6]
        if self.model.opt.coupling == "displacement":
            return dict(displacement=ring)
        return dict(loads=ring)

    def at(self, p, rate: float = 0.0) -> tuple[np.ndarray, bool]:
        """(outputs in OUTPUT_NAMES order, True if this call solved) at inputs p = (omega, 5 loads or pose
        values, T_oil) [rad/s, N, N m or m, rad, K], the shaft speed changing at rate [rad/s^2] (the cage
        lag's time constant at a solution, _lag). Raises ConvergenceError naming the point if no solution is
        found there."""
        p = np.asarray(p, dtype=float)
        res = self.res
        if res is None or self._fresh:
            res = self.model.solve(p[0], T_oil=p[6], start=res, sensitivity=True, **self._solve_args(p))
            self._fresh = False
            self.radius = self.radius_min
            self._since_refresh = 0
            self._tau_lin = res.tau_cage
            self._acc_res = None
            self._ramp_moved[:] = False
            self._lag(res, rate)
            self._accept(res)
            return res.outputs, True
        if res.acceleration != 0.0 and not self.in_ramp(res, p[0], rate):
            return self._end_ramp(res, p, rate)
        p0 = res.inputs()
        dp = p - p0
        with np.errstate(divide="ignore", invalid="ignore"):
            dn = np.where(np.isfinite(self._tol), np.abs(dp) / self._tol, 0.0)
        d = float(np.max(dn))
        pred = res.predict(p[0], p[1:6], p[6])
        a0 = self._acc_res
        ramp = a0 is not None and self.in_ramp(a0, p[0], rate)
        if d <= self.radius and abs(self._imbalance(pred) - self._imb0) <= self.balance_rel and \
                (res.acceleration == 0.0 or self.same_rate(res, rate)):
            return pred, False
        if ramp:
            a = self._ramp_step(a0, p, rate)
            if a is not None:
                self._ramp_moved |= dp != 0.0
                y = a.outputs
                k = self._keys
                e = float(np.max(np.abs(pred[k] - y[k]) / self._scales(y)))
                self.last_error = e
                a.sensitivity = self._broyden(res, a, dp)
                a.secant_inputs = res.secant_inputs
                self._since_refresh += 1
                grow = 0.8 * d / math.sqrt(max(e, 1e-12))
                self.radius = float(min(max(min(grow, 2.0 * self.radius), self.radius_min), self.radius_max))
                self._accept(a)
                return y, True
        new = self._resolve(res, p)
        y = new.outputs
        k = self._keys
        e = float(np.max(np.abs(pred[k] - y[k]) / self._scales(y)))
        self.last_error = e
        moved = tuple(int(i) for i in np.nonzero(dp != 0.0)[0])
        self._since_refresh += 1
        if e > self.refresh_error or self._since_refresh >= self.refresh_every:
            new.sensitivity = res.sensitivity.copy()
            self.model.update_sensitivity(new, columns=moved)
            if math.isfinite(new.tau_cage) and new.tau_cage > 0.0:
                self._tau_lin = new.tau_cage
            # else no restoring slope dT/dwc at this solution (every other equation in equilibrium): the lag
            # keeps the last time constant rather than none
            self._since_refresh = 0
            self.refreshes += 1
        else:
            new.sensitivity = self._broyden(res, new, dp)
            new.secant_inputs = res.secant_inputs
        self._lag(new, rate)
        grow = 0.8 * d / math.sqrt(max(e, 1e-12))
        self.radius = float(min(max(min(grow, 2.0 * self.radius), self.radius_min), self.radius_max))
        self._accept(new)
        return y, True

    def _broyden(self, res, new, dp):
        """res's sensitivity with Broyden's rank-one update along the input step dp to the solution new."""
        w = np.where(np.isfinite(self._tol) & (self._tol > 0), 1.0 / np.where(self._tol > 0, self._tol, 1.0) ** 2,
                     0.0) * dp
        den = float(dp @ w)
        S = res.sensitivity.copy()
        if den > 0.0:
            S += np.outer((new.outputs - res.outputs) - S @ dp, w) / den
        return S

    def in_ramp(self, acc_state, omega: float, rate: float) -> bool:
        """True where the shaft speed omega [rad/s] changing at rate [rad/s^2] continues the ramp of the
        accelerating state acc_state: its relative rate within [accel_min, accel_max] and of the same sign."""
        s = rate / omega
        return self.accel_min <= abs(s) <= self.accel_max and s * acc_state.acceleration > 0.0

    def same_rate(self, acc_state, rate: float) -> bool:
        """True where rate [rad/s^2] is within accel_rel of the shaft's rate at the accelerating state."""
        r0 = acc_state.acceleration * acc_state.omega
        return abs(rate - r0) <= self.accel_rel * abs(r0)

    def _ramp_step(self, a0, p, rate):
        """The accelerating state at p for the shaft's rate [rad/s^2], warm from the accelerating state a0;
        where the warm solve fails, along the straight input path from a0 in halves (at most max_bisect
        failures). Its torque and drive power are given as the level's steady ones (steady_equivalent) and its
        cage speed carries the lag (tau_cage 0). None where it is not found (the caller re-solves the steady
        state)."""
        m = self.model
        m._tol_factor = self.tol_factor
        try:
            path, start, failed = [np.asarray(p, dtype=float)], a0, 0
            while path:
                q = path[-1]
                try:
                    out = m.accelerating_at(q, rate / q[0], start)
                except (ConvergenceError, np.linalg.LinAlgError, ValueError, FloatingPointError):
                    out = None
                if out is not None:
                    start = out
                    path.pop()
                    continue
                failed += 1
                if failed > self.max_bisect:
                    return None
                path.append(0.5 * (start.inputs() + q))
        finally:
            m._tol_factor = 1.0
        a = start
        self.steady_equivalent(a)
        a.tau_cage = 0.0
        self._acc_res = a
        self.ramp_solves += 1
        return a

    @staticmethod
    def steady_equivalent(a):
        """The accelerating state a's friction torque and drive power without the rate of change of the balls'
        and cage's kinetic energy, dKE/dt = 2 KE s (every rotation growing at the relative rate s): the steady
        levels add that term from the inputs (map_kernels.steady_level_outputs). In a.outputs, a.diag and its
        attributes, in place."""
        adj = 2.0 * float(a.diag[K.OUT_INDEX["KE"]]) * a.acceleration      # [W]
        it, ip = OUTPUT_NAMES.index("friction_torque"), OUTPUT_NAMES.index("P_drive")
        a.outputs = a.outputs.copy()
        a.diag = a.diag.copy()
        a.outputs[it] -= adj / a.omega
        a.outputs[ip] -= adj
        a.diag[K.OUT_INDEX["friction_torque"]] -= adj / a.omega
        a.diag[K.OUT_INDEX["P_drive"]] -= adj
        a.friction_torque -= adj / a.omega
        a.P_drive -= adj

    def _end_ramp(self, a, p, rate):
        """The steady state at p where the ramp of the accelerating solution a has ended (or reversed), warm
        from a, with its full derivatives; the cage speed relaxes from a's to it with the secant time constant
        between the two (secant_time_constant), or with the lag of a new ramp's accelerating state (_lag)."""
        new = self._resolve(a, p)
        new.sensitivity = a.sensitivity.copy()
        new.secant_inputs = a.secant_inputs
        # the derivatives afresh along the inputs the ramp moved (the others' are the last fresh ones)
        moved = self._ramp_moved | (p != a.inputs())
        moved[0] = True
        self.model.update_sensitivity(new, columns=tuple(int(i) for i in np.nonzero(moved)[0]))
        self._ramp_moved[:] = False
        if math.isfinite(new.tau_cage) and new.tau_cage > 0.0:
            self._tau_lin = new.tau_cage
        self._since_refresh = 0
        self.refreshes += 1
        self.ramp_ends += 1
        self._acc_res = None
        s = rate / new.omega
        if self.accel_min <= abs(s) <= self.accel_max:
            self._lag(new, rate)
        else:
            tau = self.model.secant_time_constant(new, a)
            new.tau_cage = tau if math.isfinite(tau) else self._tau_lin
        self.radius = self.radius_min
        self._accept(new)
        return new.outputs, True

    def _lag(self, res, rate):
        """res.tau_cage, the time constant of the cage speed's lag at the solution res with the shaft speed
        changing at rate [rad/s^2]. Where its relative rate s = rate / omega lies in [accel_min, accel_max]: the
        secant over the lag of the accelerating state at s (QuasiStaticCageModel.accelerating and
        secant_time_constant; warm from the last one while s keeps its sign), so that the lag in a ramp is that
        state's. Otherwise, or where that state is not found: the linear one, I / (-dT/dwc) at the last
        solution whose derivatives were computed afresh with a restoring slope."""
        res.tau_cage = self._tau_lin
        s = rate / res.omega
        if not self.accel_min <= abs(s) <= self.accel_max:
            self._acc_res = None
            self._ramp_moved[:] = False
            return
        m = self.model
        m._tol_factor = self.tol_factor
        try:
            a = m.accelerating(res, s, start=self._acc_res)
        except (ConvergenceError, np.linalg.LinAlgError, ValueError, FloatingPointError):
            a = None
        finally:
            m._tol_factor = 1.0
        self._acc_res = a
        tau = m.secant_time_constant(res, a) if a is not None else float("nan")
        if math.isfinite(tau):
            res.tau_cage = tau
            self.secant_lags += 1

    def _resolve(self, res, p):
        """The solution at p from res: a warm solve; where it fails, continuation along the straight input path
        in halves (at most max_bisect failures); where that fails too, the model's full solve (warm, then
        cold)."""
        m = self.model
        try:
            m._tol_factor = self.tol_factor
            path = [p]
            start = res
            failed = 0
            while path:
                q = path[-1]
                try:
                    out = m.solve(q[0], T_oil=q[6], start=start, sensitivity=False, cold=False,
                                  **self._solve_args(q))
                    ratio = (out.cage_speed / out.omega) / (start.cage_speed / start.omega)
                    if not abs(ratio - 1.0) <= self.path_jump:
                        raise ConvergenceError(f"cage speed ratio moved by {ratio - 1.0:+.1%} (another branch)")
                    start = out
                    path.pop()
                except ConvergenceError:
                    failed += 1
                    if failed > self.max_bisect:
                        break
                    path.append(0.5 * (start.inputs() + q))
            if not path:
                return start
        finally:
            m._tol_factor = 1.0
        return m.solve(p[0], T_oil=p[6], start=res, sensitivity=False, **self._solve_args(p))

    def _imbalance(self, y):
        """(drive power - losses) / the larger of the two: 0 in an exact steady state."""
        pd, hb = y[self._i_power], y[self._i_heat]
        return (pd - hb) / max(abs(pd), abs(hb), 1e-9)

    def _accept(self, res):
        self.res = res
        self._imb0 = self._imbalance(res.outputs)
        self.resolves += 1
        # per input, the change that moves any key output by its scale on the linear update (inf: none depends
        # on it)
        s = np.abs(res.sensitivity[self._keys])
        with np.errstate(divide="ignore", invalid="ignore"):
            t = np.where(s > 0.0, self._scales(res.outputs)[:, None] / s, np.inf)
        self._tol = np.min(t, axis=0)

    def _scales(self, y):
        """The accuracy the linear update is held to, per key output: rel of its value, the forces rel of the
        load scale."""
        k = self._keys
        sc = np.maximum(np.abs(y[k]), 1e-12)
        nf = self._nforce
        sc[-nf:] = max(float(np.max(np.abs(y[k[-nf:]]))), 100.0)
        return self.rel * sc
