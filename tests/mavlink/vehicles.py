"""Vehicle sides for the MAVLink tests, independent of the bridge's code.

MavsdkVehicle: MAVSDK's MissionRawServer (the `mavsdk` wheel's libcmavsdk) acting as an
autopilot on a UDP port; it records every mission uploaded to it.
PymavlinkVehicle: a scripted vehicle on pymavlink that can refuse a mission
(MISSION_ACK with an error) or hold a mission item limit (MAV_MISSION_NO_SPACE).
RawVehicle: a vehicle on a plain UDP or TCP socket with pymavlink's codec that can be
made hostile: stray bytes before its answers, answers from another port or another
system or component, signed frames, a dropped TCP connection.
"""
from __future__ import annotations

import socket
import threading
import time
from typing import List, Optional


def free_udp_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class MavsdkVehicle:
    """An autopilot (system `sysid`, component 1) listening on udp 127.0.0.1:port."""

    def __init__(self, port: int, sysid: int = 1):
        from mavsdk.mavsdk import Configuration, Mavsdk
        from mavsdk.plugins.mission_raw_server.mission_raw_server import MissionRawServer

        self.port = port
        self.missions: List[list] = []
        self._cond = threading.Condition()
        cfg = Configuration.create_manual(sysid, 1, True)
        self._mavsdk = Mavsdk(cfg)
        result = self._mavsdk.add_any_connection(f"udpin://127.0.0.1:{port}")
        if int(result) != 0 and "SUCCESS" not in str(result).upper():
            raise RuntimeError(f"mavsdk: cannot listen on {port}: {result}")
        self._server = MissionRawServer(self._mavsdk.server_component())
        self._sub = self._server.subscribe_incoming_mission(self._on_mission)

    def _on_mission(self, result, plan, _ud) -> None:
        with self._cond:
            self.missions.append((int(result), list(plan.mission_items)))
            self._cond.notify_all()

    def wait_missions(self, n: int, timeout: float = 20.0) -> list:
        end = time.monotonic() + timeout
        with self._cond:
            while len(self.missions) < n:
                left = end - time.monotonic()
                if left <= 0:
                    break
                self._cond.wait(left)
            return list(self.missions)

    def close(self) -> None:
        self._mavsdk.destroy()


class PymavlinkVehicle(threading.Thread):
    """Answers a mission upload on udp 127.0.0.1:port as system `sysid`: requests every
    item, then MISSION_ACK `final` (0 accepted); with max_items, a MISSION_COUNT above
    it gets MAV_MISSION_NO_SPACE at once, and so do the first `refuse_first` MISSION_COUNTs
    (a vehicle still booting). A fussy vehicle ignores the first MISSION_COUNT
    (the sender must resend it), asks with the older MISSION_REQUEST, and asks for the
    items from the last to the first, each twice."""

    def __init__(self, port: int, sysid: int = 1, final: int = 0,
                 max_items: Optional[int] = None, fussy: bool = False, refuse_first: int = 0):
        super().__init__(daemon=True)
        import os
        os.environ["MAVLINK20"] = "1"
        from pymavlink import mavutil
        self.mavutil = mavutil
        self.conn = mavutil.mavlink_connection(f"udpin:127.0.0.1:{port}", source_system=sysid,
                                               source_component=1, dialect="common")
        self.final = final
        self.max_items = max_items
        self.fussy = fussy
        self.refuse_first = refuse_first
        self.counts: List[int] = []
        self.items: List[list] = []
        self._halt = threading.Event()
        self.start()

    def run(self) -> None:
        m = self.mavutil.mavlink
        cur: dict = {}
        want = 0
        peer = (0, 0)
        order: List[int] = []

        def ask():
            if self.fussy:
                self.conn.mav.mission_request_send(*peer, order[0], 0)
            else:
                self.conn.mav.mission_request_int_send(*peer, order[0], 0)

        while not self._halt.is_set():
            msg = self.conn.recv_match(blocking=True, timeout=0.1)
            if msg is None:
                continue
            t = msg.get_type()
            if t == "MISSION_COUNT":
                self.counts.append(msg.count)
                if self.fussy and len(self.counts) == 1:
                    continue  # lost: the sender's timeout must resend it
                peer = (msg.get_srcSystem(), msg.get_srcComponent())
                if len(self.counts) <= self.refuse_first:
                    self.conn.mav.mission_ack_send(*peer, m.MAV_MISSION_NO_SPACE, 0)
                    continue
                if self.max_items is not None and msg.count > self.max_items:
                    self.conn.mav.mission_ack_send(*peer, m.MAV_MISSION_NO_SPACE, 0)
                    continue
                cur, want = {}, msg.count
                order = list(range(want))
                if self.fussy:
                    order = [k for k in reversed(order) for _ in (0, 1)]
                ask()
            elif t in ("MISSION_ITEM_INT", "MISSION_ITEM") and want and order:
                if msg.seq != order[0]:
                    continue
                cur[msg.seq] = msg
                order.pop(0)
                if order:
                    ask()
                else:
                    self.items.append([cur[k] for k in range(want)])
                    want = 0
                    self.conn.mav.mission_ack_send(*peer, self.final, 0)

    def close(self) -> None:
        self._halt.set()
        self.join(2)
        self.conn.close()


