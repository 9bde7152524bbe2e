"""Bearing definition (geometry, materials, masses, cage) and named presets.

All fields are SI (m, rad, kg, kg m^2). Preset files in ``bearing_core/bearing/presets/*.json`` use mm and
degrees, with the unit in every key name, and cite their source.

Internal-geometry relations follow Harris & Kotzalas, Rolling Bearing Analysis, 5th ed., Vol. 1, Ch. 2:
  A  = (fi + fo - 1) D                       distance between groove curvature centres (Eq. 2.8)
  Pd = do - di - 2 D                          diametral clearance (Eq. 2.1)
  cos(alpha0) = 1 - Pd / (2 A)                free contact angle (Eq. 2.9)
  di = dm - D - Pd/2,  do = dm + D + Pd/2     raceway (groove bottom) diameters

Four-point-contact (gothic-arch) bearings, e.g. QJ with a split inner ring (Harris & Kotzalas Vol. 1
Ch. 1-2 'split-ring / gothic-arch' bearings; Amasorrain, Sagartzazu, Damian, Mech. Mach. Theory 38
(2003) 479-496; Leblanc & Nelias, ASME J. Tribol. 129 (2007) 801-808): each ring groove is two circular
arcs of radius f D whose curvature centres lie at +-e (inner_groove_offset, outer_groove_offset) from
the ring's groove mid-plane, each arc on the side of the mid-plane opposite to its centre. The fields
above describe one diagonal pair of arcs exactly as a two-point bearing (free contact angle alpha0 when
the rings are pushed axially until that pair touches, A, Pd of that pair); the other pair is its mirror
image about the ring mid-planes. Hence, with e_s = e_i + e_o:
  axial play          Pa = 2 (A sin(alpha0) - e_s)        (< 0: preloaded, all four contacts loaded)
  radial play         Pd4 = 2 (sqrt(A^2 - e_s^2) - A cos(alpha0))
  contact angle at zero clearance  sin(alpha_z) = e_s / A    (all four arcs touch a centred ball)
and the zero-clearance gothic arch of contact angle alpha_z has e_k = (f_k - 1/2) D sin(alpha_z).
Zero offsets give the two-point (single-arc) bearing.
"""
from __future__ import annotations

import json
import math
from dataclasses import dataclass, field, asdict, replace
from pathlib import Path

