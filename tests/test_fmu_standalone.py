"""The standalone FMU (`build_fmu.py --standalone`): its own Python runtime and precompiled kernels in
resources/, no path of the build machine inside, and runs where the build's Python, venv, checkout and HOME are
hidden (a mount namespace with tmpfs over them: `unshare -m`, root only) in a C master and in fmpy on another
Python version.

The build takes minutes (kernels compiled for numba's generic target, the standard library and packages compiled
to bytecode, 133 MiB zipped), more than the suite's budget: these tests run with BEARING_TEST_STANDALONE=1 (build
here) or BEARING_TEST_STANDALONE_FMU=<file> (one built from the same sources by `build_fmu.py --standalone`)."""
import json
import os
import shutil
import subprocess
import sys
import time
import zipfile
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))
from test_native_host import RPM, parse, seed000_short  # noqa: E402
from test_fmu_process import other_master, _other_python  # noqa: E402,F401

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def standalone(tmp_path_factory):
    if shutil.which(os.environ.get("CC", "gcc")) is None:
        pytest.skip("no C compiler")
    sys.path.insert(0, str(ROOT))
    from bearing_cosim import fmu_build
    from fmpy import read_model_description
    given = os.environ.get("BEARING_TEST_STANDALONE_FMU")
    if not given and os.environ.get("BEARING_TEST_STANDALONE") != "1":
        pytest.skip("standalone build takes minutes: set BEARING_TEST_STANDALONE=1 or BEARING_TEST_STANDALONE_FMU")
    d = tmp_path_factory.mktemp("standalone")
    fmu = Path(given) if given else fmu_build.build(d / "dist", standalone=True)
    unz = d / "unz"
    with zipfile.ZipFile(fmu) as z:
        z.extractall(unz)          # Python's zipfile keeps no modes: the runtime runs through the loader
    host = d / "host"
    subprocess.run([os.environ.get("CC", "gcc"), "-std=gnu99", "-O2", "-o", str(host),
                    str(HERE / "c_host" / "host.c"), "-ldl"], check=True)
    md = read_model_description(str(fmu))
    return {"fmu": fmu, "unz": unz, "host": host, "guid": md.guid, "dir": d,
            "vr": {v.name: v.valueReference for v in md.modelVariables}, "build_paths": fmu_build._build_paths()}


def test_contents_and_no_build_path(standalone):
    """The FMU carries libpython, a standard library, numpy, scipy, numba, llvmlite, the executable that runs
    them and the precompiled kernels (x86-64-v3 and generic targets); no file names a path of the build machine (the Python
    home, the venv, the checkout). Sizes printed."""
    unz = standalone["unz"]
    res = unz / "resources"
    cfg = json.loads((res / "model.json").read_text())
    assert [t["name"] for t in cfg["precompiled"]["targets"]] == ["x86-64-v3", "generic"]
    assert cfg["precompiled"]["kernels"] > 10
    assert list(res.glob("code/bearing_core/**/__pycache__/*.nbc"))
    assert not (res / "build_python.txt").exists()
    site = next(res.glob("python/lib/python3.*/site-packages"))
    for pkg in ("numpy", "scipy", "numba", "llvmlite"):
        assert (site / pkg / "__init__.py").is_file(), pkg
    assert (res / "python" / "bin" / "python3").is_file() and list(res.glob("python/lib/libpython3*.so*"))
    hits = []
    pats = [p.encode() for p in standalone["build_paths"]]
    for f in unz.rglob("*"):
        if f.is_file():
            data = f.read_bytes()
            hits += [(str(f.relative_to(unz)), p.decode()) for p in pats if p in data]
    assert not hits, hits[:20]
    size = sum(f.stat().st_size for f in unz.rglob("*") if f.is_file())
    print(f"standalone FMU: {standalone['fmu'].stat().st_size / 2**20:.1f} MiB zipped, {size / 2**20:.1f} MiB "
          f"unpacked, {cfg['precompiled']['kernels']} precompiled kernels")


def _sandbox(cmd, tmp, keep=(), env=None, timeout=600):
    """Runs cmd in a new mount namespace where tmpfs hides the build's Python home, its venv, the checkout and
    HOME (paths in keep are bound back in after the masking; tmp holds their temporary mount points)."""
    if os.geteuid() != 0 or shutil.which("unshare") is None:
        pytest.skip("the sandbox needs root and unshare")
    hide = {os.path.realpath(h) for h in (sys.base_prefix, sys.prefix, str(ROOT), os.path.expanduser("~"))
            if os.path.isdir(h)}
    hide = sorted(h for h in hide if not any(h.startswith(o + "/") for o in hide))   # outermost only
    kdir = Path(tmp) / "sandbox_keep"
    lines = ["set -e", "mount --make-rprivate /"]
    for k, p in enumerate(keep):
        (kdir / str(k)).mkdir(parents=True, exist_ok=True)
        lines += [f"mount --bind '{p}' '{kdir / str(k)}'"]
    lines += [f"mount -t tmpfs none '{h}'" for h in hide]
    for k, p in enumerate(keep):
        lines += [f"mkdir -p '{p}'", f"mount --bind '{kdir / str(k)}' '{p}'"]
    lines += ['exec "$@"']
    e = {"PATH": "/usr/bin:/bin", "HOME": os.path.expanduser("~"), "LANG": "C.UTF-8"}
    e.update(env or {})
    return subprocess.run(["unshare", "-m", "sh", "-c", "\n".join(lines), "sandbox", *map(str, cmd)],
                          capture_output=True, text=True, env=e, timeout=timeout)


