#!/usr/bin/env python3
"""flow's coverage against the exact optimum (sva-tools ref) at need 2 and 3.

Usage (from the repository root, after scripts/setup.sh and scripts/build.sh):
    .venv/bin/python tools/bench/flow_cover_bench.py [--results] [--cache DIR] [--jobs N] [--count N]
        [--gen-seed S]

The missions: `sva-tools gen --seed 7 --width 10:20 --hover 2` (or --gen-seed) in the sets of SETS below
(20 to 25 targets, 4 to 9 UAVs, need 2 or 3, fuel that leaves some targets uncoverable),
COUNT of each (default 25: 200 missions). flow plans each one with its default budget,
one at a time; ref (REF_DET, default 10, its deterministic limit; one CP-SAT worker) runs
on N missions at once (default 2) and its answers are kept in the cache folder (default
$SVA_REF_CACHE or build/ref-cache), keyed by the mission's content and the limit, so a
re-run only plans with flow. $SVA_BIN, when set, is the CLI to plan with (e.g. an older
build, to compare).
Prints, per set and in all: the missions where flow covers fewer targets than ref's proven
coverage (and by how much; ref proves it when its plan is optimal or its coverage equals
its covered_upper_bound), those where it covers fewer or more than an unproven ref, how
many ref leaves unproven, on how many flow proves its coverage the most (stats.coverage_proven)
and its plan optimal, on how many the most coverage is known (flow proves it, or ref does)
and flow covers it, and flow's median and p95 solve time. --results also writes
docs/results/flow_vs_ref.cover_need2_3.md (tools/bench/results.py; with --gen-seed,
flow_vs_ref.cover_need2_3_seedS.md). Exit status 1 when flow covers fewer than a proven
optimum, or claims its coverage the most where ref covers more.
"""
import argparse
import concurrent.futures
import hashlib
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SVA = os.environ.get("SVA_BIN") or os.path.join(ROOT, "build", "bin", "sva")
TOOLS = os.path.join(ROOT, ".venv", "bin", "sva-tools")

# (targets, UAVs, need, fuel): fuel about where a UAV can fly half of a fair share.
SETS = [(20, 4, 2, 70), (20, 6, 2, 60), (25, 7, 2, 70), (25, 9, 2, 60),
        (20, 6, 3, 70), (20, 9, 3, 60), (25, 7, 3, 80), (25, 9, 3, 70)]
GEN = ["--width", "10:20", "--hover", "2"]


def missions(targets, uavs, need, fuel, count, folder, seed):
    """The set's missions (paths), written by `sva-tools gen` into folder."""
    out = os.path.join(folder, f"{targets}x{uavs}_need{need}_fuel{fuel}")
    subprocess.run([TOOLS, "gen", "--targets", str(targets), "--uavs", str(uavs), "--need", str(need),
                    "--fuel", str(fuel), "--count", str(count), "-o", out, "--seed", str(seed)] + GEN,
                   check=True, capture_output=True)
    return sorted((os.path.join(out, f) for f in os.listdir(out)),
                  key=lambda p: int(p.rsplit("_", 1)[1].split(".")[0]))


def ref_answer(path, cache, det):
    """ref's plan of the mission at path, from the cache or solved (then cached)."""
    with open(path, "rb") as f:
        key = hashlib.sha256(f.read() + f"|det={det}".encode()).hexdigest()
    cached = os.path.join(cache, key + ".json")
    if os.path.exists(cached):
        with open(cached) as f:
            return json.load(f)
    out = subprocess.run([TOOLS, "ref", "--det-limit", str(det), path], capture_output=True, text=True,
                         check=True).stdout
    tmp = cached + ".tmp"
    with open(tmp, "w") as f:
        f.write(out)
    os.replace(tmp, cached)
    return json.loads(out)


def ref_proven(ref):
    """Whether ref proves its coverage the most (its cost need not be proven)."""
    return ref["stats"].get("optimal") or ref["covered"] == ref["stats"].get("covered_upper_bound")


