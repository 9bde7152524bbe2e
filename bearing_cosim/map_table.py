"""The operating-map table of the pure-C map FMU (BearingMapFMU): an operating map of ``bearing build-map``
(NetCDF) turned into the little-endian binary table that fmu_src/map/model.c reads at fmi2Instantiate.

The table holds what bearing_core.session.fidelity.MapLevel and SteadySession hand to the one-call step kernel
(map_kernels.map_step): axes, values per unit speed where speed-scaled, validity flags, the query of each axis,
the output layout (source of each FMU output, x-y pairs turned with the radial load, the cage-lag indices),
the constants of the outputs, and the map's build parameters, which are constants of the FMU. It is written
from a MapLevel built by the library itself, so the C model evaluates exactly what the Python level does.

Format version 1 (every integer little-endian; f64 IEEE 754 little-endian; str = u32 length + UTF-8 bytes)::

    header (64 bytes)
      0  char[8]  magic "BRGMAPTB"
      8  u32      format version (1)
     12  u32      header size (64)
     16  u64      file size [bytes]
     24  u32      CRC-32 (IEEE 802.3, as zlib.crc32) of bytes [64, file size)
     28  u32      0x01020304 (byte-order mark)
     32  char[32] zero
    body, in this order
      str guid                     the FMU's GUID (fmi2Instantiate compares it)
      str level, bearing, map_name attributes of the map, for messages
      str provenance               JSON: the map's attributes (command, created, code version, grid...)
      u32 n_in, n_out_real, n_out_int, n_axes, n_vals, n_points
      str input names[n_in]; f64 input start values[n_in]
      i32 i_speed, i_fx, i_fy, i_oring, rotate
      u32 n_zero, i32 zero_in[n_zero]          inputs the map does not vary (must be 0)
      per axis: str name, i32 kind (0 parameter, 1 shaft speed [rpm], 2 radial load / Fx, 3 input),
                i32 input index (-1), f64 fixed value, f64 lo, f64 hi, f64 tol, u32 n, f64 values[n]
      i32 i_axis_oil                           the oil temperature axis (-1: none; kind 0, fed by oil_temperature)
      f64 rpm                                  rad/s per rpm
      str value names[n_vals]; i32 speed_scaled[n_vals]; i32 i_tau
      f64 values[n_points * n_vals] (C order over the axes, then the value); i32 flags[n_points]
      str flag texts[2]                        the warning's words for flag 1 (gross skid) and 2 (unsteady cage)
      u32 has_k; i32 i_k; f64 kvals[n_points * 25] if has_k   the stiffness K = d(load)/d(pose) at each grid point
                                               (row-major 5 x 5) and the output index of stiffness[1,1]
      str stiffness_missing                    the warning of a map without stiffness variables ('' if it has them;
                                               the map's file written as {map})
      str output names[n_out_real + n_out_int]; i32 src[n_out]
      u32 n_rot; i32 rot[2 n_rot]; u32 n_ib; i32 ib[n_ib]
      f64 temps[7], inertia [kg m^2], csr_min [rad/s], skid_tol, skid_min [rad/s]
      i32 i_oil; f64 oil_fraction
      u32 n_par; per parameter: str name, i32 type (0 Real, 1 Integer, 2 Boolean, 3 String), i32 check
                (0 the map's build value, 1 a value the level requires, 2 fidelity, 3 map_file, 4 oil temperature
                axis range, 5 none, 6 the Enumeration item of a checked String), f64 start, str start, str repr of the required value, str detail, u32 n_alt, str alt[]
      i32 i_rate                               the fatigue damage rate's index in the values (fidelity.MAP_FATIGUE_RATE,
                                               speed-scaled; -1: the map has none, the fatigue outputs hold 0)
      i32 i_life, i_damage                     the output indices of life_L10r_h and fatigue_damage
      f64 life_cap [h]                         the life reported where it is infinite (cosim_spec.LIFE_CAP_H)
      str fatigue_missing                      the warning of a map without the damage rate ('' if it has it)
      u32 end mark 0x454e4421 ("!DNE")
"""
from __future__ import annotations

