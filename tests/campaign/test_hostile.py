"""`sva-tools campaign` against hostile specs and damaged stores (docs/campaigns.md,
"Limits and refusals"; docs/security.md).

A spec is refused before any work, in one line `sva-tools: error: campaign: SPEC: PATH:
RULE, got VALUE` and exit status 2: a billion laughs of about 1 KB and a 1 MB hostile
spec within 1 s of CPU and 200 MB of peak resident memory (getrusage of the refusing
process, run under a 1 GiB address-space limit so that a regression fails instead of
eating the machine), NaN and infinities, names that leave the campaign folder, duplicate
keys, deep nesting, bad UTF-8, sizes the core refuses and absurd totals. A damaged
Parquet part (empty, truncated, another schema) is named in a warning and skipped, and
`--repair` recomputes its tasks: the report then equals a clean run's.

Run as a script, it prints the measured figures of docs/campaigns.md:
    nice .venv/bin/python tests/campaign/test_hostile.py
"""
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pyarrow as pa
import pyarrow.parquet as pq
import pytest

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "tools"))

from sva_tools.campaign.spec import SpecError, first_tasks, load, parse, schema, validate  # noqa: E402

ENV = dict(os.environ, PYTHONPATH=str(REPO / "tools") + os.pathsep + os.environ.get("PYTHONPATH", ""))
SVA_BIN = os.environ.get("SVA_BIN", str(REPO / "build" / "bin" / "sva"))
MAX_CPU_S = 1.0
MAX_RSS_MB = 200
BASE = """name: tiny
kind: plan
sets:
  - {targets: 5, uavs: 2, width: [10, 20], need: 1, fuel: 100, hover: 2}
count: 1
algorithms: [flow, sva]
"""

# Runs argv under RLIMIT_AS of 1 GiB and prints its exit status, output, wall time and
# getrusage(RUSAGE_CHILDREN): the wrapper's only child is the command.
WRAPPER = r"""
import json, resource, subprocess, sys, time
def bounded():
    resource.setrlimit(resource.RLIMIT_AS, (1 << 30, 1 << 30))
t0 = time.perf_counter()
try:
    r = subprocess.run(sys.argv[1:], capture_output=True, text=True, timeout=30, preexec_fn=bounded)
    rc, out, err = r.returncode, r.stdout, r.stderr
except subprocess.TimeoutExpired:
    rc, out, err = "timeout after 30 s", "", ""
wall = time.perf_counter() - t0
u = resource.getrusage(resource.RUSAGE_CHILDREN)
print(json.dumps({"rc": rc, "stdout": out, "stderr": err, "wall_s": wall, "cpu_s": u.ru_utime + u.ru_stime,
                  "rss_mb": u.ru_maxrss / 1024}))
"""


def measured(*args):
    """`sva-tools campaign ARGS` in its own process: exit status, output, wall and CPU
    seconds, peak resident MB."""
    cmd = [sys.executable, "-m", "sva_tools", "campaign", "--no-progress", *map(str, args)]
    r = subprocess.run([sys.executable, "-c", WRAPPER, *cmd], capture_output=True, text=True, env=ENV,
                       timeout=120)
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


def billion_laughs(size=1024):
    """A spec of about `size` bytes whose aliases expand to 10^10 strings."""
    lines = ["lol0: &lol0 [" + ", ".join(["lolololololol"] * 10) + "]"]
    for i in range(1, 10):
        lines.append(f"lol{i}: &lol{i} [" + ", ".join([f"*lol{i - 1}"] * 10) + "]")
    text = "\n".join(lines) + "\n" + BASE.replace("count: 1\n", "count: 1\nsets: *lol9\n")
    return text + "#" * max(0, size - len(text) - 1) + "\n"


def one_mb_hostile():
    """1,000,000 bytes: the billion laughs, then a million more aliases of it."""
    text = billion_laughs()
    i = 0
    while len(text) < 1_000_000:
        text += f"more{i}: [" + ", ".join(["*lol9"] * 10) + "]\n"
        i += 1
    return text[:999_999] + "\n"


