"""`sva replan LIVE.json` (docs/cli.md, docs/SPEC.md live missions): a live mission
replayed as the on-board node flies it, the last replan printed with its changes.

Each printed plan is checked here against its residual mission (written with
--residual) by the same independent checks as `sva plan`'s plans (test_cli.check_plan).
"""
import json
import os
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
from sva_tools import schema  # noqa: E402  (the schemas of docs/schema)

from test_cli import ALGORITHMS, FIXTURES, assert_one_error_line, check_plan, limits, run

pytestmark = pytest.mark.sanitize  # cheap: also run against the ASan/UBSan build

# Two UAVs at the depot; target 1 needs both at (5, 0) in [10, 20]; targets 2 (5, 5)
# and 3 (1, 6) in [30, 40] need one each.
MISSION = {
    "name": "hand_live",
    "depot": {"x": 0, "y": 0},
    "uavs": [{"id": 1, "x": 0, "y": 0, "fuel": 100}, {"id": 2, "x": 0, "y": 0, "fuel": 100}],
    "targets": [{"id": 1, "x": 5, "y": 0, "start": 10, "end": 20, "need": 2},
                {"id": 2, "x": 5, "y": 5, "start": 30, "end": 40, "need": 1},
                {"id": 3, "x": 1, "y": 6, "start": 30, "end": 40, "need": 1}],
}
# UAV 1: targets 1 then 2; UAV 2: targets 1 then 3.
PLAN = {"routes": [{"uav": 1, "targets": [1, 2]}, {"uav": 2, "targets": [1, 3]}]}


def replan(tmp_path, doc, *options):
    live = tmp_path / "live.json"
    residual = tmp_path / "residual.json"
    live.write_text(json.dumps(doc))
    result = run(["replan", *options, "--residual", str(residual), str(live)])
    assert result.returncode == 0, result.stderr
    plan = json.loads(result.stdout)
    mission = json.loads(residual.read_text())
    check_plan(mission, {k: v for k, v in plan.items() if k not in ("changes", "live")}, plan["algorithm"])
    assert schema.errors(plan, "plan") == [] and schema.errors(mission, "mission") == []
    return mission, plan


def states(plan):
    return {t["id"]: t["state"] for t in plan["live"]["targets"]}


@pytest.mark.parametrize("algo", ALGORITHMS)
def test_lost_uav_mid_visit(tmp_path, algo):
    doc = {"mission": MISSION, "plan": PLAN, "events": [{"at": 15, "type": "uav_lost", "uav": 1}]}
    mission, plan = replan(tmp_path, doc, "--algo", algo)
    # Target 1 was under way with UAV 1: lost; UAV 2 is free at once, at (5, 0).
    assert states(plan)[1] == "lost"
    assert [u["id"] for u in mission["uavs"]] == [2]
    assert (mission["uavs"][0]["x"], mission["uavs"][0]["ready_at"]) == (5, 15)
    assert sorted(t["id"] for t in mission["targets"]) == [2, 3]
    assert plan["covered"] == 1 and plan["live"]["covered"] == 1 and plan["live"]["now"] == 15
    # Change penalty 0: target 2 (5 + 10 cells) beats keeping target 3 (10 + 7).
    assert plan["cost"] == 15 and not plan["live"]["kept"]
    assert plan["changes"] == {"dropped": [[2, 3]], "added": [[2, 2]], "count": 2, "penalty": 0}


def test_change_penalty_keeps_the_standing_visit(tmp_path):
    doc = {"mission": {**MISSION, "change_penalty": 10}, "plan": PLAN,
           "events": [{"at": 15, "type": "uav_lost", "uav": 1}]}
    mission, plan = replan(tmp_path, doc, "--algo", "flow")
    assert mission["change_penalty"] == 10
    assert plan["live"]["kept"] and plan["cost"] == 17
    assert plan["routes"] == [{"uav": 2, "targets": [3], "distance": 17, "fuel_used": 17}]
    assert plan["changes"]["count"] == 0


