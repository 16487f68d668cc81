"""A campaign's figures from its stored rows: OUT/metrics.parquet (one row per planner
result or flight, joined to ref), the printed summary and OUT/report.html (tables and
PNG plots embedded as data URIs: no network needed to view it)."""
from __future__ import annotations

import base64
import html
import io as _io
import json
import math
import os
import statistics
from typing import Dict, List

from . import spec as S
from . import tasks as T


def percentile(values: List[float], p: float):
    """Nearest-rank percentile (None for no values)."""
    if not values:
        return None
    v = sorted(values)
    return v[max(1, math.ceil(len(v) * p / 100)) - 1]


def _gap(cost, ref_cost):
    return 100.0 * (cost - ref_cost) / ref_cost if ref_cost else None


def metrics(spec: dict, rows: Dict[str, dict]) -> List[dict]:
    """kind plan: one record per planner or ref result with the ref result of the same
    mission (ref_covered, ref_cost, cover_diff, gap_pct at equal coverage);
    kind live: one record per flight with its replans judged against ref."""
    refs = {r["mission_hash"]: r for r in rows.values() if r["task"] == "ref" and not r["error"]}
    out = []
    for r in sorted(rows.values(), key=lambda r: (r["set"], r["tool"], r["penalty"] or 0, r["seed"], r["index"])):
        base = {k: r[k] for k in ("key", "set", "targets", "uavs", "seed", "index", "tool", "penalty",
                                  "mission_hash", "covered", "coverable", "cost", "optimal", "solve_us",
                                  "wall_s", "error")}
        if r["task"] in ("plan", "ref"):
            if spec["kind"] == "live":
                continue  # live: ref rows are judged through the flights
            q = refs.get(r["mission_hash"]) if r["task"] == "plan" else None  # ref: not against itself
            base.update(ref_covered=q["covered"] if q else None, ref_cost=q["cost"] if q else None,
                        ref_optimal=q["optimal"] if q else None)
            if q and not r["error"]:
                base["cover_diff"] = r["covered"] - q["covered"]
                base["gap_pct"] = _gap(r["cost"], q["cost"]) if r["covered"] == q["covered"] else None
            out.append(base)
            continue
        log = json.loads(r["result"]) if r["result"] else {"replans": []}
        judged, as_many, gaps = 0, 0, []
        for rp in log["replans"]:
            if not rp["mission"]["targets"]:
                continue
            q = refs.get(T.mission_hash(T.residual_for_ref(rp["mission"])))
            if q is None:
                continue
            judged += 1
            as_many += rp["plan"]["covered"] >= q["covered"]
            if rp["plan"]["covered"] == q["covered"] and q["cost"]:
                gaps.append(_gap(rp["plan"]["cost"], q["cost"]))
        times = r["replan_us"] or []
        later = [rp for rp in log["replans"] if rp["cause"] != "start"]
        base.update(replans=len(log["replans"]), judged=judged, as_many=as_many,
                    gap_mean=statistics.mean(gaps) if gaps else None, gap_max=max(gaps) if gaps else None,
                    gaps=gaps, changes=sum(rp["changes"]["count"] for rp in later), later=len(later),
                    p50_us=percentile(times, 50), p99_us=percentile(times, 99), replan_us=list(times))
        out.append(base)
    return out


def write_metrics(records: List[dict], out: str) -> str:
    import pandas as pd
    path = os.path.join(out, "metrics.parquet")
    df = pd.DataFrame(records)
    if "gaps" in df:
        df = df.drop(columns=["gaps"])
    tmp = os.path.join(out, ".tmp-metrics.parquet")
    df.to_parquet(tmp, index=False)
    os.replace(tmp, path)
    return path