# Hostile specs at the byte limit (64 KiB): the most work the loader may see.
def nodes_flood():
    return "algorithms: [" + ",".join(["1"] * 32000) + "]\n"


def nesting_flood():
    return "name: " + "[" * 60000 + "\n"


HOSTILE = {
    "billion_laughs_1kb": (billion_laughs, "lol0: YAML anchors are not allowed, got &lol0 at line 1, column 7"),
    "hostile_1mb": (one_mb_hostile, "spec: must be at most 65536 bytes (x-sva-max-bytes), got 1000000"),
    "nodes_64kb": (nodes_flood, "spec: must have at most 4096 YAML nodes (x-sva-max-nodes), got more at line 1, "),
    "nesting_64kb": (nesting_flood, "name[0][0][0][0][0][0][0]: must be nested at most 8 deep (x-sva-max-depth), "
                                    "got deeper at line 1, column 14"),
}


@pytest.mark.parametrize("name", list(HOSTILE))
def test_hostile_spec_is_refused_within_a_second_and_200_mb(tmp_path, name):
    make, message = HOSTILE[name]
    path = tmp_path / f"{name}.yaml"
    path.write_text(make())
    size = path.stat().st_size
    assert (900 <= size <= 1100) if name.endswith("1kb") else (size == 1_000_000 if name.endswith("1mb")
                                                                 else 60_000 <= size <= 65_536)
    m = measured(path, "--out", tmp_path / "out")
    assert m["rc"] == 2, m
    assert m["stderr"].startswith(f"sva-tools: error: campaign: {path}: {message}") and m["stderr"].count("\n") == 1, m
    assert m["stdout"] == "" and not (tmp_path / "out").exists()
    assert m["cpu_s"] < MAX_CPU_S, m
    assert m["rss_mb"] < MAX_RSS_MB, m


def refused(text):
    """The SpecError message of a spec's text or bytes."""
    with pytest.raises(SpecError) as e:
        validate(parse(text.encode("utf-8") if isinstance(text, str) else text))
    return str(e.value)


@pytest.mark.parametrize("text, message", [
    (BASE + "ref: {time_limit: .nan}\n", "ref.time_limit: must be a finite number, got .nan"),
    (BASE + "ref: {det_limit: .inf}\n", "ref.det_limit: must be a finite number, got .inf"),
    (BASE + "ref: {det_limit: -.Inf}\n", "ref.det_limit: must be a finite number, got -.inf"),
    (BASE + "ref: {det_limit: 1.0e+999}\n", "ref.det_limit: must be a finite number, got .inf"),
    (BASE + "ref: {det_limit: 1e999}\n", "ref.det_limit: must be number, got string"),  # YAML 1.1: not a float
    (BASE.replace("fuel: 100", "fuel: .NaN"), "sets[0].fuel: must be a finite number, got .nan"),
])
def test_nan_and_infinities_are_refused(text, message):
    assert refused(text) == message


RULE = 'must be a folder name: 1 to 64 of A-Z a-z 0-9 _ . -, not starting with "."'


@pytest.mark.parametrize("name, shown", [
    ("'..'", '".."'), ("'.'", '"."'), ("/etc/cron.d", '"/etc/cron.d"'), ("../../x", '"../../x"'),
    ("a/b", '"a/b"'), ("'a\\b'", '"a\\\\b"'), (".hidden", '".hidden"'), ('"t\\n"', '"t\\n"'), ("''", '""'),
])
def test_names_that_leave_the_campaign_folder_are_refused(name, shown):
    assert refused(BASE.replace("name: tiny", f"name: {name}")) == f"name: {RULE}, got {shown}"


