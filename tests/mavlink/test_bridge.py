"""sva_mavlink_bridge driven through LCM inside a private network namespace
(tools/netns/netns_run.sh): fleet, mission (with its frame) and plan messages go in as
sva_node sends them (the build's lcm-gen Python types), missions go out to MAVSDK
vehicles (and pymavlink ones that refuse) over UDP on loopback. A replan that changes
one UAV's route uploads to that vehicle only (a cancelled target not yet due is a change;
targets under way are not); a failed upload is tried again after a backoff; failures are
reported per vehicle while the other uploads go on."""
from __future__ import annotations

import os
import subprocess
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
from test_items import FRAME_MIDNIGHT  # noqa: E402
from test_upload import FOUR, as_tuples, judge, pymavlink_items  # noqa: E402
from vehicles import MavsdkVehicle, PymavlinkVehicle, free_udp_port  # noqa: E402

URL = "udpm://239.255.76.67:7667?ttl=0"
BRIDGE = os.environ["SVA_MAVLINK_BRIDGE"]
MAV_MISSION_DENIED = 14
MAV_MISSION_NO_SPACE = 4
TARGET_CANCELLED = 5  # event_t.TYPE_TARGET_CANCELLED

TWO = {"name": "two", "depot": {"x": 0, "y": 0}, "frame": FRAME_MIDNIGHT,
       "uavs": [{"id": 1, "x": 0, "y": 0, "fuel": 1000}, {"id": 2, "x": 0, "y": 0, "fuel": 1000}],
       "targets": [{"id": 1, "x": 10, "y": 0, "start": 20, "end": 30, "need": 1},
                   {"id": 2, "x": 0, "y": 10, "start": 20, "end": 30, "need": 1}]}
# The replan's residual mission: a target near target 1 after its window.
ADDED = {"id": 3, "x": 12, "y": 4, "start": 40, "end": 50, "need": 1}


def by_id(mission, tid):
    return next(t for t in mission["targets"] if t["id"] == tid)


def fleet_msg(mission, revision=1):
    f = sva_lcm.fleet_state_t()
    if hasattr(f, "version"):
        f.version = f.VERSION
    f.revision = revision
    f.uav_count = len(mission["uavs"])
    for k, u in enumerate(mission["uavs"]):
        s = f.uavs[k]
        s.id, s.x, s.y, s.fuel, s.ready_at_ticks = u["id"], u["x"], u["y"], u["fuel"], u.get("ready_at", 0)
    return f


def mission_msg(mission, revision=1, with_frame=True):
    m = sva_lcm.mission_t()
    m.version = m.VERSION
    m.revision = revision
    m.depot_x, m.depot_y = mission["depot"]["x"], mission["depot"]["y"]
    m.ticks_per_cell = mission.get("ticks_per_cell", 1)
    m.overlap_percent = 70
    m.target_count = len(mission["targets"])
    for k, t in enumerate(mission["targets"]):
        g = m.targets[k]
        g.id, g.x, g.y, g.start_ticks, g.end_ticks, g.need = (t["id"], t["x"], t["y"], t["start"],
                                                              t["end"], t["need"])
    if with_frame and "frame" in mission:
        fi = mavcheck.frame_ints(mission["frame"])
        fr = m.frame
        fr.present = 1
        fr.lat_e7, fr.lon_e7, fr.alt_cm = fi["lat_e7"], fi["lon_e7"], fi["alt_cm"]
        fr.cell_cm, fr.tick_ms, fr.t0_ms = fi["cell_cm"], fi["tick_ms"], fi["t0_ms"]
    return m


def plan_msg(plan, plan_id, revision=1):
    p = sva_lcm.plan_t()
    if hasattr(p, "version"):
        p.version = p.VERSION
    p.plan_id = plan_id
    p.fleet_revision = p.mission_revision = revision
    p.status = p.STATUS_COMPLETE if plan["status"] == "complete" else p.STATUS_PARTIAL
    p.covered = plan["covered"]
    p.cost = plan["cost"]
    p.route_count = len(plan["routes"])
    n = 0
    for k, r in enumerate(plan["routes"]):
        p.routes[k].uav_id = r["uav"]
        p.routes[k].target_count = len(r["targets"])
        p.routes[k].distance_cells = r["distance"]
        p.routes[k].fuel_used = r["fuel_used"]
        for t in r["targets"]:
            p.route_targets[n] = t
            n += 1
    p.item_count = n
    return p


