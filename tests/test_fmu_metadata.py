"""Metadata, enumerations, geometry parameters and packaging of the bearing FMU (FMI 2.0, modelDescription.xml as
the FMI 2.0.4 standard defines it; checked by fmpy's validator and by the independent FMU Manipulation Toolbox)."""
import math
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path
from xml.etree import ElementTree as ET

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))
from test_fmu import drive, fmu  # noqa: E402,F401  (session fixture: the FMU built once)


def _md(path):
    with zipfile.ZipFile(path) as z:
        return ET.fromstring(z.read("modelDescription.xml"))


def _var(md, name):
    return md.find(f"ModelVariables/ScalarVariable[@name='{name}']")


def _items(md, name):
    st = md.find(f"TypeDefinitions/SimpleType[@name='{_var(md, name).find('Enumeration').get('declaredType')}']")
    return {it.get("name"): int(it.get("value")) for it in st.find("Enumeration")}


def test_fmpy_validate_no_messages(fmu):
    from fmpy.validation import validate_fmu
    assert validate_fmu(fmu["path"]) == []


def test_fmutool_check_no_messages(fmu):
    """fmutool -check (FMU Manipulation Toolbox, pip fmu-manipulation-toolbox): generic conformity (XSD) and
    semantic checks against FMI 2.0: no warning or error."""
    exe = shutil.which("fmutool") or str(Path(sys.executable).parent / "fmutool")
    if not Path(exe).exists():
        pytest.skip("fmu-manipulation-toolbox (fmutool) is not installed")
    r = subprocess.run([exe, "-input", fmu["path"], "-check"], capture_output=True, text=True, timeout=120)
    text = r.stdout + r.stderr
    assert r.returncode == 0, text
    bad = [ln for ln in text.splitlines() if ln.split("|")[0].strip() not in ("INFO", "")]
    assert not bad, text
    assert "compliant with FMI-2.0" in text and "No semantic error" in text


def test_metadata_units_and_structure(fmu):
    """Version/license from pyproject.toml; display units rpm (factor 30/pi) and degC (offset -273.15) as FMI 2.0
    DisplayUnit (display = factor * value + offset, FMI 2.0.4 section 2.2.2); quantities; Modelica unit syntax;
    outputs without direct feedthrough (dependencies="") but the ring's reactions and pose, which depend on the ring
    inputs (docs/fmu.md "Stiffness and directional derivatives")."""
    import tomllib
    proj = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    md = _md(fmu["path"])
    assert md.get("version") == proj["version"] and md.get("license") == proj["license"]
    assert md.get("copyright") and md.get("author") and md.get("author") != "bearing-tribodynamics"
    units = {u.get("name"): u for u in md.find("UnitDefinitions")}
    rpm = units["rad/s"].find("DisplayUnit[@name='rpm']")
    assert abs(float(rpm.get("factor")) - 30.0 / math.pi) < 1e-12
    degc = units["K"].find("DisplayUnit[@name='degC']")
    assert float(degc.get("factor", 1.0)) == 1.0 and float(degc.get("offset")) == -273.15
    for u in units:   # Modelica unit syntax: no '^', no spaces
        assert "^" not in u and " " not in u, u
    assert "m3/s" in units
    sp = _var(md, "shaft_speed").find("Real")
    assert sp.get("unit") == "rad/s" and sp.get("displayUnit") == "rpm" and sp.get("quantity") == "AngularVelocity"
    assert _var(md, "temperature_ball").find("Real").get("displayUnit") == "degC"
    assert _var(md, "friction_torque").find("Real").get("quantity") == "Torque"
    assert float(_var(md, "reaction_Fx").find("Real").get("nominal")) > 0
    outs = md.find("ModelStructure/Outputs")
    names = [sv.get("name") for sv in md.find("ModelVariables")]
    ring = {"reaction_Fx", "reaction_Fy", "reaction_Fz", "reaction_Mx", "reaction_My", "ir_x", "ir_y", "ir_z",
            "ir_tx", "ir_ty"}
    ring_inputs = sorted(["Fx", "Fy", "Fz", "Mx", "My", "dx", "dy", "dz", "tx", "ty"])
    assert len(outs) > 0
    for u in outs:   # the ring outputs depend on the ring inputs (fmi2GetDirectionalDerivative); no other feedthrough
        name = names[int(u.get("index")) - 1]
        deps = sorted(names[int(i) - 1] for i in u.get("dependencies").split())
        assert deps == (ring_inputs if name in ring else []), (name, deps)


