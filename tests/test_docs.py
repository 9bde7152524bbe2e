"""The manual (MkDocs site of docs/, mkdocs.yml) and the README as its front page.

* The site builds with `mkdocs build --strict` (5.6 s wall here on 2 cores, of which about 3.5 s build the two
  FMUs for the variables tables; the test prints it), and a broken link fails such a build.
* The variables tables of the site are those of the FMUs: both FMUs are built here again and read with fmpy, and
  every row of the site's tables is compared with fmpy's reading of every variable.
* Every code block of the README and of the manual (and of the files the manual includes) is run, or marked with
  `<!-- not run: REASON -->` on the line before it: Python blocks with mktestdocs (the blocks of one file share
  one namespace, in order), shell blocks with bash, JSON blocks parsed (a bearing file is loaded).
* Every script in examples/ runs at a small size and draws its picture.
* `bearing docs` serves the site.

Together 67 s wall on 2 cores with the numba caches warm (the examples about 34 s of it).
"""
from __future__ import annotations

import json
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import time
import urllib.request
from html.parser import HTMLParser
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
BIN = Path(sys.executable).parent
MARK = re.compile(r"^<!-- not run: (.+) -->$")
INCLUDE = re.compile(r'^--8<-- "([^"]+)"\s*$', re.M)


def _env():
    env = dict(os.environ)
    env.setdefault("NUMBA_CACHE_DIR", str(ROOT / ".numba_cache"))
    env["PATH"] = str(BIN) + os.pathsep + env.get("PATH", "")
    env["NO_MKDOCS_2_WARNING"] = "1"
    return env


def _doc_files() -> list:
    """README.md, every page of docs/ (not the generated validation reports) and the files pages include."""
    files = [ROOT / "README.md"] + sorted(p for p in DOCS.rglob("*.md") if "validation_report" not in p.parts)
    for p in list(files):
        files += [ROOT / inc for inc in INCLUDE.findall(p.read_text(encoding="utf-8"))]
    return files


def _blocks(path: Path) -> list:
    """Code blocks of a Markdown file (markdown-it, CommonMark): dicts with file, line, lang, code and the reason
    of a `<!-- not run: ... -->` marker on the nearest non-blank line before the block (None if not marked)."""
    from markdown_it import MarkdownIt
    text = path.read_text(encoding="utf-8")
    lines = text.splitlines()
    out = []
    for tok in MarkdownIt().parse(text):
        if tok.type not in ("fence", "code_block"):
            continue
        k = tok.map[0] - 1
        while k >= 0 and not lines[k].strip():
            k -= 1
        m = MARK.match(lines[k].strip()) if k >= 0 else None
        out.append({"file": path.relative_to(ROOT).as_posix(), "line": tok.map[0] + 1,
                    "lang": tok.info.strip().split(" ")[0] if tok.type == "fence" else "",
                    "code": tok.content, "not_run": m.group(1) if m else None})
    return out


ALL_BLOCKS = [b for f in _doc_files() for b in _blocks(f)]
RUN_LANGS = ("python", "bash", "json")


# ---- fixtures -------------------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def fmus(tmp_path_factory):
    """dist/BearingFMU.fmu (thin build) and dist/BearingMapFMU.fmu (maps/7218B_oil.nc, linux64) in a work folder."""
    from bearing_cosim.fmu_build import build
    from bearing_cosim.map_fmu import build_map_fmu
    work = tmp_path_factory.mktemp("docs_work")
    build(work / "dist")
    build_map_fmu(ROOT / "maps" / "7218B_oil.nc", work / "dist", ["linux64"])
    return work


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    out = tmp_path_factory.mktemp("site")
    t0 = time.perf_counter()
    p = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(out)], cwd=ROOT,
                       capture_output=True, text=True, env=_env(), timeout=600)
    wall = time.perf_counter() - t0
    print(f"mkdocs build --strict: {wall:.1f} s wall")
    return {"proc": p, "dir": out, "wall_s": wall}


# ---- the site -------------------------------------------------------------------------------------------------

def test_site_builds_strict(site):
    p = site["proc"]
    assert p.returncode == 0, f"mkdocs build --strict failed:\n{p.stdout[-3000:]}\n{p.stderr[-6000:]}"
    d = site["dir"]
    for page in ("index.html", "getting_started/index.html", "using/variables/index.html", "api/index.html",
                 "examples/index.html", "validation/index.html", "validation_report/report.html",
                 "figures/main_fmu_simulation.png"):
        assert (d / page).is_file(), page
    api = (d / "api" / "index.html").read_text(encoding="utf-8")
    import bearing_core
    for name in bearing_core.__all__:          # the API reference lists the whole public face
        assert f'id="bearing_core.{bearing_core._API[name]}.{name}"' in api, name
    validation = (d / "validation" / "index.html").read_text(encoding="utf-8")
    assert 'href="../validation_report/report.html"' in validation


