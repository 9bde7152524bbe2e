"""Oil-lubricated ball-pocket contact: hydrodynamic films on both walls of a cylindrical cage pocket and the
mixed EHL / boundary friction of the penalty contact, as numba kernels for the dynamics' right-hand side.
The dry pocket contact and the inline arctangent / wrap helpers are contact.contact_kernels'."""
from __future__ import annotations

import math

from ..contact.contact_kernels import atan, atan_ratio, wrap_angle  # noqa: F401
from ..numerics import mathx as MX
from ..numerics.jit import hot
from .ehl_traction import fluid_fraction

# --------------------------------------------------------------------------------------------------
# 5. oil-lubricated ball-pocket contact (film on both pocket walls, boundary / EHL limit in contact)
#
# Pocket geometry: a cylindrical pocket (bored along the radial direction r, the usual machined cage) of
# radius R_p = R + c_p, c_p the pocket clearance per side. Each wall is a conformal ball-in-cylinder
# conjunction with the principal radii R_r = R (along the pocket axis, straight wall) and
# R_z = R R_p / c_p (around the pocket, conformal; 1/R_z = 1/R - 1/R_p). The entrainment is the ball
# surface's sliding direction on the wall (angle phi to r); the radii along and across it follow Euler's
# curvature formula, 1/R_s = cos^2 phi / R_r + sin^2 phi / R_z and 1/R_t = sin^2 phi / R_r + cos^2 phi / R_z,
# and the film formulas below take R_x = R_s and the radius ratio a_r = R_t / R_s (exact for entrainment
# along a principal axis, the Hamrock-Dowson case; the effective radius along an oblique entrainment as in
# Chittenden, Dowson, Dunn & Taylor, Proc. R. Soc. A 397 (1985) 271, recalled).
# Followed (each wall of the pocket is flooded with oil):
# * hydrodynamic load from entrainment, isoviscous-rigid: Brewe, Hamrock & Taylor, 'Effect of geometry on
#   hydrodynamic film thickness', J. Lubr. Technol. 101 (1979) 231-239, H_min,IR = 128 a_r phi_r^2
#   [0.131 atan(a_r / 2) + 1.683]^2 with H = (h/R_x)(W/U)^2, phi_r = (1 + 2 / (3 a_r))^-1, i.e.
#   F_hd = eta u R_x sqrt(H_min,IR R_x / h) (140.1 and 11.84 eta u R sqrt(R/h) for a sphere on a plane,
#   a_r = 1), u the entrainment (mean surface) speed = |v_s| / 2 for the ball surface sliding on the wall
#   (Hamrock & Dowson, Ball Bearing Lubrication, Wiley 1981, isoviscous-rigid regime; the rigid-film
#   treatment of the cage pocket of Gupta, Advanced Dynamics of Rolling Elements (1984) Ch. 5);
# * squeeze film of a sphere approaching a plane (Reynolds): F_sq = 6 pi eta R^2 (-dh/dt) / h (the
#   sphere-plane value, a lower bound for the conformal pocket); the film carries no tension (the total
#   film force is clipped at 0, half-Sommerfeld cavitation);
# * viscous shear of the film on the ball surface, the lubrication limit of a sphere rotating next to a
#   wall: torque 8 pi eta R^3 Omega [(2/5) ln(R/h) + 0.3817] (Goldman, Cox & Brenner, Chem. Eng. Sci. 22
#   (1967) 637-651), written as a surface force F_v = pi eta R |v_s| (3.2 ln(R/h) + 3.05) at the wall
#   (sphere-plane value, a lower bound for the conformal pocket);
# * in contact (ball pressed on the wall beyond the penalty onset) the conjunction is elastohydrodynamic:
#   its minimum film is the larger of Hamrock-Dowson's piezoviscous-elastic film
#   H = 3.63 U^0.68 G^0.49 W^-0.073 (1 - exp(-0.68 k)) and their isoviscous-elastic ('soft EHL', polymer
#   cages) film H = 8.70 U^0.66 W^-0.21 (1 - 0.85 exp(-0.31 k)), k = 1.0339 a_r^0.636 (Hamrock & Dowson
#   1981; k < 1, entrainment along the conformal direction, extrapolates their fits); the load is shared
#   between film and asperities by the film parameter Lambda = h_min / sigma with the same Zhou-Hoeprich
#   fluid fraction f(Lambda) as the race contacts (ehl_traction.fluid_fraction), mu = (1 - f) mu_bl +
#   f mu_film (the SKF model's mixing of mu_bl and mu_EHL by a film weighting, SKF General Catalogue 6000
#   'Friction'); the full-film coefficient is the Newtonian (Couette) shear of the film over the Hertz
#   area, mu_film = eta(p_m) |v_s| / (h_min p_m), Barus viscosity at the mean Hertz pressure
#   p_m = F / (pi a_e^2), a_e = (3 F sqrt(R_s R_t) / (2 E'))^(1/3) (equivalent-radius Hertz contact,
#   Johnson, Contact Mechanics 1985 Sec. 4.2), limited by mu_ehl (limiting shear: the SKF mu_EHL of
#   mineral oils, 0.05). Default mu_bl = 0.15 (SKF mu_bl).
# The film formulas are evaluated at h >= h_floor (the composite roughness): below it the solid contact
# (penalty) carries the load.
@hot
def _hd_pocket_film(u, eta, alpha_pv, Rx, k, E_red, F):
    """Minimum EHL film [m] of a conjunction of radius Rx [m] along the entrainment and ellipticity k at
    load F [N], entrainment u [m/s], viscosity eta [Pa s], pressure-viscosity alpha_pv [1/Pa], E_red [Pa]
    (E'): max of the Hamrock-Dowson piezoviscous-elastic and isoviscous-elastic minimum films."""
    if not (F > 0.0 and u > 0.0 and eta > 0.0):
        return 0.0
    U = eta * u / (E_red * Rx)
    W = F / (E_red * Rx * Rx)
    G = alpha_pv * E_red
    h_pe = Rx * 3.63 * U ** 0.68 * G ** 0.49 * W ** -0.073 * (1.0 - math.exp(-0.68 * k))
    h_ie = Rx * 8.70 * U ** 0.66 * W ** -0.21 * (1.0 - 0.85 * math.exp(-0.31 * k))
    return h_pe if h_pe > h_ie else h_ie


