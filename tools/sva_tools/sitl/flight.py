"""The flight of `sva-tools sitl`: vehicles, node and bridge started, the clock set, the
mission handed to the node, the scenario's events made real at their ticks on the
vehicles' clock, and everything stopped at the end (docs/sitl.md).

Order of work:
1. `sva_node` starts; one arducopter per UAV is launched at its start cell with
   `--start-time` chosen so that every vehicle's GPS clock agrees (each launch's offset
   from the first is scaled by the speedup); the bridge connects to their SERIAL0.
2. The operator links wait for every vehicle's GPS fix, EKF position and GPS time.
   t0 is the mission frame's, or the latest vehicle clock then plus the take-off
   allowance, rounded up to a whole second.
3. The fleet and the framed mission go to the node; its plan goes to the bridge, which
   uploads each route. The operator arms every vehicle that holds a mission in AUTO,
   no earlier than t0 minus the take-off allowance.
4. Each event at its tick on the vehicle clock: uav_lost SIGKILLs the vehicle's process
   (the bridge reports it LOST, the node replans), uav_back launches a fresh one on its
   cell (the bridge reports it back, the node replans, the operator arms it once it
   holds a mission), every other event is an event_t from the ground.
5. The flight ends when no event is left, every window has ended and every vehicle is
   on its way home (RTL), landed or out of service.

Faults (--fault): a vehicle with an upload fault is reached by the bridge through a
relay (sitl.relay) that silences or rewrites its next upload once armed; a reboot kills
the vehicle's process at its time and starts a fresh one where it is, on the ground.
"""
from __future__ import annotations

import functools
import math
import select
import shutil
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..frame import Frame, format_utc
from ..model import Mission
from . import judge, record
from .craft import Craft
from .ground import BridgeLine, Ground, GroundError
from .relay import UPLOAD_FAULTS, Relay
from .vehicle import Process, SitlError, write_extra_parameters

if TYPE_CHECKING:
    from tqdm import tqdm as Tqdm

BOOT_ALLOWANCE_S = 90        # vehicle seconds from launch to a ready vehicle (measured: ~41)
READY_TIMEOUT_WALL_S = 120   # host seconds to wait for every vehicle to be ready
TAKEOFF_BASE_S = 12.0        # arming, spool-up and margin (measured: climb starts 4.3 s after arming)
CLIMB_M_S = 2.5              # ArduCopter's WPNAV_SPEED_UP default
PLAN_TIMEOUT_S = 20          # host seconds to wait for the node's first plan
PLAN_WAIT_S = 2.0            # host seconds a bridge line waits for the plan it names
EVENT_ANSWER_TIMEOUT_S = 10  # host seconds to wait for the node's answer to an event
REPORT_VEHICLE_MS = 1000     # vehicle ms between two reports of a vehicle
LOST_VEHICLE_MS = 3000       # vehicle ms of silence before the bridge reports a vehicle LOST
CRUISE_M_S = 10.0            # commanded (bridge --cruise-speed): ArduCopter's WPNAV_SPEED
LINGER_MS = 10_000           # vehicle ms flown on after the end, so telemetry covers every window's end


def takeoff_allowance_s(alt_m: float) -> int:
    """Vehicle seconds from arming to the frame's altitude over the start cell, with margin
    (measured 17.7 s to 29.5 m of 30 m after the arming command, at speedup 10)."""
    return int(math.ceil(TAKEOFF_BASE_S + alt_m / CLIMB_M_S))


FOLDER_PREFIX = "sva-sitl-"

# A stop asked by SIGINT or SIGTERM (ask_stop). The tool's signal handler raises
# KeyboardInterrupt itself; where Python drops that raise ("Exception ignored": in an
# at-fork hook while a process starts, in a finalizer), the next pump raises it, once.
_STOP = {"asked": False, "raised": False}


def ask_stop() -> None:
    _STOP["asked"] = True


def stop_asked() -> bool:
    return _STOP["asked"]


