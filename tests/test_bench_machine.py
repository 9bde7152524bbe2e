"""bench/machine.py: the machine record every benchmark carries (no timing assertions)."""
import importlib.util
from pathlib import Path

KEYS = {"cpu_model", "numba_cpu_name", "numba_cpu_features", "cores", "cores_usable", "python", "numba", "numpy",
        "bearing_plain_math"}


def _machine():
    path = Path(__file__).resolve().parents[1] / "bench" / "machine.py"
    spec = importlib.util.spec_from_file_location("bench_machine", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_machine_info_keys():
    m = _machine()
    info = m.machine_info()
    assert set(info) == KEYS
    assert isinstance(info["cpu_model"], str) and info["cpu_model"].strip()
    assert info["cores"] >= 1 and info["cores_usable"] >= 1
    assert info["numba_cpu_name"]
    line = m.machine_line(info)
    assert line.startswith("machine: ") and info["cpu_model"] in line and "\n" not in line


def test_timer_reports_both_clocks():
    m = _machine()
    with m.Timer() as t:
        sum(range(1000))
    assert t.wall_s >= 0.0 and t.cpu_s >= 0.0 and t.cpu_clock == "thread"
    _, w, c = m.timed(sum, range(10), cpu="process")
    assert w >= 0.0 and c >= 0.0
