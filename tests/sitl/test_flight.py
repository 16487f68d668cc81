"""`sva-tools sitl`: fixtures/scenarios/sitl_3uav.json flown by three ArduCopter SITL
vehicles at speedup 10, with sva_node and sva_mavlink_bridge over LCM in a network
namespace the tool makes. The scenario loses UAV 1 on its way to its second target,
pops a target up and cancels one. Judged from the flight log (the vehicles' telemetry,
the node's replans, the bridge's lines) and against `sva-tools sim` on the same scenario.
Run by run_flight.sh (root and the SITL binary, else skipped)."""
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
SCENARIO = REPO / "fixtures" / "scenarios" / "sitl_3uav.json"


def tool_env():
    env = dict(os.environ)
    env["PYTHONPATH"] = str(REPO / "tools")
    env.pop("SVA_LCM_NETNS", None)
    return env


def ours():
    """Processes (vehicles, node, bridge, the tool) and working folders a sitl run leaves
    behind (none, when it cleaned up)."""
    procs = subprocess.run(["ps", "-eww", "-o", "pid,args"], capture_output=True, text=True).stdout
    programs = tuple(os.path.basename(os.environ.get(k, "-")) for k in ("SVA_NODE", "SVA_MAVLINK_BRIDGE"))
    left = [ln for ln in procs.splitlines() if "sva-sitl-" in ln or
            ("sva_tools" in ln and " sitl " in ln and "pytest" not in ln) or
            (len(ln.split()) > 1 and os.path.basename(ln.split()[1]) in programs)]
    tmp = [p.name for p in Path("/tmp").glob("sva-sitl-*")]
    return left, tmp


@pytest.fixture(scope="module")
def flight(tmp_path_factory):
    out = tmp_path_factory.mktemp("sitl")
    log, png = out / "log.json", out / "flight.png"
    t = time.monotonic()
    r = subprocess.run([sys.executable, "-m", "sva_tools", "sitl", str(SCENARIO), "--speedup", "10",
                        "--out", str(log), "--plot", str(png), "--quiet"],
                       capture_output=True, text=True, env=tool_env(), timeout=400)
    wall = time.monotonic() - t
    netns_after = subprocess.run(["ip", "netns", "list"], capture_output=True, text=True).stdout.split()
    assert r.returncode == 0, r.stderr[-3000:]
    print(f"sitl flight: {wall:.1f} s wall")
    return {"log": json.loads(log.read_text()), "stdout": r.stdout, "png": png, "wall": wall,
            "netns_after": netns_after}


def test_end_line_and_cleanup(flight):
    lines = flight["stdout"].strip().splitlines()
    assert lines[-1].startswith("covered ") and "coverable (plan promised " in lines[-1]
    assert "arrival slack p50 " in lines[-1] and lines[-1].split("; ")[-1].startswith("late arrivals ")
    left, tmp = ours()
    assert left == [] and tmp == []
    ns = flight["log"]["sitl"]["netns"]
    assert ns and ns.startswith("sva-lcm-") and ns not in flight["netns_after"]
    assert flight["png"].stat().st_size > 10_000


def test_every_promised_target_is_covered_in_the_telemetry(flight):
    log = flight["log"]
    s = log["summary"]
    promised = [t for t in log["targets"] if t["promised"] and t["outcome"] != "lost"]
    assert len(promised) == s["promised"] >= 4
    assert all(t["covered"] for t in promised), log["targets"]
    assert s["covered"] == s["coverable"] == s["promised"]
    by_id = {t["id"]: t for t in log["targets"]}
    assert by_id[5]["outcome"] == "cancelled"          # cancelled at tick 28
    assert by_id[6]["covered"] and by_id[6]["promised"]  # popped up at tick 24
    # the telemetry the judgement rests on: [t_ms, lat, lon, rel_alt] on the vehicle clock
    for u in log["uavs"]:
        tel = u["telemetry"]
        assert len(tel) > 100 and all(len(p) == 4 for p in tel)
        assert all(a[0] <= b[0] for a, b in zip(tel, tel[1:]))
        assert max(p[3] for p in tel) > 25  # flew at the frame's 30 m


