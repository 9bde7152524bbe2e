"""Load validation cases, run them (optionally in parallel processes), judge them, write the report.

Case file (JSON, one per case, bearing_validation/cases/<id>.json):
  id, title, source {reference, item (table / figure / section), page}, kind (name in kinds.KINDS),
  inputs {...}, quantity (text), reference {key: value or list} (published values only),
  tolerance {"rel" | "abs": x, "per_key": {key: {"rel" | "abs": x}}}, tolerance_reason,
  checks [ {type: monotone | greater | equal | true | range, ...} ] (trend checks on ours),
  verdict: "match" | "trend" | "known-gap", gap_reason (known-gap), quick: bool,
  plot {x, series, xlabel, ylabel, logy} (optional overlay of ours against the published values).

Judgement:
  match     - every reference key within its tolerance, and every check holds;
  trend     - every check holds (reference keys, if any, are shown with their error for information);
  known-gap - computed and listed with the recorded reason; never fails.
"""
from __future__ import annotations

import json
import math
import time
import traceback
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path

import numpy as np

from . import kinds as _kinds

VERDICT_KINDS = ("match", "trend", "known-gap")


# ------------------------------------------------------------------------------------------------
# cases
def cases_dir() -> Path:
    return Path(str(resources.files("bearing_validation") / "cases"))


def load_cases(names=None, quick=False, directory=None) -> list[dict]:
    """All cases (sorted by id), or those named, or the quick subset. Unknown names raise ValueError."""
    d = Path(directory) if directory else cases_dir()
    cases = []
    for f in sorted(d.glob("*.json")):
        c = json.loads(f.read_text())
        _validate_case(c, f)
        cases.append(c)
    if names:
        ids = {c["id"]: c for c in cases}
        missing = [n for n in names if n not in ids]
        if missing:
            raise ValueError(f"unknown validation case(s) {missing}; known: {sorted(ids)}")
        cases = [ids[n] for n in names]
    elif quick:
        cases = [c for c in cases if c.get("quick")]
    return cases


def _validate_case(c, f):
    for key in ("id", "source", "kind", "inputs", "quantity", "reference", "verdict", "quick"):
        if key not in c:
            raise ValueError(f"validation case {f.name}: missing key '{key}'")
    if c["verdict"] not in VERDICT_KINDS:
        raise ValueError(f"validation case {c['id']}: verdict '{c['verdict']}' not in {VERDICT_KINDS}")
    if c["kind"] not in _kinds.KINDS:
        raise ValueError(f"validation case {c['id']}: unknown kind '{c['kind']}'; known: {sorted(_kinds.KINDS)}")
    if c["verdict"] == "known-gap" and not c.get("gap_reason"):
        raise ValueError(f"validation case {c['id']}: a known-gap case needs 'gap_reason'")
    if c["verdict"] == "match" and c["reference"] and "tolerance" not in c:
        raise ValueError(f"validation case {c['id']}: a match case needs 'tolerance'")
    if f.stem != c["id"]:
        raise ValueError(f"validation case file {f.name} must be named after its id '{c['id']}'")


# ------------------------------------------------------------------------------------------------
# judgement
def _tol_for(case, key):
    t = case.get("tolerance", {})
    t = t.get("per_key", {}).get(key, t)
    if "abs" in t:
        return "abs", float(t["abs"])
    return "rel", float(t.get("rel", 0.0))


def _errors(ref, got, mode):
    r = np.atleast_1d(np.asarray(ref, float))
    g = np.atleast_1d(np.asarray(got, float))
    if r.size == 1 and g.size > 1:
        r = np.full(g.shape, r[0])
    if r.shape != g.shape:
        raise ValueError(f"reference shape {r.shape} and ours {g.shape} differ")
    if mode == "abs":
        return np.abs(g - r)
    return np.abs(g / r - 1.0)


def _check(chk, ours):
    """One trend check on ours. Returns (ok, text)."""
    t = chk["type"]
    if t == "monotone":
        y = np.asarray(ours[chk["key"]], float)
        d = np.diff(y)
        ok = bool(np.all(d < 0) if chk["direction"] == "decreasing" else np.all(d > 0))
        return ok, f"{chk['key']} {chk['direction']}"
    if t == "greater":
        a = float(ours[chk["a"]]) if not isinstance(chk["a"], (int, float)) else float(chk["a"])
        b = float(ours[chk["b"]]) if not isinstance(chk["b"], (int, float)) else float(chk["b"])
        f = float(chk.get("factor", 1.0))
        return a > f * b, f"{chk['a']} > {f:g} x {chk['b']}"
    if t == "equal":
        got = ours[chk["key"]]
        return got == chk["value"], f"{chk['key']} == {chk['value']}"
    if t == "true":
        v = ours[chk["key"]]
        ok = bool(all(v)) if isinstance(v, list) else bool(v)
        return ok, f"{chk['key']} holds"
    if t == "range":
        v = np.atleast_1d(np.asarray(ours[chk["key"]], float))
        lo, hi = chk.get("min", -math.inf), chk.get("max", math.inf)
        return bool(np.all((v >= lo) & (v <= hi))), f"{lo:g} <= {chk['key']} <= {hi:g}"
    raise ValueError(f"unknown check type '{t}'")


