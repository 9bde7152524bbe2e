"""The operating-map FMU all in C (bearing build-map-fmu, BearingMapFMU): the same outputs, statuses and messages as
BearingFMU at fidelity = map (through fmpy, both shipped maps and a small map of other axes built here), fmpy under
other Python versions, the win64 binary in a cross-compiled C host under wine64, the source FMU compiled by fmpy,
valgrind, repeated instantiation, corrupt tables and serialised states, and every FMI call in a wrong state."""
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import zipfile
import zlib
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(ROOT))
from map_fmu_driver import normalise, run_fmu, scenario  # noqa: E402

RPM = math.pi / 30.0
MAPS = {"oil": ROOT / "maps" / "7218B_oil.nc", "solid": ROOT / "maps" / "7218B_solid.nc"}
CC = os.environ.get("CC", "gcc")
MINGW = "x86_64-w64-mingw32-gcc"


def wine_loader():
    for p in ("/usr/lib/wine/wine64", "/usr/bin/wine64", "/usr/lib/x86_64-linux-gnu/wine/wine64"):
        if os.path.isfile(p) and os.access(p, os.X_OK):
            return p
    try:
        out = subprocess.run(["dpkg", "-L", "wine64"], capture_output=True, text=True).stdout.split()
    except OSError:
        return None
    for p in out:
        if p.endswith("/wine64") and os.path.isfile(p):
            return p
    return None


# ---- a small map with other axes: fy_N and oil_temperature_C (no rotation), a failed grid point, flags ---------
def small_map(path: Path) -> str:
    import xarray as xr
    from bearing_core.session.fidelity import MAP_FATIGUE_RATE, MAP_OUTPUTS, SPEED_SCALED
    axes = {"speed_rpm": [800.0, 1500.0, 3000.0, 4200.0], "fx_N": [0.0, 600.0, 1500.0], "fy_N": [-500.0, 500.0],
            "fz_N": [1200.0, 2500.0, 4000.0], "oil_temperature_C": [30.0, 60.0]}
    rng = np.random.default_rng(11)
    shape = tuple(len(v) for v in axes.values())
    grids = np.meshgrid(*[np.array(v) for v in axes.values()], indexing="ij")
    n = grids[0]
    data = {}
    for k, nm in enumerate(MAP_OUTPUTS):
        smooth = 0.1 * (k + 1) * (1.0 + 2e-4 * grids[1] - 1e-4 * grids[2] + 5e-5 * grids[3] + 3e-3 * grids[4])
        v = smooth * (1.0 + 0.05 * rng.standard_normal(shape))
        if nm == "cage_speed":
            v = n * RPM * np.where(grids[3] < 2000.0, 0.26, 0.43) * (1 + 0.01 * rng.standard_normal(shape))
        elif nm in ("cage_speed_pure_rolling_outer", "cage_speed_eq26", "cage_speed_pure_rolling_inner"):
            v = n * RPM * (0.44 + 1e-6 * grids[1])
        elif nm == "cage_time_constant":
            v = 0.004 + 0.002 * rng.random(shape)
        elif nm == "steady":
            v = np.ones(shape)
            v[3, 2, 1, 2, 1] = 0.0           # an unsteady corner
        elif nm == "cage_speed_cv":
            v = 1e-4 * np.ones(shape)
        elif nm in SPEED_SCALED:
            v = v * n
        data[nm] = (list(axes), v)
    data["friction_torque"][1][0, 0, 0, 0, 0] = np.nan     # a failed grid point
    # the optional fatigue damage rate [1/s] (speed-proportional at a load; 0, an infinite life, at one corner)
    rate = n * 1e-11 * (1.0 + 1e-3 * grids[1] + 2e-4 * grids[3]) * (1.0 + 0.05 * rng.standard_normal(shape))
    rate[0, 0, 0, 0, :] = 0.0
    data[MAP_FATIGUE_RATE] = (list(axes), rate)
    ds = xr.Dataset(data, coords={k: np.array(v) for k, v in axes.items()})
    params = {"bearing": "7218B", "traction_model": "lubricated", "lubrication": "auto", "friction_coefficient": 0.1,
              "cage_friction_coefficient": 0.1, "lubricant": "generic-mineral-oil", "oil": "", "oil_fraction": 0.002,
              "churning": False, "oil_temperature": 313.15}
    ds.attrs.update(bearing="7218B", level="synthetic", parameters=json.dumps(params), grid=json.dumps(axes))
    ds.to_netcdf(str(path), engine="scipy")
    return str(path)


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """The map FMUs of the shipped maps and of the small map (every platform whose compiler is here), and
    BearingFMU (thin: its model process runs on this Python)."""
    if shutil.which(CC) is None:
        pytest.skip(f"no C compiler ({CC}): install the Debian package gcc")
    from bearing_cosim.fmu_build import build
    from bearing_cosim.map_fmu import build_map_fmu
    d = tmp_path_factory.mktemp("mapfmu")
    maps = dict(MAPS, small=small_map(d / "small.nc"))
    fmus = {k: build_map_fmu(p, d / k) for k, p in maps.items()}
    cache = tmp_path_factory.getbasetemp() / "fmu_numba_cache"     # shared with the other FMU tests
    cache.mkdir(exist_ok=True)
    os.environ.setdefault("BEARING_FMU_CACHE", str(cache))
    return {"maps": maps, "fmus": fmus, "bearing": build(d / "bearing"), "dir": d}


