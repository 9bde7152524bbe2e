"""Numba kernels of the transient (Gupta-style) ball bearing model: right-hand side and integrators.

State layout (one float64 vector y; all SI), documented here once:

  y[0:5]    inner ring  x, y, z [m], tilt about x, tilt about y [rad]      (IR_POS)
  y[5:10]   their rates [m/s, rad/s]                                       (IR_VEL)
  y[10]     cage angle theta_c [rad]        y[11] cage speed [rad/s]
  y[12:14]  cage centre x_c, y_c [m]        y[14:16] their rates [m/s]
  y[16:18]  outer ring centre x_o, y_o [m] (elastic housing; 0 when fixed)   y[18:20] their rates [m/s]
  y[20 + 9 j + k], ball j (j = 0..nb-1):
            k = 0 orbital angle theta [rad], 1 radial position r of the centre [m], 2 axial position z [m],
                3 theta_dot [rad/s], 4 r_dot, 5 z_dot [m/s],
                6..8 absolute angular velocity (Omega_r, Omega_t, Omega_z) [rad/s] in the ball's local frame
                (r = radially out at theta, t = z x r = direction of increasing theta, z = bearing axis).

Frames and signs: bearing axis z, inner ring turning at omega(t) about +z (prescribed, either sign), outer
ring turning at the prescribed omega_o about +z (U_WO, default 0; its centre may translate in an elastic housing).
Every kernel is written for signed speeds (entrainment speeds enter as |u|), so a run mirrored in a plane through
the axis at -omega gives the mirrored motion. Ball-race geometry through the groove curvature centres exactly as in quasistatic.py (seed 003
Eqs. 3-8; Harris & Kotzalas Vol. 2 Ch. 3): for a ball at theta, X = B - O_o and C = O_i - O_o in (r, z),
C = (A cos a0 + x cos th + y sin th, A sin a0 + z + Ri (tx sin th - ty cos th)). Gothic-arch (four-point-
contact) grooves, P_EI / P_EO > 0: two arcs per ring, up to four contacts per ball, each through the
per-contact kernel _raceway_contact (arcs as in quasistatic.FourPointQuasiStaticModel; see rhs).

Equations of motion (Gupta, Advanced Dynamics of Rolling Elements, 1984, Ch. 3 and 5, written in the
frame turning with each ball's azimuth):
  m (r_dd - r th_d^2) = F_r,   m (r th_dd + 2 r_d th_d) = F_t,   m z_dd = F_z
  J (dOmega/dt)_local = M - J th_d z x Omega   (sphere: isotropic inertia, so the gyroscopic moment
                                               J th_d Omega_r of Jones-Harris appears on its own)
  inner ring (load-driven): m_i x_dd = F_ext + sum F_ball, I_t t_dd = M_ext + sum M_ball - gyro terms
  cage: I_c thc_dd = torque of pocket forces and land friction; m_c x_c_dd = pocket + land forces.

Contact geometry, contact kinematics, traction integrated over the Hertz ellipse and the ball-pocket
contact come from bearing_core.contact.contact_kernels (seed 002 section 2.2, seed 004 Eqs. 1-5, seed 000 Eq. 6):
lubricated traction from the oil's rheology over the same ellipse with mixed-lubrication load sharing and
the EHL rolling-resistance moment (bearing_core.lubrication.ehl_traction), the illustrative curve
mu(s) = (A + B s) exp(-C s) + D with s = |v| / max(u, u_min), regularised Coulomb
mu0 tanh(|v| / v_reg), or Kalker's simplified theory (bearing_core.contact.fastsim, seed 000 Eqs. 7-9) with
creepages from the same contact kinematics and the Hertz pressure as traction bound.
"""
from __future__ import annotations

import math

import numpy as np
from ..numerics.jit import hot

from ..contact.contact_kernels import (ball_race_contact, gothic_arch_contact, contact_kinematics_orb,
                                       ellipse_traction, ball_pocket_contact_rel, normal_contact_force, atan2,
                                       wrap_angle, DAMP_LINEAR, TRACTION_COULOMB, TRACTION_EHL, P_LUBMODEL)
from ..lubrication.pocket_film import ball_pocket_lubricated_rel
from ..lubrication.ehl_traction import ehl_ellipse_traction_into, ehl_pair_traction_into, ehl_scratch
from ..contact.fastsim import fastsim_traction_fast, PRESSURE_HERTZ
from ..lubrication.churning import cylinder_churning_torque
from ..lubrication.film import ellipticity_nb, film_parameter_nb, film_thickness_nb

NSTATE_FIXED = 20
NSB = 9  # states per ball

# ---- parameter vector indices (float64 array P) ------------------------------------------------
(P_Z, P_NB, P_D, P_DM, P_FI, P_FO, P_A0, P_MB, P_JB, P_MI, P_IT, P_IP, P_MC, P_IC,
 P_CPOCKET, P_KPOCKET, P_CPOCKETD, P_MUPOCKET, P_CLAND, P_KLAND, P_CLANDD, P_MULAND,
 P_RLAND, P_GUIDE, P_TRACTION, P_ZETA, P_RHO_EFF, P_CD, P_COUPLING, P_AXISYM, P_MULT,
 P_CRX, P_CRY, P_CRZ, P_CRTX, P_CRTY, P_FIXTILT, P_MO, P_KH, P_CH, P_OUTER_ELASTIC,
 P_ETA_LAND, P_WLAND, P_GCOMB, P_NUCOMB, P_FS_NX, P_FS_NY,
 # oil churning (seed 001 Eqs. 12-17, bearing_core.lubrication.churning): switch, mixture density and viscosity,
 # cage surface width / diameter / gap and its wall speed factor (0 fixed wall, 1 shaft-speed wall),
 # inner-ring churned width / shoulder diameter / gap
 P_CH_ON, P_CH_RHO, P_CH_ETA, P_CH_BC, P_CH_DC, P_CH_CC, P_CH_WALL, P_CH_BIR, P_CH_DLI, P_CH_CS,
 # lubrication regime of the cage (0: dry Coulomb pocket and land, solid / dry bearings; 1: oil-lubricated
 # pocket, lubrication.pocket_film.ball_pocket_lubricated, and land), boundary and full-film friction coefficients,
 # oil viscosity and pressure-viscosity coefficient at the cage, reduced modulus ball-cage, composite
 # roughness ball-pocket
 # and the largest eccentricity ratio of the flooded land's film force (legacy 0.95)
 P_LUBE, P_MUBL, P_MUEHL, P_ETA_PK, P_ALPHA_PK, P_EPK, P_SIGPK, P_EPSMAX,
 # gothic-arch (four-point-contact) grooves: offset e of the two curvature centres of the inner and the
 # outer groove from their groove mid-planes [m] (0: single-arc grooves, two-point contact)
 P_EI, P_EO,
 # film of the flooded guiding land: 0 the film of a cage centre at rest (seed 001 Eq. 4), 1 with the whirl
 # and squeeze terms of a moving centre (DynamicsOptions.land_film, _cage_flooded_land)
 P_LANDFILM,
 NPAR) = range(69)

# ---- input vector indices (float64 array U, held over an advance call) --------------------------
(U_W0, U_W1, U_T0, U_T1, U_FX, U_FY, U_FZ, U_MX, U_MY,
 U_DX, U_DY, U_DZ, U_TX, U_TY, U_VX, U_VY, U_VZ, U_WX, U_WY,
 U_WO,                      # outer-ring speed about +z [rad/s] (held)
 NU) = range(21)

# ---- output channels (per recorded instant) -----------------------------------------------------
OUT_NAMES = (
    "t", "shaft_speed", "shaft_accel", "cage_speed", "cage_x", "cage_y",
    "Fx", "Fy", "Fz", "Mx", "My",                        # reaction of the bearing on the shaft
    "ir_x", "ir_y", "ir_z", "ir_tx", "ir_ty",
    "ir_vx", "ir_vy", "ir_vz", "ir_ax", "ir_ay", "ir_az",
    "friction_torque",                                  # torque needed to drive the inner ring [N m]
    "P_drive", "P_ext",
    "P_race_inner", "P_race_outer", "P_pocket", "P_land", "P_drag", "P_damping",
    "P_race_slide", "P_race_spin", "P_race_diffslip",    # the race losses split by motion (both races)
    "P_churn_cage", "P_churn_ring",                      # oil churning of cage and inner ring (seed 001)
    "KE", "U_elastic",
    "alpha_i_mean", "alpha_o_mean", "Q_i_max", "Q_o_max", "Q_i_min",
    "pure_rolling_cage_speed", "pure_rolling_cage_speed_jh",
    "ball0_wr", "ball0_wt", "ball0_wz", "ball0_orbit_speed",
    "ball0_slide_roll_i", "ball0_slide_roll_o", "ball0_spin_roll_i", "ball0_spin_roll_o",
    "ball0_alpha_i", "ball0_alpha_o", "ball0_Q_i", "ball0_Q_o", "ball0_Ft_i", "ball0_Ft_o",
    "p_max", "outer_x", "outer_y", "housing_Fx", "housing_Fy",
    # pure-rolling cage speed at each loaded ball's own contact angles (Harris & Kotzalas Vol. 2 Ch. 3
    # cage speed with raceway control), averaged over the balls loaded at both races: outer / inner control
    "cage_speed_pure_rolling_outer", "cage_speed_pure_rolling_inner",
    "outer_ring_speed", "friction_torque_outer",         # outer ring: prescribed speed, torque to drive it [N m]
)
NOUT = len(OUT_NAMES)
OUT_INDEX = {n: i for i, n in enumerate(OUT_NAMES)}
for _i, _n in enumerate(OUT_NAMES):   # O_<NAME> integer constants, compile-time globals for numba
    globals()["O_" + _n.upper()] = _i

# per-ball diagnostics columns (ball_details)
(BD_AI, BD_AO, BD_QI, BD_QO, BD_DI, BD_DO, BD_AI_SEMI, BD_BI, BD_AO_SEMI, BD_BO, BD_PI, BD_PO,
 BD_FTI, BD_FMI, BD_FTO, BD_FMO, BD_VSI, BD_VSO, BD_UI, BD_UO, BD_SPI, BD_SPO, BD_WSI, BD_WSO,
 BD_FPOCKET,
 # contributions of the ball to the ring / cage / outer-ring loads (for the implicit integrator's Jacobian)
 BD_CFRX, BD_CFRY, BD_CFRZ, BD_CMRX, BD_CMRY, BD_CFCX, BD_CFCY, BD_CTC, BD_CFOX, BD_CFOY,
 # four-point contact: load [N] and contact angle [rad] of the second (less loaded) arc of each ring
 # (BD_QI / BD_AI ... hold the more loaded one; 0 load for two-point bearings)
 BD_QI2, BD_AI2, BD_QO2, BD_AO2, NBD) = range(40)
NCB = 10
CB_ROWS = np.array([5, 6, 7, 8, 9, 14, 15, 11, 18, 19])   # rows of dy that the channels BD_CFRX.. enter


@hot
def _shaft(U, t):
    """Shaft speed and acceleration: linear ramp from U_W0 at U_T0 to U_W1 at U_T1, held outside."""
    t0 = U[U_T0]
    t1 = U[U_T1]
    if t1 <= t0:
        return U[U_W1], 0.0
    if t <= t0:
        return U[U_W0], 0.0
    if t >= t1:
        return U[U_W1], 0.0
    acc = (U[U_W1] - U[U_W0]) / (t1 - t0)
    return U[U_W0] + acc * (t - t0), acc


@hot(nrt=True)
def _kalker_traction(a, b, Q, mu, Gc, nuc, vs_t, vs_m, wsp, ur, fnx, fny, D):
    """Traction of one ball-race contact by FASTSIM (fastsim.fastsim_traction_fast; seed 000 Eqs. 7-9), as
    _race_traction. Scalar arguments; compiled with reference counting (set explicitly, so that it is not
    taken over from the caller): FASTSIM allocates its strip arrays."""
    ft, fm, mn, pl = fastsim_traction_fast(a, b, Q, mu, Gc, nuc, vs_t, vs_m, wsp, ur, fnx, fny, PRESSURE_HERTZ)
    # the shear acts on the contact surface, D/2 from the ball centre
    return ft, fm, mn, 0.5 * D * ft, -0.5 * D * fm, pl


@hot(nrt=False)
def _race_traction(kalker, a, b, Q, p, D, Rdef, Rx, Ry, vs_t, vs_m, wsp, wrm, wrt, ur, tmodel, tp, Gc, nuc, fnx,
                   fny, qx, qwx, qy, qwy, sc):
    """Traction of one ball-race contact on the ball: (F_t, F_m [N], M_n, M_m, M_t [N m], P_loss [W]) by
    FASTSIM (kalker, _kalker_traction), the rheology-based EHL traction with rolling resistance
    (ehl_traction.ehl_ellipse_traction_into; Rx, Ry [m] the contact's effective radii; sc =
    ehl_traction.ehl_scratch of the quadrature) or the ellipse-integrated curve / Coulomb law
    (contact_kernels.ellipse_traction). Compiled without reference counting (jit.hot(nrt=False)), as are
    ellipse_traction and ehl_ellipse_traction_into: the parameter, quadrature and scratch arrays, owned by
    the caller, are not reference-counted per contact (two atomic operations per array and call otherwise,
    ~2 us per right-hand side)."""
    if kalker:
        return _kalker_traction(a, b, Q, tp[0], Gc, nuc, vs_t, vs_m, wsp, ur, fnx, fny, D)
    if tmodel == TRACTION_EHL:
        return ehl_ellipse_traction_into(a, b, p, D, Rdef, Rx, Ry, vs_t, vs_m, wsp, wrm, wrt, ur, tp, sc)
    return ellipse_traction(a, b, p, D, Rdef, vs_t, vs_m, wsp, wrm, wrt, ur, tmodel, tp, qx, qwx, qy, qwy)


@hot
def _raceway_contact(delta, n_r, n_z, Q, rb, rd, thd, zd, Wr, Wt, Wz, w_race, vcr, vct, vcz, D, gD,
                     zeta, mb):
    """Normal force and kinematics of one ball-raceway contact of the ball (rb, rd, thd, zd, Wr, Wt, Wz: state
    in its local frame) with a race turning at w_race [rad/s] whose curvature centre moves at (vcr, vct, vcz)
    [m/s]; contact geometry (delta [m], normal n from the ball centre, Hertz Q [N]) from contact_kernels.
    Normal damping linear in the deflection rate, zeta of critical for the ball mass on the local Hertz
    stiffness 1.5 Q / delta, only in contact and never pulling (contact_kernels.normal_contact_force);
    contact kinematics (contact_kernels.contact_kinematics); effective radius of the contact along the
    rolling direction Rx = D/2 (1 -+ D cos(alpha) / dm), inner / outer (Hamrock-Dowson), with
    cos(alpha) = -+ n_r; gD = D / dm.
    Returns (F_n [N] normal force with damping, P_damp [W], U_el [J] elastic energy 0.4 Q delta, Rx [m],
    then the kinematics vs_t, vs_m [m/s], w_spin, w_roll_m, w_roll_t [rad/s], u_roll [m/s]) for the
    traction (_race_traction). Scalar arguments only: no reference counting per contact."""
    Fn = Q
    pdamp = 0.0
    uel = 0.0
    if Q > 0.0:
        dd = (rd - vcr) * n_r + (zd - vcz) * n_z
        Fn = normal_contact_force(Q, delta, dd, DAMP_LINEAR, 2.0 * zeta * math.sqrt(1.5 * Q / delta * mb))
        pdamp = (Fn - Q) * dd
        uel = 0.4 * Q * delta
    vs_t, vs_m, wsp, wrm, wrt, ur = contact_kinematics_orb(rb, rd, rb * thd, zd, thd, Wr, Wt, Wz, w_race, vcr, vct,
                                                           vcz, n_r, n_z, D)
    # cos(alpha) = -n_r (inner) or n_r (outer): the contact angle from the normal (contact_kernels)
    Rx = 0.5 * D * (1.0 + gD * n_r)
    return Fn, pdamp, uel, Rx, vs_t, vs_m, wsp, wrm, wrt, ur


