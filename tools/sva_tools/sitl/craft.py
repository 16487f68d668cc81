"""One UAV of a `sva-tools sitl` flight as the ground operator sees it: its SITL
process (one per spell in service), what its operator link hears (clock, position,
mode, armed state, mission item in progress, holds), the missions the bridge uploaded to
it (read back from the vehicle) and the operator's one job: arming it in AUTO once it
holds a mission. The planner never arms; this is the pilot's switch.
"""
from __future__ import annotations

import math
import time
from typing import TYPE_CHECKING, Any, Protocol

from .vehicle import (
    COPTER_AUTO,
    COPTER_GUIDED,
    EKF_POS_HORIZ_ABS,
    MAV_MODE_FLAG_SAFETY_ARMED,
    STREAMS_US,
    Clock,
    Link,
    MissionReader,
    Process,
)

if TYPE_CHECKING:
    from .ground import BridgeLine

MAV_CMD_NAV_DELAY = 93
MAV_CMD_NAV_RETURN_TO_LAUNCH = 20
COPTER_RTL = 6
COPTER_LAND = 9
ARM_RETRY_VEHICLE_S = 1.0  # vehicle seconds between two arming steps
TEXTS_KEPT = 40


class MissionItem(Protocol):
    """The fields read of a MISSION_ITEM_INT (a pymavlink message: pymavlink has no type
    hints, so the messages themselves are Any)."""

    seq: int
    command: int
    param1: float
    param2: float
    param3: float
    param4: float
    x: int
    y: int
    z: float


class Spell:
    """One arducopter process of a UAV and the operator's link to it."""

    def __init__(self, process: Process, sysid: int, speedup: float, launched_utc_ms: float):
        self.process = process
        self.link = Link(process.serial1_port, sysid)
        self.clock = Clock(speedup)
        self.reader = MissionReader()
        self.launched_utc_ms = launched_utc_ms   # the fleet's clock at launch
        self.heard: set[int] = set()
        self.streams_due = 0.0
        self.gps_fix = 0
        self.ekf_ok = False
        self.ready_utc_ms: float | None = None
        self.ready_host: float | None = None


