"""The FMU's native FMI 2.0 layer in a master that is not Python (tests/c_host/host.c, compiled here with
the system C compiler), its FMI statuses, valgrind, two FMU versions in one process, fast refusal of load
cases without equilibrium and read-only installs."""
import math
import os
import shutil
import stat
import subprocess
import sys
import time
import zipfile
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
RPM = math.pi / 30
CLEAN_ENV = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "LD_PRELOAD")}


def _cache(tmp_path_factory):
    """numba cache shared by the FMU tests of one session (same code, same content-hashed folders)."""
    d = tmp_path_factory.getbasetemp() / "fmu_numba_cache"
    d.mkdir(exist_ok=True)
    return str(d)


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    if shutil.which(os.environ.get("CC", "gcc")) is None:
        pytest.skip("no C compiler")
    sys.path.insert(0, str(HERE.parent))
    from build_fmu import build
    from fmpy import read_model_description
    d = tmp_path_factory.mktemp("native")
    fmu = build(d / "dist")
    unz = d / "unz"
    with zipfile.ZipFile(fmu) as z:
        z.extractall(unz)
    host = d / "host"
    subprocess.run([os.environ.get("CC", "gcc"), "-std=gnu99", "-O2", "-Wall", "-o", str(host),
                    str(HERE / "c_host" / "host.c"), "-ldl"], check=True)
    md = read_model_description(str(fmu))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    return {"fmu": fmu, "unz": unz, "host": host, "guid": md.guid, "vr": vr, "cache": _cache(tmp_path_factory),
            "dir": d}


def run_host(b, script, tmp_path, env=None, unz=None, valgrind=None, timeout=600):
    p = tmp_path / "script.txt"
    p.write_text(script)
    e = dict(CLEAN_ENV, BEARING_FMU_CACHE=b["cache"])
    e.update(env or {})
    cmd = [str(b["host"]), str(unz or b["unz"]), "BearingFMU", b["guid"], str(p)]
    r = subprocess.run((valgrind or []) + cmd, capture_output=True, text=True, env=e, timeout=timeout)
    return r


def parse(out):
    status, rows, logs, values = [], [], [], []
    for ln in out.splitlines():
        w = ln.split(" ", 3)
        if w[0] == "STATUS":
            status.append((w[1], int(w[2])))
        elif w[0] == "ROW":
            rows.append([float(x) for x in ln.split()[1:]])
        elif w[0] == "LOG":
            logs.append((int(w[1]), w[2], w[3] if len(w) > 3 else ""))
        elif w[0] == "VALUE":
            values.append(float(w[2]))
    return status, rows, logs, values


def seed000_short(h=1e-3, t_end=0.3):
    """Seed 000's acceleration profile (hold 1000 rpm, then 10,000 rpm/s), shortened: hold to 0.1 s, ramp to
    t_end. Fx 1000 N, Fz 3000 N."""
    steps = []
    for k in range(int(round(t_end / h))):
        t = k * h
        n = 1000.0 + 10000.0 * max(0.0, t - 0.1)
        steps.append((h, n * RPM))
    return steps


def test_archive_and_native_library(built):
    """Every archive member is readable by all users (0644, the library 0755); the native library neither
    needs libpython nor refers to any Python symbol (the model runs in its own process)."""
    with zipfile.ZipFile(built["fmu"]) as z:
        for zi in z.infolist():
            mode = (zi.external_attr >> 16) & 0o777
            assert mode & 0o444 == 0o444, (zi.filename, oct(mode))
        names = z.namelist()
    assert {"binaries/linux64/BearingFMU.so", "resources/model.json", "resources/launch.sh",
            "resources/model_process.py", "resources/code/bearing_fmu.py"} <= set(names)
    so = str(built["unz"] / "binaries/linux64/BearingFMU.so")
    if shutil.which("nm"):
        und = subprocess.run(["nm", "-D", "--undefined-only", so], capture_output=True, text=True).stdout
        assert "Py" not in und, und
    if shutil.which("readelf"):
        dyn = subprocess.run(["readelf", "-d", so], capture_output=True, text=True).stdout
        assert "NEEDED" in dyn and "python" not in dyn.lower(), dyn


