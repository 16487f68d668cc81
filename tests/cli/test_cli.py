"""Tests of the sva command line (docs/cli.md) against SPEC sections 3 and 4.

The binary comes from $SVA_BIN (ctest sets it: build/bin/sva, or sva_san for the
sanitized run, which selects the tests marked `sanitize`), the fixtures from
$SVA_FIXTURES. Plans are checked here independently of the core: shape, ids, cost,
distances, fuel and time windows are recomputed from the mission.
"""
import json
import os
import re
import subprocess
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
SVA = str(Path(os.environ.get("SVA_BIN", HERE.parents[1] / "build" / "bin" / "sva")).resolve())
FIXTURES = Path(os.environ.get("SVA_FIXTURES", HERE.parents[1] / "fixtures"))
MISSIONS = sorted(p.stem for p in (FIXTURES / "missions").glob("*.json"))
INVALID = sorted(p.stem for p in (FIXTURES / "invalid").glob("*.json"))
ALGORITHMS = ["sva", "ga", "hga", "bfa", "flow"]
PLAN_KEYS = ["mission", "algorithm", "status", "covered", "uncovered", "cost", "routes", "stranded", "stats"]
ROUTE_KEYS = ["uav", "targets", "distance", "fuel_used"]
STATS_KEYS = ["solve_us", "pivots", "clusters", "transport_problems", "largest_cluster", "largest_sources",
              "largest_sinks", "largest_tableau_cells", "max_pivots", "dropped_sources", "chunked_clusters",
              "search_nodes", "truncated_searches"]
# flow adds its certificate and search counters.
FLOW_STATS_KEYS = ["lower_bound", "optimal", "coverage_proven", "flow_solves", "flow_augmentations", "flow_work",
                   "flow_graph_arcs", "flow_max_depth", "flow_lagrange_iters", "flow_lp_columns", "flow_dive_routes",
                   "flow_cover_dive", "flow_cover_nodes", "flow_ruin_rounds",
                   "flow_incomplete"]
TRACE_KEYS = ["algorithm", "source_uavs", "supply", "sink_targets", "demand", "dropped", "cost", "flow",
              "cost_total", "covered", "pivots"]
# Fixtures whose message names a bound of the default profile.
PROFILE_BOUND = {"too_many_uavs": "SVA_MAX_UAVS", "too_many_targets": "SVA_MAX_TARGETS",
                 "need_over_max_uavs": "SVA_MAX_UAVS"}
DEFAULT_LIMITS = {"SVA_MAX_UAVS": 64, "SVA_MAX_TARGETS": 256}


def run(args, cwd=None, stdin=None, stdout=subprocess.PIPE):
    return subprocess.run([SVA, *args], cwd=cwd, input=stdin, stdout=stdout, stderr=subprocess.PIPE,
                          timeout=300)


def limits():
    out = run(["--version"]).stdout.decode()
    return {k: int(v) for k, v in re.findall(r"(SVA_[A-Z_]+) (\d+)", out)}


def mission(name):
    return json.loads((FIXTURES / "missions" / f"{name}.json").read_text())


def assert_one_error_line(result, code):
    assert result.returncode == code, result.stderr
    assert result.stdout == b""
    err = result.stderr.decode()
    assert err.startswith("sva: error: ") and err.endswith("\n") and err.count("\n") == 1, err
    return err[len("sva: error: "):-1]


def manhattan(ax, ay, bx, by):
    return abs(ax - bx) + abs(ay - by)


