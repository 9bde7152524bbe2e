#!/usr/bin/env bash
# README command (1): set up the environment and run the main job, writing results and plots to out/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup_env.sh
export NUMBA_CACHE_DIR="${NUMBA_CACHE_DIR:-$PWD/.numba_cache}"
OUT="${1:-out}"
mkdir -p "$OUT"
echo "[1/3] transient run, seed 000 acceleration profile, 7218B, Fx = 1000 N, Fz = 3000 N (first run compiles the numba kernels)"
.venv/bin/bearing dynamics --bearing 7218B --profile seed000 --fx 1000 --fz 3000 --out "$OUT"
echo "[2/3] quasi-static solution, wan-105 at 15000 rpm, Fz = 889.84 N (seed 003 Table 2 case)"
.venv/bin/bearing quasistatic --bearing wan-105 --speed-rpm 15000 --fz 889.84 --json > "$OUT/quasistatic_wan-105.json"
.venv/bin/bearing quasistatic --bearing wan-105 --speed-rpm 15000 --fz 889.84 | head -8
echo "[3/3] quasi-static speed sweep, 7218B, Fz = 5000 N"
.venv/bin/bearing sweep --bearing 7218B --fz 5000 --speed-max-rpm 15000 --points 21 --out "$OUT"
echo "results in $OUT/"