def judge(case, ours) -> dict:
    """Compare ours with the case's reference and checks; returns the result record (JSON-able)."""
    rows = []
    worst = 0.0
    within = True
    for key, ref in case["reference"].items():
        if key not in ours:
            raise ValueError(f"case {case['id']}: kind '{case['kind']}' returned no '{key}'")
        mode, tol = _tol_for(case, key)
        err = _errors(ref, ours[key], mode)
        e = float(np.max(err))
        ok = bool(np.all(err <= tol))
        within &= ok
        worst = max(worst, e / tol if tol > 0 else (0.0 if e == 0 else math.inf))
        rows.append({"key": key, "reference": ref, "ours": ours[key], "error": e, "error_mode": mode,
                     "tolerance": tol, "ok": ok})
    checks = []
    for chk in case.get("checks", []):
        ok, text = _check(chk, ours)
        checks.append({"check": text, "ok": bool(ok)})
    checks_ok = all(c["ok"] for c in checks)
    v = case["verdict"]
    if v == "match":
        status = "PASS" if (within and checks_ok) else "FAIL"
    elif v == "trend":
        status = "PASS" if checks_ok else "FAIL"
    else:
        status = "GAP"
    # a known gap that now meets its tolerance and checks is flagged for reclassification
    gap_closed = bool(v == "known-gap" and within and checks_ok and (rows or checks))
    return {"id": case["id"], "verdict": v, "status": status, "within_tolerance": bool(within),
            "checks_ok": bool(checks_ok), "rows": rows, "checks": checks, "worst_error_over_tolerance": worst,
            "gap_closed": gap_closed}


# ------------------------------------------------------------------------------------------------
# running
@dataclass
class CaseResult:
    case: dict
    status: str                       # PASS / FAIL / GAP / ERROR
    judgement: dict = field(default_factory=dict)
    ours: dict = field(default_factory=dict)
    wall_s: float = 0.0
    error: str = ""

    @property
    def failed(self):
        return self.status in ("FAIL", "ERROR")


def run_case(case: dict) -> CaseResult:
    """Run one case in this process (the kind's library calls), judge it; exceptions become ERROR."""
    t0 = time.perf_counter()
    try:
        ours = _kinds.KINDS[case["kind"]](case["inputs"])
        j = judge(case, ours)
        return CaseResult(case, j["status"], j, _jsonable(ours), time.perf_counter() - t0)
    except Exception:  # noqa: BLE001 -- reported as ERROR with its traceback, and fails the run
        return CaseResult(case, "ERROR", {}, {}, time.perf_counter() - t0, traceback.format_exc())


def run_cases(cases, jobs=1, progress=None) -> list[CaseResult]:
    """Run the cases; jobs > 1 uses that many worker processes (ProcessPoolExecutor). Order kept."""
    if jobs <= 1 or len(cases) <= 1:
        out = []
        for c in cases:
            r = run_case(c)
            if progress:
                progress(r)
            out.append(r)
        return out
    with ProcessPoolExecutor(max_workers=jobs) as ex:
        futs = [ex.submit(run_case, c) for c in cases]
        out = []
        for f in futs:
            r = f.result()
            if progress:
                progress(r)
            out.append(r)
        return out


def _jsonable(x):
    if isinstance(x, dict):
        return {str(k): _jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_jsonable(v) for v in x]
    if isinstance(x, np.ndarray):
        return _jsonable(x.tolist())
    if isinstance(x, (np.bool_,)):
        return bool(x)
    if isinstance(x, (np.integer,)):
        return int(x)
    if isinstance(x, (np.floating, float)):
        return float(x) if math.isfinite(x) else str(float(x))
    return x


def counts(results) -> dict:
    c = {"PASS": 0, "FAIL": 0, "GAP": 0, "ERROR": 0}
    for r in results:
        c[r.status] += 1
    return c