def test_sandbox_c_host_seed000_segment(standalone, tmp_path):
    """In the sandbox (no build Python, venv, checkout or HOME; an empty HOME, so an empty cache), the C host
    runs the shortened seed 000 profile on the standalone FMU: every step OK, the reaction equals the axial
    load (0.5 %), the cage follows the shaft; instantiate + initialise + first step printed (the kernels come
    from the FMU, so no compilation)."""
    vr = standalone["vr"]
    steps = seed000_short(t_end=0.15)
    lines = ["instantiate 0", "setup 0", "enter", f"set_real {vr['shaft_speed']} {steps[0][1]!r}",
             f"set_real {vr['Fx']} 1000", f"set_real {vr['Fz']} 3000", "exit",
             "inputs " + " ".join(str(vr[k]) for k in ("shaft_speed", "Fx", "Fz")),
             "outputs " + " ".join(str(vr[k]) for k in ("cage_speed", "reaction_Fz"))]
    lines += [f"step {h!r} {w!r} 1000 3000" for h, w in steps] + ["terminate", "free"]
    script = tmp_path / "script.txt"
    script.write_text("\n".join(lines) + "\n")
    t0 = time.perf_counter()
    r = _sandbox([standalone["host"], standalone["unz"], "BearingFMU", standalone["guid"], script], tmp_path)
    wall = time.perf_counter() - t0
    assert r.returncode == 0, (r.returncode, r.stdout[-2000:], r.stderr[-2000:])
    status, rows, logs, _ = parse(r.stdout)
    assert all(s == 0 for _, s in status), (status, logs)
    rows = np.array(rows)
    assert rows.shape == (len(steps), 5) and np.all(rows[:, 0] == 0) and np.all(np.isfinite(rows))
    assert abs(-rows[50:, 4].mean() / 3000 - 1) < 0.005 and rows[-1, 3] > rows[0, 3] > 0
    print(f"sandbox C host: {len(steps)} steps in {wall:.1f} s (process start to exit)")


def test_sandbox_fmpy_other_python(standalone, other_master, tmp_path):
    """In the sandbox, fmpy on another Python version than the build's runs the same segment: every step OK and
    the cage speeds equal the C host's bit for bit (same kernels, same inputs)."""
    vr = standalone["vr"]
    steps = seed000_short(t_end=0.05)
    spec = {"fmu": str(standalone["fmu"]), "params": {}, "outputs": ["cage_speed"],
            "start_inputs": {"shaft_speed": steps[0][1], "Fx": 1000.0, "Fz": 3000.0},
            "steps": [[h, {"shaft_speed": w}] for h, w in steps]}
    p = tmp_path / "spec.json"
    p.write_text(json.dumps(spec))
    base = Path(os.path.realpath(other_master)).parent.parent
    r = _sandbox([other_master, HERE / "fmu_driver.py", p], tmp_path, keep=[base, HERE])
    assert r.returncode == 0, (r.returncode, r.stdout[-2000:], r.stderr[-2000:])
    rows = json.loads([ln for ln in r.stdout.splitlines() if ln.startswith("RESULT ")][-1][7:])["rows"]
    assert all(x["status"] == 0 for x in rows) and len(rows) == len(steps)
    lines = ["instantiate 0", "setup 0", "enter", f"set_real {vr['shaft_speed']} {steps[0][1]!r}",
             f"set_real {vr['Fx']} 1000", f"set_real {vr['Fz']} 3000", "exit", f"inputs {vr['shaft_speed']}",
             f"outputs {vr['cage_speed']}"] + [f"step {h!r} {w!r}" for h, w in steps] + ["terminate", "free"]
    script = tmp_path / "script.txt"
    script.write_text("\n".join(lines) + "\n")
    r2 = _sandbox([standalone["host"], standalone["unz"], "BearingFMU", standalone["guid"], script], tmp_path)
    assert r2.returncode == 0, r2.stderr[-2000:]
    _, crow, _, _ = parse(r2.stdout)
    assert [x[3] for x in crow] == [x["values"][0] for x in rows]
