"""sva_mavlink_bridge's reports, driven through LCM inside a private network namespace
(tools/netns/netns_run.sh), with a pymavlink vehicle stand-in (standin.py) served over TCP.

The bridge uploads the plan over TCP and, while it holds a plan, publishes one report_t
per heard vehicle and period on SVA_REPORT: the cell of the vehicle's position, the tick
of its own GPS clock (a clock running ten times as fast as the host's), fuel from its
battery and --fuel-capacity, its mission sequence numbers; LOST once per period after its
heartbeats stop and while its process is gone; OK again once a restarted vehicle takes
the reconnection. A vehicle never heard is never reported; a new fleet revision stops the
reports until its plan. Expected values come from pymap3d and the stand-in's records."""
from __future__ import annotations

import os
import sys
import threading
import time

import pytest

if not os.environ.get("SVA_LCM_NETNS"):
    pytest.skip("run through tools/netns/netns_run.sh (multicast only in a private netns)",
                allow_module_level=True)

sys.path.insert(0, os.environ["SVA_LCM_PYTHON_TYPES"])
import lcm  # noqa: E402
import sva_lcm  # noqa: E402

import mavcheck  # noqa: E402
from standin import StandIn, free_tcp_port  # noqa: E402
from test_bridge import TWO, URL, Bridge, done_lines, fleet_msg, mission_msg, plan_msg  # noqa: E402
from test_tcp import STREAMS  # noqa: E402
from test_upload import pymavlink_items  # noqa: E402

FRAME = TWO["frame"]
FI = mavcheck.frame_ints(FRAME)
PERIOD_S = 0.3


class Reports:
    """Every report_t on SVA_REPORT with the host time it arrived."""

    def __init__(self):
        self._lc = lcm.LCM(URL)
        self.got = []
        self._lock = threading.Lock()
        self._lc.subscribe("SVA_REPORT", self._on)
        self._halt = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def _on(self, _channel, data):
        r = sva_lcm.report_t.decode(data)
        with self._lock:
            self.got.append((time.monotonic(), r))

    def _run(self):
        while not self._halt.is_set():
            self._lc.handle_timeout(50)

    def between(self, t0, t1, uav=None):
        with self._lock:
            return [(t, r) for t, r in self.got if t0 <= t <= t1 and (uav is None or r.uav_id == uav)]

    def close(self):
        self._halt.set()
        self._thread.join(2)


def check_ticks(vehicle, reports):
    for t, r in reports:
        with vehicle.lock:
            sent = [mavcheck.tick_of(FRAME, g) for ts, g in vehicle.positions if t - 0.7 <= ts <= t]
        assert r.at_ticks in sent, (r.at_ticks, sent)


