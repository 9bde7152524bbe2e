"""Pure rolling lines (PRLs) and Coulomb spinning friction in the ball-race contacts of an angular-contact
ball bearing (seed 004: Rivera, Tong, Hong, J. Korean Soc. Precis. Eng. 38(11) 851-862, 2021; Houpert,
Proc. 8th ESMATS 1999; Popescu, Houpert, Olaru, Mech. Mach. Theory 144 (2020) 103669).

Units: SI throughout (m, N, s, rad, rad/s, m/s, N m). Frames and signs are those of
``bearing_core.contact.kinematics``: per ball, in-plane axes (r, z) and t = z x r (direction of orbital motion);
n_o = (cos ao, sin ao), n_i = (-cos ai, -sin ai) from the ball centre to the contacts; the ball turns
relative to the cage frame with Omega = omega_R (-sin beta, cos beta), the inner race with
(omega - omega_m) about z and the outer race with -omega_m.

Contact frame (both races): x along the major axis, unit vector m_k = (-sin alpha_k, cos alpha_k) in (r, z)
(towards the +z side of the contact line, the same physical direction at both contacts), y along t (rolling
direction). In normal operation (omega > 0) the ball's rolling angular velocity relative to either race has
w . m_k < 0, which makes E_k = 2 R_k tan(gamma_k) / a_k = (2 R_k / a_k) spin_k / roll_k with spin_k the
kinematics.py spin (w . n_k) and roll_k = |w . m_k|.

Deformed contact surface (seed 004 Eqs. 1-2, 5): the point of the major axis at x in [-a, a] is
p(x) = rho(x) n_k + x m_k from the ball centre, with
    rho(x) = sqrt(R^2 - x^2) - sqrt(R^2 - a^2) + sqrt((D/2)^2 - a^2),   R_k = 2 f_k D / (2 f_k + 1).
Sliding velocity of the ball relative to race k (w = Omega - omega_race z):
    v_y(x) = (w_z p_r - w_r p_z) - omega_race dm/2 = V0 + Vrho rho(x) + Vx x        [m/s]
    v_x(y) = -Vx y        (the spin part: a rigid rotation at the rate Vx about e3 = m x t)
Vx = -spin_o (outer), +spin_i (inner); y in [-b(x), b(x)]. Gyroscopic pivoting (sliding along x apart from
spin) is neglected, as in seed 004 section 3.4.

Houpert's c-values (c = x / a at the PRLs; derivation in ``houpert_c``): with a Hertz line load
q(x) = 3 Q / (4 a) (1 - x^2/a^2) along the major axis and Coulomb friction whose direction changes at each
PRL, the net rolling-direction friction force relative to mu Q, e = F / (mu Q), is
    two PRLs c1 < c2 (sign pattern s, -s, s):  e = s [1 + 3/2 (c1 - c2) - (c1^3 - c2^3)/2]
    one PRL c (other root outside):            e = +-(3/2) s (c - c^3/3)
with c1 + c2 = E (root sum of the parabola v_y ~ A0 + A1 x + A2 x^2). For e = 0 (no drag, no cage force):
    |E| < 1: two PRLs, c_{1,2} = E/2 -+ d, d the middle root of d^3 + (3 E^2/4 - 3) d + 1 = 0
             (E = 0: c = +-0.3473; E -> +-1: c -> (0, 1) or (-1, 0));
    |E| >= 1: one PRL at c = 0 (pure rolling at the contact centre), the second root x = E a lies outside.
Spinning friction moment (magnitude) from c-values, seed 004 Eqs. 22-23 (the strip integral of x q(x)):
    two PRLs: m_s = 3/8 mu Q a [2 (c1^2 - c2^2) - (c1^4 - c2^4)]      one PRL: m_s = 3/8 mu Q a (1 - c^2)^2
and by full integration over the ellipse (seed 004 Eq. 19) with the 2-D sliding direction (v_x, v_y).
Bearing spin torque, Eq. 24: M_s = sum_j (m_s,i sin(alpha_i) + m_s,o sin(alpha_o)).

Sign conventions of the returned signed quantities: e = (net friction force on the ball along +t) / (mu Q);
``spin_moment_full`` / ``spin_moment_strip`` return the friction moment on the ball about e3 = m_k x t
(= -n_o at the outer, +n_i at the inner contact); ``moment_about_normal`` converts to the moment about n_k,
which opposes the spin where spin dominates. Eqs. 22-23 neglect the minor-axis extent of the contact: the
full integral exceeds them by a relative amount growing like (b/a)^2 (about 3.5 % at b/a = 0.11, seed 004
bearing at rest; tests/test_spin_friction.py).

Deviations from seed 004: (i) our x axis is m_k above, so c1 + c2 = +E
(seed Eq. 13 writes -2 R tan(gamma) / a = c1 + c2; its c-values are ours mirrored, c_seed = -c_ours);
(ii) v_y contains the spin term Vx x explicitly (the PRLs are the zeros of the full rolling-direction slip);
(iii) ball speeds at e = 0 are found per ball from the exact v_y(x) profile with beta fixed (seed Eq. 6 by
default); (iv) at omega = 0 the kinematic limit omega -> 0+ is used (Coulomb results do not depend on the
speed magnitude); (v) seed Eq. 15 evaluates E with the approximation tan(gamma_k) = (D/dm) sin(alpha_k)
(exact only when beta = alpha_k, e.g. at rest); ``E_eq15`` provides it, ``SlipProfile.E`` / ``analyse`` use the
exact spin-to-roll ratio of the kinematics by default (``E_model``).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import kinematics as kin
__all__ = [
    "deformed_radius", "contact_axes", "rho_profile", "SlipProfile", "slip_profile", "prl_exact",
    "traction_ratio", "houpert_c", "houpert_e", "spin_moment_c", "spin_moment_strip", "spin_moment_full",
    "parabola_root_sum", "E_eq15", "moment_about_normal", "equilibrium_speeds", "SpinFrictionResult", "analyse",
]


# ---------------------------------------------------------------------------------------------------
# geometry of the deformed contact
# ---------------------------------------------------------------------------------------------------
def deformed_radius(f, D):
    """Radius of the deformed contact surface R_k = 2 f_k D / (2 f_k + 1) [m] (seed 004 Eq. 5);
    f: groove conformity r/D [-], D: ball diameter [m]."""
    f = np.asarray(f, dtype=float)
    return 2.0 * f * D / (2.0 * f + 1.0)


def contact_axes(alpha, race):
    """Unit vectors (n, m) in (r, z) of contact ``race`` ('i' | 'o') at contact angle(s) alpha [rad]:
    n from the ball centre to the contact (kinematics.py), m = (-sin alpha, cos alpha) along the major axis.
    Returns (n_r, n_z, m_r, m_z)."""
    alpha = np.asarray(alpha, dtype=float)
    c, s = np.cos(alpha), np.sin(alpha)
    sg = -1.0 if _race(race) == "i" else 1.0
    return sg * c, sg * s, -s, c


def rho_profile(x, a, R, D):
    """Distance from the ball centre, along n, of the deformed surface point at major-axis coordinate x [m]:
    rho(x) = sqrt(R^2 - x^2) - sqrt(R^2 - a^2) + sqrt((D/2)^2 - a^2) (seed 004 Eqs. 1-2). a: semi-major axis,
    R: deformed-surface radius, D: ball diameter [m]. Broadcasts."""
    return np.sqrt(R * R - x * x) - np.sqrt(R * R - a * a) + np.sqrt(0.25 * D * D - a * a)


def _race(race):
    r = str(race).lower()[:1]
    if r not in ("i", "o"):
        raise ValueError(f"race = {race!r}; allowed: 'i' (inner) | 'o' (outer)")
    return r


# ---------------------------------------------------------------------------------------------------
# sliding velocity
# ---------------------------------------------------------------------------------------------------
@dataclass
class SlipProfile:
    """Sliding velocity of the ball relative to one race along the contact's major axis (arrays, one entry
    per contact, or scalars):

        v_y(x) = V0 + Vrho * rho(x) + Vx * x     [m/s],   x in [-a, a]
        v_x(y) = -Vx * y                          [m/s]

    V0 [m/s], Vrho, Vx [rad/s]; a, b: Hertz semi-axes [m]; R: deformed-surface radius [m]; D: ball diameter
    [m]; Q: contact load [N]; spin: ball spin relative to the race (w . n) [rad/s]; roll: w . m [rad/s]
    (signed; < 0 in normal operation)."""

    V0: np.ndarray
    Vrho: np.ndarray
    Vx: np.ndarray
    a: np.ndarray
    b: np.ndarray
    R: np.ndarray
    D: float
    Q: np.ndarray
    spin: np.ndarray
    roll: np.ndarray

    def rho(self, x):
        """rho(x) [m] for x [m] (broadcast against the contact arrays: x[..., k] or x of shape (N, nx))."""
        a, R = _col(self.a, x), _col(self.R, x)
        return rho_profile(x, a, R, self.D)

    def v_y(self, x):
        """Rolling-direction sliding velocity [m/s] at major-axis coordinate x [m]. x may be an array of shape
        (N, ...) for N contacts (the trailing axes broadcast) or anything broadcastable for scalars."""
        return _col(self.V0, x) + _col(self.Vrho, x) * self.rho(x) + _col(self.Vx, x) * x

    def v_xy(self, x, y):
        """2-D sliding velocity (v_x, v_y) [m/s] at (x, y) in the contact ellipse [m]."""
        return -_col(self.Vx, y) * y, self.v_y(x)

    @property
    def E(self):
        """Houpert's E parameter = root sum c1 + c2 of the parabola v_y ~ A0 + A1 x + A2 x^2:
        E = -2 R Vx / (a Vrho) = -(2 R / a) spin / (w . m) = (2 R / a) spin / roll in normal operation
        (seed 004 Eqs. 13-15, 2 R tan(gamma) / a). NaN where undefined."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(np.abs(self.roll) > 0, -2.0 * self.R * self.spin / (self.a * self.roll), np.nan)

    def reversed_spin(self) -> "SlipProfile":
        """The mirror contact (x -> -x): same rolling, opposite spin; for sign/symmetry checks."""
        return SlipProfile(self.V0, self.Vrho, -self.Vx, self.a, self.b, self.R, self.D, self.Q,
                           -self.spin, self.roll)

    def scaled(self, k) -> "SlipProfile":
        """All velocities multiplied by k (k < 0 reverses the motion)."""
        return SlipProfile(k * self.V0, k * self.Vrho, k * self.Vx, self.a, self.b, self.R, self.D, self.Q,
                           k * self.spin, k * self.roll)


