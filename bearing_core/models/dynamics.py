"""Transient tribo-dynamic bearing model: Python front end of bearing_core.models.dynamics_kernels.

    m = DynamicModel(load_preset("7218B"), DynamicsOptions(traction="lubricated"))
    m.initialize(omega=1000 * pi / 30, loads=(500, 0, 2000, 0, 0))   # quasi-static start
    rec = m.advance(0.1)                          # constant inputs
    rec = m.advance(0.2, omega_end=3000 * pi / 30)  # linear speed ramp over the interval

Every ``advance`` runs the whole time integration in compiled code; Python is entered once per call.
State layout, frames and signs: see the docstring of bearing_core.models.dynamics_kernels. SI units.
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from .dynamics_setup import (  # noqa: F401  (DynamicsOptions and the option names are part of this module's API)
    COUPLINGS,
    DynamicSetup,
    DynamicsOptions,
    INTEGRATORS,
    LUBRICATION_REGIMES,
    METHOD_CODE,
    OIL_TRACTIONS,
    START_MODELS,
    ST_AGE,
    ST_C1,
    ST_C2,
    ST_CUR,
    ST_H,
    TRACTION_MODELS)
from . import dynamics_kernels as K
from ..errors import BearingInputError, ConvergenceError, check_range
from .quasistatic import quasistatic_model
from .quasistatic_tribo import TriboQuasiStaticModel

ROSW_LA_RHS = 1.0   # linear algebra of one Rosenbrock-W step attempt, in right-hand-side calls ('auto')
# The Rosenbrock-W method runs at 10x tighter absolute tolerances than the explicit ones on the balls'
# translational velocities. Its steps (5-7e-5 s at 1000 rpm) are set by atol alone, not by stability, and at
# the explicit methods' atol the window-mean friction torque came out 0.8 % low, which opened the energy
# balance by 1.1 % (7218B, 1000 rpm, Fx 1 kN, Fz 5 kN, free tilt; drive power against dissipation +
# d(KE)/dt over 0.05 s). Measured there, friction torque against the stability-limited adaptive RK4, and
# the implicit method's steps: -0.77 % at the explicit atol (742 steps in 0.05 s); 0.1x on every state
# -0.27 % (959); 0.1x on the ball velocities alone -0.30 % (862); on the ball angular velocities alone
# -0.45 % (840), on the rings and cage alone -0.49 % (861), on the ball positions alone -0.77 % (748);
# 0.01x on every state -0.07 % (1667).
IMPLICIT_ATOL_FACTOR = 0.1
AUTO_EXPLICIT = 3     # the explicit candidate of integrator='auto' (bench/bench_dynamics.py)
AUTO_PROBE = 25
AUTO_CHUNK = 5e-3   # [s] interval on which 'auto' chooses


class DynamicModel(DynamicSetup):
    """One bearing: outer ring fixed, inner ring at prescribed speed, balls (6 DOF each), cage
    (rotation and whirl), inner ring 5 DOF (load-driven) or prescribed (displacement-driven); the time
    integration of DynamicSetup's right-hand side, wholly in numba per advance."""

    def initialize(self, omega: float, loads=(0.0, 0.0, 0.0, 0.0, 0.0), displacement=None, t0: float = 0.0,
                   start: str = "jones-harris", omega_outer: float = 0.0):
        """Start at (near) equilibrium from the quasi-static solution (outer raceway control) at shaft
        speed omega [rad/s] and loads (Fx, Fy, Fz, Mx, My) [N, N m]. Displacement-driven coupling takes
        ``displacement`` = (dx, dy, dz, tx, ty, vx, vy, vz, wx, wy) [m, rad, m/s, rad/s] instead; the
        quasi-static start then uses the load that this displacement needs (found by the QS solve of the
        loads returned by a static pass). start: 'jones-harris' (raceway control) or 'tribological' (the
        quasi-static tribological model with this model's traction, bearing_core.models.quasistatic_tribo; seed 000
        Sec. 3.1 stage 1; load-driven ring on a fixed outer ring only; its result is kept in self.tribo_qs).
        Both speeds are signed (about +z), in [-2e4, 2e4] rad/s; omega_outer [rad/s] turns the outer ring.
        Start with a rotating outer ring or a negative speed difference (docs/reversal_and_outputs.md): the
        quasi-static problem is solved in the frame turning with the outer ring at the relative speed
        |omega - omega_outer| (for a negative difference with the loads mirrored in the x-z plane and the
        state mirrored back, mirror_state), then omega_outer is added to the cage, orbital and ball z
        speeds. Jones-Harris start: centrifugal force and gyroscopic moment at the absolute orbital speed
        (QuasiStaticModel.omega_outer); the tribological start solves the relative problem with a fixed
        outer ring (its centrifugal force at the relative orbital speed; the dynamics relax it).
        self.qs / self.tribo_qs keep the solved (relative, possibly mirrored) problem."""
        if start not in START_MODELS:
            raise BearingInputError("start", start, " | ".join(START_MODELS))
        if start == "tribological" and (self.opt.coupling != "load" or self.opt.outer_mount != "fixed"):
            raise BearingInputError("start", start, "jones-harris with displacement coupling or an elastic outer ring")
        omega = check_range("omega", omega, -2.0e4, 2.0e4, unit="rad/s")
        omega_outer = check_range("omega_outer", omega_outer, -2.0e4, 2.0e4, unit="rad/s")
        loads = np.asarray(loads, dtype=float).reshape(-1)
        if loads.size != 5 or not np.all(np.isfinite(loads)):
            raise BearingInputError("loads", loads.tolist(), "5 finite values (Fx, Fy, Fz, Mx, My)")
        loads_in = loads.copy()
        self.thermal = None
        self._T_oil = self.opt.oil_temperature
        self.__dict__.pop("_T_parts", None)
        self.update_operating_geometry(omega)     # fits / ring growth at the shaft speed (isothermal start)
        w_rel = omega - omega_outer
        mirror = w_rel < 0.0
        if mirror:      # solve the mirrored start (x-z plane): Fy, Mx change sign
            loads = loads * MIRROR_LOADS
        omega = abs(w_rel)
        g, o = self.g, self.opt
        axisym = (o.reduced == "axisymmetric") or (
            o.reduced == "auto" and o.coupling == "load" and np.all(loads[[0, 1, 3, 4]] == 0.0))
        if o.reduced == "axisymmetric" and np.any(loads[[0, 1, 3, 4]] != 0.0):
            raise BearingInputError("reduced", "axisymmetric", "full or auto when Fx, Fy, Mx or My is non-zero")
        self.axisym = bool(axisym)
        self.P = self._params(self.axisym)
        qsm = quasistatic_model(g, "outer", fixed_tilt=o.fixed_tilt)   # four-point model for gothic arches
        qsm.omega_outer = -omega_outer if mirror else omega_outer     # in the (mirrored) solved problem
        if o.coupling == "displacement":
            if displacement is None:
                raise BearingInputError("displacement", None, "10 values for displacement-driven coupling")
            d = np.asarray(displacement, dtype=float).reshape(-1)
            if d.size != 10 or not np.all(np.isfinite(d)):
                raise BearingInputError("displacement", d.tolist(), "10 finite values")
            self.U[K.U_DX:K.U_WY + 1] = d
            if mirror:
                d = d * MIRROR_DISP
            Fb, X, st, ok = qsm.residual(d[:5], omega)
            loads = -Fb
            loads_in = loads * MIRROR_LOADS if mirror else loads
        qs = qsm.solve(omega, loads, stiffness=(o.coupling == "load"))
        self.qs = qs
        if o.coupling == "load":
            kd = np.clip(np.diag(qs.stiffness), 0.0, None)
            mass = np.array([g.inner_ring_mass] * 3 + [g.inner_ring_tilt_inertia] * 2)
            self.P[K.P_CRX:K.P_CRTY + 1] = 2.0 * o.support_damping_ratio * np.sqrt(kd * mass)
        nb = 1 if self.axisym else g.Z
        y = np.zeros(K.NSTATE_FIXED + K.NSB * nb)
        y[0:5] = qs.u if o.coupling == "load" else 0.0
        Roo = 0.5 * g.dm - (g.fo - 0.5) * g.D * math.cos(g.alpha0)
        Zoo = -(g.fo - 0.5) * g.D * math.sin(g.alpha0)
        y[11] = qs.cage_speed
        if o.outer_mount == "elastic" and not self.axisym:
            # the housing spring carries the radial load; the inner ring moves with the outer ring
            y[16:18] = loads[:2] / o.housing_stiffness
            if o.coupling == "load":
                y[0:2] += y[16:18]
        for j in range(nb):
            b = K.NSTATE_FIXED + K.NSB * j
            y[b] = qs.psi[j]
            y[b + 1] = Roo + qs.X[j, 0]
            y[b + 2] = Zoo + qs.X[j, 1]
            y[b + 3] = qs.omega_m[j]
            y[b + 6] = -qs.omega_R[j] * math.sin(qs.beta[j])
            y[b + 7] = 0.0
            y[b + 8] = qs.omega_R[j] * math.cos(qs.beta[j]) + qs.omega_m[j]
        self.tribo_qs = None
        if start == "tribological":
            tq = TriboQuasiStaticModel(g, o).solve(omega, loads)
            self.tribo_qs = tq
            y[0:5] = tq.u
            y[11] = tq.cage_speed
            for j in range(nb):       # reduced model: ball 0 stands for all (pure axial load: all equal)
                b, bt = K.NSTATE_FIXED + K.NSB * j, K.NSTATE_FIXED + K.NSB * j
                y[b + 1:b + 9] = tq.y[bt + 1:bt + 9]
        if mirror:
            y = mirror_state(y, nb)
        if omega_outer != 0.0:      # from the frame turning with the outer ring to the absolute frame
            y[11] += omega_outer
            for j in range(nb):
                b = K.NSTATE_FIXED + K.NSB * j
                y[b + 3] += omega_outer
                y[b + 8] += omega_outer
        self.y = y
        self.t = float(t0)
        self.U[K.U_W0] = self.U[K.U_W1] = omega_outer + (-omega if mirror else omega)
        self.U[K.U_WO] = omega_outer
        self.U[K.U_T0] = self.U[K.U_T1] = self.t
        self.U[K.U_FX:K.U_MY + 1] = loads_in
        self.stats[:] = 0.0
        self.quad[:] = 0.0
        self.invalidate_jacobian()
        self._atol = self._atol_scale(nb)
        self._atol_implicit = self._atol.copy()
        for j in range(nb):                      # ball translational velocities (see IMPLICIT_ATOL_FACTOR)
            b = K.NSTATE_FIXED + K.NSB * j
            self._atol_implicit[b + 4:b + 6] *= IMPLICIT_ATOL_FACTOR
        self.thermal = None
        self.apply_temperatures(self.opt.oil_temperature, self.opt.oil_temperature)
        if self.opt.thermal:
            from ..heat.thermal import ThermalData, ThermalNetwork
            td = self.opt.thermal_data or ThermalData(T_amb=self.opt.oil_temperature, T_in=self.opt.oil_temperature)
            td = replace(td, shaft_speed=omega,      # speed-dependent convection and contact resistances
                         oil_fraction=self.oil_fraction_used() if td.oil_fraction is None else td.oil_fraction)
            if td.a_i is None:   # contact ellipses of the most loaded ball (seed 001 Eq. 26)
                bd = self.ball_details()
                j = int(np.argmax(bd["Q_i"]))
                if bd["Q_i"][j] > 0.0 and bd["Q_o"][j] > 0.0:
                    td = replace(td, a_i=float(bd["a_i"][j]), b_i=float(bd["b_i"][j]), a_o=float(bd["a_o"][j]),
                                 b_o=float(bd["b_o"][j]), ball_load=float(bd["Q_i"][j]))
            self.thermal = ThermalNetwork(g, oil=self.oil_name, data=td, T0=None)
            self._apply_thermal()
        return self

    def _atol_scale(self, nb):
        """Absolute tolerances per state for the adaptive integrator (negative: absolute only, used for
        the unbounded angles): positions atol_pos [m] (contact deflections are um), velocities
        1e4 atol_pos [m/s], angular velocities 1e6-1e7 atol_pos [rad/s]."""
        a = np.empty(K.NSTATE_FIXED + K.NSB * nb)
        # measured: velocities at 1e5 atol_pos (the highest natural frequency times atol_pos) save a third of
        # the steps at 10,000 rpm but overstate the dissipated energy of a run-up from rest by 70 % (SSP
        # drivetrain, tests/test_ssp.py) and move Dormand-Prince's mean friction torque 6 % off RK4
        sp, sv, sw = self.opt.atol_pos, self.opt.atol_pos * 1e4, self.opt.atol_pos * 1e6
        a[0:3] = sp; a[3:5] = 10 * sp; a[5:8] = sv; a[8:10] = 10 * sv
        a[10] = -1e-5; a[11] = sw; a[12:14] = 10 * sp; a[14:16] = 10 * sv
        a[16:18] = sp; a[18:20] = sv
        for j in range(nb):
            b = K.NSTATE_FIXED + K.NSB * j
            a[b] = -1e-6
            a[b + 1:b + 3] = sp
            a[b + 3] = sw
            a[b + 4:b + 6] = sv
            a[b + 6:b + 9] = 10 * sw
        return a

    # ---- time integration ---------------------------------------------------------------------
    def set_inputs(self, loads=None, displacement=None):
        """Hold new loads (Fx, Fy, Fz, Mx, My) or displacement inputs (10 values) from now on."""
        if loads is not None:
            loads = np.asarray(loads, dtype=float).reshape(-1)
            if loads.size != 5 or not np.all(np.isfinite(loads)):
                raise BearingInputError("loads", loads.tolist(), "5 finite values (Fx, Fy, Fz, Mx, My)")
            if self.axisym and np.any(loads[[0, 1, 3, 4]] != 0.0):
                raise BearingInputError("loads", loads.tolist(),
                                        "pure axial load for the reduced (axisymmetric) model; "
                                        "initialise with reduced='full'")
            self.U[K.U_FX:K.U_MY + 1] = loads
        if displacement is not None:
            d = np.asarray(displacement, dtype=float).reshape(-1)
            if d.size != 10 or not np.all(np.isfinite(d)):
                raise BearingInputError("displacement", d.tolist(), "10 finite values")
            self.U[K.U_DX:K.U_WY + 1] = d

    def set_speed(self, omega: float, omega_outer: float | None = None):
        """Hold the shaft speed at omega [rad/s] from now on (a step change, no ramp), signed about +z; also
        the outer-ring speed omega_outer [rad/s] if given (else kept)."""
        omega = check_range("shaft_speed", omega, -2.0e4, 2.0e4, unit="rad/s")
        if omega_outer is not None:
            self.U[K.U_WO] = check_range("outer_ring_speed", omega_outer, -2.0e4, 2.0e4, unit="rad/s")
        self.U[K.U_W0] = self.U[K.U_W1] = omega
        self.U[K.U_T0] = self.U[K.U_T1] = self.t
        self.update_operating_geometry()          # centrifugal ring growth at the new speed
        if self.opt.oil_supply is not None:       # the supply's cavity oil content at the new speed
            from ..lubrication.lubricants import get_oil
            oil = get_oil(self.oil_name)
            self._set_mixture(oil.density(self._T_oil), oil.eta(self._T_oil))

    def advance(self, t_end: float, omega_end: float | None = None, record_dt: float | None = None):
        """Integrate from the current time to t_end [s]; the shaft speed ramps linearly from its current
        value to omega_end [rad/s] over the interval (held if None). Returns the records (n x NOUT
        array, columns dynamics_kernels.OUT_NAMES) taken every record_dt (default options.record_dt)."""
        if self.y is None:
            raise RuntimeError("call initialize() first")
        t_end = float(t_end)
        if not math.isfinite(t_end) or t_end <= self.t:
            raise BearingInputError("t_end", t_end, f"finite and > current time {self.t}")
        w0 = self.U[K.U_W1] if self.t >= self.U[K.U_T1] else self._shaft_speed(self.t)
        w1 = w0 if omega_end is None else check_range("omega_end", omega_end, -2.0e4, 2.0e4, unit="rad/s")
        self.U[K.U_W0], self.U[K.U_W1] = w0, w1
        self.U[K.U_T0], self.U[K.U_T1] = self.t, t_end
        rdt = self.opt.record_dt if record_dt is None else float(record_dt)
        # + 1 per auto chunk: float rounding can add one record at a chunk end
        nmax = int((t_end - self.t) / rdt) + 2 + int((t_end - self.t) / AUTO_CHUNK) + 1
        rec = np.zeros((nmax, K.NOUT))
        q0 = self.quad[:K.NOUT].copy()
        if self.opt.integrator == "auto" and t_end - self.t > 1.5 * AUTO_CHUNK:
            # split into chunks (whole multiples of the record interval) and choose per chunk
            L = rdt * max(1, round(AUTO_CHUNK / rdt))
            n = 0
            ta = self.t
            while ta < t_end - 1e-12:
                tb = min(ta + L, t_end)
                if t_end - tb < 0.5 * L:
                    tb = t_end
                n += self._integrate(ta, tb, rdt, rec[n:], nmax - n)
                if self.stats[4] != 0.0:
                    break
                ta = tb
        else:
            n = self._integrate(self.t, t_end, rdt, rec, nmax)
        if self.stats[4] != 0.0 or not self._finite:
            raise FloatingPointError(
                f"integration failed at t in [{self.t:.6g}, {t_end:.6g}] s "
                f"({'non-finite state' if self.stats[4] == 1 else 'step size underflow'}); "
                "reduce dt / rtol or check the inputs")
        if self.thermal is not None and n > 0:
            # the network takes the mean powers over the interval: the time integrals accumulated in the
            # integrator (energy-consistent), not the mean of the sampled records
            mean = ((self.quad[:K.NOUT] - q0) / (t_end - self.t))[None, :]
            self._thermal_step(mean, (t_end - self.t) * self.opt.thermal_time_scale)
        self.t = t_end
        return rec[:n]

    # ---- thermal network on the slow time scale (seed 001 Eqs. 21-29) -------------------------------
    def heat_sources(self, rec) -> dict:
        """Mean loss powers [W] of records (n x NOUT) keyed by the thermal network's sources: race traction
        with half the contact damping each, pocket, land, churning of cage and inner ring, ball drag, and the
        work on the supply oil (not a load of the dynamics: _oil_work)."""
        m = rec.mean(axis=0)
        I = K.OUT_INDEX
        dmp = 0.5 * m[I["P_damping"]]
        return {"Q_br_i": max(m[I["P_race_inner"]] + dmp, 0.0), "Q_br_o": max(m[I["P_race_outer"]] + dmp, 0.0),
                "Q_bp": max(m[I["P_pocket"]], 0.0), "Q_cg": max(m[I["P_land"]], 0.0),
                "Q_ch_c": max(m[I["P_churn_cage"]], 0.0), "Q_ch_s": max(m[I["P_churn_ring"]], 0.0),
                "Q_ch_b": 0.0, "drag": max(m[I["P_drag"]], 0.0), "Q_oil_work": self._oil_work(m[I["cage_speed"]])}

    def _oil_work(self, cage_speed):
        """Work [W] of the rotating parts on the supply oil (oil_supply.supply_oil_work) at the held shaft
        speed and the cage speed [rad/s]: the jet hits the inner-ring land (d_m - 0.7 D) / 2 and leaves at the
        cage's outer surface d_m / 2 + 0.35 D (the surfaces of churning.ChurningGeometry); oil at its inlet
        temperature. 0 without a supply."""
        sup = self.opt.oil_supply
        if sup is None:
            return 0.0
        from ..lubrication.lubricants import get_oil
        from ..lubrication.oil_supply import supply_oil_work
        g, wo = self.g, self.U[K.U_WO]
        return supply_oil_work(sup, get_oil(self.oil_name).density(sup.T_in), self.U[K.U_W1] - wo,
                               cage_speed - wo, 0.5 * g.dm - 0.35 * g.D, 0.5 * g.dm + 0.35 * g.D)

    def _thermal_step(self, rec, dt):
        self.thermal.set_speed(self.U[K.U_W1] - self.U[K.U_WO])
        self.thermal.step(self.heat_sources(rec), dt)
        self._apply_thermal()
        if self.thermal.runaway():
            self.thermal_runaway = True

    @property
    def thermal_runaway(self) -> bool:
        """True once a thermal-network temperature passed the oil's limit (thermal.OIL_T_MAX); stays set
        until the thermal state is restored to one below the limit (set_thermal_state)."""
        return getattr(self, "_runaway", False)

    @thermal_runaway.setter
    def thermal_runaway(self, v):
        self._runaway = bool(v)

    def skid(self) -> dict:
        """Kinematic reference and skid classification at the current instant (bearing_core.models.skid): pure-
        rolling cage speeds at the loaded balls' contact angles with outer / inner raceway control [rad/s],
        seed 000's Eq. 26 value (spin-free, mean angles) [rad/s], cage speed [rad/s], cage_slip_ratio and
        skid_state (+1 skidding, 0 pure rolling, -1 over-skidding) with its label."""
        from .skid import SKID_LABELS, classify_skid
        o = self.outputs()
        state, s = classify_skid(o["cage_speed"], o["cage_speed_pure_rolling_outer"], omega_outer=o["outer_ring_speed"])
        return {"cage_speed": o["cage_speed"], "cage_speed_pure_rolling_outer": o["cage_speed_pure_rolling_outer"],
                "cage_speed_pure_rolling_inner": o["cage_speed_pure_rolling_inner"],
                "cage_speed_seed000_eq26": o["pure_rolling_cage_speed"], "cage_slip_ratio": s,
                "skid_state": state, "skid_label": SKID_LABELS[state]}

    def _apply_thermal(self):
        T = self.thermal.temperatures()
        self.apply_temperatures(T["oil"], T["ball"], T["inner"], T["outer"])

    def thermal_equilibrium(self, window: float = 0.05, tol: float = 0.1, max_iter: int = 30) -> dict:
        """Two-time-scale thermal steady state at the current speed and loads: repeat (advance the dynamics
        by window [s] at fixed temperatures; mean losses of that window -> steady state of the thermal
        network -> new temperatures) until no node moves by more than tol [K]. Returns temperatures [K],
        losses by source, heat generated and rejected (ambient + oil flow) [W], the iterations and the
        balance (rejected / generated - 1) at the final temperatures. The drive power and friction torque
        include the work on the supply oil (heat_sources 'Q_oil_work'; its torque as power / speed)."""
        if self.thermal is None:
            raise BearingInputError("thermal", False, "True (DynamicsOptions(thermal=True))")
        check_range("window", window, 1e-3, 10.0, unit="s")
        for it in range(1, max_iter + 1):
            rec = self.advance(self.t + window, record_dt=min(window / 20, 1e-3))
            Q = self.heat_sources(rec)
            T_old = self.thermal.T.copy()
            self.thermal.set_speed(self.U[K.U_W1] - self.U[K.U_WO])
            self.thermal.steady_state(Q, set_state=True)
            self._apply_thermal()
            if np.max(np.abs(self.thermal.T - T_old)) < tol:
                break
        else:
            # not converged: past the oil's limit it is a runaway (the fixed point keeps heating up)
            self.thermal.check_runaway(f"at {self.U[K.U_W1] * 30 / math.pi:.0f} rpm (thermal equilibrium not "
                                       f"reached in {max_iter} iterations, losses {sum(Q.values()):.0f} W)")
            raise ConvergenceError(f"thermal equilibrium not reached in {max_iter} iterations of {window} s")
        # a steady state past the oil's limit is a thermal runaway, not an equilibrium
        self.thermal.check_runaway(f"at {self.U[K.U_W1] * 30 / math.pi:.0f} rpm (thermal equilibrium after "
                                   f"{it} iterations, losses {sum(Q.values()):.0f} W)")
        # check: one more window at the final temperatures (no update); its losses must equal what the
        # network rejects at those temperatures
        th = self.thermal_state()
        rec = self.advance(self.t + window, record_dt=min(window / 20, 1e-3))
        self.set_thermal_state(th)
        Q = self.heat_sources(rec)
        gen = sum(Q.values())
        rej = self.thermal.heat_to_ambient() + self.thermal.heat_to_oil_flow()
        w_rel = float(self.U[K.U_W1] - self.U[K.U_WO])
        I = K.OUT_INDEX
        return {"temperatures_K": self.thermal.temperatures(), "losses_W": Q, "heat_generated_W": gen,
                "heat_rejected_W": rej, "balance": rej / gen - 1.0 if gen > 0 else 0.0, "iterations": it,
                # the shaft also supplies the work on the supply oil, which the dynamics' channels do not carry
                "drive_power_W": float(rec[:, I["P_drive"]].mean()) + Q["Q_oil_work"],
                "friction_torque_Nm": float(rec[:, I["friction_torque"]].mean())
                + (Q["Q_oil_work"] / abs(w_rel) if w_rel != 0.0 else 0.0),
                "cage_speed_rad_s": float(rec[:, I["cage_speed"]].mean())}

    def thermal_state(self):
        """Copy of the thermal network state (None without one), for rollback."""
        if self.thermal is None:
            return None
        th = self.thermal
        return (th.T.copy(), th.E_generated, th.E_ambient, th.E_flow)

    def set_thermal_state(self, st):
        if st is None or self.thermal is None:
            self.update_operating_geometry()     # the geometry of the (restored) held speed
            return
        th = self.thermal
        th.T[:] = st[0]
        th.E_generated, th.E_ambient, th.E_flow = st[1], st[2], st[3]
        self._apply_thermal()
        self.thermal_runaway = th.runaway()

    def temperatures(self) -> dict:
        """Node temperatures [K] (ball, outer, inner, oil) and the heat flows to ambient and to the oil flow [W];
        the isothermal oil temperature when the thermal network is off."""
        if self.thermal is None:
            T = self.opt.oil_temperature
            return {"ball": T, "outer": T, "inner": T, "oil": T, "heat_to_ambient": 0.0, "heat_to_oil_flow": 0.0}
        d = dict(self.thermal.temperatures())
        d["heat_to_ambient"] = self.thermal.heat_to_ambient()
        d["heat_to_oil_flow"] = self.thermal.heat_to_oil_flow()
        return d

    def _integrate(self, t_start, t_end, rdt, rec, nmax):
        """One kernel call from t_start to t_end (state self.y); returns the number of records."""
        if self.opt.integrator == "auto":
            method = self._auto_choose()
        else:
            method = METHOD_CODE[self.opt.integrator]
        if method == 0:
            dt0 = self.opt.dt
        else:
            hk = self.stats[ST_H[method]]
            dt0 = hk if hk > 0 else (self.stats[3] if self.stats[3] > 0 else self.opt.dt)
            if hk <= 0 and method != 2:
                # an explicit method taking over from the implicit one starts at most at dt: the implicit
                # step (~5e-5 s at 1000 rpm) lies beyond the explicit stability limit (~3e-5 s), and the
                # first steps there passed the error test yet lost ~1 % of the energy balance
                dt0 = min(dt0, self.opt.dt)
        self.stats[4] = 0.0
        nb = int(self.P[K.P_NB])
        if self._end_diag is None or self._end_bd.shape[0] != nb:
            self._end_diag, self._end_bd = np.zeros(K.NOUT), np.zeros((nb, K.NBD))
        kb = self._key_buf
        if kb is None or kb[0].shape != self.y.shape or kb[1].shape != self.U.shape or kb[2].shape != self.P.shape:
            kb = self._key_buf = (np.empty_like(self.y), np.empty_like(self.U), np.empty_like(self.P), np.empty(3))
        before = kb[3]
        before[:] = self.stats[:3]
        self._end_key = None
        if method == 2:
            nb = int(self.P[K.P_NB])
            if self._rosw_ws is None or self._rosw_ws[3].shape[0] != nb:
                self._rosw_ws = K.rosw_workspace(nb)
            n = K.integrate_rosw(self.y, t_start, t_end, dt0, self.opt.rtol, self._atol_implicit, self.P, self.U,
                                 self._tab_i, self._tab_o, self._ta0, self._tda, self._tp, *self._quad,
                                 rdt, rec, nmax, self.stats, self.quad, self._end_diag, self._end_bd,
                                 *self._rosw_ws)
            if self.stats[4] != 0.0:
                self.invalidate_jacobian()
        else:
            n = K.integrate(self.y, t_start, t_end, dt0, method, self.opt.rtol, self._atol, self.P, self.U,
                            self._tab_i, self._tab_o, self._ta0, self._tda, self._tp, *self._quad,
                            rdt, rec, nmax, self.stats, self.quad, self._end_diag, self._end_bd)
        # one kernel for the bookkeeping (numpy calls here cost several us each once the integration has
        # evicted the caches): the finiteness of y, the key of the end point's outputs (evaluate_point
        # reuses them), and for the adaptive methods their last step and their cost in right-hand-side
        # equivalents per simulated second (deterministic, unlike wall time). The implicit step adds its
        # linear algebra, 12-17 us per step attempt (7218B, 16 balls), about one right-hand side under Kalker
        # traction and half of one under EHL traction: counted as 1
        self._finite = K.close_interval(self.y, self.U, self.P, self.stats, before, ST_H.get(method, -1),
                                        ST_C2 if method == 2 else ST_C1, ROSW_LA_RHS if method == 2 else 0.0,
                                        t_start, t_end, kb[0], kb[1], kb[2])
        if self.stats[4] == 0.0:
            self._end_key = (float(t_end), kb[0], kb[1], kb[2], self._tp)
        return n

    def integrator_state(self):
        """A copy of the integrator's memory beyond stats (the implicit method's W and its factors), for
        rollback with set_integrator_state: a step repeated from a restored state repeats the arithmetic."""
        return None if self._rosw_ws is None else tuple(a.copy() for a in self._rosw_ws)

    def set_integrator_state(self, ws):
        if ws is None:
            self.invalidate_jacobian()
        else:
            self._rosw_ws = tuple(a.copy() for a in ws)

    def invalidate_jacobian(self):
        """Make the implicit integrator rebuild its Jacobian at its next step (after the state was set
        from outside, e.g. an FMU rollback, so that a repeated step repeats the same arithmetic)."""
        if self._rosw_ws is not None:
            self._rosw_ws[-1][:] = (K.JAC_EVERY, -1.0)

    def _auto_choose(self) -> int:
        """integrator='auto': run the cheaper of the explicit Dormand-Prince (1) and the Rosenbrock-W (2)
        integrators, by their measured cost per simulated second (stats[ST_C1], stats[ST_C2]); the
        other one is probed every AUTO_PROBE intervals (times how much dearer it was, up to 8x), or sooner
        when the current one becomes much dearer than the other's last cost. The selector state lives in stats, so FMU rollback restores it."""
        st = self.stats
        ex = AUTO_EXPLICIT
        # Kalker creep forces are stiff at low rolling speed: start with the Rosenbrock-W, and until the
        # explicit method has been measured take its cost from its stability limit (_explicit_cost_kalker)
        # instead of probing it at the second interval (at 1000 rpm one 5 ms probe cost as much as 20 ms of
        # the implicit method; docs/kalker.md)
        kalker = self.opt.race_traction == "kalker"
        cur = int(st[ST_CUR]) if st[ST_CUR] > 0 else (2 if kalker else ex)
        other = 2 if cur != 2 else ex
        c_cur, c_oth = st[ST_C2 if cur == 2 else ST_C1], st[ST_C2 if other == 2 else ST_C1]
        if kalker and cur == 2 and c_oth <= 0 and c_cur > 0:
            c_oth = self._explicit_cost_kalker()
        st[ST_AGE] += 1
        # the probe interval grows with how much dearer the other method was (up to 8x): a probe of a
        # method 5x dearer every AUTO_PROBE chunks cost ~15 % (explicit at 1000 rpm, EHL traction)
        every = AUTO_PROBE * min(8.0, max(1.0, c_oth / c_cur)) if c_oth > 0 and c_cur > 0 else AUTO_PROBE
        probe = st[ST_AGE] >= every or (c_oth > 0 and c_cur > 1.5 * c_oth) or (c_oth <= 0 and st[ST_AGE] >= 2)
        if probe:
            st[ST_AGE] = 0
            st[ST_CUR] = other       # run the other one now; the next choice compares the two costs
            return other
        if c_oth > 0 and c_oth < c_cur:
            cur = other
        st[ST_CUR] = cur
        return cur

    def _explicit_cost_kalker(self) -> float:
        """Right-hand sides per simulated s the explicit adaptive RK4 would need under Kalker traction, from
        the stability limit of the stiffest creep relaxation (integrator='auto', before the explicit method
        has been measured). Kalker's linear theory gives the creep force -G c^2 C11 xi with xi = v_slip /
        |u_roll|, a damper k = G c^2 C11 / |u_roll| [N s/m] on the contact slip; a ball (mass m, inertia J)
        relaxes that slip at lambda = k (1/m + (D/2)^2 / J) [1/s]. RK4 is stable to h lambda <= 2.785 on the
        negative real axis (Hairer & Wanner II, Sec. IV.2; value recalled), 4 right-hand sides per step. The
        linear-theory slope is the largest creep slope (partial slip lowers it), so this overstates the cost:
        7218B, Fx 1000 N, Fz 3000 N, mu 0.1: estimate 3.5-3.7M at 1000 rpm and 0.39-0.40M at 10,000 rpm,
        measured 1.0-1.2M and 0.27-0.29M per simulated s. It only steers the choice until the explicit
        method's own cost has been measured (its first probe)."""
        from ..contact.fastsim import max_creep_damping
        _, bd = self.evaluate_point()
        G, nu = self.P[K.P_GCOMB], self.P[K.P_NUCOMB]
        k = max(max_creep_damping(bd[:, K.BD_AI_SEMI], bd[:, K.BD_BI], bd[:, K.BD_QI], bd[:, K.BD_UI], G, nu),
                max_creep_damping(bd[:, K.BD_AO_SEMI], bd[:, K.BD_BO], bd[:, K.BD_QO], bd[:, K.BD_UO], G, nu))
        D = self.P[K.P_D]
        return 4.0 * k * (1.0 / self.P[K.P_MB] + 0.25 * D * D / self.P[K.P_JB]) / 2.785

    def integrals(self) -> dict:
        """Time integrals [channel unit x s] of every output channel (dynamics_kernels.OUT_NAMES) since the
        last reset_integrals(), accumulated inside the integrator over its accepted steps (trapezoidal
        rule, dynamics_kernels.NQUAD): e.g. 'P_race_inner' is the energy [J] dissipated at the inner races,
        'friction_torque' the angular impulse [N m s]."""
        return dict(zip(K.OUT_NAMES, self.quad[:K.NOUT].tolist()))

    def reset_integrals(self):
        """Zero the time integrals (the next integration starts a new trapezoid at its first point)."""
        self.quad[:] = 0.0

    def _shaft_speed(self, t):
        w, _ = K._shaft(self.U, t)
        return w

    def outputs(self) -> dict:
        """Output channels at the current instant (names: dynamics_kernels.OUT_NAMES)."""
        return dict(zip(K.OUT_NAMES, self.evaluate_point()[0].tolist()))

    def ball_details(self) -> dict:
        """Per-ball contact angles [rad], loads [N], semi-axes [m], pressures [Pa], traction forces
        [N], centre slips [m/s], entrainment speeds [m/s], spins [rad/s] at the current instant. For a
        four-point-contact bearing the *_i / *_o values are each ring's first (more loaded) arc and
        Q_i2, alpha_i2, Q_o2, alpha_o2 the second arc (0 load when it does not touch)."""
        diag = np.zeros(K.NOUT)
        nb = int(self.P[K.P_NB])
        bd = np.zeros((nb, K.NBD))
        K.evaluate(self.t, self.y, self.P, self.U, self._tab_i, self._tab_o, self._ta0, self._tda, self._tp,
                   *self._quad, diag, bd)
        names = ("alpha_i", "alpha_o", "Q_i", "Q_o", "delta_i", "delta_o", "a_i", "b_i", "a_o", "b_o",
                 "p_i", "p_o", "Ft_i", "Fm_i", "Ft_o", "Fm_o", "slip_i", "slip_o", "u_i", "u_o",
                 "spin_i", "spin_o", "slip_m_i", "slip_m_o", "F_pocket")
        d = {n: bd[:, k].copy() for k, n in enumerate(names)}
        # four-point contact: the second (less loaded) arc of each ring; Q_i, alpha_i, ... hold the first
        for n, k in (("Q_i2", K.BD_QI2), ("alpha_i2", K.BD_AI2), ("Q_o2", K.BD_QO2), ("alpha_o2", K.BD_AO2)):
            d[n] = bd[:, k].copy()
        b = K.NSTATE_FIXED + K.NSB * np.arange(nb)
        d["theta"] = self.y[b].copy()
        d["orbit_speed"] = self.y[b + 3].copy()
        d["omega"] = self.y[np.stack([b + 6, b + 7, b + 8], axis=1)].copy()
        W = d["omega"]
        # attitude angle (from the bearing axis, Harris's beta sign) and yaw angle of the spin axis
        Wrel_z = W[:, 2] - d["orbit_speed"]
        d["attitude"] = np.arctan2(-W[:, 0], np.abs(Wrel_z)) * np.sign(-Wrel_z + 1e-300) * -1.0
        d["yaw"] = np.arctan2(W[:, 1], np.hypot(W[:, 0], Wrel_z))
        return d