@hot
def _hd_ball_flat_film(u, eta, alpha_pv, R, E_red, F):
    """Minimum EHL film [m] of a ball (radius R) on a flat (k = 1), see _hd_pocket_film."""
    return _hd_pocket_film(u, eta, alpha_pv, R, 1.0, E_red, F)


@hot
def _brewe_hamrock_taylor(ar):
    """Isoviscous-rigid dimensionless minimum-film load number H_min,IR(a_r) (Brewe, Hamrock & Taylor 1979)."""
    return 128.0 * ar * _bht_factor(ar, 1.0)


@hot
def _bht_factor(ks, kt):
    """phi_r^2 [0.131 atan(a_r / 2) + 1.683]^2 of _brewe_hamrock_taylor at a_r = ks / kt (curvatures along
    and across the entrainment), two divisions: H_min,IR = 128 a_r (this)."""
    ph = 3.0 * ks / (3.0 * ks + 2.0 * kt)     # phi_r = (1 + 2 / (3 a_r))^-1
    c = 0.131 * atan_ratio(0.5 * ks, kt) + 1.683
    return ph * ph * c * c


@hot
def ball_pocket_lubricated(theta_b, theta_c, dtheta_b, dtheta_c, r_p, c_p, K_cb, C_cb, mu_bl, mu_ehl, v_reg,
                           eta, alpha_pv, E_red, sigma, D, vr, vz, wr, wz, vcr, vcz):
    """Oil-lubricated ball-pocket contact: films on both pocket walls of a cylindrical pocket of radius
    D/2 + c_p (axis along r) plus the penalty contact with its mixed EHL / boundary friction (see the notes
    above). Arguments as ball_pocket_contact, plus mu_bl, mu_ehl [-] boundary friction coefficient and
    limiting full-film coefficient, eta [Pa s] oil viscosity, alpha_pv [1/Pa] its
    pressure-viscosity coefficient, E_red [Pa] reduced modulus E' of ball and cage, sigma [m] composite
    rms roughness (also the film floor).
    Returns (F_n [N] largest wall force (film + solid), F_t, F_r, F_z [N] force on the ball (local
    r, t, z), M_r, M_z [N m] its moment about the ball centre, T_w [N m] the moment about the ball centre's
    orbit of the wall friction arms (sum over walls of w D/2 F_r,w: the cage gets -(this) through its
    wall offset), P_loss [W] film and friction dissipation (>= 0 on average; the hydrodynamic normal
    force can return power while the gap opens), P_damp [W] penalty damping dissipation, U_el [J]
    elastic energy of the penalty)."""
    return ball_pocket_lubricated_rel(wrap_angle(theta_b - theta_c), dtheta_b, dtheta_c, r_p, c_p, K_cb, C_cb,
                                      mu_bl, mu_ehl, v_reg, eta, alpha_pv, E_red, sigma, D, vr, vz, wr, wz, vcr,
                                      vcz)


