"""docs/schema: every fixture against its JSON Schema, every invalid fixture rejected with
the error it is paired with, and the C CLI's real output (plans, --trace) against the
plan and trace schemas, so the schemas cannot drift from the code."""
import copy
import json
import os
import re
import subprocess
from pathlib import Path

import pytest
from conftest import REPO, sva_tools
from jsonschema import Draft202012Validator

from sva_tools import io, schema

FIXTURES = REPO / "fixtures"
MISSIONS = sorted((FIXTURES / "missions").glob("*.json"))
OPTIMA_MISSIONS = sorted(p for p in (FIXTURES / "optima").glob("*.json") if not p.name.endswith(".ref.json"))
OPTIMA_PLANS = sorted((FIXTURES / "optima").glob("*.ref.json"))
GOLDEN = sorted((FIXTURES / "golden").glob("*/*.json"))
INVALID = sorted((FIXTURES / "invalid").glob("*.json"))
C_ALGOS = ("sva", "ga", "hga", "bfa", "flow")
# Invalid fixtures that only the rules beyond the schema reject (docs/SPEC.md section 4):
# they are valid JSON Schema instances. The frame's t0: its calendar, time of day, UTC
# offset and range.
BEYOND_SCHEMA = {"duplicate_target_id", "duplicate_uav_id", "start_after_end", "start_equals_end",
                 "too_many_targets", "too_many_uavs", "need_over_max_uavs",
                 "frame_t0_not_a_date", "frame_t0_hour_24", "frame_t0_offset_24",
                 "frame_t0_before_1970", "frame_t0_after_9999"}


def _load(path):
    return json.loads(Path(path).read_text(encoding="utf-8"))


def _rel(p):
    return str(Path(p).relative_to(FIXTURES))


def test_schemas_are_draft_2020_12_and_carry_the_header_version():
    header = (REPO / "core" / "include" / "sva" / "sva.h").read_text()
    version = int(re.search(r"#define SVA_SCHEMA_VERSION (\d+)", header).group(1))
    files = sorted(p.name for p in (REPO / "docs" / "schema").glob("*.json"))
    assert files == sorted(f"{k}.schema.json" for k in schema.KINDS)
    for kind, s in schema.schemas().items():
        Draft202012Validator.check_schema(s)
        assert s["$schema"] == "https://json-schema.org/draft/2020-12/schema"
        assert s["x-sva-schema-version"] == version, kind
        assert s["$id"] == f"urn:sva:schema:{version}:{kind}"
    assert schema.version() == version


@pytest.mark.parametrize("path", MISSIONS + OPTIMA_MISSIONS, ids=_rel)
def test_fixture_missions_are_valid(path):
    doc = _load(path)
    assert schema.errors(doc, "mission") == []
    assert io.mission_from_json(doc).name == doc["name"]


@pytest.mark.parametrize("path", GOLDEN + OPTIMA_PLANS, ids=_rel)
def test_fixture_plans_are_valid(path):
    assert schema.errors(_load(path), "plan") == []


def _message(path):
    """What sva-tools says about a mission file: `FILE[:WHERE]: MESSAGE`, None if valid."""
    try:
        io.load_mission(str(path))
    except io.InputError as e:
        return f"{path.name}:{e.where}: {e}" if e.where else f"{path.name}: {e}"
    return None


@pytest.mark.parametrize("path", INVALID, ids=lambda p: p.stem)
def test_invalid_fixture_rejected_with_its_error(path):
    expected = path.with_suffix(".err").read_text(encoding="utf-8").strip()
    got = _message(path)
    assert got is not None, "accepted"
    if expected.startswith(path.name + ":"):
        # The document itself (syntax, encoding, empty): jansson's words are the CLI's
        # own, so ask for the same kind of error and, where both give one, the same line.
        kind = "empty input" if expected.endswith("empty input") else "invalid JSON: "
        assert kind in got, got
        exp_loc = re.match(re.escape(path.name) + r":(\d+):", expected)
        got_loc = re.match(re.escape(path.name) + r":(\d+):", got)
        if exp_loc and got_loc:
            assert got_loc.group(1) == exp_loc.group(1), got
    else:
        assert got == f"{path.name}: {expected}"


