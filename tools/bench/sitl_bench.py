#!/usr/bin/env python3
"""Scenarios flown by ArduCopter SITL (`sva-tools sitl`, docs/sitl.md): leg timing
against the plan's grid, and coverage against the simulator and the exact reference.

Usage (from the repository root, as root, after scripts/setup.sh and scripts/build.sh):
    .venv/bin/python tools/bench/sitl_bench.py --legs [--uavs 3] [--speedup 10]
    .venv/bin/python tools/bench/sitl_bench.py --results [--count 6] [--seed 1] [--speedup 10]

--legs flies a generated scenario whose windows leave no slack: UAV k starts at
(0, 12 k) and flies a chain of legs (axis-aligned of 1 to 5 cells, diagonal, knight's
moves), each target's window starting exactly when the plan's grid timing (one cell per
ticks_per_cell ticks, departing at the previous window's end) brings it there, and
lasting 4 ticks. It prints, per leg shape, how late each vehicle arrived against that
timing: at the waypoint (first within 2 m, ArduCopter's WPNAV_RADIUS) and within the
coverage radius; the first leg of each UAV (from its take-off, before t0) apart; and the
take-off: from the arming command to `alt_m` - 0.5 m. Vehicle time throughout.

--results flies --count scenarios made by `sva-tools gen --events` (3 to 8 UAVs, need 1
and need 2 in turn; --targets 2 per UAV up to 10, --width 10:20, --max-coord 8, events
drawn from uav_lost, uav_back, target_added, target_cancelled, fuel) through
`sva-tools sim` and `sva-tools sitl`, and solves the mission at tick 0 with
`sva-tools ref` (a yardstick: the optimum without events), and prints a table: coverage
in SITL (and what its plans promised), in the simulator and by ref; arrival slack
p50/p1; late arrivals; and the latency from a vehicle's loss (its process killed) to the
node's replan and to the bridge's last upload of that replan (vehicle time, p50/p99).
Flights and logs are kept under --work (default build/sitl_bench/).
"""
import argparse
import contextlib
import io
import json
import math
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))

from sva_tools import frame  # noqa: E402
from sva_tools.lcm.simnode import percentile  # noqa: E402
from sva_tools.sitl import judge  # noqa: E402
from sva_tools.sitl.settings import DEFAULT_FRAME, parse_frame  # noqa: E402
from sva_tools.sitl.flight import takeoff_allowance_s  # noqa: E402

_FRAME = parse_frame(DEFAULT_FRAME)
# The copter's take-off in the default frame, in ticks (what `sitl` gives a mission
# without takeoff_ticks): written into every generated scenario, for sim and SITL alike.
TAKEOFF_TICKS = math.ceil(takeoff_allowance_s(_FRAME["alt_m"]) / _FRAME["tick_s"])
WPNAV_RADIUS_M = 2.0
WINDOW_TICKS = 4
# Legs (dx, dy) in cells, per UAV: axis-aligned 1..5, diagonal, knight's moves.
CHAINS = [
    [(1, 0), (0, 2), (-3, 0), (0, -4), (5, 0), (0, 1), (-2, 0)],
    [(1, 1), (2, -2), (-3, 3), (0, 3), (-2, 0), (4, -4), (0, -1)],
    [(2, 1), (-1, 3), (4, -2), (0, 1), (-3, 0), (1, -2), (0, 4)],
    [(3, 0), (1, 2), (-2, 2), (0, -5), (2, 0), (-1, -1), (0, 3)],
]


def env():
    e = dict(os.environ)
    e["PYTHONPATH"] = os.path.join(ROOT, "tools") + os.pathsep + e.get("PYTHONPATH", "")
    e.pop("SVA_LCM_NETNS", None)
    return e


def tool(*args, timeout=3600):
    return subprocess.run([sys.executable, "-m", "sva_tools", *map(str, args)], capture_output=True,
                          text=True, env=env(), timeout=timeout)


# --- legs ----------------------------------------------------------------------------

