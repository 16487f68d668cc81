"""Fault injection between the bridge and one vehicle for `sva-tools sitl --fault`
(docs/sitl.md, "Faults"): a MAVLink TCP relay on the vehicle's behalf.

The bridge connects to the relay's port instead of the vehicle's SERIAL0; for each
connection the relay connects to the vehicle and passes the bytes both ways. A vehicle
that closes or refuses its side closes the bridge's (so the bridge sees the link drop
and reconnect as it would with the vehicle itself). The bridge's bytes are parsed
with pymavlink to find message boundaries; a message the fault leaves alone is passed
on as the bytes it came in. The vehicle's bytes are passed on unparsed, but read to log
its MISSION_ACK answers.

Once armed (the fleet's clock at t0 + T), the next MISSION_COUNT from the bridge fires
the fault:
- `silent-upload`: that MISSION_COUNT and everything after it, both ways, heartbeats
  included, is dropped; the connections stay open. The vehicle flies on, unheard.
- `reject-item`: one item of that upload (seq REJECT_SEQ, or the last when the mission is
  shorter) is sent with its command changed to REJECT_COMMAND (MAV_CMD_WAYPOINT_USER_1,
  which ArduCopter does not implement) and re-encoded (sequence number, ids and CRC
  right), so the vehicle's own mission code refuses the upload.
"""
from __future__ import annotations

import select
import socket
from typing import Any, Callable

from pymavlink.dialects.v20 import ardupilotmega as mavlink

RELAY_BASE_PORT = 15760          # the relay of instance k listens on 15760 + 10 k
REJECT_SEQ = 3                   # with --ardupilot: home, take-off, speed, the first waypoint
REJECT_COMMAND = 31000           # MAV_CMD_WAYPOINT_USER_1: not implemented by ArduCopter
UPLOAD_FAULTS = ("silent-upload", "reject-item")


def result_name(code: int) -> str:
    entry = mavlink.enums["MAV_MISSION_RESULT"].get(code)
    return entry.name if entry is not None else str(code)