def test_every_event_type(tmp_path):
    doc = {"mission": MISSION, "plan": PLAN, "events": [
        {"at": 2, "type": "uav_lost", "uav": 2},
        {"at": 3, "type": "uav_back", "uav": 2, "x": 4, "y": 0, "fuel": 60},
        {"at": 4, "type": "fuel", "uav": 1, "fuel": 90},
        {"at": 5, "type": "target_added", "target": {"id": 9, "x": 2, "y": 2, "start": 50, "end": 60, "need": 1}},
        {"at": 6, "type": "target_changed", "target": {"id": 3, "x": 2, "y": 7, "start": 33, "end": 40, "need": 1}},
        {"at": 7, "type": "target_cancelled", "target": 2},
        {"at": 8, "type": "clock"},
        {"at": 9, "type": "position", "uav": 1, "x": 4, "y": 0, "fuel": 80}]}
    mission, plan = replan(tmp_path, doc, "--algo", "flow")
    assert plan["live"]["revision"] == 8 and plan["live"]["now"] == 9
    assert (mission["uavs"][0]["x"], mission["uavs"][0]["y"], mission["uavs"][0]["fuel"]) == (4, 0, 80)
    assert states(plan) == {1: "waiting", 2: "cancelled", 3: "waiting", 9: "waiting"}
    assert sorted(t["id"] for t in mission["targets"]) == [1, 3, 9]
    assert next(t for t in mission["targets"] if t["id"] == 3)["x"] == 2
    assert plan["covered"] == 3


def test_now_moves_the_clock_and_visits_get_under_way(tmp_path):
    mission, plan = replan(tmp_path, {"mission": MISSION, "plan": PLAN, "now": 12}, "--algo", "sva")
    assert plan["live"]["under_way"] == [1] and plan["live"]["covered"] == 3
    assert all((u["x"], u["ready_at"]) == (5, 20) for u in mission["uavs"])
    assert plan["live"]["kept"] and plan["changes"]["count"] == 0


def test_without_a_plan_the_mission_is_planned_first(tmp_path):
    _, plan = replan(tmp_path, {"mission": MISSION}, "--algo", "flow")
    assert plan["covered"] == 3 and plan["live"]["now"] == 0 and plan["live"]["kept"]


@pytest.mark.parametrize("events, message", [
    ([{"at": 15, "type": "uav_lost", "uav": 9}], "events[0]: event.uav: unknown id 9"),
    ([{"at": 15, "type": "clock"}, {"at": 11, "type": "clock"}], "events[1]: event.at: 11 is before now (15)"),
    ([{"at": 31, "type": "target_changed",
       "target": {"id": 2, "x": 1, "y": 1, "start": 50, "end": 60, "need": 1}}],
     "events[0]: event.target: its window started at 30 (now 31): only a target not yet started may change"),
    ([{"at": 5, "type": "target_added", "target": {"id": 3, "x": 1, "y": 1, "start": 50, "end": 60, "need": 1}}],
     "events[0]: event.target: duplicate id 3 (first at index 2)"),
    ([{"at": 5, "type": "uav_back", "uav": 1, "x": 0, "y": 0, "fuel": 5}],
     "events[0]: event.uav: the UAV is in service"),
    ([{"at": 5, "type": "teleport", "uav": 1}],
     "events[0].type: must be one of clock, uav_lost, uav_back, fuel, target_added, target_cancelled, "
     "target_changed, position"),
    ([{"at": 5, "type": "uav_lost", "uav": 1, "x": 3}], 'events[0]: unknown key "x"'),
    ([{"at": 5, "type": "position", "uav": 1, "x": 3, "fuel": 9}], 'events[0]: missing key "y"'),
    ([{"at": 2, "type": "uav_lost", "uav": 2}, {"at": 3, "type": "position", "uav": 2, "x": 1, "y": 0, "fuel": 9}],
     "events[1]: event.uav: the UAV is lost"),
    ([{"at": 12, "type": "clock"}, {"at": 14, "type": "position", "uav": 1, "x": 5, "y": 0, "fuel": -3}],
     "events[1]: event.fuel: must be >= 0, got -3"),
    ([{"at": 5, "type": "fuel", "uav": 1}], 'events[0]: missing key "fuel"'),
])
def test_rejected_events(tmp_path, events, message):
    live = tmp_path / "live.json"
    live.write_text(json.dumps({"mission": MISSION, "plan": PLAN, "events": events}))
    assert assert_one_error_line(run(["replan", str(live)]), 2) == message


