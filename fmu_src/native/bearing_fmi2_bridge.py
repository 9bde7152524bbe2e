"""Python side of the FMU's native FMI 2.0 layer (fmu_src/native/bearing_fmi2.c).

The C library loads this file under a module name unique to the FMU's content and calls
``instantiate(...)`` and the methods of ``Instance``; every method returns an fmi2Status (int) and never
raises. Arrays cross as addresses (ctypes), log records are fetched by the C side with ``take_logs`` and
passed to the master's logger after the GIL is released.

The model code (bearing_core, the pythonfmu slave and pythonfmu itself) was renamed at build time to
names carrying a hash of its content (``bearing_core_<hash>`` ...), so two FMU versions in one process,
or an installed bearing_core, never share modules. It is imported through a meta-path finder that only
answers for those names, each from a content-addressed copy in a writable cache folder (numba caches compiled
kernels next to the sources; the FMU itself may be unpacked read-only or into a new temporary folder at
each instantiation): ``$BEARING_FMU_CACHE``, else ``~/.cache/bearing_fmu``, else
``<tempdir>/bearing_fmu-<user>``; if none is writable, the unpacked copy is used in place.
"""
from __future__ import annotations

import ctypes
import importlib
import importlib.abc
import importlib.machinery
import json
import math
import os
import shutil
import sys
import tempfile
import traceback
from pathlib import Path

OK, WARNING, DISCARD, ERROR, FATAL = 0, 1, 2, 3, 4
_CATEGORY = {OK: "logInfo", WARNING: "logWarning", DISCARD: "logDiscard", ERROR: "logError", FATAL: "logError"}

_ENV_CACHE: dict = {}
_SITE_DONE: set = set()


class _FmiError(Exception):
    """A call the FMU refuses: fmi2Error with this message, the instance stays usable."""


class _Finder(importlib.abc.MetaPathFinder):
    """Finds only the FMU's content-hashed top-level modules, each in its own code folder."""

    def __init__(self, roots: dict):
        self.roots = roots

    def find_spec(self, fullname, path=None, target=None):
        root = self.roots.get(fullname)
        if root is not None:
            return importlib.machinery.PathFinder.find_spec(fullname, [str(root)])
        return None


_FINDER = _Finder({})


def _env(res: str) -> dict:
    if res not in _ENV_CACHE:
        _ENV_CACHE[res] = json.loads(Path(res, "python_env.json").read_text(encoding="utf-8"))
    return _ENV_CACHE[res]


def _writable_copy(src: Path, name: str) -> Path | None:
    """A content-addressed copy of the code folder with writable modes (see module docstring)."""
    bases = []
    if os.environ.get("BEARING_FMU_CACHE"):
        bases.append(Path(os.environ["BEARING_FMU_CACHE"]))
    try:
        bases.append(Path.home() / ".cache" / "bearing_fmu")
    except (RuntimeError, KeyError):
        pass
    try:
        user = str(os.getuid())
    except AttributeError:
        user = os.environ.get("USERNAME", "user")
    bases.append(Path(tempfile.gettempdir()) / f"bearing_fmu-{user}")
    for base in bases:
        dst = base / name
        if (dst / ".complete").is_file() and os.access(dst, os.W_OK):
            return dst
        try:
            base.mkdir(parents=True, exist_ok=True)
            tmp = Path(tempfile.mkdtemp(prefix="tmp_", dir=base))
            for d, dirs, files in os.walk(src):
                dirs[:] = [x for x in dirs if x != "__pycache__"]
                out = tmp / Path(d).relative_to(src)
                out.mkdir(exist_ok=True)
                for f in files:
                    shutil.copyfile(Path(d, f), out / f)   # contents only: the modes of a read-only unpack stay behind
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


def _load_class(res: str, own_interpreter: bool):
    env = _env(res)
    if own_interpreter:
        # an interpreter started by the native layer: the site-packages of the Python the FMU was built for
        import site
        if not hasattr(sys, "argv"):
            sys.argv = [""]
        for p in env.get("site_packages", []):
            if p not in _SITE_DONE and os.path.isdir(p):
                site.addsitedir(p)
                _SITE_DONE.add(p)
    if _FINDER not in sys.meta_path:
        sys.meta_path.insert(0, _FINDER)
    for name in env["packages"]:
        if name in _FINDER.roots:
            continue
        src = Path(res) / "code" / name
        root = _writable_copy(src, name)
        if root is None:
            root = src
            if "numba" not in sys.modules and not os.environ.get("NUMBA_CACHE_DIR"):
                os.environ["NUMBA_CACHE_DIR"] = tempfile.mkdtemp(prefix="bearing_fmu_numba_")
        _FINDER.roots[name] = root
    mod = importlib.import_module(env["slave_module"])
    return getattr(mod, env["class_name"]), env


