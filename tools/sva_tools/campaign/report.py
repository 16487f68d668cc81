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
from typing import TYPE_CHECKING, Any, cast

from .spec import missions, set_label
from .tasks import mission_hash, residual_for_ref

if TYPE_CHECKING:
    import pyarrow as pa  # no type hints: its names are Any to mypy
    from matplotlib.figure import Figure

    from .store import Store


def percentile(values: list[float], p: float) -> float | None:
    """Nearest-rank percentile (None for no values)."""
    if not values:
        return None
    v = sorted(values)
    return v[max(1, math.ceil(len(v) * p / 100)) - 1]


# A record's columns taken from its stored row (kind plan: the whole record before the
# join to ref); set, seed and index come from this run's task.
BASE = ("key", "set", "targets", "uavs", "seed", "index", "tool", "penalty", "mission_hash", "covered",
        "coverable", "cost", "optimal", "solve_us", "wall_s", "error")
# The stored columns the figures read (kind live adds result and replan_us).
STORED = ("key", "task", "tool", "targets", "uavs", "penalty", "mission_hash", "covered", "coverable",
          "cost", "optimal", "solve_us", "wall_s", "error")


def stored_columns(spec: dict[str, Any]) -> list[str]:
    """The columns of the store that metrics() reads."""
    return list(STORED) + (["replan_us", "result"] if spec["kind"] == "live" else [])


def _gap(cost: float, ref_cost: float) -> float | None:
    return 100.0 * (cost - ref_cost) / ref_cost if ref_cost else None


def _this_run(table: pa.Table, tasks: list[dict[str, Any]]) -> tuple[pa.Table, pa.Table]:
    """One row per task of this run whose key is stored: the stored figures under this
    run's set label, seed and index; and the stored ref results of this run's tasks
    without an error. A stored row is keyed by content, so its own set
    label is that of the run that first stored it (another set's, or an older name)."""
    import numpy as np
    import pyarrow as pa
    import pyarrow.compute as pc
    mine = pa.table({"key": pa.array([t["key"] for t in tasks], pa.string()),
                     "set": pa.array([t["set"] for t in tasks], pa.string()),
                     "seed": pa.array([t["seed"] for t in tasks], pa.int64()),
                     "index": pa.array([t["index"] for t in tasks], pa.int32())})
    stored = table.drop_columns([c for c in ("set", "seed", "index") if c in table.column_names])
    # joined through row numbers: Arrow's join carries no list column (replan_us)
    rows = pa.table({"key": stored["key"], "_row": pa.array(np.arange(len(stored), dtype=np.int64))})
    j = mine.join(rows, "key", join_type="inner", use_threads=False)
    t = stored.take(j["_row"])
    for c in ("set", "seed", "index"):
        t = t.append_column(c, j[c])
    # Sorted as the summary lists them: by set, tool, penalty, seed and index.
    order = pc.sort_indices(t.append_column("_penalty", pc.fill_null(t["penalty"], 0)),
                            [("set", "ascending"), ("tool", "ascending"), ("_penalty", "ascending"),
                             ("seed", "ascending"), ("index", "ascending")])
    refs = stored.filter(pc.and_(pc.equal(stored["task"], "ref"), _ok(stored)))
    return t.take(order), refs.filter(pc.is_in(refs["key"], value_set=mine["key"]))


def _ok(t: pa.Table) -> pa.ChunkedArray:
    """True where a row has no error."""
    import pyarrow.compute as pc
    return pc.invert(pc.fill_null(pc.not_equal(t["error"], ""), False))


def metrics(spec: dict[str, Any], table: pa.Table, tasks: list[dict[str, Any]]) -> pa.Table:
    """A pyarrow table, one record per task of this run with a stored row (table: the
    store's rows, stored_columns() at least; tasks: this run's task list).
    kind plan: one record per planner or ref result with the ref result of the same
    mission (ref_covered, ref_cost, cover_diff, gap_pct at equal coverage);
    kind live: one record per flight with its replans judged against ref."""
    import numpy as np
    import pyarrow as pa
    import pyarrow.compute as pc
    t, refs = _this_run(table, tasks)
    if spec["kind"] == "live":
        return _live(t, refs)
    t = t.filter(pc.is_in(t["task"], value_set=pa.array(["plan", "ref"])))
    # ref results by mission (one per mission: its key holds the mission's hash)
    refs = refs.select(["mission_hash", "covered", "cost", "optimal"]).group_by(
        "mission_hash", use_threads=False).aggregate([("covered", "first"), ("cost", "first"),
                                                      ("optimal", "first")])
    refs = refs.rename_columns(["mission_hash", "ref_covered", "ref_cost", "ref_optimal"])
    t = t.append_column("_order", pa.array(np.arange(len(t), dtype=np.int64)))
    t = t.join(refs, "mission_hash", join_type="left outer", use_threads=False)
    t = t.take(pc.sort_indices(t["_order"]))
    plan = pc.equal(t["task"], "plan")  # ref: not against itself
    nulls = {c: pa.nulls(len(t), t[c].type) for c in ("ref_covered", "ref_cost", "ref_optimal")}
    ref_cols = {c: pc.if_else(plan, t[c], nulls[c]) for c in nulls}
    judged = pc.and_(_ok(t), pc.is_valid(ref_cols["ref_covered"]))
    diff = pc.subtract(t["covered"], ref_cols["ref_covered"])
    cover_diff = pc.if_else(judged, diff, pa.nulls(len(t), diff.type))
    equal_cost = pc.and_(pc.equal(cover_diff, 0), pc.fill_null(pc.not_equal(ref_cols["ref_cost"], 0), False))
    gap = pc.divide(pc.multiply(pc.subtract(t["cost"], ref_cols["ref_cost"]).cast(pa.float64()), 100.0),
                    ref_cols["ref_cost"].cast(pa.float64()))
    gap_pct = pc.if_else(pc.fill_null(equal_cost, False), gap, pa.nulls(len(t), pa.float64()))
    return pa.table(dict({c: t[c] for c in BASE}, **ref_cols, cover_diff=cover_diff, gap_pct=gap_pct))


