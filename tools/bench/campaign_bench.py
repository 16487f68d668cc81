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
mean wall time of a task inside its worker, and the per-task overhead (the workers'
busy time not spent in a task: scheduling, transfer, Parquet writes, and idle workers
at the end); then each kind of task's mean wall time with the first worker count.
The estimate: T(N) = M * (sum over a mission's tasks of (mean task time + overhead))
/ (N * C), for M = 100,000 missions on N machines of C workers (C = the measuring machine's
cores), with the costs measured with the first worker count (default 1); also without
the ref task. It assumes tasks as costly as these, one worker per core as fast as one
worker alone here, and a scheduler that keeps up (not measured beyond 2 workers here).
--results writes docs/results/campaign.md, or with --no-ref docs/results/campaign.no_ref.md
(tools/bench/results.py).
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
             "| mean task time in a worker | cluster start and stop | overhead per task |",
             "|---|---|---|---|---|---|---|---|"]
    for r in runs:
        lines.append(f"| {r['workers']} | {args.count} | {r['tasks']} | {r['compute_s']:.1f} s | "
                     f"{args.count / r['compute_s']:.2f} | {1000 * r['busy_s'] / r['tasks']:.0f} ms | "
                     f"{r['wall_s'] - r['compute_s']:.1f} s | {1000 * r['overhead_s']:.0f} ms |")
    base = runs[0]  # per-task costs from the first worker count (1 by default: no contention between workers)
    tools = sorted({r["tool"] for r in base["rows"]}, key=lambda t: (t == "ref", t))
    lines += ["", f"Per-task costs ({base['workers']} worker):", "",
              "| task | per mission | mean wall time in the worker | largest |", "|---|---|---|---|"]
    cost_of = {}
    for t in tools:
        w = [r["wall_s"] for r in base["rows"] if r["tool"] == t]
        cost_of[t] = (statistics.mean(w) * len(w) / args.count, len(w) / args.count)
        lines.append(f"| {t} | {len(w) / args.count:g} | {statistics.mean(w) * 1000:.1f} ms | "
                     f"{max(w) * 1000:.1f} ms |")
    cores = os.cpu_count() or 1
    overhead = base["overhead_s"]

    def per_mission(names):
        return sum(cost_of[t][0] + cost_of[t][1] * overhead for t in names)

    with_ref = per_mission(tools)
    no_ref = per_mission([t for t in tools if t != "ref"])
    lines += ["", f"Estimate for {M:,} missions like these on machines of {cores} workers (one per core), from the "
              f"per-task costs above and the overhead per task measured with {base['workers']} worker "
              f"({1000 * overhead:.0f} ms): {with_ref:.3f} s per mission"
              + (f", {no_ref:.3f} s without the ref task" if "ref" in tools else "") + ".", "",
              "| machines | workers | estimated time |" + (" without ref |" if "ref" in tools else ""),
              "|---|---|---|" + ("---|" if "ref" in tools else "")]
    for n in MACHINES:
        lines.append(f"| {n} | {n * cores} | {hours(M * with_ref / (n * cores))} |"
                     + (f" {hours(M * no_ref / (n * cores))} |" if "ref" in tools else ""))
    tasks_per_mission = base["tasks"] / args.count
    lines += ["", f"Floor whatever the number of machines: the overhead per task includes the scheduler's and the "
              f"client's share, which serve every worker; were it all theirs, {M:,} missions "
              f"({M * tasks_per_mission:,.0f} tasks) would take at least {hours(M * tasks_per_mission * overhead)}"
              + (f" ({hours(M * (tasks_per_mission - 1) * overhead)} without ref)." if "ref" in tools else ".")
              + " The scheduler's own throughput was not measured apart."]
    if len(runs) > 1:
        lines += ["", "The estimate assumes tasks as costly as these, one worker per core that runs as fast as one "
                  "worker alone did here, and a scheduler that keeps up: it was measured from "
                  f"{runs[0]['workers']} to {runs[-1]['workers']} workers only, where the campaign ran "
                  f"{runs[0]['compute_s'] / runs[-1]['compute_s']:.2f}x as fast (tasks took "
                  f"{runs[-1]['busy_s'] / runs[0]['busy_s']:.2f}x as long with {runs[-1]['workers']} workers on "
                  "the cores of the machine named above, shared with other work: see its load average)."]
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
        # The default run is the section's own fragment; one with --no-ref is its part "no_ref".
        page.write(page.ROOT, "campaign.no_ref" if args.no_ref else "campaign", cmd, intro + "\n\n" + body,
                   title=f"Planners only, {args.count} missions" if args.no_ref else None, load_start=load_start)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
