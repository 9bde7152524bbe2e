"""Bearing definition (geometry, materials, masses, cage) and named presets.

All fields are SI (m, rad, kg, kg m^2). Preset files in ``bearing_core/presets/*.json`` use mm and
degrees, with the unit in every key name, and cite their source.

Internal-geometry relations follow Harris & Kotzalas, Rolling Bearing Analysis, 5th ed., Vol. 1, Ch. 2:
  A  = (fi + fo - 1) D                       distance between groove curvature centres (Eq. 2.8)
  Pd = do - di - 2 D                          diametral clearance (Eq. 2.1)
  cos(alpha0) = 1 - Pd / (2 A)                free contact angle (Eq. 2.9)
  di = dm - D - Pd/2,  do = dm + D + Pd/2     raceway (groove bottom) diameters
"""
from __future__ import annotations

import json
import math
from dataclasses import dataclass, field, asdict, replace
from pathlib import Path

from .errors import BearingInputError, check_range
from .materials import Material, get_material

PRESET_DIR = Path(__file__).with_name("presets")
CAGE_GUIDANCE = ("outer", "inner", "ball")


@dataclass(frozen=True)
class CageData:
    """Cage data (SI). pocket_clearance: diametral clearance ball-pocket [m]; land_clearance: diametral
    clearance between cage and guiding land [m]; guidance: 'outer' | 'inner' | 'ball'; mass [kg];
    inertia: polar moment about the bearing axis [kg m^2]; land_width: axial width of the guiding
    land contact [m]; material name."""

    pocket_clearance: float
    land_clearance: float
    guidance: str
    mass: float
    inertia: float
    land_width: float
    material: str = "phenolic"

    def validate(self, D: float):
        check_range("cage.pocket_clearance", self.pocket_clearance, 0.0, 0.5 * D, unit="m")
        check_range("cage.land_clearance", self.land_clearance, 0.0, 0.5 * D, unit="m")
        if self.guidance not in CAGE_GUIDANCE:
            raise BearingInputError("cage.guidance", self.guidance, " | ".join(CAGE_GUIDANCE))
        check_range("cage.mass", self.mass, 0.0, None, lo_incl=False, unit="kg")
        check_range("cage.inertia", self.inertia, 0.0, None, lo_incl=False, unit="kg m^2")
        check_range("cage.land_width", self.land_width, 0.0, None, lo_incl=False, unit="m")
        get_material(self.material)