class Bridge:
    """The bridge on the test's LCM URL; a failed upload is not tried again unless
    upload_retries says so (None: the bridge's default)."""

    def __init__(self, specs, *extra, upload_retries="0"):
        args = [BRIDGE, "--url", URL, "--timeout-ms", "300", "--retries", "2", *extra]
        if upload_retries is not None:
            args += ["--upload-retries", upload_retries]
        for uid, spec in specs.items():
            args += ["--vehicle", f"{uid}={spec}"]
        self.proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                     text=True)
        self.lines = []
        self._cond = threading.Condition()
        threading.Thread(target=self._read, daemon=True).start()
        self.wait_for(lambda ls: any("listening" in x for x in ls), 10)

    def _read(self):
        for line in self.proc.stdout:
            with self._cond:
                self.lines.append(line.rstrip("\n"))
                self._cond.notify_all()

    def wait_for(self, pred, timeout=20.0):
        end = time.monotonic() + timeout
        with self._cond:
            while not pred(self.lines):
                left = end - time.monotonic()
                if left <= 0:
                    raise AssertionError("bridge output so far:\n" + "\n".join(self.lines))
                self._cond.wait(left)
            return list(self.lines)

    def stop(self):
        self.proc.terminate()
        out = self.proc.wait(10)
        assert out == 0, self.proc.stderr.read()

    def stop_and_stderr(self) -> str:
        self.proc.terminate()
        out = self.proc.wait(10)
        err = self.proc.stderr.read()
        assert out == 0, err
        return err


@pytest.fixture
def lc():
    return lcm.LCM(URL)


def publish_start(lc, mission, plan, plan_id=1, with_frame=True):
    lc.publish("SVA_FLEET", fleet_msg(mission).encode())
    lc.publish("SVA_MISSION", mission_msg(mission, with_frame=with_frame).encode())
    time.sleep(0.2)
    lc.publish("SVA_PLAN", plan_msg(plan, plan_id).encode())


def done_lines(plan_id, n):
    return lambda ls: sum(1 for x in ls if x.startswith(f"plan {plan_id}: ") and
                          ("uploaded" in x or "error" in x or "unchanged" in x)) >= n


