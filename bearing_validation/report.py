"""Validation report: report.json, self-contained report.html (summary table, per-case detail and overlay
plots embedded as PNG), and a markdown summary table for docs."""
from __future__ import annotations

import base64
import html
import io
import json
import math
import platform
import time
from pathlib import Path

import numpy as np

from .runner import CaseResult, _jsonable, counts


def fmt(v, n=4):
    """Short text of a scalar or list (lists of more than 6 values are abbreviated)."""
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, (int, np.integer)):
        return str(int(v))
    if isinstance(v, (float, np.floating)):
        v = float(v)
        if v == 0 or not math.isfinite(v):
            return f"{v:g}"
        return f"{v:.{n}g}"
    if isinstance(v, (list, tuple)):
        items = [fmt(x, n) for x in v]
        if len(items) > 6:
            items = items[:3] + ["..."] + items[-2:]
        return "[" + ", ".join(items) + "]"
    return str(v)


def source_text(case) -> str:
    s = case["source"]
    parts = [s.get("reference", ""), s.get("item", ""), ("p. " + str(s["page"])) if s.get("page") else ""]
    return ", ".join(p for p in parts if p)


def _summary_cells(r: CaseResult):
    """(reference, ours, error, tolerance) strings for the summary table."""
    j = r.judgement
    if r.status == "ERROR":
        return "", "error", "", ""
    rows = j.get("rows", [])
    if rows:
        ref = "; ".join(f"{x['key']} {fmt(x['reference'])}" for x in rows)
        ours = "; ".join(f"{x['key']} {fmt(x['ours'])}" for x in rows)
        err = "; ".join(f"{fmt(x['error'] * (100 if x['error_mode'] == 'rel' else 1), 3)}"
                        f"{' %' if x['error_mode'] == 'rel' else ''}" for x in rows)
        tol = "; ".join(f"{fmt(x['tolerance'] * (100 if x['error_mode'] == 'rel' else 1), 3)}"
                        f"{' %' if x['error_mode'] == 'rel' else ''}" for x in rows)
    else:
        ref = r.case.get("reference_text", "")
        ours = ""
        err = ""
        tol = ""
    checks = j.get("checks", [])
    if checks:
        ctext = "; ".join(("ok: " if c["ok"] else "NOT: ") + c["check"] for c in checks)
        ours = (ours + "; " if ours else "") + ctext
        if not rows:
            tol = "trend"
    if not ref:
        ref = r.case.get("reference_text", "")
    return ref, ours, err, tol


def _plot_png(r: CaseResult) -> bytes | None:
    """Overlay of ours against the published values, as the case's "plot" spec says; None without one."""
    spec = r.case.get("plot")
    if not spec or r.status == "ERROR":
        return None
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    ref, ours, inp = r.case["reference"], r.ours, r.case["inputs"]

    def lookup(key, *where):
        for d in where:
            if key in d:
                return d[key]
        return None

    fig, ax = plt.subplots(figsize=(6.4, 4.0), constrained_layout=True)
    if spec.get("type") == "ratio":
        # table of scalars: ours over published per quantity (or ours - published where published is 0)
        keys, vals, labels = [], [], []
        for x in r.judgement.get("rows", []):
            if np.ndim(x["reference"]) or np.ndim(x["ours"]):
                continue
            keys.append(x["key"])
            ref_v, our_v = float(x["reference"]), float(x["ours"])
            if ref_v != 0:
                vals.append(our_v / ref_v)
                labels.append("ours / published")
            else:
                vals.append(1.0 + our_v)
                labels.append("1 + (ours - published)")
        ax.bar(range(len(keys)), vals, color=["C0" if lab.startswith("ours /") else "C1" for lab in labels])
        ax.axhline(1.0, color="k", lw=1, label="published")
        ax.set_xticks(range(len(keys)))
        ax.set_xticklabels(keys, rotation=30, ha="right", fontsize=7)
        lo, hi = min(vals + [1.0]), max(vals + [1.0])
        pad = max(0.005, 0.2 * (hi - lo))
        ax.set_ylim(lo - pad, hi + pad)
        spec = dict(spec, ylabel="ours / published [-]")
    elif spec.get("type") == "curves":
        for label, c in ours.get(spec["curves"], {}).items():
            ax.plot(c[spec["x"]], c[spec["y"]], lw=1.2, label=f"ours, {label}")
        for key, val in spec.get("hlines", {}).items():
            ax.axhline(val, color="k", ls="--", lw=1, label=key)
        for key, val in spec.get("vlines", {}).items():
            ax.axvline(val, color="gray", ls=":", lw=1, label=key)
    else:
        x = lookup(spec["x"], ours, ref, inp)
        for i, key in enumerate(spec["series"]):
            color = f"C{i}"
            yr = ref.get(key)
            yo = ours.get(key)
            if yo is not None:
                yo_ = np.broadcast_to(np.asarray(yo, float), np.shape(x))
                ax.plot(x, yo_, "-", color=color, marker=".", label=f"ours: {key}")
            if yr is not None:
                yr_ = np.broadcast_to(np.asarray(yr, float), np.shape(x))
                ax.plot(x, yr_, "o", mfc="none", color=color, ms=8, label=f"published: {key}")
        for key in spec.get("ours_only", []):
            if key in ours:
                ax.plot(x, ours[key], "--", marker="x", label=f"ours: {key}")
        if "band" in spec:
            ax.axhspan(spec["band"][0], spec["band"][1], color="g", alpha=0.12, label=spec.get("band_label", "tolerance"))
    if spec.get("logy"):
        ax.set_yscale("log")
    if spec.get("logx"):
        ax.set_xscale("log")
    ax.set_xlabel(spec.get("xlabel", spec.get("x", "")))
    ax.set_ylabel(spec.get("ylabel", ""))
    ax.set_title(r.case["id"], fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=80)
    plt.close(fig)
    return buf.getvalue()