def _col(v, x):
    """Reshape a per-contact array v (N,) so it broadcasts against x of shape (N, ...)."""
    v = np.asarray(v, dtype=float)
    xa = np.asarray(x)
    if v.ndim == 1 and xa.ndim > 1:
        return v.reshape(v.shape + (1,) * (xa.ndim - 1))
    return v


def slip_profile(omega, omega_m, omega_R, beta, alpha, a, b, Q, D, dm, f, race) -> SlipProfile:
    """SlipProfile of contact ``race`` ('i' | 'o') (seed 004 Eqs. 1-5, frames of kinematics.py).

    omega: inner-ring speed [rad/s]; omega_m: orbital speed [rad/s]; omega_R: ball speed relative to the
    cage [rad/s] (< 0 for omega > 0); beta: attitude angle [rad]; alpha: contact angle [rad]; a, b: Hertz
    semi-axes [m]; Q: contact load [N]; D, dm: ball and pitch diameter [m]; f: groove conformity [-].
    All per-ball inputs broadcast."""
    r = _race(race)
    omega_m, omega_R, beta, alpha, a, b, Q = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (
        omega_m, omega_R, beta, alpha, a, b, Q)))
    w_race = (omega - omega_m) if r == "i" else -omega_m
    wr = -omega_R * np.sin(beta)
    wz = omega_R * np.cos(beta) - w_race
    nr, nz, mr, mz = contact_axes(alpha, r)
    spin = wr * nr + wz * nz
    roll = wr * mr + wz * mz
    # rolling-direction (t) velocity of the ball relative to the race at p: w_z p_r - w_r p_z - w_race dm/2
    Vrho = wz * nr - wr * nz
    Vx = wz * mr - wr * mz
    V0 = -w_race * 0.5 * dm
    R = deformed_radius(f, D) * np.ones_like(a)
    return SlipProfile(V0=V0, Vrho=Vrho, Vx=Vx, a=a, b=b, R=R, D=float(D), Q=Q, spin=spin, roll=roll)