@pytest.mark.parametrize("path", [p for p in INVALID if not p.with_suffix(".err").read_text()
                                  .startswith(p.name + ":")], ids=lambda p: p.stem)
def test_schema_alone_rejects_all_but_the_rules_beyond_it(path):
    """The division of labour: the schema (with integers written as integers) catches
    every shape and range error; only BEYOND_SCHEMA need the rules of SPEC section 4."""
    doc = _load(path)
    alone = list(schema.validator("mission").iter_errors(doc))
    assert (not alone) == (path.stem in BEYOND_SCHEMA), [e.message for e in alone]


def test_integers_are_written_as_integers():
    doc = _load(MISSIONS[0])
    doc["targets"][0]["need"] = 2.0
    # JSON Schema's own "integer" takes 2.0; the CLI and the tools do not.
    assert Draft202012Validator(schema.schemas()["mission"]).is_valid(doc)
    assert schema.first_error(doc, "mission") == "targets[0].need: must be an integer, got real"


def _cli_stats_errors(plan):
    """The stats exactly as `sva plan` writes them (plan schema's cli_stats, cli_flow_stats)."""
    definition = "cli_flow_stats" if plan["algorithm"] == "flow" else "cli_stats"
    return schema.errors(plan["stats"], "plan", definition, root="stats")


def _run(sva_bin, *args, cwd=None):
    return subprocess.run([str(sva_bin), *map(str, args)], capture_output=True, text=True, cwd=cwd)


def _plan_with_trace(sva_bin, tmp_path, mission, algo, *extra):
    trace = tmp_path / f"{mission.stem}.{algo}.jsonl"
    r = _run(sva_bin, "plan", "--algo", algo, "--trace", trace, *extra, mission)
    return r, trace


@pytest.mark.parametrize("algo", C_ALGOS)
def test_cli_plans_and_traces_match_the_schemas(sva_bin, tmp_path, algo):
    traced = 0
    for mission in MISSIONS + OPTIMA_MISSIONS:
        r, trace = _plan_with_trace(sva_bin, tmp_path, mission, algo)
        if algo == "bfa" and r.returncode == 1:
            assert "SVA_BFA_MAX_" in r.stderr  # over bfa's limits: no plan to check
            continue
        assert r.returncode == 0, f"{mission.name}: {r.stderr}"
        plan = json.loads(r.stdout)
        assert schema.errors(plan, "plan") == [], mission.name
        assert _cli_stats_errors(plan) == [], mission.name
        records = io.load_trace(str(trace))  # the trace schema and its rules, per line
        assert len(records) == plan["stats"]["transport_problems"], mission.name
        assert all(rec["algorithm"] == algo for rec in records)
        traced += len(records)
    assert (traced > 0) == (algo in ("sva", "hga"))  # only these solve transportation problems


def test_flow_on_a_small_budget_matches_the_schema(sva_bin):
    """A flow plan that is not proven optimal (flow_incomplete 1: work budget)."""
    r = _run(sva_bin, "plan", "--algo", "flow", "--flow-work", "1000", FIXTURES / "missions" / "rand_25_2.json")
    assert r.returncode == 0, r.stderr
    plan = json.loads(r.stdout)
    assert plan["stats"]["optimal"] is False and plan["stats"]["flow_incomplete"] == 1
    assert schema.errors(plan, "plan") == [] and _cli_stats_errors(plan) == []


@pytest.fixture
def cli_plan(sva_bin):
    r = _run(sva_bin, "plan", "--algo", "sva", FIXTURES / "missions" / "hand_5_5.json")
    assert r.returncode == 0, r.stderr
    plan = json.loads(r.stdout)
    assert plan["status"] == "partial" and plan["uncovered"]
    return plan