MIRROR_LOADS = np.array([1.0, -1.0, 1.0, -1.0, 1.0])
"""Reflection in the x-z plane of (Fx, Fy, Fz, Mx, My): moments are axial vectors."""
MIRROR_DISP = np.array([1.0, -1.0, 1.0, -1.0, 1.0, 1.0, -1.0, 1.0, -1.0, 1.0])


def mirror_state(y: np.ndarray, nb: int) -> np.ndarray:
    """The state (dynamics_kernels layout) reflected in the x-z plane (y -> -y, a plane through the bearing
    axis): positions y, rates vy, tilts and tilt rates about x, angles and speeds about z change sign (axial
    vectors: a component in the plane flips, the normal one stays); ball j at theta goes to the ball at
    -theta, index (nb - j) % nb, with (Omega_r, Omega_t, Omega_z) -> (-Omega_r, Omega_t, -Omega_z)."""
    m = y.copy()
    for i in (1, 3, 6, 8, 10, 11, 13, 15, 17, 19):
        m[i] = -y[i]
    for j in range(nb):
        b = K.NSTATE_FIXED + K.NSB * j
        k = K.NSTATE_FIXED + K.NSB * ((nb - j) % nb)
        m[k:k + K.NSB] = y[b:b + K.NSB] * np.array([-1.0, 1.0, 1.0, -1.0, 1.0, 1.0, -1.0, 1.0, -1.0])
    return m