@hot
def _first_arc(c1, c2):
    """True if arc 1 is the first (more loaded) contact of a gothic-arch ring: the valid arc, of two valid
    ones the more loaded, of two unloaded ones the less separated (c1, c2: gothic_arch_contact results)."""
    if not c2[0]:
        return True
    if not c1[0]:
        return False
    if c1[5] != c2[5]:
        return c1[5] > c2[5]
    return c1[1] >= c2[1]


@hot(inline="always")
def _ring_pose(y, U, disp):
    """Inner-ring pose and rates (x, y, z, tilt x, tilt y, then their rates) at the state y, or the inputs U
    when displacement-driven."""
    if disp:
        # displacement-driven: ring pose and rates are inputs (held over the step)
        return U[U_DX], U[U_DY], U[U_DZ], U[U_TX], U[U_TY], U[U_VX], U[U_VY], U[U_VZ], U[U_WX], U[U_WY]
    return y[0], y[1], y[2], y[3], y[4], y[5], y[6], y[7], y[8], y[9]


@hot(inline="always")
def _groove_centres(th, rb, zb, Cr0, Cz0, Ri, Roo, Zoo, xi_, yi_, zi_, txi, tyi, vxi, vyi, vzi, wxi, wyi, xo, yo,
                    vxo, vyo):
    """The ball's azimuth (c, s) = (cos th, sin th), the inner groove centre C = (Cr, Cz) and its velocity
    (vrr, vrt, vrz) in the ball's local frame, the ball centre relative to the outer groove centre X = (Xr,
    Xz) and the outer ring's translation velocity (vor, vot) in the local frame (module docstring)."""
    c = math.cos(th)
    s = math.sin(th)
    # groove centres (QS mapping) and their rates
    Cr = Cr0 + xi_ * c + yi_ * s
    Cz = Cz0 + zi_ + Ri * (txi * s - tyi * c)
    vrr = vxi * c + vyi * s                    # ring translation velocity at the ball, local frame
    vrt = -vxi * s + vyi * c
    vrz = vzi + Ri * (wxi * s - wyi * c)
    Xr = rb - Roo - (xo * c + yo * s)      # outer groove centre moves with the outer ring
    Xz = zb - Zoo
    vor = vxo * c + vyo * s                # outer ring translation velocity, local frame
    vot = -vxo * s + vyo * c
    return c, s, Cr, Cz, vrr, vrt, vrz, Xr, Xz, vor, vot


@hot(inline="always")
def _inner_race_traction_loads(Fr, Ft, Fz, Mr, Mt, Mz, P_ri, P_sl, P_sp, TRz, rb, Fni, nir, niz, fti, fmi, mni,
                               mmi, mti, pli, vsti, vsmi, wspi):
    """Traction of the first inner contact added to the ball's forces and moments, the race losses and the
    torque on the inner ring about z; returns these and the contact's load on the ring (radial, tangential,
    axial) in the ball's local frame."""
    # traction, inner race (contact_kernels: force on the ball along t and m = (-n_z, n_r), moments
    # along n, m, t about the ball centre)
    Fr += -fmi * niz; Ft += fti; Fz += fmi * nir
    Mr += mni * nir - mmi * niz; Mt += mti; Mz += mni * niz + mmi * nir
    P_ri += pli
    P_sl -= fti * vsti + fmi * vsmi   # sliding of the contact centre (rolling direction and across)
    P_sp -= mni * wspi                # spin about the contact normal
    # the ring receives the normal force and the opposite traction; torque about z at the contact
    fr_ring = Fni * nir + fmi * niz
    ft_ring = -fti
    fz_ring = Fni * niz - fmi * nir
    # torque of the traction about the bearing axis, exact for the distributed shear: on the ball it is
    # rb F_t + (M about the ball centre) . z = rb F_t + n_z M_n + n_r M_m; the ring gets the opposite
    TRz -= rb * fti + niz * mni + nir * mmi
    return Fr, Ft, Fz, Mr, Mt, Mz, P_ri, P_sl, P_sp, TRz, fr_ring, ft_ring, fz_ring


@hot(inline="always")
def _outer_race_traction_loads(Fr, Ft, Fz, Mr, Mt, Mz, P_ro, P_sl, P_sp, FOx, FOy, TOz, c, s, rb, Fno, nor, noz,
                               fto, fmo, mno, mmo, mto, plo, vsto, vsmo, wspo):
    """Traction of the first outer contact (race turning at wo) added to the ball's forces and moments, the
    race losses, and the contact's load on the outer ring (global x, y and torque about z)."""
    # traction, outer race (turning at wo)
    Fr += -fmo * noz; Ft += fto; Fz += fmo * nor
    Mr += mno * nor - mmo * noz; Mt += mto; Mz += mno * noz + mmo * nor
    P_ro += plo
    P_sl -= fto * vsto + fmo * vsmo
    P_sp -= mno * wspo
    # the outer ring receives the normal force and the opposite traction (radial / tangential parts)
    for_r = Fno * nor + fmo * noz
    for_t = -fto
    FOx += for_r * c - for_t * s
    FOy += for_r * s + for_t * c
    TOz -= rb * fto + noz * mno + nor * mmo
    return Fr, Ft, Fz, Mr, Mt, Mz, P_ro, P_sl, P_sp, FOx, FOy, TOz


@hot(inline="always")
def _second_inner_arc(Fr, Ft, Fz, Mr, Mt, Mz, P_ri, P_sl, P_sp, P_dp, Uel, TRz, cb, ball, w, vrr, zib, tdot, vrt,
                      vrz, D, gD, zeta, mb, Rdi, Ryi, trac):
    """Second inner arc of a four-point bearing (cb, loaded): the same contact kernel as the first contact,
    its loads added to the ball, the losses and the ring's torque about z; returns these and the arc's load
    on the ring (radial, tangential, axial) in the ball's local frame. ball = (rb, rd, thd, zd, Wr, Wt, Wz):
    the ball's state in its local frame; trac = (kalker, tmodel, tp, Gc, nuc, fnx, fny, qx, qwx, qy, qwy,
    sc): the traction model and its arrays (set up in rhs)."""
    rb, rd, thd, zd, Wr, Wt, Wz = ball
    kalker, tmodel, tp, Gc, nuc, fnx, fny, qx, qwx, qy, qwy, sc = trac
    _, dli2, nir2, niz2, ai2, Qi2, ai2_s, bi2_s, pi2 = cb
    (Fn2, pd2, ue2, Rx2, vst2, vsm2, wsp2, wrm2, wrt2,
     ur2) = _raceway_contact(dli2, nir2, niz2, Qi2, rb, rd, thd, zd, Wr, Wt, Wz, w,
                             vrr - zib * tdot, vrt, vrz, D, gD, zeta, mb)
    ft2, fm2, mn2, mm2, mt2, pl2 = _race_traction(kalker, ai2_s, bi2_s, Qi2, pi2, D, Rdi, Rx2, Ryi, vst2,
                                                  vsm2, wsp2, wrm2, wrt2, ur2, tmodel, tp, Gc, nuc, fnx,
                                                  fny, qx, qwx, qy, qwy, sc)
    P_dp += pd2; Uel += ue2
    Fr += -Fn2 * nir2 - fm2 * niz2; Ft += ft2; Fz += -Fn2 * niz2 + fm2 * nir2
    Mr += mn2 * nir2 - mm2 * niz2; Mt += mt2; Mz += mn2 * niz2 + mm2 * nir2
    P_ri += pl2
    P_sl -= ft2 * vst2 + fm2 * vsm2
    P_sp -= mn2 * wsp2
    fr2_ring = Fn2 * nir2 + fm2 * niz2
    ft2_ring = -ft2
    fz2_ring = Fn2 * niz2 - fm2 * nir2
    TRz -= rb * ft2 + niz2 * mn2 + nir2 * mm2
    return Fr, Ft, Fz, Mr, Mt, Mz, P_ri, P_sl, P_sp, P_dp, Uel, TRz, fr2_ring, ft2_ring, fz2_ring


@hot(inline="always")
def _second_outer_arc(Fr, Ft, Fz, Mr, Mt, Mz, P_ro, P_sl, P_sp, P_dp, Uel, FOx, FOy, TOz, ob, c, s, ball, wo, vor,
                      vot, D, gD, zeta, mb, Rdo, Ryo, trac):
    """Second outer arc of a four-point bearing (ob, loaded): the same contact kernel, its loads added to the
    ball, the losses and the outer ring (global x, y, torque about z). ball, trac: _second_inner_arc."""
    rb, rd, thd, zd, Wr, Wt, Wz = ball
    kalker, tmodel, tp, Gc, nuc, fnx, fny, qx, qwx, qy, qwy, sc = trac
    _, dlo2, nor2, noz2, ao2, Qo2, ao2_s, bo2_s, po2 = ob
    (Fn2, pd2, ue2, Rx2, vst2, vsm2, wsp2, wrm2, wrt2,
     ur2) = _raceway_contact(dlo2, nor2, noz2, Qo2, rb, rd, thd, zd, Wr, Wt, Wz, wo, vor, vot,
                             0.0, D, gD, zeta, mb)
    ft2, fm2, mn2, mm2, mt2, pl2 = _race_traction(kalker, ao2_s, bo2_s, Qo2, po2, D, Rdo, Rx2, Ryo, vst2,
                                                  vsm2, wsp2, wrm2, wrt2, ur2, tmodel, tp, Gc, nuc, fnx,
                                                  fny, qx, qwx, qy, qwy, sc)
    P_dp += pd2; Uel += ue2
    Fr += -Fn2 * nor2 - fm2 * noz2; Ft += ft2; Fz += -Fn2 * noz2 + fm2 * nor2
    Mr += mn2 * nor2 - mm2 * noz2; Mt += mt2; Mz += mn2 * noz2 + mm2 * nor2
    P_ro += pl2
    P_sl -= ft2 * vst2 + fm2 * vsm2
    P_sp -= mn2 * wsp2
    for_r = Fn2 * nor2 + fm2 * noz2
    for_t = -ft2
    FOx += for_r * c - for_t * s
    FOy += for_r * s + for_t * c
    TOz -= rb * ft2 + noz2 * mn2 + nor2 * mm2
    return Fr, Ft, Fz, Mr, Mt, Mz, P_ro, P_sl, P_sp, P_dp, Uel, FOx, FOy, TOz


@hot(inline="always")
def _ball_pocket(Fr, Ft, Fz, Mr, Mz, FCx, FCy, TC, Uel, P_dp, P_pk, j, Z, th, c, s, ball, thc, wc, xc, yc, vxc,
                 vyc, D, lube, pocket):
    """Ball-pocket contact of ball j (dry Coulomb or lubricated pocket; pocket = (clearance, stiffness,
    damping, friction coefficient, then for the lubricated pocket the boundary and full-film friction
    coefficients, viscosity, pressure-viscosity coefficient, reduced modulus, roughness: P_CPOCKET ..
    P_MUPOCKET, P_MUBL, P_MUEHL, P_ETA_PK .. P_SIGPK)) added to the ball's forces and moments, to the cage's
    forces and torque and to the elastic energy, damping and pocket losses; returns these and the pocket
    force Fpk. ball: _second_inner_arc. Scalar arguments only: inlined without reference counting."""
    rb, rd, thd, zd, Wr, Wt, Wz = ball
    cpk, kpk, cpkd, mupk, mubl, muehl, eta_pk, alpha_pk, epk, sigpk = pocket
    # ball-pocket contact (seed 000 Eq. 6, contact_kernels.ball_pocket_contact) in the frame of the
    # (possibly whirling) cage: ball azimuth about the cage centre against the pocket azimuth
    # dth: azimuth of the ball centre about the cage centre minus the pocket azimuth thc + 2 pi j / Z,
    # = (th - pocket azimuth) + the angle of the ball centre seen from the cage centre against the ball's
    # radial direction (c, s), small (cage offset over pitch radius): no arctangent of a full angle, and
    # a wrap only if the state puts the ball a turn away from its pocket
    d0 = th - thc - 2.0 * math.pi * j / Z
    if abs(d0) > math.pi:
        d0 = wrap_angle(d0)
    dth = d0 + atan2(xc * s - yc * c, rb - xc * c - yc * s)
    bx_ = rb * c - xc
    by_ = rb * s - yc
    rr2 = bx_ * bx_ + by_ * by_
    vbx = rd * c - rb * thd * s - vxc
    vby = rd * s + rb * thd * c - vyc
    vcr_ = vxc * c + vyc * s
    rbc = math.sqrt(rr2)   # ball radius about the cage centre: the arm of the pocket force
    irbc = 1.0 / rbc
    thb_d = (bx_ * vby - by_ * vbx) * (irbc * irbc)
    if lube:
        (Fpk, fpt, fpr, fpz, mpr, mpz, tw_, pl_, pd_, ue_) = ball_pocket_lubricated_rel(
            dth, thb_d, wc, rbc, cpk, kpk, cpkd, mubl, muehl, 0.01, eta_pk,
            alpha_pk, epk, sigpk, D, rd, zd, Wr, Wz, vcr_, 0.0)
    else:
        Fpk, fpt, fpr, fpz, mpr, mpz = ball_pocket_contact_rel(dth, thb_d, wc, rbc, cpk, kpk, cpkd, mupk,
                                                               0.01, D, rd, zd, Wr, Wz, vcr_, 0.0)
        tw_ = pl_ = pd_ = ue_ = 0.0
    if lube or Fpk > 0.0:
        # pocket force along the cage-frame tangential direction at the ball; the cage gets (-fx, -fy) at
        # the ball centre (a torque about its centre) and the films' shear torque tw_
        tpx = -by_ * irbc         # (-sin, cos) of the ball's azimuth about the cage centre
        tpy = bx_ * irbc
        fx = fpt * tpx + fpr * c
        fy = fpt * tpy + fpr * s
        Fr += fx * c + fy * s
        Ft += -fx * s + fy * c
        Fz += fpz
        Mr += mpr
        Mz += mpz
        FCx -= fx
        FCy -= fy
        TC += by_ * fx - bx_ * fy + tw_
    if lube:
        Uel += ue_
        P_dp += pd_
        P_pk += pl_
    elif Fpk > 0.0:
        sg = 1.0 if fpt < 0.0 else -1.0                         # side of the pocket wall (+t or -t)
        TC += sg * 0.5 * D * fpr       # the wall friction acts at the offset sg D/2 t: torque on the cage
        pen = rbc * abs(dth) - cpk
        Uel += 0.5 * kpk * pen * pen
        # dissipation: friction and damping of the pocket contact = -(power of its forces on the
        # relative motion) - d(elastic energy)/dt, evaluated from the relative velocities
        vrel_t = (thb_d - wc) * rbc
        P_dp += (Fpk - kpk * pen) * vrel_t * sg
        vsr = rd - vcr_ - sg * 0.5 * D * (Wz - wc)
        vsz = zd + sg * 0.5 * D * Wr
        P_pk -= fpr * vsr + fpz * vsz
    return Fpk, Fr, Ft, Fz, Mr, Mz, FCx, FCy, TC, Uel, P_dp, P_pk


