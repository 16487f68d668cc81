#!/usr/bin/env python3
"""Campaign report at scale: the metrics, the summary table and report.html of a
synthetic kind-plan campaign store (`sva-tools campaign`, docs/campaigns.md), built
row by row in Python (the report before it used Arrow) and with pyarrow
(sva_tools.campaign.report as it is).

Usage (from the repository root, after scripts/setup.sh):
    nice .venv/bin/python tools/bench/campaign_report_bench.py [--results] [--missions N] [--sets S]
                                                               [--algos flow,sva] [--flush-rows R]
Defaults: 25,000 missions in 4 sets (25 to 200 targets), flow, sva and hga on each and
ref on each: 100,000 stored rows, in part files of 64 rows (the campaign's default --flush-rows), with the
store's real schema (missions and plans as JSON text of about the real size), written
once to a temporary folder. Each way runs in its own process; it prints per way the
seconds to read the store and build the records, to group them, and to write the summary
and report.html (the plots are the same for both), the stored rows per second of the
whole, and the process's peak resident memory (getrusage ru_maxrss) with its size after
the imports. It checks that both ways print the same summary table. --results writes
docs/results/campaign.report.md (tools/bench/results.py).

The synthetic figures: each planner covers the ref's targets or one or two fewer, with a
cost 0 to 30 % above ref's; one result in 500 is an error.
"""
import argparse
import json
import math
import os
import random
import resource
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))

from sva_tools.campaign import report  # noqa: E402
from sva_tools.campaign.spec import set_label, validate  # noqa: E402
from sva_tools.campaign.tasks import ROW_FIELDS, mission_hash, residual_for_ref, sha256  # noqa: E402
from sva_tools.campaign.store import Store  # noqa: E402

SIZES = ((25, 5), (40, 8), (100, 20), (200, 32))


def synthetic_spec(sets: int, algos, count: int, ref_max: int = 40) -> dict:
    """sets mission sets of 25 to 200 targets; ref on those of at most ref_max targets."""
    return validate({"name": "report_bench", "kind": "plan", "count": count, "algorithms": list(algos),
                       "sets": [{"targets": SIZES[i % len(SIZES)][0], "uavs": SIZES[i % len(SIZES)][1],
                                 "label": f"set{i}_{SIZES[i % len(SIZES)][0]}x{SIZES[i % len(SIZES)][1]}"}
                                for i in range(sets)],
                       "seeds": {"first": 1, "count": 1}, "ref": {"det_limit": 1, "max_targets": ref_max}})


