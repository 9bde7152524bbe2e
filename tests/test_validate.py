"""`bearing validate`: the quick validation cases as tests, the report, and the failure path.

Each quick case (bearing_validation/cases/*.json with "quick": true) is one test: it names its published
source, reference values, tolerance and the reason for it in the case file. A `match` or `trend` case
must pass; a `known-gap` case must run and stay listed with its reason (it never fails the run).
"""
import json

import pytest

from bearing_cosim import cli
from bearing_core.contact import hertz as hz
from bearing_validation import judge, load_cases, run_case, run_cases, write_report

QUICK = load_cases(quick=True)


@pytest.mark.parametrize("case", QUICK, ids=[c["id"] for c in QUICK])
def test_quick_case(case):
    """One quick validation case against its published reference (source and tolerance in the case file)."""
    r = run_case(case)
    assert r.status != "ERROR", r.error
    if case["verdict"] == "known-gap":
        assert r.status == "GAP" and case["gap_reason"]
    else:
        assert r.status == "PASS", json.dumps(r.judgement, indent=1, default=str)


def test_cases_are_well_formed_and_cover_the_record():
    """Every case cites a source and, when it compares numbers, a tolerance with its reason; the record covers
    the references the documentation claims."""
    cases = load_cases()
    for c in cases:
        assert c["source"]["reference"] and c["quantity"]
        if c["reference"] and c["verdict"] == "match":
            assert c["tolerance"] and c["tolerance_reason"], c["id"]
        if not c["reference"]:
            assert c["checks"] and c["reference_text"], c["id"]
    ids = " ".join(c["id"] for c in cases)
    for prefix in ("hertz-harris", "seed003-table2", "harris-218", "kalker-fastsim-linear", "contact-fastsim",
                   "kalker-table", "seed000-cage", "seed000-recovery", "seed000-table3", "seed000-preload",
                   "seed000-microslip", "seed002-", "seed004-prl", "seed004-fig11", "seed001-", "seed003-fig"):
        assert prefix in ids, prefix
    quick = [c for c in cases if c["quick"]]
    assert 0 < len(quick) < len(cases)
    assert not any(c["kind"] in ("seed000_profile", "held_speed_vibration") for c in quick)


def test_judge_match_trend_and_gap():
    """Judgement rules on hand-made results: match needs every key within tolerance, trend only its checks,
    known-gap never fails."""
    base = dict(id="x", kind="hertz_table", quantity="q", source={"reference": "r"}, inputs={}, quick=True)
    m = dict(base, verdict="match", reference={"a": [1.0, 2.0]}, tolerance={"rel": 0.01})
    assert judge(m, {"a": [1.005, 2.01]})["status"] == "PASS"
    assert judge(m, {"a": [1.005, 2.05]})["status"] == "FAIL"
    t = dict(base, verdict="trend", reference={}, checks=[{"type": "monotone", "key": "y", "direction": "decreasing"}])
    assert judge(t, {"y": [3, 2, 1]})["status"] == "PASS"
    assert judge(t, {"y": [3, 4, 1]})["status"] == "FAIL"
    g = dict(base, verdict="known-gap", reference={"a": 1.0}, tolerance={"abs": 0.1}, gap_reason="why")
    assert judge(g, {"a": 5.0})["status"] == "GAP"


def test_report_written(tmp_path):
    """report.html (summary table with source, reference, ours, error, tolerance, verdict and an embedded
    overlay plot), report.json and report.md."""
    cases = load_cases(names=["hertz-harris-dimensionless-table", "seed004-fig11-spin-torque"])
    res = run_cases(cases, jobs=1)
    p = write_report(res, tmp_path, markdown=True)
    h = p["html"].read_text()
    for s in ("hertz-harris-dimensionless-table", "Harris &amp; Kotzalas", "tolerance", "data:image/png;base64",
              "known gap", "seed004-fig11-spin-torque"):
        assert s in h, s
    d = json.loads(p["json"].read_text())
    assert [c["status"] for c in d["cases"]] == ["PASS", "GAP"]
    md = p["markdown"].read_text()
    assert "| hertz-harris-dimensionless-table |" in md and "Known gaps" in md


def test_broken_hertz_constant_fails_and_names_the_cases(monkeypatch, tmp_path, capsys):
    """Done-when check: a 5 % error in the Hertz constants (the semi-axis coefficients a = a_coef Q^(1/3),
    b = b_coef Q^(1/3) returned by hertz_exact) makes `bearing validate` exit non-zero and name the Hertz
    table cases, while a case that does not use them still passes."""
    orig = hz._constants_from_kEK_nb

    def broken(k, E, K, R, E_red):
        k, E, K, ac, bc, KL = orig(k, E, K, R, E_red)
        return k, E, K, 1.05 * ac, 1.05 * bc, KL

    monkeypatch.setattr(hz, "_constants_from_kEK_nb", broken)
    names = ["hertz-harris-dimensionless-table", "hertz-harris-astar-high-conformity", "film-stachowiak-batchelor"]
    argv = ["validate", "--out", str(tmp_path)] + [x for n in names for x in ("--case", n)]
    assert cli.main(argv) == 1
    out = capsys.readouterr().out
    failed_line = [ln for ln in out.splitlines() if ln.startswith("FAILED:")][0]
    assert "hertz-harris-dimensionless-table" in failed_line and "hertz-harris-astar-high-conformity" in failed_line
    assert "film-stachowiak-batchelor" not in failed_line
    d = json.loads((tmp_path / "report.json").read_text())
    assert {c["id"]: c["status"] for c in d["cases"]} == {
        "hertz-harris-dimensionless-table": "FAIL", "hertz-harris-astar-high-conformity": "FAIL",
        "film-stachowiak-batchelor": "PASS"}


def test_cli_bad_arguments(capsys):
    """Unknown case names and an invalid --jobs exit 2 with the reason."""
    assert cli.main(["validate", "--case", "no-such-case"]) == 2
    assert "no-such-case" in capsys.readouterr().err
    assert cli.main(["validate", "--jobs", "0", "--quick"]) == 2
    assert "--jobs" in capsys.readouterr().err


def test_parallel_runner_matches_serial():
    """--jobs 2 (worker processes) gives the same results as a serial run, in case order."""
    cases = load_cases(names=["seed003-table2-wan105", "hertz-harris-209-curvature"])
    a = run_cases(cases, jobs=1)
    b = run_cases(cases, jobs=2)
    assert [r.case["id"] for r in b] == [c["id"] for c in cases]
    assert [r.ours for r in a] == [r.ours for r in b]


def test_update_doc_section_replaces_only_its_block(tmp_path):
    """--update-doc: the generated table replaces the text between its own markers, nothing else."""
    from bearing_validation import update_doc_section
    doc = tmp_path / "v.md"
    doc.write_text("intro\n<!-- bearing validate: quick begin -->\nold\n<!-- bearing validate: quick end -->\n"
                   "middle\n<!-- bearing validate: full begin -->\nkeep\n<!-- bearing validate: full end -->\n")
    update_doc_section(doc, "quick", "| new |")
    t = doc.read_text()
    assert "old" not in t and "| new |" in t and "keep" in t and t.startswith("intro\n") and "middle" in t