def check_plan(m, plan, algo):
    """SPEC 1 and 3, recomputed from the mission."""
    assert list(plan) == PLAN_KEYS
    assert plan["mission"] == m["name"] and plan["algorithm"] == algo
    targets = {t["id"]: t for t in m["targets"]}
    tpc = m.get("ticks_per_cell", 1)
    hover = m.get("hover_fuel", 0)
    depot = m["depot"]
    # every UAV exactly once, in mission order
    assert [r["uav"] for r in plan["routes"]] == [u["id"] for u in m["uavs"]]
    served = {t: 0 for t in targets}
    for uav, route in zip(m["uavs"], plan["routes"]):
        assert list(route) == ROUTE_KEYS
        x, y, tick = uav["x"], uav["y"], uav.get("ready_at", 0)
        distance = 0
        for tid in route["targets"]:
            t = targets[tid]
            leg = manhattan(x, y, t["x"], t["y"])
            assert tick + leg * tpc <= t["start"], f"UAV {uav['id']} late at target {tid}"
            distance += leg
            x, y, tick = t["x"], t["y"], t["end"]
            served[tid] += 1
        if route["targets"] or (x, y) != (depot["x"], depot["y"]) and uav["id"] not in plan["stranded"]:
            distance += manhattan(x, y, depot["x"], depot["y"])
        if uav["id"] in plan["stranded"]:
            assert route["targets"] == [] and route["distance"] == 0
            assert manhattan(uav["x"], uav["y"], depot["x"], depot["y"]) > uav["fuel"]
        else:
            assert route["distance"] == distance
            assert route["fuel_used"] == distance + hover * len(route["targets"])
            assert route["fuel_used"] <= uav["fuel"]
    assert plan["cost"] == sum(r["distance"] for r in plan["routes"])
    # covered + uncovered = targets; uncovered in mission order and never visited
    assert plan["uncovered"] == [t["id"] for t in m["targets"] if t["id"] in plan["uncovered"]]
    assert plan["covered"] + len(plan["uncovered"]) == len(m["targets"])
    for tid, count in served.items():
        if tid in plan["uncovered"]:
            assert count == 0, f"target {tid} uncovered but visited"
        else:
            assert count == targets[tid]["need"], f"target {tid} served by {count}"
    assert plan["status"] == ("complete" if not plan["uncovered"] else "partial")
    stats = dict(plan["stats"])
    if plan["algorithm"] == "flow":
        assert list(stats) == STATS_KEYS + FLOW_STATS_KEYS
        assert isinstance(stats.pop("optimal"), bool)
        assert 0 <= stats["lower_bound"] <= plan["cost"]
    else:
        assert list(stats) == STATS_KEYS
    assert all(isinstance(v, int) and v >= 0 for v in stats.values())


# ---------------------------------------------------------------------------------
# bad input (SPEC 4)

def test_fixture_sets_are_there():
    assert len(MISSIONS) >= 16 and len(INVALID) >= 40


@pytest.mark.parametrize("name", INVALID)
def test_invalid_fixture_has_its_message(name):
    assert (FIXTURES / "invalid" / f"{name}.err").is_file()


def test_no_orphan_messages():
    errs = sorted(p.stem for p in (FIXTURES / "invalid").glob("*.err"))
    assert errs == INVALID


@pytest.mark.sanitize
@pytest.mark.parametrize("command", [["validate"], ["plan", "--algo", "sva"], ["plan", "--algo", "bfa"]])
@pytest.mark.parametrize("name", INVALID)
def test_invalid_fixture_is_rejected(name, command):
    bound = PROFILE_BOUND.get(name)
    if bound is not None and limits()[bound] != DEFAULT_LIMITS[bound]:
        pytest.skip(f"message names {bound} of the default profile")
    expected = (FIXTURES / "invalid" / f"{name}.err").read_text().rstrip("\n")
    result = run([*command, f"{name}.json"], cwd=FIXTURES / "invalid")
    assert assert_one_error_line(result, 2) == expected


@pytest.mark.parametrize("name", ["invalid_json", "duplicate_key", "empty", "unknown_key_target", "need_zero"])
def test_invalid_on_stdin_names_stdin(name):
    data = (FIXTURES / "invalid" / f"{name}.json").read_bytes()
    expected = (FIXTURES / "invalid" / f"{name}.err").read_text().rstrip("\n")
    expected = expected.replace(f"{name}.json", "<stdin>")
    assert assert_one_error_line(run(["plan", "-"], stdin=data), 2) == expected


def test_missing_file_names_the_path():
    message = assert_one_error_line(run(["validate", "no/such/mission.json"]), 2)
    assert message == "no/such/mission.json: cannot open: No such file or directory"


def test_directory_is_bad_input():
    message = assert_one_error_line(run(["plan", str(FIXTURES)]), 2)
    assert message.endswith("Is a directory")