def test_guid_is_a_content_hash(fmu, tmp_path):
    """Two builds of the same sources carry the same GUID; another start value gives another GUID."""
    from build_fmu import build, build_variant
    g1 = _md(fmu["path"]).get("guid")
    g2 = _md(build(tmp_path / "b2")).get("guid")
    assert g1 == g2 and len(g1) == 38
    g3 = _md(build_variant("BearingFMUCoulomb", {"traction_model": "coulomb"}, tmp_path / "b3")).get("guid")
    assert g3 != g1


def test_enumerations_declared_for_choices(fmu):
    """Every choice has an FMI Enumeration (drop-down) beside its String parameter, starting at the same item."""
    md = _md(fmu["path"])
    for name, items in (("traction_model", {"lubricated", "coulomb", "kalker"}), ("coupling", {"load", "displacement"}),
                        ("outer_mounting", {"fixed", "elastic"}),
                        ("integrator", {"auto", "adaptive", "implicit", "rk4"}), ("bearing", {"7218B", "7008-ma2023"})):
        ename = "bearing_preset" if name == "bearing" else f"{name}_choice"
        en = _var(md, ename).find("Enumeration")
        assert en is not None and items <= set(_items(md, ename))
        start = _var(md, name).find("String").get("start")
        assert _items(md, ename)[start] == int(en.get("start"))
    assert _var(md, "number_of_balls").find("Integer").get("min") == "0"


def test_enumerations_settable_by_value(fmu, tmp_path):
    """bearing_preset and traction_model_choice set through fmi2SetInteger (item values, as SSP runners do) give
    exactly the run of the String parameters with the same items; an out-of-range item value and a conflicting
    String/Enumeration pair are refused with fmi2Error naming the parameters."""
    md = _md(fmu["path"])
    pre, tm = _items(md, "bearing_preset"), _items(md, "traction_model_choice")
    inp = {"shaft_speed": 500 * math.pi / 30, "Fx": 200.0, "Fz": 1000.0}
    spec = {"start_inputs": inp, "steps": [[1e-3, inp]] * 5, "outputs": ["cage_speed", "friction_torque"]}
    a = drive(fmu, dict(spec, params={"bearing_preset": pre["7008-ma2023"], "traction_model_choice": tm["coulomb"]}),
              tmp_path, "a.json")
    b = drive(fmu, dict(spec, params={"bearing": "7008-ma2023", "traction_model": "coulomb"}), tmp_path, "b.json")
    # the same run to round-off: two FMU processes running the same kernels have differed by ~1e-13
    # relative in friction_torque (an adaptive step decision can amplify that, so 1e-9 is kept loose enough)
    va, vb = np.array([r["values"] for r in a["rows"]]), np.array([r["values"] for r in b["rows"]])
    assert a["init_error"] is None and va.shape == vb.shape
    assert np.allclose(va, vb, rtol=1e-9, atol=1e-12), (va, vb)
    c = drive(fmu, dict(spec, params={"bearing": "7218B"}), tmp_path, "c.json")
    vc = np.array([r["values"] for r in c["rows"]])
    assert not np.allclose(va, vc, rtol=1e-3)
    bad = drive(fmu, dict(spec, params={"traction_model_choice": 9}), tmp_path, "bad.json")
    assert bad["init_error"] and "traction_model_choice = 9 is not an item value" in bad["log"]
    both = drive(fmu, dict(spec, params={"bearing": "wan-105", "bearing_preset": pre["7008-ma2023"]}), tmp_path,
                 "both.json")
    assert both["init_error"] and "bearing_preset" in both["log"] and "wan-105" in both["log"]


def test_geometry_parameters(fmu, tmp_path):
    """number_of_balls / ball_diameter override the bearing definition: a 7218B with Z = 12 instead of 16 carries
    the same load on fewer balls, so its largest contact load rises (Stribeck: Q_max ~ 1/Z); impossible geometry
    is refused with fmi2Error naming the parameter and its allowed range."""
    inp = {"shaft_speed": 1000 * math.pi / 30, "Fx": 1000.0, "Fz": 3000.0}
    spec = {"start_inputs": inp, "steps": [[1e-3, inp]] * 2, "outputs": ["Q_i_max"]}
    z16 = drive(fmu, dict(spec, params={}), tmp_path, "z16.json")
    z12 = drive(fmu, dict(spec, params={"number_of_balls": 12}), tmp_path, "z12.json")
    ratio = z12["rows"][-1]["values"][0] / z16["rows"][-1]["values"][0]
    assert 1.2 < ratio < 1.45, ratio     # 16/12 = 1.33 with the load shared alike
    for params, name in (({"number_of_balls": 40}, "number_of_balls"), ({"ball_diameter": 0.07}, "ball_diameter"),
                         ({"inner_groove_conformity": 0.45}, "inner_groove_conformity")):
        bad = drive(fmu, dict(spec, params=params), tmp_path, f"{name}.json")
        assert bad["init_error"] and f"{name} = " in bad["log"] and "allowed" in bad["log"], bad["log"][-600:]