# ---------------------------------------------------------------------------------------------------
# pure rolling lines from the exact profile
# ---------------------------------------------------------------------------------------------------
def prl_exact(p: SlipProfile, tol: float = 1e-12):
    """Zero crossings of the exact v_y(x) in [-a, a] (the pure rolling lines), in closed form.

    v_y = 0  <=>  Vrho sqrt(R^2 - x^2) = -(L + Vx x),  L = V0 + Vrho (sqrt((D/2)^2 - a^2) - sqrt(R^2 - a^2)),
    squared: (Vrho^2 + Vx^2) x^2 + 2 L Vx x + L^2 - Vrho^2 R^2 = 0, keeping the roots of the right sign.
    Since rho(x) is concave, v_y has at most two zeros. Returns (c1, c2, n) with c = x / a, c1 <= c2,
    NaN where absent (a single PRL is returned in c1), n = number of PRLs (0, 1, 2)."""
    a = np.asarray(p.a, dtype=float)
    V0, Vr, Vx, R = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (p.V0, p.Vrho, p.Vx, p.R)))
    L = V0 + Vr * (np.sqrt(0.25 * p.D ** 2 - a * a) - np.sqrt(R * R - a * a))
    A = Vr * Vr + Vx * Vx
    B = 2.0 * L * Vx
    C = L * L - Vr * Vr * R * R
    with np.errstate(divide="ignore", invalid="ignore"):
        disc = B * B - 4.0 * A * C
        sq = np.sqrt(np.maximum(disc, 0.0))
        # numerically stable quadratic roots
        qq = -0.5 * (B + np.where(B >= 0, 1.0, -1.0) * sq)
        x1 = np.where(qq != 0, C / qq, np.nan)
        x2 = np.where(A != 0, qq / A, np.nan)
        roots = np.stack([x1, x2], axis=-1)
        ok = (disc >= 0)[..., None] & np.isfinite(roots)
        # sign condition: -(L + Vx x) must have the sign of Vrho (or vanish)
        rhs = -(L[..., None] + Vx[..., None] * roots)
        scale = np.abs(L)[..., None] + np.abs(Vx * a)[..., None] + np.abs(Vr * R)[..., None]
        ok &= rhs * np.sign(Vr)[..., None] >= -1e-9 * scale
        ok &= np.abs(roots) <= a[..., None] * (1.0 + tol)
        c = np.where(ok, np.clip(roots / a[..., None], -1.0, 1.0), np.nan)
    # a double root (tangency) counts once
    same = np.isfinite(c[..., 0]) & np.isfinite(c[..., 1]) & (np.abs(c[..., 0] - c[..., 1]) < 1e-12)
    c[..., 1] = np.where(same, np.nan, c[..., 1])
    c = np.sort(c, axis=-1)  # NaN last
    n = np.sum(np.isfinite(c), axis=-1)
    return c[..., 0], c[..., 1], n


def _G(c):
    """Fraction of the Hertz line load on [-1, c]: G(c) = (2 + 3 c - c^3) / 4."""
    return 0.25 * (2.0 + 3.0 * c - c ** 3)


def _H(c):
    """int_0^c (3/4) t (1 - t^2) dt = (3/16) (2 c^2 - c^4)."""
    return 0.1875 * (2.0 * c * c - c ** 4)


def _segments(p: SlipProfile, c1, c2):
    """Breakpoints [-1, c1, c2, 1] (NaN -> pushed to 1) and the sign of v_y on each of the 3 segments."""
    a = np.asarray(p.a, dtype=float)
    k1 = np.where(np.isfinite(c1), c1, 1.0)
    k2 = np.where(np.isfinite(c2), c2, 1.0)
    br = np.stack([-np.ones_like(k1), k1, k2, np.ones_like(k1)], axis=-1)
    mid = 0.5 * (br[..., :-1] + br[..., 1:])
    # sign at the segment middles; for an empty segment use the neighbour (does not matter: zero weight)
    sgn = np.sign(p.v_y(mid * a[..., None]) if a.ndim else p.v_y(mid * a))
    return br, sgn


