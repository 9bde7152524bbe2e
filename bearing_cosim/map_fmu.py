"""`bearing build-map-fmu MAP.nc`: the operating-map FMU all in C (BearingMapFMU), for Linux and Windows tools and
real-time targets. No Python runs in the master or beside it: the FMU is fmu_src/fmi2_common/ (the shared FMI 2.0
layer) and fmu_src/map/ (the 'map' fidelity level), compiled for each platform, with the map as a binary table
(bearing_cosim.map_table) in resources/ and the C sources in sources/.

The FMU has the inputs of BearingFMU and its outputs, with the same names, units and meaning as BearingFMU at
fidelity = map on the same map; its parameters are the map's build parameters, constants of this FMU (a master may
set them to the map's values; fmi2ExitInitializationMode refuses any other value, naming it).
"""
from __future__ import annotations

import hashlib
import math
import os
import shutil
import subprocess
import sys
import tempfile
import uuid
import zipfile
from pathlib import Path
from xml.dom.minidom import parseString
from xml.etree.ElementTree import Element, SubElement, tostring

FMU_SRC = Path(__file__).resolve().parent / "fmu_src"
C_SOURCES = (FMU_SRC / "fmi2_common" / "fmi2_common.c", FMU_SRC / "fmi2_common" / "fmi2_common.h",
             FMU_SRC / "native" / "fmi2_min.h", FMU_SRC / "map" / "model.c", FMU_SRC / "map" / "config.h")
MODEL_ID = "BearingMapFMU"
VR_OUTPUT = 1000
VR_PARAMETER = 5000
PLATFORMS = ("linux64", "win64")
CFLAGS = ("-std=c99", "-O2", "-Wall", "-Wextra", "-ffp-contract=off", "-fno-fast-math")
"""C flags of the shipped binaries: ISO C99, strict IEEE arithmetic (no contraction into fused multiply-adds), so
that the outputs equal the library's map level to the last bits."""


class BuildError(RuntimeError):
    """A requested platform cannot be built (the message names the missing compiler)."""


def _cross_compilers() -> dict:
    """{platform: (compiler command list, ext, extra flags)} of the compilers found on this machine."""
    out = {}
    cc = os.environ.get("CC", "gcc")
    if sys.platform.startswith("linux") and shutil.which(cc):
        out["linux64"] = ([cc], ".so", ["-shared", "-fPIC", "-fvisibility=hidden", "-lm"])
    for mingw in ("x86_64-w64-mingw32-gcc", "x86_64-w64-mingw32-gcc-win32"):
        if shutil.which(mingw):
            out["win64"] = ([mingw], ".dll", ["-shared", "-static-libgcc", "-lm"])
            break
    else:
        zig = _zig()
        if zig:
            out["win64"] = ([*zig, "cc", "-target", "x86_64-windows-gnu"], ".dll", ["-shared"])
    return out


def _zig():
    """The zig compiler of the `ziglang` package (python -m ziglang), or None."""
    try:
        import ziglang  # noqa: F401
    except ImportError:
        return None
    return [sys.executable, "-m", "ziglang"]


MISSING = {"linux64": "a C compiler for Linux (gcc: Debian package gcc)",
           "win64": "a win64 cross compiler (Debian package gcc-mingw-w64-x86-64-win32, or pip install ziglang)"}


def compile_binary(platform: str, out: Path, sources=None) -> Path:
    """Compile the C sources into the FMU binary of platform (linux64, win64) at out."""
    comp = _cross_compilers().get(platform)
    if comp is None:
        raise BuildError(f"--platforms {platform}: no compiler found; install {MISSING.get(platform, platform)}")
    cmd, _ext, extra = comp
    srcs = [str(s) for s in (sources or C_SOURCES) if str(s).endswith(".c")]
    incs = sorted({str(Path(s).parent) for s in (sources or C_SOURCES)})
    out.parent.mkdir(parents=True, exist_ok=True)
    args = [*cmd, *CFLAGS, *[f"-I{d}" for d in incs], "-o", str(out), *srcs, *extra]
    r = subprocess.run(args, capture_output=True, text=True)
    if r.returncode != 0:
        raise BuildError(f"compiling the {platform} binary failed ({' '.join(args)}):\n{r.stderr[-3000:]}")
    return out


