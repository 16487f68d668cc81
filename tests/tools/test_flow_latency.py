"""tools/bench/flow_latency.py: --quick against the real CLI (every plan checked, its
figures printed and written as a results fragment); a plan the checker rejects, work that
changes between runs and an unknown set are failures."""
import os
import re
import subprocess
import sys

from conftest import REPO

SCRIPT = REPO / "tools" / "bench" / "flow_latency.py"


def run(*args, env=None):
    return subprocess.run([sys.executable, str(SCRIPT), *map(str, args)], capture_output=True, text=True,
                          timeout=240, env=env)


def test_quick_plans_are_checked_and_reported(sva_bin, tmp_path):
    # --results into a scratch root (SVA_RESULTS_ROOT), not the repository's docs
    r = run("--quick", "--results", "--sva", sva_bin, env={**os.environ, "SVA_RESULTS_ROOT": str(tmp_path)})
    assert r.returncode == 0, r.stdout + r.stderr
    rows = [line for line in r.stdout.splitlines() if line.startswith("| 25x5_fuel80 ")]
    assert len(rows) == 1, r.stdout
    cells = [c.strip() for c in rows[0].split("|")[1:-1]]
    assert cells[:3] == ["25x5_fuel80", "2", "0"], rows[0]
    proven = re.fullmatch(r"(\d) of 2", cells[3])
    assert proven, rows[0]
    work = [int(x.replace(",", "")) for x in cells[4].split(" / ")]
    assert 0 < work[0] <= work[1] <= work[2], rows[0]  # median <= p90 <= largest
    times = [float(x) for x in re.findall(r"(\d+\.\d\d) ms", cells[5])]
    assert len(times) == 3 and 0 < times[0] <= times[1] <= times[2], rows[0]
    assert cells[6] == ("met" if times[1] < 1.0 and times[2] < 2.0 else "not met"), rows[0]
    assert "sva-tools gen --targets 25 --uavs 5 --need 1 --fuel 80 --seed 7 --count 2" in r.stdout
    fragment = (tmp_path / "docs" / "results" / "core.flow_latency.md").read_text()
    assert ("Command: `nice -n 15 .venv/bin/python tools/bench/flow_latency.py --results --sets 25x5_fuel80 "
            "--missions 2 --repeat 1`") in fragment
    assert rows[0] in fragment
    page = (tmp_path / "docs" / "results.md").read_text()
    assert "## Core speed and memory" in page and "### flow's time where fuel binds" in page


def fake_cli(tmp_path, sva_bin, body):
    """A CLI that runs the real one, then lets `body` (Python, `plan` in scope) change the plan."""
    fake = tmp_path / "sva"
    fake.write_text(f"""#!{sys.executable}
import json, os, subprocess, sys
out = subprocess.run([{str(sva_bin)!r}] + sys.argv[1:], capture_output=True, text=True)
plan = json.loads(out.stdout)
{body}
print(json.dumps(plan))
""")
    fake.chmod(0o755)
    return str(fake)


def test_a_plan_the_checker_rejects_is_a_failure(sva_bin, tmp_path):
    # One covered target taken off its route and left nowhere.
    fake = fake_cli(tmp_path, sva_bin, "next(r for r in plan['routes'] if r['targets'])['targets'].pop()")
    r = run("--sets", "25x5_fuel80", "--missions", 1, "--repeat", 1, "--sva", fake)
    assert r.returncode == 1, r.stdout + r.stderr
    assert "failures 1" in r.stdout and "checker:" in r.stdout, r.stdout


def test_work_that_changes_between_runs_is_a_failure(sva_bin, tmp_path):
    # Each run reports one unit of work more than the run before.
    count = tmp_path / "runs"
    fake = fake_cli(tmp_path, sva_bin, f"""
n = int(open({str(count)!r}).read()) if os.path.exists({str(count)!r}) else 0
open({str(count)!r}, "w").write(str(n + 1))
plan["stats"]["flow_work"] += n""")
    r = run("--sets", "25x5_fuel80", "--missions", 1, "--repeat", 2, "--sva", fake)
    assert r.returncode == 1, r.stdout + r.stderr
    assert "work differs between runs" in r.stdout, r.stdout


def test_an_unknown_set_is_refused(sva_bin):
    r = run("--sets", "25x5_fuel81", "--sva", sva_bin)
    assert r.returncode == 2 and "unknown set(s) ['25x5_fuel81']" in r.stderr, r.stderr
