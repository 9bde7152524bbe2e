"""The bearing definition: geometry and presets (with sources), ISO catalogue designations, materials,
ring fits and ring growth (operating clearance). SI units."""
