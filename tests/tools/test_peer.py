"""`peer` (OR-tools routing) plans pass the checker and never beat the exact optimum."""
import pytest

from sva_tools import check, gen, peer, ref
from test_ref import tiny


@pytest.mark.parametrize("seed", range(8))
def test_peer_tiny(seed):
    m = tiny(seed)
    p = peer.solve_peer(m, solution_limit=30)
    assert check.check_plan(m, p) == []
    r = ref.solve_ref(m)
    assert (p.covered < r.covered) or (p.covered == r.covered and p.cost >= r.cost)


@pytest.mark.parametrize("ratio", ["any", "low", "high"])
def test_peer_generated(ratio):
    m = gen.generate(8, 4, ratio=ratio, seed=9, hover=2)
    p = peer.solve_peer(m, solution_limit=30)
    assert check.check_plan(m, p) == [] and p.stats["found"]
    assert p.covered >= 1


def test_peer_repeatable():
    m = gen.generate(7, 4, seed=4)
    a = peer.solve_peer(m, solution_limit=30)
    b = peer.solve_peer(m, solution_limit=30)
    assert [r.targets for r in a.routes] == [r.targets for r in b.routes]