def traction_ratio(p: SlipProfile, c=None):
    """Net Coulomb friction force on the ball in the rolling direction (+t) relative to mu Q (Houpert's e):
    e = -(1/Q) int q(x) sign(v_y(x)) dx with q(x) = 3Q/(4a)(1 - x^2/a^2), evaluated exactly from the zeros of
    the exact profile (``prl_exact``) [-]. ``c``: optionally (c1, c2, n) already computed."""
    c1, c2, _ = prl_exact(p) if c is None else c
    br, sgn = _segments(p, c1, c2)
    w = _G(br[..., 1:]) - _G(br[..., :-1])
    return -np.sum(sgn * w, axis=-1)


# ---------------------------------------------------------------------------------------------------
# Houpert's analytical c-values
# ---------------------------------------------------------------------------------------------------
def houpert_e(c1, c2=np.nan, s=1.0):
    """Houpert's e from c-values (strip integration of the Hertz line load, sliding direction changing at
    each PRL). Two PRLs c1 < c2 with sign pattern (s, -s, s) of the friction force over [-1, c1], [c1, c2],
    [c2, 1]: e = s [1 + 3/2 (c1 - c2) - (c1^3 - c2^3)/2]. One PRL (c2 = NaN), pattern (s, -s):
    e = s (3 c - c^3) / 2 = (3/2) s (c - c^3/3)."""
    c1 = np.asarray(c1, dtype=float)
    c2 = np.asarray(c2, dtype=float)
    two = s * (1.0 + 1.5 * (c1 - c2) - 0.5 * (c1 ** 3 - c2 ** 3))
    one = s * 0.5 * (3.0 * c1 - c1 ** 3)
    return np.where(np.isfinite(c2), two, one)


def houpert_c(E, e=0.0):
    """c-values of the PRLs from Houpert's E parameter and the traction ratio e (Houpert 1999; Popescu,
    Houpert, Olaru 2020; seed 004 Eqs. 13-16).

    ``e`` is measured relative to the sliding direction outside the root pair (e = +1: the whole contact
    slides that way; e = 0: no net traction). Derivation (c1 = E/2 - d, c2 = E/2 + d, load fraction
    G(c) = (2 + 3c - c^3)/4 on [-1, c]):
      two PRLs:  e = 1 + 2 G(c1) - 2 G(c2) = 1 - 3 d + d (3 E^2/4 + d^2)
                 -> d^3 + (3 E^2/4 - 3) d + (1 - e) = 0, middle root; valid while |E|/2 + d <= 1;
      one PRL (the other root E - c outside [-1, 1]):  sign(E) e = (3 c - c^3)/2
                 -> c = 2 sin(arcsin(sign(E) e) / 3).
    For e = 0: two PRLs for |E| < 1 (c -> (0, 1) as E -> 1), one PRL at c = 0 for |E| >= 1.
    Returns (c1, c2, n) like ``prl_exact`` (NaN where absent)."""
    E = np.asarray(E, dtype=float)
    e = np.broadcast_to(np.asarray(e, dtype=float), E.shape)
    pcoef = 0.75 * E * E - 3.0
    qcoef = 1.0 - e
    with np.errstate(invalid="ignore", divide="ignore"):
        # three real roots when 4 p^3 + 27 q^2 < 0 (p < 0 here for |E| < 2)
        mag = 2.0 * np.sqrt(np.maximum(-pcoef / 3.0, 0.0))
        arg = np.clip(3.0 * qcoef / (pcoef * mag), -1.0, 1.0)  # (3q/2p) sqrt(-3/p)
        th = np.arccos(arg) / 3.0
        roots = np.stack([mag * np.cos(th - 2.0 * np.pi * k / 3.0) for k in range(3)], axis=-1)
        real3 = (4.0 * pcoef ** 3 + 27.0 * qcoef ** 2 <= 0) & (pcoef < 0)
        d = np.sort(roots, axis=-1)[..., 1]
        two_ok = real3 & (d > 0) & (0.5 * np.abs(E) + d <= 1.0 + 1e-12)
        c1_two = 0.5 * E - d
        c2_two = 0.5 * E + d
        t = np.sign(E) * e
        c_one = 2.0 * np.sin(np.arcsin(np.clip(t, -1.0, 1.0)) / 3.0)
        one_ok = (~two_ok) & (np.abs(t) <= 1.0) & (np.abs(E - c_one) >= 1.0 - 1e-12) & np.isfinite(E)
    c1 = np.where(two_ok, c1_two, np.where(one_ok, c_one, np.nan))
    c2 = np.where(two_ok, c2_two, np.nan)
    c1 = np.clip(c1, -1.0, 1.0)
    c2 = np.clip(c2, -1.0, 1.0)
    n = np.where(two_ok, 2, np.where(one_ok, 1, 0))
    return c1, c2, n


def E_eq15(alpha, a, f, D, dm):
    """Seed 004 Eq. 15 approximation of Houpert's E: E_k = (2 R_k / a_k) (D / dm) sin(alpha_k), i.e. the
    spin-to-roll ratio tan(gamma_k) taken as (D/dm) sin(alpha_k) (exact when the ball axis attitude equals
    the contact angle, e.g. at rest with alpha_i = alpha_o = beta). alpha [rad], a [m], f [-], D, dm [m]."""
    return 2.0 * deformed_radius(f, D) / np.asarray(a, dtype=float) * (D / dm) * np.sin(alpha)


