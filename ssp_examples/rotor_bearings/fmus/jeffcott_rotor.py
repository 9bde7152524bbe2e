"""Jeffcott rotor on two displacement-driven bearing FMUs (FMI 2.0 co-simulation slave, pythonfmu).

Geometry (physical frame, SI): shaft axis z, gravity along -y, the shaft turns at shaft_speed about +z.
Bearing A sits at z = 0, bearing B at z = span, the disk (mass disk_mass, mass eccentricity
unbalance_eccentricity) at z = disk_position on a massless elastic shaft. The disk moves in x, y relative to
the chord through the two journals; the shaft spring (shaft_stiffness, 3 E I L / (a^2 b^2) for a point mass at
a, b from the supports) pulls it back; external viscous damping disk_damping acts on the disk.

Journals: massless (the classical Jeffcott rotor on flexible supports). Their coordinates q = (x_A, y_A, x_B, y_B,
z) (z: axial position of the rigid rotor) are in quasi-static equilibrium between the shaft spring, the bearing
reactions and axial_load. The journals follow the chord: tilt of each inner ring tx = -(y_B - y_A)/span,
ty = (x_B - x_A)/span, so the bearings' moment reactions act on the rotor as force couples +-M/span (virtual work).

Bearing frames: bearing A's frame is the physical one. Bearing B is mounted the other way round (the pair is
preloaded against each other); its frame is the mirror image z' = -z, so that both bearing FMUs see their own
+z as the direction that loads them: vectors (d, v, F) change the sign of z, axial vectors (tilts, tilt rates,
moments) change the sign of x and y; the shaft speed about +z' equals the one about +z. Fixed-position preload:
at z = 0 each bearing is pushed preload_A / preload_B into its contact direction (own dz).

Co-simulation coupling (explicit, Jacobi masters such as fmpy's simulate_ssp and libcosim's fixed-step
algorithm): the reactions received at the start of a step were computed by the bearings from the pose this rotor
sent one step earlier. The journal equilibrium uses them through an interface Jacobian: reaction(q) = received
+ G (pose(q) - pose_sent), G = -diag(k_xx, k_yy, k_zz, 0, 0) in each bearing frame (the parameters
A_kxx ... B_kzz). Across steps this is a fixed-point iteration on the journal positions that converges (linear
bearing) when the bearing's true stiffness lies between 0 and twice the estimate, and its converged (steady) result does
not depend on the estimate. make_ssp.py sets the estimate to twice the bearings' quasi-static stiffness at the
static equilibrium: the bearing's reaction one step after a pose step overshoots its static value ~1.4x (ball
inertia), and with the estimate equal to the static stiffness the loop oscillated at ~550 Hz and grew (measured,
7218B, h = 1e-4 s); 1.5x, 2x and 3x gave the same, stable result. (Massless journals cannot be coupled by a
plain exchange at all: their position is set by the bearing force itself.)
"""
from __future__ import annotations

import math

import numpy as np
from pythonfmu import Fmi2Causality, Fmi2Slave, Fmi2Variability, Real
from pythonfmu.enums import Fmi2Initial

POSE = ("dx", "dy", "dz", "tx", "ty")
RATE = ("vx", "vy", "vz", "wx", "wy")
REAC = ("Fx", "Fy", "Fz", "Mx", "My")
MIRROR = np.array([1.0, 1.0, -1.0, -1.0, -1.0])   # bearing B frame: z' = -z (on poses, rates and reactions)

