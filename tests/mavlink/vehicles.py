"""Vehicle sides for the MAVLink tests, independent of the bridge's code.

MavsdkVehicle: MAVSDK's MissionRawServer (the `mavsdk` wheel's libcmavsdk) acting as an
autopilot on a UDP port; it records every mission uploaded to it.
PymavlinkVehicle: a scripted vehicle on pymavlink that can refuse a mission
(MISSION_ACK with an error) or hold a mission item limit (MAV_MISSION_NO_SPACE).
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
    it gets MAV_MISSION_NO_SPACE at once. A fussy vehicle ignores the first MISSION_COUNT
    (the sender must resend it), asks with the older MISSION_REQUEST, and asks for the
    items from the last to the first, each twice."""

    def __init__(self, port: int, sysid: int = 1, final: int = 0,
                 max_items: Optional[int] = None, fussy: bool = False):
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