def test_c_host_runs_seed000_profile_like_fmpy(built, tmp_path):
    """A C master (no Python in the process, no PYTHONPATH, no LD_PRELOAD) runs the shortened seed 000 profile
    and exits 0: every step OK, outputs finite, the reaction equals the applied axial load (0.5 %, statics) and
    the cage follows the shaft at the end of the ramp (cage-shaft ratio within 5 % of its spin-free theoretical
    value, seed 000 Eq. 26, lubricated traction); fmpy on the same FMU gives the same mean cage speed (0.1 %)."""
    import json
    vr = built["vr"]
    outs = ["cage_speed", "reaction_Fz", "cage_shaft_ratio", "cage_shaft_ratio_theory"]
    steps = seed000_short()
    lines = ["instantiate 0", "setup 0", "enter", f"set_real {vr['shaft_speed']} {steps[0][1]!r}",
             f"set_real {vr['Fx']} 1000", f"set_real {vr['Fz']} 3000", "exit",
             "inputs " + " ".join(str(vr[k]) for k in ("shaft_speed", "Fx", "Fz")),
             "outputs " + " ".join(str(vr[k]) for k in outs)]
    lines += [f"step {h!r} {w!r} 1000 3000" for h, w in steps]
    lines += ["terminate", "free"]
    r = run_host(built, "\n".join(lines) + "\n", tmp_path)
    assert r.returncode == 0, (r.returncode, r.stderr[-2000:])
    status, rows, logs, _ = parse(r.stdout)
    assert all(s == 0 for _, s in status), status
    rows = np.array(rows)
    assert rows.shape == (len(steps), 3 + len(outs)) and np.all(rows[:, :2] == 0) and np.all(np.isfinite(rows))
    late = rows[100:]
    assert abs(-late[:, 4].mean() / 3000 - 1) < 0.005
    assert abs(rows[-20:, 5].mean() / rows[-20:, 6].mean() - 1) < 0.05
    # the same inputs through fmpy (tests/fmu_driver.py)
    spec = {"fmu": str(built["fmu"]), "params": {}, "outputs": outs,
            "start_inputs": {"shaft_speed": steps[0][1], "Fx": 1000.0, "Fz": 3000.0},
            "steps": [[h, {"shaft_speed": w, "Fx": 1000.0, "Fz": 3000.0}] for h, w in steps]}
    p = tmp_path / "spec.json"
    p.write_text(json.dumps(spec))
    r2 = subprocess.run([sys.executable, str(HERE / "fmu_driver.py"), str(p)], capture_output=True, text=True,
                        env=dict(os.environ, BEARING_FMU_CACHE=built["cache"]), timeout=600)
    assert r2.returncode == 0, r2.stderr[-2000:]
    res = json.loads([ln for ln in r2.stdout.splitlines() if ln.startswith("RESULT ")][-1][7:])
    cage_fmpy = np.array([x["values"][0] for x in res["rows"]])
    assert abs(rows[:, 3].mean() / cage_fmpy.mean() - 1) < 0.001


