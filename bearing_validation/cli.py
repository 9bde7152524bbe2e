"""`bearing validate`: runs the validation cases and writes the report (registered by the `bearing` console
script, bearing_cosim.cli)."""
from __future__ import annotations

import json

from bearing_core.cli import _BadArg as BadArg


def add_parser(subparsers):
    """Add the `validate` command to an argparse subparsers action."""
    va = subparsers.add_parser("validate", help="run the validation cases (published references: papers, textbooks) "
                                         "and write report.html / report.json; exit 1 if a match or trend "
                                         "case fails")
    va.add_argument("--quick", action="store_true", help="fast subset only (no transient dynamics)")
    va.add_argument("--case", action="append", default=[], metavar="NAME", help="run this case (repeatable)")
    va.add_argument("--jobs", type=int, default=1, help="parallel worker processes (default 1)")
    va.add_argument("--out", default="out/validation", help="report directory")
    va.add_argument("--markdown", action="store_true", help="also write report.md (summary table for docs)")
    va.add_argument("--update-doc", metavar="FILE.md", help="write the summary table into this markdown file "
                                                             "between its 'bearing validate: quick|full' markers")
    va.add_argument("--list", action="store_true", help="list the cases and exit")
    va.set_defaults(func=cmd_validate)


def cmd_validate(a) -> int:
    import time

    from . import counts, load_cases, markdown_table, run_cases, update_doc_section, write_report

    if not (1 <= a.jobs <= 64):
        raise BadArg(f"--jobs = {a.jobs} is invalid; allowed: 1 <= jobs <= 64")
    try:
        cases = load_cases(names=a.case or None, quick=a.quick)
    except ValueError as e:
        raise BadArg(str(e))
    if a.list:
        for c in cases:
            print(f"{c['id']:42s} {c['verdict']:9s} {'quick' if c.get('quick') else 'full '} {c['kind']}")
        return 0
    t0 = time.perf_counter()

    def progress(r):
        print(f"{r.status:5s} {r.case['id']:42s} {r.case['verdict']:9s} {r.wall_s:7.1f} s", flush=True)

    results = run_cases(cases, jobs=a.jobs, progress=progress)
    wall = time.perf_counter() - t0
    argv = (["bearing validate"] + (["--quick"] if a.quick else []) + [f"--case {n}" for n in a.case]
            + ([f"--jobs {a.jobs}"] if a.jobs > 1 else []))
    paths = write_report(results, a.out, command=" ".join(argv), wall_s=wall, markdown=a.markdown)
    if a.update_doc:
        meta = json.loads(paths["json"].read_text())["meta"]
        update_doc_section(a.update_doc, "quick" if a.quick else ("cases" if a.case else "full"),
                           markdown_table(results, meta))
    c = counts(results)
    print(f"{len(results)} cases in {wall:.1f} s: {c['PASS']} pass, {c['FAIL']} fail, {c['GAP']} known gap, "
          f"{c['ERROR']} error; report: {paths['html']}")
    failed = [r.case["id"] for r in results if r.failed]
    if failed:
        print("FAILED: " + ", ".join(failed))
        return 1
    return 0