SEED000_PROFILE = ((0.0, 1000.0), (0.5, 1000.0), (1.4, 10000.0), (2.0, 10000.0))
"""Seed 000 acceleration case: (time [s], inner-ring speed [rpm]) breakpoints: 1000 rpm to 0.5 s, then
10,000 rpm/s up to 10,000 rpm at 1.4 s, held to 2 s (Lubricants 2025 13(5) 218, section 4)."""


PROFILE_LOAD_COLUMNS = ("Fx_N", "Fy_N", "Fz_N", "Mx_Nm", "My_Nm")


def read_profile(spec: str):
    """A speed profile: 'seed000' (SEED000_PROFILE) or a CSV file with columns time_s, speed_rpm (signed:
    negative turns the shaft backwards, |speed| <= 190,986 rpm = 2e4 rad/s) and optionally Fx_N, Fy_N,
    Fz_N, Mx_Nm, My_Nm and outer_speed_rpm (held per segment at the segment's start value in
    simulate_profile when given as a third tuple element). Returns (times [s], speeds [rpm], loads) with loads a dict
    of the load columns present (None if none). Bad files raise BearingInputError('profile', ...)."""
    import csv
    from pathlib import Path
    if spec == "seed000":
        t, n = zip(*SEED000_PROFILE)
        return np.array(t), np.array(n), None
    p = Path(spec)
    if not p.is_file():
        raise BearingInputError("profile", spec, "seed000 or an existing CSV file")
    with p.open() as fh:
        rows = list(csv.DictReader(fh))
    try:
        t = np.array([float(r["time_s"]) for r in rows])
        n = np.array([float(r["speed_rpm"]) for r in rows])
        loads = {c: np.array([float(r[c]) for r in rows]) for c in PROFILE_LOAD_COLUMNS if rows and c in rows[0]}
    except (KeyError, ValueError, TypeError):
        raise BearingInputError("profile", spec, "rows with numeric time_s, speed_rpm (and load columns if given)")
    vals = np.concatenate([t, n] + list(loads.values()))
    if len(t) < 2 or np.any(np.diff(t) <= 0) or not np.all(np.isfinite(vals)):
        raise BearingInputError("profile", spec, ">= 2 rows, strictly increasing finite time_s, finite values")
    if np.any(np.abs(n) > 2.0e4 * 30.0 / math.pi):
        raise BearingInputError("profile", spec, "|speed_rpm| <= 190986 rpm (2e4 rad/s)")
    if rows and "outer_speed_rpm" in rows[0]:
        try:
            no = np.array([float(r["outer_speed_rpm"]) for r in rows])
        except (ValueError, TypeError):
            raise BearingInputError("profile", spec, "numeric outer_speed_rpm")
        if not np.all(np.isfinite(no)) or np.any(np.abs(no) > 2.0e4 * 30.0 / math.pi):
            raise BearingInputError("profile", spec, "finite |outer_speed_rpm| <= 190986 rpm")
        loads = dict(loads, outer_speed_rpm=no)
    return t, n, (loads or None)