def parabola_root_sum(p: SlipProfile, n: int = 201):
    """Least-squares parabola v_y(c a) ~ A0 + A1 c + A2 c^2 on c in [-1, 1] (n points) of the exact profile;
    returns its root sum -A1/A2 (to compare with E) and the coefficients (A0, A1, A2) [m/s]."""
    c = np.linspace(-1.0, 1.0, n)
    a = np.atleast_1d(np.asarray(p.a, dtype=float))
    pp = p if np.ndim(p.a) else SlipProfile(*(np.atleast_1d(v) if k != "D" else v for k, v in vars(p).items()))
    V = pp.v_y(c[None, :] * a[:, None])               # (N, n)
    Mx = np.vander(c, 3, increasing=True)             # (n, 3)
    coef, *_ = np.linalg.lstsq(Mx, V.T, rcond=None)   # (3, N)
    A0, A1, A2 = coef
    rs = -A1 / A2
    if not np.ndim(p.a):
        return rs[0], (A0[0], A1[0], A2[0])
    return rs, (A0, A1, A2)


# ---------------------------------------------------------------------------------------------------
# spinning friction moment
# ---------------------------------------------------------------------------------------------------
def spin_moment_c(c1, c2, Q, a, mu=0.1):
    """Spinning friction moment magnitude [N m] from c-values (seed 004 Eqs. 22-23; Houpert 1999):
    two PRLs: 3/8 mu Q a |2 (c1^2 - c2^2) - (c1^4 - c2^4)|; one PRL (c2 NaN): 3/8 mu Q a (1 - c1^2)^2;
    no PRL (c1 NaN): 0 (gross sliding, the rolling-direction force does not produce a spin moment in the
    strip model). Q [N], a [m]."""
    c1 = np.asarray(c1, dtype=float)
    c2 = np.asarray(c2, dtype=float)
    two = np.abs(2.0 * (c1 ** 2 - c2 ** 2) - (c1 ** 4 - c2 ** 4))
    one = (1.0 - c1 ** 2) ** 2
    val = np.where(np.isfinite(c2), two, np.where(np.isfinite(c1), one, 0.0))
    return 0.375 * mu * np.asarray(Q) * np.asarray(a) * val


def spin_moment_strip(p: SlipProfile, mu=0.1, c=None):
    """Signed spinning friction moment on the ball about e3 = m x t [N m] by strip integration of the Hertz
    line load with Coulomb friction along y only: m = -mu int x q(x) sign(v_y(x)) dx, using the zeros of the
    exact profile (its magnitude equals ``spin_moment_c`` of those zeros). Convert to the moment about n_k
    with ``moment_about_normal``."""
    c1, c2, _ = prl_exact(p) if c is None else c
    br, sgn = _segments(p, c1, c2)
    w = _H(br[..., 1:]) - _H(br[..., :-1])
    return -mu * np.asarray(p.Q) * np.asarray(p.a) * np.sum(sgn * w, axis=-1)


_GL_CACHE: dict = {}


def _gl(n):
    if n not in _GL_CACHE:
        _GL_CACHE[n] = np.polynomial.legendre.leggauss(n)
    return _GL_CACHE[n]


def spin_moment_full(p: SlipProfile, mu=0.1, nx: int = 48, ny: int = 48, split: bool = True):
    """Signed spinning friction moment on the ball about e3 = m x t [N m] by full integration over the
    contact ellipse (seed 004 Eqs. 17-21):

        m = int int (x dF_y - y dF_x),  dF = -mu p(x, y) (v_x, v_y)/|v| dA,
        p = 3 Q / (2 pi a b) sqrt(1 - x^2/a^2 - y^2/b^2),  (v_x, v_y) = (-Vx y, v_y(x)).

    Quadrature: x = a c with Gauss-Legendre (nx nodes) on each of the up to three sub-intervals of [-1, 1]
    between the PRLs (``split``; the integrand's y-integral has a |v| log|v| behaviour there); for each x,
    y = b sqrt(1 - c^2) sin(phi), phi in [-pi/2, pi/2] with Gauss-Legendre (ny nodes), which absorbs the
    square-root of the pressure (p dy = 3Q/(2 pi a b) b (1-c^2) cos^2(phi) dphi). Relative error about
    2e-5 at nx = ny = 16 and 1e-6 at 48 (tests/test_spin_friction.py)."""
    a = np.atleast_1d(np.asarray(p.a, dtype=float))
    b = np.atleast_1d(np.asarray(p.b, dtype=float))
    Q = np.atleast_1d(np.asarray(p.Q, dtype=float))
    Vx = np.atleast_1d(np.asarray(p.Vx, dtype=float)) * np.ones_like(a)
    pp = SlipProfile(*(np.atleast_1d(v) * np.ones_like(a) if k != "D" else v for k, v in vars(p).items()))
    N = a.size
    tx, wx = _gl(nx)
    tp, wp = _gl(ny)
    phi = 0.5 * np.pi * tp
    wphi = 0.5 * np.pi * wp
    if split:
        c1, c2, _ = prl_exact(pp)
        k1 = np.where(np.isfinite(c1), c1, 1.0)
        k2 = np.where(np.isfinite(c2), c2, 1.0)
        br = np.stack([-np.ones(N), k1, k2, np.ones(N)], axis=-1)  # (N, 4)
    else:
        br = np.stack([-np.ones(N), np.ones(N)], axis=-1)
    lo, hi = br[:, :-1], br[:, 1:]                                  # (N, S)
    half = 0.5 * (hi - lo)
    cx = (0.5 * (hi + lo))[..., None] + half[..., None] * tx       # (N, S, nx)
    wcx = half[..., None] * wx                                      # (N, S, nx)
    cx = cx.reshape(N, -1)
    wcx = wcx.reshape(N, -1)
    x = cx * a[:, None]
    vy = pp.v_y(x)                                                  # (N, M)
    hb = b[:, None] * np.sqrt(np.maximum(1.0 - cx * cx, 0.0))       # half chord (N, M)
    y = hb[..., None] * np.sin(phi)                                 # (N, M, ny)
    vx = -Vx[:, None, None] * y
    vyy = np.broadcast_to(vy[..., None], y.shape)
    speed = np.hypot(vx, vyy)
    with np.errstate(invalid="ignore", divide="ignore"):
        integrand = np.where(speed > 0, (x[..., None] * vyy - y * vx) / speed, 0.0)
    p0 = 1.5 * Q / (np.pi * a * b)
    inner = np.sum(integrand * (np.cos(phi) ** 2 * wphi), axis=-1) * hb * hb / b[:, None]  # (N, M)
    # (p0 sqrt(1-c^2) cos phi) (hb cos phi dphi) = p0 (hb^2 / b) cos^2 phi dphi, since sqrt(1-c^2) = hb / b
    m = -mu * p0 * np.sum(inner * wcx, axis=-1) * a
    return m if np.ndim(p.a) else m[0]