@hot(inline="always")
def _ball_drag(Ft, P_dr, rb, thd, wc, rp, rho_eff, cd, D):
    """Drag of the ball in the oil-air mixture added to its tangential force and to the drag loss."""
    # ball drag in the oil-air mixture (seed 001 Eq. 10): opposes the orbital motion
    vorb = rb * thd - wc * rp * 0.0
    Fd = 0.5 * rho_eff * cd * (math.pi * D * D / 4.0) * vorb * abs(vorb)
    Ft -= Fd
    P_dr += Fd * vorb
    return Ft, P_dr


@hot(inline="always")
def _ball_eom(Fr, Ft, Fz, Mr, Mt, Mz, rb, rd, thd, Wr, Wt, imb, iJb):
    """Equations of motion of a ball (module docstring) under the forces (Fr, Ft, Fz) and moments (Mr, Mt,
    Mz) in its local frame, imb = 1 / m, iJb = 1 / J: (theta_dd, r_dd, z_dd, dOmega_r, dOmega_t,
    dOmega_z) / dt."""
    return ((Ft * imb - 2.0 * rd * thd) / rb, Fr * imb + rb * thd * thd, Fz * imb,
            Mr * iJb + thd * Wt, Mt * iJb - thd * Wr, Mz * iJb)


@hot(inline="always")
def _inner_ring_loads(FRx, FRy, FRz, MRx, MRy, axisym, fourpt, c, s, Ri, zia, zib, fr_ring, ft_ring, fz_ring,
                      fr2_ring, ft2_ring, fz2_ring):
    """The loads of one ball's inner contacts (local radial, tangential, axial; second arc for four-point
    bearings) added to the inner ring's forces and tilting moments (global)."""
    # ring loads from ball j (global)
    gx = fr_ring * c - ft_ring * s
    gy = fr_ring * s + ft_ring * c
    if not axisym:
        FRx += gx
        FRy += gy
        MRx += Ri * s * fz_ring
        MRy += -Ri * c * fz_ring
    FRz += fz_ring
    if fourpt:
        # second inner arc, and the arms z = +-e_i of the arc centres above the inner-ring mid-plane:
        # the force (fr, ft, fz) at Ri e_r + z e_z has the moment Ri fz - z fr about e_t and -z ft about e_r
        FRz += fz2_ring
        if not axisym:
            FRx += fr2_ring * c - ft2_ring * s
            FRy += fr2_ring * s + ft2_ring * c
            MRx += (Ri * s * fz2_ring - zia * (fr_ring * s + ft_ring * c)
                    - zib * (fr2_ring * s + ft2_ring * c))
            MRy += (-Ri * c * fz2_ring + zia * (fr_ring * c - ft_ring * s)
                    + zib * (fr2_ring * c - ft2_ring * s))
    return FRx, FRy, FRz, MRx, MRy


@hot(inline="always")
def _contact_statistics(sai, nai, sao, nao, Qimax, Qomax, Qimin, pmax, sco, sci, npr, fourpt, w, wo, gD, ai, ao,
                        nir, niz, nor, noz, Qi, Qo, Qi2, Qo2, pi_, po, pi2, po2):
    """One ball added to the contact statistics: sums and counts of the loaded contact angles, largest /
    smallest loads, largest pressure, sums of the pure-rolling cage speeds of the balls loaded at both
    races."""
    # four-point contact: the first contacts' angles by magnitude (a diagonal pair i2/o2 is the mirror
    # image of i1/o1, with the same pure-rolling cage speed; a ball on i1 and o2 gets the estimate of
    # equal-sign angles)
    ai_k = abs(ai) if fourpt else ai
    ao_k = abs(ao) if fourpt else ao
    sai_k = abs(niz) if fourpt else -niz      # sin of ai_k, ao_k from the contact normals
    sao_k = abs(noz) if fourpt else noz
    if Qi > 0.0:
        sai += ai_k; nai += 1.0
        Qimax = max(Qimax, Qi)
        pmax = max(pmax, pi_)          # p_max = 1.5 Q / (pi a b) of the contact kernel
    Qimin = min(Qimin, Qi)
    if Qi > 0.0 and Qo > 0.0:
        wco, wci = pure_rolling_cage_speeds_cs(w, -nir, sai_k, nor, sao_k, gD, wo)
        sco += wco; sci += wci; npr += 1.0
    if Qo > 0.0:
        sao += ao_k; nao += 1.0
        Qomax = max(Qomax, Qo)
        pmax = max(pmax, po)
    if Qi2 > 0.0:
        Qimax = max(Qimax, Qi2)
        pmax = max(pmax, pi2)
    if Qo2 > 0.0:
        Qomax = max(Qomax, Qo2)
        pmax = max(pmax, po2)
    return sai, nai, sao, nao, Qimax, Qomax, Qimin, pmax, sco, sci, npr


@hot(nrt=False)
def _ball_details(bd, j, ca, cb, oa, ob, tri_t, tri_m, tro_t, tro_m, sl_i, sl_o, u_i, u_o, sp_i, sp_o, sm_i, sm_o,
                  Fpk, contrib):
    """Row j of the per-ball details bd (BD_* columns): contacts, traction, kinematics, pocket force and the
    ball's contributions contrib = (dFRx, dFRy, dFRz, dMRx, dMRy, dFCx, dFCy, dTC, dFOx, dFOy) to the ring,
    cage and outer-ring loads. Stores only; compiled without reference counting (bd owned by the caller)."""
    dFRx, dFRy, dFRz, dMRx, dMRy, dFCx, dFCy, dTC, dFOx, dFOy = contrib
    _, dli, nir, niz, ai, Qi, ai_s, bi_s, pi_ = ca
    _, dlo, nor, noz, ao, Qo, ao_s, bo_s, po = oa
    _, dli2, nir2, niz2, ai2, Qi2, ai2_s, bi2_s, pi2 = cb
    _, dlo2, nor2, noz2, ao2, Qo2, ao2_s, bo2_s, po2 = ob
    bd[j, BD_QI2] = Qi2; bd[j, BD_AI2] = ai2; bd[j, BD_QO2] = Qo2; bd[j, BD_AO2] = ao2
    bd[j, BD_AI] = ai; bd[j, BD_AO] = ao; bd[j, BD_QI] = Qi; bd[j, BD_QO] = Qo
    bd[j, BD_DI] = dli; bd[j, BD_DO] = dlo
    bd[j, BD_AI_SEMI] = ai_s; bd[j, BD_BI] = bi_s; bd[j, BD_AO_SEMI] = ao_s; bd[j, BD_BO] = bo_s
    bd[j, BD_PI] = pi_
    bd[j, BD_PO] = po
    bd[j, BD_FTI] = tri_t; bd[j, BD_FMI] = tri_m; bd[j, BD_FTO] = tro_t; bd[j, BD_FMO] = tro_m
    bd[j, BD_VSI] = sl_i; bd[j, BD_VSO] = sl_o; bd[j, BD_UI] = u_i; bd[j, BD_UO] = u_o
    bd[j, BD_SPI] = sp_i; bd[j, BD_SPO] = sp_o; bd[j, BD_WSI] = sm_i; bd[j, BD_WSO] = sm_o
    bd[j, BD_FPOCKET] = Fpk
    bd[j, BD_CFRX] = dFRx; bd[j, BD_CFRY] = dFRy; bd[j, BD_CFRZ] = dFRz
    bd[j, BD_CMRX] = dMRx; bd[j, BD_CMRY] = dMRy
    bd[j, BD_CFCX] = dFCx; bd[j, BD_CFCY] = dFCy; bd[j, BD_CTC] = dTC
    bd[j, BD_CFOX] = dFOx; bd[j, BD_CFOY] = dFOy


@hot(nrt=False)
def _ball0_channels(diag, D, Wr, Wt, Wz, thd, sl_i, sl_o, u_i, u_o, sp_i, sp_o, ai, ao, Qi, Qo, tri_t, tro_t):
    """The output channels of ball 0 (spin, orbit speed, slide / spin to roll ratios, contacts); compiled
    without reference counting (diag owned by the caller)."""
    diag[O_BALL0_WR] = Wr
    diag[O_BALL0_WT] = Wt
    diag[O_BALL0_WZ] = Wz
    diag[O_BALL0_ORBIT_SPEED] = thd
    diag[O_BALL0_SLIDE_ROLL_I] = sl_i / max(u_i, 1e-12)
    diag[O_BALL0_SLIDE_ROLL_O] = sl_o / max(u_o, 1e-12)
    diag[O_BALL0_SPIN_ROLL_I] = sp_i * 0.5 * D / max(u_i, 1e-12)
    diag[O_BALL0_SPIN_ROLL_O] = sp_o * 0.5 * D / max(u_o, 1e-12)
    diag[O_BALL0_ALPHA_I] = ai
    diag[O_BALL0_ALPHA_O] = ao
    diag[O_BALL0_Q_I] = Qi
    diag[O_BALL0_Q_O] = Qo
    diag[O_BALL0_FT_I] = tri_t
    diag[O_BALL0_FT_O] = tro_t


@hot(inline="always")
def _cage_land_contact(e, cl, xc, yc, vxc, vyc, wc, w, wo, lube, P, FCx, FCy, FRx, FRy, FOx, FOy, TC, TRz, TOz,
                       P_dp, Uel):
    """Dry contact of the cage with its guiding land at eccentricity e > clearance cl: forces and friction
    torque on the cage and the guiding ring, damping and land losses, elastic energy. Returns the land loss
    P_ld and the updated loads and energies."""
    P_ld = 0.0
    pen = e - cl
    ex = xc / e
    ey = yc / e
    ve = vxc * ex + vyc * ey
    Fl = max(P[P_KLAND] * pen + P[P_CLANDD] * ve, 0.0)
    P_dp += (Fl - P[P_KLAND] * pen) * ve
    Uel += 0.5 * P[P_KLAND] * pen * pen
    FCx -= Fl * ex
    FCy -= Fl * ey
    if P[P_GUIDE] > 0.5:        # the guiding land takes the opposite force: inner ring or outer ring
        FRx += Fl * ex
        FRy += Fl * ey
    else:
        FOx += Fl * ex
        FOy += Fl * ey
    vsl = (wc - wo) * P[P_RLAND]    # land turning with the outer ring or with the shaft (inner)
    if P[P_GUIDE] > 0.5:
        vsl = (wc - w) * P[P_RLAND]
    muf = (P[P_MUBL] if lube else P[P_MULAND]) * math.tanh(vsl / 0.01)
    TC -= muf * Fl * P[P_RLAND]
    P_ld += muf * Fl * vsl
    if P[P_GUIDE] > 0.5:
        TRz += muf * Fl * P[P_RLAND]   # inner-land guided: the ring gets the opposite friction torque
    else:
        TOz += muf * Fl * P[P_RLAND]
    return P_ld, FCx, FCy, FRx, FRy, FOx, FOy, TC, TRz, TOz, P_dp, Uel


@hot(inline="always")
def _cage_flooded_land(eta, e, cl, xc, yc, vxc, vyc, wc, w, wo, P, FCx, FCy, FRx, FRy, FOx, FOy, TC, TRz, TOz,
                       P_ld):
    """Oil film of the flooded guiding land (viscosity eta > 0): film force and drag torque on the cage and
    the guiding ring, added to the land loss."""
    # oil-flooded guiding land: short journal bearing (seed 001 Eq. 4; Ocvirk, Hamrock 'Fundamentals of
    # Fluid Film Lubrication' Ch. 12) and Petroff drag torque with eccentricity (seed 001 Eq. 5).
    # Seed 001's Eq. 4 is the film of a cage centre at rest (P_LANDFILM 0, 'stationary'). 'moving' (1) adds
    # the Reynolds equation's dh/dt for a moving centre: the line of centres turning at phid replaces the sum
    # of the surface speeds by (wg + wc - 2 phid), and the approach rate adds the squeeze film, both over
    # the same half-Sommerfeld pi film (Childs, 'Turbomachinery Rotordynamics', 1993, Sec. 3.6; San Andres,
    # 'Modern Lubrication Theory', short-length journal bearings). Without them the film drives any whirl of
    # the cage forward, at any whirl speed
    cg = cl
    R = P[P_RLAND]
    B = P[P_WLAND]
    wg = w if P[P_GUIDE] > 0.5 else wo
    eps = min(e / cg, P[P_EPSMAX])
    if e > 1e-15:
        ex = xc / e
        ey = yc / e
    else:
        ex = 1.0
        ey = 0.0
    if P[P_LANDFILM] > 0.5 and e > 1e-15:
        phid = (ex * vyc - ey * vxc) / e             # whirl: turning rate of the line of centres [rad/s]
        epsd = 0.0
        if e / cg < P[P_EPSMAX]:
            epsd = (ex * vxc + ey * vyc) / cg        # squeeze: d eps / dt [1/s] (none held at the film's limit)
        Us = R * (wg + wc - 2.0 * phid)
        q = 1.0 - eps * eps
        Kf = eta * R * B ** 3 / (cg * cg)
        sg = 1.0 if Us >= 0.0 else -1.0              # the pi film lies on the side the effective speed sets
        Fr_h = Kf * (abs(Us) / R * eps * eps / q ** 2 + math.pi * (1.0 + 2.0 * eps * eps) * epsd / (2.0 * q ** 2.5))
        Ft_h = Kf * (math.pi * Us / R * eps / (4.0 * q ** 1.5) + sg * 2.0 * eps * epsd / q ** 2)
    else:
        Us = R * (wg + wc)
        Fr_h = eta * abs(Us) * B ** 3 * eps * eps / (cg * cg * (1.0 - eps * eps) ** 2)
        Ft_h = math.pi * eta * Us * B ** 3 * eps / (4.0 * cg * cg * (1.0 - eps * eps) ** 1.5)
    fhx = -Fr_h * ex - Ft_h * ey
    fhy = -Fr_h * ey + Ft_h * ex
    FCx += fhx
    FCy += fhy
    if P[P_GUIDE] > 0.5:
        FRx -= fhx
        FRy -= fhy
    else:
        FOx -= fhx
        FOy -= fhy
    Th = 2.0 * math.pi * eta * R ** 3 * B * (wg - wc) / (cg * math.sqrt(1.0 - eps * eps))
    TC += Th
    if P[P_GUIDE] > 0.5:
        TRz -= Th
    else:
        TOz -= Th
    P_ld += Th * (wg - wc) - (fhx * vxc + fhy * vyc)
    return FCx, FCy, FRx, FRy, FOx, FOy, TC, TRz, TOz, P_ld


@hot(inline="always")
def _churning(P, wc, w, wo, TC, TRz, TOz):
    """Oil churning torques on the cage (reaction on the facing ring) and on the inner ring: returns the
    updated torques TC, TRz, TOz, the cage's and the ring's churning losses and the ring's torque T_chs."""
    # oil churning (seed 001 Eqs. 12-17 as torques, bearing_core.lubrication.churning): on the cage against its
    # speed relative to the facing wall, and on the inner ring (the drive supplies it)
    P_chc = 0.0
    P_chs = 0.0
    T_chs = 0.0
    if P[P_CH_ON] > 0.5:
        wrel = wc - (w if P[P_CH_WALL] > 0.5 else wo)      # facing wall: inner ring or outer ring
        Tch = cylinder_churning_torque(P[P_CH_RHO], P[P_CH_ETA], wrel, P[P_CH_BC], P[P_CH_DC], P[P_CH_CC])
        TC += Tch
        P_chc = -Tch * wrel
        if P[P_CH_WALL] > 0.5:
            TRz -= Tch            # the shaft-speed wall (inner ring) takes the reaction
        else:
            TOz -= Tch            # the outer-ring wall takes it (no power when the outer ring stands)
        T_chs = cylinder_churning_torque(P[P_CH_RHO], P[P_CH_ETA], w, P[P_CH_BIR], P[P_CH_DLI], P[P_CH_CS])
        P_chs = -T_chs * w
    return TC, TRz, TOz, P_chc, P_chs, T_chs


