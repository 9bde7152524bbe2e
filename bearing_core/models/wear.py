"""Sliding wear of the raceways: the modified Archard model of seed 003 integrated over each Hertz contact
ellipse, raceway wear volume and depth, and a two-time-scale estimate over a duty cycle.

SI units throughout: m, s, N, Pa, rad, rad/s, m/s; wear coefficients in m^3/(N m) = 1/Pa; wear volume
rates in m^3/s, depth rates in m/s.

Model (seed 003 = Liu et al., "Research on sliding wear of angular contact ball bearing raceway under
combined load", Preprints 2026, Sec. 3)
---------------------------------------------------------------------------------------------------
* Archard's law applied to an element dA of the contact ellipse (Eqs. 20-21):
      dV = k dF dL = k p(x, y) v(x, y) dA dt,    V = iint k p v dA dt,
  p the Hertz pressure, v the local sliding speed of the ball relative to the race. With uniform p and
  v this is Archard's V = k F s exactly (tested).
* Wear coefficient from the film parameter (Eq. 22):  k = alpha* Lambda^beta* / H, with
  alpha* = 3.433e-8, beta* = -1.032, H = 8470 MPa (the seed's values) and
  Lambda = h_min / sqrt(sigma_r^2 + sigma_s^2), sigma = 0.18 um each.
  The seed is silent on the range of the fit; Lambda is floored at ``lambda_floor`` (default 0.05) so
  that k stays finite at standstill.
* h_min from Hamrock-Dowson (Eq. 23; bearing_core.lubrication.film), with Rx, Ry of Eqs. 24-25
  (Rx = (D/2)(1 -+ D cos(alpha)/dm), Ry = f D/(2f - 1)) and the entrainment speed u. The seed's u
  (Eqs. 24-25) is the race surface speed relative to the cage at the contact; here u is
  contact_kernels.contact_kinematics' u_roll (the mean of the ball and race surface speeds relative to
  the contact point), which equals it under the quasi-static pure-rolling condition (tested within 0.5%).
  Oil and roughness data: the seed's (film.SEED003_*).
* Sliding speed over the ellipse. The seed's Eqs. 26-28 combine the rolling-direction (Heathcote)
  slip over the major axis, v_y(x) with the rolling radius sqrt(r^2 - x^2) - sqrt(r^2 - a^2) +
  sqrt((D/2)^2 - a^2), and the spin omega_s. We use the SAME relative-velocity field as the dynamics'
  traction (contact_kernels.ellipse_traction, seed 004 Eqs. 1-5): at (x, y) in the ellipse (x along
  the major axis m, y along the rolling direction t),
      v_t = vs_t - w_spin x + w_roll_m d(x),   v_m = vs_m + w_spin y - w_roll_t d(x),   v = |(v_t, v_m)|,
      d(x) = rho(x) - D/2,  rho(x) = sqrt(R^2 - x^2) - sqrt(R^2 - a^2) + sqrt((D/2)^2 - a^2),
  with (vs_t, vs_m, w_spin, w_roll_m, w_roll_t) from contact_kernels.contact_kinematics. R is the
  deformed-surface radius 2 f D / (2 f + 1) (the dynamics' choice, default ``surface='deformed'``) or the
  groove radius f D as the seed's Eq. 26 writes it (``surface='groove'``). The seed's Eq. 28 appears
  garbled (it puts the spin term omega_s y into the rolling-direction component); the rigid-body field
  above is the standard one (Johnson, Contact Mechanics, Ch. 8; Harris & Kotzalas Vol. 2 Ch. 3).
* Integration: the ellipse is mapped to strips x = a xi, y = b sqrt(1 - xi^2) zeta; Gauss-Legendre
  in xi and Gauss-Chebyshev (2nd kind) in zeta for the Hertz pressure, Chebyshev in xi and Legendre in
  zeta for a uniform pressure; both integrate the pressure to Q exactly.

Raceway wear volume and depth
-----------------------------
Per contact the strip integral q(x) = int k p v dy [m^2/s] is the volume removed per unit time per unit
width at major-axis coordinate x. A raceway point at groove angle theta = alpha + x / (f D) (first order
in x / (f D)) passes through the contacts; with the contact point at radius R_c from the bearing axis, the
depth rate at theta is
    inner ring (turning, loads fixed in space: every point sees every ball):
        dh_i/dt(theta) = sum_j q_j(theta) / (2 pi R_c,j)
    outer ring (fixed: the point at azimuth psi_j sees only the balls passing there, all like ball j):
        dh_o/dt(psi_j, theta) = Z q_j(theta) / (2 pi R_c,j)
Integrating either over the raceway gives back the wear volume rate sum_j V_dot_j (tested).

Two time scales
---------------
The contact states change in milliseconds, wear in hours. ``wear_over_duty_cycle`` takes, for each
segment of a duty cycle, the wear rates of a converged operating point (the quasi-static solution here;
per-contact states from a converged cycle of the dynamics through ``wear_rates`` and
``average_rates``) and multiplies them by the segment duration; depth profiles and volumes accumulate
over the segments. The contact geometry is NOT updated for the worn profile: the estimate holds while
the depth stays small against the Hertz approach (``geometry_update_advised`` flags depths above 10% of
the smallest loaded-contact deflection of the cycle).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from ..lubrication import film as _film
from ..contact.contact_kernels import contact_kinematics
from ..errors import BearingInputError, check_range
from ..bearing.geometry import BearingGeometry
from ..contact.hertz import _contact_curvature_nb, reduced_modulus

# ---- seed 003 Sec. 3.1.1 data --------------------------------------------------------------------------
SEED003_ALPHA_STAR = 3.433e-8   # [-] "alpha* ... 3.433e-8"
SEED003_BETA_STAR = -1.032      # [-] "beta* ... -1.032"
SEED003_HARDNESS = 8470e6       # Pa, "H takes 8470 MPa"

RACES = ("inner", "outer")


# --------------------------------------------------------------------------------------------------
# parameters
@dataclass(frozen=True)
class WearParams:
    """Wear model inputs (SI). Defaults: seed 003 Sec. 3.1.1.

    alpha_star, beta_star [-]: wear-coefficient fit k = alpha* Lambda^beta* / H (Eq. 22); hardness H [Pa];
    sigma_race, sigma_ball [m]: rms roughness; eta0 [Pa s], alpha_pv [1/Pa]: oil (pass the values of
    bearing_core.lubrication.lubricants for another oil); E_film [Pa]: modulus in the Hamrock-Dowson groups (None:
    E' of the bearing materials; film.SEED003_E_FILM reproduces the seed as printed, see film.py);
    lambda_floor [-]: lower bound of Lambda in k; k_const [1/Pa]: a constant wear coefficient instead of
    Eq. 22 (None: Eq. 22); thermal: film.ThermalOptions for Gupta's inlet-heating factor (None: isothermal);
    surface: 'deformed' (R = 2fD/(2f+1), as the dynamics) | 'groove' (R = fD, seed Eq. 26) radius of the
    contact surface in the rolling-radius profile."""

    alpha_star: float = SEED003_ALPHA_STAR
    beta_star: float = SEED003_BETA_STAR
    hardness: float = SEED003_HARDNESS
    sigma_race: float = _film.SEED003_SIGMA_RACE
    sigma_ball: float = _film.SEED003_SIGMA_BALL
    eta0: float = _film.SEED003_ETA0
    alpha_pv: float = _film.SEED003_XI
    E_film: float | None = None
    lambda_floor: float = 0.05
    k_const: float | None = None
    thermal: _film.ThermalOptions | None = None
    surface: str = "deformed"

    def validate(self):
        check_range("alpha_star", self.alpha_star, 0.0, None, unit="-")
        check_range("beta_star", self.beta_star, -10.0, 10.0)
        check_range("hardness", self.hardness, 0.0, None, lo_incl=False, unit="Pa")
        check_range("sigma_race", self.sigma_race, 0.0, 1e-4, unit="m")
        check_range("sigma_ball", self.sigma_ball, 0.0, 1e-4, unit="m")
        if self.sigma_race == 0.0 and self.sigma_ball == 0.0 and self.k_const is None:
            raise BearingInputError("sigma_race", 0.0, "> 0 m (or sigma_ball > 0): Lambda needs a roughness")
        check_range("eta0", self.eta0, 0.0, None, lo_incl=False, unit="Pa s")
        check_range("alpha_pv", self.alpha_pv, 0.0, 1e-6, unit="1/Pa")
        if self.E_film is not None:
            check_range("E_film", self.E_film, 0.0, None, lo_incl=False, unit="Pa")
        check_range("lambda_floor", self.lambda_floor, 0.0, None, lo_incl=False)
        if self.k_const is not None:
            check_range("k_const", self.k_const, 0.0, 1e-9, unit="1/Pa")
        if self.surface not in ("deformed", "groove"):
            raise BearingInputError("surface", self.surface, "'deformed' | 'groove'")
        return self


SEED003 = WearParams()   # the seed's data with E' of the bearing materials in the film groups
SEED003_AS_PRINTED = WearParams(E_film=_film.SEED003_E_FILM, surface="groove")  # the seed's E and Eq. 26 radius


# --------------------------------------------------------------------------------------------------
# kernels
@njit(cache=True)
def wear_coefficient_nb(Lambda, alpha_star, beta_star, hardness, lambda_floor):
    """Seed 003 Eq. 22: k = alpha* max(Lambda, floor)^beta* / H [1/Pa = m^3/(N m)]."""
    lam = Lambda if Lambda > lambda_floor else lambda_floor
    return alpha_star * lam ** beta_star / hardness


@njit(cache=True)
def ellipse_wear_nb(a, b, p0, D, R_def, vs_t, vs_m, w_spin, w_roll_m, w_roll_t, k_wear, xi, omega, sxi, zeta,
                    wzeta, q_out):
    """Archard wear integrated over one contact ellipse (seed 003 Eqs. 20-21).

    a, b [m] semi-axes (a along m, b along t); p0 [Pa] the pressure scale (Hertz: p_max; uniform:
    Q/(pi a b)) matching the quadrature (xi, omega, sxi, zeta, wzeta) from ``wear_quadrature``; D [m] ball
    diameter; R_def [m] contact-surface radius across the groove (0: flat, d = 0); the relative motion
    (vs_t, vs_m [m/s], w_spin, w_roll_m, w_roll_t [rad/s]) from contact_kernels.contact_kinematics;
    k_wear [1/Pa] wear coefficient. Sliding at (x, y): see the module docstring (the field of
    contact_kernels.ellipse_traction).
    Fills q_out[i] = int k p v dy at x = a xi[i] [m^2/s] and returns
    (V_dot [m^3/s] = iint k p v dA, P_pv [W] = iint p v dA, F [N] = iint p dA, v_max [m/s] on the nodes)."""
    n = xi.shape[0]
    for i in range(n):
        q_out[i] = 0.0
    if not (p0 > 0.0 and a > 0.0 and b > 0.0):
        return 0.0, 0.0, 0.0, 0.0
    h = 0.5 * D
    curv = R_def > a and h > a
    c0 = 0.0
    if curv:
        c0 = math.sqrt(h * h - a * a) - math.sqrt(R_def * R_def - a * a)
    P = 0.0
    F = 0.0
    vmax = 0.0
    for i in range(n):
        x = a * xi[i]
        w = math.sqrt(max(0.0, 1.0 - xi[i] * xi[i]))
        if curv:
            d = math.sqrt(R_def * R_def - x * x) + c0 - h
        else:
            d = 0.0
        vt = vs_t - w_spin * x + w_roll_m * d
        vm0 = vs_m - w_roll_t * d
        S = 0.0
        Sw = 0.0
        for j in range(zeta.shape[0]):
            y = b * w * zeta[j]
            vm = vm0 + w_spin * y
            v = math.sqrt(vt * vt + vm * vm)
            if v > vmax:
                vmax = v
            S += wzeta[j] * v
            Sw += wzeta[j]
        strip = p0 * b * sxi[i]          # int p dy = strip * Sw ; int p v dy = strip * S
        q_out[i] = k_wear * strip * S
        P += a * omega[i] * strip * S
        F += a * omega[i] * strip * Sw
    return k_wear * P, P, F, vmax


def wear_quadrature(n_major: int = 48, n_minor: int = 24, pressure: str = "hertz"):
    """Nodes and weights (xi, omega, sxi, zeta, wzeta) for ellipse_wear_nb (built once, not numba).

    The ellipse is mapped to strips x = a xi, y = b w zeta, w = sqrt(1 - xi^2), dA = a b w dxi dzeta.
    Hertz (p = p_max w sqrt(1 - zeta^2)): int p f dA = p_max a b int w^2 [int sqrt(1-zeta^2) f dzeta] dxi:
    xi Gauss-Legendre (omega), strip factor sxi = w^2, zeta Gauss-Chebyshev of the 2nd kind (wzeta holds
    sqrt(1 - zeta^2)). Uniform p: int p f dA = p a b int w [int f dzeta] dxi: xi Gauss-Chebyshev of the 2nd
    kind with omega = its weight / w, sxi = w, zeta Gauss-Legendre. Both integrate p to Q to rounding."""
    n_major = int(check_range("n_major", n_major, 2, 4096))
    n_minor = int(check_range("n_minor", n_minor, 2, 4096))
    j = np.arange(1, n_major + 1)
    if pressure == "hertz":
        xi, om = np.polynomial.legendre.leggauss(n_major)
        sxi = 1.0 - xi * xi
        jj = np.arange(1, n_minor + 1)
        th = jj * np.pi / (n_minor + 1)
        zeta = np.cos(th)
        wz = np.pi / (n_minor + 1) * np.sin(th) ** 2
    elif pressure == "uniform":
        th = j * np.pi / (n_major + 1)
        xi = np.cos(th)
        w = np.sin(th)
        om = np.pi / (n_major + 1) * w ** 2 / w
        sxi = w
        zeta, wz = np.polynomial.legendre.leggauss(n_minor)
    else:
        raise BearingInputError("pressure", pressure, "'hertz' | 'uniform'")
    c = np.ascontiguousarray
    return c(xi, dtype=float), c(om, dtype=float), c(sxi, dtype=float), c(zeta, dtype=float), c(wz, dtype=float)


# --------------------------------------------------------------------------------------------------
# per-contact states
@dataclass
class ContactStates:
    """Kinematic and Hertz state of a set of ball-race contacts of one race (arrays of length n, SI).

    Q [N], a, b [m] Hertz semi-axes, p_max [Pa], alpha [rad] contact angle, psi [rad] ball azimuth,
    Rx, Ry [m] effective radii (film), R_c [m] radius of the contact point from the bearing axis,
    vs_t, vs_m [m/s], w_spin, w_roll_m, w_roll_t [rad/s], u_roll [m/s]: contact_kernels.contact_kinematics
    at the contact centre. Scalars: race 'inner' | 'outer'; D [m]; R_def [m] contact-surface radius for the
    rolling-radius profile; r_groove [m] = f D; E_prime [Pa] of the materials; n_balls [-] (Z);
    ring_turns: the ring turns relative to the (space-fixed) load, so that its points see every ball
    (inner ring of a shaft bearing)."""

    race: str
    Q: np.ndarray
    a: np.ndarray
    b: np.ndarray
    p_max: np.ndarray
    alpha: np.ndarray
    psi: np.ndarray
    Rx: np.ndarray
    Ry: np.ndarray
    R_c: np.ndarray
    vs_t: np.ndarray
    vs_m: np.ndarray
    w_spin: np.ndarray
    w_roll_m: np.ndarray
    w_roll_t: np.ndarray
    u_roll: np.ndarray
    D: float
    R_def: float
    r_groove: float
    E_prime: float
    n_balls: int
    ring_turns: bool

    def __post_init__(self):
        if self.race not in RACES:
            raise BearingInputError("race", self.race, "'inner' | 'outer'")
        names = ("Q", "a", "b", "p_max", "alpha", "psi", "Rx", "Ry", "R_c", "vs_t", "vs_m", "w_spin",
                 "w_roll_m", "w_roll_t", "u_roll")
        n = None
        for nm in names:
            v = np.atleast_1d(np.asarray(getattr(self, nm), dtype=float))
            if n is None:
                n = v.size
            if v.size != n:
                raise BearingInputError(nm, v.size, f"an array of the same length as Q ({n})")
            if not np.all(np.isfinite(v)):
                raise BearingInputError(nm, v.tolist(), "finite values")
            setattr(self, nm, v)
        for nm in ("Q", "a", "b", "p_max"):
            if np.any(getattr(self, nm) < 0):
                raise BearingInputError(nm, getattr(self, nm).tolist(), "values >= 0")
        for nm in ("Rx", "Ry", "R_c"):
            if np.any(getattr(self, nm) <= 0):
                raise BearingInputError(nm, getattr(self, nm).tolist(), "values > 0 m")
        check_range("D", self.D, 0.0, None, lo_incl=False, unit="m")
        check_range("R_def", self.R_def, 0.0, None, unit="m")
        check_range("r_groove", self.r_groove, 0.0, None, lo_incl=False, unit="m")
        check_range("E_prime", self.E_prime, 0.0, None, lo_incl=False, unit="Pa")
        check_range("n_balls", self.n_balls, 1, 1000)

    @property
    def n(self) -> int:
        return int(self.Q.size)


def contact_states_from_quasistatic(res, surface: str = "deformed") -> dict:
    """ContactStates of both races from a quasistatic.QuasiStaticResult (outer ring fixed, inner ring at
    res.omega). The ball motion is the quasi-static one written in the dynamics' state variables (as
    dynamics.DynamicModel.initialize does): ball centre at radius r_b = dm/2 - (fo - 1/2) D cos(alpha0) + X_r
    moving at r_b omega_m along t; ball angular velocity (-omega_R sin(beta), 0, omega_R cos(beta) + omega_m)
    in (r, t, z); then contact_kernels.contact_kinematics at each contact, the same call as the dynamics.
    surface: 'deformed' | 'groove' (see WearParams). Returns {'inner': ContactStates, 'outer': ...}."""
    g: BearingGeometry = res.geometry
    if surface not in ("deformed", "groove"):
        raise BearingInputError("surface", surface, "'deformed' | 'groove'")
    E_prime = reduced_modulus(g.ring_material.E, g.ring_material.nu, g.ball_material.E, g.ball_material.nu)
    D, dm = g.D, g.dm
    Roo = 0.5 * dm - (g.fo - 0.5) * D * math.cos(g.alpha0)
    out = {}
    for race in RACES:
        inner = race == "inner"
        f = g.fi if inner else g.fo
        alpha = np.asarray(res.alpha_i if inner else res.alpha_o, dtype=float)
        Q = np.asarray(res.Q_i if inner else res.Q_o, dtype=float)
        a = np.asarray(res.a_i if inner else res.a_o, dtype=float)
        b = np.asarray(res.b_i if inner else res.b_o, dtype=float)
        p = np.asarray(res.p_i if inner else res.p_o, dtype=float)
        n = alpha.size
        cols = {k: np.zeros(n) for k in ("Rx", "Ry", "R_c", "vs_t", "vs_m", "w_spin", "w_roll_m", "w_roll_t",
                                         "u_roll")}
        for j in range(n):
            rb = Roo + float(res.X[j, 0])
            wm, wR, beta = float(res.omega_m[j]), float(res.omega_R[j]), float(res.beta[j])
            wr, wt, wz = -wR * math.sin(beta), 0.0, wR * math.cos(beta) + wm
            if inner:
                nr, nz, Om = -math.cos(alpha[j]), -math.sin(alpha[j]), float(res.omega)
            else:
                nr, nz, Om = math.cos(alpha[j]), math.sin(alpha[j]), 0.0
            vs_t, vs_m, wsp, wrm, wrt, ur = contact_kinematics(rb, 0.0, rb * wm, 0.0, wr, wt, wz, Om, 0.0, 0.0,
                                                               0.0, nr, nz, D)
            Rx, Ry, _, _ = _contact_curvature_nb(D, dm, f, abs(alpha[j]), inner)
            cols["Rx"][j], cols["Ry"][j] = Rx, Ry
            cols["R_c"][j] = rb + 0.5 * D * nr
            cols["vs_t"][j], cols["vs_m"][j], cols["w_spin"][j] = vs_t, vs_m, wsp
            cols["w_roll_m"][j], cols["w_roll_t"][j], cols["u_roll"][j] = wrm, wrt, ur
        R_def = 2.0 * f * D / (2.0 * f + 1.0) if surface == "deformed" else f * D
        out[race] = ContactStates(race=race, Q=Q, a=a, b=b, p_max=p, alpha=alpha, psi=np.asarray(res.psi, float),
                                  D=D, R_def=R_def, r_groove=f * D, E_prime=E_prime, n_balls=g.Z,
                                  ring_turns=inner, **cols)
    return out


# --------------------------------------------------------------------------------------------------
# wear rates
@dataclass
class WearRates:
    """Wear rates of the contacts of one race (arrays per contact, SI).

    h_c, h_min [m] film thickness; Lambda [-]; k [1/Pa] wear coefficient (Eq. 22); V_dot [m^3/s] wear
    volume rate of each contact; P_pv [W] iint p v dA (the sliding power per unit friction coefficient);
    F [N] iint p dA (= Q, a check); v_max [m/s] largest sliding speed on the nodes; x [m] (n, n_major)
    major-axis coordinates of the strips; q [m^2/s] (n, n_major) strip wear rates int k p v dy; the
    ContactStates used."""

    states: ContactStates
    h_c: np.ndarray
    h_min: np.ndarray
    Lambda: np.ndarray
    k: np.ndarray
    V_dot: np.ndarray
    P_pv: np.ndarray
    F: np.ndarray
    v_max: np.ndarray
    x: np.ndarray
    q: np.ndarray

    @property
    def V_dot_total(self) -> float:
        """Wear volume rate of the race [m^3/s] (sum over its contacts)."""
        return float(np.sum(self.V_dot))

    def groove_angle(self) -> np.ndarray:
        """Groove angle theta = alpha + x / (f D) [rad] of every strip (n, n_major) (first order in x/(f D))."""
        s = self.states
        return s.alpha[:, None] + self.x / s.r_groove

    def depth_rate_profile(self, theta: np.ndarray) -> np.ndarray:
        """Raceway depth rate [m/s] on the groove-angle grid theta [rad] (module docstring).
        Turning ring (inner): shape (len(theta),), the same all round the ring. Fixed ring (outer): shape
        (n, len(theta)), row j at the azimuth of contact j."""
        s = self.states
        theta = np.asarray(theta, dtype=float)
        th = self.groove_angle()
        rows = np.zeros((s.n, theta.size))
        for j in range(s.n):
            if not np.any(self.q[j] > 0):
                continue
            order = np.argsort(th[j])
            tj = th[j][order]
            qj = self.q[j][order]
            # the strip rate vanishes at the ellipse ends x = +-a
            half = s.a[j] / s.r_groove
            tt = np.concatenate(([s.alpha[j] - half], tj, [s.alpha[j] + half]))
            qq = np.concatenate(([0.0], qj, [0.0]))
            # q is a rate per unit width along x; theta = alpha + x / r  ->  per unit arc length r dtheta
            rows[j] = np.interp(theta, tt, qq, left=0.0, right=0.0) / (2.0 * math.pi * s.R_c[j])
        if s.ring_turns:
            return rows.sum(axis=0)
        return s.n_balls * rows

    def max_depth_rate(self, n_theta: int = 2001) -> float:
        """Largest raceway depth rate [m/s] (over the groove, and over azimuth for the fixed ring)."""
        th = self.theta_grid(n_theta)
        return float(np.max(self.depth_rate_profile(th))) if th.size else 0.0

    def theta_grid(self, n_theta: int = 2001) -> np.ndarray:
        """A groove-angle grid [rad] that covers every loaded contact of this race."""
        s = self.states
        on = s.a > 0
        if not np.any(on):
            return np.zeros(0)
        lo = float(np.min(s.alpha[on] - s.a[on] / s.r_groove))
        hi = float(np.max(s.alpha[on] + s.a[on] / s.r_groove))
        return np.linspace(lo, hi, int(n_theta))


def _film_of_states(s: ContactStates, p: WearParams):
    """(h_c, h_min, Lambda) per contact: film.film_thickness_nb with the seed's Eq. 23."""
    Ef = s.E_prime if p.E_film is None else p.E_film
    n = s.n
    hc = np.full(n, np.nan)
    hm = np.full(n, np.nan)
    lam = np.full(n, np.nan)
    sig = math.hypot(p.sigma_race, p.sigma_ball)
    for j in range(n):
        if not s.Q[j] > 0.0:
            continue
        k_el = _film.ellipticity_nb(s.Rx[j], s.Ry[j], _film.ELLIPTICITY_BH77)
        phi = 1.0
        if p.thermal is not None:
            ph = p.thermal.p_h if p.thermal.p_h is not None else s.p_max[j]
            srr = p.thermal.srr
            phi = _film.thermal_reduction_nb(abs(s.u_roll[j]), p.eta0, p.thermal.beta_T, p.thermal.K_f, ph, Ef, srr)
        hc[j], hm[j] = _film.film_thickness_nb(abs(s.u_roll[j]), p.eta0, p.alpha_pv, s.Rx[j], s.Ry[j], Ef, s.Q[j],
                                              k_el, phi)
        lam[j] = hm[j] / sig if sig > 0 else math.inf
    return hc, hm, lam


