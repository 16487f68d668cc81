#!/usr/bin/env python3
"""flow's solve time and work where fuel binds at 25 targets x 5 UAVs: median, p90, worst.

Usage (from the repository root, after scripts/setup.sh and scripts/build.sh):
    nice -n 15 .venv/bin/python tools/bench/flow_latency.py [--sets NAME,...] [--missions N]
        [--repeat K] [--sva PATH] [--results] [--quick]
Sets (`sva-tools gen --need 1 --seed 7`, the first N missions; default all, 30 each):
    25x5_fuel80         25 targets x 5 UAVs, fuel 80, the generator's windows (20 to 40)
                        and hover fuel (0)
    25x5_fuel80_hover2  the same with windows of 10 to 20 and hover fuel 2 (the sets of
                        tools/bench/flow_vs_ref.py)
Each mission is planned by `sva plan --algo flow` (--sva PATH, else $SVA_BIN, else
build/bin/sva) K times (default 3), one plan per process, at the default work budget.
Its time is the fastest of the K `stats.solve_us` (wall clock inside the planner, without
reading the mission or writing the plan); its work `stats.flow_work`, which must be the
same every time (plans are deterministic). Every plan goes through the independent
checker (sva_tools.check); a refused plan, a CLI error or work that changes between
runs is a failure.
Prints per set: failures, plans proven optimal, flow's work (median, p90, largest) and
time (median, p90, worst; p90 by nearest rank), and whether the goal holds: p90 under
1 ms and worst under 2 ms. Exit status 1 on a failure (not on a missed goal: times
depend on the machine).
--results writes docs/results/core.flow_latency.md (tools/bench/results.py) and
reassembles docs/results.md. --quick: 2 missions of 25x5_fuel80, one run each (ctest
runs it, label tools).
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))

from sva_tools import check, gen, io  # noqa: E402

SEED = 7
SETS = {
    "25x5_fuel80": dict(targets=25, uavs=5, fuel=80),
    "25x5_fuel80_hover2": dict(targets=25, uavs=5, fuel=80, width=(10, 20), hover=2),
}
GOAL_P90_US, GOAL_WORST_US = 1000, 2000


def missions_of(name, count):
    s = SETS[name]
    extra = {k: s[k] for k in ("width", "hover") if k in s}
    return [gen.generate(s["targets"], s["uavs"], need=(1, 1), fuel=s["fuel"], seed=SEED, index=i, **extra)
            for i in range(count)]


def gen_command(name, count):
    s = SETS[name]
    extra = ""
    if "width" in s:
        extra = f" --width {s['width'][0]}:{s['width'][1]} --hover {s['hover']}"
    return (f"sva-tools gen --targets {s['targets']} --uavs {s['uavs']} --need 1 --fuel {s['fuel']}"
            f"{extra} --seed {SEED} --count {count}")


def run_flow(sva, m, path, repeat):
    """(fastest solve_us, work, optimal) of the mission's checked plans, else (None, reason)."""
    times, works, optimal = [], set(), False
    for _ in range(repeat):
        out = subprocess.run([sva, "plan", "--algo", "flow", path], capture_output=True, text=True)
        if out.returncode != 0:
            return None, f"{m.name}: sva exited {out.returncode}: {out.stderr.strip()[:200]}"
        plan = io.plan_from_json(json.loads(out.stdout))
        violations = check.check_plan(m, plan)
        if violations:
            return None, f"{m.name}: checker: {violations[0]}"
        stats = plan.stats or {}
        times.append(stats["solve_us"])
        works.add(stats["flow_work"])
        optimal = bool(stats.get("optimal"))
    if len(works) != 1:
        return None, f"{m.name}: work differs between runs: {sorted(works)}"
    return (min(times), works.pop(), optimal), None


def p90(values):
    """The nearest-rank 90th percentile."""
    ordered = sorted(values)
    return ordered[max(0, math.ceil(0.9 * len(ordered)) - 1)]


def ms(us):
    return f"{us / 1000:.2f} ms"


def summary(name, runs):
    ok = [r for r, _ in runs if r is not None]
    times = [t for t, _, _ in ok]
    works = [w for _, w, _ in ok]
    f = {"set": name, "missions": len(runs), "failures": [why for r, why in runs if r is None],
         "proven": sum(1 for _, _, o in ok if o)}
    if ok:
        f["us"] = (statistics.median(times), p90(times), max(times))
        f["work"] = (statistics.median(works), p90(works), max(works))
        f["goal"] = f["us"][1] < GOAL_P90_US and f["us"][2] < GOAL_WORST_US
    return f


