"""IH: the integer LP per transportation problem. Its optimum equals enumeration on
random small problems, IH plans pass the checker, and on every problem the C `sva`
traced, the integer LP optimum equals the tableau's cost_total."""
import itertools
import random

import pytest

from sva_tools import cbin, check, gen, ih, solvers


def enumerate_tp(supply, demand, cost):
    """(max covered, min cost) by enumerating every flow (tiny problems only)."""
    ns, nk = len(supply), len(demand)
    arcs = [(i, j) for i in range(ns) for j in range(nk) if cost[i][j] is not None]
    best = None
    for f in itertools.product(*[range(min(supply[i], demand[j]) + 1) for i, j in arcs]):
        out = [0] * ns
        inn = [0] * nk
        c = 0
        for (i, j), x in zip(arcs, f):
            out[i] += x
            inn[j] += x
            c += cost[i][j] * x
        if any(o > s for o, s in zip(out, supply)) or any(0 < a != d for a, d in zip(inn, demand)):
            continue
        key = (-sum(1 for a, d in zip(inn, demand) if a == d), c)
        best = key if best is None or key < best else best
    return -best[0], best[1]


@pytest.mark.parametrize("seed", range(30))
def test_ilp_equals_enumeration(seed):
    rng = random.Random(seed)
    ns, nk = rng.randint(1, 3), rng.randint(1, 3)
    supply = [rng.randint(1, 3) for _ in range(ns)]
    demand = [rng.randint(1, 2) for _ in range(nk)]
    cost = [[rng.randint(0, 20) if rng.random() < 0.8 else None for _ in range(nk)] for _ in range(ns)]
    sol = solvers.solve_max_cover(supply, demand, cost)
    assert (sol.covered, sol.cost) == enumerate_tp(supply, demand, cost)
    # the exact-demand model on the sinks max-cover kept has the same optimum
    keep = [j for j in range(nk) if sol.kept[j]]
    ex = solvers.solve_exact(supply, [demand[j] for j in keep], [[r[j] for j in keep] for r in cost])
    assert ex is not None and ex.cost == sol.cost


@pytest.mark.parametrize("ratio", ["any", "low", "mid", "high"])
def test_ih_plans_pass_checker(ratio):
    for i in range(4):
        m = gen.generate(10, 5, ratio=ratio, seed=21, index=i, hover=1)
        p = ih.plan_ih(m)
        assert check.check_plan(m, p) == [], m.name
        assert p.covered >= 1


def test_verify_record_catches_a_wrong_cost():
    rec = {"supply": [2, 1], "demand": [2, 1], "dropped": [False, False],
           "cost": [[3, 5], [4, None]], "flow": [[1, 1], [1, 0]], "cost_total": 12,
           "covered": 2, "sink_targets": [1, 2]}
    v = ih.TraceVerdict()
    ih.verify_record(rec, v)
    assert v.mismatches == [] and v.problems == 1
    rec["cost_total"] = 13
    v = ih.TraceVerdict()
    ih.verify_record(rec, v)
    assert v.mismatches, "a non-optimal tableau cost must be reported"


def test_traced_problems_equal_ilp(sva_bin):
    """Every transportation problem `sva plan --trace` wrote: ILP optimum == cost_total."""
    v = ih.TraceVerdict()
    for ratio, n, u in [("any", 10, 5), ("high", 10, 5), ("mid", 10, 5), ("low", 10, 5),
                        ("any", 25, 5), ("any", 7, 5), ("high", 30, 12)]:
        for i in range(6):
            m = gen.generate(n, u, ratio=ratio, seed=31, index=i, need=(1, 3), hover=i % 2)
            r = cbin.plan_mission(m, "sva", trace=True)
            assert r.status == 0, r.stderr
            assert check.check_plan(m, r.plan) == []
            for rec in r.trace:
                ih.verify_record(rec, v, f"{m.name}: ")
    assert v.problems > 50, "sva traced too few transportation problems"
    assert v.mismatches == []
    print(f"traced problems {v.problems}, with drops {v.with_drops}, "
          f"max-cover keeps more: {v.drop_worse}")


def test_ih_compare_cli(sva_bin, tmp_path):
    from conftest import sva_tools
    from sva_tools import io
    for i in range(3):
        io.write_json(gen.generate(10, 5, seed=41, index=i).to_json(), str(tmp_path / f"m{i}.json"))
    r = sva_tools("ih", "--compare", tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "missions: 3;" in r.stdout and "integer LP optimum == tableau cost_total" in r.stdout
