"""Whole-bearing friction torque estimates used by bearing engineers: the SKF model (2004) and Palmgren's.

Both are catalogue-style correlations in their own (non-SI) units; the functions take SI-friendly
arguments (mm, rpm, mm^2/s as named) and return N m. They serve as references for the dynamics' friction
torque, not as part of it.

SKF model [SKF04]:  M = phi_ish phi_rs M_rr + M_sl + M_seal + M_drag          [N mm]
  M_rr = G_rr (nu n)^0.6,  M_sl = G_sl mu_sl,
  angular contact ball bearings:
      G_rr = R1 dm^1.97 (Fr + Fg + R2 Fa)^0.54,          Fg = R3 dm^4 n^2
      G_sl = S1 dm^0.26 ((Fr + Fg)^(4/3) + S2 Fa^(4/3)),  Fg = S3 dm^4 n^2
  mu_sl = phi_bl mu_bl + (1 - phi_bl) mu_EHL,  phi_bl = exp(-2.6e-8 (n nu)^1.4 dm),
          mu_bl = 0.15, mu_EHL = 0.05 (mineral oils; 0.04 synthetic oils, 0.1 transmission fluids)
  inlet shear heating:  phi_ish = 1 / (1 + 1.84e-9 (n dm)^1.28 nu^0.64)
  kinematic replenishment / starvation:
          phi_rs = exp(-K_rs nu n (d + D) sqrt(K_Z / (2 (D - d)))),
          K_rs = 3e-8 (low-level oil bath, oil jet), 6e-8 (grease, oil-air); K_Z = 4.4 single-row ACBB
  drag (oil bath):  M_drag = V_M K_ball dm^5 n^2,  K_ball = i_rw K_Z (d + D) / (D - d) 1e-12
          V_M = V_M(H / dm), SKF's diagram 'drag loss variable V_M' for ball bearings against the oil level
          H over dm (``drag_loss_variable``; 0 for jet / mist lubrication here)
  dm = (d + D) / 2 [mm], n [rpm], nu [mm^2/s] at operating temperature, loads [N].
  72 B (40 deg) geometry constants: R1 = 5.03e-7, R2 = 1.97, R3 = 1.90e-12, S1 = 1.30e-2, S2 = 0.68,
  S3 = 1.91e-12 (SKF General Catalogue 6000 EN (2008), 'Friction', table of geometry constants for
  rolling and sliding frictional moments, angular contact ball bearings, series 72 B; the equations of
  table 2a of the same chapter were checked against a reproduction of the catalogue page; the constant
  values are recalled from memory -- not re-checked against the printed table).

Palmgren [HK07]:  M = M0 + M1                                                   [N mm]
  M0 = 1e-7 f0 (nu n)^(2/3) dm^3  for nu n >= 2000,   M0 = 160e-7 f0 dm^3  below (the two meet at 2000)
  M1 = f1 P1 dm,  single-row angular contact ball bearings: f1 = 0.001 (P0 / C0)^0.33,
       P1 = max(Fa - 0.1 Fr, Fr)  (Harris & Kotzalas Vol. 2 Ch. 'Friction', Palmgren's f1 / P1 table)
  f0 = 2 for single-row angular contact ball bearings in an oil bath (Harris & Kotzalas, f0 table; half
  of that for oil mist, twice for a vertical shaft / oil jet flooding); recalled from memory.
  P0 = X0 Fr + Y0 Fa, X0 = 0.5, Y0 = 0.26 for 40 deg (ISO 76:2006 Table 2), P0 >= Fr.
  C0: ISO 76 basic static load rating; when not given it is computed with ISO 76's own basis (the
  4200 MPa contact stress at the most loaded inner contact, with Stribeck's Q_max = 5 P0 / (Z cos alpha)).

[SKF04] SKF, 'The SKF model for calculating the frictional moment', General Catalogue 6000 EN (2005/2008)
        and Rolling bearings catalogue PUB BU/P1 17000 EN (2018), chapter 'Friction'.
[VM]    The V_M(H/dm) curve for ball bearings (VM_BALL_CURVE): SKF's diagram 'Drag loss variable V_M' (SKF General
        Catalogue 10000 EN, friction chapter, drag losses in oil bath lubrication), FIGURE-DIGITISED by a
        third party with WebPlotDigitizer (J. Raposo, SKF-Bearing-Selection-Tool, github.com/JRaposo-m/
        SKF-Bearing-Selection-Tool, files 'Graficos/Friction Moments/Drag Moment/Drag Loss Factor Vm/
        ball_bearing_ampliado.csv' (H/dm 0-0.2) and 'ball_bearing.csv' (full range)): all their points, the
        zoomed file below H/dm = 0.2, the full-range file above 0.25, and V_M(0) = 0; not re-read against
        the printed diagram here. The catalogue's own rule for deep levels, use
        H = 1.2 dm when H > 1.2 dm, is applied (the curve is flat from there). The 2004 form M_drag = V_M
        K_ball dm^5 n^2 of GC 6000 EN is used with it; later SKF catalogues add a viscous correction to the
        drag term that is not modelled here.
[HK07]  T. A. Harris, M. N. Kotzalas, Rolling Bearing Analysis 5th ed., Vol. 2 (2007), chapter on friction
        ('Bearing friction torque', Palmgren's empirical equations).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import BearingInputError, check_range


@dataclass(frozen=True)
class SKFConstants:
    """SKF geometry constants of one bearing series (see module docstring for the source)."""

    R1: float
    R2: float
    R3: float
    S1: float
    S2: float
    S3: float
    K_Z: float
    source: str


SKF_CONSTANTS = {
    "72B": SKFConstants(5.03e-7, 1.97, 1.90e-12, 1.30e-2, 0.68, 1.91e-12, 4.4,
                        "SKF GC 6000 EN friction chapter, ACBB series 72 B (recalled from memory); "
                        "K_Z = 4.4 single-row ACBB"),
}
MU_EHL = {"mineral": 0.05, "synthetic": 0.04, "transmission": 0.1}   # [SKF04]
MU_BL = 0.15                                                            # [SKF04]
K_RS = {"oil-jet": 3e-8, "oil-bath": 3e-8, "grease": 6e-8, "oil-air": 6e-8}   # [SKF04]


# SKF's V_M(H/dm) for ball bearings [VM]: (H/dm, V_M), figure-digitised by a third party (module docstring)
VM_BALL_CURVE = (
    (0.0000, 0.0000e+00), (0.0096, 1.6177e-06), (0.0193, 6.1047e-06), (0.0322, 1.0553e-05),
    (0.0444, 1.5011e-05), (0.0559, 2.2350e-05), (0.0667, 3.1422e-05), (0.0763, 4.1656e-05),
    (0.0841, 5.1337e-05), (0.0919, 6.1592e-05), (0.1007, 7.4134e-05), (0.1085, 8.5539e-05),
    (0.1163, 9.8093e-05), (0.1226, 1.0894e-04), (0.1319, 1.2435e-04), (0.1378, 1.3520e-04),
    (0.1448, 1.4777e-04), (0.1504, 1.5805e-04), (0.1578, 1.7175e-04), (0.1659, 1.8603e-04),
    (0.1748, 2.0144e-04), (0.1815, 2.1401e-04), (0.1893, 2.2656e-04), (0.1944, 2.3628e-04),
    (0.2004, 2.4713e-04), (0.2522, 3.1624e-04), (0.2826, 3.6410e-04), (0.3239, 4.0513e-04),
    (0.3652, 4.4615e-04), (0.4348, 5.1111e-04), (0.5000, 5.6581e-04), (0.5978, 6.3761e-04),
    (0.6609, 6.7521e-04), (0.7239, 7.1966e-04), (0.8087, 7.8462e-04), (0.8674, 8.3590e-04),
    (0.9391, 9.0085e-04), (1.0022, 9.4872e-04), (1.0413, 9.7949e-04), (1.0696, 1.0068e-03),
    (1.1043, 1.0513e-03), (1.1348, 1.0889e-03), (1.1543, 1.1299e-03), (1.1717, 1.1778e-03),
    (1.1826, 1.2222e-03), (1.2087, 1.2462e-03), (1.2630, 1.2496e-03), (1.3848, 1.2462e-03),
)
VM_H_CAP = 1.2          # [SKF04]: for an oil level H > 1.2 dm use H = 1.2 dm


def drag_loss_variable(H_over_dm: float) -> tuple[float, bool]:
    """SKF's drag loss variable V_M [-] of ball bearings at the oil level H over the pitch diameter dm [-]
    (VM_BALL_CURVE, piecewise linear between the digitised points); returns (V_M, capped): levels above
    1.2 dm are taken at 1.2 dm as the catalogue prescribes (capped True)."""
    check_range("H / dm", H_over_dm, 0.0, 100.0)
    capped = H_over_dm > VM_H_CAP
    x = min(H_over_dm, VM_H_CAP)
    pts = VM_BALL_CURVE
    for (x0, y0), (x1, y1) in zip(pts[:-1], pts[1:]):
        if x <= x1:
            return y0 + (y1 - y0) * (x - x0) / (x1 - x0), capped
    return pts[-1][1], capped


def skf_drag_torque(d_mm: float, D_mm: float, n_rpm: float, H_mm: float, series: str = "72B",
                    rows: int = 1) -> float:
    """SKF (2004) drag moment [N m] of a ball bearing in an oil bath of level H_mm [mm] (module docstring):
    V_M(H/dm) K_ball dm^5 n^2 1e-3, K_ball = rows K_Z (d + D) / (D - d) 1e-12, dm = (d + D)/2 [mm]."""
    c = _series(series)
    check_range("d_mm", d_mm, 0.0, 5000.0, lo_incl=False, unit="mm")
    check_range("D_mm", D_mm, d_mm, 6000.0, lo_incl=False, unit="mm")
    check_range("n_rpm", n_rpm, 0.0, 1e6, unit="rpm")
    check_range("H_mm", H_mm, 0.0, 1e4, unit="mm")
    dm = 0.5 * (d_mm + D_mm)
    V_M, _ = drag_loss_variable(H_mm / dm)
    K_ball = rows * c.K_Z * (d_mm + D_mm) / (D_mm - d_mm) * 1e-12
    return V_M * K_ball * dm ** 5 * n_rpm * n_rpm * 1e-3


def _series(series):
    if series not in SKF_CONSTANTS:
        raise BearingInputError("series", series, " | ".join(SKF_CONSTANTS))
    return SKF_CONSTANTS[series]


def skf_friction(d_mm: float, D_mm: float, n_rpm: float, nu_mm2s: float, Fr: float = 0.0, Fa: float = 0.0,
                 series: str = "72B", oil: str = "mineral", lubrication: str = "oil-jet", V_M: float = 0.0,
                 rows: int = 1, M_seal: float = 0.0, oil_level_mm: float | None = None) -> dict:
    """SKF (2004) frictional moment of an angular contact ball bearing (module docstring).

    d_mm, D_mm: bore and outside diameter [mm]; n_rpm [rpm]; nu_mm2s: operating kinematic viscosity
    [mm^2/s]; Fr, Fa [N]; series: key of SKF_CONSTANTS; oil: 'mineral' | 'synthetic' | 'transmission'
    (mu_EHL); lubrication: key of K_RS; V_M: drag loss variable of SKF's oil-bath diagram (0: no bath);
    oil_level_mm: oil-bath level H [mm] -- when given, V_M = drag_loss_variable(H / dm) (and V_M must be 0);
    M_seal [N m]. Returns the parts and the total in N m: M_rr (with phi_ish phi_rs), M_sl, M_drag,
    M_seal, M, and the factors phi_ish, phi_rs, phi_bl, mu_sl, G_rr, G_sl."""
    c = _series(series)
    check_range("d_mm", d_mm, 0.0, 5000.0, lo_incl=False, unit="mm")
    check_range("D_mm", D_mm, d_mm, 6000.0, lo_incl=False, unit="mm")
    check_range("n_rpm", n_rpm, 0.0, 1e6, unit="rpm")
    check_range("nu_mm2s", nu_mm2s, 0.1, 1e5, unit="mm^2/s")
    check_range("Fr", Fr, 0.0, 1e8, unit="N")
    check_range("Fa", Fa, 0.0, 1e8, unit="N")
    check_range("V_M", V_M, 0.0, 1e-2)
    if oil_level_mm is not None:
        if V_M != 0.0:
            raise BearingInputError("V_M", V_M, "0 when oil_level_mm is given (V_M then follows from the level)")
        check_range("oil_level_mm", oil_level_mm, 0.0, 1e4, unit="mm")
        V_M = drag_loss_variable(oil_level_mm / (0.5 * (d_mm + D_mm)))[0]
    if oil not in MU_EHL:
        raise BearingInputError("oil", oil, " | ".join(MU_EHL))
    if lubrication not in K_RS:
        raise BearingInputError("lubrication", lubrication, " | ".join(K_RS))
    dm = 0.5 * (d_mm + D_mm)
    n = n_rpm
    Fg_rr = c.R3 * dm ** 4 * n * n
    Fg_sl = c.S3 * dm ** 4 * n * n
    G_rr = c.R1 * dm ** 1.97 * (Fr + Fg_rr + c.R2 * Fa) ** 0.54
    G_sl = c.S1 * dm ** 0.26 * ((Fr + Fg_sl) ** (4.0 / 3.0) + c.S2 * Fa ** (4.0 / 3.0))
    M_rr = G_rr * (nu_mm2s * n) ** 0.6
    phi_bl = math.exp(-2.6e-8 * (n * nu_mm2s) ** 1.4 * dm)
    mu_sl = phi_bl * MU_BL + (1.0 - phi_bl) * MU_EHL[oil]
    M_sl = G_sl * mu_sl
    phi_ish = 1.0 / (1.0 + 1.84e-9 * (n * dm) ** 1.28 * nu_mm2s ** 0.64)
    phi_rs = math.exp(-K_RS[lubrication] * nu_mm2s * n * (d_mm + D_mm) * math.sqrt(c.K_Z / (2.0 * (D_mm - d_mm))))
    K_ball = rows * c.K_Z * (d_mm + D_mm) / (D_mm - d_mm) * 1e-12
    M_drag = V_M * K_ball * dm ** 5 * n * n
    Mrr = phi_ish * phi_rs * M_rr
    return {"M_rr": Mrr * 1e-3, "M_sl": M_sl * 1e-3, "M_drag": M_drag * 1e-3, "M_seal": M_seal,
            "M": (Mrr + M_sl + M_drag) * 1e-3 + M_seal, "M_rr_unreduced": M_rr * 1e-3,
            "phi_ish": phi_ish, "phi_rs": phi_rs, "phi_bl": phi_bl, "mu_sl": mu_sl, "G_rr": G_rr, "G_sl": G_sl}


def iso76_static_rating(geometry, p_limit: float = 4.2e9) -> float:
    """Basic static load rating C0 [N] of a single-row angular contact ball bearing on ISO 76's basis:
    C0 = Z cos(alpha0) Q_lim / 5, Q_lim the ball load that gives p_limit [Pa] (4200 MPa) at the inner
    contact (Hertz, bearing_core.contact.hertz), 5 = Stribeck's load-distribution constant used by ISO 76."""
    from ..contact.hertz import contact_curvature, hertz_exact, reduced_modulus
    g = geometry
    E = reduced_modulus(g.ring_material.E, g.ring_material.nu, g.ball_material.E, g.ball_material.nu)
    cur = contact_curvature(g.D, g.dm, g.fi, g.alpha0, True)
    hc = hertz_exact(cur[2], cur[3], E)
    # p_max = 1.5 Q / (pi a b) with a, b ~ Q^(1/3): Q = (p_lim pi a1 b1 / 1.5)^3 for unit coefficients
    Q_lim = (p_limit * math.pi * hc.a_coef * hc.b_coef / 1.5) ** 3
    return g.Z * math.cos(g.alpha0) * Q_lim / 5.0