def wear_rates(states: ContactStates, params: WearParams = SEED003, n_major: int = 48, n_minor: int = 24,
               pressure: str = "hertz") -> WearRates:
    """Wear rates of every contact in ``states`` (one race): film (Eq. 23), wear coefficient (Eq. 22) and
    the Archard integral over the ellipse (Eqs. 20-21). pressure: 'hertz' (default) | 'uniform'
    (p = Q/(pi a b), for checks). n_major, n_minor: quadrature points (wear_quadrature)."""
    params.validate()
    s = states
    xi, om, sxi, zeta, wz = wear_quadrature(n_major, n_minor, pressure)
    hc, hm, lam = _film_of_states(s, params)
    n = s.n
    k = np.zeros(n)
    V = np.zeros(n)
    P = np.zeros(n)
    F = np.zeros(n)
    vmax = np.zeros(n)
    q = np.zeros((n, xi.size))
    qrow = np.zeros(xi.size)
    R_def = s.R_def if s.R_def > 0 else 0.0
    for j in range(n):
        if not (s.Q[j] > 0.0 and s.a[j] > 0.0 and s.b[j] > 0.0):
            continue
        if params.k_const is not None:
            k[j] = params.k_const
        else:
            k[j] = wear_coefficient_nb(lam[j], params.alpha_star, params.beta_star, params.hardness,
                                       params.lambda_floor)
        p0 = s.p_max[j] if pressure == "hertz" else s.Q[j] / (math.pi * s.a[j] * s.b[j])
        V[j], P[j], F[j], vmax[j] = ellipse_wear_nb(s.a[j], s.b[j], p0, s.D, R_def, s.vs_t[j], s.vs_m[j],
                                                    s.w_spin[j], s.w_roll_m[j], s.w_roll_t[j], k[j], xi, om, sxi,
                                                    zeta, wz, qrow)
        q[j] = qrow
    x = s.a[:, None] * xi[None, :]
    return WearRates(states=s, h_c=hc, h_min=hm, Lambda=lam, k=k, V_dot=V, P_pv=P, F=F, v_max=vmax, x=x, q=q)


