"""The model server (`bearing serve`, bearing_cosim/fmu_server.py) and the native layer's TCP transport
(bearing_tcp.c, BEARING_FMU_SERVER): the same outputs as the local model process, faults (server killed, model
process killed or stopped, master gone), bad clients, connect/step/free cycles. Real processes on 127.0.0.1:
the C host (tests/c_host/host.c), fmpy, the server."""
import json
import math
import os
import random
import signal
import socket
import struct
import subprocess
import sys
import time
import zipfile
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent))
from test_native_host import CLEAN_ENV, RPM, _cache, parse  # noqa: E402
from test_fmu_process import children, gone  # noqa: E402

TOKEN = "test-token-0123456789abcdef"

# a slave on the same FMI layer that steps in real time (delay [s] of sleep per step): faults and cycles
# without the bearing model's start-up
_TICKER = '''
import time
from pythonfmu import Fmi2Causality, Fmi2Slave, Fmi2Variability, Real
from pythonfmu.enums import Fmi2Initial


class Ticker(Fmi2Slave):
    author = "bearing-tribodynamics tests"
    description = "integrates its input; sleeps delay seconds per step"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.u, self.y, self.delay = 1.0, 0.0, 0.0
        self.register_variable(Real("u", causality=Fmi2Causality.input, variability=Fmi2Variability.continuous))
        self.register_variable(Real("delay", causality=Fmi2Causality.parameter, variability=Fmi2Variability.tunable))
        self.register_variable(Real("y", causality=Fmi2Causality.output, variability=Fmi2Variability.continuous,
                                    initial=Fmi2Initial.calculated))

    def do_step(self, current_time, step_size):
        if self.delay > 0:
            time.sleep(self.delay)
        self.y += self.u * step_size
        return True
'''


def _unpack(fmu, d):
    with zipfile.ZipFile(fmu) as z:
        z.extractall(d)
    return d


def _guid(unz):
    import re
    return re.search(r'guid="([^"]*)"', (unz / "modelDescription.xml").read_text()).group(1)


@pytest.fixture(scope="module")
def fmus(tmp_path_factory):
    from bearing_cosim import fmu_build
    from fmpy import read_model_description
    d = tmp_path_factory.mktemp("server")
    plats = ("linux64", "win64") if fmu_build.win64_compiler() else ("linux64",)
    bearing = fmu_build.build(d / "dist", platforms=plats)
    ticker = fmu_build._build("Ticker", {"ticker": _TICKER}, "ticker", d / "tdist")
    host = d / "host"
    subprocess.run([os.environ.get("CC", "gcc"), "-std=gnu99", "-O2", "-o", str(host), str(HERE / "c_host" / "host.c"),
                    "-ldl"], check=True)
    out = {"dir": d, "host": host, "cache": _cache(tmp_path_factory), "win64": "win64" in plats}
    for tag, f in (("bearing", bearing), ("ticker", ticker)):
        unz = _unpack(f, d / f"unz_{tag}")
        md = read_model_description(str(f))
        out[tag] = {"fmu": f, "unz": unz, "guid": md.guid, "vr": {v.name: v.valueReference for v in md.modelVariables}}
    (d / "token").write_text(TOKEN + "\n")
    return out


def start_server(f, *extra, token=True):
    """`bearing serve` on a free port of 127.0.0.1 serving both FMUs; (process, port, log file)."""
    log = f["dir"] / f"serve_{time.monotonic_ns()}.log"
    cmd = [sys.executable, "-m", "bearing_cosim.cli", "serve", "--port", "0", "--fmu", str(f["bearing"]["fmu"]),
           "--fmu", str(f["ticker"]["fmu"]), "--handshake-timeout", "1", *extra]
    if token:
        cmd += ["--token-file", str(f["dir"] / "token")]
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=open(log, "w"), text=True,
                         env=dict(CLEAN_ENV, BEARING_FMU_CACHE=f["cache"], PYTHONPATH=str(HERE.parent)))
    line = p.stdout.readline()
    assert "listening on" in line, (line, log.read_text()[-2000:])
    return p, int(line.rsplit(":", 1)[1]), log


@pytest.fixture(scope="module")
def server(fmus):
    p, port, log = start_server(fmus)
    yield {"proc": p, "port": port, "log": log, "addr": f"127.0.0.1:{port}"}
    p.send_signal(signal.SIGINT)
    p.wait(30)


def remote_env(server, **kw):
    return dict(CLEAN_ENV, BEARING_FMU_SERVER=server["addr"], BEARING_FMU_TOKEN=TOKEN, **kw)


