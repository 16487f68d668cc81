"""tools/bench/live_bench.py: live missions flown with each algorithm, every figure of its
results fragment (docs/results/live.md) recomputed here from the flight logs it keeps and
from `sva-tools ref` run again on the replans' residual missions."""
import json
import math
import os
import re
import shutil
import subprocess
import sys

from conftest import REPO, sva_tools

sys.path.insert(0, str(REPO / "tools" / "bench"))
import results  # noqa: E402

BENCH = REPO / "tools" / "bench" / "live_bench.py"


def nearest_rank(values, p):
    values = sorted(values)
    return values[math.ceil(len(values) * p / 100) - 1]


def run_bench(tmp_path, sva_bin):
    root = tmp_path / "repo"
    (root / "docs").mkdir(parents=True)
    shutil.copytree(REPO / "docs" / "results", root / "docs" / "results")
    shutil.copy(REPO / "docs" / "results.md", root / "docs" / "results.md")
    work = tmp_path / "work"
    env = dict(os.environ, SVA_RESULTS_ROOT=str(root), SVA_BIN=str(sva_bin))
    r = subprocess.run([sys.executable, str(BENCH), "--results", "--set", "6x2:2", "--events", "3",
                        "--algos", "sva,flow", "--penalties", "0,1000", "--gen=--need", "--gen=1",
                        "--work", str(work)], capture_output=True, text=True, env=env, timeout=240)
    assert r.returncode == 0, r.stderr
    return root, work, r.stdout


def test_fragment_shape_and_figures_from_the_logs(tmp_path, sva_bin):
    root, work, stdout = run_bench(tmp_path, sva_bin)
    text = (root / "docs" / "results" / "live.md").read_text(encoding="utf-8")
    results.check(str(root))  # the page is reassembled with the new section
    page = (root / "docs" / "results.md").read_text(encoding="utf-8")
    assert "## Live missions" in page and text.strip() in page
    assert ("Command: `nice .venv/bin/python tools/bench/live_bench.py --results --set 6x2:2 --events 3 "
            "--algos sva,flow --gen=--need --gen=1`") in text
    assert re.search(r"^Machine: \d+ cores, ", text, re.M)
    assert "latency through the LCM node is measured by `live_bench.py --node`" in text
    assert "#### 6 targets x 2 UAVs, 2 scenarios" in text
    rows = {(m.group(1), int(m.group(2))): m.groups()[2:] for m in re.finditer(
        r"^\| (\w+) \| (\d+) \| (\d+)/(\d+) \(.*?\) \| (\d+)/(\d+) \(.*?\) \| (\d+)/(\d+) \(.*?\) "
        r"\| mean (\S+) %, largest (\S+) % \| (\S+) \| (\S+) ms \| (\S+) ms \|$", text, re.M)}
    assert set(rows) == {("sva", 0), ("sva", 1000), ("flow", 0), ("flow", 1000)}
    goal = re.search(r"^- flow, change_penalty 0: covers as many targets as ref on (\S+) % of (\d+) "
                     r"residual missions \(goal at least 99 %\): (met|not met)\.$", text, re.M)
    assert goal, text

    logs_dir = next(work.glob("6x2_*")) / "logs"
    for (algo, pen), row in rows.items():
        logs = [json.loads(p.read_text()) for p in sorted(logs_dir.glob(f"live_*.{algo}.p{pen}.json"))]
        assert len(logs) == 2
        for log in logs:  # each log flew its penalty
            assert log["algorithm"] == algo and log["scenario"].get("change_penalty") == pen
        # Flight coverage, recomputed from the targets' outcomes (not the summary).
        covered = sum(t["covered"] for log in logs for t in log["targets"])
        coverable = sum(t["outcome"] in ("covered", "uncovered") for log in logs for t in log["targets"])
        assert (int(row[0]), int(row[1])) == (covered, coverable)
        replans = [r for log in logs for r in log["replans"]]
        later = [r for r in replans if r["cause"] != "start"]
        changes = sum(len(r["changes"]["dropped"]) + len(r["changes"]["added"]) for r in later)
        assert later and row[8] == f"{changes / len(later):.2f}"
        times = [r["solve_us"] for r in replans]
        assert row[9] == f"{nearest_rank(times, 50) / 1000:.3f}"
        assert row[10] == f"{nearest_rank(times, 99) / 1000:.3f}"
        if (algo, pen) != ("flow", 0):
            continue
        # Against ref, run again here on every residual mission with a target.
        as_many = mine = theirs = 0
        judged = [r for r in replans if r["mission"]["targets"]]
        for i, r in enumerate(judged):
            path = tmp_path / f"residual_{i}.json"
            path.write_text(json.dumps(r["mission"]))
            out = sva_tools("ref", "--det-limit", "10", "--workers", "1", path)
            assert out.returncode == 0, out.stderr
            ref = json.loads(out.stdout)
            as_many += r["plan"]["covered"] >= ref["covered"]
            mine += r["plan"]["covered"]
            theirs += ref["covered"]
        assert (int(row[2]), int(row[3])) == (as_many, len(judged))
        assert (int(row[4]), int(row[5])) == (mine, theirs)
        assert float(goal.group(1)) == round(100.0 * as_many / len(judged), 1)
        assert goal.group(3) == ("met" if 100.0 * as_many / len(judged) >= 99 else "not met")
    assert stdout.count("| flow |") == 2