@hot(inline="always")
def _cage_eom(dy, P, axisym, wc, vxc, vyc, TC, FCx, FCy):
    """Equations of motion of the cage: dy[10:16]."""
    # cage equations
    dy[10] = wc
    dy[11] = TC / P[P_IC]
    dy[12] = vxc
    dy[13] = vyc
    dy[14] = FCx / P[P_MC]
    dy[15] = FCy / P[P_MC]
    if axisym:  # one representative ball: the cage cannot whirl
        dy[12] = 0.0; dy[13] = 0.0; dy[14] = 0.0; dy[15] = 0.0


@hot(inline="always")
def _outer_ring_eom(dy, diag, P, axisym, mult, xo, yo, vxo, vyo, FOx, FOy, KE, Uel, P_dp):
    """Equations of motion of the outer ring (dy[16:20]; fixed, or elastic housing) and its channels; returns
    KE, Uel, P_dp with the housing's share."""
    # outer ring: fixed, or elastically mounted in the housing (2 DOF, stiffness kh, damping ch)
    hx = P[P_KH] * xo + P[P_CH] * vxo
    hy = P[P_KH] * yo + P[P_CH] * vyo
    if P[P_OUTER_ELASTIC] > 0.5 and not axisym:
        dy[16] = vxo
        dy[17] = vyo
        dy[18] = (FOx - hx) / P[P_MO]
        dy[19] = (FOy - hy) / P[P_MO]
        KE += 0.5 * P[P_MO] * (vxo * vxo + vyo * vyo)
        Uel += 0.5 * P[P_KH] * (xo * xo + yo * yo)
        P_dp += P[P_CH] * (vxo * vxo + vyo * vyo)
    else:
        dy[16] = 0.0; dy[17] = 0.0; dy[18] = 0.0; dy[19] = 0.0
        hx = FOx * mult if not axisym else 0.0
        hy = FOy * mult if not axisym else 0.0
    diag[O_OUTER_X] = xo
    diag[O_OUTER_Y] = yo
    diag[O_HOUSING_FX] = hx
    diag[O_HOUSING_FY] = hy
    return KE, Uel, P_dp


@hot(inline="always")
def _inner_ring_eom(dy, P, U, disp, axisym, w, vxi, vyi, vzi, wxi, wyi, FRx, FRy, FRz, MRx, MRy, P_dp, KE):
    """Equations of motion of the inner ring (dy[0:10]; zero when displacement-driven): returns its
    accelerations (axx, ayy, azz), the power of the external loads and P_dp, KE with the ring's share."""
    Ip = P[P_IP]
    It = P[P_IT]
    mi = P[P_MI]
    if disp:
        for k in range(10):
            dy[k] = 0.0
        axx = 0.0; ayy = 0.0; azz = 0.0
        Pext = 0.0
    else:
        dy[0] = vxi; dy[1] = vyi; dy[2] = vzi; dy[3] = wxi; dy[4] = wyi
        # support damping of the shaft mounting (viscous, to ground; zero force at rest)
        dfx = -P[P_CRX] * vxi
        dfy = -P[P_CRY] * vyi
        dfz = -P[P_CRZ] * vzi
        dmx = -P[P_CRTX] * wxi
        dmy = -P[P_CRTY] * wyi
        P_dp -= dfx * vxi + dfy * vyi + dfz * vzi + dmx * wxi + dmy * wyi
        axx = (U[U_FX] + FRx + dfx) / mi
        ayy = (U[U_FY] + FRy + dfy) / mi
        azz = (U[U_FZ] + FRz + dfz) / mi
        dy[5] = axx
        dy[6] = ayy
        dy[7] = azz
        # tilt with the spinning ring's gyroscopic coupling (Ip w)
        dy[8] = (U[U_MX] + MRx + dmx - Ip * w * wyi) / It
        dy[9] = (U[U_MY] + MRy + dmy + Ip * w * wxi) / It
        if P[P_FIXTILT] > 0.5:   # rigid shaft held by other bearings: no tilt, Mx, My are reactions
            dy[3] = 0.0; dy[4] = 0.0; dy[8] = 0.0; dy[9] = 0.0
        if axisym:
            dy[0] = 0.0; dy[1] = 0.0; dy[3] = 0.0; dy[4] = 0.0
            dy[5] = 0.0; dy[6] = 0.0; dy[8] = 0.0; dy[9] = 0.0
            axx = 0.0; ayy = 0.0
        Pext = U[U_FX] * vxi + U[U_FY] * vyi + U[U_FZ] * vzi + U[U_MX] * wxi + U[U_MY] * wyi
        KE += 0.5 * mi * (vxi * vxi + vyi * vyi + vzi * vzi) + 0.5 * It * (wxi * wxi + wyi * wyi)
    return axx, ayy, azz, Pext, P_dp, KE


@hot(inline="always")
def _drive_channels(diag, t, w, wdot, wo, wc, xc, yc, FRx, FRy, FRz, MRx, MRy, xi_, yi_, zi_, txi, tyi, vxi, vyi,
                    vzi, axx, ayy, azz, TRz, TOz, T_chs, Pext):
    """Output channels of the shaft, cage, ring loads and pose, and the drive torques and powers of both
    rings."""
    # drive: the shaft must supply the traction torque (TRz is the torque of the balls on the ring)
    fric = -TRz - T_chs
    fric_o = -TOz
    diag[O_T] = t
    diag[O_SHAFT_SPEED] = w
    diag[O_SHAFT_ACCEL] = wdot
    diag[O_CAGE_SPEED] = wc
    diag[O_CAGE_X] = xc
    diag[O_CAGE_Y] = yc
    diag[O_FX] = FRx
    diag[O_FY] = FRy
    diag[O_FZ] = FRz
    diag[O_MX] = MRx
    diag[O_MY] = MRy
    diag[O_IR_X] = xi_; diag[O_IR_Y] = yi_; diag[O_IR_Z] = zi_
    diag[O_IR_TX] = txi; diag[O_IR_TY] = tyi
    diag[O_IR_VX] = vxi; diag[O_IR_VY] = vyi; diag[O_IR_VZ] = vzi
    diag[O_IR_AX] = axx; diag[O_IR_AY] = ayy; diag[O_IR_AZ] = azz
    diag[O_FRICTION_TORQUE] = fric
    diag[O_P_DRIVE] = fric * w + fric_o * wo     # both rings' drives
    diag[O_OUTER_RING_SPEED] = wo
    diag[O_FRICTION_TORQUE_OUTER] = fric_o
    diag[O_P_EXT] = Pext


@hot(inline="always")
def _loss_channels(diag, P_ri, P_ro, P_sl, P_sp, P_pk, P_chc, P_chs, P_ld, P_dr, P_dp, KE, Uel):
    """Output channels of the losses (race losses split by motion), kinetic and elastic energy."""
    diag[O_P_RACE_INNER] = P_ri
    diag[O_P_RACE_OUTER] = P_ro
    # split of the race losses: centre sliding, spin, and the rest = differential slip across the curved
    # contact (Heathcote slip, the 'rolling' loss of the conformal groove); the three add up to the total
    diag[O_P_RACE_SLIDE] = P_sl
    diag[O_P_RACE_SPIN] = P_sp
    diag[O_P_RACE_DIFFSLIP] = P_ri + P_ro - P_sl - P_sp
    diag[O_P_POCKET] = P_pk
    diag[O_P_CHURN_CAGE] = P_chc
    diag[O_P_CHURN_RING] = P_chs
    diag[O_P_LAND] = P_ld
    diag[O_P_DRAG] = P_dr
    diag[O_P_DAMPING] = P_dp
    diag[O_KE] = KE
    diag[O_U_ELASTIC] = Uel


@hot(inline="always")
def _contact_channels(diag, D, dm, a0, w, wo, sai, nai, sao, nao, Qimax, Qomax, Qimin, pmax, sco, sci, npr):
    """Output channels of the contact statistics and the pure-rolling cage speed estimates."""
    diag[O_ALPHA_I_MEAN] = sai / nai if nai > 0 else 0.0
    diag[O_ALPHA_O_MEAN] = sao / nao if nao > 0 else 0.0
    diag[O_Q_I_MAX] = Qimax
    diag[O_Q_O_MAX] = Qomax
    diag[O_Q_I_MIN] = Qimin
    ami = sai / nai if nai > 0 else a0
    amo = sao / nao if nao > 0 else a0
    # theoretical cage speed, spin neglected (seed 000 Eq. 26): both rolling radii D/2, so
    # (w - wc) (1 - D cos ai / dm) = (wc - wo) (1 + D cos ao / dm); equal angles give the classical
    # [w (1 - g) + wo (1 + g)] / 2 (Harris & Kotzalas Vol. 1 Ch. 8, both rings rotating). Linear in the
    # speeds: no division by a speed, finite and continuous through zero.
    gi = D * math.cos(ami) / dm
    go = D * math.cos(amo) / dm
    diag[O_PURE_ROLLING_CAGE_SPEED] = (w * (1.0 - gi) + wo * (1.0 + go)) / (2.0 - gi + go)
    # Jones-Harris pure rolling at both contact centres with outer raceway control (kinematics.py), in the
    # frame turning with the outer ring (kinematics depend on the ring speed difference only)
    bet = math.atan2(math.sin(amo), math.cos(amo) + D / dm)
    ci_ = math.cos(ami - bet)
    co_ = math.cos(amo - bet)
    diag[O_PURE_ROLLING_CAGE_SPEED_JH] = wo + (w - wo) * (1.0 - gi) / ((1.0 - gi) + (1.0 + go) * ci_ / co_)
    diag[O_P_MAX] = pmax
    diag[O_CAGE_SPEED_PURE_ROLLING_OUTER] = sco / npr if npr > 0 else diag[O_PURE_ROLLING_CAGE_SPEED_JH]
    diag[O_CAGE_SPEED_PURE_ROLLING_INNER] = sci / npr if npr > 0 else diag[O_PURE_ROLLING_CAGE_SPEED_JH]