def host_cmd(f, tag, script_path):
    return [str(f["host"]), str(f[tag]["unz"]), tag.capitalize() if tag == "ticker" else "BearingFMU",
            f[tag]["guid"], str(script_path)]


def run_host(f, tag, script, tmp_path, env, timeout=300, name="script.txt"):
    p = tmp_path / name
    p.write_text(script)
    return subprocess.run(host_cmd(f, tag, p), capture_output=True, text=True, env=env, timeout=timeout)


def ticker_script(f, steps, delay=0.0, h=0.01):
    vr = f["ticker"]["vr"]
    lines = ["instantiate 0", "setup 0", f"set_real {vr['delay']} {delay}", "enter", "exit", f"inputs {vr['u']}",
             f"outputs {vr['y']}"]
    lines += [f"step {h} 2.0"] * steps + ["terminate", "free"]
    return "\n".join(lines) + "\n"


# the integrator 'auto' picks by measured wall-clock cost, so two runs may integrate differently; a fixed one
# repeats its arithmetic
INTEGRATOR = "adaptive"


def seed000_script(f, fidelity, t_end, outs):
    from bearing_core.models.dynamics import read_profile
    t_pts, rpm_pts, _ = read_profile("seed000")
    vr, h = f["bearing"]["vr"], 1e-3
    speeds = [float(np.interp(k * h, t_pts, rpm_pts)) * RPM for k in range(int(round(t_end / h)))]
    lines = ["instantiate 0", "setup 0", f"set_string {vr['fidelity']} {fidelity}",
             f"set_string {vr['integrator']} {INTEGRATOR}", "enter",
             f"set_real {vr['shaft_speed']} {speeds[0]!r}", f"set_real {vr['Fx']} 1000", f"set_real {vr['Fz']} 3000",
             "exit", f"inputs {vr['shaft_speed']}", "outputs " + " ".join(str(vr[o]) for o in outs)]
    lines += [f"step {h!r} {w!r}" for w in speeds] + ["terminate", "free"]
    return "\n".join(lines) + "\n", speeds


OUTS = ["cage_speed", "friction_torque", "reaction_Fz", "heat_flux_total", "ir_z", "max_contact_pressure"]
CASES = (("dynamic", 0.2), ("quasi-static", 1.0))


@pytest.fixture(scope="module")
def local_runs(fmus, tmp_path_factory):
    """Seed 000's profile, 0.2 s at 'dynamic' and 1 s at 'quasi-static', through the local model process (C host)."""
    d = tmp_path_factory.mktemp("local")
    out = {}
    env = dict(CLEAN_ENV, BEARING_FMU_CACHE=fmus["cache"])
    for fid, _ in CASES:   # kernels compiled in a process may round unlike those loaded from numba's cache: every
        script, _ = seed000_script(fmus, fid, 0.003, OUTS)   # compared run loads them
        assert run_host(fmus, "bearing", script, d, env, timeout=900).returncode == 0
    for fid, t_end in CASES:
        script, _ = seed000_script(fmus, fid, t_end, OUTS)
        r = run_host(fmus, "bearing", script, d, dict(CLEAN_ENV, BEARING_FMU_CACHE=fmus["cache"]), timeout=900)
        assert r.returncode == 0, r.stderr[-2000:]
        status, rows, logs, _ = parse(r.stdout)
        assert all(s == 0 for _, s in status) and all(x[0] == 0 for x in rows), logs[-5:]
        out[fid] = np.array(rows)
    return out


def test_fmpy_through_the_server_equals_the_local_process(fmus, server, local_runs, tmp_path):
    """The Linux .so with BEARING_FMU_SERVER, in fmpy: the same outputs as the local model process (C host),
    bit for bit, at 'dynamic' (0.2 s) and 'quasi-static' (1 s) on seed 000's profile."""
    for fid, t_end in CASES:
        _, speeds = seed000_script(fmus, fid, t_end, OUTS)
        spec = {"fmu": str(fmus["bearing"]["fmu"]), "params": {"fidelity": fid, "integrator": INTEGRATOR},
                "outputs": OUTS,
                "start_inputs": {"shaft_speed": speeds[0], "Fx": 1000.0, "Fz": 3000.0},
                "steps": [[1e-3, {"shaft_speed": w}] for w in speeds]}
        p = tmp_path / f"{fid}.json"
        p.write_text(json.dumps(spec))
        r = subprocess.run([sys.executable, str(HERE / "fmu_driver.py"), str(p)], capture_output=True, text=True,
                           env=remote_env(server), timeout=900)
        assert r.returncode == 0, r.stderr[-2000:]
        rows = json.loads([ln for ln in r.stdout.splitlines() if ln.startswith("RESULT ")][-1][7:])["rows"]
        assert all(x["status"] == 0 for x in rows)
        remote = np.array([x["values"] for x in rows])
        assert np.array_equal(remote, local_runs[fid][:, 3:]), fid


