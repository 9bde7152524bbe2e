"""The model process of the bearing FMU: one per FMU instance, started by the native FMI 2.0 layer
(bearing_fmi2.c) through resources/launch.sh, which picks the Python.

    python model_process.py <resources dir> <shared-memory fd> <master pid>

The native layer and this process share one memory segment (an anonymous memfd, inherited as a file
descriptor: nothing to unlink, nothing to leak). Each FMI call that reaches the model is one exchange: the
master writes a request and bumps ``req_seq``, this process answers and bumps ``resp_seq``; the waiting side
spins for a short, bounded time and then sleeps on the futex of that word. Layout and command codes are
those of bearing_fmi2.c (PROTOCOL must match). Every request starts with the inputs the master set since
the last exchange; a step's answer carries every output.

The model is the pythonfmu slave (bearing_fmu.BearingFMU) around bearing_core's CoSimSession; this module
only checks and routes FMI calls to it. The code is copied into a writable per-user folder named by its
content hash ($BEARING_FMU_CACHE, else ~/.cache/bearing_fmu, else <tmp>/bearing_fmu-<uid>), so that numba's
cache next to the sources holds wherever and however (read-only) the FMU is unpacked.
"""
from __future__ import annotations

import ctypes
import functools
import json
import math
import mmap
import os
import shutil
import signal
import struct
import sys
import tempfile
import time
import traceback
from pathlib import Path

PROTOCOL = 2
MAGIC = 0x58475242            # "BRGX"
HDR = 4096                    # header bytes; requests at HDR, responses at HDR + (size - HDR) // 2
# header fields (byte offsets)
O_MAGIC, O_VERSION, O_REQ, O_RESP, O_CMD, O_STATUS, O_MODE, O_FLAGS = 0, 4, 8, 12, 16, 20, 24, 28
O_REQLEN, O_RESPLEN, O_TIME, O_BUSY, O_PID, O_PROG = 32, 40, 48, 56, 64, 72
O_MCPU, O_WCPU = 76, 80       # i32: the processors of the master's last request and of this process's answer
Q_OFF = 1024                  # the dynamic model's time integrals (with its live integration time) in the header

(C_HELLO, C_DEBUG, C_SETUP, C_ENTER, C_EXIT, C_STEP, C_TERMINATE, C_RESET, C_FREE, C_GET, C_SET, C_GETSTATE,
 C_SETSTATE, C_FREESTATE, C_SERIALIZE, C_DESERIALIZE, C_UNSUPPORTED) = range(1, 18)
T_REAL, T_INTEGER, T_BOOLEAN, T_STRING = range(4)
MODES = ("instantiated", "init", "step", "failed", "terminated")
CAUSALITY = ("parameter", "calculatedParameter", "input", "output", "local", "independent")
F_SNAPSHOT = 1

OK, WARNING, DISCARD, ERROR, FATAL = 0, 1, 2, 3, 4
_CATEGORY = {OK: "logInfo", WARNING: "logWarning", DISCARD: "logDiscard", ERROR: "logError", FATAL: "logError"}
_KIND = ("Real", "Integer", "Boolean", "String")
_CONV = (float, int, bool, lambda b: b.decode("utf-8") if isinstance(b, bytes) else str(b))

_FMI_NAME = {C_DEBUG: "fmi2SetDebugLogging", C_SETUP: "fmi2SetupExperiment", C_ENTER: "fmi2EnterInitializationMode",
             C_EXIT: "fmi2ExitInitializationMode", C_STEP: "fmi2DoStep", C_TERMINATE: "fmi2Terminate",
             C_RESET: "fmi2Reset", C_FREE: "fmi2FreeInstance", C_GETSTATE: "fmi2GetFMUstate",
             C_SETSTATE: "fmi2SetFMUstate", C_FREESTATE: "fmi2FreeFMUstate", C_SERIALIZE: "fmi2SerializeFMUstate",
             C_DESERIALIZE: "fmi2DeSerializeFMUstate"}


class FmiError(Exception):
    """A call the FMU refuses: fmi2Error with this message, the instance stays usable."""


# ---- futex wake-ups ----------------------------------------------------------------------------------
_libc = ctypes.CDLL(None, use_errno=True)
_SYS_FUTEX = {"x86_64": 202, "aarch64": 98}.get(os.uname().machine, 202)
_FUTEX_WAIT, _FUTEX_WAKE = 0, 1


class _Timespec(ctypes.Structure):
    _fields_ = [("tv_sec", ctypes.c_long), ("tv_nsec", ctypes.c_long)]


def _futex_wait(addr: int, expected: int, timeout_s: float):
    ts = _Timespec(int(timeout_s), int((timeout_s % 1.0) * 1e9))
    _libc.syscall(_SYS_FUTEX, ctypes.c_void_p(addr), _FUTEX_WAIT, ctypes.c_uint32(expected), ctypes.byref(ts),
                  None, 0)


def _futex_wake(addr: int):
    _libc.syscall(_SYS_FUTEX, ctypes.c_void_p(addr), _FUTEX_WAKE, 0x7FFFFFFF, None, None, 0)


# ---- processor placement ------------------------------------------------------------------------------
_getcpu = getattr(_libc, "sched_getcpu", None)
SHORT_STEP = 300e-6     # [s]


def _cpu() -> int:
    """The processor this thread runs on, -1 if unknown."""
    return int(_getcpu()) if _getcpu is not None else -1


def _leave_processor(cpu: int, allowed: set):
    """Move this process off processor cpu, then give the scheduler all of allowed again (before a short step,
    SHORT_STEP: the master spins through those, bearing_fmi2.c's SPIN_SHORT_STEP). The scheduler's
    wake-up placement puts a woken thread on its waker's processor: after the master has slept through a long
    step, master and model process can end up sharing one processor while another idles, and every short step
    then costs a time slice (0.26-0.31 ms instead of 16 us per step measured on a 2-processor machine,
    bench/fidelity_speed.py at the quasi-static level). The master does not spin while it sees this
    (bearing_fmi2.c, await)."""
    try:
        os.sched_setaffinity(0, allowed - {cpu})
        os.sched_setaffinity(0, allowed)
    except OSError:
        pass


