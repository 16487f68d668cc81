"""What the ground view knows, built from the LCM traffic (or from a flight log).

`Ground` keeps one JSON-able picture of the mission: the mission and its frame, the UAVs
(position, fuel, health, track, lost or not), the targets and their states, the plan in
force, the replans, an event log, the node's health and a count of bad messages. Each
`on_message(channel, data)` decodes one LCM message (types of sva_tools.lcm.wire); a
message that does not decode, or has a version this view does not speak, is counted
as a warning and changes nothing else.

Target states from traffic (the node does not send them): `cancelled` after an accepted
target_cancelled; `waiting` while in the residual mission of the last replan (or, before
any replan, in the mission); not in it and not cancelled: `under_way` while its window
is open at the live mission's clock, `covered` after its end, `lost` when a UAV the
plan had sent to it was lost while it was under way, `expired` when its window ended
while it was waiting and no plan covered it.
"""
from __future__ import annotations

import time
from typing import Any

from ..lcm import wire
from ..sim import event_text

# History is bounded (docs/ground.md "Limits"), so memory stays flat however long the
# mission: the last MAX_REPLANS replans in full, the older ones counted in
# `replans_summary`; MAX_TRACK points per UAV (the oldest dropped, counted per UAV);
# MAX_TARGETS_KEPT targets and MAX_UAVS_KEPT UAVs (finished or lost ones forgotten
# first, counted in `forgotten`). The lists a message brings are bounded by its type.
MAX_LOG = 500
MAX_WARNINGS = 50
MAX_REPLANS = 200
MAX_TRACK = 300
MAX_TARGETS_KEPT = 1024
MAX_UAVS_KEPT = 256
FRAME_KEYS = ("lat", "lon", "alt_m", "cell_m", "tick_s", "t0")


class FrameError(ValueError):
    pass


def check_frame(frame: Any, where: str = "frame") -> dict[str, Any]:
    """A mission frame {"lat", "lon", "alt_m", "cell_m", "tick_s", "t0"} checked by the
    frame's contract (docs/flight-stack.md: the mission schema's `frame` and t0's rules,
    sva_tools.frame), returned at its resolutions as `sva plan` echoes it (t0 in UTC with
    milliseconds). FrameError in the words of `sva validate`, after where's file part
    (`f.json: mission: frame.tick_s: must be >= 0.001, got -1`)."""
    prefix = where[:-len("frame")] if where.endswith("frame") else f"{where}: "
    if frame is None:
        raise FrameError(f"{prefix}frame: must be an object, got null")
    try:
        doc = wire.frame_document(wire.frame_message(frame))
    except wire.InputError as e:
        raise FrameError(prefix + str(e)) from None
    if doc is None:  # cannot happen: the frame is there
        raise FrameError(f"{prefix}frame: must be an object")
    return doc


