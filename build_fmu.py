"""Build the bearing FMU (FMI 2.0 co-simulation, pythonfmu) into dist/.

    python build_fmu.py [--dest dist]

The FMU bundles fmu_src/bearing_fmu.py and a copy of bearing_core (without caches). It runs with the
Python interpreter of the host process or of the system, which needs numpy, scipy, numba and pythonfmu.
"""
from __future__ import annotations

import argparse
import shutil
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent


def build(dest: Path | str = HERE / "dist") -> Path:
    from pythonfmu.builder import FmuBuilder

    dest = Path(dest)
    dest.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="bearing_fmu_build_") as td:
        stage = Path(td)
        shutil.copytree(HERE / "bearing_core", stage / "bearing_core",
                        ignore=shutil.ignore_patterns("__pycache__", "*.nbi", "*.nbc", "*.pyc"))
        script = stage / "bearing_fmu.py"
        shutil.copy2(HERE / "fmu_src" / "bearing_fmu.py", script)
        fmu = FmuBuilder.build_FMU(script, dest=dest, project_files=[stage / "bearing_core"],
                                   canGetAndSetFMUstate=True)
    return Path(fmu)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dest", default=str(HERE / "dist"), help="output folder (default dist/)")
    a = ap.parse_args(argv)
    fmu = build(a.dest)
    print(f"built {fmu} ({fmu.stat().st_size / 1024:.0f} KiB)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
