"""A file of another of our kinds (mission, plan, live mission, scenario, flight log)
given to `sva plan`, `sva validate` or `sva replan`: one line naming what the file is,
the command that takes it and what the command takes (docs/cli.md), exit 2."""
import json

import pytest

from test_cli import FIXTURES, assert_one_error_line, run

MISSION_TAKER = "sva plan and sva validate take a mission (name, depot, uavs, targets; SPEC 3)"
LIVE_TAKER = "sva replan takes a live mission (mission, plan, events, now; SPEC 12.5)"
IS_MISSION = "this is a mission (name, depot, uavs, targets): sva plan takes it"
IS_PLAN = "this is a plan (mission, algorithm, status, routes): sva-tools check MISSION PLAN takes it"
IS_LIVE = "this is a live mission (mission, plan, events, now): sva replan takes it"
IS_SCENARIO = "this is a scenario (mission, events, change_penalty): sva-tools sim takes it"
IS_LOG = ("this is a flight log (scenario, uavs, targets, replans): sva-tools sim writes it, "
          "and takes its scenario")


def mission_doc():
    return json.loads((FIXTURES / "missions" / "hand_3_1.json").read_text())


def documents():
    """Each kind as a document, with what the messages call it."""
    m = mission_doc()
    plan = json.loads((FIXTURES / "golden" / "sva" / "hand_3_1.json").read_text())
    scenario = json.loads((FIXTURES / "scenarios" / "hand_events.json").read_text())
    return {
        "mission": (m, IS_MISSION),
        "plan": (plan, IS_PLAN),
        "live": ({"mission": m, "plan": {"routes": plan["routes"]}, "now": 5}, IS_LIVE),
        "scenario": (scenario, IS_SCENARIO),
        "log": ({"scenario": scenario, "algorithm": "sva", "end_tick": 0, "uavs": [], "targets": [],
                 "replans": [], "summary": {}}, IS_LOG),
    }


@pytest.mark.parametrize("command", ["plan", "validate"])
@pytest.mark.parametrize("kind", ["plan", "live", "scenario", "log"])
def test_plan_and_validate_name_a_file_that_is_not_a_mission(tmp_path, command, kind):
    doc, what = documents()[kind]
    (tmp_path / "in.json").write_text(json.dumps(doc))
    err = assert_one_error_line(run([command, "in.json"], cwd=tmp_path), 2)
    assert err == f"in.json: {what}; {MISSION_TAKER}"


@pytest.mark.parametrize("kind", ["mission", "plan", "scenario", "log"])
def test_replan_names_a_file_that_is_not_a_live_mission(tmp_path, kind):
    doc, what = documents()[kind]
    (tmp_path / "in.json").write_text(json.dumps(doc))
    err = assert_one_error_line(run(["replan", "in.json"], cwd=tmp_path), 2)
    assert err == f"in.json: {what}; {LIVE_TAKER}"


def test_replan_of_the_scenario_fixture():
    err = assert_one_error_line(run(["replan", "hand_events.json"], cwd=FIXTURES / "scenarios"), 2)
    assert err == f"hand_events.json: {IS_SCENARIO}; {LIVE_TAKER}"


def test_standard_input_is_named_too():
    doc, _ = documents()["scenario"]
    err = assert_one_error_line(run(["replan", "-"], stdin=json.dumps(doc).encode()), 2)
    assert err.endswith(f": {IS_SCENARIO}; {LIVE_TAKER}") and "\n" not in err