def _mutated(doc, path, value):
    d = copy.deepcopy(doc)
    *head, last = path
    node = d
    for k in head:
        node = node[k]
    if value is KeyError:
        del node[last]
    else:
        node[last] = value
    return d


STATS_MUTATIONS = [
    (["pivots"], KeyError, 'stats: missing key "pivots"'),
    (["lower_bound"], 0, 'stats: unknown key "lower_bound"'),  # flow's key on an sva plan
    (["pivots"], -1, "stats.pivots: must be >= 0, got -1"),
]


@pytest.mark.parametrize("path,value,message", STATS_MUTATIONS, ids=lambda v: str(v)[:30])
def test_mutated_cli_stats_are_rejected(cli_plan, path, value, message):
    assert _cli_stats_errors(cli_plan) == []
    assert _cli_stats_errors(_mutated(cli_plan, ["stats"] + path, value))[0] == message


PLAN_MUTATIONS = [
    (["stats", "solve_us"], -1, "stats.solve_us: must be >= 0, got -1"),
    (["stats", "optimal"], 1, "stats.optimal: must be a boolean, got integer"),
    (["algorithm"], "Simplex", 'algorithm: must match ^[a-z][a-z0-9_-]{0,31}$, got "Simplex"'),
    (["status"], "complete", 'uncovered: must be empty when status is "complete", got 1 entries'),
    (["cost"], -3, "cost: must be >= 0, got -3"),
    (["covered"], 1.0, "covered: must be an integer, got real"),
    (["routes", 0, "distance"], "3", "routes[0].distance: must be an integer, got string"),
    (["routes", 0, "targets"], [1, 1], "routes[0].targets[1]: duplicate 1 (first at index 0)"),
    (["routes", 1, "uav"], 0, "routes[1].uav: must be >= 1, got 0"),
    (["routes", 2, "hover"], 0, 'routes[2]: unknown key "hover"'),
    (["stranded"], {}, "stranded: must be an array, got object"),
    (["mission"], "", "mission: must be a non-empty string of at most 63 bytes, got 0"),
    (["route"], [], 'plan: unknown key "route"'),
]


@pytest.mark.parametrize("path,value,message", PLAN_MUTATIONS, ids=lambda v: str(v)[:30])
def test_a_mutated_plan_is_rejected(cli_plan, path, value, message):
    assert schema.errors(cli_plan, "plan") == []
    assert schema.first_error(_mutated(cli_plan, path, value), "plan") == message


def test_a_flow_plan_needs_its_certificate(sva_bin):
    r = _run(sva_bin, "plan", "--algo", "flow", FIXTURES / "missions" / "hand_3_3.json")
    plan = json.loads(r.stdout)
    assert schema.errors(plan, "plan") == [] and _cli_stats_errors(plan) == []
    assert _cli_stats_errors(_mutated(plan, ["stats", "optimal"], KeyError)) == \
        ['stats: missing key "optimal"']
    assert schema.first_error(_mutated(plan, ["stats", "flow_incomplete"], 6), "plan") == \
        "stats.flow_incomplete: must be one of 0, 1, 2, 3, 4, 5, got 6"