# ---- the model code ----------------------------------------------------------------------------------
def _writable_copy(src: Path, name: str, skip=()) -> Path | None:
    """A copy of the code folder, named by its content hash, in the first writable cache base; None if none.
    skip: names of data files at the top of src that are not copied (their hash is not in the name)."""
    bases = []
    if os.environ.get("BEARING_FMU_CACHE"):
        bases.append(Path(os.environ["BEARING_FMU_CACHE"]))
    try:
        bases.append(Path.home() / ".cache" / "bearing_fmu")
    except (RuntimeError, KeyError):
        pass
    bases.append(Path(tempfile.gettempdir()) / f"bearing_fmu-{os.getuid()}")
    for base in bases:
        dst = base / name
        if (dst / ".complete").is_file() and os.access(dst, os.W_OK):
            return dst
        try:
            base.mkdir(parents=True, exist_ok=True)
            tmp = Path(tempfile.mkdtemp(prefix="tmp_", dir=base))
            for d, dirs, files in os.walk(src):
                out = tmp / Path(d).relative_to(src)
                out.mkdir(exist_ok=True)
                for f in files:
                    if d == str(src) and f in skip:
                        continue
                    shutil.copyfile(Path(d, f), out / f)   # contents only: the modes of a read-only unpack stay behind
                    st = os.stat(Path(d, f))
                    os.utime(out / f, ns=(st.st_atime_ns, st.st_mtime_ns))
            (tmp / ".complete").write_text("")
            try:
                os.replace(tmp, dst)
            except OSError:   # another process won the race: use its copy
                shutil.rmtree(tmp, ignore_errors=True)
            if (dst / ".complete").is_file():
                return dst
        except OSError:
            continue
    return None


def _cpu_flags() -> set:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("flags"):
                return set(line.split(":", 1)[1].split())
    except OSError:
        pass
    return set()


def _use_shipped_kernels(cfg: dict):
    """The name of the FMU's precompiled target that fits this process (same Python minor version and numba
    version, the processor has the target's features, the user chose no target), selected before numba loads;
    None: numba compiles for this processor (JIT)."""
    pre = cfg.get("precompiled")
    if not pre or "NUMBA_CPU_NAME" in os.environ or "NUMBA_CPU_FEATURES" in os.environ:
        return None
    from importlib.metadata import PackageNotFoundError, version
    try:
        if version("numba") != pre["numba"] or f"{sys.version_info.major}.{sys.version_info.minor}" != pre["python"]:
            return None
    except PackageNotFoundError:
        return None
    flags = _cpu_flags()
    for t in pre["targets"]:
        if set(t["needs"]) <= flags:
            os.environ["NUMBA_CPU_NAME"] = t["name"]
            os.environ["NUMBA_CPU_FEATURES"] = t["features"]
            return t["name"]
    return None


class CompileLock:
    """Instances of one FMU share the numba cache of its code copy. The first ones to initialise compile the
    kernels; without coordination instances initialised at once from several master threads compile the same
    kernels at once. This lock (flock on <code copy>/.compile.lock) is held during fmi2ExitInitializationMode
    and during the first fmi2DoStep, where nearly all kernels are compiled or loaded, so that the next instance
    loads them from the cache. Never held between two calls (a master may call the instances in any order);
    without a writable code copy there is nothing to share and no lock."""

    def __init__(self, root):
        self.fd = None
        self.path = None if root is None else Path(root) / ".compile.lock"
        self.done = False

    def acquire(self):
        if self.path is None or self.done or self.fd is not None:
            return
        import fcntl
        try:
            self.fd = os.open(self.path, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC, 0o666)
            fcntl.flock(self.fd, fcntl.LOCK_EX)
        except OSError:
            self.release()

    def release(self):
        if self.fd is not None:
            os.close(self.fd)   # closing drops the flock
            self.fd = None


def load_slave_class(res: Path, cfg: dict):
    target = _use_shipped_kernels(cfg)
    own = set(cfg.get("slave_files", ())) | set(cfg.get("data_files", ()))
    root = _writable_copy(res / "code", f"code-{cfg['code_hash']}" + (f"-{target}" if target else ""), skip=own)
    lock = CompileLock(root)
    if root is None:
        root = res / "code"
        os.environ["NUMBA_CACHE_DIR"] = tempfile.mkdtemp(prefix="bearing_fmu_numba_")
    # the copy first (bearing_core, pythonfmu with their kernel cache), then this FMU's own code folder for
    # its slave modules, which the copy leaves out (FMUs of other slaves share the copy)
    sys.path.insert(0, str(res / "code"))
    sys.path.insert(0, str(root))
    import importlib
    mod = importlib.import_module(cfg["slave_module"])
    return getattr(mod, cfg["class_name"]), lock


class Profile:
    """BEARING_FMU_PROFILE=<file>: per fmi2DoStep, the model process's time in the call, in the slave's
    do_step, and in the numba integration kernels (bench/bench_fmu.py), written as JSON to <file> at
    fmi2FreeInstance."""

    def __init__(self, path, slave_cls):
        from bearing_core.models import dynamics
        self.path, self.kern, self.bare, self.slave = path, [0.0], [0.0], [0.0]
        self.rows = []
        K = dynamics.K
        for obj, name, box in ((dynamics.DynamicModel, "_integrate", self.kern), (K, "integrate", self.bare),
                               (K, "integrate_rosw", self.bare), (slave_cls, "do_step", self.slave)):
            setattr(obj, name, self._timed(getattr(obj, name), box))

    @staticmethod
    def _timed(f, box):
        def timed(*a):
            t1 = time.perf_counter()
            try:
                return f(*a)
            finally:
                box[0] += time.perf_counter() - t1
        return timed

    def record(self, busy):
        self.rows.append((busy, self.kern[0], self.bare[0], self.slave[0]))
        self.kern[0] = self.bare[0] = self.slave[0] = 0.0

    def write(self):
        Path(self.path).write_text(json.dumps({"busy": [r[0] for r in self.rows], "kernel": [r[1] for r in self.rows],
                                               "bare_kernel": [r[2] for r in self.rows],
                                               "slave_step": [r[3] for r in self.rows]}))