def palmgren_friction(dm_mm: float, n_rpm: float, nu_mm2s: float, Fr: float = 0.0, Fa: float = 0.0,
                      C0: float = 1.0, f0: float = 2.0, X0: float = 0.5, Y0: float = 0.26) -> dict:
    """Palmgren's friction torque of a single-row angular contact ball bearing (module docstring).

    dm_mm: pitch diameter [mm]; n_rpm; nu_mm2s [mm^2/s]; Fr, Fa [N]; C0: basic static load rating [N];
    f0: lubrication factor (2: oil bath); X0, Y0: ISO 76 static load factors (40 deg). Returns M0, M1, M
    [N m] and f1, P0, P1."""
    check_range("dm_mm", dm_mm, 0.0, 6000.0, lo_incl=False, unit="mm")
    check_range("n_rpm", n_rpm, 0.0, 1e6, unit="rpm")
    check_range("nu_mm2s", nu_mm2s, 0.1, 1e5, unit="mm^2/s")
    check_range("C0", C0, 0.0, 1e9, lo_incl=False, unit="N")
    check_range("f0", f0, 0.0, 100.0)
    vn = nu_mm2s * n_rpm
    M0 = 1e-7 * f0 * vn ** (2.0 / 3.0) * dm_mm ** 3 if vn >= 2000.0 else 160e-7 * f0 * dm_mm ** 3
    P0 = max(X0 * Fr + Y0 * Fa, Fr)
    f1 = 0.001 * (P0 / C0) ** 0.33
    P1 = max(Fa - 0.1 * Fr, Fr)
    M1 = f1 * P1 * dm_mm
    return {"M0": M0 * 1e-3, "M1": M1 * 1e-3, "M": (M0 + M1) * 1e-3, "f1": f1, "P0": P0, "P1": P1}


