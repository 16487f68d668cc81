"""`sva-tools sim SCENARIO.json [--algo A] [--out LOG.json] [--plot FILE.png]`: a live
mission flown tick by tick as ground truth, steered by the on-board planner.

The scenario is `{"mission": MISSION, "events": [EVENT, ...], "change_penalty": N}`
(the last optional). This module flies its own physics (SPEC section 12.2): a UAV flies
each leg x first, then y, one cell per ticks_per_cell ticks, paying 1 fuel when a cell's
step starts; it waits at a target until its start, pays hover_fuel at the start and
leaves at the end; arriving after a start it does not stop; a step in progress is
finished before new orders; with no orders it flies home. A lost UAV vanishes at its
event and reappears on uav_back. A position event puts a UAV in service on its cell
with its fuel (blown off course), a step in progress dropped; off its target's cell
during a visit, it breaks the visit as a loss there would.

At tick 0 (cause "start") and at every tick with events (after applying them) it runs
the C CLI's `sva replan` over the whole history (mission, events so far, now) and gives
every UAV in service the new plan's route as its orders. With `--via lcm` the planner
is a real sva_node over LCM instead (sva_tools.lcm.simnode, in a network namespace of
its own; root); `--kill-node N` then kills it N times with SIGKILL at seeded moments
(`--seed`) and starts it again on its journal (`--state-dir`): it must resume by itself,
and the flight log lists the kills (`node_kills`). It stops when every UAV in
service is home with no orders (or out of fuel) and no window or event is left. The
flight log (docs/live.md) is JSON: tracks, visits, every target's outcome, every
replan with its residual mission and plan, and a summary.

Order of work within tick t: steps ending at t complete and visits ending at t end;
UAVs standing at their next target at its start begin to hover (hover_fuel paid); the
events at t are applied and the planner replans; then every free UAV takes its next
step (its fuel paid). A track entry [t, x, y, fuel] is the state after all of that.
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Tuple

from . import cbin
from . import io
from . import model as M

EVENT_TYPES = ("clock", "uav_lost", "uav_back", "fuel", "target_added", "target_cancelled",
               "target_changed", "position")
OUTCOMES = ("covered", "uncovered", "cancelled", "lost")


class SimError(Exception):
    """The planner refused the scenario (an event it rejects) or failed; `status` is the
    exit status to return (2: a bad scenario or event)."""

    def __init__(self, message: str, status: int = 2):
        super().__init__(message)
        self.status = status


@dataclass
class Craft:
    """One UAV as flown."""
    id: int
    x: int
    y: int
    fuel: int
    in_service: bool = True
    orders: List[int] = field(default_factory=list)
    step_to: Optional[Tuple[int, int]] = None
    step_end: int = 0
    hover: Optional[int] = None       # target id it hovers over until the window ends
    free_at: int = 0                  # it may not leave before (the mission's ready_at)
    arrived: int = 0                  # tick it reached its current cell
    out: List[list] = field(default_factory=list)
    track: List[list] = field(default_factory=list)
    visits: List[dict] = field(default_factory=list)
    cells: int = 0


def _target(doc: dict, where: str) -> M.Target:
    """A target in mission JSON form, through the mission parser's own checks."""
    m = io.mission_from_json({"name": where, "depot": {"x": 0, "y": 0}, "uavs": [],
                              "targets": [doc]})
    return m.targets[0]


