"""Count host processes that abort at exit after running the bearing FMU (docs/fmu.md).

    python bench/fmu_exit_check.py [--runs 200] [--fmu dist/BearingFMU.fmu] [--hosts fmpy,fmpy-numba,two,c] [--progress]

Each run is a fresh process (round robin over the hosts; with --progress one JSON line per run on stderr, so a
check stopped early still counts every host alike) that loads the FMU, simulates 10 ms (1 ms steps, 1000 rpm, Fx 1 kN, Fz 3 kN)
and exits normally (the C exit handlers and library destructors run). Hosts:
  fmpy        tests/fmu_driver.py (fmpy FMU2Slave)
  fmpy-numba  the same, with numba imported by the host before the FMU is loaded
  two         two instances of the FMU in one fmpy process
  c           tests/c_host/host.c (compiled here with gcc): a C master, no Python in the host
Prints one JSON line per host: exit-status histogram, runs without results, model processes left without their
master (orphans), hangs (runs killed after --timeout), wall time (wall_s) and beside it the CPU time of the child processes (children_cpu_s: user +
system of the finished runs, os.times; the work runs in child processes), and the machine (bench/machine.py) under
"machine", e.g. {"host": "c", "runs": 200, "exit": {"0": 200}, "orphans": 0, ...}. Quickest check: ``--runs 1
--hosts fmpy``.
"""
import argparse
import collections
import json
import math
import os
import subprocess
import sys
import tempfile
import time
import zipfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))
from machine import machine_info  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=50)
    ap.add_argument("--fmu", default=str(ROOT / "dist" / "BearingFMU.fmu"))
    ap.add_argument("--hosts", default="fmpy,fmpy-numba,two,c")
    ap.add_argument("--progress", action="store_true", help="one line per run on stderr (partial counts)")
    ap.add_argument("--timeout", type=float, default=300.0,
                    help="a run not finished after this many seconds is killed and counted as a hang")
    a = ap.parse_args()
    mach = machine_info()
    w = 1000 * math.pi / 30
    inp = {"shaft_speed": w, "Fx": 1000.0, "Fz": 3000.0}
    spec = {"fmu": a.fmu, "params": {}, "start_inputs": inp, "steps": [[1e-3, inp]] * 10, "outputs": ["cage_speed"]}
    with tempfile.TemporaryDirectory() as td:
        td = Path(td)
        p1 = td / "spec.json"
        p1.write_text(json.dumps(spec))
        p2 = td / "two.json"
        p2.write_text(json.dumps(dict(spec, mode="two", start_inputs_2=dict(inp, Fz=4000.0),
                                      inputs_2=dict(inp, Fz=4000.0))))
        numba_first = td / "numba_first.py"
        numba_first.write_text("import runpy, sys\nimport numba  # noqa: F401\nsys.argv = sys.argv[1:]\n"
                               "runpy.run_path(sys.argv[0], run_name='__main__')\n")
        driver = str(ROOT / "tests" / "fmu_driver.py")
        cmds = {"fmpy": [sys.executable, driver, str(p1)],
                "fmpy-numba": [sys.executable, str(numba_first), driver, str(p1)],
                "two": [sys.executable, driver, str(p2)]}
        env = dict(os.environ)
        if "c" in a.hosts.split(","):
            from fmpy import read_model_description
            md = read_model_description(a.fmu)
            vr = {v.name: v.valueReference for v in md.modelVariables}
            unz = td / "unz"
            with zipfile.ZipFile(a.fmu) as z:
                z.extractall(unz)
            host = td / "host"
            subprocess.run(["gcc", "-std=gnu99", "-O2", "-o", str(host), str(ROOT / "tests" / "c_host" / "host.c"),
                            "-ldl"], check=True)
            script = td / "script.txt"
            script.write_text("\n".join(
                ["instantiate 0", "setup 0", "enter", f"set_real {vr['shaft_speed']} {w!r}",
                 f"set_real {vr['Fx']} 1000", f"set_real {vr['Fz']} 3000", "exit",
                 f"inputs {vr['shaft_speed']} {vr['Fx']} {vr['Fz']}", f"outputs {vr['cage_speed']}"]
                + [f"step 0.001 {w!r} 1000 3000"] * 10 + ["terminate", "free"]) + "\n")
            cmds["c"] = [str(host), str(unz), md.coSimulation.modelIdentifier, md.guid, str(script)]
        hosts = a.hosts.split(",")
        counts = {h: collections.Counter() for h in hosts}
        bad_out = dict.fromkeys(hosts, 0)
        hangs = dict.fromkeys(hosts, 0)
        wall = dict.fromkeys(hosts, 0.0)
        seen_orphans = set()
        # round robin over the hosts, so that a run stopped early has the same count of each
        for k in range(a.runs):
            for name in hosts:
                e = env if name != "c" else {k2: v for k2, v in env.items() if k2 not in ("PYTHONPATH", "LD_PRELOAD")}
                t0 = time.perf_counter()
                try:
                    r = subprocess.run(cmds[name], capture_output=True, text=True, env=e, timeout=a.timeout)
                except subprocess.TimeoutExpired:
                    hangs[name] += 1
                    counts[name]["hang"] += 1
                    if a.progress:
                        sys.stderr.write(json.dumps({"run": k, "host": name, "hang": True}) + "\n")
                    continue
                finally:
                    wall[name] += time.perf_counter() - t0
                counts[name][str(r.returncode)] += 1
                ok_out = ("RESULT " in r.stdout) if name != "c" else (r.stdout.count("ROW 0 0") == 10)
                bad_out[name] += not ok_out
                if a.progress:
                    sys.stderr.write(json.dumps({"run": k, "host": name, "exit": r.returncode, "results": ok_out})
                                     + "\n")
                    sys.stderr.flush()
            if k % 10 == 9 or k == a.runs - 1:
                time.sleep(1.0)   # a model process whose master ended exits within 0.5 s
                seen_orphans |= set(orphans())
                if a.progress:
                    sys.stderr.write(json.dumps({"run": k, "orphans": len(seen_orphans)}) + "\n")
        ch = os.times()
        for name in hosts:
            print(json.dumps({"host": name, "runs": a.runs, "exit": dict(counts[name]),
                              "runs_without_results": bad_out[name] + hangs[name], "hangs": hangs[name],
                              "orphans": len(seen_orphans), "wall_s": round(wall[name], 1),
                              "children_cpu_s_all_hosts": round(ch.children_user + ch.children_system, 1),
                              "machine": mach}), flush=True)


def orphans():
    """Model processes of the FMU (resources/model_process.py) whose master has gone (parent pid 1)."""
    out = []
    for d in Path("/proc").iterdir():
        if d.name.isdigit():
            try:
                cmd = (d / "cmdline").read_bytes().replace(b"\0", b" ")
                ppid = int((d / "stat").read_text().rsplit(")", 1)[1].split()[1])
            except (OSError, ValueError):
                continue
            if b"model_process.py" in cmd and ppid == 1:
                out.append(int(d.name))
    return out


if __name__ == "__main__":
    main()