def average_rates(rates: list, weights=None) -> dict:
    """Time average of race wear quantities over the samples of a converged cycle of the dynamics:
    ``rates`` a list of WearRates of the same race (e.g. one per recorded time), weights the time steps
    [s] (None: equal). Returns {'V_dot_total' [m^3/s], 'max_depth_rate' [m/s] of the averaged profile,
    'theta' [rad], 'depth_rate' [m/s] averaged profile (fixed ring: per-sample azimuths are kept as rows
    only when every sample has the same contact count; the maximum over rows is what is reported)}."""
    if not rates:
        raise BearingInputError("rates", rates, "a non-empty list of WearRates")
    w = np.ones(len(rates)) if weights is None else np.asarray(weights, dtype=float)
    if w.size != len(rates) or np.any(w < 0) or not w.sum() > 0:
        raise BearingInputError("weights", np.asarray(weights).tolist(), "one non-negative weight per sample, sum > 0")
    w = w / w.sum()
    grids = [r.theta_grid() for r in rates]
    grids = [g_ for g_ in grids if g_.size]
    if not grids:
        return {"V_dot_total": 0.0, "max_depth_rate": 0.0, "theta": np.zeros(0), "depth_rate": np.zeros(0)}
    theta = np.linspace(min(g_[0] for g_ in grids), max(g_[-1] for g_ in grids), 2001)
    V = float(sum(wi * r.V_dot_total for wi, r in zip(w, rates)))
    prof = sum(wi * r.depth_rate_profile(theta) for wi, r in zip(w, rates))
    return {"V_dot_total": V, "max_depth_rate": float(np.max(prof)), "theta": theta, "depth_rate": prof}