# ---- the FMI calls -----------------------------------------------------------------------------------
class Model:
    """The checks and modes of the FMI calls around one pythonfmu slave."""

    def __init__(self, cls, name, visible, logging_on, resources=None):
        self.cls, self.name, self.visible, self.resources = cls, name, visible, resources
        self.logging_on = logging_on
        self.categories = None
        self.logs = []
        self.worst = OK
        self.time = 0.0
        self.states = {}
        self.next_state = 1
        self.new_slave()

    def new_slave(self):
        # pythonfmu's convention: resources is the FMU's resources folder (the slave reads its data there)
        self.slave = self.cls(instance_name=self.name, resources=self.resources, visible=self.visible)
        self.vars = self.slave.vars
        self.fast_set = {}
        self.mode = "instantiated"
        self.failure = None

    # logging
    def log(self, status, msg, category=None):
        if status >= WARNING:
            self.worst = max(self.worst, status)
        cat = category or _CATEGORY.get(status, "logInfo")
        if status == OK and not self.logging_on:
            return
        if status == OK and self.categories is not None and cat not in self.categories:
            return
        self.logs.append(f"{int(status)}\x1f{cat}\x1f{msg}".replace("\0", " "))

    def drain_slave(self):
        q = getattr(getattr(self, "slave", None), "log_queue", None)
        while q:
            m = q.pop(0)
            self.log(int(m.status), m.msg)

    def take_logs(self) -> bytes:
        if not self.logs:
            return b""
        out = "".join(r + "\0" for r in self.logs).encode("utf-8", errors="replace")
        self.logs.clear()
        return out

    # variables
    def var(self, vr, kind):
        var = self.vars.get(vr)
        if var is None:
            raise FmiError(f"unknown value reference {vr}")
        if type(var).__name__ != kind:
            raise FmiError(f"value reference {vr} ({var.name}) is a {type(var).__name__}, not a {kind}")
        return var

    def check_get(self):
        if self.mode == "failed":
            raise FmiError(f"no values: the initialisation failed ({self.failure})")

    def check_set(self, var, value):
        caus, vari = var.causality.name, var.variability.name
        if self.mode in ("failed", "terminated"):
            why = f"the initialisation failed ({self.failure})" if self.mode == "failed" else "after fmi2Terminate"
            raise FmiError(f"cannot set {var.name}: {why}")
        if caus in ("output", "calculatedParameter", "local") or vari == "constant":
            raise FmiError(f"{var.name} is a{'n' if caus[0] in 'aeiou' else ''} {caus} ({vari}); it cannot be set")
        if caus == "parameter" and vari == "fixed" and self.mode == "step":
            raise FmiError(f"{var.name} is a fixed parameter: it can only be set before fmi2ExitInitializationMode "
                           f"(it stays {var.getter()!r}; to change it, fmi2Reset or instantiate anew)")
        items = getattr(self.slave, "_enums", {}).get(var.name, (None, None))[1]
        if items is not None and not 1 <= value <= len(items):
            raise FmiError(f"{var.name} = {value!r} is not an item value of its enumeration; allowed: "
                           + ", ".join(f"{i + 1} ({it})" for i, it in enumerate(items)))
        if caus == "parameter" and isinstance(value, (float, int)) and not isinstance(value, bool):
            rng = getattr(self.slave, "_ranges", {}).get(var.name)
            if not math.isfinite(value) or (rng and not rng[0] <= value <= rng[1]):
                allowed = f"[{rng[0]:g}, {rng[1]:g}]" if rng else "a finite number"
                raise FmiError(f"{var.name} = {value!r} is outside the allowed range {allowed}")

    def get(self, kind, vrs):
        self.check_get()
        out = []
        for vr in vrs:
            var = self.var(vr, _KIND[kind])
            if self.mode == "instantiated" and var.causality.name == "output":
                raise FmiError(f"{var.name} is an output: it is computed by fmi2ExitInitializationMode")
            out.append(_CONV[kind](var.getter()))
        return out

    def set(self, kind, vrs, values):
        todo = []
        for vr, v in zip(vrs, values):
            var = self.var(vr, _KIND[kind])
            v = _CONV[kind](v)
            self.check_set(var, v)
            todo.append((var, v))
        for var, v in todo:   # all or nothing
            var.setter(v)

    def apply_inputs(self, vrs, values):
        """The inputs the master set in step mode (checked there: known Real/Integer/Boolean inputs)."""
        fast = self.fast_set
        for vr, v in zip(vrs, values):
            entry = fast.get(vr)
            if entry is None:
                var = self.vars[vr]
                entry = fast[vr] = (var.setter, _CONV[_KIND.index(type(var).__name__)])
            entry[0](entry[1](v))

    # FMI calls
    def setup(self, tol_defined, tol, start, stop, stop_defined):
        if self.mode != "instantiated":
            raise FmiError(f"fmi2SetupExperiment is allowed only after fmi2Instantiate (mode: {self.mode})")
        self.time = float(start)
        self.slave.setup_experiment(float(start), float(stop) if stop_defined else None,
                                    float(tol) if tol_defined else None)

    def enter(self):
        if self.mode != "instantiated":
            raise FmiError(f"fmi2EnterInitializationMode is allowed only after fmi2Instantiate (mode: {self.mode})")
        self.slave.enter_initialization_mode()
        self.mode = "init"

    def exit(self):
        if self.mode != "init":
            raise FmiError(f"fmi2ExitInitializationMode is allowed only in initialization mode (mode: {self.mode})")
        try:
            self.slave.exit_initialization_mode()
        except Exception as e:
            self.mode = "failed"
            self.failure = str(e)
            raise FmiError(f"initialisation failed: {e}") from None
        self.mode = "step"

    def step(self, t, h):
        if self.mode != "step":
            why = {"failed": f"the initialisation failed ({self.failure})", "terminated": "after fmi2Terminate"}
            raise FmiError("not allowed: " + why.get(self.mode, f"the FMU is in {self.mode} mode, "
                                                                 "call fmi2ExitInitializationMode first"))
        ok = self.slave.do_step(t, h)
        self.drain_slave()
        if ok:
            self.time = t + h
            return OK
        return max(self.worst, DISCARD)

    def terminate(self):
        if self.mode in ("step", "init", "failed", "instantiated"):
            self.slave.terminate()
        self.mode = "terminated"

    def reset(self):
        self.slave.terminate()
        self.states.clear()
        self.new_slave()

    def get_state(self, sid):
        if self.mode not in ("init", "step"):
            raise FmiError(f"no state in {self.mode} mode")
        if sid not in self.states:
            sid = self.next_state
            self.next_state += 1
        self.states[sid] = (self.slave._get_fmu_state(), self.time, self.mode)
        return sid

    def set_state(self, sid):
        if sid not in self.states:
            raise FmiError(f"unknown FMU state {sid:#x}")
        if self.mode in ("failed", "terminated"):
            raise FmiError(f"fmi2SetFMUstate is not allowed in {self.mode} mode")
        state, self.time, self.mode = self.states[sid]
        self.slave._set_fmu_state(state)

    def serialize(self, sid):
        if sid not in self.states:
            raise FmiError(f"unknown FMU state {sid:#x}")
        slave_state, t, mode = self.states[sid]
        conv = {v.name: _CONV[_KIND.index(type(v).__name__)] for v in self.vars.values()}
        slave_state = {k: conv[k](v) if k in conv else v for k, v in slave_state.items()}
        return encode_state({"guid": self.guid, "time": float(t), "mode": mode, "slave": slave_state})

    def check_state(self, st):
        """A decoded serialised state checked field by field against this instance: the FMU's GUID, the mode
        and time, every settable variable with its type (and range), and the session's rollback state with the
        kinds, dtypes and shapes of this instance's session. Returns (slave state, time, mode)."""
        if st.get("guid") != self.guid:
            raise FmiError(f"the state is of the FMU with GUID {st.get('guid')!r}; this FMU is {self.guid}")
        mode, t = st.get("mode"), st.get("time")
        if mode not in ("init", "step"):
            raise FmiError(f"state field mode = {mode!r} is invalid; allowed: 'init' or 'step'")
        if type(t) is not float or not math.isfinite(t):
            raise FmiError(f"state field time = {t!r} is invalid; allowed: a finite float")
        slave = st.get("slave")
        if type(slave) is not dict:
            raise FmiError(f"state field slave is a {type(slave).__name__}; allowed: a map of variable values")
        # the names this instance's own state holds (the bearing slave: its settable variables; a plain pythonfmu
        # slave: every variable)
        own = {k: v for k, v in self.slave._get_fmu_state().items() if k != "_session_state"}
        by_name = {v.name: v for v in self.vars.values()}
        want = {n: by_name[n] for n in own if n in by_name}
        names = set(slave) - {"_session_state"}
        if names != set(own):
            extra, missing = sorted(names - set(own)), sorted(set(own) - names)
            raise FmiError("state variables do not match this FMU's"
                           + (f"; unknown: {', '.join(map(str, extra[:10]))}" if extra else "")
                           + (f"; missing: {', '.join(missing[:10])}" if missing else ""))
        for n in set(own) - set(want):   # other attributes a slave keeps in its state
            _check_like(slave[n], own[n], f"state field {n}")
        ranges = getattr(self.slave, "_ranges", {})
        enums = getattr(self.slave, "_enums", {})
        for name, var in want.items():
            v, kind = slave[name], type(var).__name__
            ok = {"Real": float, "Integer": int, "Boolean": bool, "String": str}[kind]
            if type(v) is not ok:
                raise FmiError(f"state variable {name} = {v!r:.60} is a {type(v).__name__}; allowed: a {kind} "
                               f"({ok.__name__})")
            if kind == "Integer" and name in enums and not 1 <= v <= len(enums[name][1]):
                raise FmiError(f"state variable {name} = {v} is not an item value of its enumeration; allowed: "
                               f"1..{len(enums[name][1])}")
            if kind == "Real" and var.causality.name == "parameter" and name in ranges:
                lo, hi = ranges[name]
                if not lo <= v <= hi:
                    raise FmiError(f"state variable {name} = {v!r} is outside the allowed range [{lo:g}, {hi:g}]")
        sess = getattr(self.slave, "_session", None)
        got = slave.get("_session_state")
        if got is not None:
            if sess is None:
                raise FmiError("the state holds a running simulation; this instance has none yet (deserialise "
                               "it after fmi2ExitInitializationMode)")
            _check_like(got, _session_template(sess), "session state")
        return slave, t, mode

    def deserialize(self, data, sid):
        state = self.check_state(decode_state(data))
        if sid not in self.states:
            sid = self.next_state
            self.next_state += 1
        self.states[sid] = state
        return sid


