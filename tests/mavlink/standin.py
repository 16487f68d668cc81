"""A vehicle stand-in on pymavlink for the telemetry and TCP tests, independent of the
bridge's code: it serves TCP (listens on 127.0.0.1:port and takes one client at a time,
as ArduPilot SITL does) or UDP (listens on 127.0.0.1:port, answers the last sender).

It streams HEARTBEAT, GLOBAL_POSITION_INT, SYSTEM_TIME, SYS_STATUS (and optionally
BATTERY_STATUS, MISSION_CURRENT, MISSION_ITEM_REACHED) from a clock of its own: time since
boot runs `rate` times as fast as the host's, and the GPS clock is `gps_at_boot_ms` plus
the time since boot (as SITL's runs at its speedup), so host time and vehicle time differ.
It answers the mission upload protocol (MISSION_REQUEST_INT per item, then MISSION_ACK;
with `refuse`, a MISSION_ACK of that result to every MISSION_COUNT) and
SET_MESSAGE_INTERVAL (COMMAND_ACK), recording what it got; with `strays`, every reply
is preceded by stray bytes (a cycle of malformed, truncated and corrupted frames).
"""
from __future__ import annotations

import select
import socket
import threading
import time
from typing import Dict, List, Optional, Tuple

from pymavlink.dialects.v20 import common as mavlink2

SET_MESSAGE_INTERVAL = 511


def free_tcp_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _frame(build) -> bytes:
    mav = mavlink2.MAVLink(None, srcSystem=1, srcComponent=1)
    return build(mav).pack(mav)


def stray_patterns() -> List[Tuple[str, bytes]]:
    """Byte runs that are not a good frame, each put before a good one."""
    heartbeat = _frame(lambda m: m.heartbeat_encode(2, 3, 0, 0, 4))
    position = _frame(lambda m: m.global_position_int_encode(1, 2, 3, 4, 5, 6, 7, 8, 9))
    bad_crc = heartbeat[:-1] + bytes([heartbeat[-1] ^ 0xFF])
    return [
        ("FD FF 00: a MAVLink 2 header of 255 bytes", b"\xfd\xff\x00"),
        ("a heartbeat cut after 12 bytes", heartbeat[:12]),
        ("a heartbeat with a bad checksum", bad_crc),
        ("garbage", b"\x00\x55\xaa\x13"),
        ("FE 09 00: a MAVLink 1 header", b"\xfe\x09\x00"),
        ("a GLOBAL_POSITION_INT cut after 10 bytes", position[:10]),
    ]