def bearing_envelope_mm(geometry) -> tuple[float, float, str]:
    """(bore d, outside diameter D) [mm] of a preset for the catalogue models, and how they were found:
    the preset's 'bore_mm' / 'outside_diameter_mm' if it has them, else estimated from the raceways as
    bearing_core.heat.thermal.ThermalData.resolved does (D = outer raceway + 0.55 D_ball, d = inner raceway -
    0.55 D_ball; 7218B: 90.6 / 160.0 mm against the ISO 90 / 160 mm)."""
    from ..bearing.geometry import preset_data
    try:
        pd = preset_data(geometry.name)
    except Exception:     # not a preset (custom geometry): estimate
        pd = {}
    if "bore_mm" in pd and "outside_diameter_mm" in pd:
        return float(pd["bore_mm"]), float(pd["outside_diameter_mm"]), "preset"
    d = (geometry.inner_raceway_diameter - 0.55 * geometry.D) * 1e3
    D = (geometry.outer_raceway_diameter + 0.55 * geometry.D) * 1e3
    return d, D, "estimated from the raceway diameters"


def reference_torques(geometry, n_rpm, nu_mm2s, Fr, Fa, lubrication: str = "oil-jet") -> dict:
    """SKF (series 72B constants) and Palmgren (f0 = 2, C0 from iso76_static_rating) friction torques [N m]
    of a single-row angular contact ball bearing at arrays of speed [rpm], radial and axial load [N] and
    one viscosity [mm^2/s]: {'skf': array, 'palmgren': array, 'envelope': how d, D were found}."""
    import numpy as np
    d, D, how = bearing_envelope_mm(geometry)
    C0 = iso76_static_rating(geometry)
    n, fr, fa = (np.broadcast_arrays(np.asarray(n_rpm, float), np.abs(np.asarray(Fr, float)),
                                     np.abs(np.asarray(Fa, float))))
    skf = np.array([skf_friction(d, D, max(a, 0.0), nu_mm2s, b, c, lubrication=lubrication)["M"]
                    for a, b, c in zip(n.ravel(), fr.ravel(), fa.ravel())]).reshape(n.shape)
    pal = np.array([palmgren_friction(geometry.dm * 1e3, max(a, 0.0), nu_mm2s, b, c, C0)["M"]
                    for a, b, c in zip(n.ravel(), fr.ravel(), fa.ravel())]).reshape(n.shape)
    return {"skf": skf, "palmgren": pal, "envelope": how, "d_mm": d, "D_mm": D}