def parse_scenario(doc) -> Tuple[M.Mission, List[dict], Optional[int]]:
    """The mission, the events and the change penalty of a scenario document. The shape
    is checked here; whether each event may be applied is the planner's to judge."""
    if not isinstance(doc, dict):
        raise io.InputError("file: must be a JSON object")
    io.wrong_kind(doc, "scenario",
                  "sva-tools sim takes a scenario (mission, events, change_penalty; SPEC 12.5)")
    for k in doc:
        if k not in ("mission", "events", "change_penalty"):
            raise io.InputError(f"{k}: unknown key")
    for k in ("mission", "events"):
        if k not in doc:
            raise io.InputError(f"{k}: missing key")
    mdoc = doc["mission"]
    if isinstance(mdoc, dict) and "change_penalty" in mdoc:
        raise io.InputError("mission.change_penalty: give it at the top level of the scenario")
    try:
        mission = io.mission_from_json(mdoc)
    except io.InputError as e:
        msg = str(e)
        raise io.InputError(msg if msg.startswith("mission") else f"mission.{msg}") from None
    penalty = doc.get("change_penalty")
    if penalty is not None and (not isinstance(penalty, int) or isinstance(penalty, bool)
                                or penalty < 0):
        raise io.InputError(f"change_penalty: must be an integer >= 0, got {json.dumps(penalty)}")
    events = doc["events"]
    if not isinstance(events, list):
        raise io.InputError("events: must be a JSON array")
    for i, e in enumerate(events):
        w = f"events[{i}]"
        if not isinstance(e, dict):
            raise io.InputError(f"{w}: must be a JSON object")
        if e.get("type") not in EVENT_TYPES:
            raise io.InputError(f"{w}.type: must be one of {', '.join(EVENT_TYPES)}, "
                                f"got {json.dumps(e.get('type'))}")
        at = e.get("at")
        if not isinstance(at, int) or isinstance(at, bool) or at < 0:
            raise io.InputError(f"{w}.at: must be an integer >= 0, got {json.dumps(at)}")
    return mission, events, penalty


def load_scenario(path: str):
    try:
        return parse_scenario(io.read_json(path))
    except io.InputError as e:
        e.path = path
        raise


# --- the planner ---------------------------------------------------------------------

def replan(mission_doc: dict, events: List[dict], now: int, algo: str,
           timeout: float = 600) -> Tuple[dict, dict]:
    """`sva replan --algo ALGO --residual R LIVE.json` over the history; returns (the
    printed plan with its changes and live keys, the residual mission)."""
    exe = cbin.sva_bin()
    with tempfile.TemporaryDirectory(prefix="sva-sim-") as d:
        live = os.path.join(d, "live.json")
        res = os.path.join(d, "residual.json")
        io.write_json({"mission": mission_doc, "events": events, "now": now}, live)
        r = subprocess.run([str(exe), "replan", "--algo", algo, "--residual", res, live],
                           capture_output=True, text=True, timeout=timeout)
        if r.returncode != 0:
            lines = [ln for ln in r.stderr.strip().splitlines() if ln.strip()]
            msg = lines[-1] if lines else f"exit {r.returncode}"
            if msg.startswith("sva: error: "):
                msg = msg[len("sva: error: "):]
            raise SimError(f"tick {now}: sva replan: {msg}",
                           2 if r.returncode == 2 else 1)
        out = json.loads(r.stdout)
        with open(res, encoding="utf-8") as f:
            residual = json.load(f)
    return out, residual


# --- the flight ----------------------------------------------------------------------

def _toward(x: int, y: int, tx: int, ty: int) -> Tuple[int, int]:
    """The next cell from (x, y) towards (tx, ty): x first, then y."""
    if x != tx:
        return (x + (1 if tx > x else -1), y)
    return (x, y + (1 if ty > y else -1))


