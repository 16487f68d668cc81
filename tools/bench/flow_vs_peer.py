#!/usr/bin/env python3
"""flow against the OR-tools routing peer on the bench's missions, at several work budgets.

Usage (from the repository root, after scripts/setup.sh and scripts/build.sh):
    .venv/bin/python tools/bench/flow_vs_peer.py --cache build/bench-cache2 [--targets 25 --uavs 5]
        [--missions 100] [--results] [BUDGET ...]
BUDGET: flow's work budget (`sva plan --flow-work`), or `default`; default: default 1000000 500000 250000.
The missions are `sva-tools bench`'s (its generator settings and seed 2024). peer's
results come from the bench's result cache (--cache, tools/sva_tools/cache.py, the bench's
peer settings); a mission missing from it is solved now and stored there. peer's times are
those of the run that computed them (the cache records its load). Prints per budget: the
medians of flow's and peer's solve times and their ratio, the missions where flow covers
more or fewer targets than peer, and at equal coverage on how many flow costs no more.
--results also writes the set's part of docs/results.md (docs/results/flow_vs_peer.<set>.md,
tools/bench/results.py).
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

from sva_tools import cache, gen, io, peer  # noqa: E402
from sva_tools.bench import GEN  # noqa: E402

SVA = os.path.join(ROOT, "build", "bin", "sva")
PEER_SETTINGS = {"solution_limit": 100, "time_limit": 300.0, "hard_all_or_none": False}


def peer_result(store, m):
    """(covered, cost, solve_us) of peer's plan for m, from the cache or solved now."""
    hit = store.get(m, "peer", PEER_SETTINGS)
    if hit is None:
        plan = peer.solve_peer(m, PEER_SETTINGS["solution_limit"], PEER_SETTINGS["time_limit"])
        us = (plan.stats or {}).get("solve_us")
        store.put(m, "peer", PEER_SETTINGS, {"plan": plan, "us": us, "error": None}, cache.measurement())
        return plan.covered, plan.cost, us
    return hit["result"]["plan"].covered, hit["result"]["plan"].cost, hit["result"]["us"]


def flow_result(path, budget):
    cmd = [SVA, "plan", "--algo", "flow"] + ([] if budget == "default" else ["--flow-work", budget])
    doc = json.loads(subprocess.run(cmd + [path], capture_output=True, text=True, check=True).stdout)
    return doc["covered"], doc["cost"], doc["stats"]["solve_us"]


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cache", required=True, help="the bench's result cache (peer's results)")
    ap.add_argument("--targets", type=int, default=25)
    ap.add_argument("--uavs", type=int, default=5)
    ap.add_argument("--missions", type=int, default=100)
    ap.add_argument("--results", action="store_true", help="write the set's part of docs/results.md")
    ap.add_argument("budgets", nargs="*", default=["default", "1000000", "500000", "250000"])
    args = ap.parse_args(argv)
    store = cache.Cache(args.cache)
    n, u = args.targets, args.uavs
    missions = [gen.generate(n, u, ratio="any", seed=2024, index=i, name=f"bench_{n}t{u}u_any_{i:03d}", **GEN)
                for i in range(args.missions)]
    load_start = " ".join(f"{x:.2f}" for x in os.getloadavg())
    peers = [peer_result(store, m) for m in missions]
    rows = []
    print(f"{n}t/{u}u, {len(missions)} bench missions; peer from {args.cache} ({store.hits} cached, "
          f"{store.misses} solved now)")
    with tempfile.TemporaryDirectory(prefix="flow-vs-peer-") as d:
        paths = []
        for m in missions:
            p = os.path.join(d, f"{m.name}.json")
            io.write_json(m.to_json(), p)
            paths.append(p)
        for budget in args.budgets:
            flows = [flow_result(p, budget) for p in paths]
            more = sum(1 for f, q in zip(flows, peers) if f[0] > q[0])
            fewer = sum(1 for f, q in zip(flows, peers) if f[0] < q[0])
            equal = [(f, q) for f, q in zip(flows, peers) if f[0] == q[0]]
            no_dearer = sum(1 for f, q in equal if f[1] <= q[1])
            ft = statistics.median(f[2] for f in flows)
            pt = statistics.median(q[2] for q in peers)
            print(f"  flow-work {budget}: flow median {ft / 1000:.1f} ms, peer median {pt / 1000:.1f} ms, "
                  f"{pt / ft:.0f}x; flow covers more on {more}, fewer on {fewer}; at equal coverage "
                  f"({len(equal)}) it costs no more on {no_dearer}")
            rows.append(f"| {budget} | {ft / 1000:.1f} ms | {pt / 1000:.1f} ms | {pt / ft:,.0f}x | more on {more}, "
                        f"fewer on {fewer} | {no_dearer} of {len(equal)} |")
    if args.results:
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        import results  # tools/bench/results.py
        cmd = (f".venv/bin/python tools/bench/flow_vs_peer.py --results --cache {args.cache} --targets {n} "
               f"--uavs {u} --missions {args.missions} " + " ".join(args.budgets))
        body = "\n".join([
            f"`sva-tools bench`'s {len(missions)} missions at {n} targets x {u} UAVs (need 2, fuel 150, "
            f"windows 20 to 40, seed 2024). "
            + ("peer was solved in this run, under the same load as flow, and stored in the cache. "
               if not store.hits else
               f"peer's results and times come from the bench's cache ({store.hits} cached, "
               f"{store.misses} solved now): they were measured when the cache was filled, under that "
               "run's load (the cache records it), so compare the ratio with care. ")
            + "flow: one plan per process, `stats.solve_us`.", "",
            "| flow work budget | flow median | peer median | ratio | coverage vs peer | "
            "at equal coverage, flow costs no more on |",
            "|---|---|---|---|---|---|", *rows])
        results.write(results.ROOT, f"flow_vs_peer.{n:03d}x{u:02d}", cmd, body,
                      title=f"{n} targets x {u} UAVs", load_start=load_start)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