def test_a_mutated_trace_record_is_rejected(sva_bin, tmp_path):
    r, trace = _plan_with_trace(sva_bin, tmp_path, FIXTURES / "missions" / "rand_25_1.json", "sva")
    assert r.returncode == 0, r.stderr
    rec = next(rec for rec in io.load_trace(str(trace))
               if len(rec["source_uavs"]) > 1 and any(c is None for row in rec["cost"] for c in row))
    assert schema.errors(rec, "trace") == []
    s, k = next((s, k) for s, row in enumerate(rec["cost"]) for k, c in enumerate(row) if c is None)
    cases = [
        (["pivots"], KeyError, 'record: missing key "pivots"'),
        (["cost"], rec["cost"][:-1], f"cost: must have one entry per source ({len(rec['supply'])}), "
                                     f"got {len(rec['supply']) - 1}"),
        (["flow", s, k], 0, f"flow[{s}][{k}]: must be null exactly where cost is, got 0"),
        (["supply", 0], 0, "supply[0]: must be >= 1, got 0"),
        (["algorithm"], "ga", 'algorithm: must be one of "sva", "hga", "ih", got "ga"'),
        (["dropped", 0], 0, "dropped[0]: must be a boolean, got integer"),
        (["cost", 0, 0], "x", "cost[0][0]: must be an integer, got string"),
    ]
    for path, value, message in cases:
        assert schema.first_error(_mutated(rec, path, value), "trace") == message
    # A bad line in a file is named by its number.
    lines = trace.read_text().splitlines()
    lines[1] = json.dumps(_mutated(json.loads(lines[1]), ["covered"], -1))
    trace.write_text("\n".join(lines) + "\n")
    with pytest.raises(io.InputError) as e:
        io.load_trace(str(trace))
    assert e.value.where == "2" and str(e.value) == "covered: must be >= 0, got -1"


def test_validate_command(tmp_path, sva_bin):
    mission = FIXTURES / "missions" / "hand_3_1.json"
    golden = FIXTURES / "golden" / "flow" / "hand_3_1.json"
    trace = tmp_path / "t.jsonl"
    assert _run(sva_bin, "plan", "--trace", trace, mission).returncode == 0
    r = sva_tools("validate", mission, golden, trace)
    assert r.returncode == 0, r.stderr
    assert r.stdout.splitlines() == [
        f"ok: {mission}: mission hand_3_1: 3 UAVs, 3 targets",
        f"ok: {golden}: plan of hand_3_1 by flow, complete",
        f"ok: {trace}: trace, {len(trace.read_text().splitlines())} records"]
    bad = FIXTURES / "invalid" / "unknown_key_uav.json"
    r = sva_tools("validate", mission, bad)
    assert r.returncode == 2 and r.stderr == f'sva-tools: error: {bad}: uavs[1]: unknown key "speed"\n'
    r = sva_tools("validate", "--kind", "plan", mission)
    assert r.returncode == 2 and r.stdout == ""
    assert r.stderr == f'sva-tools: error: {mission}: plan: unknown key "name"\n'


def test_bound_and_cache_entry_match_their_schemas(tmp_path):
    from sva_tools import cache, ref

    m = io.load_mission(str(FIXTURES / "missions" / "hand_3_3.json"))
    bound = ref.fuel_free_bound(m)
    assert schema.errors(bound, "bound") == []
    assert bound["complete_possible"] is True
    assert schema.first_error(dict(bound, lower_bound=None), "bound") == \
        "lower_bound: must be an integer, got null"
    assert schema.first_error(dict(bound, complete_possible=False), "bound") == \
        "lower_bound: must be null, got integer"
    c = cache.Cache(str(tmp_path))
    plan = io.load_plan(str(FIXTURES / "optima" / "proven_fuel100_s7_2.ref.json"))
    p = c.put(m, "ref", {"det_limit": 10}, {"plan": plan, "us": 5, "error": None}, cache.measurement())
    entry = json.loads(p.read_text())
    assert schema.errors(entry, "cache-entry") == []
    assert c.get(m, "ref", {"det_limit": 10}) is not None
    entry["result"]["plan"]["cost"] = -1
    p.write_text(json.dumps(entry))
    assert schema.first_error(entry, "cache-entry") == "result.plan.cost: must be >= 0, got -1"
    assert c.get(m, "ref", {"det_limit": 10}) is None  # a foreign entry is a miss


def test_plans_of_other_producers_match_the_plan_schema(cli_plan):
    """stats differ by producer; the plan schema types every known key and allows the rest."""
    lcm = _mutated(cli_plan, ["stats"], {"plan_id": 7, "solve_us": 41, "fleet_revision": 1,
                                         "mission_revision": 2})
    assert schema.errors(lcm, "plan") == []
    assert schema.first_error(_mutated(lcm, ["stats", "plan_id"], "7"), "plan") == \
        "stats.plan_id: must be an integer, got string"
    peer = _mutated(cli_plan, ["algorithm"], "peer")
    peer["stats"] = {"solve_us": 9, "solution_limit": 100, "stopped_by": "local_optimum"}
    assert schema.errors(peer, "plan") == []


