"""The route master's LP bound (sva_tools.route_lp): on small missions solved exactly it
never exceeds the optimum's cost, is never below the fuel-free bound where a complete
plan exists, and meets the optimum on most; where fuel splits a route it sees what the
fuel-free bound does not; its column generation ends with no route left to price. The
bench built on it (tools/bench/route_lp_bound.py --quick) runs and finds no bound above
a checked plan."""
import os
import random
import subprocess
import sys

import pytest
from conftest import mission

from sva_tools import check, ref, route_lp

SEEDS = range(60)


def small(seed):
    """4 to 6 targets, 2 or 3 UAVs, need 1 or 2, windows spread out, fuel often binding."""
    rng = random.Random(seed)
    uavs = []
    for i in range(rng.randint(2, 3)):
        x, y = (0, 0) if rng.random() < 0.6 else (rng.randint(-4, 6), rng.randint(-4, 6))
        uavs.append((i + 1, x, y, rng.randint(16, 60), rng.choice([0, 0, 3])))
    targets = []
    for i in range(rng.randint(4, 6)):
        s = rng.randint(8, 80)
        targets.append((i + 1, rng.randint(-6, 6), rng.randint(-6, 6), s, s + rng.randint(1, 8),
                        rng.choice([1, 1, 1, 2])))
    return mission(uavs, targets, name=f"small{seed}", hover=rng.choice([0, 2]))


def bounds(seed):
    m = small(seed)
    best = ref.solve_ref(m, time_limit=60)
    assert best.stats["optimal"] and check.check_plan(m, best) == [], f"seed {seed}"
    lp = route_lp.route_lp_bound(m, best.covered)  # from the empty routes: every column priced
    free = ref.fuel_free_bound(m) if best.status == "complete" else None
    return best, lp, free


@pytest.mark.parametrize("seed", SEEDS)
def test_bound_lies_between_the_fuel_free_bound_and_the_optimum(seed):
    best, lp, free = bounds(seed)
    assert lp.converged and lp.bound is not None
    assert lp.bound <= best.cost, f"seed {seed}: bound {lp.bound} above the optimum {best.cost}"
    if free is not None:
        assert free["lower_bound"] <= lp.bound, f"seed {seed}: below the fuel-free bound {free}"
    assert all(v <= lp.bound + 1e-6 for v in lp.history), "every Lagrangian value is a bound"


def test_bound_meets_the_optimum_on_most():
    exact = sum(bounds(seed)[1].bound == bounds(seed)[0].cost for seed in SEEDS)
    print(f"{len(SEEDS)} missions: the bound is the optimum's cost on {exact}")
    assert exact > len(SEEDS) // 2


def test_bound_knows_the_fuel():
    # Two targets 10 and 16 cells out, 6 apart, 4 fuel to hover at each: one UAV serves
    # both on 32 cells and 40 fuel, each alone takes 24 and 36. With fuel 38 each needs
    # its own UAV (20 + 32 cells), which the fuel-free bound does not see.
    m = mission([(1, 0, 0, 38), (2, 0, 0, 38)], [(1, 10, 0, 20, 22, 1), (2, 10, 6, 50, 52, 1)], hover=4)
    best = ref.solve_ref(m, time_limit=60)
    lp = route_lp.route_lp_bound(m, 2)
    assert (best.covered, best.cost) == (2, 52)
    assert ref.fuel_free_bound(m)["lower_bound"] == 32
    assert lp.converged and lp.bound == 52


def test_bench_quick_run_finds_no_bound_above_a_plan():
    # tools/bench/route_lp_bound.py on 2 missions of 25 x 5: exit 1 would mean an LP
    # bound above a checked plan's cost at the same coverage.
    bench = os.path.join(os.path.dirname(__file__), "..", "..", "tools", "bench", "route_lp_bound.py")
    out = subprocess.run([sys.executable, bench, "--quick"], capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stdout + out.stderr
    assert "| 025x05_tight | 2 | 2 |" in out.stdout, out.stdout
