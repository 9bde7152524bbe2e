"""Material data (SI units: Pa, -, kg/m^3).

Values: AISI 52100 bearing steel as used by the seed papers (E = 206 GPa, nu = 0.3, 7800 kg/m^3,
Lubricants 2025 13(5) 218 Table 2); silicon nitride (hot-pressed Si3N4) and the cage materials from
Harris & Kotzalas, Rolling Bearing Analysis, 5th ed., Vol. 1, Ch. 2 (material tables).
"""
from __future__ import annotations

from dataclasses import dataclass

from .errors import BearingInputError, check_range


@dataclass(frozen=True)
class Material:
    """Isotropic elastic material: E [Pa], nu [-], density [kg/m^3]."""

    name: str
    E: float
    nu: float
    density: float

    def __post_init__(self):
        check_range(f"material[{self.name}].E", self.E, 0.0, None, lo_incl=False, unit="Pa")
        check_range(f"material[{self.name}].nu", self.nu, -1.0, 0.5, lo_incl=False, hi_incl=False)
        check_range(f"material[{self.name}].density", self.density, 0.0, None, lo_incl=False, unit="kg/m^3")


MATERIALS = {
    "steel": Material("steel", 206e9, 0.3, 7800.0),          # AISI 52100, seed 000 Table 2
    "silicon_nitride": Material("silicon_nitride", 310e9, 0.26, 3200.0),  # Harris & Kotzalas
    "brass": Material("brass", 100e9, 0.34, 8500.0),
    "phenolic": Material("phenolic", 7e9, 0.35, 1360.0),     # cotton-reinforced phenolic resin
    "nylon": Material("nylon", 2.8e9, 0.4, 1140.0),          # PA66 cage (seed 002 Table 2 names nylon)
}


def get_material(name_or_dict) -> Material:
    """Material by name (see MATERIALS) or from a dict with keys name, E, nu, density (SI)."""
    if isinstance(name_or_dict, Material):
        return name_or_dict
    if isinstance(name_or_dict, dict):
        d = dict(name_or_dict)
        return Material(d.get("name", "custom"), float(d["E"]), float(d["nu"]), float(d["density"]))
    key = str(name_or_dict).strip().lower().replace(" ", "_")
    if key not in MATERIALS:
        raise BearingInputError("material", name_or_dict, "one of " + ", ".join(sorted(MATERIALS)))
    return MATERIALS[key]