# ---- serialised FMU state: plain data, never pickled -------------------------------------------------
STATE_MAGIC = b"BRGSTATE"
STATE_VERSION = 1
_STATE_HDR = struct.Struct("<8sII")         # magic, format version, body length
_DTYPES = {1: "<f8", 2: "<i8"}              # the array dtypes a state may hold
_MAX_DEPTH, _MAX_NDIM, _MAX_ITEMS = 8, 4, 1 << 24


def encode_state(obj) -> bytes:
    """obj (None, bool, int, float, str, tuple/list, dict with str keys, numpy float64/int64 arrays and scalars)
    as tagged little-endian binary behind a versioned header."""
    import numpy as np
    out = []

    def enc(x):
        if x is None:
            out.append(b"N")
        elif isinstance(x, (bool, np.bool_)):
            out.append(b"T" if x else b"F")
        elif isinstance(x, (int, np.integer)):
            out.append(b"i" + struct.pack("<q", int(x)))
        elif isinstance(x, (float, np.floating)):
            out.append(b"d" + struct.pack("<d", float(x)))
        elif isinstance(x, str):
            b = x.encode("utf-8")
            out.append(b"s" + struct.pack("<I", len(b)) + b)
        elif isinstance(x, (tuple, list)):
            out.append(b"t" + struct.pack("<I", len(x)))
            for v in x:
                enc(v)
        elif isinstance(x, dict):
            out.append(b"m" + struct.pack("<I", len(x)))
            for k, v in x.items():
                enc(str(k))
                enc(v)
        elif isinstance(x, np.ndarray):
            code = {np.dtype("<f8"): 1, np.dtype("<i8"): 2}.get(x.dtype.newbyteorder("<") if x.dtype.byteorder == ">"
                                                             else x.dtype)
            if code is None or x.ndim > _MAX_NDIM:
                raise FmiError(f"cannot serialise an array of {x.dtype} with {x.ndim} dimensions")
            out.append(b"a" + struct.pack(f"<BB{x.ndim}I", code, x.ndim, *x.shape)
                       + np.ascontiguousarray(x, dtype=_DTYPES[code]).tobytes())
        else:
            raise FmiError(f"cannot serialise a {type(x).__name__} in the FMU state")

    enc(obj)
    body = b"".join(out)
    return _STATE_HDR.pack(STATE_MAGIC, STATE_VERSION, len(body)) + body