def ranges_of(map_path):
    from bearing_cosim.map_table import map_session
    s, _b, _m = map_session(map_path)
    lv = s.steady.level
    r = {name: (float(lo), float(hi)) for name, lo, hi, _u in lv.ranges()}
    return r, lv.rotate


def bearing_start(map_path, start=None):
    """Start values of BearingFMU at fidelity = map on the map: its build parameters, then start."""
    from bearing_cosim.map_table import map_session
    from bearing_core.session.fidelity import MAP_PARAMETERS
    _s, built_params, _m = map_session(map_path)
    return dict({k: built_params[k] for k in MAP_PARAMETERS}, fidelity="map", map_file=str(map_path), **(start or {}))


def rel_diff(a, b):
    den = np.maximum(np.abs(a), np.abs(b))
    return np.where(den > 0, np.abs(a - b) / np.where(den > 0, den, 1.0), 0.0)


def scenario_of(key, built, n=320):
    r, rotate = ranges_of(built["maps"][key])
    extra = {k: v for k, v in r.items() if k not in ("shaft_speed", "Fx", "Fz")}
    rows = scenario(r, n, seed=hash(key) % 1000, rotate=rotate, extra_axes=extra)
    if key == "small":      # the failed grid point's cell (800 rpm, Fx 0 N, Fy -500 N, Fz 1200 N), an unsteady one
        rows[40] = {"shaft_speed": 900.0 * RPM, "Fx": 100.0, "Fy": -400.0, "Fz": 1300.0}
        rows[60] = {"shaft_speed": 4200.0 * RPM, "Fx": 1500.0, "Fy": 500.0, "Fz": 4000.0}
    return rows


@pytest.mark.parametrize("key", ["oil", "solid", "small"])
def test_equals_bearing_fmu_at_fidelity_map(built, key):
    """>= 300 steps (ramps, rotating radial loads, range edges, refusals) through fmpy: every common output of the
    C FMU within 1e-12 relative of BearingFMU at fidelity = map on the same map, the same statuses (OK, Warning,
    Discard) and the same messages (the map's file path aside)."""
    rows = scenario_of(key, built)
    start = {"oil_temperature": 323.15} if key == "small" else {}
    c = run_fmu(str(built["fmus"][key]), start, rows)
    p = run_fmu(str(built["bearing"]), bearing_start(built["maps"][key], start), rows, outputs=c["names"])
    assert c["init"] == p["init"] <= 1, (c["logs"][:3], p["logs"][:3])
    assert len(c["status"]) >= 300 and c["status"] == p["status"]
    assert {1, 2} <= set(c["status"]) or key == "solid", set(c["status"])   # warnings and refusals exercised
    assert 2 in c["status"]
    assert np.all(np.isfinite(c["out"]))
    r = rel_diff(c["out"], p["out"])
    k = np.unravel_index(r.argmax(), r.shape)
    assert r.max() <= 1e-12, (c["names"][k[1]], k[0], c["out"][k], p["out"][k])
    assert [(i, s, normalise(m)) for i, s, m in c["logs"]] == [(i, s, normalise(m)) for i, s, m in p["logs"]]
    if key == "small":       # the failed grid point is refused, naming the outputs without a value
        assert any("a failed grid point" in m and "'friction_torque'" in m for _i, _s, m in c["logs"])


