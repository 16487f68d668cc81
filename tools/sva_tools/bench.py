"""The paper benchmark: missions, solves, summaries, tables and figures
(`sva-tools bench`)."""
from __future__ import annotations

import argparse
import os
import statistics
import tempfile
import time
from collections import defaultdict
from typing import TYPE_CHECKING, Any

from . import cache, cbin, check, ih, io, model, peer, ref

if TYPE_CHECKING:
    from tqdm import tqdm as Tqdm

PY_ALGOS = ("ih", "ref", "peer")
DEFAULT_ALGOS = "sva,ga,hga,bfa,flow,ih,ref,peer"
DEFAULT_SCALING_ALGOS = "sva,ga,hga,flow,ih,peer"
SIZE_SETS = [(3, 3), (5, 3), (7, 5), (10, 5), (25, 5)]
RATIO_SETS = ["low", "mid", "high"]
SCALING_SETS = [(50, 10), (100, 20), (200, 40)]
GEN: dict[str, Any] = dict(width=(20, 40), max_coord=20, need=(2, 2), fuel=150, hover=0)


def solver_settings(algo: str, opts: argparse.Namespace) -> dict[str, Any]:
    """The settings a host solver's result depends on (part of its cache key)."""
    if algo == "ref":
        return {"det_limit": opts.ref_det_limit, "workers": 1, "time_limit": opts.ref_time_limit}
    if algo == "peer":
        return {"solution_limit": opts.peer_solution_limit, "time_limit": opts.peer_time_limit,
                "hard_all_or_none": False}
    return {}


def _run_algo(algo: str, m: model.Mission, path: str, opts: argparse.Namespace) -> dict[str, Any]:
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
            if r.status != 0 or r.plan is None:
                msg = r.stderr.strip().splitlines()
                return {"plan": None, "us": None, "error": f"exit {r.status}: {msg[-1] if msg else ''}"}
            p = r.plan
    except io.InputError as e:
        return {"plan": None, "us": None, "error": f"bad plan: {e}"}
    us = (p.stats or {}).get("solve_us")
    return {"plan": p, "us": us, "error": None}


def _solve(algo: str, m: model.Mission, path: str, opts: argparse.Namespace) -> dict[str, Any]:
    """_run_algo through the cache (ih, ref, peer with --cache): the record also says
    whether it came from the cache ('cached') and when and under what load it was
    measured ('measured': utc, loadavg, cpus)."""
    store = getattr(opts, "cache_store", None) if algo in cache.CACHED_SOLVERS else None
    if store is not None:
        hit = store.get(m, algo, solver_settings(algo, opts))
        if hit is not None:
            r = dict(hit["result"])
            r.update(cached=True, measured=hit["measured"])
            return r
    meas = cache.measurement()
    r = _run_algo(algo, m, path, opts)
    if store is not None:
        store.put(m, algo, solver_settings(algo, opts), r, meas)
    r.update(cached=False, measured=meas)
    return r


def _pct(xs: list[float], q: float) -> float | None:
    if not xs:
        return None
    xs = sorted(xs)
    k = max(0, min(len(xs) - 1, int(round(q * (len(xs) - 1)))))
    return xs[k]


def new_set(label: str) -> dict[str, Any]:
    return {"label": label, "missions": [], "recs": defaultdict(list), "optima": [],
            "bounds": [], "disagree": []}


def run_mission(s: dict[str, Any], m: model.Mission, algos: list[str], opts: argparse.Namespace,
                workdir: str) -> None:
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


def run_set(label: str, missions: list[model.Mission], algos: list[str], opts: argparse.Namespace,
            bar: Tqdm[Any]) -> dict[str, Any]:
    """Runs every algorithm on every mission of one set; returns the raw records."""
    s = new_set(label)
    with tempfile.TemporaryDirectory(prefix="sva-bench-") as d:
        for m in missions:
            run_mission(s, m, algos, opts, d)
            bar.update(1)
            log_progress(opts, s, len(missions))
    return s


def log_progress(opts: argparse.Namespace, s: dict[str, Any], count: int) -> None:
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


def summarise(s: dict[str, Any], algo: str) -> dict[str, Any]:
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


def _fmt(v: float | None, spec: str = "{:.1f}") -> str:
    return "–" if v is None else spec.format(v)


def _fmt_us(v: float | None) -> str:
    if v is None:
        return "–"
    if v >= 1e6:
        return f"{v / 1e6:.2f} s"
    if v >= 1e3:
        return f"{v / 1e3:.1f} ms"
    return f"{v:.0f} µs"


def _cert(x: dict[str, Any]) -> str:
    """Certified gap column: 'gap % (plans with a bound > 0); optimal k/n' or '–'."""
    if not x.get("cert_n"):
        return "–"
    return f"{_fmt(x['cert_gap'])} ({x['cert_gap_n']}); optimal {x['cert_optimal']}/{x['cert_n']}"


def _name(a: str, x: dict[str, Any]) -> str:
    """Algorithm cell: marks rows whose results came from the cache (--cache)."""
    if not x.get("cached"):
        return a
    return f"{a} (cached)" if x["cached"] == x["n"] else f"{a} (cached {x['cached']}/{x['n']})"


def table(sets: list[dict[str, Any]], algos: list[str], bound_mode: bool = False) -> str:
    gap_h = "mean gap to bound % (n)" if bound_mode else "mean gap to optimum % (n)"
    lines = [f"| set | algorithm | planned | complete % | mean covered | mean cost | {gap_h} "
             "| fewer covered than optimum | certified gap % (n); proven optimal | median time | p95 time "
             "| check failures |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for s in sets:
        for a in algos:
            x = summarise(s, a)
            if x["planned"] == 0:
                errors = "; ".join(x["errors"])[:80]
                lines.append(f"| {s['label']} | {_name(a, x)} | 0/{x['n']} ({errors}) | | | | | | | | | |")
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


def figure(sets: list[dict[str, Any]], algos: list[str], xlabel: str, path: str, title: str) -> None:
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


def headline(sets: list[dict[str, Any]], algos: list[str]) -> str:
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


def _range(xs: list[float], spec: str = "{:.2f}") -> str:
    if not xs:
        return "–"
    lo, hi = min(xs), max(xs)
    return spec.format(lo) if lo == hi else f"{spec.format(lo)}–{spec.format(hi)}"


def provenance(sets: list[dict[str, Any]], algos: list[str]) -> list[str]:
    """Per algorithm: results measured in this run and results from the cache, with
    when (UTC) and under what 1-minute load average they were measured."""
    lines = ["| algorithm | measured in this run: results (1-min load) "
             "| from the cache: results, measured (UTC), 1-min load |",
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