def test_cli_refuses_a_dot_dot_name_in_one_line(tmp_path):
    p = tmp_path / "dots.yaml"
    p.write_text(BASE.replace("name: tiny", "name: '..'"))
    m = measured(p)
    assert m["rc"] == 2 and m["stdout"] == ""
    assert m["stderr"] == f'sva-tools: error: campaign: {p}: name: {RULE}, got ".."\n'


@pytest.mark.parametrize("text, message", [
    (BASE + "count: 2\n", 'count: keys must be unique, got "count" again at line 7, column 1 '
                          '(first at line 5, column 1)'),
    (BASE.replace("need: 1,", "need: 1, need: 2,"),
     'sets[0].need: keys must be unique, got "need" again at line 4, column 53 (first at line 4, column 44)'),
    (BASE + "sets: []\n", 'sets: keys must be unique, got "sets" again at line 7, column 1 '
                          '(first at line 3, column 1)'),
    (BASE + "<<: {count: 2}\n", "spec: YAML merge keys are not allowed, got << at line 7, column 1"),
    (BASE + "1: 2\n", "spec: keys must be strings, got 1 at line 7, column 1"),
    (BASE + "? [a]\n: 2\n", "spec: keys must be strings, got a list or mapping at line 7, column 3"),
])
def test_duplicate_and_odd_keys_are_refused(text, message):
    assert refused(text) == message


@pytest.mark.parametrize("text, message", [
    (BASE + "x: " + "[" * 9 + "]" * 9 + "\n",
     "x[0][0][0][0][0][0][0]: must be nested at most 8 deep (x-sva-max-depth), got deeper at line 7, column 11"),
    (BASE + "x:\n" + "".join(" " * i + "- \n" for i in range(1, 10)),
     "x[0][0][0][0][0][0][0]: must be nested at most 8 deep (x-sva-max-depth), got deeper at line 15, column 9"),
    (b"name: t\xc3\x28\n", "spec: must be UTF-8 text, got byte 0xc3 at line 1, column 8"),
    (BASE.encode() + b"\xff\xfe", "spec: must be UTF-8 text, got byte 0xff at line 7, column 1"),
    (BASE.encode().replace(b"tiny", b"ti\x00ny"), "spec: must be printable text, got character U+0000 at line 1, "
                                                  "column 9"),
    (BASE + "seeds: {first: " + "9" * 2000 + "}\n",
     "seeds.first: must be at most 1024 characters (x-sva-max-scalar-chars), got 2000 at line 7, column 16"),
    (BASE.replace("name: tiny", "name: 2024-01-01"), "name: must be a string, number, boolean or null (quote a "
                                                      "string that looks like another YAML type), got YAML type "
                                                      "timestamp at line 1, column 7"),
    (BASE + "x: !!binary aGVsbG8=\n", "x: must be a string, number, boolean or null (quote a string that looks "
                                      "like another YAML type), got YAML type binary at line 7, column 4"),
    (BASE + "x: !!int abc\n", 'x: must be a YAML int, got "abc" at line 7, column 4'),
    (BASE + "x: !!bool maybe\n", 'x: must be a YAML bool, got "maybe" at line 7, column 4'),
    (BASE + "x: !!set {a: null}\n", "x: must be a list or a mapping, got YAML type tag:yaml.org,2002:set at "
                                    "line 7, column 4"),
    (BASE + "x: !!python/object:os.system {}\n", "x: must be a list or a mapping, got YAML type "
                                                 "tag:yaml.org,2002:python/object:os.system at line 7, column 4"),
])
def test_deep_nesting_bad_text_and_foreign_types_are_refused(text, message):
    assert refused(text) == message


def core_limits():
    """SVA_MAX_* of the C CLI's build (`sva --version`)."""
    out = subprocess.run([SVA_BIN, "--version"], capture_output=True, text=True, check=True).stdout
    return {k: int(v) for k, v in re.findall(r"(SVA_MAX_\w+) (\d+)", out)}