def test_wine_host_through_the_server_equals_the_local_process(fmus, server, local_runs, tmp_path):
    """Under wine64, the C host cross-compiled with mingw-w64 loads binaries/win64/BearingFMU.dll, which
    connects to the model server: the same statuses and outputs as the local model process, bit for bit."""
    from test_map_fmu import MINGW, wine_loader
    from bearing_cosim.fmu_build import WIN64_PACKAGE
    if not fmus["win64"]:
        pytest.skip(f"no win64 cross compiler: install the Debian package {WIN64_PACKAGE}")
    loader = wine_loader()
    if loader is None:
        pytest.skip("no wine64 loader: install the Debian package wine64")
    exe = tmp_path / "host.exe"
    subprocess.run([MINGW, "-std=gnu99", "-O2", "-o", str(exe), str(HERE / "c_host" / "host.c")], check=True)
    for fid, t_end in CASES:
        script, _ = seed000_script(fmus, fid, t_end, OUTS)
        p = tmp_path / f"{fid}.txt"
        p.write_text(script)
        r = subprocess.run([loader, str(exe), "Z:" + str(fmus["bearing"]["unz"]), "BearingFMU", fmus["bearing"]["guid"],
                            str(p)], capture_output=True, text=True, env=remote_env(server, WINEDEBUG="-all"),
                           timeout=900)
        assert r.returncode == 0, (r.stdout[-2000:], r.stderr[-2000:])
        status, rows, logs, _ = parse(r.stdout.replace("\r", ""))
        assert all(s_ == 0 for _, s_ in status) and len(rows) == len(local_runs[fid]), logs[-5:]
        assert np.array_equal(np.array(rows), local_runs[fid]), fid


def _model_pids(server_pid):
    """The model processes of a server (its children; launch.sh execs Python in place)."""
    return [p for p in children(server_pid) if not gone(p)]


def _wait(cond, timeout=10.0):
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout:
        if cond():
            return True
        time.sleep(0.05)
    return cond()


def _start(f, script, tmp_path, env, name):
    p = tmp_path / name
    p.write_text(script)
    return subprocess.Popen(host_cmd(f, "ticker", p), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env=env)


def _rows_until(proc, n):
    got = 0
    while got < n:
        ln = proc.stdout.readline()
        assert ln, proc.stderr.read()[-2000:]
        got += ln.startswith("ROW ")


def test_faults(fmus, server, tmp_path):
    """Model process killed (kill -9) and stopped (SIGSTOP, BEARING_FMU_STEP_TIMEOUT=2): the master's next call
    returns fmi2Error with the reason, later calls fmi2Error, the master exits 0, and the server reaps the
    process. A master killed mid-run leaves no model process on the server. The server keeps serving."""
    spid = server["proc"].pid
    script = ticker_script(fmus, 400, delay=0.01)
    # kill -9 of the model process
    before = set(_model_pids(spid))
    h = _start(fmus, script, tmp_path, remote_env(server), "k.txt")
    _rows_until(h, 5)
    mine = set(_model_pids(spid)) - before
    assert len(mine) == 1
    os.kill(mine.pop(), signal.SIGKILL)
    out, err = h.communicate(timeout=60)
    assert h.returncode == 0, err[-2000:]
    status, rows, logs, _ = parse(out)
    bad = [r for r in rows if r[0] == 3]
    assert bad and all(r[0] == 3 for r in rows[rows.index(bad[0]):])
    assert any("killed by signal 9" in m for _, _, m in logs), logs[:3]
    # SIGSTOP: fmi2Error after the step timeout, the stopped process killed by the server
    h = _start(fmus, script, tmp_path, remote_env(server, BEARING_FMU_STEP_TIMEOUT="2"), "s.txt")
    _rows_until(h, 5)
    mine = set(_model_pids(spid)) - before
    assert len(mine) == 1
    pid = mine.pop()
    os.kill(pid, signal.SIGSTOP)
    t0 = time.monotonic()
    out, err = h.communicate(timeout=60)
    assert h.returncode == 0 and time.monotonic() - t0 < 20, err[-2000:]
    status, rows, logs, _ = parse(out)
    assert any(r[0] == 3 for r in rows)
    assert any("did not answer within 2 s" in m and "BEARING_FMU_STEP_TIMEOUT" in m for _, _, m in logs), logs[:3]
    assert _wait(lambda: gone(pid)), "the stopped model process was left"
    # the master killed mid-run
    h = _start(fmus, script, tmp_path, remote_env(server), "m.txt")
    _rows_until(h, 5)
    mine = set(_model_pids(spid)) - before
    assert len(mine) == 1
    pid = mine.pop()
    h.kill()
    h.communicate()
    assert _wait(lambda: gone(pid)), "the model process outlived its master"
    r = run_host(fmus, "ticker", ticker_script(fmus, 3), tmp_path, remote_env(server))
    assert r.returncode == 0 and [x[0] for x in parse(r.stdout)[1]] == [0, 0, 0]