def _units_xml(root, units):
    from .fmu_src.bearing_fmu import _DISPLAY_UNITS, _UNITS
    ue = SubElement(root, "UnitDefinitions")
    for u in sorted(units):
        e = SubElement(ue, "Unit", name=u)
        SubElement(e, "BaseUnit", {k: str(v) for k, v in _UNITS[u].items()})
        for du, factor, offset in _DISPLAY_UNITS.get(u, ()):
            SubElement(e, "DisplayUnit", {"name": du, "factor": repr(factor), **({"offset": repr(offset)} if offset
                                                                                else {})})


def _param_unit(name: str):
    """The unit of a Real parameter of the map FMU (as BearingFMU's), or None."""
    from .fmu_src.bearing_fmu import _GEOMETRY_PARAMS, _MODELICA_UNIT, _PARAMS
    for p in _PARAMS:
        if p[0] == name and p[1] is float:
            return _MODELICA_UNIT.get(p[3], p[3]) if p[3] not in (None, "1") else None
    for p in _GEOMETRY_PARAMS:
        if p[0] == name and p[1] is float:
            return p[2] if p[2] != "1" else None
    return None


def model_description(desc: dict, guid: str) -> Element:
    """modelDescription.xml of the map FMU (FMI 2.0 co-simulation) from the table's description."""
    from bearing_core.session.cosim_spec import INPUT_NAMES, INPUT_UNITS, INT_OUTPUT_SPEC, OUTPUT_SPEC
    from .fmu_src.bearing_fmu import (_DISPLAY_DEFAULT, _INPUT_DESC, _MODELICA_UNIT, _NOMINAL, _QUANTITY,
                                      INPUT_START, _PARAMS)
    from importlib.metadata import PackageNotFoundError, version
    try:
        ver = version("bearing-tribodynamics")
    except PackageNotFoundError:
        ver = "unknown"
    attrs = desc["attrs"]
    root = Element("fmiModelDescription", {
        "fmiVersion": "2.0", "modelName": MODEL_ID, "guid": guid,
        "description": (f"Angular-contact ball bearing, fidelity 'map' in C: the operating map of {attrs.get('bearing')} "
                        f"({desc['map_name']}, {attrs.get('level', '?')} level) interpolated multilinearly, never "
                        "extrapolated, with a first-order lag of the cage speed; isothermal, load-driven, outer ring "
                        "fixed. No Python."),
        "author": "bearing-tribodynamics", "version": ver, "license": "MIT",
        "generationTool": f"bearing-tribodynamics {ver} bearing build-map-fmu (pure C, libc and libm)",
        "variableNamingConvention": "structured", "numberOfEventIndicators": "0"})
    cs = SubElement(root, "CoSimulation", {
        "modelIdentifier": MODEL_ID, "needsExecutionTool": "false", "canHandleVariableCommunicationStepSize": "true",
        "canInterpolateInputs": "false", "maxOutputDerivativeOrder": "0", "canRunAsynchronuously": "false",
        "canBeInstantiatedOnlyOncePerProcess": "false", "canNotUseMemoryManagementFunctions": "true",
        "canGetAndSetFMUstate": "true", "canSerializeFMUstate": "true", "providesDirectionalDerivative": "true"})
    sf = SubElement(cs, "SourceFiles")
    for s in C_SOURCES:
        if s.suffix == ".c":
            SubElement(sf, "File", name=s.name)
    out_spec = list(OUTPUT_SPEC) + list(INT_OUTPUT_SPEC)
    units = {_MODELICA_UNIT.get(u, u) for u in INPUT_UNITS} | {_MODELICA_UNIT.get(u, u) for _n, u, _d in OUTPUT_SPEC}
    units |= {u for p in desc["parameters"] if (u := _param_unit(p[0]))}
    _units_xml(root, units)
    enums = {ename: (param, items) for param, (ename, items) in desc["enums"].items()}
    declared = {p[0] for p in desc["parameters"]} & set(enums)
    if declared:
        from .fmu_src.bearing_fmu import _ENUM_DESC
        td = SubElement(root, "TypeDefinitions")
        for ename in sorted(declared):
            param, items = enums[ename]
            st = SubElement(td, "SimpleType", name=f"{param}_choices")
            en = SubElement(st, "Enumeration")
            descs = _ENUM_DESC.get(param, ())
            for i, it in enumerate(items):
                SubElement(en, "Item", {"name": it, "value": str(i + 1),
                                        **({"description": descs[i]} if i < len(descs) else {})})
    lc = SubElement(root, "LogCategories")
    for cat, d in (("logError", "the reason of every fmi2Error"), ("logDiscard", "the reason of every rejected step "
                   "(fmi2Discard)"), ("logWarning", "warnings (the operating point enters a region where the map is "
                   "weak)"), ("logInfo", "information (only with logging on)")):
        SubElement(lc, "Category", name=cat, description=d)
    SubElement(root, "DefaultExperiment", startTime="0.0", stopTime="1.0", stepSize="0.001")
    mv = SubElement(root, "ModelVariables")
    ranges = {name: (lo, hi) for name, lo, hi, _u in desc["ranges"]}
    index = 0
    out_index = []
    pdesc = {p[0]: p[4] for p in _PARAMS}

    def real_attrs(unit, start=None, lo=None, hi=None, continuous=True):
        a = {}
        if unit:
            a["unit"] = unit
            if unit in _QUANTITY:
                a["quantity"] = _QUANTITY[unit]
            if unit in _DISPLAY_DEFAULT:
                a["displayUnit"] = _DISPLAY_DEFAULT[unit]
            if unit in _NOMINAL and continuous:
                a["nominal"] = repr(_NOMINAL[unit])
        if lo is not None:
            a["min"], a["max"] = repr(float(lo)), repr(float(hi))
        if start is not None:
            a["start"] = repr(float(start))
        return a

    for k, (name, unit) in enumerate(zip(INPUT_NAMES, INPUT_UNITS)):
        d = _INPUT_DESC[name]
        if name in ranges:
            lo, hi = ranges[name]
            d += f" (the map's range: {lo:.6g} to {hi:.6g} {_MODELICA_UNIT.get(unit, unit)})"
        sv = SubElement(mv, "ScalarVariable", name=name, valueReference=str(k), causality="input",
                        variability="continuous", description=d)
        SubElement(sv, "Real", real_attrs(_MODELICA_UNIT.get(unit, unit), INPUT_START.get(name, 0.0)))
        index += 1
    for k, (name, unit, d) in enumerate(out_spec):
        is_int = k >= len(OUTPUT_SPEC)
        sv = SubElement(mv, "ScalarVariable", name=name, valueReference=str(VR_OUTPUT + k), causality="output",
                        variability="discrete" if is_int else "continuous", initial="calculated", description=d)
        if is_int:
            SubElement(sv, "Integer")
        else:
            SubElement(sv, "Real", real_attrs(_MODELICA_UNIT.get(unit, unit)))
        index += 1
        out_index.append(index)
    for k, (name, typ, check, start, rep, detail, alts, d) in enumerate(desc["parameters"]):
        full = pdesc.get(name, d)
        sv = SubElement(mv, "ScalarVariable", name=name, valueReference=str(VR_PARAMETER + k), causality="parameter",
                        variability="fixed", initial="exact",
                        description=(d if name in ("fidelity", "map_file") or check in (4, 5, 6) else
                                     f"{full} -- fixed by the map: {rep}"))
        if typ is str:
            SubElement(sv, "String", start=str(start))
        elif typ is bool:
            SubElement(sv, "Boolean", start="true" if start else "false")
        elif typ is int and name in enums:
            SubElement(sv, "Enumeration", declaredType=f"{enums[name][0]}_choices", start=str(int(start)))
        elif typ is int:
            SubElement(sv, "Integer", start=str(int(start)))
        else:
            SubElement(sv, "Real", real_attrs(_param_unit(name), start, continuous=False))
        index += 1
    ms = SubElement(root, "ModelStructure")
    outs = SubElement(ms, "Outputs")
    # fmi2GetDirectionalDerivative (model.c): the reactions and the ring pose depend on the ring inputs, as in
    # BearingFMU; every other output is a function of the state at the communication point (no dependency)
    index = {sv.get("name"): str(i + 1) for i, sv in enumerate(mv)}
    ring_inputs = " ".join(index[n] for n in ("Fx", "Fy", "Fz", "Mx", "My", "dx", "dy", "dz", "tx", "ty"))
    ring_outputs = {index[n] for n in ("reaction_Fx", "reaction_Fy", "reaction_Fz", "reaction_Mx", "reaction_My",
                                       "ir_x", "ir_y", "ir_z", "ir_tx", "ir_ty")}
    for i in out_index:
        SubElement(outs, "Unknown", index=str(i), dependencies=ring_inputs if str(i) in ring_outputs else "")
    init = SubElement(ms, "InitialUnknowns")
    for i in out_index:
        SubElement(init, "Unknown", index=str(i))
    return root