class Flight:
    def __init__(self, mission: M.Mission, events: List[dict], penalty: Optional[int],
                 algo: str, planner=replan):
        self.m = mission
        self.events = events
        self.penalty = penalty
        self.algo = algo
        self.planner = planner
        self.crafts = [Craft(u.id, u.x, u.y, u.fuel, free_at=u.ready_at) for u in mission.uavs]
        self.by_id = {c.id: c for c in self.crafts}
        self.targets: Dict[int, M.Target] = {t.id: t for t in mission.targets}
        self.order = [t.id for t in mission.targets]   # first appearance
        self.outcome: Dict[int, str] = {}               # cancelled / lost, decided early
        self.replans: List[dict] = []
        self.tpc = mission.ticks_per_cell

    # The mission document the planner reads: the mission as at tick 0.
    def mission_doc(self) -> dict:
        doc = self.m.to_json()
        if self.penalty is not None:
            doc["change_penalty"] = self.penalty
        return doc

    def _end_hover(self, c: Craft, t: int) -> None:
        c.visits[-1]["left"] = t
        c.hover = None

    def _phase_arrivals(self, t: int) -> None:
        for c in self.crafts:
            if not c.in_service:
                continue
            if c.step_to is not None and c.step_end == t:
                c.x, c.y = c.step_to
                c.step_to = None
                c.cells += 1
                c.arrived = t
            if c.hover is not None and self.targets[c.hover].end <= t:
                self._end_hover(c, t)
            self._maybe_hover(c, t)

    def _maybe_hover(self, c: Craft, t: int) -> None:
        if c.step_to is not None or c.hover is not None or not c.orders or t < c.free_at:
            return
        tg = self.targets[c.orders[0]]
        if (c.x, c.y) == (tg.x, tg.y) and t == tg.start:
            c.orders.pop(0)
            c.hover = tg.id
            c.fuel -= self.m.hover_fuel
            c.visits.append({"target": tg.id, "arrived": c.arrived, "left": None})

    def _free_target(self, tid: int, t: int, outcome: str) -> None:
        self.outcome[tid] = outcome
        for c in self.crafts:
            if c.in_service and c.hover == tid:
                self._end_hover(c, t)
            if tid in c.orders:
                c.orders.remove(tid)

    def _apply(self, e: dict, t: int) -> None:
        kind = e["type"]
        if kind == "uav_lost":
            c = self.by_id[e["uav"]]
            tid = c.hover
            if tid is not None:
                # SPEC 12.1: a visit under way (every UAV sent there hovering) is lost.
                hovering = sum(1 for o in self.crafts if o.in_service and o.hover == tid)
                self._end_hover(c, t)
                if hovering >= self.targets[tid].need:
                    self._free_target(tid, t, "lost")
            c.in_service = False
            c.step_to = None
            c.orders = []
            c.out.append([t, None])
        elif kind == "uav_back":
            c = self.by_id[e["uav"]]
            c.in_service = True
            c.x, c.y, c.fuel = e["x"], e["y"], e["fuel"]
            # on the ground where it is: it takes off before it leaves (SPEC 12.2)
            c.orders, c.step_to, c.hover, c.arrived = [], None, None, t
            c.free_at = t + self.m.takeoff_ticks
            c.out[-1][1] = t
        elif kind == "fuel":
            self.by_id[e["uav"]].fuel = e["fuel"]
        elif kind == "position":
            c = self.by_id[e["uav"]]
            tid = c.hover
            cell = (e["x"], e["y"])
            if tid is not None and cell == (self.targets[tid].x, self.targets[tid].y):
                c.fuel = e["fuel"]  # on station: the visit goes on
                return
            if tid is not None:
                # Off station during its visit: broken, as by a loss there.
                hovering = sum(1 for o in self.crafts if o.in_service and o.hover == tid)
                self._end_hover(c, t)
                if hovering >= self.targets[tid].need:
                    self._free_target(tid, t, "lost")
            (c.x, c.y), c.fuel = cell, e["fuel"]
            c.step_to, c.arrived, c.free_at = None, t, t
        elif kind in ("target_added", "target_changed"):
            tg = _target(e["target"], "event")
            if tg.id not in self.targets:
                self.order.append(tg.id)
            self.targets[tg.id] = tg
        elif kind == "target_cancelled":
            self._free_target(e["target"], t, "cancelled")

    def _step(self, c: Craft, t: int, dest: Tuple[int, int]) -> None:
        if c.fuel < 1 or t < c.free_at:
            return  # an empty tank, or not ready yet: it stays where it is
        c.fuel -= 1
        c.step_to = _toward(c.x, c.y, *dest)
        c.step_end = t + self.tpc

    def _phase_orders(self, t: int) -> None:
        for c in self.crafts:
            if not c.in_service or c.step_to is not None:
                continue
            self._maybe_hover(c, t)
            if c.hover is not None:
                continue
            while c.orders:
                tg = self.targets[c.orders[0]]
                if (c.x, c.y) != (tg.x, tg.y):
                    self._step(c, t, (tg.x, tg.y))
                    break
                if t < tg.start:
                    break  # waits for its start
                c.orders.pop(0)  # arrived after the start: it does not stop
            else:
                if (c.x, c.y) != self.m.depot:
                    self._step(c, t, self.m.depot)

    def _replan(self, t: int, cause: str, history: List[dict], now_events: List[dict]) -> None:
        # The planner judges the events before the flight takes them: a rejected one
        # stops the flight (SimError) with nothing applied.
        out, residual = self.planner(self.mission_doc(), list(history), t, self.algo)
        for e in now_events:
            self._apply(e, t)
        cli_changes = out.pop("changes", None)
        live = out.pop("live", None)
        node = out.pop("node", None)
        solve_us = (out.get("stats") or {}).get("solve_us")
        changes = self._changes(residual, out, now_events, cli_changes)
        rec = {"at": t, "cause": cause, "mission": residual, "plan": out,
               "changes": changes, "solve_us": solve_us, "live": live}
        if node is not None:
            rec["node"] = node  # --via lcm: the node's plan id and every message's round trip
        self.replans.append(rec)
        routes = {r["uav"]: list(r["targets"]) for r in out.get("routes", [])}
        for c in self.crafts:
            if c.in_service:
                new = routes.get(c.id, [])
                if new and self._idle(c) and (c.x, c.y) == self.m.depot and \
                        t > max(c.arrived, c.free_at):
                    # landed at the depot: it takes off before it leaves (SPEC 12.2)
                    c.free_at = t + self.m.takeoff_ticks
                c.orders = new

    def _changes(self, residual: dict, plan: dict, now_events: List[dict],
                 cli_changes: Optional[dict]) -> dict:
        """SPEC 12.4's changed visits of this replan: (UAV, target) pairs of the residual
        mission that the plan in force had (the previous replan's plan; none for a UAV
        that came back since) and this plan drops, or that this plan adds. Recomputed
        here from consecutive plans, as the CLI's own figure describes only its last
        replan over the history."""
        if not self.replans:
            pairs_before: set = set()
        else:
            uavs = {u["id"] for u in residual.get("uavs", [])}
            targets = {t["id"] for t in residual.get("targets", [])}
            back = {e["uav"] for e in now_events if e["type"] == "uav_back"}
            pairs_before = {(r["uav"], tid) for r in self.replans[-1]["plan"]["routes"]
                            if r["uav"] in uavs and r["uav"] not in back
                            for tid in r["targets"] if tid in targets}
        pairs_now = {(r["uav"], tid) for r in plan.get("routes", []) for tid in r["targets"]}
        dropped = sorted(pairs_before - pairs_now)
        added = sorted(pairs_now - pairs_before) if self.replans else []
        count = len(dropped) + len(added)
        pen = self.penalty or 0
        out = {"dropped": [list(p) for p in dropped], "added": [list(p) for p in added],
               "count": count, "penalty": pen * count}
        if cli_changes is not None:
            out["cli"] = cli_changes
        return out

    def _idle(self, c: Craft) -> bool:
        if not c.in_service:
            return True
        if c.step_to is not None or c.hover is not None or c.orders:
            return False
        return (c.x, c.y) == self.m.depot or c.fuel < 1

    def fly(self, max_ticks: Optional[int] = None) -> dict:
        last_event = max((e["at"] for e in self.events), default=0)
        coords = [abs(v) for t in self.m.targets for v in (t.x, t.y)]
        coords += [abs(v) for u in self.m.uavs for v in (u.x, u.y)] + [abs(v) for v in self.m.depot]
        extent = 2 * max(coords + [1])
        if max_ticks is None:
            ends = [t.end for t in self.m.targets] + [0]
            for e in self.events:
                if isinstance(e.get("target"), dict):
                    ends.append(int(e["target"].get("end", 0)))
            max_ticks = max(ends + [last_event]) + 4 * extent * self.tpc + 1000
        history: List[dict] = []
        pending = list(self.events)
        t = 0
        while True:
            self._phase_arrivals(t)
            now_events = []
            while pending and pending[0]["at"] <= t:
                now_events.append(pending.pop(0))
            if now_events or t == 0:
                history += now_events
                cause = "start" if t == 0 else ",".join(e["type"] for e in now_events)
                self._replan(t, cause, history, now_events)
            self._phase_orders(t)
            for c in self.crafts:
                if c.in_service:
                    c.track.append([t, c.x, c.y, c.fuel])
            open_windows = any(tg.end > t for tid, tg in self.targets.items()
                               if self.outcome.get(tid) is None)
            if not pending and not open_windows and all(self._idle(c) for c in self.crafts):
                return self._log(t)
            t += 1
            if t > max_ticks:
                raise SimError(f"the flight did not end by tick {max_ticks}", 1)

    # --- the log ---------------------------------------------------------------------

    def _served_by(self, tg: M.Target) -> List[int]:
        """UAVs in service at the target's cell at every tick of [start, end)."""
        ids = []
        for c in self.crafts:
            at = {e[0]: (e[1], e[2]) for e in c.track}
            if all(at.get(k) == (tg.x, tg.y) for k in range(tg.start, tg.end)):
                ids.append(c.id)
        return ids

    def _log(self, end: int) -> dict:
        targets = []
        for tid in self.order:
            tg = self.targets[tid]
            served = self._served_by(tg)
            outcome = self.outcome.get(tid)
            covered = outcome is None and len(served) == tg.need
            targets.append({"id": tid, "covered": covered, "served_by": served,
                            "outcome": outcome or ("covered" if covered else "uncovered")})
        coverable = sum(1 for t in targets if t["outcome"] not in ("cancelled", "lost"))
        return {
            "scenario": self.scenario_doc(),
            "algorithm": self.algo,
            "end_tick": end,
            "uavs": [{"id": c.id, "out": c.out, "track": c.track, "visits": c.visits}
                     for c in self.crafts],
            "targets": targets,
            "replans": self.replans,
            "summary": {
                "covered": sum(1 for t in targets if t["covered"]),
                "coverable": coverable,
                "targets": len(targets),
                "distance": sum(c.cells for c in self.crafts),
                "replans": len(self.replans),
                "changes": sum(int((r["changes"] or {}).get("count", 0)) for r in self.replans),
            },
        }

    def scenario_doc(self) -> dict:
        doc = {"mission": self.m.to_json(), "events": self.events}
        if self.penalty is not None:
            doc["change_penalty"] = self.penalty
        return doc