def test_a_replan_uploads_to_the_changed_vehicle_only(lc, tmp_path):
    plan = mavcheck.plan_mission(TWO, tmp_path)
    assert all(len(r["targets"]) == 1 for r in plan["routes"])
    pa, pb = free_udp_port(), free_udp_port()
    va, vb = MavsdkVehicle(pa, 1), MavsdkVehicle(pb, 2)
    vehicles = {1: va, 2: vb}
    bridge = Bridge({1: f"udp:127.0.0.1:{pa}:1", 2: f"udp:127.0.0.1:{pb}:2"})
    try:
        publish_start(lc, TWO, plan)
        bridge.wait_for(done_lines(1, 2))
        for r in plan["routes"]:
            got = vehicles[r["uav"]].wait_missions(1)
            assert len(got) == 1 and got[0][0] == 1
            problems = mavcheck.check_route(as_tuples(got[0][1]), TWO, TWO["frame"], r["uav"], r["targets"])
            assert problems == [], "\n".join(problems)

        # the replan: target 3 added; the residual mission carries no frame (the
        # bridge keeps the mission's)
        residual = dict(TWO, targets=TWO["targets"] + [ADDED])
        plan2 = mavcheck.plan_mission(dict(residual, name="two_replan"), tmp_path)
        changed = [r for r in plan2["routes"] if ADDED["id"] in r["targets"]]
        assert len(changed) == 1
        changed_uav = changed[0]["uav"]
        other_uav = 3 - changed_uav
        before = {r["uav"]: r["targets"] for r in plan["routes"]}
        after = {r["uav"]: r["targets"] for r in plan2["routes"]}
        assert after[other_uav] == before[other_uav]
        rp = sva_lcm.replan_t()
        rp.version = rp.VERSION
        rp.event_seq = 1
        rp.event_type = 4
        rp.accepted = 1
        rp.added = rp.added_listed = 1
        rp.added_uav[0], rp.added_target[0] = changed_uav, ADDED["id"]
        rp.residual_fleet = fleet_msg(TWO, 1)
        rp.residual_mission = mission_msg(residual, 1, with_frame=False)
        rp.plan = plan_msg(plan2, 2)
        lc.publish("SVA_REPLAN", rp.encode())
        lines = bridge.wait_for(done_lines(2, 2))
        assert (f"plan 2: uav {other_uav} (udp:127.0.0.1:{(pa, pb)[other_uav - 1]}): route "
                f"unchanged, not uploaded") in lines
        got = vehicles[changed_uav].wait_missions(2)
        assert len(got) == 2 and got[1][0] == 1
        problems = mavcheck.check_route(as_tuples(got[1][1]), residual, TWO["frame"], changed_uav,
                                 after[changed_uav])
        assert problems == [], "\n".join(problems)
        time.sleep(1.0)
        assert len(vehicles[other_uav].missions) == 1  # it got nothing new

        # at tick 25 both first targets are under way: the residual mission holds target 3
        # alone, the UAVs stand at their targets until 30. The changed UAV's remaining
        # route [3] is the end of what it has, the other's is empty: nothing to upload.
        at = {changed_uav: by_id(TWO, after[changed_uav][0]), other_uav: by_id(TWO, after[other_uav][0])}
        fleet3 = dict(TWO, uavs=[dict(u, x=at[u["id"]]["x"], y=at[u["id"]]["y"], ready_at=30)
                                 for u in TWO["uavs"]])
        residual3 = dict(fleet3, name="two_at_25", targets=[ADDED])
        plan3 = mavcheck.plan_mission(residual3, tmp_path)
        assert {r["uav"]: r["targets"] for r in plan3["routes"]} == {changed_uav: [3], other_uav: []}
        rp3 = sva_lcm.replan_t()
        rp3.version = rp3.VERSION
        rp3.event_seq = 2
        rp3.accepted = 1
        rp3.now_ticks = 25
        rp3.residual_fleet = fleet_msg(residual3, 1)
        rp3.residual_mission = mission_msg(residual3, 1)
        rp3.plan = plan_msg(plan3, 3)
        lc.publish("SVA_REPLAN", rp3.encode())
        lines = bridge.wait_for(done_lines(3, 2))
        assert sum(1 for x in lines if x.startswith("plan 3: ") and
                   x.endswith("route unchanged, not uploaded")) == 2, lines
        time.sleep(1.0)
        assert len(vehicles[changed_uav].missions) == 2 and len(vehicles[other_uav].missions) == 1
    finally:
        bridge.stop()
        va.close()
        vb.close()


