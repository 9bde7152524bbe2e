"""Ball kinematics of the quasi-static (Jones-Harris) model: orbital speed, ball spin speed and its
attitude angle, spin and rolling speeds at each contact, for a rotating inner ring and a fixed outer ring.

Frames and signs (used throughout bearing_core): the bearing axis is z, the inner ring turns at
omega > 0 about +z. For a ball at azimuth psi (from +x towards +y) the local in-plane unit vectors are
r (radially out) and z, and t = z x r is the direction of orbital motion. The unit vector from the
ball centre to the outer contact is n_o = (cos ao, sin ao) and to the inner contact
n_i = (-cos ai, -sin ai) in (r, z). The ball's angular velocity relative to the cage frame (which
turns at omega_m) is omega_R * (-sin(beta), cos(beta)) in (r, z), with beta the attitude (pitch) angle
of Harris & Kotzalas; omega_R < 0 for omega > 0 (Harris's sign).

Pure rolling at the contact centres in the rolling direction (Jones 1960, Harris & Kotzalas 5th ed.
Vol. 2 Ch. 3) gives
    outer:  omega_R (D/2) cos(ao - beta) + omega_m (dm/2) (1 + D cos(ao)/dm) = 0
    inner:  omega_R (D/2) cos(ai - beta) + (omega - omega_m) (dm/2) (1 - D cos(ai)/dm) = 0
and raceway control fixes beta:
    outer control (no spin on the outer race): tan(beta) = sin(ao) / (cos(ao) + D/dm)
    inner control (no spin on the inner race): tan(beta) = sin(ai) / (cos(ai) - D/dm)
All functions are numpy-vectorised; angles in rad, speeds in rad/s.
"""
from __future__ import annotations

import numpy as np

CONTROL_MODES = ("outer", "inner", "hybrid")


def attitude_outer(alpha_o, gamma):
    """beta for outer raceway control; gamma = D/dm."""
    return np.arctan2(np.sin(alpha_o), np.cos(alpha_o) + gamma)


def attitude_inner(alpha_i, gamma):
    """beta for inner raceway control; gamma = D/dm."""
    return np.arctan2(np.sin(alpha_i), np.cos(alpha_i) - gamma)


def ball_speeds(omega, alpha_i, alpha_o, beta, D, dm):
    """Orbital speed omega_m and ball spin speed omega_R [rad/s] from pure rolling at both contact
    centres (see module docstring), for inner-ring speed omega [rad/s]."""
    gi = D * np.cos(alpha_i) / dm
    go = D * np.cos(alpha_o) / dm
    ci = np.cos(alpha_i - beta)
    co = np.cos(alpha_o - beta)
    omega_m = omega * (1.0 - gi) / ((1.0 - gi) + (1.0 + go) * ci / co)
    omega_R = -omega_m * dm * (1.0 + go) / (D * co)
    return omega_m, omega_R


def contact_spin_roll(omega, omega_m, omega_R, beta, alpha_i, alpha_o):
    """Spin and rolling angular speeds of the ball relative to each raceway [rad/s].

    Returns (spin_i, roll_i, spin_o, roll_o): spin = (ball rel. angular velocity) . n (signed),
    roll = magnitude of its component perpendicular to n. Spin-to-roll ratio = spin / roll
    (Harris & Kotzalas Vol. 2 Ch. 3; seed 003 Table 2 'spin-to-roll ratio')."""
    wr = -omega_R * np.sin(beta)
    wz = omega_R * np.cos(beta)
    # relative to inner ring (turning at omega - omega_m in the cage frame)
    wzi = wz - (omega - omega_m)
    nir, niz = -np.cos(alpha_i), -np.sin(alpha_i)
    spin_i = wr * nir + wzi * niz
    roll_i = np.abs(-wr * niz + wzi * nir)  # in-plane perpendicular component (t-component is 0)
    wzo = wz + omega_m
    nor, noz = np.cos(alpha_o), np.sin(alpha_o)
    spin_o = wr * nor + wzo * noz
    roll_o = np.abs(-wr * noz + wzo * nor)
    return spin_i, roll_i, spin_o, roll_o


def kinematics(omega, alpha_i, alpha_o, D, dm, control="outer", outer_controls=None):
    """(beta, omega_m, omega_R) per ball for the chosen raceway control.

    control: 'outer' | 'inner' | 'hybrid'. For 'hybrid' pass ``outer_controls`` (bool array, True where
    the outer race controls, from Harris's criterion, see quasistatic.hybrid_outer_controls)."""
    gamma = D / dm
    if control == "outer":
        beta = attitude_outer(alpha_o, gamma)
    elif control == "inner":
        beta = attitude_inner(alpha_i, gamma)
    elif control == "hybrid":
        if outer_controls is None:
            outer_controls = np.ones_like(np.asarray(alpha_i, dtype=float), dtype=bool)
        beta = np.where(outer_controls, attitude_outer(alpha_o, gamma), attitude_inner(alpha_i, gamma))
    else:
        raise ValueError(f"control = {control!r}; allowed: outer | inner | hybrid")
    omega_m, omega_R = ball_speeds(omega, alpha_i, alpha_o, beta, D, dm)
    return beta, omega_m, omega_R


def rotating_inertia(Z, ball_mass, ball_inertia, cage_inertia, alpha_o, D, dm):
    """Rotating inertia of balls and cage referred to the cage speed, I_c = 2 KE / omega_m^2 [kg m^2], for
    pure rolling with outer raceway control at the outer contact angle alpha_o [rad] (numpy-vectorised).

    KE is the kinetic energy of the Z balls (mass ball_mass [kg], inertia ball_inertia [kg m^2] about a
    diameter) and the cage (polar inertia cage_inertia [kg m^2]), as the dynamic model sums it: each ball's
    orbital translation m (dm/2)^2 omega_m^2 / 2 and its absolute rotation J |w|^2 / 2, with w in (r, z) the
    spin omega_R (-sin beta, cos beta) relative to the cage plus the cage's omega_m about z (ball_speeds:
    omega_R / omega_m = -dm (1 + D cos ao / dm) / (D cos(ao - beta)); Harris & Kotzalas Vol. 2 Ch. 3). Ratios
    of speeds only, so I_c does not depend on the shaft speed. A speed change of the rotating parts then
    costs the drive dKE/dt = I_c omega_m d(omega_m)/dt."""
    alpha_o = np.asarray(alpha_o, dtype=float)
    beta = attitude_outer(alpha_o, D / dm)
    go = D * np.cos(alpha_o) / dm
    rho = -dm * (1.0 + go) / (D * np.cos(alpha_o - beta))     # omega_R / omega_m
    w2 = (rho * np.sin(beta)) ** 2 + (rho * np.cos(beta) + 1.0) ** 2
    return cage_inertia + Z * (ball_mass * (0.5 * dm) ** 2 + ball_inertia * w2)