def test_schema_bounds_are_the_cores():
    limits = core_limits()
    sets = schema()["$defs"]["set"]["properties"]
    assert sets["targets"]["maximum"] == limits["SVA_MAX_TARGETS"] and sets["targets"]["x-sva-maximum-name"] == \
        "SVA_MAX_TARGETS"
    assert sets["uavs"]["maximum"] == limits["SVA_MAX_UAVS"]
    assert schema()["$defs"]["need"]["oneOf"][0]["maximum"] == limits["SVA_MAX_UAVS"]


def test_a_set_at_the_cores_bounds_is_accepted_and_its_mission_taken_by_the_core(tmp_path):
    limits = core_limits()
    t, u = limits["SVA_MAX_TARGETS"], limits["SVA_MAX_UAVS"]
    spec = validate(parse(BASE.replace("targets: 5, uavs: 2", f"targets: {t}, uavs: {u}")
                              .replace("need: 1", f"need: [1, {u}]").encode()))
    task = first_tasks(spec, "bounds")[0]
    (tmp_path / "m.json").write_text(task["mission"])
    r = subprocess.run([SVA_BIN, "validate", str(tmp_path / "m.json")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


@pytest.mark.parametrize("old, new, message", [
    ("targets: 5,", "targets: 257,", "sets[0].targets: must be <= 256 (SVA_MAX_TARGETS), got 257"),
    ("uavs: 2,", "uavs: 65,", "sets[0].uavs: must be <= 64 (SVA_MAX_UAVS), got 65"),
    ("need: 1,", "need: 65,", "sets[0].need: must be <= 64 (SVA_MAX_UAVS), got 65"),
    ("need: 1,", "need: [1, 65],", "sets[0].need[1]: must be <= 64 (SVA_MAX_UAVS), got 65"),
    ("fuel: 100,", "fuel: 1000000001,", "sets[0].fuel: must be <= 1000000000 (SVA_MAX_FUEL), got 1000000001"),
    ("hover: 2}", "hover: 1000001}", "sets[0].hover: must be <= 1000000 (SVA_MAX_HOVER_FUEL), got 1000001"),
    ("hover: 2}", "hover: 2, ticks_per_cell: 1001}",
     "sets[0].ticks_per_cell: must be <= 1000 (SVA_MAX_TICKS_PER_CELL), got 1001"),
    ("count: 1\n", "count: 1\nflow_work: 2000001\n", "flow_work: must be <= 2000000 (SVA_FLOW_MAX_WORK), got 2000001"),
    ("count: 1\n", "count: 1\nflow_work: 999\n", "flow_work: must be >= 1000, got 999"),
    ("kind: plan", "kind: live\npenalties: [1000001]",
     "penalties[0]: must be <= 1000000 (SVA_MAX_CHANGE_PENALTY), got 1000001"),
    ("targets: 5,", "targets: 5.0,", "sets[0].targets: must be integer, got real"),
    ("count: 1\n", "count: 100001\n", "count: must be <= 100000 (missions or scenarios per set and seed), got 100001"),
    ("count: 1\n", "count: 100000\nseeds: {first: 1, count: 2}\n",
     "spec: must name at most 100000 missions or scenarios in all (each set's count x seeds.count, summed), "
     "got 200000"),
    ("count: 1\n", "count: 100000\nseeds: {first: 1, count: 100000}\n",
     "spec: must name at most 100000 missions or scenarios in all (each set's count x seeds.count, summed), "
     "got 10000000000"),
    ("targets: 5,", "targets: 256,", None),
])
def test_sizes_the_core_refuses_and_absurd_totals_are_refused_with_the_field(old, new, message):
    text = BASE.replace(old, new)
    if message is None:  # 256 targets x 10,001 missions: one past the generated-targets limit
        assert validate(parse(text.replace("count: 1\n", "count: 10000\n").encode()))["count"] == 10000
        text = text.replace("count: 1\n", "count: 10001\n")
        message = ("spec: must generate at most 2560000 targets in all (each set's targets x count x "
                   "seeds.count, summed), got 2560256")
    assert refused(text) == message


@pytest.mark.parametrize("text, message", [
    (BASE + "---\n" + BASE, "spec: must be YAML, got but found another document at line 7, column 1"),
    (BASE + "seeds: [1\n", "spec: must be YAML, got expected ',' or ']', but got '<stream end>' at line 8, column 1"),
    (BASE.replace("need: 1,", "need: 1, label: 5x2,").replace("count:", "  - {targets: 5, uavs: 2}\ncount:"),
     "sets[1].label: must be unique (give one of them a distinct label), got \"5x2\" again (sets[0]'s)"),
])
def test_yaml_syntax_and_label_clashes_are_refused_in_the_same_form(text, message):
    assert refused(text) == message


def test_absurd_spec_is_refused_before_any_work(tmp_path):
    """64 sets of 100,000 missions and 100,000 seeds: refused by the totals before a
    mission is generated or a folder made."""
    p = tmp_path / "absurd.yaml"
    p.write_text(BASE.replace("sets:\n", "sets:\n" + "".join(f"  - {{targets: 256, uavs: 64, label: s{i}}}\n"
                                                                for i in range(63)))
                 .replace("count: 1\n", "count: 100000\nseeds: {first: 1, count: 100000}\n"))
    m = measured(p, "--out", tmp_path / "out")
    assert m["rc"] == 2 and m["cpu_s"] < MAX_CPU_S and m["rss_mb"] < MAX_RSS_MB, m
    assert m["stderr"] == (f"sva-tools: error: campaign: {p}: spec: must name at most 100000 missions or "
                           "scenarios in all (each set's count x seeds.count, summed), got 640000000000\n")
    assert not (tmp_path / "out").exists()


def test_a_mission_gen_cannot_make_is_refused_naming_the_set(monkeypatch, tmp_path):
    from sva_tools import gen

    def cannot(*args, **kw):
        raise ValueError("no free cell left on the 4-cell-wide grid")

    spec = validate(parse(BASE.encode()))
    monkeypatch.setattr(gen, "generate", cannot)
    with pytest.raises(SpecError) as e:
        first_tasks(spec, "x")
    assert str(e.value) == ("sets[0]: must be settings gen can make missions from, got for seed 1, mission 0: "
                            "no free cell left on the 4-cell-wide grid")


def test_a_live_grid_too_small_for_its_cells_is_refused():
    text = BASE.replace("kind: plan", "kind: live").replace("hover: 2}", "hover: 2, max_coord: 3, events: 11}")
    assert refused(text) == ("sets[0].max_coord: kind live needs (max_coord + 1)^2 >= targets + events + 1 (17) "
                             "free cells, got 16")


# Damaged Parquet parts and --repair.

SMALL = BASE.replace("count: 1\n", "count: 3\n")
TIMES = ("solve p50", "solve p95")


def campaign(*args):
    r = subprocess.run([sys.executable, "-m", "sva_tools", "campaign", "--no-progress", "--workers", "1",
                        *map(str, args)], capture_output=True, text=True, env=ENV, timeout=240)
    return r


def table_without_times(stdout):
    """The summary table, timing columns left out (recomputed plans have other times)."""
    rows = [[c.strip() for c in ln.strip("|").split("|")] for ln in stdout.splitlines() if ln.startswith("| ")]
    keep = [i for i, c in enumerate(rows[0]) if c not in TIMES]
    return [[r[i] for i in keep] for r in rows]


def metrics_without_times(out):
    return sorted((r["key"], r["covered"], r["cost"], r["error"])
                  for r in pq.read_table(out / "metrics.parquet").to_pylist())


def test_damaged_parts_are_named_skipped_and_repaired(tmp_path):
    spec = tmp_path / "small.yaml"
    spec.write_text(SMALL)
    clean = tmp_path / "clean"
    r = campaign(spec, "--out", clean, "--flush-rows", "1", "--no-report")
    assert r.returncode == 0, r.stderr
    parts = sorted((clean / "results").glob("part-*.parquet"))
    assert len(parts) == 6  # 3 missions x (flow, sva), one row per part
    damaged = tmp_path / "damaged"
    shutil.copytree(clean, damaged)
    names = [p.name for p in parts]
    (damaged / "results" / names[0]).write_bytes(b"")  # empty
    whole = (damaged / "results" / names[1]).read_bytes()
    (damaged / "results" / names[1]).write_bytes(whole[:len(whole) // 2])  # truncated
    pq.write_table(pa.table({"covered": [1]}), damaged / "results" / names[2])  # another schema
    before = sorted((damaged / "results").iterdir())

    r = campaign(spec, "--out", damaged, "--no-report")
    assert r.returncode == 1, r.stderr
    lines = r.stderr.splitlines()
    reasons = {names[0]: "empty file", names[1]: "unreadable: ", names[2]: 'foreign schema: no column "key"'}
    for name, reason in reasons.items():
        path = damaged / "results" / name
        assert any(ln.startswith(f"sva-tools: warning: campaign: {path}: damaged part ({reason}") and
                   ln.endswith("skipped; --repair moves it to damaged/ and computes its tasks again")
                   for ln in lines), (name, lines)
    assert lines[-1] == (f"sva-tools: warning: campaign: 3 damaged part file(s) in {damaged / 'results'} skipped, "
                         "3 task(s) not computed; run again with --repair")
    assert len(lines) == 4 and "Traceback" not in r.stderr
    assert "3 already stored, 0 computed, 0 failed; 3 not computed (damaged part files: --repair);" in r.stdout
    assert sorted((damaged / "results").iterdir()) == before  # nothing computed, nothing written

    r = campaign(spec, "--out", damaged, "--no-report", "--repair")
    assert r.returncode == 0, r.stderr
    assert "3 already stored, 3 computed, 0 failed;" in r.stdout
    assert sorted(p.name for p in (damaged / "damaged").iterdir()) == names[:3]
    for name in names[:3]:
        assert (f"sva-tools: warning: campaign: {damaged / 'results' / name}: moved to "
                f"{damaged / 'damaged' / name}; its tasks were computed again") in r.stderr.splitlines()
    repaired = r.stdout

    r = campaign(spec, "--out", clean, "--no-report")  # the clean store's report, read again
    assert r.returncode == 0 and r.stderr == "", r.stderr
    assert table_without_times(repaired) == table_without_times(r.stdout)
    assert metrics_without_times(damaged) == metrics_without_times(clean)

    r = campaign(spec, "--out", damaged, "--no-report")  # resume: everything stored, nothing to say
    assert r.returncode == 0 and r.stderr == "", r.stderr
    assert "6 already stored, 0 computed, 0 failed;" in r.stdout


if __name__ == "__main__":
    import tempfile
    import time
    with tempfile.TemporaryDirectory() as d:
        print("| spec | bytes | refused with | sva-tools campaign: wall, CPU, peak RSS | spec.load() alone |\n"
              "|---|---|---|---|---|")
        for name, (make, message) in HOSTILE.items():
            path = Path(d) / f"{name}.yaml"
            path.write_text(make())
            m = measured(path, "--out", Path(d) / "out")
            assert m["rc"] == 2, m
            best = float("inf")
            for _ in range(5):  # the refusal itself, in this process (imports done)
                t0 = time.perf_counter()
                try:
                    load(str(path))
                except SpecError:
                    best = min(best, time.perf_counter() - t0)
            print(f"| {name} | {path.stat().st_size:,} | `{message.split(', got')[0]}` | {m['wall_s']:.2f} s, "
                  f"{m['cpu_s']:.2f} s, {m['rss_mb']:.0f} MB | {best * 1000:.1f} ms |")