def _live(t: pa.Table, refs: pa.Table) -> pa.Table:
    """kind live: the flights' records (each flight's log is read here, row by row)."""
    import pyarrow as pa
    import pyarrow.compute as pc
    t = t.filter(pc.equal(t["task"], "fly"))
    by_hash = {h: (c, k) for h, c, k in zip(refs["mission_hash"].to_pylist(), refs["covered"].to_pylist(),
                                            refs["cost"].to_pylist())}
    cols: dict[str, list[Any]] = {c: [] for c in ("replans", "judged", "as_many", "gap_mean", "gap_max", "gaps",
                                             "changes", "later", "p50_us", "p99_us", "replan_us")}
    for result, times in zip(t["result"].to_pylist(), t["replan_us"].to_pylist()):
        log = json.loads(result) if result else {"replans": []}
        judged, as_many, gaps = 0, 0, []
        for rp in log["replans"]:
            if not rp["mission"]["targets"]:
                continue
            q = by_hash.get(mission_hash(residual_for_ref(rp["mission"])))
            if q is None:
                continue
            judged += 1
            as_many += rp["plan"]["covered"] >= q[0]
            if rp["plan"]["covered"] == q[0] and q[1]:
                gaps.append(cast(float, _gap(rp["plan"]["cost"], q[1])))  # a float: ref's cost is not 0
        times = times or []
        later = [rp for rp in log["replans"] if rp["cause"] != "start"]
        for k, v in (("replans", len(log["replans"])), ("judged", judged), ("as_many", as_many),
                     ("gap_mean", statistics.mean(gaps) if gaps else None), ("gap_max", max(gaps) if gaps else None),
                     ("gaps", gaps), ("changes", sum(rp["changes"]["count"] for rp in later)),
                     ("later", len(later)), ("p50_us", percentile(times, 50)), ("p99_us", percentile(times, 99)),
                     ("replan_us", list(times))):
            cols[k].append(v)
    types = {"gap_mean": pa.float64(), "gap_max": pa.float64(), "gaps": pa.list_(pa.float64()),
             "replan_us": pa.list_(pa.int64())}
    out = {c: t[c] for c in BASE}
    out.update({c: pa.array(v, types.get(c, pa.int64())) for c, v in cols.items()})
    return pa.table(out)


def build(spec: dict[str, Any], store: Store,
          tasks: list[dict[str, Any]]) -> tuple[pa.Table, list[dict[str, Any]], int]:
    """(metrics(), groups(), how many stored rows the tasks have) from a Store, reading
    only stored_columns()."""
    import pyarrow as pa
    import pyarrow.compute as pc
    table = store.table(stored_columns(spec))
    records = metrics(spec, table, tasks)
    keys = pa.array([t["key"] for t in tasks], pa.string())
    stored = pc.sum(pc.is_in(table["key"], value_set=keys)).as_py() or 0
    return records, groups(spec, records), stored


def write_metrics(records: pa.Table, out: str) -> str:
    import pyarrow.parquet as pq
    path = os.path.join(out, "metrics.parquet")
    if "gaps" in records.column_names:
        records = records.drop_columns(["gaps"])
    tmp = os.path.join(out, ".tmp-metrics.parquet")
    pq.write_table(records, tmp)
    os.replace(tmp, path)
    return path


