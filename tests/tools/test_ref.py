"""`ref` equals a brute force on tiny missions; the fuel-free bound is a true bound."""
import random

import pytest
from bruteforce import optimum
from conftest import mission

from sva_tools import check, ref


def tiny(seed):
    rng = random.Random(seed)
    nu, nt = rng.randint(1, 3), rng.randint(1, 3)
    uavs = []
    for i in range(nu):
        x, y = (0, 0) if rng.random() < 0.6 else (rng.randint(-4, 6), rng.randint(-4, 6))
        uavs.append((i + 1, x, y, rng.randint(4, 40), rng.choice([0, 0, 3, 8])))
    targets = []
    for i in range(nt):
        s = rng.randint(3, 30)
        targets.append((i + 1, rng.randint(-6, 6), rng.randint(-6, 6), s, s + rng.randint(1, 12),
                        rng.randint(1, 2)))
    return mission(uavs, targets, name=f"tiny{seed}", tpc=rng.choice([1, 1, 2]),
                   hover=rng.choice([0, 0, 2]))


@pytest.mark.parametrize("seed", range(40))
def test_ref_equals_brute_force(seed):
    m = tiny(seed)
    p = ref.solve_ref(m, time_limit=20)
    assert p.stats["optimal"] and p.stats["feasible"]
    assert check.check_plan(m, p) == []
    assert (p.covered, p.cost) == optimum(m), f"seed {seed}"
    assert p.stats["lower_bound"] == p.cost
    b = ref.fuel_free_bound(m)
    if p.status == "complete":
        assert b["complete_possible"] and b["lower_bound"] <= p.cost
    if not b["complete_possible"]:
        assert p.status == "partial"


def test_stranded_uav_in_ref():
    m = mission([(1, 0, 0, 50), (2, 9, 9, 10)], [(1, 3, 0, 10, 20, 1)])
    p = ref.solve_ref(m)
    assert p.stranded == [2] and p.covered == 1 and check.check_plan(m, p) == []


def test_bound_beats_nothing_it_should_not():
    # Fuel-free: the bound finds a complete plan that fuel forbids.
    m = mission([(1, 0, 0, 5)], [(1, 5, 0, 10, 20, 1)])
    b = ref.fuel_free_bound(m)
    assert b == {"complete_possible": True, "lower_bound": 10, "solve_us": b["solve_us"]}
    assert ref.solve_ref(m).covered == 0