@dataclass
class Settings:
    scenario_path: str
    mission: Mission
    events: list[dict[str, Any]]
    penalty: int | None
    frame: dict[str, Any]       # lat, lon, alt_m, cell_m, tick_s, and t0 (None: choose it)
    algo: str
    speedup: float
    sitl: Path
    defaults: Path
    url: str
    prefix: str
    progress: bool = True
    faults: list[dict[str, Any]] = field(default_factory=list)  # {kind, uav, t_s} (cli.parse_fault)
    folder: Path | None = None  # the working folder (None: a new one under the temp dir)


class Flight:
    def __init__(self, s: Settings):
        self.s = s
        self.tmp = s.folder or Path(tempfile.mkdtemp(prefix=FOLDER_PREFIX))
        f = s.frame
        self.geo = Frame.from_json({**f, "t0": f.get("t0") or "1970-01-01T00:00:00Z"})
        self.t0_ms: int | None = self.geo.t0_ms if f.get("t0") else None
        self.tick_ms = self.geo.tick_ms
        self.allowance_s = takeoff_allowance_s(self.geo.alt_m)
        self.crafts: list[Craft] = [Craft(u.id, k, s.speedup) for k, u in enumerate(s.mission.uavs)]
        self.by_id: dict[int, Craft] = {c.id: c for c in self.crafts}
        self.ground: Ground | None = None
        self.defaults = f"{s.defaults},{write_extra_parameters(self.tmp)}"
        self.pending = [dict(e, index=i) for i, e in enumerate(s.events)]
        self.flown_events: list[dict[str, Any]] = []
        self.awaiting: dict[int, dict[str, Any]] = {}  # event seq -> its record
        self.replans: list[dict[str, Any]] = []
        self.replans_seen = 0
        # plan_id -> (residual ready_at per UAV, the replan's now): the bridge's lines name
        # the plan they upload
        self.residual_ready: dict[str, tuple[dict[int, int], int]] = {}
        # (host monotonic, fleet UTC ms, the line) of bridge lines not taken yet
        self.held_lines: list[tuple[float, float | None, BridgeLine]] = []
        self.plans_seen = 0
        self.node_now = 0
        self.bridge_log: list[list[Any]] = []  # [fleet UTC ms, line]
        self.name = s.mission.name
        self.start_doc: dict[str, Any] | None = None
        self.clock_spread_ms: float | None = None
        self.ended_by = "the end of the mission"
        self.bar: Tqdm[Any] | None = None  # the progress bar while flying
        self.wall0 = time.monotonic()
        self.wall_s = 0.0
        self.end_utc_ms: float | None = None
        self.bridge_cmd: list[str] = []
        self.frame_doc: dict[str, Any] = {}
        self.mission_doc: dict[str, Any] = {}
        self.closed = False
        self._last_fleet: tuple[float, float] | None = None  # (fleet UTC ms, host monotonic)
        # --fault: a relay per vehicle with an upload fault; reboots due at their time
        self.relays: dict[int, Relay] = {}
        self.reboots = [dict(f) for f in s.faults if f["kind"] == "reboot"]
        self.fault_log: list[dict[str, Any]] = []
        self.faulty = {f["uav"] for f in s.faults}

    # --- clocks ----------------------------------------------------------------------

    def fleet_utc_ms(self) -> float | None:
        """The fleet's clock: the median of the clocks of the vehicles in service. It never
        runs back (the median can, when a vehicle leaves or joins the service), so that
        the record's instants keep the order in which this process saw them."""
        clocks = sorted(c for c in (k.utc_ms() for k in self.crafts if k.in_service and k.ready)
                        if c is not None)
        if not clocks:
            if self._last_fleet is None:
                return None
            at, host = self._last_fleet  # nobody in service: the last clock, run on
            return at + (time.monotonic() - host) * 1000.0 * self.s.speedup
        now = clocks[len(clocks) // 2]
        if self._last_fleet is not None:
            now = max(now, self._last_fleet[0])
        self._last_fleet = (now, time.monotonic())
        return now

    @property
    def _gnd(self) -> Ground:
        """The ground side (node, bridge, LCM), there from launch() on."""
        if self.ground is None:
            raise GroundError("the flight has not been launched", 2)
        return self.ground

    def _t0(self) -> int:
        """t0 on the vehicles' clock (the mission's, else chosen at launch)."""
        if self.t0_ms is None:
            raise GroundError("the flight has no t0 before launch", 2)
        return self.t0_ms

    def tick_of(self, utc_ms: float | None) -> float | None:
        if utc_ms is None or self.t0_ms is None:
            return None
        return (utc_ms - self.t0_ms) / self.tick_ms

    # --- start -----------------------------------------------------------------------

    def _launch(self, c: Craft, cell: tuple[int, int], start_time_s: int, launched_utc_ms: float,
                home: tuple[float, float] | None = None) -> None:
        home = home or self.geo.cell_to_geodetic(*cell)
        folder = self.tmp / f"uav{c.id}-{len(c.spells)}"
        p = Process(self.s.sitl, self.defaults, folder, c.instance, c.sysid, home,
                    self.s.speedup, start_time_s)
        c.launch(p, launched_utc_ms)
        c.spells[-1]["home"] = list(cell)

    def _pump(self, timeout: float) -> None:
        if _STOP["asked"] and not _STOP["raised"]:
            _STOP["raised"] = True
            raise KeyboardInterrupt
        fds = [c.fileno() for c in self.crafts if c.fileno() >= 0]
        fds += [fd for r in self.relays.values() for fd in r.fds()]
        if self.ground is not None:
            fds += self.ground.fds()
        if fds:
            select.select(fds, [], [], timeout)
        else:
            time.sleep(timeout)
        for r in self.relays.values():
            r.pump()
        for c in self.crafts:
            c.pump()
        if self.ground is not None:
            self.ground.handle()
            self._take_ground()

    def start(self) -> None:
        s = self.s
        self.ground = Ground(self.tmp, s.algo, s.penalty or 0, s.url, s.prefix,
                             s.mission.takeoff_ticks)
        self._gnd.start_node()
        if self.t0_ms is not None:
            base = self.t0_ms // 1000 - BOOT_ALLOWANCE_S - self.allowance_s
        else:
            base = int(time.time())
        w0 = time.monotonic()
        for c, u in zip(self.crafts, s.mission.uavs):
            offset = round((time.monotonic() - w0) * s.speedup)
            self._launch(c, (u.x, u.y), base + offset, (base + offset) * 1000.0)
        report_ms = max(10, round(REPORT_VEHICLE_MS / s.speedup))
        lost_ms = max(500, round(LOST_VEHICLE_MS / s.speedup))
        for f in s.faults:
            if f["kind"] in UPLOAD_FAULTS:
                c = self.by_id[f["uav"]]
                self.relays[c.id] = Relay(f["kind"], c.id, c.instance, c.sysid, self.fleet_utc_ms,
                                          functools.partial(self._fault_at, f))
                self.relays[c.id].record["t_s"] = f["t_s"]
        self.bridge_cmd = self._gnd.start_bridge(
            [(c.id, self.relays[c.id].port if c.id in self.relays else 5760 + 10 * c.instance,
              c.sysid) for c in self.crafts], report_ms, lost_ms, CRUISE_M_S)
        self._say(f"booting {len(self.crafts)} vehicles")
        end = time.monotonic() + READY_TIMEOUT_WALL_S
        while not all(c.ready for c in self.crafts):
            self._pump(0.05)
            self._gnd.check_alive()
            for c in self.crafts:
                if c.unexpected_exit is not None:
                    raise SitlError(f"uav {c.id}: arducopter exited: {c.unexpected_exit}")
            if time.monotonic() > end:
                late = "; ".join(f"uav {c.id}: {c.not_ready_because()}"
                                 for c in self.crafts if not c.ready)
                raise SitlError(f"not ready within {READY_TIMEOUT_WALL_S} s of launch: {late}")
        # every clock at one host instant
        clocks = [t for t in (c.utc_ms() for c in self.crafts) if t is not None]
        if len(clocks) < len(self.crafts):
            raise SitlError("a vehicle that reported ready has no clock")
        self.clock_spread_ms = max(clocks) - min(clocks)
        if self.t0_ms is None:
            self.t0_ms = int(math.ceil((max(clocks) + self.allowance_s * 1000.0) / 1000.0)) * 1000
        frame_doc = dict(self.s.frame)
        frame_doc["t0"] = format_utc(self.t0_ms)
        self.frame_doc = frame_doc
        doc = s.mission.to_json()
        doc["frame"] = frame_doc
        self.mission_doc = doc
        if not self._gnd.wait(lambda: self._gnd.statuses > 0, 10):
            raise GroundError("no status from sva_node within 10 s", 3)
        self.name = self._gnd.publish_mission(doc)
        self._say("planning")
        end = time.monotonic() + PLAN_TIMEOUT_S
        while self.start_doc is None:
            self._pump(0.05)
            self._gnd.check_alive()
            if time.monotonic() > end:
                raise GroundError(f"no plan from sva_node within {PLAN_TIMEOUT_S} s", 3)

    def _say(self, text: str) -> None:
        if self.bar is not None:
            self.bar.set_description_str(text)
        elif self.s.progress:
            print(f"sva-tools: sitl: {text}", file=sys.stderr)

    # --- what the node and the bridge say ----------------------------------------------

    def _take_ground(self) -> None:
        from ..lcm import wire

        g = self._gnd
        # The bridge's lines first, then LCM: the replan a line is about was multicast to
        # this process and the bridge at once, so it is taken before the line.
        lines = g.bridge_lines()
        g.handle()
        if self.start_doc is None:
            first = g.first_plan()
            if first is not None:
                _at, p = first
                if p.status not in (p.STATUS_COMPLETE, p.STATUS_PARTIAL):
                    raise GroundError(f"the node did not plan the mission: {wire.diag_text(p)}",
                                      2 if p.status == p.STATUS_REJECTED else 1)
                plan = wire.plan_document(p, self.name)
                self.start_doc = plan
                self.residual_ready[str(p.plan_id)] = ({u.id: u.ready_at for u in self.s.mission.uavs}, 0)
                self.replans.append({"at": 0, "cause": "start", "mission": self.mission_doc,
                                     "plan": plan, "changes": {"dropped": [], "added": [],
                                                               "count": 0, "penalty": 0},
                                     "solve_us": p.solve_us, "live": None, "utc_ms": self.fleet_utc_ms(),
                                     "event_seq": None})
        while self.replans_seen < len(g.replans):
            _at, r = g.replans[self.replans_seen]
            self.replans_seen += 1
            try:
                doc = wire.replan_document(r, self.name)
            except wire.InputError:
                continue
            self.node_now = max(self.node_now, doc["now"])
            mine = self.awaiting.pop(doc["event_seq"], None)
            if mine is not None:
                mine["accepted"] = doc["accepted"]
                mine["now"] = doc["now"]
                if doc["accepted"]:
                    mine.pop("error", None)
                else:
                    mine["error"] = doc.get("error")
                    if doc["now"] > mine["published_at"] and mine.get("retries", 0) < 3:
                        # the node's clock (vehicle reports) passed the tick meanwhile:
                        # the ground says it again at the node's now
                        self._publish(mine, doc["now"])
            if not doc["accepted"] or "plan" not in doc:
                continue
            ch = doc["changes"]
            cause = doc["event"] if mine is not None else f"report:{doc['event']}"
            self._note_out(doc, cause)
            # a UAV serving a visit under way stands in the residual mission ready at the
            # window's end (docs/live.md)
            self.residual_ready[str(doc["plan"]["stats"]["plan_id"])] = (
                {u["id"]: u["ready_at"] for u in doc["residual"]["uavs"]}, doc["now"])
            self.replans.append({
                "at": doc["now"], "cause": cause, "mission": doc["residual"], "plan": doc["plan"],
                "changes": {"dropped": ch["dropped_visits"], "added": ch["added_visits"],
                            "count": ch["dropped"] + ch["added"],
                            "penalty": doc["change_penalty"] * (ch["dropped"] + ch["added"])},
                "solve_us": doc["plan"]["stats"]["solve_us"],
                "live": {"now": doc["now"], "revision": doc["revision"], "kept": doc["kept"],
                         "covered": doc["covered"], "under_way_count": doc["under_way"],
                         "objective": doc["objective"]},
                "utc_ms": self.fleet_utc_ms(), "event_seq": doc["event_seq"]})
        host = time.monotonic()
        for line in lines:
            now = self.fleet_utc_ms()
            self.bridge_log.append([now, line])
            parsed = g.parse_bridge_line(line)
            if parsed is not None and parsed["uav"] in self.by_id:
                self.held_lines.append((host, now, parsed))
        # A line about an upload is taken with the plan it uploads (its plan_id), which
        # can reach this process after the bridge acted on it; a line whose plan has not
        # arrived within PLAN_WAIT_S is taken without it.
        keep = []
        for at_host, now, parsed in self.held_lines:
            residual = self.residual_ready.get(parsed["plan"])
            if residual is None and host - at_host < PLAN_WAIT_S:
                keep.append((at_host, now, parsed))
                continue
            c = self.by_id[parsed["uav"]]
            busy = None
            if residual is not None and self.t0_ms is not None:
                ready, plan_now = residual[0].get(c.id), residual[1]
                if ready is not None and ready > plan_now:
                    busy = float(self.t0_ms + ready * self.tick_ms)
            c.on_upload(parsed, now, busy)
        self.held_lines = keep

    # --- faults (--fault) -------------------------------------------------------------

    def _fault_at(self, f: dict[str, Any]) -> float | None:
        """The fleet-clock instant (UTC ms) a fault arms at: None (from the start) for an
        upload fault without T_S; infinity while t0 is not known."""
        if f["t_s"] is None and f["kind"] in UPLOAD_FAULTS:
            return None
        if self.t0_ms is None:
            return math.inf
        return self.t0_ms + (f["t_s"] or 0.0) * 1000.0

    def _reboot(self, f: dict[str, Any]) -> None:
        """SIGKILL the vehicle's process and start a fresh one at once (fresh working
        folder, same instance, system id and ports), home where it is, on the ground."""
        c = self.by_id[f["uav"]]
        now = self.fleet_utc_ms()
        rec = {"kind": "reboot", "uav": c.id, "t_s": f["t_s"], "fired_utc_ms": now}
        self.fault_log.append(rec)
        if not c.in_service or c.spell is None:
            rec["skipped"] = "not in service"
            return
        own = c.utc_ms()
        if own is not None:
            rec["fired_utc_ms"] = own
        at = c.telemetry[-1] if c.telemetry else None
        home = (at[1], at[2]) if at is not None else self.geo.cell_to_geodetic(0, 0)
        cell = self.geo.geodetic_to_cell(*home)
        rec.update(position=[round(home[0], 7), round(home[1], 7)], cell=list(cell),
                   alt_m=None if at is None else round(at[3], 2))
        c.kill()
        start = int(round((own or now or time.time() * 1000.0) / 1000.0))
        self._launch(c, cell, start, own or now or start * 1000.0, home=home)

    def _note_out(self, doc: dict[str, Any], cause: str) -> None:
        """A faulty UAV's time out of service as the node sees it: from the replan that
        drops it from the residual fleet to the one that takes it back."""
        ids = {u["id"] for u in doc["residual"]["uavs"]}
        for uid in self.faulty:
            c = self.by_id[uid]
            is_out = bool(c.out) and c.out[-1][1] is None
            if uid not in ids and not is_out and cause == "report:uav_lost":
                c.out.append([doc["now"], None])
            elif uid in ids and is_out and cause == "report:uav_back":
                c.out[-1][1] = doc["now"]

    # --- the flight ------------------------------------------------------------------

    def _due(self, e: dict[str, Any]) -> bool:
        at_ms: float = self.t0_ms + e["at"] * self.tick_ms
        if e["type"] == "uav_lost" and e["uav"] in self.by_id:
            c = self.by_id[e["uav"]]
            own = c.utc_ms() if c.in_service else None
            if own is not None:
                return own >= at_ms
        now = self.fleet_utc_ms()
        return now is not None and now >= at_ms

    def _do(self, e: dict[str, Any]) -> None:
        now = self.fleet_utc_ms()
        rec = {"index": e["index"], "type": e["type"], "at": e["at"], "utc_ms": now}
        if "uav" in e:
            rec["uav"] = e["uav"]
        kind = e["type"]
        if kind == "uav_lost":
            c = self.by_id.get(e["uav"])
            if c is not None and c.in_service:
                own = c.utc_ms()
                rec["utc_ms"] = own if own is not None else now
                c.lose()
                c.out.append([e["at"], None])
            else:
                rec["skipped"] = "not in service"
        elif kind == "uav_back":
            c = self.by_id.get(e["uav"])
            if c is not None and not c.in_service:
                start = int(round((now or time.time() * 1000.0) / 1000.0))
                self._launch(c, (e["x"], e["y"]), start, now or start * 1000.0)
                if c.out:
                    c.out[-1][1] = e["at"]
            else:
                rec["skipped"] = "in service"
        else:
            rec["event"] = {k: v for k, v in e.items() if k != "index"}
            self._publish(rec, max(e["at"], self.node_now, self._gnd.report_now))
        self.flown_events.append(rec)

    def _publish(self, rec: dict[str, Any], at: int) -> None:
        """An event_t from the ground at tick `at` (its tick, or the node's clock when the
        vehicles' reports have moved it past)."""
        ev = dict(rec["event"], at=at)
        if "seq" in rec:
            rec["retries"] = rec.get("retries", 0) + 1
        rec["published_at"] = at
        seq = self._gnd.publish_event(ev)
        rec["seq"] = seq
        rec["host"] = time.monotonic()
        self.awaiting[seq] = rec

    def _last_end(self) -> int:
        ends: list[int] = [t.end for t in self.s.mission.targets] + [e["at"] for e in self.s.events]
        for e in self.s.events:
            if isinstance(e.get("target"), dict):
                ends.append(int(e["target"]["end"]))
        return max(ends + [0])

    def fly(self) -> None:
        from tqdm import tqdm

        last_end = self._last_end()
        extent = max([abs(v) for t in self.s.mission.targets for v in (t.x, t.y)] + [1])
        limit_tick = last_end + 4 * extent * self.s.mission.ticks_per_cell + 60
        self.bar = bar = tqdm(total=last_end, unit="tick", file=sys.stderr, disable=not self.s.progress,
                        dynamic_ncols=True, bar_format="{desc}: {n:.0f}/{total} ticks |{bar}| "
                                                       "{elapsed}")
        self._say("flying")
        linger: float | None = None
        try:
            while True:
                self._pump(0.02)
                self._gnd.check_alive()
                now_host = time.monotonic()
                for c in self.crafts:
                    own = c.utc_ms()
                    c.step(now_host, own is not None and own >= self._t0() - self.allowance_s * 1000)
                while self.pending and self._due(self.pending[0]):
                    self._do(self.pending.pop(0))
                for f in list(self.reboots):
                    at = self._fault_at(f)
                    fleet = self.fleet_utc_ms()
                    if at is not None and fleet is not None and fleet >= at:
                        self.reboots.remove(f)
                        self._reboot(f)
                for seq, rec in list(self.awaiting.items()):
                    if now_host - rec["host"] > EVENT_ANSWER_TIMEOUT_S:
                        rec["error"] = "no answer from sva_node"
                        del self.awaiting[seq]
                now = self.fleet_utc_ms()
                tick = self.tick_of(now)
                if tick is not None and now is not None:
                    shown = max(0, min(last_end, int(tick)))
                    if shown != bar.n:
                        bar.n = shown
                        bar.refresh()
                    if linger is None and not self.pending and not self.awaiting and not self.held_lines and \
                            not self.reboots and \
                            tick >= last_end and all(c.finished() for c in self.crafts):
                        linger = now + LINGER_MS
                    if linger is not None and now >= linger:
                        break
                    if tick > limit_tick:
                        self.ended_by = f"the time limit (tick {limit_tick})"
                        break
                elif not any(c.in_service for c in self.crafts) and not self.pending:
                    self.ended_by = "no vehicle left in service"
                    break
        finally:
            bar.close()
            self.bar = None
        self.end_utc_ms = self.fleet_utc_ms()

    def close(self, keep: str | None = None) -> None:
        if self.closed:
            return
        self.closed = True
        for c in self.crafts:
            c.kill()
        for r in self.relays.values():
            self.fault_log.append(r.log())
            r.close()
        if self.ground is not None:
            self.ground.close()
        if keep:
            shutil.copytree(self.tmp, keep, dirs_exist_ok=True)
        shutil.rmtree(self.tmp, ignore_errors=True)

    def log(self) -> dict[str, Any]:
        return judge.judge_log(record.record(self))
