"""An independent checker of `sva-tools sim` flight logs (docs/live.md), for the tests.

It shares no code with tools/sva_tools/sim.py: it rebuilds what it needs from the
scenario stored in the log (the mission and the events) and the SPEC text, and judges:

- service: each UAV has a track entry for exactly the ticks it is in service (from the
  scenario's uav_lost / uav_back events), from 0 to end_tick, and `out` says the same;
  it starts where the mission (or its uav_back event) puts it, and stands where a
  position event puts it at that event's tick.
- movement: between consecutive ticks a UAV moves 0 or 1 cell (Manhattan; a position
  event may move it anywhere, and its next step may start then), and two
  moves within one stretch in service are at least ticks_per_cell ticks apart (the first
  at least ticks_per_cell after the stretch starts, or after the mission's ready_at).
- take-off (SPEC 12.2, the mission's takeoff_ticks k): a UAV back in service at tick b
  starts no step before b + k; a UAV resting at the depot (there since tick a, or free to
  leave from a) that a replan at r > a routes again starts no step before r + k.
- visits: a visit's UAV stands on the target's cell from `arrived` to `left`, arrived by
  the start, and leaves at the end, or earlier only when the target was cancelled or
  lost or the UAV itself was lost then.
- fuel: never negative; from one tick to the next it drops by exactly 1 for each step
  that starts then (a step started at t shows as a move at t + ticks_per_cell; a step cut
  short by the UAV's loss may be paid without a move) plus hover_fuel for each visit
  whose window starts then; a fuel event sets the reading before the tick's steps (it
  may count the hover fuel of a window starting then: that is paid before events).
- coverage: a target is covered iff it was not cancelled and exactly `need` UAVs stand in
  service on its cell for every tick of [start, end); `served_by` lists the UAVs there
  for the whole window; the summary counts agree.
- replans: one at tick 0 (cause "start") and one at each tick with events; each plan
  passes `sva-tools check` on its residual mission; its changes are the (UAV, target)
  pairs of the residual mission the previous plan had and it drops, or it adds; and
  the never-fewer rule: a replan
  covers no fewer targets than the previous plan's visits of the new residual mission
  still could (those visits pruned by SPEC 12.4 step 2, recomputed here).
- the end: every UAV in service is at the depot (or has no fuel) at end_tick.

check_flight(log) returns the list of violations (empty: the log is right).
"""
from __future__ import annotations

from typing import Dict, List, Optional, Set, Tuple

from sva_tools import check
from sva_tools import io


def _dist(a: Tuple[int, int], b: Tuple[int, int]) -> int:
    return abs(a[0] - b[0]) + abs(a[1] - b[1])


class _T:
    def __init__(self, d: dict):
        self.id, self.x, self.y = d["id"], d["x"], d["y"]
        self.start, self.end, self.need = d["start"], d["end"], d["need"]
        self.cell = (self.x, self.y)


def _service(uav0: dict, events: List[dict], end: int) -> Tuple[Set[int], Dict[int, tuple]]:
    """Ticks in service and, per stretch start, (x, y, fuel) it starts with."""
    starts = {0: (uav0["x"], uav0["y"], uav0["fuel"])}
    ticks: Set[int] = set()
    on, since = True, 0
    for e in events:
        if e.get("uav") != uav0["id"]:
            continue
        if e["type"] == "uav_lost" and on:
            ticks.update(range(since, e["at"]))
            on = False
        elif e["type"] == "uav_back" and not on:
            on, since = True, e["at"]
            starts[e["at"]] = (e["x"], e["y"], e["fuel"])
    if on:
        ticks.update(range(since, end + 1))
    return ticks, starts


def uav0_ready(u0: dict) -> int:
    return u0.get("ready_at", 0)