def row(f):
    if "us" not in f:
        return f"| {f['set']} | {f['missions']} | {len(f['failures'])} | – | – | – | – |"
    us, work = f["us"], f["work"]
    return (f"| {f['set']} | {f['missions']} | {len(f['failures'])} | {f['proven']} of {f['missions']} | "
            f"{work[0]:,.0f} / {work[1]:,} / {work[2]:,} | {ms(us[0])} / {ms(us[1])} / {ms(us[2])} | "
            f"{'met' if f['goal'] else 'not met'} |")


TABLE_HEAD = ["| set | missions | failures | proven optimal | flow's work median / p90 / largest | "
              "flow's time (fastest solve_us) median / p90 / worst | goal: p90 under 1 ms, worst under 2 ms |",
              "|---|---|---|---|---|---|---|"]


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sets", default=",".join(SETS), help=f"comma-separated, of: {', '.join(SETS)}")
    ap.add_argument("--missions", type=int, default=30)
    ap.add_argument("--repeat", type=int, default=3, help="runs per mission; its time is the fastest")
    ap.add_argument("--sva", help="the CLI (default: $SVA_BIN, else build/bin/sva)")
    ap.add_argument("--results", action="store_true", help="write docs/results/core.flow_latency.md")
    ap.add_argument("--quick", action="store_true", help="2 missions of 25x5_fuel80, one run each")
    args = ap.parse_args(argv)
    if args.quick:
        args.sets, args.missions, args.repeat = "25x5_fuel80", 2, 1
    sets = [s for s in args.sets.split(",") if s]
    bad = [s for s in sets if s not in SETS]
    if bad:
        ap.error(f"--sets: unknown set(s) {bad}; sets: {', '.join(SETS)}")
    if args.missions < 1 or args.repeat < 1:
        ap.error("--missions and --repeat must be >= 1")
    sva = args.sva or os.environ.get("SVA_BIN") or os.path.join(ROOT, "build", "bin", "sva")
    if not os.path.isfile(sva):
        ap.error(f"--sva: no CLI at {sva} (build it with scripts/build.sh)")
    load_start = " ".join(f"{x:.2f}" for x in os.getloadavg())
    figures = []
    for name in sets:
        with tempfile.TemporaryDirectory(prefix="flow-latency-") as d:
            runs = []
            for m in missions_of(name, args.missions):
                path = os.path.join(d, f"{m.name}.json")
                io.write_json(m.to_json(), path)
                runs.append(run_flow(sva, m, path, args.repeat))
        f = summary(name, runs)
        figures.append(f)
        print(f"{name} ({gen_command(name, args.missions)}): missions {f['missions']}, "
              f"failures {len(f['failures'])}")
        for reason in f["failures"]:
            print(f"  failure: {reason}")
        if "us" in f:
            print(f"  proven optimal {f['proven']} of {f['missions']}; work median {f['work'][0]:,.0f}, p90 "
                  f"{f['work'][1]:,}, largest {f['work'][2]:,}")
            print(f"  time (fastest of {args.repeat}): median {ms(f['us'][0])}, p90 {ms(f['us'][1])}, worst "
                  f"{ms(f['us'][2])}; goal (p90 under 1 ms, worst under 2 ms) "
                  f"{'met' if f['goal'] else 'not met'}")
    table = [*TABLE_HEAD, *[row(f) for f in figures]]
    print()
    print("\n".join(table))
    if args.results:
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        import results  # tools/bench/results.py
        cmd = (f"nice -n 15 .venv/bin/python tools/bench/flow_latency.py --results --sets {','.join(sets)} "
               f"--missions {args.missions} --repeat {args.repeat}")
        body = "\n".join([
            "Missions: " + "; ".join(f"{f['set']}: `{gen_command(f['set'], args.missions)}`" for f in figures)
            + f". `sva plan --algo flow`, one plan per process, the default work budget, {args.repeat} runs "
              "per mission: its time is the fastest `stats.solve_us` (wall clock inside the planner), its "
              "work `stats.flow_work` (the same on every run). Every plan passed the independent checker "
              "unless counted as a failure. p90: nearest rank. At this size flow stops before its budget "
              "(2,000,000 units, `SVA_FLOW_MAX_WORK`) only when it proves its plan optimal.",
            "", *table])
        results.write(results.ROOT, "core.flow_latency", cmd, body, title="flow's time where fuel binds",
                      load_start=load_start)
    return 1 if any(f["failures"] for f in figures) else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