def test_messages_of_another_version_are_refused_with_a_line_each(lc, tmp_path):
    """A fleet, mission, plan or replan (or a message inside a replan) whose `version` is
    not its type's VERSION is ignored with one line naming both (docs/flight-stack.md
    "Wire versions"); a refused plan also drops the one held back."""
    plan = mavcheck.plan_mission(TWO, tmp_path)
    pa = free_udp_port()
    va = MavsdkVehicle(pa, 1)
    bridge = Bridge({1: f"udp:127.0.0.1:{pa}:1"})
    err = ""
    try:
        old_fleet, old_mission = fleet_msg(TWO), mission_msg(TWO)
        old_fleet.version, old_mission.version = 1, 1
        lc.publish("SVA_FLEET", old_fleet.encode())
        lc.publish("SVA_MISSION", old_mission.encode())
        time.sleep(0.2)
        lc.publish("SVA_PLAN", plan_msg(plan, 7).encode())  # held back: no fleet, no mission
        old_plan = plan_msg(plan, 8)
        old_plan.version = 3
        lc.publish("SVA_PLAN", old_plan.encode())  # refused, and plan 7 is no longer held
        time.sleep(0.2)
        lc.publish("SVA_FLEET", fleet_msg(TWO).encode())
        lc.publish("SVA_MISSION", mission_msg(TWO).encode())
        time.sleep(0.2)
        rp = sva_lcm.replan_t()
        rp.version = rp.VERSION
        rp.event_seq, rp.accepted = 1, 1
        rp.residual_fleet = fleet_msg(TWO)
        rp.residual_mission = mission_msg(TWO)
        rp.residual_mission.version = 1
        rp.plan = plan_msg(plan, 9)
        lc.publish("SVA_REPLAN", rp.encode())
        rp.residual_mission.version = rp.residual_mission.VERSION
        rp.version = 1
        rp.plan = plan_msg(plan, 11)
        lc.publish("SVA_REPLAN", rp.encode())
        time.sleep(1.0)
        lc.publish("SVA_PLAN", plan_msg(plan, 10).encode())  # this version: uploaded
        lines = bridge.wait_for(done_lines(10, 1))
        assert not [x for x in lines if x.startswith(("plan 7:", "plan 8:", "plan 9:", "plan 11:"))]
        assert len(va.wait_missions(1)) == 1
    finally:
        err = bridge.stop_and_stderr()
        va.close()
    t = sva_lcm
    for kind, what, got, want in [("FLEET", "fleet_state_t", 1, t.fleet_state_t.VERSION),
                                  ("MISSION", "mission_t", 1, t.mission_t.VERSION),
                                  ("PLAN", "plan_t", 3, t.plan_t.VERSION),
                                  ("REPLAN", "replan_t.residual_mission", 1, t.mission_t.VERSION),
                                  ("REPLAN", "replan_t", 1, t.replan_t.VERSION)]:
        assert (f"sva_mavlink_bridge: {kind}: {what}.version is {got}, this bridge speaks "
                f"version {want}; ignored") in err.splitlines(), err


def test_a_plan_without_a_frame_is_an_error_per_vehicle(lc, tmp_path):
    plan = mavcheck.plan_mission(TWO, tmp_path)
    pa = free_udp_port()
    va = MavsdkVehicle(pa, 1)
    bridge = Bridge({1: f"udp:127.0.0.1:{pa}:1", 2: "udp:127.0.0.1:9:2"})
    try:
        publish_start(lc, TWO, plan, plan_id=5, with_frame=False)
        lines = bridge.wait_for(done_lines(5, 2))
        for uid, port in ((1, pa), (2, 9)):
            assert (f"plan 5: uav {uid} (udp:127.0.0.1:{port}): error: frame: the mission has "
                    f"none (mission_t.frame.present 0): cells and ticks cannot be placed on the "
                    f"Earth; nothing uploaded") in lines
        time.sleep(0.5)
        assert va.missions == []
    finally:
        bridge.stop()
        va.close()


