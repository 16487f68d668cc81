"""bench's result cache (--cache): a hit returns the stored plan and its measurement;
a changed mission, setting or solver code misses; ref and peer limits are repeatable."""
import argparse
import dataclasses
import json

import pytest
from conftest import sva_tools

from sva_tools import bench, cache, gen, ref


def opts(store, **kw):
    o = argparse.Namespace(ref_det_limit=2.0, ref_time_limit=600.0, peer_solution_limit=30,
                           peer_time_limit=300.0, cache_store=store)
    for k, v in kw.items():
        setattr(o, k, v)
    return o


def plan_json(r):
    return json.dumps(r["plan"].to_json(), sort_keys=True)


@pytest.mark.parametrize("algo", ["ih", "ref", "peer"])
def test_hit_returns_the_same_plan(tmp_path, algo):
    m = gen.generate(6, 3, seed=11)
    store = cache.Cache(str(tmp_path / "c"))
    a = bench._solve(algo, m, "unused.json", opts(store))
    assert a["cached"] is False and store.misses == 1 and store.hits == 0
    files = list((tmp_path / "c" / algo).glob("*.json"))
    assert len(files) == 1
    b = bench._solve(algo, m, "unused.json", opts(store))
    assert b["cached"] is True and store.hits == 1
    assert plan_json(a) == plan_json(b) and a["us"] == b["us"]  # the solve time measured then
    assert b["measured"] == a["measured"] and len(b["measured"]["loadavg"]) == 3
    # A fresh Cache object on the same directory (a later run) hits too.
    c = bench._solve(algo, m, "unused.json", opts(cache.Cache(str(tmp_path / "c"))))
    assert c["cached"] is True and plan_json(c) == plan_json(a)


def test_changed_mission_misses(tmp_path):
    m = gen.generate(6, 3, seed=11)
    store = cache.Cache(str(tmp_path))
    bench._solve("ih", m, "unused.json", opts(store))
    t0 = m.targets[0]
    moved = dataclasses.replace(m, targets=[dataclasses.replace(t0, x=t0.x + 1)] + m.targets[1:])
    renamed = dataclasses.replace(m, name=m.name + "_b")
    for other in (moved, renamed):
        r = bench._solve("ih", other, "unused.json", opts(store))
        assert r["cached"] is False
    assert store.hits == 0 and store.misses == 3
    assert bench._solve("ih", m, "unused.json", opts(store))["cached"] is True


def test_changed_setting_misses(tmp_path):
    m = gen.generate(6, 3, seed=12)
    store = cache.Cache(str(tmp_path))
    bench._solve("ref", m, "unused.json", opts(store))
    bench._solve("peer", m, "unused.json", opts(store))
    assert bench._solve("ref", m, "unused.json", opts(store, ref_det_limit=3.0))["cached"] is False
    assert bench._solve("ref", m, "unused.json", opts(store, ref_time_limit=60.0))["cached"] is False
    assert bench._solve("peer", m, "unused.json", opts(store, peer_solution_limit=31))["cached"] is False
    assert store.hits == 0
    assert bench._solve("ref", m, "unused.json", opts(store))["cached"] is True
    assert bench._solve("peer", m, "unused.json", opts(store))["cached"] is True


def test_changed_code_or_version_misses(tmp_path, monkeypatch):
    m = gen.generate(5, 3, seed=13)
    store = cache.Cache(str(tmp_path))
    bench._solve("ih", m, "unused.json", opts(store))
    monkeypatch.setitem(cache._code, "ih", "0" * 64)  # as if ih.py had been edited
    assert bench._solve("ih", m, "unused.json", opts(store))["cached"] is False
    monkeypatch.setattr(cache, "__version__", "9.9.9")
    assert bench._solve("ih", m, "unused.json", opts(store))["cached"] is False
    assert store.hits == 0


def test_damaged_or_foreign_entry_misses(tmp_path):
    m = gen.generate(5, 3, seed=14)
    store = cache.Cache(str(tmp_path))
    bench._solve("ih", m, "unused.json", opts(store))
    (path,) = (tmp_path / "ih").glob("*.json")
    doc = json.loads(path.read_text())
    doc["key"]["settings"] = {"other": 1}  # an entry stored for other key fields
    path.write_text(json.dumps(doc))
    assert bench._solve("ih", m, "unused.json", opts(store))["cached"] is False
    path.write_text(path.read_text()[:50])  # torn file
    assert store.get(m, "ih", {}) is None
    assert bench._solve("ih", m, "unused.json", opts(store))["cached"] is False
    assert bench._solve("ih", m, "unused.json", opts(store))["cached"] is True


def test_c_planners_are_not_cached(tmp_path):
    with pytest.raises(ValueError):
        cache.key_fields(gen.generate(3, 2, seed=1), "sva", {})


def test_ref_deterministic_limit_repeats():
    """One worker and a deterministic limit: the same plan and bound however loaded the
    machine is (the limit is hit here, so a wall-clock limit would differ run to run)."""
    m = gen.generate(25, 5, seed=2024, index=5, **bench.GEN)
    a = ref.solve_ref(m, det_limit=0.6)
    b = ref.solve_ref(m, det_limit=0.6)
    assert a.stats["stopped_by"] == "det_limit" and not a.stats["optimal"]
    assert json.dumps(a.to_json()["routes"]) == json.dumps(b.to_json()["routes"])
    for k in ("lower_bound", "covered_upper_bound", "deterministic_time", "feasible"):
        assert a.stats[k] == b.stats[k], k


def test_bench_rerun_uses_the_cache(sva_bin, tmp_path):
    """Second run: ih rows come from the cache, marked, with the same figures and times;
    sva runs again; the report says what was reused."""
    args = ["bench", "--missions", 1, "--algos", "sva,ih", "--cache", tmp_path / "c",
            "--log", tmp_path / "log.txt"]
    r1 = sva_tools(*args, "--out", tmp_path / "a")
    assert r1.returncode == 0, r1.stderr[-2000:]
    r2 = sva_tools(*args, "--out", tmp_path / "b")
    assert r2.returncode == 0, r2.stderr[-2000:]
    a = (tmp_path / "a" / "README.md").read_text()
    b = (tmp_path / "b" / "README.md").read_text()
    assert "8 results reused, 0 computed" in b and "0 results reused, 8 computed" in a

    def rows(md, algo):
        return [line.split("|")[1:-1] for line in md.splitlines()
                if line.startswith("| ") and line.split("|")[2].strip().startswith(algo)]
    ia, ib = rows(a, "ih"), rows(b, "ih")
    assert len(ia) == len(ib) == 8
    for x, y in zip(ia, ib):
        assert x[1].strip() == "ih" and y[1].strip() == "ih (cached)"
        assert x[2:] == y[2:]  # same figures, and the solve times measured in run a
    assert all(row[1].strip() == "sva" for row in rows(b, "sva"))
    assert "| ih | 0 | 8, " in b and "| sva | 8 (" in b
    assert len((tmp_path / "log.txt").read_text().splitlines()) == 16