def simulate_profile(model: DynamicModel, profile, record_dt: float | None = None, progress=None) -> np.ndarray:
    """Drive an initialised model through a piecewise-linear speed profile ((t [s], speed [rpm]), ...)
    starting at the model's current time; returns the concatenated records. Python is entered once per
    profile segment (or per chunk of at most 0.05 s when ``progress`` is given, to report progress)."""
    prof = [(float(p[0]), float(p[1])) for p in profile]
    outer = [float(p[2]) if len(p) > 2 else None for p in profile]
    if any(not (math.isfinite(t) and math.isfinite(n)) for t, n in prof):
        raise BearingInputError("profile", profile, "finite (time s, speed rpm) pairs")
    if any(b[0] <= a[0] for a, b in zip(prof, prof[1:])):
        raise BearingInputError("profile", profile, "strictly increasing times")
    if any(abs(n) > 2.0e4 * 30.0 / math.pi for _, n in prof):
        raise BearingInputError("profile", profile, "speeds within +-190986 rpm (2e4 rad/s), signed")
    out = []
    t_end = prof[-1][0]
    for i, ((t0, n0), (t1, n1)) in enumerate(zip(prof, prof[1:])):
        if t1 <= model.t + 1e-12:
            continue
        if outer[i] is not None:       # outer-ring speed [rpm] held over the segment
            model.U[K.U_WO] = check_range("outer_speed_rpm", outer[i], -2.0e4 * 30.0 / math.pi,
                                          2.0e4 * 30.0 / math.pi, unit="rpm") * math.pi / 30.0
        chunks = [t1] if progress is None else list(np.arange(model.t + 0.05, t1, 0.05)) + [t1]
        for tc in chunks:
            if tc <= model.t + 1e-12:
                continue
            w = (n0 + (n1 - n0) * (tc - t0) / (t1 - t0)) * math.pi / 30.0
            out.append(model.advance(tc, omega_end=w, record_dt=record_dt))
            model.update_operating_geometry()     # ring growth at the speed reached (piecewise per chunk)
            if progress is not None:
                progress(model.t, t_end)
    return np.concatenate(out) if out else np.zeros((0, K.NOUT))


