#!/usr/bin/env python3
"""flow against the exact optimum (sva-tools ref) on generated missions.

Usage (from the repository root, after scripts/setup.sh and scripts/build.sh):
    .venv/bin/python tools/bench/flow_vs_ref.py [--results] [--scheduler=tcp://HOST:PORT] TARGETS UAVS COUNT
                                                [sva-tools gen options]
    e.g. .venv/bin/python tools/bench/flow_vs_ref.py 25 5 30 --width 10:20 --need 1 --hover 2 --fuel 120
--results also writes the set's part of docs/results.md (docs/results/flow_vs_ref.<set>.md,
tools/bench/results.py). Environment: FLOW_WORK=N passes --flow-work N to the planner; FLOW_REPEAT=N passes
--repeat N (flow's time is then its fastest of N runs in one process, memory warm); REF_DET (default 10) is
ref's deterministic limit (load-independent; docs/tools.md). It is a campaign
(`sva-tools campaign`, docs/campaigns.md): flow and ref run as tasks on a Dask
LocalCluster of two workers, or on the cluster of --scheduler; results are stored in
build/flow_vs_ref/<set>/campaign/ (Parquet, keyed by mission content and tool version),
so a re-run solves only what is not stored (delete the folder to recompute).
Prints: missions where flow's coverage equals, is below or above ref's; the mean and
largest cost gap at equal coverage; how many flow plans are proven optimal; flow's
median and p95 solve time; the gap to the proven optima alone; flow's own certified
gap; on how many proven optima fuel matters (flow's optimum of the same mission with
fuel no route can use up differs from ref's: the protocol's fuel is calibrated by it,
about a third at fuel 105); and any bound above a proven optimum (must be none).
"""
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SVA = os.path.join(ROOT, "build", "bin", "sva")


def fuel_free(doc):
    """(covered, cost) of flow's plan for the mission doc with fuel no route uses up
    (every leg at most the grid's width plus height), or None if flow does not prove it."""
    doc = json.loads(json.dumps(doc))
    xs = [doc["depot"]["x"]] + [p["x"] for p in doc["uavs"] + doc["targets"]]
    ys = [doc["depot"]["y"]] + [p["y"] for p in doc["uavs"] + doc["targets"]]
    leg = (max(xs) - min(xs)) + (max(ys) - min(ys))
    n = len(doc["targets"])
    for u in doc["uavs"]:
        u["fuel"] = min((n + 1) * leg + n * doc["hover_fuel"] + 1, 10**9)  # SVA_MAX_FUEL
    with tempfile.NamedTemporaryFile("w", suffix=".json") as f:
        json.dump(doc, f)
        f.flush()
        out = json.loads(subprocess.run([SVA, "plan", "--algo", "flow", f.name], capture_output=True, text=True,
                                        check=True).stdout)
    return (out["covered"], out["cost"]) if out["stats"]["optimal"] else None


def campaign_spec(tag, targets, uavs, count, gen_args):
    """The campaign of this set: the first COUNT missions of `sva-tools gen --seed 7 GEN_ARGS`,
    flow (with FLOW_WORK, FLOW_REPEAT) and ref (REF_DET, one worker) on each."""
    sys.path.insert(0, os.path.join(ROOT, "tools"))
    from sva_tools.commands import gen
    from sva_tools.commands.common import Parser
    sub = Parser(prog="flow_vs_ref.py").add_subparsers()
    gen.add_parser(sub)
    a = sub.choices["gen"].parse_args(gen_args)
    s = {"targets": targets, "uavs": uavs, "width": list(a.width), "need": list(a.need), "ratio": a.ratio,
         "max_coord": a.max_coord, "fuel": a.fuel, "hover": a.hover, "ticks_per_cell": a.ticks_per_cell,
         "overlap_percent": a.overlap_percent}
    spec = {"name": "flow_vs_ref_" + re.sub(r"[^A-Za-z0-9_.-]+", "_", tag)[:50], "kind": "plan", "sets": [s],
            "seeds": {"first": 7, "count": 1}, "count": count, "algorithms": ["flow"],
            "ref": {"det_limit": float(os.environ.get("REF_DET", "10")), "max_targets": 1000}}
    if os.environ.get("FLOW_WORK"):
        spec["flow_work"] = int(os.environ["FLOW_WORK"])
    if os.environ.get("FLOW_REPEAT"):
        spec["repeat"] = int(os.environ["FLOW_REPEAT"])
    return spec