def documentation_html(xml, desc) -> str:
    """documentation/index.html: what the level is and is not, the map's provenance, the variables."""
    from html import escape
    from .fmu_build import documentation_html as variables_html
    page = variables_html(xml)
    attrs = desc["attrs"]
    axes = "; ".join(f"{n}: {lo:g} to {hi:g} ({k} values)" for n, lo, hi, k in desc["axes"])
    prov = "".join(f"<tr><td>{escape(k)}</td><td>{escape(str(v))}</td></tr>" for k, v in sorted(attrs.items()))
    model = f"""<h2>The model</h2>
<p>The 'map' fidelity level of the bearing model, all in C (no Python, no process): the steady outputs of the
dynamic tribo-dynamic model over an operating map ({escape(desc['map_name'])}: {escape(axes)}; {desc['n_points']} grid
points) interpolated multilinearly and never extrapolated. Outputs proportional to the speed (speeds, powers) are
interpolated per unit speed. Without Fy and My axes, a radial load (Fx, Fy) is read at hypot(Fx, Fy) and the x-y
outputs are turned by its direction. The cage speed follows its steady value through a first-order lag with the
map's own time constant; torque and drive power add the power that accelerates balls and cage when the shaft speed
changes. An input outside the map, a non-finite input or a load the map does not vary makes fmi2DoStep return
fmi2Discard naming the input, the value and the map's range (the state is kept). Entering a region where the map
is weak (gross skidding, an unsteady cage at a neighbouring grid point) logs a warning (fmi2Warning).</p>
<p>What it is not: no displacement coupling (the loads are the inputs), no oil supply (the cavity oil content is
the map's oil_fraction), no thermal network (isothermal at the map's oil temperature), no per-ball outputs
(ball0_* and ir_ax hold 0). The parameters are the map's build parameters, constants of this FMU: a master may set
them to these values; fmi2ExitInitializationMode refuses any other value, naming it. The same model runs in the
Python library and in BearingFMU at fidelity = map (docs/fidelity.md); this FMU gives the same outputs.</p>
<h2>The operating map</h2><table>{prov}</table>"""
    i = page.index("<h2>The model</h2>")
    k = page.index("<h2>Variables</h2>")
    page = page[:i] + model + page[k:]
    return page[:page.index("<p>OSP model description")] + "</body></html>\n"


