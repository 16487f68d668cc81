"""The independent checker catches every kind of SPEC 1 violation (one case each)."""
import copy

import pytest
from conftest import mission, sva_tools, write

from sva_tools import check, model

# Depot (0,0). UAV 1, 2 at the depot; UAV 3 at (4,0) (not at the depot).
BASE = mission(
    uavs=[(1, 0, 0, 100), (2, 0, 0, 100), (3, 4, 0, 100)],
    targets=[(1, 5, 0, 10, 20, 2),    # needs 2
             (2, 5, 5, 30, 40, 1),    # after t1: 20 + 5 <= 30
             (3, 20, 20, 12, 18, 1)],  # left uncovered
    hover=1)


def good_plan():
    return model.make_plan(BASE, "hand", {1: [1, 2], 2: [1], 3: []})


def test_good_plan_passes():
    p = good_plan()
    assert check.check_plan(BASE, p) == []
    # The figures make_plan derived are the SPEC ones, recomputed by hand here:
    r1, r2, r3 = p.routes
    assert (r1.distance, r1.fuel_used) == (5 + 5 + 10, 20 + 2)
    assert (r2.distance, r2.fuel_used) == (10, 11)
    assert (r3.distance, r3.fuel_used) == (4, 4)   # not at the depot: flies home
    assert (p.covered, p.uncovered, p.cost, p.status) == (2, [3], 34, "partial")


def mutate(fn):
    p = copy.deepcopy(good_plan())
    fn(p)
    return check.check_plan(BASE, p)


def expect(violations, text):
    assert violations, "the checker accepted a bad plan"
    assert any(text in v for v in violations), violations


def test_first_leg_late():
    m = mission([(1, 0, 0, 100)], [(1, 9, 0, 8, 20, 1)])
    expect(check.check_plan(m, model.make_plan(m, "x", {1: [1]})), "after its start 8")


def test_ready_at_counts():
    m = mission([(1, 0, 0, 100, 6)], [(1, 5, 0, 10, 20, 1)])
    assert check.check_plan(m, model.make_plan(m, "x", {1: []})) == []
    expect(check.check_plan(m, model.make_plan(m, "x", {1: [1]})), "ready_at 6")


def test_ticks_per_cell_counts():
    m = mission([(1, 0, 0, 100)], [(1, 5, 0, 8, 20, 1)], tpc=2)
    expect(check.check_plan(m, model.make_plan(m, "x", {1: [1]})), "reaches target 1 at tick 10")


def test_leg_between_targets_late():
    m = mission([(1, 0, 0, 100)], [(1, 5, 0, 10, 20, 1), (2, 5, 9, 25, 30, 1)])
    expect(check.check_plan(m, model.make_plan(m, "x", {1: [1, 2]})), "leaves target 1")


def test_fuel_with_return_leg():
    # 5 out + 5 back = 10 > fuel 9, although the outbound leg alone fits.
    m = mission([(1, 0, 0, 9)], [(1, 5, 0, 10, 20, 1)])
    expect(check.check_plan(m, model.make_plan(m, "x", {1: [1]})), "route needs 10 fuel")


def test_fuel_with_hover():
    m = mission([(1, 0, 0, 10)], [(1, 5, 0, 10, 20, 1)], hover=1)
    expect(check.check_plan(m, model.make_plan(m, "x", {1: [1]})), "route needs 11 fuel")


def test_same_uav_twice_on_one_target():
    expect(mutate(lambda p: p.routes[0].targets.__setitem__(slice(None), [1, 1])),
           "serves target 1 2 times")


def test_more_uavs_than_need():
    m = mission([(1, 0, 0, 100), (2, 0, 0, 100)], [(1, 5, 0, 10, 20, 1)])
    expect(check.check_plan(m, model.make_plan(m, "x", {1: [1], 2: [1]})), "needs exactly 1")


def test_uav_sent_to_uncovered_target():
    m = mission([(1, 0, 0, 100)], [(1, 5, 0, 10, 20, 2)])
    expect(check.check_plan(m, model.make_plan(m, "x", {1: [1]})), "sent to a target left uncovered")


def test_covered_count():
    expect(mutate(lambda p: setattr(p, "covered", 3)), "covered: is 3, recomputed 2")


def test_uncovered_list():
    expect(mutate(lambda p: setattr(p, "uncovered", [])), "uncovered: is []")


def test_status():
    expect(mutate(lambda p: setattr(p, "status", "complete")), "status: is 'complete'")


def test_cost():
    expect(mutate(lambda p: setattr(p, "cost", 33)), "cost: is 33")


def test_distance_without_return_leg():
    expect(mutate(lambda p: setattr(p.routes[0], "distance", 10)), "distance is 10, recomputed 20")


def test_idle_uav_away_from_depot_flies_home():
    expect(mutate(lambda p: setattr(p.routes[2], "distance", 0)), "distance is 0, recomputed 4")


def test_fuel_used():
    expect(mutate(lambda p: setattr(p.routes[0], "fuel_used", 20)), "fuel_used is 20, recomputed 22")


def test_missing_route():
    expect(mutate(lambda p: p.routes.pop()), "no route for uav(s) [3]")


def test_duplicate_route():
    expect(mutate(lambda p: p.routes.append(copy.deepcopy(p.routes[2]))), "uav 3 has 2 routes")


def test_routes_out_of_order():
    expect(mutate(lambda p: p.routes.reverse()), "not in mission order")


def test_unknown_uav():
    expect(mutate(lambda p: setattr(p.routes[2], "uav", 9)), "uav 9 is not in the mission")


def test_unknown_target():
    expect(mutate(lambda p: p.routes[1].targets.append(77)), "target 77 is not in the mission")


def test_mission_name():
    expect(mutate(lambda p: setattr(p, "mission", "other")), "plan is for 'other'")


STRANDED = mission([(1, 0, 0, 100), (2, 10, 10, 15)], [(1, 5, 0, 10, 20, 1)])


def test_stranded_uav_passes_when_reported():
    p = model.make_plan(STRANDED, "x", {1: [1]})
    assert p.stranded == [2] and p.routes[1].distance == 0
    assert check.check_plan(STRANDED, p) == []


def test_stranded_uav_not_listed():
    p = model.make_plan(STRANDED, "x", {1: [1]})
    p.stranded = []
    expect(check.check_plan(STRANDED, p), "must be listed in stranded")


def test_stranded_uav_with_a_route():
    p = model.make_plan(STRANDED, "x", {1: [1]})
    p.routes[1].distance = 20
    p.routes[1].fuel_used = 20
    expect(check.check_plan(STRANDED, p), "route must be empty")


def test_listed_stranded_but_can_return():
    p = model.make_plan(STRANDED, "x", {1: [1]})
    p.stranded = [1, 2]
    expect(check.check_plan(STRANDED, p), "uav 1: listed in stranded")


def test_cli_exit_codes(tmp_path):
    mp = write(tmp_path, "m.json", BASE.to_json())
    good = write(tmp_path, "good.json", good_plan().to_json())
    bad_doc = good_plan().to_json()
    bad_doc["cost"] = 1
    bad_doc["covered"] = 0
    bad = write(tmp_path, "bad.json", bad_doc)
    r = sva_tools("check", mp, good)
    assert r.returncode == 0, r.stdout + r.stderr
    r = sva_tools("check", mp, bad)
    assert r.returncode == 1
    assert len(r.stdout.strip().splitlines()) == 2  # one line per violation
    bad_doc.pop("routes")
    r = sva_tools("check", mp, write(tmp_path, "shape.json", bad_doc))
    assert r.returncode == 2 and 'plan: missing key "routes"' in r.stderr
