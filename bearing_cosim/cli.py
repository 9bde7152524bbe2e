"""The `bearing` console script: bearing_core's subcommands plus `simulate` (drive the FMU with fmpy)."""
from __future__ import annotations

import argparse
import json
import re
import sys
from pathlib import Path

from bearing_core import cli as core_cli
# argparse takes "-1e-3" for an option name (its negative-number pattern has no exponent), so
# "--step -1e-3" failed with "expected one argument"; numbers in any float notation are values.
_NEGATIVE_NUMBER = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|nan)$", re.IGNORECASE)


def _package_version() -> str:
    from importlib.metadata import PackageNotFoundError, version
    try:
        return version("bearing-tribodynamics")
    except PackageNotFoundError:
        return "unknown (not installed)"


def _accept_negative_numbers(parser: argparse.ArgumentParser):
    parser._negative_number_matcher = _NEGATIVE_NUMBER
    for act in parser._actions:
        if isinstance(act, argparse._SubParsersAction):
            for sp in act.choices.values():
                _accept_negative_numbers(sp)


def build_parser():
    p = core_cli.build_parser()
    p.add_argument("--version", action="version", version=f"bearing-tribodynamics {_package_version()}")
    sub = next(a for a in p._actions if a.dest == "cmd")
    from bearing_validation.cli import add_parser as add_validate
    add_validate(sub)
    s = sub.add_parser("simulate", help="drive the bearing FMU with fmpy through a speed profile "
                                        "(CSV time_s, speed_rpm [, Fx_N, Fy_N, Fz_N, Mx_Nm, My_Nm]) or 'seed000'")
    s.add_argument("--fmu", default="dist/BearingFMU.fmu", help="FMU file (bearing build-fmu builds it)")
    s.add_argument("--profile", default="seed000")
    for nm, unit in (("fx", "N"), ("fy", "N"), ("fz", "N"), ("mx", "N m"), ("my", "N m")):
        s.add_argument(f"--{nm}", type=core_cli._finite(f"--{nm}"), default=0.0,
                       help=f"load held on the inner ring [{unit}] (unless the profile has the column)")
    s.add_argument("--step", type=core_cli._finite("--step"), default=1e-3, help="communication step [s]")
    s.add_argument("--bearing", default="7218B")
    s.add_argument("--traction", choices=("lubricated", "coulomb", "kalker"), default="lubricated")
    s.add_argument("--mu", type=core_cli._finite("--mu"), default=0.1)
    s.add_argument("--mu-cage", type=core_cli._finite("--mu-cage"), default=0.1)
    s.add_argument("--stop-time", type=core_cli._finite("--stop-time"), default=None,
                   help="end of the run [s] (default: end of the profile; past it the profile's last values are held)")
    s.add_argument("--param", action="append", default=[], metavar="NAME=VALUE",
                   help="set any FMU parameter by its modelDescription name, typed from it (repeatable), "
                        "e.g. --param integrator=rk4 --param thermal=true")
    s.add_argument("--lubrication", choices=("auto", "oil", "solid", "dry"), default="auto",
                   help="lubrication regime (FMU parameter lubrication): oil | solid | dry | auto (from --traction)")
    s.add_argument("--oil", default="", help="oil name for viscosity (bearing_core.lubrication.lubricants; default: the "
                                             "traction curve's oil)")
    s.add_argument("--oil-temperature-c", type=core_cli._finite("--oil-temperature-c"), default=40.0,
                   help="oil temperature [degC] (thermal network off)")
    s.add_argument("--out", default="out")
    s.set_defaults(func=cmd_simulate)
    b = sub.add_parser("build-fmu", help="build the bearing FMU (FMI 2.0 co-simulation) from the sources shipped "
                                         "in this package (needs pythonfmu and a C compiler: pip install '.[fmu]')")
    b.add_argument("--dest", default="dist", help="output folder (default dist/)")
    b.add_argument("--with-reference", action="store_true",
                   help="also run the default experiment and ship the FMI cross-check reference files and a plot "
                        "(documentation/; takes a few seconds, about a minute with an empty numba cache)")
    b.add_argument("--precompile", action="store_true",
                   help="ship the compiled kernels (numba cache for the generic x86-64 target; adds a few minutes "
                        "to the build): no compilation at first use with the build's Python and numba versions")
    b.add_argument("--standalone", action="store_true",
                   help="bundle the runtime (this Python's libpython, a pruned standard library, numpy, scipy, "
                        "numba, llvmlite) and the precompiled kernels: the FMU needs no installed Python")
    b.add_argument("--map", default=None, metavar="FILE",
                   help="embed this operating map (bearing build-map) in resources/: the FMU uses it at fidelity "
                        "'map' when the parameter map_file is empty")
    b.add_argument("--platforms", default="linux64",
                   help="comma-separated binaries: linux64 (default), win64 (cross-compiled with mingw-w64 or zig cc; "
                        "its instances run the model on a model server, bearing serve; docs/fmu.md)")
    b.set_defaults(func=cmd_build_fmu)
    mf = sub.add_parser("build-map-fmu", help="build the operating-map FMU all in C (dist/BearingMapFMU.fmu): the "
                                            "'map' fidelity level of MAP.nc with no Python, binaries for linux64 and "
                                            "win64 (cross-compiled) and its C sources")
    from .map_fmu import add_arguments as _map_fmu_args
    _map_fmu_args(mf)
    mf.set_defaults(func=cmd_build_map_fmu)
    v = sub.add_parser("validate-fmu", help="check an FMU with fmpy's validate_fmu; prints every problem, exit "
                                            "status 1 if there is any")
    v.add_argument("fmu", help="FMU file")
    v.set_defaults(func=cmd_validate_fmu)
    from .fmu_server import add_arguments as add_serve
    sv = sub.add_parser("serve", help="run the model server: FMU instances whose master runs elsewhere (the win64 "
                                      "FMU, or BEARING_FMU_SERVER set) get their model process here (docs/fmu.md)")
    add_serve(sv)
    sv.set_defaults(func=cmd_serve)
    d = sub.add_parser("docs", help="serve the manual (MkDocs site of docs/ in the source tree) on a local address: "
                                    "python -m mkdocs serve")
    d.add_argument("--dev-addr", default="127.0.0.1:8000", help="IP:PORT to serve on (default 127.0.0.1:8000)")
    d.set_defaults(func=cmd_docs)
    _accept_negative_numbers(p)
    return p


