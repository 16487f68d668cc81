"""Uploads over UDP on loopback to vehicle sides that are not the bridge's code:
`sva-tools mavlink upload` (pymavlink) and the C library (mavlink_tool) to MAVSDK's
MissionRawServer, whose received missions are read back and judged item by item; and
the failures (no frame, a vehicle that does not answer, a refusal, a vehicle's item
limit) each reported for its vehicle while the others' uploads go on."""
from __future__ import annotations

import json
import os
import subprocess

import pytest

import mavcheck as C
from vehicles import MavsdkVehicle, PymavlinkVehicle, free_udp_port
from test_items import CASES, FRAME_MIDNIGHT, with_frame

MAV_MISSION_DENIED = 14
FAST = ["--timeout-ms", "300", "--retries", "2"]


def as_tuples(mavsdk_items):
    return [(i.command, i.frame, i.param1, i.param2, i.param3, i.param4, i.x, i.y, i.z)
            for i in mavsdk_items]


def write(tmp_path, name, doc):
    path = tmp_path / name
    path.write_text(json.dumps(doc))
    return str(path)


def sva_tools(*args):
    return subprocess.run([os.environ["SVA_TOOLS"], "mavlink", "upload", *args],
                          capture_output=True, text=True, timeout=120)


@pytest.fixture
def vehicles():
    made = []

    def make(kind, *args, **kw):
        port = free_udp_port()
        v = (MavsdkVehicle if kind == "mavsdk" else PymavlinkVehicle)(port, *args, **kw)
        made.append(v)
        return port, v
    yield make
    for v in made:
        v.close()


def routed(plan, n):
    rs = [r for r in plan["routes"] if r["targets"]]
    assert len(rs) >= n, "the case must route enough UAVs"
    return rs[:n]


def judge(mission, frame, route, got, home=False):
    assert len(got) == 1, f"uav {route['uav']}: {len(got)} missions received"
    result, items = got[0]
    assert result == 1  # MissionRawServerResult.SUCCESS
    items = as_tuples(items)
    if home:  # ArduPilot's item 0: a waypoint where the take-off is, altitude 0
        assert (items[0][0], items[0][6], items[0][7], items[0][8]) == \
            (C.NAV_WAYPOINT, items[1][6], items[1][7], 0.0)
        items = items[1:]
    problems = C.check_route(items, mission, frame, route["uav"], route["targets"])
    assert problems == [], "\n".join(problems)


@pytest.mark.parametrize("frame_in", ["mission", "plan", "ardupilot"])
def test_host_tool_uploads_to_mavsdk_vehicles(frame_in, tmp_path, vehicles):
    mission = CASES[0]
    plan = C.plan_mission(mission, tmp_path)
    if frame_in == "plan":
        # the plan's frame wins over the mission's
        plan = dict(plan, frame=mission["frame"])
        mission = dict(mission, frame=dict(mission["frame"], lat=10.0, lon=20.0))
    a, b = routed(plan, 2)
    (pa, va), (pb, vb) = vehicles("mavsdk", 1), vehicles("mavsdk", 7)
    home = frame_in == "ardupilot"
    p = sva_tools(write(tmp_path, "plan.json", plan), "--mission",
                  write(tmp_path, "mission.json", mission),
                  "--vehicle", f"{a['uav']}=udp:127.0.0.1:{pa}",
                  "--vehicle", f"{b['uav']}=udp:127.0.0.1:{pb}:7", *(["--ardupilot"] if home else []))
    assert p.returncode == 0, p.stderr + p.stdout
    n_a, n_b = 3 + home + 2 * len(a["targets"]), 3 + home + 2 * len(b["targets"])
    assert p.stdout.splitlines() == [
        f"uav {a['uav']}: udp:127.0.0.1:{pa}: uploaded {n_a} items",
        f"uav {b['uav']}: udp:127.0.0.1:{pb}:7: uploaded {n_b} items"]
    frame = plan.get("frame", mission["frame"])
    judge(mission, frame, a, va.wait_missions(1), home)
    judge(mission, frame, b, vb.wait_missions(1), home)