def groups(spec: dict, records: List[dict]) -> List[dict]:
    """The summary rows: per set and tool (and change_penalty for live)."""
    order = [S.set_label(s) for s in spec["sets"]]
    keyf = (lambda r: (r["set"], r["tool"], r["penalty"])) if spec["kind"] == "live" else \
        (lambda r: (r["set"], r["tool"]))
    by: Dict[tuple, List[dict]] = {}
    for r in records:
        by.setdefault(keyf(r), []).append(r)
    tools = list(spec["algorithms"]) + ["ref"]
    out = []
    for k in sorted(by, key=lambda k: (order.index(k[0]), tools.index(k[1]), k[2:] and k[2] or 0)):
        rs = [r for r in by[k] if not r["error"]]
        g = {"set": k[0], "tool": k[1], "penalty": k[2] if len(k) > 2 else None, "n": len(by[k]),
             "errors": len(by[k]) - len(rs), "covered": sum(r["covered"] for r in rs),
             "coverable": sum(r["coverable"] or 0 for r in rs)}
        if spec["kind"] == "plan":
            judged = [r for r in rs if r.get("ref_covered") is not None]
            gaps = [r["gap_pct"] for r in judged if r.get("gap_pct") is not None]
            times = [r["solve_us"] for r in rs if r["solve_us"] is not None]
            g.update(judged=len(judged), equal=sum(1 for r in judged if r["cover_diff"] == 0),
                     below=sum(1 for r in judged if r["cover_diff"] < 0),
                     above=sum(1 for r in judged if r["cover_diff"] > 0),
                     gap_mean=statistics.mean(gaps) if gaps else None, gap_max=max(gaps) if gaps else None,
                     gaps=gaps, times=times, p50_us=percentile(times, 50), p95_us=percentile(times, 95))
        else:
            gaps = [x for r in rs for x in r["gaps"]]
            times = [x for r in rs for x in r["replan_us"]]
            g.update(judged=sum(r["judged"] for r in rs), as_many=sum(r["as_many"] for r in rs),
                     gap_mean=statistics.mean(gaps) if gaps else None, gap_max=max(gaps) if gaps else None,
                     gaps=gaps, times=times, p50_us=percentile(times, 50), p99_us=percentile(times, 99))
        out.append(g)
    return out


def _pct(a, b):
    return f"{100.0 * a / b:.1f} %" if b else "–"


def _ms(us):
    return "–" if us is None else f"{us / 1000:.3f} ms"


def _gaps(g):
    return "–" if g["gap_mean"] is None else f"mean {g['gap_mean']:.3f} %, largest {g['gap_max']:.2f} %"


def table(spec: dict, gs: List[dict]) -> List[List[str]]:
    """Header and rows of the summary table (text cells)."""
    if spec["kind"] == "plan":
        rows = [["set", "algorithm", "missions", "covered / targets", "coverage vs ref (equal, below, above)",
                 "cost gap to ref at equal coverage", "solve p50", "solve p95", "errors"]]
        for g in gs:
            vs = f"{g['equal']}/{g['judged']}, {g['below']}, {g['above']}" if g["judged"] else "–"
            rows.append([g["set"], g["tool"], str(g["n"]), f"{g['covered']}/{g['coverable']} "
                         f"({_pct(g['covered'], g['coverable'])})", vs, _gaps(g), _ms(g["p50_us"]),
                         _ms(g["p95_us"]), str(g["errors"])])
        return rows
    rows = [["set", "algorithm", "change_penalty", "flights", "flight: covered / coverable",
             "replans covering as many as ref", "cost gap to ref at equal coverage", "replan p50",
             "replan p99", "errors"]]
    for g in gs:
        rows.append([g["set"], g["tool"], str(g["penalty"]), str(g["n"]),
                     f"{g['covered']}/{g['coverable']} ({_pct(g['covered'], g['coverable'])})",
                     f"{g['as_many']}/{g['judged']} ({_pct(g['as_many'], g['judged'])})" if g["judged"] else "–",
                     _gaps(g), _ms(g["p50_us"]), _ms(g["p99_us"]), str(g["errors"])])
    return rows


def markdown(rows: List[List[str]]) -> str:
    lines = ["| " + " | ".join(rows[0]) + " |", "|" + "---|" * len(rows[0])]
    return "\n".join(lines + ["| " + " | ".join(r) + " |" for r in rows[1:]])


def summary(spec: dict, stats: dict, records: List[dict]) -> str:
    units = "missions" if spec["kind"] == "plan" else "scenarios"
    n = S.missions(spec)
    wall = stats.get("wall_s") or 0.0
    head = (f"campaign {spec['name']}: {stats['tasks']} tasks for {n} {units}; {stats['stored']} already stored, "
            f"{stats['computed']} computed, {len(stats['failed'])} failed; {wall:.1f} s, of which "
            f"{stats.get('compute_s', 0.0):.1f} s computing on {stats.get('workers', 0)} workers")
    return head + "\n" + markdown(table(spec, groups(spec, records)))