def test_files_the_tools_write_match_their_schemas(tmp_path):
    """gen's missions, ih's plan and its --trace: written by the tools, read back through
    the schemas (a drift between writer and schema fails here)."""
    r = sva_tools("gen", "--count", "3", "--targets", "12", "--hover", "2", "--seed", "5",
                  "-o", tmp_path / "gen")
    assert r.returncode == 0, r.stderr
    generated = sorted((tmp_path / "gen").glob("*.json"))
    assert len(generated) == 3
    for p in generated:
        assert schema.errors(_load(p), "mission") == [], p.name
    trace, plan = tmp_path / "ih.jsonl", tmp_path / "ih.json"
    r = sva_tools("ih", generated[0], "--trace", trace, "-o", plan)
    assert r.returncode == 0, r.stderr
    assert schema.errors(_load(plan), "plan") == []
    records = io.load_trace(str(trace))
    assert records and all(rec["algorithm"] == "ih" for rec in records)
    assert len(records) == _load(plan)["stats"]["transport_problems"]


CITATION = re.compile(r"SPEC(?:\.md)?\s+(?:section\s+|§\s*)?(\d+)")
SKIP_DIRS = {".git", ".venv", "build", "__pycache__", "node_modules"}


def test_spec_citations_name_sections_that_exist():
    """Code and docs cite docs/SPEC.md by section number ("SPEC section 3", "SPEC §4")."""
    spec = (REPO / "docs" / "SPEC.md").read_text(encoding="utf-8")
    sections = {int(n) for n in re.findall(r"^## (\d+)\. ", spec, re.M)}
    assert sections == set(range(1, len(sections) + 1)) and len(sections) >= 4
    cited, bad = 0, []
    for root, dirs, files in os.walk(REPO):
        dirs[:] = [d for d in dirs if d not in SKIP_DIRS and not d.startswith("build")]
        for name in files:
            path = Path(root) / name
            if path.suffix not in (".png", ".jar"):
                cited += _check_citations(path, sections, bad)
    assert cited > 50 and bad == []


def _check_citations(path, sections, bad):
    """Counts the SPEC citations of one file; appends those of no section to bad."""
    try:
        text = path.read_text(encoding="utf-8")
    except UnicodeDecodeError:
        return 0
    found = list(CITATION.finditer(text))
    bad.extend(f"{path.relative_to(REPO)}: {m.group(0)}" for m in found if int(m.group(1)) not in sections)
    return len(found)


def test_input_cap_is_the_clis(tmp_path, sva_bin):
    big = tmp_path / "big.json"
    big.write_bytes(b"{" + b" " * io.MAX_INPUT_BYTES + b"}")
    with pytest.raises(io.InputError) as e:
        io.load_mission(str(big))
    assert str(e.value) == "input exceeds 16777216 bytes"
    r = _run(sva_bin, "validate", big)
    assert r.returncode == 2 and r.stderr == f"sva: error: {big}: input exceeds 16777216 bytes\n"


def test_spec_examples_match_the_schemas():
    """docs/SPEC.md's mission, plan and trace examples are valid, and the plan is right."""
    from sva_tools import check

    blocks = re.findall(r"```json\n(.*?)```", (REPO / "docs" / "SPEC.md").read_text(), re.S)
    mission, plan, record, live = (json.loads(b.replace("\n ", " ")) for b in blocks)
    assert schema.errors(mission, "mission") == [] and schema.errors(plan, "plan") == []
    assert schema.errors(live["mission"], "mission") == []  # the live mission's (section 12.5)
    assert schema.errors(record, "trace") == []
    assert check.check_plan(io.mission_from_json(mission), io.plan_from_json(plan)) == []
