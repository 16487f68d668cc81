"""Multi-process LCM test over real udpm multicast: the C node (sva_node) and the
Python ground tool (python -m sva_tools.lcm) in a network namespace that
netns_run.sh creates for this run (never in the machine's own namespace)."""
import json
import os
import signal
import subprocess
import sys
import time
import uuid
from pathlib import Path

import pytest

if not os.environ.get("SVA_LCM_NETNS"):
    pytest.skip("run through tests/lcm/netns_run.sh (multicast only in a private netns)",
                allow_module_level=True)

import lcm  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from plan_check import check_plan  # noqa: E402

from sva_tools.lcm import wire  # noqa: E402

HERE = Path(__file__).resolve().parent
DATA = HERE / "data"
URL = "udpm://239.255.76.67:7667?ttl=0"
NODE = os.environ["SVA_NODE"]


def rss_kib(pid):
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1])
    return -1


class Node:
    def __init__(self, prefix, *extra):
        self.prefix = prefix
        self.proc = subprocess.Popen([NODE, "--url", URL, "--prefix", prefix, "--status-ms", "100",
                                      *extra], stderr=subprocess.PIPE, text=True)
        # The listener gets the node's buffer size; floods go out through a second,
        # publish-only instance (udpm opens no receive socket without a subscription).
        self.lc = lcm.LCM(URL + "&recv_buf_size=4194304")
        self.pub = lcm.LCM(URL)
        self.statuses = []
        self.plans = []
        t = wire.types()
        st = self.lc.subscribe(prefix + "STATUS", lambda c, d: self.statuses.append(
            t.node_status_t.decode(d)))
        st.set_queue_capacity(100000)
        s = self.lc.subscribe(prefix + "PLAN", lambda c, d: self.plans.append(t.plan_t.decode(d)))
        s.set_queue_capacity(5000)
        assert self.wait(lambda: self.statuses), "node published no status"

    def wait(self, cond, timeout=5.0):
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            if cond():
                return True
            self.lc.handle_timeout(50)
        return cond()

    def fresh_status(self):
        """A status published after everything sent so far was handled: published after
        this call began, with the same counters as the status before it."""
        t0 = time.time_ns() // 1000

        def settled():
            s = self.statuses
            return (len(s) >= 2 and s[-2].utime > t0 and s[-1].fleet_rx == s[-2].fleet_rx
                    and s[-1].mission_rx == s[-2].mission_rx)
        assert self.wait(settled, timeout=10)
        return self.statuses[-1]

    def stop(self, sig=signal.SIGTERM):
        self.proc.send_signal(sig)
        try:
            _, err = self.proc.communicate(timeout=5)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.communicate()
            raise AssertionError("node did not stop within 5 s")
        return self.proc.returncode, err


@pytest.fixture
def node():
    n = Node(f"T{uuid.uuid4().hex[:6]}_")
    yield n
    if n.proc.poll() is None:
        rc, err = n.stop()
        assert rc == 0, err


def send(prefix, mission, *extra, timeout=10):
    env = dict(os.environ)
    return subprocess.run([sys.executable, "-m", "sva_tools.lcm", "send", str(mission),
                           "--url", URL, "--prefix", prefix, "--timeout", "5", *extra],
                          capture_output=True, text=True, env=env, timeout=timeout)


@pytest.mark.parametrize("name", ["small_5x8.json", "bench_25x5.json"])
def test_ground_tool_gets_a_plan_that_checks(node, name, tmp_path):
    out = tmp_path / "plan.json"
    r = send(node.prefix, DATA / name, "-o", str(out))
    assert r.returncode == 0, r.stderr
    mission = json.loads((DATA / name).read_text())
    plan = json.loads(out.read_text())
    assert plan["algorithm"] == "sva"
    assert plan["covered"] >= 1
    assert check_plan(mission, plan) == []


def test_algorithm_option(tmp_path):
    n = Node(f"A{uuid.uuid4().hex[:6]}_", "--algorithm", "ga")
    try:
        r = send(n.prefix, DATA / "small_5x8.json")
        assert r.returncode == 0, r.stderr
        plan = json.loads(r.stdout)
        assert plan["algorithm"] == "ga"
        assert check_plan(json.loads((DATA / "small_5x8.json").read_text()), plan) == []
    finally:
        rc, err = n.stop(signal.SIGINT)
    assert rc == 0, err
    assert "exit:" in err


def test_node_rejects_bad_options():
    r = subprocess.run([NODE, "--algorithm", "simplex"], capture_output=True, text=True)
    assert r.returncode == 2 and "--algorithm" in r.stderr
    r = subprocess.run([NODE, "--prefix", "P" * 60], capture_output=True, text=True)
    assert r.returncode == 2 and "--prefix" in r.stderr


def test_core_rejection_reaches_the_ground(node, tmp_path):
    doc = json.loads((DATA / "small_5x8.json").read_text())
    doc["targets"][4]["id"] = doc["targets"][1]["id"]
    bad = tmp_path / "dup.json"
    bad.write_text(json.dumps(doc))
    r = send(node.prefix, bad)
    assert r.returncode == 1
    assert "targets[4].id" in r.stderr and "duplicate" in r.stderr
    assert r.stdout == ""
    assert node.fresh_status().rejected[5] == 1  # REJECT_INVALID