def _png(fig) -> str:
    buf = _io.BytesIO()
    fig.savefig(buf, format="png", dpi=90, bbox_inches="tight")
    return "data:image/png;base64," + base64.b64encode(buf.getvalue()).decode("ascii")


def figures(spec: dict, gs: List[dict]) -> List[tuple]:
    """(title, data URI) of the coverage, gap and latency plots."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    labels = [f"{g['set']}\n{g['tool']}" + (f" p{g['penalty']}" if g["penalty"] is not None else "") for g in gs]
    out = []
    fig, ax = plt.subplots(figsize=(max(5, 0.9 * len(gs)), 3.2))
    ax.bar(range(len(gs)), [100.0 * g["covered"] / g["coverable"] if g["coverable"] else 0 for g in gs])
    ax.set_xticks(range(len(gs)), labels, fontsize=7)
    ax.set_ylabel("covered / coverable (%)")
    ax.set_ylim(0, 105)
    out.append(("Coverage per set and algorithm", _png(fig)))
    plt.close(fig)
    with_gaps = [(lab, g["gaps"]) for lab, g in zip(labels, gs) if g["gaps"]]
    if with_gaps:
        fig, ax = plt.subplots(figsize=(max(5, 0.9 * len(with_gaps)), 3.2))
        ax.boxplot([v for _, v in with_gaps])
        ax.set_xticks(range(1, len(with_gaps) + 1), [lab for lab, _ in with_gaps], fontsize=7)
        ax.set_ylabel("cost gap to ref at equal coverage (%)")
        out.append(("Gap to the reference", _png(fig)))
        plt.close(fig)
    with_times = [(lab, [max(t, 1) / 1000 for t in g["times"]]) for lab, g in zip(labels, gs) if g["times"]]
    if with_times:
        fig, ax = plt.subplots(figsize=(max(5, 0.9 * len(with_times)), 3.2))
        ax.boxplot([v for _, v in with_times])
        ax.set_yscale("log")
        ax.set_xticks(range(1, len(with_times) + 1), [lab for lab, _ in with_times], fontsize=7)
        ax.set_ylabel("solve time (ms, log)" if spec["kind"] == "plan" else "replan time (ms, log)")
        out.append(("Latency distribution per size and algorithm", _png(fig)))
        plt.close(fig)
    return out


def write_html(spec: dict, stats: dict, records: List[dict], out: str) -> str:
    gs = groups(spec, records)
    rows = table(spec, gs)
    e = html.escape
    head = summary(spec, stats, records).splitlines()[0]
    parts = ["<!doctype html><html><head><meta charset='utf-8'>",
             f"<title>campaign {e(spec['name'])}</title>",
             "<style>body{font-family:sans-serif;margin:1.5em}table{border-collapse:collapse}"
             "td,th{border:1px solid #bbb;padding:3px 6px;font-size:13px}pre{background:#f4f4f4;padding:6px}"
             "</style></head><body>",
             f"<h1>Campaign {e(spec['name'])}</h1>", f"<p>{e(head)}</p>",
             "<table><tr>" + "".join(f"<th>{e(c)}</th>" for c in rows[0]) + "</tr>"]
    parts += ["<tr>" + "".join(f"<td>{e(c)}</td>" for c in r) + "</tr>" for r in rows[1:]]
    parts.append("</table>")
    for title, uri in figures(spec, gs):
        parts += [f"<h2>{e(title)}</h2>", f"<img alt='{e(title)}' src='{uri}'>"]
    parts += ["<h2>Spec</h2>", f"<pre>{e(json.dumps(spec, indent=1))}</pre>",
              f"<p>Results: results/*.parquet ({len(stats['rows'])} rows for this spec); metrics.parquet.</p>",
              "</body></html>"]
    path = os.path.join(out, "report.html")
    with open(path + ".tmp", "w", encoding="utf-8") as f:
        f.write("\n".join(parts))
    os.replace(path + ".tmp", path)
    return path