def _closed(r: CaseResult) -> str:
    return " (now within tolerance: reclassify)" if r.judgement.get("gap_closed") else ""


_CSS = """body{font-family:sans-serif;margin:1.5em;max-width:1400px}table{border-collapse:collapse;font-size:13px}
td,th{border:1px solid #bbb;padding:3px 6px;vertical-align:top}th{background:#eee}
.PASS{background:#d8f5d8}.FAIL{background:#f8c8c8}.ERROR{background:#f8c8c8}.GAP{background:#fdf0c0}
pre{background:#f6f6f6;padding:6px;overflow-x:auto;font-size:12px}h2{margin-top:2em}"""


def write_html(results, path: Path, meta: dict):
    c = counts(results)
    out = [f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>Validation report</title>"
           f"<style>{_CSS}</style></head><body>",
           "<h1>bearing validate: validation report</h1>",
           f"<p>{html.escape(meta.get('command', ''))} &mdash; {html.escape(meta.get('date', ''))}, "
           f"wall {meta.get('wall_s', 0):.1f} s, {len(results)} cases: "
           f"{c['PASS']} pass, {c['FAIL']} fail, {c['GAP']} known gap, {c['ERROR']} error.</p>",
           "<p>Verdict kinds: <b>match</b> (within the tolerance), <b>trend</b> (sign, order or monotonicity "
           "checked), <b>known-gap</b> (computed and listed with its reason; never fails). References are "
           "published values (papers, textbooks), never our own output.</p>",
           "<table><tr><th>case</th><th>source</th><th>quantity</th><th>reference</th><th>ours</th>"
           "<th>error</th><th>tolerance</th><th>verdict</th></tr>"]
    for r in results:
        ref, ours, err, tol = _summary_cells(r)
        out.append(f"<tr class='{r.status}'><td><a href='#{r.case['id']}'>{html.escape(r.case['id'])}</a></td>"
                   f"<td>{html.escape(source_text(r.case))}</td><td>{html.escape(r.case['quantity'])}</td>"
                   f"<td>{html.escape(ref)}</td><td>{html.escape(ours)}</td><td>{html.escape(err)}</td>"
                   f"<td>{html.escape(tol)}</td><td>{r.case['verdict']}: <b>{r.status}</b>{_closed(r)}</td></tr>")
    out.append("</table>")
    for r in results:
        cs = r.case
        out.append(f"<h2 id='{cs['id']}'>{html.escape(cs['id'])}: {html.escape(cs.get('title', ''))} "
                   f"<span class='{r.status}'>[{r.status}]</span></h2>")
        out.append(f"<p><b>Source:</b> {html.escape(source_text(cs))}<br><b>Quantity:</b> "
                   f"{html.escape(cs['quantity'])}<br><b>Verdict kind:</b> {cs['verdict']}"
                   f"{' (quick)' if cs.get('quick') else ''}, wall {r.wall_s:.1f} s</p>")
        if cs.get("tolerance_reason"):
            out.append(f"<p><b>Tolerance:</b> {html.escape(cs['tolerance_reason'])}</p>")
        if cs.get("gap_reason"):
            out.append(f"<p><b>Known gap:</b> {html.escape(cs['gap_reason'])}</p>")
        if cs.get("notes"):
            out.append(f"<p>{html.escape(cs['notes'])}</p>")
        if r.status == "ERROR":
            out.append(f"<pre>{html.escape(r.error)}</pre>")
            continue
        rows = r.judgement.get("rows", [])
        if rows:
            out.append("<table><tr><th>key</th><th>reference</th><th>ours</th><th>error</th><th>tolerance</th>"
                       "<th>ok</th></tr>")
            for x in rows:
                m = x["error_mode"]
                out.append(f"<tr class='{'PASS' if x['ok'] else ('GAP' if cs['verdict'] != 'match' else 'FAIL')}'>"
                           f"<td>{html.escape(x['key'])}</td><td>{html.escape(fmt(x['reference']))}</td>"
                           f"<td>{html.escape(fmt(x['ours']))}</td><td>{fmt(x['error'], 3)} ({m})</td>"
                           f"<td>{fmt(x['tolerance'], 3)} ({m})</td><td>{'yes' if x['ok'] else 'no'}</td></tr>")
            out.append("</table>")
        for ch in r.judgement.get("checks", []):
            out.append(f"<p class='{'PASS' if ch['ok'] else 'FAIL'}'>check: {html.escape(ch['check'])}: "
                       f"{'holds' if ch['ok'] else 'DOES NOT HOLD'}</p>")
        png = _plot_png(r)
        if png:
            out.append(f"<p><img alt='{cs['id']} overlay' src='data:image/png;base64,"
                       f"{base64.b64encode(png).decode()}'></p>")
        extra = {k: v for k, v in r.ours.items() if k != "curves"}
        out.append(f"<details><summary>all computed values</summary><pre>"
                   f"{html.escape(json.dumps(extra, indent=1)[:20000])}</pre></details>")
    out.append(f"<p>Python {platform.python_version()}, {platform.platform()}</p></body></html>")
    path.write_text("\n".join(out), encoding="utf-8")


