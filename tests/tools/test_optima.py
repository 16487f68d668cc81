"""flow on missions whose optimum the host tools' ref (CP-SAT) proved: fixtures/optima.

Each MISSION.json has MISSION.ref.json, ref's plan with "optimal": true, or on a
`cover_*` mission at least with its coverage proven the most (covered ==
covered_upper_bound; ref's lower_bound is then a bound on the cost at that coverage).
flow must cover as many targets, with a lower bound at or below ref's cost and a cost
at or above ref's bound, and its plan must pass the independent checker; on
`optimum_*` missions it must also reach the optimum's cost. These are missions flow once missed (a target short, or a costlier
plan): see fixtures/README.md. On `proven_*` missions flow's Lagrangian phase proves
its plan optimal, and flow must stop there instead of spending the rest of its work
budget. On `certified_*` missions flow must prove its plan optimal within its default
budget: its lower bound reaches ref's optimum. On `short_*` missions ref found a plan
covering more targets than flow does (unproven, but checked): flow must not claim its
coverage the most there.
"""
import json
import subprocess
from pathlib import Path

import pytest
from conftest import REPO

from sva_tools import check, io

OPTIMA = REPO / "fixtures" / "optima"


def proven_plans():
    if not OPTIMA.is_dir():
        return []
    return sorted(p for p in OPTIMA.glob("*.ref.json") if not p.name.startswith("short_"))


def short_plans():
    return sorted(OPTIMA.glob("short_*.ref.json")) if OPTIMA.is_dir() else []


@pytest.mark.parametrize("ref_path", proven_plans(), ids=lambda p: p.name[: -len(".ref.json")])
def test_flow_reaches_the_proven_optimum(sva_bin, ref_path, tmp_path):
    mission_path = Path(str(ref_path)[: -len(".ref.json")] + ".json")
    mission = io.load_mission(str(mission_path))
    ref = json.loads(ref_path.read_text())
    optimal = ref["stats"]["optimal"] is True
    assert optimal or (ref_path.name.startswith("cover_")
                       and ref["covered"] == ref["stats"]["covered_upper_bound"])
    assert check.check_plan(mission, io.load_plan(str(ref_path))) == []

    out = subprocess.run([sva_bin, "plan", "--algo", "flow", str(mission_path)],
                         capture_output=True, text=True, check=True).stdout
    plan_path = tmp_path / "flow.json"
    plan_path.write_text(out)
    flow = json.loads(out)
    assert check.check_plan(mission, io.load_plan(str(plan_path))) == []
    assert flow["covered"] == ref["covered"]
    assert ref["cost"] >= flow["stats"]["lower_bound"]
    # Nothing covering as many targets costs less than ref's optimum, or its proven bound.
    assert flow["cost"] >= (ref["cost"] if optimal else ref["stats"]["lower_bound"])
    if ref_path.name.startswith(("optimum_", "proven_", "certified_")):
        assert flow["cost"] == ref["cost"]
    if ref_path.name.startswith("certified_"):
        assert flow["stats"]["lower_bound"] == ref["cost"]
        assert flow["stats"]["optimal"] is True


BUDGET = 2_000_000  # flow's default work budget (SVA_FLOW_MAX_WORK)


@pytest.mark.parametrize("ref_path", [p for p in proven_plans() if p.name.startswith("proven_")],
                         ids=lambda p: p.name[: -len(".ref.json")])
def test_flow_stops_once_its_bound_proves_the_plan(sva_bin, ref_path):
    mission_path = Path(str(ref_path)[: -len(".ref.json")] + ".json")
    out = subprocess.run([sva_bin, "plan", "--algo", "flow", "--flow-work", str(BUDGET),
                          str(mission_path)], capture_output=True, text=True, check=True).stdout
    stats = json.loads(out)["stats"]
    assert stats["optimal"] is True
    assert stats["flow_lp_columns"] > 0  # proven by the Lagrangian phase, not the first search
    assert stats["flow_work"] < BUDGET // 2


@pytest.mark.parametrize("ref_path", short_plans(), ids=lambda p: p.name[: -len(".ref.json")])
def test_flow_claims_no_coverage_a_checked_plan_beats(sva_bin, ref_path):
    mission_path = Path(str(ref_path)[: -len(".ref.json")] + ".json")
    mission = io.load_mission(str(mission_path))
    ref = json.loads(ref_path.read_text())
    assert check.check_plan(mission, io.load_plan(str(ref_path))) == []
    out = subprocess.run([sva_bin, "plan", "--algo", "flow", str(mission_path)],
                         capture_output=True, text=True, check=True).stdout
    flow = json.loads(out)
    if flow["covered"] < ref["covered"]:
        assert flow["stats"]["coverage_proven"] is False
        assert flow["stats"]["optimal"] is False


def test_the_fixtures_are_there():
    names = [p.name for p in proven_plans()]
    kinds = ("optimum_", "cover_", "proven_", "certified_")
    assert all(any(n.startswith(kind) for n in names) for kind in kinds)
    assert short_plans()
