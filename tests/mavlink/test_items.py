"""Mission items of the C library (through tests/mavlink/mavlink_tool) and of
`sva-tools mavlink` (sva_tools.mavlink.build_items), each judged item by item by
mavcheck against pymap3d, the window times and the plan's timing."""
from __future__ import annotations

import json
import os

import pytest

import mavcheck
from sva_tools import mavlink
from sva_tools import io as sio

FIXTURES = os.environ["SVA_FIXTURES"]

# Holds that cross midnight UTC (t0 two minutes before it, windows up to tick 138).
FRAME_MIDNIGHT = {"lat": 47.3977419, "lon": 8.5455938, "alt_m": 50, "cell_m": 25, "tick_s": 2,
                  "t0": "2026-11-25T23:58:00Z"}
# Tight axis-aligned legs: departure + Manhattan travel == start exactly, high up.
TIGHT = {
    "name": "tight", "depot": {"x": 0, "y": 0}, "ticks_per_cell": 3,
    "uavs": [{"id": 1, "x": 0, "y": 0, "fuel": 10000, "ready_at": 5},
             {"id": 2, "x": 0, "y": 0, "fuel": 10000}],
    "targets": [{"id": 1, "x": 40, "y": 0, "start": 125, "end": 130, "need": 1},
                {"id": 2, "x": 40, "y": 35, "start": 235, "end": 240, "need": 1},
                {"id": 3, "x": -30, "y": -30, "start": 180, "end": 200, "need": 1}],
    "frame": {"lat": -33.8688, "lon": 151.2093, "alt_m": 400, "cell_m": 100, "tick_s": 1.5,
              "t0": "2026-06-30T12:00:00.250Z"},
}


def with_frame(name: str, frame: dict) -> dict:
    with open(os.path.join(FIXTURES, "missions", f"{name}.json")) as f:
        m = json.load(f)
    m["frame"] = frame
    return m


CASES = [with_frame("rand_7_2", FRAME_MIDNIGHT), TIGHT,
         with_frame("hand_5_3", dict(FRAME_MIDNIGHT, lat=-60.5, lon=-179.9, cell_m=500, tick_s=30,
                                     t0="2026-01-01T00:00:00Z"))]


@pytest.mark.parametrize("mission", CASES, ids=lambda m: m["name"])
def test_c_items_match_the_plan(mission, tmp_path):
    plan = mavcheck.plan_mission(mission, tmp_path)
    items, results, rc, err = mavcheck.run_tool(mavcheck.tool_input(mission, mission["frame"], plan, {}))
    assert rc == 0, err
    routed = [r for r in plan["routes"] if r["targets"]]
    assert routed, "the case must route something"
    for r in plan["routes"]:
        got = items.get(r["uav"], [])
        problems = mavcheck.check_route(got, mission, mission["frame"], r["uav"], r["targets"])
        assert problems == [], "\n".join(problems)


@pytest.mark.parametrize("mission", CASES, ids=lambda m: m["name"])
def test_python_items_match_the_plan_and_the_c_items(mission, tmp_path):
    plan = mavcheck.plan_mission(mission, tmp_path)
    c_items, _, rc, err = mavcheck.run_tool(mavcheck.tool_input(mission, mission["frame"], plan, {}))
    assert rc == 0, err
    m = sio.mission_from_json({k: v for k, v in mission.items() if k != "frame"})
    frame = mavlink.frame_from_json(mission["frame"])
    uavs = {u.id: u for u in m.uavs}
    for r in plan["routes"]:
        py = [(i.command, i.frame, i.param1, i.param2, i.param3, i.param4, i.x, i.y, i.z)
              for i in mavlink.build_items(frame, m, uavs[r["uav"]], r["targets"])]
        problems = mavcheck.check_route(py, mission, mission["frame"], r["uav"], r["targets"])
        assert problems == [], "\n".join(problems)
        ci = c_items.get(r["uav"], [])
        assert len(ci) == len(py)
        for a, b in zip(ci, py):
            # PROJ (C) and pymap3d (Python) agree to the last 1e-7 degree
            assert a[0:2] == b[0:2] and abs(a[6] - b[6]) <= 1 and abs(a[7] - b[7]) <= 1, (a, b)
            for pa, pb in zip(a[2:6] + a[8:], b[2:6] + b[8:]):
                assert (pa != pa and pb != pb) or pa == pytest.approx(pb, rel=1e-7), (a, b)


