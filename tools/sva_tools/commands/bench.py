"""`sva-tools bench`: the paper's evaluation (section 5) against the C planners.

Protocol: random missions from `gen` (20x20 grid, depot (0, 0), every UAV at the
depot, need 2, fuel 150, windows 20..40 ticks), sizes 3 and 5 targets with 3 UAVs and
7, 10, 25 targets with 5 UAVs (intersection ratio any), plus 10 targets / 5 UAVs in
each intersection category low, mid, high; --missions per set (paper: 100).
Algorithms: the C planners through `sva plan --algo` (sva, ga, hga, bfa, flow, and any
other name the C CLI accepts, given in --algos; a name this build of the CLI does not
know is skipped with a note), and ih, ref, peer from this package.
Every plan is checked with `check`; the optimum of a mission is ref's plan when ref
proved it optimal, else bfa's. Figures per set and algorithm: completion ratio, mean
covered, mean cost, mean gap to the optimum (over missions where the plan covers as
many targets as the optimum), how often it covers fewer, median and p95 solve time
(stats.solve_us: the C planners time sva_plan() alone; Python planners their solve).
Plans that carry a certificate in stats (flow, ref: `lower_bound`, `optimal`) add the
certified gap, mean of (cost - lower_bound) / lower_bound, and how many were proven
optimal.
--scaling adds 50/10, 100/20, 200/40 targets/UAVs with the fuel-free lower bound
(`ref --bound`) in place of the optimum, in rounds of one mission per size; --time-box
MIN starts no new round after MIN minutes (the paper sets and one round always run).
ref and peer use limits that do not depend on machine load (ref: one CP-SAT worker,
--ref-det-limit deterministic time; peer: greedy descent, --peer-solution-limit); their
wall-clock limits are safety nets, and the report counts results they ended.
--cache DIR stores ih, ref and peer results (one JSON per mission content, solver,
settings and code version; tools/sva_tools/cache.py) and reuses them on a later run,
so a re-run after a C planner changed only runs the C planners. A cached result keeps
the solve time measured when it was computed; the report marks cached rows and says
when and under what load every algorithm's results were measured, and gives the load
average at the start and end of the run. --log FILE: one progress line per mission.
Writes DIR/README.md and PNG figures.
"""
from __future__ import annotations

import argparse
import os
import platform
import statistics
import sys
import tempfile
import time
from typing import Any

from .. import cache, cbin, gen, model, peer, ref
from ..bench import (
    DEFAULT_ALGOS,
    DEFAULT_SCALING_ALGOS,
    GEN,
    PY_ALGOS,
    RATIO_SETS,
    SCALING_SETS,
    SIZE_SETS,
    figure,
    headline,
    log_progress,
    new_set,
    provenance,
    run_mission,
    run_set,
    summarise,
    table,
)
from ..text import shown