def legs_scenario(uavs):
    us, targets, legs = [], [], []
    tid = 1
    for k in range(uavs):
        chain = CHAINS[k % len(CHAINS)]
        x, y = 0, 12 * k + (12 * len(CHAINS) * (k // len(CHAINS)))
        us.append({"id": k + 1, "x": x, "y": y, "fuel": 500})
        t = 0
        for n, (dx, dy) in enumerate(chain):
            t += abs(dx) + abs(dy)
            x, y = x + dx, y + dy
            targets.append({"id": tid, "x": x, "y": y, "start": t, "end": t + WINDOW_TICKS, "need": 1})
            legs.append({"target": tid, "uav": k + 1, "dx": dx, "dy": dy, "first": n == 0})
            t += WINDOW_TICKS
            tid += 1
    mission = {"name": f"sitl_legs_{uavs}u", "depot": {"x": 0, "y": 0}, "ticks_per_cell": 1,
               "hover_fuel": 0, "uavs": us, "targets": targets}
    return {"mission": mission, "events": []}, legs


def crossing(t, d, r, after):
    """First instant >= after at which the distance d (over times t) falls to r or below,
    interpolated; None if never."""
    for k in range(1, len(t)):
        if t[k] < after or d[k] > r:
            continue
        if d[k - 1] > r and t[k - 1] >= after - 2000:
            f = (d[k - 1] - r) / (d[k - 1] - d[k])
            return t[k - 1] + f * (t[k] - t[k - 1])
        return t[k]
    return None


def leg_figures(log, legs):
    geo = frame.Frame.from_json(log["sitl"]["frame"])
    tick_ms = geo.tick_ms
    r = log["sitl"]["radius_m"]
    tel = {u["id"]: u["telemetry"] for u in log["uavs"]}
    enu = {}
    for uid, rows in tel.items():
        import numpy as np
        a = np.array(rows, dtype=float)
        e, n = judge.enu(geo, a[:, 1], a[:, 2])
        enu[uid] = (a[:, 0], e, n, a[:, 3])
    targets = {t["id"]: t for t in log["scenario"]["mission"]["targets"]}
    rows = []
    for leg in legs:
        t = targets[leg["target"]]
        ts, e, n, _alt = enu[leg["uav"]]
        d = ((e - t["x"] * geo.cell_m) ** 2 + (n - t["y"] * geo.cell_m) ** 2) ** 0.5
        depart = (t["start"] - abs(leg["dx"]) - abs(leg["dy"])) * tick_ms
        after = -10 ** 9 if leg["first"] else depart
        point = crossing(list(ts), list(d), WPNAV_RADIUS_M, after)
        inside = crossing(list(ts), list(d), r, after)
        ws = t["start"] * tick_ms
        rows.append(dict(leg, cells=abs(leg["dx"]) + abs(leg["dy"]),
                         metres=math.hypot(leg["dx"], leg["dy"]) * geo.cell_m,
                         late_point_s=None if point is None else (point - ws) / 1000.0,
                         late_radius_s=None if inside is None else (inside - ws) / 1000.0))
    return rows


def takeoff_figures(log):
    alt = log["sitl"]["frame"]["alt_m"]
    out = []
    for u in log["uavs"]:
        arm = next((x[0] for x in u["texts"] if x[1] == "Arming motors" and x[0] is not None), None)
        if arm is None:
            continue
        top = next((p[0] for p in u["telemetry"] if p[0] >= arm and p[3] >= alt - 0.5), None)
        leave = next((x[0] for x in u["texts"] if x[0] is not None and x[0] >= arm
                      and x[1].startswith("Mission: 3 ")), None)
        out.append({"uav": u["id"], "climb_s": None if top is None else (top - arm) / 1000.0,
                    "first_leg_at_s": None if leave is None else leave / 1000.0})
    return out


def shape(row):
    dx, dy = abs(row["dx"]), abs(row["dy"])
    if dx == 0 or dy == 0:
        return f"axis {row['cells']} cell{'s' if row['cells'] > 1 else ''}"
    if dx == dy:
        return f"diagonal {dx}+{dy}"
    return f"oblique {max(dx, dy)}+{min(dx, dy)}"


def fmt(v, digits=1):
    return "-" if v is None else f"{v:+.{digits}f}"


def run_legs(args):
    os.makedirs(args.work, exist_ok=True)
    doc, legs = legs_scenario(args.uavs)
    path = os.path.join(args.work, "legs.json")
    with open(path, "w", encoding="utf-8") as f:
        json.dump(doc, f)
    log_path = os.path.join(args.work, "legs.log.json")
    t = time.monotonic()
    r = tool("sitl", path, "--algo", args.algo, "--speedup", args.speedup, "--out", log_path, "--quiet",
             *(["--frame", args.frame] if args.frame else []))
    if r.returncode != 0:
        print(r.stderr, file=sys.stderr)
        return r.returncode
    wall = time.monotonic() - t
    with open(log_path, encoding="utf-8") as f:
        log = judge.judge_log(json.load(f))
    rows = leg_figures(log, legs)
    fr = log["sitl"]["frame"]
    v = fr["cell_m"] / fr["tick_s"]
    print(f"frame: {fr['cell_m']:g} m cells, {fr['tick_s']:g} s ticks, {fr['alt_m']:g} m up: planned "
          f"speed {v:g} m/s; coverage radius {log['sitl']['radius_m']:g} m; speedup {args.speedup:g}; "
          f"{r.stdout.strip()}; {wall:.0f} s wall")
    print("lateness against the grid timing (s, vehicle clock; + late, - early):")
    print(f"{'leg':<16} {'n':>3} {'m':>6} {'at waypoint min/med/max':>26} {'in radius min/med/max':>24}")
    groups = {}
    for row in rows:
        if not row["first"]:
            groups.setdefault(shape(row), []).append(row)
    order = sorted(groups, key=lambda k: (groups[k][0]["cells"], k))
    for key in order + ["all legs after a hold"]:
        g = groups[key] if key in groups else [x for x in rows if not x["first"]]
        p = sorted(x["late_point_s"] for x in g if x["late_point_s"] is not None)
        q = sorted(x["late_radius_s"] for x in g if x["late_radius_s"] is not None)
        med = lambda s: None if not s else s[len(s) // 2]  # noqa: E731
        print(f"{key:<16} {len(g):>3} {g[0]['metres'] if key in groups else 0:>6.0f} "
              f"{fmt(p[0] if p else None):>8}/{fmt(med(p)):>6}/{fmt(p[-1] if p else None):>6}"
              f"     {fmt(q[0] if q else None):>8}/{fmt(med(q)):>6}/{fmt(q[-1] if q else None):>6}")
    first = [x for x in rows if x["first"]]
    print("first legs (from the take-off, started before t0): " + ", ".join(
        f"uav {x['uav']} {shape(x)} {fmt(x['late_point_s'])} s" for x in first))
    to = takeoff_figures(log)
    print("take-off: arming to alt_m - 0.5 m: " + ", ".join(
        f"uav {x['uav']} {x['climb_s']:.1f} s" for x in to if x["climb_s"] is not None)
        + f"; allowance {log['sitl']['takeoff_allowance_s']} s; first leg began at "
        + ", ".join(f"{x['first_leg_at_s']:+.1f} s" for x in to if x["first_leg_at_s"] is not None)
        + " from t0")
    with open(os.path.join(args.work, "legs.figures.json"), "w", encoding="utf-8") as f:
        json.dump({"legs": rows, "takeoff": to}, f, indent=1)
    return 0


# --- coverage --------------------------------------------------------------------------

def scenario_set(count):
    """(uavs, need) per scenario: 3..8 UAVs, need 1 and 2 in turn."""
    return [(3 + (i % 6), 1 + (i % 2)) for i in range(count)]


def run_results(args):
    os.makedirs(args.work, exist_ok=True)
    rows = []
    slack, late, lat_replan, lat_upload = [], 0, [], []
    for i, (uavs, need) in enumerate(scenario_set(args.count)):
        name = f"s{i:02d}_{uavs}u_n{need}"
        path = os.path.join(args.work, name + ".json")
        targets = min(10, 2 * uavs)
        r = tool("gen", "--targets", targets, "--uavs", uavs, "--events", args.events, "--need", need,
                 "--width", "10:20", "--max-coord", "8", "--fuel", "400", "--seed", args.seed + i,
                 "--kinds", "uav_lost,uav_back,target_added,target_cancelled,fuel", "--name", name,
                 "-o", path)
        if r.returncode != 0:
            print(r.stderr, file=sys.stderr)
            return 1
        with open(path, encoding="utf-8") as f:
            scenario = json.load(f)
        # sim and SITL fly the same mission: the copter's take-off in the default frame
        mission = scenario["mission"]
        mission["takeoff_ticks"] = TAKEOFF_TICKS
        with open(path, "w", encoding="utf-8") as f:
            json.dump(scenario, f)
        mpath = os.path.join(args.work, name + ".mission.json")
        with open(mpath, "w", encoding="utf-8") as f:
            json.dump(mission, f)
        sim_log = os.path.join(args.work, name + ".sim.json")
        sitl_log = os.path.join(args.work, name + ".sitl.json")
        ref_plan = os.path.join(args.work, name + ".ref.json")
        if not os.path.exists(sim_log):
            r = tool("sim", path, "--algo", args.algo, "--out", sim_log)
            if r.returncode != 0:
                print(f"{name}: sim: {r.stderr.strip()}", file=sys.stderr)
                continue
        if not os.path.exists(ref_plan):
            tool("ref", mpath, "--det-limit", "10", "-o", ref_plan)
        t = time.monotonic()
        if not os.path.exists(sitl_log):
            r = tool("sitl", path, "--algo", args.algo, "--speedup", args.speedup, "--out", sitl_log,
                     "--quiet")
            if r.returncode != 0:
                print(f"{name}: sitl: {r.stderr.strip()}", file=sys.stderr)
                continue
        wall = time.monotonic() - t
        with open(sim_log, encoding="utf-8") as f:
            sim = json.load(f)["summary"]
        with open(sitl_log, encoding="utf-8") as f:
            log = judge.judge_log(json.load(f))  # judged again: the judge's current rules
        s = log["summary"]
        ref = None
        if os.path.exists(ref_plan):
            with open(ref_plan, encoding="utf-8") as f:
                ref = json.load(f).get("covered")
        vs = [v["slack_s"] for u in log["uavs"] for v in u["visits"] if v["sent"]]
        slack += vs
        late += s["late_arrivals"]
        for x in log["sitl"]["losses"]:
            if x["replan_ms"] is not None:
                lat_replan.append(x["replan_ms"] / 1000.0)
            if x["upload_ms"] is not None:
                lat_upload.append(x["upload_ms"] / 1000.0)
        rows.append((name, uavs, need, len(mission["targets"]), s, sim, ref, vs, log["sitl"]["wall_s"], wall))
        print(f"{name}: sitl {s['covered']}/{s['coverable']} (promised {s['promised']}), sim "
              f"{sim['covered']}/{sim['coverable']}, ref {ref}/{len(mission['targets'])}", file=sys.stderr)
    print("| scenario | UAVs | need | targets | SITL covered / coverable (promised) | sim covered / "
          "coverable | ref covered at t0 | slack p50 / p1 (s) | late | flight (s wall) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    tot = [0, 0, 0, 0, 0, 0]
    for name, uavs, need, nt, s, sim, ref, vs, flight_s, _wall in rows:
        p50, p1 = percentile(vs, 50), percentile(vs, 1)
        print(f"| {name} | {uavs} | {need} | {nt} | {s['covered']} / {s['coverable']} ({s['promised']}) | "
              f"{sim['covered']} / {sim['coverable']} | {ref if ref is not None else '-'} | "
              f"{'-' if p50 is None else f'{p50:.1f}'} / {'-' if p1 is None else f'{p1:.1f}'} | "
              f"{s['late_arrivals']} | {flight_s:.0f} |")
        tot = [a + b for a, b in zip(tot, [s["covered"], s["coverable"], s["promised"], sim["covered"],
                                            sim["coverable"], ref or 0])]
    print(f"\nall: SITL covered {tot[0]} of {tot[1]} coverable (promised {tot[2]}); sim {tot[3]} of "
          f"{tot[4]}; ref at t0 {tot[5]}")
    p = lambda v, q: "-" if percentile(v, q) is None else f"{percentile(v, q):.1f}"  # noqa: E731
    print(f"arrival slack p50 {p(slack, 50)} s, p1 {p(slack, 1)} s over {len(slack)} visits; late "
          f"arrivals {late}")
    print(f"loss to replan p50 {p(lat_replan, 50)} s, p99 {p(lat_replan, 99)} s; loss to re-upload "
          f"p50 {p(lat_upload, 50)} s, p99 {p(lat_upload, 99)} s (vehicle time, {len(lat_upload)} "
          f"loss{'' if len(lat_upload) == 1 else 'es'} with an upload)")
    return 0


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    what = ap.add_mutually_exclusive_group(required=True)
    what.add_argument("--legs", action="store_true", help="leg timing against the plan's grid")
    what.add_argument("--results", action="store_true", help="coverage: SITL, sim, ref")
    ap.add_argument("--uavs", type=int, default=3, help="--legs: vehicles (default 3)")
    ap.add_argument("--count", type=int, default=6, help="--results: scenarios (default 6)")
    ap.add_argument("--events", type=int, default=3, help="--results: events per scenario (default 3)")
    ap.add_argument("--seed", type=int, default=1, help="--results: gen's first seed (default 1)")
    ap.add_argument("--algo", default="sva", help="the node's algorithm (default sva)")
    ap.add_argument("--speedup", type=float, default=10.0, help="SITL speedup (default 10)")
    ap.add_argument("--frame", default=None, help="--legs: sva-tools sitl --frame (default its own)")
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "sitl_bench"),
                    help="scenarios and logs (default build/sitl_bench/)")
    ap.add_argument("--write", action="store_true",
                    help="also write the figures to docs/results/ (sitl.md, or sitl.legs.md)")
    args = ap.parse_args(argv)
    if not args.write:
        return run_legs(args) if args.legs else run_results(args)
    load_start = " ".join(f"{x:.2f}" for x in os.getloadavg())
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        rc = run_legs(args) if args.legs else run_results(args)
    print(out.getvalue(), end="")
    if rc == 0:
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        import results as page  # tools/bench/results.py
        argv_shown = " ".join(a for a in (argv if argv is not None else sys.argv[1:]))
        cmd = f".venv/bin/python tools/bench/sitl_bench.py {argv_shown}"
        if args.legs:
            title, name = "Leg timing against the plan's grid", "sitl.legs"
            intro = ("Three UAVs fly chains of legs whose windows leave no slack (`--legs`: the "
                     "grid's arrival is the window's start), with the default frame and the bridge "
                     "commanding 10 m/s. Lateness = arrival - the grid's arrival, vehicle clock, at "
                     "the waypoint (within 2 m) and into the coverage radius (docs/sitl.md).")
        else:
            title, name = None, "sitl"
            intro = ("Scenarios from `sva-tools gen --events` (3 to 8 UAVs, need 1 and 2 in turn) "
                     "flown by `sva-tools sitl` (one ArduCopter SITL process per UAV, sva_node and "
                     "the bridge over LCM), by `sva-tools sim` (the same planner, the simulator's "
                     "physics) and solved at tick 0 by `sva-tools ref` (the optimum without events). "
                     "Coverage in SITL is judged from the vehicles' telemetry (docs/sitl.md).")
        body = intro + "\n\n```\n" + out.getvalue().strip("\n") + "\n```\n" \
            if args.legs else intro + "\n\n" + out.getvalue()
        page.write(ROOT, name, cmd, body, title=title, load_start=load_start)
    return rc


if __name__ == "__main__":
    sys.exit(main())