def test_failing_vehicles_are_reported_and_the_others_uploaded(lc, tmp_path):
    plan = mavcheck.plan_mission(FOUR, tmp_path)
    rs = [r for r in plan["routes"] if r["targets"]]
    assert len(rs) == 4
    good_port, deny_port, small_port, silent_port = (free_udp_port() for _ in range(4))
    good = MavsdkVehicle(good_port, 1)
    deny = PymavlinkVehicle(deny_port, 3, final=MAV_MISSION_DENIED)
    small = PymavlinkVehicle(small_port, 4, max_items=3)
    specs = {rs[0]["uav"]: f"udp:127.0.0.1:{good_port}:1",
             rs[1]["uav"]: f"udp:127.0.0.1:{silent_port}:2",
             rs[2]["uav"]: f"udp:127.0.0.1:{deny_port}:3",
             rs[3]["uav"]: f"udp:127.0.0.1:{small_port}:4"}
    bridge = Bridge(specs)
    try:
        publish_start(lc, FOUR, plan, plan_id=9)
        lines = bridge.wait_for(done_lines(9, 4), 30)

        def line(r, text):
            port = specs[r["uav"]].split(":")[2]
            return f"plan 9: uav {r['uav']} (udp:127.0.0.1:{port}): {text}"
        assert line(rs[0], f"uploaded {3 + 2 * len(rs[0]['targets'])} items") in lines
        assert line(rs[1], "error: timeout: no answer to MISSION_COUNT after 3 tries of 300 ms") in lines
        assert line(rs[2], "error: MISSION_ACK: the vehicle refused the mission: "
                           "MAV_MISSION_DENIED (14)") in lines
        assert line(rs[3], "error: MISSION_ACK: the vehicle refused the mission: "
                           "MAV_MISSION_NO_SPACE (4)") in lines
        got = good.wait_missions(1)
        problems = mavcheck.check_route(as_tuples(got[0][1]), FOUR, FOUR["frame"], rs[0]["uav"],
                                 rs[0]["targets"])
        assert problems == [], "\n".join(problems)
        assert len(deny.items) == 1 and small.items == []
    finally:
        bridge.stop()
        good.close()
        deny.close()
        small.close()


def test_ardupilot_home_item(lc, tmp_path):
    plan = mavcheck.plan_mission(TWO, tmp_path)
    r = next(r for r in plan["routes"] if r["uav"] == 1)
    pa = free_udp_port()
    va = MavsdkVehicle(pa, 1)
    bridge = Bridge({1: f"udp:127.0.0.1:{pa}:1"}, "--ardupilot")
    try:
        publish_start(lc, TWO, plan, plan_id=11)
        lines = bridge.wait_for(done_lines(11, 1))
        assert f"plan 11: uav 1 (udp:127.0.0.1:{pa}): uploaded {4 + 2 * len(r['targets'])} items" in lines
        judge(TWO, TWO["frame"], r, va.wait_missions(1), home=True)
    finally:
        bridge.stop()
        va.close()


def test_a_cancelled_first_target_uploads_the_shorter_mission_to_its_vehicle_only(lc, tmp_path):
    """Target 1, the first of UAV 1's two, is cancelled at tick 5, before its window (20):
    the new route [3] is the end of the mission UAV 1 has, but target 1 was not served, so
    the shorter mission is uploaded; UAV 2's route is unchanged."""
    three = dict(TWO, name="three", targets=TWO["targets"] + [ADDED])
    plan = mavcheck.plan_mission(three, tmp_path)
    routes = {r["uav"]: r["targets"] for r in plan["routes"]}
    assert routes == {1: [1, ADDED["id"]], 2: [2]}, routes
    pa, pb = free_udp_port(), free_udp_port()
    va, vb = MavsdkVehicle(pa, 1), MavsdkVehicle(pb, 2)
    bridge = Bridge({1: f"udp:127.0.0.1:{pa}:1", 2: f"udp:127.0.0.1:{pb}:2"})
    try:
        publish_start(lc, three, plan)
        bridge.wait_for(done_lines(1, 2))
        assert len(va.wait_missions(1)) == 1 and len(vb.wait_missions(1)) == 1

        # at tick 5 the UAVs are on their way (ready again at 5 where they stand)
        residual = dict(three, name="three_cancelled",
                        uavs=[dict(u, ready_at=5) for u in three["uavs"]],
                        targets=[t for t in three["targets"] if t["id"] != 1])
        plan2 = dict(plan, covered=2, routes=[dict(r, targets=[t for t in r["targets"] if t != 1])
                                              for r in plan["routes"]])
        rp = sva_lcm.replan_t()
        rp.version = rp.VERSION
        rp.event_seq = 1
        rp.event_type = TARGET_CANCELLED
        rp.accepted = 1
        rp.now_ticks = 5
        rp.residual_fleet = fleet_msg(residual, 1)
        rp.residual_mission = mission_msg(residual, 1)
        rp.plan = plan_msg(plan2, 2)
        lc.publish("SVA_REPLAN", rp.encode())
        lines = bridge.wait_for(done_lines(2, 2))
        assert f"plan 2: uav 1 (udp:127.0.0.1:{pa}): uploaded {3 + 2 * 1} items" in lines, lines
        assert f"plan 2: uav 2 (udp:127.0.0.1:{pb}): route unchanged, not uploaded" in lines
        got = va.wait_missions(2)
        assert len(got) == 2 and got[1][0] == 1
        problems = mavcheck.check_route(as_tuples(got[1][1]), residual, TWO["frame"], 1, [ADDED["id"]])
        assert problems == [], "\n".join(problems)
        time.sleep(1.0)
        assert len(vb.missions) == 1  # it got nothing new
    finally:
        bridge.stop()
        va.close()
        vb.close()