class Ground:
    def __init__(self, prefix: str = "SVA_", frame: dict[str, Any] | None = None,
                 source: str = "lcm") -> None:
        self.prefix = prefix
        self.source = source
        self.version = 0           # bumps on every change (the server pushes when it moves)
        self.frame = frame
        self.given_frame = frame   # --frame (or a flight log's); a mission_t's frame wins
        self.mission: dict[str, Any] | None = None
        self.now = 0
        self.uavs: dict[int, dict[str, Any]] = {}
        self.targets: dict[int, dict[str, Any]] = {}
        self.plan: dict[str, Any] | None = None
        self.replans: list[dict[str, Any]] = []
        self.replans_summary = _no_replans()
        self.forgotten = {"targets": 0, "uavs": 0}
        self.log: list[dict[str, Any]] = []
        self.node: dict[str, Any] = {"status": None, "replans_answered": 0, "refused": 0,
                                     "last_solve_us": None, "plans": 0}
        self.warnings: dict[str, Any] = {"count": 0, "recent": []}
        self.counts: dict[str, int] = {}
        self.events_seen: dict[int, dict[str, Any]] = {}
        self.end: int | None = None

    # --- bookkeeping ------------------------------------------------------------------

    def _changed(self) -> None:
        self.version += 1

    def add_replan(self, entry: dict[str, Any]) -> None:
        """Keeps the last MAX_REPLANS replans; an older one goes into the summary."""
        self.replans.append(entry)
        if len(self.replans) > MAX_REPLANS:
            old = self.replans.pop(0)
            acc = self.replans_summary
            acc["count"] += 1
            acc["accepted" if old["accepted"] else "refused"] += 1
            acc["kept"] += 1 if old.get("kept") else 0
            if acc["first_now"] is None:
                acc["first_now"] = old["now"]
            acc["last_now"] = old["now"]

    def clear_replans(self) -> None:
        self.replans = []
        self.replans_summary = _no_replans()

    @staticmethod
    def add_track(uav: dict[str, Any], point: list[int]) -> None:
        uav["track"].append(point)
        if len(uav["track"]) > MAX_TRACK:
            del uav["track"][0]
            uav["track_dropped"] = uav.get("track_dropped", 0) + 1

    def _bound_targets(self) -> None:
        """Forgets targets past MAX_TARGETS_KEPT: finished ones first, oldest first."""
        excess = len(self.targets) - MAX_TARGETS_KEPT
        if excess <= 0:
            return
        done = [tid for tid, tg in self.targets.items()
                if tg["state"] not in ("waiting", "under_way")][:excess]
        chosen = set(done)
        rest = [tid for tid in self.targets if tid not in chosen][:excess - len(done)]
        for tid in done + rest:
            del self.targets[tid]
        self.forgotten["targets"] += excess

    def _bound_uavs(self) -> None:
        """Forgets UAVs past MAX_UAVS_KEPT: lost ones first, oldest first."""
        excess = len(self.uavs) - MAX_UAVS_KEPT
        if excess <= 0:
            return
        lost = [uid for uid, u in self.uavs.items() if u["lost"]][:excess]
        chosen = set(lost)
        rest = [uid for uid in self.uavs if uid not in chosen][:excess - len(lost)]
        for uid in lost + rest:
            del self.uavs[uid]
        self.forgotten["uavs"] += excess

    def _log(self, kind: str, text: str, **extra: Any) -> None:
        self.log.append({"t": self.now, "kind": kind, "text": text,
                         "wall": round(time.time(), 3), **extra})
        del self.log[:-MAX_LOG]

    def warn(self, channel: str, text: str) -> None:
        self.warnings["count"] += 1
        self.warnings["recent"].append({"channel": channel, "text": text,
                                        "wall": round(time.time(), 3)})
        del self.warnings["recent"][:-MAX_WARNINGS]
        self._log("warning", f"{channel}: {text}")
        self._changed()

    # --- LCM messages -----------------------------------------------------------------

    def on_message(self, channel: str, data: bytes) -> None:
        if not channel.startswith(self.prefix):
            return
        kind = channel[len(self.prefix):]
        t = wire.types()
        decoders = {"FLEET": t.fleet_state_t, "MISSION": t.mission_t, "PLAN": t.plan_t,
                    "EVENT": t.event_t, "REPLAN": t.replan_t, "STATUS": t.node_status_t}
        if kind not in decoders:
            return
        self.counts[kind] = self.counts.get(kind, 0) + 1
        try:
            msg = decoders[kind].decode(data)
        except Exception as e:  # any undecodable bytes: a warning, nothing else
            self.warn(channel, f"{len(data)} bytes that are not a {decoders[kind].__name__} "
                               f"({type(e).__name__}: {e})")
            return
        try:
            getattr(self, "_on_" + kind.lower())(msg)
        except wire.InputError as e:
            self.warn(channel, str(e))
            return
        except (IndexError, KeyError, TypeError, ValueError) as e:
            self.warn(channel, f"a {decoders[kind].__name__} this view cannot use "
                               f"({type(e).__name__}: {e})")
            return
        self._changed()

    def _on_fleet(self, f: wire.Message) -> None:
        if not 0 <= f.uav_count <= len(f.uavs):
            raise ValueError(f"uav_count {f.uav_count}")
        self.uavs = {}
        for u in f.uavs[:f.uav_count]:
            self.uavs[u.id] = {"id": u.id, "x": u.x, "y": u.y, "fuel": u.fuel,
                               "health": "ok" if u.health == 0 else "unavailable",
                               "lost": False, "track": [[self.now, u.x, u.y]]}
        self._log("fleet", f"fleet revision {f.revision}: {f.uav_count} UAVs")

    def _on_mission(self, m: wire.Message) -> None:
        if not 0 <= m.target_count <= len(m.targets):
            raise ValueError(f"target_count {m.target_count}")
        self.mission = {"revision": m.revision, "depot": [m.depot_x, m.depot_y],
                        "ticks_per_cell": m.ticks_per_cell, "hover_fuel": m.hover_fuel}
        self.targets = {}
        for g in m.targets[:m.target_count]:
            self._put_target(g)
        self.clear_replans()
        self.plan, self.now, self.end = None, 0, None
        self._log("mission", f"mission revision {m.revision}: {m.target_count} targets")
        # The frame the node plans with and the vehicles fly: the mission's when it has
        # one (checked as every frame is), else the one the view was given.
        link = check_frame(wire.frame_document(m.frame)) if m.frame.present else None
        if link is not None and self.given_frame is not None and link != self.given_frame:
            self._log("frame", "the mission's frame differs from --frame; showing the "
                               f"mission's: {link}")
        self.frame = link if link is not None else self.given_frame

    def _put_target(self, g: wire.Message) -> None:
        old = self.targets.get(g.id, {})
        self.targets[g.id] = {"id": g.id, "x": g.x, "y": g.y, "start": g.start_ticks,
                              "end": g.end_ticks, "need": g.need,
                              "state": old.get("state", "waiting"),
                              "planned": old.get("planned", []), "visits": old.get("visits", [])}

    def _plan_doc(self, p: wire.Message) -> dict[str, Any]:
        status = {1: "complete", 2: "partial", 3: "rejected", 4: "failed", 5: "too_large"}.get(
            p.status, str(p.status))
        doc = {"plan_id": p.plan_id, "status": status, "solve_us": p.solve_us,
               "algorithm": wire.ALGORITHMS[p.algorithm] if 0 <= p.algorithm < 5 else "?",
               "covered": p.covered, "cost": p.cost, "routes": []}
        if p.status in (p.STATUS_COMPLETE, p.STATUS_PARTIAL):
            d = wire.plan_document(p, "plan")
            doc["routes"] = [{"uav": r["uav"], "targets": r["targets"]} for r in d["routes"]]
            doc["uncovered"] = d["uncovered"]
        return doc

    def _set_plan(self, doc: dict[str, Any]) -> None:
        self.plan = doc
        for r in doc["routes"]:
            for tid in r["targets"]:
                tg = self.targets.get(tid)
                if tg is not None and tg["state"] == "waiting":
                    tg["planned"] = sorted(set(tg["planned"]) | {r["uav"]})

    def _on_plan(self, p: wire.Message) -> None:
        doc = self._plan_doc(p)
        self.node["plans"] += 1
        self.node["last_solve_us"] = p.solve_us
        if doc["status"] in ("complete", "partial"):
            for tg in self.targets.values():
                tg["planned"] = []
            self._set_plan(doc)
        self._log("plan", f"plan {p.plan_id} ({doc['algorithm']}, {doc['status']}): covers "
                          f"{p.covered}, cost {p.cost}, solved in {p.solve_us} µs")

    def _on_event(self, e: wire.Message) -> None:
        if e.version != self.types_version("event_t"):
            raise wire.InputError(f"event_t.version is {e.version}, this view speaks version "
                                  f"{self.types_version('event_t')}")
        kind = wire.EVENT_TYPES[e.type] if 0 <= e.type < len(wire.EVENT_TYPES) else str(e.type)
        doc = {"seq": e.seq, "type": kind, "at": e.at_ticks, "uav": e.uav_id, "x": e.x,
               "y": e.y, "fuel": e.fuel, "target": {"id": e.target.id, "x": e.target.x,
                                                    "y": e.target.y,
                                                    "start": e.target.start_ticks,
                                                    "end": e.target.end_ticks,
                                                    "need": e.target.need}}
        self.events_seen[e.seq] = doc
        if len(self.events_seen) > 4 * MAX_LOG:
            self.events_seen.pop(next(iter(self.events_seen)))
        self._log("event", f"event {e.seq}: {event_text(doc)} at tick {e.at_ticks}")

    @staticmethod
    def types_version(name: str) -> int:
        version: int = getattr(wire.types(), name).VERSION
        return version

    def _on_replan(self, r: wire.Message) -> None:
        doc = wire.replan_document(r, "mission")  # InputError on another version
        ev = self.events_seen.get(r.event_seq)
        self.node["replans_answered"] += 1
        entry = {"seq": r.event_seq, "event": doc["event"], "accepted": doc["accepted"],
                 "now": r.now_ticks, "revision": r.revision}
        if not doc["accepted"]:
            self.node["refused"] += 1
            entry["error"] = doc["error"]
            self.add_replan(entry)
            self._log("refused", f"event {r.event_seq} ({doc['event']}) refused: {doc['error']}")
            return
        self.now = max(self.now, r.now_ticks)
        plan = self._plan_doc(r.plan)
        self.node["last_solve_us"] = r.plan.solve_us
        entry.update(kept=doc["kept"], covered=doc["covered"], under_way=doc["under_way"],
                     objective=doc["objective"], cost=plan["cost"], solve_us=r.plan.solve_us,
                     plan_id=r.plan.plan_id, dropped=doc["changes"]["dropped"],
                     added=doc["changes"]["added"])
        self.add_replan(entry)
        if ev is not None:
            self._apply_event(ev)
        residual = doc["residual"]
        # UAVs: where the flight model puts them now (the residual fleet); the others out.
        here = {u["id"]: u for u in residual["uavs"]}
        for uid, u in here.items():
            c = self.uavs.setdefault(uid, {"id": uid, "health": "ok", "lost": False,
                                           "track": []})
            c.update(x=u["x"], y=u["y"], fuel=u["fuel"], lost=False)
            if not c["track"] or c["track"][-1][1:] != [u["x"], u["y"]]:
                self.add_track(c, [r.now_ticks, u["x"], u["y"]])
        for uid, c in self.uavs.items():
            if uid not in here and doc["event"] == "uav_lost" and ev and ev["uav"] == uid:
                c["lost"] = True
        # Targets: waiting in the residual mission; the others by the clock.
        waiting = {g["id"] for g in residual["targets"]}
        for g in residual["targets"]:
            tg = self.targets.get(g["id"])
            if tg is None or (tg["x"], tg["y"], tg["start"], tg["end"]) != (
                    g["x"], g["y"], g["start"], g["end"]):
                self.targets[g["id"]] = {**g, "state": "waiting", "visits": [],
                                         "planned": tg["planned"] if tg else []}
            self.targets[g["id"]]["state"] = "waiting"
        for tid, tg in self.targets.items():
            if tid in waiting or tg["state"] in ("cancelled", "lost"):
                continue
            if r.now_ticks >= tg["end"]:
                tg["state"] = "covered" if tg["state"] == "under_way" or tg["planned"] \
                    else "expired"
            elif r.now_ticks >= tg["start"]:
                tg["state"] = "under_way" if tg["planned"] else "expired"
            else:
                tg["state"] = "expired"
        for tg in self.targets.values():
            if tg["state"] == "waiting":
                tg["planned"] = []
        self._set_plan(plan)
        self._bound_targets()
        self._bound_uavs()
        self._log("replan", f"replan of event {r.event_seq} ({doc['event']}) at tick "
                            f"{r.now_ticks}: covers {doc['covered']}, cost {plan['cost']}, "
                            f"{'kept' if doc['kept'] else 'new plan'}, "
                            f"{doc['changes']['dropped']} dropped, {doc['changes']['added']} "
                            f"added, solved in {r.plan.solve_us} µs")

    def _apply_event(self, ev: dict[str, Any]) -> None:
        kind = ev["type"]
        if kind == "uav_lost":
            c = self.uavs.get(ev["uav"])
            if c is not None:
                c["lost"] = True
            for tg in self.targets.values():
                if tg["state"] == "under_way" and ev["uav"] in tg["planned"]:
                    tg["state"] = "lost"
        elif kind == "uav_back":
            c = self.uavs.get(ev["uav"])
            if c is not None:
                c.update(lost=False, x=ev["x"], y=ev["y"], fuel=ev["fuel"])
        elif kind == "target_cancelled":
            cancelled = self.targets.get(ev["target"]["id"])
            if cancelled is not None:
                cancelled["state"] = "cancelled"
        elif kind in ("target_added", "target_changed"):
            g = ev["target"]
            old = self.targets.get(g["id"], {})
            self.targets[g["id"]] = {**g, "state": "waiting", "visits": old.get("visits", []),
                                     "planned": []}
            self._bound_targets()

    def _on_status(self, s: wire.Message) -> None:
        self.node["status"] = {
            "seq": s.seq, "state": "ready" if s.state == 1 else "waiting",
            "algorithm": wire.ALGORITHMS[s.algorithm] if 0 <= s.algorithm < 5 else "?",
            "fleet_revision": s.fleet_revision, "mission_revision": s.mission_revision,
            "last_plan_id": s.last_plan_id, "plans_published": s.plans_published,
            "fleet_rx": s.fleet_rx, "mission_rx": s.mission_rx, "unchanged": s.unchanged,
            "rejected": dict(zip(wire.REJECT_REASONS, list(s.rejected))),
            "rejected_total": sum(s.rejected), "wall": round(time.time(), 3)}

    # --- the picture ------------------------------------------------------------------

    def snapshot(self) -> dict[str, Any]:
        return {"version": self.version, "source": self.source, "prefix": self.prefix,
                "frame": self.frame, "mission": self.mission, "now": self.now, "end": self.end,
                "uavs": sorted(self.uavs.values(), key=lambda u: u["id"]),
                "targets": sorted(self.targets.values(), key=lambda t: t["id"]),
                "plan": self.plan, "replans": self.replans,
                "replan_count": self.replans_summary["count"] + len(self.replans),
                "replans_summary": self.replans_summary, "forgotten": self.forgotten,
                "log": self.log[-200:],
                "node": self.node, "warnings": self.warnings, "counts": self.counts}


