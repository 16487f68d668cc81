"""`sva-tools sim --via lcm`: the simulator flies a bundled scenario against a real
sva_node over LCM multicast. Every run here happens in a network namespace the tool
creates for itself (tools/netns/netns_run.sh), or, for --attach, in one this test makes.
The flight logs are judged by the independent checker (tests/tools/flight_checker.py)
and compared with the in-process run (`sva replan` through the CLI)."""
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "tools"))
sys.path.insert(0, str(REPO / "tests" / "tools"))

from flight_checker import check_flight  # noqa: E402

SCENARIOS = REPO / "fixtures" / "scenarios"
NETNS_RUN = REPO / "tools" / "netns" / "netns_run.sh"

if os.geteuid() != 0:
    pytest.skip("sim --via lcm makes a network namespace: needs root", allow_module_level=True)


def sim(*args, env=None, timeout=300):
    e = dict(os.environ if env is None else env)
    e["PYTHONPATH"] = str(REPO / "tools")
    return subprocess.run([sys.executable, "-m", "sva_tools", "sim", *args], capture_output=True,
                          text=True, env=e, timeout=timeout)


def outside_env():
    """The environment of a command run outside any namespace made for it."""
    e = dict(os.environ)
    e.pop("SVA_LCM_NETNS", None)
    return e


def fly(tmp_path, scenario, algo, via):
    out = tmp_path / f"{scenario.stem}-{algo}-{via}.json"
    r = sim(str(scenario), "--algo", algo, "--via", via, "--out", str(out), env=outside_env())
    assert r.returncode == 0, r.stderr
    return json.loads(out.read_text())


@pytest.mark.parametrize("scenario, algo", [("hand_events", "sva"), ("hand_events", "flow"),
                                            ("gen_25t5u_events", "sva")])
def test_flight_via_the_node_passes_the_checker_and_covers_as_in_process(tmp_path, scenario,
                                                                         algo):
    path = SCENARIOS / f"{scenario}.json"
    events = json.loads(path.read_text())["events"]
    lcm_log = fly(tmp_path, path, algo, "lcm")
    cli_log = fly(tmp_path, path, algo, "cli")
    assert check_flight(lcm_log) == []
    assert lcm_log["via"] == "lcm" and "via" not in cli_log
    assert lcm_log["summary"]["covered"] == cli_log["summary"]["covered"]
    assert [t["outcome"] for t in lcm_log["targets"]] == [t["outcome"] for t in cli_log["targets"]]
    assert [r["at"] for r in lcm_log["replans"]] == [r["at"] for r in cli_log["replans"]]
    # The node's own record: one message per event, a clock at tick 0, the first plan.
    node = lcm_log["node"]
    assert node["algorithm"] == algo and node["attached"] is False
    assert node["messages"] == len(events) + 2
    msgs = [m for r in lcm_log["replans"] for m in r["node"]["messages"]]
    assert len(msgs) == node["messages"]
    assert msgs[0]["channel"] == "PLAN" and msgs[1]["event"] == "clock"
    assert [m["event"] for m in msgs[2:]] == [e["type"] for e in events]
    assert all(m["round_trip_us"] > 0 for m in msgs)
    assert node["round_trip_us"]["p50"] <= node["round_trip_us"]["p99"] <= \
        node["round_trip_us"]["max"]
    for r in lcm_log["replans"]:
        last = r["node"]["messages"][-1]
        assert r["solve_us"] == last["solve_us"] == r["plan"]["stats"]["solve_us"]
        assert r["node"]["plan_id"] == last["plan_id"] == r["plan"]["stats"]["plan_id"]
        assert r["live"]["now"] == r["at"]


def test_attach_to_a_running_node_and_its_algorithm_is_checked(tmp_path):
    """--attach inside a namespace this test makes: a node running ga is refused for
    --algo sva (naming the node option); one running sva flies the scenario."""
    path = SCENARIOS / "hand_events.json"
    script = tmp_path / "attach.sh"
    out = tmp_path / "log.json"
    script.write_text(f"""set -u
"$SVA_NODE" --algorithm ga --change-penalty 2 --status-ms 100 >/dev/null 2>&1 & ga=$!
"{sys.executable}" -m sva_tools sim "{path}" --via lcm --attach --algo sva --timeout 5
echo "rc=$?"
kill $ga; wait $ga
"$SVA_NODE" --algorithm sva --change-penalty 2 --status-ms 100 >/dev/null 2>&1 & node=$!
"{sys.executable}" -m sva_tools sim "{path}" --via lcm --attach --out "{out}"
echo "rc=$?"
kill $node; wait $node
""")
    e = outside_env()
    e["PYTHONPATH"] = str(REPO / "tools")
    r = subprocess.run([str(NETNS_RUN), "bash", str(script)], capture_output=True, text=True,
                       env=e, timeout=120)
    assert r.stdout.split() == ["rc=2", "rc=0"], r.stderr
    assert "--algo sva: the node plans with ga (start sva_node --algorithm sva)" in r.stderr
    log = json.loads(out.read_text())
    assert check_flight(log) == [] and log["node"]["attached"] is True