def simulate(mission: M.Mission, events: List[dict], penalty: Optional[int] = None,
             algo: str = "sva", planner=replan) -> dict:
    """Flies the scenario and returns the flight log (raises SimError)."""
    return Flight(mission, events, penalty, algo, planner).fly()


# --- the timeline --------------------------------------------------------------------

def event_text(e: dict) -> str:
    """One line for a live event (scenario JSON; a cancelled target as its id or its
    object): the timeline's and the ground view's words."""
    k = e["type"]
    if k == "uav_lost":
        return f"uav {e['uav']} lost"
    if k == "uav_back":
        return f"uav {e['uav']} back at ({e['x']}, {e['y']}) with fuel {e['fuel']}"
    if k == "fuel":
        return f"uav {e['uav']} fuel reads {e['fuel']}"
    if k == "position":
        return f"uav {e['uav']} seen at ({e['x']}, {e['y']}) with fuel {e['fuel']}"
    if k == "target_added":
        t = e["target"]
        return (f"target {t['id']} added at ({t['x']}, {t['y']}) [{t['start']}, {t['end']}) "
                f"need {t['need']}")
    if k == "target_cancelled":
        t = e["target"]
        return f"target {t['id'] if isinstance(t, dict) else t} cancelled"
    if k == "target_changed":
        t = e["target"]
        return (f"target {t['id']} moved to ({t['x']}, {t['y']}) [{t['start']}, {t['end']}) "
                f"need {t['need']}")
    return "clock"