def test_a_refused_upload_is_tried_again_and_lands(lc, tmp_path):
    """A vehicle that answers the first MISSION_COUNT with MAV_MISSION_NO_SPACE (as a
    freshly booted ArduPilot does) and takes the second: one retry line, after the default
    5 tries again and 2000 ms, then the whole mission, judged item by item."""
    plan = mavcheck.plan_mission(TWO, tmp_path)
    r = next(r for r in plan["routes"] if r["uav"] == 1)
    pa = free_udp_port()
    va = PymavlinkVehicle(pa, 1, refuse_first=1)
    bridge = Bridge({1: f"udp:127.0.0.1:{pa}:1"}, upload_retries=None)
    link = f"uav 1 (udp:127.0.0.1:{pa})"
    n = 3 + 2 * len(r["targets"])
    try:
        publish_start(lc, TWO, plan, plan_id=21)
        lines = bridge.wait_for(lambda ls: any(x.startswith(f"plan 21: {link}: uploaded") or
                                               f"plan 21: {link}: error" in x for x in ls), 20)
        mine = [x for x in lines if x.startswith(f"plan 21: {link}: ")]
        assert mine == [f"plan 21: {link}: uploading {n} items",
                        f"plan 21: {link}: retry 1 of 5 in 2000 ms: MISSION_ACK: the vehicle "
                        f"refused the mission: MAV_MISSION_NO_SPACE ({MAV_MISSION_NO_SPACE})",
                        f"plan 21: {link}: uploaded {n} items"], mine
        assert va.counts == [n, n] and len(va.items) == 1
        problems = mavcheck.check_route(pymavlink_items(va.items[0]), TWO, TWO["frame"], 1, r["targets"])
        assert problems == [], "\n".join(problems)
    finally:
        bridge.stop()
        va.close()


def test_a_vehicle_that_always_refuses_gets_n_retries_and_holds_up_no_other(lc, tmp_path):
    """--upload-retries 2: the refused mission is sent again after 2000 ms and 4000 ms,
    then the error line; the other vehicle's upload is done long before."""
    plan = mavcheck.plan_mission(TWO, tmp_path)
    r = {r["uav"]: r for r in plan["routes"]}
    pa, pb = free_udp_port(), free_udp_port()
    refuser = PymavlinkVehicle(pa, 1, max_items=1)
    good = MavsdkVehicle(pb, 2)
    bridge = Bridge({1: f"udp:127.0.0.1:{pa}:1", 2: f"udp:127.0.0.1:{pb}:2"},
                    upload_retries="2")
    bad_link, good_link = f"uav 1 (udp:127.0.0.1:{pa})", f"uav 2 (udp:127.0.0.1:{pb})"
    n = 3 + 2 * len(r[1]["targets"])
    refused = (f"MISSION_ACK: the vehicle refused the mission: MAV_MISSION_NO_SPACE "
               f"({MAV_MISSION_NO_SPACE})")
    try:
        start = time.monotonic()
        publish_start(lc, TWO, plan, plan_id=22)
        lines = bridge.wait_for(lambda ls: f"plan 22: {bad_link}: error: {refused}" in ls, 30)
        took = time.monotonic() - start
        mine = [x for x in lines if x.startswith(f"plan 22: {bad_link}: ")]
        assert mine == [f"plan 22: {bad_link}: uploading {n} items",
                        f"plan 22: {bad_link}: retry 1 of 2 in 2000 ms: {refused}",
                        f"plan 22: {bad_link}: retry 2 of 2 in 4000 ms: {refused}",
                        f"plan 22: {bad_link}: error: {refused}"], mine
        assert 6.0 <= took < 15.0, took
        uploaded = f"plan 22: {good_link}: uploaded {3 + 2 * len(r[2]['targets'])} items"
        assert lines.index(uploaded) < lines.index(mine[2]), lines
        judge(TWO, TWO["frame"], r[2], good.wait_missions(1))
        time.sleep(2.5)
        assert refuser.counts == [n, n, n] and refuser.items == []
        assert not [x for x in bridge.lines[len(lines):] if x.startswith("plan 22:")]
    finally:
        bridge.stop()
        refuser.close()
        good.close()


