"""A plan's routes as MAVLink missions, uploaded over the MAVLink mission protocol
(`sva-tools mavlink`)."""
from __future__ import annotations

import functools
import math
import re
import select
import socket
import struct
import time
from dataclasses import dataclass
from typing import Any, Callable

from . import io
from .frame import Frame as GeoFrame
from .model import SVA_MAX_ID, Mission, Uav
from .text import shown

# MAVLink common.xml values (pymavlink.dialects.v20.common has the same names).
MAV_CMD_NAV_WAYPOINT = 16
MAV_CMD_NAV_RETURN_TO_LAUNCH = 20
MAV_CMD_NAV_TAKEOFF = 22
MAV_CMD_NAV_DELAY = 93
MAV_CMD_DO_CHANGE_SPEED = 178
MAV_FRAME_MISSION = 2
MAV_FRAME_GLOBAL_RELATIVE_ALT_INT = 6

MAX_ROUTE_TARGETS = 256                # SVA_MAVLINK_MAX_ROUTE_TARGETS
MAX_HOLD_MS = 86_400_000               # SVA_MAVLINK_MAX_HOLD_MS
MIN_RADIUS_M = 6335439.327             # SVA_MAVLINK_MIN_RADIUS_M: b^2 / a of WGS84
TIMEOUT_MS = 1500                      # the MAVLink mission protocol's defaults
RETRIES = 5
OWN_SYSTEM = 250
OWN_COMPONENT = 190                    # MAV_COMP_ID_MISSIONPLANNER

# The last instant a frame names (sva_frame.h SVA_FRAME_MAX_T0_MS).
MAX_T0_MS = 253402300799999


@dataclass(frozen=True)
class Frame:
    lat_e7: int
    lon_e7: int
    alt_cm: int
    cell_cm: int
    tick_ms: int
    t0_ms: int

    def tick_utc_ms(self, tick: int) -> int:
        return self.t0_ms + tick * self.tick_ms


@dataclass(frozen=True)
class Item:
    command: int
    frame: int
    param1: float
    param2: float
    param3: float
    param4: float
    x: int
    y: int
    z: float


def _round_half_away(v: float) -> int:
    return int(math.floor(abs(v) + 0.5)) * (1 if v >= 0 else -1)


def frame_from_json(doc: dict[str, Any]) -> Frame:
    """The integers of a frame that passed validation (the mission and plan schemas and
    SPEC section 4's t0 rules, sva_tools.frame), as sva_frame_t holds them."""
    f = GeoFrame.from_json(doc)
    return Frame(_round_half_away(f.lat * 1e7), _round_half_away(f.lon * 1e7),
                 _round_half_away(f.alt_m * 100), _round_half_away(f.cell_m * 100), f.tick_ms,
                 f.t0_ms)


def _f32(v: float) -> float:
    value: float = struct.unpack("<f", struct.pack("<f", v))[0]
    return value


def _f32_up(v: float) -> float:
    """v rounded up to a float32."""
    f = _f32(v)
    if f < v:
        bits = struct.unpack("<I", struct.pack("<f", f))[0]
        bits = bits + 1 if f >= 0 else bits - 1
        f = struct.unpack("<f", struct.pack("<I", bits))[0]
    return f


def speed_m_s(frame: Frame, ticks_per_cell: int) -> float:
    """The commanded ground speed: cell / (ticks_per_cell * tick), times
    (1 + alt / MIN_RADIUS_M), rounded up to a float32 (docs/mavlink.md)."""
    v = (frame.cell_cm / 100.0) / (ticks_per_cell * frame.tick_ms / 1000.0)
    return _f32_up(v * (1.0 + (frame.alt_cm / 100.0) / MIN_RADIUS_M))


def cell_to_geo(frame: Frame, x: int, y: int) -> tuple[int, int]:
    """Cell (x, y) in 1e-7 degree: x * cell east and y * cell north of the origin in its
    local East-North-Up plane (pymap3d.enu2geodetic, WGS84)."""
    import pymap3d
    cell = frame.cell_cm / 100.0
    lat, lon, _ = pymap3d.enu2geodetic(x * cell, y * cell, 0.0, frame.lat_e7 / 1e7,
                                       frame.lon_e7 / 1e7, 0.0)
    return _round_half_away(float(lat) * 1e7), _round_half_away(float(lon) * 1e7)