def instantiate(res, name, guid, visible, logging_on, own_interpreter):
    return Instance(res, name, guid, bool(visible), bool(logging_on), bool(own_interpreter))


_FMI_NAME = {"set_debug_logging": "fmi2SetDebugLogging", "setup_experiment": "fmi2SetupExperiment",
             "enter_initialization_mode": "fmi2EnterInitializationMode",
             "exit_initialization_mode": "fmi2ExitInitializationMode", "do_step": "fmi2DoStep",
             "terminate": "fmi2Terminate", "reset": "fmi2Reset", "free": "fmi2FreeInstance",
             "get_fmu_state": "fmi2GetFMUstate", "set_fmu_state": "fmi2SetFMUstate", "free_fmu_state": "fmi2FreeFMUstate",
             "get_status": "fmi2GetStatus"}


def _fmi(method):
    """Wraps an FMI call: returns its status, logs the reason of every refusal or failure."""
    name = _FMI_NAME.get(method.__name__) or "fmi2" + "".join(w.capitalize() for w in method.__name__.split("_"))

    def call(self, *args):
        try:
            st = method(self, *args)
            st = OK if st is None else int(st)
        except _FmiError as e:
            self._log(ERROR, f"{name}: {e}" if method.__name__ != "unsupported" else str(e))
            st = ERROR
        except Exception as e:  # the model's own failure: fmi2Error with the reason, never fatal
            self._log(ERROR, f"{name}: {type(e).__name__}: {e}")
            if self.logging_on:
                self._log(OK, traceback.format_exc())
            st = ERROR
        finally:
            self._drain_slave()
        return max(st, self._worst)
    call.__name__ = method.__name__
    return call


