#!/usr/bin/env python3
"""flow with the large bound profile at 1,000 targets x 100 UAVs, need 1.

Usage (from the repository root, after scripts/setup.sh):
    nice -n 15 .venv/bin/python tools/bench/large_profile.py [--sets NAME,...] [--missions N]
        [--sva PATH] [--results] [--quick]
The CLI is `sva` built with the large profile (core/profiles/sva_profile_large.h): --sva
PATH, else $SVA_LARGE_BIN, else build-large/bin/sva, which the script configures
(`cmake -S . -B build-large -DSVA_PROFILE=large`, no tests, no ports) and builds (target
sva only) first. It refuses a CLI whose `sva --version` does not report the large
profile's bounds.
Sets (`sva-tools gen --need 1 --seed 7`, the first N missions, checked against the
large profile's bounds):
    1000x100        1,000 targets x 100 UAVs, the generator's fuel (150) and windows (20 to 40)
    1000x100_tight  the same, --fuel 80
    300x80          300 targets x 80 UAVs (past the default profile's bounds), gen's fuel
    300x80_tight    the same, --fuel 80
Default: --sets 1000x100,1000x100_tight --missions 10. Each mission is planned by `sva plan
--algo flow` (one plan per process, the default work budget) and the plan goes through the
independent checker (sva_tools.check); a refused plan or a CLI error is a failure.
Prints per set: failures, coverage (smallest, and on how many missions every target),
cost (median and largest), flow's time (stats.solve_us: median and worst, wall clock), the
process's CPU time (user + system: median and worst; less sensitive to a shared machine's
load), flow's certified gap (cost / stats.lower_bound - 1: median and worst), how many
plans are proven optimal, and flow's work (stats.flow_work) with the most search nodes,
Lagrangian iterations and ruin and recreate rounds of any plan (which phases ran).
Exit status 1 when any plan failed.
--results writes docs/results/large.md (tools/bench/results.py) and reassembles
docs/results.md. --quick: one mission of each 300x80 set (ctest runs it, label tools).
"""
import argparse
import json
import os
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))

from sva_tools import check, gen, io, schema  # noqa: E402

BUILD = os.path.join(ROOT, "build-large")
SEED = 7
# The large profile's mission bounds (core/profiles/sva_profile_large.h).
MAX_UAVS, MAX_TARGETS = 128, 1024
SETS = {
    "1000x100": dict(targets=1000, uavs=100, fuel=150),
    "1000x100_tight": dict(targets=1000, uavs=100, fuel=80),
    "300x80": dict(targets=300, uavs=80, fuel=150),
    "300x80_tight": dict(targets=300, uavs=80, fuel=80),
}
GOAL_US = 1_000_000  # flow's time goal per plan at 1,000 x 100


def large_cli(path):
    """The large-profile CLI: `path`, $SVA_LARGE_BIN, or build-large/bin/sva (built here)."""
    path = path or os.environ.get("SVA_LARGE_BIN")
    if not path:
        if not os.path.isfile(os.path.join(BUILD, "CMakeCache.txt")):
            gen_args = ["-G", "Ninja"] if shutil.which("ninja") else []
            subprocess.run(["cmake", "-S", ROOT, "-B", BUILD, *gen_args, "-DCMAKE_BUILD_TYPE=RelWithDebInfo",
                            "-DSVA_BUILD_TESTS=OFF", "-DSVA_BUILD_PORTS=OFF", "-DSVA_PROFILE=large"],
                           check=True, stdout=subprocess.DEVNULL)
        subprocess.run(["cmake", "--build", BUILD, "--target", "sva"], check=True, stdout=subprocess.DEVNULL)
        path = os.path.join(BUILD, "bin", "sva")
    out = subprocess.run([path, "--version"], capture_output=True, text=True, check=True).stdout
    bounds = re.search(r"SVA_MAX_UAVS (\d+), SVA_MAX_TARGETS (\d+)", out)
    if not bounds or (int(bounds[1]), int(bounds[2])) != (MAX_UAVS, MAX_TARGETS):
        sys.exit(f"large_profile: {path} is not built with the large profile (its --version: "
                 f"{out.splitlines()[1] if len(out.splitlines()) > 1 else out!r})")
    return path


def missions_of(name, count):
    s = SETS[name]
    with schema.profile_bounds(MAX_UAVS, MAX_TARGETS):
        return [gen.generate(s["targets"], s["uavs"], need=(1, 1), fuel=s["fuel"], seed=SEED, index=i)
                for i in range(count)]