def fmu_parameters(fmu: str, pairs) -> dict:
    """Start values from NAME=VALUE strings, typed by the FMU's modelDescription (Real, Integer, Boolean,
    String, Enumeration by item name or number); unknown names and values that do not parse are errors."""
    from fmpy import read_model_description

    md = read_model_description(fmu)
    settable = {v.name: v for v in md.modelVariables if v.causality in ("parameter", "input")
                or v.variability == "tunable"}
    out = {}
    for pair in pairs:
        if "=" not in pair:
            raise core_cli._BadArg(f"--param {pair!r} is invalid; allowed: NAME=VALUE")
        name, value = (x.strip() for x in pair.split("=", 1))
        if name not in settable:
            raise core_cli._BadArg(f"--param {name} is not a parameter of {Path(fmu).name}; allowed: "
                                   + ", ".join(sorted(settable)))
        v = settable[name]
        try:
            if v.type == "Real":
                out[name] = float(value)
            elif v.type == "Integer":
                out[name] = int(value)
            elif v.type == "Boolean":
                if value.lower() not in ("true", "false", "1", "0"):
                    raise ValueError(value)
                out[name] = value.lower() in ("true", "1")
            elif v.type == "Enumeration":
                items = {it.name: it.value for it in (v.declaredType.items if v.declaredType else [])}
                out[name] = int(items[value]) if value in items else int(value)
            else:
                out[name] = value
        except (ValueError, KeyError):
            raise core_cli._BadArg(f"--param {name} = {value!r} is invalid; allowed: a {v.type} value") from None
    return out


def cmd_build_fmu(a) -> int:
    from .fmu_build import build
    if a.map is not None and not Path(a.map).is_file():
        raise core_cli._BadArg(f"--map = {a.map!r} is not a file")
    from .fmu_build import parse_platforms
    try:
        platforms = parse_platforms(a.platforms)
    except ValueError as e:
        raise core_cli._BadArg(str(e)) from None
    fmu = build(a.dest, reference=a.with_reference, precompile=a.precompile, standalone=a.standalone, map_file=a.map,
                platforms=platforms)
    print(f"built {fmu} ({fmu.stat().st_size / 1024:.0f} KiB)")
    return 0