def test_initialisation_refusals_equal_bearing_fmu(built):
    """A parameter other than the map's, a fixed parameter of the level, an oil temperature outside the map's axis,
    an input outside the map at the first point (with a parameter that has no effect at the map level set) and a
    non-finite input: fmi2ExitInitializationMode returns Error in both FMUs with the same message."""
    key = "small"
    r, _ = ranges_of(built["maps"][key])
    good = {"shaft_speed": 2000 * RPM, "Fx": 300.0, "Fz": 2000.0}
    cases = [({"bearing": "7008", "friction_coefficient": 0.2}, good), ({"coupling": "displacement"}, good),
             ({"oil_temperature": 400.0}, good), ({"integrator": "rk4"}, dict(good, shaft_speed=9000 * RPM)),
             ({"churning": True}, dict(good, Fz=float("nan")))]
    for start, row in cases:
        c = run_fmu(str(built["fmus"][key]), start, [row])
        p = run_fmu(str(built["bearing"]), bearing_start(built["maps"][key], start), [row])
        assert c["init"] == p["init"] == 3, (start, row, c["logs"], p["logs"])
        cm = [normalise(m) for _i, s, m in c["logs"] if s == 3]
        pm = [normalise(m) for _i, s, m in p["logs"] if s == 3]
        assert cm == pm, (start, row)


def test_model_description_and_validate(built):
    """fmpy.validate_fmu: 0 problems; the same inputs and outputs (names, units, causality) as BearingFMU; the C
    sources listed; the size (zipped, less the table) under 1 MB."""
    from fmpy import read_model_description
    from fmpy.validation import validate_fmu
    from bearing_cosim.map_table import TABLE_NAME
    for fmu in built["fmus"].values():
        assert validate_fmu(str(fmu)) == []
    md = read_model_description(str(built["fmus"]["oil"]))
    mb = read_model_description(str(built["bearing"]))
    sig = lambda m, c: {(v.name, v.type, getattr(v, "unit", None)) for v in m.modelVariables if v.causality == c}
    assert sig(md, "input") == sig(mb, "input")
    assert sig(md, "output") == sig(mb, "output")
    assert md.coSimulation.modelIdentifier == "BearingMapFMU" and md.guid != mb.guid
    assert md.guid != read_model_description(str(built["fmus"]["solid"])).guid      # its own GUID per map
    with zipfile.ZipFile(built["fmus"]["oil"]) as z:
        names = z.namelist()
        table = z.getinfo(f"resources/{TABLE_NAME}").compress_size
    assert {"sources/model.c", "sources/fmi2_common.c", "sources/fmi2_common.h", "sources/config.h"} <= set(names)
    assert "binaries/linux64/BearingMapFMU.so" in names
    assert built["fmus"]["oil"].stat().st_size - table < 1 << 20


def test_other_python_versions(built, tmp_path):
    """fmpy in Python versions other than the build's (pyenv) drives the C FMU to the same outputs."""
    versions = sorted(Path(os.path.expanduser("~/.pyenv/versions")).glob("3.1[0-3]*"))
    mine = f"{sys.version_info.major}.{sys.version_info.minor}"
    others = [v for v in versions if not v.name.startswith(mine + ".")][-2:]
    if len(others) < 2:
        pytest.skip(f"fewer than two other Python versions under ~/.pyenv/versions ({[v.name for v in versions]})")
    rows = scenario_of("oil", built, n=120)
    ref = run_fmu(str(built["fmus"]["oil"]), {}, rows)
    (tmp_path / "rows.json").write_text(json.dumps(rows))
    code = ("import json, sys; sys.path.insert(0, sys.argv[1]); from map_fmu_driver import run_fmu; "
            "r = run_fmu(sys.argv[2], {}, json.load(open(sys.argv[3]))); "
            "print('RESULT', json.dumps({'status': r['status'], 'out': r['out'].tolist()}))")
    for v in others:
        venv = Path(os.path.expanduser(f"~/.cache/bearing-tribodynamics/fmpy-venv-{v.name}"))
        if not (venv / "bin" / "python").exists():
            subprocess.run([str(v / "bin" / "python3"), "-m", "venv", str(venv)], check=True)
            r = subprocess.run([str(venv / "bin" / "python"), "-m", "pip", "install", "-q",
                                "--disable-pip-version-check", "fmpy", "numpy"], capture_output=True, text=True)
            if r.returncode != 0:
                shutil.rmtree(venv, ignore_errors=True)
                pytest.skip(f"fmpy does not install under Python {v.name}: {r.stderr[-500:]}")
        r = subprocess.run([str(venv / "bin" / "python"), "-c", code, str(HERE), str(built["fmus"]["oil"]),
                            str(tmp_path / "rows.json")], capture_output=True, text=True, timeout=300)
        assert r.returncode == 0, r.stderr[-2000:]
        res = json.loads([ln for ln in r.stdout.splitlines() if ln.startswith("RESULT ")][-1][7:])
        assert res["status"] == ref["status"], v.name
        assert np.array_equal(np.array(res["out"]), ref["out"]), v.name