@hot
def rhs(t, y, dy, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd, want_bd):
    """dy/dt of the bearing model. diag (len NOUT) receives the output channels at (t, y); bd (nb x NBD)
    receives per-ball details when want_bd is True. tp: contact_kernels traction parameters; (qx, qwx,
    qy, qwy): contact_kernels.ellipse_quadrature.
    Per ball: raceway contacts (_groove_centres, contact_kernels' normal contact, _raceway_contact and
    _race_traction or the EHL pair kernel, the tractions' loads _inner_race_traction_loads /
    _outer_race_traction_loads, second arcs of four-point bearings _second_inner_arc / _second_outer_arc),
    pocket (_ball_pocket), drag (_ball_drag), equations of motion (_ball_eom), its loads on the inner ring
    (_inner_ring_loads) and statistics (_contact_statistics, _ball_details, _ball0_channels); then cage
    guidance (_cage_land_contact, _cage_flooded_land), churning (_churning), the equations of the cage
    (_cage_eom), outer ring (_outer_ring_eom) and inner ring (_inner_ring_eom), and the output channels
    (_drive_channels, _loss_channels, _contact_channels).
    Kernels inlined into the ball loop take scalars (tuples of scalars) only: an array argument of an inlined
    kernel is reference-counted per ball. The normal contact and the first contacts' traction, whose callees
    take the tables and quadrature arrays, stay in this loop: moved into a kernel compiled on its own (no
    reference counting), the fastmath re-association no longer spans the call and the results change in
    the last bits."""
    Z = P[P_Z]
    tmodel = int(tp[P_LUBMODEL]) if P[P_TRACTION] < 0.5 else TRACTION_COULOMB   # lubricated: EHL or curve
    kalker = P[P_TRACTION] > 1.5          # Kalker's simplified theory (FASTSIM), seed 000 Eqs. 7-9
    ehl = (not kalker) and tmodel == TRACTION_EHL
    sc = ehl_scratch(qx, qwx, qy, qwy)    # EHL traction's point quadrature and scratch, shared by all contacts
    Gc = P[P_GCOMB]
    nuc = P[P_NUCOMB]
    fnx = int(P[P_FS_NX])
    fny = int(P[P_FS_NY])
    nb = int(P[P_NB])
    D = P[P_D]
    dm = P[P_DM]
    fi = P[P_FI]
    fo = P[P_FO]
    a0 = P[P_A0]
    mb = P[P_MB]
    Jb = P[P_JB]
    mult = P[P_MULT]
    axisym = P[P_AXISYM] > 0.5
    Aa = (fi + fo - 1.0) * D
    Ri = 0.5 * dm + (fi - 0.5) * D * math.cos(a0)
    Roo = 0.5 * dm - (fo - 0.5) * D * math.cos(a0)
    Zoo = -(fo - 0.5) * D * math.sin(a0)
    Cr0 = Aa * math.cos(a0)               # inner groove centre relative to the outer one, ring at rest
    Cz0 = Aa * math.sin(a0)
    offi = (fi - 0.5) * D
    offo = (fo - 0.5) * D
    Rdi = 2.0 * fi * D / (2.0 * fi + 1.0)
    Rdo = 2.0 * fo * D / (2.0 * fo + 1.0)
    Ryi = fi * D / (2.0 * fi - 1.0)       # effective radii across the rolling direction (Hamrock-Dowson)
    Ryo = fo * D / (2.0 * fo - 1.0)
    zeta = P[P_ZETA]
    ei = P[P_EI]
    eo = P[P_EO]
    fourpt = ei > 0.0 or eo > 0.0         # gothic-arch grooves: up to four raceway contacts per ball
    w, wdot = _shaft(U, t)
    wo = U[U_WO]
    disp = P[P_COUPLING] > 0.5
    xi_, yi_, zi_, txi, tyi, vxi, vyi, vzi, wxi, wyi = _ring_pose(y, U, disp)
    thc = y[10]
    wc = y[11]
    xc = y[12]
    yc = y[13]
    vxc = y[14]
    vyc = y[15]
    xo = y[16]
    yo = y[17]
    vxo = y[18]
    vyo = y[19]
    FOx = 0.0; FOy = 0.0                                             # balls -> outer ring
    # accumulators
    FRx = 0.0; FRy = 0.0; FRz = 0.0; MRx = 0.0; MRy = 0.0; TRz = 0.0   # balls -> inner ring
    TOz = 0.0                                                        # balls -> outer ring, about z
    FCx = 0.0; FCy = 0.0; TC = 0.0                                   # balls -> cage
    P_ri = 0.0; P_ro = 0.0; P_pk = 0.0; P_dr = 0.0; P_dp = 0.0
    P_sl = 0.0; P_sp = 0.0
    KE = 0.0; Uel = 0.0
    sai = 0.0; sao = 0.0; nai = 0.0; nao = 0.0
    Qimax = 0.0; Qomax = 0.0; Qimin = 1e300; pmax = 0.0
    rp = 0.5 * dm
    cpk = P[P_CPOCKET]
    kpk = P[P_KPOCKET]
    cpkd = P[P_CPOCKETD]
    mupk = P[P_MUPOCKET]
    rho_eff = P[P_RHO_EFF]
    cd = P[P_CD]
    lube = P[P_LUBE] > 0.5
    sco = 0.0; sci = 0.0; npr = 0.0        # pure-rolling cage speeds of the loaded balls
    gD = D / dm
    imb = 1.0 / mb
    iJb = 1.0 / Jb
    trac = (kalker, tmodel, tp, Gc, nuc, fnx, fny, qx, qwx, qy, qwy, sc)
    pocket = (cpk, kpk, cpkd, mupk, P[P_MUBL], P[P_MUEHL], P[P_ETA_PK], P[P_ALPHA_PK], P[P_EPK], P[P_SIGPK])
    for j in range(nb):
        o = NSTATE_FIXED + NSB * j
        th = y[o]; rb = y[o + 1]; zb = y[o + 2]
        thd = y[o + 3]; rd = y[o + 4]; zd = y[o + 5]
        s_frx = FRx; s_fry = FRy; s_frz = FRz; s_mrx = MRx; s_mry = MRy
        s_fcx = FCx; s_fcy = FCy; s_tc = TC; s_fox = FOx; s_foy = FOy
        Wr = y[o + 6]; Wt = y[o + 7]; Wz = y[o + 8]
        ball = (rb, rd, thd, zd, Wr, Wt, Wz)
        c, s, Cr, Cz, vrr, vrt, vrz, Xr, Xz, vor, vot = _groove_centres(th, rb, zb, Cr0, Cz0, Ri, Roo, Zoo, xi_,
                                                                       yi_, zi_, txi, tyi, vxi, vyi, vzi, wxi,
                                                                       wyi, xo, yo, vxo, vyo)
        # normal contact with the raceways (contact_kernels): single-arc grooves, or the four arcs of
        # gothic-arch grooves. Inner arc 1 is centred at C, arc 2 at C - 2 e_i axially; outer arc 1 at the
        # outer groove centre, arc 2 at + 2 e_o; an inner arc centre at height z_k = +-e_i above the
        # inner-ring mid-plane (the tilt reference) moves radially by -z_k tilt, as in
        # quasistatic.FourPointQuasiStaticModel. Per ring the more loaded arc is the first contact (the
        # two-point diagnostics alpha_i, Q_i, ...); the other arc is a second contact where it is loaded.
        if fourpt:
            tilt = txi * s - tyi * c
            ci1 = gothic_arch_contact(Xr - (Cr - ei * tilt), Xz - Cz, offi, fi * D, ei, 1, tab_i, ta0, tda, True)
            ci2 = gothic_arch_contact(Xr - (Cr + ei * tilt), Xz - (Cz - 2.0 * ei), offi, fi * D, ei, 2, tab_i,
                                      ta0, tda, True)
            co1 = gothic_arch_contact(Xr, Xz, offo, fo * D, eo, 1, tab_o, ta0, tda, False)
            co2 = gothic_arch_contact(Xr, Xz - 2.0 * eo, offo, fo * D, eo, 2, tab_o, ta0, tda, False)
            if _first_arc(ci1, ci2):
                ca = ci1; cb = ci2; zia = ei
            else:
                ca = ci2; cb = ci1; zia = -ei
            if _first_arc(co1, co2):
                oa = co1; ob = co2
            else:
                oa = co2; ob = co1
            zib = -zia
            tdot = wxi * s - wyi * c
            vri = vrr - zia * tdot              # radial velocity of the first inner arc's centre
        else:
            (dlo, nor, noz, ao, Qo, ao_s, bo_s, po,
             dli, nir, niz, ai, Qi, ai_s, bi_s, pi_) = ball_race_contact(Xr, Xz, Cr, Cz, offo, offi,
                                                                         tab_i, tab_o, ta0, tda)
            ca = (True, dli, nir, niz, ai, Qi, ai_s, bi_s, pi_)
            oa = (True, dlo, nor, noz, ao, Qo, ao_s, bo_s, po)
            cb = ob = (False, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
            zia = 0.0; zib = 0.0; tdot = 0.0
            vri = vrr
        _, dli, nir, niz, ai, Qi, ai_s, bi_s, pi_ = ca
        _, dlo, nor, noz, ao, Qo, ao_s, bo_s, po = oa
        Qi2 = cb[5]; pi2 = cb[8]
        Qo2 = ob[5]; po2 = ob[8]
        # each contact: normal force with damping and contact kinematics (_raceway_contact), traction
        # (_race_traction)
        (Fni, pd_i, ue_i, Rxi, vsti, vsmi, wspi, wrmi, wrti,
         uri) = _raceway_contact(dli, nir, niz, Qi, rb, rd, thd, zd, Wr, Wt, Wz, w, vri, vrt, vrz, D,
                                 gD, zeta, mb)
        (Fno, pd_o, ue_o, Rxo, vsto, vsmo, wspo, wrmo, wrto,
         uro) = _raceway_contact(dlo, nor, noz, Qo, rb, rd, thd, zd, Wr, Wt, Wz, wo, vor, vot, 0.0, D,
                                 gD, zeta, mb)
        if ehl:     # EHL traction: the inner and the outer contact together (ehl_pair_traction_into)
            (fti, fmi, mni, mmi, mti, pli,
             fto, fmo, mno, mmo, mto, plo) = ehl_pair_traction_into(ai_s, bi_s, pi_, Rdi, Rxi, vsti, vsmi, wspi,
                                                                    wrmi, wrti, uri, ao_s, bo_s, po, Rdo, Rxo,
                                                                    vsto, vsmo, wspo, wrmo, wrto, uro, D, tp, sc)
        else:
            fti, fmi, mni, mmi, mti, pli = _race_traction(kalker, ai_s, bi_s, Qi, pi_, D, Rdi, Rxi, Ryi, vsti,
                                                          vsmi, wspi, wrmi, wrti, uri, tmodel, tp, Gc, nuc, fnx,
                                                          fny, qx, qwx, qy, qwy, sc)
            fto, fmo, mno, mmo, mto, plo = _race_traction(kalker, ao_s, bo_s, Qo, po, D, Rdo, Rxo, Ryo, vsto,
                                                          vsmo, wspo, wrmo, wrto, uro, tmodel, tp, Gc, nuc, fnx,
                                                          fny, qx, qwx, qy, qwy, sc)
        P_dp += pd_i
        Uel += ue_i
        P_dp += pd_o
        Uel += ue_o
        # forces on the ball (local r, t, z) and moments about its centre
        Fr = -Fni * nir - Fno * nor
        Ft = 0.0
        Fz = -Fni * niz - Fno * noz
        Mr = 0.0; Mt = 0.0; Mz = 0.0
        (Fr, Ft, Fz, Mr, Mt, Mz, P_ri, P_sl, P_sp, TRz,
         fr_ring, ft_ring, fz_ring) = _inner_race_traction_loads(Fr, Ft, Fz, Mr, Mt, Mz, P_ri, P_sl, P_sp, TRz, rb,
                                                                 Fni, nir, niz, fti, fmi, mni, mmi, mti, pli, vsti,
                                                                 vsmi, wspi)
        tri_t = fti; tri_m = fmi
        sl_i = vsti; u_i = abs(uri); sp_i = wspi; sm_i = vsmi
        (Fr, Ft, Fz, Mr, Mt, Mz, P_ro, P_sl, P_sp, FOx, FOy,
         TOz) = _outer_race_traction_loads(Fr, Ft, Fz, Mr, Mt, Mz, P_ro, P_sl, P_sp, FOx, FOy, TOz, c, s, rb, Fno,
                                           nor, noz, fto, fmo, mno, mmo, mto, plo, vsto, vsmo, wspo)
        tro_t = fto; tro_m = fmo
        sl_o = vsto; u_o = abs(uro); sp_o = wspo; sm_o = vsmo
        # second arcs (four-point contact): the same contact kernel, with their loads on ball and rings
        fr2_ring = 0.0; ft2_ring = 0.0; fz2_ring = 0.0
        if Qi2 > 0.0:
            (Fr, Ft, Fz, Mr, Mt, Mz, P_ri, P_sl, P_sp, P_dp, Uel, TRz, fr2_ring, ft2_ring,
             fz2_ring) = _second_inner_arc(Fr, Ft, Fz, Mr, Mt, Mz, P_ri, P_sl, P_sp, P_dp, Uel, TRz, cb, ball, w,
                                           vrr, zib, tdot, vrt, vrz, D, gD, zeta, mb, Rdi, Ryi, trac)
        if Qo2 > 0.0:
            (Fr, Ft, Fz, Mr, Mt, Mz, P_ro, P_sl, P_sp, P_dp, Uel, FOx, FOy,
             TOz) = _second_outer_arc(Fr, Ft, Fz, Mr, Mt, Mz, P_ro, P_sl, P_sp, P_dp, Uel, FOx, FOy, TOz, ob, c,
                                      s, ball, wo, vor, vot, D, gD, zeta, mb, Rdo, Ryo, trac)
        Fpk, Fr, Ft, Fz, Mr, Mz, FCx, FCy, TC, Uel, P_dp, P_pk = _ball_pocket(
            Fr, Ft, Fz, Mr, Mz, FCx, FCy, TC, Uel, P_dp, P_pk, j, Z, th, c, s, ball, thc, wc, xc, yc, vxc, vyc, D,
            lube, pocket)
        Ft, P_dr = _ball_drag(Ft, P_dr, rb, thd, wc, rp, rho_eff, cd, D)
        # equations of motion, ball j
        dy[o] = thd
        dy[o + 1] = rd
        dy[o + 2] = zd
        (dy[o + 3], dy[o + 4], dy[o + 5], dy[o + 6], dy[o + 7],
         dy[o + 8]) = _ball_eom(Fr, Ft, Fz, Mr, Mt, Mz, rb, rd, thd, Wr, Wt, imb, iJb)
        FRx, FRy, FRz, MRx, MRy = _inner_ring_loads(FRx, FRy, FRz, MRx, MRy, axisym, fourpt, c, s, Ri, zia, zib,
                                                    fr_ring, ft_ring, fz_ring, fr2_ring, ft2_ring, fz2_ring)
        KE += 0.5 * mb * (rd * rd + (rb * thd) ** 2 + zd * zd) + 0.5 * Jb * (Wr * Wr + Wt * Wt + Wz * Wz)
        (sai, nai, sao, nao, Qimax, Qomax, Qimin, pmax, sco, sci,
         npr) = _contact_statistics(sai, nai, sao, nao, Qimax, Qomax, Qimin, pmax, sco, sci, npr, fourpt, w, wo,
                                    gD, ai, ao, nir, niz, nor, noz, Qi, Qo, Qi2, Qo2, pi_, po, pi2, po2)
        if want_bd:
            _ball_details(bd, j, ca, cb, oa, ob, tri_t, tri_m, tro_t, tro_m, sl_i, sl_o, u_i, u_o, sp_i, sp_o,
                          sm_i, sm_o, Fpk, (FRx - s_frx, FRy - s_fry, FRz - s_frz, MRx - s_mrx, MRy - s_mry,
                                            FCx - s_fcx, FCy - s_fcy, TC - s_tc, FOx - s_fox, FOy - s_foy))
        if j == 0:
            _ball0_channels(diag, D, Wr, Wt, Wz, thd, sl_i, sl_o, u_i, u_o, sp_i, sp_o, ai, ao, Qi, Qo, tri_t,
                            tro_t)
    # multiplicity (reduced axisymmetric model: one ball stands for Z)
    FRz *= mult
    TRz *= mult
    TOz *= mult
    TC *= mult
    P_ri *= mult; P_ro *= mult; P_pk *= mult; P_dr *= mult; P_dp *= mult
    P_sl *= mult; P_sp *= mult
    KE *= mult
    Uel *= mult
    # cage guidance: land contact (penalty + damping + Coulomb drag torque) on the guiding land
    P_ld = 0.0
    e = math.sqrt(xc * xc + yc * yc)
    cl = P[P_CLAND]
    if e > cl and P[P_GUIDE] < 1.5:
        P_ld, FCx, FCy, FRx, FRy, FOx, FOy, TC, TRz, TOz, P_dp, Uel = _cage_land_contact(
            e, cl, xc, yc, vxc, vyc, wc, w, wo, lube, P, FCx, FCy, FRx, FRy, FOx, FOy, TC, TRz, TOz, P_dp, Uel)
    eta = P[P_ETA_LAND]
    if eta > 0.0 and P[P_GUIDE] < 1.5:
        FCx, FCy, FRx, FRy, FOx, FOy, TC, TRz, TOz, P_ld = _cage_flooded_land(
            eta, e, cl, xc, yc, vxc, vyc, wc, w, wo, P, FCx, FCy, FRx, FRy, FOx, FOy, TC, TRz, TOz, P_ld)
    TC, TRz, TOz, P_chc, P_chs, T_chs = _churning(P, wc, w, wo, TC, TRz, TOz)
    _cage_eom(dy, P, axisym, wc, vxc, vyc, TC, FCx, FCy)
    KE, Uel, P_dp = _outer_ring_eom(dy, diag, P, axisym, mult, xo, yo, vxo, vyo, FOx, FOy, KE, Uel, P_dp)
    KE += 0.5 * P[P_IC] * wc * wc + 0.5 * P[P_MC] * (vxc * vxc + vyc * vyc)
    # inner ring
    axx, ayy, azz, Pext, P_dp, KE = _inner_ring_eom(dy, P, U, disp, axisym, w, vxi, vyi, vzi, wxi, wyi, FRx, FRy,
                                                    FRz, MRx, MRy, P_dp, KE)
    _drive_channels(diag, t, w, wdot, wo, wc, xc, yc, FRx, FRy, FRz, MRx, MRy, xi_, yi_, zi_, txi, tyi, vxi, vyi,
                    vzi, axx, ayy, azz, TRz, TOz, T_chs, Pext)
    _loss_channels(diag, P_ri, P_ro, P_sl, P_sp, P_pk, P_chc, P_chs, P_ld, P_dr, P_dp, KE, Uel)
    _contact_channels(diag, D, dm, a0, w, wo, sai, nai, sao, nao, Qimax, Qomax, Qimin, pmax, sco, sci, npr)


@hot
def pure_rolling_cage_speeds(w, ai, ao, gD, wo=0.0):
    """Pure-rolling cage (ball orbital) speed [rad/s] of one ball with contact angles ai, ao [rad] at shaft
    speed w [rad/s] and outer-ring speed wo [rad/s] (both signed), gD = D / dm: (outer-raceway control,
    inner-raceway control). In the frame turning with the outer ring the inner ring turns at w - wo and the
    kinematics are those of a fixed outer ring, so w_c = wo + f (w - wo) with f the fixed-outer ratio. Harris & Kotzalas Vol. 2 Ch. 3 (Jones' raceway control): the ball rolls without slip at both
    contact centres, its spin axis at tan(beta) = sin(ao) / (cos(ao) + gD) (outer control) or
    sin(ai) / (cos(ai) - gD) (inner control), and
    w_c = w (1 - gD cos ai) / [(1 - gD cos ai) + (1 + gD cos ao) cos(ai - beta) / cos(ao - beta)]."""
    return pure_rolling_cage_speeds_cs(w, math.cos(ai), math.sin(ai), math.cos(ao), math.sin(ao), gD, wo)


@hot
def pure_rolling_cage_speeds_cs(w, ca, sa, co, so, gD, wo=0.0):
    """pure_rolling_cage_speeds from the cosines and sines of the contact angles (ca, sa) = (cos ai, sin ai),
    (co, so) = (cos ao, sin ao), without trigonometric calls: with beta = atan2(so, co + gD) (outer control)
    cos(ai - beta) / cos(ao - beta) = (ca (co + gD) + sa so) / (co (co + gD) + so so), the common factor
    1 / hypot(so, co + gD) cancelling; inner control likewise with beta = atan2(sa, ca - gD)."""
    gi = gD * ca
    go = gD * co
    cbo = co + gD
    cbi = ca - gD
    wr = w - wo
    # w_c = wo + wr (1 - gi) / [(1 - gi) + (1 + go) n / d], one division: wr (1 - gi) d / [(1 - gi) d + (1 + go) n]
    d_o = co * cbo + so * so
    d_i = co * cbi + so * sa
    c_o = wo + wr * (1.0 - gi) * d_o / ((1.0 - gi) * d_o + (1.0 + go) * (ca * cbo + sa * so))
    c_i = wo + wr * (1.0 - gi) * d_i / ((1.0 - gi) * d_i + (1.0 + go) * (ca * cbi + sa * sa))
    return c_o, c_i


NQUAD = 2 * NOUT + 2
"""Time integrals of the output channels (the energies of the power channels), accumulated inside the
integrators: quad[0:NOUT] = integral of each channel over time since the last reset [unit s],
quad[NOUT:2 NOUT] the channels at the last accepted point, quad[2 NOUT] its time, quad[2 NOUT + 1] = 1 once
a point is stored. Each accepted step adds h * sum_s b_s p(Y_s): the integrator's own weights b_s on the
channels p at its stages Y_s, i.e. the method applied to the augmented system q' = p(y) (Hairer, Norsett &
Wanner I, Sec. II.1; for the Rosenbrock-W method with zero Jacobian rows for q, which a W-method allows),
so the energies agree with the integrated state to the method's order and the energy balance closes as
well as the state is integrated (a trapezoid over steps of 5e-5 s missed the pocket-contact power peaks by
~1-2 %). An input step at a communication point adds a zero-width interval, so it is taken exactly."""


@hot
def _quad_store(quad, t, diag):
    """Store (t, diag) as the last accepted point of the integrals (no integral added)."""
    for k in range(NOUT):
        quad[NOUT + k] = diag[k]
    quad[2 * NOUT] = t
    quad[2 * NOUT + 1] = 1.0


@hot
def _quad_step(quad, h, dq, t, diag):
    """Add one accepted step's integrals h * dq (dq = sum of the method's weights b_s times the channels at
    its stages) and store the step's end point (t, diag)."""
    for k in range(NOUT):
        quad[k] += h * dq[k]
    _quad_store(quad, t, diag)


@hot
def _quad_stage(dq, b, diag, first):
    """dq = b * diag (first) or dq += b * diag."""
    if first:
        for k in range(NOUT):
            dq[k] = b * diag[k]
    else:
        for k in range(NOUT):
            dq[k] += b * diag[k]


@hot
def _quad_point(quad, t, diag):
    """Add the trapezoid from the last stored point to (t, diag) and store this point."""
    if quad[2 * NOUT + 1] > 0.5:
        w = 0.5 * (t - quad[2 * NOUT])
        for k in range(NOUT):
            quad[k] += w * (quad[NOUT + k] + diag[k])
    for k in range(NOUT):
        quad[NOUT + k] = diag[k]
    quad[2 * NOUT] = t
    quad[2 * NOUT + 1] = 1.0


@hot
def _record_point(rec, nrec, nrec_max, next_rec, rec_dt, t, t1, d):
    """Store the channels d at the accepted point t when a record is due (not at t1: that is the first record
    of the next call); returns (nrec, next_rec). A full buffer stops recording: a stale next_rec would cap
    every later step at 1e-12 s (a stall)."""
    if t >= next_rec - 1e-12 and t < t1 - 1e-12:
        if nrec < nrec_max:
            for k in range(NOUT):
                rec[nrec, k] = d[k]
            nrec += 1
            next_rec += rec_dt
        else:
            next_rec = 1e300
    return nrec, next_rec


@hot
def _step_cap(t, t1, next_rec, rec_dt):
    """Largest step [s] from t: to the interval end t1 and to the next record time."""
    hmax = t1 - t
    if rec_dt > 0 and next_rec < t1 - 1e-12:
        hmax = min(hmax, max(next_rec - t, 1e-12))
    return hmax


@hot
def _error_norm(e, y, ynew, atol_scale, rtol):
    """RMS error norm of the local error estimate e with per-state scales atol_scale[i] + rtol
    max(|y_i|, |ynew_i|) (a negative atol_scale entry: absolute only, for the unbounded angles); 1e300 if
    any component is not finite."""
    n = e.size
    acc = 0.0
    for i in range(n):
        at = atol_scale[i]
        sc = -at if at < 0.0 else at + rtol * max(abs(y[i]), abs(ynew[i]))
        q = e[i] / sc
        if not math.isfinite(q):
            return 1e300
        acc += q * q
    return math.sqrt(acc / n)


@hot
def _start_point(quad, t, diag, d0):
    """First point (t, y) of an adaptive integration call, its channels diag: stored for the integrals
    (a zero-width interval at the start of a call) and kept in d0 as the accepted point's channels."""
    _quad_point(quad, t, diag)
    for k in range(NOUT):
        d0[k] = diag[k]


@hot
def _accept_point(quad, h, dq, t, diag, d0):
    """Bookkeeping of an accepted step h ending at t: its integrals added (_quad_step) and the end point's
    channels diag kept in d0."""
    _quad_step(quad, h, dq, t, diag)
    for k in range(NOUT):
        d0[k] = diag[k]


@hot
def _propose_step(rec, nrec, nrec_max, next_rec, rec_dt, t, t1, d0, h):
    """Before an attempt from the accepted point t (channels d0): record it when due (_record_point) and
    cap the proposed step h at the interval end and the next record time (_step_cap). Returns (nrec,
    next_rec, step to attempt)."""
    nrec, next_rec = _record_point(rec, nrec, nrec_max, next_rec, rec_dt, t, t1, d0)
    return nrec, next_rec, min(h, _step_cap(t, t1, next_rec, rec_dt))


@hot
def _store_outputs(diag_out, bd_out, diag, bd):
    """Output channels and per-ball details at the end of an integration call."""
    for k in range(NOUT):
        diag_out[k] = diag[k]
    for j in range(bd.shape[0]):
        for k in range(NBD):
            bd_out[j, k] = bd[j, k]


@hot
def _all_finite(y):
    """True if every entry of y is finite."""
    for i in range(y.size):
        if not math.isfinite(y[i]):
            return False
    return True


@hot(fastmath=frozenset())     # strict IEEE: the cost steers 'auto', the same in every build
def close_interval(y, U, P, stats, before, i_h, i_c, la_rhs, t0, t1, key_y, key_U, key_P):
    """Bookkeeping after an integration call from t0 to t1 [s], in one call: returns True if the state y is
    finite. If the call succeeded (stats[4] == 0) y, U, P are copied into key_y, key_U, key_P (the key of the
    end point's outputs). With i_h >= 0 (an adaptive method) its last step size goes to stats[i_h] and its
    cost in right-hand-side equivalents per simulated second, (rhs calls + la_rhs x step attempts) / (t1 -
    t0) counted from before = stats[:3] at the call's start, into the running mean stats[i_c] (the 'auto'
    selector's measure)."""
    ok = _all_finite(y)
    if stats[4] == 0.0:
        for i in range(y.size):
            key_y[i] = y[i]
        for i in range(U.size):
            key_U[i] = U[i]
        for i in range(P.size):
            key_P[i] = P[i]
    if i_h >= 0:
        stats[i_h] = stats[3]
        cost = ((stats[2] - before[2]) + la_rhs * ((stats[0] - before[0]) + (stats[1] - before[1]))) / (t1 - t0)
        stats[i_c] = cost if stats[i_c] <= 0 else 0.5 * (stats[i_c] + cost)
    return ok


@hot
def _accept_fsal(y, ynew, k1, kf, quad, h, dq, t, diag, d0):
    """Take an accepted explicit step ending at t: y <- ynew, first stage <- the FSAL derivative kf, its
    integrals added and the end point's channels diag kept in d0."""
    for i in range(y.size):
        y[i] = ynew[i]
        k1[i] = kf[i]
    _accept_point(quad, h, dq, t, diag, d0)


@hot
def _pi_factor(err, err_prev, q, fac_max):
    """Step factor of the PI controller for an order-q error estimate (Gustafsson; Hairer & Wanner II,
    IV.8) after an accepted step with error norm err, the previous accepted one err_prev; in [0.2, fac_max]."""
    fac = 0.9 * (max(err, 1e-10) ** (-0.7 / q)) * (max(err_prev, 1e-10) ** (0.4 / q))
    return min(fac_max, max(0.2, fac))


@hot
def _pi_next_step(h, h_prop, err, err_prev, q, fac_max):
    """Next step after an accepted step h with error norm err (<= 1): PI controller (_pi_factor), growth
    limited to fac_max; a step shortened to hit a record or the interval end (h < h_prop) does not shrink the
    next one. Returns (h_next, err_prev)."""
    fac = _pi_factor(err, err_prev, q, fac_max)
    hn = h * fac
    if h_prop > hn and fac >= 1.0:
        hn = h_prop
    return hn, max(err, 1e-4)


@hot
def _pi_next_step_held(h, hs, err, err_prev, q, fac_max, hold):
    """Next step after an accepted step hs (h proposed) of a method that refactors its matrix on a change of
    step (the Rosenbrock-W integrator): PI factor (_pi_factor); a step shortened to hit a record or the
    interval end (hs < h) keeps h (growing it from a short step let h run away, to 1e70), and factors in
    [1, hold] keep h (small increases keep the factorisation). Returns (h_next, err_prev)."""
    fac = _pi_factor(err, err_prev, q, fac_max)
    if hs < h:
        pass
    elif fac < 1.0 or fac > hold:
        h = hs * fac
    return h, max(err, 1e-4)


@hot
def _rejected_step(h, ok, err, q):
    """Step after a rejection: a quarter for a non-finite attempt, else 0.9 err^(-1/q), at least 0.2 h."""
    if not ok:
        return h * 0.25
    return h * max(0.2, 0.9 * err ** (-1.0 / q))


@hot
def _reject(stats, h, ok, err, q):
    """A rejected attempt h (ok: finite; err: error norm of an order-q estimate): counted in stats[1], the
    next attempt from _rejected_step. Returns (h_next, failed): failed when the step collapsed below 1e-12 s,
    flagged stats[4] = 2."""
    stats[1] += 1
    h = _rejected_step(h, ok, err, q)
    if h < 1e-12:
        stats[4] = 2.0
        return h, True
    return h, False


@hot(inline="always")
def _rk4_stages(t, h, y, out, yt, k1, k2, k3, k4, dq, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag,
                bd):
    """Stages 2-4 of classical RK4 from y with the first stage k1 given, their output channels added to
    the step integrals dq (weights 1/3, 1/3, 1/6), and out <- y + h/6 (k1 + 2 k2 + 2 k3 + k4) (out may be
    y itself; yt is scratch)."""
    n = y.size
    for i in range(n):
        yt[i] = y[i] + 0.5 * h * k1[i]
    rhs(t + 0.5 * h, yt, k2, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd, False)
    _quad_stage(dq, 1.0 / 3.0, diag, False)
    for i in range(n):
        yt[i] = y[i] + 0.5 * h * k2[i]
    rhs(t + 0.5 * h, yt, k3, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd, False)
    _quad_stage(dq, 1.0 / 3.0, diag, False)
    for i in range(n):
        yt[i] = y[i] + h * k3[i]
    rhs(t + h, yt, k4, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd, False)
    _quad_stage(dq, 1.0 / 6.0, diag, False)
    for i in range(n):
        out[i] = y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])