class Relay:
    """One vehicle's relay. `clock()` gives the instant the fault is armed against (UTC ms
    of the fleet's clock, None while unknown); `armed_at()` the instant it arms (None:
    from the start). Serviced from the flight's loop: fds() to select on, pump() after."""

    def __init__(self, kind: str, uav_id: int, instance: int, sysid: int,
                 clock: Callable[[], float | None], armed_at: Callable[[], float | None]):
        self.kind, self.uav_id, self.sysid = kind, uav_id, sysid
        self.port = RELAY_BASE_PORT + 10 * instance
        self.vehicle_port = 5760 + 10 * instance
        self.clock, self.armed_at = clock, armed_at
        self.server = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        self.server.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        self.server.bind(("127.0.0.1", self.port))
        self.server.listen(1)
        self.server.setblocking(False)
        self.bridge: socket.socket | None = None
        self.vehicle: socket.socket | None = None
        self.rx_bridge = self._parser()
        self.rx_vehicle = self._parser()
        self.tx = mavlink.MAVLink(None)
        self.fired = False
        self.silent = False
        self.rejecting: int | None = None     # the seq to rewrite in the upload under way
        self.record: dict[str, Any] = {"kind": kind, "uav": uav_id, "relay_port": self.port,
                                       "connections": 0, "fired_utc_ms": None}
        self.acks: list[dict[str, Any]] = []     # the vehicle's MISSION_ACKs to the bridge
        self.dropped = {"to_vehicle": 0, "to_bridge": 0}

    @staticmethod
    def _parser() -> mavlink.MAVLink:
        p = mavlink.MAVLink(None)
        p.robust_parsing = True
        return p

    def fds(self) -> list[int]:
        return [s.fileno() for s in (self.server, self.bridge, self.vehicle) if s is not None]

    def close(self) -> None:
        self._drop()
        self.server.close()

    def _drop(self) -> None:
        for s in (self.bridge, self.vehicle):
            if s is not None:
                try:
                    s.close()
                except OSError:
                    pass
        self.bridge = self.vehicle = None

    def _accept(self) -> None:
        try:
            conn, _addr = self.server.accept()
        except (BlockingIOError, OSError):
            return
        self._drop()
        try:
            up = socket.create_connection(("127.0.0.1", self.vehicle_port), timeout=1.0)
        except OSError:
            conn.close()   # the vehicle is not listening: the bridge sees a closed link
            return
        for s in (conn, up):
            s.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
            s.settimeout(2.0)
        self.bridge, self.vehicle = conn, up
        self.rx_bridge, self.rx_vehicle = self._parser(), self._parser()
        self.record["connections"] = int(self.record["connections"]) + 1

    @staticmethod
    def _read(s: socket.socket | None) -> bytes | None:
        """Bytes waiting on s (b"" when none); None when it closed."""
        if s is None:
            return b""
        readable, _w, _x = select.select([s], [], [], 0)
        if not readable:
            return b""
        try:
            data = s.recv(65536)
        except OSError:
            return None
        return data if data else None

    def _send(self, s: socket.socket | None, data: bytes) -> None:
        if s is None or not data:
            return
        try:
            s.sendall(data)
        except OSError:
            self._drop()

    def pump(self) -> None:
        self._accept()
        if self.bridge is None:
            return
        down = self._read(self.bridge)
        up = self._read(self.vehicle)
        if down is None or up is None:
            self._drop()   # either side closed: so does the other
            return
        if down:
            self._from_bridge(down)
        if up:
            self._from_vehicle(up)

    def _armed(self) -> bool:
        at = self.armed_at()
        if at is None:
            return True
        now = self.clock()
        return now is not None and now >= at

    def _from_bridge(self, data: bytes) -> None:
        out = bytearray()
        for m in self.rx_bridge.parse_buffer(data) or []:
            kind = m.get_type()
            raw = bytes(m.data) if kind == "BAD_DATA" else bytes(m.get_msgbuf())
            if self.silent:
                self.dropped["to_vehicle"] += 1
                continue
            if kind == "MISSION_COUNT" and m.target_system == self.sysid and \
                    getattr(m, "mission_type", 0) == 0 and not self.fired and self._armed():
                self.fired = True
                self.record["fired_utc_ms"] = self.clock()
                self.record["count"] = m.count
                if self.kind == "silent-upload":
                    self.silent = True
                    self.dropped["to_vehicle"] += 1
                    continue
                self.rejecting = min(REJECT_SEQ, m.count - 1)
            elif kind == "MISSION_ITEM_INT" and self.rejecting is not None and \
                    m.seq == self.rejecting and m.target_system == self.sysid:
                self.record["item"] = {"seq": m.seq, "command": m.command, "frame": m.frame,
                                       "rewritten_command": REJECT_COMMAND}
                m.command = REJECT_COMMAND
                self.tx.srcSystem, self.tx.srcComponent = m.get_srcSystem(), m.get_srcComponent()
                self.tx.seq = m.get_seq()
                raw = bytes(m.pack(self.tx))
                self.rejecting = None
            out += raw
        self._send(self.vehicle, bytes(out))

    def _from_vehicle(self, data: bytes) -> None:
        if self.silent:
            self.dropped["to_bridge"] += 1
            return
        for m in self.rx_vehicle.parse_buffer(data) or []:
            if m.get_type() == "MISSION_ACK" and m.get_srcSystem() == self.sysid:
                self.acks.append({"utc_ms": self.clock(), "type": m.type,
                                  "result": result_name(m.type)})
        self._send(self.bridge, data)

    def log(self) -> dict[str, Any]:
        """What the fault did (instants as UTC ms; sitl.record makes them ms since t0)."""
        out = dict(self.record)
        out["acks"] = list(self.acks)
        out["dropped"] = dict(self.dropped)
        return out