@pytest.mark.parametrize("mission", CASES, ids=lambda m: m["name"])
def test_c_library_uploads_to_mavsdk_vehicles(mission, tmp_path, vehicles):
    plan = C.plan_mission(mission, tmp_path)
    rs = [r for r in plan["routes"] if r["targets"]][:3]
    ports = {r["uav"]: vehicles("mavsdk", 1 + k) for k, r in enumerate(rs)}
    specs = {u: f"udp:127.0.0.1:{port}:{1 + k}" for k, (u, (port, _)) in enumerate(ports.items())}
    items, results, rc, err = C.run_tool(C.tool_input(mission, mission["frame"], plan, specs))
    assert rc == 0, err
    for r in rs:
        assert results[r["uav"]] == f"ok {3 + 2 * len(r['targets'])}"
        got = ports[r["uav"]][1].wait_missions(1)
        judge(mission, mission["frame"], r, got)
        # what the vehicle holds is what the library built
        assert [(i[0], i[1], i[6], i[7]) for i in as_tuples(got[0][1])] == \
            [(i[0], i[1], i[6], i[7]) for i in items[r["uav"]]]


def test_host_tool_refuses_a_plan_without_a_frame(tmp_path):
    mission = with_frame("rand_7_2", FRAME_MIDNIGHT)
    plan = C.plan_mission(mission, tmp_path)
    bare = {k: v for k, v in mission.items() if k != "frame"}
    plan_path = write(tmp_path, "plan.json", plan)
    p = sva_tools(plan_path, "--mission", write(tmp_path, "m.json", bare),
                  "--vehicle", "1=udp:127.0.0.1:9")
    assert p.returncode == 2
    assert p.stdout == ""
    assert p.stderr == (f"sva-tools: error: {plan_path}: frame: missing: neither the plan nor the "
                        f"mission has a \"frame\" (lat, lon, alt_m, cell_m, tick_s, t0): cells and "
                        f"ticks cannot be placed on the Earth\n")


def test_host_tool_names_a_bad_frame_field(tmp_path):
    mission = with_frame("rand_7_2", dict(FRAME_MIDNIGHT, cell_m=0.05))
    plan = C.plan_mission(mission, tmp_path)
    mpath = write(tmp_path, "m.json", mission)
    p = sva_tools(write(tmp_path, "plan.json", plan), "--mission", mpath,
                  "--vehicle", "1=udp:127.0.0.1:9")
    assert p.returncode == 2
    assert p.stderr == f"sva-tools: error: {mpath}: frame.cell_m: must be >= 0.1, got 0.05\n"


# Four UAVs, four targets that each needs one of them.
FOUR = {"name": "four", "depot": {"x": 0, "y": 0}, "frame": FRAME_MIDNIGHT,
        "uavs": [{"id": u, "x": 0, "y": 0, "fuel": 1000} for u in (1, 2, 3, 4)],
        "targets": [{"id": k + 1, "x": x, "y": y, "start": 20, "end": 30, "need": 1}
                    for k, (x, y) in enumerate([(10, 0), (0, 10), (-10, 0), (0, -10)])]}


def failing_fleet(tmp_path, vehicles):
    """Four routed UAVs: a MAVSDK vehicle that accepts, one port nobody answers on, a
    pymavlink vehicle that refuses (MAV_MISSION_DENIED), one whose limit is 3 items."""
    mission = FOUR
    plan = C.plan_mission(mission, tmp_path)
    rs = routed(plan, 4)
    good_port, good = vehicles("mavsdk", 1)
    deny_port, deny = vehicles("pymavlink", 3, final=MAV_MISSION_DENIED)
    small_port, small = vehicles("pymavlink", 4, max_items=3)
    silent_port = free_udp_port()
    specs = {rs[0]["uav"]: f"udp:127.0.0.1:{good_port}:1",
             rs[1]["uav"]: f"udp:127.0.0.1:{silent_port}:2",
             rs[2]["uav"]: f"udp:127.0.0.1:{deny_port}:3",
             rs[3]["uav"]: f"udp:127.0.0.1:{small_port}:4"}
    return mission, plan, rs, specs, good, deny, small