def decode_state(data: bytes):
    """The inverse of encode_state; every length is checked against the bytes there are. Raises FmiError naming
    what is wrong."""
    import numpy as np
    data = bytes(data)
    if len(data) < _STATE_HDR.size or data[:8] != STATE_MAGIC:
        raise FmiError(f"not a serialized state of this FMU ({len(data)} bytes without the {STATE_MAGIC.decode()} "
                       "header)")
    _, version, n = _STATE_HDR.unpack_from(data)
    if version != STATE_VERSION:
        raise FmiError(f"serialized state format version {version}; this FMU reads version {STATE_VERSION}")
    if n != len(data) - _STATE_HDR.size:
        raise FmiError(f"serialized state body length {n} does not match the {len(data) - _STATE_HDR.size} bytes "
                       "given")
    pos = [_STATE_HDR.size]

    def take(k):
        if k < 0 or pos[0] + k > len(data):
            raise FmiError(f"serialized state truncated at byte {pos[0]} (needs {k} more)")
        b = data[pos[0]:pos[0] + k]
        pos[0] += k
        return b

    def count():
        (k,) = struct.unpack("<I", take(4))
        if k > len(data) - pos[0]:
            raise FmiError(f"serialized state: a count of {k} at byte {pos[0] - 4} exceeds the remaining bytes")
        return k

    def dec(depth):
        if depth > _MAX_DEPTH:
            raise FmiError(f"serialized state nested deeper than {_MAX_DEPTH}")
        tag = take(1)
        if tag == b"N":
            return None
        if tag in (b"T", b"F"):
            return tag == b"T"
        if tag == b"i":
            return struct.unpack("<q", take(8))[0]
        if tag == b"d":
            return struct.unpack("<d", take(8))[0]
        if tag == b"s":
            try:
                return take(count()).decode("utf-8")
            except UnicodeDecodeError:
                raise FmiError(f"serialized state: a string before byte {pos[0]} is not UTF-8") from None
        if tag == b"t":
            return tuple(dec(depth + 1) for _ in range(count()))
        if tag == b"m":
            out = {}
            for _ in range(count()):
                k = dec(depth + 1)
                if type(k) is not str:
                    raise FmiError(f"serialized state: a map key before byte {pos[0]} is a {type(k).__name__}")
                out[k] = dec(depth + 1)
            return out
        if tag == b"a":
            code, ndim = struct.unpack("<BB", take(2))
            if code not in _DTYPES or ndim > _MAX_NDIM:
                raise FmiError(f"serialized state: array of dtype code {code} with {ndim} dimensions; allowed: "
                               f"float64 or int64, at most {_MAX_NDIM} dimensions")
            shape = struct.unpack(f"<{ndim}I", take(4 * ndim))
            size = math.prod(shape)
            if size > _MAX_ITEMS:
                raise FmiError(f"serialized state: array of shape {shape} exceeds {_MAX_ITEMS} items")
            return np.frombuffer(take(8 * size), dtype=_DTYPES[code]).reshape(shape).astype(_DTYPES[code][1:])
        raise FmiError(f"serialized state: unknown tag {tag!r} at byte {pos[0] - 1}")

    obj = dec(0)
    if pos[0] != len(data):
        raise FmiError(f"serialized state: {len(data) - pos[0]} bytes after its end")
    if type(obj) is not dict:
        raise FmiError("serialized state: not a map of fields")
    return obj


def _session_template(sess):
    """What the session's get_state of this instance may return: its own state, with the implicit integrator's
    workspace (absent until its first implicit step) of this bearing's size."""
    import numpy as np
    cur = sess.get_state()
    if cur is not None and not isinstance(cur[0], str) and len(cur) == 8 and cur[7] is None:
        K = sys.modules["bearing_core.models.dynamics"].K
        cur = cur[:7] + (tuple(K.rosw_workspace(int(sess.model.P[K.P_NB]))),)
    return cur


def _check_like(got, want, where):
    """got has the kinds of want: None, str (equal), float, int, bool, tuples of the same length, arrays of the
    same dtype and shape; the implicit integrator's workspace (the last item of the dynamic state) may be None."""
    import numpy as np
    if isinstance(want, np.ndarray):
        if not isinstance(got, np.ndarray) or got.dtype != want.dtype or got.shape != want.shape:
            desc = f"an array of {got.dtype} {got.shape}" if isinstance(got, np.ndarray) else type(got).__name__
            raise FmiError(f"{where} is {desc}; allowed: an array of {want.dtype} {want.shape}")
    elif isinstance(want, tuple):
        if type(got) is not tuple or len(got) != len(want):
            raise FmiError(f"{where} is {type(got).__name__}"
                           + (f" of {len(got)} items" if isinstance(got, tuple) else "")
                           + f"; allowed: {len(want)} items")
        for k, (g, w) in enumerate(zip(got, want)):
            if k == 7 and len(want) == 8 and g is None:
                continue
            _check_like(g, w, f"{where}[{k}]")
    elif want is None:
        if got is not None:
            raise FmiError(f"{where} is a {type(got).__name__}; allowed: None for this instance's parameters")
    elif isinstance(want, str):
        if got != want:
            raise FmiError(f"{where} = {got!r:.40}; allowed: {want!r}")
    elif isinstance(want, (bool, np.bool_)):
        if type(got) is not bool:
            raise FmiError(f"{where} is a {type(got).__name__}; allowed: a bool")
    elif isinstance(want, (int, np.integer)):
        if type(got) is not int:
            raise FmiError(f"{where} is a {type(got).__name__}; allowed: an int")
    elif isinstance(want, (float, np.floating)):
        if type(got) is not float or not math.isfinite(got):
            raise FmiError(f"{where} = {got!r:.40}; allowed: a finite float")
    else:
        raise FmiError(f"{where}: unexpected {type(want).__name__} in this instance's state")


# ---- the exchange loop -------------------------------------------------------------------------------
_STEP_ARGS = struct.Struct("<ddi")     # fmi2DoStep: current time, step size, noSetFMUStatePriorToCurrentPoint


@functools.lru_cache(maxsize=16)
def _in_formats(n: int):
    """The compiled formats of n input references and values (a step's request)."""
    return struct.Struct(f"<{n}I"), struct.Struct(f"<{n}d")


