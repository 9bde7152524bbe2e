"""Validation record of the bearing model as executable cases (``bearing validate``).

Each case (cases/*.json) names its published source, inputs, reference values, tolerance and verdict kind;
kinds.py holds the computation of each kind of case (library calls only, no reference values);
runner.py runs and judges the cases; report.py writes report.html / report.json / report.md.
"""
from .runner import CaseResult, counts, judge, load_cases, run_case, run_cases  # noqa: F401
from .report import markdown_table, update_doc_section, write_report  # noqa: F401