def test_host_tool_reports_each_failing_vehicle_and_uploads_the_others(tmp_path, vehicles):
    mission, plan, rs, specs, good, deny, small = failing_fleet(tmp_path, vehicles)
    args = [write(tmp_path, "plan.json", plan), "--mission", write(tmp_path, "m.json", mission)]
    for u, s in specs.items():
        args += ["--vehicle", f"{u}={s}"]
    p = sva_tools(*args, *FAST)
    assert p.returncode == 1, p.stderr
    lines = p.stdout.splitlines()
    n0 = 3 + 2 * len(rs[0]["targets"])
    assert lines == [
        f"uav {rs[0]['uav']}: {specs[rs[0]['uav']]}: uploaded {n0} items",
        f"uav {rs[1]['uav']}: {specs[rs[1]['uav']]}: error: timeout: no answer to MISSION_COUNT "
        f"after 3 tries of 300 ms",
        f"uav {rs[2]['uav']}: {specs[rs[2]['uav']]}: error: MISSION_ACK: the vehicle refused the "
        f"mission: MAV_MISSION_DENIED (14)",
        f"uav {rs[3]['uav']}: {specs[rs[3]['uav']]}: error: MISSION_ACK: the vehicle refused the "
        f"mission: MAV_MISSION_NO_SPACE (4)"]
    judge(mission, mission["frame"], rs[0], good.wait_missions(1))
    assert len(deny.items) == 1 and len(deny.items[0]) == 3 + 2 * len(rs[2]["targets"])
    assert small.counts == [3 + 2 * len(rs[3]["targets"])] and small.items == []


def test_c_library_reports_each_failing_vehicle_and_uploads_the_others(tmp_path, vehicles):
    mission, plan, rs, specs, good, deny, small = failing_fleet(tmp_path, vehicles)
    _, results, rc, err = C.run_tool(C.tool_input(mission, mission["frame"], plan, specs,
                                                  timeout="300 2"))
    assert rc == 1, err
    assert results[rs[0]["uav"]] == f"ok {3 + 2 * len(rs[0]['targets'])}"
    assert results[rs[1]["uav"]] == ("error timeout: no answer to MISSION_COUNT after 3 tries of "
                                     "300 ms")
    assert results[rs[2]["uav"]] == ("error MISSION_ACK: the vehicle refused the mission: "
                                     "MAV_MISSION_DENIED (14)")
    assert results[rs[3]["uav"]] == ("error MISSION_ACK: the vehicle refused the mission: "
                                     "MAV_MISSION_NO_SPACE (4)")
    judge(mission, mission["frame"], rs[0], good.wait_missions(1))
    assert len(deny.items) == 1
    assert small.items == []


def pymavlink_items(msgs):
    assert all(m.get_type() == "MISSION_ITEM_INT" for m in msgs)
    return [(m.command, m.frame, m.param1, m.param2, m.param3, m.param4, m.x, m.y, m.z)
            for m in msgs]


def test_c_library_answers_a_fussy_vehicle(tmp_path, vehicles):
    """A lost MISSION_COUNT (resent after the timeout), MISSION_REQUEST instead of
    MISSION_REQUEST_INT, items asked for backwards and twice each."""
    mission = CASES[0]
    plan = C.plan_mission(mission, tmp_path)
    r = routed(plan, 1)[0]
    port, v = vehicles("pymavlink", 5, fussy=True)
    _, results, rc, err = C.run_tool(C.tool_input(mission, mission["frame"], plan,
                                                  {r["uav"]: f"udp:127.0.0.1:{port}:5"},
                                                  timeout="300 2"))
    assert rc == 0, err
    assert results[r["uav"]] == f"ok {3 + 2 * len(r['targets'])}"
    assert len(v.counts) == 2 and len(v.items) == 1
    problems = C.check_route(pymavlink_items(v.items[0]), mission, mission["frame"], r["uav"],
                             r["targets"])
    assert problems == [], "\n".join(problems)


def test_host_tool_answers_a_fussy_vehicle(tmp_path, vehicles):
    mission = CASES[0]
    plan = C.plan_mission(mission, tmp_path)
    r = routed(plan, 1)[0]
    port, v = vehicles("pymavlink", 5, fussy=True)
    p = sva_tools(write(tmp_path, "plan.json", plan), "--mission",
                  write(tmp_path, "m.json", mission), "--vehicle",
                  f"{r['uav']}=udp:127.0.0.1:{port}:5", *FAST)
    assert p.returncode == 0, p.stderr + p.stdout
    assert len(v.counts) == 2 and len(v.items) == 1
    problems = C.check_route(pymavlink_items(v.items[0]), mission, mission["frame"], r["uav"],
                             r["targets"])
    assert problems == [], "\n".join(problems)