class StandIn(threading.Thread):
    """One vehicle (system `sysid`, component 1) on `transport` ("tcp" or "udp")."""

    def __init__(self, transport: str, port: int, sysid: int = 1, *, lat_e7: int, lon_e7: int,
                 gps_at_boot_ms: int, rate: float = 1.0, battery: int = 73,
                 battery_status: Optional[int] = None, mission_current: Optional[int] = None,
                 reached: Optional[int] = None, position_hz: float = 5.0,
                 system_time_every_s: float = 1.0, strays: bool = False,
                 drop_after_items: Optional[int] = None, refuse: Optional[int] = None):
        super().__init__(daemon=True)
        self.transport, self.port, self.sysid = transport, port, sysid
        self.lat_e7, self.lon_e7 = lat_e7, lon_e7
        self.gps_at_boot_ms, self.rate = gps_at_boot_ms, rate
        self.battery, self.battery_status = battery, battery_status
        self.mission_current, self.reached = mission_current, reached
        self.position_every = 1.0 / position_hz
        self.system_time_every = system_time_every_s
        self.strays = stray_patterns() if strays else []
        self.drop_after_items = drop_after_items
        self.refuse = refuse                 # answer MISSION_COUNT with this MISSION_ACK result
        self.heartbeats = True
        self.counts: List[int] = []          # MISSION_COUNT values received
        self.item_seqs: List[int] = []       # MISSION_ITEM_INT seqs received (resends too)
        self.missions: List[list] = []       # accepted missions: their MISSION_ITEM_INT
        self.intervals: List[Tuple[float, int, float]] = []  # (host time, msgid, interval us)
        self.positions: List[Tuple[float, int]] = []  # (host time sent, GPS ms of the fix)
        self.clients = 0
        self.lock = threading.Lock()
        self._boot = time.monotonic()
        self._tx = mavlink2.MAVLink(None, srcSystem=sysid, srcComponent=1)
        self._rx = mavlink2.MAVLink(None)
        self._rx.robust_parsing = True
        self._stray_next = 0
        self._halt = threading.Event()
        self._client: Optional[socket.socket] = None
        self._peer = None
        if transport == "tcp":
            self._server = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
            self._server.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            self._server.bind(("127.0.0.1", port))
            self._server.listen(1)
        else:
            self._server = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
            self._server.bind(("127.0.0.1", port))
        self.start()

    # --- the vehicle's clocks -------------------------------------------------------
    def boot_ms(self) -> int:
        return int((time.monotonic() - self._boot) * 1000 * self.rate)

    def gps_ms(self, boot_ms: int) -> int:
        return self.gps_at_boot_ms + boot_ms

    # --- sending ------------------------------------------------------------------------
    def _write(self, data: bytes) -> None:
        try:
            if self.transport == "tcp":
                if self._client is not None:
                    self._client.sendall(data)
            elif self._peer is not None:
                self._server.sendto(data, self._peer)
        except OSError:
            self._drop_client()

    def _send(self, msg, reply: bool = False) -> None:
        data = msg.pack(self._tx)
        self._tx.seq = (self._tx.seq + 1) % 256
        if reply and self.strays:
            _, stray = self.strays[self._stray_next % len(self.strays)]
            if self.transport == "udp" and self._stray_next % 2 == 1:
                self._write(stray)  # a datagram of its own
            else:
                data = stray + data  # before the reply, in the same write
            self._stray_next += 1
        self._write(data)

    def _drop_client(self) -> None:
        if self._client is not None:
            try:
                self._client.close()
            except OSError:
                pass
        self._client = None

    def _stream(self, due: Dict[str, float]) -> None:
        now = time.monotonic()
        boot = self.boot_ms()
        if now >= due["heartbeat"]:
            due["heartbeat"] = now + 1.0
            if self.heartbeats:
                self._send(self._tx.heartbeat_encode(mavlink2.MAV_TYPE_QUADROTOR,
                                                     mavlink2.MAV_AUTOPILOT_ARDUPILOTMEGA,
                                                     mavlink2.MAV_MODE_FLAG_SAFETY_ARMED, 4,
                                                     mavlink2.MAV_STATE_ACTIVE))
        if now >= due["time"]:
            due["time"] = now + self.system_time_every
            self._send(self._tx.system_time_encode(self.gps_ms(boot) * 1000, boot))
        if now >= due["position"]:
            due["position"] = now + self.position_every
            with self.lock:
                self.positions.append((time.monotonic(), self.gps_ms(boot)))
            self._send(self._tx.global_position_int_encode(boot, self.lat_e7, self.lon_e7,
                                                           500000, 30000, 0, 0, 0, 0))
        if now >= due["status"]:
            due["status"] = now + 0.5
            self._send(self._tx.sys_status_encode(0, 0, 0, 500, 12000, -1, self.battery,
                                                  0, 0, 0, 0, 0, 0))
            if self.battery_status is not None:
                self._send(self._tx.battery_status_encode(
                    0, 0, 0, 2500, [65535] * 10, -1, -1, -1, self.battery_status))
            if self.mission_current is not None:
                self._send(self._tx.mission_current_encode(self.mission_current))
            if self.reached is not None:
                self._send(self._tx.mission_item_reached_encode(self.reached))

    # --- receiving ----------------------------------------------------------------------
    def _on_message(self, msg, state: dict) -> None:
        t = msg.get_type()
        to_us = getattr(msg, "target_system", self.sysid) == self.sysid
        if t == "COMMAND_LONG" and to_us and msg.command == SET_MESSAGE_INTERVAL:
            with self.lock:
                self.intervals.append((time.monotonic(), int(msg.param1), msg.param2))
            self._send(self._tx.command_ack_encode(SET_MESSAGE_INTERVAL, 0), reply=True)
        elif t == "MISSION_COUNT" and to_us:
            state["peer"] = (msg.get_srcSystem(), msg.get_srcComponent())
            state["want"], state["got"] = msg.count, {}
            self.counts.append(msg.count)
            if self.refuse is not None:
                state["want"] = 0
                self._send(self._tx.mission_ack_encode(*state["peer"], self.refuse, 0), reply=True)
                return
            self._send(self._tx.mission_request_int_encode(*state["peer"], 0, 0), reply=True)
        elif t == "MISSION_ITEM_INT" and to_us and state.get("want"):
            self.item_seqs.append(msg.seq)
            if self.drop_after_items is not None and len(self.item_seqs) >= self.drop_after_items:
                self._drop_client()
                return
            if msg.seq != len(state["got"]):
                return
            state["got"][msg.seq] = msg
            if len(state["got"]) < state["want"]:
                self._send(self._tx.mission_request_int_encode(*state["peer"], len(state["got"]), 0),
                           reply=True)
            else:
                with self.lock:
                    self.missions.append([state["got"][k] for k in range(state["want"])])
                state["want"] = 0
                self._send(self._tx.mission_ack_encode(*state["peer"], 0, 0), reply=True)

    def run(self) -> None:
        due = {"heartbeat": 0.0, "time": 0.0, "position": 0.0, "status": 0.0}
        state: dict = {}
        while not self._halt.is_set():
            socks = [self._server] if self.transport == "udp" or self._client is None \
                else [self._server, self._client]
            try:
                readable, _, _ = select.select(socks, [], [], 0.01)
            except (OSError, ValueError):
                readable = []
            for s in readable:
                if self.transport == "tcp" and s is self._server:
                    self._drop_client()
                    self._client, _ = self._server.accept()
                    self._client.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
                    self.clients += 1
                    self._rx = mavlink2.MAVLink(None)
                    self._rx.robust_parsing = True
                    continue
                try:
                    if self.transport == "udp":
                        data, self._peer = s.recvfrom(4096)
                    else:
                        data = s.recv(4096)
                except OSError:
                    data = b""
                if not data:
                    self._drop_client()
                    continue
                for msg in self._rx.parse_buffer(data) or []:
                    self._on_message(msg, state)
            if self._client is not None or (self.transport == "udp" and self._peer is not None):
                self._stream(due)

    def requested(self) -> Dict[int, float]:
        """SET_MESSAGE_INTERVAL requests so far: message id -> interval in us."""
        with self.lock:
            return {msgid: us for _, msgid, us in self.intervals}

    def close(self) -> None:
        self._halt.set()
        self.join(2)
        self._drop_client()
        self._server.close()