@pytest.mark.parametrize("doc, message", [
    ({"mission": MISSION, "colour": 1}, 'live mission: unknown key "colour"'),
    ({"plan": PLAN}, 'live mission: missing key "mission"'),
    ({"mission": {**MISSION, "change_penalty": -1}}, "mission.change_penalty: must be >= 0, got -1"),
    ({"mission": MISSION, "plan": {"routes": [{"uav": 1, "targets": [7]}]}},
     "plan.routes[0].targets[0]: not a target id of the mission, got 7"),
    ({"mission": MISSION, "plan": {"routes": [{"uav": 2, "targets": []}, {"uav": 1, "targets": []}]}},
     "plan.routes[0].uav: must follow the mission's UAVs (1), got 2"),
    ({"mission": MISSION, "plan": PLAN, "events": {"at": 1}}, "events: must be an array, got object"),
    ({"mission": MISSION, "events": [{"at": "5", "type": "clock"}]},
     "events[0].at: must be an integer, got string"),
    ({"mission": MISSION, "events": [{"at": 2 ** 31, "type": "clock"}]},
     "events[0].at: must be an integer in [-2147483648, 2147483647], got 2147483648"),
    ({"mission": MISSION, "events": [{"at": 15, "type": "clock"}], "now": 10},
     "now: 10 is before the last event (15)"),
])
def test_rejected_documents(tmp_path, doc, message):
    live = tmp_path / "live.json"
    live.write_text(json.dumps(doc))
    assert assert_one_error_line(run(["replan", str(live)]), 2) == message


def test_usage(tmp_path):
    assert assert_one_error_line(run(["replan"]), 2) == "replan: missing LIVE.json (or - for standard input)"
    assert assert_one_error_line(run(["replan", "--residual="]), 2) == "replan: --residual needs a file name"
    assert "sva replan" in run(["--help"]).stdout.decode()


def test_the_spec_example(tmp_path):
    """docs/SPEC.md section 12.5's LIVE.json replays: UAV 1 lost mid-visit at 15, now 20."""
    import re
    spec = (Path(__file__).resolve().parents[2] / "docs" / "SPEC.md").read_text()
    doc = json.loads(re.findall(r"```json\n(.*?)```", spec, re.S)[3])
    mission, plan = replan(tmp_path, doc, "--algo", "flow")
    assert plan["live"]["now"] == 20 and plan["live"]["revision"] == 2
    assert states(plan) == {1: "lost", 2: "waiting"} and plan["covered"] == 1


def test_flow_work_is_the_budget_of_every_replan(tmp_path):
    """A replan with a plan in force searches within SVA_FLOW_REPLAN_WORK (60,000 units;
    the seeds come on top), far below the full search; --flow-work N is the search budget
    of every replan, smaller or up to the full search. On a mission where the full search
    runs to its budget (need 2, 25 x 5)."""
    live = Path(os.environ["SVA_FIXTURES"]) / "scenarios" / "replan_budget.json"

    def work(*options):
        result = run(["replan", "--algo", "flow", *options, str(live)])
        assert result.returncode == 0, result.stderr
        return json.loads(result.stdout)["stats"]["flow_work"]

    default, small, full = work(), work("--flow-work", "2000"), work("--flow-work", "2000000")
    print(f"flow_work of the last replan: default {default}, --flow-work 2000 {small}, "
          f"--flow-work 2000000 {full}")
    assert small < default < full
    assert default < 100000 and full > 1000000


# --- the plan in force against SPEC section 1 -------------------------------------

LIVE_INVALID = FIXTURES / "invalid" / "live"


@pytest.mark.parametrize("name", sorted(p.stem for p in LIVE_INVALID.glob("*.json")))
def test_a_plan_in_force_that_breaks_the_rules_is_refused(name):
    """fixtures/invalid/live: each LIVE.json's plan in force breaks one rule (SPEC
    section 1: a target half or over covered, a visit reached after its start, a route
    beyond its UAV's fuel; or the plan's layout or shape): exit 2, its message, nothing
    on stdout."""
    expected = (LIVE_INVALID / f"{name}.err").read_text().rstrip("\n")
    result = run(["replan", f"{name}.json"], cwd=LIVE_INVALID)
    assert assert_one_error_line(result, 2) == expected
    assert expected.startswith("plan")


def test_every_invalid_live_document_has_its_message():
    jsons = sorted(p.stem for p in LIVE_INVALID.glob("*.json"))
    assert jsons == sorted(p.stem for p in LIVE_INVALID.glob("*.err"))
    assert len(jsons) >= 15


# At every limit of SPEC section 1: UAV 1 reaches target 1 exactly at its start (ready
# at 5, 5 cells) and target 2 exactly at its start (20 + 5); UAV 2 reaches target 1 at 5;
# each route uses exactly its fuel (hover_fuel 1); UAV 3 cannot get home (stranded) and
# has an empty route; target 1 has exactly its need, target 3 no UAV.
EDGE = {
    "name": "edge_live", "depot": {"x": 0, "y": 0}, "hover_fuel": 1,
    "uavs": [{"id": 1, "x": 0, "y": 0, "fuel": 22, "ready_at": 5},
             {"id": 2, "x": 0, "y": 0, "fuel": 11},
             {"id": 3, "x": 40, "y": 0, "fuel": 5}],
    "targets": [{"id": 1, "x": 5, "y": 0, "start": 10, "end": 20, "need": 2},
                {"id": 2, "x": 5, "y": 5, "start": 25, "end": 40, "need": 1},
                {"id": 3, "x": 1, "y": 6, "start": 30, "end": 40, "need": 1}],
}
EDGE_PLAN = {"routes": [{"uav": 1, "targets": [1, 2]}, {"uav": 2, "targets": [1]},
                        {"uav": 3, "targets": []}]}