class Reader:
    def __init__(self, mm, off):
        self.mm, self.off = mm, off

    def unpack(self, fmt):
        v = struct.unpack_from(fmt, self.mm, self.off)
        self.off += struct.calcsize(fmt)
        return v

    def unpack_s(self, st: struct.Struct):
        """unpack with a compiled format (the per-step fields: no format parsing per call)."""
        v = st.unpack_from(self.mm, self.off)
        self.off += st.size
        return v

    def bytes(self):
        (n,) = self.unpack("<I")
        b = self.mm[self.off:self.off + n]
        self.off += n
        return b


class Writer:
    def __init__(self):
        self.parts = []

    def pack(self, fmt, *v):
        self.parts.append(struct.pack(fmt, *v))

    def bytes(self, b):
        self.parts.append(struct.pack("<I", len(b)) + b)


def snapshot(model: Model, w: Writer):
    """Every variable's value, in the order of the variable table of the handshake."""
    for var in model.vars.values():
        k = _KIND.index(type(var).__name__)
        try:
            v = var.getter()
        except Exception:
            v = 0
        if k == T_REAL:
            w.pack("<d", float(v))
        elif k == T_STRING:
            w.bytes(str(v).encode("utf-8"))
        else:
            w.pack("<i", int(v))


def var_table(model: Model, w: Writer):
    out_index = {}
    slave = model.slave
    if hasattr(slave, "_out") and hasattr(slave, "_out_names"):
        out_index = {n: i for i, n in enumerate(slave._out_names)}
    w.pack("<I", len(model.vars))
    for vr, var in model.vars.items():
        w.pack("<IBBxxi", vr, _KIND.index(type(var).__name__), CAUSALITY.index(var.causality.name),
               out_index.get(var.name, -1))
        w.bytes(var.name.encode("utf-8"))


def publish_progress(mm, model, box):
    """Puts the dynamic model's time-integral array (DynamicModel.quad, updated in place by the numba
    integrators at every accepted step, its entry 2 NOUT the integration's current time [s]) into the shared
    header, so that the native layer sees how far a step has come and wakes up just before its end; O_PROG:
    the byte offset of that time, 0 without a dynamic model (e.g. before fmi2ExitInitializationMode)."""
    import numpy as np
    m = getattr(getattr(model.slave, "_session", None), "model", None) if model is not None else None
    q = getattr(m, "quad", None)
    if q is box.get("view") and q is not None:
        return
    kernels = sys.modules.get("bearing_core.models.dynamics_kernels")
    if (q is None or kernels is None or not isinstance(q, np.ndarray) or q.dtype != np.float64 or q.ndim != 1
            or q.size != kernels.NQUAD or Q_OFF + 8 * q.size > HDR):
        struct.pack_into("<I", mm, O_PROG, 0)
        box["view"] = None
        return
    view = np.frombuffer(mm, dtype=np.float64, count=q.size, offset=Q_OFF)
    view[:] = q
    m.quad = view
    box["view"] = view
    struct.pack_into("<I", mm, O_PROG, Q_OFF + 8 * 2 * kernels.NOUT)


SHM_SIZE = 64 << 20    # the native layer's segment (bearing_fmi2.c SHM_SIZE): the TCP path uses the same layout
_CHANNEL = None