def test_penalty_the_node_does_not_use_is_an_error(tmp_path):
    """An attached node with another --change-penalty than the scenario's is refused."""
    path = SCENARIOS / "hand_events.json"  # change_penalty 2
    script = tmp_path / "p.sh"
    script.write_text(f"""
"$SVA_NODE" --status-ms 100 >/dev/null 2>&1 & node=$!
"{sys.executable}" -m sva_tools sim "{path}" --via lcm --attach
echo "rc=$?"
kill $node; wait $node
""")
    e = outside_env()
    e["PYTHONPATH"] = str(REPO / "tools")
    r = subprocess.run([str(NETNS_RUN), "bash", str(script)], capture_output=True, text=True,
                       env=e, timeout=120)
    assert r.stdout.split() == ["rc=2"], r.stderr
    assert ("change_penalty: the scenario asks 2, the node replans with 0 "
            "(start sva_node --change-penalty 2)") in r.stderr


def test_without_root_it_refuses_clearly(tmp_path):
    setpriv = shutil.which("setpriv")
    if setpriv is None:
        pytest.skip("setpriv (util-linux) is not installed")
    import tempfile

    with tempfile.NamedTemporaryFile("w", suffix=".json", dir="/tmp", delete=False) as f:
        f.write((SCENARIOS / "hand_events.json").read_text())  # readable by nobody
    path = Path(f.name)
    os.chmod(path, 0o644)
    e = outside_env()
    e["PYTHONPATH"] = str(REPO / "tools")
    r = subprocess.run([setpriv, "--reuid=65534", "--regid=65534", "--clear-groups",
                        sys.executable, "-m", "sva_tools", "sim", str(path), "--via", "lcm"],
                       capture_output=True, text=True, env=e, timeout=60)
    path.unlink()
    assert r.returncode == 2, r.stderr
    assert "sim --via lcm: needs root to create the network namespace" in r.stderr


def test_via_cli_refuses_lcm_options():
    r = sim(str(SCENARIOS / "hand_events.json"), "--attach")
    assert r.returncode == 2 and "--attach, --url and --prefix need --via lcm" in r.stderr


def test_live_bench_node_figures_recomputed_from_its_logs(tmp_path):
    """tools/bench/live_bench.py --node: its fragment (docs/results/live.node.md in a copy)
    gives the round trip and node solve percentiles of the flight logs it keeps."""
    import math
    import re

    root = tmp_path / "repo"
    (root / "docs").mkdir(parents=True)
    shutil.copytree(REPO / "docs" / "results", root / "docs" / "results")
    shutil.copy(REPO / "docs" / "results.md", root / "docs" / "results.md")
    work = tmp_path / "work"
    e = outside_env()
    e["SVA_RESULTS_ROOT"] = str(root)
    r = subprocess.run([sys.executable, str(REPO / "tools" / "bench" / "live_bench.py"), "--node",
                        "--results", "--set", "6x2:2", "--events", "3", "--algos", "sva",
                        "--penalties", "0", "--work", str(work)],
                       capture_output=True, text=True, env=e, timeout=300)
    assert r.returncode == 0, r.stderr
    text = (root / "docs" / "results" / "live.node.md").read_text()
    assert "Command: `nice .venv/bin/python tools/bench/live_bench.py --results --node --set 6x2:2 " \
           "--events 3 --algos sva --penalties 0`" in text
    assert (root / "docs" / "results" / "live.md").read_text() == \
        (REPO / "docs" / "results" / "live.md").read_text()  # --node leaves the main part alone
    m = re.search(r"^\| sva \| 0 \| (\d+)/(\d+) \| (\d+) \| (\S+) ms \| (\S+) ms \| (\S+) ms "
                  r"\| (\S+) ms \| (\S+) ms \|$", text, re.M)
    assert m, text
    logs = [json.loads(p.read_text()) for p in sorted(work.glob("6x2_*/logs/live_*.sva.p0.lcm.json"))]
    cli = [json.loads(p.read_text()) for p in sorted(work.glob("6x2_*/logs/live_*.sva.p0.json"))]
    assert len(logs) == len(cli) == 2 and all(lg["via"] == "lcm" for lg in logs)
    msgs = [x for lg in logs for rp in lg["replans"] for x in rp["node"]["messages"]
            if x["channel"] == "REPLAN"]
    rank = lambda v, p: sorted(v)[math.ceil(len(v) * p / 100) - 1]  # noqa: E731
    rts = [x["round_trip_us"] for x in msgs]
    solve = [x["solve_us"] for x in msgs]
    same = sum(a["summary"]["covered"] == b["summary"]["covered"] for a, b in zip(logs, cli))
    assert (int(m[1]), int(m[2]), int(m[3])) == (same, 2, len(msgs))
    assert m[4] == f"{rank(rts, 50) / 1000:.3f}" and m[5] == f"{rank(rts, 99) / 1000:.3f}"
    assert m[6] == f"{max(rts) / 1000:.3f}"
    assert m[7] == f"{rank(solve, 50) / 1000:.3f}" and m[8] == f"{rank(solve, 99) / 1000:.3f}"