def test_source_fmu_compiled_by_fmpy(built, tmp_path):
    """The FMU with its binaries removed, compiled from sources/ by fmpy (CMake), gives the same outputs."""
    if shutil.which("cmake") is None:
        pytest.skip("no cmake: install the Debian package cmake")
    from fmpy.build import build_platform_binary
    unz = tmp_path / "src_fmu"
    with zipfile.ZipFile(built["fmus"]["oil"]) as z:
        z.extractall(unz)
    shutil.rmtree(unz / "binaries")
    (tmp_path / "cmake_build").mkdir()
    build_platform_binary(str(unz), build_dir=str(tmp_path / "cmake_build"))
    assert (unz / "binaries" / "linux64" / "BearingMapFMU.so").is_file()
    src = tmp_path / "BearingMapFMU_src.fmu"
    with zipfile.ZipFile(src, "w") as z:
        for f in unz.rglob("*"):
            if f.is_file():
                z.write(f, f.relative_to(unz).as_posix())
    rows = scenario_of("oil", built, n=120)
    a = run_fmu(str(built["fmus"]["oil"]), {}, rows)
    b = run_fmu(str(src), {}, rows)
    assert a["status"] == b["status"]
    assert rel_diff(a["out"], b["out"]).max() <= 1e-12


# ---- the C host: Linux, valgrind, wine ---------------------------------------------------------------------------
@pytest.fixture(scope="module")
def host(built):
    d = built["dir"] / "host"
    d.mkdir(exist_ok=True)
    exe = d / "host"
    subprocess.run([CC, "-std=gnu99", "-O2", "-Wall", "-o", str(exe), str(HERE / "c_host" / "host.c"), "-ldl"],
                   check=True)
    unz = {}
    for k, fmu in built["fmus"].items():
        unz[k] = d / f"unz_{k}"
        with zipfile.ZipFile(fmu) as z:
            z.extractall(unz[k])
    from fmpy import read_model_description
    guid = {k: read_model_description(str(f)).guid for k, f in built["fmus"].items()}
    return {"exe": exe, "unz": unz, "guid": guid, "dir": d}


def host_script(rows, outputs, h=1e-3):
    """The host's script: initialise at rows[0], one step per later row (every input), a state round trip, a state
    left for fmi2FreeInstance."""
    from bearing_core.session.cosim_spec import INPUT_NAMES
    out = ["instantiate", "setup 0", "enter", "inputs " + " ".join(str(i) for i in range(len(INPUT_NAMES))),
           "outputs " + " ".join(str(1000 + i) for i in outputs)]
    out += [f"set_real {i} {float(rows[0].get(n, 0.0))!r}" for i, n in enumerate(INPUT_NAMES)]
    out.append("exit")
    for r in rows[1:]:
        out.append("step " + repr(h) + " " + " ".join(repr(float(r.get(n, 0.0))) for n in INPUT_NAMES))
    # the last state is left to fmi2FreeInstance, which frees it (valgrind: no leak)
    out += ["getstate", "roundtrip", "freestate", "getstate", "terminate", "free"]
    return "\n".join(out) + "\n"


def parse_rows(stdout):
    st, vals = [], []
    for ln in stdout.splitlines():
        if ln.startswith("ROW "):
            p = ln.split()
            st.append(int(p[1]))
            vals.append([float(x) for x in p[4:]])
    return st, np.array(vals)