import json
import math
import struct
import zlib
from pathlib import Path

import numpy as np

MAGIC = b"BRGMAPTB"
VERSION = 1
HEADER = 64
END_MARK = 0x454E4421
TABLE_NAME = "map_table.bin"
"""The table's file name in the FMU's resources/."""

PARAM_TYPES = {float: 0, int: 1, bool: 2, str: 3}
CHECK_BUILT, CHECK_FIXED, CHECK_FIDELITY, CHECK_MAP_FILE, CHECK_OIL_AXIS, CHECK_NONE, CHECK_ENUM = range(7)
"""How fmi2ExitInitializationMode checks a parameter: the map's build value, a value the level requires, 'map',
an empty map_file, within the map's oil temperature axis, not at all (a parameter of BearingFMU that has no
effect at the map level), the item of a checked String parameter (its Enumeration twin)."""


class _W:
    def __init__(self):
        self.parts = []

    def u32(self, *v):
        self.parts.append(struct.pack(f"<{len(v)}I", *v))

    def i32(self, *v):
        self.parts.append(struct.pack(f"<{len(v)}i", *[int(x) for x in v]))

    def f64(self, *v):
        self.parts.append(struct.pack(f"<{len(v)}d", *[float(x) for x in v]))

    def i32a(self, a):
        self.parts.append(np.asarray(a, dtype="<i4").tobytes())

    def f64a(self, a):
        self.parts.append(np.asarray(a, dtype="<f8").tobytes())

    def str(self, s):
        b = str(s).encode("utf-8")
        self.u32(len(b))
        self.parts.append(b)

    def bytes(self) -> bytes:
        return b"".join(self.parts)


def map_session(map_path):
    """A CoSimSession at fidelity 'map' on the map with its own build parameters (the session the table mirrors),
    and the build parameters {name: value}."""
    from bearing_core.session.cosim import CoSimParameters, CoSimSession
    from bearing_core.session.fidelity import MAP_PARAMETERS, read_map
    m = read_map(map_path)
    try:
        built = json.loads(m["attrs"].get("parameters", "{}"))
    except json.JSONDecodeError:
        built = {}
    kw = {k: built[k] for k in MAP_PARAMETERS if k in built}
    s = CoSimSession(CoSimParameters(**kw, fidelity="map", map_file=str(map_path)))
    return s, built, m


def _py_type(v):
    return bool if isinstance(v, bool) else (int if isinstance(v, int) else (float if isinstance(v, float) else str))


def pinned_parameters(built: dict, axis_names) -> list:
    """The FMU's parameters: (name, type, check, start, repr of the required value, detail, alternatives,
    description). Their values are the map's: a master may set them (scripts written for BearingFMU at fidelity
    'map' set them), and fmi2ExitInitializationMode refuses any other value, as MapLevel does."""
    from bearing_core.session.cosim import CoSimParameters
    from bearing_core.session.fidelity import FIXED_PARAMETERS, MAP_PARAMETERS, fixed_parameter_reason
    defaults = CoSimParameters()
    out = [("fidelity", str, CHECK_FIDELITY, "map", "'map'", "this FMU is the pure-C 'map' level; BearingFMU "
            "has the other levels", (), "model fidelity: map only (the operating map embedded in this FMU)"),
           ("map_file", str, CHECK_MAP_FILE, "", "''", "this FMU embeds its map (resources/map_table.bin); build "
            "another one with bearing build-map-fmu MAP", (), "empty: the map embedded in this FMU")]
    for k in MAP_PARAMETERS:
        b = built[k]
        typ = type(getattr(defaults, k))
        if k == "oil_temperature" and "oil_temperature_C" in axis_names:
            out.append((k, float, CHECK_OIL_AXIS, float(b), "", "", (), "oil temperature [K] (isothermal), "
                        "within the map's oil temperature axis"))
            continue
        # MapLevel._check_parameters: lubrication 'auto' (exact) stands for the regime the map resolved it to
        alts = ("auto",) if k == "lubrication" and built.get("lubrication_auto", b) == b else ()
        start = typ(b) if typ is not str else str(b)
        out.append((k, typ, CHECK_BUILT, start, repr(b), "", alts, f"{k}: the value the map was built for "
                    "(a constant of this FMU)"))
    for k, want in FIXED_PARAMETERS.items():
        typ = type(getattr(defaults, k))
        what = fixed_parameter_reason(k)
        out.append((k, typ, CHECK_FIXED, want, repr(want), what, (), f"{k}: {want!r} at the map level"))
    # BearingFMU's other parameters: accepted, no effect at the map level (as in BearingFMU at fidelity = map)
    from .fmu_src.bearing_fmu import _GEOMETRY_PARAMS, _PARAMS
    have = {p[0] for p in out}
    for name, typ, start, _unit, desc, _rng in _PARAMS:
        if name not in have:
            out.append((name, typ, CHECK_NONE, start, repr(start), "", (), f"{desc} (no effect at the map level)"))
    for name, typ, _unit, desc, _rng in _GEOMETRY_PARAMS:
        if name not in have:
            out.append((name, typ, CHECK_NONE, typ(0), repr(typ(0)), "", (), f"{desc} (no effect at the map level)"))
    # the Enumeration twins of the choice parameters: the item of the map's value
    values = {p[0]: p for p in out}
    for param, (ename, items) in enum_twins().items():
        v = values[param][3]
        if v not in items:
            continue                 # a bearing file or designation: no preset item
        checked = values[param][2] != CHECK_NONE
        out.append((ename, int, CHECK_ENUM if checked else CHECK_NONE, items.index(v) + 1,
                    f"{items.index(v) + 1} ({v})", f"the item of {param}, {v!r}", (),
                    f"Enumeration of the String parameter {param}"))
    return out


