"""Basic dynamic load rating of a ball bearing after ISO 281:2007, from the bearing definition.

Units: the ISO formulas take mm and give N; the functions here take SI (m, rad) and give N.

[ISO281] ISO 281:2007, Rolling bearings - Dynamic load ratings and rating life, clause 6.1.1:
         radial and angular contact ball bearings (nominal contact angle alpha <= 45 deg), one row (i = 1):
           C_r = b_m f_c (i cos alpha)^0.7 Z^(2/3) D_w^1.8            for D_w <= 25.4 mm
           C_r = 3.647 b_m f_c (i cos alpha)^0.7 Z^(2/3) D_w^1.4      for D_w >  25.4 mm
         b_m = 1.3 (Table 1, radial and angular contact groove ball bearings); f_c from Table 2 against
         gamma = D_w cos(alpha) / D_pw, column 'single-row radial contact groove ball bearings and single-
         and double-row angular contact groove ball bearings', linear interpolation between its rows.
         The Table 2 values below were entered as recalled and should be checked against a copy; the
         Lundberg-Palmgren expression they derive from (lundberg_palmgren_fc) reproduces them within 5 %
         (tests/test_life.py, bearing_validation case iso281-fc-lundberg-palmgren).
[LP]     G. Lundberg, A. Palmgren, Dynamic capacity of rolling bearings, Acta Polytech. Mech. Eng. Ser. 1(3),
         1947; in the form of Harris & Kotzalas, Rolling Bearing Analysis 5th ed., Vol. 2 Ch. 8 and
         ISO/TR 1281-1 (explanatory notes on ISO 281), for point contact with f_i = 0.52, f_e = 0.53:
           f_c = 39.9 {1 + [1.04 ((1 - g)/(1 + g))^1.72 (f_i (2 f_e - 1) / (f_e (2 f_i - 1)))^0.41]^(10/3)}^(-0.3)
                 g^0.3 (1 - g)^1.39 / (1 + g)^(1/3) (2 f_i / (2 f_i - 1))^0.41
         (without b_m and the standard's reduction factors).

Thrust ball bearings (alpha > 45 deg) are rated with other tables of ISO 281 (Table 4, C_a) that are not
implemented: such a bearing needs its catalogue rating in the bearing file (dynamic_load_rating_N).
"""
from __future__ import annotations

import math

from ..errors import BearingInputError

B_M_BALL = 1.3                # ISO 281:2007 Table 1, radial and angular contact groove ball bearings
DW_LIMIT_MM = 25.4            # ISO 281:2007 6.1.1: the D_w^1.8 form holds up to 25.4 mm
ALPHA_MAX_RADIAL = math.radians(45.0)   # ISO 281: radial ball bearings have alpha <= 45 deg

# ISO 281:2007 Table 2, gamma = D_w cos(alpha) / D_pw -> f_c (single-row radial and angular contact groove
# ball bearings), as recalled (see the module docstring).
FC_TABLE_GAMMA = (0.01, 0.02, 0.03, 0.04, 0.05, 0.06, 0.07, 0.08, 0.09, 0.10, 0.12, 0.14, 0.16, 0.18, 0.20,
                  0.22, 0.24, 0.26, 0.28, 0.30, 0.32, 0.34, 0.36, 0.38, 0.40)
FC_TABLE_VALUE = (29.1, 35.8, 40.3, 43.8, 46.7, 49.1, 51.1, 52.8, 54.3, 55.5, 57.5, 58.8, 59.6, 59.9, 59.9,
                  59.6, 59.0, 58.2, 57.1, 56.0, 54.6, 53.2, 51.7, 50.0, 48.4)


def iso281_fc(gamma: float) -> float:
    """f_c of ISO 281:2007 Table 2 at gamma = D_w cos(alpha) / D_pw [-], linear interpolation between the
    table's rows (as the standard prescribes); outside 0.01 <= gamma <= 0.40 a BearingInputError."""
    g = float(gamma)
    lo, hi = FC_TABLE_GAMMA[0], FC_TABLE_GAMMA[-1]
    if not (lo <= g <= hi):
        raise BearingInputError("D_w cos(alpha0) / d_m", round(g, 6), f"{lo} <= value <= {hi} (ISO 281 Table 2)")
    for k in range(len(FC_TABLE_GAMMA) - 1):
        g0, g1 = FC_TABLE_GAMMA[k], FC_TABLE_GAMMA[k + 1]
        if g <= g1:
            w = (g - g0) / (g1 - g0)
            return FC_TABLE_VALUE[k] + w * (FC_TABLE_VALUE[k + 1] - FC_TABLE_VALUE[k])
    return FC_TABLE_VALUE[-1]


def lundberg_palmgren_fc(gamma: float, fi: float = 0.52, fe: float = 0.53) -> float:
    """Lundberg-Palmgren f_c [LP] of a single-row radial ball bearing (N, mm) at gamma = D cos(alpha)/dm,
    groove conformities fi, fe (ISO 281's basis: 0.52, 0.53); no b_m, no reduction factors."""
    g = float(gamma)
    ratio = fi * (2.0 * fe - 1.0) / (fe * (2.0 * fi - 1.0))
    t = (1.04 * ((1.0 - g) / (1.0 + g)) ** 1.72 * ratio ** 0.41) ** (10.0 / 3.0)
    return (39.9 * (1.0 + t) ** -0.3 * g ** 0.3 * (1.0 - g) ** 1.39 / (1.0 + g) ** (1.0 / 3.0)
            * (2.0 * fi / (2.0 * fi - 1.0)) ** 0.41)


def iso281_dynamic_load_rating(Z: int, D: float, dm: float, alpha: float, rows: int = 1,
                               b_m: float = B_M_BALL) -> float:
    """Basic dynamic radial load rating C_r [N] of a radial or angular contact ball bearing [ISO281] 6.1.1.

    Z balls per row, ball diameter D [m], pitch diameter dm [m], nominal contact angle alpha [rad]
    (0 <= alpha <= 45 deg), rows i."""
    if not (0.0 <= alpha <= ALPHA_MAX_RADIAL + 1e-12):
        raise BearingInputError("free_contact_angle_deg", round(math.degrees(alpha), 6),
                                "0 <= value <= 45 deg for the ISO 281 radial rating (thrust ball bearings: give "
                                "dynamic_load_rating_N from the catalogue)")
    Dw, Dpw = D * 1e3, dm * 1e3
    fc = iso281_fc(Dw * math.cos(alpha) / Dpw)
    common = b_m * fc * (rows * math.cos(alpha)) ** 0.7 * Z ** (2.0 / 3.0)
    if Dw <= DW_LIMIT_MM:
        return common * Dw ** 1.8
    return 3.647 * common * Dw ** 1.4
