"""The FMU's model process: faults stay in it (kill -9, SIGSTOP, master death), instances run in parallel
from two master threads, a Python master of another version, and a clear refusal when no Python fits.
Real processes throughout: the C host (tests/c_host/host.c) and fmpy in fresh interpreters."""
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from test_native_host import CLEAN_ENV, RPM, built, parse  # noqa: E402,F401  (module fixture: FMU + C host)


def children(pid):
    """Processes whose parent is pid (from /proc)."""
    out = []
    for d in Path("/proc").iterdir():
        if d.name.isdigit():
            try:
                fields = (d / "stat").read_text().rsplit(")", 1)[1].split()
            except OSError:
                continue
            if int(fields[1]) == pid:
                out.append(int(d.name))
    return out


def gone(pid):
    """The process has ended (no /proc entry, or a zombie waiting for its reaper)."""
    try:
        return (Path("/proc") / str(pid) / "stat").read_text().rsplit(")", 1)[1].split()[0] == "Z"
    except OSError:
        return True


def start_host(b, script, tmp_path, env=None):
    p = tmp_path / "script.txt"
    p.write_text(script)
    e = dict(CLEAN_ENV, BEARING_FMU_CACHE=b["cache"])
    e.update(env or {})
    return subprocess.Popen([str(b["host"]), str(b["unz"]), "BearingFMU", b["guid"], str(p)], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, env=e)


def long_run(b, n):
    vr = b["vr"]
    lines = ["instantiate 0", "setup 0", "enter", "exit", f"inputs {vr['shaft_speed']}",
             f"outputs {vr['cage_speed']}"]
    lines += [f"step 0.001 {1000 * RPM!r}"] * n + ["terminate", "free"]
    return "\n".join(lines) + "\n"


def read_rows_until(proc, n_rows):
    """stdout lines of the host until its n-th ROW line."""
    lines, rows = [], 0
    while rows < n_rows:
        ln = proc.stdout.readline()
        assert ln, "the host ended early: " + proc.stderr.read()[-2000:]
        lines.append(ln)
        rows += ln.startswith("ROW ")
    return lines


def finish(proc, timeout=60):
    """The rest of the host's stdout (through the reader already used: communicate() would bypass the lines
    it buffered), its stderr, after the host ended."""
    out = proc.stdout.read()
    err = proc.stderr.read()
    proc.wait(timeout=timeout)
    return out, err


def model_pid(host_pid):
    kids = children(host_pid)
    assert len(kids) == 1, kids
    return kids[0]


def test_kill_9_mid_run(built, tmp_path):
    """kill -9 of the model process between steps of a C master: the next fmi2DoStep returns fmi2Error
    within a second, the logger names the signal, every later call returns fmi2Error at once, fmi2FreeInstance
    returns, the master exits 0 and no process of the FMU is left."""
    proc = start_host(built, long_run(built, 400), tmp_path)
    head = read_rows_until(proc, 20)
    pid = model_pid(proc.pid)
    os.kill(pid, signal.SIGKILL)
    t0 = time.perf_counter()
    out, err = finish(proc)
    wall = time.perf_counter() - t0
    assert proc.returncode == 0, err[-2000:]
    status, rows, logs, _ = parse("".join(head) + out)
    sts = [int(r[0]) for r in rows]
    k = sts.index(3)
    assert 20 <= k < 300 and all(s == 0 for s in sts[:k]) and all(s == 3 for s in sts[k:]), sts
    assert len(rows) == 400 and wall < 5.0
    assert any("killed by signal 9" in m for s, c, m in logs if s == 3), logs[:5]
    assert ("terminate", 3) in status
    assert gone(pid) and children(proc.pid) == []


def test_sigstop_errors_after_the_timeout(built, tmp_path):
    """SIGSTOP of the model process (it stops answering): fmi2DoStep returns fmi2Error after
    BEARING_FMU_STEP_TIMEOUT (3 s here), the logger says so, the stopped process is killed and reaped, and the
    master goes on to its end (later calls fmi2Error) and exits 0."""
    proc = start_host(built, long_run(built, 60), tmp_path, env={"BEARING_FMU_STEP_TIMEOUT": "3"})
    head = read_rows_until(proc, 10)
    pid = model_pid(proc.pid)
    t0 = time.perf_counter()
    os.kill(pid, signal.SIGSTOP)
    try:
        ln = ""
        while not ln.startswith("ROW 3 "):   # rows the host printed before the stop come first
            ln = proc.stdout.readline()
            assert ln, "the host ended early: " + proc.stderr.read()[-2000:]
            head.append(ln)
        waited = time.perf_counter() - t0
        out, err = finish(proc)
    finally:
        if not gone(pid):
            os.kill(pid, signal.SIGKILL)
    assert proc.returncode == 0, err[-2000:]
    _, rows, logs, _ = parse("".join(head) + out)
    sts = [int(r[0]) for r in rows]
    k = sts.index(3)
    assert all(s == 3 for s in sts[k:]) and k >= 10 and len(rows) == 60
    assert 2.5 < waited < 10.0, waited
    assert any("did not answer within 3 s" in m for s, c, m in logs if s == 3)
    assert gone(pid)