def _cli(*args, cwd=None):
    import os
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    return subprocess.run([sys.executable, "-m", "bearing_cosim.cli", *args], capture_output=True, text=True,
                          env=env, cwd=cwd, timeout=300)


def test_cli_build_and_validate_fmu(tmp_path):
    """`bearing build-fmu` builds from the package's sources (any working directory); `bearing validate-fmu`
    prints fmpy's verdict, exit 0 on a valid FMU and 1 with the problem on a broken one."""
    r = _cli("build-fmu", "--dest", str(tmp_path / "d"), cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    fmu = tmp_path / "d" / "BearingFMU.fmu"
    r = _cli("validate-fmu", str(fmu))
    assert r.returncode == 0 and "valid" in r.stdout, r.stdout + r.stderr
    bad = tmp_path / "bad.fmu"
    bad.write_text("not a zip")
    r = _cli("validate-fmu", str(bad))
    assert r.returncode == 1 and "problem" in r.stdout


def test_wheel_and_fmu_carry_the_same_sources(fmu, tmp_path):
    """`pip wheel --no-deps .` gives a wheel with the FMU sources (slave, model process, launcher, native C layer)
    as package data of bearing_cosim, the build module and the `fmu` extra; every source file of
    bearing_cosim/fmu_src is in the wheel byte for byte, the FMU built from the tree carries the same bytes, and
    the repository holds no symbolic link (git mode 120000)."""
    r = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(tmp_path), str(ROOT)],
                       capture_output=True, text=True, timeout=600)
    if r.returncode != 0 and ("Could not find a version" in r.stderr or "No matching distribution" in r.stderr):
        pytest.skip("build backend (setuptools>=77) not available offline: " + r.stderr[-300:])
    assert r.returncode == 0, r.stderr[-2000:]
    whl = zipfile.ZipFile(next(tmp_path.glob("bearing_tribodynamics-*.whl")))
    names = set(whl.namelist())
    src = ROOT / "bearing_cosim" / "fmu_src"
    files = [f for f in sorted(src.rglob("*")) if f.is_file() and "__pycache__" not in f.parts]
    assert {"bearing_fmu.py", "native/bearing_fmi2.c", "native/fmi2_min.h", "native/model_process.py",
            "native/launch.sh"} <= {f.relative_to(src).as_posix() for f in files}
    for f in files:
        name = "bearing_cosim/fmu_src/" + f.relative_to(src).as_posix()
        assert name in names and whl.read(name) == f.read_bytes(), name
    assert "bearing_cosim/fmu_build.py" in names and "bearing_core/bearing/presets/7218B.json" in names
    meta = next(n for n in names if n.endswith(".dist-info/METADATA"))
    text = whl.read(meta).decode()
    assert "Provides-Extra: fmu" in text and "Requires-Dist: fmpy" in text
    with zipfile.ZipFile(fmu["path"]) as z:
        pairs = {"resources/code/bearing_fmu.py": "bearing_fmu.py",
                 "resources/model_process.py": "native/model_process.py", "resources/launch.sh": "native/launch.sh",
                 "resources/native/bearing_fmi2.c": "native/bearing_fmi2.c",
                 "resources/native/fmi2_min.h": "native/fmi2_min.h"}
        for in_fmu, in_pkg in pairs.items():
            assert z.read(in_fmu) == whl.read("bearing_cosim/fmu_src/" + in_pkg), in_fmu
    if shutil.which("git") and (ROOT / ".git").exists():
        ls = subprocess.run(["git", "-C", str(ROOT), "ls-files", "-s"], capture_output=True, text=True).stdout
        links = [ln for ln in ls.splitlines() if ln.startswith("120000")]
        assert not links, links