def synthetic_store(out: str, spec: dict, flush_rows: int = 64, seed: int = 1, shared=None):
    """Writes a store of the spec's tasks with random figures; returns this run's task
    list (plain dicts with the fields the report reads). shared: {set label: label
    whose rows it stores under}: the rows of those sets carry another set's label, as
    rows first stored by another set or run do."""
    rnd = random.Random(seed)
    store = Store(out, "bench", flush_rows=flush_rows, flush_s=1e9)
    tasks = []
    shared = shared or {}
    for s in spec["sets"]:
        label = set_label(s)
        for i in range(s.get("count", spec["count"])):
            mh = sha256(f"{label}/{i}")
            mission = json.dumps({"name": f"m{i}", "targets": [[rnd.randrange(20), rnd.randrange(20)]
                                                               for _ in range(s["targets"] // 4)]})
            ref_cov = rnd.randint(s["targets"] // 2, s["targets"])
            ref_cost = rnd.randint(100, 5000)
            tools = list(spec["algorithms"]) + (["ref"] if s["targets"] <= spec["ref"]["max_targets"] else [])
            for tool in tools:
                task = "ref" if tool == "ref" else "plan"
                key = sha256(f"{task}/{tool}/{mh}")
                row = {k: None for k in ROW_FIELDS}
                row.update(key=key, campaign=spec["name"], run="bench", task=task, tool=tool,
                           set=shared.get(label, label), targets=s["targets"], uavs=s["uavs"], seed=1, index=i,
                           mission_hash=mh, mission_name=f"m{i}", version="{}", settings="{}", mission=mission,
                           coverable=s["targets"], wall_s=rnd.random(), worker="w", host="h", pid=1, utc="now")
                if rnd.random() < 1 / 500:
                    row["error"] = "sva plan exit 1: synthetic"
                else:
                    cov = ref_cov if tool == "ref" else max(0, ref_cov - rnd.choice((0, 0, 0, 1, 2)))
                    cost = ref_cost if tool == "ref" else int(ref_cost * (1 + rnd.random() * 0.3))
                    row.update(covered=cov, cost=cost, optimal=tool == "ref", solve_us=rnd.randint(50, 200000),
                               result=json.dumps({"covered": cov, "cost": cost, "routes": mission}))
                store.add(row)
                tasks.append({"key": key, "task": task, "tool": tool, "set": label, "seed": 1, "index": i})
    store.flush()
    return tasks


# --- the report before it used Arrow: every stored row as a dict, grouped in Python ---

def row_wise_rows(store: Store, tasks, spec: dict) -> dict:
    """key -> stored row, as the campaign CLI read them (all columns but the missions and,
    kind plan, the plans) for this run's keys."""
    import pyarrow as pa
    import pyarrow.parquet as pq
    from sva_tools.campaign.store import SCHEMA
    keep = [c for c in ROW_FIELDS if c != "mission" and (c != "result" or spec["kind"] == "live")]
    t = pa.concat_tables([pq.read_table(p, columns=keep, schema=SCHEMA) for p in store.files()])
    keys, seen, first = t.column("key").to_pylist(), set(), []
    for i, k in enumerate(keys):  # the first of each key, in file order
        if k not in seen:
            seen.add(k)
            first.append(i)
    if len(first) != len(keys):
        t = t.take(pa.array(first))
    wanted = {x["key"] for x in tasks}
    return {r["key"]: r for r in t.to_pylist() if r["key"] in wanted}


def row_wise_metrics(spec: dict, rows: dict) -> list:
    """kind plan: one record per planner or ref result with ref's result of its mission;
    kind live: one record per flight with its replans judged against ref."""
    refs = {r["mission_hash"]: r for r in rows.values() if r["task"] == "ref" and not r["error"]}
    out = []
    for r in sorted(rows.values(), key=lambda r: (r["set"], r["tool"], r["penalty"] or 0, r["seed"], r["index"])):
        base = {k: r[k] for k in report.BASE}
        if r["task"] in ("plan", "ref"):
            if spec["kind"] == "live":
                continue
            q = refs.get(r["mission_hash"]) if r["task"] == "plan" else None
            base.update(ref_covered=q["covered"] if q else None, ref_cost=q["cost"] if q else None,
                        ref_optimal=q["optimal"] if q else None, cover_diff=None, gap_pct=None)
            if q and not r["error"]:
                base["cover_diff"] = r["covered"] - q["covered"]
                base["gap_pct"] = (100.0 * (r["cost"] - q["cost"]) / q["cost"]
                                   if r["covered"] == q["covered"] and q["cost"] else None)
            out.append(base)
            continue
        log = json.loads(r["result"]) if r["result"] else {"replans": []}
        judged, as_many, gaps = 0, 0, []
        for rp in log["replans"]:
            if not rp["mission"]["targets"]:
                continue
            q = refs.get(mission_hash(residual_for_ref(rp["mission"])))
            if q is None:
                continue
            judged += 1
            as_many += rp["plan"]["covered"] >= q["covered"]
            if rp["plan"]["covered"] == q["covered"] and q["cost"]:
                gaps.append(100.0 * (rp["plan"]["cost"] - q["cost"]) / q["cost"])
        times = r["replan_us"] or []
        later = [rp for rp in log["replans"] if rp["cause"] != "start"]
        base.update(replans=len(log["replans"]), judged=judged, as_many=as_many,
                    gap_mean=statistics.mean(gaps) if gaps else None, gap_max=max(gaps) if gaps else None,
                    gaps=gaps, changes=sum(rp["changes"]["count"] for rp in later), later=len(later),
                    p50_us=nearest_rank(times, 50), p99_us=nearest_rank(times, 99), replan_us=list(times))
        out.append(base)
    return out


def nearest_rank(values, p):
    if not values:
        return None
    v = sorted(values)
    return v[max(1, math.ceil(len(v) * p / 100)) - 1]


def row_wise_groups(spec: dict, records: list) -> list:
    """The summary rows per set and tool (and change_penalty for live)."""
    order = [set_label(s) for s in spec["sets"]]
    tools = list(spec["algorithms"]) + ["ref"]
    live = spec["kind"] == "live"
    by = {}
    for r in records:
        by.setdefault((r["set"], r["tool"], r["penalty"]) if live else (r["set"], r["tool"]), []).append(r)
    out = []
    for k in sorted(by, key=lambda k: (order.index(k[0]), tools.index(k[1]), k[2:] and k[2] or 0)):
        rs = [r for r in by[k] if not r["error"]]
        g = {"set": k[0], "tool": k[1], "penalty": k[2] if live else None, "n": len(by[k]),
             "errors": len(by[k]) - len(rs), "covered": sum(r["covered"] for r in rs),
             "coverable": sum(r["coverable"] or 0 for r in rs)}
        if not live:
            judged = [r for r in rs if r["ref_covered"] is not None]
            gaps = [r["gap_pct"] for r in judged if r["gap_pct"] is not None]
            times = [r["solve_us"] for r in rs if r["solve_us"] is not None]
            g.update(judged=len(judged), equal=sum(1 for r in judged if r["cover_diff"] == 0),
                     below=sum(1 for r in judged if r["cover_diff"] < 0),
                     above=sum(1 for r in judged if r["cover_diff"] > 0),
                     gap_mean=statistics.mean(gaps) if gaps else None, gap_max=max(gaps) if gaps else None,
                     gaps=gaps, times=times, p50_us=nearest_rank(times, 50), p95_us=nearest_rank(times, 95))
        else:
            gaps = [x for r in rs for x in r["gaps"]]
            times = [x for r in rs for x in r["replan_us"]]
            g.update(judged=sum(r["judged"] for r in rs), as_many=sum(r["as_many"] for r in rs),
                     gap_mean=statistics.mean(gaps) if gaps else None, gap_max=max(gaps) if gaps else None,
                     gaps=gaps, times=times, p50_us=nearest_rank(times, 50), p99_us=nearest_rank(times, 99))
        out.append(g)
    return out


# --- one way, in a child process ---

def child(way: str, folder: str, sets: int, algos, count: int) -> None:
    import matplotlib  # imported before the clock starts, for both ways
    matplotlib.use("Agg")
    import matplotlib.pyplot  # noqa: F401
    import numpy  # noqa: F401
    import pyarrow as pa
    import pyarrow.compute  # noqa: F401
    import pyarrow.parquet  # noqa: F401
    base_kb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    spec = synthetic_spec(sets, algos, count, ref_max=1000)
    with open(os.path.join(folder, "tasks.json"), encoding="utf-8") as f:
        tasks = json.load(f)
    store = Store(folder, "read")
    t0 = time.perf_counter()
    if way == "rows":
        rows = row_wise_rows(store, tasks, spec)
        records = row_wise_metrics(spec, rows)
        stored = len(rows)
    else:
        records = report.metrics(spec, store.table(report.stored_columns(spec)), tasks)
        stored = len(records)
    t1 = time.perf_counter()
    records_kb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    gs = row_wise_groups(spec, records) if way == "rows" else report.groups(spec, records)
    t2 = time.perf_counter()
    out = os.path.join(folder, way)
    os.makedirs(out, exist_ok=True)
    stats = {"tasks": len(tasks), "stored": len(tasks), "computed": 0, "failed": [], "wall_s": 0.0}
    text = report.summary(spec, stats, gs)
    report.write_html(spec, stats, gs, out, stored)
    t3 = time.perf_counter()
    n = len(records) if way == "rows" else records.num_rows
    assert n == stored == len(tasks), (n, stored, len(tasks))
    print(json.dumps({"way": way, "read_metrics_s": t1 - t0, "groups_s": t2 - t1, "report_s": t3 - t2,
                      "rows": n, "base_kb": base_kb, "records_kb": records_kb, "peak_kb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss,
                      "summary": text, "pyarrow": pa.__version__}))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--missions", type=int, default=25_000, help="missions in all (default 25,000)")
    ap.add_argument("--sets", type=int, default=4, help="mission sets (default 4)")
    ap.add_argument("--algos", default="flow,sva,hga", help="planners (default flow,sva,hga)")
    ap.add_argument("--flush-rows", type=int, default=64, help="rows per part file (default 64)")
    ap.add_argument("--results", action="store_true", help="write docs/results/campaign.report.md")
    ap.add_argument("--child", nargs=2, metavar=("WAY", "DIR"), help=argparse.SUPPRESS)
    args = ap.parse_args()
    algos = [a for a in args.algos.split(",") if a]
    count = max(1, args.missions // args.sets)
    if args.child:
        child(args.child[0], args.child[1], args.sets, algos, count)
        return
    load_start = " ".join(f"{x:.2f}" for x in os.getloadavg())
    lines = []
    with tempfile.TemporaryDirectory(prefix="sva-report-bench-") as d:
        t0 = time.perf_counter()
        tasks = synthetic_store(d, synthetic_spec(args.sets, algos, count, ref_max=1000), args.flush_rows)
        with open(os.path.join(d, "tasks.json"), "w", encoding="utf-8") as f:
            json.dump(tasks, f)
        files = len(os.listdir(os.path.join(d, "results")))
        lines.append(f"Store: {len(tasks):,} rows ({args.sets} sets of {count:,} missions, {', '.join(algos)} and "
                     f"ref on each) in {files:,} part files of "
                     f"{args.flush_rows} rows, written in {time.perf_counter() - t0:.0f} s.")
        print(lines[-1])
        res = {}
        for way in ("rows", "arrow"):
            r = subprocess.run([sys.executable, os.path.abspath(__file__), "--missions", str(args.missions),
                                "--sets", str(args.sets), "--algos", args.algos, "--child", way, d],
                               capture_output=True, text=True, check=True)
            res[way] = json.loads(r.stdout.splitlines()[-1])
    same = res["rows"]["summary"] == res["arrow"]["summary"]
    lines += ["", f"pyarrow {res['arrow']['pyarrow']}, Python {sys.version.split()[0]}. Each way in its own "
              "process; peak RSS is the process's ru_maxrss, with its size after the imports in brackets. "
              "Summary tables of the two ways identical: " + ("yes." if same else "NO."), "",
              "| report | read + records | groups | summary + report.html | total | rows/s (read to groups) "
              "| rows/s (total) | peak RSS |", "|---|---|---|---|---|---|---|---|"]
    for way, name in (("rows", "row by row (Python dicts, before)"), ("arrow", "pyarrow (now)")):
        r = res[way]
        mg = r["read_metrics_s"] + r["groups_s"]
        total = mg + r["report_s"]
        lines.append(f"| {name} | {r['read_metrics_s']:.2f} s | {r['groups_s']:.2f} s | {r['report_s']:.2f} s | "
                     f"{total:.2f} s | {r['rows'] / mg:,.0f} | {r['rows'] / total:,.0f} | "
                     f"{r['peak_kb'] / 1024:.0f} MiB ({r['base_kb'] / 1024:.0f} MiB) |")
    body = "\n".join(lines)
    print(body)
    if not same:
        sys.exit("campaign_report_bench: the two ways print different summary tables")
    if args.results:
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        import results as page  # tools/bench/results.py
        opts = [f"--missions {args.missions}"] if args.missions != 25_000 else []
        opts += [f"--sets {args.sets}"] if args.sets != 4 else []
        opts += [f"--algos {args.algos}"] if args.algos != "flow,sva,hga" else []
        opts += [f"--flush-rows {args.flush_rows}"] if args.flush_rows != 64 else []
        cmd = " ".join(["nice .venv/bin/python tools/bench/campaign_report_bench.py --results"] + opts)
        intro = ("The report of a large campaign (`sva-tools campaign`: metrics.parquet, the summary table and "
                 "report.html) from a synthetic kind-plan store with the real schema and random figures: "
                 "built row by row in Python (every stored row as a dict) and with pyarrow (only the needed "
                 "columns, grouped with Arrow compute). The plots are drawn from the same figures by both.")
        page.write(page.ROOT, "campaign.report", cmd, intro + "\n\n" + body,
                   title=f"The report of {len(tasks):,} stored results", load_start=load_start)


if __name__ == "__main__":
    main()
