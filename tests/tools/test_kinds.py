"""A file of another of our kinds (mission, plan, live mission, scenario, flight log)
given to `sva-tools sim` or `sva-tools validate`: one line naming what it is and the
command that takes it, exit 2; `plot` refuses a plan of another mission (docs/tools.md)."""
import json

import pytest

from conftest import REPO, sva_tools

FIXTURES = REPO / "fixtures"
SIM_TAKER = "sva-tools sim takes a scenario (mission, events, change_penalty; SPEC 12.5)"
VALIDATE_TAKER = "sva-tools validate takes a mission, plan, trace, bound or cache entry (SPEC 9)"
IS = {
    "mission": "this is a mission (name, depot, uavs, targets): sva plan takes it",
    "plan": "this is a plan (mission, algorithm, status, routes): sva-tools check MISSION PLAN takes it",
    "live": "this is a live mission (mission, plan, events, now): sva replan takes it",
    "scenario": "this is a scenario (mission, events, change_penalty): sva-tools sim takes it",
    "log": ("this is a flight log (scenario, uavs, targets, replans): sva-tools sim writes it, "
            "and takes its scenario"),
}


def documents():
    m = json.loads((FIXTURES / "missions" / "hand_3_1.json").read_text())
    plan = json.loads((FIXTURES / "golden" / "sva" / "hand_3_1.json").read_text())
    scenario = json.loads((FIXTURES / "scenarios" / "hand_events.json").read_text())
    return {
        "mission": m,
        "plan": plan,
        "live": {"mission": m, "plan": {"routes": plan["routes"]}, "now": 5},
        "scenario": scenario,
        "log": {"scenario": scenario, "algorithm": "sva", "end_tick": 0, "uavs": [], "targets": [],
                "replans": [], "summary": {}},
    }


def one_error(r, path):
    assert r.returncode == 2, r.stderr
    assert r.stdout == ""
    prefix = f"sva-tools: error: {path}: "
    assert r.stderr.startswith(prefix) and r.stderr.count("\n") == 1, r.stderr
    return r.stderr[len(prefix):-1]


@pytest.mark.parametrize("kind", ["mission", "plan", "live", "log"])
def test_sim_names_a_file_that_is_not_a_scenario(tmp_path, kind):
    (tmp_path / "in.json").write_text(json.dumps(documents()[kind]))
    r = sva_tools("sim", "in.json", cwd=tmp_path)
    assert one_error(r, "in.json") == f"{IS[kind]}; {SIM_TAKER}"


@pytest.mark.parametrize("kind", ["live", "scenario", "log"])
def test_validate_names_a_file_of_a_kind_it_does_not_take(tmp_path, kind):
    (tmp_path / "in.json").write_text(json.dumps(documents()[kind]))
    r = sva_tools("validate", "in.json", cwd=tmp_path)
    assert one_error(r, "in.json") == f"{IS[kind]}; {VALIDATE_TAKER}"


def test_validate_names_a_gen_events_scenario():
    r = sva_tools("validate", "gen_25t5u_events.json", cwd=FIXTURES / "scenarios")
    assert one_error(r, "gen_25t5u_events.json") == f"{IS['scenario']}; {VALIDATE_TAKER}"


def test_plot_refuses_a_plan_of_another_mission(tmp_path):
    out = tmp_path / "x.png"
    r = sva_tools("plot", "missions/hand_3_1.json", "golden/sva/hand_3_2.json", "-o", out,
                  cwd=FIXTURES)
    assert one_error(r, "golden/sva/hand_3_2.json") == (
        "not a plan of this mission (SPEC section 1): mission: plan is for 'hand_3_2', "
        "mission is 'hand_3_1'")
    assert not out.exists()


def test_plot_refuses_a_plan_with_uavs_the_mission_lacks(tmp_path):
    plan = documents()["plan"]
    plan["routes"].append({"uav": 99, "targets": [], "distance": 0, "fuel_used": 0})
    (tmp_path / "plan.json").write_text(json.dumps(plan))
    out = tmp_path / "x.png"
    r = sva_tools("plot", FIXTURES / "missions" / "hand_3_1.json", "plan.json", "-o", out, cwd=tmp_path)
    assert one_error(r, "plan.json").startswith("not a plan of this mission (SPEC section 1): ")
    assert not out.exists()