@hot(inline="always")
def _dp5_stages(t, h, y, y5, yt, k1, k2, k3, k4, k5, k6, k7, ev, dq, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy,
                qwy, diag, bd, last):
    """Stages 2-7 of Dormand-Prince 5(4) from y with the first stage k1 given (Hairer, Norsett & Wanner,
    Solving ODEs I, Sec. II.5): y5 <- the order-5 solution, k7 = f(t + h, y5) its FSAL derivative (with the
    per-ball details when last), ev <- the local error estimate; the stages' output channels added to the
    step integrals dq (weights b = (35/384, 0, 500/1113, ...), the first one's added by the caller); yt is
    scratch."""
    n = y.size
    for i in range(n):
        yt[i] = y[i] + h * (0.2 * k1[i])
    rhs(t + 0.2 * h, yt, k2, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd, False)
    for i in range(n):
        yt[i] = y[i] + h * (3.0 / 40.0 * k1[i] + 9.0 / 40.0 * k2[i])
    rhs(t + 0.3 * h, yt, k3, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd, False)
    _quad_stage(dq, 500.0 / 1113.0, diag, False)
    for i in range(n):
        yt[i] = y[i] + h * (44.0 / 45.0 * k1[i] - 56.0 / 15.0 * k2[i] + 32.0 / 9.0 * k3[i])
    rhs(t + 0.8 * h, yt, k4, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd, False)
    _quad_stage(dq, 125.0 / 192.0, diag, False)
    for i in range(n):
        yt[i] = y[i] + h * (19372.0 / 6561.0 * k1[i] - 25360.0 / 2187.0 * k2[i]
                            + 64448.0 / 6561.0 * k3[i] - 212.0 / 729.0 * k4[i])
    rhs(t + 8.0 / 9.0 * h, yt, k5, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd, False)
    _quad_stage(dq, -2187.0 / 6784.0, diag, False)
    for i in range(n):
        yt[i] = y[i] + h * (9017.0 / 3168.0 * k1[i] - 355.0 / 33.0 * k2[i] + 46732.0 / 5247.0 * k3[i]
                            + 49.0 / 176.0 * k4[i] - 5103.0 / 18656.0 * k5[i])
    rhs(t + h, yt, k6, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd, False)
    _quad_stage(dq, 11.0 / 84.0, diag, False)
    for i in range(n):
        y5[i] = y[i] + h * (35.0 / 384.0 * k1[i] + 500.0 / 1113.0 * k3[i] + 125.0 / 192.0 * k4[i]
                            - 2187.0 / 6784.0 * k5[i] + 11.0 / 84.0 * k6[i])
    rhs(t + h, y5, k7, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd, last)
    for i in range(n):
        ev[i] = h * (71.0 / 57600.0 * k1[i] - 71.0 / 16695.0 * k3[i] + 71.0 / 1920.0 * k4[i]
                     - 17253.0 / 339200.0 * k5[i] + 22.0 / 525.0 * k6[i] - 1.0 / 40.0 * k7[i])


