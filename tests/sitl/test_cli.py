"""`sva-tools sitl`: what is refused before any vehicle starts (no root, no SITL needed):
a frame whose plan speed the copter cannot fly with margin, a bad --frame, a position
event, a missing SITL binary, a mission with a frame and --frame. One line each, exit 2."""
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
SCENARIO = REPO / "fixtures" / "scenarios" / "sitl_3uav.json"


def sitl(*args):
    env = dict(os.environ, PYTHONPATH=str(REPO / "tools"))
    return subprocess.run([sys.executable, "-m", "sva_tools", "sitl", *map(str, args)],
                          capture_output=True, text=True, env=env, timeout=60)


def refused(r, text):
    assert r.returncode == 2, r.stderr
    assert r.stdout == ""
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("sva-tools: error: "), r.stderr
    assert text in lines[0], lines[0]


def scenario(tmp_path, **changes):
    doc = json.loads(SCENARIO.read_text())
    doc["mission"].update(changes.pop("mission", {}))
    doc.update(changes)
    p = tmp_path / "s.json"
    p.write_text(json.dumps(doc))
    return p


def test_a_frame_too_fast_for_the_copter(tmp_path):
    r = sitl(SCENARIO, "--frame", "47.3977,8.5456,30,50,1")
    refused(r, "frame: the plan's speed cell_m / (ticks_per_cell * tick_s) = 50 / (1 * 1) = 50 m/s "
               "must be <= 6 m/s (60% of the copter's 10 m/s WPNAV_SPEED)")
    # ticks_per_cell counts: the same frame at 10 ticks a cell flies 5 m/s (then: no SITL here)
    r = sitl(scenario(tmp_path, mission={"ticks_per_cell": 10, "takeoff_ticks": 0}),
             "--frame", "47.3977,8.5456,30,50,1",
             "--sitl", tmp_path / "none")
    refused(r, "the ArduCopter SITL binary is missing")


def test_the_missions_own_frame_is_checked_too(tmp_path):
    frame = {"lat": 47.3977, "lon": 8.5456, "alt_m": 30, "cell_m": 40, "tick_s": 5,
             "t0": "2030-01-01T00:00:00Z"}
    r = sitl(scenario(tmp_path, mission={"frame": frame}))
    refused(r, "= 40 / (1 * 5) = 8 m/s must be <= 6 m/s")
    r = sitl(scenario(tmp_path, mission={"frame": dict(frame, cell_m=25)}))
    refused(r, "frame: a cell takes ticks_per_cell * tick_s = 1 * 5 = 5 s in the plan, must be "
               ">= 5.80 s: the copter's time from a hold into the coverage radius")
    r = sitl(scenario(tmp_path, mission={"frame": dict(frame, cell_m=25, tick_s=6)}), "--frame",
             "47.3977,8.5456,30,25,6")
    refused(r, "--frame: the mission has a frame of its own")


@pytest.mark.parametrize("text, message", [
    ("47.3977,8.5456,30,25", "--frame: must be LAT,LON,ALT_M,CELL_M,TICK_S"),
    ("47.3977,8.5456,30,x,5", "--frame: must be five numbers"),
    ("95,8.5456,30,25,5", "--frame: frame.lat: must be <= 85, got 95"),
    ("47.3977,8.5456,30,0.05,5", "--frame: frame.cell_m: must be >= 0.1, got 0.05"),
])
def test_bad_frames(text, message):
    refused(sitl(SCENARIO, f"--frame={text}"), message)


def test_a_position_event_is_not_flown(tmp_path):
    doc = json.loads(SCENARIO.read_text())
    doc["events"].append({"at": 30, "type": "position", "uav": 2, "x": 1, "y": 1, "fuel": 100})
    p = tmp_path / "s.json"
    p.write_text(json.dumps(doc))
    refused(sitl(p), "events[3].type: position is not flown in SITL")


def test_bad_scenario_and_speedup(tmp_path):
    p = tmp_path / "bad.json"
    p.write_text('{"mission": {}, "events": []}')
    r = sitl(p)
    assert r.returncode == 2 and r.stderr.startswith("sva-tools: error: ")
    refused(sitl(SCENARIO, "--speedup", "0"), "--speedup: must be in (0, 100], got 0")


def test_listed_among_the_commands():
    env = dict(os.environ, PYTHONPATH=str(REPO / "tools"))
    r = subprocess.run([sys.executable, "-m", "sva_tools", "sitl", "--help"], capture_output=True,
                       text=True, env=env, timeout=60)
    assert r.returncode == 0 and "--speedup" in r.stdout and "47.3977,8.5456,30,25,6" in r.stdout


@pytest.mark.parametrize("value, text", [
    ("x:1", '--fault: KIND must be one of silent-upload, reject-item, reboot, got "x"'),
    ("reboot:9", "--fault: UAV_ID must be the id of a UAV of the mission (1, 2, 3), got \"9\""),
    ("reboot:one", "--fault: UAV_ID must be the id of a UAV of the mission (1, 2, 3), got \"one\""),
    ("reboot:1:-1", '--fault: T_S must be a number of seconds after t0 in [0, 86400], got "-1"'),
    ("reboot:1:86401", '--fault: T_S must be a number of seconds after t0 in [0, 86400], got "86401"'),
    ("reboot:1:nan", '--fault: T_S must be a number of seconds after t0 in [0, 86400], got "nan"'),
    ("reboot", '--fault: must be KIND:UAV_ID[:T_S], got "reboot"'),
    ("reboot:1:2:3", '--fault: must be KIND:UAV_ID[:T_S], got "reboot:1:2:3"'),
])
def test_a_bad_fault_is_refused_naming_the_rule_and_the_limit(tmp_path, value, text):
    r = sitl(SCENARIO, "--fault", value, "--sitl", tmp_path / "none")
    refused(r, text)


def test_one_fault_per_uav(tmp_path):
    r = sitl(SCENARIO, "--fault", "reboot:1", "--fault", "reject-item:1", "--sitl", tmp_path / "none")
    refused(r, "--fault: uav 1 has a fault already: at most one per UAV")
    # both ends of T_S pass the option (then: no SITL here)
    r = sitl(SCENARIO, "--fault", "reboot:1:0", "--fault", "silent-upload:2:86400", "--sitl", tmp_path / "none")
    refused(r, "the ArduCopter SITL binary is missing")


def test_help_names_the_faults():
    r = sitl("--help")
    assert r.returncode == 0 and "--fault KIND:UAV_ID[:T_S]" in r.stdout
    text = "".join(r.stdout.split())  # argparse wraps lines, at hyphens too
    for kind in ("silent-upload", "reject-item", "reboot"):
        assert kind in text


def test_a_take_off_shorter_than_the_copters_is_refused(tmp_path):
    r = sitl(scenario(tmp_path, mission={"takeoff_ticks": 2}))
    refused(r, "mission.takeoff_ticks: must be >= 4 (the copter's take-off to 30 m, 24 s, in 6 s "
               "ticks), got 2")
    # at 1 s ticks the same 24 s is 24 ticks
    r = sitl(scenario(tmp_path, mission={"takeoff_ticks": 23, "ticks_per_cell": 10}),
             "--frame=47.3977,8.5456,30,4,1")
    refused(r, "mission.takeoff_ticks: must be >= 24 (")
