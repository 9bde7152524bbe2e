"""Material data (SI units: Pa, -, kg/m^3, 1/K).

Values: AISI 52100 bearing steel as used by the seed papers (E = 206 GPa, nu = 0.3, 7800 kg/m^3,
Lubricants 2025 13(5) 218 Table 2); silicon nitride (hot-pressed Si3N4) and the cage materials from
Harris & Kotzalas, Rolling Bearing Analysis, 5th ed., Vol. 1, Ch. 2 (material tables).

Linear thermal expansion coefficients (room temperature to ~150 degC), used for ring and ball growth
(bearing_core.bearing.ring_fits): AISI 52100 bearing steel 12.5e-6 /K (SKF rolling bearings catalogue,
'Materials for rolling bearings'; Harris & Kotzalas Vol. 1 Ch. 'Bearing materials' gives the same
value); hot-pressed silicon nitride 3.2e-6 /K (Harris & Kotzalas Vol. 1, ceramic materials table);
shaft/housing materials: carbon steel 11.7e-6 /K, grey cast iron 10.5e-6 /K, aluminium alloy 23e-6 /K
(E 110 GPa / nu 0.26 for cast iron, 70 GPa / 0.33 for aluminium); cage materials: brass 19e-6 /K,
phenolic (fabric-reinforced) 30e-6 /K, PA66 80e-6 /K. The handbook values are recalled from those
tables, not re-read; the cage values do not enter any model yet.
"""
from __future__ import annotations

from dataclasses import dataclass

from ..errors import BearingInputError, check_range


@dataclass(frozen=True)
class Material:
    """Isotropic elastic material: E [Pa], nu [-], density [kg/m^3], expansion: linear thermal
    expansion coefficient [1/K]."""

    name: str
    E: float
    nu: float
    density: float
    expansion: float = 12.5e-6

    def __post_init__(self):
        check_range(f"material[{self.name}].E", self.E, 0.0, None, lo_incl=False, unit="Pa")
        check_range(f"material[{self.name}].nu", self.nu, -1.0, 0.5, lo_incl=False, hi_incl=False)
        check_range(f"material[{self.name}].density", self.density, 0.0, None, lo_incl=False, unit="kg/m^3")
        check_range(f"material[{self.name}].expansion", self.expansion, 0.0, 1e-3, unit="1/K")


MATERIALS = {
    "steel": Material("steel", 206e9, 0.3, 7800.0, 12.5e-6),          # AISI 52100, seed 000 Table 2
    "silicon_nitride": Material("silicon_nitride", 310e9, 0.26, 3200.0, 3.2e-6),  # Harris & Kotzalas
    "brass": Material("brass", 100e9, 0.34, 8500.0, 19e-6),
    "phenolic": Material("phenolic", 7e9, 0.35, 1360.0, 30e-6),     # cotton-reinforced phenolic resin
    "nylon": Material("nylon", 2.8e9, 0.4, 1140.0, 80e-6),          # PA66 cage (seed 002 Table 2 names nylon)
    # shaft and housing materials (bearing_core.bearing.ring_fits)
    "carbon_steel": Material("carbon_steel", 206e9, 0.3, 7850.0, 11.7e-6),
    "cast_iron": Material("cast_iron", 110e9, 0.26, 7200.0, 10.5e-6),
    "aluminium": Material("aluminium", 70e9, 0.33, 2700.0, 23e-6),
}


def get_material(name_or_dict) -> Material:
    """Material by name (see MATERIALS) or from a dict with keys name, E, nu, density and optionally
    expansion (SI)."""
    if isinstance(name_or_dict, Material):
        return name_or_dict
    if isinstance(name_or_dict, dict):
        d = dict(name_or_dict)
        return Material(d.get("name", "custom"), float(d["E"]), float(d["nu"]), float(d["density"]),
                        float(d.get("expansion", 12.5e-6)))
    key = str(name_or_dict).strip().lower().replace(" ", "_")
    if key not in MATERIALS:
        raise BearingInputError("material", name_or_dict, "one of " + ", ".join(sorted(MATERIALS)))
    return MATERIALS[key]