def build_map_fmu(map_file, dest="dist", platforms=None) -> Path:
    """Build dest/BearingMapFMU.fmu from the operating map (NetCDF of bearing build-map). platforms: names of
    PLATFORMS to build (None: every platform whose compiler is found); a requested platform without its compiler
    raises BuildError naming it."""
    from bearing_core.errors import BearingInputError
    from .map_table import TABLE_NAME, build_table, with_guid
    found = _cross_compilers()
    if platforms is None:
        platforms = [p for p in PLATFORMS if p in found]
        if not platforms:
            raise BuildError("no C compiler found; install " + " or ".join(MISSING.values()))
    platforms = list(dict.fromkeys(platforms))
    if not platforms:
        raise BearingInputError("--platforms", "", "one or more of " + ", ".join(PLATFORMS))
    for p in platforms:
        if p not in PLATFORMS:
            raise BearingInputError("--platforms", p, ", ".join(PLATFORMS))
        if p not in found:
            raise BuildError(f"--platforms {p}: no compiler found; install {MISSING[p]}")
    table0, desc = build_table(map_file)
    code = b"".join(s.read_bytes() for s in C_SOURCES)
    digest = hashlib.sha256(table0 + code).hexdigest()
    guid = "{" + str(uuid.UUID(digest[:32])) + "}"
    table = with_guid(table0, guid)
    xml = model_description(desc, guid)
    md = parseString(tostring(xml, "UTF-8")).toprettyxml(encoding="UTF-8")
    dest = Path(dest)
    dest.mkdir(parents=True, exist_ok=True)
    fmu = dest / f"{MODEL_ID}.fmu"
    with tempfile.TemporaryDirectory(prefix="bearing_map_fmu_") as td:
        stage = Path(td)
        members = {"modelDescription.xml": (md, 0o644), f"resources/{TABLE_NAME}": (table, 0o644)}
        for s in C_SOURCES:
            members[f"sources/{s.name}"] = (s.read_bytes(), 0o644)
        for p in platforms:
            ext = found[p][1]
            b = compile_binary(p, stage / p / f"{MODEL_ID}{ext}")
            members[f"binaries/{p}/{MODEL_ID}{ext}"] = (b.read_bytes(), 0o755)
        members["documentation/index.html"] = (documentation_html(xml, desc).encode("utf-8"), 0o644)
        tmp = fmu.with_suffix(".fmu.tmp")
        with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
            for name, (data, mode) in members.items():
                zi = zipfile.ZipInfo(name, date_time=(2020, 1, 1, 0, 0, 0))
                zi.external_attr = (0o100000 | mode) << 16
                zi.compress_type = zipfile.ZIP_DEFLATED
                z.writestr(zi, data)
        os.replace(tmp, fmu)
    return fmu


def main(argv=None) -> int:
    import argparse
    ap = argparse.ArgumentParser(prog="bearing build-map-fmu", description=__doc__.splitlines()[0])
    add_arguments(ap)
    a = ap.parse_args(argv)
    return run(a)


def add_arguments(ap):
    ap.add_argument("map", help="operating map (NetCDF of bearing build-map)")
    ap.add_argument("--dest", default="dist", help="output folder (default dist/)")
    ap.add_argument("--platforms", default=None,
                    help="comma-separated: linux64, win64 (default: every platform whose compiler is found)")


def run(a) -> int:
    plats = None if a.platforms is None else [p.strip() for p in a.platforms.split(",") if p.strip()]
    fmu = build_map_fmu(a.map, a.dest, plats)
    with zipfile.ZipFile(fmu) as z:
        bins = sorted(n.split("/")[1] for n in z.namelist() if n.startswith("binaries/"))
    print(f"built {fmu} ({fmu.stat().st_size / 1024:.0f} KiB; binaries: {', '.join(bins)})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
