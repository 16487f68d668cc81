#!/usr/bin/env python3
"""How much the route master's LP bound can certify, next to flow's certified bound.

Usage (from the repository root, after scripts/setup.sh and scripts/build.sh):
    nice .venv/bin/python tools/bench/route_lp_bound.py [--results] [--sets 100x20_tight,...]
        [--missions N] [--lp-time S] [--time-limit S] [--quick]

The missions are tools/bench/flow_vs_pyvrp.py's sets (the same generator and seed). For
each mission: flow's plan at its default budget and its certified bound
(`stats.lower_bound`), PyVRP's plan (--time-limit, default 1 s, seed 1), both checked by
the independent checker, and the route master's LP bound for flow's coverage by column
generation (tools/sva_tools/route_lp.py: exact elementary pricing, CLP; flow's routes
as its first columns; at most --lp-time seconds, default 600: stopped earlier, or by an
LP that CLP does not solve, the best Lagrangian value found so far is the bound).
Prints per set: missions where the column generation finished, the gap of flow's plan to
its own bound and to the LP bound, the gap of the cheaper of flow's and PyVRP's plans
(at flow's coverage) to the LP bound, and the LP's median time. That last gap is the
least any bound from this LP can certify: the optimum lies between the LP bound and the
cheaper plan. Exit status 1 when an LP bound exceeds a checked plan's cost at the same
coverage (the bound would be wrong).
--results writes docs/results/flow_vs_peer.route_lp_bound.md (tools/bench/results.py). --quick: 2
missions of 025x05_tight, PyVRP 0.2 s (a test).
"""
import argparse
import os
import statistics
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import flow_vs_pyvrp as fvp  # noqa: E402  (tools/bench: the sets, flow and PyVRP runs)

from sva_tools import io, route_lp  # noqa: E402


def pct(v):
    return "–" if v is None else f"{v:.1f} %"


def med_worst(gaps):
    return (f"{pct(statistics.median(gaps))} / {pct(max(gaps))}") if gaps else "–"


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sets", default="100x20_tight", help=f"comma-separated, of: {', '.join(fvp.SETS)}")
    ap.add_argument("--missions", type=int, default=10)
    ap.add_argument("--lp-time", type=float, default=600.0)
    ap.add_argument("--time-limit", type=float, default=1.0, help="PyVRP's wall clock, s")
    ap.add_argument("--results", action="store_true")
    ap.add_argument("--quick", action="store_true", help="2 missions of 025x05_tight, PyVRP 0.2 s")
    args = ap.parse_args(argv)
    if args.quick:
        args.sets, args.missions, args.time_limit = "025x05_tight", 2, 0.2
    sets = [s for s in args.sets.split(",") if s]
    bad = [s for s in sets if s not in fvp.SETS]
    if bad:
        ap.error(f"--sets: unknown set(s) {bad}; sets: {', '.join(fvp.SETS)}")
    load_start = " ".join(f"{x:.2f}" for x in os.getloadavg())
    rows = []
    wrong = 0
    for name in sets:
        missions = fvp.missions_of(name, args.missions)
        own, to_lp, best_to_lp, lp_secs, finished = [], [], [], [], 0
        print(f"{name} ({fvp.gen_command(name, args.missions)}): {len(missions)} missions")
        for m in missions:
            with tempfile.TemporaryDirectory(prefix="route-lp-") as d:
                path = os.path.join(d, f"{m.name}.json")
                io.write_json(m.to_json(), path)
                flow = fvp.run_flow(m, path, "default")
            if flow is None:
                print(f"  {m.name}: flow failed or its plan was rejected")
                wrong += 1
                continue
            covered, cost, _, stats, plan = flow
            pyvrp = fvp.run_pyvrp(m, args.time_limit, 1)
            lp = route_lp.route_lp_bound(m, covered, [(r.uav, r.targets) for r in plan.routes],
                                         time_limit=args.lp_time)
            best = min([cost] + ([pyvrp[1]] if pyvrp is not None and pyvrp[0] >= covered else []))
            finished += lp.converged
            lp_secs.append(lp.seconds)
            flow_lb = stats.get("lower_bound", 0)
            if flow_lb > 0:
                own.append(100.0 * (cost / flow_lb - 1))
            if lp.bound:
                to_lp.append(100.0 * (cost / lp.bound - 1))
                best_to_lp.append(100.0 * (best / lp.bound - 1))
            if lp.bound is not None and lp.bound > best:
                print(f"  {m.name}: the LP bound {lp.bound} exceeds a checked plan's cost {best}")
                wrong += 1
            print(f"  {m.name}: flow {covered} targets, cost {cost}, its bound {flow_lb}; PyVRP "
                  f"{'failed' if pyvrp is None else f'{pyvrp[0]} targets, cost {pyvrp[1]}'}; route LP bound "
                  f"{lp.bound} ({'finished' if lp.converged else 'stopped: ' + lp.stopped_by} after "
                  f"{lp.iterations} pricings, "
                  f"{lp.columns} routes, {lp.seconds:.1f} s)", flush=True)
        rows.append(f"| {name} | {len(missions)} | {finished} | {med_worst(own)} | {med_worst(to_lp)} | "
                    f"{med_worst(best_to_lp)} | "
                    + (f"{statistics.median(lp_secs):.1f} s" if lp_secs else "–") + " |")
    table = ["| set | missions | LP finished | flow's plan over its certified bound, median / worst | "
             "flow's plan over the route LP bound | the cheaper plan (flow, PyVRP) over the route LP bound | "
             "LP time, median |", "|---|---|---|---|---|---|---|", *rows]
    print()
    print("\n".join(table))
    if args.results:
        import results  # tools/bench/results.py
        cmd = ("nice .venv/bin/python tools/bench/route_lp_bound.py --results "
               f"--sets {','.join(sets)} --missions {args.missions} --lp-time {args.lp_time:g} "
               f"--time-limit {args.time_limit:g}")
        body = "\n".join([
            "Missions: " + "; ".join(f"{n}: `{fvp.gen_command(n, args.missions)}`" for n in sets) + ". "
            "flow: `sva plan --algo flow` at its default budget; its certified bound is `stats.lower_bound`. "
            f"PyVRP {fvp.pyvrp_version()}: {args.time_limit:g} s, seed 1. Route LP bound: the route master's "
            "LP for flow's coverage by column generation (tools/sva_tools/route_lp.py: exact elementary "
            "pricing with fuel, CLP through OR-tools), flow's routes as its first columns, at most "
            f"{args.lp_time:g} s per mission. Gaps: cost / bound - 1. The optimum lies between the LP "
            "bound and the cheaper plan: no bound from this LP certifies that plan closer than its gap here.",
            "", *table])
        results.write(results.ROOT, "flow_vs_peer.route_lp_bound", cmd, body,
                      title="The route master's LP bound against flow's certified bound", load_start=load_start)
    return 1 if wrong else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