def carried_covered(prev_plan: dict, residual: dict, backs: Set[int]) -> int:
    """SPEC 12.4 step 2: the previous plan's visits of the residual targets, pruned until
    every visit left fits (no UAV late or short of fuel home; whole needs only); the
    number of targets it covers. UAVs in `backs` came back since: they have no visits."""
    tm = {t["id"]: _T(t) for t in residual["targets"]}
    depot = (residual["depot"]["x"], residual["depot"]["y"])
    tpc = residual.get("ticks_per_cell", 1)
    hover = residual.get("hover_fuel", 0)
    prev = {r["uav"]: r["targets"] for r in prev_plan["routes"]}
    uavs = residual["uavs"]
    routes = {}
    for u in uavs:
        stranded = u["fuel"] < _dist((u["x"], u["y"]), depot)
        keep = [] if (u["id"] in backs or stranded) else prev.get(u["id"], [])
        routes[u["id"]] = [t for t in keep if t in tm]

    def drop(tid: int) -> None:
        for k in routes:
            routes[k] = [t for t in routes[k] if t != tid]

    while True:
        count: Dict[int, int] = {}
        for r in routes.values():
            for t in r:
                count[t] = count.get(t, 0) + 1
        short = [t for t, n in count.items() if n != tm[t].need]
        for t in short:
            drop(t)
        if short:
            continue
        misfit = None
        for u in uavs:
            pos, free, fuel = (u["x"], u["y"]), u.get("ready_at", 0), u["fuel"]
            for tid in routes[u["id"]]:
                t = tm[tid]
                cells = _dist(pos, t.cell)
                fuel -= cells + hover
                if free + cells * tpc > t.start or fuel < _dist(t.cell, depot):
                    misfit = tid
                    break
                pos, free = t.cell, t.end
            if misfit is not None:
                break
        if misfit is None:
            break
        drop(misfit)
    count = {}
    for r in routes.values():
        for t in r:
            count[t] = count.get(t, 0) + 1
    return sum(1 for t, n in count.items() if n == tm[t].need)


