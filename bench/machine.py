"""The machine a benchmark ran on, and the clocks it reports.

Every benchmark in bench/ puts ``machine_info()`` under a top-level "machine" key of its JSON output and prints
``machine_line()`` first in its text output. Machines differ by up to 3x on the same code (see docs/speed.md,
"Which machine"), so a figure without its CPU is not comparable.

Clocks: the headline is wall time (time.perf_counter). Beside it the thread's CPU time (time.thread_time)
where the work runs in the calling thread, or the process's CPU time (time.process_time, all threads of this
process) where it runs in other threads; work in child processes is wall time only. CPU time leaves out the
time the thread spends descheduled on a shared machine, so on a loaded machine it is the figure to compare,
on a quiet one the two agree.

    python bench/machine.py [--json]
"""
from __future__ import annotations

import json
import os
import platform
import sys
import time

WALL_CPU_NOTE = "wall time, thread CPU time beside it"


def _cpu_model() -> str:
    try:
        with open("/proc/cpuinfo", encoding="utf-8", errors="replace") as f:
            for line in f:
                if line.lower().startswith("model name"):
                    name = line.split(":", 1)[1].strip()
                    if name:
                        return name
    except OSError:
        pass
    return platform.processor() or platform.machine() or "unknown"


def _numba_target():
    """numba's target CPU name and features as it compiles: NUMBA_CPU_NAME / NUMBA_CPU_FEATURES if set,
    else the host's as LLVM sees them."""
    try:
        from numba.core import config
        import llvmlite.binding as llvm
    except ImportError:
        return None, None
    name = getattr(config, "CPU_NAME", None) or llvm.get_host_cpu_name()
    feats = getattr(config, "CPU_FEATURES", None)
    if not feats:
        try:
            feats = llvm.get_host_cpu_features().flatten()
        except RuntimeError:       # some hosts report no feature list
            feats = ""
    return str(name), str(feats)


def _version(mod: str):
    try:
        return __import__(mod).__version__
    except Exception:  # noqa: BLE001  (a benchmark must not fail on a missing version)
        return None


def machine_info() -> dict:
    """The machine and software a benchmark runs on (keys: cpu_model, numba_cpu_name, numba_cpu_features,
    cores, cores_usable, python, numba, numpy, bearing_plain_math)."""
    name, feats = _numba_target()
    try:
        usable = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        usable = os.cpu_count()
    return {
        "cpu_model": _cpu_model(),
        "numba_cpu_name": name,
        "numba_cpu_features": feats,
        "cores": os.cpu_count(),
        "cores_usable": usable,
        "python": platform.python_version(),
        "numba": _version("numba"),
        "numpy": _version("numpy"),
        "bearing_plain_math": os.environ.get("BEARING_PLAIN_MATH"),
    }


def _key_features(feats: str | None) -> str:
    """The SIMD features that matter for the kernels' speed, from LLVM's '+a,-b,...' list."""
    if not feats:
        return ""
    on = {f[1:] for f in feats.split(",") if f.startswith("+")}
    keep = [f for f in ("avx512f", "avx2", "fma", "avx", "sse4.2", "neon", "sve") if f in on]
    return ",".join("+" + f for f in keep)


def machine_line(info: dict | None = None, clock: str = WALL_CPU_NOTE) -> str:
    """One line for the top of a benchmark's text output, e.g.
    'machine: AMD EPYC 7B12 | numba target znver2 (+avx2,+fma,+avx) | 2 cores | wall time, thread CPU time
    beside it'. clock says which times the benchmark reports."""
    m = info or machine_info()
    cores = f"{m['cores']} cores" + (f" ({m['cores_usable']} usable)" if m["cores_usable"] != m["cores"] else "")
    feats = _key_features(m["numba_cpu_features"])
    plain = " | BEARING_PLAIN_MATH=" + m["bearing_plain_math"] if m["bearing_plain_math"] else ""
    return (f"machine: {m['cpu_model']} | numba target {m['numba_cpu_name']}" + (f" ({feats})" if feats else "")
            + f" | {cores}{plain} | {clock}")


class Timer:
    """Wall time (the headline) and CPU time beside it over a ``with`` block.

    cpu='thread' (time.thread_time, for work in the calling thread) or 'process' (time.process_time, all
    threads of this process: work in a thread pool). After the block: .wall_s, .cpu_s, .cpu_clock."""

    def __init__(self, cpu: str = "thread"):
        if cpu not in ("thread", "process"):
            raise ValueError("cpu must be 'thread' or 'process'")
        self.cpu_clock = cpu
        self._cpu = time.thread_time if cpu == "thread" else time.process_time
        self.wall_s = self.cpu_s = 0.0

    def __enter__(self):
        self._c0 = self._cpu()
        self._w0 = time.perf_counter()
        return self

    def __exit__(self, *exc):
        self.wall_s = time.perf_counter() - self._w0
        self.cpu_s = self._cpu() - self._c0
        return False


def timed(fn, *args, cpu: str = "thread", **kw):
    """(result, wall_s, cpu_s) of fn(*args, **kw); cpu as in Timer."""
    with Timer(cpu) as t:
        r = fn(*args, **kw)
    return r, t.wall_s, t.cpu_s


def best_of(fn, repeats: int, *args, cpu: str = "thread"):
    """Smallest wall time and smallest CPU time [s] of `repeats` calls fn(*args) (each minimum on its own)."""
    bw = bc = float("inf")
    for _ in range(repeats):
        _, w, c = timed(fn, *args, cpu=cpu)
        bw, bc = min(bw, w), min(bc, c)
    return bw, bc


if __name__ == "__main__":
    if "--json" in sys.argv[1:]:
        print(json.dumps({"machine": machine_info()}))
    else:
        print(machine_line())
