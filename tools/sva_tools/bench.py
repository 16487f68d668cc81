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
from collections import defaultdict
from typing import Dict, List, Optional

from . import cache, cbin, check, gen, ih, io, peer, ref
from . import model as M
from .text import shown

PY_ALGOS = ("ih", "ref", "peer")
DEFAULT_ALGOS = "sva,ga,hga,bfa,flow,ih,ref,peer"
DEFAULT_SCALING_ALGOS = "sva,ga,hga,flow,ih,peer"
SIZE_SETS = [(3, 3), (5, 3), (7, 5), (10, 5), (25, 5)]
RATIO_SETS = ["low", "mid", "high"]
SCALING_SETS = [(50, 10), (100, 20), (200, 40)]
GEN = dict(width=(20, 40), max_coord=20, need=(2, 2), fuel=150, hover=0)


def solver_settings(algo: str, opts) -> dict:
    """The settings a host solver's result depends on (part of its cache key)."""
    if algo == "ref":
        return {"det_limit": opts.ref_det_limit, "workers": 1, "time_limit": opts.ref_time_limit}
    if algo == "peer":
        return {"solution_limit": opts.peer_solution_limit, "time_limit": opts.peer_time_limit,
                "hard_all_or_none": False}
    return {}


def _run_algo(algo: str, m: M.Mission, path: str, opts) -> dict:
    """One planner on one mission: {'plan': Plan|None, 'us': int|None, 'error': str|None}."""
    try:
        if algo == "ih":
            p = ih.plan_ih(m)
        elif algo == "ref":
            p = ref.solve_ref(m, opts.ref_time_limit, 1, opts.ref_det_limit)
        elif algo == "peer":
            p = peer.solve_peer(m, opts.peer_solution_limit, opts.peer_time_limit)
        else:
            r = cbin.plan(path, algo)
            if r.status != 0:
                msg = r.stderr.strip().splitlines()
                return {"plan": None, "us": None, "error": f"exit {r.status}: {msg[-1] if msg else ''}"}
            p = r.plan
    except io.InputError as e:
        return {"plan": None, "us": None, "error": f"bad plan: {e}"}
    us = (p.stats or {}).get("solve_us")
    return {"plan": p, "us": us, "error": None}


def _solve(algo: str, m: M.Mission, path: str, opts) -> dict:
    """_run_algo through the cache (ih, ref, peer with --cache): the record also says
    whether it came from the cache ('cached') and when and under what load it was
    measured ('measured': utc, loadavg, cpus)."""
    store = getattr(opts, "cache_store", None)
    cached = store is not None and algo in cache.CACHED_SOLVERS
    if cached:
        hit = store.get(m, algo, solver_settings(algo, opts))
        if hit is not None:
            r = dict(hit["result"])
            r.update(cached=True, measured=hit["measured"])
            return r
    meas = cache.measurement()
    r = _run_algo(algo, m, path, opts)
    if cached:
        store.put(m, algo, solver_settings(algo, opts), r, meas)
    r.update(cached=False, measured=meas)
    return r


def _pct(xs: List[float], q: float) -> Optional[float]:
    if not xs:
        return None
    xs = sorted(xs)
    k = max(0, min(len(xs) - 1, int(round(q * (len(xs) - 1)))))
    return xs[k]


def new_set(label: str) -> dict:
    return {"label": label, "missions": [], "recs": defaultdict(list), "optima": [],
            "bounds": [], "disagree": []}


def run_mission(s: dict, m: M.Mission, algos: List[str], opts, workdir: str) -> None:
    """Runs every algorithm on one mission and appends the records to set s."""
    path = os.path.join(workdir, f"{m.name}.json")
    io.write_json(m.to_json(), path)
    if opts.keep_missions:
        os.makedirs(opts.keep_missions, exist_ok=True)
        io.write_json(m.to_json(), os.path.join(opts.keep_missions, f"{m.name}.json"))
    res = {}
    for a in algos:
        r = _solve(a, m, path, opts)
        if r["plan"] is not None:
            r["violations"] = check.check_plan(m, r["plan"])
        res[a] = r
        s["recs"][a].append(r)
    opt = None
    if "ref" in res and res["ref"]["plan"] is not None and res["ref"]["plan"].stats.get("optimal"):
        opt = res["ref"]["plan"]
    if "bfa" in res and res["bfa"]["plan"] is not None:
        b = res["bfa"]["plan"]
        if opt is not None and (b.covered, b.cost) != (opt.covered, opt.cost):
            s["disagree"].append(f"{m.name}: bfa ({b.covered}, {b.cost}) != ref ({opt.covered}, {opt.cost})")
        opt = opt or b
    s["missions"].append(m)
    s["optima"].append(opt)
    s["bounds"].append(ref.fuel_free_bound(m) if opts.bounds else None)