def test_statuses(built, tmp_path):
    """FMI statuses a master sees, each with its reason in the logger (category logError / logDiscard):
    failed initialisation (no axial load) -> fmi2Error, refused within 5 s; getReal and doStep after it ->
    fmi2Error; default start values initialise (OK); a fixed parameter set after initialisation -> fmi2Error and
    the value is unchanged; an output set -> fmi2Error; fmi2SerializeFMUstate (unsupported) -> fmi2Error and
    the instance keeps stepping; a reversed axial load mid-run -> fmi2Discard with the ring where it was; a
    1e7 N axial load mid-run -> fmi2Discard (beyond the ISO 76 contact-stress limit), the next step OK."""
    vr = built["vr"]
    script = f"""instantiate 0
setup 0
enter
set_real {vr['Fz']} 0
exit
get_real {vr['cage_speed']}
outputs {vr['ir_z']}
step 0.001
free
instantiate 0
setup 0
enter
exit
outputs {vr['ir_z']} {vr['reaction_Fz']}
inputs {vr['shaft_speed']} {vr['Fx']} {vr['Fz']}
step 0.001 314.159 1000 3000
set_string {vr['bearing']} 7008-ma2023
set_real {vr['friction_coefficient']} 0.5
get_real {vr['friction_coefficient']}
set_real {vr['cage_speed']} 1.0
getstate
serialize
step 0.001 314.159 1000 3000
step 0.001 314.159 1000 -3000
step 0.001 314.159 1000 3000
step 0.001 314.159 1000 1e7
step 0.001 314.159 1000 3000
terminate
free
"""
    t0 = time.perf_counter()
    r = run_host(built, script, tmp_path)
    wall = time.perf_counter() - t0
    assert r.returncode == 0, (r.returncode, r.stderr[-2000:])
    status, rows, logs, values = parse(r.stdout)
    st = dict()
    for k, (name, s) in enumerate(status):
        st.setdefault(name, []).append(s)
    assert st["exit"] == [3, 0]
    assert st["get_real"] == [3, 0] and values[1] == pytest.approx(0.1)
    assert st["set_string"] == [3] and st["set_real"] == [0, 3, 3]   # Fz before init, fixed parameter, output
    assert st["getstate"] == [0] and st["serialize"] == [3]
    assert [int(r_[0]) for r_ in rows] == [3, 0, 0, 2, 0, 2, 0]
    assert rows[3][3] == rows[2][3]          # ir_z unchanged by the refused step
    assert abs(rows[4][3] - rows[2][3]) < 1e-6
    errs = [m for s, c, m in logs if s == 3 and c == "logError"]
    assert any("initialisation failed" in m and "Fz" in m and "no axial load" in m for m in errs)
    assert any("fmi2GetReal" in m and "initialisation failed" in m for m in errs)
    assert any("fmi2DoStep" in m for m in errs)
    assert any("bearing is a fixed parameter" in m for m in errs)
    assert any("friction_coefficient is a fixed parameter" in m for m in errs)
    assert any("cage_speed is an output" in m for m in errs)
    assert any("fmi2SerializeFMUstate: size = 64 bytes is less than the state's" in m for m in errs)
    assert any(s == 2 and c == "logDiscard" and "reversed axial load" in m for s, c, m in logs)
    assert any(s == 2 and c == "logDiscard" and "contact pressure at least" in m for s, c, m in logs)
    assert wall < 120