# --------------------------------------------------------------------------------------------------
# operating point and duty cycle
def operating_point_wear(geometry: BearingGeometry, omega: float, loads, params: WearParams = SEED003,
                         control: str = "outer", n_major: int = 48, n_minor: int = 24) -> dict:
    """Quasi-static solution at inner-ring speed omega [rad/s] and loads (Fx, Fy, Fz, Mx, My) [N, N m]
    (quasistatic.solve_quasistatic) and the wear rates of both races. Returns {'qs': result,
    'inner': WearRates, 'outer': WearRates}."""
    from .quasistatic import solve_quasistatic
    params.validate()
    geometry.require_two_point("wear model")
    res = solve_quasistatic(geometry, omega, loads, control=control, stiffness=False)
    st = contact_states_from_quasistatic(res, surface=params.surface)
    return {"qs": res,
            "inner": wear_rates(st["inner"], params, n_major, n_minor),
            "outer": wear_rates(st["outer"], params, n_major, n_minor)}


THETA_GRID = np.radians(np.linspace(-10.0, 100.0, 22001))   # groove-angle grid of the duty-cycle profiles


def wear_over_duty_cycle(geometry: BearingGeometry, segments, params: WearParams = SEED003,
                         control: str = "outer", n_major: int = 48, n_minor: int = 24) -> dict:
    """Two-time-scale wear estimate over a duty cycle.

    segments: iterable of (duration_s [s], omega [rad/s], loads (Fx, Fy, Fz, Mx, My) [N, N m]). For each
    segment the wear rates of the converged quasi-static operating point are multiplied by the duration;
    raceway depth profiles (groove angle THETA_GRID) and volumes accumulate. The contact geometry is not
    updated for wear (see module docstring); ``geometry_update_advised`` is True when the largest depth
    exceeds 10% of the smallest Hertz deflection of a loaded contact over the cycle.
    Returns a dict (SI, units in the names): per race '<race>_wear_volume_m3', '<race>_max_wear_depth_m',
    '<race>_depth_profile_m' (inner: (n_theta,), outer: (Z, n_theta) by ball azimuth), 'theta_rad',
    'segments' (per segment: duration, speed, loads, volume rates, max depth rates, min Lambda, h_min),
    'operating_points' (per segment: operating_point_wear's dict), 'total_time_s', 'geometry_update_advised', 'min_contact_deflection_m'."""
    params.validate()
    segs = list(segments)
    if not segs:
        raise BearingInputError("segments", segs, "at least one (duration_s, omega, loads) segment")
    Z = geometry.Z
    vol = {"inner": 0.0, "outer": 0.0}
    depth = {"inner": np.zeros(THETA_GRID.size), "outer": np.zeros((Z, THETA_GRID.size))}
    seg_out = []
    ops = []
    dmin = math.inf
    total = 0.0
    for i, seg in enumerate(segs):
        try:
            dur, omega, loads = seg
        except (TypeError, ValueError):
            raise BearingInputError(f"segments[{i}]", seg, "(duration_s, omega_rad_s, (Fx, Fy, Fz, Mx, My))")
        dur = check_range(f"segments[{i}].duration_s", dur, 0.0, None, unit="s")
        omega = check_range(f"segments[{i}].omega", omega, 0.0, 2.0e4, unit="rad/s")
        op = operating_point_wear(geometry, omega, loads, params, control, n_major, n_minor)
        res = op["qs"]
        rec = {"duration_s": dur, "omega_rad_s": omega, "speed_rpm": omega * 30.0 / math.pi,
               "loads_N_Nm": [float(v) for v in np.asarray(loads, dtype=float).ravel()]}
        for race in RACES:
            r: WearRates = op[race]
            prof = r.depth_rate_profile(THETA_GRID)
            vol[race] += r.V_dot_total * dur
            depth[race] += prof * dur
            loaded = r.states.Q > 0
            rec[f"{race}_wear_volume_rate_m3_per_s"] = r.V_dot_total
            rec[f"{race}_max_depth_rate_m_per_s"] = float(np.max(prof))
            rec[f"{race}_min_lambda"] = float(np.nanmin(r.Lambda)) if loaded.any() else float("nan")
            rec[f"{race}_min_h_min_m"] = float(np.nanmin(r.h_min)) if loaded.any() else float("nan")
            dl = (res.delta_i if race == "inner" else res.delta_o)[loaded]
            if dl.size:
                dmin = min(dmin, float(np.min(dl)))
        total += dur
        seg_out.append(rec)
        ops.append(op)
    out = {"theta_rad": THETA_GRID, "segments": seg_out, "total_time_s": total, "operating_points": ops,
           "min_contact_deflection_m": dmin if math.isfinite(dmin) else float("nan")}
    for race in RACES:
        out[f"{race}_wear_volume_m3"] = vol[race]
        out[f"{race}_max_wear_depth_m"] = float(np.max(depth[race]))
        out[f"{race}_depth_profile_m"] = depth[race]
    maxd = max(out["inner_max_wear_depth_m"], out["outer_max_wear_depth_m"])
    out["geometry_update_advised"] = bool(math.isfinite(dmin) and maxd > 0.1 * dmin)
    return out