def run_host(host, key, script, tmp_path, exe=None, prefix=(), unz=None, timeout=300):
    p = tmp_path / f"script_{key}.txt"
    p.write_text(script)
    cmd = [*prefix, str(exe or host["exe"]), str(unz or host["unz"][key]), "BearingMapFMU", host["guid"][key], str(p)]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout,
                          env=dict(os.environ, WINEDEBUG="-all"))


def real_outputs():
    from bearing_core.session.cosim_spec import OUTPUT_NAMES
    return list(range(len(OUTPUT_NAMES)))


def test_c_host_linux_equals_fmpy_and_valgrind_clean(built, host, tmp_path):
    """The C host on the Linux binary: the fmpy run's outputs exactly; a state round trip through
    fmi2SerializeFMUstate / fmi2DeSerializeFMUstate; valgrind: no error, no leak."""
    rows = scenario_of("small", built, n=150)
    outs = real_outputs()
    r = run_host(host, "small", host_script(rows, outs), tmp_path)
    assert r.returncode == 0, r.stderr[-2000:]
    st, vals = parse_rows(r.stdout)
    ref = run_fmu(str(built["fmus"]["small"]), {}, rows)
    assert st == ref["status"]
    assert np.array_equal(vals, ref["out"][1:, outs])
    assert "STATUS roundtrip 0" in r.stdout
    if shutil.which("valgrind") is None:
        pytest.skip("no valgrind: install the Debian package valgrind")
    v = run_host(host, "small", host_script(rows[:40], outs), tmp_path,
                 prefix=("valgrind", "--error-exitcode=9", "--leak-check=full", "--errors-for-leak-kinds=definite",
                         "-q"))
    assert v.returncode == 0, v.stderr[-3000:]
    assert parse_rows(v.stdout)[0] == ref["status"][:39]


def test_repeated_instantiation_no_growth(built, host, tmp_path):
    """10,000 instantiate/free cycles in one process: the resident set does not grow (after 1,000 cycles and after
    10,000 within 200 kB)."""
    script = "instantiate\ncycles 1000\nrss\ncycles 9000\nrss\nfree\n"
    r = run_host(host, "small", script, tmp_path)
    assert r.returncode == 0 and "STATUS cycles 0" in r.stdout, r.stdout[-2000:] + r.stderr[-2000:]
    rss = [int(ln.split()[1]) for ln in r.stdout.splitlines() if ln.startswith("RSS ")]
    assert len(rss) == 2 and rss[1] - rss[0] <= 200, rss