def _no_replans() -> dict[str, Any]:
    return {"count": 0, "accepted": 0, "refused": 0, "kept": 0, "first_now": None,
            "last_now": None}


# --- a simulator flight log, tick by tick -----------------------------------------------

def flight_at(g: Ground, log: dict[str, Any], t: int) -> None:
    """Sets g to the flight log's picture at tick t (the log is the ground truth: tracks,
    visits, outcomes; the replans up to t)."""
    mission = log["scenario"]["mission"]
    events = [e for e in log["scenario"]["events"] if e["at"] <= t]
    g.now, g.end = t, log["end_tick"]
    g.mission = {"name": mission.get("name"), "depot": [mission["depot"]["x"],
                                                        mission["depot"]["y"]],
                 "ticks_per_cell": mission.get("ticks_per_cell", 1),
                 "hover_fuel": mission.get("hover_fuel", 0)}
    g.uavs = {}
    for u in log["uavs"]:
        track = [e for e in u["track"] if e[0] <= t]
        lost = any(a <= t and (b is None or t < b) for a, b in u["out"])
        last = track[-1] if track else None
        if last is None:
            u0 = next(x for x in mission["uavs"] if x["id"] == u["id"])
            last = [0, u0["x"], u0["y"], u0["fuel"]]
        g.uavs[u["id"]] = {"id": u["id"], "x": last[1], "y": last[2], "fuel": last[3],
                           "health": "ok", "lost": lost,
                           "track": [[e[0], e[1], e[2]] for e in track[-MAX_TRACK:]]}
        if len(track) > MAX_TRACK:
            g.uavs[u["id"]]["track_dropped"] = len(track) - MAX_TRACK
    defs = {tg["id"]: dict(tg) for tg in mission["targets"]}
    cancelled = set()
    for e in events:
        if e["type"] in ("target_added", "target_changed"):
            defs[e["target"]["id"]] = dict(e["target"])
        elif e["type"] == "target_cancelled":
            cancelled.add(e["target"])
    outcome = {x["id"]: x for x in log["targets"]}
    hover: dict[int, Any] = {}
    for u in log["uavs"]:
        for v in u["visits"]:
            hover.setdefault(v["target"], []).append((u["id"], v))
    g.targets = {}
    for tid, d in defs.items():
        visits = hover.get(tid, [])
        o = outcome.get(tid, {}).get("outcome")
        active = [uid for uid, v in visits if v["arrived"] <= t and
                  (v["left"] is None or t < v["left"]) and t >= d["start"]]
        if tid in cancelled:
            state = "cancelled"
        elif o == "lost" and visits and t >= min(v["left"] or d["end"] for _, v in visits) \
                and t < d["end"]:
            state = "lost"
        elif o == "lost" and t >= d["end"]:
            state = "lost"
        elif active:
            state = "under_way"
        elif t >= d["end"]:
            state = "covered" if o == "covered" else "expired"
        elif t >= d["start"]:
            state = "expired" if not active else "under_way"
        else:
            state = "waiting"
        g.targets[tid] = {**{k: d[k] for k in ("id", "x", "y", "start", "end", "need")},
                          "state": state, "planned": [],
                          "visits": [[uid, v["arrived"], v["left"]] for uid, v in visits
                                     if v["arrived"] <= t]}
    replans = [r for r in log["replans"] if r["at"] <= t]
    g.clear_replans()
    for n, r in enumerate(replans):
        live = r.get("live") or {}
        g.add_replan({"seq": n, "event": r["cause"], "accepted": True,
                          "now": r["at"], "revision": live.get("revision"),
                          "kept": live.get("kept"), "covered": live.get("covered"),
                          "cost": r["plan"]["cost"], "solve_us": r.get("solve_us"),
                          "plan_id": (r.get("node") or {}).get("plan_id"),
                          "dropped": len(r["changes"]["dropped"]),
                          "added": len(r["changes"]["added"])})
    if replans:
        p = replans[-1]["plan"]
        g.plan = {"plan_id": (replans[-1].get("node") or {}).get("plan_id"),
                  "status": p["status"], "solve_us": replans[-1].get("solve_us"),
                  "algorithm": p["algorithm"], "covered": p["covered"], "cost": p["cost"],
                  "routes": [{"uav": x["uav"], "targets": x["targets"]} for x in p["routes"]],
                  "uncovered": p.get("uncovered", [])}
        g.node["last_solve_us"] = replans[-1].get("solve_us")
    g.node["replans_answered"] = len(replans)
    g.log = []
    items = [(e["at"], 0, "event", event_text(e)) for e in events]
    items += [(r["at"], 1, "replan", f"replan at tick {r['at']} ({r['cause']}): covers "
               f"{(r.get('live') or {}).get('covered', r['plan']['covered'])}, cost "
               f"{r['plan']['cost']}, {r['changes']['count']} changed visits"
               + (f", solved in {r['solve_us']} µs" if r.get("solve_us") is not None else ""))
              for r in replans]
    for at, _, kind, text in sorted(items, key=lambda x: (x[0], x[1])):
        g.log.append({"t": at, "kind": kind, "text": text, "wall": None})
    g._changed()