class TcpChannel:
    """The exchange over a TCP connection of the model server (bearing_cosim/fmu_server.py), instead of shared
    memory: the same request and response bytes, in length-prefixed frames (bearing_tcp.c). The request is
    copied into a private segment of the shared-memory layout, so that the loop below serves both alike.

    request frame:  u32 length (of what follows), u32 command, request bytes
    response frame: u32 length, u32 kind (0: response), i32 status, u32 mode, u32 flags, f64 time, f64 busy,
                    response bytes
    """
    MAX_FRAME = (SHM_SIZE - HDR) // 2

    def __init__(self, fd: int, server_pid: int, idle: float):
        import socket
        self.sock = socket.socket(fileno=fd)
        self.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.sock.settimeout(0.5)
        self.server_pid, self.idle = server_pid, idle
        self.seq = 0

    def _recv(self, n: int, first: bool):
        """n bytes, None when the connection ends, the server is gone or (first) the master stays idle too long."""
        buf = bytearray(n)
        view, got, t0 = memoryview(buf), 0, time.monotonic()
        while got < n:
            try:
                k = self.sock.recv_into(view[got:])
            except TimeoutError:
                if os.getppid() != self.server_pid:
                    return None
                if first and got == 0 and time.monotonic() - t0 > self.idle:
                    sys.stderr.write(f"bearing FMU model process: no request for {self.idle:g} s (idle timeout); "
                                     "closing the connection\n")
                    return None
                continue
            except OSError:
                return None
            if k == 0:
                return None
            got += k
        return buf

    def wait(self, mm, words) -> bool:
        """The next request into mm (command, length, bytes at HDR); False: the connection ended."""
        head = self._recv(8, True)
        if head is None:
            return False
        n, cmd = struct.unpack("<II", head)
        if not 4 <= n <= self.MAX_FRAME:
            sys.stderr.write(f"bearing FMU model process: request frame of {n} bytes; allowed: 4..{self.MAX_FRAME}; "
                             "closing the connection\n")
            sys.stderr.flush()
            os._exit(3)     # the server reports the status and this message to the master
        body = self._recv(n - 4, False)
        if body is None:
            return False
        mm[HDR:HDR + n - 4] = body
        struct.pack_into("<I", mm, O_CMD, cmd)
        struct.pack_into("<Q", mm, O_REQLEN, n - 4)
        self.seq = (self.seq + 1) & 0xFFFFFFFF
        words[O_REQ // 4] = self.seq
        return True

    def send(self, mm, resp_off: int, length: int):
        status, mode, flags = struct.unpack_from("<iII", mm, O_STATUS)
        t, busy = struct.unpack_from("<dd", mm, O_TIME)
        head = struct.pack("<IIiIIdd", 4 + 24 + 4 + length, 0, status, mode, flags, t, busy)
        self.sock.settimeout(None)
        try:
            self.sock.sendall(head + mm[resp_off:resp_off + length])
        except OSError:
            pass
        self.sock.settimeout(0.5)


def serve(res: Path, fd: int, master_pid: int, chan: TcpChannel | None = None):
    global _CHANNEL
    if chan is None:
        size = os.fstat(fd).st_size
        mm = mmap.mmap(fd, size)
        os.close(fd)
    else:
        size = SHM_SIZE
        mm = mmap.mmap(-1, size)
        struct.pack_into("<II", mm, O_MAGIC, MAGIC, PROTOCOL)
        struct.pack_into("<ii", mm, O_MCPU, -1, -1)
        _CHANNEL = chan
    words = memoryview(mm).cast("I")
    base = ctypes.addressof(ctypes.c_char.from_buffer(mm))
    req_addr, resp_addr = base + O_REQ, base + O_RESP
    req_off, resp_off = HDR, HDR + (size - HDR) // 2
    resp_cap = size - resp_off
    if words[O_MAGIC // 4] != MAGIC or words[O_VERSION // 4] != PROTOCOL:
        sys.stderr.write(f"bearing FMU model process: protocol {words[O_VERSION // 4]} of the native layer, this "
                         f"model process speaks {PROTOCOL} (mixed FMU files?)\n")
        return 3
    struct.pack_into("<i", mm, O_PID, os.getpid())
    spin = float(os.environ.get("BEARING_FMU_SPIN_US", "200")) * 1e-6
    try:
        allowed = set(os.sched_getaffinity(0))
    except OSError:
        allowed = set()
    step_busy = math.inf    # this process's time in the last step [s]
    cfg = json.loads((res / "model.json").read_text(encoding="utf-8"))
    model = None
    lock = CompileLock(None)
    profile = None
    out_view = None
    gen_out = None          # output variables of a slave without the bearing's output array
    last = 0
    prog = {}
    import numpy as np
    while True:
        # wait for the next request: a short spin, then sleep on the futex (checking that the master lives)
        if chan is not None:
            if not chan.wait(mm, words):
                return 0
            spin = 0.0
        t_end = time.perf_counter() + spin
        while words[O_REQ // 4] == last and time.perf_counter() < t_end:
            pass
        while words[O_REQ // 4] == last:
            _futex_wait(req_addr, last, 0.5)
            if os.getppid() != master_pid:
                return 0
        last = words[O_REQ // 4]
        t0 = time.perf_counter()
        cmd = words[O_CMD // 4]
        if cmd == C_STEP and step_busy < SHORT_STEP and len(allowed) > 1:
            here = _cpu()
            if here >= 0 and here == struct.unpack_from("<i", mm, O_MCPU)[0] and here in allowed:
                _leave_processor(here, allowed)
        r = Reader(mm, req_off)
        w = Writer()
        status, flags = OK, 0
        (n_in,) = r.unpack("<I")
        if chan is not None and 4 + 12 * n_in > struct.unpack_from("<Q", mm, O_REQLEN)[0]:
            sys.stderr.write(f"bearing FMU model process: malformed request ({n_in} inputs in "
                             f"{struct.unpack_from('<Q', mm, O_REQLEN)[0]} bytes); closing the connection\n")
            return 3
        if n_in:
            f_vrs, f_vals = _in_formats(n_in)
            in_vrs, in_vals = r.unpack_s(f_vrs), r.unpack_s(f_vals)
        else:
            in_vrs = in_vals = ()
        r0 = r.off
        try:
            if cmd == C_HELLO:
                guid, name = r.bytes().decode(), r.bytes().decode()
                visible, logging_on = r.unpack("<ii")
                if guid and guid != cfg["guid"]:
                    raise FmiError(f"fmi2Instantiate: GUID {guid} does not match this FMU's {cfg['guid']}")
                cls, lock = load_slave_class(res, cfg)
                model = Model(cls, name, bool(visible), bool(logging_on), str(res))
                model.guid = cfg["guid"]
                slave = model.slave
                if hasattr(slave, "_out"):
                    from bearing_core.session.cosim_spec import INT_OUTPUT_SPEC, OUTPUT_SPEC
                    slave._out_names = [n for n, *_ in OUTPUT_SPEC] + [n for n, *_ in INT_OUTPUT_SPEC]
                else:
                    # any other pythonfmu slave: its Real, Integer and Boolean outputs, read through their
                    # getters after every step, form the output array
                    gen_out = [v for v in model.vars.values() if v.causality.name == "output"
                               and type(v).__name__ in ("Real", "Integer", "Boolean")]
                    slave._out_names = [v.name for v in gen_out]
                    slave._out = np.zeros(len(gen_out))
                var_table(model, w)
                flags |= F_SNAPSHOT
                if os.environ.get("BEARING_FMU_PROFILE"):
                    profile = Profile(os.environ["BEARING_FMU_PROFILE"], type(model.slave))
            elif model is None:
                raise FmiError("the model was not instantiated")
            else:
                if n_in:
                    model.apply_inputs(in_vrs, in_vals)
                if cmd in (C_EXIT, C_STEP):
                    lock.acquire()
                if cmd == C_STEP:
                    t, h, _ = r.unpack_s(_STEP_ARGS)
                    try:
                        status = model.step(t, h)
                    except FmiError:
                        raise
                    except Exception as e:
                        model.log(ERROR, f"fmi2DoStep: {type(e).__name__}: {e}")
                        status = ERROR
                elif cmd == C_GET:
                    kind, n = r.unpack("<II")
                    vals = model.get(kind, r.unpack(f"<{n}I"))
                    if kind == T_REAL:
                        w.pack(f"<{n}d", *vals)
                    elif kind == T_STRING:
                        for v in vals:
                            w.bytes(v.encode("utf-8"))
                    else:
                        w.pack(f"<{n}i", *vals)
                elif cmd == C_SET:
                    kind, n = r.unpack("<II")
                    vrs = r.unpack(f"<{n}I")
                    if kind == T_REAL:
                        vals = r.unpack(f"<{n}d")
                    elif kind == T_STRING:
                        vals = [r.bytes().decode("utf-8") for _ in range(n)]
                    else:
                        vals = r.unpack(f"<{n}i")
                    model.set(kind, vrs, vals)
                elif cmd == C_DEBUG:
                    on, n = r.unpack("<ii")
                    cats = [r.bytes().decode("utf-8", "replace") for _ in range(n)]
                    model.logging_on = bool(on)
                    model.categories = set(cats) if cats else None
                elif cmd == C_SETUP:
                    model.setup(*r.unpack("<idddi")[:5])
                elif cmd == C_ENTER:
                    model.enter()
                elif cmd == C_EXIT:
                    model.exit()
                elif cmd == C_TERMINATE:
                    model.terminate()
                elif cmd == C_RESET:
                    model.reset()
                elif cmd == C_FREE:
                    if model.mode in ("step", "init"):
                        model.slave.terminate()
                    model.states.clear()
                elif cmd == C_GETSTATE:
                    w.pack("<Q", model.get_state(r.unpack("<Q")[0]))
                elif cmd == C_SETSTATE:
                    model.set_state(r.unpack("<Q")[0])
                elif cmd == C_FREESTATE:
                    model.states.pop(r.unpack("<Q")[0], None)
                elif cmd == C_SERIALIZE:
                    w.bytes(model.serialize(r.unpack("<Q")[0]))
                elif cmd == C_DESERIALIZE:
                    data = r.bytes()
                    w.pack("<Q", model.deserialize(data, r.unpack("<Q")[0]))
                elif cmd == C_UNSUPPORTED:
                    raise FmiError(f"{r.bytes().decode()} is not supported by this FMU (see modelDescription.xml); "
                                   "the instance is unchanged and stays usable")
                else:
                    raise FmiError(f"unknown command {cmd} (protocol {PROTOCOL})")
        except FmiError as e:
            if model is not None:
                if cmd in (C_GET, C_SET):
                    name = f"fmi2{'Get' if cmd == C_GET else 'Set'}{_KIND[struct.unpack_from('<I', mm, r0)[0]]}"
                else:
                    name = _FMI_NAME.get(cmd)
                model.log(ERROR, f"{name}: {e}" if name and cmd != C_UNSUPPORTED else str(e))
            else:
                w.parts = [struct.pack("<I", 0)]
                logs = f"{ERROR}\x1flogError\x1f{e}\0".encode()
                _respond(mm, words, resp_off, resp_cap, ERROR, 0, 0, 0.0, t0, logs, w, resp_addr, last)
                return 3
            status = ERROR
        except Exception as e:   # the model's own failure: fmi2Error with the reason, never fatal
            name = _FMI_NAME.get(cmd, "FMI call")
            if model is not None:
                model.log(ERROR, f"{name}: {type(e).__name__}: {e}")
                if model.logging_on:
                    model.log(OK, traceback.format_exc())
                status = ERROR
            else:
                traceback.print_exc()
                logs = f"{ERROR}\x1flogError\x1f{name}: cannot load the model: {type(e).__name__}: {e}\0".encode()
                w.parts = [struct.pack("<I", 0)]
                _respond(mm, words, resp_off, resp_cap, ERROR, 0, 0, 0.0, t0, logs, w, resp_addr, last)
                return 3
        if cmd in (C_EXIT, C_STEP):
            lock.done = lock.done or (cmd == C_STEP and lock.fd is not None)
            lock.release()
        model.drain_slave()
        status = max(status, model.worst)
        model.worst = OK
        if model.mode == "step" and cmd in (C_HELLO, C_EXIT, C_SETSTATE, C_RESET, C_DESERIALIZE):
            flags |= F_SNAPSHOT
        if flags & F_SNAPSHOT:
            snapshot(model, w)
        if cmd == C_STEP:
            # outputs already in place after the 16 bytes (count, logs offset) at resp_off
            out = model.slave._out
            if gen_out is not None:
                for i, v in enumerate(gen_out):
                    out[i] = float(v.getter())
            n = len(out)
            if out_view is None or len(out_view) != n:
                out_view = np.frombuffer(mm, dtype=np.float64, count=n, offset=resp_off + 16)
            out_view[:] = out
            logs = model.take_logs()
            step_busy = time.perf_counter() - t0
            if profile is not None:
                profile.record(step_busy)
            struct.pack_into("<II", mm, resp_off, n, 0)
            off = resp_off + 16 + 8 * n
            struct.pack_into("<I", mm, off, len(logs))
            mm[off + 4:off + 4 + len(logs)] = logs
            _finish(mm, words, status, MODES.index(model.mode), flags, model.time, t0, off + 4 + len(logs) - resp_off,
                    resp_addr, last)
        else:
            publish_progress(mm, model, prog)
            _respond(mm, words, resp_off, resp_cap, status, MODES.index(model.mode), flags, model.time, t0,
                     model.take_logs(), w, resp_addr, last)
        if cmd == C_FREE:
            if profile is not None:
                profile.write()
            return 0


def _respond(mm, words, resp_off, resp_cap, status, mode, flags, t, t0, logs, w, resp_addr, seq):
    body = struct.pack("<I", len(logs)) + logs + b"".join(w.parts)
    if len(body) > resp_cap:
        body = struct.pack("<I", 0) + b""
        status = ERROR
    mm[resp_off:resp_off + len(body)] = body
    _finish(mm, words, status, mode, flags, t, t0, len(body), resp_addr, seq)


def _finish(mm, words, status, mode, flags, t, t0, length, resp_addr, seq):
    struct.pack_into("<iII", mm, O_STATUS, status, mode, flags)
    struct.pack_into("<i", mm, O_WCPU, _cpu())
    struct.pack_into("<Qdd", mm, O_RESPLEN, length, t, time.perf_counter() - t0)
    words[O_RESP // 4] = seq
    if _CHANNEL is not None:
        _CHANNEL.send(mm, HDR + (len(mm) - HDR) // 2, length)
    else:
        _futex_wake(resp_addr)


def main(argv):
    signal.signal(signal.SIGINT, signal.SIG_IGN)   # the master decides; its death ends this process
    os.environ.pop("NUMBA_CACHE_DIR", None)         # numba's cache lives with the content-addressed code copy
    if argv[2] == "--tcp":   # <res> --tcp <socket fd> <server pid> <idle timeout [s]>: a model server's instance
        res, fd, server_pid, idle = Path(argv[1]), int(argv[3]), int(argv[4]), float(argv[5])
        _die_with_parent()
        if os.getppid() != server_pid:
            return 0
        rc = serve(res, -1, server_pid, TcpChannel(fd, server_pid, idle))
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(rc)   # at once: the server reaps it (interpreter finalisation with numba loaded takes seconds)
    res, fd, master_pid = Path(argv[1]), int(argv[2]), int(argv[3])
    return serve(res, fd, master_pid)


def _die_with_parent():
    """SIGKILL when the model server that started this process ends (Linux prctl PR_SET_PDEATHSIG)."""
    try:
        _libc.prctl(1, signal.SIGKILL, 0, 0, 0)
    except (AttributeError, OSError):
        pass


if __name__ == "__main__":
    sys.exit(main(sys.argv))