def flow_answer(path):
    out = subprocess.run([SVA, "plan", "--algo", "flow", path], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--results", action="store_true")
    ap.add_argument("--cache", default=os.environ.get("SVA_REF_CACHE", os.path.join(ROOT, "build", "ref-cache")))
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--count", type=int, default=25)
    ap.add_argument("--gen-seed", type=int, default=7)
    args = ap.parse_args(argv)
    det = float(os.environ.get("REF_DET", "10"))
    load_start = " ".join(f"{x:.2f}" for x in os.getloadavg())
    os.makedirs(args.cache, exist_ok=True)
    rows = []  # (set, name, flow, ref)
    with tempfile.TemporaryDirectory() as folder:
        todo = [(s, p) for s in SETS for p in missions(*s, args.count, folder, args.gen_seed)]
        # ref solves the sets' first missions first, then their second ones, and so on.
        order = sorted(range(len(todo)), key=lambda i: (i % args.count, i))
        with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
            solved = dict(zip(order, pool.map(lambda i: ref_answer(todo[i][1], args.cache, det), order)))
        refs = [solved[i] for i in range(len(todo))]
        for (s, p), ref in zip(todo, refs):
            index = p.rsplit("_", 1)[1][:-5]
            rows.append((s, f"{s[0]}x{s[1]}n{s[2]}#{index}", flow_answer(p), ref))
    lines = []
    table = ["| set | missions | ref's coverage proven | flow's coverage proven | the most known, flow covers it "
             "| flow fewer than proven | flow fewer than unproven ref | flow more than unproven ref "
             "| flow proven optimal | median | p95 |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    below_all = []
    false_claims = [n for _, n, fl, ref in rows
                    if fl["stats"].get("coverage_proven") and ref["covered"] > fl["covered"]]
    for s in SETS + [None]:
        rs = [r for r in rows if s is None or r[0] == s]
        name = "all" if s is None else f"{s[0]}x{s[1]} need {s[2]} fuel {s[3]}"
        below = [(n, ref["covered"] - fl["covered"]) for _, n, fl, ref in rs
                 if ref_proven(ref) and fl["covered"] < ref["covered"]]
        short = [(n, ref["covered"] - fl["covered"]) for _, n, fl, ref in rs
                 if not ref_proven(ref) and fl["covered"] < ref["covered"]]
        above = [n for _, n, fl, ref in rs if fl["covered"] > ref["covered"]]
        unproven = [n for _, n, _, ref in rs if not ref_proven(ref)]
        optimal = sum(1 for _, _, fl, _ in rs if fl["stats"]["optimal"])
        flow_proven = sum(1 for _, _, fl, _ in rs if fl["stats"].get("coverage_proven"))
        known = sum(1 for _, _, fl, ref in rs if fl["stats"].get("coverage_proven")
                    or (ref_proven(ref) and fl["covered"] >= ref["covered"]))
        times = sorted(fl["stats"]["solve_us"] for _, _, fl, _ in rs)
        med = times[len(times) // 2] / 1000
        p95 = times[min(len(times) - 1, int(len(times) * 0.95))] / 1000
        uncovered = statistics.mean(len(r[3]["uncovered"]) for r in rs)
        lines.append(f"{name}: {len(rs)} missions (ref leaves {uncovered:.1f} uncovered on average); "
                     f"flow below ref's proven coverage on {len(below)}: {below}; below an unproven ref: {short}; "
                     f"above an unproven ref: {above}; ref unproven: {len(unproven)}; flow's coverage proven: "
                     f"{flow_proven}; the most known and covered: {known}; flow optimal: {optimal}; "
                     f"solve median {med:.2f} ms, p95 {p95:.2f} ms")

        def listed(pairs):
            return f"{len(pairs)}" + (f" ({', '.join(f'{n} by {k}' for n, k in pairs)})" if pairs else "")
        table.append(f"| {name} | {len(rs)} | {len(rs) - len(unproven)} | {flow_proven} | {known} "
                     f"| {listed(below)} | {listed(short)} "
                     f"| {len(above)} | {optimal} | {med:.2f} ms | {p95:.2f} ms |")
        if s is None:
            below_all = below
    print("\n".join(lines))
    if false_claims:
        print(f"flow claims its coverage the most where ref covers more: {false_claims}")
    if args.results:
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        import results as page  # tools/bench/results.py
        env = f"REF_DET={os.environ['REF_DET']} " if os.environ.get("REF_DET") else ""
        seeded = args.gen_seed != 7
        cmd = (f"{env}.venv/bin/python tools/bench/flow_cover_bench.py --results --count {args.count}"
               + (f" --gen-seed {args.gen_seed}" if seeded else ""))
        body = "\n".join([
            f"{len(rows)} missions: `sva-tools gen {' '.join(GEN)} --seed {args.gen_seed}` with --targets, --uavs, "
            "--need and --fuel "
            f"per row, {args.count} of each; flow with its default work budget, one plan per process; ref "
            f"with deterministic limit {det:g}, one worker. \"Fewer\" counts missions where flow covers fewer "
            "targets than ref's proven coverage (ref proves it when its plan is optimal or its coverage "
            "equals its `covered_upper_bound`); flow's when `stats.coverage_proven`. \"The most known\": "
            "flow proves its coverage the most, or ref proves its own and flow covers as many. "
            "Time: `stats.solve_us`.", ""] + table)
        page.write(page.ROOT, "flow_vs_ref.cover_need2_3" + (f"_seed{args.gen_seed}" if seeded else ""), cmd, body,
                   title=f"Coverage at need 2 and 3, {len(rows)} missions, 20 to 25 targets x 4 to 9 UAVs"
                   + (f", gen seed {args.gen_seed}" if seeded else ""),
                   load_start=load_start)
    return 1 if (below_all or false_claims) else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
