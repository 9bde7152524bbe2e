"""The package's architecture, checked mechanically: the import-linter contracts of pyproject.toml (bearing_core's
layers import only downward; bearing_core never imports the FMU glue, the validation record, fmpy or pythonfmu),
no import cycle among the project's own modules (imports inside functions included), and a short top level."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import grimp

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = ("bearing_core", "bearing_cosim", "bearing_validation")


def _cycles(graph) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan), i.e. the import cycles."""
    index, low, on, stack, out = {}, {}, set(), [], []
    counter = [0]
    sys.setrecursionlimit(max(10000, sys.getrecursionlimit()))

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph.find_modules_directly_imported_by(v):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for m in sorted(graph.modules):
        if m not in index:
            visit(m)
    return out


def test_import_linter_contracts_hold():
    exe = Path(sys.executable).with_name("lint-imports")
    r = subprocess.run([str(exe), "--config", str(ROOT / "pyproject.toml")], cwd=ROOT, capture_output=True,
                       text=True, timeout=300)
    assert r.returncode == 0, r.stdout[-4000:] + r.stderr[-2000:]
    assert "2 kept, 0 broken" in r.stdout


def test_no_import_cycle_among_project_modules():
    graph = grimp.build_graph(*PACKAGES)
    assert _cycles(graph) == []


def test_cycle_finder_finds_a_cycle(tmp_path, monkeypatch):
    """The check above can fail: two modules importing each other are reported."""
    pkg = tmp_path / "cyclepkg_layers"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "a.py").write_text("from . import b\n")
    (pkg / "b.py").write_text("def f():\n    from . import a\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    graph = grimp.build_graph("cyclepkg_layers", cache_dir=None)
    assert _cycles(graph) == [["cyclepkg_layers.a", "cyclepkg_layers.b"]]


def test_top_level_is_short_and_every_layer_is_a_package():
    core = ROOT / "bearing_core"
    top = sorted(p.name for p in core.glob("*.py"))
    assert len(top) <= 5, top
    for layer in ("numerics", "bearing", "contact", "lubrication", "heat", "models", "session", "maps"):
        assert (core / layer / "__init__.py").is_file(), layer


def test_public_api_resolves_and_import_stays_light():
    """`import bearing_core` loads no numba; every name of the public face resolves to its layer's object."""
    code = ("import sys, bearing_core as b\n"
            "assert 'numba' not in sys.modules, 'numba imported by the package import'\n"
            "from bearing_core.models.dynamics import DynamicModel\n"
            "assert b.DynamicModel is DynamicModel\n"
            "missing = [n for n in b.__all__ if getattr(b, n, None) is None]\n"
            "assert not missing, missing\n"
            "try:\n    b.no_such_name\nexcept AttributeError:\n    pass\nelse:\n    raise SystemExit('no error')\n")
    r = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-3000:]