def test_master_death_ends_the_model_process(built, tmp_path):
    """kill -9 of the master mid-run: its model process notices (its parent changes) and exits within a few
    seconds, leaving no orphan."""
    proc = start_host(built, long_run(built, 2000), tmp_path)
    read_rows_until(proc, 5)
    pid = model_pid(proc.pid)
    proc.kill()
    proc.communicate(timeout=30)
    t0 = time.perf_counter()
    while not gone(pid) and time.perf_counter() - t0 < 10:
        time.sleep(0.05)
    assert gone(pid), f"model process {pid} still alive {time.perf_counter() - t0:.1f} s after its master died"


TWO_THREADS = r"""
import json, sys, threading, time
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
path, n = sys.argv[1], int(sys.argv[2])
md = read_model_description(path)
vr = {v.name: v.valueReference for v in md.modelVariables}
unz = extract(path)
def make(name):
    f = FMU2Slave(guid=md.guid, unzipDirectory=unz, modelIdentifier="BearingFMU", instanceName=name)
    f.instantiate(); f.setupExperiment(startTime=0.0); f.enterInitializationMode(); f.exitInitializationMode()
    for k in range(5):   # warm: kernels loaded, first-step work done
        f.doStep(k * 1e-3, 1e-3)
    return f
def run(f, out):
    for k in range(5, 5 + n):
        a = time.perf_counter()
        f.doStep(k * 1e-3, 1e-3)
        out.append((a, time.perf_counter(), f.getReal([vr["cage_speed"]])[0]))
w = make("w")   # the same steps once before: every kernel compiled into the cache, so that a, b and c run the
run(w, [])      # same machine code (freshly compiled and cached kernels may round differently)
w.terminate(); w.freeInstance()
fs = [make("a"), make("b")]
one = []
c = make("c")
t0 = time.perf_counter(); run(c, one); t_one = time.perf_counter() - t0
c.terminate(); c.freeInstance()
res = [[], []]
th = [threading.Thread(target=run, args=(f, r)) for f, r in zip(fs, res)]
t0 = time.perf_counter()
for t in th: t.start()
for t in th: t.join()
t_two = time.perf_counter() - t0
for f in fs: f.terminate(); f.freeInstance()
print("RESULT", json.dumps({"one": t_one, "two": t_two, "a": res[0], "b": res[1], "c": one}))
"""