def test_strict_build_fails_on_a_broken_link(tmp_path):
    """The site's own settings (mkdocs.yml, inherited) turn a link to a missing page into a failed build."""
    docs = tmp_path / "docs"
    docs.mkdir()
    (docs / "index.md").write_text("# Home\n\nSee [the missing page](missing.md).\n")
    cfg = tmp_path / "mkdocs.yml"
    cfg.write_text(f"INHERIT: {ROOT / 'mkdocs.yml'}\ndocs_dir: {docs}\nnav:\n  - index.md\nhooks: []\n"
                   "plugins:\n  - search\n")
    p = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-f", str(cfg), "--site-dir",
                        str(tmp_path / "site")], capture_output=True, text=True, env=_env(), timeout=120)
    assert p.returncode != 0 and "missing.md" in p.stderr, p.stderr[-3000:]


class _Tables(HTMLParser):
    """Rows of cell texts of every <table> of a page, and the text of each <p> before a table."""

    def __init__(self):
        super().__init__()
        self.tables, self.paras, self._row, self._cell, self._p = [], [], None, None, None

    def handle_starttag(self, tag, attrs):
        if tag == "table":
            self.tables.append([])
        elif tag == "tr":
            self._row = []
        elif tag in ("td", "th"):
            self._cell = ""
        elif tag == "p":
            self._p = ""

    def handle_endtag(self, tag):
        if tag in ("td", "th"):
            self._row.append(self._cell)
            self._cell = None
        elif tag == "tr":
            self.tables[-1].append(self._row)
        elif tag == "p":
            self.paras.append(self._p)
            self._p = None

    def handle_data(self, data):
        if self._cell is not None:
            self._cell += data
        if self._p is not None:
            self._p += data


def _expected_row(v) -> list:
    """A variable as fmpy reads it, in the site's columns: name, causality, variability, type, unit, start,
    range, description."""
    start = v.start or ""
    items = ""
    if v.type == "Enumeration":
        names = {it.value: it.name for it in v.declaredType.items}
        start = f"{start} ({names[start]})" if start else ""
        items = ", ".join(f"{it.value} = {it.name}" for it in v.declaredType.items)
    unit = (v.unit or "") + (f" (display {v.displayUnit})" if v.displayUnit else "") if v.type == "Real" else ""
    rng = f"[{v.min}, {v.max}]" if v.min is not None else ""
    desc = (v.description or "") + (f" [items: {items}]" if items else "")
    return [v.name, v.causality, v.variability, v.type, unit, start, rng, desc]


def test_variables_tables_match_the_fmus(site, fmus):
    from fmpy import read_model_description
    assert site["proc"].returncode == 0
    page = _Tables()
    page.feed((site["dir"] / "using" / "variables" / "index.html").read_text(encoding="utf-8"))
    assert len(page.tables) == 2, "one table per FMU"
    captions = [p for p in page.paras if p.startswith("Generated when this site was built")]
    for table, caption, fmu in zip(page.tables, captions, ("BearingFMU", "BearingMapFMU")):
        md = read_model_description(str(fmus / "dist" / f"{fmu}.fmu"))
        assert f"model description of {fmu} " in caption and md.guid in caption, caption
        assert table[0] == ["name", "causality", "variability", "type", "unit", "start", "range", "description"]
        assert len(table) - 1 == len(md.modelVariables), fmu
        for row, v in zip(table[1:], md.modelVariables):
            assert row == _expected_row(v), (fmu, v.name)


def test_fmu_documentation_has_the_same_table(fmus):
    """Each FMU's own documentation/index.html carries the table the site is generated from (one generator)."""
    import zipfile
    from xml.etree import ElementTree as ET
    from bearing_cosim.fmu_build import variable_rows, variables_table_html
    for fmu in ("BearingFMU", "BearingMapFMU"):
        with zipfile.ZipFile(fmus / "dist" / f"{fmu}.fmu") as z:
            xml = ET.fromstring(z.read("modelDescription.xml"))
            html = z.read("documentation/index.html").decode()
        assert variables_table_html(xml) in html, fmu
        assert len(variable_rows(xml)) == len(xml.find("ModelVariables"))


def test_bearing_docs_serves_the_site(tmp_path):
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    p = subprocess.Popen([str(BIN / "bearing"), "docs", "--dev-addr", f"127.0.0.1:{port}"], cwd=tmp_path,
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=_env(), start_new_session=True)
    try:
        deadline, html = time.time() + 180, None
        while time.time() < deadline and p.poll() is None and html is None:
            try:
                html = urllib.request.urlopen(f"http://127.0.0.1:{port}/using/variables/", timeout=5).read().decode()
            except OSError:
                time.sleep(1)
        assert html is not None, f"not served (exit {p.poll()}): {p.stderr.read().decode()[-3000:] if p.poll() else ''}"
        assert re.search(r"<title>FMU variables[^<]* - bearing-tribodynamics</title>", html) and "shaft_speed" in html
    finally:
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGTERM)
        p.wait(timeout=60)


# ---- the README -----------------------------------------------------------------------------------------------