@hot
def ball_pocket_lubricated_rel(dth, dtheta_b, dtheta_c, r_p, c_p, K_cb, C_cb, mu_bl, mu_ehl, v_reg, eta,
                               alpha_pv, E_red, sigma, D, vr, vz, wr, wz, vcr, vcz):
    """ball_pocket_lubricated from dth [rad], the ball azimuth minus the pocket-centre azimuth already
    wrapped to [-pi, pi)."""
    R = 0.5 * D
    hfl = sigma if sigma > 1e-9 else 1e-9
    # conformal cylindrical pocket: curvature 1/R along the pocket axis r, 1/R - 1/(R + c_p) around it
    kz = c_p / (R * (R + c_p)) if c_p > 0.0 else 1.0 / R
    kr = 1.0 / R
    Ft = 0.0
    Fr = 0.0
    Fz = 0.0
    Mr = 0.0
    Mz = 0.0
    Tw = 0.0
    Pl = 0.0
    Pd = 0.0
    Ue = 0.0
    Fmax = 0.0
    vrel = (dtheta_b - dtheta_c) * r_p
    for k in range(2):
        w = 1.0 if k == 0 else -1.0
        gap = c_p - w * dth * r_p            # film gap at wall w (the wall at w D/2 t)
        gdot = -w * vrel
        h = gap if gap > hfl else hfl
        vsr = vr - vcr - w * R * (wz - dtheta_c)
        vsz = vz - vcz + w * R * wr
        vs = math.sqrt(vsr * vsr + vsz * vsz)
        # curvatures along (ks = 1 / Rs) and across (kt = 1 / Rt) the entrainment direction (Euler)
        ks = kr
        kt = kr
        ivs = 0.0
        if vs > 0.0:
            ivs = 1.0 / vs
            c2 = (vsr * ivs) ** 2
            ks = c2 * kr + (1.0 - c2) * kz
            kt = (1.0 - c2) * kr + c2 * kz
        rk = 1.0 / (ks * kt)
        Rs = kt * rk
        ih = 1.0 / h
        # film normal force (entrainment + squeeze), never tensile; H_min,IR at a_r = Rt / Rs = ks / kt
        Ff = (eta * 0.5 * vs * Rs * math.sqrt(128.0 * ks * ks * rk * _bht_factor(ks, kt) * Rs * ih)
              - 6.0 * math.pi * eta * R * R * gdot * ih)
        if Ff < 0.0:
            Ff = 0.0
        # solid / EHL contact (penalty) beyond the clearance
        Fc = 0.0
        pen = -gap
        if pen > 0.0:
            Fc = K_cb * pen - C_cb * gdot
            if Fc < 0.0:
                Fc = 0.0
            Pd += (Fc - K_cb * pen) * (-gdot)
            Ue += 0.5 * K_cb * pen * pen
        Fn = Ff + Fc
        if Fn > Fmax:
            Fmax = Fn
        Ft -= w * Fn
        Pl += Ff * (-gdot)     # work of the film force on the closing gap
        # friction on the ball surface at the wall: viscous shear of the film + EHL / mixed friction
        if vs > 0.0:
            lr = MX.log(R * ih)
            if lr < 0.0:
                lr = 0.0
            f = math.pi * eta * R * vs * (3.2 * lr + 3.05)       # viscous shear
            if Fc > 0.0:
                ar = ks * ks * rk
                hm = _hd_pocket_film(0.5 * vs, eta, alpha_pv, Rs, 1.0339 * ar ** 0.636, E_red, Fc)
                ff = fluid_fraction(hm / hfl)
                mu_f = mu_ehl
                if hm > 0.0:
                    ae = (3.0 * Fc * Rs * math.sqrt(ar) / (2.0 * E_red)) ** (1.0 / 3.0)
                    pm = Fc / (math.pi * ae * ae)
                    ap = alpha_pv * pm
                    mu_n = eta * math.exp(ap if ap < 30.0 else 30.0) * vs / (hm * pm)
                    if mu_n < mu_f:
                        mu_f = mu_n
                mu = (1.0 - ff) * mu_bl + ff * mu_f
                f += mu * Fc * math.tanh(vs / v_reg)             # mixed / EHL friction in contact
            f *= ivs
            fr = -f * vsr
            fz = -f * vsz
            Fr += fr
            Fz += fz
            Mr += w * R * fz
            Mz -= w * R * fr
            Tw += w * R * fr
            Pl -= fr * vsr + fz * vsz
    return Fmax, Ft, Fr, Fz, Mr, Mz, Tw, Pl, Pd, Ue