from ..errors import BearingInputError, check_range
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
    width: bearing width [m]; name, source: provenance strings.
    inner_groove_offset, outer_groove_offset: axial distance of each of the two curvature centres of a
    gothic-arch groove from the ring's groove mid-plane [m] (0: single-arc groove, two-point bearing);
    split_inner_ring: the inner ring is made of two halves clamped together (QJ construction; the
    halves act as one rigid ring in the models); bore, outside_diameter: boundary dimensions d, D_o [m]
    (0: not given; needed for fits, bearing_core.bearing.ring_fits). ball_roughness, race_roughness: rms
    surface roughness Rq [m] of the balls and raceways (film parameter, mixed lubrication). Defaults
    0.03 um and 0.08 um: typical finishes of precision bearing balls (0.02-0.05 um Rq) and superfinished
    raceways (0.05-0.1 um Rq) (Harris & Kotzalas, Rolling Bearing Analysis 5th ed., Vol. 2 Ch. 4; recalled).
    dynamic_load_rating: catalogue basic dynamic load rating C_r [N] (0: ISO 281 from the geometry,
    bearing_core.bearing.ratings); see the property basic_dynamic_load_rating.
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
    inner_groove_offset: float = 0.0
    outer_groove_offset: float = 0.0
    split_inner_ring: bool = False
    bore: float = 0.0
    outside_diameter: float = 0.0
    ball_roughness: float = 0.03e-6
    race_roughness: float = 0.08e-6
    dynamic_load_rating: float = 0.0

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
        check_range("dynamic_load_rating", self.dynamic_load_rating, 0.0, 1e9, unit="N")
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
        for nm, f in (("inner_groove_offset", self.fi), ("outer_groove_offset", self.fo)):
            check_range(nm, getattr(self, nm), 0.0, (f - 0.5) * self.D, unit="m")
        es = self.inner_groove_offset + self.outer_groove_offset
        if es >= self.A:
            raise BearingInputError("inner_groove_offset + outer_groove_offset", es,
                                    f"< A = (fi + fo - 1) D = {self.A:.6g} m")
        if not isinstance(self.split_inner_ring, bool):
            raise BearingInputError("split_inner_ring", self.split_inner_ring, "true | false")
        check_range("bore", self.bore, 0.0, self.inner_raceway_diameter, hi_incl=False, unit="m")
        if self.outside_diameter != 0.0:
            check_range("outside_diameter", self.outside_diameter, self.outer_raceway_diameter, None,
                        lo_incl=False, unit="m")

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

    @property
    def iso281_dynamic_load_rating(self) -> float:
        """Basic dynamic radial load rating C_r [N] from the geometry, ISO 281:2007 6.1.1 (one row, nominal
        contact angle alpha0 <= 45 deg; bearing_core.bearing.ratings)."""
        from .ratings import iso281_dynamic_load_rating
        return iso281_dynamic_load_rating(self.Z, self.D, self.dm, self.alpha0)

    @property
    def basic_dynamic_load_rating(self) -> float:
        """C_r [N] used for rating life: the catalogue value of the bearing file (dynamic_load_rating_N) if
        given, else ISO 281 from the geometry (iso281_dynamic_load_rating)."""
        return self.dynamic_load_rating if self.dynamic_load_rating > 0.0 else self.iso281_dynamic_load_rating

    # ---- four-point contact (gothic arch), see the module docstring ----------------------------
    @property
    def is_four_point(self) -> bool:
        """True for a gothic-arch (four-point-contact) bearing: a non-zero groove offset."""
        return self.inner_groove_offset > 0.0 or self.outer_groove_offset > 0.0

    @property
    def axial_play(self) -> float:
        """Axial internal play of a four-point bearing, 2 (A sin(alpha0) - e_i - e_o) [m] (< 0: preload)."""
        return 2.0 * (self.A * math.sin(self.alpha0) - self.inner_groove_offset - self.outer_groove_offset)

    @property
    def radial_play(self) -> float:
        """Diametral (radial) play of the centred four-point bearing [m] (equals Pd at zero offsets)."""
        es = self.inner_groove_offset + self.outer_groove_offset
        return 2.0 * (math.sqrt(self.A ** 2 - es ** 2) - self.A * math.cos(self.alpha0))

    @property
    def contact_angle_zero_clearance(self) -> float:
        """Contact angle at which all four arcs touch a centred ball, asin((e_i + e_o) / A) [rad]."""
        return math.asin((self.inner_groove_offset + self.outer_groove_offset) / self.A)

    def require_two_point(self, model: str):
        """Raise BearingInputError for a four-point bearing in a model that handles two-point contact
        only (it would silently ignore the second arc of each groove)."""
        if self.is_four_point:
            nm, v = (("inner_groove_offset_mm", self.inner_groove_offset) if self.inner_groove_offset > 0
                     else ("outer_groove_offset_mm", self.outer_groove_offset))
            raise BearingInputError(nm, round(v * 1e3, 6), "0 (two-point bearing)",
                                    f"{self.name} is a four-point-contact bearing; the {model} handles "
                                    "two-point angular-contact bearings only (use the quasi-static model: "
                                    "bearing_core.models.quasistatic.solve_quasistatic)")

    def with_overrides(self, **kw) -> "BearingGeometry":
        """A copy with some fields replaced (validated again)."""
        return replace(self, **kw)

    def to_dict(self) -> dict:
        d = asdict(self)
        return d