PARAMS = (
    # name, start, unit, description
    ("disk_mass", 100.0, "kg", "disk mass (the shaft's mass lumped into it)"),
    ("unbalance_eccentricity", 20e-6, "m", "mass eccentricity of the disk"),
    ("shaft_stiffness", 7.0e6, "N/m", "lateral stiffness of the shaft at the disk relative to the journal chord"),
    ("disk_damping", 1000.0, "N.s/m", "external viscous damping on the disk"),
    ("span", 1.0, "m", "distance between the bearing centres (A at z = 0, B at z = span)"),
    ("disk_position", 0.4, "m", "axial position of the disk, from bearing A"),
    ("gravity", 9.81, "m/s2", "gravity, acting along -y"),
    ("axial_load", 0.0, "N", "external axial force on the rotor along +z"),
    ("preload_A", 0.0, "m", "fixed-position preload of bearing A (its own dz at z = 0)"),
    ("preload_B", 0.0, "m", "fixed-position preload of bearing B (its own dz at z = 0)"),
    ("A_kxx", 1e8, "N/m", "interface stiffness estimate of bearing A, x"),
    ("A_kyy", 1e8, "N/m", "interface stiffness estimate of bearing A, y"),
    ("A_kzz", 1e8, "N/m", "interface stiffness estimate of bearing A, z"),
    ("B_kxx", 1e8, "N/m", "interface stiffness estimate of bearing B, x (own frame)"),
    ("B_kyy", 1e8, "N/m", "interface stiffness estimate of bearing B, y (own frame)"),
    ("B_kzz", 1e8, "N/m", "interface stiffness estimate of bearing B, z (own frame)"),
    ("x_A0", 0.0, "m", "initial journal A x"), ("y_A0", 0.0, "m", "initial journal A y"),
    ("x_B0", 0.0, "m", "initial journal B x"), ("y_B0", 0.0, "m", "initial journal B y"),
    ("z0", 0.0, "m", "initial axial position"),
    ("disk_x0", 0.0, "m", "initial (static) disk x"), ("disk_y0", 0.0, "m", "initial (static) disk y"),
    ("max_substep", 2.5e-5, "s", "largest internal RK4 step of the disk motion"),
)
INPUTS = [("shaft_speed", "rad/s", "shaft speed about +z"), ("shaft_accel", "rad/s2", "shaft angular acceleration")]
INPUTS += [(f"{b}_{r}", "N.m" if r[0] == "M" else "N", f"reaction of bearing {b} on the shaft, {r} (bearing frame)")
           for b in "AB" for r in REAC]
OUTPUTS = [(f"{b}_{p}", "rad" if p[0] == "t" else "m", f"inner-ring pose of bearing {b}, {p} (bearing frame)")
           for b in "AB" for p in POSE]
OUTPUTS += [(f"{b}_{p}", "rad/s" if p[0] == "w" else "m/s", f"inner-ring rate of bearing {b}, {p} (bearing frame)")
            for b in "AB" for p in RATE]
OUTPUTS += [("disk_x", "m", "disk centre x"), ("disk_y", "m", "disk centre y"),
            ("disk_whirl", "m", "distance of the disk centre from its static position"),
            ("rotor_angle", "rad", "angle of the unbalance (0 along +x at t = 0)"),
            ("kinetic_energy", "J", "translational kinetic energy of the disk")]