def timeline(log: dict) -> str:
    """One line per replan (tick, cause, targets the planner then expects covered: done
    ones included, plan cost, changed visits, kept or not, solve time) under the events
    that caused it, and the flight's summary."""
    by_tick: Dict[int, List[dict]] = {}
    for e in log["scenario"]["events"]:
        by_tick.setdefault(e["at"], []).append(e)
    w = max([len(r["cause"]) for r in log["replans"]] + [5])
    lines = [f"{'tick':>6}  {'cause':<{w}} {'covered':>7} {'cost':>6} {'changes':>7} "
             f"{'kept':>5} {'solve_us':>9}"]
    for r in log["replans"]:
        for e in by_tick.get(r["at"], []):
            lines.append(f"{e['at']:>6}  - {event_text(e)}")
        live = r.get("live") or {}
        done = sum(1 for t in live.get("targets", []) if t.get("state") == "done")
        covered = done + int(live.get("covered", r["plan"].get("covered", 0)))
        ch = r.get("changes") or {}
        kept = live.get("kept")
        lines.append(f"{r['at']:>6}  {r['cause']:<{w}} {covered:>7} {r['plan']['cost']:>6} "
                     f"{ch.get('count', 0):>7} {('-' if kept is None else str(kept).lower()):>5} "
                     f"{r['solve_us'] if r['solve_us'] is not None else '-':>9}")
    s = log["summary"]
    lines.append(f"flown to tick {log['end_tick']}: covered {s['covered']} of {s['coverable']} "
                 f"coverable ({s['targets']} targets; cancelled and lost ones are not "
                 f"coverable), {s['distance']} cells, {s['replans']} replans, "
                 f"{s['changes']} changed visits")
    return "\n".join(lines) + "\n"