def gen_command(name, count):
    s = SETS[name]
    return (f"sva-tools gen --targets {s['targets']} --uavs {s['uavs']} --need 1 --fuel {s['fuel']} "
            f"--seed {SEED} --count {count}")


def run_flow(sva, m, path):
    """(plan, CPU seconds of the process) of a plan the checker accepts, else (None, reason)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run([sva, "plan", "--algo", "flow", path], capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if out.returncode != 0:
        return None, f"sva exited {out.returncode}: {out.stderr.strip()[:200]}"
    with schema.profile_bounds(MAX_UAVS, MAX_TARGETS):
        plan = io.plan_from_json(json.loads(out.stdout))
        violations = check.check_plan(m, plan)
    if violations:
        return None, f"checker: {violations[0]}"
    return plan, cpu


def median_worst(values, worst=max):
    return (statistics.median(values), worst(values)) if values else (None, None)


def ms(us):
    return "–" if us is None else (f"{us / 1e6:.2f} s" if us >= 1e6 else f"{us / 1000:.0f} ms")


def summary(name, missions, runs):
    """The set's figures (a dict) from its missions and their (plan, cpu or reason)."""
    ok = [(m, p, cpu) for m, (p, cpu) in zip(missions, runs) if p is not None]
    stats = [p.stats or {} for _, p, _ in ok]
    gaps = [100.0 * (p.cost / s["lower_bound"] - 1) for (_, p, _), s in zip(ok, stats)
            if s.get("lower_bound", 0) > 0]
    return {
        "set": name, "missions": len(missions), "failures": [r for p, r in runs if p is None],
        "covered_min": min((p.covered for _, p, _ in ok), default=None),
        "all_covered": sum(1 for m, p, _ in ok if p.covered == len(m.targets)),
        "cost": median_worst([p.cost for _, p, _ in ok]),
        "us": median_worst([s["solve_us"] for s in stats if "solve_us" in s]),
        "cpu_us": median_worst([cpu * 1e6 for _, _, cpu in ok]),
        "gap": median_worst(gaps), "bounds": len(gaps),
        "proven": sum(1 for s in stats if s.get("optimal")),
        "work": median_worst([s.get("flow_work", 0) for s in stats]),
        "phases": (max((s.get("search_nodes", 0) for s in stats), default=0),
                   max((s.get("flow_lagrange_iters", 0) for s in stats), default=0),
                   max((s.get("flow_ruin_rounds", 0) for s in stats), default=0)),
    }


def gap_text(g):
    return "–" if g[0] is None else f"{g[0]:.2f} % / {g[1]:.2f} %"


def row(f):
    cost = "–" if f["cost"][0] is None else f"{f['cost'][0]:,.0f} / {f['cost'][1]:,}"
    return (f"| {f['set']} | {f['missions']} | {len(f['failures'])} | {f['covered_min']} "
            f"({f['all_covered']} of {f['missions']} cover all) | {cost} | {ms(f['us'][0])} / {ms(f['us'][1])} | "
            f"{ms(f['cpu_us'][0])} / {ms(f['cpu_us'][1])} | {gap_text(f['gap'])} (bounds: {f['bounds']}) | "
            f"{f['proven']} of {f['missions']} |")