def test_at_the_bounds_is_accepted(tmp_path):
    lim = limits()
    m = mission("hand_3_1")
    m["uavs"] = [{"id": i + 1, "x": 0, "y": 0, "fuel": 100} for i in range(lim["SVA_MAX_UAVS"])]
    m["targets"] = [{"id": i + 1, "x": i % 20, "y": i // 20, "start": 400, "end": 410, "need": 1}
                    for i in range(lim["SVA_MAX_TARGETS"])]
    m["targets"][0]["need"] = lim["SVA_MAX_UAVS"]
    path = tmp_path / "bounds.json"
    path.write_text(json.dumps(m))
    result = run(["validate", str(path)])
    assert result.returncode == 0, result.stderr
    assert result.stdout.decode() == f"ok: hand_3_1: {lim['SVA_MAX_UAVS']} UAVs, {lim['SVA_MAX_TARGETS']} targets\n"
    # one more UAV is over the bound, with the core's message
    m["uavs"].append({"id": 9999, "x": 0, "y": 0, "fuel": 100})
    path.write_text(json.dumps(m))
    n = lim["SVA_MAX_UAVS"]
    assert assert_one_error_line(run(["validate", str(path)]), 2) == \
        f"uavs: {n + 1} entries exceed SVA_MAX_UAVS ({n})"


def test_defaults_of_optional_keys(tmp_path):
    m = mission("hand_3_1")  # leaves out ticks_per_cell, hover_fuel, overlap_percent, ready_at
    explicit = dict(m, ticks_per_cell=1, hover_fuel=0, overlap_percent=70,
                    uavs=[dict(u, ready_at=0) for u in m["uavs"]])
    path = tmp_path / "explicit.json"
    path.write_text(json.dumps(explicit))
    a = json.loads(run(["plan", str(FIXTURES / "missions" / "hand_3_1.json")]).stdout)
    b = json.loads(run(["plan", str(path)]).stdout)
    del a["stats"], b["stats"]
    assert a == b


# ---------------------------------------------------------------------------------
# planning every mission with every algorithm

@pytest.mark.parametrize("name", MISSIONS)
def test_validate(name):
    m = mission(name)
    result = run(["validate", str(FIXTURES / "missions" / f"{name}.json")])
    assert result.returncode == 0, result.stderr
    assert result.stderr == b""
    assert result.stdout.decode() == f"ok: {name}: {len(m['uavs'])} UAVs, {len(m['targets'])} targets\n"


@pytest.mark.sanitize
@pytest.mark.parametrize("algo", ALGORITHMS)
@pytest.mark.parametrize("name", MISSIONS)
def test_plan(name, algo):
    m = mission(name)
    result = run(["plan", "--algo", algo, str(FIXTURES / "missions" / f"{name}.json")])
    if algo == "bfa":
        lim = limits()
        over = [bound for bound, size in (("SVA_BFA_MAX_TARGETS", len(m["targets"])),
                                          ("SVA_BFA_MAX_UAVS", len(m["uavs"]))) if size > lim[bound]]
        if over:
            message = assert_one_error_line(result, 1)
            assert over[0] in message and str(lim[over[0]]) in message
            return
        if result.returncode == 1:  # within the size limits, but over the node budget
            assert "SVA_BFA_MAX_NODES" in assert_one_error_line(result, 1)
            return
    assert result.returncode == 0, result.stderr
    assert result.stderr == b""
    check_plan(m, json.loads(result.stdout), algo)


def test_fixtures_cover_the_cases_the_brief_asks_for():
    ms = [mission(n) for n in MISSIONS]
    assert any(t["need"] >= 2 for m in ms for t in m["targets"])
    assert any(m.get("ticks_per_cell", 1) == 2 for m in ms)
    assert any(u.get("ready_at", 0) > 0 and (u["x"], u["y"]) != (m["depot"]["x"], m["depot"]["y"])
               for m in ms for u in m["uavs"])
    stranded = [n for n in MISSIONS if json.loads(run(["plan", str(FIXTURES / "missions" / f"{n}.json")]).stdout)
                ["stranded"]]
    assert stranded, "no mission has a stranded UAV"


def test_fuel_binds_somewhere(tmp_path):
    """rand_25_2 has tight fuel: with 400 fuel per UAV more targets get covered."""
    m = mission("rand_25_2")
    tight = json.loads(run(["plan", str(FIXTURES / "missions" / "rand_25_2.json")]).stdout)
    for u in m["uavs"]:
        u["fuel"] = 400
    path = tmp_path / "generous.json"
    path.write_text(json.dumps(m))
    generous = json.loads(run(["plan", str(path)]).stdout)
    assert generous["covered"] > tight["covered"]


def test_stdin_gives_the_same_plan():
    path = FIXTURES / "missions" / "hand_5_3.json"
    from_file = json.loads(run(["plan", "--algo", "hga", str(path)]).stdout)
    result = run(["plan", "--algo", "hga", "-"], stdin=path.read_bytes())
    assert result.returncode == 0, result.stderr
    from_stdin = json.loads(result.stdout)
    del from_file["stats"], from_stdin["stats"]
    assert from_file == from_stdin


@pytest.mark.parametrize("algo", ALGORITHMS)
@pytest.mark.parametrize("name", ["rand_10_1", "rand_25_2"])
def test_repeat_plans_the_same_and_keeps_the_fastest(name, algo):
    if algo == "bfa" and name == "rand_25_2":
        pytest.skip("over bfa's limits")
    path = str(FIXTURES / "missions" / f"{name}.json")
    once = json.loads(run(["plan", "--algo", algo, path]).stdout)
    result = run(["plan", "--algo", algo, "--repeat", "4", path])
    assert result.returncode == 0, result.stderr
    again = json.loads(result.stdout)
    assert again["stats"]["solve_us"] >= 0
    del once["stats"]["solve_us"], again["stats"]["solve_us"]
    assert once == again  # every stat but the time, and the plan


def test_repeat_traces_one_run(tmp_path):
    path = str(FIXTURES / "missions" / "rand_25_1.json")
    traces = []
    for repeat in ("1", "3"):
        trace = tmp_path / f"trace_{repeat}.jsonl"
        result = run(["plan", "--repeat", repeat, "--trace", str(trace), path])
        assert result.returncode == 0, result.stderr
        traces.append(trace.read_text())
    assert traces[0] == traces[1] and traces[0].count("\n") > 0


def test_plan_is_indented_json_ending_in_newline():
    out = run(["plan", str(FIXTURES / "missions" / "hand_3_1.json")]).stdout.decode()
    assert out.startswith('{\n  "mission": "hand_3_1",\n  "algorithm": "sva",') and out.endswith("}\n")


def test_algo_equals_form_and_default_is_sva():
    path = str(FIXTURES / "missions" / "hand_3_3.json")
    assert json.loads(run(["plan", path]).stdout)["algorithm"] == "sva"
    assert json.loads(run(["plan", "--algo=ga", path]).stdout)["algorithm"] == "ga"
    assert json.loads(run(["plan", path, "--algo", "bfa"]).stdout)["algorithm"] == "bfa"


# ---------------------------------------------------------------------------------
# --schedule

def test_schedule():
    name = "rand_7_2"  # partial, with a stranded UAV and UAVs away from the depot
    m = mission(name)
    path = str(FIXTURES / "missions" / f"{name}.json")
    plan = json.loads(run(["plan", path]).stdout)
    result = run(["plan", "--schedule", path])
    assert result.returncode == 0 and result.stderr == b""
    text = result.stdout.decode()
    lines = text.splitlines()
    assert lines[0] == (f"mission {name}: algorithm sva, {plan['status']}, covered {plan['covered']}/"
                        f"{len(m['targets'])} targets, cost {plan['cost']}")
    for u, r in zip(m["uavs"], plan["routes"]):
        block = re.search(rf"^UAV {u['id']} from \({u['x']}, {u['y']}\), ready at {u['ready_at']}.*?(?=^UAV |^\n|\Z)",
                          text, re.M | re.S)
        assert block, f"no block for UAV {u['id']}"
        listed = [int(t) for t in re.findall(r"^  target (\d+) at", block.group(0), re.M)]
        assert listed == r["targets"]
        if u["id"] in plan["stranded"]:
            assert "stranded" in block.group(0)
        else:
            assert f"distance {r['distance']}, fuel {r['fuel_used']}/{u['fuel']}" in block.group(0)
    assert f"stranded: {' '.join(f'UAV {i}' for i in plan['stranded']) or 'none'}" in lines
    uncovered = text.split("uncovered:")[1]
    assert [int(t) for t in re.findall(r"target (\d+) at", uncovered)] == plan["uncovered"]
    t = {t["id"]: t for t in m["targets"]}[plan["uncovered"][0]]
    assert f"target {t['id']} at ({t['x']}, {t['y']}), window [{t['start']}, {t['end']}], need {t['need']}" in uncovered


def test_schedule_of_a_complete_plan_says_none_uncovered():
    text = run(["plan", "--schedule", str(FIXTURES / "missions" / "hand_3_1.json")]).stdout.decode()
    assert "uncovered: none" in text and "stranded: none" in text and ", complete, covered 3/3" in text


# ---------------------------------------------------------------------------------
# --trace

@pytest.mark.parametrize("algo", ["sva", "hga"])
@pytest.mark.parametrize("name", ["hand_5_3", "rand_10_2", "rand_25_1"])
def test_trace(tmp_path, name, algo):
    m = mission(name)
    uav_ids = [u["id"] for u in m["uavs"]]
    targets = {t["id"]: t for t in m["targets"]}
    trace = tmp_path / "trace.jsonl"
    result = run(["plan", "--algo", algo, "--trace", str(trace), str(FIXTURES / "missions" / f"{name}.json")])
    assert result.returncode == 0, result.stderr
    plan = json.loads(result.stdout)
    lines = trace.read_text().splitlines()
    assert len(lines) == plan["stats"]["transport_problems"] > 0
    pivots = 0
    for line in lines:
        p = json.loads(line)
        assert list(p) == TRACE_KEYS and p["algorithm"] == algo
        s, k = len(p["source_uavs"]), len(p["sink_targets"])
        assert set(p["source_uavs"]) <= set(uav_ids) and set(p["sink_targets"]) <= set(targets)
        assert len(p["supply"]) == s and len(p["demand"]) == k and len(p["dropped"]) == k
        assert [targets[t]["need"] for t in p["sink_targets"]] == p["demand"]
        assert len(p["cost"]) == len(p["flow"]) == s
        total = 0
        for i in range(s):
            assert len(p["cost"][i]) == len(p["flow"][i]) == k
            for j in range(k):
                assert (p["cost"][i][j] is None) == (p["flow"][i][j] is None)
                if p["flow"][i][j] is not None:
                    total += p["cost"][i][j] * p["flow"][i][j]
            assert sum(f or 0 for f in p["flow"][i]) <= p["supply"][i]
        assert total == p["cost_total"]
        into = [sum(p["flow"][i][j] or 0 for i in range(s)) for j in range(k)]
        met = [into[j] == p["demand"][j] for j in range(k)]
        assert sum(met) == p["covered"]
        for j in range(k):
            assert into[j] in (0, p["demand"][j]), "a sink half covered"
            if p["dropped"][j]:
                assert into[j] == 0
        if algo == "hga":
            assert p["pivots"] == 0
        pivots += p["pivots"]
    assert pivots == plan["stats"]["pivots"]


def test_trace_of_ga_is_empty(tmp_path):
    trace = tmp_path / "trace.jsonl"
    result = run(["plan", "--algo", "ga", "--trace", str(trace), str(FIXTURES / "missions" / "hand_5_3.json")])
    assert result.returncode == 0 and trace.read_text() == ""


def test_trace_to_an_unwritable_path_fails():
    result = run(["plan", "--trace", "/nonexistent/dir/trace.jsonl", str(FIXTURES / "missions" / "hand_3_1.json")])
    assert "/nonexistent/dir/trace.jsonl: cannot open for writing" in assert_one_error_line(result, 1)


def test_trace_is_not_written_for_a_rejected_mission(tmp_path):
    trace = tmp_path / "trace.jsonl"
    result = run(["plan", "--trace", str(trace), "need_zero.json"], cwd=FIXTURES / "invalid")
    assert_one_error_line(result, 2)
    assert not trace.exists()


# ---------------------------------------------------------------------------------
# usage, help, version, output errors

@pytest.mark.parametrize("args, message", [
    ([], "missing command (try 'sva --help')"),
    (["frobnicate"], "unknown command \"frobnicate\" (try 'sva --help')"),
    (["plan"], "plan: missing MISSION.json (or - for standard input)"),
    (["validate"], "validate: missing MISSION.json (or - for standard input)"),
    (["plan", "a.json", "b.json"], "plan: one mission expected, got \"a.json\" and \"b.json\""),
    (["plan", "--algo"], "plan: --algo needs a value"),
    (["plan", "--trace"], "plan: --trace needs a file name"),
    (["plan", "--repeat", "0", "a.json"], "plan: --repeat: must be an integer in [1, 1000]"),
    (["plan", "--repeat=1001", "a.json"], "plan: --repeat: must be an integer in [1, 1000]"),
    (["plan", "--repeat", "x", "a.json"], "plan: --repeat: must be an integer in [1, 1000]"),
    (["plan", "--flow-work", "999", "a.json"], "plan: --flow-work: must be an integer in [1000, "),
    (["plan", "--fast", "a.json"], "plan: unknown option \"--fast\" (try 'sva --help')"),
    (["validate", "--algo", "sva", "a.json"], "validate: unknown option \"--algo\" (try 'sva --help')"),
    (["plan", "--algo", "simplex", "a.json"], "plan: --algo: unknown algorithm \"simplex\" (known: sva, ga, hga, bfa"),
])
def test_usage_errors(args, message):
    got = assert_one_error_line(run(args), 2)
    assert got.startswith(message)


def test_help_and_version():
    result = run(["--help"])
    assert result.returncode == 0 and result.stdout.startswith(b"usage: sva plan")
    assert b"sva, ga, hga, bfa" in result.stdout
    result = run(["plan", "--help"])
    assert result.returncode == 0 and result.stdout.startswith(b"usage: sva plan")
    result = run(["--version"])
    assert result.returncode == 0
    assert re.match(r"sva \d+\.\d+\.\d+ \(mission/plan schema \d+\)\n", result.stdout.decode())
    assert {"SVA_MAX_UAVS", "SVA_MAX_TARGETS", "SVA_BFA_MAX_UAVS", "SVA_BFA_MAX_TARGETS",
            "SVA_BFA_MAX_NODES"} <= set(limits())
    assert "unless its search passes SVA_BFA_MAX_NODES nodes" in result.stdout.decode()


# ---------------------------------------------------------------------------------
# bfa at its advertised bounds: SVA_BFA_MAX_UAVS x SVA_BFA_MAX_TARGETS is planned
# unless the search passes SVA_BFA_MAX_NODES; one more UAV or target is refused.

def bfa_mission(uavs, targets, need):
    """All UAVs at the depot. Targets in chained windows (each can follow every
    earlier one), so with need >= 2 the search is at its widest."""
    xs = [7, -3, 12, -15, 4, 9, -8, 18, -11, 2, 14, -6, 5, -17]
    return {
        "name": f"bfa_{uavs}x{targets}_need{need}",
        "depot": {"x": 0, "y": 0},
        "uavs": [{"id": u + 1, "x": 0, "y": 0, "fuel": 100000} for u in range(uavs)],
        "targets": [{"id": t + 1, "x": xs[t], "y": xs[-1 - t], "start": 100 * (t + 1), "end": 100 * (t + 1) + 5,
                     "need": need} for t in range(targets)],
    }


def plan_bfa(tmp_path, m):
    path = tmp_path / f"{m['name']}.json"
    path.write_text(json.dumps(m))
    return run(["plan", "--algo", "bfa", str(path)])


def test_bfa_plans_a_mission_at_its_size_bounds(tmp_path):
    lim = limits()
    m = bfa_mission(lim["SVA_BFA_MAX_UAVS"], lim["SVA_BFA_MAX_TARGETS"], 1)
    result = plan_bfa(tmp_path, m)
    assert result.returncode == 0, result.stderr
    plan = json.loads(result.stdout)
    check_plan(m, plan, "bfa")
    assert plan["status"] == "complete"
    assert 0 < plan["stats"]["search_nodes"] <= lim["SVA_BFA_MAX_NODES"]


@pytest.mark.parametrize("extra_uav, extra_target, bound", [(1, 0, "SVA_BFA_MAX_UAVS"),
                                                            (0, 1, "SVA_BFA_MAX_TARGETS")])
def test_bfa_refuses_one_past_its_size_bounds(tmp_path, extra_uav, extra_target, bound):
    lim = limits()
    m = bfa_mission(lim["SVA_BFA_MAX_UAVS"] + extra_uav, lim["SVA_BFA_MAX_TARGETS"] + extra_target, 1)
    message = assert_one_error_line(plan_bfa(tmp_path, m), 1)
    size = lim[bound] + 1
    assert message == f"{'uavs' if extra_uav else 'targets'}: {size} entries exceed {bound} ({lim[bound]})"


def test_bfa_within_its_size_bounds_is_refused_past_its_node_budget(tmp_path):
    """8 x 12 with need 3 in chained windows: within the size bounds, but the search
    passes the node budget (about 5 s); refused as --version says, one node past it."""
    lim = limits()
    m = bfa_mission(lim["SVA_BFA_MAX_UAVS"], lim["SVA_BFA_MAX_TARGETS"], 3)
    message = assert_one_error_line(plan_bfa(tmp_path, m), 1)
    budget = lim["SVA_BFA_MAX_NODES"]
    assert message == f"mission: {budget + 1} search nodes exceed SVA_BFA_MAX_NODES ({budget})"
    # the same mission is within every other algorithm's reach
    assert json.loads(run(["plan", str(tmp_path / f"{m['name']}.json")]).stdout)["algorithm"] == "sva"


@pytest.mark.skipif(not Path("/dev/full").exists(), reason="needs /dev/full")
@pytest.mark.parametrize("extra", [[], ["--schedule"]])
def test_write_failure_is_exit_1(extra):
    with open("/dev/full", "wb") as full:
        result = run(["plan", *extra, str(FIXTURES / "missions" / "rand_25_1.json")], stdout=full)
    assert result.returncode == 1
    assert result.stderr.decode().startswith("sva: error: writing the ")


# ---------------------------------------------------------------------------------
# mutated missions: never a crash, always a plan or exactly one error line

@pytest.mark.sanitize
def test_mutated_missions_never_crash():
    import random
    seed = int(os.environ.get("SVA_MUTATION_SEED", "20240607"))
    print(f"mutation seed {seed} (replay with SVA_MUTATION_SEED={seed})")
    rng = random.Random(seed)
    files = sorted((FIXTURES / "missions").glob("*.json")) + sorted((FIXTURES / "invalid").glob("*.json"))
    inserts = [b"-", b"9999999999", b"{", b"]", b'"x": 1,', b"0", b"null", b"1e9", b'"', b","]
    for i in range(200):
        data = bytearray(rng.choice(files).read_bytes())
        for _ in range(rng.randint(1, 4)):
            if not data:
                break
            at = rng.randrange(len(data))
            op = rng.random()
            if op < 0.4:
                data[at] = rng.randrange(256)
            elif op < 0.7:
                del data[at:at + rng.randint(1, 8)]
            else:
                data[at:at] = rng.choice(inserts)
        algo = rng.choice(ALGORITHMS)
        result = run(["plan", "--algo", algo, "-"], stdin=bytes(data))
        where = f"seed {seed}, case {i}, --algo {algo}"
        if result.returncode == 0:
            assert result.stderr == b"" and json.loads(result.stdout)["algorithm"] == algo, where
        else:
            assert result.returncode in (1, 2), f"{where}: exit {result.returncode}: {result.stderr[-2000:]!r}"
            assert_one_error_line(result, result.returncode)


# ---------------------------------------------------------------------------------
# getopt_long: both value forms, abbreviations, options anywhere, "--"

def test_value_forms_give_the_same_plan():
    path = str(FIXTURES / "missions" / "hand_5_3.json")
    runs = [run(args) for args in (["plan", "--algo=hga", "--repeat=2", path],
                                   ["plan", "--algo", "hga", "--repeat", "2", path],
                                   ["plan", path, "--repeat", "2", "--algo", "hga"],
                                   ["plan", "--al=hga", "--rep", "2", path])]  # unique prefixes
    plans = []
    for result in runs:
        assert result.returncode == 0 and result.stderr == b"", result.stderr
        plan = json.loads(result.stdout)
        del plan["stats"]
        plans.append(plan)
    assert plans[0]["algorithm"] == "hga" and all(p == plans[0] for p in plans)


def test_double_dash_ends_the_options(tmp_path):
    (tmp_path / "--algo").write_bytes((FIXTURES / "missions" / "hand_3_1.json").read_bytes())
    result = run(["validate", "--", "--algo"], cwd=tmp_path)
    assert result.returncode == 0 and result.stdout == b"ok: hand_3_1: 3 UAVs, 3 targets\n"
    result = run(["plan", "--schedule", "--", "--algo"], cwd=tmp_path)
    assert result.returncode == 0 and result.stdout.startswith(b"mission hand_3_1: algorithm sva")


@pytest.mark.parametrize("args, message", [
    (["plan", "a.json", "--algo"], "plan: --algo needs a value"),
    (["plan", "a.json", "--trace"], "plan: --trace needs a file name"),
    (["plan", "--trace=", "a.json"], "plan: --trace needs a file name"),
    (["plan", "a.json", "--repeat"], "plan: --repeat: must be an integer in [1, 1000]"),
    (["plan", "a.json", "--flow-work"], "plan: --flow-work: must be an integer in [1000, "),
    (["plan", "--algo=", "a.json"], "plan: --algo: unknown algorithm \"\" (known: sva, ga, hga, bfa"),
    (["plan", "--schedule=yes", "a.json"], "plan: unknown option \"--schedule=yes\" (try 'sva --help')"),
    (["plan", "-x", "a.json"], "plan: unknown option \"-x\" (try 'sva --help')"),
    (["plan", "--", "a.json", "b.json"], "plan: one mission expected, got \"a.json\" and \"b.json\""),
    (["validate", "--schedule", "a.json"], "validate: unknown option \"--schedule\" (try 'sva --help')"),
    (["validate", "--algo=sva", "a.json"], "validate: unknown option \"--algo=sva\" (try 'sva --help')"),
])
def test_getopt_usage_errors(args, message):
    got = assert_one_error_line(run(args), 2)
    assert got.startswith(message), got


# ---------------------------------------------------------------------------------
# user-supplied text is printed escaped: no forged lines, no terminal control

HOSTILE = "x\n\x1b[31mforged\x1b[0m\r\t\x7f"
HOSTILE_SHOWN = "x\\n\\x1b[31mforged\\x1b[0m\\r\\t\\x7f"


def assert_no_raw_control(data):
    """Only the line ends of the output itself: no ESC, CR, TAB, DEL or C1 byte."""
    assert all(b >= 0x20 or b == 0x0a for b in data) and b"\x7f" not in data, data
    text = data.decode("utf-8")
    assert not any(0x80 <= ord(c) <= 0x9f for c in text), text


def test_hostile_algo_value_is_escaped():
    path = str(FIXTURES / "missions" / "hand_3_1.json")
    for args in (["plan", f"--algo={HOSTILE}", path], ["plan", "--algo", HOSTILE, path]):
        result = run(args)
        assert_no_raw_control(result.stderr)
        got = assert_one_error_line(result, 2)
        assert got.startswith(f'plan: --algo: unknown algorithm "{HOSTILE_SHOWN}" (known: '), got


def test_hostile_command_and_option_are_escaped():
    result = run([HOSTILE])
    assert_no_raw_control(result.stderr)
    assert assert_one_error_line(result, 2) == f"unknown command \"{HOSTILE_SHOWN}\" (try 'sva --help')"
    result = run(["plan", "--" + HOSTILE, "a.json"])
    assert_no_raw_control(result.stderr)
    assert assert_one_error_line(result, 2) == f"plan: unknown option \"--{HOSTILE_SHOWN}\" (try 'sva --help')"
    result = run(["plan", "--repeat", HOSTILE, "a.json"])
    assert_no_raw_control(result.stderr)
    assert_one_error_line(result, 2)


@pytest.mark.sanitize
def test_hostile_file_names_are_escaped(tmp_path):
    # missing, then present but invalid JSON, then a trace file that cannot be opened
    result = run(["validate", HOSTILE + ".json"], cwd=tmp_path)
    assert_no_raw_control(result.stderr)
    assert assert_one_error_line(result, 2) == f"{HOSTILE_SHOWN}.json: cannot open: No such file or directory"
    (tmp_path / (HOSTILE + ".json")).write_text("{\n  oops")
    result = run(["plan", HOSTILE + ".json"], cwd=tmp_path)
    assert_no_raw_control(result.stderr)
    assert assert_one_error_line(result, 2).startswith(f"{HOSTILE_SHOWN}.json:2:6: invalid JSON: ")
    mission_path = str((FIXTURES / "missions" / "hand_3_1.json").resolve())
    result = run(["plan", "--trace", f"no_dir/{HOSTILE}", mission_path], cwd=tmp_path)
    assert_no_raw_control(result.stderr)
    assert assert_one_error_line(result, 1) == f"no_dir/{HOSTILE_SHOWN}: cannot open for writing: No such file or directory"
    result = run(["plan", f"{HOSTILE}\u009b.json"], cwd=tmp_path)  # a C1 control (CSI), UTF-8 c2 9b
    assert_no_raw_control(result.stderr)
    assert assert_one_error_line(result, 2).startswith(f"{HOSTILE_SHOWN}\\xc2\\x9b.json: cannot open")


@pytest.mark.sanitize
def test_hostile_mission_name_is_escaped(tmp_path):
    m = mission("hand_3_1")
    m["name"] = "évasion " + HOSTILE  # printable UTF-8 is kept
    path = tmp_path / "hostile.json"
    path.write_text(json.dumps(m))
    result = run(["validate", str(path)])
    assert result.returncode == 0 and result.stderr == b""
    assert_no_raw_control(result.stdout)
    assert result.stdout.decode() == f"ok: évasion {HOSTILE_SHOWN}: 3 UAVs, 3 targets\n"
    result = run(["plan", "--schedule", str(path)])
    assert result.returncode == 0 and result.stderr == b""
    assert_no_raw_control(result.stdout)
    lines = result.stdout.decode().split("\n")
    assert lines[0].startswith(f"mission évasion {HOSTILE_SHOWN}: algorithm sva, ")
    assert lines[1].startswith("depot (")
    # in the plan JSON the name is a JSON string, escaped by JSON's rules (which let DEL
    # through), read back whole
    result = run(["plan", str(path)])
    assert all(b >= 0x20 or b == 0x0a for b in result.stdout)
    assert json.loads(result.stdout)["mission"] == m["name"]
