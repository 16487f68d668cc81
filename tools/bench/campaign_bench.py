#!/usr/bin/env python3
"""Campaign throughput: one mission set run as a campaign (`sva-tools campaign`,
docs/campaigns.md) on a LocalCluster of 1 and of 2 workers, each from an empty store,
and an estimate of a 100,000-mission campaign on N machines from the measured per-task
costs.

Usage (from the repository root, after scripts/setup.sh and scripts/build.sh):
    nice .venv/bin/python tools/bench/campaign_bench.py [--results] [--count N] [--targets T] [--uavs U]
                                                        [--workers 1,2] [--no-ref]
Defaults: 12 missions of 25 targets x 5 UAVs (`sva-tools gen --width 10:20 --need 1
--hover 2 --fuel 105 --seed 7`), flow and sva on each, ref (deterministic limit 10) on
each. Prints per worker count the missions per second (missions / the time from the
first submission to the last result stored; the cluster's start is shown apart), the
mean wall time of each kind of task inside its worker, and the per-task overhead (the
workers' busy time not spent in a task: scheduling, transfer, Parquet writes).
The estimate: T(N) = M * (sum of the mean task times per mission + tasks per mission *
overhead) / (N * C), for M = 100,000 missions on N machines of C workers (C = this
machine's cores). It assumes tasks as costly as these, one worker per core and a
scheduler that keeps up (it is not measured beyond 2 workers here).
--results writes docs/results/campaign.md (tools/bench/results.py).
"""
import argparse
import os
import statistics
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
os.environ["PYTHONPATH"] = os.path.join(ROOT, "tools") + os.pathsep + os.environ.get("PYTHONPATH", "")
sys.path.insert(0, os.path.join(ROOT, "tools"))

import sva_tools.campaign as campaign  # noqa: E402
from sva_tools.campaign import spec as cspec  # noqa: E402

M = 100_000
MACHINES = (1, 10, 100)


def spec(args):
    doc = {"name": "campaign_bench", "kind": "plan",
           "sets": [{"targets": args.targets, "uavs": args.uavs, "width": [10, 20], "need": 1, "hover": 2,
                     "fuel": 105}],
           "seeds": {"first": 7, "count": 1}, "count": args.count, "algorithms": ["flow", "sva"]}
    if not args.no_ref:
        doc["ref"] = {"det_limit": 10, "max_targets": 1000}
    return cspec.validate(doc)


def measure(s, workers):
    with tempfile.TemporaryDirectory(prefix="sva-campaign-bench-") as out:
        t0 = time.perf_counter()
        stats = campaign.run(s, out, workers=workers, progress=False)
        wall = time.perf_counter() - t0
    if stats["failed"] or stats["computed"] != stats["tasks"]:
        sys.exit(f"campaign_bench: {len(stats['failed'])} tasks failed: {stats['failed'][:3]}")
    rows = list(stats["rows"].values())
    busy = sum(r["wall_s"] for r in rows)
    return {"workers": workers, "tasks": len(rows), "compute_s": stats["compute_s"], "wall_s": wall,
            "busy_s": busy, "rows": rows,
            "overhead_s": max(0.0, (stats["compute_s"] * workers - busy) / len(rows))}


def hours(seconds):
    return f"{seconds / 3600:.1f} h" if seconds >= 3600 else f"{seconds / 60:.0f} min"


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--results", action="store_true", help="write docs/results/campaign.md")
    ap.add_argument("--count", type=int, default=12, help="missions (default 12)")
    ap.add_argument("--targets", type=int, default=25)
    ap.add_argument("--uavs", type=int, default=5)
    ap.add_argument("--workers", default="1,2", help="worker counts, comma-separated (default 1,2)")
    ap.add_argument("--no-ref", action="store_true", help="no ref task")
    args = ap.parse_args(argv)
    load_start = " ".join(f"{x:.2f}" for x in os.getloadavg())
    s = spec(args)
    runs = [measure(s, int(w)) for w in args.workers.split(",") if w]
    lines = ["| workers | missions | tasks | first submission to last result | missions per second "
             "| cluster start and stop | overhead per task |", "|---|---|---|---|---|---|---|"]
    for r in runs:
        lines.append(f"| {r['workers']} | {args.count} | {r['tasks']} | {r['compute_s']:.1f} s | "
                     f"{args.count / r['compute_s']:.2f} | {r['wall_s'] - r['compute_s']:.1f} s | "
                     f"{1000 * r['overhead_s']:.0f} ms |")
    base = runs[0]
    tools = sorted({r["tool"] for r in base["rows"]}, key=lambda t: (t == "ref", t))
    lines += ["", "| task | per mission | mean wall time in the worker | largest |", "|---|---|---|---|"]
    per_mission = 0.0
    for t in tools:
        w = [r["wall_s"] for r in base["rows"] if r["tool"] == t]
        per_mission += statistics.mean(w) * len(w) / args.count
        lines.append(f"| {t} | {len(w) / args.count:g} | {statistics.mean(w) * 1000:.1f} ms | "
                     f"{max(w) * 1000:.1f} ms |")
    cores = os.cpu_count() or 1
    tasks_per_mission = base["tasks"] / args.count
    overhead = statistics.mean(r["overhead_s"] for r in runs)
    cost = per_mission + tasks_per_mission * overhead
    lines += ["", f"Estimate for {M:,} missions like these ({tasks_per_mission:g} tasks each, "
              f"{per_mission:.3f} s of task time and {tasks_per_mission * overhead * 1000:.0f} ms of measured overhead "
              f"per mission: {cost:.3f} s), {cores} workers per machine:", "",
              "| machines | workers | estimated time |", "|---|---|---|"]
    for n in MACHINES:
        lines.append(f"| {n} | {n * cores} | {hours(M * cost / (n * cores))} |")
    lines += ["", "The estimate assumes one worker per core, tasks as costly as these and a scheduler "
              "that keeps up; scaling was measured here from 1 to 2 workers only "
              f"({runs[0]['compute_s'] / runs[-1]['compute_s']:.2f}x from {runs[0]['workers']} to "
              f"{runs[-1]['workers']} workers)." if len(runs) > 1 else ""]
    body = "\n".join(lines)
    print(body)
    if args.results:
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        import results as page  # tools/bench/results.py
        opts = [f"--count {args.count}"] if args.count != 12 else []
        opts += [f"--targets {args.targets}"] if args.targets != 25 else []
        opts += [f"--uavs {args.uavs}"] if args.uavs != 5 else []
        opts += [f"--workers {args.workers}"] if args.workers != "1,2" else []
        opts += ["--no-ref"] if args.no_ref else []
        cmd = " ".join(["nice .venv/bin/python tools/bench/campaign_bench.py --results"] + opts)
        intro = (f"{args.count} missions `sva-tools gen --targets {args.targets} --uavs {args.uavs} --width 10:20 "
                 f"--need 1 --hover 2 --fuel 105 --seed 7`; flow and sva (`sva plan`) on each"
                 + ("" if args.no_ref else ", ref (`--det-limit 10`, one CP-SAT worker) on each")
                 + ". Each worker count runs the whole campaign from an empty store on an embedded "
                 "LocalCluster (one thread per worker process). Missions per second: missions over the time "
                 "from the first submission to the last result stored. Overhead per task: the workers' "
                 "time not spent inside a task (scheduling, transfer, the client's Parquet writes), per task.")
        page.write(page.ROOT, "campaign", cmd, intro + "\n\n" + body, load_start=load_start)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