def test_a_plan_in_force_at_every_limit_is_taken(tmp_path):
    _, plan = replan(tmp_path, {"mission": EDGE, "plan": EDGE_PLAN}, "--algo", "flow")
    assert plan["live"]["now"] == 0 and plan["covered"] >= 2


@pytest.mark.parametrize("change, message", [
    (("uavs", 0, "ready_at", 6),
     "plan.routes[0].targets[0]: uav 1 reaches target 1 at tick 11, after its start 10 (ready_at 6, 5 cells)"),
    (("targets", 1, "start", 24),
     "plan.routes[0].targets[1]: uav 1 leaves target 1 at its end 20 and reaches target 2 at tick 25, "
     "after its start 24"),
    (("uavs", 0, "fuel", 21),
     "plan.routes[0]: the route of uav 1 needs 22 fuel (return leg and hover included), more than its fuel 21"),
    (("uavs", 1, "fuel", 10),
     "plan.routes[1]: the route of uav 2 needs 11 fuel (return leg and hover included), more than its fuel 10"),
    (("targets", 0, "need", 3),
     "plan.routes: target 1 is served by 2 UAVs, must be served by exactly its need (3) or by none"),
    (("targets", 0, "need", 1),
     "plan.routes: target 1 is served by 2 UAVs, must be served by exactly its need (1) or by none"),
], ids=["late first visit", "late next visit", "fuel", "fuel, hover", "need 3", "need 1"])
def test_one_past_a_limit_is_refused(tmp_path, change, message):
    key, index, field, value = change
    mission = json.loads(json.dumps(EDGE))
    mission[key][index][field] = value
    live = tmp_path / "live.json"
    live.write_text(json.dumps({"mission": mission, "plan": EDGE_PLAN,
                                "events": [{"at": 3, "type": "clock"}]}))
    assert assert_one_error_line(run(["replan", str(live)]), 2) == message


PLANNED = ["hand_5_3", "hand_5_4", "rand_7_2", "rand_10_2", "rand_25_2"]


@pytest.mark.parametrize("algo", ALGORITHMS)
@pytest.mark.parametrize("name", PLANNED)
def test_every_plan_sva_plan_makes_is_taken_as_the_plan_in_force(tmp_path, name, algo):
    """The check refuses no plan of the planner: plans of every algorithm (stranded
    UAVs, UAVs away from the depot and busy, ticks_per_cell 2, binding fuel) replay."""
    mission = json.loads((FIXTURES / "missions" / f"{name}.json").read_text())
    if algo == "bfa" and (len(mission["targets"]) > limits()["SVA_BFA_MAX_TARGETS"] or
                          len(mission["uavs"]) > limits()["SVA_BFA_MAX_UAVS"]):
        pytest.skip("over bfa's bounds")
    made = run(["plan", "--algo", algo, str(FIXTURES / "missions" / f"{name}.json")])
    assert made.returncode == 0, made.stderr
    _, plan = replan(tmp_path, {"mission": mission, "plan": json.loads(made.stdout)}, "--algo", algo)
    assert plan["live"]["now"] == 0


def test_a_framed_plan_is_taken_as_the_plan_in_force(tmp_path):
    """`sva plan` of a mission with a frame echoes the frame: that plan document is a
    plan in force as it is (its frame, like its figures, is not read)."""
    path = FIXTURES / "geo" / "zurich.json"
    made = run(["plan", "--algo", "flow", str(path)])
    assert made.returncode == 0, made.stderr
    plan = json.loads(made.stdout)
    assert "frame" in plan
    live, residual = tmp_path / "live.json", tmp_path / "residual.json"
    live.write_text(json.dumps({"mission": json.loads(path.read_text()), "plan": plan, "now": 1}))
    result = run(["replan", "--algo", "flow", "--residual", str(residual), str(live)])
    assert result.returncode == 0, result.stderr
    replanned = json.loads(result.stdout)
    assert replanned["live"]["now"] == 1 and replanned["frame"] == plan["frame"]
    check_plan({k: v for k, v in json.loads(residual.read_text()).items() if k != "frame"},
               {k: v for k, v in replanned.items() if k not in ("changes", "live", "frame")}, "flow")
