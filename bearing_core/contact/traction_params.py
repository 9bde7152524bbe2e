"""Layout of the traction parameter array and the quadrature of the Hertz ellipse: what every traction kernel
reads, dry (contact_kernels: Coulomb, illustrative curve) or lubricated (lubrication.ehl_traction: oil
rheology), so that both sit above this module and neither imports the other.

The parameter array is float64 of length N_TRACTION_PARAMS: slots P_* of the dry laws, then the oil's
rheology R_* (filled by lubrication.lubricants.rheology_traction_params); its P_LUBMODEL slot selects the law
(TRACTION_*)."""
from __future__ import annotations

import numpy as np

TRACTION_COULOMB = 0      # mu = mu0 tanh(|v| / v_reg)
TRACTION_CURVE = 1        # illustrative curve mu = (A + B s) exp(-C s) + D,  s = |v| / max(|u_roll|, u_min)
TRACTION_EHL = 2          # rheology-based EHL traction (bearing_core.lubrication.ehl_traction.ehl_ellipse_traction)
TRACTION_LUBRICATED = TRACTION_EHL
# layout of the traction parameter array (float64, length N_TRACTION_PARAMS): Coulomb / curve slots,
# then the oil's rheology (R_*)
P_MU0, P_VREG, P_A, P_B, P_C, P_D, P_UMIN = range(7)
# rheology slots (ehl_traction; filled by lubricants.rheology_traction_params), after the Coulomb / curve ones
(R_LUBMODEL, R_ETA0, R_LNE, R_Z, R_ALPHA, R_BETA, R_TAU0, R_TAUL0, R_GAML, R_GFILM, R_KOIL, R_EPRIME,
 R_GSC11, R_RCK, R_RQ, R_MUBL, R_VBL, R_RR, R_THERMAL, R_KGAM) = range(7, 27)
N_PARAMS = 27
P_LUBMODEL = R_LUBMODEL
N_TRACTION_PARAMS = N_PARAMS


def traction_params(mu0=0.1, v_reg=1e-3, A=0.0, B=0.0, C=0.0, D=0.0, u_min=1e-3):
    """Parameter array for traction_coefficient / ellipse_traction / ehl_traction.ehl_ellipse_traction.

    mu0 [-], v_reg [m/s] (Coulomb model); A, B, C, D [-] (illustrative curve mu(s) = (A + B s)
    exp(-C s) + D; A + D = 0 makes mu(0) = 0); u_min [m/s]: floor of the rolling speed in s and of the
    entrainment speed of the EHL model. The rheology slots stay 0 here (lubricants.rheology_traction_params
    fills them)."""
    p = np.zeros(N_TRACTION_PARAMS)
    p[P_MU0], p[P_VREG], p[P_A], p[P_B], p[P_C], p[P_D], p[P_UMIN] = mu0, v_reg, A, B, C, D, u_min
    p[P_LUBMODEL] = TRACTION_CURVE
    return p


def ellipse_quadrature(n_major, n_minor):
    """Nodes and weights (xi, w_xi, zeta, w_zeta) for ellipse_traction (not numba; build once).

    The ellipse is mapped to the unit disc, x = a xi, y = b sqrt(1 - xi^2) zeta. xi: Gauss-Legendre
    on [-1, 1] (n_major strips across the major axis); zeta: Gauss-Chebyshev of the 2nd kind,
    w_zeta already containing sqrt(1 - zeta^2) (n_minor points along each strip). With this choice
    the Hertz pressure integrates to Q exactly (to rounding) for any n >= 2."""
    xi, wxi = np.polynomial.legendre.leggauss(int(n_major))
    j = np.arange(1, int(n_minor) + 1)
    th = j * np.pi / (n_minor + 1)
    zeta = np.cos(th)
    wz = np.pi / (n_minor + 1) * np.sin(th) ** 2
    # exactly symmetric about the middle (cos(pi - t) = -cos(t) only to rounding), so that kernels can
    # evaluate the pressure-dependent terms once per mirrored pair (ehl_traction.ehl_ellipse_traction)
    zeta = 0.5 * (zeta - zeta[::-1])
    wz = 0.5 * (wz + wz[::-1])
    return (np.ascontiguousarray(xi), np.ascontiguousarray(wxi), np.ascontiguousarray(zeta),
            np.ascontiguousarray(wz))