# --- the command ---------------------------------------------------------------------

def add_parser(sub) -> None:
    ap = sub.add_parser("sim", help="fly a live-mission scenario, steered by `sva replan`",
                        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenario", help="SCENARIO.json: {mission, events, change_penalty}")
    ap.add_argument("--algo", default="sva", choices=list(cbin.C_ALGORITHMS),
                    help="the on-board planner's algorithm (default sva)")
    ap.add_argument("--out", help="flight log JSON (default: stdout, or none with --timeline)")
    ap.add_argument("--timeline", action="store_true",
                    help="print a timeline of events and replans on stdout instead of the log")
    ap.add_argument("--plot", metavar="FILE.png", help="also draw the flight (map and Gantt)")
    ap.add_argument("--via", choices=["cli", "lcm"], default="cli",
                    help="how the planner is reached: cli (`sva replan`, default) or lcm (a "
                         "real sva_node over LCM multicast, in a network namespace made for "
                         "the run; needs root)")
    ap.add_argument("--attach", action="store_true",
                    help="--via lcm: use the sva_node already running (started with the same "
                         "--algorithm and --change-penalty) instead of starting one, and no "
                         "namespace of its own")
    ap.add_argument("--url", default=None,
                    help="--via lcm: LCM provider (default udpm://239.255.76.67:7667?ttl=0)")
    ap.add_argument("--prefix", default=None, help="--via lcm: channel prefix (default SVA_)")
    ap.add_argument("--timeout", type=float, default=10.0,
                    help="--via lcm: seconds to wait for each answer of the node (default 10)")
    ap.add_argument("--kill-node", type=int, default=0, metavar="N",
                    help="--via lcm: SIGKILL the node N times at seeded moments of the flight and "
                         "start it again on its journal (sva_node --state-dir, a temporary folder "
                         "of the run's own); it must resume by itself (default 0)")
    ap.add_argument("--seed", type=int, default=0,
                    help="--kill-node: the seed of the moments (default 0)")
    ap.set_defaults(func=run)


def _argv(args) -> List[str]:
    """The command line of this run, for its re-execution inside a network namespace."""
    argv = ["sim", args.scenario, "--algo", args.algo, "--via", "lcm",
            "--timeout", str(args.timeout), "--kill-node", str(args.kill_node),
            "--seed", str(args.seed)]
    for opt in ("out", "plot", "url", "prefix"):
        if getattr(args, opt) is not None:
            argv += [f"--{opt}", getattr(args, opt)]
    if args.timeline:
        argv.append("--timeline")
    if args.attach:
        argv.append("--attach")
    return argv


def simulate_via_lcm(mission: M.Mission, events: List[dict], penalty: Optional[int] = None,
                     algo: str = "sva", kill_node: int = 0, seed: int = 0, **link) -> dict:
    """Flies the scenario against sva_node over LCM (sva_tools.lcm.simnode; `link`: url,
    prefix, attach, timeout) from inside a network namespace; with kill_node, kills and
    restarts the node that many times at moments drawn with seed (`node_kills` in the
    log). Raises SimError or simnode.NodeError."""
    from .lcm import simnode

    kills = simnode.kill_plan(events, kill_node, seed) if kill_node > 0 else None
    node = simnode.NodePlanner(algo, penalty, kills=kills, takeoff=mission.takeoff_ticks, **link)
    try:
        log = simulate(mission, events, penalty, algo, planner=node)
    finally:
        node.close()
    log["via"] = "lcm"
    log["node"] = node.summary()
    if kill_node > 0:
        log["node_kills"] = node.kills
    return log


def _fly_via_lcm(args, mission, events, penalty) -> dict:
    kw = {k: getattr(args, k) for k in ("url", "prefix") if getattr(args, k) is not None}
    return simulate_via_lcm(mission, events, penalty, args.algo, kill_node=args.kill_node,
                            seed=args.seed, attach=args.attach, timeout=args.timeout, **kw)


def run(args) -> int:
    if args.via == "cli" and (args.attach or args.url or args.prefix):
        print("sva-tools: error: sim: --attach, --url and --prefix need --via lcm",
              file=sys.stderr)
        return 2
    if args.kill_node and (args.via != "lcm" or args.attach or args.kill_node < 0):
        print("sva-tools: error: sim: --kill-node: needs --via lcm and a node of the run's own "
              f"(not --attach), and a count >= 0, got {args.kill_node}", file=sys.stderr)
        return 2
    if args.via == "lcm" and not args.attach and not os.environ.get("SVA_LCM_NETNS"):
        load_scenario(args.scenario)  # a bad scenario is reported before any namespace
        from .lcm import simnode
        return simnode.reexec_in_netns(_argv(args))
    mission, events, penalty = load_scenario(args.scenario)
    try:
        if args.via == "lcm":
            from .lcm import simnode
            try:
                log = _fly_via_lcm(args, mission, events, penalty)
            except simnode.NodeError as e:
                print(f"sva-tools: error: {args.scenario}: --via lcm: {e}", file=sys.stderr)
                return e.status
        else:
            log = simulate(mission, events, penalty, args.algo)
    except cbin.CliMissing as e:
        print(f"sva-tools: error: sim: {e}", file=sys.stderr)
        return 2
    except SimError as e:
        print(f"sva-tools: error: {args.scenario}: {e}", file=sys.stderr)
        return e.status
    if args.timeline:
        sys.stdout.write(timeline(log))
    if args.out or not args.timeline:
        io.write_json(log, args.out or "-")
    if args.plot:
        from . import simplot
        simplot.render_flight(log, args.plot)
    return 0
