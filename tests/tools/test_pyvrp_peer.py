"""The PyVRP peer: its model admits every optimum, its plans pass the checker and never beat
the exact reference; tools/bench/flow_vs_pyvrp.py --quick prints its table."""
import dataclasses
import subprocess
import sys

import pytest

from conftest import REPO
from sva_tools import check, gen, pyvrp_peer, ref
from test_ref import tiny


def need_one(seed):
    """tiny()'s mission (UAVs away from the depot, ready later, ticks per cell, hover fuel)
    with every target needing one UAV."""
    m = tiny(seed)
    m.targets = [dataclasses.replace(t, need=1) for t in m.targets]
    return m


@pytest.mark.parametrize("seed", range(40))
def test_model_admits_the_optimum(seed):
    """The model check (docs/results.md, "flow against PyVRP"): ref's proven optimum is
    feasible in the PyVRP model, its distance there is its fuel, and the objective is the
    plan's cost less the fleet's ways home, so a miss of the peer is a search failure, not a modelling error."""
    m = need_one(seed)
    r = ref.solve_ref(m)
    assert r.stats["optimal"]
    pm = pyvrp_peer.build_model(m)
    sol = pyvrp_peer.solution_of(pm, r)
    assert sol.is_feasible()
    assert sol.num_clients() == r.covered
    assert sol.distance() == sum(x.fuel_used for x in r.routes if x.targets)
    homes = sum(abs(u.x - m.depot[0]) + abs(u.y - m.depot[1]) for u in m.uavs if u.id not in r.stranded)
    used_homes = sum(abs(u.x - m.depot[0]) + abs(u.y - m.depot[1])
                     for u in m.uavs for x in r.routes if x.uav == u.id and x.targets)
    assert sol.fixed_vehicle_cost() == -used_homes
    flying = sum(x.distance for x in r.routes if x.targets)
    assert flying + sol.fixed_vehicle_cost() == r.cost - homes


@pytest.mark.parametrize("seed", range(12))
def test_pyvrp_never_beats_ref(seed):
    m = need_one(seed)
    p = pyvrp_peer.solve_pyvrp(m, time_limit=0.2, seed=1)
    assert check.check_plan(m, p) == [], f"seed {seed}"
    assert p.stats["feasible"]
    r = ref.solve_ref(m)
    assert r.stats["optimal"]
    assert p.covered <= r.covered
    assert p.covered < r.covered or p.cost >= r.cost


@pytest.mark.parametrize("fuel", [80, 150])
def test_pyvrp_generated(fuel):
    m = gen.generate(12, 3, width=(10, 20), need=(1, 1), fuel=fuel, hover=2, seed=5)
    p = pyvrp_peer.solve_pyvrp(m, time_limit=0.3, seed=1)
    assert check.check_plan(m, p) == []
    r = ref.solve_ref(m)
    assert p.covered <= r.covered and (p.covered < r.covered or p.cost >= r.cost)
    assert p.covered >= 1


def test_need_two_is_refused():
    m = gen.generate(5, 3, need=(2, 2), seed=1)
    with pytest.raises(ValueError, match="need-1"):
        pyvrp_peer.solve_pyvrp(m, time_limit=0.1)


def test_bench_quick():
    out = subprocess.run([sys.executable, str(REPO / "tools" / "bench" / "flow_vs_pyvrp.py"), "--quick"],
                         capture_output=True, text=True, timeout=240, cwd=str(REPO))
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    header = [i for i, line in enumerate(lines) if line.startswith("| set | flow budget | peer |")]
    assert header, out.stdout
    rows = [line for line in lines[header[0] + 2:] if line.startswith("| 025x05_tight |")]
    assert [r.split("|")[3].strip() for r in rows] == ["PyVRP", "OR-tools"], out.stdout
    assert all(r.split("|")[4].strip() == "0" for r in rows), out.stdout  # no peer failure
