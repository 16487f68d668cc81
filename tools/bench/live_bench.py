#!/usr/bin/env python3
"""Live missions flown with each algorithm: coverage, replans against the exact optimum,
changed visits and replan latency (docs/live.md, docs/SPEC.md section 12).

Usage (from the repository root, after scripts/setup.sh and scripts/build.sh):
    .venv/bin/python tools/bench/live_bench.py [--results] [--set TxU:N ...] [options]
    e.g. nice .venv/bin/python tools/bench/live_bench.py --results --set 25x5:20 --set 100x20:5

For each set (T targets, U UAVs, N scenarios) it writes N scenarios with
`sva-tools gen --targets T --uavs U --events E --count N --seed S` (plus --gen options),
flies each with `sva-tools sim` in this process (the simulator calls `sva replan`) for
each algorithm (--algos, default sva,ga,hga,flow) and each change_penalty (--penalties,
default 0,1000), and runs `sva-tools ref --det-limit D --workers 1` on every replan's
residual mission that has a target. It prints, per set, algorithm and penalty:
- flight coverage: targets covered / targets coverable after the events (the sums of the
  flight logs' summaries);
- replans against ref: the share of residual missions where the replan covers as many
  targets as ref, the replans' covered targets / ref's, and the cost gap at equal coverage;
- changed visits per replan (the logs' changes.count; the start replan has none);
- replan latency p50 / p99: stats.solve_us of each replan, timed by `sva replan` around
  sva_live_replan() in its own process (nearest-rank percentiles).
Goals: flow covers as many targets as ref on at least 99 % of the residual missions;
flow at 25 x 5 replans in p50 < 1 ms and p99 < 10 ms.

--node measures the node instead (root: the bench re-runs itself in a network namespace
made with tools/netns/netns_run.sh): every scenario is flown in process (a campaign task,
as above) and again with `sva-tools sim --via lcm`'s planner, a real sva_node per flight
over LCM multicast, in the bench's process (cached under --work/<set>/logs/); ref is not
run. Its table gives per algorithm and penalty: flights whose coverage equals the in-process flight's, the replan round trip (event_t published to
replan_t received, monotonic clock, nearest-rank p50 / p99 over every event and clock
message) and the node's solve time (plan_t.solve_us of those replans). Goal: a replan
round trip through the node at 25 x 5 in p99 < 20 ms. --node --results writes
docs/results/live.node.md (a part of the same section).

It is a campaign (`sva-tools campaign`, docs/campaigns.md): the flights and the ref
solves run as tasks on a Dask LocalCluster of --jobs workers, or on the cluster of
--scheduler. Results are stored under --work (default build/live_bench/) in campaign/
(Parquet, keyed by scenario or residual mission content and tool version), so a re-run
only flies and solves what is not stored (delete the folder to recompute); the flight
logs are also written to --work/<set>/logs/. --results writes docs/results/live.md
(tools/bench/results.py).
"""
import argparse
import hashlib
import json
import os
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
# The host tools, here and in the Dask workers this process starts.
os.environ["PYTHONPATH"] = os.path.join(ROOT, "tools") + os.pathsep + os.environ.get("PYTHONPATH", "")
sys.path.insert(0, os.path.join(ROOT, "tools"))

import sva_tools.campaign as campaign  # noqa: E402
from sva_tools import sim  # noqa: E402
from sva_tools.campaign import spec as cspec, tasks  # noqa: E402

GOAL_EQUAL = 99.0       # % of residual missions where flow covers as many targets as ref
GOAL_P50_MS = 1.0       # flow at 25 x 5
GOAL_P99_MS = 10.0
GOAL_NODE_P99_MS = 20.0  # replan round trip through sva_node at 25 x 5


