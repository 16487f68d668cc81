"""Bad mission and plan files get SPEC 4's treatment: exit 2, one line naming the field."""
import copy
import os
import json

import pytest
from conftest import sva_tools, write

GOOD = {"name": "m", "depot": {"x": 0, "y": 0},
        "uavs": [{"id": 1, "x": 0, "y": 0, "fuel": 60}],
        "targets": [{"id": 1, "x": 5, "y": 7, "start": 12, "end": 20, "need": 1}]}


def bad(path, value):
    d = copy.deepcopy(GOOD)
    *head, last = path
    node = d
    for k in head:
        node = node[k]
    if value is KeyError:
        del node[last]
    else:
        node[last] = value
    return d


CASES = [
    (bad(["uavs", 0, "fuel"], KeyError), 'uavs[0]: missing key "fuel"'),
    (bad(["uavs", 0, "speed"], 3), 'uavs[0]: unknown key "speed"'),
    (bad(["depot", "x"], "0"), "depot.x: must be an integer, got string"),
    (bad(["targets", 0, "need"], True), "targets[0].need: must be an integer, got boolean"),
    (bad(["targets", 0, "need"], 0), "targets[0].need: must be >= 1, got 0"),
    (bad(["targets", 0, "end"], 12), "targets[0].end: must be > start (12), got 12"),
    (bad(["uavs", 0, "fuel"], -1), "uavs[0].fuel: must be >= 0, got -1"),
    (bad(["targets", 0, "x"], 32768), "targets[0].x: must be <= 32767, got 32768"),
    (bad(["depot", "y"], -32769), "depot.y: must be >= -32768, got -32769"),
    (bad(["ticks_per_cell"], 0), "ticks_per_cell: must be >= 1, got 0"),
    (bad(["overlap_percent"], 101), "overlap_percent: must be <= 100, got 101"),
    (bad(["uavs"], [{"id": i + 1, "x": 0, "y": 0, "fuel": 1} for i in range(65)]),
     "uavs: 65 entries exceed SVA_MAX_UAVS (64)"),
    (bad(["uavs"], [{"id": 1, "x": 0, "y": 0, "fuel": 1}, {"id": 1, "x": 0, "y": 0, "fuel": 1}]),
     "uavs[1].id: duplicate id 1 (first at index 0)"),
    (bad(["targets"], {"id": 1}), "targets: must be an array, got object"),
    (bad(["name"], KeyError), 'mission: missing key "name"'),
]


@pytest.mark.parametrize("doc,message", CASES, ids=[c[1].split(":")[0] for c in CASES])
def test_bad_mission(tmp_path, doc, message):
    mp = write(tmp_path, "m.json", doc)
    r = sva_tools("ref", "--bound", mp)
    assert r.returncode == 2
    assert message in r.stderr, r.stderr
    assert r.stdout == ""  # never a plan for a rejected mission
    assert len(r.stderr.strip().splitlines()) == 1


def test_not_json_and_duplicate_keys(tmp_path):
    p = tmp_path / "m.json"
    p.write_text("{\"name\": \"m\",")
    r = sva_tools("ih", str(p))
    assert r.returncode == 2 and f"{p}:1:14: invalid JSON: " in r.stderr, r.stderr
    p.write_text('{"name": "m", "name": "n"}')
    r = sva_tools("ih", str(p))
    assert r.returncode == 2 and 'invalid JSON: duplicate object key "name"' in r.stderr
    r = sva_tools("ih", str(tmp_path / "absent.json"))
    assert r.returncode == 2 and "absent.json: cannot open: No such file" in r.stderr


@pytest.mark.parametrize("cmd", [["check", "M", "M"], ["ref", "M"], ["ref", "--bound", "M"],
                                 ["ih", "M"], ["peer", "M"], ["plot", "M", "M"]])
def test_every_subcommand_rejects(tmp_path, cmd):
    mp = write(tmp_path, "m.json", bad(["targets", 0, "need"], 0))
    r = sva_tools(*[mp if a == "M" else a for a in cmd])
    assert r.returncode == 2 and "targets[0].need" in r.stderr and r.stdout == ""


