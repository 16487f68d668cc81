"""tools/bench/large_profile.py --quick against the large-profile CLI ($SVA_LARGE_BIN): every
plan checked and its figures printed; a CLI of another profile is refused, and a plan the
checker rejects is a failure (exit status 1)."""
import os
import re
import subprocess
import sys

import pytest
from conftest import REPO

SCRIPT = REPO / "tools" / "bench" / "large_profile.py"


@pytest.fixture
def sva_large():
    path = os.environ.get("SVA_LARGE_BIN")
    if not path or not os.path.isfile(path):
        pytest.fail("SVA_LARGE_BIN must name the CLI built with the large profile (ctest sets it)")
    return path


def run(*args, env=None):
    return subprocess.run([sys.executable, str(SCRIPT), *map(str, args)], capture_output=True, text=True,
                          timeout=240, env=env)


def test_quick_plans_are_checked_and_reported(sva_large, tmp_path):
    # --results into a scratch root (SVA_RESULTS_ROOT), not the repository's docs
    r = run("--quick", "--results", "--sva", sva_large, env={**os.environ, "SVA_RESULTS_ROOT": str(tmp_path)})
    assert r.returncode == 0, r.stdout + r.stderr
    rows = [line for line in r.stdout.splitlines() if line.startswith("| 300x80")]
    names = []
    for line in rows:
        cells = [c.strip() for c in line.split("|")[1:-1]]
        name, missions, failures, covered = cells[0], cells[1], cells[2], cells[3]
        names.append(name)
        assert missions == "1" and failures == "0", line
        assert int(covered.split()[0]) > 0, line
        assert re.fullmatch(r"\d+ ms / \d+ ms", cells[5]), line  # flow's time
        gap = re.fullmatch(r"(\d+\.\d\d) % / (\d+\.\d\d) % \(bounds: 1\)", cells[7])
        assert gap and float(gap[1]) >= 0.0, line  # a certified gap from flow's own bound
    assert names == ["300x80", "300x80_tight"], r.stdout
    assert "gen --targets 300 --uavs 80 --need 1 --fuel 80" in r.stdout
    fragment = (tmp_path / "docs" / "results" / "large.md").read_text()
    assert ("Command: `nice -n 15 .venv/bin/python tools/bench/large_profile.py --results --sets "
            "300x80,300x80_tight --missions 1`") in fragment
    assert all(line in fragment for line in rows), fragment
    page = (tmp_path / "docs" / "results.md").read_text()
    assert "## flow at 1,000 targets x 100 UAVs (the large profile)" in page


def test_refuses_a_cli_of_another_profile():
    sva = os.environ.get("SVA_BIN") or str(REPO / "build" / "bin" / "sva")
    if not os.path.isfile(sva):
        pytest.fail("SVA_BIN must name the default CLI (ctest sets it)")
    r = run("--quick", "--sva", sva)
    assert r.returncode != 0 and "is not built with the large profile" in r.stderr, r.stderr


def test_a_plan_the_checker_rejects_is_a_failure(sva_large, tmp_path):
    # The real CLI, with one covered target moved from its route to no route at all.
    fake = tmp_path / "sva"
    fake.write_text(f"""#!{sys.executable}
import json, subprocess, sys
out = subprocess.run([{sva_large!r}] + sys.argv[1:], capture_output=True, text=True)
if sys.argv[1:2] != ["plan"]:
    sys.stdout.write(out.stdout)
    sys.exit(out.returncode)
plan = json.loads(out.stdout)
route = next(r for r in plan["routes"] if r["targets"])
route["targets"].pop()
print(json.dumps(plan))
""")
    fake.chmod(0o755)
    r = run("--sets", "300x80", "--missions", 1, "--sva", fake)
    assert r.returncode == 1, r.stdout + r.stderr
    assert "failures 1" in r.stdout and "failure: checker:" in r.stdout, r.stdout