def run_set(label: str, missions: List[M.Mission], algos: List[str], opts, bar) -> dict:
    """Runs every algorithm on every mission of one set; returns the raw records."""
    s = new_set(label)
    with tempfile.TemporaryDirectory(prefix="sva-bench-") as d:
        for m in missions:
            run_mission(s, m, algos, opts, d)
            bar.update(1)
            _log(opts, s, len(missions))
    return s


def _log(opts, s: dict, count: int) -> None:
    """One progress line per mission in --log FILE (the tqdm bar goes to stderr)."""
    if not getattr(opts, "log", None):
        return
    la = os.getloadavg()
    st = getattr(opts, "cache_store", None)
    line = (f"{time.strftime('%H:%M:%S')} +{(time.time() - opts.t_start) / 60:5.1f} min "
            f"{s['label']:>12} {len(s['missions'])}/{count} load {la[0]:.2f}"
            + (f" cache hits {st.hits} misses {st.misses}" if st is not None else ""))
    with open(opts.log, "a", encoding="utf-8") as f:
        f.write(line + "\n")


def summarise(s: dict, algo: str) -> dict:
    rs = s["recs"][algo]
    n = len(rs)
    ok = [r for r in rs if r["plan"] is not None]
    out = {"n": n, "planned": len(ok),
           "errors": sorted({r["error"] for r in rs if r["error"]}),
           "violations": sum(1 for r in ok if r["violations"]),
           "cached": sum(1 for r in rs if r.get("cached")),
           # ref and peer results ended by their wall-clock safety net: not repeatable
           "safety_net": sum(1 for r in ok if (r["plan"].stats or {}).get("stopped_by") == "time_limit")}
    if not ok:
        return out
    out["completion"] = 100.0 * sum(1 for r in ok if r["plan"].status == "complete") / len(ok)
    out["covered"] = statistics.mean(r["plan"].covered for r in ok)
    out["cost"] = statistics.mean(r["plan"].cost for r in ok)
    gaps, fewer, known = [], 0, 0
    bgaps = []
    for r, opt, bnd in zip(rs, s["optima"], s["bounds"]):
        p = r["plan"]
        if p is None:
            continue
        if opt is not None:
            known += 1
            if p.covered < opt.covered:
                fewer += 1
            elif p.covered == opt.covered and opt.cost > 0:
                gaps.append(100.0 * (p.cost - opt.cost) / opt.cost)
        if bnd and bnd["complete_possible"] and p.status == "complete" and bnd["lower_bound"]:
            bgaps.append(100.0 * (p.cost - bnd["lower_bound"]) / bnd["lower_bound"])
    out["opt_known"] = known
    out["fewer"] = fewer
    out["gap"] = statistics.mean(gaps) if gaps else None
    out["gap_n"] = len(gaps)
    out["bound_gap"] = statistics.mean(bgaps) if bgaps else None
    out["bound_gap_n"] = len(bgaps)
    us = [r["us"] for r in ok if r["us"] is not None]
    out["median_us"] = statistics.median(us) if us else None
    out["p95_us"] = _pct(us, 0.95)
    # The plan's own certificate (flow, ref): no plan covering as many targets costs
    # less than stats.lower_bound, so (cost - bound) / bound bounds the gap to the optimum.
    cert = [r["plan"] for r in ok if "lower_bound" in (r["plan"].stats or {})]
    out["cert_n"] = len(cert)
    cgaps = [100.0 * (p.cost - p.stats["lower_bound"]) / p.stats["lower_bound"]
             for p in cert if p.stats["lower_bound"] > 0]
    out["cert_gap"] = statistics.mean(cgaps) if cgaps else None
    out["cert_gap_n"] = len(cgaps)
    out["cert_optimal"] = sum(1 for p in cert if p.stats.get("optimal") is True)
    return out


def _fmt(v, spec="{:.1f}"):
    return "–" if v is None else spec.format(v)


def _fmt_us(v):
    if v is None:
        return "–"
    if v >= 1e6:
        return f"{v / 1e6:.2f} s"
    if v >= 1e3:
        return f"{v / 1e3:.1f} ms"
    return f"{v:.0f} µs"


def _cert(x: dict) -> str:
    """Certified gap column: 'gap % (plans with a bound > 0); optimal k/n' or '–'."""
    if not x.get("cert_n"):
        return "–"
    return f"{_fmt(x['cert_gap'])} ({x['cert_gap_n']}); optimal {x['cert_optimal']}/{x['cert_n']}"


def _name(a: str, x: dict) -> str:
    """Algorithm cell: marks rows whose results came from the cache (--cache)."""
    if not x.get("cached"):
        return a
    return f"{a} (cached)" if x["cached"] == x["n"] else f"{a} (cached {x['cached']}/{x['n']})"