class Craft:
    def __init__(self, uav_id: int, index: int, speedup: float):
        self.id = uav_id
        self.instance = index
        self.sysid = index + 1
        self.speedup = speedup
        self.spell: Spell | None = None
        self.spells: list[dict[str, Any]] = []
        self.in_service = False
        self.out: list[list[int | None]] = []  # [lost tick, back tick (None: not yet)]
        self.telemetry: list[list[float]] = []  # [utc_ms, lat, lon, rel_alt_m]
        self.armed = False
        self.mode: int | None = None
        self.current: int | None = None
        self.currents: list[list[float | None]] = []  # [utc_ms, seq]
        self.reached: list[list[float | None]] = []   # [utc_ms, seq]
        self.uploads: list[dict[str, Any]] = []       # bridge lines for this UAV
        self.mission_version = 0               # accepted uploads (bridge) this spell
        self.start_wanted = False              # a mission uploaded and not started yet
        self.pause_until: float | None = None   # GUIDED until this UTC ms (a hold's end)
        self.pause_item: tuple[Any, Any] | None = None  # the hold item paused, and its waypoint
        self.pauses: list[dict[str, Any]] = []
        self.start_asked_host: float | None = None
        self.start_seen = False                # item 1..3 began since the start was asked
        self.current_command: int | None = None
        self.current_item: Any = None  # pymavlink messages (untyped)
        self.current_wp: Any = None
        self.items: list[Any] = []          # the mission it holds (read back)
        self.missions: list[dict[str, Any]] = []  # every read-back: {utc_ms, items}
        self.holds: list[dict[str, Any]] = []
        self.starts: list[dict[str, Any]] = []    # {utc_ms, version, was_armed, mode, started_utc_ms}
        self.reenter_auto = False              # a start from the ground in AUTO: leave AUTO first
        self.texts: list[list[Any]] = []      # [utc_ms, text]
        self.next_try = 0.0
        self.unexpected_exit: str | None = None

    # --- spells ----------------------------------------------------------------------

    def launch(self, process: Process, launched_utc_ms: float) -> None:
        self.spell = Spell(process, self.sysid, self.speedup, launched_utc_ms)
        self.in_service = True
        self.armed, self.mode, self.current, self.items = False, None, None, []
        self.mission_version = 0
        self.start_wanted, self.start_seen, self.current_command = False, False, None
        self.current_item = self.current_wp = None
        self.pause_until = self.pause_item = None
        self.spells.append({"launched_utc_ms": launched_utc_ms, "start_time_s": process.start_time_s,
                            "home": None, "ready_utc_ms": None, "ready_wall_s": None})

    def kill(self) -> None:
        """SIGKILL its process (a loss; or the end of the flight)."""
        if self.spell is not None:
            self.spell.link.close()
            self.spell.process.kill()

    def lose(self) -> None:
        self.kill()
        self.in_service = False
        self.spell = None

    @property
    def clock(self) -> Clock | None:
        return self.spell.clock if self.spell is not None else None

    def utc_ms(self) -> float | None:
        return self.spell.clock.utc_ms() if self.spell is not None else None

    def not_ready_because(self) -> str:
        sp = self.spell
        if sp is None:
            return "out of service"
        why = []
        if sp.link.sock is None:
            why.append("no operator link")
        if sp.clock.offset_ms is None:
            why.append("no GPS time")
        if sp.gps_fix < 3:
            why.append(f"GPS fix type {sp.gps_fix}")
        if not sp.ekf_ok:
            why.append("no EKF position")
        return ", ".join(why) or "ready"

    @property
    def ready(self) -> bool:
        return self.spell is not None and self.spell.ready_utc_ms is not None

    # --- the link --------------------------------------------------------------------

    def fileno(self) -> int:
        return self.spell.link.fileno() if self.spell is not None else -1

    def pump(self) -> None:
        """Connects, asks for streams, and takes in every message that arrived."""
        sp = self.spell
        if sp is None:
            return
        if sp.link.sock is None and not sp.link.closed:
            if not sp.link.connect():
                if not sp.process.alive() and self.unexpected_exit is None:
                    self.unexpected_exit = sp.process.tail()
                return
        for m in sp.link.poll():
            sp.heard.add(m.get_msgId())
            self._take(sp, m)
        # Streams are asked once the vehicle speaks (earlier requests can be lost while
        # it boots), and again each second for those not heard yet.
        missing = [k for k in STREAMS_US if k not in sp.heard]
        if missing and sp.heard and time.monotonic() >= sp.streams_due:
            sp.link.ask_streams(missing)
            sp.streams_due = time.monotonic() + 1.0
        sp.reader.retry(sp.link)
        if sp.ready_utc_ms is None and sp.clock.offset_ms is not None and sp.gps_fix >= 3 \
                and sp.ekf_ok:
            sp.ready_utc_ms = sp.clock.utc_ms()
            sp.ready_host = time.monotonic()
            self.spells[-1]["ready_utc_ms"] = sp.ready_utc_ms
            self.spells[-1]["ready_wall_s"] = round(sp.ready_host - sp.process.launched, 3)

    def _take(self, sp: Spell, m: Any) -> None:  # m: a pymavlink message (untyped)
        kind = m.get_type()
        if kind == "GLOBAL_POSITION_INT":
            sp.clock.on_boot(m.time_boot_ms)
            at = sp.clock.utc_ms(m.time_boot_ms)
            if at is not None:
                self.telemetry.append([at, m.lat / 1e7, m.lon / 1e7, m.relative_alt / 1000.0])
        elif kind == "SYSTEM_TIME":
            sp.clock.on_system_time(m.time_unix_usec, m.time_boot_ms)
        elif kind == "HEARTBEAT":
            if m.autopilot == 3:  # MAV_AUTOPILOT_ARDUPILOTMEGA: the vehicle, not a GCS
                self.armed = bool(m.base_mode & MAV_MODE_FLAG_SAFETY_ARMED)
                self.mode = m.custom_mode
        elif kind == "MISSION_CURRENT":
            self._current(m.seq)
        elif kind == "STATUSTEXT":
            text = m.text.rstrip("\0") if isinstance(m.text, str) else str(m.text)
            now = sp.clock.utc_ms()
            self.texts = (self.texts + [[now, text]])[-TEXTS_KEPT:]
            if text.startswith("Mission: "):
                try:
                    self._current(int(text.split()[1]))
                except (IndexError, ValueError):
                    pass
        elif kind == "MISSION_ITEM_REACHED":
            self.reached.append([sp.clock.utc_ms(), m.seq])
        elif kind == "GPS_RAW_INT":
            sp.gps_fix = m.fix_type
        elif kind == "EKF_STATUS_REPORT":
            sp.ekf_ok = bool(m.flags & EKF_POS_HORIZ_ABS)
        elif kind in ("MISSION_COUNT", "MISSION_ITEM_INT", "MISSION_ITEM"):
            items = sp.reader.on_message(sp.link, m)
            if items is not None:
                self.items = items
                self.missions.append({"utc_ms": sp.clock.utc_ms(),
                                      "items": [_item_json(i) for i in items]})
                # The vehicle switched to this mission when its upload ended, before the
                # read-back: the item in progress is this mission's (a paused hold keeps
                # the item it was paused in).
                seq = self.current
                if seq is not None and 0 <= seq < len(items):
                    self.current_item = items[seq]
                    self.current_wp = items[seq - 1] if seq >= 1 else None
                    self.current_command = self.current_item.command

    def _current(self, seq: int) -> None:
        """The vehicle began item seq. The item it left is the one it began under the
        mission it held then (a re-upload does not rename the item in progress)."""
        if seq == self.current:
            return
        now = self.utc_ms()
        ended, ended_wp = self.current_item, self.current_wp
        self.current = seq
        self.currents.append([now, seq])
        self.current_item = self.items[seq] if 0 <= seq < len(self.items) else None
        self.current_wp = self.items[seq - 1] if 1 <= seq <= len(self.items) else None
        self.current_command = self.current_item.command if self.current_item is not None else None
        if self.start_asked_host is not None and 1 <= seq <= 3:
            self.start_seen = True
        if ended is not None and ended.command == MAV_CMD_NAV_DELAY and self.pause_until is None:
            # a hold the operator's start of a new mission ended (the replan sent the UAV
            # elsewhere before that window began) is cut, not ended by the clock
            self._hold_ended(ended, ended_wp, now, cut=self.start_asked_host is not None)

    def _hold_ended(self, item: MissionItem, wp: MissionItem | None, now: float | None,
                    cut: bool = False) -> None:
        hold: dict[str, Any] = {"seq": item.seq, "ended_utc_ms": now, "until_tod_s": _tod_s(item), "cut": cut}
        if wp is not None:
            hold["wp"] = (wp.x / 1e7, wp.y / 1e7)
        self.holds.append(hold)

    # --- missions and arming -----------------------------------------------------------

    def on_upload(self, line: BridgeLine, utc_ms: float | None, busy_until: float | None) -> None:
        """A bridge line about this UAV. After an accepted upload the operator starts the
        new mission from its first item: ArduPilot would go on with the new mission's
        item at the index it was flying (it restarts that command when its mission
        changes). A vehicle holding a target that the replan leaves serving a visit under
        way (busy_until: the UTC ms of its residual ready_at, when later than the replan's
        now) is first put in GUIDED, holding its position, until then; then the new
        mission starts."""
        self.uploads.append({"utc_ms": utc_ms, "plan": line["plan"], "text": line["text"]})
        if self.spell is None:
            return
        if line["text"].startswith("uploading") and self.armed and self.holding() and \
                busy_until is not None and self.pause_until is None:
            self.pause_until = busy_until
            self.pause_item = (self.current_item, self.current_wp)
            self.spell.link.set_mode(COPTER_GUIDED)
            self.pauses.append({"utc_ms": self.utc_ms(), "until_utc_ms": busy_until})
        if line["items"] is None:
            return
        self.mission_version += 1
        self.uploads[-1]["items"] = line["items"]
        returns_only = line["items"] <= 2   # home and RTL: nothing to take off for
        self.uploads[-1]["returns_only"] = returns_only
        self.start_wanted = not (returns_only and not self.armed)
        self.start_asked_host = None
        self.start_seen = False
        self.spell.reader.start(self.spell.link)

    def holding(self) -> bool:
        return self.current_command == MAV_CMD_NAV_DELAY

    def step(self, now_host: float, may_start: bool) -> None:
        """The operator's work on this vehicle: keep a paused vehicle in GUIDED until its
        hold's time, then start the mission it holds; start a new mission (may_start: the
        clock allows a take-off)."""
        if self.spell is None or not self.ready:
            return
        if self.pause_until is not None:
            now = self.utc_ms()
            if now is not None and now >= self.pause_until:
                if self.pause_item is not None:
                    item, wp = self.pause_item
                    # cut: the replan ended the visit before the time the item held until
                    until = tod_instant_ms(_tod_s(item), now)
                    self._hold_ended(item, wp, now, cut=until - now > 1000.0)
                    self.current_item, self.current_command = None, None  # that hold is over
                self.pauses[-1]["ended_utc_ms"] = now
                self.pause_until = self.pause_item = None
                self.start_wanted = True
                self.start_asked_host = None
                self.start_seen = False
            else:
                if self.mode != COPTER_GUIDED and now_host >= self.next_try:
                    self.next_try = now_host + max(0.05, ARM_RETRY_VEHICLE_S / self.speedup)
                    self.spell.link.set_mode(COPTER_GUIDED)
                return
        if self.start_wanted and may_start:
            self.try_start(now_host)

    def try_start(self, now_host: float) -> None:
        """One step towards flying the new mission from item 1 in AUTO, armed: the first
        item, the mode, then the arming command, retried until the vehicle shows them."""
        if now_host < self.next_try or self.spell is None:
            return
        self.next_try = now_host + max(0.05, ARM_RETRY_VEHICLE_S / self.speedup)
        link = self.spell.link
        if self.start_asked_host is None:
            self.start_asked_host = now_host
            self.starts.append({"utc_ms": self.utc_ms(), "version": self.mission_version,
                                "was_armed": self.armed, "mode": self.mode})
            # On the ground in AUTO (it landed at the end of a mission): ArduCopter runs a
            # mission when it enters AUTO, not when it is armed, so it leaves AUTO first.
            self.reenter_auto = not self.armed and self.mode == COPTER_AUTO
        if not self.start_seen:
            link.send("mission_set_current", self.sysid, 1, 1)
        if self.reenter_auto:
            if self.mode == COPTER_AUTO:
                link.set_mode(COPTER_GUIDED)
                return
            self.reenter_auto = False
        if self.mode != COPTER_AUTO:
            link.set_mode(COPTER_AUTO)
        elif not self.armed:
            link.arm()
        if self.start_seen and self.armed and self.mode == COPTER_AUTO:
            self.start_wanted = self.start_seen = False
            self.start_asked_host = None
            self.starts[-1]["started_utc_ms"] = self.utc_ms()

    def finished(self) -> bool:
        """Nothing left to fly: out of service, or on its way home (RTL, landing), or on
        the ground with no mission to start."""
        if self.spell is None:
            return True
        if self.start_wanted or self.spell.reader.active or self.pause_until is not None:
            return False
        if not self.armed:
            return True
        if self.mode in (COPTER_RTL, COPTER_LAND):
            return True
        return self.current_command == MAV_CMD_NAV_RETURN_TO_LAUNCH


def _tod_s(item: MissionItem) -> int:
    """The UTC time of day (s) a MAV_CMD_NAV_DELAY item holds until."""
    return int(item.param2) * 3600 + int(item.param3) * 60 + int(item.param4)


def tod_instant_ms(tod_s: int, near_ms: float) -> float:
    """The UTC instant (ms) of a time of day nearest to near_ms."""
    day = math.floor(near_ms / 86_400_000) * 86_400_000
    return float(min((d + tod_s * 1000 for d in (day - 86_400_000, day, day + 86_400_000)),
                     key=lambda c: abs(c - near_ms)))


def _num(v: float) -> float | None:
    return None if v != v else round(float(v), 7)  # NaN (the vehicle's choice): null


def _item_json(m: MissionItem) -> list[float | None]:
    """[seq, command, param1..4, lat, lon, alt] of a MISSION_ITEM_INT (NaN as null)."""
    return [m.seq, m.command, _num(m.param1), _num(m.param2), _num(m.param3), _num(m.param4),
            m.x / 1e7, m.y / 1e7, _num(m.z)]