def moment_about_normal(m_e3, race):
    """Convert a moment about e3 = m x t to the moment about the contact normal n_k (ball centre to
    contact): e3 = -n_o at the outer, +n_i at the inner contact."""
    return -np.asarray(m_e3) if _race(race) == "o" else np.asarray(m_e3)


# ---------------------------------------------------------------------------------------------------
# ball speeds with zero net rolling-direction traction
# ---------------------------------------------------------------------------------------------------
def equilibrium_speeds(omega, alpha_i, alpha_o, beta, a_i, b_i, a_o, b_o, Q_i, Q_o, D, dm, fi, fo,
                       omega_m0=None, omega_R0=None, tol=1e-12, maxit=60):
    """Orbital and ball speeds (omega_m, omega_R) [rad/s] per ball with zero net Coulomb traction in the
    rolling direction at both contacts, e_i = e_o = 0, for the exact v_y(x) profiles and a fixed attitude
    beta [rad] (seed 004 section 3.3: 'equilibrium of frictional moments acting on individual balls').

    Start: rolling-at-centre speeds (kinematics.ball_speeds), then a fixed-point iteration on Houpert's
    analytical solution: E_k from the current speeds, target PRL c_k from ``houpert_c(E_k, 0)``, and the two
    conditions v_y,k(c_k a_k) = 0 (linear in the speeds) solved for (omega_m, omega_R). Finally a damped
    Newton iteration on the exact e_i, e_o (from the zeros of the exact profiles) with a finite-difference
    Jacobian, vectorised over the balls. omega must be non-zero (the results scale with omega).
    Returns (omega_m, omega_R, e_i, e_o, iterations)."""
    if omega == 0:
        raise ValueError("omega = 0: use the limit omega -> 0+ (scale the speeds), see analyse()")
    arrs = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (alpha_i, alpha_o, beta, a_i, b_i, a_o,
                                                                        b_o, Q_i, Q_o)))
    alpha_i, alpha_o, beta, a_i, b_i, a_o, b_o, Q_i, Q_o = (np.atleast_1d(v).copy() for v in arrs)
    if omega_m0 is None or omega_R0 is None:
        omega_m0, omega_R0 = kin.ball_speeds(omega, alpha_i, alpha_o, beta, D, dm)
    u = np.stack([np.broadcast_to(omega_m0, alpha_i.shape) / omega,
                  np.broadcast_to(omega_R0, alpha_i.shape) / omega], axis=-1).astype(float)

    def prof(uu):
        pi = slip_profile(omega, uu[:, 0] * omega, uu[:, 1] * omega, beta, alpha_i, a_i, b_i, Q_i, D, dm, fi, "i")
        po = slip_profile(omega, uu[:, 0] * omega, uu[:, 1] * omega, beta, alpha_o, a_o, b_o, Q_o, D, dm, fo, "o")
        return pi, po

    def res(uu):
        pi, po = prof(uu)
        return np.stack([traction_ratio(pi), traction_ratio(po)], axis=-1)

    # --- fixed point on Houpert's c-values (v_y linear in the speeds) ---
    zero = np.zeros_like(u)
    e0, e1, e2 = zero.copy(), zero.copy(), zero.copy()
    e1[:, 0] = 1.0
    e2[:, 1] = 1.0
    for _ in range(20):
        pi, po = prof(u)
        ct = []
        for p_ in (pi, po):
            c1, c2, n = houpert_c(p_.E, 0.0)
            # the PRL nearer the centre
            ct.append(np.where(n == 2, np.where(np.abs(c1) <= np.abs(c2), c1, c2), np.where(n == 1, c1, 0.0)))
        xi, xo = ct[0] * a_i, ct[1] * a_o
        vals = []
        for uu in (e0, e1, e2):
            qi, qo = prof(uu)
            vals.append((qi.v_y(xi), qo.v_y(xo)))
        (fi0, fo0), (fi1, fo1), (fi2, fo2) = vals
        M11, M12, M21, M22 = fi1 - fi0, fi2 - fi0, fo1 - fo0, fo2 - fo0
        det = M11 * M22 - M12 * M21
        un = np.stack([(-fi0 * M22 + fo0 * M12) / det, (-fo0 * M11 + fi0 * M21) / det], axis=-1)
        done = np.max(np.abs(un - u)) < 1e-13 * max(1.0, np.max(np.abs(u)))
        u = np.where(np.isfinite(un), un, u)
        if done:
            break

    r = res(u)
    it = 0
    for it in range(1, maxit + 1):
        if np.all(np.abs(r) < tol):
            break
        J = np.empty(u.shape + (2,))
        for k in range(2):
            h = 1e-7 * np.maximum(np.abs(u[:, k]), 1.0)
            up = u.copy()
            up[:, k] += h
            um = u.copy()
            um[:, k] -= h
            J[:, :, k] = (res(up) - res(um)) / (2 * h[:, None])
        det = J[:, 0, 0] * J[:, 1, 1] - J[:, 0, 1] * J[:, 1, 0]
        det = np.where(np.abs(det) > 0, det, np.inf)
        du0 = -(J[:, 1, 1] * r[:, 0] - J[:, 0, 1] * r[:, 1]) / det
        du1 = -(-J[:, 1, 0] * r[:, 0] + J[:, 0, 0] * r[:, 1]) / det
        du = np.stack([du0, du1], axis=-1)
        # damping: halve the step where the residual norm does not decrease
        lam = np.ones(u.shape[0])
        nr0 = np.max(np.abs(r), axis=-1)
        for _ in range(30):
            un = u + lam[:, None] * du
            rn = res(un)
            bad = np.max(np.abs(rn), axis=-1) > nr0 * (1 - 1e-4 * lam)
            bad &= nr0 > tol
            if not bad.any():
                break
            lam = np.where(bad, 0.5 * lam, lam)
        u, r = un, rn
    return u[:, 0] * omega, u[:, 1] * omega, r[:, 0], r[:, 1], it


