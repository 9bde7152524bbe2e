"""Catalogue of common angular-contact ball bearing series: 70xx, 72xx and 73xx with contact-angle
suffix C (15 deg), AC (25 deg), A (30 deg) or B (40 deg), e.g. ``7210B``, ``7006C``, ``7312AC``.

Boundary dimensions (bore d, outside diameter D_o, width B, in mm) are ISO 15 dimension series 10
(70xx), 02 (72xx) and 03 (73xx); they are the same for the 60xx/62xx/63xx deep-groove series.

The internal geometry is NOT published by ISO: it is ESTIMATED by the stated rule below and every
definition produced here says so in its ``notes``. Bearings built from a manufacturer's drawing
should be given as a bearing file (docs/bearing_files.md) instead.

Estimation rule (all lengths mm):
  pitch diameter        dm = (d + D_o) / 2
  ball diameter         D_w = k (D_o - d), rounded to the nearest 1/32 in (ISO 3290 inch sizes), with
                        k = 0.3175 for series 02, calibrated on Harris & Kotzalas' 209 and 218 bearings
                        (12.7 mm on 45 x 85 and 22.23 mm on 90 x 160: both 0.3175);
                        k = 0.2835 for series 10, calibrated on the 7008 of Rivera et al. 2021 (seed 004:
                        7.938 mm on 40 x 68);
                        k = 0.31 for series 03: no internal geometry of this series is in our sources; the
                        value is the usual 63xx ball size (e.g. 3/4 in on 50 x 110), recalled, not cited;
  number of balls       the largest Z whose ball-to-ball chord dm sin(pi/Z) is >= 1.09 D_w (the 218 of
                        Harris & Kotzalas has 16 balls at a chord of 1.099 D_w);
  conformities          fi = 0.52, fo = 0.53 (typical angular-contact values, Harris & Kotzalas Vol. 1 Ch. 2);
  free contact angle    from the suffix: C 15, AC 25, A 30, B 40 deg;
  rings                 steel annuli from the bore to the inner raceway (groove bottom) diameter and from
                        the outer raceway diameter to D_o, of width B (shoulders and grooves neglected);
  cage                  outer-land guided ring at the pitch circle of radial section 0.36 D_w and width
                        0.67 B with 40 % pocket void (phenolic for B, polyamide otherwise); pocket clearance
                        0.018 D_w, land clearance 0.0048 dm, land width 0.2 B (the 7218B preset's ratios).
"""
from __future__ import annotations

import math
import re

# ISO 15 boundary dimensions (d, D_o, B) in mm by bore code, per dimension series.
_SERIES_10 = {  # 70xx (as 60xx)
    0: (10, 26, 8), 1: (12, 28, 8), 2: (15, 32, 9), 3: (17, 35, 10), 4: (20, 42, 12), 5: (25, 47, 12),
    6: (30, 55, 13), 7: (35, 62, 14), 8: (40, 68, 15), 9: (45, 75, 16), 10: (50, 80, 16), 11: (55, 90, 18),
    12: (60, 95, 18), 13: (65, 100, 18), 14: (70, 110, 20), 15: (75, 115, 20), 16: (80, 125, 22),
    17: (85, 130, 22), 18: (90, 140, 24), 19: (95, 145, 24), 20: (100, 150, 24),
}
_SERIES_02 = {  # 72xx (as 62xx)
    0: (10, 30, 9), 1: (12, 32, 10), 2: (15, 35, 11), 3: (17, 40, 12), 4: (20, 47, 14), 5: (25, 52, 15),
    6: (30, 62, 16), 7: (35, 72, 17), 8: (40, 80, 18), 9: (45, 85, 19), 10: (50, 90, 20), 11: (55, 100, 21),
    12: (60, 110, 22), 13: (65, 120, 23), 14: (70, 125, 24), 15: (75, 130, 25), 16: (80, 140, 26),
    17: (85, 150, 28), 18: (90, 160, 30), 19: (95, 170, 32), 20: (100, 180, 34),
}
_SERIES_03 = {  # 73xx (as 63xx)
    0: (10, 35, 11), 1: (12, 37, 12), 2: (15, 42, 13), 3: (17, 47, 14), 4: (20, 52, 15), 5: (25, 62, 17),
    6: (30, 72, 19), 7: (35, 80, 21), 8: (40, 90, 23), 9: (45, 100, 25), 10: (50, 110, 27), 11: (55, 120, 29),
    12: (60, 130, 31), 13: (65, 140, 33), 14: (70, 150, 35), 15: (75, 160, 37), 16: (80, 170, 39),
    17: (85, 180, 41), 18: (90, 190, 43), 19: (95, 200, 45), 20: (100, 215, 47),
}
SERIES = {"70": ("10", _SERIES_10, 0.2835), "72": ("02", _SERIES_02, 0.3175), "73": ("03", _SERIES_03, 0.31)}
CONTACT_ANGLE_DEG = {"C": 15.0, "AC": 25.0, "A": 30.0, "B": 40.0}
_DESIGNATION = re.compile(r"^(70|72|73)(\d\d)(AC|A|B|C)$", re.IGNORECASE)
_INCH = 25.4
_STEEL_DENSITY = 7800.0            # kg/m^3, as materials.MATERIALS["steel"]
_CAGE_DENSITY = {"phenolic": 1360.0, "nylon": 1140.0}