def cmd_validate_fmu(a) -> int:
    if not Path(a.fmu).is_file():
        raise core_cli._BadArg(f"FMU = {a.fmu!r} is not a file")
    from fmpy.validation import validate_fmu
    try:
        problems = list(validate_fmu(a.fmu))
    except Exception as e:   # not an FMU archive, unreadable modelDescription.xml, ...
        problems = [f"{type(e).__name__}: {e}"]
    for msg in problems:
        print(msg)
    print(f"{a.fmu}: {len(problems)} problem(s)" if problems else f"{a.fmu}: valid (fmpy validate_fmu: no messages)")
    return 1 if problems else 0


def cmd_serve(a) -> int:
    from .fmu_server import run
    return run(a)


def cmd_build_map_fmu(a) -> int:
    from .map_fmu import BuildError, run
    if not Path(a.map).is_file():
        raise core_cli._BadArg(f"MAP = {a.map!r} is not a file; build an operating map with: bearing build-map")
    try:
        return run(a)
    except BuildError as e:
        raise core_cli._BadArg(str(e))


def cmd_docs(a) -> int:
    import subprocess
    root = Path(__file__).resolve().parent.parent
    if not (root / "mkdocs.yml").is_file():
        raise core_cli._BadArg(f"no mkdocs.yml in {root}: the manual is served from a source tree (git clone)")
    return subprocess.call([sys.executable, "-m", "mkdocs", "serve", "--dev-addr", a.dev_addr], cwd=root)


def cmd_simulate(a) -> int:
    from .simulate import simulate
    if not Path(a.fmu).is_file():
        raise core_cli._BadArg(f"--fmu = {a.fmu!r} is not a file; build it with: bearing build-fmu")
    if not (1e-5 <= a.step <= 0.1):
        raise core_cli._BadArg(f"--step = {a.step} is invalid; allowed: 1e-5 <= step <= 0.1 s")
    if not (0.0 <= a.mu <= 1.0) or not (0.0 <= a.mu_cage <= 1.0):
        raise core_cli._BadArg(f"--mu = {a.mu}, --mu-cage = {a.mu_cage}: allowed 0 <= value <= 1")
    if a.stop_time is not None and a.stop_time <= 0:
        raise core_cli._BadArg(f"--stop-time = {a.stop_time} is invalid; allowed: > 0 s")
    params = {"bearing": a.bearing, "traction_model": a.traction, "friction_coefficient": a.mu,
              "cage_friction_coefficient": a.mu_cage, "lubrication": a.lubrication, "oil": a.oil,
              "oil_temperature": a.oil_temperature_c + 273.15}
    params.update(fmu_parameters(a.fmu, a.param))
    s = simulate(a.fmu, a.profile, (a.fx, a.fy, a.fz, a.mx, a.my), a.step, params, a.out, stop_time=a.stop_time)
    print(f"wrote {s['csv']}, {s['plot']} and {Path(a.out) / 'fmu_simulation_summary.json'}")
    print(json.dumps({k: v for k, v in s.items() if k.startswith("final") or k in ("simulated_s", "wall_s")}))
    return 0


def main(argv=None) -> int:
    from bearing_core.errors import BearingInputError, ConvergenceError
    a = build_parser().parse_args(argv)
    try:
        return a.func(a)
    except (BearingInputError, core_cli._BadArg) as e:
        sys.stderr.write(f"bearing {a.cmd}: error: {e}\n")
        return 2
    except ConvergenceError as e:
        sys.stderr.write(f"bearing {a.cmd}: solver failed: {e}\n")
        return 3
    except Exception as e:  # an FMU error status surfaces here as fmpy's exception
        sys.stderr.write(f"bearing {a.cmd}: simulation failed: {type(e).__name__}: {e}\n")
        return 1


def console_main() -> None:
    """Console-script entry. The process exits normally after an FMU run: the FMU's own native layer
    leaves the interpreter and the heap intact at unload (docs/fmu.md)."""
    import signal
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)   # `bearing ... | head` ends quietly
    sys.exit(main())


if __name__ == "__main__":
    console_main()