@hot(nogil=True)
def integrate(y, t0, t1, dt, method, rtol, atol_scale, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy,
              rec_dt, rec, nrec_max, stats, quad, diag_out, bd_out):
    """Advance y (in place) from t0 to exactly t1 inside compiled code.

    method 0: classical fixed-step RK4 with step dt (the papers' baseline, seed 000: dt = 1e-5 s);
    method 1: adaptive Dormand-Prince 5(4), FSAL, PI step control, RMS error norm (rtol, absolute
              tolerances atol_scale[k] per state; a negative entry means absolute-only), initial step dt;
    method 3: adaptive RK4 with an embedded order-3 FSAL error estimate (4 calls per step), same control.
    Records the output channels every rec_dt into rec (nrec_max x NOUT); returns the number of
    records written. stats: [0] accepted steps, [1] rejected steps, [2] rhs calls, [3] last dt.
    quad (NQUAD): time integrals of the output channels, accumulated over the accepted steps.
    diag_out (NOUT), bd_out (nb x NBD): the output channels and per-ball details at the final (t1, y), from
    the last right-hand side of the last step (no extra call for the outputs at a communication point)."""
    n = y.size
    nb = int(P[P_NB])
    k1 = np.empty(n); k2 = np.empty(n); k3 = np.empty(n); k4 = np.empty(n)
    yt = np.empty(n)
    ev = np.empty(n)          # local error estimate of the adaptive methods
    diag = np.empty(NOUT)
    d0 = np.empty(NOUT)       # channels at the accepted point (t, y)
    dq = np.empty(NOUT)       # sum of b_s * channels at the stages of the current step
    bd = np.empty((nb, NBD))
    nrec = 0
    t = t0
    next_rec = t0 if rec_dt > 0 else 1e300
    h = dt
    if method == 0:
        while t < t1 - 1e-15:
            h = min(dt, t1 - t)
            rhs(t, y, k1, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd, False)
            _quad_point(quad, t, diag)     # zero-width at the start of a call; otherwise already stored
            _quad_stage(dq, 1.0 / 6.0, diag, True)
            nrec, next_rec = _record_point(rec, nrec, nrec_max, next_rec, rec_dt, t, t1, diag)
            _rk4_stages(t, h, y, y, yt, k1, k2, k3, k4, dq, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy,
                        diag, bd)
            if not _all_finite(y):
                stats[4] = 1.0
                return nrec
            t += h
            for k in range(NOUT):
                quad[k] += h * dq[k]
            quad[2 * NOUT] = t            # the end point's channels are stored by the next step's first call
            stats[0] += 1
            stats[2] += 4
        rhs(t, y, k1, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd, True)
        _quad_store(quad, t, diag)
        stats[2] += 1
        stats[3] = h
    elif method == 3:
        # Classical RK4 advancing the solution with an embedded order-3 error estimate that reuses the
        # first stage of the next step (FSAL): with c = (0, 1/2, 1/2, 1, 1) and stage 5 = f(t + h, y1), the
        # weights (1/6, 1/3, 1/3, 0, 1/6) satisfy the four order-3 conditions (Hairer, Norsett & Wanner,
        # Solving ODEs I, Sec. II.2, Table 2.2), so err = h/6 (k4 - k5) = O(h^4). Four right-hand sides per
        # accepted step against six for Dormand-Prince, with a slightly larger stability interval per call
        # (RK4 |R(z)| <= 1 to z = -2.79 and +-2.83i; DP5 to -3.31 and +-3.4i over six calls): where the
        # step is stability-limited (the stiff ball modes) this is the cheaper explicit method.
        # Error norm, tolerances and PI control as for method 1 with the exponents of an order-3 estimate.
        k5 = np.empty(n)
        rhs(t, y, k1, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd, True)
        _start_point(quad, t, diag, d0)
        stats[2] += 1
        err_prev = 1e-4
        while t < t1 - 1e-15:
            h_prop = h
            nrec, next_rec, h = _propose_step(rec, nrec, nrec_max, next_rec, rec_dt, t, t1, d0, h)
            _quad_stage(dq, 1.0 / 6.0, d0, True)
            _rk4_stages(t, h, y, yt, yt, k1, k2, k3, k4, dq, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy,
                        diag, bd)
            # the last step's FSAL call also fills the per-ball details (outputs at t1)
            rhs(t + h, yt, k5, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd, t + h >= t1 - 1e-15)
            stats[2] += 4
            for i in range(n):
                ev[i] = h / 6.0 * (k4[i] - k5[i])
            err = _error_norm(ev, y, yt, atol_scale, rtol)
            ok = err < 1e300
            if ok and err <= 1.0:
                t += h
                _accept_fsal(y, yt, k1, k5, quad, h, dq, t, diag, d0)
                stats[0] += 1
                h, err_prev = _pi_next_step(h, h_prop, err, err_prev, 4.0, 4.0)
            else:
                h, failed = _reject(stats, h, ok, err, 4.0)
                if failed:
                    return nrec
        stats[3] = h
    else:
        # Dormand-Prince 5(4) (Hairer, Norsett & Wanner, Solving ODEs I, Sec. II.5), FSAL, RMS error norm
        # with per-state scales atol_scale[i] + rtol |y_i| (rtol is not applied to the unbounded angles:
        # their atol_scale entries are negative, flagging an absolute-only tolerance), PI step control.
        k5 = np.empty(n); k6 = np.empty(n); k7 = np.empty(n); y5 = np.empty(n)
        rhs(t, y, k1, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd, True)
        _start_point(quad, t, diag, d0)
        stats[2] += 1
        err_prev = 1e-4
        while t < t1 - 1e-15:
            h_prop = h
            nrec, next_rec, h = _propose_step(rec, nrec, nrec_max, next_rec, rec_dt, t, t1, d0, h)
            _quad_stage(dq, 35.0 / 384.0, d0, True)     # Dormand-Prince b = (35/384, 0, 500/1113, ...)
            _dp5_stages(t, h, y, y5, yt, k1, k2, k3, k4, k5, k6, k7, ev, dq, P, U, tab_i, tab_o, ta0, tda, tp, qx,
                        qwx, qy, qwy, diag, bd, t + h >= t1 - 1e-15)
            stats[2] += 6
            err = _error_norm(ev, y, y5, atol_scale, rtol)
            ok = err < 1e300
            if ok and err <= 1.0:
                t += h
                _accept_fsal(y, y5, k1, k7, quad, h, dq, t, diag, d0)   # diag of the FSAL call rhs(t + h, y5)
                stats[0] += 1
                h, err_prev = _pi_next_step(h, h_prop, err, err_prev, 5.0, 5.0)
            else:
                h, failed = _reject(stats, h, ok, err, 5.0)
                if failed:
                    return nrec
        stats[3] = h
    _store_outputs(diag_out, bd_out, diag, bd)
    return nrec


@hot(nogil=True)
def evaluate(t, y, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd):
    """Output channels and per-ball details at (t, y) without integrating."""
    dy = np.empty(y.size)
    rhs(t, y, dy, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd, True)
    return dy


@hot
def contact_films(bd, D, dm, fi, fo, eta0, alpha, Ep, s_ball, s_race, out):
    """Hamrock-Dowson central and minimum film thickness (bearing_core.lubrication.film, seed 003 Eq. 23) of every
    ball-race contact from the per-ball details bd of evaluate() (loads, contact angles, entrainment speeds):
    out[0..3, j] = h_c inner, h_min inner, h_c outer, h_min outer [m] of ball j (0 where unloaded or not
    rolling). eta0 [Pa s], alpha [1/Pa] of the oil, Ep [Pa] the reduced modulus, s_ball, s_race [m] rms
    roughness. Returns the smallest film parameter Lambda [-] (inf if no contact is loaded)."""
    nb = bd.shape[0]
    lam = math.inf
    for r in range(2):
        f = fi if r == 0 else fo
        sgn = -1.0 if r == 0 else 1.0
        cq = BD_QI if r == 0 else BD_QO
        ca = BD_AI if r == 0 else BD_AO
        cu = BD_UI if r == 0 else BD_UO
        Ry = f * D / (2.0 * f - 1.0)
        for j in range(nb):
            Q, u = bd[j, cq], bd[j, cu]
            out[2 * r, j] = 0.0
            out[2 * r + 1, j] = 0.0
            if Q <= 0.0 or u <= 0.0:
                continue
            Rx = 0.5 * D * (dm + sgn * D * math.cos(bd[j, ca])) / dm
            k = ellipticity_nb(Rx, Ry, 0)
            hc, hm = film_thickness_nb(u, eta0, alpha, Rx, Ry, Ep, Q, k, 1.0)
            out[2 * r, j] = hc
            out[2 * r + 1, j] = hm
            lam = min(lam, film_parameter_nb(hm, s_ball, s_race))
    return lam


# ---- Rosenbrock-W integrator with a ball-block Jacobian ------------------------------------------
# ROS34PW2 (Rang & Angermann, BIT Numer. Math. 45 (2005) 761-787): 4 stages, order 3, embedded order 2,
# L-stable, and a W-method: it keeps order 3 with ANY approximation W of the Jacobian (lagged, finite
# differences). Hairer & Wanner, Solving ODEs II, Sec. IV.7, form:
#   (I - h g W) k_i = f(t + a_i h, y + h sum_j A_ij k_j) + h W sum_j G_ij k_j,
#   y1 = y + h sum b_i k_i,  err = h sum (b_i - bh_i) k_i.
# W has the bearing's arrow structure: balls do not touch each other, so the ball-ball part is block
# diagonal (9 x 9 per ball: Hertz normal contact at ~3e4 rad/s and the traction slope, which at low rolling
# speed damps ball slip at ~1e5 1/s), plus the coupling of every ball to the 20 ring / cage / outer-ring
# states (the cage pocket contacts are as stiff as the balls). Column k of every ball block comes from ONE
# right-hand side call that perturbs state k of all balls at once; the rhs reports each ball's share of
# the ring / cage loads (bd columns BD_C*), which gives the fixed-state rows of those columns per ball.
# 20 more calls give the fixed-state columns (fewer when the configuration freezes some of them, e.g. a
# rigid outer ring): 29 calls per Jacobian at most (f and the details at the point itself come from the
# integrator's last call there). The linear systems are solved
# by eliminating the ball blocks (Schur complement on the 20 fixed states). t is treated as a state with
# a zero column in W (allowed for a W-method), so no df/dt term appears.
ROSW_G = 4.3586652150845900e-01
ROSW_A = np.array([[0.0, 0.0, 0.0, 0.0],
                   [8.7173304301691801e-01, 0.0, 0.0, 0.0],
                   [8.4457060015369423e-01, -1.1299064236484185e-01, 0.0, 0.0],
                   [0.0, 0.0, 1.0, 0.0]])
ROSW_GAM = np.array([[0.0, 0.0, 0.0, 0.0],
                     [-8.7173304301691801e-01, 0.0, 0.0, 0.0],
                     [-9.0338057013044082e-01, 5.4180672388095326e-02, 0.0, 0.0],
                     [2.4212380706095346e-01, -1.2232505839045147e+00, 5.4526025533510214e-01, 0.0]])
ROSW_B = np.array([2.4212380706095346e-01, -1.2232505839045147e+00, 1.5452602553351020e+00,
                   4.3586652150845900e-01])
ROSW_BH = np.array([3.7810903145819369e-01, -9.6042292212423178e-02, 0.5, 2.1793326075422950e-01])
ROSW_C = np.array([0.0, 8.7173304301691801e-01, 7.3157995778885238e-01, 1.0])
JAC_EVERY = 20
# The factorisation of I - h_lu g W is kept for a step hs with 0.8 <= h_lu / hs <= 1.25: that is the
# W-method with W' = (h_lu / hs) W, which keeps order 3 (any W) and, for W = alpha J with 0.7 <= alpha <= 2,
# an A-stable stability function R(z, alpha z) (|R| <= 1 on the left half-plane, checked numerically on a
# polar grid to |z| = 1e7), but not an L-stable one: |R(-inf)| = 0.29 / 0.40 at alpha = 0.8 / 1.25 (0 at
# alpha = 1), so stiff components are damped less. Refactorising at every change of h took 6 of 10 step
# attempts (Kalker, 1000 rpm). Against refactorising at every change, over 0.2 s of Kalker / 0.5 s of EHL
# traction at 1000 rpm: the band 0.8..1.25 took -2 % / +4 % right-hand sides and -7 % / +2 % CPU time;
# a band 0.8..2 took -5 % / +14 % right-hand sides (the less damped stiff modes cost rejected steps).
ROSW_REUSE_LO = 0.8
ROSW_REUSE_HI = 1.25
# The stages are solved for u_s = sum_{q<=s} Gamma_sq k_s (Gamma = ROSW_GAM + g I) instead of k_s, which
# removes the product W sum gamma_sq k_q from every stage (Hairer & Wanner II, Sec. IV.7, Eq. 7.25):
#   (I - h g W) u_s = g (f(y + h sum_q A'_sq u_q) + sum_{q<s} C_sq u_q),
#   y1 = y + h sum_s m_s u_s, error h sum_s e_s u_s,
# with A' = A Gamma^-1, C = diag(1/g) - Gamma^-1, m = b Gamma^-1, e = (b - b^) Gamma^-1.
_ROSW_GINV = np.linalg.inv(ROSW_GAM + ROSW_G * np.eye(4))
ROSW_TA = ROSW_A @ _ROSW_GINV
ROSW_TC = np.diag(np.full(4, 1.0 / ROSW_G)) - _ROSW_GINV
ROSW_TM = ROSW_B @ _ROSW_GINV
ROSW_TE = (ROSW_B - ROSW_BH) @ _ROSW_GINV


@hot
def _lu_factor(M, piv):
    """In-place LU with partial pivoting of a small dense matrix (Golub & Van Loan Alg. 3.4.1)."""
    m = M.shape[0]
    for k in range(m):
        p = k
        big = abs(M[k, k])
        for i in range(k + 1, m):
            if abs(M[i, k]) > big:
                big = abs(M[i, k]); p = i
        piv[k] = p
        if p != k:
            for c in range(m):
                tmp = M[k, c]; M[k, c] = M[p, c]; M[p, c] = tmp
        d = M[k, k]
        if d == 0.0:
            d = 1e-300
            M[k, k] = d
        for i in range(k + 1, m):
            M[i, k] /= d
            f = M[i, k]
            if f != 0.0:
                for c in range(k + 1, m):
                    M[i, c] -= f * M[k, c]


@hot
def _lu_solve(M, piv, x):
    """Solve (LU) z = x in place on x[:m] (M: m x m)."""
    m = M.shape[0]
    for k in range(m):
        p = piv[k]
        if p != k:
            tmp = x[k]; x[k] = x[p]; x[p] = tmp
    for i in range(1, m):
        s = x[i]
        for c in range(i):
            s -= M[i, c] * x[c]
        x[i] = s
    for i in range(m - 1, -1, -1):
        s = x[i]
        for c in range(i + 1, m):
            s -= M[i, c] * x[c]
        x[i] = s / M[i, i]


@hot
def _cb_rows(P):
    """Rows of dy that the ball contribution channels BD_CFRX..BD_CFOY enter, and their factors
    (mirrors the end of rhs: masses, multiplicity and the zeroed rows of each configuration)."""
    rows = CB_ROWS.copy()
    fac = np.zeros(NCB)
    axisym = P[P_AXISYM] > 0.5
    mult = P[P_MULT]
    if P[P_COUPLING] < 0.5:
        if not axisym:
            fac[0] = 1.0 / P[P_MI]; fac[1] = 1.0 / P[P_MI]
            if P[P_FIXTILT] < 0.5:
                fac[3] = 1.0 / P[P_IT]; fac[4] = 1.0 / P[P_IT]
        fac[2] = mult / P[P_MI]
    if not axisym:
        fac[5] = 1.0 / P[P_MC]; fac[6] = 1.0 / P[P_MC]
        if P[P_OUTER_ELASTIC] > 0.5:
            fac[8] = 1.0 / P[P_MO]; fac[9] = 1.0 / P[P_MO]
    fac[7] = mult / P[P_IC]
    return rows, fac