# ---- presets, catalogue designations and bearing files ----------------------------------------
def list_presets() -> list[str]:
    return sorted(json.loads(p.read_text())["name"] for p in PRESET_DIR.glob("*.json"))


def _is_file_spec(spec) -> bool:
    s = str(spec)
    return s.lower().endswith(".json") or "/" in s or "\\" in s


def bearing_definition(spec) -> dict:
    """The bearing definition in user units (see docs/bearing_files.md) for ``spec``: a preset name
    (list_presets()), a catalogue designation such as ``7210B`` (bearing_core.bearing.catalogue, internal geometry
    estimated), the path of a bearing JSON file, or a dict in that format."""
    from .catalogue import catalogue_definition, is_catalogue_designation

    if isinstance(spec, dict):
        return dict(spec)
    if isinstance(spec, Path) or _is_file_spec(spec):
        path = Path(spec).expanduser()
        if not path.is_file():
            raise BearingInputError("bearing", str(spec), "a preset name, a catalogue designation or an existing "
                                    "bearing JSON file", "file not found")
        try:
            d = json.loads(path.read_text())
        except (OSError, UnicodeDecodeError, json.JSONDecodeError) as e:
            raise BearingInputError("bearing", str(spec), "a readable JSON bearing file", str(e)) from None
        if not isinstance(d, dict):
            raise BearingInputError("bearing", str(spec), "a JSON object with the bearing-file fields")
        d.setdefault("name", path.stem)
        d.setdefault("source", f"bearing file {path.name}")
        return d
    for p in PRESET_DIR.glob("*.json"):
        d = json.loads(p.read_text())
        if d["name"].lower() == str(spec).lower():
            return d
    if is_catalogue_designation(spec):
        return catalogue_definition(spec)
    raise BearingInputError("bearing", spec, "one of " + ", ".join(list_presets())
                            + ", a catalogue designation (70xx/72xx/73xx + C/AC/A/B, e.g. 7210B) or a bearing "
                            "JSON file (docs/bearing_files.md)")


def load_bearing(spec, **overrides) -> BearingGeometry:
    """Bearing from a preset name, catalogue designation, bearing JSON file path or definition dict
    (see bearing_definition()); keyword overrides replace SI fields."""
    geo = from_dict(bearing_definition(spec))
    return geo.with_overrides(**overrides) if overrides else geo


def load_preset(name, **overrides) -> BearingGeometry:
    """Load a named preset (see list_presets()); also accepts what load_bearing() accepts."""
    return load_bearing(name, **overrides)


def preset_data(name) -> dict:
    """The raw definition (user units, with source and notes) of a preset, designation or file."""
    return bearing_definition(name)


# Fields of a bearing definition (docs/bearing_files.md); anything else is refused so that a misspelt
# optional field does not silently fall back to its default.
BEARING_FIELDS = (
    "name", "source", "notes", "estimated", "number_of_balls", "ball_diameter_mm", "pitch_diameter_mm",
    "free_contact_angle_deg", "diametral_clearance_mm", "inner_raceway_diameter_mm", "outer_raceway_diameter_mm",
    "fi", "fo", "inner_groove_radius_mm", "outer_groove_radius_mm", "ring_material", "ball_material", "width_mm",
    "inner_ring_mass_kg", "outer_ring_mass_kg", "inner_ring_inertia_kg_mm2", "inner_ring_tilt_inertia_kg_mm2",
    "cage", "inner_groove_offset_mm", "outer_groove_offset_mm", "split_inner_ring", "bore_diameter_mm",
    "outside_diameter_mm", "ball_roughness_um", "race_roughness_um", "dynamic_load_rating_N",
)
CAGE_FIELDS = ("pocket_clearance_mm", "land_clearance_mm", "guidance", "mass_kg", "inertia_kg_mm2",
               "land_width_mm", "material")


