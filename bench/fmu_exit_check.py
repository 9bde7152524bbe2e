"""Count host processes that abort at exit after running the bearing FMU (docs/fmu.md).

    python bench/fmu_exit_check.py [--runs 50] [--fmu dist/BearingFMU.fmu]

Each run is a fresh Python process that loads the FMU with fmpy, simulates 10 ms and exits normally
(running the C exit handlers). Prints the exit-status histogram, e.g. {"0": 50}.
"""
import argparse
import collections
import json
import math
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=50)
    ap.add_argument("--fmu", default=str(HERE.parent / "dist" / "BearingFMU.fmu"))
    a = ap.parse_args()
    inp = {"shaft_speed": 1000 * math.pi / 30, "Fx": 1000.0, "Fz": 3000.0}
    spec = {"fmu": a.fmu, "params": {}, "start_inputs": inp, "steps": [[1e-3, inp]] * 10, "outputs": ["cage_speed"]}
    with tempfile.TemporaryDirectory() as td:
        p = Path(td) / "spec.json"
        p.write_text(json.dumps(spec))
        counts = collections.Counter()
        for _ in range(a.runs):
            r = subprocess.run([sys.executable, str(HERE.parent / "tests" / "fmu_driver.py"), str(p), "--normal-exit"],
                               capture_output=True, text=True)
            counts[str(r.returncode)] += 1
    print(json.dumps(dict(counts)))


if __name__ == "__main__":
    main()