def test_documentation_and_osp_model_description(fmu):
    """documentation/index.html lists every variable with its unit and start value; the OSP model description
    (OSP-IS 1.0) groups shaft speed with friction torque as an AngularMechanicalPort and forces with displacements
    as LinearMechanicalQuasiPorts, each variable an existing FMU variable with its FMU unit."""
    md = _md(fmu["path"])
    with zipfile.ZipFile(fmu["path"]) as z:
        html = z.read("documentation/index.html").decode()
        osp = ET.fromstring(z.read("documentation/BearingFMU_OspModelDescription.xml"))
    for sv in md.find("ModelVariables"):
        assert f"<td>{sv.get('name')}</td>" in html
    assert "<td>rad/s (display rpm)</td>" in html
    ns = {"o": "https://open-simulation-platform.com/OspModelDescription/1.0.0"}
    port = osp.find("o:VariableGroups/o:AngularMechanicalPort", ns)
    assert [v.get("ref") for v in port.findall("o:Torque/o:Variable", ns)] == ["friction_torque"]
    assert [v.get("ref") for v in port.findall("o:AngularVelocity/o:Variable", ns)] == ["shaft_speed"]
    quasi = osp.findall("o:VariableGroups/o:LinearMechanicalQuasiPort", ns)
    assert quasi and all(len(q.findall("o:Force/o:Variable", ns)) == len(q.findall("o:LinearDisplacement/o:Variable",
                                                                                    ns)) == 3 for q in quasi)
    units = {u.get("name") for u in osp.find("o:UnitDefinitions", ns)}
    for v in osp.iter(f"{{{ns['o']}}}Variable"):
        assert _var(md, v.get("ref")).find("Real").get("unit") == v.get("unit") and v.get("unit") in units
    assert (Path(fmu["path"]).parent / "BearingFMU_OspModelDescription.xml").is_file()   # next to the FMU (libcosim)


def test_reference_results_reproduce(fmu, tmp_path, monkeypatch):
    """build --with-reference ships the FMI cross-check files (<id>_in.csv, _ref.opt, _ref.csv; default experiment
    0-1 s, 1 ms steps, seed 000 acceleration profile) and a plot; rerunning the experiment from those files with
    fmpy on the FMU reproduces _ref.csv (same master, deterministic: relative difference < 1e-9); libcosim driven
    by the same inputs gives the same mean cage speed (0.5 %) and friction torque (2 %) over 0.1-1 s."""
    import numpy as np
    from build_fmu import build
    monkeypatch.setenv("BEARING_FMU_CACHE", fmu["cache"])
    path = build(tmp_path / "ref", reference=True)
    names = set(zipfile.ZipFile(path).namelist())
    for f in ("BearingFMU_in.csv", "BearingFMU_ref.opt", "BearingFMU_ref.csv", "BearingFMU_ref.png", "index.html"):
        assert f"documentation/{f}" in names
    assert _md(path).get("guid") == _md(fmu["path"]).get("guid")    # documentation does not change the model
    d = tmp_path / "ref"
    code = ("import sys, numpy as np, os; from bearing_cosim.fmu_reference import simulate_reference as s; "
            "r = s(sys.argv[1], sys.argv[2], sys.argv[3]); np.save(sys.argv[4], r); sys.stdout.flush(); os._exit(0)")
    import os
    env = dict(os.environ, PYTHONPATH=str(ROOT), BEARING_FMU_CACHE=fmu["cache"])
    r = subprocess.run([sys.executable, "-c", code, str(path), str(d / "BearingFMU_in.csv"),
                        str(d / "BearingFMU_ref.opt"), str(tmp_path / "again.npy")], capture_output=True, text=True,
                       env=env, timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    again = np.load(tmp_path / "again.npy")
    ref = np.genfromtxt(d / "BearingFMU_ref.csv", delimiter=",", names=True)
    assert len(ref) == len(again) == 1001
    for k in ref.dtype.names:
        assert np.allclose(again[k], ref[k], rtol=1e-9, atol=1e-12 * np.abs(ref[k]).max()), k
    # a second master: libcosim (C++) with the same inputs (speed from _in.csv at the start of each step, held).
    # The cage motion is chaotic and the masters round time differently, so trajectories differ in detail:
    # compare means over 0.1-1 s (docs/fmu.md: masters agree within 0.3 % on means)
    import json
    t_in = np.genfromtxt(d / "BearingFMU_in.csv", delimiter=",", names=True)
    speeds = np.interp(ref["time"][:-1], t_in["time"], t_in["shaft_speed"])
    outs = ["cage_speed", "friction_torque"]
    spec = {"fmu": str(path), "h": 1e-3, "t_end": 1.0, "outputs": outs, "speeds": speeds.tolist(),
            "inputs": {"shaft_speed": float(speeds[0]), "Fx": 1000.0, "Fz": 3000.0}}
    (tmp_path / "lc.json").write_text(json.dumps(spec))
    r = subprocess.run([sys.executable, str(HERE / "libcosim_driver.py"), str(tmp_path / "lc.json")],
                       capture_output=True, text=True, env=env, timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    lc = json.loads([ln for ln in r.stdout.splitlines() if ln.startswith("RESULT ")][-1][7:])
    assert lc["ok"]
    win = ref["time"][1:] > 0.1
    for k, tol in (("cage_speed", 0.005), ("friction_torque", 0.02)):
        a, b = np.asarray(lc["series"][k])[-len(ref) + 1:][win].mean(), ref[k][1:][win].mean()
        print(k, "libcosim", a, "fmpy reference", b)
        assert abs(a / b - 1) < tol, (k, a, b)