def build_items(frame: Frame, m: Mission, uav: Uav, target_ids: list[int]) -> list[Item]:
    """The items of one UAV's route (none when it has no targets). InputError naming the
    UAV and the rule when the route cannot be carried."""
    if not target_ids:
        return []
    if len(target_ids) > MAX_ROUTE_TARGETS:
        raise io.InputError(f"uav {uav.id}: route: {len(target_ids)} targets need "
                            f"{3 + 2 * len(target_ids)} mission items, more than the limit "
                            f"{3 + 2 * MAX_ROUTE_TARGETS}")
    by_id = m.target_by_id()
    alt = _f32(frame.alt_cm / 100.0)
    nan = float("nan")
    lat, lon = cell_to_geo(frame, uav.x, uav.y)
    items = [Item(MAV_CMD_NAV_TAKEOFF, MAV_FRAME_GLOBAL_RELATIVE_ALT_INT, 0, 0, 0, nan, lat, lon, alt),
             Item(MAV_CMD_DO_CHANGE_SPEED, MAV_FRAME_MISSION, 1, speed_m_s(frame, m.ticks_per_cell),
                  -1, 0, 0, 0, 0)]
    at, departure = (uav.x, uav.y), uav.ready_at
    for i, tid in enumerate(target_ids):
        t = by_id[tid]
        travel = (abs(t.x - at[0]) + abs(t.y - at[1])) * m.ticks_per_cell
        if departure + travel > t.start:
            raise io.InputError(f"uav {uav.id}: targets[{i}] (id {t.id}): leaving at tick "
                                f"{departure} and flying {travel} ticks arrives after the "
                                f"window's start {t.start}")
        end_ms = frame.tick_utc_ms(t.end)
        if end_ms > MAX_T0_MS:
            raise io.InputError(f"uav {uav.id}: targets[{i}] (id {t.id}).end: tick {t.end} is "
                                f"outside the frame's UTC range (1970 to 9999)")
        hold = end_ms - frame.tick_utc_ms(departure)
        if hold >= MAX_HOLD_MS:
            raise io.InputError(f"uav {uav.id}: targets[{i}] (id {t.id}): from the departure at "
                                f"tick {departure} to the window's end {t.end} is {hold} ms, "
                                f"must be < 86400000 (MAV_CMD_NAV_DELAY holds until a UTC "
                                f"time of day)")
        lat, lon = cell_to_geo(frame, t.x, t.y)
        items.append(Item(MAV_CMD_NAV_WAYPOINT, MAV_FRAME_GLOBAL_RELATIVE_ALT_INT, 0, 0, 0, nan,
                          lat, lon, alt))
        tod = ((end_ms + 999) // 1000) % 86400
        items.append(Item(MAV_CMD_NAV_DELAY, MAV_FRAME_MISSION, -1, tod // 3600, (tod // 60) % 60,
                          tod % 60, 0, 0, 0))
        at, departure = (t.x, t.y), t.end
    items.append(Item(MAV_CMD_NAV_RETURN_TO_LAUNCH, MAV_FRAME_MISSION, 0, 0, 0, 0, 0, 0, 0))
    return items


def prepend_home(takeoff: Item) -> Item:
    """ArduPilot's item 0 (it overwrites it with its home): a waypoint at the take-off's
    position, altitude 0 (sva_mavlink_prepend_home)."""
    return Item(MAV_CMD_NAV_WAYPOINT, takeoff.frame, takeoff.param1, takeoff.param2,
                takeoff.param3, 0.0, takeoff.x, takeoff.y, 0.0)


_ACK_NAMES = {0: "MAV_MISSION_ACCEPTED", 1: "MAV_MISSION_ERROR", 2: "MAV_MISSION_UNSUPPORTED_FRAME",
              3: "MAV_MISSION_UNSUPPORTED", 4: "MAV_MISSION_NO_SPACE", 5: "MAV_MISSION_INVALID",
              6: "MAV_MISSION_INVALID_PARAM1", 7: "MAV_MISSION_INVALID_PARAM2",
              8: "MAV_MISSION_INVALID_PARAM3", 9: "MAV_MISSION_INVALID_PARAM4",
              10: "MAV_MISSION_INVALID_PARAM5_X", 11: "MAV_MISSION_INVALID_PARAM6_Y",
              12: "MAV_MISSION_INVALID_PARAM7", 13: "MAV_MISSION_INVALID_SEQUENCE",
              14: "MAV_MISSION_DENIED", 15: "MAV_MISSION_OPERATION_CANCELLED"}


# --- frames out of untrusted bytes -------------------------------------------------

_STX_V2 = 0xFD
_STX_V1 = 0xFE
_HEADER_V2 = 10
_HEADER_V1 = 6
_CRC_LEN = 2
_SIGNATURE_LEN = 13
_IFLAG_SIGNED = 0x01
_GOOD, _BAD, _INCOMPLETE = range(3)


def _dialect() -> Any:
    """pymavlink's MAVLink 2 common dialect (imported on first use: it is slow to load)."""
    from pymavlink.dialects.v20 import common
    return common


class Frames:
    """MAVLink 1 and 2 frames out of untrusted bytes, by the rules of the C library's
    parser (docs/mavlink.md "Stray and broken bytes"). pymavlink decodes each candidate
    (`MAVLink.decode`: length, checksum with CRC_EXTRA, payload); this class finds where
    a candidate starts and how long its header says it is, and judges it as soon as it
    can: an incompatibility flag, a message id common.xml lacks, a payload longer than
    the message's or a failed decode make it bad. A bad candidate loses its first byte
    only and the search resumes right after it, so a good frame behind stray, truncated
    or corrupted bytes is always found (pymavlink's own parser takes a bad header's
    length as its frame, and keeps that state from one call to the next).

    Signed frames are not taken (counted in `signed`): this side holds no key to check
    a signature, and a frame that claims one without it would take the next frame's
    first 13 bytes. `datagram()` parses one datagram on its own; `stream()` holds the
    bytes of a candidate whose declared length has not arrived yet (under 280)."""

    def __init__(self) -> None:
        dialect = _dialect()
        self._map = dialect.mavlink_map
        self._mav = dialect.MAVLink(None)
        self._held = bytearray()
        self.signed = 0  # signed frames with a good checksum, not taken

    def datagram(self, data: bytes) -> list[Any]:
        out: list[Any] = []
        self._scan(bytearray(data), out, final=True)
        return out

    def stream(self, data: bytes) -> list[Any]:
        out: list[Any] = []
        self._held = self._scan(self._held + data, out, final=False)
        return out

    def _scan(self, buf: bytearray, out: list[Any], final: bool) -> bytearray:
        i = 0
        while i < len(buf):
            if buf[i] != _STX_V2 and buf[i] != _STX_V1:
                starts = [k for k in (buf.find(_STX_V2, i), buf.find(_STX_V1, i)) if k >= 0]
                i = min(starts) if starts else len(buf)
                continue
            verdict, msg, size = self._judge(buf, i)
            if verdict == _GOOD:
                out.append(msg)
                i += size
            elif verdict == _INCOMPLETE and not final:
                break
            else:
                i += 1
        return buf[i:]

    def _judge(self, buf: bytearray, i: int) -> tuple[int, object, int]:
        v2 = buf[i] == _STX_V2
        header = _HEADER_V2 if v2 else _HEADER_V1
        have = len(buf) - i
        flags = 0
        if v2:
            if have < 3:
                return _INCOMPLETE, None, 0
            flags = buf[i + 2]
            if flags & ~_IFLAG_SIGNED:
                return _BAD, None, 0
        if have < header:
            return _INCOMPLETE, None, 0
        length = buf[i + 1]
        msgid = (buf[i + 7] | buf[i + 8] << 8 | buf[i + 9] << 16) if v2 else buf[i + 5]
        kind = self._map.get(msgid)
        if kind is None or length > kind.unpacker.size:
            return _BAD, None, 0
        size = header + length + _CRC_LEN + (_SIGNATURE_LEN if flags else 0)
        if have < size:
            # A signed candidate is never taken: no need to wait for its signature.
            return (_BAD if flags else _INCOMPLETE), None, 0
        try:
            msg = self._mav.decode(bytearray(buf[i:i + size]))
        except Exception:  # noqa: BLE001 -- MAVError, struct.error: a bad candidate
            return _BAD, None, 0
        if flags:
            self.signed += 1
            return _BAD, None, 0
        return _GOOD, msg, size


# --- links ---------------------------------------------------------------------------

AUTOPILOT_COMPONENT = 1                # MAV_COMP_ID_AUTOPILOT1
RECONNECT_S = 0.5                      # SVA_MAVLINK_RECONNECT_MS
CONNECT_TIMEOUT_S = 3.0                # SVA_MAVLINK_CONNECT_TIMEOUT_MS


@dataclass(frozen=True)
class Vehicle:
    """A `--vehicle UAV_ID=udp|tcp:HOST:PORT[:SYSID]`, its address resolved once."""
    uav: int
    transport: str
    host: str
    port: int
    sysid: int
    family: int = 0
    address: tuple[Any, ...] = ()

    @property
    def endpoint(self) -> str:
        return f"{self.transport}:{self.host}:{self.port}"


class Link:
    """One vehicle's socket. UDP: connected to the vehicle's address and port, so the
    kernel delivers datagrams from there only, each parsed on its own. TCP: a
    connection (tried again every RECONNECT_S while it is not made), parsed as a
    stream. Used as the pymavlink MAVLink object's file: write() sends one frame."""

    def __init__(self, vehicle: Vehicle) -> None:
        self.vehicle = vehicle
        self.tcp = vehicle.transport == "tcp"
        self.frames = Frames()
        self.error = ""          # why a TCP link is not up
        self.lost = False        # a TCP connection that was up is gone
        self.next_connect = 0.0
        self.sock: socket.socket | None = None
        if not self.tcp:
            self.sock = socket.socket(vehicle.family, socket.SOCK_DGRAM)
            self.sock.connect(vehicle.address)

    def up(self) -> bool:
        return self.sock is not None

    def connect(self, now: float, budget_s: float) -> bool:
        """A TCP connection attempt when one is due; True when it was made now."""
        if self.up() or self.lost or now < self.next_connect:
            return False
        self.next_connect = now + RECONNECT_S
        sock = socket.socket(self.vehicle.family, socket.SOCK_STREAM)
        sock.settimeout(max(0.05, min(CONNECT_TIMEOUT_S, budget_s)))
        try:
            sock.connect(self.vehicle.address)
        except socket.timeout:
            sock.close()
            self.error = f"no connection after {int(CONNECT_TIMEOUT_S * 1000)} ms"
            return False
        except OSError as e:
            sock.close()
            self.error = e.strerror or str(e)
            return False
        sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.sock = sock
        return True

    def _lose(self, why: str) -> list[Any]:
        self.close()
        self.lost, self.error = True, why
        return []

    def write(self, data: bytes) -> None:
        if self.sock is None:
            return  # TCP not connected yet: the upload's timeout resends
        try:
            if self.tcp:
                self.sock.sendall(data)
            else:
                self.sock.send(data)
        except OSError as e:
            if self.tcp:
                self._lose(e.strerror or str(e))
            elif not isinstance(e, ConnectionRefusedError):
                raise  # refused: an ICMP error of an earlier datagram (nobody listening yet)

    def receive(self, wait_s: float) -> list[Any]:
        """The messages that arrive within wait_s (every good frame, any sender)."""
        if self.sock is None:
            time.sleep(wait_s)
            return []
        if not select.select([self.sock], [], [], wait_s)[0]:
            return []
        try:
            data = self.sock.recv(65535)
        except OSError as e:
            if self.tcp:
                return self._lose(e.strerror or str(e))
            if isinstance(e, ConnectionRefusedError):
                return []
            raise
        if not self.tcp:
            return self.frames.datagram(data)
        return self.frames.stream(data) if data else self._lose("closed by the vehicle")

    def close(self) -> None:
        if self.sock is not None:
            self.sock.close()
        self.sock = None


def upload(vehicle: Vehicle, items: list[Item], timeout_ms: int = TIMEOUT_MS,
           retries: int = RETRIES) -> str | None:
    """The MAVLink mission protocol, sender side, with pymavlink's codec. None when
    the vehicle accepted the mission, else the reason. Only messages of the vehicle's
    system id and component 1 (MAV_COMP_ID_AUTOPILOT1), to this side's system id and
    of the mission type count."""
    dialect = _dialect()
    link = Link(vehicle)
    mav = dialect.MAVLink(link, srcSystem=OWN_SYSTEM, srcComponent=OWN_COMPONENT)
    timeout = timeout_ms / 1000.0
    try:
        def heartbeat() -> None:
            mav.heartbeat_send(dialect.MAV_TYPE_GCS, dialect.MAV_AUTOPILOT_INVALID, 0, 0,
                               dialect.MAV_STATE_ACTIVE)

        def send_count() -> None:
            mav.mission_count_send(vehicle.sysid, AUTOPILOT_COMPONENT, len(items), 0)

        def send_item(seq: int) -> None:
            it = items[seq]
            mav.mission_item_int_send(vehicle.sysid, AUTOPILOT_COMPONENT, seq, it.frame,
                                      it.command, 1 if seq == 0 else 0, 1, it.param1, it.param2,
                                      it.param3, it.param4, it.x, it.y, it.z, 0)

        resend: Callable[[], None] = send_count
        what = "MISSION_COUNT"
        tries, sent = 0, set[int]()
        now = time.monotonic()
        deadline, next_hb = now + timeout, now + 1.0
        if link.up():
            heartbeat()
            send_count()
        while True:
            now = time.monotonic()
            if link.tcp and not link.up():
                if link.lost:
                    return (f"link: {vehicle.endpoint}: connection lost during the upload: "
                            f"{link.error}")
                if link.connect(now, deadline - now):
                    # The MISSION_COUNT goes out now, with every retry still to come.
                    heartbeat()
                    send_count()
                    now = time.monotonic()
                    tries, deadline, next_hb = 0, now + timeout, now + 1.0
            if now >= deadline:
                if tries >= retries:
                    why = f"timeout: no answer to {what} after {tries + 1} tries of {timeout_ms} ms"
                    if link.tcp and not link.up():
                        why += f"; {vehicle.endpoint} not connected: {link.error or 'connecting'}"
                    if link.frames.signed:
                        why += (f"; {link.frames.signed} signed frames not taken (this side "
                                f"checks no MAVLink signature)")
                    return why
                tries += 1
                resend()
                deadline = now + timeout
            if now >= next_hb and link.up():
                heartbeat()
                next_hb = now + 1.0
            for msg in link.receive(0.05):
                if msg.get_srcSystem() != vehicle.sysid or \
                        msg.get_srcComponent() != AUTOPILOT_COMPONENT:
                    continue  # another system or component: not the vehicle's autopilot
                kind = msg.get_type()
                if kind not in ("MISSION_REQUEST_INT", "MISSION_REQUEST", "MISSION_ACK") or \
                        msg.target_system != OWN_SYSTEM or msg.mission_type != 0:
                    continue
                if kind == "MISSION_ACK":
                    if msg.type != 0:
                        name = _ACK_NAMES.get(msg.type, "an unknown MAV_MISSION_RESULT")
                        return f"MISSION_ACK: the vehicle refused the mission: {name} ({msg.type})"
                    if len(sent) == len(items):
                        return None
                    return (f"MISSION_ACK: MAV_MISSION_ACCEPTED after {len(sent)} of "
                            f"{len(items)} items were sent")
                if 0 <= msg.seq < len(items):
                    seq = msg.seq
                    send_item(seq)
                    sent.add(seq)
                    resend, what = functools.partial(send_item, seq), f"MISSION_ITEM_INT {seq}"
                    tries = 0
                    deadline = time.monotonic() + timeout
    finally:
        link.close()


_VEHICLE = re.compile(r"^([1-9][0-9]{0,9})=(udp|tcp):([^:]+):([0-9]{1,5})(?::([0-9]{1,3}))?$")


def parse_vehicle(text: str) -> Vehicle:
    """A --vehicle value (its address not resolved yet)."""
    m = _VEHICLE.match(text)
    if not m or int(m.group(1)) > SVA_MAX_ID or not 1 <= int(m.group(4)) <= 65535 or \
            (m.group(5) is not None and not 1 <= int(m.group(5)) <= 255):
        raise io.InputError(f"--vehicle: must be UAV_ID=udp:HOST:PORT[:SYSID] or "
                            f"UAV_ID=tcp:HOST:PORT[:SYSID] (UAV_ID in [1, {SVA_MAX_ID}], PORT in "
                            f"[1, 65535], SYSID in [1, 255]), got \"{shown(text)[:60]}\"")
    return Vehicle(int(m.group(1)), m.group(2), m.group(3), int(m.group(4)), int(m.group(5) or 1))


def resolve(vehicle: Vehicle) -> Vehicle:
    """The vehicle with its address (the first getaddrinfo gives), resolved once."""
    kind = socket.SOCK_STREAM if vehicle.transport == "tcp" else socket.SOCK_DGRAM
    try:
        family, _, _, _, address = socket.getaddrinfo(vehicle.host, vehicle.port, type=kind)[0]
    except (OSError, UnicodeError) as e:
        raise io.InputError(f"--vehicle: {vehicle.uav}: {shown(vehicle.endpoint)}: cannot "
                            f"resolve: {shown(getattr(e, 'strerror', None) or e)}") from None
    return Vehicle(vehicle.uav, vehicle.transport, vehicle.host, vehicle.port, vehicle.sysid,
                   family, address)
