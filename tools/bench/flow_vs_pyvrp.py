#!/usr/bin/env python3
"""flow against PyVRP and the OR-tools routing peer on generated need-1 missions.

Usage (from the repository root, after scripts/setup.sh and scripts/build.sh):
    nice -n 15 .venv/bin/python tools/bench/flow_vs_pyvrp.py [--sets NAME,...] [--missions N]
        [--budgets default,N,...] [--time-limit S] [--pyvrp-seed N] [--gen-seed N] [--no-ortools]
        [--results] [--quick]
Sets (`sva-tools gen --need 1 --seed 7`, the first N missions; --gen-seed another seed):
    025x05_tight  25 targets x 5 UAVs, --width 10:20 --hover 2 --fuel 80
    025x05_loose  25 targets x 5 UAVs, --width 10:20 --hover 2 --fuel 150
    100x20        100 targets x 20 UAVs, the generator's fuel (150) and windows (20 to 40)
    200x40        200 targets x 40 UAVs, the same
    100x20_tight  100 targets x 20 UAVs, windows 20 to 40, --fuel 80
    200x40_tight  200 targets x 40 UAVs, the same
Default: --sets 100x20,200x40 --missions 20 --budgets default. flow is the C CLI (`sva plan
--algo flow`, one plan per process, `stats.solve_us`); `default` is its largest budget
(2,000,000 arc scans: SVA_FLOW_MAX_WORK), so further budgets can only be smaller. PyVRP:
tools/sva_tools/pyvrp_peer.py, --time-limit seconds of wall clock (default 1) and
--pyvrp-seed (default 1); its time is the wall time of the whole call. OR-tools: `sva-tools
peer` with the bench's settings (greedy descent, solution limit 100), solved now. Every plan,
flow's too, goes through the independent checker (sva_tools.check); a refused plan or an
error is a failure of that solver and is left out of its comparisons.
Prints per set, per flow budget and per peer: flow's wins / ties / losses at equal coverage,
the missions where it covers more or fewer (and by how many targets), the cost ratio
flow / peer at equal coverage (median and worst), the median times and their ratio, and
flow's certified gap (cost / lower_bound - 1, from its stats): median and worst.
--results writes docs/results/flow_vs_peer.pyvrp_<sets>.md (tools/bench/results.py; with
`_seed<N>` for another --gen-seed) and reassembles docs/results.md. --quick: 3 missions of 025x05_tight, PyVRP 0.2 s (a test).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))

from sva_tools import check, gen, io, peer, pyvrp_peer  # noqa: E402

SVA = os.environ.get("SVA_BIN") or os.path.join(ROOT, "build", "bin", "sva")
SEED = 7
SETS = {
    "025x05_tight": dict(targets=25, uavs=5, width=(10, 20), fuel=80, hover=2),
    "025x05_loose": dict(targets=25, uavs=5, width=(10, 20), fuel=150, hover=2),
    "100x20": dict(targets=100, uavs=20, width=(20, 40), fuel=150, hover=0),
    "200x40": dict(targets=200, uavs=40, width=(20, 40), fuel=150, hover=0),
    "100x20_tight": dict(targets=100, uavs=20, width=(20, 40), fuel=80, hover=0),
    "200x40_tight": dict(targets=200, uavs=40, width=(20, 40), fuel=80, hover=0),
}
PEER_SOLUTION_LIMIT = 100


def missions_of(name, count, seed=SEED):
    s = SETS[name]
    return [gen.generate(s["targets"], s["uavs"], width=s["width"], need=(1, 1), fuel=s["fuel"],
                         hover=s["hover"], seed=seed, index=i) for i in range(count)]


def gen_command(name, count, seed=SEED):
    s = SETS[name]
    return (f"sva-tools gen --targets {s['targets']} --uavs {s['uavs']} --width {s['width'][0]}:{s['width'][1]} "
            f"--need 1 --fuel {s['fuel']} --hover {s['hover']} --seed {seed} --count {count}")


def checked(m, plan):
    """(covered, cost, solve_us, stats, plan) of a plan the checker accepts, else None."""
    if check.check_plan(m, plan):
        return None
    return plan.covered, plan.cost, (plan.stats or {}).get("solve_us"), plan.stats or {}, plan


def run_flow(m, path, budget):
    cmd = [SVA, "plan", "--algo", "flow"] + ([] if budget == "default" else ["--flow-work", budget])
    out = subprocess.run(cmd + [path], capture_output=True, text=True)
    if out.returncode != 0:
        return None
    return checked(m, io.plan_from_json(json.loads(out.stdout)))


def run_pyvrp(m, time_limit, seed):
    try:
        return checked(m, pyvrp_peer.solve_pyvrp(m, time_limit, seed))
    except Exception as e:  # a crash is the peer's failure, reported
        print(f"  pyvrp on {m.name}: {type(e).__name__}: {e}", file=sys.stderr)
        return None


def run_ortools(m):
    try:
        return checked(m, peer.solve_peer(m, PEER_SOLUTION_LIMIT))
    except Exception as e:
        print(f"  ortools on {m.name}: {type(e).__name__}: {e}", file=sys.stderr)
        return None


def compare(flows, peers):
    """Figures of flow against one peer over the missions both solved."""
    pairs = [(f, q) for f, q in zip(flows, peers) if f is not None and q is not None]
    more = [(f[0] - q[0]) for f, q in pairs if f[0] > q[0]]
    fewer = [(q[0] - f[0]) for f, q in pairs if f[0] < q[0]]
    equal = [(f, q) for f, q in pairs if f[0] == q[0]]
    wins = sum(1 for f, q in equal if f[1] < q[1])
    ties = sum(1 for f, q in equal if f[1] == q[1])
    losses = sum(1 for f, q in equal if f[1] > q[1])
    ratios = [f[1] / q[1] for f, q in equal if q[1] > 0]
    ft = [f[2] for f in flows if f is not None]
    qt = [q[2] for q in peers if q is not None]
    return {"pairs": len(pairs), "more": more, "fewer": fewer, "equal": len(equal), "wins": wins,
            "ties": ties, "losses": losses, "ratio_median": statistics.median(ratios) if ratios else None,
            "ratio_worst": max(ratios) if ratios else None,
            "flow_us": statistics.median(ft) if ft else None, "peer_us": statistics.median(qt) if qt else None,
            "failures": sum(1 for q in peers if q is None)}


def certified(flows):
    gaps = [100.0 * (f[1] / f[3]["lower_bound"] - 1) for f in flows
            if f is not None and f[3].get("lower_bound", 0) > 0]
    return (statistics.median(gaps), max(gaps)) if gaps else (None, None)


def cov_text(c):
    more = f"more on {len(c['more'])} (+{sum(c['more'])} targets)" if c["more"] else "never more"
    fewer = f"fewer on {len(c['fewer'])} (-{sum(c['fewer'])} targets)" if c["fewer"] else "never fewer"
    return f"{more}, {fewer}"


def ratio_text(c):
    if c["ratio_median"] is None:
        return "–"
    return f"{c['ratio_median']:.3f} / {c['ratio_worst']:.3f}"


def ms(us):
    return "–" if us is None else (f"{us / 1e6:.2f} s" if us >= 1e6 else f"{us / 1000:.1f} ms")


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sets", default="100x20,200x40", help=f"comma-separated, of: {', '.join(SETS)}")
    ap.add_argument("--missions", type=int, default=20)
    ap.add_argument("--budgets", default="default", help="flow's --flow-work values, comma-separated")
    ap.add_argument("--time-limit", type=float, default=pyvrp_peer.TIME_LIMIT, help="PyVRP's limit, seconds")
    ap.add_argument("--pyvrp-seed", type=int, default=pyvrp_peer.SEED)
    ap.add_argument("--gen-seed", type=int, default=SEED, help="the missions' generator seed")
    ap.add_argument("--no-ortools", action="store_true", help="leave the OR-tools peer out")
    ap.add_argument("--results", action="store_true", help="write this run's part of docs/results.md")
    ap.add_argument("--quick", action="store_true", help="3 missions of 025x05_tight, PyVRP 0.2 s")
    args = ap.parse_args(argv)
    if args.quick:
        args.sets, args.missions, args.time_limit = "025x05_tight", 3, 0.2
    sets = [s for s in args.sets.split(",") if s]
    bad = [s for s in sets if s not in SETS]
    if bad:
        ap.error(f"--sets: unknown set(s) {bad}; sets: {', '.join(SETS)}")
    budgets = [b for b in args.budgets.split(",") if b]
    load_start = " ".join(f"{x:.2f}" for x in os.getloadavg())
    peers = ["PyVRP"] + ([] if args.no_ortools else ["OR-tools"])
    rows = []
    for name in sets:
        missions = missions_of(name, args.missions, args.gen_seed)
        with tempfile.TemporaryDirectory(prefix="flow-vs-pyvrp-") as d:
            paths = []
            for m in missions:
                p = os.path.join(d, f"{m.name}.json")
                io.write_json(m.to_json(), p)
                paths.append(p)
            flows = {b: [run_flow(m, p, b) for m, p in zip(missions, paths)] for b in budgets}
        results = {"PyVRP": [run_pyvrp(m, args.time_limit, args.pyvrp_seed) for m in missions]}
        if not args.no_ortools:
            results["OR-tools"] = [run_ortools(m) for m in missions]
        print(f"{name} ({gen_command(name, args.missions, args.gen_seed)}): {len(missions)} missions")
        for b in budgets:
            fails = sum(1 for f in flows[b] if f is None)
            med, worst = certified(flows[b])
            cert = "–" if med is None else f"{med:.2f} % / {worst:.2f} %"
            print(f"  flow (budget {b}): {fails} failures; certified gap median / worst {cert}")
            for who in peers:
                c = compare(flows[b], results[who])
                speed = (c["peer_us"] / c["flow_us"]) if c["flow_us"] and c["peer_us"] else None
                print(f"    vs {who}: {c['failures']} peer failures; at equal coverage ({c['equal']}) flow wins "
                      f"{c['wins']}, ties {c['ties']}, loses {c['losses']}; coverage: {cov_text(c)}; cost ratio "
                      f"flow/{who} median / worst {ratio_text(c)}; time flow {ms(c['flow_us'])}, {who} "
                      f"{ms(c['peer_us'])}" + (f" ({speed:,.0f}x)" if speed else ""))
                rows.append(f"| {name} | {b} | {who} | {c['failures']} | {c['wins']} / {c['ties']} / {c['losses']} "
                            f"of {c['equal']} | {cov_text(c)} | {ratio_text(c)} | {ms(c['flow_us'])} | "
                            f"{ms(c['peer_us'])} | " + (f"{speed:,.0f}x" if speed else "–") + f" | {cert} |")
    table = ["| set | flow budget | peer | peer failures | flow wins / ties / losses at equal coverage | "
             "flow's coverage against the peer | cost ratio flow / peer at equal coverage, median / worst | "
             "flow median | peer median | ratio | flow's certified gap, median / worst |",
             "|---|---|---|---|---|---|---|---|---|---|---|", *rows]
    print()
    print("\n".join(table))
    if args.results:
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        import results  # tools/bench/results.py
        flags = ["--results", f"--sets {','.join(sets)}", f"--missions {args.missions}",
                 f"--budgets {','.join(budgets)}", f"--time-limit {args.time_limit:g}",
                 f"--pyvrp-seed {args.pyvrp_seed}"] + (["--no-ortools"] if args.no_ortools else []) \
            + ([f"--gen-seed {args.gen_seed}"] if args.gen_seed != SEED else [])
        cmd = "nice -n 15 .venv/bin/python tools/bench/flow_vs_pyvrp.py " + " ".join(flags)
        body = "\n".join(
            ["Missions: " + "; ".join(f"{n}: `{gen_command(n, args.missions, args.gen_seed)}`" for n in sets) + ". "
             f"PyVRP {pyvrp_version()} (tools/sva_tools/pyvrp_peer.py: prize-collecting, the exact "
             f"lexicographic objective on need-1 missions), {args.time_limit:g} s of wall clock, seed "
             f"{args.pyvrp_seed}, its time the wall time of the whole call. "
             + ("" if args.no_ortools else f"OR-tools: `sva-tools peer`, greedy descent, solution limit "
                                           f"{PEER_SOLUTION_LIMIT}. ")
             + "flow: `sva plan --algo flow`, one plan per process, `stats.solve_us`; `default` is its "
               "largest budget. Every plan passed the independent checker unless counted as a failure. "
               "Cost ratio: flow's cost over the peer's where both cover as many targets (above 1: flow "
               "costs more); ratio: the peer's median time over flow's.", "", *table])
        limit = "" if args.time_limit == pyvrp_peer.TIME_LIMIT else f"_pyvrp{args.time_limit:g}s"
        seeded = "" if args.gen_seed == SEED else f"_seed{args.gen_seed}"
        results.write(results.ROOT, "flow_vs_peer.pyvrp_" + "_".join(sets) + limit.replace(".", "_") + seeded, cmd,
                      body, title="flow against PyVRP: " + ", ".join(sets)
                      + ("" if not limit else f", PyVRP {args.time_limit:g} s")
                      + ("" if not seeded else f", gen seed {args.gen_seed}"), load_start=load_start)
    return 0


def pyvrp_version():
    from importlib import metadata
    try:
        return metadata.version("pyvrp")
    except metadata.PackageNotFoundError:
        return "(not installed)"


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