def test_default_start_values_run_in_fmpy(built, tmp_path):
    """fmpy.simulate_fmu with the FMU's own start values and default experiment (shortened to 20 ms) runs to
    the end: a loaded bearing at 3000 rpm."""
    code = ("import fmpy, sys, json; r = fmpy.simulate_fmu(sys.argv[1], stop_time=0.02, output=['cage_speed', "
            "'reaction_Fz']); print('RESULT', json.dumps([float(r['time'][-1]), float(r['reaction_Fz'][-1])]))")
    r = subprocess.run([sys.executable, "-c", code, str(built["fmu"])], capture_output=True, text=True,
                       env=dict(os.environ, BEARING_FMU_CACHE=built["cache"]), timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    import json
    t_end, fz = json.loads(r.stdout.split("RESULT", 1)[1])
    assert t_end == pytest.approx(0.02) and abs(-fz / 3000 - 1) < 0.01


def test_unsolvable_load_refused_fast():
    """No axial load and a reversed axial load on a single angular-contact bearing have no equilibrium (all
    ball loads push the inner ring axially one way), and a 1e7 N axial load needs a ball load >= 1e7 N / Z,
    whose Hertz pressure on any inner contact exceeds the 4.2 GPa static limit (ISO 76): refused at
    initialisation with that reason, before any solve (generous bound 5 s here; measured time in
    docs/fmu.md)."""
    from bearing_core.session.cosim import CoSimParameters, CoSimSession
    from bearing_core.errors import BearingInputError
    for inp, why in (({"shaft_speed": 314.0, "Fx": 1000.0, "Fz": 0.0}, "no axial load"),
                     ({"shaft_speed": 314.0, "Fz": -3000.0}, "reversed axial load"),
                     ({"shaft_speed": 0.0}, "no axial load"),
                     ({"shaft_speed": 314.0, "Fz": 1e7}, "contact pressure at least")):
        t0 = time.perf_counter()
        with pytest.raises(BearingInputError, match=why):
            CoSimSession(CoSimParameters()).initialize(0.0, inp)
        assert time.perf_counter() - t0 < 5.0


def test_two_versions_side_by_side(built, tmp_path):
    """Two versions of the FMU in one fmpy process (v2's slave doubles cage_speed), after the host imported
    the installed bearing_core and broke it (contact-stress limit set to 1 Pa): each FMU runs its own code in
    its own model process, v2 gives twice v1's cage speed and both accept every step."""
    sys.path.insert(0, str(HERE.parent))
    from build_fmu import _build
    src = (HERE.parent / "bearing_cosim" / "fmu_src" / "bearing_fmu.py").read_text()
    marker = "        self._out = self._session.values\n"
    assert marker in src
    v2 = src.replace(marker, marker + "        self._out = self._out.copy()\n"
                     "        self._out[[n for n, *_ in OUTPUT_SPEC].index('cage_speed')] *= 2.0\n")
    fmu2 = _build("BearingFMU", {"bearing_fmu": v2}, "bearing_fmu", tmp_path / "v2")
    code = r"""
import json, sys
import bearing_core.session.cosim
bearing_core.session.cosim.P_LIMIT = 1.0
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
res = {}
fs = []
for tag, path in (("v1", sys.argv[1]), ("v2", sys.argv[2])):
    md = read_model_description(path)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    f = FMU2Slave(guid=md.guid, unzipDirectory=extract(path), modelIdentifier="BearingFMU", instanceName=tag)
    f.instantiate(); f.setupExperiment(startTime=0.0); f.enterInitializationMode(); f.exitInitializationMode()
    fs.append((tag, f, vr))
    res[tag] = []
for k in range(5):
    for tag, f, vr in fs:
        st = f.doStep(k * 1e-3, 1e-3)
        res[tag].append((int(st or 0), f.getReal([vr["cage_speed"]])[0]))
for tag, f, vr in fs:
    f.terminate(); f.freeInstance()
print("RESULT", json.dumps(res))
"""
    r = subprocess.run([sys.executable, "-c", code, str(built["fmu"]), str(fmu2)], capture_output=True, text=True,
                       env=dict(os.environ, BEARING_FMU_CACHE=built["cache"], PYTHONPATH=str(HERE.parent)),
                       timeout=600)
    assert r.returncode == 0, r.stderr[-3000:]
    import json
    res = json.loads(r.stdout.split("RESULT", 1)[1])
    assert all(s == 0 for s, _ in res["v1"] + res["v2"])
    # the two slaves share bearing_core (same code hash: one code copy, one kernel cache) but not the GUID;
    # kernels compiled in the process and kernels loaded from the cache may round differently (1e-13 at the
    # first step, growing over the steps), hence 1e-5
    cfg = [json.loads(zipfile.ZipFile(p).read("resources/model.json")) for p in (built["fmu"], fmu2)]
    assert cfg[0]["code_hash"] == cfg[1]["code_hash"] and cfg[0]["guid"] != cfg[1]["guid"]
    for (_, a), (_, b) in zip(res["v1"], res["v2"]):
        assert b == pytest.approx(2.0 * a, rel=1e-5) and a > 0


def test_read_only_unpack_and_home(built, tmp_path):
    """The FMU unpacked read-only (modes a-w), HOME unwritable (below a regular file, so that not even root
    can create ~/.cache), no BEARING_FMU_CACHE: the code is copied to a folder named by its content hash under
    TMPDIR (modes of the read-only unpack not kept) and the FMU instantiates, refuses a load case without
    equilibrium with fmi2Error (model code and numba imported) and frees cleanly."""
    ro = tmp_path / "ro"
    shutil.copytree(built["unz"], ro)
    (tmp_path / "file").write_text("")
    home = tmp_path / "file" / "home"
    tmpd = tmp_path / "tmp"
    tmpd.mkdir()
    for p in [*ro.rglob("*"), ro]:
        p.chmod(p.stat().st_mode & ~0o222)
    try:
        vr = built["vr"]
        script = f"instantiate 0\nsetup 0\nenter\nset_real {vr['Fz']} -1\nexit\nfree\n"
        e = dict(HOME=str(home), TMPDIR=str(tmpd))
        r = run_host(dict(built, cache=""), script, tmp_path, env=e, unz=ro)
        assert r.returncode == 0, r.stderr[-2000:]
        status, _, logs, _ = parse(r.stdout)
        assert status[:4] == [("instantiate", 0), ("setup", 0), ("enter", 0), ("set_real", 0)]
        assert status[4] == ("exit", 3) and any("reversed axial load" in m for _, _, m in logs)
        copies = list(tmpd.glob("bearing_fmu-*/code-*/bearing_core/session/cosim.py"))
        assert copies and copies[0].stat().st_mode & 0o200
    finally:
        for p in [ro, *ro.rglob("*")]:
            p.chmod(p.stat().st_mode | 0o200)


@pytest.mark.slow
def test_valgrind_c_host(built, tmp_path):
    """valgrind memcheck on the C host (the model process runs outside valgrind) over instantiate / set / get /
    refused calls / steps / terminate / free / process exit: no invalid read, write or free with a frame in the
    FMU's native layer, and no memory of the layer definitely lost."""
    vg = shutil.which("valgrind")
    if vg is None:
        pytest.skip("valgrind not installed")
    vr = built["vr"]
    script = (f"instantiate 1\nsetup 0\nenter\nset_real {vr['Fx']} 500\nset_string {vr['bearing']} 7218B\n"
              f"get_real {vr['Fx']}\nset_real {vr['cage_speed']} 1\nserialize\nexit\n"
              f"inputs {vr['shaft_speed']} {vr['Fz']}\noutputs {vr['cage_speed']} {vr['reaction_Fz']}\n"
              "step 0.001 314.159 3000\nstep 0.001 314.159 3000\ngetstate\nsetstate\nfreestate\n"
              "terminate\nfree\ninstantiate 0\nfree\n")
    log = tmp_path / "vg.txt"
    r = run_host(built, script, tmp_path,
                 valgrind=[vg, "--error-limit=no", "--num-callers=40", "--leak-check=full", f"--log-file={log}"],
                 timeout=900)
    assert r.returncode == 0, r.stderr[-2000:]
    status, rows, _, _ = parse(r.stdout)
    assert [s for _, s in status] == [0, 0, 0, 0, 0, 0, 3, 3, 0, 0, 0, 0, 0, 0, 0, 0]
    assert [int(x[0]) for x in rows] == [0, 0]
    text = log.read_text()
    assert "ERROR SUMMARY" in text
    assert not invalid_in_layer(text)
    assert not lost_in_layer(text), lost_in_layer(text)


def lost_in_layer(text):
    """valgrind 'definitely lost' records allocated in the FMU's native library."""
    import re
    blocks = re.split(r"\n==\d+== \n", text)
    return [b for b in blocks if "definitely lost" in b and ("BearingFMU.so" in b or "bearing_fmi2" in b)]


def invalid_in_layer(text):
    """valgrind records 'Invalid read/write/free' with a stack frame in the FMU's native library."""
    import re
    recs, cur = [], None
    for ln in text.splitlines():
        body = re.sub(r"^==\d+==\s?", "", ln)
        if body.startswith(("Invalid read", "Invalid write", "Invalid free")):
            cur = [body]
            recs.append(cur)
        elif cur is not None:
            if not body.strip():
                cur = None
            else:
                cur.append(body)
    return [r for r in recs if any("BearingFMU.so" in x or "bearing_fmi2" in x for x in r)]


@pytest.mark.slow
def test_masters_agree_on_seed000_profile(built, tmp_path):
    """Seed 000's acceleration profile (bearing_core.models.dynamics SEED000_PROFILE: 1000 rpm to 0.5 s, 10,000
    rpm/s to 10,000 rpm, held to 2 s; 7218B, Fx 1 kN, Fz 3 kN, lubricated traction, 1 ms steps, speed held
    over each step) in three masters: fmpy, libcosim (C++, libcosimpy) and the C host. The mean cage speed
    over the profile agrees within 0.1 % (the masters round communication points differently)."""
    import json
    from bearing_core.models.dynamics import read_profile
    t_pts, rpm_pts, _ = read_profile("seed000")
    h = 1e-3
    n = int(round((t_pts[-1] - t_pts[0]) / h))
    speeds = [float(np.interp(k * h, t_pts, rpm_pts)) * RPM for k in range(n)]
    vr = built["vr"]
    env = dict(os.environ, BEARING_FMU_CACHE=built["cache"])
    means = {}
    # fmpy
    spec = {"fmu": str(built["fmu"]), "params": {}, "outputs": ["cage_speed"],
            "start_inputs": {"shaft_speed": speeds[0], "Fx": 1000.0, "Fz": 3000.0},
            "steps": [[h, {"shaft_speed": w}] for w in speeds]}
    p = tmp_path / "fmpy.json"
    p.write_text(json.dumps(spec))
    r = subprocess.run([sys.executable, str(HERE / "fmu_driver.py"), str(p)], capture_output=True, text=True,
                       env=env, timeout=900)
    assert r.returncode == 0, r.stderr[-2000:]
    rows = json.loads([ln for ln in r.stdout.splitlines() if ln.startswith("RESULT ")][-1][7:])["rows"]
    assert all(x["status"] == 0 for x in rows)
    means["fmpy"] = float(np.mean([x["values"][0] for x in rows]))
    # libcosim
    p = tmp_path / "cosim.json"
    p.write_text(json.dumps({"fmu": str(built["fmu"]), "h": h, "t_end": n * h, "outputs": ["cage_speed"],
                             "inputs": {"shaft_speed": speeds[0], "Fx": 1000.0, "Fz": 3000.0}, "speeds": speeds}))
    r = subprocess.run([sys.executable, str(HERE / "libcosim_driver.py"), str(p)], capture_output=True, text=True,
                       env=env, timeout=900)
    assert r.returncode == 0, r.stderr[-2000:]
    res = json.loads([ln for ln in r.stdout.splitlines() if ln.startswith("RESULT ")][-1][7:])
    assert res["ok"]
    means["libcosim"] = float(np.mean(res["series"]["cage_speed"][-n:]))
    # C host
    lines = ["instantiate 0", "setup 0", "enter", f"set_real {vr['shaft_speed']} {speeds[0]!r}",
             f"set_real {vr['Fx']} 1000", f"set_real {vr['Fz']} 3000", "exit",
             f"inputs {vr['shaft_speed']}", f"outputs {vr['cage_speed']}"]
    lines += [f"step {h!r} {w!r}" for w in speeds] + ["terminate", "free"]
    r = run_host(built, "\n".join(lines) + "\n", tmp_path)
    assert r.returncode == 0, r.stderr[-2000:]
    _, crow, _, _ = parse(r.stdout)
    assert all(x[0] == 0 for x in crow) and len(crow) == n
    means["c"] = float(np.mean([x[3] for x in crow]))
    print("mean cage speed [rpm]:", {k: v / RPM for k, v in means.items()})
    for k in ("libcosim", "c"):
        assert abs(means[k] / means["fmpy"] - 1) < 1e-3, means