def write_json(results, path: Path, meta: dict):
    data = {"meta": meta, "counts": counts(results),
            "cases": [{"id": r.case["id"], "source": r.case["source"], "quantity": r.case["quantity"],
                       "verdict_kind": r.case["verdict"], "status": r.status, "wall_s": r.wall_s,
                       "judgement": r.judgement, "ours": r.ours, "error": r.error} for r in results]}
    path.write_text(json.dumps(_jsonable(data), indent=1), encoding="utf-8")


def markdown_table(results, meta: dict) -> str:
    c = counts(results)
    lines = [f"Generated by `{meta.get('command', 'bearing validate')}` on {meta.get('date', '')} "
             f"({len(results)} cases: {c['PASS']} pass, {c['FAIL']} fail, {c['GAP']} known gap, "
             f"{c['ERROR']} error; wall {meta.get('wall_s', 0):.0f} s). Do not edit by hand.", "",
             "| case | source | quantity | reference | ours | error | tolerance | verdict |",
             "|---|---|---|---|---|---|---|---|"]
    for r in results:
        ref, ours, err, tol = _summary_cells(r)
        cells = [r.case["id"], source_text(r.case), r.case["quantity"], ref, ours, err, tol,
                 f"{r.case['verdict']}: **{r.status}**{_closed(r)}"]
        lines.append("| " + " | ".join(x.replace("|", "/") for x in cells) + " |")
    gaps = [r for r in results if r.case["verdict"] == "known-gap"]
    if gaps:
        lines += ["", "Known gaps:", ""]
        lines += [f"* `{r.case['id']}`: {r.case['gap_reason']}" for r in gaps]
    return "\n".join(lines) + "\n"


def write_report(results, out_dir, command="bearing validate", wall_s=0.0, markdown=False) -> dict:
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    meta = {"command": command, "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), "wall_s": wall_s}
    write_html(results, out / "report.html", meta)
    write_json(results, out / "report.json", meta)
    paths = {"html": out / "report.html", "json": out / "report.json"}
    if markdown:
        (out / "report.md").write_text(markdown_table(results, meta), encoding="utf-8")
        paths["markdown"] = out / "report.md"
    return paths


def update_doc_section(doc: Path, label: str, text: str) -> None:
    """Replace the generated block between '<!-- bearing validate: LABEL begin -->' and
    '<!-- bearing validate: LABEL end -->' in doc (appended at the end if the markers are absent)."""
    doc = Path(doc)
    begin, end = f"<!-- bearing validate: {label} begin -->", f"<!-- bearing validate: {label} end -->"
    body = doc.read_text(encoding="utf-8") if doc.exists() else ""
    block = f"{begin}\n{text.rstrip()}\n{end}"
    if begin in body and end in body:
        pre, rest = body.split(begin, 1)
        _, post = rest.split(end, 1)
        body = pre + block + post
    else:
        body = body.rstrip() + "\n\n" + block + "\n"
    doc.write_text(body, encoding="utf-8")