def test_readme_is_a_front_page():
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    assert len(text.splitlines()) <= 120
    first = _blocks(ROOT / "README.md")[0]
    commands = [ln.split("#")[0].strip() for ln in first["code"].splitlines()]
    assert commands == ["bash scripts/main.sh", "bash scripts/test.sh"]       # the two commands come first
    assert (ROOT / "scripts" / "main.sh").is_file() and (ROOT / "scripts" / "test.sh").is_file()
    assert text.index("```bash") < text.index("![")                         # before the picture and the rest
    for target in re.findall(r"\]\(([^)#]+)(?:#[^)]*)?\)", text):
        if not target.startswith(("http://", "https://")):
            assert (ROOT / target).is_file(), f"README links to a missing file: {target}"
    png = ROOT / "docs" / "figures" / "main_fmu_simulation.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert any(b["lang"] == "python" and "simulate_fmu" in b["code"] and b["not_run"] is None
               for b in _blocks(ROOT / "README.md"))


# ---- code blocks ----------------------------------------------------------------------------------------------

def test_every_code_block_is_run_or_marked():
    bad = [f"{b['file']}:{b['line']} ({b['lang'] or 'no language'})" for b in ALL_BLOCKS
           if b["not_run"] is None and b["lang"] not in RUN_LANGS]
    assert not bad, "code blocks neither run here nor marked <!-- not run: REASON -->: " + ", ".join(bad)
    marked_python = [f"{b['file']}:{b['line']}" for b in ALL_BLOCKS if b["not_run"] and b["lang"] == "python"]
    assert not marked_python, "Python blocks are all run (mktestdocs runs every one of a file): " + \
        ", ".join(marked_python)
    assert all(len(b["not_run"].split()) >= 3 for b in ALL_BLOCKS if b["not_run"]), "a marker says why"


PY_FILES = sorted({b["file"] for b in ALL_BLOCKS if b["lang"] == "python"})


@pytest.mark.parametrize("path", PY_FILES)
def test_python_blocks_run(path, fmus, monkeypatch):
    """The file's Python blocks in order in one namespace (mktestdocs, memory mode), in a folder that has
    dist/BearingFMU.fmu and dist/BearingMapFMU.fmu."""
    from mktestdocs import check_md_file
    monkeypatch.chdir(fmus)
    check_md_file(ROOT / path, memory=True, lang="python")


SHELL_BLOCKS = [b for b in ALL_BLOCKS if b["lang"] == "bash" and b["not_run"] is None]


@pytest.mark.parametrize("block", SHELL_BLOCKS, ids=[f"{b['file']}:{b['line']}" for b in SHELL_BLOCKS])
def test_shell_blocks_run(block, fmus):
    """bash -e on the block as shown, in a folder with the FMUs in dist/, the venv's commands on PATH."""
    p = subprocess.run(["bash", "-euo", "pipefail", "-c", block["code"]], cwd=fmus, capture_output=True, text=True,
                       env=_env(), timeout=300)
    assert p.returncode == 0, f"{block['file']}:{block['line']} exit {p.returncode}:\n{p.stderr[-3000:]}"
    assert p.stdout.strip()


JSON_BLOCKS = [b for b in ALL_BLOCKS if b["lang"] == "json" and b["not_run"] is None]


@pytest.mark.parametrize("block", JSON_BLOCKS, ids=[f"{b['file']}:{b['line']}" for b in JSON_BLOCKS])
def test_json_blocks_parse(block, tmp_path):
    """JSON parses; a bearing file loads (bearing_core.load_bearing)."""
    d = json.loads(block["code"])
    if "number_of_balls" in d:
        import bearing_core as bc
        f = tmp_path / "bearing.json"
        f.write_text(block["code"])
        g = bc.load_bearing(str(f))
        assert g.Z == d["number_of_balls"]


# ---- examples -------------------------------------------------------------------------------------------------

EXAMPLES = {   # script: (arguments at a small size, picture)
    "fmpy_speed_load_profile.py": (["--stop-time", "0.05", "--fmu", "{fmu}"], "profile.png"),
    "user_bearing_file.py": (["--points", "3"], "user_bearing.png"),
    "map_build_and_use.py": ([], "map_fmu.png"),
    "ssp_rotor.py": (["--stop-time", "0.01"], "ssp_rotor.png"),
}


def test_examples_are_all_listed():
    assert sorted(p.name for p in (ROOT / "examples").glob("*.py")) == sorted(EXAMPLES)
    page = (DOCS / "examples.md").read_text(encoding="utf-8")
    assert all(f"examples/{name}" in page for name in EXAMPLES)


@pytest.mark.parametrize("script", sorted(EXAMPLES))
def test_example_runs(script, fmus, tmp_path):
    args, png = EXAMPLES[script]
    args = [a.replace("{fmu}", str(fmus / "dist" / "BearingFMU.fmu")) for a in args]
    p = subprocess.run([sys.executable, str(ROOT / "examples" / script), *args, "--out", str(tmp_path / "out")],
                       cwd=tmp_path, capture_output=True, text=True, env=_env(), timeout=600)
    assert p.returncode == 0, f"{script} exit {p.returncode}:\n{p.stdout[-2000:]}\n{p.stderr[-4000:]}"
    assert "wrote" in p.stdout.splitlines()[-1]
    assert (tmp_path / "out" / png).stat().st_size > 10_000
    shutil.rmtree(tmp_path / "out", ignore_errors=True)
