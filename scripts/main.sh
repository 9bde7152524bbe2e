#!/usr/bin/env bash
# README command (1): set up the environment, build the bearing FMU and drive it with fmpy through seed 000's
# acceleration profile, writing results and plots to out/ (then two quasi-static results).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup_env.sh
export NUMBA_CACHE_DIR="${NUMBA_CACHE_DIR:-$PWD/.numba_cache}"
OUT="${1:-out}"
mkdir -p "$OUT"
echo "[1/5] building the FMU (dist/BearingFMU.fmu)"
.venv/bin/python build_fmu.py --dest dist
echo "[2/5] FMU via fmpy, OIL-LUBRICATED 7218B (ISO VG 32 at 40 degC, lubricated race traction, oil-lubricated pocket"
echo "      and land), oil supply: JET, 2.0 L/min (3.333e-5 m^3/s) at 40 degC -- the cavity oil content follows from the"
echo "      flow and the running speed (Parker's correlation, output oil_fraction_used): seed 000 profile (1000 rpm to"
echo "      0.5 s, 10,000 rpm/s to 10,000 rpm, held to 2 s), Fx = 1000 N, Fz = 3000 N;"
echo "      friction torque next to the SKF (2004) and Palmgren estimates, heat by source: $OUT/fmu_friction.png"
echo "      (the first run of this FMU compiles the numba kernels for this processor into its cache, about a minute
      on 2 cores; later runs load them. The standalone FMU ships them: python build_fmu.py --standalone)"
.venv/bin/bearing simulate --fmu dist/BearingFMU.fmu --profile seed000 --fx 1000 --fz 3000 --lubrication oil \
    --oil iso-vg32-mineral --oil-temperature-c 40 --param lubrication_method=jet --param oil_flow_rate=3.333e-5 \
    --param oil_inlet_temperature=313.15 --out "$OUT"
echo "[3/5] FMU via fmpy, seed 000's SOLID-LUBRICATED case: Kalker traction mu = 0.1, dry Coulomb cage mu = 0.1, same profile"
.venv/bin/bearing simulate --fmu dist/BearingFMU.fmu --profile seed000 --fx 1000 --fz 3000 --lubrication solid \
    --traction kalker --mu 0.1 --mu-cage 0.1 --out "$OUT/seed000_solid"
echo "[4/5] quasi-static solution, wan-105 at 15000 rpm, Fz = 889.84 N (seed 003 Table 2 case)"
.venv/bin/bearing quasistatic --bearing wan-105 --speed-rpm 15000 --fz 889.84 --json > "$OUT/quasistatic_wan-105.json"
.venv/bin/bearing quasistatic --bearing wan-105 --speed-rpm 15000 --fz 889.84 > "$OUT/quasistatic_wan-105.txt"
head -8 "$OUT/quasistatic_wan-105.txt"
echo "[5/5] quasi-static speed sweep, 7218B, Fz = 5000 N"
.venv/bin/bearing sweep --bearing 7218B --fz 5000 --speed-max-rpm 15000 --points 21 --out "$OUT"
echo "results in $OUT/: fmu_simulation.csv/.png/_summary.json and fmu_friction.png (oil), seed000_solid/ (solid-lubricated),"
echo "  quasistatic_wan-105.json/.txt, quasistatic_sweep_7218B.csv/.png"