def test_a_newer_plan_replaces_the_retry_pending(lc, tmp_path):
    """A plan for the vehicle that arrives while a refused upload waits for its retry is
    uploaded instead; the older mission is not sent again."""
    plan = mavcheck.plan_mission(TWO, tmp_path)
    moved = dict(TWO, name="two_moved",
                 targets=[dict(t, x=8) if t["id"] == 1 else t for t in TWO["targets"]])
    plan2 = mavcheck.plan_mission(moved, tmp_path)
    r2 = next(r for r in plan2["routes"] if r["uav"] == 1)
    assert r2["targets"] == [1]
    pa = free_udp_port()
    va = PymavlinkVehicle(pa, 1, refuse_first=1)
    bridge = Bridge({1: f"udp:127.0.0.1:{pa}:1"}, upload_retries="3")
    link = f"uav 1 (udp:127.0.0.1:{pa})"
    n = 3 + 2 * len(r2["targets"])
    try:
        publish_start(lc, TWO, plan, plan_id=23)
        bridge.wait_for(lambda ls: any(x.startswith(f"plan 23: {link}: retry 1 of 3 in 2000 ms: ")
                                       for x in ls), 10)
        lc.publish("SVA_FLEET", fleet_msg(moved, 2).encode())
        lc.publish("SVA_MISSION", mission_msg(moved, 2).encode())
        time.sleep(0.2)
        lc.publish("SVA_PLAN", plan_msg(plan2, 24, revision=2).encode())
        bridge.wait_for(lambda ls: f"plan 24: {link}: uploaded {n} items" in ls, 10)
        time.sleep(3.0)  # past the retry's 2000 ms
        assert va.counts == [n, n] and len(va.items) == 1, va.counts
        problems = mavcheck.check_route(pymavlink_items(va.items[0]), moved, TWO["frame"], 1,
                                 r2["targets"])
        assert problems == [], "\n".join(problems)
        refused = (f"MISSION_ACK: the vehicle refused the mission: MAV_MISSION_NO_SPACE "
                   f"({MAV_MISSION_NO_SPACE})")
        assert [x for x in bridge.lines if x.startswith(("plan 23: ", "plan 24: "))] == [
            f"plan 23: {link}: uploading {n} items",
            f"plan 23: {link}: retry 1 of 3 in 2000 ms: {refused}",
            f"plan 24: {link}: uploading {n} items",
            f"plan 24: {link}: uploaded {n} items"], bridge.lines
    finally:
        bridge.stop()
        va.close()


@pytest.mark.parametrize("value", ["-1", "101", "2s"])
def test_a_bad_upload_retries_is_one_line_and_exit_2(value):
    p = subprocess.run([BRIDGE, "--vehicle", "1=udp:127.0.0.1:9", "--upload-retries", value],
                       capture_output=True, text=True, timeout=30)
    assert p.returncode == 2 and p.stdout == ""
    assert p.stderr == (f"sva_mavlink_bridge: error: --upload-retries: must be an integer in "
                        f"[0, 100], got \"{value}\"\n")


def test_upload_retries_takes_both_ends():
    for value in ("0", "100"):
        Bridge({1: "udp:127.0.0.1:9:1"}, upload_retries=value).stop()