def test_server_killed_mid_run(fmus, tmp_path):
    """kill -9 of the server mid-run: the master's next call returns fmi2Error naming the lost server, later
    calls fmi2Error, the master exits 0; the server's model process ends with it."""
    p, port, log = start_server(fmus)
    try:
        env = dict(CLEAN_ENV, BEARING_FMU_SERVER=f"127.0.0.1:{port}", BEARING_FMU_TOKEN=TOKEN)
        h = _start(fmus, ticker_script(fmus, 400, delay=0.01), tmp_path, env, "k.txt")
        _rows_until(h, 5)
        mine = _model_pids(p.pid)
        assert len(mine) == 1
        p.kill()
        p.wait()
        t0 = time.monotonic()
        out, err = h.communicate(timeout=60)
        assert h.returncode == 0 and time.monotonic() - t0 < 10, err[-2000:]
        status, rows, logs, _ = parse(out)
        assert any(r[0] == 3 for r in rows)
        assert any(f"model server at 127.0.0.1:{port}" in m and "stopped or killed" in m for _, _, m in logs), logs[:3]
        assert _wait(lambda: gone(mine[0])), "the model process outlived its server"
    finally:
        if p.poll() is None:
            p.kill()


def _raw(port, data, read=True, wait=5.0):
    """Sends data, then what the server answers until it closes (b'' if nothing); None if it did not close."""
    s = socket.create_connection(("127.0.0.1", port), timeout=wait)
    try:
        if data:
            s.sendall(data)
        got = b""
        t0 = time.monotonic()
        while time.monotonic() - t0 < wait:
            try:
                b = s.recv(4096)
            except socket.timeout:
                return None
            except ConnectionResetError:
                return got
            if not b:
                return got
            got += b
        return None
    finally:
        s.close()


def _hello(token, proto, guid):
    t, g = token.encode(), guid.encode()
    return (struct.pack("<I", 8 + len(t)) + b"BRGT" + struct.pack("<I", len(t)) + t
            + struct.pack("<III", 8 + len(g), proto, len(g)) + g)


def test_bad_clients_are_closed_and_the_next_runs(fmus, server, tmp_path):
    """Random bytes, a 4 GB length prefix, a wrong token, a wrong protocol, a wrong GUID, a half-open
    connection (no handshake within the server's handshake timeout, 1 s here): each closed, logged with the
    peer's address, and the next good client runs."""
    port = server["port"]
    rnd = random.Random(7)
    good = ticker_script(fmus, 2)
    guid = fmus["ticker"]["guid"]
    cases = [
        (bytes(rnd.randrange(256) for _ in range(3000)), "handshake frame length|not a bearing FMU handshake"),
        (b"\xff\xff\xff\xff" + b"\0" * 64, "handshake frame length 4294967295 bytes; allowed: at most 4096"),
        (_hello("wrong-token-0123456789", 2, guid), "wrong token"),
        (_hello(TOKEN, 99, guid), "protocol 99 of the FMU's native layer"),
        (_hello(TOKEN, 2, "{not-served}"), "GUID '{not-served}' is not served here"),
        (b"", "no complete handshake within 1 s"),
        (struct.pack("<I", 100) + b"BRGT", "no complete handshake within 1 s"),
    ]
    for data, why in cases:
        got = _raw(port, data)
        assert got is not None, f"not closed: {why}"
        assert _wait(lambda: why.split("|")[0] in server["log"].read_text()
                     or why.split("|")[-1] in server["log"].read_text(), 5), why
        r = run_host(fmus, "ticker", good, tmp_path, remote_env(server))
        assert r.returncode == 0 and [x[0] for x in parse(r.stdout)[1]] == [0, 0], (why, r.stdout[-1000:])
    text = server["log"].read_text()
    assert "127.0.0.1:" in text and "connection closed: wrong token" in text
    # the C layer's view of a refusal: wrong token and no server, each a NULL instance with the reason
    r = run_host(fmus, "ticker", good, tmp_path, dict(remote_env(server), BEARING_FMU_TOKEN="wrong-token-xxxxxxxx"))
    _, _, logs, _ = parse(r.stdout)
    assert r.returncode == 0 and "STATUS instantiate 3" in r.stdout and any("wrong token" in m for _, _, m in logs)
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        free = s.getsockname()[1]
    r = run_host(fmus, "ticker", good, tmp_path, dict(CLEAN_ENV, BEARING_FMU_SERVER=f"127.0.0.1:{free}"))
    _, _, logs, _ = parse(r.stdout)
    assert "STATUS instantiate 3" in r.stdout and any("bearing serve" in m and f"127.0.0.1:{free}" in m
                                                      for _, _, m in logs), logs


