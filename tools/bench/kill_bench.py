#!/usr/bin/env python3
"""Crash safety of sva_node under SIGKILL, measured (docs/lcm.md, "Crash safety").

Usage (root: the bench runs in a network namespace of its own; from the repository root,
after scripts/setup.sh and scripts/build.sh):
    .venv/bin/python tools/bench/kill_bench.py [--seeds N] [--kills K] [--generated G]
                                               [--algos sva,flow] [--out FIGURES.json]

Scenarios: the bundled fixtures/scenarios named by --scenarios, and G scenarios written by
`sva-tools gen --targets 15 --uavs 4 --need 1:2 --events 12 --kinds <the six>,position
--seed i` (i = 1..G). For each scenario and algorithm, one flight through a real sva_node
without kills (`sva-tools sim --via lcm`'s planner), then N flights with K kills each
(`--kill-node K --seed s`, s = 1..N): the node is SIGKILLed after the answer to a seeded
message and started again on its journal; nothing is sent again.

It prints, per algorithm and in total:
- kills survived: kills after which the node came back by itself with the plan id,
  revisions, clock and revision of the last answer (checked on its first status and its
  own resume line) and the flight went on to its end;
- identical flights: killed flights whose plans, replans (residual missions, plans and
  their ids, changed visits, live figures, every answer), tracks and target outcomes equal
  the uninterrupted flight's, times and revisions aside;
- the restart time, SIGKILL to the new node's first status (replay included), p50, p99
  and max;
- the round trip of an event (event_t published to its replan_t) without a journal (the
  uninterrupted flights) and with one (the killed flights: one fsync per event), p50 and
  p99.
Exit status 0 when every kill was survived and every flight is identical, 1 otherwise.
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))

from sva_tools import sim  # noqa: E402
from sva_tools.lcm import simnode  # noqa: E402

BUNDLED = "hand_events,hand_loss,gen_25t5u_events,replan_budget"
KINDS = "uav_lost,uav_back,fuel,target_added,target_cancelled,target_changed,position"


def event_round_trips(log: dict) -> list:
    return [m["round_trip_us"] for r in log["replans"] for m in r["node"]["messages"]
            if m["channel"] == "REPLAN"]


def percentile(values, p):
    if not values:
        return None
    s = sorted(values)
    k = max(1, -(-len(s) * p // 100))
    return s[int(k) - 1]


def generated(count: int, folder: str) -> list:
    paths = []
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "tools"))
    for i in range(1, count + 1):
        path = os.path.join(folder, f"gen_15t4u_e12_s{i}.json")
        subprocess.run([sys.executable, "-m", "sva_tools", "gen", "--targets", "15", "--uavs", "4",
                        "--need", "1:2", "--events", "12", "--kinds", KINDS, "--seed", str(i),
                        "-o", path], check=True, env=env)
        paths.append(path)
    return paths


def fly(path: str, algo: str, kills: int, seed: int):
    mission, events, penalty = sim.load_scenario(path)
    return sim.simulate_via_lcm(mission, events, penalty, algo, kill_node=kills, seed=seed)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="kill_bench.py", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seeds", type=int, default=5, help="killed flights per scenario and "
                    "algorithm (seeds 1..N, default 5)")
    ap.add_argument("--kills", type=int, default=5, help="kills per flight (default 5)")
    ap.add_argument("--generated", type=int, default=6, help="generated scenarios (default 6)")
    ap.add_argument("--scenarios", default=BUNDLED,
                    help="bundled scenarios (fixtures/scenarios), comma-separated "
                         f"(default {BUNDLED})")
    ap.add_argument("--algos", default="sva,flow", help="algorithms (default sva,flow)")
    ap.add_argument("--out", help="also write the figures and every failure as JSON")
    ap.add_argument("--results", action="store_true",
                    help="also write docs/results/live.kill.md (tools/bench/results.py)")
    args = ap.parse_args(argv)
    if not os.environ.get("SVA_LCM_NETNS"):
        if os.geteuid() != 0:
            print("kill_bench.py: error: needs root (the node runs in a network namespace made "
                  "for the bench)", file=sys.stderr)
            return 2
        return subprocess.run([str(simnode.netns_helper()), sys.executable,
                               os.path.abspath(__file__), *sys.argv[1:]]).returncode
    algos = [a for a in args.algos.split(",") if a]
    started = time.monotonic()
    load = " ".join(f"{x:.2f}" for x in os.getloadavg())
    rows = {}
    failures = []
    restarts = []
    round_trips = {"without": [], "with": []}
    with tempfile.TemporaryDirectory(prefix="sva-kill-bench-") as folder:
        paths = [os.path.join(ROOT, "fixtures", "scenarios", f"{s}.json")
                 for s in args.scenarios.split(",") if s]
        paths += generated(args.generated, folder)
        for algo in algos:
            row = rows.setdefault(algo, {"scenarios": 0, "flights": 0, "kills": 0, "survived": 0,
                                         "identical": 0})
            for path in paths:
                name = os.path.basename(path)
                try:
                    whole = fly(path, algo, 0, 0)
                    want = simnode.comparable_flight(whole)
                    round_trips["without"] += event_round_trips(whole)
                except (simnode.NodeError, sim.SimError) as e:
                    failures.append({"scenario": name, "algo": algo, "seed": None, "error": str(e)})
                    continue
                row["scenarios"] += 1
                for seed in range(1, args.seeds + 1):
                    row["flights"] += 1
                    row["kills"] += args.kills
                    try:
                        log = fly(path, algo, args.kills, seed)
                    except (simnode.NodeError, sim.SimError) as e:
                        failures.append({"scenario": name, "algo": algo, "seed": seed,
                                         "error": str(e)})
                        continue
                    row["survived"] += len(log["node_kills"])
                    round_trips["with"] += event_round_trips(log)
                    restarts += [k["resume_ms"] for k in log["node_kills"]]
                    if simnode.comparable_flight(log) == want:
                        row["identical"] += 1
                    else:
                        failures.append({"scenario": name, "algo": algo, "seed": seed,
                                         "error": "the flight differs from the uninterrupted one"})
                print(f"kill_bench: {algo} {name}: {row['survived']} kills survived so far",
                      file=sys.stderr, flush=True)
    total = {k: sum(r[k] for r in rows.values()) for k in ("flights", "kills", "survived",
                                                            "identical")}
    elapsed = time.monotonic() - started
    lines = [f"machine: {platform.machine()}, {os.cpu_count()} cores, load at start {load}; "
             f"{elapsed:.0f} s",
             "| algorithm | scenarios | killed flights | kills | kills survived "
             "| identical flights |",
             "|---|---|---|---|---|---|"]
    for algo, r in rows.items():
        lines.append(f"| {algo} | {r['scenarios']} | {r['flights']} | {r['kills']} | "
                     f"{r['survived']} | {r['identical']} |")
    lines.append(f"| total | | {total['flights']} | {total['kills']} | {total['survived']} | "
                 f"{total['identical']} |")
    lines.append(f"restart (SIGKILL to the new node's first status, replay included): p50 "
                 f"{percentile(restarts, 50)} ms, p99 {percentile(restarts, 99)} ms, max "
                 f"{max(restarts) if restarts else None} ms")
    for key in ("without", "with"):
        rts = round_trips[key]
        lines.append(f"event round trip {key} a journal: {len(rts)} events, p50 "
                     f"{percentile(rts, 50)} us, p99 {percentile(rts, 99)} us")
    lines.append(f"failures: {len(failures)}")
    lines += [f"- {f['algo']} {f['scenario']} seed {f['seed']}: {f['error']}"
              for f in failures[:20]]
    print("\n".join(lines))
    if args.out:
        with open(args.out, "w", encoding="utf-8") as f:
            json.dump({"rows": rows, "total": total, "restart_ms": restarts,
                       "round_trip_us": round_trips,
                       "failures": failures, "elapsed_s": round(elapsed, 1)}, f, indent=1)
    ok = not failures and total["survived"] == total["kills"] == (total["identical"] * args.kills)
    if args.results and ok:
        cmd = ".venv/bin/python tools/bench/kill_bench.py --results"
        if argv:
            cmd += " " + " ".join(a for a in argv if a != "--results")
        intro = ("sva_node killed (SIGKILL) at seeded moments of `sva-tools sim --via lcm` "
                 "flights and started again on its journal (`--state-dir`); a flight is "
                 "identical when its plans, replans, tracks and outcomes equal the "
                 "uninterrupted flight's, times and revisions aside (docs/lcm.md, \"Crash "
                 f"safety\"). {elapsed:.0f} s.")
        body = intro + "\n\n" + "\n".join(ln for ln in lines[1:]  # results.py writes the machine
                                           if not ln.startswith("failures:"))
        subprocess.run([sys.executable, os.path.join(ROOT, "tools", "bench", "results.py"), "write",
                        "live.kill", "--title", "Crash safety of the LCM node", "--command", cmd],
                       input=body + "\n", text=True, check=True)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
