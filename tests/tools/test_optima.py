"""flow on missions whose optimum the host tools' ref (CP-SAT) proved: fixtures/optima.

Each MISSION.json has MISSION.ref.json, ref's plan with "optimal": true. flow must
cover as many targets, at the same cost, with a lower bound at or below it, and its
plan must pass the independent checker. These are missions flow once missed (a
target short, or a costlier plan): see fixtures/README.md.
"""
import json
import subprocess
from pathlib import Path

import pytest
from conftest import REPO

from sva_tools import check, io

OPTIMA = REPO / "fixtures" / "optima"


def proven_plans():
    return sorted(OPTIMA.glob("*.ref.json")) if OPTIMA.is_dir() else []


@pytest.mark.parametrize("ref_path", proven_plans(), ids=lambda p: p.name[: -len(".ref.json")])
def test_flow_reaches_the_proven_optimum(sva_bin, ref_path, tmp_path):
    mission_path = Path(str(ref_path)[: -len(".ref.json")] + ".json")
    mission = io.load_mission(str(mission_path))
    ref = json.loads(ref_path.read_text())
    assert ref["stats"]["optimal"] is True
    assert check.check_plan(mission, io.load_plan(str(ref_path))) == []

    out = subprocess.run([sva_bin, "plan", "--algo", "flow", str(mission_path)],
                         capture_output=True, text=True, check=True).stdout
    plan_path = tmp_path / "flow.json"
    plan_path.write_text(out)
    flow = json.loads(out)
    assert check.check_plan(mission, io.load_plan(str(plan_path))) == []
    assert (flow["covered"], flow["cost"]) == (ref["covered"], ref["cost"])
    assert flow["stats"]["lower_bound"] <= ref["cost"]


def test_the_fixtures_are_there():
    assert len(proven_plans()) >= 2