# ---------------------------------------------------------------------------------------------------
# convenience: everything for a quasi-static result
# ---------------------------------------------------------------------------------------------------
@dataclass
class SpinFrictionResult:
    """Per-ball PRL and spin-friction results (arrays of length Z; SI units).

    beta, omega_m, omega_R [rad/s]: kinematics used (equilibrium speeds for e = 0 unless speeds='qs');
    spin_i/o, roll_i/o [rad/s]; E_i/o [-] (exact kinematic E); E15_i/o [-] (seed Eq. 15); c-values from the exact profile (c1_i, c2_i, n_i, ...) and from
    Houpert's (E, e = 0) formulas with the E of ``E_model`` (c1h_i, c2h_i, nh_i, ...), NaN where absent; e_i/o: traction residuals;
    ms_full_i/o: Eq. 19 moment magnitude [N m]; ms_c_i/o: Eqs. 22-23 from the exact c-values [N m];
    ms_h_i/o: Eqs. 22-23 from Houpert's c-values [N m]; msn_full_i/o: signed Eq. 19 moment on the ball
    about n_k [N m]; Ms_full, Ms_c, Ms_h: bearing spin torques, Eq. 24 [N m]."""

    mu: float
    omega: float
    beta: np.ndarray
    omega_m: np.ndarray
    omega_R: np.ndarray
    spin_i: np.ndarray
    spin_o: np.ndarray
    roll_i: np.ndarray
    roll_o: np.ndarray
    E_i: np.ndarray
    E_o: np.ndarray
    E15_i: np.ndarray
    E15_o: np.ndarray
    c1_i: np.ndarray
    c2_i: np.ndarray
    n_i: np.ndarray
    c1_o: np.ndarray
    c2_o: np.ndarray
    n_o: np.ndarray
    c1h_i: np.ndarray
    c2h_i: np.ndarray
    nh_i: np.ndarray
    c1h_o: np.ndarray
    c2h_o: np.ndarray
    nh_o: np.ndarray
    e_i: np.ndarray
    e_o: np.ndarray
    ms_full_i: np.ndarray
    ms_full_o: np.ndarray
    ms_c_i: np.ndarray
    ms_c_o: np.ndarray
    ms_h_i: np.ndarray
    ms_h_o: np.ndarray
    msn_full_i: np.ndarray
    msn_full_o: np.ndarray
    Ms_full: float
    Ms_c: float
    Ms_h: float
    alpha_i: np.ndarray
    alpha_o: np.ndarray