class Instance:
    def __init__(self, res, name, guid, visible, logging_on, own_interpreter):
        self._logs = []
        self._worst = OK
        self.ok = 0
        self.logging_on = logging_on
        self.categories = None
        self.res, self.name, self.visible = res, name, visible
        self.time = 0.0
        self._states = {}
        self._next_state = 1
        self._strbufs = []
        self.failure = None
        try:
            self.cls, env = _load_class(res, own_interpreter)
            if guid and guid != env.get("guid"):
                self._log(ERROR, f"fmi2Instantiate: GUID {guid} does not match this FMU's {env.get('guid')}")
                return
            self._new_slave()
            self.ok = 1
        except Exception as e:
            self._log(ERROR, f"fmi2Instantiate: cannot load the model: {type(e).__name__}: {e}")
            self._log(ERROR, traceback.format_exc())

    def _new_slave(self):
        self.slave = self.cls(instance_name=self.name, resources=self.res, visible=self.visible)
        # per value reference and type, the getter / setter of variables already checked once: outputs and
        # parameters to get (any mode after fmi2ExitInitializationMode), inputs to set (their check depends on
        # the mode only); the per-step fmi2Get/Set calls then skip the checks that cannot fail again
        self._fast_get = {}
        self._fast_set = {}
        self.mode = "instantiated"
        self.failure = None

    # ---- logging ----------------------------------------------------------------------------
    def _log(self, status, msg, category=None):
        if status >= WARNING:
            self._worst = max(self._worst, status)
        cat = category or _CATEGORY.get(status, "logInfo")
        if status == OK and not self.logging_on:
            return
        if status == OK and self.categories is not None and cat not in self.categories:
            return
        self._logs.append(f"{int(status)}\x1f{cat}\x1f{msg}".replace("\0", " "))

    def _drain_slave(self):
        q = getattr(getattr(self, "slave", None), "log_queue", None)
        while q:
            m = q.pop(0)
            st = int(m.status)
            self._log(st, m.msg)

    def take_logs(self):
        out = "".join(r + "\0" for r in self._logs).encode("utf-8", errors="replace")
        self._logs.clear()
        self._worst = OK
        return out

    # ---- helpers ----------------------------------------------------------------------------
    def _var(self, vr, kind):
        var = self.slave.vars.get(vr)
        if var is None:
            raise _FmiError(f"unknown value reference {vr}")
        if type(var).__name__ != kind:
            raise _FmiError(f"value reference {vr} ({var.name}) is a {type(var).__name__}, not a {kind}")
        return var

    def _check_get(self):
        if self.mode == "failed":
            raise _FmiError(f"no values: the initialisation failed ({self.failure})")

    def _check_set(self, var, value):
        caus = var.causality.name
        vari = var.variability.name
        if self.mode in ("failed", "terminated"):
            why = f"the initialisation failed ({self.failure})" if self.mode == "failed" else "after fmi2Terminate"
            raise _FmiError(f"cannot set {var.name}: {why}")
        if caus in ("output", "calculatedParameter", "local") or vari == "constant":
            raise _FmiError(f"{var.name} is a{'n' if caus[0] in 'aeiou' else ''} {caus} ({vari}); it cannot be set")
        if caus == "parameter" and vari == "fixed" and self.mode == "step":
            raise _FmiError(f"{var.name} is a fixed parameter: it can only be set before fmi2ExitInitializationMode "
                            f"(it stays {var.getter()!r}; to change it, fmi2Reset or instantiate anew)")
        items = getattr(self.slave, "_enums", {}).get(var.name, (None, None))[1]   # Enumeration: (String twin, items)
        if items is not None and not 1 <= value <= len(items):
            raise _FmiError(f"{var.name} = {value!r} is not an item value of its enumeration; allowed: "
                            + ", ".join(f"{i + 1} ({it})" for i, it in enumerate(items)))
        if caus == "parameter" and isinstance(value, (float, int)) and not isinstance(value, bool):
            rng = getattr(self.slave, "_ranges", {}).get(var.name)
            if not math.isfinite(value) or (rng and not rng[0] <= value <= rng[1]):
                allowed = f"[{rng[0]:g}, {rng[1]:g}]" if rng else "a finite number"
                raise _FmiError(f"{var.name} = {value!r} is outside the allowed range {allowed}")

    def _get(self, vr_addr, n, val_addr, kind, ctype, conv):
        self._check_get()
        vrs = (ctypes.c_uint * n).from_address(vr_addr) if n else []
        out = (ctype * n).from_address(val_addr) if n else []
        fast = self._fast_get if self.mode != "instantiated" else None
        for i in range(n):
            getter = fast.get((kind, vrs[i])) if fast is not None else None
            if getter is None:
                var = self._var(vrs[i], kind)
                if self.mode == "instantiated" and var.causality.name == "output":
                    raise _FmiError(f"{var.name} is an output: it is computed by fmi2ExitInitializationMode")
                getter = var.getter
                if fast is not None:
                    fast[(kind, vrs[i])] = getter
            out[i] = conv(getter())

    def _set(self, vr_addr, n, val_addr, kind, ctype, conv):
        vrs = (ctypes.c_uint * n).from_address(vr_addr) if n else []
        vals = (ctype * n).from_address(val_addr) if n else []
        if self.mode not in ("failed", "terminated"):
            # inputs checked before: only the mode check applies to them (done above)
            fast = self._fast_set
            setters = [fast.get((kind, vrs[i])) for i in range(n)]
            if None not in setters:
                vs = [conv(vals[i]) for i in range(n)]
                for setter, v in zip(setters, vs):
                    setter(v)
                return
        todo = []
        for i in range(n):
            var = self._var(vrs[i], kind)
            v = conv(vals[i])
            self._check_set(var, v)
            todo.append((var, v))
        for var, v in todo:   # all or nothing
            var.setter(v)
            if var.causality.name == "input":
                self._fast_set[(kind, var.value_reference)] = var.setter

    # ---- FMI calls --------------------------------------------------------------------------
    @_fmi
    def set_debug_logging(self, on, n, cats_addr):
        self.logging_on = bool(on)
        if n:
            arr = (ctypes.c_char_p * n).from_address(cats_addr)
            self.categories = {arr[i].decode("utf-8", "replace") for i in range(n) if arr[i]}
        else:
            self.categories = None

    @_fmi
    def setup_experiment(self, tol_defined, tol, start, stop, stop_defined):
        if self.mode != "instantiated":
            raise _FmiError(f"fmi2SetupExperiment is allowed only after fmi2Instantiate (mode: {self.mode})")
        self.time = float(start)
        self.slave.setup_experiment(float(start), float(stop) if stop_defined else None,
                                    float(tol) if tol_defined else None)

    @_fmi
    def enter_initialization_mode(self):
        if self.mode != "instantiated":
            raise _FmiError(f"fmi2EnterInitializationMode is allowed only after fmi2Instantiate (mode: {self.mode})")
        self.slave.enter_initialization_mode()
        self.mode = "init"

    @_fmi
    def exit_initialization_mode(self):
        if self.mode != "init":
            raise _FmiError(f"fmi2ExitInitializationMode is allowed only in initialization mode (mode: {self.mode})")
        try:
            self.slave.exit_initialization_mode()
        except Exception as e:
            self.mode = "failed"
            self.failure = str(e)
            raise _FmiError(f"initialisation failed: {e}") from None
        self.mode = "step"

    @_fmi
    def do_step(self, t, h, no_set_prior):
        if self.mode != "step":
            why = {"failed": f"the initialisation failed ({self.failure})", "terminated": "after fmi2Terminate"}
            raise _FmiError("not allowed: " + why.get(self.mode, f"the FMU is in {self.mode} mode, "
                                                                             "call fmi2ExitInitializationMode first"))
        ok = self.slave.do_step(float(t), float(h))
        self._drain_slave()
        if ok:
            self.time = float(t) + float(h)
            return OK
        return max(self._worst, DISCARD)

    @_fmi
    def terminate(self):
        if self.mode in ("step", "init", "failed", "instantiated"):
            self.slave.terminate()
        self.mode = "terminated"

    @_fmi
    def reset(self):
        self.slave.terminate()
        self._states.clear()
        self._new_slave()

    @_fmi
    def free(self):
        if self.mode in ("step", "init"):
            self.slave.terminate()
        self._states.clear()
        self._strbufs = []

    @_fmi
    def get_real(self, vr, n, v):
        self._get(vr, n, v, "Real", ctypes.c_double, float)

    @_fmi
    def get_integer(self, vr, n, v):
        self._get(vr, n, v, "Integer", ctypes.c_int, int)

    @_fmi
    def get_boolean(self, vr, n, v):
        self._get(vr, n, v, "Boolean", ctypes.c_int, lambda x: 1 if x else 0)

    @_fmi
    def get_string(self, vr, n, v):
        self._check_get()
        vrs = (ctypes.c_uint * n).from_address(vr) if n else []
        out = (ctypes.c_void_p * n).from_address(v) if n else []
        bufs = []   # kept alive until the next call on this instance (FMI 2.0 rule for fmi2GetString)
        for i in range(n):
            var = self._var(vrs[i], "String")
            b = ctypes.create_string_buffer(str(var.getter()).encode("utf-8"))
            bufs.append(b)
            out[i] = ctypes.addressof(b)
        self._strbufs = bufs

    @_fmi
    def set_real(self, vr, n, v):
        self._set(vr, n, v, "Real", ctypes.c_double, float)

    @_fmi
    def set_integer(self, vr, n, v):
        self._set(vr, n, v, "Integer", ctypes.c_int, int)

    @_fmi
    def set_boolean(self, vr, n, v):
        self._set(vr, n, v, "Boolean", ctypes.c_int, bool)

    @_fmi
    def set_string(self, vr, n, v):
        self._set(vr, n, v, "String", ctypes.c_char_p, lambda b: (b or b"").decode("utf-8"))

    @_fmi
    def get_fmu_state(self, addr):
        if self.mode not in ("init", "step"):
            raise _FmiError(f"fmi2GetFMUstate: no state in {self.mode} mode")
        ptr = ctypes.c_void_p.from_address(addr)
        sid = ptr.value if ptr.value in self._states else None
        if sid is None:
            sid = self._next_state
            self._next_state += 1
        self._states[sid] = (self.slave._get_fmu_state(), self.time, self.mode)
        ptr.value = sid

    @_fmi
    def set_fmu_state(self, sid):
        if sid not in self._states:
            raise _FmiError(f"unknown FMU state {sid:#x}")
        if self.mode in ("failed", "terminated"):
            raise _FmiError(f"fmi2SetFMUstate is not allowed in {self.mode} mode")
        state, self.time, self.mode = self._states[sid]
        self.slave._set_fmu_state(state)

    @_fmi
    def free_fmu_state(self, addr):
        ptr = ctypes.c_void_p.from_address(addr)
        if ptr.value:
            self._states.pop(ptr.value, None)
        ptr.value = None

    @_fmi
    def unsupported(self, what):
        raise _FmiError(f"{what} is not supported by this FMU (see modelDescription.xml); the instance is unchanged "
                        "and stays usable")

    @_fmi
    def get_status(self, kind, addr, typ):
        if kind == 2 and typ == "real":       # fmi2LastSuccessfulTime
            ctypes.c_double.from_address(addr).value = self.time
            return OK
        if kind == 3 and typ == "boolean":    # fmi2Terminated
            ctypes.c_int.from_address(addr).value = 0
            return OK
        self._log(DISCARD, "status not available: this FMU steps synchronously (fmi2DoStep never returns fmi2Pending)")
        return DISCARD
