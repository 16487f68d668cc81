"""Every golden plan in fixtures/golden passes the independent checker."""
import json
from pathlib import Path

import pytest
from conftest import REPO

from sva_tools import check, io

GOLDEN = REPO / "fixtures" / "golden"
MISSIONS = REPO / "fixtures" / "missions"


def golden_plans():
    return sorted(GOLDEN.rglob("*.json")) if GOLDEN.is_dir() else []


def find_mission(name):
    for p in MISSIONS.rglob("*.json") if MISSIONS.is_dir() else []:
        try:
            if json.loads(p.read_text()).get("name") == name:
                return p
        except (ValueError, AttributeError):
            continue
    return None


@pytest.mark.skipif(not golden_plans(), reason="no fixtures/golden in this checkout")
@pytest.mark.parametrize("plan_path", golden_plans(), ids=lambda p: str(p.relative_to(GOLDEN)))
def test_golden_plan_passes_checker(plan_path):
    p = io.load_plan(str(plan_path))
    mp = find_mission(p.mission)
    assert mp is not None, f"no mission named {p.mission!r} under fixtures/missions"
    m = io.load_mission(str(mp))
    assert check.check_plan(m, p) == []