def enum_twins() -> dict:
    """{String parameter: (its Enumeration twin's name, items)} of BearingFMU (bearing_fmu.ENUMERATIONS)."""
    from bearing_core.session.fidelity import FIDELITIES
    from .fmu_src.bearing_fmu import ENUM_NAME, ENUMERATIONS, bearing_preset_items
    out = {}
    for param, items in ENUMERATIONS.items():
        if items is None:
            items = tuple(FIDELITIES) if param == "fidelity" else tuple(bearing_preset_items())
        out[param] = (ENUM_NAME.get(param, f"{param}_choice"), tuple(items))
    return out


def build_table(map_path, guid: str = "") -> tuple[bytes, dict]:
    """The binary table (bytes, format above) of the operating map, and its description {axes, outputs,
    parameters, inputs, attrs} for the model description."""
    from bearing_core.session.cosim_spec import INPUT_NAMES, INT_OUTPUT_NAMES, OUTPUT_NAMES
    from bearing_core.session.fidelity import FLAG_CAGE_UNSTEADY, FLAG_GROSS_SKID
    s, built, m = map_session(map_path)
    st = s.steady
    lv = st.level
    (i_speed, i_fx, i_fy, i_oring, zero_in, rotate, rpm, qkind, qidx, qval, qlo, qhi, qtol,
     axes_flat, ptr, strides, values, speed_scaled, flags, *_work) = lv.step_args
    w = _W()
    attrs = m["attrs"]
    w.str(guid)
    w.str(attrs.get("level", "?"))
    w.str(attrs.get("bearing", "?"))
    w.str(Path(map_path).name)
    prov = {k: (attrs[k].item() if hasattr(attrs[k], "item") else attrs[k]) for k in sorted(attrs)}
    w.str(json.dumps(prov))
    n_out_real, n_out_int = len(OUTPUT_NAMES), len(INT_OUTPUT_NAMES)
    n_axes = len(lv.axis_names)
    n_vals = len(lv.names)
    n_points = int(values.shape[0])
    w.u32(len(INPUT_NAMES), n_out_real, n_out_int, n_axes, n_vals, n_points)
    for nm in INPUT_NAMES:
        w.str(nm)
    from .fmu_src.bearing_fmu import INPUT_START     # BearingFMU's start values: the same first point
    w.f64a([float(INPUT_START.get(nm, 0.0)) for nm in INPUT_NAMES])
    w.i32(i_speed, i_fx, i_fy, i_oring, 1 if rotate else 0)
    w.u32(len(zero_in))
    w.i32a(zero_in)
    i_axis_oil = -1
    for d, name in enumerate(lv.axis_names):
        a = axes_flat[ptr[d]:ptr[d + 1]]
        w.str(name)
        w.i32(qkind[d], qidx[d])
        w.f64(qval[d], qlo[d], qhi[d], qtol[d])
        w.u32(len(a))
        w.f64a(a)
        if name == "oil_temperature_C":
            i_axis_oil = d
    w.i32(i_axis_oil)
    w.f64(rpm)
    for nm in lv.names:
        w.str(nm)
    w.i32a(speed_scaled)
    w.i32(lv.i_tau)
    w.f64a(values.ravel())
    w.i32a(flags)
    w.str(lv.FLAG_TEXT[FLAG_GROSS_SKID])
    w.str(lv.FLAG_TEXT[FLAG_CAGE_UNSTEADY])
    # the stiffness outputs (map_kernels.map_stiffness): the map's stiffness variables, or the warning of a map
    # without them (the outputs then hold 0)
    if getattr(lv, "stiffness_into", None) is not None:
        from bearing_core.session.cosim_spec import STIFFNESS_NAMES
        w.u32(1)
        w.i32((OUTPUT_NAMES + INT_OUTPUT_NAMES).index(STIFFNESS_NAMES[0]))
        w.f64a(np.asarray(lv.kvalues).ravel())
    else:
        w.u32(0)
        w.i32(-1)
    w.str(getattr(lv, "stiffness_missing", "").replace(lv.path, "{map}"))   # the C FMU names its own table
    for nm in OUTPUT_NAMES + INT_OUTPUT_NAMES:
        w.str(nm)
    w.i32a(st._src)
    w.u32(st._rot.shape[0])
    w.i32a(st._rot.ravel())
    w.u32(len(st._ib))
    w.i32a(st._ib)
    c0, c1, c2 = st._consts
    w.f64a(st._temps)
    w.f64(lv.inertia, c0, c1, c2)
    w.i32(st._i_oil)
    w.f64(st._oil)
    params = pinned_parameters(built, lv.axis_names)
    w.u32(len(params))
    for name, typ, check, start, rep, detail, alts, _desc in params:
        w.str(name)
        w.i32(PARAM_TYPES[typ], check)
        w.f64(float(start) if typ is not str else 0.0)
        w.str(start if typ is str else "")
        w.str(rep)
        w.str(detail)
        w.u32(len(alts))
        for a in alts:
            w.str(a)
    # the fatigue outputs (SteadySession._life_into)
    from bearing_core.session.cosim_spec import LIFE_CAP_H
    w.i32(st._i_rate, st._i_life, st._i_damage)
    w.f64(LIFE_CAP_H)
    w.str(getattr(lv, "fatigue_missing", "").replace(lv.path, "{map}"))
    w.u32(END_MARK)
    body = w.bytes()
    desc = {"axes": [(nm, float(qlo[d]), float(qhi[d]), int(ptr[d + 1] - ptr[d]))
                     for d, nm in enumerate(lv.axis_names)],
            "ranges": lv.ranges(), "parameters": params, "enums": enum_twins(), "attrs": prov, "built": built, "rotate": bool(rotate),
            "n_points": n_points, "map_name": Path(map_path).name}
    return _framed(body), desc


def _framed(body: bytes) -> bytes:
    """The table: its header (size, CRC-32 of the body) and the body."""
    header = MAGIC + struct.pack("<IIQII", VERSION, HEADER, HEADER + len(body), zlib.crc32(body) & 0xFFFFFFFF,
                                 0x01020304)
    return header + b"\0" * (HEADER - len(header)) + body


def with_guid(table: bytes, guid: str) -> bytes:
    """The table written with guid "" (build_table), its GUID set (the body's first field)."""
    body = table[HEADER:]
    if struct.unpack_from("<I", body, 0)[0] != 0:
        raise ValueError("with_guid takes a table written without a GUID")
    g = guid.encode("utf-8")
    return _framed(struct.pack("<I", len(g)) + g + body[4:])

