"""Build the bearing FMU (FMI 2.0 co-simulation) into dist/ of the source tree.

    python build_fmu.py [--dest dist]

A thin wrapper of bearing_cosim.fmu_build (also `bearing build-fmu` of the installed package); see that
module and docs/fmu.md.
"""
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
if str(HERE) not in sys.path:
    sys.path.insert(0, str(HERE))

from bearing_cosim.fmu_build import _build, build as _build_to, build_variant as _variant_to  # noqa: E402,F401
from bearing_cosim import fmu_build as _fb  # noqa: E402


def build(dest=HERE / "dist", reference=False, platforms=("linux64",)):
    return _build_to(dest, reference, platforms=platforms)


def build_variant(class_name, start_values, dest=HERE / "dist"):
    return _variant_to(class_name, start_values, dest)


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    if "--dest" not in argv and not any(a.startswith("--dest=") for a in argv):
        argv += ["--dest", str(HERE / "dist")]
    return _fb.main(argv)


if __name__ == "__main__":
    sys.exit(main())