PLAN = {"mission": "m", "algorithm": "sva", "status": "complete", "covered": 1,
        "uncovered": [], "cost": 24, "routes": [{"uav": 1, "targets": [1], "distance": 24,
                                                  "fuel_used": 24}]}


@pytest.mark.parametrize("key,value,message", [
    ("status", "done", 'status: must be one of "complete", "partial", got "done"'),
    ("extra", 1, 'plan: unknown key "extra"'),
    ("routes", [{"uav": 1, "targets": [1], "distance": 24}], 'routes[0]: missing key "fuel_used"'),
    ("cost", -1, "cost: must be >= 0, got -1"),
    ("stranded", "1", "stranded: must be an array, got string"),
])
def test_bad_plan(tmp_path, key, value, message):
    mp = write(tmp_path, "m.json", GOOD)
    doc = dict(PLAN)
    doc[key] = value
    r = sva_tools("check", mp, write(tmp_path, "p.json", doc))
    assert r.returncode == 2 and message in r.stderr, r.stderr


def test_good_files_accepted(tmp_path):
    r = sva_tools("check", write(tmp_path, "m.json", GOOD), write(tmp_path, "p.json", PLAN))
    assert r.returncode == 0, r.stdout + r.stderr


def test_highspy_is_neither_pinned_nor_imported():
    """IH uses the HiGHS inside ortools; the highspy wheel ships a clashing
    libhighs.so.1 (docs/tools.md), so it must not come back."""
    import importlib
    import pkgutil
    import sys
    from pathlib import Path

    import sva_tools

    repo = Path(__file__).resolve().parents[2]
    assert "highspy" not in (repo / "requirements.txt").read_text()
    assert "highspy" not in (repo / "tools" / "pyproject.toml").read_text()
    names = [m.name for m in pkgutil.walk_packages(sva_tools.__path__, "sva_tools.")
             if not m.name.endswith("__main__")]
    assert "sva_tools.solvers" in names and "sva_tools.ih" in names
    for name in names:
        importlib.import_module(name)
    assert "highspy" not in sys.modules


HOSTILE = "x\n\x1b[31mforged"
HOSTILE_SHOWN = "x\\n\\x1b[31mforged"


def test_shown_escapes_like_the_c_helper():
    from sva_tools.text import shown
    assert shown("plain \\ é €") == "plain \\ é €"
    assert shown("a\nb\rc\td\x1b[2J\x7f") == "a\\nb\\rc\\td\\x1b[2J\\x7f"
    assert shown("\u009b31m") == "\\xc2\\x9b31m"  # C1 CSI, as its UTF-8 bytes
    assert shown(os.fsdecode(b"bad\xff")) == "bad\\xff"  # a byte that was not UTF-8
    assert shown(shown(HOSTILE)) == shown(HOSTILE) == HOSTILE_SHOWN


def test_hostile_file_and_mission_names_are_escaped(tmp_path):
    r = sva_tools("ih", str(tmp_path / HOSTILE))
    assert r.returncode == 2 and "\x1b" not in r.stderr
    assert r.stderr.splitlines() == [f"sva-tools: error: {tmp_path}/{HOSTILE_SHOWN}: cannot read file: "
                                     "No such file or directory"]
    # a bad mission whose file name is hostile: one line, escaped
    mp = write(tmp_path, HOSTILE + ".json", bad(["targets", 0, "need"], 0))
    r = sva_tools("ref", "--bound", mp)
    assert r.returncode == 2 and "\x1b" not in r.stderr and len(r.stderr.splitlines()) == 1
    assert r.stderr.startswith(f"sva-tools: error: {tmp_path}/{HOSTILE_SHOWN}.json: ")
    # a usage error quoting the argument (argparse)
    r = sva_tools("gen", "--targets", HOSTILE)
    assert r.returncode == 2 and "\x1b" not in r.stderr and HOSTILE_SHOWN in r.stderr