def test_the_timing_check_catches_the_unscaled_speed(tmp_path):
    """The judge can fail: at exactly cell / (ticks_per_cell * tick), the tight legs flown
    400 m up arrive after their windows' starts."""
    plan = mavcheck.plan_mission(TIGHT, tmp_path)
    items, _, rc, err = mavcheck.run_tool(mavcheck.tool_input(TIGHT, TIGHT["frame"], plan, {}))
    assert rc == 0, err
    fi = mavcheck.frame_ints(TIGHT["frame"])
    plain = (fi["cell_cm"] / 100.0) / (TIGHT["ticks_per_cell"] * fi["tick_ms"] / 1000.0)
    late = []
    for r in plan["routes"]:
        got = list(items.get(r["uav"], []))
        if not got:
            continue
        got[1] = got[1][:3] + (plain,) + got[1][4:]
        late += [p for p in mavcheck.check_route(got, TIGHT, TIGHT["frame"], r["uav"], r["targets"])
                 if "arrives at" in p]
    assert late, "tight legs at the plain plan speed should arrive late at altitude"


def test_a_hold_of_a_day_is_refused():
    text = ("frame 473977419 85455938 5000 2500 1000 1764115200000\ntpc 1\n"
            "route 1 0 0 0\ntarget 1 2 0 10 86401\nroute 2 0 0 0\ntarget 2 1 0 5 10\n")
    items, results, rc, _ = mavcheck.run_tool(text)
    assert rc == 1
    assert results[1].startswith("error uav 1: targets[0] (id 1): from the departure at tick 0")
    assert "must be < 86400000" in results[1]
    assert 2 in items and 1 not in items  # the other UAV is built all the same


def test_a_route_the_plan_cannot_fly_is_refused():
    text = ("frame 473977419 85455938 5000 2500 1000 1764115200000\ntpc 2\n"
            "route 1 0 0 3\ntarget 1 5 5 22 30\n")
    _, results, rc, _ = mavcheck.run_tool(text)
    assert rc == 1
    assert results[1] == ("error uav 1: targets[0] (id 1): leaving at tick 3 and flying 20 ticks "
                          "arrives after the window's start 22")


def test_a_route_over_the_item_limit_is_refused():
    lines = ["frame 473977419 85455938 5000 2500 1000 1764115200000", "tpc 1", "route 7 0 0 0"]
    for k in range(257):
        lines.append(f"target {k + 1} 0 {k % 2} {2 * k + 1} {2 * k + 2}")
    _, results, rc, _ = mavcheck.run_tool("\n".join(lines) + "\n")
    assert rc == 1
    assert results[7] == "error uav 7: route: 257 targets need 517 mission items, more than the limit 515"


def test_cruise_speed_is_commanded_and_never_below_the_plan():
    """A cruise speed replaces the plan's in DO_CHANGE_SPEED (the rest unchanged); one
    below the plan's speed is refused, naming both speeds."""
    lines = ["frame 473977419 85455938 3000 2500 5000 1764115200000", "tpc 1", "route 4 0 0 0",
             "target 1 3 0 20 30"]
    plain, _, rc, err = mavcheck.run_tool("\n".join(lines) + "\n")
    assert rc == 0, err
    assert plain[4][1][0] == 178 and plain[4][1][3] == pytest.approx(5.0, rel=1e-5)
    fast, _, rc, err = mavcheck.run_tool("cruise 9.5\n" + "\n".join(lines) + "\n")
    assert rc == 0, err
    assert fast[4][1][3] == pytest.approx(9.5)
    assert [repr(i) for k, i in enumerate(fast[4]) if k != 1] == \
        [repr(i) for k, i in enumerate(plain[4]) if k != 1]
    _, results, rc, err = mavcheck.run_tool("cruise 4.9\n" + "\n".join(lines) + "\n")
    assert rc == 1
    assert results[4].startswith("error uav 4: cruise speed 4.9 m/s is below the plan's speed 5 m/s")


def test_ardupilot_home_item_comes_first(tmp_path):
    """With a home item 0 the rest is the same mission, shifted by one; 256 targets
    (515 items + home) still fit."""
    mission = CASES[0]
    plan = mavcheck.plan_mission(mission, tmp_path)
    text = mavcheck.tool_input(mission, mission["frame"], plan, {})
    plain, _, rc, err = mavcheck.run_tool(text)
    assert rc == 0, err
    homed, _, rc, err = mavcheck.run_tool("ardupilot\n" + text)
    assert rc == 0, err
    for r in plan["routes"]:
        a, b = plain.get(r["uav"], []), homed.get(r["uav"], [])
        if not a:
            assert b == []
            continue
        assert [repr(i) for i in b[1:]] == [repr(i) for i in a]  # repr: NaN equals NaN
        assert (b[0][0], b[0][1], b[0][6], b[0][7], b[0][8]) == (mavcheck.NAV_WAYPOINT, mavcheck.FRAME_GLOBAL_REL_ALT_INT,
                                                                  a[0][6], a[0][7], 0.0)
    lines = ["ardupilot", "frame 473977419 85455938 5000 2500 1000 1764115200000", "tpc 1",
             "route 7 0 0 0"]
    for k in range(256):
        lines.append(f"target {k + 1} 0 {k % 2} {2 * k + 1} {2 * k + 2}")
    items, results, rc, err = mavcheck.run_tool("\n".join(lines) + "\n")
    assert rc == 0, err
    assert len(items[7]) == 516