def add_parser(sub) -> None:
    ap = sub.add_parser("bench", help="reproduce the paper's evaluation (markdown + PNG)",
                        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--missions", type=int, default=100, help="missions per set (paper: 100)")
    ap.add_argument("--algos", default=DEFAULT_ALGOS,
                    help=f"comma-separated algorithms (default {DEFAULT_ALGOS}); names other "
                         f"than ih, ref, peer go to `sva plan --algo`")
    ap.add_argument("--seed", type=int, default=2024)
    ap.add_argument("--out", default="docs/bench", help="report directory (default docs/bench)")
    ap.add_argument("--no-paper", action="store_true", help="skip the paper sets")
    ap.add_argument("--scaling", action="store_true", help="also run 50/10, 100/20, 200/40")
    ap.add_argument("--scaling-missions", type=int, default=5)
    ap.add_argument("--scaling-algos", default=DEFAULT_SCALING_ALGOS)
    ap.add_argument("--ref-det-limit", type=float, default=ref.DET_LIMIT,
                    help=f"ref: CP-SAT deterministic time per mission, one worker "
                         f"(default {ref.DET_LIMIT:g}; repeatable under any load)")
    ap.add_argument("--ref-time-limit", type=float, default=ref.SAFETY_TIME_LIMIT,
                    help=f"ref: wall-clock safety net in seconds (default {ref.SAFETY_TIME_LIMIT:g})")
    ap.add_argument("--peer-solution-limit", type=int, default=peer.SOLUTION_LIMIT,
                    help=f"peer: greedy descent stops after this many solutions (default {peer.SOLUTION_LIMIT})")
    ap.add_argument("--peer-time-limit", type=float, default=peer.SAFETY_TIME_LIMIT,
                    help=f"peer: wall-clock safety net in seconds (default {peer.SAFETY_TIME_LIMIT:g})")
    ap.add_argument("--cache", metavar="DIR",
                    help="reuse and store ih, ref and peer results in DIR (one JSON per mission "
                         "content, solver, settings and code version); C planners always run")
    ap.add_argument("--time-box", type=float, metavar="MIN",
                    help="scaling runs in rounds (one mission of each size); once the run has "
                         "taken MIN minutes no further round starts (the paper sets always run "
                         "in full, and at least one scaling round; the report says how many ran)")
    ap.add_argument("--log", metavar="FILE", help="append one progress line per mission to FILE")
    ap.add_argument("--results", action="store_true",
                    help="also write the headline as docs/results.md's section (docs/results/paper.md)")
    ap.add_argument("--keep-missions", metavar="DIR", help="also write the missions there")
    ap.set_defaults(func=run)


def run(args) -> int:
    algos = [a for a in args.algos.split(",") if a]
    salgos = [a for a in args.scaling_algos.split(",") if a]
    notes = []
    if any(a not in PY_ALGOS for a in algos + (salgos if args.scaling else [])):
        try:
            cbin.sva_bin()
        except cbin.CliMissing as e:
            print(f"sva-tools: error: {shown(e)}", file=sys.stderr)
            return 2
        # A C algorithm this build of the CLI does not know (e.g. flow before it is
        # merged) is skipped with a note instead of failing every mission.
        skipped = set()
        for a in dict.fromkeys(algos + (salgos if args.scaling else [])):
            why = None if a in PY_ALGOS else cbin.algorithm_available(a)
            if why is not None:
                skipped.add(a)
                notes.append(f"- {a}: skipped: {why}")
                print(f"sva-tools bench: {shown(a)} skipped: {shown(why)}", file=sys.stderr)
        algos = [a for a in algos if a not in skipped]
        salgos = [a for a in salgos if a not in skipped]
    from tqdm import tqdm

    os.makedirs(args.out, exist_ok=True)
    args.cache_store = cache.Cache(args.cache) if args.cache else None
    args.t_start = t_start = time.time()
    load_start = os.getloadavg()
    utc_start = cache.measurement(load_start)["utc"]
    size_sets: list[dict[str, Any]] = []
    ratio_sets: list[dict[str, Any]] = []
    scale_sets: list[dict[str, Any]] = []
    plan_sets = []
    if not args.no_paper:
        for n, u in SIZE_SETS:
            plan_sets.append(("size", f"{n}t/{u}u", n, u, "any"))
        for r in RATIO_SETS:
            plan_sets.append(("ratio", f"10t/5u {r}", 10, 5, r))
    total = len(plan_sets) * args.missions + (len(SCALING_SETS) * args.scaling_missions
                                              if args.scaling else 0)
    bar = tqdm(total=total, unit="mission", desc="bench", file=sys.stderr)

    def missions_of(n, u, ratio, count):
        return [gen.generate(n, u, ratio=ratio, seed=args.seed, index=i,
                             name=f"bench_{n}t{u}u_{ratio}_{i:03d}", **GEN) for i in range(count)]

    for kind, label, n, u, ratio in plan_sets:
        missions = missions_of(n, u, ratio, args.missions)
        args.bounds = False
        bar.set_description(f"bench {label}")
        s = run_set(label, missions, algos, args, bar)
        s["ratio_mean"] = statistics.mean(model.intersection_ratio(m) for m in missions)
        {"size": size_sets, "ratio": ratio_sets}[kind].append(s)
    scaling_done = 0
    if args.scaling:
        # Rounds of one mission per size, so a time box cuts every size alike.
        args.bounds = True
        scale_sets = [new_set(f"{n}t/{u}u") for n, u in SCALING_SETS]
        scale_missions = [missions_of(n, u, "any", args.scaling_missions) for n, u in SCALING_SETS]
        with tempfile.TemporaryDirectory(prefix="sva-bench-") as d:
            for i in range(args.scaling_missions):
                if i > 0 and args.time_box is not None and time.time() - t_start >= 60 * args.time_box:
                    break
                for s, ms in zip(scale_sets, scale_missions):
                    bar.set_description(f"bench {s['label']}")
                    run_mission(s, ms[i], salgos, args, d)
                    bar.update(1)
                    log_progress(args, s, args.scaling_missions)
                scaling_done = i + 1
        for s in scale_sets:
            s["ratio_mean"] = statistics.mean(model.intersection_ratio(m) for m in s["missions"]) \
                if s["missions"] else float("nan")
        if scaling_done == 0:  # --scaling-missions 0
            scale_sets = []
    bar.close()
    elapsed = time.time() - t_start
    load_end = os.getloadavg()
    argv = sys.argv[1:]
    cmd = "tools/sva-tools bench " + " ".join(argv[1:] if argv[:1] == ["bench"] else argv)
    cut = args.scaling and scaling_done < args.scaling_missions
    st = args.cache_store
    md = ["# sva benchmark: the paper's evaluation, reproduced", "",
          f"Command: `{cmd}`", "",
          f"Machine: {platform.machine()}, {os.cpu_count()} CPUs, Python {platform.python_version()}; "
          f"started {utc_start}, wall time {elapsed / 60:.1f} min, niceness {os.nice(0)}. Seed {args.seed}.", "",
          f"Load average (1, 5, 15 min): {', '.join(f'{x:.2f}' for x in load_start)} at the start, "
          f"{', '.join(f'{x:.2f}' for x in load_end)} at the end. The machine may be shared: "
          "solve times of the C planners (tens of microseconds) are noisy under load; "
          "ref and peer results do not depend on load (deterministic limits), their times do.", ""]
    if cut:
        md += [f"**Scaling reduced by the time box**: {scaling_done} of {args.scaling_missions} "
               f"missions per scaling set ran (`--time-box {args.time_box:g}`: no new round "
               f"after {args.time_box:g} min); the paper sets ran in full.", ""]
    if st is not None:
        md += [f"Cache `{args.cache}`: {st.hits} results reused, {st.misses} computed and stored. "
               "A result from the cache keeps the solve time measured when it was computed; "
               "rows marked (cached) come from it, and the table below says when and under "
               "what load their results were measured.", ""]
    md += [f"Missions (`sva-tools gen`): {GEN}, depot (0, 0), every UAV at the depot. Protocol, "
           "definitions and how to reproduce: docs/tools.md.", ""]
    if notes:
        md += notes + [""]
    if size_sets:
        md += ["## Headline", "",
               f"Per paper size, {args.missions} missions each: complete plans % / mean gap to the "
               "optimum % (over missions where the plan covers as many targets as the optimum; "
               "'k fewer': plans covering fewer) / median solve time.", "",
               headline(size_sets, algos), ""]
    if size_sets or ratio_sets:
        md += ["## Paper sizes and intersection categories", "",
               f"{args.missions} missions per set. Optimum: ref (CP-SAT, one worker, deterministic "
               f"limit {args.ref_det_limit:g}) when proven optimal, else bfa. Gap: mean of "
               "(cost - optimum cost) / optimum cost over "
               "missions where the plan covers as many targets as the optimum; 'fewer covered' "
               "counts the others. Certified gap: from the plan's own stats.lower_bound (flow, "
               "ref), mean of (cost - lower_bound) / lower_bound over plans with a bound > 0, "
               "and how many plans say optimal. Time: stats.solve_us (C: sva_plan() alone).", "",
               table(size_sets + ratio_sets, algos), ""]
        for s in size_sets + ratio_sets:
            if s["disagree"]:
                md += [f"- {s['label']}: bfa and ref disagree: " + "; ".join(s["disagree"][:5])]
        md += ["Mean measured intersection ratio per set: " +
               ", ".join(f"{s['label']}: {s['ratio_mean']:.2f}" for s in size_sets + ratio_sets), ""]
        if size_sets:
            figure(size_sets, algos, "targets / UAVs", os.path.join(args.out, "bench_size.png"),
                   "Against problem size (random missions)")
            md += ["![time, cost and completion against size](bench_size.png)", ""]
        if ratio_sets:
            figure(ratio_sets, algos, "intersection category (10 targets, 5 UAVs)",
                   os.path.join(args.out, "bench_ratio.png"), "Against window intersection ratio")
            md += ["![time, cost and completion against intersection ratio](bench_ratio.png)", ""]
    if scale_sets:
        md += ["## Scaling", "",
               f"{scaling_done} mission{'s' if scaling_done != 1 else ''} per set"
               + (f" (of {args.scaling_missions} asked; time box)" if cut else "")
               + ". No optimum: the gap is to the fuel-free "
               "min-cost-flow lower bound (`ref --bound`), over complete plans of missions where "
               "that bound says a complete plan may exist.", "",
               table(scale_sets, salgos, bound_mode=True), ""]
        figure(scale_sets, salgos, "targets / UAVs", os.path.join(args.out, "bench_scaling.png"),
               "Scaling")
        md += ["![scaling](bench_scaling.png)", ""]
    paper = size_sets + ratio_sets
    every = [(s, a) for s in paper for a in algos] + [(s, a) for s in scale_sets for a in salgos]
    viol = sum(summarise(s, a)["violations"] for s, a in every)
    safety = {a: sum(summarise(s, b)["safety_net"] for s, b in every if b == a) for a in ("ref", "peer")}
    md += ["## Where the figures come from", "",
           *provenance(paper + scale_sets, list(dict.fromkeys(algos + salgos))), "",
           f"ref: one CP-SAT worker, deterministic time limit {args.ref_det_limit:g} for both solves, "
           f"wall-clock safety net {args.ref_time_limit:g} s; peer: greedy descent capped at "
           f"{args.peer_solution_limit} solutions, safety net {args.peer_time_limit:g} s. Results "
           f"ended by a safety net (not repeatable): ref {safety['ref']}, peer {safety['peer']}.", "",
           f"Plans failing `sva-tools check`: {viol}.", ""]
    with open(os.path.join(args.out, "README.md"), "w", encoding="utf-8") as f:
        f.write("\n".join(md))
    print("\n".join(md))
    if args.results and size_sets:
        write_results(args, cmd, size_sets, algos, load_start, elapsed, st)
    return 1 if viol else 0


def write_results(args, cmd, size_sets, algos, load_start, elapsed, st) -> None:
    """docs/results.md's section of the bench (docs/results/paper.md): the headline table,
    with a link to the full report."""
    import importlib.util
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
    spec = importlib.util.spec_from_file_location("sva_results", os.path.join(root, "tools", "bench", "results.py"))
    if spec is None or spec.loader is None:
        raise RuntimeError(f"cannot load {root}/tools/bench/results.py")
    results = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(results)
    report = os.path.relpath(os.path.join(args.out, "README.md"), os.path.join(results.ROOT, "docs"))
    cached = (f" {st.hits} results came from the cache (`--cache`): those rows keep the solve times "
              "measured when they were computed, under that run's load; the report's last table says "
              "when and under what load." if st is not None and st.hits else "")
    body = "\n".join([
        f"{args.missions} random missions per size (need 2, fuel 150, windows 20 to 40 ticks, 20x20 grid, "
        f"seed {args.seed}). Each cell: complete plans % / mean gap to the optimum % over missions where the "
        "plan covers as many targets as the optimum ('k fewer': plans covering fewer) / median solve time "
        "(C planners: `sva_plan()` alone; ih, ref, peer: the Python solve). Optimum: ref (CP-SAT, one worker, "
        f"deterministic limit {args.ref_det_limit:g}) when proven, else bfa. ref's and peer's limits do not "
        f"depend on the load, their times do. Wall time {elapsed / 60:.1f} min.{cached}", "",
        headline(size_sets, algos), "",
        f"The full report, with the intersection categories, the scaling sets to 200 targets / 40 UAVs, "
        f"figures and where each figure comes from: [{report}]({report}); protocol: [tools.md](tools.md)."])
    results.write(results.ROOT, "paper", cmd, body,
                  load_start=" ".join(f"{x:.2f}" for x in load_start))