def test_bad_mission_file_never_sent(node, tmp_path):
    doc = json.loads((DATA / "small_5x8.json").read_text())
    doc["targets"][0]["colour"] = 3
    bad = tmp_path / "unknown.json"
    bad.write_text(json.dumps(doc))
    r = send(node.prefix, bad)
    assert r.returncode == 2 and "targets[0].colour: unknown key" in r.stderr
    assert node.fresh_status().mission_rx == 0


def test_malformed_traffic_and_flood(node):
    t = wire.types()
    doc = json.loads((DATA / "small_5x8.json").read_text())
    _, fleet, mission = wire.mission_messages(doc, 1, 1)
    fb, mb = fleet.encode(), mission.encode()
    F, M = node.prefix + "FLEET", node.prefix + "MISSION"

    _, over, _ = wire.mission_messages(doc, 1, 1)
    over.uav_count = 65
    _, val, _ = wire.mission_messages(doc, 1, 1)
    val.uavs[3].fuel = -1
    _, _, mval = wire.mission_messages(doc, 1, 1)
    mval.targets[2].need = 0
    _, _, mover = wire.mission_messages(doc, 1, 1)
    mover.target_count = 300
    bad = [  # (channel, bytes, reason index)
        (F, fb[:-1], 0), (M, mb[:9], 0), (F, b"", 0), (F, fb + b"\0", 1),
        (F, bytes([fb[0] ^ 1]) + fb[1:], 2), (M, mb[:8][::-1] + mb[8:], 2),
        (F, over.encode(), 3), (M, mover.encode(), 3), (F, val.encode(), 4),
        (M, mval.encode(), 4), (F, mb, 1), (M, fb, 0),
    ]
    node.pub.publish(F, fb)
    node.pub.publish(M, mb)
    assert node.wait(lambda: len(node.plans) == 1)
    for ch, data, _ in bad:
        node.pub.publish(ch, data)
    s = node.fresh_status()
    want = [0] * 8
    for _, _, why in bad:
        want[why] += 1
    assert list(s.rejected) == want
    assert node.proc.poll() is None
    rss0 = rss_kib(node.proc.pid)

    # Flood: 1000 malformed messages back to back, with a valid new fleet every 100th.
    def flood(rev0):
        valid = 0
        for i in range(1000):
            if i % 100 == 99:
                fleet.revision = rev0 + i
                node.pub.publish(F, fleet.encode())
                valid += 1
            ch, data, _ = bad[i % len(bad)]
            node.pub.publish(ch, data)
        return valid

    plans0 = len(node.plans)
    valid = flood(1000)
    s = node.fresh_status()
    assert sum(s.rejected) == sum(want) + 1000  # every malformed message seen and counted
    n_fleet_bad = sum(1 for ch, _, _ in bad if ch == F)
    flood_fleet = sum(1 for i in range(1000) if bad[i % len(bad)][0] == F)
    assert s.fleet_rx == 1 + n_fleet_bad + flood_fleet + valid  # nothing lost
    assert s.mission_rx == 1 + (len(bad) - n_fleet_bad) + (1000 - flood_fleet)
    assert s.plans_published == 1 + valid
    assert node.wait(lambda: len(node.plans) == plans0 + valid)
    assert [p.fleet_revision for p in node.plans[plans0:]] == [1000 + i for i in range(99, 1000, 100)]
    rss1 = rss_kib(node.proc.pid)
    for k in range(3):  # one flood of 1000 at a time, as above
        flood(5000 + 1000 * k)
        s = node.fresh_status()
        assert sum(s.rejected) == sum(want) + 2000 + 1000 * k
    rss2 = rss_kib(node.proc.pid)
    # LCM's receive pool follows the deepest burst (its high-water mark, kept for reuse);
    # a leak of even 1 KiB per message would add ~3 MiB over these 3000 messages.
    assert rss2 - rss1 <= 1536, (rss0, rss1, rss2)
    print(f"node RSS KiB: before floods {rss0}, after 1 {rss1}, after 4 {rss2}")

    # and the node still plans a valid mission end to end
    r = send(node.prefix, DATA / "small_5x8.json")
    assert r.returncode == 0, r.stderr
    assert check_plan(doc, json.loads(r.stdout)) == []


def test_record_and_replay(tmp_path):
    prefix = f"R{uuid.uuid4().hex[:6]}_"
    log = tmp_path / "session.lcmlog"
    n = Node(prefix)
    rec = subprocess.Popen([sys.executable, "-m", "sva_tools.lcm", "record", "-o", str(log),
                            "--url", URL, "--channels", prefix + ".*"])
    try:
        time.sleep(0.5)
        r = send(prefix, DATA / "small_5x8.json", "--revision", "77")
        assert r.returncode == 0, r.stderr
        time.sleep(0.5)
    finally:
        rec.send_signal(signal.SIGINT)
        rec.wait(timeout=5)
        rc, err = n.stop()
    assert rc == 0, err
    channels = [e.channel for e in lcm.EventLog(str(log), "r")]
    assert {prefix + "FLEET", prefix + "MISSION", prefix + "PLAN"} <= set(channels)

    # a fresh node answers the replayed inputs with a plan for the recorded revisions
    n2 = Node(prefix)
    try:
        r = subprocess.run([sys.executable, "-m", "sva_tools.lcm", "replay", str(log), "--url",
                            URL, "--speed", "10", "--channels", prefix + "(FLEET|MISSION)"],
                           capture_output=True, text=True, timeout=30)
        assert r.returncode == 0, r.stderr
        assert n2.wait(lambda: any(p.fleet_revision == 77 and p.mission_revision == 77
                                   for p in n2.plans))
    finally:
        rc, err = n2.stop()
    assert rc == 0, err