def analyse(res, mu: float = 0.1, beta: str = "equal", speeds: str = "equilibrium", E_model: str = "kinematic",
            nx: int = 48, ny: int = 48) -> SpinFrictionResult:
    """PRLs and spinning friction of every ball of a quasistatic.QuasiStaticResult ``res``.

    mu: Coulomb sliding friction coefficient [-]; beta: 'equal' (seed 004 Eq. 6, beta = (alpha_i +
    alpha_o)/2, equal raceway control) | 'qs' (the result's beta); speeds: 'equilibrium' (omega_m, omega_R
    solved per ball for e_i = e_o = 0, ``equilibrium_speeds``) | 'qs' (the result's speeds; with beta='equal'
    the rolling-at-centre speeds for that beta); E_model: E fed to Houpert's c-values (c1h_*, c2h_*, nh_*,
    ms_h_*, Ms_h): 'kinematic' (exact spin-to-roll ratio, = root sum of the exact profile) | 'eq15' (seed 004
    Eq. 15 approximation, ``E_eq15``). nx, ny: quadrature orders of ``spin_moment_full``. Unloaded contacts (Q = 0) give NaN. At omega = 0 the limit
    omega -> 0+ is used (Coulomb quantities do not depend on the speed magnitude)."""
    g = res.geometry
    D, dm = g.D, g.dm
    ai, ao = np.asarray(res.alpha_i, float), np.asarray(res.alpha_o, float)
    if beta == "equal":
        bt = 0.5 * (ai + ao)
    elif beta == "qs":
        bt = np.asarray(res.beta, float)
    else:
        raise ValueError(f"beta = {beta!r}; allowed: 'equal' | 'qs'")
    om = float(res.omega)
    om_k = om if om != 0 else 1.0
    loaded = (np.asarray(res.Q_i) > 0) & (np.asarray(res.Q_o) > 0)
    # placeholders for unloaded balls (results masked to NaN below)
    Qi = np.where(loaded, res.Q_i, 1.0)
    Qo = np.where(loaded, res.Q_o, 1.0)
    a_i = np.where(loaded, res.a_i, 1e-4)
    b_i = np.where(loaded, res.b_i, 1e-5)
    a_o = np.where(loaded, res.a_o, 1e-4)
    b_o = np.where(loaded, res.b_o, 1e-5)
    if speeds == "equilibrium":
        wm, wR, _, _, _ = equilibrium_speeds(om_k, ai, ao, bt, a_i, b_i, a_o, b_o, Qi, Qo, D, dm, g.fi, g.fo)
    elif speeds == "qs":
        if beta == "qs" and om != 0:
            wm, wR = np.asarray(res.omega_m, float), np.asarray(res.omega_R, float)
        else:
            wm, wR = kin.ball_speeds(om_k, ai, ao, bt, D, dm)
    else:
        raise ValueError(f"speeds = {speeds!r}; allowed: 'equilibrium' | 'qs'")
    pi = slip_profile(om_k, wm, wR, bt, ai, a_i, b_i, Qi, D, dm, g.fi, "i")
    po = slip_profile(om_k, wm, wR, bt, ao, a_o, b_o, Qo, D, dm, g.fo, "o")
    ci = prl_exact(pi)
    co = prl_exact(po)
    Ei, Eo = pi.E, po.E
    E15i, E15o = E_eq15(ai, a_i, g.fi, D, dm), E_eq15(ao, a_o, g.fo, D, dm)
    if E_model == "kinematic":
        hi, ho = houpert_c(Ei, 0.0), houpert_c(Eo, 0.0)
    elif E_model == "eq15":
        hi, ho = houpert_c(E15i, 0.0), houpert_c(E15o, 0.0)
    else:
        raise ValueError(f"E_model = {E_model!r}; allowed: 'kinematic' | 'eq15'")
    e_i = traction_ratio(pi, ci)
    e_o = traction_ratio(po, co)
    mfi = spin_moment_full(pi, mu, nx, ny)
    mfo = spin_moment_full(po, mu, nx, ny)
    mci = spin_moment_c(ci[0], ci[1], Qi, a_i, mu)
    mco = spin_moment_c(co[0], co[1], Qo, a_o, mu)
    mhi = spin_moment_c(hi[0], hi[1], Qi, a_i, mu)
    mho = spin_moment_c(ho[0], ho[1], Qo, a_o, mu)

    def mask(v):
        v = np.asarray(v, dtype=float)
        return np.where(loaded, v, np.nan)

    def maskn(v):
        return np.where(loaded, np.asarray(v), 0)

    si, so = np.sin(ai), np.sin(ao)
    Ms_full = float(np.sum(np.where(loaded, np.abs(mfi) * si + np.abs(mfo) * so, 0.0)))
    Ms_c = float(np.sum(np.where(loaded, mci * si + mco * so, 0.0)))
    Ms_h = float(np.sum(np.where(loaded, mhi * si + mho * so, 0.0)))
    kf = 1.0 if om != 0 else 0.0  # speeds reported as 0 at omega = 0 (the shapes are those of omega -> 0+)
    return SpinFrictionResult(
        mu=mu, omega=om, beta=bt, omega_m=wm * kf, omega_R=wR * kf,
        spin_i=mask(pi.spin) * kf, spin_o=mask(po.spin) * kf, roll_i=mask(pi.roll) * kf, roll_o=mask(po.roll) * kf,
        E_i=mask(Ei), E_o=mask(Eo), E15_i=mask(E15i), E15_o=mask(E15o),
        c1_i=mask(ci[0]), c2_i=mask(ci[1]), n_i=maskn(ci[2]), c1_o=mask(co[0]), c2_o=mask(co[1]), n_o=maskn(co[2]),
        c1h_i=mask(hi[0]), c2h_i=mask(hi[1]), nh_i=maskn(hi[2]),
        c1h_o=mask(ho[0]), c2h_o=mask(ho[1]), nh_o=maskn(ho[2]),
        e_i=mask(e_i), e_o=mask(e_o),
        ms_full_i=mask(np.abs(mfi)), ms_full_o=mask(np.abs(mfo)),
        ms_c_i=mask(mci), ms_c_o=mask(mco), ms_h_i=mask(mhi), ms_h_o=mask(mho),
        msn_full_i=mask(moment_about_normal(mfi, "i")), msn_full_o=mask(moment_about_normal(mfo, "o")),
        Ms_full=Ms_full, Ms_c=Ms_c, Ms_h=Ms_h, alpha_i=ai, alpha_o=ao)