def is_catalogue_designation(name: str) -> bool:
    m = _DESIGNATION.match(str(name).strip())
    return bool(m) and int(m.group(2)) in SERIES[m.group(1)][1]


def list_catalogue() -> list[str]:
    """All designations this catalogue can build (series x bore code x contact-angle suffix)."""
    return [f"{s}{code:02d}{suf}" for s in SERIES for code in SERIES[s][1] for suf in CONTACT_ANGLE_DEG]


def catalogue_definition(name: str) -> dict:
    """Bearing definition (the bearing-file format: mm, deg, kg, kg mm^2) for a designation such as
    ``7210B``, with internal geometry estimated by the rule in this module's docstring."""
    m = _DESIGNATION.match(str(name).strip())
    if not m or int(m.group(2)) not in SERIES[m.group(1)][1]:
        raise KeyError(name)
    series, code, suffix = m.group(1), int(m.group(2)), m.group(3).upper()
    iso_series, table, k = SERIES[series]
    d, Do, B = (float(x) for x in table[code])
    dm = 0.5 * (d + Do)
    Dw = round(k * (Do - d) / (_INCH / 32.0)) * (_INCH / 32.0)
    Z = 3
    while dm * math.sin(math.pi / (Z + 1)) >= 1.09 * Dw:
        Z += 1
    fi, fo = 0.52, 0.53
    alpha0 = CONTACT_ANGLE_DEG[suffix]
    A = (fi + fo - 1.0) * Dw
    Pd = 2.0 * A * (1.0 - math.cos(math.radians(alpha0)))
    di = dm - Dw - 0.5 * Pd                       # raceway (groove bottom) diameters, Harris & Kotzalas Eq. 2.1
    do = dm + Dw + 0.5 * Pd

    def annulus(r1, r2):                          # mass [kg], polar and diametral inertia [kg mm^2]
        m_ = _STEEL_DENSITY * math.pi * (r2 ** 2 - r1 ** 2) * B * 1e-9
        J = 0.5 * m_ * (r1 ** 2 + r2 ** 2)
        Jt = m_ * (3.0 * (r1 ** 2 + r2 ** 2) + B ** 2) / 12.0
        return m_, J, Jt

    mi, Ji, Jti = annulus(0.5 * d, 0.5 * di)
    mo, _, _ = annulus(0.5 * do, 0.5 * Do)
    cage_mat = "phenolic" if suffix == "B" else "nylon"
    t_c, w_c = 0.36 * Dw, 0.67 * B
    m_c = _CAGE_DENSITY[cage_mat] * 0.6 * t_c * w_c * math.pi * dm * 1e-9
    J_c = m_c * (0.5 * dm) ** 2 + m_c * t_c ** 2 / 12.0
    return {
        "name": f"{series}{code:02d}{suffix}",
        "source": (f"ISO 15 boundary dimensions, dimension series {iso_series}: {d:g} x {Do:g} x {B:g} mm; "
                   f"internal geometry ESTIMATED by the rule in bearing_core/bearing/catalogue.py"),
        "notes": ("Estimated, not a manufacturer's design: ball size, ball count, conformities, clearances, "
                  "masses and inertias follow bearing_core.bearing.catalogue's stated rule. Use a bearing file with "
                  "the manufacturer's internal geometry for design work."),
        "estimated": True,
        "number_of_balls": Z,
        "ball_diameter_mm": round(Dw, 4),
        "pitch_diameter_mm": round(dm, 4),
        "free_contact_angle_deg": alpha0,
        "fi": fi,
        "fo": fo,
        "ring_material": "steel",
        "ball_material": "steel",
        "width_mm": B,
        "inner_ring_mass_kg": round(mi, 5),
        "outer_ring_mass_kg": round(mo, 5),
        "inner_ring_inertia_kg_mm2": round(Ji, 3),
        "inner_ring_tilt_inertia_kg_mm2": round(Jti, 3),
        "cage": {"pocket_clearance_mm": round(0.018 * Dw, 4), "land_clearance_mm": round(0.0048 * dm, 4),
                 "guidance": "outer", "mass_kg": round(m_c, 5), "inertia_kg_mm2": round(J_c, 3),
                 "land_width_mm": round(0.2 * B, 3), "material": cage_mat},
    }