def parse_set(text):
    """TxU:N[:K] -> (T, U, N, K): K (default N) scenarios of the N whose replans meet ref."""
    try:
        size, *counts = text.split(":")
        t, u = size.lower().split("x")
        if len(counts) not in (1, 2):
            raise ValueError
        out = (int(t), int(u), int(counts[0]), int(counts[-1]))
    except ValueError:
        raise argparse.ArgumentTypeError(f"--set {text!r}: expected TARGETSxUAVS:SCENARIOS[:REF_SCENARIOS], "
                                         "e.g. 25x5:20 or 100x20:5:1")
    if min(out[:3]) < 1 or not 0 <= out[3] <= out[2]:
        raise argparse.ArgumentTypeError(f"--set {text!r}: targets, UAVs and scenarios must be >= 1, "
                                         "ref scenarios between 0 and the scenarios")
    return out


def percentile(sorted_values, p):
    """Nearest-rank percentile of a sorted list."""
    k = max(1, -(-len(sorted_values) * p // 100))
    return sorted_values[int(k) - 1]


def campaign_spec(sets, algos, penalties, args):
    """One campaign for every set: its scenarios flown with each algorithm and penalty, ref
    on the replans' residual missions of the set's first ref_count scenarios."""
    from sva_tools.commands import gen
    from sva_tools.commands.common import Parser
    sub = Parser(prog="live_bench.py --gen").add_subparsers()
    gen.add_parser(sub)
    a = sub.choices["gen"].parse_args(args.gen)
    specs = []
    for t, u, n, k in sets:
        specs.append({"label": f"{t}x{u}_n{n}_k{k}", "targets": t, "uavs": u, "events": args.events,
                      "count": n, "ref_count": k, "width": list(a.width), "need": list(a.need), "ratio": a.ratio,
                      "max_coord": a.max_coord, "fuel": a.fuel, "hover": a.hover,
                      "ticks_per_cell": a.ticks_per_cell, "overlap_percent": a.overlap_percent})
    return specs


def fly_node(path, algo, penalty, log_path):
    """The flight against a real sva_node (`sim --via lcm`'s planner), cached like fly."""
    if os.path.exists(log_path):
        with open(log_path, encoding="utf-8") as f:
            return json.load(f)
    mission, events, _ = sim.load_scenario(path)
    log = sim.simulate_via_lcm(mission, events, penalty, algo)
    with open(log_path, "w", encoding="utf-8") as f:
        json.dump(log, f)
    return log


def node_figures(node_logs, cli_logs):
    """Round trips and node solve times of the REPLAN answers of node_logs; flights whose
    coverage equals the in-process flight's."""
    msgs = [m for l in node_logs for r in l["replans"] for m in r["node"]["messages"]
            if m["channel"] == "REPLAN"]
    rts = sorted(m["round_trip_us"] for m in msgs)
    solve = sorted(m["solve_us"] for m in msgs)
    def name(log):
        return log["scenario"]["mission"]["name"]

    covered = {name(b): b["summary"]["covered"] for b in cli_logs}  # paired by scenario name
    same = sum(1 for a in node_logs if covered.get(name(a)) == a["summary"]["covered"])
    return {"flights": len(node_logs), "same": same, "messages": len(msgs),
            "rt_p50": percentile(rts, 50) if rts else None, "rt_p99": percentile(rts, 99) if rts else None,
            "rt_max": rts[-1] if rts else None,
            "solve_p50": percentile(solve, 50) if solve else None,
            "solve_p99": percentile(solve, 99) if solve else None}


NODE_HEAD = ("| algorithm | change_penalty | flights covering as in process | replans through the node "
             "| round trip p50 | round trip p99 | round trip max | node solve p50 | node solve p99 |\n"
             "|---|---|---|---|---|---|---|---|---|")


def node_row(algo, penalty, f):
    return (f"| {algo} | {penalty} | {f['same']}/{f['flights']} | {f['messages']} | {ms(f['rt_p50'])} "
            f"| {ms(f['rt_p99'])} | {ms(f['rt_max'])} | {ms(f['solve_p50'])} | {ms(f['solve_p99'])} |")


def node_goals(targets, uavs, by):
    if (targets, uavs) != (25, 5):
        return []
    return [f"- {algo}, change_penalty {pen}: replan round trip through the node p99 {ms(f['rt_p99'])} "
            f"(goal under {GOAL_NODE_P99_MS:g} ms): "
            f"{'met' if f['rt_p99'] is not None and f['rt_p99'] / 1000 < GOAL_NODE_P99_MS else 'not met'} "
            f"({f['messages']} replans)." for (algo, pen), f in sorted(by.items())]


def node_section(targets, uavs, count, paths, folder, logs, algos, penalties, args):
    by = {}
    for algo in algos:
        for pen in penalties:
            node_logs = [fly_node(p, algo, pen, os.path.join(
                folder, "logs", f"{os.path.basename(p)[:-5]}.{algo}.p{pen}.lcm.json")) for p in paths]
            by[algo, pen] = node_figures(node_logs, logs[algo, pen])
            print(f"{targets}x{uavs}: flown {algo} penalty {pen} through the node", file=sys.stderr, flush=True)
    lines = [f"#### {targets} targets x {uavs} UAVs, {count} scenarios, through the LCM node", "",
             f"`sva-tools gen --targets {targets} --uavs {uavs} --events {args.events} --count {count} "
             f"--seed {args.seed} {' '.join(args.gen)}`".replace("  ", " ").replace(" `", "`") + ".", "",
             NODE_HEAD] + [node_row(a, p, by[a, p]) for a in algos for p in penalties]
    g = node_goals(targets, uavs, by)
    return "\n".join(lines + ([""] + g if g else []))


def ref_key(residual):
    doc = {k: v for k, v in residual.items() if k not in ("change_penalty", "name")}
    return hashlib.sha256(json.dumps(doc, sort_keys=True).encode()).hexdigest()[:24]


def figures(logs, refs, ref_count):
    """The figures of one (set, algorithm, penalty) from its flight logs and the ref plans
    of the replans' residual missions of the first ref_count logs (refs: ref_key -> plan)."""
    covered = sum(l["summary"]["covered"] for l in logs)
    coverable = sum(l["summary"]["coverable"] for l in logs)
    replans = [r for l in logs for r in l["replans"]]
    judged = [(r["plan"], refs[ref_key(r["mission"])]) for l in logs[:ref_count] for r in l["replans"]
              if r["mission"]["targets"]]
    as_many = sum(1 for p, q in judged if p["covered"] >= q["covered"])
    above = sum(1 for p, q in judged if p["covered"] > q["covered"])
    gaps = [100.0 * (p["cost"] - q["cost"]) / q["cost"] for p, q in judged
            if p["covered"] == q["covered"] and q["cost"] > 0]
    later = [r for r in replans if r["cause"] != "start"]
    times = sorted(r["solve_us"] for r in replans if r["solve_us"] is not None)
    return {
        "scenarios": len(logs), "covered": covered, "coverable": coverable,
        "replans": len(replans), "judged": len(judged), "as_many": as_many, "above": above,
        "plan_covered": sum(p["covered"] for p, _ in judged), "ref_covered": sum(q["covered"] for _, q in judged),
        "ref_proven": sum(1 for _, q in judged if q["stats"].get("optimal")),
        "gap_mean": statistics.mean(gaps) if gaps else 0.0, "gap_max": max(gaps) if gaps else 0.0,
        "changes": sum(r["changes"]["count"] for r in later), "later": len(later),
        "p50_us": percentile(times, 50) if times else None, "p99_us": percentile(times, 99) if times else None,
        "timed": len(times),
    }


def pct(a, b):
    return 100.0 * a / b if b else 100.0


def ms(us):
    return "–" if us is None else f"{us / 1000:.3f} ms"


def row(algo, penalty, f):
    if f["judged"]:
        against = (f"{f['as_many']}/{f['judged']} ({pct(f['as_many'], f['judged']):.1f} %) "
                   f"| {f['plan_covered']}/{f['ref_covered']} ({pct(f['plan_covered'], f['ref_covered']):.1f} %) "
                   f"| mean {f['gap_mean']:.2f} %, largest {f['gap_max']:.2f} %")
    else:
        against = "– | – | –"  # ref not run on this set
    return (f"| {algo} | {penalty} | {f['covered']}/{f['coverable']} ({pct(f['covered'], f['coverable']):.1f} %) "
            f"| {against} | {f['changes'] / f['later'] if f['later'] else 0.0:.2f} | {ms(f['p50_us'])} "
            f"| {ms(f['p99_us'])} |")


HEAD = ("| algorithm | change_penalty | flight: covered / coverable | replans covering as many as ref "
        "| replans' covered / ref's | cost gap at equal coverage | changed visits per replan "
        "| replan p50 | replan p99 |\n|---|---|---|---|---|---|---|---|---|")


def goals(targets, uavs, by):
    """Goal lines for flow in this set (None when flow was not flown)."""
    lines = []
    for (algo, pen), f in sorted(by.items()):
        if algo != "flow":
            continue
        share = pct(f["as_many"], f["judged"])
        if not f["judged"]:
            lines.append(f"- flow, change_penalty {pen}: against ref: not measured on this set (ref not run).")
        else:
                lines.append(f"- flow, change_penalty {pen}: covers as many targets as ref on {share:.1f} % of "
                         f"{f['judged']} residual missions (goal at least {GOAL_EQUAL:g} %): "
                         f"{'met' if share >= GOAL_EQUAL else 'not met'}.")
        if (targets, uavs) == (25, 5) and f["p50_us"] is not None:
            ok50 = f["p50_us"] / 1000 < GOAL_P50_MS
            ok99 = f["p99_us"] / 1000 < GOAL_P99_MS
            lines.append(f"- flow, change_penalty {pen}: replan p50 {ms(f['p50_us'])} (goal under {GOAL_P50_MS:g} ms): "
                         f"{'met' if ok50 else 'not met'}; p99 {ms(f['p99_us'])} (goal under {GOAL_P99_MS:g} ms): "
                         f"{'met' if ok99 else 'not met'} ({f['timed']} replans).")
    return lines


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--results", action="store_true", help="write docs/results/live.md and docs/results.md")
    ap.add_argument("--set", dest="sets", action="append", type=parse_set, metavar="TxU:N",
                    help="a scenario set: targets x UAVs : scenarios [: how many of them (the first) meet ref, "
                         "default all] (repeatable; default 25x5:20 and 100x20:5)")
    ap.add_argument("--events", type=int, default=10, help="events per scenario (default 10)")
    ap.add_argument("--seed", type=int, default=7, help="gen's seed (default 7)")
    ap.add_argument("--algos", default="sva,ga,hga,flow", help="comma-separated (default sva,ga,hga,flow)")
    ap.add_argument("--penalties", default="0,1000", help="change_penalty values, comma-separated (default 0,1000)")
    ap.add_argument("--det-limit", type=float, default=10.0, help="ref's deterministic limit (default 10)")
    ap.add_argument("--jobs", type=int, default=2,
                    help="Dask LocalCluster workers: tasks at once (default 2)")
    ap.add_argument("--scheduler", metavar="tcp://HOST:PORT",
                    help="run the tasks on this Dask scheduler's workers instead (docs/campaigns.md)")
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "live_bench"),
                    help="the campaign's results and the flight logs (default build/live_bench)")
    ap.add_argument("--gen", action="append", default=[], metavar="ARG",
                    help="an extra `sva-tools gen` argument, e.g. --gen=--need --gen=1:2 (repeatable)")
    ap.add_argument("--node", action="store_true",
                    help="also fly every scenario through a real sva_node over LCM (root; the bench runs in "
                         "a network namespace of its own) and measure the replan round trip")
    args = ap.parse_args(argv)
    if args.node and not os.environ.get("SVA_LCM_NETNS"):
        from sva_tools.lcm import simnode
        if os.geteuid() != 0:
            print("live_bench: --node needs root (the node runs in a network namespace made for the bench)",
                  file=sys.stderr)
            return 2
        return subprocess.run([str(simnode.netns_helper()), sys.executable, os.path.abspath(__file__), *argv],
                              env=os.environ).returncode
    sets = args.sets or [(25, 5, 20, 20), (100, 20, 5, 5)]
    asked_sets = sets
    if args.node:  # the node's figures need no ref
        sets = [(t, u, n, 0) for t, u, n, _ in sets]
    algos = [a for a in args.algos.split(",") if a]
    penalties = [int(p) for p in args.penalties.split(",") if p]
    load_start = " ".join(f"{x:.2f}" for x in os.getloadavg())
    gen_tag = "_".join(a.strip("-").replace(":", "-") for a in args.gen)
    sections = []
    # One campaign: each set a spec set with its own scenario count.
    spec = cspec.validate({
        "name": "live_bench", "kind": "live", "sets": campaign_spec(sets, algos, penalties, args),
        "seeds": {"first": args.seed, "count": 1}, "count": 1, "algorithms": algos,
        "penalties": penalties, "ref": {"det_limit": args.det_limit, "max_targets": 1000}})
    stats = campaign.run(spec, os.path.join(args.work, "campaign"), args.scheduler,
                         None if args.scheduler else args.jobs)
    if stats["failed"]:
        sys.exit("live_bench: tasks failed: " + "; ".join(stats["failed"][:5]))
    rows = stats["rows"]
    by_hash = {r["mission_hash"]: r for r in rows.values() if r["task"] == "ref"}
    for targets, uavs, count, ref_count in sets:
        tag = f"{targets}x{uavs}_e{args.events}_s{args.seed}" + (f"_{gen_tag}" if gen_tag else "")
        folder = os.path.join(args.work, tag)
        os.makedirs(os.path.join(folder, "logs"), exist_ok=True)
        label = f"{targets}x{uavs}_n{count}_k{ref_count}"
        logs = {}
        for algo in algos:
            for pen in penalties:
                # a stored row is keyed by content, so it may carry the set label of the run
                # that stored it: this run's tasks pick their rows
                flights = [rows[t["key"]] for t in sorted(
                    (t for t in stats["task_list"] if t["task"] == "fly" and t["set"] == label
                     and t["tool"] == algo and t["penalty"] == pen), key=lambda t: t["index"])]
                for r in flights:
                    if r["error"]:
                        sys.exit(f"live_bench: {algo} penalty {pen} on {r['mission_name']}: {r['error']}")
                logs[algo, pen] = [json.loads(r["result"]) for r in flights]
                for r, log in zip(flights, logs[algo, pen]):
                    with open(os.path.join(folder, "logs", f"{r['mission_name']}.{algo}.p{pen}.json"), "w",
                              encoding="utf-8") as f:
                        json.dump(log, f)
        refs = {}  # ref_key of a residual mission -> ref's plan of it
        if args.node:
            # the scenarios as files for `sim --via lcm`, in the campaign's order
            paths = []
            os.makedirs(os.path.join(folder, "scenarios"), exist_ok=True)
            for t in stats["task_list"]:
                if t["task"] == "fly" and t["set"] == label and t["tool"] == algos[0] and t["penalty"] == penalties[0]:
                    path = os.path.join(folder, "scenarios", f"{t['mission_name']}.json")
                    with open(path, "w", encoding="utf-8") as f:
                        f.write(t["mission"])
                    paths.append((t["index"], path))
            paths = [p for _, p in sorted(paths)]
            sections.append(node_section(targets, uavs, count, paths, folder, logs, algos, penalties, args))
            print(sections[-1] + "\n")
            continue
        for i in range(ref_count):
            for ls in logs.values():
                for r in ls[i]["replans"]:
                    if r["mission"]["targets"]:
                        q = by_hash[tasks.mission_hash(tasks.residual_for_ref(r["mission"]))]
                        if q["error"]:
                            sys.exit(f"live_bench: ref on a residual mission: {q['error']}")
                        refs[ref_key(r["mission"])] = json.loads(q["result"])
        by = {k: figures(v, refs, ref_count) for k, v in logs.items()}
        proven = sum(1 for q in refs.values() if q["stats"].get("optimal"))
        ref_s = sorted(q["stats"]["solve_us"] / 1e6 for q in refs.values()) or [0.0]
        lines = [f"#### {targets} targets x {uavs} UAVs, {count} scenarios", "",
                 f"`sva-tools gen --targets {targets} --uavs {uavs} --events {args.events} --count {count} "
                 f"--seed {args.seed} {' '.join(args.gen)}`".replace("  ", " ").replace(" `", "`") +
                 (f"; ref on the replans of {'all' if ref_count == count else f'the first {ref_count}'} "
                  f"{'scenarios' if ref_count != 1 else 'scenario'}: {len(refs)} distinct residual missions "
                  f"with a target, {proven} of them proven optimal by ref; ref's wall time per mission "
                  f"(its stats.solve_us): median {ref_s[len(ref_s) // 2]:.1f} s, largest {ref_s[-1]:.1f} s."
                  if ref_count else
                  "; ref not run on this set (the columns against ref are empty)."), "",
                 HEAD] + [row(a, p, by[a, p]) for a in algos for p in penalties]
        g = goals(targets, uavs, by)
        if g:
            lines += [""] + g
        sections.append("\n".join(lines))
        print("\n".join(lines) + "\n")
    if args.results:
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        import results as page  # tools/bench/results.py
        opts = []
        for t, u, n, k in asked_sets:
            opts += ["--set", f"{t}x{u}:{n}" + (f":{k}" if k != n else "")]
        if args.events != 10:
            opts += ["--events", str(args.events)]
        if args.seed != 7:
            opts += ["--seed", str(args.seed)]
        if args.algos != "sva,ga,hga,flow":
            opts += ["--algos", args.algos]
        if args.penalties != "0,1000":
            opts += ["--penalties", args.penalties]
        if args.det_limit != 10.0:
            opts += ["--det-limit", f"{args.det_limit:g}"]
        opts += [f"--gen={a}" for a in args.gen]
        if args.node:
            opts.insert(0, "--node")
        cmd = " ".join(["nice .venv/bin/python tools/bench/live_bench.py --results"] + opts)
        intro = "\n".join([
            "Scenarios from `sva-tools gen --events`, flown tick by tick by `sva-tools sim` (in the bench's "
            "process; the simulator calls `sva replan` at tick 0 and at each tick with events) with each "
            f"algorithm and `change_penalty` {' and '.join(map(str, penalties))}. Flight coverage: targets "
            "covered over targets still coverable after the events (neither cancelled nor lost), summed over "
            "the flight logs. Each replan's plan of its residual mission is compared with `sva-tools ref "
            f"--det-limit {args.det_limit:g} --workers 1` on that residual mission (replans whose residual "
            "mission has no target left are not counted); ref is not always proven optimal, so a replan can "
            "cover more. Changed visits per replan: SPEC 12 changed visits of each replan after the start one. "
            "Latency: `stats.solve_us` of each replan, the wall time of `sva_live_replan()` in the `sva replan` "
            "process (nearest-rank p50 and p99 over all replans, the start one included). `change_penalty` "
            "weighs only between the algorithm's plan and the plan in force, after coverage (docs/live.md), so "
            "a large one removes only the changes that buy no coverage.", "",
            "The replan latency through the LCM node is measured by `live_bench.py --node` (the part "
            "\"through the LCM node\" below).", ""])
        if args.node:
            intro = " ".join([
                "The scenarios above flown again by the simulator against a real `sva_node` per flight (its "
                "algorithm and `change_penalty`; `sva-tools sim --via lcm`'s planner) over LCM UDP multicast on "
                "the loopback of a network namespace, the simulator and the node on the same machine. Round "
                "trip: from publishing an `event_t` (each event, and a clock at tick 0) to receiving its "
                "`replan_t`, on the simulator's monotonic clock: the node's decoding, `sva_live_apply`, "
                "`sva_live_replan`, encoding, both datagrams (a replan_t is 34926 bytes) and the Python side's "
                "decoding of the answer (nearest-rank p50 and p99 over every replan). Node solve: "
                "`plan_t.solve_us` of those replans. Flights covering as in process: the flights whose covered "
                "count equals the in-process flight's (`sva replan`)."]) + "\n"
            page.write(page.ROOT, "live.node", cmd, intro + "\n" + "\n\n".join(sections),
                       title="Replans through the LCM node", load_start=load_start)
            return 0
        page.write(page.ROOT, "live", cmd, intro + "\n" + "\n\n".join(sections), load_start=load_start)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