@dataclass(frozen=True)
class BearingGeometry:
    """Angular-contact ball bearing. Units: m, rad, kg, kg m^2.

    Z: number of balls; D: ball diameter; dm: pitch diameter; fi, fo: groove conformities r/D;
    alpha0: free (unloaded) contact angle; ring_material / ball_material: Material;
    inner_ring_mass, outer_ring_mass [kg]; inner_ring_inertia: polar inertia of the inner ring
    about its axis [kg m^2]; inner_ring_tilt_inertia: about a diameter [kg m^2]; cage: CageData;
    width: bearing width [m]; name, source: provenance strings; ball_roughness, race_roughness: rms
    surface roughness Rq [m] of the balls and raceways (film parameter, mixed lubrication). Defaults
    0.03 um and 0.08 um: typical finishes of precision bearing balls (0.02-0.05 um Rq) and superfinished
    raceways (0.05-0.1 um Rq) (Harris & Kotzalas, Rolling Bearing Analysis 5th ed., Vol. 2 Ch. 4; recalled).
    """

    name: str
    Z: int
    D: float
    dm: float
    fi: float
    fo: float
    alpha0: float
    ring_material: Material
    ball_material: Material
    inner_ring_mass: float
    outer_ring_mass: float
    inner_ring_inertia: float
    inner_ring_tilt_inertia: float
    width: float
    cage: CageData
    source: str = ""
    notes: str = ""
    ball_roughness: float = 0.03e-6
    race_roughness: float = 0.08e-6

    def __post_init__(self):
        self.validate()

    # ---- validation -------------------------------------------------------------------------
    def validate(self):
        if not isinstance(self.Z, (int,)) or isinstance(self.Z, bool):
            raise BearingInputError("Z", self.Z, "integer >= 3")
        if self.Z < 3:
            raise BearingInputError("Z", self.Z, "integer >= 3 (fewer balls cannot centre the rings)")
        check_range("D", self.D, 0.0, None, lo_incl=False, unit="m")
        check_range("dm", self.dm, self.D, None, lo_incl=False, unit="m")
        check_range("fi", self.fi, 0.5, 1.0, lo_incl=False, hi_incl=False)
        check_range("fo", self.fo, 0.5, 1.0, lo_incl=False, hi_incl=False)
        check_range("alpha0", self.alpha0, 0.0, math.radians(60.0), unit="rad")
        check_range("ball_roughness", self.ball_roughness, 0.0, 5e-6, unit="m")
        check_range("race_roughness", self.race_roughness, 0.0, 5e-6, unit="m")
        # Balls must fit the pitch circle: chord between neighbouring ball centres > D.
        chord = self.dm * math.sin(math.pi / self.Z)
        if chord <= self.D:
            zmax = int(math.floor(math.pi / math.asin(min(1.0, self.D / self.dm))))
            raise BearingInputError(
                "Z", self.Z, f"Z <= {zmax} for D = {self.D*1e3:.4g} mm on dm = {self.dm*1e3:.4g} mm",
                "balls do not fit on the pitch circle")
        for nm in ("inner_ring_mass", "outer_ring_mass", "inner_ring_inertia", "inner_ring_tilt_inertia", "width"):
            check_range(nm, getattr(self, nm), 0.0, None, lo_incl=False)
        if not isinstance(self.ring_material, Material) or not isinstance(self.ball_material, Material):
            raise BearingInputError("material", (self.ring_material, self.ball_material), "Material instances")
        self.cage.validate(self.D)
        if self.inner_raceway_diameter <= 0:
            raise BearingInputError("dm", self.dm, "large enough for a positive inner raceway diameter")

    # ---- derived quantities (Harris & Kotzalas Ch. 2) --------------------------------------
    @property
    def A(self) -> float:
        """Distance between the groove curvature centres in the unloaded bearing [m]."""
        return (self.fi + self.fo - 1.0) * self.D

    @property
    def Pd(self) -> float:
        """Diametral clearance [m]: Pd = 2 A (1 - cos alpha0)."""
        return 2.0 * self.A * (1.0 - math.cos(self.alpha0))

    @property
    def inner_raceway_diameter(self) -> float:
        return self.dm - self.D - 0.5 * self.Pd

    @property
    def outer_raceway_diameter(self) -> float:
        return self.dm + self.D + 0.5 * self.Pd

    @property
    def ri(self) -> float:
        """Inner groove radius [m]."""
        return self.fi * self.D

    @property
    def ro(self) -> float:
        return self.fo * self.D

    @property
    def gamma0(self) -> float:
        """D cos(alpha0) / dm [-]."""
        return self.D * math.cos(self.alpha0) / self.dm

    @property
    def ball_mass(self) -> float:
        return self.ball_material.density * math.pi * self.D ** 3 / 6.0

    @property
    def ball_inertia(self) -> float:
        """Ball moment of inertia about a diameter, J = m D^2 / 10 = rho pi D^5 / 60 [kg m^2]."""
        return self.ball_mass * self.D ** 2 / 10.0

    @property
    def Ri(self) -> float:
        """Radius of the locus of inner groove curvature centres, dm/2 + (fi - 0.5) D cos(alpha0) [m]
        (Harris & Kotzalas Vol. 2 Ch. 1; seed 003 Eq. 2)."""
        return 0.5 * self.dm + (self.fi - 0.5) * self.D * math.cos(self.alpha0)

    def with_overrides(self, **kw) -> "BearingGeometry":
        """A copy with some fields replaced (validated again)."""
        return replace(self, **kw)

    def to_dict(self) -> dict:
        d = asdict(self)
        return d


# ---- presets -----------------------------------------------------------------------------
def list_presets() -> list[str]:
    return sorted(json.loads(p.read_text())["name"] for p in PRESET_DIR.glob("*.json"))


def _preset_path(name: str) -> Path:
    for p in PRESET_DIR.glob("*.json"):
        if json.loads(p.read_text())["name"].lower() == str(name).lower():
            return p
    raise BearingInputError("bearing", name, "one of " + ", ".join(list_presets()))


def load_preset(name: str, **overrides) -> BearingGeometry:
    """Load a named preset (see list_presets()); keyword overrides replace SI fields."""
    geo = from_dict(json.loads(_preset_path(name).read_text()))
    return geo.with_overrides(**overrides) if overrides else geo


def preset_data(name: str) -> dict:
    """The raw preset file content (user units, with source and notes)."""
    return json.loads(_preset_path(name).read_text())


def _req(d: dict, key: str):
    if key not in d:
        raise BearingInputError(key, None, "required field of a bearing definition")
    return d[key]


