"""The live-mission simulator: scenarios flown with replans (`sva-tools sim`)."""
from __future__ import annotations

import json
import os
import subprocess
import tempfile
from dataclasses import dataclass, field
from typing import Any, Callable

from . import cbin, io, model

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
    orders: list[int] = field(default_factory=list)
    step_to: tuple[int, int] | None = None
    step_end: int = 0
    hover: int | None = None       # target id it hovers over until the window ends
    free_at: int = 0                  # it may not leave before (the mission's ready_at)
    arrived: int = 0                  # tick it reached its current cell
    out: list[list[int | None]] = field(default_factory=list)      # [lost at, back at]
    track: list[list[int]] = field(default_factory=list)           # [tick, x, y, fuel]
    visits: list[dict[str, Any]] = field(default_factory=list)
    cells: int = 0


def _target(doc: dict[str, Any], where: str) -> model.Target:
    """A target in mission JSON form, through the mission parser's own checks."""
    m = io.mission_from_json({"name": where, "depot": {"x": 0, "y": 0}, "uavs": [],
                              "targets": [doc]})
    return m.targets[0]


def parse_scenario(doc: Any) -> tuple[model.Mission, list[dict[str, Any]], int | None]:
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
    for i, ev in enumerate(events):
        w = f"events[{i}]"
        if not isinstance(ev, dict):
            raise io.InputError(f"{w}: must be a JSON object")
        if ev.get("type") not in EVENT_TYPES:
            raise io.InputError(f"{w}.type: must be one of {', '.join(EVENT_TYPES)}, "
                                f"got {json.dumps(ev.get('type'))}")
        at = ev.get("at")
        if not isinstance(at, int) or isinstance(at, bool) or at < 0:
            raise io.InputError(f"{w}.at: must be an integer >= 0, got {json.dumps(at)}")
    return mission, events, penalty


def load_scenario(path: str) -> tuple[model.Mission, list[dict[str, Any]], int | None]:
    try:
        return parse_scenario(io.read_json(path))
    except io.InputError as e:
        e.path = path
        raise


# --- the planner ---------------------------------------------------------------------

def replan(mission_doc: dict[str, Any], events: list[dict[str, Any]], now: int, algo: str,
           timeout: float = 600) -> tuple[dict[str, Any], dict[str, Any]]:
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

def _toward(x: int, y: int, tx: int, ty: int) -> tuple[int, int]:
    """The next cell from (x, y) towards (tx, ty): x first, then y."""
    if x != tx:
        return (x + (1 if tx > x else -1), y)
    return (x, y + (1 if ty > y else -1))


# How a flight is replanned: (mission doc, events so far, now, algorithm) -> (the plan
# with its changes and live keys, the residual mission); replan() or a node over LCM.
Planner = Callable[[dict[str, Any], list[dict[str, Any]], int, str], tuple[dict[str, Any], dict[str, Any]]]


class Flight:
    def __init__(self, mission: model.Mission, events: list[dict[str, Any]], penalty: int | None,
                 algo: str, planner: Planner = replan):
        self.m = mission
        self.events = events
        self.penalty = penalty
        self.algo = algo
        self.planner = planner
        self.crafts = [Craft(u.id, u.x, u.y, u.fuel, free_at=u.ready_at) for u in mission.uavs]
        self.by_id = {c.id: c for c in self.crafts}
        self.targets: dict[int, model.Target] = {t.id: t for t in mission.targets}
        self.order = [t.id for t in mission.targets]   # first appearance
        self.outcome: dict[int, str] = {}               # cancelled / lost, decided early
        self.replans: list[dict[str, Any]] = []
        self.tpc = mission.ticks_per_cell

    # The mission document the planner reads: the mission as at tick 0.
    def mission_doc(self) -> dict[str, Any]:
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

    def _apply(self, e: dict[str, Any], t: int) -> None:
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

    def _step(self, c: Craft, t: int, dest: tuple[int, int]) -> None:
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

    def _replan(self, t: int, cause: str, history: list[dict[str, Any]], now_events: list[dict[str, Any]]) -> None:
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

    def _changes(self, residual: dict[str, Any], plan: dict[str, Any], now_events: list[dict[str, Any]],
                 cli_changes: dict[str, Any] | None) -> dict[str, Any]:
        """SPEC 12.4's changed visits of this replan: (UAV, target) pairs of the residual
        mission that the plan in force had (the previous replan's plan; none for a UAV
        that came back since) and this plan drops, or that this plan adds. Recomputed
        here from consecutive plans, as the CLI's own figure describes only its last
        replan over the history."""
        if not self.replans:
            pairs_before: set[tuple[int, int]] = set()
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

    def fly(self, max_ticks: int | None = None) -> dict[str, Any]:
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
        history: list[dict[str, Any]] = []
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

    def _served_by(self, tg: model.Target) -> list[int]:
        """UAVs in service at the target's cell at every tick of [start, end)."""
        ids = []
        for c in self.crafts:
            at = {e[0]: (e[1], e[2]) for e in c.track}
            if all(at.get(k) == (tg.x, tg.y) for k in range(tg.start, tg.end)):
                ids.append(c.id)
        return ids

    def _log(self, end: int) -> dict[str, Any]:
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

    def scenario_doc(self) -> dict[str, Any]:
        doc: dict[str, Any] = {"mission": self.m.to_json(), "events": self.events}
        if self.penalty is not None:
            doc["change_penalty"] = self.penalty
        return doc


def simulate(mission: model.Mission, events: list[dict[str, Any]], penalty: int | None = None,
             algo: str = "sva", planner: Planner = replan) -> dict[str, Any]:
    """Flies the scenario and returns the flight log (raises SimError)."""
    return Flight(mission, events, penalty, algo, planner).fly()


# --- the timeline --------------------------------------------------------------------

def event_text(e: dict[str, Any]) -> str:
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


def timeline(log: dict[str, Any]) -> str:
    """One line per replan (tick, cause, targets the planner then expects covered: done
    ones included, plan cost, changed visits, kept or not, solve time) under the events
    that caused it, and the flight's summary."""
    by_tick: dict[int, list[dict[str, Any]]] = {}
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


def simulate_via_lcm(mission: model.Mission, events: list[dict[str, Any]], penalty: int | None = None,
                     algo: str = "sva", kill_node: int = 0, seed: int = 0, **link: Any) -> dict[str, Any]:
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