class RawVehicle(threading.Thread):
    """A vehicle on a plain socket (pymavlink's codec, no mavutil) that answers a mission
    upload and can be made hostile, for the host command's tests:

    - transport "udp" (answers the last sender) or "tcp" (listens, one client at a time,
      and sends a HEARTBEAT every `heartbeat_s` as a vehicle's telemetry would);
    - `sysid`, `compid`: who the answers come from (a wrong system id or component);
    - `strays(k)`: bytes put before its k-th answer, in the answer's datagram (or, with
      `alone`, as a datagram of its own just before it); in the stream over TCP;
    - `decoys`: (system id, component) pairs that each send a MISSION_ACK
      MAV_MISSION_DENIED from the same socket before every answer;
    - `answer_from_port`: the answers leave from another UDP port (a spoofer that sees
      the traffic), the socket on `port` says nothing;
    - `drop_after_items`: over TCP, closes the connection when that many items came;
    - `signed`: its frames carry a MAVLink signature (a key of its own).
    Records every MISSION_COUNT (`counts`), every MISSION_ITEM_INT seq (`item_seqs`) and
    each mission received whole (`items`)."""

    def __init__(self, port: int, sysid: int = 1, *, transport: str = "udp", compid: int = 1,
                 strays=None, alone: bool = False, decoys=(),
                 answer_from_port: Optional[int] = None, heartbeat_s: float = 0.05,
                 drop_after_items: Optional[int] = None, signed: bool = False):
        super().__init__(daemon=True)
        from pymavlink.dialects.v20 import common
        self.m = common
        self.port, self.transport, self.strays, self.alone = port, transport, strays, alone
        self.heartbeat_s = heartbeat_s
        self.drop_after_items = drop_after_items
        self._tx = common.MAVLink(None, srcSystem=sysid, srcComponent=compid)
        self._decoys = [common.MAVLink(None, srcSystem=s, srcComponent=c) for s, c in decoys]
        if signed:
            self._tx.signing.secret_key = bytes(range(32))
            self._tx.signing.timestamp = 1
            self._tx.signing.sign_outgoing = True
        self.counts: List[int] = []
        self.item_seqs: List[int] = []
        self.items: List[list] = []
        self.answers = 0
        self._halt = threading.Event()
        self._client: Optional[socket.socket] = None
        self._peer = None
        kind = socket.SOCK_STREAM if transport == "tcp" else socket.SOCK_DGRAM
        self._sock = socket.socket(socket.AF_INET, kind)
        self._sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        self._sock.bind(("127.0.0.1", port))
        if transport == "tcp":
            self._sock.listen(1)
        self._out = self._sock
        if answer_from_port is not None:
            self._out = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
            self._out.bind(("127.0.0.1", answer_from_port))
        self.start()

    def _pack(self, mav, msg) -> bytes:
        data = msg.pack(mav)
        mav.seq = (mav.seq + 1) % 256
        return data

    def _write(self, data: bytes) -> None:
        try:
            if self.transport == "tcp":
                if self._client is not None:
                    self._client.sendall(data)
            elif self._peer is not None:
                self._out.sendto(data, self._peer)
        except OSError:
            pass

    def _reply(self, msg, peer) -> None:
        for mav in self._decoys:
            self._write(self._pack(mav, mav.mission_ack_encode(*peer, 14, 0)))  # DENIED
        data = self._pack(self._tx, msg)
        stray = self.strays(self.answers) if self.strays is not None else b""
        self.answers += 1
        if stray and self.alone and self.transport == "udp":
            self._write(stray)
            stray = b""
        self._write(stray + data)

    def _on_message(self, msg, state: dict) -> None:
        kind = msg.get_type()
        if kind == "MISSION_COUNT":
            self.counts.append(msg.count)
            state["peer"] = (msg.get_srcSystem(), msg.get_srcComponent())
            state["want"], state["got"] = msg.count, {}
            self._reply(self._tx.mission_request_int_encode(*state["peer"], 0, 0), state["peer"])
        elif kind == "MISSION_ITEM_INT" and state.get("want"):
            self.item_seqs.append(msg.seq)
            if self._client is not None and len(self.item_seqs) == self.drop_after_items:
                self._client.close()
                self._client = None
                return
            if msg.seq != len(state["got"]):
                return
            state["got"][msg.seq] = msg
            if len(state["got"]) < state["want"]:
                self._reply(self._tx.mission_request_int_encode(*state["peer"], len(state["got"]), 0),
                            state["peer"])
            else:
                self.items.append([state["got"][k] for k in range(state["want"])])
                state["want"] = 0
                self._reply(self._tx.mission_ack_encode(*state["peer"], 0, 0), state["peer"])

    def run(self) -> None:
        import select
        state: dict = {}
        rx = self.m.MAVLink(None)
        rx.robust_parsing = True
        next_hb = 0.0
        while not self._halt.is_set():
            socks = [self._sock] if self._client is None else [self._client]
            readable, _, _ = select.select(socks, [], [], 0.01)
            for s in readable:
                if self.transport == "tcp" and s is self._sock:
                    self._client, _ = self._sock.accept()
                    rx = self.m.MAVLink(None)
                    rx.robust_parsing = True
                    continue
                try:
                    data, peer = s.recvfrom(4096)
                except OSError:
                    continue
                if self.transport == "udp":
                    self._peer = peer
                elif not data:
                    self._client.close()
                    self._client = None
                    continue
                for msg in rx.parse_buffer(data) or []:
                    if msg.get_type() != "BAD_DATA":
                        self._on_message(msg, state)
            if self.transport == "tcp" and self._client is not None and \
                    time.monotonic() >= next_hb:
                next_hb = time.monotonic() + self.heartbeat_s
                self._write(self._pack(self._tx, self._tx.heartbeat_encode(2, 3, 0, 0, 4)))

    def close(self) -> None:
        self._halt.set()
        self.join(2)
        for s in (self._client, self._sock, self._out):
            if s is not None:
                s.close()