def test_reports_follow_the_vehicle_and_its_link(tmp_path):
    plan = mavcheck.plan_mission(TWO, tmp_path)
    route1 = next(r for r in plan["routes"] if r["uav"] == 1)
    pa, pb = free_tcp_port(), free_tcp_port()  # nobody ever listens on pb
    lat, lon = mavcheck.position_e7(FRAME, 3.3, -2.2)
    a = StandIn("tcp", pa, 1, lat_e7=lat, lon_e7=lon, gps_at_boot_ms=FI["t0_ms"] + 1_000_000,
                rate=10.0, system_time_every_s=2.0, battery=73, mission_current=4, reached=3)
    reports = Reports()
    lc = lcm.LCM(URL)
    bridge = Bridge({1: f"tcp:127.0.0.1:{pa}:1", 2: f"tcp:127.0.0.1:{pb}:2"}, "--report-ms", "300",
                    "--heartbeat-timeout-ms", "1500", "--fuel-capacity", "500")
    b = None
    try:
        link1 = f"uav 1 (tcp:127.0.0.1:{pa})"
        bridge.wait_for(lambda ls: f"{link1}: connected" in ls)
        time.sleep(1.0)
        assert reports.between(0, time.monotonic()) == [], "reports before any plan"
        assert a.requested() == STREAMS  # at the first heartbeat, plan or not

        # (a) the upload over TCP; the vehicle that never answers is named with its link
        lc.publish("SVA_FLEET", fleet_msg(TWO).encode())
        lc.publish("SVA_MISSION", mission_msg(TWO).encode())
        time.sleep(0.2)
        lc.publish("SVA_PLAN", plan_msg(plan, 1).encode())
        lines = bridge.wait_for(done_lines(1, 2), 30)
        n = 3 + 2 * len(route1["targets"])
        assert f"plan 1: {link1}: uploaded {n} items" in lines
        assert (f"plan 1: uav 2 (tcp:127.0.0.1:{pb}): error: timeout: no answer to MISSION_COUNT "
                f"after 3 tries of 300 ms; tcp:127.0.0.1:{pb} not connected: Connection refused") in lines
        assert len(a.missions) == 1
        problems = mavcheck.check_route(pymavlink_items(a.missions[0]), TWO, FRAME, 1, route1["targets"])
        assert problems == [], "\n".join(problems)

        # (b) reports in mission terms, from the vehicle's clock
        start = time.monotonic()
        time.sleep(2.0)
        got = reports.between(start, time.monotonic())
        assert got and all(r.uav_id == 1 for _, r in got), "uav 2 was never heard"
        assert 4 <= len(got) <= 9, len(got)
        cell = mavcheck.cell_of(FRAME, lat, lon)
        assert cell == (3, -2)
        for _, r in got:
            assert (r.version, r.health, r.x, r.y, r.fuel, r.mission_seq, r.reached_seq) == \
                (1, r.HEALTH_OK, 3, -2, 500 * 73 // 100, 4, 3)
        check_ticks(a, got)

        # LOST once per period after the heartbeats stop, then while the process is gone
        a.heartbeats = False
        time.sleep(2.5)
        now = time.monotonic()
        lost = reports.between(now - 1.2, now)
        assert 3 <= len(lost) <= 5 and all(r.health == r.HEALTH_LOST for _, r in lost), lost
        assert f"{link1}: LOST: no HEARTBEAT for more than 1500 ms" in bridge.lines
        a.close()
        bridge.wait_for(lambda ls: f"{link1}: connection lost: closed by the vehicle; "
                                   f"reconnecting every 500 ms" in ls)
        time.sleep(1.0)
        now = time.monotonic()
        gone = reports.between(now - 0.9, now)
        assert gone and all((r.health, r.x, r.y) == (r.HEALTH_LOST, 3, -2) for _, r in gone)

        # a restarted vehicle (a new boot, elsewhere, battery from BATTERY_STATUS) takes
        # the reconnection: streams requested again, OK reports of the new boot
        lat_b, lon_b = mavcheck.position_e7(FRAME, -1.0, 4.0)
        b = StandIn("tcp", pa, 1, lat_e7=lat_b, lon_e7=lon_b,
                    gps_at_boot_ms=FI["t0_ms"] + 2_000_000, battery=-1, battery_status=40)
        back = time.monotonic()
        bridge.wait_for(lambda ls: ls.count(f"{link1}: connected") == 2)
        assert time.monotonic() - back < 1.5
        bridge.wait_for(lambda ls: f"{link1}: OK: heard again" in ls)
        time.sleep(1.5)
        assert b.requested() == STREAMS
        now = time.monotonic()
        ok = reports.between(now - 0.9, now)
        assert ok and all((r.health, r.x, r.y, r.fuel, r.mission_seq, r.reached_seq) ==
                          (r.HEALTH_OK, -1, 4, 200, -1, -1) for _, r in ok), ok
        check_ticks(b, ok)
        assert min(r.at_ticks for _, r in ok) >= 2_000_000 // FI["tick_ms"]

        # a new fleet revision stops the reports until its plan
        lc.publish("SVA_FLEET", fleet_msg(TWO, revision=2).encode())
        stopped = time.monotonic()
        time.sleep(1.2)
        assert reports.between(stopped + PERIOD_S + 0.1, time.monotonic()) == []
        lc.publish("SVA_MISSION", mission_msg(TWO, revision=2).encode())
        time.sleep(0.2)
        lc.publish("SVA_PLAN", plan_msg(plan, 2, revision=2).encode())
        bridge.wait_for(done_lines(2, 2), 30)
        resumed = time.monotonic()
        time.sleep(1.0)
        assert reports.between(resumed, time.monotonic())
    finally:
        bridge.stop()
        reports.close()
        a.close()
        if b is not None:
            b.close()


MAV_MISSION_UNSUPPORTED = 3


def test_a_refused_upload_or_a_restart_withholds_the_vehicle_until_it_is_back(tmp_path):
    """The withheld rule (docs/mavlink.md): a vehicle that refuses the mission itself
    (MAV_MISSION_UNSUPPORTED: not tried again) is reported LOST while its heartbeats go
    on, and gets no upload, until its link drops and it is heard again; a vehicle whose
    link drops (a restart: a new boot) is reported LOST at least once and is back when
    heard again, and the next plan uploads to it afresh even when its route is the same."""
    plan = mavcheck.plan_mission(TWO, tmp_path)
    route1 = next(r for r in plan["routes"] if r["uav"] == 1)
    n = 3 + 2 * len(route1["targets"])
    pa, pb = free_tcp_port(), free_tcp_port()
    lat, lon = mavcheck.position_e7(FRAME, 3.3, -2.2)

    def vehicle(boot_s, **kw):
        return StandIn("tcp", pa, 1, lat_e7=lat, lon_e7=lon,
                       gps_at_boot_ms=FI["t0_ms"] + boot_s * 1000, rate=10.0, **kw)

    a = vehicle(1000, refuse=MAV_MISSION_UNSUPPORTED)
    b = c = None
    reports = Reports()
    lc = lcm.LCM(URL)
    bridge = Bridge({1: f"tcp:127.0.0.1:{pa}:1", 2: f"tcp:127.0.0.1:{pb}:2"}, "--report-ms", "300",
                    "--heartbeat-timeout-ms", "1500", upload_retries=None)
    link1 = f"uav 1 (tcp:127.0.0.1:{pa})"
    try:
        bridge.wait_for(lambda ls: f"{link1}: connected" in ls)
        lc.publish("SVA_FLEET", fleet_msg(TWO).encode())
        lc.publish("SVA_MISSION", mission_msg(TWO).encode())
        time.sleep(0.2)
        lc.publish("SVA_PLAN", plan_msg(plan, 1).encode())
        refused = (f"plan 1: {link1}: error: MISSION_ACK: the vehicle refused the mission: "
                   f"MAV_MISSION_UNSUPPORTED ({MAV_MISSION_UNSUPPORTED})")
        bridge.wait_for(lambda ls: refused in ls, 10)
        bridge.wait_for(lambda ls: any(x.startswith(f"{link1}: LOST: an upload failed for good")
                                       for x in ls), 5)
        assert not [x for x in bridge.lines if x.startswith(f"plan 1: {link1}: retry")]
        time.sleep(1.5)
        now = time.monotonic()
        held = reports.between(now - 1.0, now, uav=1)
        assert len(held) >= 2 and all((r.health, r.x, r.y) == (r.HEALTH_LOST, 3, -2) for _, r in held)
        # withheld: no upload, whatever the plan
        lc.publish("SVA_PLAN", plan_msg(plan, 2).encode())
        bridge.wait_for(lambda ls: f"plan 2: {link1}: withheld (reported LOST), not uploaded" in ls, 10)
        assert a.counts == [n]

        # its link drops (a restart): LOST until a new boot is heard, then OK
        a.close()
        b = vehicle(2000)
        bridge.wait_for(lambda ls: ls.count(f"{link1}: connected") == 2, 10)
        bridge.wait_for(lambda ls: f"{link1}: OK: heard again" in ls, 10)
        time.sleep(1.0)
        now = time.monotonic()
        ok = reports.between(now - 0.9, now, uav=1)
        assert ok and all(r.health == r.HEALTH_OK for _, r in ok)
        assert min(r.at_ticks for _, r in ok) >= 2_000_000 // FI["tick_ms"]
        # what it held is forgotten: the same route is uploaded again
        lc.publish("SVA_PLAN", plan_msg(plan, 3).encode())
        bridge.wait_for(lambda ls: f"plan 3: {link1}: uploaded {n} items" in ls, 10)
        assert len(b.missions) == 1

        # a restart of a vehicle in good standing: LOST at least once, then back, and the
        # same plan again is uploaded to the new boot (it holds no mission of ours)
        b.close()
        dropped = time.monotonic()
        c = vehicle(3000)
        bridge.wait_for(lambda ls: ls.count(f"{link1}: connected") == 3, 10)
        bridge.wait_for(lambda ls: ls.count(f"{link1}: OK: heard again") == 2, 10)
        lost = [r for _, r in reports.between(dropped, time.monotonic(), uav=1) if r.health == r.HEALTH_LOST]
        assert lost and all((r.x, r.y) == (3, -2) for r in lost)
        lc.publish("SVA_PLAN", plan_msg(plan, 4).encode())
        bridge.wait_for(lambda ls: f"plan 4: {link1}: uploaded {n} items" in ls, 10)
        assert len(c.missions) == 1
    finally:
        bridge.stop()
        reports.close()
        for v in (a, b, c):
            if v is not None:
                v.close()