def advance_many(models, t_end, omega_end=None, record_dt: float | None = None, workers: int | None = None,
                 return_exceptions: bool = False) -> list:
    """Advance independent initialised models (e.g. the operating points of a sweep) to t_end [s] (a scalar
    or one per model) concurrently in one process: each model runs in a thread of a pool of ``workers``
    (default: one per CPU); the integration kernels release the GIL (numba nogil), so the threads run in
    parallel for all but the little Python around each kernel call. omega_end: None, a scalar or one per
    model [rad/s]. Returns the records of each model (as DynamicModel.advance), in order; the first error
    of any model is raised after all have finished, or with return_exceptions=True a model's exception
    takes its place in the list (the other models' results are kept)."""
    import os
    from concurrent.futures import ThreadPoolExecutor
    models = list(models)
    n = len(models)
    t_end = list(t_end) if np.ndim(t_end) else [t_end] * n
    omega_end = list(omega_end) if np.ndim(omega_end) else [omega_end] * n
    if len(t_end) != n or len(omega_end) != n:
        raise BearingInputError("t_end / omega_end", (len(t_end), len(omega_end)), f"scalars or {n} values")
    workers = max(1, min(n, workers or os.cpu_count() or 1))
    if workers == 1 and not return_exceptions:
        return [m.advance(t, omega_end=w, record_dt=record_dt) for m, t, w in zip(models, t_end, omega_end)]
    if workers == 1:
        out = []
        for m, t, w in zip(models, t_end, omega_end):
            try:
                out.append(m.advance(t, omega_end=w, record_dt=record_dt))
            except Exception as e:       # this model's error, in its place
                out.append(e)
        return out
    with ThreadPoolExecutor(max_workers=workers) as ex:
        futs = [ex.submit(m.advance, t, w, record_dt) for m, t, w in zip(models, t_end, omega_end)]
        if not return_exceptions:
            return [f.result() for f in futs]
        return [f.exception() or f.result() for f in futs]


def records_to_dict(rec: np.ndarray) -> dict:
    """Columns of an advance() record array by name."""
    return {n: rec[:, k] for k, n in enumerate(K.OUT_NAMES)}