class JeffcottRotor(Fmi2Slave):
    author = "bearing-tribodynamics ssp_examples"
    description = "Jeffcott rotor with unbalance on two displacement-driven bearings (interface-Jacobian coupling)"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        for name, start, unit, desc in PARAMS:
            setattr(self, name, start)
            self.register_variable(Real(name, causality=Fmi2Causality.parameter, variability=Fmi2Variability.fixed,
                                        initial=Fmi2Initial.exact, description=f"{desc} [{unit}]"))
        for name, unit, desc in INPUTS:
            setattr(self, name, 0.0)
            self.register_variable(Real(name, causality=Fmi2Causality.input, variability=Fmi2Variability.continuous,
                                        description=f"{desc} [{unit}]"))
        for name, unit, desc in OUTPUTS:
            setattr(self, name, 0.0)
            self.register_variable(Real(name, causality=Fmi2Causality.output,
                                        variability=Fmi2Variability.continuous, initial=Fmi2Initial.calculated,
                                        description=f"{desc} [{unit}]"))
        self._ready = False

    # ---- set-up ---------------------------------------------------------------------------------
    def _setup(self):
        L, a = float(self.span), float(self.disk_position)
        b = L - a
        self._bx = np.array([b / L, 0.0, a / L, 0.0, 0.0])
        self._by = np.array([0.0, b / L, 0.0, a / L, 0.0])
        TA = np.zeros((5, 5)); TB = np.zeros((5, 5))
        for T, ix, iy in ((TA, 0, 1), (TB, 2, 3)):
            T[0, ix] = 1.0; T[1, iy] = 1.0; T[2, 4] = 1.0
            T[3, 1] = 1.0 / L; T[3, 3] = -1.0 / L          # tx = -(y_B - y_A) / L
            T[4, 0] = -1.0 / L; T[4, 2] = 1.0 / L          # ty = (x_B - x_A) / L
        self._T = (TA, TB)
        self._S = (np.ones(5), MIRROR)
        self._c = (np.array([0, 0, self.preload_A, 0, 0.0]), np.array([0, 0, self.preload_B, 0, 0.0]))
        GA = -np.diag([self.A_kxx, self.A_kyy, self.A_kzz, 0.0, 0.0])
        GB = -np.diag([self.B_kxx, self.B_kyy, self.B_kzz, 0.0, 0.0])   # diagonal: S G S = G
        self._H = TA.T @ GA @ TA + TB.T @ GB @ TB
        ks = float(self.shaft_stiffness)
        self._A = self._H - ks * (np.outer(self._bx, self._bx) + np.outer(self._by, self._by))
        self._Ainv = np.linalg.inv(self._A)
        self._Cx = self._Ainv @ (-ks * self._bx)
        self._Cy = self._Ainv @ (-ks * self._by)
        self._q = np.array([self.x_A0, self.y_A0, self.x_B0, self.y_B0, self.z0], dtype=float)
        self._q_prev = self._q.copy()
        self._s = np.array([self.disk_x0, self.disk_y0, 0.0, 0.0])   # disk x, y, vx, vy
        self._phi = 0.0
        self._qdot = np.zeros(5)
        self._ready = True
        self._publish()

    def enter_initialization_mode(self):
        # outputs depend on parameters only: publish them already here, so that masters that propagate initial
        # values during initialisation (libcosim) hand the bearings the right pose before they initialise
        self._setup()

    def exit_initialization_mode(self):
        self._setup()

    def _reactions(self):
        """Bearing reactions on the shaft in the physical frame."""
        out = []
        for b, S in zip("AB", self._S):
            r = np.array([getattr(self, f"{b}_{k}") for k in REAC], dtype=float)
            out.append(S * r)
        return out

    def _publish(self):
        q, qd = self._q, self._qdot
        for b, T, S, c in zip("AB", self._T, self._S, self._c):
            pose = S * (T @ q) + c
            rate = S * (T @ qd)
            for k, v in zip(POSE, pose):
                setattr(self, f"{b}_{k}", float(v))
            for k, v in zip(RATE, rate):
                setattr(self, f"{b}_{k}", float(v))
        x, y, vx, vy = self._s
        self.disk_x, self.disk_y = float(x), float(y)
        self.disk_whirl = float(math.hypot(x - self.disk_x0, y - self.disk_y0))
        self.rotor_angle = float(self._phi)
        self.kinetic_energy = float(0.5 * self.disk_mass * (vx * vx + vy * vy))

    # ---- time step ------------------------------------------------------------------------------
    def do_step(self, current_time, step_size):
        if not self._ready:
            return False
        RA, RB = self._reactions()
        q_sent = self._q_prev                     # the pose the bearings used for the reactions we hold now
        rhs0 = self._H @ q_sent - self._T[0].T @ RA - self._T[1].T @ RB - np.array([0, 0, 0, 0, self.axial_load])
        q0 = self._Ainv @ rhs0                    # q = q0 + Cx x_d + Cy y_d
        Cx, Cy, bx, by = self._Cx, self._Cy, self._bx, self._by
        m, e, c, ks, g = self.disk_mass, self.unbalance_eccentricity, self.disk_damping, self.shaft_stiffness, self.gravity
        w0, al = float(self.shaft_speed), float(self.shaft_accel)
        phi0 = self._phi

        def f(tau, s):
            x, y, vx, vy = s
            q = q0 + Cx * x + Cy * y
            rx = x - bx @ q
            ry = y - by @ q
            w = w0 + al * tau
            ph = phi0 + w0 * tau + 0.5 * al * tau * tau
            cp, sp = math.cos(ph), math.sin(ph)
            fx = -ks * rx - c * vx + m * e * (w * w * cp + al * sp)
            fy = -ks * ry - c * vy - m * g + m * e * (w * w * sp - al * cp)
            return np.array([vx, vy, fx / m, fy / m])

        n = max(1, int(math.ceil(step_size / self.max_substep - 1e-9)))
        dt = step_size / n
        s = self._s.copy()
        tau = 0.0
        for _ in range(n):
            k1 = f(tau, s)
            k2 = f(tau + 0.5 * dt, s + 0.5 * dt * k1)
            k3 = f(tau + 0.5 * dt, s + 0.5 * dt * k2)
            k4 = f(tau + dt, s + dt * k3)
            s = s + dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
            tau += dt
        self._s = s
        self._phi = phi0 + w0 * step_size + 0.5 * al * step_size ** 2
        self._q_prev = self._q
        self._q = q0 + Cx * s[0] + Cy * s[1]
        self._qdot = Cx * s[2] + Cy * s[3]
        self._publish()
        return True