def test_two_instances_from_two_threads(built, tmp_path):
    """Two instances stepped from two threads of one fmpy master run at the same time (their fmi2DoStep
    calls overlap: one model process each, no shared lock) and give results identical to each other and to a
    third instance stepped alone. The throughput ratio (two threads / one) is printed; on an idle machine with
    two cores it is near 2."""
    r = subprocess.run([sys.executable, "-c", TWO_THREADS, str(built["fmu"]), "150"], capture_output=True,
                       text=True, env=dict(os.environ, BEARING_FMU_CACHE=built["cache"]), timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    res = json.loads(r.stdout.split("RESULT", 1)[1])
    a, b = res["a"], res["b"]
    assert [x[2] for x in a] == [x[2] for x in b] == [x[2] for x in res["c"]]
    # overlap: the share of a's steps during which one of b's steps was in flight
    overlap = sum(any(sb < ea and sa < eb for sb, eb, _ in b) for sa, ea, _ in a) / len(a)
    print(f"two-thread throughput ratio {2 * res['one'] / res['two']:.2f}, overlapping steps {overlap:.0%}")
    assert overlap > 0.5


def _python_without(module):
    for p in sorted(Path("/root/.pyenv/versions").glob("3.*/bin/python")) + [Path("/usr/bin/python3")]:
        if p.is_file() and subprocess.run([str(p), "-c", f"import {module}"], capture_output=True).returncode != 0:
            return str(p)
    return None


def test_no_fitting_python_is_a_clear_error(built, tmp_path):
    """BEARING_FMU_PYTHON pointing at a Python without numba: fmi2Instantiate returns NULL and the logger
    names that Python and the missing package; the master exits 0."""
    py = _python_without("numba")
    if py is None:
        pytest.skip("no Python without numba on this machine")
    proc = start_host(built, "instantiate 0\n", tmp_path, env={"BEARING_FMU_PYTHON": py})
    out, err = proc.communicate(timeout=120)
    assert proc.returncode == 0, err
    status, _, logs, _ = parse(out)
    assert status == [("instantiate", 3)]
    msgs = " ".join(m for s, c, m in logs if s == 3)
    assert f"BEARING_FMU_PYTHON={py}" in msgs and "numba" in msgs and "exited with status 3" in msgs, msgs


def _other_python():
    """A Python 3.13, 3.12 or 3.10 under pyenv (set BEARING_TEST_MASTER_PYTHON to choose), not the build's."""
    if os.environ.get("BEARING_TEST_MASTER_PYTHON"):
        return Path(os.environ["BEARING_TEST_MASTER_PYTHON"])
    v = f"{sys.version_info.major}.{sys.version_info.minor}"
    for want in ("3.13", "3.12", "3.10"):
        for p in sorted(Path("/root/.pyenv/versions").glob(f"{want}.*/bin/python")):
            if want != v and p.is_file():
                return p
    return None


@pytest.fixture(scope="module")
def other_master(tmp_path_factory):
    """A venv with fmpy for a Python version other than the build's."""
    py = _other_python()
    if py is None:
        pytest.skip("no other Python version under /root/.pyenv")
    d = tmp_path_factory.mktemp("other_master")
    r = subprocess.run([str(py), "-m", "venv", str(d / "venv")], capture_output=True, text=True)
    if r.returncode != 0:
        pytest.skip(f"cannot create a venv with {py}: {r.stderr[-300:]}")
    vpy = d / "venv" / "bin" / "python"
    r = subprocess.run([str(vpy), "-m", "pip", "install", "-q", "--disable-pip-version-check", "fmpy"],
                       capture_output=True, text=True, timeout=600)
    if r.returncode != 0:
        pytest.skip(f"fmpy not installable for {py}: {r.stderr[-300:]}")
    return vpy


def test_fmpy_master_of_another_python_version(built, other_master, tmp_path):
    """fmpy running on another Python version than the FMU's build (in-process embedding crashed there) runs
    the shortened seed 000 profile segment: every step OK and the cage speeds equal, bit for bit, those of the
    C master with the same inputs (both with every kernel loaded from the same numba cache)."""
    vr = built["vr"]
    steps = [(1e-3, (1000.0 + 10000.0 * max(0.0, k * 1e-3 - 0.02)) * RPM) for k in range(60)]
    spec = {"fmu": str(built["fmu"]), "params": {}, "outputs": ["cage_speed"],
            "start_inputs": {"shaft_speed": steps[0][1], "Fx": 1000.0, "Fz": 3000.0},
            "steps": [[h, {"shaft_speed": w}] for h, w in steps]}
    p = tmp_path / "spec.json"
    p.write_text(json.dumps(spec))
    lines = ["instantiate 0", "setup 0", "enter", f"set_real {vr['shaft_speed']} {steps[0][1]!r}",
             f"set_real {vr['Fx']} 1000", f"set_real {vr['Fz']} 3000", "exit", f"inputs {vr['shaft_speed']}",
             f"outputs {vr['cage_speed']}"] + [f"step {h!r} {w!r}" for h, w in steps] + ["terminate", "free"]
    crows = []
    for k in range(2):   # the first run fills the numba cache: both compared runs load every kernel from it
        proc = start_host(built, "\n".join(lines) + "\n", tmp_path)
        out, err = proc.communicate(timeout=600)
        assert proc.returncode == 0, err[-2000:]
        crows.append(parse(out)[1])
    env = dict(CLEAN_ENV, BEARING_FMU_CACHE=built["cache"])
    r = subprocess.run([str(other_master), str(HERE / "fmu_driver.py"), str(p)], capture_output=True, text=True,
                       env=env, timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    rows = json.loads([ln for ln in r.stdout.splitlines() if ln.startswith("RESULT ")][-1][7:])["rows"]
    assert all(x["status"] == 0 for x in rows) and len(rows) == len(steps)
    assert [x[3] for x in crows[1]] == [x["values"][0] for x in rows]