def test_the_lost_vehicles_work_goes_to_the_others_only(flight):
    log = flight["log"]
    loss = [r for r in log["replans"] if r["cause"] == "report:uav_lost"]
    assert len(loss) == 1
    r = loss[0]
    assert 1 not in [u["id"] for u in r["mission"]["uavs"]]
    assert r["changes"]["added"] and all(u != 1 for u, _t in r["changes"]["added"])
    # UAV 1's second target (5) was taken over by another UAV
    assert any(t == 5 for _u, t in r["changes"]["added"])
    lat = log["sitl"]["losses"][0]
    assert lat["uav"] == 1 and lat["uploaded_to"] and 1 not in lat["uploaded_to"]
    # both instants are when this side read the node's reply and the bridge's line: the
    # line can be read first
    assert 0 < lat["replan_ms"] < 15_000 and 0 < lat["upload_ms"] < 15_000
    u1 = next(u for u in log["uavs"] if u["id"] == 1)
    kill = next(e["at_ms"] for e in log["sitl"]["events"] if e["type"] == "uav_lost")
    assert not [x for x in u1["uploads"] if x.get("items") and x["at_ms"] > kill]
    assert u1["out"] == [[20, None]]


def test_holds_end_at_the_windows_end_on_the_vehicle_clock(flight):
    log = flight["log"]
    holds = [h for u in log["uavs"] for h in u["holds"] if "error_ms" in h and not h["cut"]]
    covered = [t for t in log["targets"] if t["covered"]]
    assert len(holds) >= len(covered)
    assert all(abs(h["error_ms"]) <= 1000 for h in holds), holds
    assert log["summary"]["hold_error_max_ms"] <= 1000


def test_nobody_arrives_after_a_window_start(flight):
    s = flight["log"]["summary"]
    assert s["late_arrivals"] == 0 and s["missed_visits"] == []
    assert s["visits"] >= s["covered"] and s["slack_p1_s"] >= 0


def test_sim_covers_the_same_targets(flight, tmp_path):
    out = tmp_path / "sim.json"
    r = subprocess.run([sys.executable, "-m", "sva_tools", "sim", str(SCENARIO), "--out", str(out)],
                       capture_output=True, text=True, env=tool_env(), timeout=120)
    assert r.returncode == 0, r.stderr
    sim = json.loads(out.read_text())
    covered = lambda log: sorted(t["id"] for t in log["targets"] if t["covered"])  # noqa: E731
    assert covered(flight["log"]) == covered(sim)
    assert [t["outcome"] for t in flight["log"]["targets"]] == [t["outcome"] for t in sim["targets"]]


def test_the_log_reads_as_a_sim_log(flight, tmp_path):
    from sva_tools import simplot

    log = flight["log"]
    for key in ("scenario", "algorithm", "end_tick", "uavs", "targets", "replans", "summary"):
        assert key in log
    simplot.render_flight(log, str(tmp_path / "as_sim.png"))
    assert (tmp_path / "as_sim.png").stat().st_size > 10_000