def _sockets(port):
    """Connections of this port not closed (ESTABLISHED, CLOSE_WAIT, FIN_WAIT...; TIME_WAIT is the kernel's)."""
    n = 0
    for f in ("/proc/net/tcp", "/proc/net/tcp6"):
        try:
            lines = Path(f).read_text().splitlines()[1:]
        except OSError:
            continue
        for ln in lines:
            w = ln.split()
            if int(w[1].rsplit(":", 1)[1], 16) == port and w[3] not in ("0A", "06"):
                n += 1
    return n


def test_100_cycles_leave_nothing(fmus, server, tmp_path):
    """100 connect/initialise/step/free cycles in one master: every call OK, and afterwards no model process
    and no open connection left on the server."""
    vr = fmus["ticker"]["vr"]
    lines = []
    for _ in range(100):
        lines += ["instantiate 0", "setup 0", "enter", "exit", f"inputs {vr['u']}", f"outputs {vr['y']}",
                  "step 0.01 2.0", "free"]
    r = run_host(fmus, "ticker", "\n".join(lines) + "\n", tmp_path, remote_env(server), timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]
    status, rows, logs, _ = parse(r.stdout)
    assert len(rows) == 100 and all(x[0] == 0 and x[3] == pytest.approx(0.02) for x in rows), logs[:3]
    assert all(s == 0 for _, s in status)
    assert _wait(lambda: not _model_pids(server["proc"].pid)), _model_pids(server["proc"].pid)
    assert _wait(lambda: _sockets(server["port"]) == 0), _sockets(server["port"])


def test_serve_refuses_an_open_address_without_token_and_stops_on_ctrl_c(fmus, tmp_path):
    """A non-loopback --host without --token-file is refused at once, naming both; Ctrl-C (SIGINT) stops the
    server and every model process it started."""
    r = subprocess.run([sys.executable, "-m", "bearing_cosim.cli", "serve", "--host", "0.0.0.0", "--port", "0"],
                       capture_output=True, text=True, env=dict(CLEAN_ENV, PYTHONPATH=str(HERE.parent)), timeout=60)
    assert r.returncode == 2 and "--host = '0.0.0.0' is not a loopback address" in r.stderr
    assert "--token-file" in r.stderr
    p, port, log = start_server(fmus)
    env = dict(CLEAN_ENV, BEARING_FMU_SERVER=f"127.0.0.1:{port}", BEARING_FMU_TOKEN=TOKEN)
    hs = [_start(fmus, ticker_script(fmus, 400, delay=0.01), tmp_path, env, f"c{k}.txt") for k in range(2)]
    for h in hs:
        _rows_until(h, 3)
    kids = _model_pids(p.pid)
    assert len(kids) == 2
    p.send_signal(signal.SIGINT)
    assert p.wait(30) == 0
    assert _wait(lambda: all(gone(k) for k in kids))
    for h in hs:
        out, _ = h.communicate(timeout=60)
        assert h.returncode == 0 and any(x[0] == 3 for x in parse(out)[1])