def main(argv):
    write_results = "--results" in argv
    load_start = " ".join(f"{x:.2f}" for x in os.getloadavg())
    scheduler = next((a.split("=", 1)[1] for a in argv if a.startswith("--scheduler=")), None)
    argv = [a for a in argv if a != "--results" and not a.startswith("--scheduler=")]
    if len(argv) < 3:
        sys.exit(__doc__)
    targets, uavs, count, gen_args = int(argv[0]), int(argv[1]), int(argv[2]), argv[3:]
    tag = "_".join([str(targets), str(uavs)] + [a.strip("-").replace(":", "-") for a in gen_args])
    folder = os.path.join(ROOT, "build", "flow_vs_ref", tag)
    os.makedirs(folder, exist_ok=True)
    sys.path.insert(0, os.path.join(ROOT, "tools"))
    import sva_tools.campaign as campaign  # noqa: E402
    from sva_tools.campaign import spec as cspec  # noqa: E402
    spec = cspec.validate(campaign_spec(tag, targets, uavs, count, gen_args))
    stats = campaign.run(spec, os.path.join(folder, "campaign"), scheduler, None if scheduler else 2)
    if stats["failed"]:
        sys.exit("flow_vs_ref: tasks failed: " + "; ".join(stats["failed"][:5]))
    rows = stats["rows"].values()
    refs = {r["mission_hash"]: r for r in rows if r["tool"] == "ref"}
    for r in rows:
        if r["error"]:
            sys.exit(f"flow_vs_ref: {r['tool']} on {r['mission_name']}: {r['error']}")
    # The first COUNT missions of seed 7, in gen's order (`sva-tools gen --seed 7` names them ..._s7_<index>).
    results = [(r["mission_name"], json.loads(r["result"]), json.loads(refs[r["mission_hash"]]["result"]))
               for r in sorted(rows, key=lambda r: r["index"]) if r["tool"] == "flow"]
    missions = {r["mission_name"]: json.loads(r["mission"]) for r in rows if r["tool"] == "flow"}
    equal = [r for r in results if r[1]["covered"] == r[2]["covered"]]
    below = [(n, fl["covered"], ref["covered"]) for n, fl, ref in results if fl["covered"] < ref["covered"]]
    above = [(n, fl["covered"], ref["covered"]) for n, fl, ref in results if fl["covered"] > ref["covered"]]
    gaps = [100.0 * (fl["cost"] - ref["cost"]) / ref["cost"] for _, fl, ref in equal if ref["cost"] > 0]
    exact = [(fl, ref) for _, fl, ref in results if ref["stats"].get("optimal")]
    free = [fuel_free(missions[n]) for n, _, ref in results if ref["stats"].get("optimal")]
    fuel_matters = sum(1 for (_, ref), f in zip(exact, free) if f is not None and f != (ref["covered"], ref["cost"]))
    exact_gaps = [100.0 * (fl["cost"] - ref["cost"]) / ref["cost"] for fl, ref in exact
                  if fl["covered"] == ref["covered"] and ref["cost"] > 0]
    certified = [100.0 * (fl["cost"] - fl["stats"]["lower_bound"]) / fl["stats"]["lower_bound"]
                 for _, fl, _ in results if fl["stats"]["lower_bound"] > 0]
    proven = sum(1 for _, fl, _ in results if fl["stats"]["optimal"])
    times = sorted(fl["stats"]["solve_us"] for _, fl, _ in results)
    bad = [n for n, fl, ref in results if ref["stats"].get("optimal") and fl["covered"] == ref["covered"]
           and fl["stats"]["lower_bound"] > ref["cost"]]
    print(f"{targets}x{uavs} {' '.join(gen_args)}: {len(results)} missions, flow-work "
          f"{os.environ.get('FLOW_WORK', 'default')}, repeat {os.environ.get('FLOW_REPEAT', '1')}")
    print(f"  coverage equal to ref: {len(equal)}; below: {below}; above (ref not proven): {above}")
    print(f"  cost gap at equal coverage: mean {statistics.mean(gaps) if gaps else 0.0:.3f} %, "
          f"largest {max(gaps) if gaps else 0.0:.2f} %")
    print(f"  against the {len(exact)} proven optima: coverage equal on "
          f"{sum(1 for fl, ref in exact if fl['covered'] == ref['covered'])}, cost gap mean "
          f"{statistics.mean(exact_gaps) if exact_gaps else 0.0:.3f} %, largest "
          f"{max(exact_gaps) if exact_gaps else 0.0:.2f} %, zero on {sum(1 for g in exact_gaps if g == 0)}")
    print(f"  flow's own certificate (cost - lower_bound) / lower_bound: mean "
          f"{statistics.mean(certified) if certified else 0.0:.2f} %, largest "
          f"{max(certified) if certified else 0.0:.2f} % ({len(certified)} plans with a bound)")
    print(f"  flow proven optimal: {proven}/{len(results)}; solve median {times[len(times) // 2]} us, "
          f"p95 {times[min(len(times) - 1, int(len(times) * 0.95))]} us")
    print(f"  fuel matters (the optimum without it differs) on {fuel_matters} of the {len(exact)} proven optima"
          f" ({sum(1 for f in free if f is None)} fuel-free plans unproven)")
    print(f"  bounds above a proven optimum: {bad}")
    if write_results:
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        import results as page  # tools/bench/results.py
        env = " ".join(f"{k}={os.environ[k]}" for k in ("FLOW_WORK", "FLOW_REPEAT", "REF_DET") if os.environ.get(k))
        cmd = " ".join(([env] if env else []) + [".venv/bin/python tools/bench/flow_vs_ref.py --results",
                                                 str(targets), str(uavs), str(count)] + gen_args)
        n_exact = len(exact)
        cov = (f"equal on {len(equal)}/{len(results)}" + (f", more on {len(above)} (ref unproven)" if above else "")
               + (f", fewer on {len(below)}" if below else ", never fewer"))
        gap = (f"mean {statistics.mean(exact_gaps):.3f} %, largest {max(exact_gaps):.2f} % ({n_exact} proven, "
               f"{sum(1 for g in exact_gaps if g == 0)} equal)" if exact_gaps else f"– ({n_exact} proven)")
        cert = (f"mean {statistics.mean(certified):.2f} %, largest {max(certified):.2f} %" if certified else "–")
        med = times[len(times) // 2] / 1000
        p95 = times[min(len(times) - 1, int(len(times) * 0.95))] / 1000
        repeat = os.environ.get("FLOW_REPEAT")
        timing = f"fastest of {repeat} in one process (warm)" if repeat else "one plan per process"
        body = "\n".join([
            f"{len(results)} missions `sva-tools gen --targets {targets} --uavs {uavs} --count {count} --seed 7 "
            f"{' '.join(gen_args)}`; flow work budget {os.environ.get('FLOW_WORK', 'default')}; "
            f"ref with deterministic limit {os.environ.get('REF_DET', '10')}, one worker. "
            f"Time: `stats.solve_us`, {timing}; " + ("the script plans two missions at once (a campaign, "
            "docs/campaigns.md, on two local workers)." if not scheduler else "a campaign on a Dask cluster "
            "(docs/campaigns.md)."), "",
            "| fuel matters on | coverage vs ref | cost gap at equal coverage | cost gap to the proven optima "
            "| certified gap | proven optimal | median | p95 |",
            "|---|---|---|---|---|---|---|---|",
            f"| {fuel_matters} of {n_exact} | {cov} | mean {statistics.mean(gaps) if gaps else 0.0:.3f} %, "
            f"largest {max(gaps) if gaps else 0.0:.2f} % | {gap} | {cert} | {proven}/{len(results)} | "
            f"{med:.2f} ms | {p95:.2f} ms |", "",
            f"Bounds above a proven optimum: {len(bad)} (must be 0)."])
        title = (f"{count} missions, {targets} targets x {uavs} UAVs, " + (" ".join(gen_args) or "gen defaults")
                 + (f", warm (fastest of {repeat})" if repeat else "")
                 + (f", work budget {os.environ['FLOW_WORK']}" if os.environ.get("FLOW_WORK") else ""))
        part = re.sub(r"[^A-Za-z0-9_-]+", "_", f"{tag}_n{count}" + (f"_repeat{repeat}" if repeat else "")
                      + (f"_work{os.environ['FLOW_WORK']}" if os.environ.get("FLOW_WORK") else ""))
        page.write(page.ROOT, f"flow_vs_ref.{part}", cmd, body, title=title, load_start=load_start)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