def check_flight(log: dict) -> List[str]:
    v: List[str] = []
    sc = log["scenario"]
    mission = sc["mission"]
    events = sc["events"]
    tpc = mission.get("ticks_per_cell", 1)
    hover = mission.get("hover_fuel", 0)
    takeoff = mission.get("takeoff_ticks", 0)
    routed_at = [(r["at"], {x["uav"] for x in r["plan"].get("routes", []) if x["targets"]})
                 for r in log.get("replans", [])]
    depot = (mission["depot"]["x"], mission["depot"]["y"])
    end = log["end_tick"]

    targets = {t["id"]: _T(t) for t in mission["targets"]}
    cancelled: Dict[int, int] = {}
    for e in events:
        if e["type"] in ("target_added", "target_changed"):
            targets[e["target"]["id"]] = _T(e["target"])
        elif e["type"] == "target_cancelled":
            cancelled[e["target"]] = e["at"]
    fuel_at: Dict[Tuple[int, int], int] = {}
    lost_at: Dict[int, List[int]] = {}
    seen_at: Dict[Tuple[int, int], Tuple[int, int]] = {}   # position events
    moved_at: Dict[int, List[int]] = {}
    for e in events:
        if e["type"] in ("fuel", "position"):
            fuel_at[(e["uav"], e["at"])] = e["fuel"]
        if e["type"] == "position":
            seen_at[(e["uav"], e["at"])] = (e["x"], e["y"])
            moved_at.setdefault(e["uav"], []).append(e["at"])
        elif e["type"] == "uav_lost":
            lost_at.setdefault(e["uav"], []).append(e["at"])

    logged = {u["id"]: u for u in log["uavs"]}
    if sorted(logged) != sorted(u["id"] for u in mission["uavs"]):
        v.append(f"uavs: logged {sorted(logged)}, mission has {[u['id'] for u in mission['uavs']]}")
        return v
    pos: Dict[int, Dict[int, Tuple[int, int]]] = {}
    lost_targets: Set[int] = set()
    for u0 in mission["uavs"]:
        uid = u0["id"]
        u = logged[uid]
        w = f"uav {uid}"
        ticks, starts = _service(u0, events, end)
        track = {e[0]: e for e in u["track"]}
        if len(track) != len(u["track"]) or set(track) != ticks:
            extra = sorted(set(track) - ticks)[:5]
            missing = sorted(ticks - set(track))[:5]
            v.append(f"{w}: track ticks differ from its service (extra {extra}, missing {missing})")
            continue
        outs = [[e["at"], None] for e in events if e.get("uav") == uid and e["type"] == "uav_lost"]
        backs = [e["at"] for e in events if e.get("uav") == uid and e["type"] == "uav_back"]
        for k, b in enumerate(backs[:len(outs)]):
            outs[k][1] = b
        if [list(o) for o in u["out"]] != outs:
            v.append(f"{w}: out is {u['out']}, the events say {outs}")
        p = {t: (e[1], e[2]) for t, e in track.items()}
        pos[uid] = p
        # Visits, checked against the track and the events.
        hover_ticks: Dict[int, int] = {}
        for vis in u["visits"]:
            t = targets.get(vis["target"])
            if t is None:
                v.append(f"{w}: visit of unknown target {vis['target']}")
                continue
            a, left = vis["arrived"], vis["left"]
            # Lost there, or seen off the cell (a position event) at `left`.
            lost_here = (left in lost_at.get(uid, []) or
                         (uid, left) in seen_at and seen_at[(uid, left)] != t.cell)
            stay_to = left - 1 if lost_here else left
            if a > t.start or left is None or left > t.end or left < t.start:
                v.append(f"{w}: visit of target {t.id} from {a} to {left} does not hold its "
                         f"window [{t.start}, {t.end})")
                continue
            if any(p.get(k) != t.cell for k in range(a, stay_to + 1)):
                v.append(f"{w}: not on target {t.id}'s cell {t.cell} for its whole visit "
                         f"[{a}, {left}]")
            early = left < t.end
            if early and not (lost_here or cancelled.get(t.id) == left or
                              any(left in lost_at.get(o, []) + moved_at.get(o, [])
                                  for o in logged if o != uid)):
                v.append(f"{w}: left target {t.id} at {left}, before its end {t.end}, "
                         f"with no cancellation or loss then")
            if early and cancelled.get(t.id) != left:
                lost_targets.add(t.id)
            if t.start in ticks:
                hover_ticks[t.start] = hover_ticks.get(t.start, 0) + 1
        # Movement and fuel, tick by tick.
        last_move: Optional[int] = None
        prev_fuel: Optional[int] = None
        rest_from: Optional[int] = None  # resting at the depot since (or free from) then
        for t in sorted(ticks):
            x, y, f = track[t][1], track[t][2], track[t][3]
            if f < 0:
                v.append(f"{w}: fuel {f} < 0 at tick {t}")
            if t in starts:
                sx, sy, sf = starts[t]
                if (x, y) != (sx, sy):
                    v.append(f"{w}: at {(x, y)} at tick {t}, must start at {(sx, sy)}")
                # The first step may start at t (at tick 0: at the UAV's ready_at; back in
                # service: after its take-off).
                free = uav0_ready(u0) if t == 0 else t + takeoff
                last_move = free - tpc
                rest_from = free if (sx, sy) == depot else None
                prev_fuel = sf
            elif (uid, t) in seen_at:
                if (x, y) != seen_at[(uid, t)]:
                    v.append(f"{w}: at {(x, y)} at tick {t}, a position event puts it at "
                             f"{seen_at[(uid, t)]}")
                last_move = t - tpc  # its next step may start now
                rest_from = t if (x, y) == depot else None
            else:
                d = _dist(p[t - 1], (x, y))
                if d > 1:
                    v.append(f"{w}: moves {d} cells from tick {t - 1} to {t} (teleport)")
                if d == 1:
                    if last_move is not None and t - last_move < tpc:
                        v.append(f"{w}: moves at {last_move} and {t}, less than "
                                 f"ticks_per_cell ({tpc}) apart")
                    if p[t - 1] == depot and rest_from is not None and takeoff > 0:
                        step = t - tpc  # the step that shows now started then
                        r0 = next((r for r, uids in routed_at
                                   if rest_from < r <= step and uid in uids), None)
                        if r0 is not None and step < r0 + takeoff:
                            v.append(f"{w}: leaves the depot at {step}, routed at {r0} after "
                                     f"landing by {rest_from}: take-off ({takeoff}) not flown")
                    rest_from = t if (x, y) == depot else None
                    last_move = t
            if (uid, t) in fuel_at:
                prev_fuel = fuel_at[(uid, t)]
            later = t + tpc
            # A loss before the step would end cuts it short (a return may follow).
            cut = any(t < lt <= later for lt in lost_at.get(uid, []))
            moves = 1 if (not cut and later in p and later - 1 in p and
                          p[later] != p[later - 1]) else 0
            want = moves + hover * hover_ticks.get(t, 0)
            paid = prev_fuel - f
            ok = {want, want + 1} if cut else {want}
            if any(t < st <= later for st in moved_at.get(uid, [])):
                # A position event before the step would end: the track cannot tell
                # whether a step started.
                ok = {want - moves, want - moves + 1}
            if (uid, t) in fuel_at:
                # A reading at the start of a window the UAV already hovers over counts
                # the hover fuel paid then (it is paid before the tick's events).
                ok |= {x - hover * hover_ticks.get(t, 0) for x in ok}
            if paid not in ok:
                v.append(f"{w}: fuel drops by {paid} at tick {t}, the flight pays {want} "
                         f"({moves} step(s), {hover_ticks.get(t, 0)} window(s) starting)")
            prev_fuel = f
        if end in ticks and p[end] != depot and track[end][3] > 0:
            v.append(f"{w}: ends at {p[end]}, not at the depot {depot}, with fuel left")

    # Coverage.
    if sorted(t["id"] for t in log["targets"]) != sorted(targets):
        v.append(f"targets: logged {sorted(t['id'] for t in log['targets'])}, the scenario "
                 f"has {sorted(targets)}")
    covered = 0
    out_of_reach = 0
    for lt in log["targets"]:
        t = targets.get(lt["id"])
        if t is None:
            continue
        there = sorted(uid for uid, p in pos.items()
                       if all(p.get(k) == t.cell for k in range(t.start, t.end)))
        ok = t.id not in cancelled and len(there) == t.need
        covered += ok
        if lt["covered"] != ok:
            v.append(f"target {t.id}: covered is {lt['covered']}, the tracks say {ok} "
                     f"({len(there)} of {t.need} UAVs for the whole window"
                     f"{', cancelled' if t.id in cancelled else ''})")
        if sorted(lt["served_by"]) != there:
            v.append(f"target {t.id}: served_by is {sorted(lt['served_by'])}, "
                     f"the tracks say {there}")
        outcome = lt.get("outcome")
        if outcome == "cancelled" and t.id not in cancelled:
            v.append(f"target {t.id}: outcome cancelled, but no event cancels it")
        if outcome == "lost" and t.id not in lost_targets:
            v.append(f"target {t.id}: outcome lost, but no visit of it was cut by a loss")
        out_of_reach += outcome in ("cancelled", "lost")
    s = log["summary"]
    if s["covered"] != covered:
        v.append(f"summary.covered is {s['covered']}, the tracks say {covered}")
    if s["coverable"] != len(targets) - out_of_reach:
        v.append(f"summary.coverable is {s['coverable']}, targets less cancelled and lost "
                 f"are {len(targets) - out_of_reach}")

    # Replans.
    want_at = sorted({0} | {e["at"] for e in events})
    got_at = [r["at"] for r in log["replans"]]
    if got_at != want_at:
        v.append(f"replans at ticks {got_at}, must be at 0 and at each tick with events {want_at}")
    if log["replans"] and log["replans"][0]["cause"] != "start":
        v.append(f"replans[0].cause is {log['replans'][0]['cause']!r}, must be 'start'")
    prev = None
    for k, r in enumerate(log["replans"]):
        try:
            m = io.mission_from_json(r["mission"])
            p = io.plan_from_json(r["plan"])
        except io.InputError as e:
            v.append(f"replans[{k}] (tick {r['at']}): not a valid mission or plan: {e}")
            prev = None
            continue
        for msg in check.check_plan(m, p):
            v.append(f"replans[{k}] (tick {r['at']}): sva-tools check: {msg}")
        if prev is not None:
            backs = {e["uav"] for e in events
                     if e["type"] == "uav_back" and prev["at"] < e["at"] <= r["at"]}
            uids = {u["id"] for u in r["mission"]["uavs"]}
            tids = {t["id"] for t in r["mission"]["targets"]}
            before = {(x["uav"], t) for x in prev["plan"]["routes"]
                      if x["uav"] in uids and x["uav"] not in backs
                      for t in x["targets"] if t in tids}
            now = {(x["uav"], t) for x in r["plan"]["routes"] for t in x["targets"]}
            ch = r.get("changes") or {}
            if ({tuple(p) for p in ch.get("dropped", [])} != before - now or
                    {tuple(p) for p in ch.get("added", [])} != now - before or
                    ch.get("count") != len(before ^ now)):
                v.append(f"replans[{k}] (tick {r['at']}): changes {ch.get('dropped')} dropped, "
                         f"{ch.get('added')} added; the plans say {sorted(before - now)} "
                         f"dropped, {sorted(now - before)} added")
            could = carried_covered(prev["plan"], r["mission"], backs)
            if p.covered < could:
                v.append(f"replans[{k}] (tick {r['at']}): covers {p.covered} residual targets, "
                         f"the previous plan's visits still could cover {could}")
        prev = r
    return v