def table(sets: List[dict], algos: List[str], bound_mode: bool = False) -> str:
    gap_h = "mean gap to bound % (n)" if bound_mode else "mean gap to optimum % (n)"
    lines = [f"| set | algorithm | planned | complete % | mean covered | mean cost | {gap_h} | fewer covered than optimum | certified gap % (n); proven optimal | median time | p95 time | check failures |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for s in sets:
        for a in algos:
            x = summarise(s, a)
            if x["planned"] == 0:
                lines.append(f"| {s['label']} | {_name(a, x)} | 0/{x['n']} ({'; '.join(x['errors'])[:80]}) | | | | | | | | | |")
                continue
            if bound_mode:
                gap = f"{_fmt(x['bound_gap'])} ({x['bound_gap_n']})"
                fewer = "–"
            else:
                gap = f"{_fmt(x['gap'])} ({x['gap_n']})"
                fewer = f"{x['fewer']}/{x['opt_known']}"
            lines.append(f"| {s['label']} | {_name(a, x)} | {x['planned']}/{x['n']} | {_fmt(x['completion'])} | "
                         f"{_fmt(x['covered'], '{:.2f}')} | {_fmt(x['cost'])} | {gap} | {fewer} | "
                         f"{_cert(x)} | {_fmt_us(x['median_us'])} | {_fmt_us(x['p95_us'])} | {x['violations']} |")
    return "\n".join(lines)


def figure(sets: List[dict], algos: List[str], xlabel: str, path: str, title: str) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.2))
    xs = list(range(len(sets)))
    labels = [s["label"] for s in sets]
    for a in algos:
        summ = [summarise(s, a) for s in sets]
        t = [(x.get("median_us") or float("nan")) / 1000.0 if x["planned"] else float("nan") for x in summ]
        c = [x.get("cost", float("nan")) if x["planned"] else float("nan") for x in summ]
        r = [x.get("completion", float("nan")) if x["planned"] else float("nan") for x in summ]
        axes[0].plot(xs, t, marker="o", label=a)
        axes[1].plot(xs, c, marker="o", label=a)
        axes[2].plot(xs, r, marker="o", label=a)
    axes[0].set_yscale("log")
    axes[0].set_ylabel("median solve time (ms, log)")
    axes[1].set_ylabel("mean cost (fuel: cells flown)")
    axes[2].set_ylabel("complete plans (%)")
    for ax in axes:
        ax.set_xticks(xs)
        ax.set_xticklabels(labels, rotation=20)
        ax.set_xlabel(xlabel)
        ax.grid(True, alpha=0.3)
    axes[2].legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def headline(sets: List[dict], algos: List[str]) -> str:
    """Compact table: one row per set, one column per algorithm, each cell
    'complete % / mean gap to the optimum % / median time' (README headline)."""
    lines = ["| set | " + " | ".join(algos) + " |", "|---" * (len(algos) + 1) + "|"]
    for s in sets:
        cells = []
        for a in algos:
            x = summarise(s, a)
            if x["planned"] == 0:
                cells.append("–")
                continue
            c = f"{x['completion']:.0f} / {_fmt(x['gap'])} / {_fmt_us(x['median_us'])}"
            if x.get("fewer"):
                c += f" ({x['fewer']} fewer)"
            cells.append(c)
        lines.append(f"| {s['label']} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def _range(xs: List[float], spec: str = "{:.2f}") -> str:
    if not xs:
        return "–"
    lo, hi = min(xs), max(xs)
    return spec.format(lo) if lo == hi else f"{spec.format(lo)}–{spec.format(hi)}"


def provenance(sets: List[dict], algos: List[str]) -> List[str]:
    """Per algorithm: results measured in this run and results from the cache, with
    when (UTC) and under what 1-minute load average they were measured."""
    lines = ["| algorithm | measured in this run: results (1-min load) | from the cache: results, measured (UTC), 1-min load |",
             "|---|---|---|"]
    for a in algos:
        rs = [r for s in sets for r in s["recs"].get(a, [])]
        if not rs:
            continue
        now = [r for r in rs if not r.get("cached")]
        old = [r for r in rs if r.get("cached")]
        c1 = f"{len(now)} ({_range([r['measured']['loadavg'][0] for r in now])})" if now else "0"
        if old:
            ts = sorted(r["measured"].get("utc", "?") for r in old)
            c2 = (f"{len(old)}, {ts[0]} to {ts[-1]}, "
                  f"{_range([r['measured']['loadavg'][0] for r in old if r['measured'].get('loadavg')])}")
        else:
            c2 = "0"
        lines.append(f"| {a} | {c1} | {c2} |")
    return lines


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
    size_sets, ratio_sets, scale_sets = [], [], []
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
        s["ratio_mean"] = statistics.mean(M.intersection_ratio(m) for m in missions)
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
                    _log(args, s, args.scaling_missions)
                scaling_done = i + 1
        for s in scale_sets:
            s["ratio_mean"] = statistics.mean(M.intersection_ratio(m) for m in s["missions"]) \
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
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    spec = importlib.util.spec_from_file_location("sva_results", os.path.join(root, "tools", "bench", "results.py"))
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
