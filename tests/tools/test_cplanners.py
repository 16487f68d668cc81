"""The C planners' plans on generated missions pass the independent checker; bfa is
the optimum (equals ref) on small missions."""
import pytest

from sva_tools import cbin, check, gen, ref
from test_ref import tiny


@pytest.mark.parametrize("algo", ["sva", "ga", "hga"])
def test_c_plans_pass_checker(sva_bin, algo):
    n = 0
    for ratio, t, u in [("any", 3, 3), ("any", 10, 5), ("low", 10, 5), ("high", 10, 5),
                        ("any", 25, 5), ("any", 60, 16)]:
        for i in range(3):
            m = gen.generate(t, u, ratio=ratio, seed=51, index=i, need=(1, 3), hover=i)
            r = cbin.plan_mission(m, algo)
            assert r.status == 0, f"{m.name}: {r.stderr}"
            assert r.plan.algorithm == algo
            assert check.check_plan(m, r.plan) == [], m.name
            n += 1
    assert n == 18


@pytest.mark.parametrize("seed", range(12))
def test_bfa_is_optimal(sva_bin, seed):
    m = tiny(seed)
    r = cbin.plan_mission(m, "bfa")
    assert r.status == 0, r.stderr
    assert check.check_plan(m, r.plan) == []
    o = ref.solve_ref(m)
    assert (r.plan.covered, r.plan.cost) == (o.covered, o.cost)


def test_c_stranded_and_ready_at(sva_bin):
    from conftest import mission
    m = mission([(1, 0, 0, 60), (2, 30, 30, 10), (3, 2, 0, 40, 15)],
                [(1, 5, 0, 10, 20, 1), (2, 4, 4, 30, 45, 2)], hover=1)
    for algo in ("sva", "ga", "hga", "bfa"):
        r = cbin.plan_mission(m, algo)
        assert r.status == 0, r.stderr
        assert check.check_plan(m, r.plan) == [], algo
        assert r.plan.stranded == [2]


def test_bfa_over_limit_is_an_error(sva_bin):
    m = gen.generate(13, 3, seed=1)
    r = cbin.plan_mission(m, "bfa")
    assert r.status == 1 and r.plan is None and "sva: error:" in r.stderr
