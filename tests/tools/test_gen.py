"""The generator: deterministic, honours its parameters, hits intersection categories."""
import json

import pytest
from conftest import sva_tools

from sva_tools import gen, io, model


def test_deterministic(tmp_path):
    a = sva_tools("gen", "--targets", 7, "--uavs", 4, "--seed", 11)
    b = sva_tools("gen", "--targets", 7, "--uavs", 4, "--seed", 11)
    c = sva_tools("gen", "--targets", 7, "--uavs", 4, "--seed", 12)
    assert a.returncode == 0 and a.stdout == b.stdout and a.stdout != c.stdout
    io.mission_from_json(json.loads(a.stdout))


def test_parameters_honoured():
    m = gen.generate(12, 6, width=(15, 25), max_coord=30, need=(1, 3), fuel=77, hover=2,
                     ticks_per_cell=2, seed=3)
    assert len(m.targets) == 12 and len(m.uavs) == 6
    assert all(u.fuel == 77 and (u.x, u.y) == m.depot for u in m.uavs)
    assert all(0 <= t.x <= 30 and 0 <= t.y <= 30 and 15 <= t.end - t.start <= 25
               and 1 <= t.need <= 3 for t in m.targets)
    assert m.hover_fuel == 2 and m.ticks_per_cell == 2
    # every target is reachable from the depot by its start
    assert all(model.dist_pt(m.depot, t) * 2 <= t.start for t in m.targets)


@pytest.mark.parametrize("ratio", ["low", "mid", "high"])
def test_categories(ratio):
    lo, hi = gen.RATIOS[ratio]
    for i in range(15):
        m = gen.generate(10, 5, ratio=ratio, seed=5, index=i)
        r = model.intersection_ratio(m)
        assert lo <= r <= hi and (r < hi or ratio == "high"), (ratio, r)


def test_count_writes_directory(tmp_path):
    r = sva_tools("gen", "--count", 3, "--targets", 3, "--uavs", 2, "--name", "x", "-o", tmp_path / "d")
    assert r.returncode == 0, r.stderr
    files = sorted(p.name for p in (tmp_path / "d").iterdir())
    assert files == ["x_0000.json", "x_0001.json", "x_0002.json"]


def test_lcm_dispatch(monkeypatch):
    import sys
    import types
    from sva_tools import commands
    fake = types.ModuleType("sva_tools.commands.lcm")
    seen = []
    fake.main = lambda argv: seen.append(argv) or 7
    monkeypatch.setitem(sys.modules, "sva_tools.commands.lcm", fake)
    assert commands.main(["lcm", "serve", "--x"]) == 7 and seen == [["serve", "--x"]]
    monkeypatch.setitem(sys.modules, "sva_tools.commands.lcm", None)  # import fails
    assert commands.main(["lcm"]) == 2