def from_dict(d: dict) -> BearingGeometry:
    """Build a BearingGeometry from a definition in user units (mm, deg, kg, kg mm^2).

    Geometry may be given as (pitch_diameter_mm, free_contact_angle_deg), (pitch_diameter_mm,
    diametral_clearance_mm) or (inner_raceway_diameter_mm, outer_raceway_diameter_mm); conformity as
    fi/fo or as groove radii inner_groove_radius_mm / outer_groove_radius_mm.
    """
    mm = 1e-3
    D = float(_req(d, "ball_diameter_mm")) * mm
    check_range("ball_diameter_mm", D / mm, 0.0, None, lo_incl=False, unit="mm")
    if "fi" in d:
        fi = float(d["fi"])
    else:
        fi = float(_req(d, "inner_groove_radius_mm")) * mm / D
    if "fo" in d:
        fo = float(d["fo"])
    else:
        fo = float(_req(d, "outer_groove_radius_mm")) * mm / D
    check_range("fi", fi, 0.5, 1.0, lo_incl=False, hi_incl=False)
    check_range("fo", fo, 0.5, 1.0, lo_incl=False, hi_incl=False)
    A = (fi + fo - 1.0) * D
    if "inner_raceway_diameter_mm" in d and "outer_raceway_diameter_mm" in d:
        di = float(d["inner_raceway_diameter_mm"]) * mm
        do = float(d["outer_raceway_diameter_mm"]) * mm
        Pd = do - di - 2.0 * D
        if Pd < 0:
            raise BearingInputError("outer_raceway_diameter_mm", do / mm,
                                    f">= inner_raceway_diameter_mm + 2 D = {(di + 2*D)/mm:.4f} mm",
                                    "negative diametral clearance")
        dm = 0.5 * (di + do)
        c = 1.0 - Pd / (2.0 * A)
        if c < -1.0:
            raise BearingInputError("diametral clearance", Pd / mm, f"<= 4 A = {4*A/mm:.4f} mm")
        alpha0 = math.acos(c)
    else:
        dm = float(_req(d, "pitch_diameter_mm")) * mm
        if "free_contact_angle_deg" in d:
            alpha0 = math.radians(float(d["free_contact_angle_deg"]))
        elif "diametral_clearance_mm" in d:
            Pd = float(d["diametral_clearance_mm"]) * mm
            check_range("diametral_clearance_mm", Pd / mm, 0.0, 4 * A / mm, unit="mm")
            alpha0 = math.acos(1.0 - Pd / (2.0 * A))
        else:
            raise BearingInputError("free_contact_angle_deg", None,
                                    "give free_contact_angle_deg or diametral_clearance_mm")
    ring_mat = get_material(d.get("ring_material", "steel"))
    ball_mat = get_material(d.get("ball_material", "steel"))
    c = d.get("cage", {})
    width = float(_req(d, "width_mm")) * mm
    cage = CageData(
        pocket_clearance=float(c.get("pocket_clearance_mm", 0.02 * D / mm)) * mm,
        land_clearance=float(c.get("land_clearance_mm", 0.01 * dm / mm)) * mm,
        guidance=str(c.get("guidance", "outer")),
        mass=float(_req(c, "mass_kg")),
        inertia=float(_req(c, "inertia_kg_mm2")) * 1e-6,
        land_width=float(c.get("land_width_mm", 0.2 * width / mm)) * mm,
        material=str(c.get("material", "phenolic")),
    )
    return BearingGeometry(
        name=str(_req(d, "name")),
        Z=_as_int("number_of_balls", _req(d, "number_of_balls")),
        D=D, dm=dm, fi=fi, fo=fo, alpha0=alpha0,
        ring_material=ring_mat, ball_material=ball_mat,
        inner_ring_mass=float(_req(d, "inner_ring_mass_kg")),
        outer_ring_mass=float(_req(d, "outer_ring_mass_kg")),
        inner_ring_inertia=float(_req(d, "inner_ring_inertia_kg_mm2")) * 1e-6,
        inner_ring_tilt_inertia=float(_req(d, "inner_ring_tilt_inertia_kg_mm2")) * 1e-6,
        width=width, cage=cage,
        source=str(d.get("source", "")), notes=str(d.get("notes", "")),
        ball_roughness=float(d.get("ball_roughness_um", 0.03)) * 1e-6,
        race_roughness=float(d.get("race_roughness_um", 0.08)) * 1e-6,
    )


def _as_int(name, v) -> int:
    try:
        iv = int(v)
    except (TypeError, ValueError):
        raise BearingInputError(name, v, "integer >= 3")
    if iv != v:
        raise BearingInputError(name, v, "integer >= 3")
    return iv