@hot
def _frozen_fixed(P):
    """Fixed states whose derivative the rhs sets to zero in this configuration (mirrors its end:
    prescribed inner-ring motion, fixed tilt, the reduced axisymmetric model, a rigid outer ring). Such a
    state's row of I - h g W is a unit row and its right-hand sides are zero, so its component of every
    stage solution is 0 and its Jacobian column never enters: the Jacobian skips those columns."""
    fr = np.zeros(NSTATE_FIXED, dtype=np.bool_)
    axisym = P[P_AXISYM] > 0.5
    if P[P_COUPLING] > 0.5:
        for k in range(10):
            fr[k] = True
    else:
        if P[P_FIXTILT] > 0.5:
            fr[3] = True; fr[4] = True; fr[8] = True; fr[9] = True
        if axisym:
            for k in (0, 1, 3, 4, 5, 6, 8, 9):
                fr[k] = True
    if axisym:
        for k in range(12, 16):
            fr[k] = True
    if not (P[P_OUTER_ELASTIC] > 0.5 and not axisym):
        for k in range(16, 20):
            fr[k] = True
    return fr


@hot
def _jacobian(t, y, f0, Wff, Wbf, Wfb, Wbb, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, atol_scale,
              yt, ft, diag, bd, bd0):
    """Finite-difference W in arrow form: Wff (20 x 20), Wbf (nb x 9 x 20: ball rows, fixed columns),
    Wfb (nb x 20 x 9: fixed rows, ball columns), Wbb (nb x 9 x 9). f0 and bd0 must hold f and the
    per-ball details at (t, y) (the caller's last right-hand side there); diag and bd are scratch.
    Returns the number of rhs calls (NSTATE_FIXED + NSB less the frozen fixed states, _frozen_fixed)."""
    n = y.size
    nb = Wbb.shape[0]
    rows, fac = _cb_rows(P)
    frozen = _frozen_fixed(P)
    ncall = NSB
    for k in range(NSTATE_FIXED):
        if frozen[k]:
            for r in range(NSTATE_FIXED):
                Wff[r, k] = 0.0
            for j in range(nb):
                for r in range(NSB):
                    Wbf[j, r, k] = 0.0
            continue
        ncall += 1
        for i in range(n):
            yt[i] = y[i]
        d = 1.5e-8 * max(abs(y[k]), abs(atol_scale[k]) * 1e2)
        yt[k] = y[k] + d
        d = yt[k] - y[k]
        rhs(t, yt, ft, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd, False)
        for r in range(NSTATE_FIXED):
            Wff[r, k] = (ft[r] - f0[r]) / d
        for j in range(nb):
            o = NSTATE_FIXED + NSB * j
            for r in range(NSB):
                Wbf[j, r, k] = (ft[o + r] - f0[o + r]) / d
    for k in range(NSB):
        for i in range(n):
            yt[i] = y[i]
        for j in range(nb):
            i = NSTATE_FIXED + NSB * j + k
            sc = abs(atol_scale[i]) * 1e2
            yt[i] = y[i] + 1.5e-8 * max(abs(y[i]), sc)
        rhs(t, yt, ft, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd, True)
        for j in range(nb):
            o = NSTATE_FIXED + NSB * j
            d = yt[o + k] - y[o + k]
            for r in range(NSB):
                Wbb[j, r, k] = (ft[o + r] - f0[o + r]) / d
            for r in range(NSTATE_FIXED):
                Wfb[j, r, k] = 0.0
            for c in range(NCB):
                Wfb[j, rows[c], k] = fac[c] * (bd[j, BD_CFRX + c] - bd0[j, BD_CFRX + c]) / d
    return ncall


@hot
def _lu_block(LUb, pivb, j):
    """In-place LU with partial pivoting of the NSB x NSB ball block LUb[j] (Golub & Van Loan
    Alg. 3.4.1; loops of constant length, no array views)."""
    for k in range(NSB):
        p = k
        big = abs(LUb[j, k, k])
        for i in range(k + 1, NSB):
            if abs(LUb[j, i, k]) > big:
                big = abs(LUb[j, i, k]); p = i
        pivb[j, k] = p
        if p != k:
            for c in range(NSB):
                tmp = LUb[j, k, c]; LUb[j, k, c] = LUb[j, p, c]; LUb[j, p, c] = tmp
        d = LUb[j, k, k]
        if d == 0.0:
            d = 1e-300
            LUb[j, k, k] = d
        for i in range(k + 1, NSB):
            LUb[j, i, k] /= d
            f = LUb[j, i, k]
            if f != 0.0:
                for c in range(k + 1, NSB):
                    LUb[j, i, c] -= f * LUb[j, k, c]


@hot
def _w_factor(hg, Wff, Wbf, Wfb, Wbb, LUb, pivb, Minv, Z, S, pivs):
    """Factor M = I - hg W in arrow form: ball blocks M_j = I - hg Wbb_j (LU in LUb, pivb, and the
    explicit inverse Minv_j, whose product with a vector has no dependency chain), the row blocks
    Z_j = Wfb_j M_j^-1 on the NCB rows CB_ROWS that Wfb can fill (NCB x NSB), and the Schur complement on
    the fixed states S = I - hg Wff - hg^2 sum_j Z_j Wbf_j (LU in place, pivs). No allocation."""
    nb = Wbb.shape[0]
    nf = NSTATE_FIXED
    hg2 = hg * hg
    for r in range(nf):
        for c in range(nf):
            S[r, c] = -hg * Wff[r, c]
        S[r, r] += 1.0
    for j in range(nb):
        for a in range(NSB):
            for c in range(NSB):
                LUb[j, a, c] = -hg * Wbb[j, a, c]
            LUb[j, a, a] += 1.0
        _lu_block(LUb, pivb, j)
        # row r of M_j^-1: z M_j = e_r with P M_j = L U: solve a U = e_r, then b L = a, then z = b P
        for r in range(NSB):
            for c in range(NSB):
                sacc = 1.0 if c == r else 0.0
                for k in range(c):
                    sacc -= Minv[j, r, k] * LUb[j, k, c]
                Minv[j, r, c] = sacc / LUb[j, c, c]
            for c in range(NSB - 2, -1, -1):
                sacc = Minv[j, r, c]
                for k in range(c + 1, NSB):
                    sacc -= Minv[j, r, k] * LUb[j, k, c]
                Minv[j, r, c] = sacc
            for k in range(NSB - 1, -1, -1):
                p = pivb[j, k]
                if p != k:
                    tmp = Minv[j, r, k]; Minv[j, r, k] = Minv[j, r, p]; Minv[j, r, p] = tmp
        for q in range(NCB):
            r = CB_ROWS[q]
            for c in range(NSB):
                Z[j, q, c] = 0.0
            for a in range(NSB):
                w = Wfb[j, r, a]
                if w != 0.0:
                    for c in range(NSB):
                        Z[j, q, c] += w * Minv[j, a, c]
            for a in range(NSB):
                za = hg2 * Z[j, q, a]
                if za != 0.0:
                    for c in range(nf):
                        S[r, c] -= za * Wbf[j, a, c]
    _lu_factor(S, pivs)


@hot
def _w_solve(hg, x, Wbf, Minv, Z, S, pivs, tmp):
    """x <- (I - hg W)^-1 x with the factors of _w_factor (same hg): eliminate the ball blocks
    (x_f += hg sum_j Z_j x_j), solve S on the fixed states, then x_j <- M_j^-1 (x_j + hg Wbf_j x_f)
    (tmp: NSB scratch)."""
    nb = Minv.shape[0]
    nf = NSTATE_FIXED
    for j in range(nb):
        o = nf + NSB * j
        for q in range(NCB):
            acc = 0.0
            for a in range(NSB):
                acc += Z[j, q, a] * x[o + a]
            x[CB_ROWS[q]] += hg * acc
    _lu_solve(S, pivs, x)         # acts on x[:nf] (S is nf x nf)
    for j in range(nb):
        o = nf + NSB * j
        for a in range(NSB):
            acc = 0.0
            for c in range(nf):
                acc += Wbf[j, a, c] * x[c]
            tmp[a] = x[o + a] + hg * acc
        for a in range(NSB):
            acc = 0.0
            for c in range(NSB):
                acc += Minv[j, a, c] * tmp[c]
            x[o + a] = acc


@hot
def rosw_workspace(nb):
    """Jacobian and factorisation arrays of integrate_rosw, kept between calls so that consecutive
    intervals (FMU communication steps, 'auto' chunks) reuse W and its LU factors (a W-method keeps its
    order with any W, so a lagged W from the previous interval is legitimate): Wff, Wbf, Wfb, Wbb (the
    Jacobian in arrow form), LUb, pivb, Minv, Z, S, pivs (_w_factor), jst = [age of W in accepted steps
    (>= JAC_EVERY: rebuild), h of the current factorisation (< 0: none)]."""
    nf = NSTATE_FIXED
    return (np.zeros((nf, nf)), np.zeros((nb, NSB, nf)), np.zeros((nb, nf, NSB)), np.zeros((nb, NSB, NSB)),
            np.zeros((nb, NSB, NSB)), np.zeros((nb, NSB), dtype=np.int64), np.zeros((nb, NSB, NSB)),
            np.zeros((nb, NCB, NSB)), np.zeros((nf, nf)), np.zeros(nf, dtype=np.int64),
            np.array([float(JAC_EVERY), -1.0]))


@hot(inline="always")
def _rosw_stages(t, hs, hg, y, f0, us, yt, r, tmp9, dq, Wbf, Minv, Z, S, pivs, P, U, tab_i, tab_o, ta0, tda, tp, qx,
                 qwx, qy, qwy, diag, bd):
    """The four transformed stages us of ROS34PW2 (see ROSW_TA ..) for the step hs from (t, y), f0 = f(t, y),
    with the factorised W of hg = h_lu gamma (_w_solve); their output channels added to the step integrals
    dq (the first one's added by the caller). yt, r, tmp9: scratch. Returns False if a stage is not
    finite."""
    n = y.size
    ok = True
    for s in range(4):
        if s == 0:
            for i in range(n):
                r[i] = ROSW_G * f0[i]
        else:
            for i in range(n):
                acc = 0.0
                for q in range(s):
                    acc += ROSW_TA[s, q] * us[q, i]
                yt[i] = y[i] + hs * acc
            rhs(t + ROSW_C[s] * hs, yt, r, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd,
                False)
            # integrals: the W-method on q' = p(y) with zero Jacobian rows gives q += h sum b_s p(Y_s)
            _quad_stage(dq, ROSW_B[s], diag, False)
            for i in range(n):
                acc = r[i]
                for q in range(s):
                    acc += ROSW_TC[s, q] * us[q, i]
                r[i] = ROSW_G * acc
        _w_solve(hg, r, Wbf, Minv, Z, S, pivs, tmp9)
        for i in range(n):
            us[s, i] = r[i]
            if not math.isfinite(r[i]):
                ok = False
    return ok


@hot(inline="always")
def _rosw_solution(y, us, hs, ynew, atol_scale, rtol):
    """The order-3 solution ynew = y + hs sum_s m_s u_s of ROS34PW2 from its transformed stages us; returns
    the RMS norm of the local error estimate hs sum_s (m_s - mhat_s) u_s (ROSW_TM, ROSW_TE), with the
    scales of _error_norm, in the same pass (no error vector), 1e300 if not finite."""
    n = y.size
    acc2 = 0.0
    for i in range(n):
        e = 0.0
        yn = y[i]
        for s in range(4):
            yn += hs * ROSW_TM[s] * us[s, i]
            e += hs * ROSW_TE[s] * us[s, i]
        ynew[i] = yn
        at = atol_scale[i]
        sc = -at if at < 0.0 else at + rtol * max(abs(y[i]), abs(yn))
        q = e / sc
        acc2 += q * q
    if not math.isfinite(acc2):
        return 1e300
    return math.sqrt(acc2 / n)


@hot(nogil=True)
def integrate_rosw(y, t0, t1, h0, rtol, atol_scale, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy,
                   rec_dt, rec, nrec_max, stats, quad, diag_out, bd_out, Wff, Wbf, Wfb, Wbb, LUb, pivb, Minv, Z, S,
                   pivs, jst):
    """Adaptive ROS34PW2 with the arrow-structured W (see above); same contract as integrate() (diag_out,
    bd_out included). The W
    arrays and their factors (Wff .. pivs, jst: rosw_workspace) carry over between calls."""
    n = y.size
    nb = int(P[P_NB])
    nf = NSTATE_FIXED
    f0 = np.empty(n)
    us = np.empty((4, n))     # transformed stages u_s (see ROSW_TA ..)
    yt = np.empty(n)
    ft = np.empty(n)
    r = np.empty(n)
    ynew = np.empty(n)
    tmp9 = np.empty(NSB)
    diag = np.empty(NOUT)
    d0 = np.empty(NOUT)       # channels at the accepted point (t, y) (diag is scratch for the stages)
    dq = np.empty(NOUT)
    bd = np.empty((nb, NBD))
    bd0 = np.empty((nb, NBD))
    nrec = 0
    t = t0
    next_rec = t0 if rec_dt > 0 else 1e300
    h = h0
    jac_age = int(jst[0])
    h_lu = jst[1] if jac_age < JAC_EVERY else -1.0
    nrej = 0
    err_prev = 1e-4
    # f0, d0 and bd0 always describe the accepted point (t, y); bd0 feeds the Jacobian's fixed-state rows
    rhs(t, y, f0, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd0, True)
    _start_point(quad, t, diag, d0)
    stats[2] += 1
    while t < t1 - 1e-15:
        if jac_age >= JAC_EVERY:
            stats[2] += _jacobian(t, y, f0, Wff, Wbf, Wfb, Wbb, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy,
                                  qwy, atol_scale, yt, ft, diag, bd, bd0)
            jac_age = 0
            h_lu = -1.0
        nrec, next_rec, hs = _propose_step(rec, nrec, nrec_max, next_rec, rec_dt, t, t1, d0, h)
        if h_lu <= 0.0 or hs * ROSW_REUSE_LO > h_lu or hs * ROSW_REUSE_HI < h_lu:
            _w_factor(hs * ROSW_G, Wff, Wbf, Wfb, Wbb, LUb, pivb, Minv, Z, S, pivs)
            h_lu = hs
        hg = h_lu * ROSW_G
        _quad_stage(dq, ROSW_B[0], d0, True)
        ok = _rosw_stages(t, hs, hg, y, f0, us, yt, r, tmp9, dq, Wbf, Minv, Z, S, pivs, P, U, tab_i, tab_o, ta0,
                          tda, tp, qx, qwx, qy, qwy, diag, bd)
        stats[2] += 3
        err = _rosw_solution(y, us, hs, ynew, atol_scale, rtol) if ok else 1e300
        ok = err < 1e300
        if ok and err <= 1.0:
            t += hs
            for i in range(n):
                y[i] = ynew[i]
            stats[0] += 1
            jac_age += 1
            nrej = 0
            rhs(t, y, f0, P, U, tab_i, tab_o, ta0, tda, tp, qx, qwx, qy, qwy, diag, bd0, True)
            _accept_point(quad, hs, dq, t, diag, d0)
            stats[2] += 1
            # PI controller for an order-2 error estimate; factors in [1, 1.25] keep h (and W's factors)
            h, err_prev = _pi_next_step_held(h, hs, err, err_prev, 3.0, 4.0, 1.25)
        else:
            h, failed = _reject(stats, hs, ok, err, 3.0)
            nrej += 1
            if nrej >= 2 and jac_age > 0:
                jac_age = JAC_EVERY       # repeated rejections: refresh the lagged Jacobian
            if failed:
                jst[0] = JAC_EVERY
                return nrec
    stats[3] = h
    jst[0] = jac_age
    jst[1] = h_lu
    _store_outputs(diag_out, bd_out, diag, bd0)
    return nrec