def groups(spec: dict[str, Any], records: pa.Table) -> list[dict[str, Any]]:
    """The summary rows: per set and tool (and change_penalty for live). records: the
    table metrics() returns (sorted by set, tool and penalty, so a group is a run of
    consecutive records); its figures are computed with pyarrow, group by group."""
    import pyarrow as pa
    import pyarrow.compute as pc
    live = spec["kind"] == "live"
    keys = ["set", "tool"] + (["penalty"] if live else [])
    n = len(records)
    change = pa.array([False] * max(n - 1, 0), pa.bool_())
    for key in keys:  # where a record's group differs from the one before it
        c = records[key]
        change = pc.or_(change, pc.fill_null(pc.not_equal(c.slice(1), c.slice(0, max(n - 1, 0))), False))
    bounds = ([0] if n else []) + [i + 1 for i in pc.indices_nonzero(change).to_pylist()] + [n]
    order = [set_label(s) for s in spec["sets"]]
    tools = list(spec["algorithms"]) + ["ref"]
    out = []
    for a, b in zip(bounds, bounds[1:]):
        r = records.slice(a, b - a)
        k = tuple(r[c][0].as_py() for c in keys)
        rs = r.filter(_ok(r))

        def total(col: str, rows: pa.Table = rs) -> int:
            return pc.sum(rows[col]).as_py() or 0

        g = {"set": k[0], "tool": k[1], "penalty": k[2] if live else None, "n": len(r),
             "errors": len(r) - len(rs), "covered": total("covered"), "coverable": total("coverable")}
        if not live:
            judged = rs.filter(pc.is_valid(rs["ref_covered"]))
            gaps = pc.drop_null(judged["gap_pct"]).to_pylist()
            times = pc.drop_null(rs["solve_us"]).to_pylist()
            diff = judged["cover_diff"]
            g.update(judged=len(judged), equal=pc.sum(pc.equal(diff, 0)).as_py() or 0,
                     below=pc.sum(pc.less(diff, 0)).as_py() or 0, above=pc.sum(pc.greater(diff, 0)).as_py() or 0,
                     gap_mean=statistics.mean(gaps) if gaps else None, gap_max=max(gaps) if gaps else None,
                     gaps=gaps, times=times, p50_us=_rank(times, 50), p95_us=_rank(times, 95))
        else:
            gaps = pc.list_flatten(rs["gaps"]).to_pylist()
            times = pc.list_flatten(rs["replan_us"]).to_pylist()
            g.update(judged=total("judged"), as_many=total("as_many"),
                     gap_mean=statistics.mean(gaps) if gaps else None, gap_max=max(gaps) if gaps else None,
                     gaps=gaps, times=times, p50_us=_rank(times, 50), p99_us=_rank(times, 99))
        out.append((order.index(k[0]), tools.index(k[1]), k[2] if live and k[2] else 0, g))
    return [g for *_, g in sorted(out, key=lambda x: x[:3])]


def _rank(values: list[Any], p: float) -> Any:
    """percentile() through numpy's sort (the same nearest rank)."""
    if not values:
        return None
    import numpy as np
    v = np.sort(np.asarray(values))
    return v[max(1, math.ceil(len(v) * p / 100)) - 1].item()


def _pct(a: float, b: float) -> str:
    return f"{100.0 * a / b:.1f} %" if b else "–"


def _ms(us: float | None) -> str:
    return "–" if us is None else f"{us / 1000:.3f} ms"


def _gaps(g: dict[str, Any]) -> str:
    return "–" if g["gap_mean"] is None else f"mean {g['gap_mean']:.3f} %, largest {g['gap_max']:.2f} %"


def table(spec: dict[str, Any], gs: list[dict[str, Any]]) -> list[list[str]]:
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


def markdown(rows: list[list[str]]) -> str:
    lines = ["| " + " | ".join(rows[0]) + " |", "|" + "---|" * len(rows[0])]
    return "\n".join(lines + ["| " + " | ".join(r) + " |" for r in rows[1:]])


def summary(spec: dict[str, Any], stats: dict[str, Any], gs: list[dict[str, Any]]) -> str:
    """The printed summary: one line of counts and times, and the table of groups()."""
    units = "missions" if spec["kind"] == "plan" else "scenarios"
    n = missions(spec)
    wall = stats.get("wall_s") or 0.0
    head = (f"campaign {spec['name']}: {stats['tasks']} tasks for {n} {units}; {stats['stored']} already stored, "
            f"{stats['computed']} computed, {len(stats['failed'])} failed; "
            + (f"{stats['held']} not computed (damaged part files: --repair); " if stats.get("held") else "")
            + f"{wall:.1f} s, of which "
            f"{stats.get('compute_s', 0.0):.1f} s computing on {stats.get('workers', 0)} workers")
    return head + "\n" + markdown(table(spec, gs))


def _png(fig: Figure) -> str:
    buf = _io.BytesIO()
    fig.savefig(buf, format="png", dpi=90, bbox_inches="tight")
    return "data:image/png;base64," + base64.b64encode(buf.getvalue()).decode("ascii")


def figures(spec: dict[str, Any], gs: list[dict[str, Any]]) -> list[tuple[str, str]]:
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


def write_html(spec: dict[str, Any], stats: dict[str, Any], gs: list[dict[str, Any]], out: str,
               stored: int) -> str:
    """OUT/report.html from groups(); stored: how many stored rows this spec's tasks have."""
    rows = table(spec, gs)
    e = html.escape
    head = summary(spec, stats, gs).splitlines()[0]
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
              f"<p>Results: results/*.parquet ({stored} rows for this spec); metrics.parquet.</p>",
              "</body></html>"]
    path = os.path.join(out, "report.html")
    with open(path + ".tmp", "w", encoding="utf-8") as f:
        f.write("\n".join(parts))
    os.replace(path + ".tmp", path)
    return path