def _req(d: dict, key: str, prefix: str = ""):
    if key not in d:
        raise BearingInputError(prefix + key, None, "required field of a bearing definition")
    return d[key]


def _num(d: dict, key: str, lo=0.0, hi=None, lo_incl=False, prefix="", default=None, unit=""):
    """A finite number from field ``key`` (or ``default`` when absent), range-checked under its own name."""
    v = d.get(key, default) if default is not None else _req(d, key, prefix)
    if isinstance(v, bool) or not isinstance(v, (int, float, str)):
        raise BearingInputError(prefix + key, v, "a number")
    return check_range(prefix + key, v, lo, hi, lo_incl=lo_incl, unit=unit)


def _check_fields(d: dict, allowed, prefix=""):
    import difflib

    for k in d:
        if k not in allowed:
            near = difflib.get_close_matches(str(k), allowed, n=1)
            hint = f"did you mean '{prefix}{near[0]}'?" if near else "unknown field"
            raise BearingInputError(prefix + str(k), d[k], "one of the bearing-file fields "
                                    "(docs/bearing_files.md)", hint)


def from_dict(d: dict) -> BearingGeometry:
    """Build a BearingGeometry from a definition in user units (mm, deg, kg, kg mm^2).

    Geometry may be given as (pitch_diameter_mm, free_contact_angle_deg), (pitch_diameter_mm,
    diametral_clearance_mm) or (inner_raceway_diameter_mm, outer_raceway_diameter_mm); conformity as
    fi/fo or as groove radii inner_groove_radius_mm / outer_groove_radius_mm.
    """
    mm = 1e-3
    if not isinstance(d, dict):
        raise BearingInputError("bearing", d, "a bearing definition (JSON object)")
    _check_fields(d, BEARING_FIELDS)
    D = _num(d, "ball_diameter_mm", unit="mm") * mm
    if "fi" in d:
        fi = _num(d, "fi")
    else:
        fi = _num(d, "inner_groove_radius_mm", unit="mm") * mm / D
    if "fo" in d:
        fo = _num(d, "fo")
    else:
        fo = _num(d, "outer_groove_radius_mm", unit="mm") * mm / D
    check_range("fi", fi, 0.5, 1.0, lo_incl=False, hi_incl=False)
    check_range("fo", fo, 0.5, 1.0, lo_incl=False, hi_incl=False)
    A = (fi + fo - 1.0) * D
    if "inner_raceway_diameter_mm" in d and "outer_raceway_diameter_mm" in d:
        di = _num(d, "inner_raceway_diameter_mm", unit="mm") * mm
        do = _num(d, "outer_raceway_diameter_mm", unit="mm") * mm
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
        dm = _num(d, "pitch_diameter_mm", unit="mm") * mm
        if "free_contact_angle_deg" in d:
            alpha0 = math.radians(_num(d, "free_contact_angle_deg", 0.0, 60.0, lo_incl=True, unit="deg"))
        elif "diametral_clearance_mm" in d:
            Pd = _num(d, "diametral_clearance_mm", lo_incl=True, unit="mm") * mm
            check_range("diametral_clearance_mm", Pd / mm, 0.0, 4 * A / mm, unit="mm")
            alpha0 = math.acos(1.0 - Pd / (2.0 * A))
        else:
            raise BearingInputError("free_contact_angle_deg", None,
                                    "give free_contact_angle_deg or diametral_clearance_mm")
    ring_mat = get_material(d.get("ring_material", "steel"))
    ball_mat = get_material(d.get("ball_material", "steel"))
    c = _req(d, "cage")
    if not isinstance(c, dict):
        raise BearingInputError("cage", c, "an object with the cage fields (docs/bearing_files.md)")
    _check_fields(c, CAGE_FIELDS, "cage.")
    width = _num(d, "width_mm", unit="mm") * mm
    cage = CageData(
        pocket_clearance=_num(c, "pocket_clearance_mm", lo_incl=True, prefix="cage.", default=0.02 * D / mm,
                              unit="mm") * mm,
        land_clearance=_num(c, "land_clearance_mm", lo_incl=True, prefix="cage.", default=0.01 * dm / mm,
                            unit="mm") * mm,
        guidance=str(c.get("guidance", "outer")),
        mass=_num(c, "mass_kg", prefix="cage.", unit="kg"),
        inertia=_num(c, "inertia_kg_mm2", prefix="cage.", unit="kg mm^2") * 1e-6,
        land_width=_num(c, "land_width_mm", prefix="cage.", default=0.2 * width / mm, unit="mm") * mm,
        material=str(c.get("material", "phenolic")),
    )
    offs = {k: (_num(d, k, lo_incl=True, unit="mm") * mm if k in d else 0.0)
            for k in ("inner_groove_offset_mm", "outer_groove_offset_mm", "bore_diameter_mm", "outside_diameter_mm")}
    for k, f in (("inner_groove_offset_mm", fi), ("outer_groove_offset_mm", fo)):
        check_range(k, offs[k] / mm, 0.0, (f - 0.5) * D / mm, unit="mm")
    if offs["inner_groove_offset_mm"] + offs["outer_groove_offset_mm"] >= A:
        raise BearingInputError("inner_groove_offset_mm + outer_groove_offset_mm",
                                (offs["inner_groove_offset_mm"] + offs["outer_groove_offset_mm"]) / mm,
                                f"< A = (fi + fo - 1) D = {A / mm:.4f} mm")
    split = d.get("split_inner_ring", False)
    if not isinstance(split, bool):
        raise BearingInputError("split_inner_ring", split, "true | false")
    Z = _as_int("number_of_balls", _req(d, "number_of_balls"))
    if Z >= 3 and dm * math.sin(math.pi / Z) <= D:
        zmax = int(math.floor(math.pi / math.asin(min(1.0, D / dm))))
        raise BearingInputError("number_of_balls (Z)", Z, f"Z <= {zmax} for ball_diameter_mm = {D/mm:.4g} on a "
                                f"pitch diameter of {dm/mm:.4g} mm", "balls do not fit on the pitch circle")
    return BearingGeometry(
        name=str(_req(d, "name")),
        Z=Z,
        D=D, dm=dm, fi=fi, fo=fo, alpha0=alpha0,
        ring_material=ring_mat, ball_material=ball_mat,
        inner_ring_mass=_num(d, "inner_ring_mass_kg", unit="kg"),
        outer_ring_mass=_num(d, "outer_ring_mass_kg", unit="kg"),
        inner_ring_inertia=_num(d, "inner_ring_inertia_kg_mm2", unit="kg mm^2") * 1e-6,
        inner_ring_tilt_inertia=_num(d, "inner_ring_tilt_inertia_kg_mm2", unit="kg mm^2") * 1e-6,
        width=width, cage=cage,
        source=str(d.get("source", "")), notes=str(d.get("notes", "")),
        inner_groove_offset=offs["inner_groove_offset_mm"], outer_groove_offset=offs["outer_groove_offset_mm"],
        split_inner_ring=split, bore=offs["bore_diameter_mm"], outside_diameter=offs["outside_diameter_mm"],
        ball_roughness=_num(d, "ball_roughness_um", lo_incl=True, default=0.03, unit="um") * 1e-6,
        race_roughness=_num(d, "race_roughness_um", lo_incl=True, default=0.08, unit="um") * 1e-6,
        dynamic_load_rating=(_num(d, "dynamic_load_rating_N", 0.0, 1e9, unit="N")
                             if "dynamic_load_rating_N" in d else 0.0),
    )


def _as_int(name, v) -> int:
    try:
        iv = int(v)
    except (TypeError, ValueError):
        raise BearingInputError(name, v, "integer >= 3")
    if iv != v:
        raise BearingInputError(name, v, "integer >= 3")
    return iv