def _table_variants(table: bytes):
    """(name, bytes, words expected in the reason) of broken tables."""
    body = table[64:]

    def with_crc(b):
        return table[:24] + struct.pack("<I", zlib.crc32(b) & 0xFFFFFFFF) + table[28:64] + b
    guid_len = struct.unpack_from("<I", body, 0)[0]
    yield "truncated", table[:len(table) // 2], "truncated or padded"
    yield "empty", b"", "no BRGMAPTB header"
    yield "bit flip", table[:1000] + bytes([table[1000] ^ 0x10]) + table[1001:], "CRC-32"
    yield "other version", table[:8] + struct.pack("<I", 99) + table[12:], "format version 99"
    yield "not a table", b"CDF\x01" + table[4:], "no BRGMAPTB header"
    # a consistent header and CRC over a body whose counts lie: n_axes = 99
    off = 4 + guid_len
    for _ in range(4):                       # level, bearing, map name, provenance
        off += 4 + struct.unpack_from("<I", body, off)[0]
    bad = bytearray(body)
    struct.pack_into("<I", bad, off + 12, 99)
    b = bytes(bad)
    yield "lying counts", with_crc(b)[:16] + struct.pack("<Q", 64 + len(b)) + with_crc(b)[24:], "n_axes = 99"
    yield "cut body", with_crc(body[:-100])[:16] + struct.pack("<Q", len(body) - 36) + with_crc(body[:-100])[24:], \
        "truncated table"


def test_corrupt_tables_give_null_with_reason(built, host, tmp_path):
    """A missing, truncated or corrupt table, or one of another version: fmi2Instantiate returns NULL and logs why;
    the host goes on (no crash)."""
    from bearing_cosim.map_table import TABLE_NAME
    src = host["unz"]["small"]
    table = (src / "resources" / TABLE_NAME).read_bytes()
    cases = list(_table_variants(table)) + [("missing", None, "cannot open")]
    for name, data, words in cases:
        d = tmp_path / f"fmu_{name.replace(' ', '_')}"
        shutil.copytree(src, d)
        if data is None:
            (d / "resources" / TABLE_NAME).unlink()
        else:
            (d / "resources" / TABLE_NAME).write_bytes(data)
        r = run_host(host, "small", "instantiate\ninstantiate\n", tmp_path, unz=d)
        assert r.returncode == 0, (name, r.stderr[-1000:])
        assert r.stdout.count("STATUS instantiate 3") == 2, (name, r.stdout)
        assert words in r.stdout, (name, r.stdout)


def test_corrupt_serialized_states_refused(built, host, tmp_path):
    """A serialised state with a flipped byte, cut short, of another FMU or a Python pickle: fmi2Error with the
    reason, the instance unchanged and usable."""
    import pickle
    st_file = tmp_path / "state.bin"
    head = "instantiate\nsetup 0\nenter\nexit\ninputs 0 1 3\noutputs 1005\nstep 0.001 300 400 2000\n"
    r = run_host(host, "small", head + f"getstate\nsave_state {st_file}\n", tmp_path)
    good = st_file.read_bytes()
    assert r.returncode == 0 and len(good) > 96
    variants = {"flip": good[:120] + bytes([good[120] ^ 1]) + good[121:], "short": good[:-8],
                "pickle": pickle.dumps(("state", [1.0, 2.0])), "header only": good[:96]}
    other = run_host(host, "oil", head + f"getstate\nsave_state {tmp_path / 'other.bin'}\n", tmp_path)
    assert other.returncode == 0
    variants["other FMU"] = (tmp_path / "other.bin").read_bytes()
    for name, data in variants.items():
        f = tmp_path / f"bad_{name.replace(' ', '_')}.bin"
        f.write_bytes(data)
        r = run_host(host, "small", head + f"load_state {f}\nstep 0.001 300 400 2000\n", tmp_path)
        assert r.returncode == 0, r.stderr
        assert "STATUS load_state 3" in r.stdout and "fmi2DeSerializeFMUstate" in r.stdout, (name, r.stdout)
        assert len(parse_rows(r.stdout)[0]) == 2 and max(parse_rows(r.stdout)[0]) <= 1, name   # still usable
    r = run_host(host, "small", head + f"getstate\nload_state {st_file}\n", tmp_path)
    assert "STATUS load_state 0" in r.stdout


def test_calls_in_wrong_state_return_error(built, host, tmp_path):
    """Every FMI call in a state that does not allow it returns fmi2Error with the reason (FMI 2.0 section
    4.3.1); the host goes on."""
    script = ("instantiate\ninputs 0\noutputs 1005\nstep 0.001 100\nexit\ngetstate\nsetup 0\nenter\nsetup 0\nenter\n"
              "exit\nexit\nset_real 5005 0.1\nset_real 1005 3.0\nget_real 99999\nset_int 1005 1\nterminate\n"
              "step 0.001 100\nset_real 0 100\nreset\nsetup 0\nenter\nexit\nfree\n")
    r = run_host(host, "oil", script, tmp_path)
    assert r.returncode == 0, r.stderr
    st = [ln for ln in r.stdout.splitlines() if ln.startswith(("STATUS", "ROW"))]
    expect = ["STATUS instantiate 0", "ROW 3", "STATUS exit 3", "STATUS getstate 3", "STATUS setup 0",
              "STATUS enter 0", "STATUS setup 3", "STATUS enter 3", "STATUS exit 1", "STATUS exit 3",
              "STATUS set_real 3", "STATUS set_real 3", "STATUS get_real 3", "STATUS set_int 3", "STATUS terminate 0",
              "ROW 3", "STATUS set_real 3", "STATUS reset 0", "STATUS setup 0", "STATUS enter 0", "STATUS exit 1",
              "STATUS free 0"]
    # (initialisation on the shipped map: Warning, 1, its warning that it has no fatigue_damage_rate)
    assert [s[:len(e)] for s, e in zip(st, expect)] == expect, r.stdout
    assert "not allowed" in r.stdout and "fixed parameter" in r.stdout and "unknown value reference" in r.stdout


def test_win64_dll_under_wine_equals_linux(built, host, tmp_path):
    """A C host cross-compiled with mingw-w64 loads binaries/win64/BearingMapFMU.dll under wine64 (the resources
    as a file:///Z:/ URI): its outputs equal the Linux host's within 1e-12, the same statuses."""
    if shutil.which(MINGW) is None:
        pytest.skip(f"no {MINGW}: install the Debian package gcc-mingw-w64-x86-64-win32")
    loader = wine_loader()
    if loader is None:
        pytest.skip("no wine64 loader: install the Debian package wine64")
    assert (host["unz"]["oil"] / "binaries" / "win64" / "BearingMapFMU.dll").is_file()
    exe = host["dir"] / "host.exe"
    subprocess.run([MINGW, "-std=gnu99", "-O2", "-Wall", "-o", str(exe), str(HERE / "c_host" / "host.c")],
                   check=True)
    rows = scenario_of("oil", built, n=150)
    script = host_script(rows, real_outputs())
    lin = run_host(host, "oil", script, tmp_path)
    win = run_host(host, "oil", script, tmp_path, exe=exe, prefix=(loader,), unz="Z:" + str(host["unz"]["oil"]),
                   timeout=600)
    assert win.returncode == 0, win.stderr[-2000:]
    sl, vl = parse_rows(lin.stdout)
    sw, vw = parse_rows(win.stdout)
    assert sl == sw and len(sl) == 150
    assert rel_diff(vl, vw).max() <= 1e-12
    assert "STATUS roundtrip 0" in win.stdout


def test_cli_build_and_simulate(built, tmp_path):
    """`bearing build-map-fmu` builds the FMU (a platform without its compiler or an unknown one is refused, naming
    it), and `bearing simulate --fmu BearingMapFMU.fmu` drives it through seed 000's profile with the parameters it
    sets for BearingFMU (the map's values)."""
    exe = Path(sys.executable).with_name("bearing")
    r = subprocess.run([str(exe), "build-map-fmu", str(MAPS["oil"]), "--dest", str(tmp_path / "d"), "--platforms",
                        "linux64"], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0 and "binaries: linux64" in r.stdout, r.stderr
    r = subprocess.run([str(exe), "build-map-fmu", str(MAPS["oil"]), "--platforms", "darwin64"], capture_output=True,
                       text=True, timeout=300)
    assert r.returncode == 2 and "--platforms = 'darwin64' is invalid; allowed: linux64, win64" in r.stderr
    r = subprocess.run([str(exe), "build-map-fmu", str(MAPS["oil"]), "--platforms", ""], capture_output=True,
                       text=True, timeout=300)
    assert r.returncode == 2 and "--platforms = '' is invalid; allowed: one or more of linux64, win64" in r.stderr
    env = dict(os.environ, PATH="/nonexistent")          # no cross compiler on this PATH
    r = subprocess.run([str(exe), "build-map-fmu", str(MAPS["oil"]), "--platforms", "win64", "--dest",
                        str(tmp_path / "w")], capture_output=True, text=True, timeout=300, env=env)
    assert r.returncode == 2 and "gcc-mingw-w64-x86-64-win32" in r.stderr, r.stderr
    r = subprocess.run([str(exe), "simulate", "--fmu", str(tmp_path / "d" / "BearingMapFMU.fmu"), "--profile",
                        "seed000", "--fx", "1000", "--fz", "3000", "--stop-time", "0.7", "--out", str(tmp_path / "o")],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    s = json.loads((tmp_path / "o" / "fmu_simulation_summary.json").read_text())
    assert 0.35 < s["final_cage_shaft_ratio"] < 0.5 and s["final_friction_torque_Nm"] > 0.0


def _jacobian(fmu, start, inputs):
    """d(ir_x..ir_ty, reaction_Fx..My)/d(Fx..My) by fmi2GetDirectionalDerivative after one step at inputs, and
    the stiffness outputs; (None, message) if the call fails."""
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave
    md = read_model_description(str(fmu))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    s = FMU2Slave(guid=md.guid, unzipDirectory=extract(str(fmu)), modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName="dd")
    s.instantiate()
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    for k, v in start.items():
        setter = s.setString if isinstance(v, str) else (s.setBoolean if isinstance(v, bool) else s.setReal)
        setter([vr[k]], [v])
    s.setReal([vr[k] for k in inputs], list(inputs.values()))
    s.exitInitializationMode()
    s.doStep(currentCommunicationPoint=0.0, communicationStepSize=1e-3)
    unknown = [vr[n] for n in ("ir_x", "ir_y", "ir_z", "ir_tx", "ir_ty", "reaction_Fx", "reaction_Fy", "reaction_Fz",
                               "reaction_Mx", "reaction_My")]
    known = [vr[n] for n in ("Fx", "Fy", "Fz", "Mx", "My")]
    try:
        J = np.array([s.getDirectionalDerivative(unknown, known, list(np.eye(5)[j])) for j in range(5)]).T
    except Exception as e:      # noqa: BLE001 - fmpy raises on fmi2Error
        J = None, str(e)
    K = np.array(s.getReal([vr[f"stiffness[{i},{j}]"] for i in range(1, 6) for j in range(1, 6)])).reshape(5, 5)
    s.terminate()
    s.freeInstance()
    return J, K


def test_directional_derivative_equals_bearing_fmu(built):
    """fmi2GetDirectionalDerivative of the C FMU (coupling load): d ir/d load is the inverse of the stiffness outputs
    (turned with a rotating radial load), d reaction/d load = -I, and both equal BearingFMU's at fidelity = map; a
    map without stiffness variables refuses it with Error."""
    for inputs in ({"shaft_speed": 4000 * RPM, "Fx": 700.0, "Fy": 900.0, "Fz": 2600.0},
                   {"shaft_speed": 9000 * RPM, "Fx": -1500.0, "Fy": 0.0, "Fz": 5000.0}):
        Jc, Kc = _jacobian(built["fmus"]["oil"], {}, inputs)
        Jp, Kp = _jacobian(built["bearing"], bearing_start(built["maps"]["oil"]), inputs)
        assert np.array_equal(Kc, Kp)
        scale = np.abs(Jc[:5]).max()
        assert np.abs(Jc[:5] - Jp[:5]).max() <= 1e-9 * scale
        assert np.array_equal(Jc[5:], -np.eye(5)) and np.array_equal(Jp[5:], -np.eye(5))
        free = [k for k in range(5) if np.any(Kc[k] != 0)]
        assert np.allclose((Kc @ Jc[:5])[np.ix_(free, free)], np.eye(len(free)), atol=1e-8)
    J, _K = _jacobian(built["fmus"]["small"], {}, {"shaft_speed": 2000 * RPM, "Fx": 300.0, "Fz": 2000.0})
    assert J[0] is None


def test_fatigue_damage_follows_the_fmu_state(built):
    """The small map carries fatigue_damage_rate: the C FMU's fatigue_damage grows by rate x h per step, and
    fmi2GetFMUstate / fmi2SetFMUstate and a serialised state bring it back (the damage is part of the state)."""
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave
    fmu = str(built["fmus"]["small"])
    md = read_model_description(fmu)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    unz = extract(fmu)
    s = FMU2Slave(guid=md.guid, unzipDirectory=unz, modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName="fat")
    try:
        s.instantiate()
        s.setupExperiment(startTime=0.0)
        s.enterInitializationMode()
        s.setReal([vr["oil_temperature"], vr["shaft_speed"], vr["Fx"], vr["Fz"]], [323.15, 2000 * RPM, 700.0, 2600.0])
        s.exitInitializationMode()
        get = lambda: s.getReal([vr["life_L10r_h"], vr["fatigue_damage"]])  # noqa: E731
        L0, d0 = get()
        assert d0 == 0.0 and 0.0 < L0 < 1e12
        t, h = 0.0, 0.01
        for _ in range(5):
            s.doStep(t, h)
            t += h
        L, d5 = get()
        assert L == L0 and d5 == pytest.approx(5 * h / (3600.0 * L0), rel=1e-12)
        st = s.getFMUstate()
        ser = s.serializeFMUstate(st)
        s.setReal([vr["shaft_speed"]], [4000 * RPM])
        for _ in range(5):
            s.doStep(t + 0.0, h)
            t += h
        assert get()[1] > 2 * d5
        s.setFMUstate(st)
        assert get()[1] == d5
        st2 = s.deSerializeFMUstate(ser)
        s.setFMUstate(st2)
        assert get()[1] == d5
        s.freeFMUstate(st)
        s.freeFMUstate(st2)
        s.terminate()
    finally:
        s.freeInstance()
        shutil.rmtree(unz, ignore_errors=True)