TABLE_HEAD = ["| set | missions | failures | covered: fewest (missions covering every target) | cost median / "
              "largest | flow's time (solve_us) median / worst | process CPU median / worst | certified gap "
              "median / worst | proven optimal |",
              "|---|---|---|---|---|---|---|---|---|"]


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sets", default="1000x100,1000x100_tight", help=f"comma-separated, of: {', '.join(SETS)}")
    ap.add_argument("--missions", type=int, default=10)
    ap.add_argument("--sva", help="the large-profile CLI (default: $SVA_LARGE_BIN, else build-large/bin/sva)")
    ap.add_argument("--results", action="store_true", help="write docs/results/large.md")
    ap.add_argument("--quick", action="store_true", help="one mission of each 300x80 set")
    args = ap.parse_args(argv)
    if args.quick:
        args.sets, args.missions = "300x80,300x80_tight", 1
    sets = [s for s in args.sets.split(",") if s]
    bad = [s for s in sets if s not in SETS]
    if bad:
        ap.error(f"--sets: unknown set(s) {bad}; sets: {', '.join(SETS)}")
    if args.missions < 1:
        ap.error("--missions must be >= 1")
    sva = large_cli(args.sva)
    load_start = " ".join(f"{x:.2f}" for x in os.getloadavg())
    figures = []
    for name in sets:
        missions = missions_of(name, args.missions)
        with tempfile.TemporaryDirectory(prefix="large-profile-") as d:
            runs = []
            for m in missions:
                p = os.path.join(d, f"{m.name}.json")
                io.write_json(m.to_json(), p)
                runs.append(run_flow(sva, m, p))
        f = summary(name, missions, runs)
        figures.append(f)
        print(f"{name} ({gen_command(name, args.missions)}): missions {f['missions']}, "
              f"failures {len(f['failures'])}")
        for reason in f["failures"]:
            print(f"  failure: {reason}")
        if f["covered_min"] is not None:
            print(f"  covered: fewest {f['covered_min']}, every target on {f['all_covered']}; cost median "
                  f"{f['cost'][0]:,.0f}, largest {f['cost'][1]:,}")
            print(f"  flow's time (solve_us): median {ms(f['us'][0])}, worst {ms(f['us'][1])}; process CPU: "
                  f"median {ms(f['cpu_us'][0])}, worst {ms(f['cpu_us'][1])}")
            print(f"  certified gap (cost / lower_bound - 1): median / worst {gap_text(f['gap'])} "
                  f"(plans with a bound: {f['bounds']}); proven optimal {f['proven']} of {f['missions']}")
            print(f"  flow's work (arc scans): median {f['work'][0]:,.0f}, largest {f['work'][1]:,}; at most "
                  f"{f['phases'][0]} search nodes, {f['phases'][1]} Lagrangian iterations, {f['phases'][2]} ruin "
                  "and recreate rounds")
    table = [*TABLE_HEAD, *[row(f) for f in figures]]
    print()
    print("\n".join(table))
    if args.results:
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        import results  # tools/bench/results.py
        cmd = ("nice -n 15 .venv/bin/python tools/bench/large_profile.py --results "
               f"--sets {','.join(sets)} --missions {args.missions}")
        big = [f for f in figures if SETS[f["set"]]["targets"] == 1000 and f["us"][1] is not None]
        goal = ""
        if big:
            wall = max(f["us"][1] for f in big)
            cpu = max(f["cpu_us"][1] for f in big)
            goal = (f" Goal at 1,000 x 100: a checked plan within 1 s. Worst here: {ms(wall)} of flow's "
                    f"wall-clock time ({'within' if wall < GOAL_US else 'over'} 1 s on this run, at the load "
                    f"below), {ms(cpu)} of process CPU time ({'within' if cpu < GOAL_US else 'over'} 1 s).")
        body = "\n".join([
            "Missions: " + "; ".join(f"{f['set']}: `{gen_command(f['set'], args.missions)}`" for f in figures)
            + ". The CLI built with `-DSVA_PROFILE=large` (128 UAVs, 1,024 targets, flow's graph up to "
              "656,000 arcs); `sva plan --algo flow`, one plan per process, the default work budget. Every "
              "plan passed the independent checker unless counted as a failure. flow's time is "
              "`stats.solve_us` (wall clock); the process's CPU time (user + system) includes reading "
              "the mission and writing the plan. Certified gap: cost / `stats.lower_bound` - 1." + goal,
            "", *table, "",
            "flow's work (`stats.flow_work`, arc scans; the default budget, `SVA_FLOW_MAX_WORK`, is "
            "2,000,000) and the most search nodes, Lagrangian iterations and ruin and recreate rounds of any plan: "
            + "; ".join(f"{f['set']}: median {f['work'][0]:,.0f}, {f['phases'][0]} / {f['phases'][1]} / "
                        f"{f['phases'][2]}" for f in figures) + ". Where the root relaxation alone passes the "
            "budget, the plan starts from its rounding and the repaired `ga` and `sva` plans after the local "
            "search; the search (which branches on fuel) does not run and the Lagrangian phase (which prices "
            "fuel into the bound) takes at most one step, so with tight fuel the bound is about the fuel-free "
            "relaxation's; ruin and recreate then gets half the budget (the rounds above)."])
        results.write(results.ROOT, "large", cmd, body, title=None, load_start=load_start)
    return 1 if any(f["failures"] for f in figures) else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