def start_and_wait_for_vehicles(out):
    p = subprocess.Popen([sys.executable, "-m", "sva_tools", "sitl", str(SCENARIO), "--quiet",
                          "--out", str(out)],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=tool_env(),
                         preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    end = time.monotonic() + 60
    while time.monotonic() < end and not any("arducopter" in ln for ln in ours()[0]):
        time.sleep(0.2)
    return p


def test_ctrl_c_stops_everything(tmp_path):
    p = start_and_wait_for_vehicles(tmp_path / "never.json")
    time.sleep(3)
    p.send_signal(signal.SIGINT)
    _out, err = p.communicate(timeout=60)
    assert p.returncode == 130, err
    assert "interrupted" in err
    time.sleep(1)
    assert ours() == ([], [])
    assert not (tmp_path / "never.json").exists()


# `python -m sva_tools`, saying "up" once the interpreter has started: a SIGINT during
# Python's own start-up (its site module, before any code of the tool exists) ends it
# with Python's fatal error, which no program can catch; on a loaded machine that start-up
# can outlast the first delay, so the delays count from "up".
LAUNCH = ("import runpy, sys; sys.stderr.write('up\\n'); sys.stderr.flush(); "
          "runpy.run_module('sva_tools', run_name='__main__', alter_sys=True)")


def test_ctrl_c_while_starting_up_is_said_and_leaves_nothing(tmp_path):
    for delay in (0.5, 1.0, 2.0):
        p = subprocess.Popen([sys.executable, "-c", LAUNCH, "sitl", str(SCENARIO), "--quiet",
                              "--out", str(tmp_path / "never.json")],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=tool_env(),
                             preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
        assert p.stderr.readline() == "up\n", delay
        time.sleep(delay)
        p.send_signal(signal.SIGINT)
        _out, err = p.communicate(timeout=60)
        assert p.returncode == 130, (delay, err)
        assert "interrupted" in err and "Traceback" not in err, (delay, err)
        time.sleep(1)
        assert ours() == ([], []), delay


def test_ctrl_c_before_the_run_inside_is_up_waits_for_it(tmp_path):
    # The namespace helper starts 3 s late, so the stop comes while the tool waits for the
    # run inside: passed on at once, it would end that run's interpreter in its start-up.
    started = tmp_path / "helper-started"
    slow = tmp_path / "slow_netns_run.sh"
    helper = REPO / "tools" / "netns" / "netns_run.sh"
    slow.write_text(f'#!/bin/sh\ntouch "{started}"\nsleep 3\nexec "{helper}" "$@"\n')
    slow.chmod(0o755)
    env = tool_env()
    env["SVA_NETNS_RUN"] = str(slow)
    p = subprocess.Popen([sys.executable, "-m", "sva_tools", "sitl", str(SCENARIO), "--quiet",
                          "--out", str(tmp_path / "never.json")],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
                         preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    end = time.monotonic() + 60
    while time.monotonic() < end and not started.exists():
        time.sleep(0.05)
    assert started.exists()
    p.send_signal(signal.SIGINT)
    _out, err = p.communicate(timeout=90)
    assert p.returncode == 130, err
    assert "vehicles, node and bridge stopped" in err and "Traceback" not in err, err
    time.sleep(1)
    assert ours() == ([], [])
    assert not (tmp_path / "never.json").exists()


def flight_process(outer, timeout=30):
    """The pid of the run inside the namespace: the namespace helper's child."""
    end = time.monotonic() + timeout
    table = ""
    while time.monotonic() < end:
        table = subprocess.run(["ps", "-eww", "-o", "pid=,ppid=,args="], capture_output=True,
                               text=True).stdout
        rows = [ln.split(None, 2) for ln in table.splitlines()]
        helper = [int(pid) for pid, ppid, args in rows if int(ppid) == outer and "netns_run" in args]
        inner = [int(pid) for pid, ppid, args in rows if helper and int(ppid) == helper[0] and
                 "sva_tools sitl" in args]
        if inner:
            return inner[0]
        time.sleep(0.2)
    raise AssertionError(f"no flight process under the namespace helper of {outer}:\n{table}")


def test_a_killed_flight_takes_its_vehicles_and_folder_with_it(tmp_path):
    p = start_and_wait_for_vehicles(tmp_path / "never.json")
    os.kill(flight_process(p.pid), signal.SIGKILL)
    _out, err = p.communicate(timeout=60)
    assert p.returncode == 128 + signal.SIGKILL, err
    assert "ended by SIGKILL" in err
    time.sleep(1)
    assert ours() == ([], [])
    netns = subprocess.run(["ip", "netns", "list"], capture_output=True, text=True).stdout
    assert "sva-lcm-" not in netns
    assert not (tmp_path / "never.json").exists()