def test_crafted_state_over_the_server(fmus, server, tmp_path):
    """Through the server: a state round trip (serialise, deserialise, set) is OK; a pickle that would create a
    file, given to fmi2DeSerializeFMUstate, is fmi2Error with the reason, no file appears, and the instance
    steps on."""
    import pickle
    target = tmp_path / "pwned"

    class Evil:
        def __reduce__(self):
            return (os.system, (f"touch {target}",))

    (tmp_path / "evil.bin").write_bytes(pickle.dumps((2, {"x": Evil()}), protocol=4))
    vr = fmus["ticker"]["vr"]
    script = (f"instantiate 0\nsetup 0\nenter\nexit\ninputs {vr['u']}\noutputs {vr['y']}\nstep 0.01 2.0\ngetstate\n"
              f"roundtrip\nload_state {tmp_path / 'evil.bin'}\nstep 0.01 2.0\nfree\n")
    r = run_host(fmus, "ticker", script, tmp_path, remote_env(server))
    assert r.returncode == 0, r.stderr[-2000:]
    status, rows, logs, _ = parse(r.stdout)
    st = dict(status)
    assert st["roundtrip"] == 0 and st["load_state"] == 3 and [x[0] for x in rows] == [0, 0], logs
    assert any("fmi2DeSerializeFMUstate: not a serialized state of this FMU" in m for _, _, m in logs), logs
    assert not target.exists()


def test_idle_timeout_and_instance_limit(fmus, tmp_path):
    """--max-instances 1: a second instance is refused at its handshake, naming the limit; --idle-timeout 1: an
    accepted connection without requests is closed after about 1 s and its model process ends."""
    p, port, log = start_server(fmus, "--idle-timeout", "1", "--max-instances", "1")
    try:
        s = socket.create_connection(("127.0.0.1", port), timeout=10)
        s.sendall(_hello(TOKEN, 2, fmus["ticker"]["guid"]))
        n, code = struct.unpack("<II", s.recv(8))
        assert code == 0 and s.recv(n - 4) == b"accepted"
        assert _wait(lambda: len(_model_pids(p.pid)) == 1)
        kid = _model_pids(p.pid)[0]
        got = _raw(port, _hello(TOKEN, 2, fmus["ticker"]["guid"]))
        assert got is not None and b"already runs 1 instances, its limit (--max-instances 1)" in got
        t0 = time.monotonic()
        assert s.recv(100) == b""      # closed by the idle timeout
        assert 0.5 < time.monotonic() - t0 < 10
        assert _wait(lambda: gone(kid))
        assert "idle timeout" in log.read_text()
        s.close()
    finally:
        p.send_signal(signal.SIGINT)
        p.wait(30)


def test_malformed_requests_after_the_handshake(fmus, server):
    """An accepted connection that sends a 4 GB request frame, or a request whose input count exceeds its bytes:
    that connection is closed (its model process ends, the reason in a fault frame and the server's log) and the
    server keeps serving."""
    for frame, why in ((struct.pack("<II", 0xFFFFFFFF, 6), "request frame of 4294967295 bytes"),
                       (struct.pack("<III", 8, 6, 0xFFFFFFFF), "malformed request (4294967295 inputs in 4 bytes)")):
        s = socket.create_connection(("127.0.0.1", server["port"]), timeout=30)
        s.sendall(_hello(TOKEN, 2, fmus["ticker"]["guid"]))
        n, code = struct.unpack("<II", s.recv(8))
        assert code == 0 and s.recv(n - 4) == b"accepted"
        s.sendall(frame)
        got = b""
        while True:
            b = s.recv(65536)
            if not b:
                break
            got += b
        s.close()
        assert why.encode() in got, got[:300]
        assert _wait(lambda: why in server["log"].read_text())
    assert _wait(lambda: not _model_pids(server["proc"].pid))


def test_build_platforms_refused_naming_what_is_missing(tmp_path, monkeypatch):
    """--platforms names only linux64 and win64; win64 without a cross compiler stops naming the package."""
    from bearing_cosim import cli, fmu_build
    assert fmu_build.parse_platforms("linux64, win64") == ("linux64", "win64")
    with pytest.raises(ValueError, match="--platforms = 'darwin64' is invalid; allowed: .*linux64, win64"):
        fmu_build.parse_platforms("darwin64")
    assert cli.main(["build-fmu", "--dest", str(tmp_path), "--platforms", "darwin64"]) == 2
    monkeypatch.delenv("CC_WIN64", raising=False)
    monkeypatch.setattr(fmu_build.shutil, "which", lambda name: None)
    with pytest.raises(RuntimeError, match="apt install gcc-mingw-w64-x86-64-win32"):
        fmu_build._compile(tmp_path / "x.dll", "win64")