# --------------------------------------------------------------------------------------------------
# CLI-callable report
def wear_report(bearing, speed_rpm: float, fx: float = 0.0, fz: float = 0.0, hours: float = 1.0, fy: float = 0.0,
                mx: float = 0.0, my: float = 0.0, control: str = "outer", params: WearParams = SEED003,
                n_major: int = 48, n_minor: int = 24) -> dict:
    """Raceway wear after ``hours`` at one operating point (for a ``bearing wear`` CLI command).

    bearing: preset name or BearingGeometry; speed_rpm [rpm] inner-ring speed; fx, fy, fz [N], mx, my
    [N m] loads on the inner ring; hours [h]; control: raceway control of the quasi-static model;
    params: WearParams (default seed 003). Returns a JSON-ready dict, SI with units in the key names.
    Raises BearingInputError (parameter, value, allowed) on bad input."""
    from ..bearing.geometry import load_preset
    g = load_preset(bearing) if isinstance(bearing, str) else bearing
    if not isinstance(g, BearingGeometry):
        raise BearingInputError("bearing", bearing, "a preset name or a BearingGeometry")
    speed_rpm = check_range("speed_rpm", speed_rpm, 0.0, 2.0e4 * 30.0 / math.pi, unit="rpm")
    hours = check_range("hours", hours, 0.0, 1e7, unit="h")
    loads = [check_range(nm, v, -1e7, 1e7, unit=u) for nm, v, u in
             (("fx", fx, "N"), ("fy", fy, "N"), ("fz", fz, "N"), ("mx", mx, "N m"), ("my", my, "N m"))]
    omega = speed_rpm * math.pi / 30.0
    t = hours * 3600.0
    d = wear_over_duty_cycle(g, [(t, omega, loads)], params, control, n_major, n_minor)
    seg = d["segments"][0]
    op = d["operating_points"][0]
    out = {
        "bearing": g.name,
        "speed_rpm": speed_rpm,
        "loads": {"Fx_N": loads[0], "Fy_N": loads[1], "Fz_N": loads[2], "Mx_Nm": loads[3], "My_Nm": loads[4]},
        "hours": hours,
        "control": control,
        "model": "modified Archard, seed 003 Eqs. 20-25 (bearing_core.models.wear); quasi-static operating point; "
                 "geometry not updated for wear",
        "geometry_update_advised": d["geometry_update_advised"],
    }
    for race in RACES:
        r: WearRates = op[race]
        out[f"{race}_wear_volume_m3"] = d[f"{race}_wear_volume_m3"]
        out[f"{race}_wear_depth_m"] = d[f"{race}_max_wear_depth_m"]
        out[f"{race}_wear_volume_rate_m3_per_s"] = seg[f"{race}_wear_volume_rate_m3_per_s"]
        out[f"{race}_max_depth_rate_m_per_s"] = seg[f"{race}_max_depth_rate_m_per_s"]
        out[f"{race}_min_lambda"] = seg[f"{race}_min_lambda"]
        out[f"{race}_h_min_m"] = [None if not np.isfinite(v) else float(v) for v in r.h_min]
        out[f"{race}_lambda"] = [None if not np.isfinite(v) else float(v) for v in r.Lambda]
        out[f"{race}_wear_coefficient_per_Pa"] = [float(v) for v in r.k]
        out[f"{race}_contact_wear_volume_rate_m3_per_s"] = [float(v) for v in r.V_dot]
    out["ball_azimuth_deg"] = [float(v) for v in np.degrees(op["qs"].psi)]
    out["params"] = {"alpha_star": params.alpha_star, "beta_star": params.beta_star,
                     "hardness_Pa": params.hardness, "sigma_race_m": params.sigma_race,
                     "sigma_ball_m": params.sigma_ball, "eta0_Pa_s": params.eta0, "alpha_pv_per_Pa": params.alpha_pv,
                     "E_film_Pa": params.E_film, "lambda_floor": params.lambda_floor, "k_const_per_Pa": params.k_const,
                     "surface": params.surface, "thermal": params.thermal is not None}
    return out
